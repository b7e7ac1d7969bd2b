"""The option strings that ``foilbearing orbit`` and ``foilbearing rotor --orbit`` share, read
by one module (:mod:`foilbearing.control.options`): each string gives the same speed profile
or voltage program through both commands, and a bad one the same one-line error."""

from __future__ import annotations

import math
from dataclasses import asdict
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from foilbearing.case import default_case
from foilbearing.cli.common import positive_quantity
from foilbearing.cli.main import _parser
from foilbearing.cli.orbit import run_spec_from_args
from foilbearing.cli.rotor import _orbit_profile, _programs
from foilbearing.constants import RPM
from foilbearing.control import SpeedProfile, SubsyncController, VoltageSchedule
from foilbearing.control.options import positive_time, speed_program
from foilbearing.errors import InputError
from foilbearing.orbit.spec import ControllerParams


def _orbit(*options: str) -> Any:
    """The built run of ``foilbearing orbit OPTIONS`` (default case): profile, program, ..."""
    return run_spec_from_args(_parser().parse_args(["orbit", *options])).build()


def _rotor(orbit: str, *options: str) -> tuple[SpeedProfile, Any]:
    """The speed profile and the first bearing's program of ``foilbearing rotor R.toml
    --orbit ORBIT OPTIONS``, on a rotor whose one bearing is the default case."""
    args = _parser().parse_args(["rotor", "r.toml", "--orbit", orbit, *options])
    rotor = SimpleNamespace(bearings=[SimpleNamespace(case=default_case())])
    profile = _orbit_profile(args.orbit)
    programs = _programs(args, rotor, profile)
    return profile, None if programs is None else programs[0]


def _same_profile(a: SpeedProfile, b: SpeedProfile) -> None:
    assert np.array_equal(a.times, b.times) and np.array_equal(a.speeds, b.speeds)


@pytest.mark.parametrize(
    ("start", "stop", "acceleration"),
    [
        ("3000rpm", "90000rpm", "500rad/s**2"),
        ("30krpm", "60krpm", "500rad/s2"),
        ("1000rad/s", "2000rad/s", "1e3rad/s**2"),
    ],
)
def test_a_speed_ramp_is_the_same_profile_through_both_commands(
    start: str, stop: str, acceleration: str
) -> None:
    """``--speed-ramp`` of the orbit and ``--orbit`` of the rotor read START:STOP:ACCELERATION
    alike; the ramp lasts (stop − start)/acceleration (the paper's: 87 krpm at 500 rad/s²,
    18.2 s)."""
    text = f"{start}:{stop}:{acceleration}"
    orbit = _orbit("--speed-ramp", text).profile
    rotor, _ = _rotor(text)
    _same_profile(orbit, rotor)
    w0, w1 = orbit.speeds
    assert orbit.duration == pytest.approx((w1 - w0) / orbit.state(0.5 * orbit.duration)[1])
    if text == "3000rpm:90000rpm:500rad/s**2":
        assert orbit.duration == pytest.approx(87_000 * RPM / 500.0) == pytest.approx(18.22, 1e-3)


def test_a_constant_speed_is_the_same_profile_through_both_commands() -> None:
    """``--speed S --duration D`` of the orbit is ``--orbit S:D`` of the rotor; the angle
    turned is ω D."""
    orbit = _orbit("--speed", "40000rpm", "--duration", "0.2s").profile
    rotor, _ = _rotor("40000rpm:0.2s")
    _same_profile(orbit, rotor)
    assert orbit.phase(0.2) == pytest.approx(40_000 * RPM * 0.2, rel=1e-14)


def test_a_voltage_ramp_is_the_same_program_through_both_commands() -> None:
    """``--voltage-ramp T0:T1:V`` starts from the case's voltages in both commands and ends at
    V on every actuator; halfway it is the mean of the two."""
    orbit = _orbit("--speed", "40000rpm", "--duration", "1s", "--voltage-ramp", "0.4s:0.6s:150V")
    _, rotor = _rotor("40000rpm:1s", "--voltage-ramp", "0.4s:0.6s:150V")
    assert isinstance(orbit.program, VoltageSchedule) and isinstance(rotor, VoltageSchedule)
    assert np.array_equal(orbit.program.times, rotor.times)
    assert np.array_equal(orbit.program.volts, rotor.volts)
    start = np.asarray(default_case().actuators.voltages, float)
    assert np.allclose(rotor(0.5), 0.5 * (start + 150.0), rtol=1e-14)


def test_a_controller_string_is_the_same_controller_through_both_commands() -> None:
    text = "threshold=1um,target=120V,slew=5000V/s,window=0.03s,period=5ms,initial=10V"
    orbit = _orbit("--speed", "40000rpm", "--duration", "1s", "--controller", text).program
    _, rotor = _rotor("40000rpm:1s", "--controller", text)
    assert isinstance(orbit, SubsyncController) and isinstance(rotor, SubsyncController)
    assert asdict(ControllerParams.of(orbit)) == asdict(ControllerParams.of(rotor))
    assert rotor.threshold == pytest.approx(1e-6) and rotor.period == pytest.approx(5e-3)
    assert rotor.slew_rate == 5000.0 and rotor.target == 120.0 and rotor.initial == 10.0


@pytest.mark.parametrize(
    ("option", "text", "message"),
    [
        (
            "--controller",
            "gain=2",
            "--controller 'gain=2': expected KEY=VALUE with KEY one of threshold, target, "
            "slew, window, period, initial",
        ),
        ("--controller", "threshold=2V", "--controller threshold"),
        ("--voltage-ramp", "1s:150V", "--voltage-ramp '1s:150V': expected T0:T1:V"),
        ("--voltage-ramp", "1s:2s:150rpm", "--voltage-ramp V"),
    ],
)
def test_a_bad_program_string_is_the_same_one_line_error_in_both_commands(
    option: str, text: str, message: str
) -> None:
    with pytest.raises(InputError) as orbit:
        _orbit("--speed", "40000rpm", "--duration", "1s", option, text)
    with pytest.raises(InputError) as rotor:
        _rotor("40000rpm:1s", option, text)
    assert str(orbit.value) == str(rotor.value)
    assert message in str(rotor.value) and "\n" not in str(rotor.value)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("40000rpm", "--orbit '40000rpm': write SPEED:DURATION"),
        ("40000rpm:0s", "--orbit '40000rpm:0s': speed and duration must be > 0"),
        ("3krpm:90krpm:500V", "--orbit ACCELERATION"),
    ],
)
def test_a_bad_speed_string_names_its_option(text: str, message: str) -> None:
    with pytest.raises(InputError, match=r"^[^\n]*$") as err:
        speed_program(text, "--orbit")
    assert message in str(err.value)
    with pytest.raises(InputError, match="--speed-ramp '3krpm:90krpm': expected START:STOP"):
        _orbit("--speed-ramp", "3krpm:90krpm")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("0s", "--checkpoint-every = '0s': a time must be > 0"),
        ("-1s", "--checkpoint-every = '-1s': a time must be > 0"),
        ("nan s", "--checkpoint-every = 'nan s': must be finite"),
    ],
)
def test_a_time_that_is_not_positive_is_refused(text: str, message: str) -> None:
    """``--checkpoint-every`` (both commands) and the rotor's ``--stop-time``, worded as the
    orbit's ``--stop-time`` is (:func:`foilbearing.cli.common.positive_quantity`)."""
    with pytest.raises(InputError) as err:
        positive_time(text, "--checkpoint-every")
    assert str(err.value) == message
    if text != "nan s":
        with pytest.raises(InputError) as orbit:
            positive_quantity(text, "time", "--checkpoint-every", "a time")
        assert str(orbit.value) == message
    assert positive_time("30s", "--checkpoint-every") == 30.0
    assert math.isclose(positive_time("5 ms", "--stop-time"), 5e-3)
