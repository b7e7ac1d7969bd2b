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
from foilbearing.cli import main
from foilbearing.errors import InputError
from foilbearing.study_plan import study_plan

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
    assert main(["study", str(path), "--out", str(tmp_path), "--orbits", "none", "--json"]) == 0
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
    rows = {r["quantity"].split(" (")[0]: r for r in out["reference_comparison"]["rows"]}
    onset = rows["linear onset speed of instability"]
    assert onset["reference"] == pytest.approx(30000.0)
    if onset["ours"] is not None:
        assert onset["deviation_percent"] == pytest.approx(100 * (onset["ours"] / 30000 - 1))
    assert "divergence speed of the speed-up orbit" in rows
    assert '<section id="reference_comparison"' in (tmp_path / "report.html").read_text()


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
    assert main(["study", str(path), "--out", str(tmp_path), "--json"]) == 0
    rows = {r["scale"]: r for r in json.loads(capsys.readouterr().out)["shim_stability"]["rows"]}
    assert sorted(rows) == [0.0, 0.5, 1.0, 1.5]

    def passive(d) -> None:
        _passive(d)
        d["study"] = {"orbit": False, "speed_range": ["10000 rpm", "50000 rpm", "10000 rpm"]}

    bare = write_case("bare", n_theta=32, n_z=4, edit=passive)
    assert main(["study", str(bare), "--out", str(tmp_path / "bare"), "--json"]) == 0
    onset = json.loads(capsys.readouterr().out)["bearing_stability"]["onset"]
    assert rows[0.0]["onset_speed_rpm"] == pytest.approx(onset["onset_speed_rpm"], rel=1e-9)
    assert rows[1.5]["onset_speed_rpm"] > 1.5 * rows[0.0]["onset_speed_rpm"]


@pytest.mark.slow
def test_a_cgfb_other_than_the_papers_gets_its_own_plan(write_case, tmp_path: Path, capsys) -> None:
    """A C-GFB case from another file runs the plan (onset against voltage, the schedule
    over the plan's speeds) and shows no paper comparison and no identification from the
    paper's synthetic data. The voltages' preload delays the onset (0 -> 150 V)."""

    def edit(d) -> None:
        d["study"] = {
            "speed_range": ["30000 rpm", "60000 rpm", "10000 rpm"],
            "voltages": ["0 V", "150 V"],
            "orbit": False,
        }

    path = write_case("mine", n_theta=32, n_z=4, edit=edit)
    assert main(["study", str(path), "--out", str(tmp_path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["plan"]["bearing_kind"] == "C-GFB" and out["plan"]["voltages_V"] == [0.0, 150.0]
    assert "paper_comparison" not in out and "identification" not in out
    rows = {r["voltage_V"]: r for r in out["voltage_stability"]["rows"]}
    assert rows[150.0]["onset_speed_rpm"] > rows[0.0]["onset_speed_rpm"]
    sched = out["schedule"]["schedule"]
    assert sched["speeds_rpm"] == pytest.approx([30000, 40000, 50000, 60000])
    assert len(sched["voltages_V"]) == 4 and (tmp_path / "schedule.png").exists()
