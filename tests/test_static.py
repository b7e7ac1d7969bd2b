"""Static analysis: equilibrium, limits, and the paper's static results (Figs. 9-12).

Paper numbers and trends are from docs/model.md §6. The viscosity (1.85e-5 Pa s) is our
choice (the paper does not give it) and the grid is the default 96 x 12, so published values
are checked with stated tolerances rather than digits.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Foil, default_case
from foilbearing.errors import InputError
from foilbearing.film import film_model
from foilbearing.static import film_at_position, solve_equilibrium
from foilbearing.study.static import static_sweep

RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def sweep():
    """C-GFB and shimmed GFB at 0/50/100/150 V and 10/30/50/90 krpm (continuation in speed)."""
    return static_sweep(
        default_case(),
        [10e3 * RPM, 30e3 * RPM, 50e3 * RPM, 90e3 * RPM],
        [0.0, 50.0, 100.0, 150.0],
    )


def test_equilibrium_balances_the_load() -> None:
    case = default_case().with_voltages(150.0)
    res = solve_equilibrium(case, speed=50e3 * RPM)
    assert res.converged, res.message
    fx, fy = res.force
    w = case.operation.load
    assert math.hypot(fx + w, fy) / w < 1e-6
    assert np.all(np.isfinite(res.P)) and res.H.min() > 0


def test_block_cyclic_and_superlu_give_the_same_equilibrium(monkeypatch) -> None:
    # The static Newton factorises dR/dP with the compiled block-cyclic LU; with SuperLU
    # instead (its fallback) the iterates and the equilibrium must be the same.
    import foilbearing.reynolds.blocksolve as blocksolve
    import foilbearing.reynolds.steady as steady
    import foilbearing.static as static

    case = default_case().with_voltages(150.0)
    block = solve_equilibrium(case, speed=50e3 * RPM)

    calls = []

    def superlu(data, indices, indptr, n_theta, n_z):
        calls.append(n_theta)
        return blocksolve.TransposedSuperLU(data, indices, indptr, n_theta * n_z)

    monkeypatch.setattr(static, "factor_coupled", superlu)
    monkeypatch.setattr(steady, "factor_coupled", superlu)
    reference = solve_equilibrium(case, speed=50e3 * RPM)
    assert block.converged and reference.converged and calls
    assert block.iterations == reference.iterations
    np.testing.assert_allclose(
        [block.eps_x, block.eps_y], [reference.eps_x, reference.eps_y], rtol=1e-9
    )
    np.testing.assert_allclose(block.P, reference.P, rtol=1e-9)


def test_equilibrium_is_independent_of_the_start() -> None:
    case = default_case().with_voltages(100.0)
    a = solve_equilibrium(case, speed=30e3 * RPM)
    b = solve_equilibrium(case, speed=30e3 * RPM, start=(0.3, -0.2, None))
    assert a.converged and b.converged
    assert abs(a.eps_x - b.eps_x) < 1e-7 and abs(a.eps_y - b.eps_y) < 1e-7


def test_journal_sinks_along_the_load_at_low_speed() -> None:
    # As the speed falls the bearing number vanishes, the film needs a near-closed wedge
    # and the line of centres turns towards the load: ε -> 1 (into the foil), φ -> 0.
    case = default_case()
    att = []
    for rpm in (1e3, 3e3, 10e3):
        res = solve_equilibrium(case, speed=rpm * RPM)
        assert res.converged, res.message
        att.append(math.degrees(res.attitude_angle))
    assert att[0] < att[1] < att[2]
    assert att[0] < 15.0


def test_concentric_rigid_journal_without_preload() -> None:
    case = replace(default_case(), foil=None, actuators=None)
    res = film_at_position(case, 0.0, 0.0, speed=50e3 * RPM)
    np.testing.assert_allclose(res.P, 1.0, atol=1e-12)
    assert abs(res.force[0]) < 1e-9 and abs(res.force[1]) < 1e-9
    # Petroff's torque for the concentric journal: T = 2π μ ω R³ L / C, exactly on any grid.
    b, mu, omega = case.bearing, case.gas.viscosity, 50e3 * RPM
    petroff = 2 * math.pi * mu * omega * b.radius**3 * b.length / b.clearance
    assert res.drag_torque == pytest.approx(petroff, rel=1e-12)


def test_stiff_foil_tends_to_rigid_bearing() -> None:
    # With the suction retained a very stiff foil is a rigid surface; under lift-off it is
    # not (a rigid surface holds suction), and the journal, pushed by no sub-ambient film,
    # sits further along the load.
    base = default_case()
    rigid = replace(base, foil=None, actuators=None)
    stiff = replace(
        base, foil=Foil(bump_stiffness=1e16, loss_factor=0.1, subambient="retained"), actuators=None
    )
    soft = replace(
        base, foil=Foil(bump_stiffness=1e9, loss_factor=0.1, subambient="retained"), actuators=None
    )
    lifted = replace(stiff, foil=replace(stiff.foil, subambient="lift-off"))
    assert (
        solve_equilibrium(lifted, speed=40e3 * RPM).eccentricity
        > solve_equilibrium(rigid, speed=40e3 * RPM).eccentricity
    )
    r, s, f = (solve_equilibrium(c, speed=40e3 * RPM) for c in (rigid, stiff, soft))
    assert r.converged and s.converged and f.converged
    assert abs(r.eps_x - s.eps_x) < 1e-5 and abs(r.eps_y - s.eps_y) < 1e-5
    # A soft foil lets the journal sink further into the bearing.
    assert f.eccentricity > r.eccentricity


def test_reported_preload_is_eq3b() -> None:
    """Eq. (3b): r_p = r_base − p_A/(k_p + 4 k_sp) where the film pushes the stinger, and
    r_base where it does not. The stiffness is the paper's (k_p = 1.30e9 N/m³ identified,
    k_sp = 3.95e6 N/m³ per spring, slip S1), not the model's; the base preload at 150 V is
    the paper's 72.92 µm (to 0.05 %, its rounding and the identified D33). With the suction
    retained and the journal at 0.6 C towards 30°, the 300° actuator faces a sub-ambient
    film (p_A ≈ −8.9 kPa): its preload stays the base one."""
    case = default_case().with_voltages(150.0).with_subambient("retained")
    k_act = 1.30e9 + 4 * 3.95e6
    assert case.actuators is not None
    assert case.actuators.base_preloads() == pytest.approx([72.92e-6] * 3, rel=5e-4)
    at = math.radians(30.0)
    res = film_at_position(case, 0.6 * math.cos(at), 0.6 * math.sin(at), speed=30e3 * RPM)
    p_a = res.actuator_pressure
    assert p_a[0] > 0.0 and p_a[1] > 0.0 and p_a[2] < 0.0  # both branches run
    base = case.actuators.base_preloads()
    assert res.preload[2] == base[2]
    for n in (0, 1):  # k_p is given to 3 figures: 0.2 % of the preload here
        assert res.preload[n] == pytest.approx(base[n] - p_a[n] / k_act, rel=2e-3)


def test_paper_preloads_at_150V_90krpm() -> None:
    # Paper Fig. 11: 65.36 / 54.06 / 64.62 um at 60/180/300 deg. Under lift-off we find
    # 66.06 / 54.92 / 65.22 um (+1.1 / +1.6 / +0.9 %): the tolerance is 3 %, which dropping
    # the foil's or the actuator's compliance (-11.5 / -9.7 % at 180 deg) would break.
    res = solve_equilibrium(default_case().with_voltages(150.0), speed=90e3 * RPM)
    np.testing.assert_allclose(res.preload * 1e6, [65.36, 54.06, 64.62], rtol=0.03)
    # Abstract: reductions up to ~11 % at 60/300 deg, far more at the loaded 180 deg, where
    # Fig. 11 reads 1 - 54.06/72.92 = 25.9 %; ours within 3 percentage points of it.
    reduction = 1.0 - res.preload / 72.92e-6
    assert reduction[1] == pytest.approx(0.259, abs=0.03)
    assert max(reduction[0], reduction[2]) < 0.12


def test_fig9_peaks_at_actuators_grow_with_voltage_and_cgfb_below_shims(sweep) -> None:
    at50 = sweep.sel(speed=50.0)
    p180 = at50.actuator_pressure.sel(actuator=180.0)
    # Pressure at the loaded actuator rises with voltage, for both bearings.
    assert np.all(np.diff(p180.sel(bearing="C-GFB").values) > 0)
    assert np.all(np.diff(p180.sel(bearing="shimmed").values) > 0)
    # The compliant actuators give lower peaks and a thicker minimum film than rigid shims,
    # most at 180 deg (compare the 150 V case).
    hi = at50.sel(voltage=150.0)
    cg, sh = hi.sel(bearing="C-GFB"), hi.sel(bearing="shimmed")
    assert float(cg.midplane_pressure.max()) < float(sh.midplane_pressure.max())
    assert float(cg.min_film) > float(sh.min_film)
    gap = (sh.actuator_pressure - cg.actuator_pressure).values
    assert np.argmax(gap) == 1  # the 180 deg actuator


def test_fig10_local_pressure_trends(sweep) -> None:
    cg = sweep.sel(bearing="C-GFB", voltage=150.0)
    for angle in (60.0, 300.0):
        p = cg.actuator_pressure.sel(actuator=angle).values
        assert np.all(np.diff(p) > 0)  # rises with speed
    # At the loaded 180 deg the pressure first falls then rises with speed (paper Fig. 10):
    # under lift-off the minimum is near 30 krpm at 150 V.
    p180 = cg.actuator_pressure.sel(actuator=180.0).values
    k = int(np.argmin(p180))
    assert 0 < k < p180.size - 1 and p180[-1] > p180[0]
    # C-GFB below the shimmed GFB at every speed for 100 and 150 V.
    for volt in (100.0, 150.0):
        sel = sweep.sel(voltage=volt, actuator=180.0).actuator_pressure
        assert np.all(sel.sel(bearing="C-GFB").values < sel.sel(bearing="shimmed").values)


def test_fig12_eccentricity_trends(sweep) -> None:
    for bearing in ("C-GFB", "shimmed"):
        for volt in sweep.voltage.values:
            ecc = sweep.eccentricity.sel(bearing=bearing, voltage=volt).values
            assert np.all(np.diff(ecc) < 0)  # falls with speed
    # The C-GFB sits more eccentric than the shimmed GFB (its preload at 180 deg is lower).
    # We find this at 150 V at every speed; at 50 and 100 V the two differ by under 2 % and
    # the order changes with speed (reported beside the paper's figure in the study).
    e = sweep.eccentricity.sel(voltage=150.0)
    assert np.all(e.sel(bearing="C-GFB").values > e.sel(bearing="shimmed").values)


def test_equilibrium_grid_convergence() -> None:
    # Eccentricity on three grids refined by 2: the differences shrink at about second order.
    case = default_case().with_voltages(100.0)
    ecc = []
    for n_theta, n_z in ((48, 6), (96, 12), (192, 24)):
        res = solve_equilibrium(case, speed=50e3 * RPM, model=film_model(case, n_theta, n_z))
        assert res.converged
        ecc.append(res.eccentricity)
    d1, d2 = abs(ecc[1] - ecc[0]), abs(ecc[2] - ecc[1])
    order = math.log2(d1 / d2)
    assert 1.5 < order < 2.6, (ecc, order)
    assert d2 / ecc[2] < 5e-3  # the default grid is within 0.5 % of the finest


def test_a_fine_grid_started_from_the_coarser_one_finds_the_same_equilibrium(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Grid sequencing (a cold start on 192 × 24 from the 96 × 12 equilibrium, its
    pressures repeated 2 × 2) and the start from the centre are two routes to one
    equilibrium: the same ε to 1e-9 of C, in under half the Newton iterations on the fine
    grid (11 against 40 at 50 krpm, 150 V; 12 against 239 on 384 × 48 near the onset)."""
    import foilbearing.analysis.equilibrium as equilibrium

    case = default_case().with_voltages(150.0)
    fine = replace(case, grid=replace(case.grid, n_theta=192, n_z=24))
    sequenced = solve_equilibrium(fine, speed=50e3 * RPM)
    monkeypatch.setattr(equilibrium, "SEQUENCE_ABOVE_CELLS", 10**9)
    centred = solve_equilibrium(fine, speed=50e3 * RPM)
    assert sequenced.converged and centred.converged
    assert abs(sequenced.eps_x - centred.eps_x) < 1e-9
    assert abs(sequenced.eps_y - centred.eps_y) < 1e-9
    assert 2 * sequenced.iterations < centred.iterations


def test_bad_inputs() -> None:
    case = default_case()
    with pytest.raises(InputError, match="speed"):
        solve_equilibrium(case, speed=0.0)
    heavy = replace(case, operation=replace(case.operation, load=300.0))
    res = solve_equilibrium(heavy, speed=1e3 * RPM)
    assert not res.converged
    assert "Try" in res.message and np.isfinite(res.eccentricity)
    rigid = replace(case, foil=None, actuators=None)
    with pytest.raises(InputError, match="closes the film"):
        film_at_position(rigid, 1.2, 0.0)


def test_a_zero_load_is_a_centred_journal(write_case, capsys) -> None:
    """``operation.load = "0 N"`` (allowed): the force balance is tested absolutely where
    the load is zero (static.FORCE_FLOOR), and the unloaded journal sits at the centre.

    The three actuators 120° apart make the bearing three-fold symmetric, so the film force
    at the centre is zero and the centred journal's stiffness is isotropic, K_XX = K_YY and
    K_XY = -K_YX (the only 2 x 2 tensors unchanged by a 120° turn). On 48 x 4 the grid shares
    the symmetry: both hold to round-off. On 32 x 4 it does not: ε = 4.6e-5, within 1e-3.
    """
    from foilbearing.cli.main import main
    from foilbearing.coefficients import force_coefficients

    base = default_case()
    unloaded = replace(base.operation, load=0.0)
    centred = {}
    for n_theta, tol in ((48, 1e-9), (32, 1e-3)):
        case = replace(base, grid=replace(base.grid, n_theta=n_theta, n_z=4), operation=unloaded)
        res = centred[n_theta] = solve_equilibrium(case)
        assert res.converged and "continuation" not in res.message, res.message
        assert res.eccentricity < tol
        assert np.all(np.abs(res.force) < 1e-9)  # N, against the 8.8 N of the case's load
    (k,) = force_coefficients(centred[48], [2 * math.pi * 500.0]).K
    scale = float(np.max(np.abs(k)))
    assert abs(k[0, 0] - k[1, 1]) < 1e-9 * scale and abs(k[0, 1] + k[1, 0]) < 1e-9 * scale
    path = write_case(
        "unloaded", n_theta=48, n_z=4, edit=lambda d: d["operation"].update(load="0 N")
    )
    argv = ["stability", str(path), "--voltage", "0V", "--speed-range"]
    assert main([*argv, "20000rpm:60000rpm:20000rpm", "--json"]) == 0
    (entry,) = json.loads(capsys.readouterr().out)["voltages"]
    assert entry["whirl_frequency_Hz"] > 0.0
