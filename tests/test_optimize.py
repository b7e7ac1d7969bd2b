"""Voltage optimisation: machinery on a synthetic objective, physics on a coarse grid, CLI."""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np
import pytest
import tomlkit

import foilbearing.design.voltages as opt
from foilbearing.case import load_case
from foilbearing.cli.optimize import cmd_optimize, register
from foilbearing.errors import InputError

RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def coarse_path(write_case) -> Path:
    return write_case("coarse", n_theta=32, n_z=4)


@pytest.fixture(scope="module")
def coarse(coarse_path: Path):
    return load_case(coarse_path)


def _synthetic(peak: tuple[float, ...], top: float):
    """Onset with a known interior maximum ``top`` rad/s at ``peak`` V (a quadratic bowl)."""
    calls = []

    def onset_of(case, speeds):
        v = np.array(case.actuators.voltages)
        calls.append(tuple(v))
        return top - 0.05 * float(np.sum((v - np.array(peak)) ** 2)), False

    return onset_of, calls


@pytest.mark.parametrize("method", ["Nelder-Mead", "Powell"])
def test_synthetic_interior_maximum_is_found(monkeypatch, coarse, method) -> None:
    peak = (40.0, 95.0, 120.0)
    onset_of, calls = _synthetic(peak, top=3000.0)
    monkeypatch.setattr(opt, "_onset_of", onset_of)
    res = opt.maximize_onset(coarse, method=method, max_evaluations=200)
    assert res.voltages == pytest.approx(peak, abs=2.0)
    assert res.value == pytest.approx(3000.0, abs=0.5)
    assert res.converged, res.message
    # the cache: each voltage set reaches the physics once, and all are in the history
    assert len(calls) == len(set(calls)) == res.evaluations == len(res.history)
    assert res.baseline_voltages in {(v, v, v) for v in opt.PAPER_VOLTAGES}


def test_hard_cap_on_evaluations(monkeypatch, coarse) -> None:
    onset_of, calls = _synthetic((40.0, 95.0, 120.0), top=3000.0)
    monkeypatch.setattr(opt, "_onset_of", onset_of)
    res = opt.maximize_onset(coarse, max_evaluations=15)
    assert res.evaluations == len(calls) == 15
    assert not res.converged and "budget" in res.message
    assert res.value >= res.baseline_value


def test_bounds_are_respected(monkeypatch, coarse) -> None:
    onset_of, _ = _synthetic((40.0, 95.0, 120.0), top=3000.0)
    monkeypatch.setattr(opt, "_onset_of", onset_of)
    bounds = [(60.0, 150.0), (0.0, 80.0), (0.0, 150.0)]
    res = opt.maximize_onset(coarse, bounds=bounds, max_evaluations=200)
    assert res.voltages == pytest.approx((60.0, 80.0, 120.0), abs=2.0)
    for v, _ in res.history:
        assert all(lo <= x <= hi for x, (lo, hi) in zip(v, bounds, strict=True))
    with pytest.raises(InputError, match="bounds"):
        opt.maximize_onset(coarse, bounds=[(0.0, 200.0)] * 3)


def test_onset_optimum_not_worse_than_equal_voltages(coarse) -> None:
    speeds = [rpm * RPM for rpm in range(5_000, 40_001, 5_000)]
    res = opt.maximize_onset(coarse, speeds=speeds, max_evaluations=8, n_random=2)
    assert res.evaluations <= 8
    assert res.value >= res.baseline_value
    values = [val for _, val in res.history]
    assert res.value == np.nanmax(values)
    equal = [val for v, val in res.history if len(set(v)) == 1]
    assert len(equal) == 4 and res.baseline_value == max(equal)
    assert all(0.0 <= x <= 150.0 for x in res.voltages)
    head = res.headline()
    assert head["onset_speed_rpm"] == pytest.approx(res.value / RPM)
    assert head["improvement_percent"] >= 0.0


def test_drag_optimum_is_feasible_and_best_of_history(coarse) -> None:
    # Minimum film at 50 krpm on this grid: 0.33 C at 0 V falling to 0.20 C at 150 V, so a
    # 0.30 C floor is feasible near 0 V and binds elsewhere.
    frac = 0.30
    res = opt.minimize_drag(coarse, 50_000 * RPM, min_film_fraction=frac, max_evaluations=40)
    assert res.evaluations <= 40
    assert res.min_film is not None and res.min_film >= frac * coarse.bearing.clearance
    feasible = [val for _, val in res.history if math.isfinite(val)]
    assert res.value == min(feasible)
    assert res.value <= res.baseline_value
    assert any(math.isnan(val) for _, val in res.history)  # the constraint bites somewhere
    assert all(0.0 <= x <= 150.0 for x in res.voltages)


def test_drag_input_errors(coarse) -> None:
    with pytest.raises(InputError, match="speed"):
        opt.minimize_drag(coarse, -1.0)
    with pytest.raises(InputError, match="load"):
        opt.minimize_drag(coarse, 1000.0, load=-3.0)
    with pytest.raises(InputError, match="actuators"):
        opt.minimize_drag(coarse.shimmed(), 1000.0)
    with pytest.raises(InputError, match="method"):
        opt.minimize_drag(coarse, 1000.0, method="BFGS")
    with pytest.raises(InputError, match="max_evaluations"):
        opt.maximize_onset(coarse, max_evaluations=3)
    with pytest.raises(InputError, match="speeds"):
        opt.maximize_onset(coarse, speeds=[1000.0])


def _args(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="foilbearing")
    register(parser.add_subparsers())
    return parser.parse_args(["optimize", *argv])


def test_cli_json_keys(coarse_path: Path, capsys) -> None:
    argv = [str(coarse_path), "--objective", "drag", "--speed", "50000rpm"]
    assert cmd_optimize(_args([*argv, "--max-evaluations", "12", "--json"])) == 0
    head = json.loads(capsys.readouterr().out)
    keys = {
        "voltages_V",
        "drag_torque_Nm",
        "baseline_voltages_V",
        "baseline_drag_torque_Nm",
        "improvement_percent",
        "evaluations",
        "min_film_um",
        "speed_rpm",
        "converged",
        "message",
    }
    assert keys <= set(head)
    assert head["evaluations"] <= 12 and head["speed_rpm"] == pytest.approx(50000.0)
    assert head["drag_torque_Nm"] <= head["baseline_drag_torque_Nm"]
    assert cmd_optimize(_args([*argv, "--max-evaluations", "5"])) == 0
    assert "paper (equal)" in capsys.readouterr().out


def test_cli_bad_input(coarse_path: Path, tmp_path: Path) -> None:
    case = str(coarse_path)
    with pytest.raises(InputError, match="objective"):
        cmd_optimize(_args([case, "--objective", "weight"]))
    with pytest.raises(InputError, match="--speed"):
        cmd_optimize(_args([case, "--objective", "drag"]))
    with pytest.raises(InputError, match="--speed"):
        cmd_optimize(_args([case, "--objective", "onset", "--speed", "5000rpm"]))
    with pytest.raises(InputError, match="max-evaluations"):
        cmd_optimize(_args([case, "--max-evaluations", "3"]))
    data = tomlkit.parse(coarse_path.read_text())
    del data["actuators"]
    bare = tmp_path / "bare.toml"
    bare.write_text(tomlkit.dumps(data))
    with pytest.raises(InputError, match="actuators"):
        cmd_optimize(_args([str(bare), "--objective", "drag", "--speed", "50000rpm"]))
