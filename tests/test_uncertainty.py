"""Uncertainty envelopes and sensitivity indices: the file, the design, the physics they read.

The physical checks run the real analyses on a coarse grid (48 × 6 cells), in
process (each point as the Dask task :func:`run_point` runs it); one test runs
the command on its own local cluster.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from foilbearing.case import case_from_dict, default_case_path
from foilbearing.cli.main import main
from foilbearing.errors import InputError
from foilbearing.static import solve_equilibrium
from foilbearing.sweep.runner import run_point
from foilbearing.uncertainty import load_uncertainty, run_uncertainty, summarise, summary_json
from foilbearing.uncertainty.design import unit_sample
from foilbearing.uncertainty.evaluate import ONSET_REL_TOL, evaluate_sample

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "uncertainty_paper.toml"
COARSE = "[set]\ngrid.n_theta = 48\ngrid.n_z = 6\n"
RPM = math.pi / 30.0


def _write(tmp_path: Path, body: str, name: str = "uq.toml") -> Path:
    path = tmp_path / name
    path.write_text(body, encoding="utf-8")
    return path


def _records(spec) -> dict[int, dict]:
    """Every point evaluated in process, as the sweep engine's Dask task would."""
    return {
        i: run_point(i, spec.point_data(i), spec.point_source(i), evaluate_sample, spec.options)
        for i in range(spec.n_points)
    }


# --------------------------------------------------------------------------- the file and the design


def test_example_file_is_the_issue_s_inputs() -> None:
    spec = load_uncertainty(EXAMPLE)
    lows = {i.name: i.distribution.a / i.scale for i in spec.inputs}
    highs = {i.name: i.distribution.b / i.scale for i in spec.inputs}
    assert lows == pytest.approx(
        {
            "gas.viscosity": 1.8e-5,
            "rotor.mass": 0.45,
            "foil.loss_factor": 0.05,
            "bearing.clearance": 80.0,
            "rotor.imbalance": 1.0,
        }
    )
    assert highs["bearing.clearance"] == pytest.approx(120.0)
    assert highs["rotor.imbalance"] == pytest.approx(8.5)
    # Saltelli design: (samples // (D + 2)) groups of D + 2 evaluations
    assert spec.n_points == (256 // 7) * 7
    # every value inside its distribution's range, in SI
    lo = np.array([i.distribution.a for i in spec.inputs])
    hi = np.array([i.distribution.b for i in spec.inputs])
    assert ((spec.design >= lo) & (spec.design <= hi)).all()
    assert set(spec.outputs) == {"static", "stability"}


def test_saltelli_groups_change_one_input_at_a_time() -> None:
    d = 4
    u = unit_sample(d, 10 * (d + 2), "sobol", "sobol", seed=3).reshape(10, d + 2, d)
    a, b = u[:, 0], u[:, d + 1]
    for i in range(d):
        changed = u[:, 1 + i] != a
        assert changed[:, i].all() and not np.delete(changed, i, axis=1).any()
        assert np.array_equal(u[:, 1 + i, i], b[:, i])


def test_log_uniform_is_uniform_in_the_logarithm(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        'estimator = "rbd_fast"\nsampler = "lhs"\nsamples = 400\n[inputs]\n'
        '"rotor.imbalance" = { distribution = "log-uniform", low = "1 g*mm", high = "8.5 g*mm" }\n'
        '[outputs.static]\nspeeds = ["60000 rpm"]\n',
    )
    x = load_uncertainty(path).design[:, 0]
    # a Latin hypercube puts exactly one point in each of 400 equal-probability strata
    strata = np.floor((np.log(x) - math.log(1e-6)) / (math.log(8.5e-6) - math.log(1e-6)) * 400)
    assert sorted(strata.astype(int)) == list(range(400))


# --------------------------------------------------------------------------- physics read from a sample


def test_inputs_a_static_equilibrium_does_not_see_get_zero_indices(tmp_path: Path) -> None:
    """The equilibrium under a given load does not depend on the rotor mass or the
    foil's loss factor: both enter only the dynamics (the foil damping, the journal's inertia).
    With the Saltelli design both estimators then give exactly 0, whatever N;
    the clearance, which sets the film, carries the variance."""
    path = _write(
        tmp_path,
        "samples = 40\n" + COARSE + "[inputs]\n"
        '"rotor.mass" = { distribution = "uniform", low = "0.45 kg", high = "0.9 kg" }\n'
        '"foil.loss_factor" = { distribution = "uniform", low = 0.05, high = 0.2 }\n'
        '"bearing.clearance" = { distribution = "uniform", low = "80 um", high = "120 um" }\n'
        '[outputs.static]\nspeeds = ["60000 rpm"]\nvoltages = ["150 V"]\n',
    )
    spec = load_uncertainty(path)
    ds = summarise(spec, _records(spec))
    assert (ds["status"] == "ok").all()
    for name in ("rotor.mass", "foil.loss_factor"):
        for key in ("first_order", "total_order"):
            assert np.abs(ds[key].sel(input=name).values).max() < 1e-12, (name, key)
    total = ds["total_order"].sel(input="bearing.clearance").values
    assert (total > 0.5).all()


def test_percentiles_of_a_monotone_output_are_its_values_at_the_input_percentiles(
    tmp_path: Path,
) -> None:
    """Quantiles commute with a monotone map: the 5th/50th/95th percentiles of the
    eccentricity over the sample equal the eccentricity solved directly at the
    clearance's 5th/50th/95th percentiles (82, 100, 118 µm). Tolerance: the
    eccentricity's change over two strata of the 64-point sample (2/64 of the
    range, 1.25 µm): a scrambled Sobol' sample has one point per stratum, and the
    linear interpolation between order statistics moves by up to two."""
    path = _write(
        tmp_path,
        'samples = 24\nestimator = "rbd_fast"\n' + COARSE + "[inputs]\n"
        '"bearing.clearance" = { distribution = "uniform", low = "80 um", high = "120 um" }\n'
        '[outputs.static]\nspeeds = ["60000 rpm"]\nvoltages = ["150 V"]\n',
    )
    with pytest.raises(InputError, match="needs at least 28 samples"):
        load_uncertainty(path)  # RBD-FAST's bias correction and bootstrap need 6 M + 4 (M = 4)
    spec = load_uncertainty(path, samples=64)
    ds = summarise(spec, _records(spec))
    sel = ds.sel(output="eccentricity_ratio[60 krpm, 150 V]")
    data = spec.point_data(0)  # the coarse case; its clearance set below

    def eccentricity(c_um: float) -> float:
        data["bearing"]["clearance"] = f"{c_um} um"
        case = case_from_dict(data).with_voltages(150.0)
        return solve_equilibrium(case, speed=60000 * RPM).eccentricity

    for c_um, got in zip((82.0, 100.0, 118.0), sel["percentile"].values, strict=True):
        e = eccentricity(c_um)
        tol = max(abs(eccentricity(c_um + s) - e) for s in (-1.25, 1.25))
        assert tol > 0.0
        assert got == pytest.approx(e, abs=tol), c_um


# --------------------------------------------------------------------------- the indices as reported


def _synthetic(spec, f) -> dict[int, dict]:
    """Point records whose every output is ``f(u, j)``: u the point's unit values, j the output."""
    from foilbearing.uncertainty.evaluate import output_names

    n_act = len(spec.base.get("actuators", {}).get("angles", []))
    names = [o["name"] for o in output_names(spec.outputs, n_act)]
    lo = np.array([i.distribution.a for i in spec.inputs])
    hi = np.array([i.distribution.b for i in spec.inputs])
    u = (spec.design - lo) / (hi - lo)
    return {
        i: {
            "index": i,
            "status": "ok",
            "result": {"outputs": {n: float(f(u[i], j)) for j, n in enumerate(names)}},
        }
        for i in range(spec.n_points)
    }


def _film_like(u: np.ndarray, j: int) -> float:
    """An output the viscosity (input 0) decides, as the minimum film at 0 V: S1 ≈ 0.96."""
    return 47.0 + 1.5 * u[0] + 0.3 * u[3] ** 2 + 0.01 * (j % 5) * u[1]


def test_screen_keeps_every_index_in_the_unit_interval_or_says_it_is_not_estimable() -> None:
    from foilbearing.uncertainty.design import screen

    raw = np.array([0.4, 2.19, 1.1, -0.1, -0.5, np.nan, 1.0, 0.0])
    conf = np.array([0.1, 0.55, 0.8, 0.3, 0.2, np.nan, 0.0, np.nan])
    value, half, status = screen(raw, conf)
    assert list(status) == [
        "ok",
        "not estimable",  # 2.19 ± 0.55: the whole interval above 1
        "clipped",
        "clipped",
        "not estimable",
        "not estimable",
        "ok",
        "ok",
    ]
    assert np.array_equal(value, [0.4, np.nan, 1.0, 0.0, np.nan, np.nan, 1.0, 0.0], equal_nan=True)
    assert np.array_equal(
        half, [0.1, np.nan, 0.8, 0.3, np.nan, np.nan, 0.0, np.nan], equal_nan=True
    )


def test_the_old_quick_sample_s_sobol_indices_are_clipped_or_marked_not_estimable() -> None:
    """The Sobol' estimator on the 8 base rows of 56 evaluations (the study's quick plan
    before issue 33) puts the dominant input's first order at 1.7 on an output it
    decides (true value 0.96): the report keeps it out, and keeps SALib's number as raw."""
    spec = load_uncertainty(samples=56)
    assert spec.estimator == "sobol" and spec.n_points == 56
    ds = summarise(spec, _synthetic(spec, _film_like))
    raw = ds["first_order_raw"].values
    assert np.nanmax(raw) > 1.5  # what the old report printed
    for kind in ("first_order", "total_order"):
        v = ds[kind].values
        ok = np.isfinite(v)
        assert ((v[ok] >= 0.0) & (v[ok] <= 1.0)).all(), kind
        assert (ds[f"{kind}_status"].values[~ok] == "not estimable").all(), kind
    summary = summary_json(ds)
    film = summary["outputs"]["min_film_um[90 krpm, 0 V]"]
    assert film["first_order"]["gas.viscosity"] is None
    assert film["first_order_status"]["gas.viscosity"] == "not estimable"
    assert film["first_order_raw"]["gas.viscosity"] > 1.5
    assert summary["indices"]["estimator"] == "sobol"
    assert summary["indices"]["n_points"] == 56
    assert "8 base rows" in summary["indices"]["description"]


def test_the_study_s_quick_plan_gives_indices_in_the_unit_interval_and_names_its_estimator(
    tmp_path: Path,
) -> None:
    """The quick plan (RBD-FAST, 64 evaluations) on outputs the viscosity or the
    clearance decides: every index in [0, 1], the deciding input ranked first, the
    estimator and the sample size in the JSON, the dataset and the report."""
    from foilbearing.output.report import render_report
    from foilbearing.output.result import StudyResult
    from foilbearing.study.envelopes import uncertainty_plan

    spec = uncertainty_plan("quick")
    assert (spec.estimator, spec.n_points) == ("rbd_fast", 64)
    assert uncertainty_plan("full").n_points == 252

    def outputs(u: np.ndarray, j: int) -> float:  # odd outputs: the clearance decides
        return _film_like(u, j) if j % 2 == 0 else 100.0 / (0.5 + u[3]) + 2.0 * u[0]

    ds = summarise(spec, _synthetic(spec, outputs))
    s1 = ds["first_order"].values
    ok = np.isfinite(s1)
    assert ok.mean() > 0.9
    assert ((s1[ok] >= 0.0) & (s1[ok] <= 1.0)).all()
    assert (ds["first_order_status"].values[~ok] == "not estimable").all()
    assert np.isnan(ds["total_order"].values).all()
    top = np.nanargmax(np.where(ok, s1, -1.0), axis=1)
    assert (top[0::2] == 0).all() and (top[1::2] == 3).all()
    assert s1[0::2, 0].min() > 0.8
    assert ds.attrs["indices_from"] == "RBD-FAST first order (4 harmonics) from 64 evaluations"
    summary = summary_json(ds)
    assert summary["indices"]["estimator"] == "rbd_fast"
    assert summary["indices"]["n_points"] == 64
    assert "total_order" not in summary["outputs"]["min_film_um[90 krpm, 0 V]"]
    html = render_report(StudyResult.from_summary({"uncertainty": summary}, tmp_path))
    assert "RBD-FAST first order (4 harmonics) from 64 evaluations" in html
    assert "gas.viscosity: " in html and "not estimable at this sample size" in html


def test_on_the_measured_outputs_the_quick_plan_agrees_with_the_full_run() -> None:
    """The built-in file's real outputs (tests/data/uncertainty_issue33.json, the runs of
    docs/uncertainty.md). On the full plan's first 56 points (the old quick plan's
    design) the Sobol' estimator put the viscosity's indices on the minimum film at
    90 krpm, 0 V at 2.07 (first order) and 2.19 (total, the issue's figure): both are
    now not estimable. The quick plan's RBD-FAST on its own 64 points stays in
    [0, 1], ranks the full run's first input first and lies within 0.2 of the full
    run's first order (the largest difference measured over all 47 outputs is 0.17)."""
    from foilbearing.study.envelopes import uncertainty_plan

    data = json.loads((Path(__file__).parent / "data" / "uncertainty_issue33.json").read_text())
    names = list(data["quick"])

    def records(values: dict[str, list[float]]) -> dict[int, dict]:
        n = len(next(iter(values.values())))
        return {
            i: {
                "index": i,
                "status": "ok",
                "result": {"outputs": {k: v[i] for k, v in values.items()}},
            }
            for i in range(n)
        }

    old = summarise(load_uncertainty(samples=56), records(data["old_quick"]))
    film = old.sel(output="min_film_um[90 krpm, 0 V]", input="gas.viscosity")
    assert float(film["first_order_raw"]) > 2.0 and float(film["total_order_raw"]) > 2.1
    assert film["first_order_status"].item() == film["total_order_status"].item() == "not estimable"

    ds = summarise(uncertainty_plan("quick"), records(data["quick"]))
    for name in names:
        s1 = ds["first_order"].sel(output=name).values
        full = np.array(data["full_first_order"][name])
        assert ((s1 >= 0.0) & (s1 <= 1.0)).all(), (name, s1)
        assert np.argmax(s1) == np.argmax(full), name
        assert np.abs(s1 - full).max() < 0.2, (name, s1, full)


def test_estimator_override(tmp_path: Path) -> None:
    """``--estimator`` (load_uncertainty's ``estimator``) replaces the file's; the
    file's own value is still checked."""
    body = '[inputs]\n"foil.loss_factor" = { distribution = "uniform", low = 0.1, high = 0.2 }\n'
    path = _write(tmp_path, "samples = 64\n" + body)
    spec = load_uncertainty(path, estimator="rbd_fast")
    assert (spec.estimator, spec.n_points) == ("rbd_fast", 64)
    assert load_uncertainty(path).n_points == 63  # Sobol': whole groups of 3
    with pytest.raises(InputError, match="--estimator 'fast'"):
        load_uncertainty(path, estimator="fast")
    bad = _write(tmp_path, 'estimator = "fast"\n' + body, "bad.toml")
    with pytest.raises(InputError, match="estimator = 'fast'"):
        load_uncertainty(bad, estimator="rbd_fast")


# --------------------------------------------------------------------------- bad input, one line each


@pytest.mark.parametrize(
    ("body", "message"),
    [
        (
            '[inputs]\n"bearing.nonsense" = { distribution = "uniform", low = 1, high = 2 }\n',
            "inputs.bearing.nonsense: unknown field",
        ),
        (
            '[inputs]\n"bearing.clearance" = { distribution = "uniform", low = "120 um", '
            'high = "80 um" }\n',
            "expected low < high",
        ),
        (
            '[inputs]\n"bearing.clearance" = { distribution = "normal", mean = "100 um", '
            'std = "-5 um" }\n',
            "expected σ > 0",
        ),
        (
            '[inputs]\n"bearing.clearance" = { distribution = "normal", mean = "100 um", '
            'std = "30 um" }\n',
            "outside the field's allowed range",
        ),
        (
            '[inputs]\n"foil.loss_factor" = { distribution = "gamma", low = 0.1, high = 0.2 }\n',
            "expected one of",
        ),
        (
            'samples = 20\n[inputs]\n"foil.loss_factor" = { distribution = "uniform", low = 0.1, '
            "high = 0.2 }\n",
            "needs at least 24 samples",
        ),
        (
            '[inputs]\n"operation.speed" = { distribution = "uniform", low = "1 rpm", '
            'high = "2 rpm" }\n',
            "set by the outputs",
        ),
        (
            '[inputs]\n"grid.lift_off_smoothing" = { distribution = "uniform", low = 0.05, '
            "high = 0.2 }\n",
            "a numerical (grid) setting",
        ),
        (
            '[inputs]\n"foil.loss_factor" = { distribution = "uniform", low = 0.1, high = 0.2 }\n'
            '[outputs.static]\nvoltages = ["200 V"]\n',
            "expected voltages in [0, 150] V",
        ),
        (
            '[inputs]\n"foil.loss_factor" = { distribution = "uniform", low = 0.1, high = 0.2 }\n'
            '[outputs.orbit]\nvoltage_ramp = ["6 s", "6.5 s"]\n',
            "give the voltages it ramps to",
        ),
    ],
)
def test_bad_file_is_one_line_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], body: str, message: str
) -> None:
    path = _write(tmp_path, body)
    assert main(["uncertainty", str(path), "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and message in err and str(path) in err
    assert not (tmp_path / "r").exists()


# --------------------------------------------------------------------------- the command, on Dask


@pytest.mark.slow
def test_command_on_its_own_cluster_persists_resumes_and_plots(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Percentiles and indices, the points persisted as they finish, a resume that
    computes nothing more, and the figures; the JSON has the issue's layout."""
    path = _write(
        tmp_path,
        "samples = 24\n" + COARSE + "[inputs]\n"
        '"gas.viscosity" = { distribution = "uniform", low = "1.8e-5 Pa*s", high = "2.1e-5 Pa*s" }\n'
        '[outputs.static]\nspeeds = ["60000 rpm"]\nvoltages = ["150 V"]\n',
    )
    out, plots = tmp_path / "r", tmp_path / "figs"
    argv = ["uncertainty", str(path), "--out", str(out), "--workers", "1", "--json"]
    assert main([*argv, "--plot", str(plots)]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["n_ok"] == summary["n_points"] == 24
    assert len(list((out / "points").glob("*.json"))) == 24
    film = summary["outputs"]["min_film_um[60 krpm, 150 V]"]
    assert film["p5"] < film["p50"] < film["p95"]
    assert set(film) >= {"p5", "p50", "p95", "first_order", "total_order"}
    assert list(film["first_order"]) == ["gas.viscosity"]
    assert {p.name for p in plots.iterdir()} == {"uncertainty_bands.png", "uncertainty_indices.png"}
    ds = xr.load_dataset(out / "uncertainty.nc")
    assert ds["y"].shape == (24, 7)  # 4 readouts and 3 preloads
    assert main(argv) == 2  # the folder exists: --resume or another --out
    assert "--resume" in capsys.readouterr().err
    assert main([*argv, "--resume", "--grid-check"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert (again["n_computed"], again["n_skipped"]) == (0, 24)
    assert again["outputs"] == summary["outputs"]
    check = again["grid_check"]
    assert (check["grid"], check["refined_grid"]) == ([48, 6], [96, 12])
    assert set(check["outputs"]) == set(summary["outputs"])


def test_a_stopped_run_keeps_what_it_computed(tmp_path: Path) -> None:
    """Interrupted after 3 points: those are on disk and in the dataset, the rest
    missing; --resume then computes only the missing ones."""
    distributed = pytest.importorskip("distributed")
    path = _write(
        tmp_path,
        "samples = 24\n" + COARSE + "[inputs]\n"
        '"gas.viscosity" = { distribution = "uniform", low = "1.8e-5 Pa*s", high = "2.1e-5 Pa*s" }\n'
        '[outputs.static]\nspeeds = ["60000 rpm"]\nvoltages = ["150 V"]\n',
    )
    spec = load_uncertainty(path)

    class _Stop(Exception):
        pass

    seen: list[int] = []

    def stop_after_3(rec: dict) -> None:
        seen.append(rec["index"])
        if len(seen) == 3:
            raise _Stop

    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1) as client:
        with pytest.raises(_Stop):
            run_uncertainty(spec, tmp_path / "r", client=client, on_point=stop_after_3)
        ds = xr.load_dataset(tmp_path / "r" / "uncertainty.nc")
        assert sorted(np.flatnonzero(ds["status"].values == "ok")) == sorted(seen)
        assert (ds["status"] == "missing").sum() == 21
        _, summary = run_uncertainty(spec, tmp_path / "r", client=client, resume=True)
    assert (summary["n_computed"], summary["n_skipped"], summary["n_ok"]) == (21, 3, 24)
    assert summary_json(xr.load_dataset(tmp_path / "r" / "uncertainty.nc"))["n_ok"] == 24


def test_default_file_is_the_example() -> None:
    from foilbearing.uncertainty import default_uncertainty_path

    assert EXAMPLE.resolve() == default_uncertainty_path().resolve()
    assert load_uncertainty().fingerprint() == load_uncertainty(EXAMPLE).fingerprint()
    assert str(default_case_path()).endswith("cgfb.toml")


@pytest.mark.slow
def test_the_linear_onset_does_not_see_the_imbalance_and_falls_with_rotor_mass(
    tmp_path: Path,
) -> None:
    """The imbalance drives the synchronous response only: the linear stability of
    the equilibrium does not see it (exactly 0 indices). A heavier rotor goes
    unstable earlier (the classical critical-mass curve of a gas bearing falls
    with speed): the onset speed falls monotonically with the mass across the
    sample, and the mass carries the variance."""
    path = _write(
        tmp_path,
        "samples = 32\n" + COARSE + "[inputs]\n"
        '"rotor.mass" = { distribution = "uniform", low = "0.45 kg", high = "0.9 kg" }\n'
        '"rotor.imbalance" = { distribution = "log-uniform", low = "1 g*mm", high = "8.5 g*mm" }\n'
        '[outputs.stability]\nvoltages = ["150 V"]\n'
        'speed_range = ["10000 rpm", "150000 rpm", "10000 rpm"]\n',
    )
    spec = load_uncertainty(path)
    ds = summarise(spec, _records(spec))
    onset = ds.sel(output="onset_speed_krpm[150 V]")
    assert int(onset["n_valid"]) == spec.n_points
    for key in ("first_order", "total_order"):
        assert abs(float(onset[key].sel(input="rotor.imbalance"))) < 1e-12
    # the mass's total index is exactly 1 here (the only input that matters): the
    # estimate (N = 8 base rows) must hold it within its 95 % bootstrap half-width
    st = float(onset["total_order"].sel(input="rotor.mass"))
    assert abs(st - 1.0) <= float(onset["total_order_conf"].sel(input="rotor.mass")), st
    mass = ds["x"].sel(input="rotor.mass").values
    order = np.argsort(mass)
    # within Brent's tolerance (ONSET_REL_TOL of the bracket's top): two runs differ by 2
    y = onset["y"].values[order]
    assert np.all(np.diff(y) <= 2 * ONSET_REL_TOL * y.max())
    assert y[0] > y[-1] + 10 * 2e-4 * y.max()


@pytest.mark.slow
def test_the_study_s_stage_and_its_report_section(tmp_path: Path, monkeypatch) -> None:
    """The study's uncertainty stage runs the built-in file (here a small stand-in)
    and the report shows its envelopes: the table's percentiles are the run's,
    both figures are embedded."""
    import foilbearing.uncertainty.spec as uq_spec
    from foilbearing.output.report import render_report
    from foilbearing.output.result import StudyResult
    from foilbearing.study.envelopes import uncertainty_stage

    small = _write(
        tmp_path,
        "samples = 24\n" + COARSE + "[inputs]\n"
        '"bearing.clearance" = { distribution = "uniform", low = "80 um", high = "120 um" }\n'
        '[outputs.static]\nspeeds = ["60000 rpm", "90000 rpm"]\nvoltages = ["150 V"]\n',
    )
    monkeypatch.setattr(uq_spec, "default_uncertainty_path", lambda: small)
    section = uncertainty_stage(tmp_path, "full", lambda line: None, grid_check=2)
    assert section["n_ok"] == 24
    film = section["outputs"]["min_film_um[90 krpm, 150 V]"]
    html = render_report(StudyResult.from_summary({"uncertainty": section}, tmp_path))
    assert "What the unknowns allow" in html
    assert f"{film['p95']:.4g}" in html and "min_film_um[90 krpm, 150 V]" in html
    # each output's grid error at the inputs' centre, 48 x 6 against 96 x 12
    check = section["grid_check"]["outputs"]["min_film_um[90 krpm, 150 V]"]
    assert check["error"] == pytest.approx(check["value"] - check["refined"])
    assert f"{check['error']:+.2g}" in html and "grid error" in html
    assert "--grid-check" in section["command"]
    assert html.count("data:image/png;base64,") == 2


@pytest.mark.slow
def test_orbit_outputs_are_the_orbit_command_s_readouts(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The opt-in orbit outputs of a sample are what ``foilbearing orbit --json``
    reads from the same speed-up (two entry points, one run each): 0 V on a coarse
    48 × 6 grid, 3 to 12 krpm at 500 rad/s², where the 8.5 g·mm run has a
    sub-synchronous onset but no divergence yet; the missing divergence is None,
    with its reason in the point's message."""
    import tomlkit

    data = tomlkit.parse(default_case_path().read_text(encoding="utf-8"))
    data["grid"]["n_theta"], data["grid"]["n_z"] = 48, 6
    (tmp_path / "coarse.toml").write_text(tomlkit.dumps(data), encoding="utf-8")
    path = _write(
        tmp_path,
        'case = "coarse.toml"\nsamples = 24\n[inputs]\n'
        '"foil.loss_factor" = { distribution = "uniform", low = 0.05, high = 0.2 }\n'
        "[outputs.orbit]\n"
        'speed_ramp = ["3000 rpm", "12000 rpm", "500 rad/s**2"]\nvoltages = ["0 V"]\n',
    )
    spec = load_uncertainty(path)
    point = spec.point_data(0)
    rec = run_point(0, point, spec.point_source(0), evaluate_sample, spec.options)
    assert rec["status"] == "ok", rec
    got = rec["result"]["outputs"]
    (tmp_path / "point.toml").write_text(tomlkit.dumps(point), encoding="utf-8")
    argv = ["orbit", str(tmp_path / "point.toml"), "--speed-ramp", "3000rpm:12000rpm:500rad/s**2"]
    assert main([*argv, "--json"]) == 0
    direct = json.loads(capsys.readouterr().out)
    assert direct["onset_speed_rpm"] is not None and direct["divergence_speed_rpm"] is None
    assert got["orbit_onset_krpm[0 V]"] == pytest.approx(direct["onset_speed_rpm"] / 1e3)
    assert got["orbit_whip_frequency_Hz[0 V]"] == pytest.approx(direct["whip_frequency_Hz"])
    assert got["orbit_max_subsync_um[0 V]"] == pytest.approx(direct["max_subsync_amplitude_um"])
    assert got["orbit_divergence_krpm[0 V]"] is None
    assert "no divergence up to" in rec["result"]["message"]


@pytest.mark.slow
def test_points_without_any_output_are_failed_and_recorded(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A scan that starts above every onset (100 krpm at 150 V; the onset is near
    55 krpm) gives no onset anywhere: each point is recorded as failed with its
    reason, the run completes, the exit code is 3 and the percentiles are null."""
    path = _write(
        tmp_path,
        "samples = 24\n" + COARSE + "[inputs]\n"
        '"foil.loss_factor" = { distribution = "uniform", low = 0.05, high = 0.2 }\n'
        '[outputs.stability]\nvoltages = ["150 V"]\n'
        'speed_range = ["100000 rpm", "150000 rpm", "10000 rpm"]\n',
    )
    out = tmp_path / "r"
    argv = ["uncertainty", str(path), "--out", str(out), "--workers", "1", "--json"]
    assert main(argv) == 3
    summary = json.loads(capsys.readouterr().out)
    assert (summary["n_failed"], summary["n_ok"]) == (24, 0)
    assert summary["outputs"]["onset_speed_krpm[150 V]"]["p50"] is None
    ds = xr.load_dataset(out / "uncertainty.nc")
    assert all("unstable already at 100000 rpm" in e for e in ds["error"].values)
    assert len(list((out / "points").glob("*.json"))) == 24
