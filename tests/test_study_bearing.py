"""The study of any bearing: the plan from the case and its [study] table, the stages
that apply to a passive foil bearing and a rigid gas bearing, bad input before work.

Physics on a coarse grid (32 x 4): each stage's readouts are checked against a fact
that does not depend on the grid (a gas bearing lifts as it speeds up and sinks as
it is loaded; the least stable mode's log decrement changes sign at the onset the
Brent search finds from another set of equilibria).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from foilbearing.case import load_case
from foilbearing.cli.main import main
from foilbearing.errors import InputError
from foilbearing.identification import example_measurements
from foilbearing.study.plan import study_plan

RPM = math.pi / 30.0


def _passive(d) -> None:
    del d["actuators"]


def _rigid(d) -> None:
    del d["actuators"]
    del d["foil"]


def test_plan_defaults_and_the_study_table(write_case) -> None:
    plan = study_plan(load_case(write_case("gfb", edit=_passive)))
    assert plan.kind == "GFB"
    assert [w / RPM for w in plan.speeds] == pytest.approx(np.arange(5000, 50001, 5000))
    assert plan.onset_top == pytest.approx(150_000 * RPM) and plan.loads == ()
    assert plan.orbit and plan.orbit_acceleration == 500.0
    assert plan.onset_scan()[-1] == pytest.approx(150_000 * RPM)

    def table(d) -> None:
        _rigid(d)
        d["study"] = {
            "speed_range": ["20000 rpm", "60000 rpm", "20000 rpm"],
            "loads": ["20 N", "5 N"],
            "orbit": False,
            "reference": {"onset_speed": "30000 rpm", "whirl_frequency": "55 Hz"},
        }

    plan = study_plan(load_case(write_case("rigid", edit=table)))
    assert plan.kind == load_case(write_case("r2", edit=_rigid)).kind == "rigid"
    assert [w / RPM for w in plan.speeds] == pytest.approx([20000, 40000, 60000])
    assert plan.loads == (5.0, 20.0) and not plan.orbit
    assert plan.reference == pytest.approx({"onset_speed": 30000 * RPM, "whirl_frequency": 55.0})


@pytest.mark.parametrize(
    ("study", "match"),
    [
        ({"speeds": ["1 rpm"]}, r"unknown field 'speeds' in \[study\]"),
        ({"speed_range": ["1000 rpm", "200000 rpm", "1000 rpm"]}, "max_speed = 150000 rpm"),
        ({"orbit": "yes"}, "study.orbit = 'yes': expected true or false"),
        ({"loads": ["-1 N"]}, "loads >= 0 N"),
        ({"reference": {"onset": "1 rpm"}}, r"unknown field 'onset' in \[study.reference\]"),
        ({"map_speeds": ["500000 rpm"]}, "up to operation.max_speed"),
        ({"shim_scales": [1.0]}, r"nothing: this bearing has no \[shims\]"),
    ],
)
def test_bad_study_tables_are_one_line_errors(write_case, capsys, study, match) -> None:
    def edit(d) -> None:
        _passive(d)
        d["study"] = study

    path = write_case("bad", edit=edit)
    with pytest.raises(InputError, match=match) as err:
        study_plan(load_case(path))
    assert "\n" not in str(err.value) and "bad.toml" in str(err.value)
    assert main(["study", str(path), "--out", str(path.parent / "out")]) == 2
    assert not (path.parent / "out").exists(), "an error before any work writes nothing"


def test_a_load_no_speed_can_carry_is_refused_before_work(write_case, capsys) -> None:
    def heavy(d) -> None:
        _rigid(d)
        d["operation"]["load"] = "5000 N"

    path = write_case("heavy", n_theta=32, n_z=4, edit=heavy)
    assert main(["study", str(path), "--out", str(path.parent / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert "operation.load = 5000 N: no equilibrium even at the top speed" in err
    assert "\n" not in err and not (path.parent / "out").exists()


@pytest.mark.slow
def test_passive_foil_bearing_study_runs_every_stage(write_case, tmp_path: Path, capsys) -> None:
    path = write_case("gfb", n_theta=32, n_z=4, edit=_passive)
    # --theta-refine 1: the refined branch is checked on the rigid bearing and in the report
    argv = ["study", str(path), "--out", str(tmp_path), "--orbits", "none", "--json"]
    assert main([*argv, "--theta-refine", "1"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "paper_comparison" not in out and out["plan"]["bearing_kind"] == "GFB"
    static = out["bearing_static"]["points"]
    assert all(p["converged"] for p in static)
    # a gas bearing lifts as it speeds up: eccentricity falls, the minimum film grows
    assert np.all(np.diff([p["eccentricity"] for p in static]) < 0)
    assert np.all(np.diff([p["min_film_um"] for p in static]) > 0)
    # and sinks as it is loaded, until the film closes (the curve's last point)
    load = out["load_capacity"]["points"]
    assert np.all(np.diff([p["eccentricity"] for p in load if p["converged"]]) > 0)
    assert not load[-1]["converged"] or load[-1]["min_film_um"] < 0.02 * 100.0
    # the log decrement at the static points first turns negative where Brent, on its own
    # equilibria, puts the onset (on this coarse grid it hovers near zero after that)
    stab = out["bearing_stability"]
    onset = stab["onset"]["onset_speed_rpm"]
    dec = [(m["speed_rpm"], m["log_decrement"]) for m in stab["modes"]]
    first = next(k for k, (_, d) in enumerate(dec) if d < 0)
    assert onset is not None and dec[first - 1][0] < onset < dec[first][0]
    assert all(d > 0 for w, d in dec[:first])
    assert len(out["bearing_coefficients"]["synchronous"]) == len(static)
    html = (tmp_path / "report.html").read_text()
    assert '<section id="plan"' in html and '<section id="comparison"' not in html
    for name in ("static_vs_speed", "load_capacity", "coefficients_vs_speed", "log_decrement"):
        assert (tmp_path / f"{name}.png").stat().st_size > 10_000


def test_rigid_bearing_with_reference_values_and_its_orbit(
    write_case, tmp_path: Path, capsys
) -> None:
    def edit(d) -> None:
        _rigid(d)
        d["rotor"]["imbalance"] = "1 g*mm"
        d["study"] = {
            "speed_range": ["10000 rpm", "12000 rpm", "1000 rpm"],
            "orbit_acceleration": "2000 rad/s**2",
            "reference": {"onset_speed": "30000 rpm", "divergence_speed": "50000 rpm"},
        }

    path = write_case("rigid", n_theta=32, n_z=4, edit=edit)
    assert main(["study", str(path), "--out", str(tmp_path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["plan"]["bearing_kind"] == "rigid"
    orbit = out["bearing_orbit"]
    assert orbit["end_speed_rpm"] == pytest.approx(12000, rel=1e-3) or orbit["status"] == "contact"
    assert orbit["mean_power_loss_W"] > 0
    # the CLI's default --theta-refine 2: the speed-up again on 64 θ cells, its file beside
    assert orbit["theta_refined"]["grid"] == [64, 4]
    assert (tmp_path / "orbit_speedup_theta2x.nc").is_file()
    rows = {r["quantity"].split(" (")[0]: r for r in out["reference_comparison"]["rows"]}
    onset = rows["linear onset speed of instability"]
    assert onset["reference"] == pytest.approx(30000.0)
    if onset["ours"] is not None:
        assert onset["deviation_percent"] == pytest.approx(100 * (onset["ours"] / 30000 - 1))
    assert "divergence speed of the speed-up orbit" in rows
    assert '<section id="reference_comparison"' in (tmp_path / "report.html").read_text()


def test_a_speed_up_that_cannot_start_is_recorded_not_fatal(
    write_case, tmp_path: Path, capsys
) -> None:
    # A rigid bearing cannot carry 20 N at 3 krpm (its film would close) but can at
    # 12 krpm: the static points at 3 krpm fail, and so does the orbit's start; both
    # are recorded with what to try, and the study goes on to its report.
    def edit(d) -> None:
        _rigid(d)
        d["operation"]["load"] = "20 N"
        d["study"] = {
            "speed_range": ["3000 rpm", "12000 rpm", "9000 rpm"],
            "onset_top": "12000 rpm",
        }

    path = write_case("rigid_low", n_theta=32, n_z=4, edit=edit)
    assert main(["study", str(path), "--out", str(tmp_path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    first, last = out["bearing_static"]["points"]
    assert not first["converged"] and "try" in first["message"] and last["converged"]
    orbit = out["bearing_orbit"]
    assert orbit["status"] == "failed" and "could not start at 3000 rpm" in orbit["message"]
    assert "speed_range" in orbit["message"]
    assert '<section id="bearing_orbit"' in (tmp_path / "report.html").read_text()


@pytest.mark.slow
def test_shimmed_bearing_onset_against_shim_thickness(write_case, tmp_path: Path, capsys) -> None:
    """Shims of zero thickness are no shims: their onset is the passive bearing's, found
    by another route (a case without [shims]). Thick shims preload the foil and delay
    the onset (75 um: measured about 2.4 times later on the default grid)."""

    def shimmed(d) -> None:
        _passive(d)
        d["shims"] = {"angles": ["60 deg", "180 deg", "300 deg"], "arc": "27.7 deg"}
        d["shims"]["thickness"] = "50 um"
        d["study"] = {"orbit": False, "speed_range": ["10000 rpm", "50000 rpm", "10000 rpm"]}

    path = write_case("shimmed", n_theta=32, n_z=4, edit=shimmed)
    assert main(["study", str(path), "--out", str(tmp_path), "--json", "--theta-refine", "1"]) == 0
    rows = {r["scale"]: r for r in json.loads(capsys.readouterr().out)["shim_stability"]["rows"]}
    assert sorted(rows) == [0.0, 0.5, 1.0, 1.5]

    def passive(d) -> None:
        _passive(d)
        d["study"] = {"orbit": False, "speed_range": ["10000 rpm", "50000 rpm", "10000 rpm"]}

    bare = write_case("bare", n_theta=32, n_z=4, edit=passive)
    bare_out = ["--out", str(tmp_path / "bare"), "--json", "--theta-refine", "1"]
    assert main(["study", str(bare), *bare_out]) == 0
    onset = json.loads(capsys.readouterr().out)["bearing_stability"]["onset"]
    assert rows[0.0]["onset_speed_rpm"] == pytest.approx(onset["onset_speed_rpm"], rel=1e-9)
    assert rows[1.5]["onset_speed_rpm"] > 1.5 * rows[0.0]["onset_speed_rpm"]


@pytest.mark.slow
def test_a_cgfb_other_than_the_papers_gets_its_own_plan(write_case, tmp_path: Path, capsys) -> None:
    """A C-GFB case from another file runs the plan: onset and static readouts against
    voltage, the schedule over the plan's speeds, the identification from its own stack
    files, reference values at the case speed, and a speed-up with a voltage ramp. It
    shows no paper comparison. Facts checked: the voltages' preload delays the onset
    (0 -> 150 V) and raises every actuator's preload; an equilibrium continued from the
    last voltage is the one found from the centre; the synchronous coefficients beside
    the reference are those of a separate linearisation at the case speed; the orbit
    applies the ramp (case's 0 V before it, 150 V after)."""
    import shutil

    import xarray as xr

    from foilbearing.coefficients import force_coefficients
    from foilbearing.orbit.spec import PiecewiseVoltages, RunSpec
    from foilbearing.static import solve_equilibrium

    def edit(d) -> None:
        d["operation"]["speed"] = "40000 rpm"
        d["rotor"]["imbalance"] = "1 g*mm"
        d["study"] = {
            "speed_range": ["30000 rpm", "40000 rpm", "10000 rpm"],
            "voltages": ["0 V", "75 V", "150 V"],
            "orbit_acceleration": "4000 rad/s**2",
            "orbit_voltage_ramp": {"start": "0.05 s", "end": "0.1 s", "voltage": "150 V"},
            "identification": {"no_load": "data/no_load.csv", "stiffness": "data/k.csv"},
            "reference": {"K_xx": "2e6 N/m", "C_yx": "-50 N*s/m", "eccentricity": 0.5},
        }

    path = write_case("mine", n_theta=32, n_z=4, edit=edit)
    (path.parent / "data").mkdir()
    no_load, stiffness = example_measurements()
    shutil.copy(no_load, path.parent / "data" / "no_load.csv")
    shutil.copy(stiffness, path.parent / "data" / "k.csv")
    assert main(["study", str(path), "--out", str(tmp_path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["plan"]["bearing_kind"] == "C-GFB" and out["plan"]["voltages_V"] == [0, 75, 150]
    assert "paper_comparison" not in out
    rows = {r["voltage_V"]: r for r in out["voltage_stability"]["rows"]}
    assert rows[150.0]["onset_speed_rpm"] > rows[0.0]["onset_speed_rpm"]
    sched = out["schedule"]["schedule"]
    assert sched["speeds_rpm"] == pytest.approx([30000, 40000])
    assert (tmp_path / "schedule.png").exists()

    case = load_case(path)
    points = out["actuator_static"]["points"]
    assert [p["voltage_V"] for p in points] == [0, 75, 150] and all(p["converged"] for p in points)
    assert np.all(np.diff([p["preload_um"] for p in points], axis=0) > 0)
    fresh = solve_equilibrium(case.with_voltages(150.0), speed=case.operation.speed)
    assert points[-1]["eccentricity"] == pytest.approx(fresh.eccentricity, rel=1e-5)
    assert (tmp_path / "preloads_vs_voltage.png").stat().st_size > 10_000

    data = path.parent / "data"
    assert main(["identify", str(data / "no_load.csv"), str(data / "k.csv"), "--json"]) == 0
    alone = json.loads(capsys.readouterr().out)
    ident = out["identification"]
    assert ident["k_p_N_per_m3"] == pytest.approx(alone["k_p_N_per_m3"], rel=1e-12)
    assert set(ident["for_the_case_file"]) == {"d33_quadratic", "d33_linear", "stack_stiffness"}
    assert (tmp_path / "stack_stiffness.png").exists()

    st = solve_equilibrium(case, speed=case.operation.speed)
    fc = force_coefficients(st, case.operation.speed)
    ref = {r["quantity"].split(" (")[0]: r for r in out["reference_comparison"]["rows"]}
    kxx = ref["synchronous stiffness KXX at the case speed"]
    assert kxx["ours"] == pytest.approx(float(fc.K[0][0, 0]), rel=1e-6) and kxx["ours"] > 0
    assert kxx["deviation_percent"] == pytest.approx(100 * (kxx["ours"] / 2e6 - 1))
    assert ref["synchronous damping CYX at the case speed"]["reference"] == -50.0
    assert ref["eccentricity ratio at the case speed and load"]["ours"] == pytest.approx(
        st.eccentricity, rel=1e-6
    )

    orbit = xr.load_dataset(out["bearing_orbit"]["netcdf"])
    t, volts = orbit.time.values, orbit.voltage.values
    assert np.all(volts[t < 0.05] == 0.0) and np.allclose(volts[t > 0.1], 150.0)
    ramp = RunSpec.from_json(orbit.attrs["run_spec"]).voltage  # the ramp, stored as data
    assert ramp == PiecewiseVoltages((0.05, 0.1), ((0.0,) * 3, (150.0,) * 3))
    html = (tmp_path / "report.html").read_text()
    assert '<section id="actuator_static"' in html and '<section id="identification"' in html


@pytest.mark.parametrize(
    ("study", "match"),
    [
        ({"orbit_voltage_ramp": {"start": "1 s", "end": "0.5 s", "voltage": "150 V"}},
         "study.orbit_voltage_ramp.end = '0.5 s': expected a time at or after start"),
        ({"orbit_voltage_ramp": {"start": "1 s", "end": "2 s", "voltage": "200 V"}},
         "max_voltage = 150 V"),
        ({"orbit_voltage_ramp": {"start": "1 s", "end": "2 s"}},
         "study.orbit_voltage_ramp.voltage is missing"),
        ({"identification": {"no_load": "nowhere.csv", "stiffness": "k.csv"}},
         "study.identification.no_load = 'nowhere.csv': expected an existing file"),
        ({"identification": {"stiffness": "k.csv"}}, "study.identification.no_load missing"),
        ({"reference": {"K_xx": "2e6 N"}}, "study.reference.K_xx"),
    ],
)  # fmt: skip
def test_bad_cgfb_study_tables_are_one_line_errors(write_case, study, match) -> None:
    def edit(d) -> None:
        d["study"] = study

    path = write_case("bad_cgfb", edit=edit)
    (path.parent / "k.csv").write_text("stack,voltage_V,load_N,displacement_um\n1,0,0,0\n")
    with pytest.raises(InputError, match=match) as err:
        study_plan(load_case(path))
    assert "\n" not in str(err.value) and "bad_cgfb.toml" in str(err.value)


@pytest.mark.parametrize("key", ["orbit_voltage_ramp", "identification"])
def test_actuator_study_keys_on_a_passive_bearing_are_errors(write_case, key) -> None:
    def edit(d) -> None:
        _passive(d)
        d["study"] = {key: {"start": "1 s"}}

    with pytest.raises(InputError, match=rf"study.{key} .*nothing: this bearing has no"):
        study_plan(load_case(write_case("passive_keys", edit=edit)))
