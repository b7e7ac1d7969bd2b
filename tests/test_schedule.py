"""Voltage schedule: the slew envelope, the search against brute force, the file, the orbit.

Physics on a coarse grid (48 x 6): the schedule and the orbit use the same case,
so their agreement is a property of the model, not of the grid.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import tomlkit

from foilbearing.case import load_case
from foilbearing.cli.main import main
from foilbearing.control import linear_ramp
from foilbearing.design.schedule_search import (
    SpeedSchedule,
    _envelope,
    _limit_speed,
    evaluate_voltages,
    voltage_schedule,
)
from foilbearing.errors import InputError
from foilbearing.schedule_file import load_schedule, schedule_toml

RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def coarse_path(write_case) -> Path:
    return write_case("coarse", n_theta=48, n_z=6)


@pytest.fixture(scope="module")
def coarse(coarse_path: Path):
    return load_case(coarse_path)


def test_envelope_is_the_least_slope_limited_majorant() -> None:
    """V_s ≥ V, |dV_s/dΩ| ≤ k, and V_s = V where V already respects the slope."""
    rng = np.random.default_rng(1)
    speeds = np.sort(rng.uniform(1000.0, 9000.0, 25))
    volts = rng.uniform(0.0, 150.0, (25, 3))
    k = 0.05
    env = _envelope(speeds, volts, k)
    assert np.all(env >= volts - 1e-12)
    slopes = np.abs(np.diff(env, axis=0)) / np.diff(speeds)[:, None]
    assert slopes.max() <= k * (1 + 1e-9)
    # each value is attained by some original point (least: no lower majorant exists)
    gap = np.abs(speeds[:, None] - speeds[None, :])
    attained = np.isclose(env[:, None, :], volts[None, :, :] - k * gap[:, :, None]).any(axis=1)
    assert attained.all()
    smooth = 20.0 + 0.01 * speeds[:, None] * np.ones((1, 3))
    assert _envelope(speeds, smooth, k) == pytest.approx(smooth)


def test_limit_speed_interpolates_the_first_zero() -> None:
    w = np.array([1.0, 2.0, 3.0, 4.0])
    assert _limit_speed(w, np.array([0.3, 0.1, -0.1, 0.2])) == pytest.approx(2.5)
    assert _limit_speed(w, np.array([0.3, 0.2, 0.1, 0.05])) is None
    assert _limit_speed(w, np.array([-0.1, 0.2, 0.1, 0.05])) == 1.0


def test_schedule_beats_a_brute_force_grid(coarse) -> None:
    """At one speed the search's voltages meet the margin with no more power loss than
    the best of a 5 x 5 x 5 grid of voltage sets that meets it (an independent search), to
    0.5 %: the stable voltages' power loss is flat to 0.1 % along a valley 30 V long
    (0 / 112-146 / 29-38 V, 18.12-18.14 W at κ = 0.1), which 40 evaluations need not
    resolve. A search trapped at a corner of the box is 2 % worse (0 / 150 / 0 V, 18.48 W,
    before the Nelder-Mead restarts)."""
    speed = 55_000 * RPM
    sched = voltage_schedule(coarse, [speed], margin=0.1)
    assert sched.meets_margin is not None and bool(sched.meets_margin[0])
    assert sched.log_decrement is not None and sched.log_decrement[0] >= 0.1
    levels = np.linspace(0.0, 150.0, 5)
    best = math.inf
    start = None
    for v in np.stack(np.meshgrid(levels, levels, levels, indexing="ij"), -1).reshape(-1, 3):
        point, start = evaluate_voltages(coarse, speed, v, start)
        if point is not None and point.log_decrement >= 0.1:
            best = min(best, point.power_loss)
    assert math.isfinite(best), "some grid point must meet the margin at 55 krpm"
    assert sched.power_loss is not None
    assert sched.power_loss[0] <= best * (1 + 5e-3)
    # and the 0 V bearing, unstable here, needs the voltage the schedule pays for
    zero, _ = evaluate_voltages(coarse, speed, (0.0, 0.0, 0.0))
    assert zero is not None and zero.log_decrement < 0.1


def test_where_no_voltages_meet_the_margin_the_most_stable_are_chosen(coarse) -> None:
    """With a margin no voltage can meet, the search maximises the log decrement: it is
    no less stable than the best of a 5 x 5 x 5 grid of voltage sets."""
    speed = 60_000 * RPM
    sched = voltage_schedule(coarse, [speed], margin=5.0)
    assert sched.meets_margin is not None and not sched.meets_margin[0]
    levels = np.linspace(0.0, 150.0, 5)
    best = -math.inf
    start = None
    for v in np.stack(np.meshgrid(levels, levels, levels, indexing="ij"), -1).reshape(-1, 3):
        point, start = evaluate_voltages(coarse, speed, v, start)
        if point is not None:
            best = max(best, point.log_decrement)
    assert sched.log_decrement is not None
    assert sched.log_decrement[0] >= best - 1e-6, (sched.log_decrement[0], best)


def test_file_round_trip_and_slew_limited_program(coarse, tmp_path: Path) -> None:
    speeds = np.array([10_000.0, 40_000.0, 41_000.0, 80_000.0]) * RPM
    volts = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [150.0, 20.0, 150.0], [90.0, 90.0, 90.0]])
    sched = SpeedSchedule(speeds, volts, slew_rate=300.0)
    path = tmp_path / "s.toml"
    path.write_text(schedule_toml(sched))
    back = load_schedule(path, coarse)
    assert back.speeds == pytest.approx(speeds, rel=1e-6)
    assert back.voltages == pytest.approx(volts, abs=0.005)
    assert back.slew_rate == 300.0
    profile = linear_ramp(3000 * RPM, 90000 * RPM, 500.0)
    prog = back.program(profile)
    t = np.linspace(0.0, profile.duration, 20_001)
    v = np.array([prog(x) for x in t])
    rate = np.abs(np.diff(v, axis=0)) / np.diff(t)[:, None]
    assert rate.max() <= 300.0 * (1 + 1e-6)
    # the jump of 150 V over 1000 rpm (0.21 s at 500 rad/s²) cannot be followed at 300 V/s,
    # so the applied voltage lags the command there; elsewhere they agree
    w, _ = profile.speed_and_phase(t)
    lag = np.abs(v - back.command(w)).max(axis=1)
    assert lag.max() > 50.0
    assert lag[w < 40_000 * RPM].max() < 1e-9
    assert lag[w > 60_000 * RPM].max() < 1e-6


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "bad.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (
            '[[point]]\nspeed = "20000 rpm"\nvoltages = "0 V"\n'
            '[[point]]\nspeed = "10000 rpm"\nvoltages = "0 V"\n',
            r"point\[1\]\.speed = 10000 rpm: expected speeds increasing",
        ),
        ('[[point]]\nspeed = "20000 rpm"\nvoltages = "200 V"\n', "max_voltage = 150 V"),
        ('[[point]]\nspeed = "20000 rpm"\nvoltages = ["0 V", "0 V"]\n', "1 or 3 values"),
        ('[schedule]\nslew_rate = "-3 V/s"\n[[point]]\nspeed = 1.0\nvoltages = 0\n', "> 0"),
        ("[schedule]\n", r"no \[\[point\]\]"),
        ('[[point]]\nspeed = "20000 rpm"\nvolts = "0 V"\n', "voltages is missing"),
    ],
)
def test_bad_schedule_files_are_one_line_errors(coarse, tmp_path: Path, text, match) -> None:
    with pytest.raises(InputError, match=match) as err:
        load_schedule(_write(tmp_path, text), coarse)
    assert "\n" not in str(err.value) and "bad.toml" in str(err.value)


def test_cli_bad_input_before_any_work(coarse_path: Path, tmp_path: Path, capsys) -> None:
    case = str(coarse_path)
    for argv, match in (
        (["--speed-range", "10000rpm:200000rpm"], "max_speed = 150000 rpm"),
        (["--margin", "-0.1"], "--margin"),
        (["--slew-rate", "0V/s"], "--slew-rate"),
        (["--speed-range", "10000rpm"], "START:STOP"),
    ):
        assert main(["schedule", case, *argv]) == 2
        err = capsys.readouterr().err.strip()
        assert match in err and "\n" not in err, err
    bad = _write(tmp_path, '[[point]]\nspeed = "20000 rpm"\nvoltages = "200 V"\n')
    assert main(["orbit", case, "--voltage-schedule", str(bad)]) == 2
    assert "max_voltage" in capsys.readouterr().err
    good = _write(tmp_path, '[[point]]\nspeed = "20000 rpm"\nvoltages = "20 V"\n')
    argv = ["orbit", case, "--voltage-schedule", str(good), "--voltage-ramp", "1s:2s:50V"]
    assert main(argv) == 2
    assert "choose one" in capsys.readouterr().err


def test_cli_json_and_file(coarse_path: Path, tmp_path: Path, capsys) -> None:
    out = tmp_path / "schedule.toml"
    argv = ["schedule", str(coarse_path), "--speed-range", "30000rpm:50000rpm:20000rpm"]
    assert main([*argv, "--out", str(out), "--plot", str(tmp_path), "--json", "--grid-check"]) == 0
    head = json.loads(capsys.readouterr().out)
    check = head["grid_refined"]  # the schedule's points again on 96 x 12
    assert check["refined_grid"] == [96, 12]
    assert [a - b for a, b in zip(head["log_decrement"], check["log_decrement"], strict=True)] == (
        pytest.approx(check["errors"]["log_decrement"])
    )
    for key in (
        "speeds_rpm",
        "voltages_V",
        "power_loss_W",
        "power_loss_150V_W",
        "log_decrement",
        "limit_speed_rpm",
    ):
        assert key in head
    assert head["speeds_rpm"] == pytest.approx([30000.0, 50000.0])
    assert len(head["voltages_V"]) == 2 and len(head["voltages_V"][0]) == 3
    assert (tmp_path / "schedule.png").stat().st_size > 10_000
    back = load_schedule(out, load_case(coarse_path))
    assert back.voltages == pytest.approx(np.array(head["voltages_V"]), abs=0.005)
    # the table prints each log decrement's grid error and what the finer grid says
    one = ["schedule", str(coarse_path), "--speed-range", "30000rpm:40000rpm:20000rpm"]
    assert main([*one, "--grid-check"]) == 0
    text = capsys.readouterr().out
    assert "± grid" in text and "grid check: the schedule's points on 96 x 12" in text


def test_orbit_on_the_schedule_stays_stable_below_the_limit(coarse) -> None:
    """The nonlinear orbit on the schedule shows no sustained sub-synchronous motion and
    no contact below the schedule's limit speed (here: the top speed, the schedule is
    stable to it); the 0 V run on the same speed-up does not get there (so the test
    can fail)."""
    from foilbearing.orbit import simulate
    from foilbearing.orbit.analysis import analyse_orbit

    case = replace(coarse, rotor=replace(coarse.rotor, imbalance=1e-6))
    speeds = np.arange(30_000, 80_001, 5_000) * RPM
    sched = voltage_schedule(case, speeds, margin=0.1)
    top = sched.limit_speed or float(speeds[-1])
    profile = linear_ramp(35_000 * RPM, top, 2000.0)
    runs = {}
    for name, program in (("schedule", sched.program(profile)), ("0 V", None)):
        run = simulate(case, profile, program, progress=False)
        found = analyse_orbit(run).onset
        rpm = None if found is None else found.onset_speed_rpm
        onset = None if rpm is None else rpm * RPM
        runs[name] = (run.status, onset, float(run.speed[-1]) / RPM)
    status, onset, _ = runs["schedule"]
    assert status == "completed" and (onset is None or onset >= top), runs
    status, onset, _ = runs["0 V"]
    assert status == "contact" or (onset is not None and onset < top), runs


def test_orbit_resumes_on_the_stored_schedule(write_case, tmp_path: Path, capsys) -> None:
    """A run keeps the schedule's text: it resumes after the file is gone, on the same
    voltages (the command at the run's speed, 40 V halfway between 30 and 50 V)."""
    sched = tmp_path / "s.toml"
    sched.write_text(
        '[schedule]\nslew_rate = "1000 V/s"\n'
        '[[point]]\nspeed = "10000 rpm"\nvoltages = "30 V"\n'
        '[[point]]\nspeed = "14000 rpm"\nvoltages = ["50 V", "50 V", "50 V"]\n'
    )
    case = write_case(
        "light", n_theta=48, n_z=6, edit=lambda d: d["rotor"].update(imbalance="1 g*mm")
    )
    out = tmp_path / "run.nc"
    argv = ["orbit", str(case), "--speed", "12000rpm", "--duration", "0.06s"]
    argv += ["--voltage-schedule", str(sched), "--out", str(out), "--json"]
    assert main([*argv, "--stop-time", "0.03s"]) == 0
    assert json.loads(capsys.readouterr().out)["status"] == "stopped"
    sched.unlink()
    assert main(["orbit", "--resume", str(out), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["status"] == "completed"
    import xarray as xr

    ds = xr.load_dataset(out)
    assert ds.time.values[-1] == pytest.approx(0.06, abs=2e-4)
    assert ds.voltage.values == pytest.approx(40.0, abs=1e-9)
    assert np.all(np.isfinite(ds.power_loss.values))


def test_case_max_speed_bounds_the_speed_range(coarse_path: Path, tmp_path: Path, capsys) -> None:
    data = tomlkit.parse(coarse_path.read_text())
    data["operation"]["max_speed"] = "60000 rpm"
    path = tmp_path / "slow.toml"
    path.write_text(tomlkit.dumps(data))
    assert load_case(path).operation.max_speed == pytest.approx(60_000 * RPM)
    assert main(["schedule", str(path), "--speed-range", "10000rpm:90000rpm"]) == 2
    assert "operation.max_speed = 60000 rpm" in capsys.readouterr().err
    data["operation"]["max_speed"] = "40000 rpm"
    path.write_text(tomlkit.dumps(data))
    with pytest.raises(InputError, match=r"above operation\.max_speed"):
        load_case(path)


def _equal_voltage_schedule(case, speeds_rpm: list[float]) -> SpeedSchedule:
    """0 V on every actuator at each speed, evaluated as the search evaluates a schedule
    (grid speeds and midpoints), so that its limit speed is the linear onset at 0 V."""
    w = np.array(speeds_rpm) * RPM
    mid_w = 0.5 * (w[1:] + w[:-1])
    zero = (0.0,) * len(case.actuators.angles)
    points = [evaluate_voltages(case, float(s), zero)[0] for s in w]
    mid = np.array([evaluate_voltages(case, float(s), zero)[0].log_decrement for s in mid_w])
    dec = np.array([p.log_decrement for p in points])
    both_w, both = np.empty(2 * w.size - 1), np.empty(2 * w.size - 1)
    both_w[0::2], both_w[1::2], both[0::2], both[1::2] = w, mid_w, dec, mid
    return SpeedSchedule(
        speeds=w,
        voltages=np.zeros((w.size, len(zero))),
        margin=0.1,
        power_loss=np.array([p.power_loss for p in points]),
        log_decrement=dec,
        whirl_frequency=np.array([p.whirl_frequency for p in points]),
        midpoint_log_decrement=mid,
        limit_speed=_limit_speed(both_w, both),
    )


def test_the_schedule_s_grid_error_shrinks_and_its_limit_is_the_refined_onset() -> None:
    """The schedule's points on twice the cells (``schedule_grid_check``, issue 49, as the
    study's ``schedule_errors`` runs it and the report prints it), on
    48 × 6 and on 96 × 12 at 0 V from 35 to 50 krpm: the power loss's error shrinks at the
    statics' second order (measured 0.24-0.25 of the coarser grid's: at most 0.35 asserted),
    the log decrement's where it is more than round-off (0.28-0.31 measured past 35 krpm:
    0.5 asserted); and the limit speed read from the refined log decrements (linear between
    grid speeds and midpoints) is the linear onset found by Brent's method on the refined
    grid (1e-5 and 8e-4 of it measured: 0.2 % asserted), two methods."""
    from dataclasses import replace

    from foilbearing.analysis.stability import onset_speed
    from foilbearing.case import default_case
    from foilbearing.check import refined
    from foilbearing.output.report.beyond import _schedule
    from foilbearing.study.schedule import schedule_errors

    base = default_case()
    speeds = [35e3, 40e3, 45e3, 50e3]
    errors = []
    for n_theta, n_z in ((48, 6), (96, 12)):
        case = replace(base, grid=replace(base.grid, n_theta=n_theta, n_z=n_z))
        sched = _equal_voltage_schedule(case, speeds)
        check = schedule_errors(case, sched, 2, lambda _line: None)
        assert check["refined_grid"] == [2 * n_theta, 2 * n_z]
        errors.append(check["errors"])
        onset = onset_speed(refined(case, 2), [s * RPM for s in speeds]).onset_speed / RPM
        assert check["limit_speed_rpm"] == pytest.approx(onset, rel=2e-3)
        assert check["limit_speed_error_rpm"] == pytest.approx(
            sched.limit_speed / RPM - check["limit_speed_rpm"]
        )
        assert check["below_margin_rpm"] == []  # 0 V misses the margin on both grids
        # the report prints each log decrement and the limit with its error
        page = _schedule({"schedule": sched.headline() | {"grid_refined": check}}, {})
        assert f"above {check['texts']['limit_speed_krpm']} krpm" in page
        assert all(f">{t}<" in page for t in check["texts"]["log_decrement"])
        assert f"again on {2 * n_theta} × {2 * n_z}" in page
    coarse, finer = errors
    for e1, e2 in zip(coarse["power_loss_W"], finer["power_loss_W"], strict=True):
        assert abs(e2) < 0.35 * abs(e1)
    for e1, e2 in zip(coarse["log_decrement"][1:], finer["log_decrement"][1:], strict=True):
        assert abs(e1) > 1e-3 and abs(e2) < 0.5 * abs(e1)
