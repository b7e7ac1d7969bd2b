"""The specification of an orbit run as plain data (SI): what a file stores to be resumed.

A :class:`RunSpec` holds everything :func:`foilbearing.orbit.simulate` needs
besides the checkpoint: the case itself as data (:class:`~foilbearing.case.record.CaseRecord`,
every field with the overrides applied, and a sha256 of it), the case file it came from
(and the overrides), the speed profile's breakpoints, the voltage program as data, the
integrator settings and the stop time. A run is rebuilt from the recorded case alone;
specifications of earlier versions, which held only the case file's path, rebuild the
case from the file. It round-trips through JSON
(:meth:`RunSpec.to_json`, :meth:`RunSpec.from_json`) and is stored in the
orbit's NetCDF file (:mod:`foilbearing.orbit.netcdf`); :meth:`RunSpec.build`
makes the objects again. The command line's strings are parsed into one by
:meth:`RunSpec.from_cli_strings`, which also reads the string dictionaries
that earlier versions stored.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field, fields
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from foilbearing.case.record import CaseRecord
from foilbearing.control import SubsyncController
from foilbearing.control.options import (  # cli_quantity, controller_args: importable from here
    cli_quantity,
    controller_args,
    speed_ramp,
    steady_speed,
    voltage_ramp_times,
)
from foilbearing.errors import InputError
from foilbearing.orbit.settings import OrbitSettings

if TYPE_CHECKING:
    from foilbearing.case import Case
    from foilbearing.control import SpeedProfile, VoltageProgram

__all__ = [
    "BuiltRun",
    "ControllerParams",
    "PiecewiseVoltages",
    "RunSpec",
    "ScheduleText",
    "VoltageSpec",
    "cli_quantity",
]

#: The ``format`` key of a stored specification (the dictionaries of earlier versions
#: held the command line's strings and no such key; /1 held the case file's path only).
FORMAT = "foilbearing.orbit.RunSpec/2"
_FORMATS = ("foilbearing.orbit.RunSpec/1", FORMAT)

#: The command line's defaults, for the keys an earlier version's dictionary may lack.
_CLI_DEFAULTS: dict[str, Any] = {
    "case": None,
    "speed_ramp": "3000rpm:90000rpm:500rad/s**2",
    "speed": None,
    "duration": "1 s",
    "voltage_ramp": None,
    "controller": None,
    "voltage_schedule": None,
    "stop_time": None,
    "steps_per_rev": OrbitSettings.steps_per_rev,
    "order": None,  # runs saved before the order was stored: BDF2
    "steps": OrbitSettings.steps,
    "step_rtol": OrbitSettings.step_rtol,
    "sample_rate": "10000Hz",
    "subambient": None,
    "preload_response": None,
    "actuator_dynamics": None,
    "load": None,
}


@dataclass(frozen=True)
class PiecewiseVoltages:
    """An open-loop program as data: :class:`foilbearing.control.VoltageSchedule`'s rows.

    Attributes
    ----------
    times
        Breakpoints, s, non-decreasing.
    volts
        Voltages at the breakpoints, V, one row per time (one column per actuator,
        or one for all).
    """

    times: tuple[float, ...]
    volts: tuple[tuple[float, ...], ...]

    @classmethod
    def of(cls, program: Any) -> PiecewiseVoltages:
        """The rows of a :class:`~foilbearing.control.VoltageSchedule` (e.g. ``voltage_ramp``)."""
        volts = np.atleast_2d(np.asarray(program.volts, float))
        return cls(
            tuple(np.asarray(program.times, float).tolist()),
            tuple(tuple(row) for row in volts.tolist()),
        )

    def program(self, case: Case, profile: SpeedProfile) -> VoltageProgram:
        """The :class:`~foilbearing.control.VoltageSchedule` of these rows."""
        from foilbearing.control import VoltageSchedule

        return VoltageSchedule(np.array(self.times, float), np.array(self.volts, float))


@dataclass(frozen=True)
class ControllerParams:
    """The closed-loop :class:`foilbearing.control.SubsyncController`'s parameters.

    Attributes
    ----------
    threshold
        Sub-synchronous amplitude that triggers the control, m.
    target
        Commanded voltage once triggered, V.
    slew_rate
        Amplifier slew-rate limit, V/s.
    window
        Length of the analysis window, s.
    period
        Control period, s.
    initial
        Voltage before triggering, V.
    """

    # The controller's own defaults (one source: a parameter left out is the controller's).
    threshold: float = SubsyncController.threshold
    target: float = SubsyncController.target
    slew_rate: float = SubsyncController.slew_rate
    window: float = SubsyncController.window
    period: float = SubsyncController.period
    initial: float = SubsyncController.initial

    @classmethod
    def of(cls, controller: Any) -> ControllerParams:
        """The parameters of a controller (its state, the latch, is the checkpoint's)."""
        return cls(**{f.name: float(getattr(controller, f.name)) for f in fields(cls)})

    def program(self, case: Case, profile: SpeedProfile) -> VoltageProgram:
        """A fresh controller with these parameters."""
        return SubsyncController(**asdict(self))


@dataclass(frozen=True)
class ScheduleText:
    """A voltage-schedule file (``foilbearing schedule --out``), kept as its text.

    Attributes
    ----------
    text
        The file's TOML text: a resumed run follows it after the file is gone.
    path
        Where it was read from (for the record and error messages).
    """

    text: str
    path: str

    def program(self, case: Case, profile: SpeedProfile) -> VoltageProgram:
        """The schedule along the speed profile (through its slew-rate limit)."""
        import tomllib

        from foilbearing.control.schedule_file import parse_schedule

        return parse_schedule(tomllib.loads(self.text), case, self.path).program(profile)


#: A voltage program as data (None: the case's voltages held).
VoltageSpec = PiecewiseVoltages | ControllerParams | ScheduleText

_VOLTAGE_KINDS: dict[str, type[Any]] = {
    "piecewise": PiecewiseVoltages,
    "controller": ControllerParams,
    "schedule_file": ScheduleText,
}


class BuiltRun(NamedTuple):
    """What :func:`foilbearing.orbit.simulate` takes, made from a :class:`RunSpec`."""

    case: Case
    profile: SpeedProfile
    program: VoltageProgram | None
    settings: OrbitSettings
    stop_time: float | None


@dataclass(frozen=True)
class RunSpec:
    """An orbit run as plain data in SI: stored with its results, resumed from them.

    Attributes
    ----------
    speed_times, speeds
        Breakpoints of the piecewise-linear speed profile: times, s (first 0),
        and speeds, rad/s.
    voltage
        The voltage program as data (:class:`PiecewiseVoltages`,
        :class:`ControllerParams`, :class:`ScheduleText`), or None: the case's
        voltages held.
    case
        Case file (None: the built-in default case).
    subambient
        Sub-ambient film model applied to the case (None: the case's).
    preload_response, actuator_dynamics
        The reading of the actuator in the film applied to the case
        (docs/model.md §3.8; None: the case's).
    imbalance
        Rotor imbalance applied to the case, kg·m (None: the case's).
    load
        Static load applied to the case, N (None: the case's ``operation.load``).
    settings
        Integrator and output settings.
    stop_time
        End the run at this simulated time, s (None: the end of the profile).
    recorded_case
        The case the run runs on, as data (:meth:`with_case`): the run is rebuilt from it,
        not from the file. None in specifications of earlier versions: from the file.
    """

    speed_times: tuple[float, ...]
    speeds: tuple[float, ...]
    voltage: VoltageSpec | None = None
    case: str | None = None
    subambient: str | None = None
    imbalance: float | None = None
    settings: OrbitSettings = field(default_factory=OrbitSettings)
    stop_time: float | None = None
    preload_response: str | None = None
    actuator_dynamics: str | None = None
    load: float | None = None
    recorded_case: CaseRecord | None = None

    @classmethod
    def of(
        cls,
        profile: SpeedProfile,
        program: Any = None,
        *,
        case: str | None = None,
        subambient: str | None = None,
        imbalance: float | None = None,
        settings: OrbitSettings | None = None,
        stop_time: float | None = None,
        preload_response: str | None = None,
        actuator_dynamics: str | None = None,
        load: float | None = None,
    ) -> RunSpec:
        """The specification of a run from its objects.

        ``program`` is a :class:`~foilbearing.control.VoltageSchedule`, a
        :class:`~foilbearing.control.SubsyncController`, one of the data forms
        (:data:`VoltageSpec`) or None; the other arguments are the fields.
        """
        from foilbearing.control import VoltageSchedule

        voltage: VoltageSpec | None
        if program is None or isinstance(program, VoltageSpec):
            voltage = program
        elif isinstance(program, VoltageSchedule):
            voltage = PiecewiseVoltages.of(program)
        elif isinstance(program, SubsyncController):
            voltage = ControllerParams.of(program)
        else:
            raise TypeError(f"no data form for the voltage program {type(program).__name__}")
        return cls(
            tuple(np.asarray(profile.times, float).tolist()),
            tuple(np.asarray(profile.speeds, float).tolist()),
            voltage,
            case,
            subambient,
            None if imbalance is None else float(imbalance),
            OrbitSettings() if settings is None else settings,
            None if stop_time is None else float(stop_time),
            preload_response,
            actuator_dynamics,
            None if load is None else float(load),
        )

    def with_case(self, case: Case) -> RunSpec:
        """This specification with ``case`` recorded as the run's (made from :attr:`case`,
        the file, which is read now for its digest)."""
        from dataclasses import replace

        return replace(self, recorded_case=CaseRecord.of(case, self.case))

    def load_case(self) -> Case:
        """The recorded case; without one (earlier versions), the case file with the
        overrides (sub-ambient model, actuator reading, imbalance, load) applied."""
        if self.recorded_case is not None:
            from foilbearing.case import default_case_path

            source = str(default_case_path()) if self.case is None else self.case
            return self.recorded_case.case(source)
        return _load_case(
            self.case,
            self.subambient,
            self.imbalance,
            self.preload_response,
            self.actuator_dynamics,
            self.load,
        )

    def build(self, case: Case | None = None) -> BuiltRun:
        """The case, speed profile, voltage program, settings and stop time of the run.

        ``case``: the case :meth:`load_case` gives, when the caller has it already.
        """
        from foilbearing.control import SpeedProfile

        case = self.load_case() if case is None else case
        profile = SpeedProfile(np.array(self.speed_times, float), np.array(self.speeds, float))
        program = None if self.voltage is None else self.voltage.program(case, profile)
        return BuiltRun(case, profile, program, self.settings, self.stop_time)

    def to_dict(self) -> dict[str, Any]:
        """Plain data (JSON types), with a ``format`` key and the voltage program's ``kind``."""
        voltage: dict[str, Any] | None = None
        if self.voltage is not None:
            kind = next(k for k, c in _VOLTAGE_KINDS.items() if isinstance(self.voltage, c))
            voltage = {"kind": kind, **asdict(self.voltage)}
        return {
            "format": FORMAT,
            "case": self.case,
            "subambient": self.subambient,
            "preload_response": self.preload_response,
            "actuator_dynamics": self.actuator_dynamics,
            "imbalance": self.imbalance,
            "load": self.load,
            "speed_times": list(self.speed_times),
            "speeds": list(self.speeds),
            "voltage": voltage,
            "settings": asdict(self.settings),
            "stop_time": self.stop_time,
            "recorded_case": None if self.recorded_case is None else self.recorded_case.to_dict(),
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> RunSpec:
        """The specification of :meth:`to_dict`'s data, or of an earlier version's
        dictionary of command-line strings (:meth:`from_cli_strings`).

        Raises
        ------
        InputError
            One line for data that is not such a specification: a missing or mistyped
            key, a value that is not a finite number, a recorded case that does not match
            its sha256, an unknown format or voltage program.
        """
        if not isinstance(data, dict):
            raise InputError(f"run specification: expected a JSON object, got {data!r:.40}")
        if "format" in data and data["format"] not in _FORMATS:
            raise InputError(f"run specification of an unknown format {data['format']!r:.60}")
        try:
            if "format" not in data:  # an earlier version's command-line strings
                return cls.from_cli_strings(data)
            return cls._from_dict(data)
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            what = f"key {exc} missing" if isinstance(exc, KeyError) else str(exc)
            raise InputError(f"run specification damaged: {what}") from None

    @classmethod
    def _from_dict(cls, data: dict[str, Any]) -> RunSpec:
        record = data.get("recorded_case")
        recorded = None if record is None else CaseRecord.from_dict(record)
        times = _finite(data["speed_times"], "speed_times")
        speeds = _finite(data["speeds"], "speeds")
        stop = data.get("stop_time")
        if stop is not None:
            stop = _finite([stop], "stop_time")[0]
        voltage = data.get("voltage")
        program: VoltageSpec | None = None
        if voltage is not None:
            kind = voltage["kind"]
            rest = {k: v for k, v in voltage.items() if k != "kind"}
            if kind == "piecewise":
                program = PiecewiseVoltages(
                    tuple(float(t) for t in rest["times"]),
                    tuple(tuple(float(v) for v in row) for row in rest["volts"]),
                )
            elif kind in _VOLTAGE_KINDS:
                program = _VOLTAGE_KINDS[kind](**rest)
            else:
                raise InputError(f"run specification: unknown voltage program {kind!r}")
        return cls(
            times,
            speeds,
            program,
            data.get("case"),
            data.get("subambient"),
            data.get("imbalance"),
            OrbitSettings(**data.get("settings", {})),
            stop,
            data.get("preload_response"),
            data.get("actuator_dynamics"),
            data.get("load"),
            recorded_case=recorded,
        )

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON (floats written exactly: the run reads back equal)."""
        return json.dumps(self.to_dict())

    @classmethod
    def from_json(cls, text: str) -> RunSpec:
        """The specification of :meth:`to_json`'s text (or of an earlier version's).

        Raises
        ------
        InputError
            Text that is not JSON (a cut record) or not a specification (:meth:`from_dict`).
        """
        try:
            data = json.loads(text)
        except (TypeError, ValueError) as exc:
            raise InputError(
                f"run specification is not valid JSON (cut or damaged?): {exc}"
            ) from None
        return cls.from_dict(data)

    @classmethod
    def from_cli_strings(cls, strings: dict[str, Any]) -> RunSpec:
        """Parse ``foilbearing orbit``'s option strings (the dictionary earlier versions
        stored): ``speed_ramp`` or ``speed`` and ``duration``, at most one of
        ``voltage_ramp``, ``controller`` and ``voltage_schedule`` ({"path", "text"}),
        ``stop_time``, ``steps_per_rev``, ``order``, ``steps``, ``step_rtol``,
        ``sample_rate``, ``case``,
        ``subambient`` and ``load``; missing keys take the command's defaults.

        Raises
        ------
        InputError
            One line naming the option, for a string that does not parse or a
            program that cannot be built (a voltage ramp needs ``[actuators]``).
        """
        from foilbearing.control import voltage_ramp

        spec = _CLI_DEFAULTS | dict(strings)
        case_obj = _load_case(  # its errors come first
            spec["case"],
            spec["subambient"],
            None,
            spec["preload_response"],
            spec["actuator_dynamics"],
            None if spec["load"] is None else cli_quantity(spec["load"], "force", "--load"),
        )
        if spec["speed"] is not None:
            profile = steady_speed(spec["speed"], spec["duration"])
        else:
            profile = speed_ramp(spec["speed_ramp"])
        chosen = [
            f"--{k.replace('_', '-')}"
            for k in ("voltage_ramp", "controller", "voltage_schedule")
            if spec[k] is not None
        ]
        if len(chosen) > 1:
            raise InputError(f"{' and '.join(chosen)}: choose one voltage program")
        program: VoltageSpec | None = None
        if spec["voltage_schedule"] is not None:
            given = spec["voltage_schedule"]
            program = ScheduleText(given["text"], given["path"])
        if spec["voltage_ramp"] is not None:
            t0, t1, volts = voltage_ramp_times(spec["voltage_ramp"])
            if case_obj.actuators is None:
                raise InputError("--voltage-ramp needs a case with [actuators]")
            initial = np.asarray(case_obj.actuators.voltages)  # from the case's
            program = PiecewiseVoltages.of(voltage_ramp(t0, t1, volts, initial=initial))
        if spec["controller"] is not None:
            program = ControllerParams(**controller_args(spec["controller"]))
        settings = OrbitSettings(
            steps_per_rev=int(spec["steps_per_rev"]),
            order=int(spec["order"] or 2),
            steps=str(spec["steps"]),
            step_rtol=float(spec["step_rtol"]),
            sample_rate=cli_quantity(spec["sample_rate"], "frequency", "--sample-rate"),
        )
        stop = spec["stop_time"]
        made = cls.of(
            profile,
            program,
            case=None if spec["case"] is None else str(spec["case"]),
            subambient=spec["subambient"],
            preload_response=spec["preload_response"],
            actuator_dynamics=spec["actuator_dynamics"],
            load=case_obj.operation.load if spec["load"] is not None else None,
            settings=settings,
            stop_time=None if stop is None else cli_quantity(stop, "time", "--stop-time"),
        )
        return made.with_case(case_obj)


def _load_case(
    path: str | None,
    subambient: str | None,
    imbalance: float | None,
    preload_response: str | None = None,
    actuator_dynamics: str | None = None,
    load: float | None = None,
) -> Case:
    """The case file (None: the default case) with the overrides applied."""
    from dataclasses import replace

    from foilbearing.case import load_case

    case = load_case(path)
    if subambient is not None:
        case = case.with_subambient(subambient)
    if preload_response is not None or actuator_dynamics is not None:
        case = case.with_actuator_reading(preload_response, actuator_dynamics)
    if imbalance is not None:
        case = replace(case, rotor=replace(case.rotor, imbalance=imbalance))
    if load is not None:
        case = case.with_load(load)
    return case


def _finite(values: Any, name: str) -> tuple[float, ...]:
    """``values`` as floats, each finite (ValueError naming ``name`` otherwise)."""
    out = tuple(float(v) for v in values)
    if not all(np.isfinite(out)):
        raise ValueError(f"{name} = {list(out)!r:.60}: expected finite numbers")
    return out
