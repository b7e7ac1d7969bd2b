"""Shooting, Floquet multipliers and Hopf branches on systems whose cycles are known.

- The Hopf normal form ``ṙ = μr + l r³ (+ c r⁵)``, ``θ̇ = ω``: cycles of radius r with
  ``μ + l r² + c r⁴ = 0``, period 2π/ω, radial multiplier ``exp(T dṙ/dr)``; with l < 0
  (supercritical) the branch lives at μ > 0 and is stable, with l > 0 (subcritical) at
  μ < 0 and unstable, and with c = −1 it turns at the fold μ = −1/4, r² = 1/2.
- The van der Pol oscillator ``ẍ − (1 − x²)ẋ + x = 0``: period 6.66328686 and
  amplitude 2.00861986 (the published limit cycle); its nontrivial multiplier is
  ``exp(∮ (1 − x²) dt)`` (the trace of the Jacobian integrated over the orbit: Liouville),
  computed here by quadrature along the converged orbit, apart from the monodromy.
- The matrix-free path (GMRES, Arnoldi): the normal form with 70 decaying linear modes
  appended, whose multipliers are ``exp(−k T)``.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp, trapezoid

from foilbearing.bifurcation import (
    FlowMap,
    HopfPoint,
    ShootingError,
    hopf_branch,
    periodic_orbit,
)

OMEGA = 1.3


def normal_form(l3: float, c5: float = 0.0, extra: np.ndarray | None = None) -> FlowMap:
    """ẋ = μx − ωy + (l r² + c r⁴) x, ẏ = ωx + μy + (l r² + c r⁴) y; z_k' = −k_k z_k."""
    decay = np.zeros(0) if extra is None else extra

    def field(y: np.ndarray, mu: float) -> np.ndarray:
        x, v = y[0], y[1]
        r2 = x * x + v * v
        g = mu + l3 * r2 + c5 * r2 * r2
        return np.concatenate([[g * x - OMEGA * v, OMEGA * x + g * v], -decay * y[2:]])

    def jac(y: np.ndarray, mu: float) -> np.ndarray:
        x, v = y[0], y[1]
        r2 = x * x + v * v
        g = mu + l3 * r2 + c5 * r2 * r2
        dg = 2.0 * (l3 + 2.0 * c5 * r2)  # dg/d(x or v) = dg * x or dg * v
        j = np.zeros((y.size, y.size))
        j[0, 0], j[0, 1] = g + dg * x * x, -OMEGA + dg * x * v
        j[1, 0], j[1, 1] = OMEGA + dg * x * v, g + dg * v * v
        j[2:, 2:] = -np.diag(decay)
        return j

    def advance(y0: np.ndarray, T: float, mu: float) -> np.ndarray:
        sol = solve_ivp(
            lambda t, y: field(y, mu), (0.0, T), y0, method="DOP853", rtol=1e-12, atol=1e-13
        )
        return sol.y[:, -1]

    def tangent(y0: np.ndarray, T: float, mu: float, w: np.ndarray) -> np.ndarray:
        n = y0.size

        def rhs(t: float, s: np.ndarray) -> np.ndarray:
            return np.concatenate([field(s[:n], mu), jac(s[:n], mu) @ s[n:]])

        sol = solve_ivp(
            rhs, (0.0, T), np.concatenate([y0, w]), method="DOP853", rtol=1e-12, atol=1e-13
        )
        return sol.y[n:, -1]

    return FlowMap(advance=advance, field=field, tangent=tangent)


def _hopf(flow_size: int, unstable_side: int = 1) -> HopfPoint:
    q = np.zeros(flow_size, complex)
    q[0], q[1] = 1.0, -1j  # A q = iω q for A = [[0, −ω], [ω, 0]]
    return HopfPoint(0.0, OMEGA, q, unstable_side)


def test_shooting_finds_the_normal_form_cycle_and_its_multipliers() -> None:
    """From a guess 25 % off in radius and 10 % in period, the supercritical cycle at
    μ = 0.04: r = 0.2 to 1e-8, T = 2π/ω to 1e-9, multipliers 1 and exp(−2μT) to 1e-7."""
    flow = normal_form(-1.0)
    mu = 0.04
    orbit = periodic_orbit(flow, np.array([0.25, 0.0]), 1.1 * 2 * np.pi / OMEGA, mu)
    T = 2 * np.pi / OMEGA
    assert np.hypot(*orbit.state) == pytest.approx(0.2, abs=1e-8)
    assert orbit.period == pytest.approx(T, rel=1e-9)
    values = np.sort(np.abs(orbit.multipliers))
    np.testing.assert_allclose(values, [np.exp(-2 * mu * T), 1.0], rtol=1e-7)
    assert orbit.stable


def test_shooting_that_cannot_converge_says_how_far_it_got() -> None:
    """No cycle exists at μ = −0.04 for l < 0: the error names the residual and what to try."""
    with pytest.raises(ShootingError, match=r"did not converge in 4 Newton iterations.*residual"):
        periodic_orbit(
            normal_form(-1.0), np.array([0.2, 0.0]), 2 * np.pi / OMEGA, -0.04, max_iter=4
        )


@pytest.mark.parametrize(
    ("l3", "kind", "side"), [(-1.0, "supercritical", 1), (1.0, "subcritical", -1)]
)
def test_the_branch_direction_gives_the_hopf_type(l3: float, kind: str, side: int) -> None:
    """Both signs of the cubic coefficient: the type, the side of the branch, its radius
    r = √(−μ/l) to 1e-6 along it and its stability (stable only when supercritical)."""
    flow = normal_form(l3)
    branch = hopf_branch(
        flow, _hopf(2), lambda mu: np.zeros(2), amplitude=0.02, steps=6, ds=0.5, p_scale=0.01
    )
    assert branch.bifurcation_type == kind
    mus = branch.parameters
    assert np.all(np.sign(mus) == side)
    np.testing.assert_allclose(branch.amplitudes, np.sqrt(-mus / l3), rtol=1e-6)
    assert np.all(branch.stable) == (kind == "supercritical")
    assert not np.any(branch.stable) == (kind == "subcritical")
    assert branch.folds == []


def test_a_state_the_flow_never_moves_stays_put_on_the_branch() -> None:
    """A coordinate with ż = 0 (the foil of a bearing without one: the state carries it,
    nothing moves it) makes the shooting system exactly singular; it is left where it is,
    and the branch is the normal form's, r = √(μ) to 1e-6, with z = 0.3 throughout."""
    flow = normal_form(-1.0, extra=np.array([0.0]))
    rest = np.array([0.0, 0.0, 0.3])
    branch = hopf_branch(
        flow, _hopf(3), lambda mu: rest, amplitude=0.02, steps=4, ds=0.5, p_scale=0.01
    )
    assert branch.bifurcation_type == "supercritical"
    np.testing.assert_allclose(branch.amplitudes, np.sqrt(branch.parameters), rtol=1e-6)
    assert all(o.state[2] == 0.3 for o in branch.orbits)


def test_the_subcritical_branch_turns_at_its_fold_and_regains_stability() -> None:
    """ṙ = μr + r³ − r⁵: the branch leaves μ = 0 backwards (unstable), turns at the fold
    μ = −1/4 (found within the branch's spacing, 0.01), and comes back stable on the large
    cycles r² = (1 + √(1 + 4μ))/2, every orbit on the analytic curve to 1e-6."""
    flow = normal_form(1.0, -1.0)
    branch = hopf_branch(
        flow,
        _hopf(2),
        lambda mu: np.zeros(2),
        amplitude=0.05,
        steps=40,
        ds=0.3,
        p_scale=0.05,
        p_bounds=(-1.0, 0.02),
    )
    assert branch.bifurcation_type == "subcritical"
    assert len(branch.folds) == 1
    assert branch.folds[0] == pytest.approx(-0.25, abs=0.01)
    mu, r = branch.parameters, branch.amplitudes
    np.testing.assert_allclose(mu + r**2 - r**4, 0.0, atol=1e-6)
    small, large = r**2 < 0.5 - 1e-3, r**2 > 0.5 + 1e-3
    assert small.any() and large.any()
    assert not np.any(branch.stable[small]) and np.all(branch.stable[large])


def test_van_der_pol_cycle_period_amplitude_and_multiplier() -> None:
    """The published cycle of μ = 1 (T = 6.663286859, max x = 2.008619860) to 1e-8, with
    finite-difference monodromy products (no tangent given); the nontrivial multiplier
    equals exp(∮ (1 − x²) dt) = 8.6e-4 by quadrature along the orbit, to 1e-5 (the
    products' own error), and the trivial one is 1."""

    def field(y: np.ndarray, mu: float) -> np.ndarray:
        return np.array([y[1], mu * (1 - y[0] ** 2) * y[1] - y[0]])

    def advance(y0: np.ndarray, T: float, mu: float) -> np.ndarray:
        sol = solve_ivp(
            lambda t, y: field(y, mu), (0, T), y0, method="DOP853", rtol=1e-12, atol=1e-13
        )
        return sol.y[:, -1]

    flow = FlowMap(advance=advance, field=field, fd_step=1e-6)
    orbit = periodic_orbit(flow, np.array([2.0, 0.0]), 6.6, 1.0, tol=1e-10)
    assert orbit.period == pytest.approx(6.663286859, rel=1e-8)
    sol = solve_ivp(
        lambda t, y: field(y, 1.0), (0, orbit.period), orbit.state, method="DOP853",
        rtol=1e-12, atol=1e-13, dense_output=True,
    )  # fmt: skip
    t = np.linspace(0.0, orbit.period, 20001)
    x = sol.sol(t)[0]
    assert np.max(x) == pytest.approx(2.008619860, rel=1e-7)
    liouville = np.exp(trapezoid(1.0 - x**2, t))
    # Finite-difference products carry errors of about fd_step times the largest
    # multiplier (1), so the small one is held in absolute terms.
    assert abs(orbit.nontrivial_multipliers[0]) == pytest.approx(liouville, abs=1e-5)
    assert np.max(np.abs(orbit.multipliers)) == pytest.approx(1.0, abs=1e-5)
    assert orbit.stable


def test_the_matrix_free_path_on_a_large_system() -> None:
    """70 decaying modes beside the normal form (n = 72 > dense_max): GMRES shooting finds
    the same cycle, and Arnoldi the largest multipliers: 1, exp(−2μT) and exp(−k_min T)."""
    decay = np.linspace(0.5, 5.0, 70)
    flow = normal_form(-1.0, extra=decay)
    mu, T = 0.04, 2 * np.pi / OMEGA
    y0 = np.concatenate([[0.22, 0.01], 1e-3 * np.ones(70)])
    orbit = periodic_orbit(flow, y0, T, mu, multipliers=4)
    assert np.hypot(*orbit.state[:2]) == pytest.approx(0.2, abs=1e-8)
    assert np.max(np.abs(orbit.state[2:])) < 1e-8
    got = np.sort(np.abs(orbit.multipliers))[::-1][:3]
    want = np.sort([1.0, np.exp(-2 * mu * T), np.exp(-decay[0] * T)])[::-1]
    np.testing.assert_allclose(got, want, rtol=1e-6)


@pytest.mark.no_cover  # its long transients: line coverage took it from 52 to 76 s in CI
def test_the_bearing_whirl_branch_from_its_linear_onset() -> None:
    """The default C-GFB at 0 V with suction retained, on 32 x 4 (its flow is smooth): the
    branch starts at the linear onset of the same grid (its smallest cycle within 0.5 %),
    its cycles whirl at the linear frequency (1 %), grow with the speed past the onset
    (supercritical) and are stable. At the speeds of the last two cycles, long fixed-speed
    transients started 10 % outside the last and 10 % inside the one before settle on
    their amplitudes within 1 %, run for twice the periods their own multipliers
    (0.992-0.997 a period) need to leave a tenth of the offset. At 48 steps a revolution:
    shooting restarts the stepper every period, so a cycle of the shooting map differs from
    the limit of a long run by the start-up's error (measured 1.0 % and 1.7 % at the
    orbit's 24 steps a revolution, 0.3 % and 0.5 % at 48: docs/bifurcation.md)."""
    from dataclasses import replace

    from foilbearing.bifurcation.bearing import bearing_flow, whirl_branch
    from foilbearing.case import Grid, default_case

    rpm = np.pi / 30.0
    case = replace(
        default_case(),
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
    ).with_subambient("retained")
    scan = [r * rpm for r in range(5000, 30001, 2500)]
    wb = whirl_branch(case, scan=scan, steps=2, steps_per_rev=48)
    head = wb.headline()
    assert head["bifurcation_type"] == "supercritical"
    speeds, amps = np.array(head["speeds_rpm"]) * rpm, np.array(head["amplitude_um"])
    assert speeds[np.argmin(amps)] == pytest.approx(wb.hopf_speed, rel=5e-3)
    np.testing.assert_allclose(
        head["whirl_frequency_Hz"], wb.whirl_frequency / (2 * np.pi), rtol=0.01
    )
    order = np.argsort(amps)
    assert np.all(np.diff(speeds[order]) > 0) and all(head["stable"])
    _flow, parts = bearing_flow(case, wb.whirl_frequency, 1e-5, steps_per_rev=48)
    for k in (-2, -1):  # at two speeds, from inside and from outside the cycle
        orbit = wb.branch.orbits[k]
        y_e = parts.equilibrium(orbit.parameter)
        start = y_e + (1.1 if k == -1 else 0.9) * (orbit.state - y_e)
        mult = float(np.max(np.abs(orbit.nontrivial_multipliers)))
        periods = 2 * int(np.ceil(np.log(0.1) / np.log(mult)))
        assert periods < 2000
        settle = parts.advance(start, periods * orbit.period, orbit.parameter)
        res = parts.run(settle, orbit.period, orbit.parameter)
        extent = max(np.ptp(res.e_x), np.ptp(res.e_y)) / 2.0
        assert extent == pytest.approx(wb.amplitude[k], rel=0.01)


def test_under_lift_off_the_0V_onset_is_subcritical_as_transients_confirm() -> None:
    """The default C-GFB at 0 V under top-foil lift-off, on 32 x 4, its monodromy from the
    stepper's variational equations: the branch starts at the linear onset of the same grid
    (0.5 %), and its first cycles lie below the onset and are unstable: subcritical. The
    orbit itself confirms it at the second cycle's speed (0.98 of the onset): a transient
    started at 0.6 times that cycle's distance from the equilibrium decays, one started at
    1.5 times grows (measured 1.22 -> 0.64 µm and 3.16 -> 5.40 µm in 60 whirl periods)."""
    from dataclasses import replace

    from foilbearing.bifurcation.bearing import bearing_flow, whirl_branch
    from foilbearing.case import Grid, default_case

    rpm = np.pi / 30.0
    case = replace(
        default_case(),
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
    )
    wb = whirl_branch(case, scan=[r * rpm for r in range(40000, 50001, 2500)], steps=0)
    head = wb.headline()
    assert head["bifurcation_type"] == "subcritical"
    assert head["speeds_rpm"][0] * rpm == pytest.approx(wb.hopf_speed, rel=5e-3)
    assert head["speeds_rpm"][1] * rpm < 0.99 * wb.hopf_speed
    assert not any(head["stable"])
    orbit = wb.branch.orbits[1]
    _flow, parts = bearing_flow(case, wb.whirl_frequency, 1e-4)
    y_e = parts.equilibrium(orbit.parameter)

    def extent_after(factor: float) -> tuple[float, float]:
        y = y_e + factor * (orbit.state - y_e)
        start = parts.run(y, orbit.period, orbit.parameter)
        later = parts.advance(y, 60 * orbit.period, orbit.parameter)
        end = parts.run(later, orbit.period, orbit.parameter)
        size = [max(np.ptp(r.e_x), np.ptp(r.e_y)) / 2.0 for r in (start, end)]
        return size[0], size[1]

    inside, outside = extent_after(0.6), extent_after(1.5)
    assert inside[1] < 0.7 * inside[0]  # decays towards the equilibrium
    assert outside[1] > 1.3 * outside[0]  # grows away from the unstable cycle


def test_an_iterate_past_the_case_speeds_has_no_flow_and_ends_its_newton() -> None:
    """A shooting or continuation iterate whose speed leaves ``(0, max_speed]`` (a corrector
    diverging in the speed) has no flow: NaN, and its Newton iteration ends in a
    :class:`ShootingError` that halves the continuation's step, where it used to stop the
    whole branch with the case's speed error."""
    from foilbearing.bifurcation.bearing import bearing_flow
    from foilbearing.case import Grid, default_case

    case = replace(
        default_case(),
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
    )
    flow, parts = bearing_flow(case, 2 * np.pi * 60.0, 1e-4)
    top = case.operation.max_speed
    y = np.array(parts.equilibrium(0.3 * top))
    assert np.all(np.isnan(parts.advance(y, 0.01, 1.2 * top)))
    assert np.all(np.isnan(parts.tangent(y, 0.01, 1.2 * top, np.eye(y.size)[:, :2])))
    with pytest.raises(ShootingError, match="did not converge"):
        periodic_orbit(flow, y, 0.01, 1.2 * top, normal=np.ones(y.size))


def test_the_bifurcation_command(write_case, capsys, tmp_path) -> None:
    """``foilbearing bifurcation --json`` gives the issue's keys, with the branch's cycles
    the API's; its figure is written, with a speed-up's sub-synchronous amplitude laid over
    it on request; a scan with no onset in it exits 0 with the linear readouts and says so;
    two voltages, an overlay without a figure and a file that is no orbit are one-line
    errors."""
    import json

    from foilbearing.cli.main import main

    path = write_case("coarse_bifurcation", n_theta=32, n_z=4)
    base = ["bifurcation", str(path), "--subambient", "retained", "--steps", "0"]
    scan = ["--speed-range", "5000rpm:30000rpm:2500rpm"]
    assert main([*base, *scan, "--json", "--plot", str(tmp_path)]) == 0
    out = json.loads(capsys.readouterr().out)
    keys = {"bifurcation_type", "hopf_speed_rpm", "speed_limit_rpm", "speeds_rpm"}
    assert keys | {"amplitude_um", "whirl_frequency_Hz", "stable"} <= set(out)
    assert out["bifurcation_type"] == "supercritical" and len(out["speeds_rpm"]) == 2
    assert (tmp_path / "whirl_branch.png").stat().st_size > 10_000
    assert main([*base, "--speed-range", "3000rpm:8000rpm:2500rpm", "--json"]) == 0
    stable = json.loads(capsys.readouterr().out)
    assert stable["bifurcation_type"] is None and "no Hopf point" in stable["message"]
    assert main([*base, "--voltage", "0,150V"]) == 2
    assert "one voltage" in capsys.readouterr().err
    # A speed-up's sub-synchronous amplitude laid over the branch (any orbit file).
    run = tmp_path / "speedup.nc"
    ramp = ["--speed-ramp", "10000rpm:16000rpm:500rad/s**2", "--subambient", "retained"]
    assert main(["orbit", str(path), *ramp, "--out", str(run), "--json"]) == 0
    capsys.readouterr()
    plain = (tmp_path / "whirl_branch.png").stat().st_size
    laid = [*base, *scan, "--json", "--plot", str(tmp_path), "--overlay", str(run)]
    assert main(laid) == 0
    capsys.readouterr()
    assert (tmp_path / "whirl_branch.png").stat().st_size != plain
    assert main([*base, *scan, "--overlay", str(run)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "needs --plot" in err[0]
    assert main([*base, *scan, "--plot", str(tmp_path), "--overlay", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "cannot read it as a run" in err[0] and "orbit --out" in err[0]


def test_the_study_stage_runs_each_reading_as_a_dask_sweep(tmp_path) -> None:
    """The study's stage (issue 31): at 150 V, under the case's reading and the paper's,
    each branch a point of a Dask sweep whose file is written beside it; each row is the
    API's branch (its linear onset and type), the figure is written, and the report's
    section names the readings and the grid; refined on twice the θ cells, each row's
    finer onset is that grid's own and the report prints the errors."""
    from foilbearing.analysis.stability import onset_speed
    from foilbearing.bifurcation.bearing import whirl_branch_headline
    from foilbearing.case import Grid, default_case
    from foilbearing.constants import RPM
    from foilbearing.output.report.sections import _TABLES
    from foilbearing.study.bifurcation import READINGS, SCAN, bifurcation_stage
    from foilbearing.units import parse_quantity

    case = default_case()
    lines: list[str] = []
    out = bifurcation_stage(
        case, tmp_path, lines.append, voltages=(150.0,), steps=0, grid=(32, 4), theta_refine=2
    )
    assert [r["reading"] for r in out["rows"]] == ["local + compliant", "lobe + held"]
    assert all(r["status"] == "ok" and r["cycles"] == 2 for r in out["rows"])
    start, stop, step = (parse_quantity(s, "speed", field="scan") for s in SCAN)
    scan = list(np.arange(start, stop + 0.5 * step, step))
    g = case.grid
    coarse = replace(
        case,
        grid=Grid(
            32,
            4,
            axial_order=g.orbit_order,
            lift_off_smoothing=g.lift_off_smoothing,
            orbit_n_z=None,
            orbit_axial_order=None,
        ),
    ).with_voltages(150.0)
    for row, reading in zip(out["rows"], READINGS, strict=True):
        direct, _ = whirl_branch_headline(coarse.with_actuator_reading(*reading), scan, 0)
        # A worker rounds differently: each onset is within Brent's tolerance of the root,
        # 1e-4 of its bracket's upper speed (at most 2500 rpm above it), two within twice it.
        upper = direct["hopf_speed_rpm"] + 2500.0
        assert row["hopf_speed_rpm"] == pytest.approx(direct["hopf_speed_rpm"], abs=2e-4 * upper)
        assert row["bifurcation_type"] == direct["bifurcation_type"]
        # refined (--theta-refine 2): the finer onset is the 64 × 4 grid's own, and each
        # error printed is at least the two grids' difference
        fine = row["theta_refined"]
        finer = replace(coarse, grid=replace(coarse.grid, n_theta=64, orbit_n_theta=64))
        alone = onset_speed(finer.with_actuator_reading(*reading).orbit_case(), scan)
        assert fine["grid"] == [64, 4]
        high = alone.onset_speed / RPM + 2500.0
        assert fine["hopf_speed_rpm"] == pytest.approx(alone.onset_speed / RPM, abs=2e-4 * high)
        step = abs(fine["hopf_speed_rpm"] - row["hopf_speed_rpm"])
        assert fine["errors"]["hopf_speed_rpm"] >= step
        assert "grid error from 64 θ cells" in fine["text"]
    assert len(out["sweep_files"]) == 4 and out["refined_grid"] == [64, 4]
    assert all(Path(f).exists() for f in out["sweep_files"] + out["figures"])
    html = _TABLES["bifurcation"](out, {})
    assert "lobe + held" in html and "32 × 4" in html and "foilbearing sweep" in html
    assert "64 × 4" in html and " ± " in html


def test_the_study_stage_s_sweep_file_carries_the_whole_orbit_grid(tmp_path) -> None:
    """The stage's sweep file runs its branches on the case's orbit grid as a whole: its
    shape, axial order and lift-off smoothing (the study on an order-4, κ = 0.2 orbit grid
    had run its branches on the sharp law at order 2)."""
    from foilbearing.case import default_case
    from foilbearing.study.bifurcation import READINGS, _sweep_file
    from foilbearing.sweep.spec import load_sweep

    case = default_case()
    case = replace(
        case,
        grid=replace(case.grid, orbit_n_z=4, orbit_axial_order=4, lift_off_smoothing=0.15),
    )
    on = case.orbit_case().grid
    path = tmp_path / "branches.toml"
    path.write_text(_sweep_file(case, (0.0, 150.0), READINGS[1], 1, on), encoding="utf-8")
    spec = load_sweep(path)
    for index in range(spec.n_points):
        point = spec.point_case(index).orbit_case()
        assert point.grid.orbit_shape == (96, 4)
        assert point.grid.orbit_order == 4
        assert point.grid.lift_off_smoothing == 0.15
        assert (point.actuators.preload_response, point.actuators.dynamics) == READINGS[1]
