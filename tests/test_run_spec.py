"""The orbit run's specification (``RunSpec``) and status (``RunStatus``): plain data that
round-trips, builds the same run from the command line's strings as from objects."""

from __future__ import annotations

import json

import numpy as np
import pytest

from foilbearing.case import default_case
from foilbearing.cli.main import _parser
from foilbearing.cli.orbit import run_spec_from_args
from foilbearing.constants import RPM
from foilbearing.control import SubsyncController, linear_ramp, voltage_ramp
from foilbearing.errors import InputError
from foilbearing.orbit import OrbitSettings, RunSpec, RunStatus
from foilbearing.orbit.spec import ControllerParams, PiecewiseVoltages, ScheduleText

SCHEDULE = '[schedule]\nslew_rate = "1000 V/s"\n[[point]]\nspeed = "10000 rpm"\nvoltages = "30 V"\n'


def _specs() -> list[RunSpec]:
    paper = linear_ramp(3000 * RPM, 90000 * RPM, 500.0)
    return [
        RunSpec.of(paper),
        RunSpec.of(
            paper,
            voltage_ramp(6.0, 6.5, 150.0, initial=[0.0, 10.0, 20.0]),
            case="mine.toml",
            subambient="retained",
            imbalance=1e-6,
            settings=OrbitSettings(steps_per_rev=20, order=2, sample_rate=12_345.5, rtol=1e-5),
            stop_time=5.0 / 3.0,
            preload_response="lobe",
            actuator_dynamics="held",
        ),
        RunSpec.of(paper, SubsyncController(threshold=3e-6, slew_rate=500.0), stop_time=1.0),
        RunSpec.of(paper, ScheduleText(SCHEDULE, "s.toml")),
    ]


@pytest.mark.parametrize("spec", _specs(), ids=["none", "ramp", "controller", "schedule"])
def test_a_run_spec_round_trips_through_json(spec: RunSpec) -> None:
    text = spec.to_json()
    assert json.loads(text)["format"] == "foilbearing.orbit.RunSpec/2"
    assert RunSpec.from_json(text) == spec
    assert RunSpec.from_dict(json.loads(text)) == spec


def test_the_papers_protocol_from_cli_strings_equals_it_from_objects() -> None:
    """3000 -> 90000 rpm at 500 rad/s², all actuators 0 -> 150 V at 6.0-6.5 s: parsed from
    the command line, the same specification and the same profile and program as made
    from the objects."""
    args = _parser().parse_args(["orbit", "--voltage-ramp", "6.0s:6.5s:150V"])
    from_cli = run_spec_from_args(args)
    case = default_case()
    profile = linear_ramp(3000 * RPM, 90000 * RPM, 500.0)
    program = voltage_ramp(6.0, 6.5, 150.0, initial=np.asarray(case.actuators.voltages))
    from_objects = RunSpec.of(profile, program).with_case(case)
    assert from_cli == from_objects
    assert from_cli.voltage == PiecewiseVoltages((6.0, 6.5), ((0.0,) * 3, (150.0,) * 3))
    built = from_cli.build()
    np.testing.assert_allclose(built.profile.speeds, [3000 * RPM, 90000 * RPM], rtol=1e-15)
    np.testing.assert_allclose(built.profile.times, [0.0, 87000 * RPM / 500.0], rtol=1e-15)
    t = np.linspace(0.0, built.profile.duration, 1001)
    np.testing.assert_array_equal(
        built.profile.speed_and_phase(t)[0], profile.speed_and_phase(t)[0]
    )
    for ti in (0.0, 5.9, 6.0, 6.2, 6.5, 7.0, 18.0):
        np.testing.assert_array_equal(built.program(ti), program(ti))
    assert built.settings == OrbitSettings() and built.stop_time is None
    assert built.case.title == case.title


def test_cli_strings_of_every_program_and_the_old_files_defaults() -> None:
    """The controller's and the schedule's strings give their data forms; a dictionary of an
    earlier version without ``order`` ran BDF2; the strings' errors are one line."""
    spec = RunSpec.from_cli_strings(
        {"speed": "12000rpm", "duration": "0.5s", "controller": "threshold=3um,slew=500V/s"}
    )
    assert spec.voltage == ControllerParams(threshold=3e-6, slew_rate=500.0)
    assert spec.speed_times == (0.0, 0.5) and spec.speeds == (12000 * RPM, 12000 * RPM)
    assert spec.settings.order == 2 and spec.settings.steps_per_rev == 24
    controller = spec.build().program
    assert isinstance(controller, SubsyncController) and controller.threshold == 3e-6
    sched = RunSpec.from_cli_strings(
        {"voltage_schedule": {"path": "s.toml", "text": SCHEDULE}, "stop_time": "2s"}
    )
    assert sched.voltage == ScheduleText(SCHEDULE, "s.toml") and sched.stop_time == 2.0
    assert sched.build().program(1.0) == pytest.approx(30.0)
    with pytest.raises(InputError, match="choose one voltage program"):
        RunSpec.from_cli_strings({"voltage_ramp": "1s:2s:3V", "controller": "target=3V"})
    with pytest.raises(InputError, match="expected T0:T1:V"):
        RunSpec.from_cli_strings({"voltage_ramp": "1s:2s"})


def test_the_imbalance_override_reaches_the_built_case() -> None:
    spec = RunSpec.of(linear_ramp(300.0, 400.0, 500.0), imbalance=1e-6, subambient="retained")
    case = spec.build().case
    assert case.rotor.imbalance == 1e-6 and case.foil.subambient == "retained"


def test_run_status_is_the_plain_word_with_advice() -> None:
    """A ``str``: equal to its word, written as it in JSON and f-strings, read back from it;
    every status but "completed" says what to try."""
    assert RunStatus("contact") is RunStatus.CONTACT and RunStatus.CONTACT == "contact"
    assert json.dumps({"s": RunStatus.STOPPED}) == '{"s": "stopped"}'
    assert f"{RunStatus.FAILED} at" == "failed at"
    assert RunStatus.COMPLETED.advice == ""
    for status in set(RunStatus) - {RunStatus.COMPLETED}:
        assert status.advice, status
    assert "--resume" in RunStatus.INTERRUPTED.advice and "--resume" in RunStatus.STOPPED.advice
    assert "not an error" in RunStatus.CONTACT.advice
    assert "--steps-per-rev" in RunStatus.FAILED.advice
    assert not RunStatus.CONTACT.resumable and RunStatus.RUNNING.resumable


def test_the_actuator_reading_travels_from_the_command_line_to_the_run() -> None:
    """``orbit --preload-response lobe --actuator-dynamics held`` is stored in the run's
    specification, so a resumed run integrates the same reading."""
    args = _parser().parse_args(
        ["orbit", "--preload-response", "lobe", "--actuator-dynamics", "held"]
    )
    spec = run_spec_from_args(args)
    assert (spec.preload_response, spec.actuator_dynamics) == ("lobe", "held")
    act = RunSpec.from_json(spec.to_json()).load_case().actuators
    assert act is not None and (act.preload_response, act.dynamics) == ("lobe", "held")
    bad = _parser().parse_args(["orbit", "--actuator-dynamics", "frozen"])
    with pytest.raises(InputError, match="dynamics = 'frozen'"):
        run_spec_from_args(bad)
