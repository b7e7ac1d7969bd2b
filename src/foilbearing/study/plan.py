"""The study's plan for any bearing: what to run, derived from the case and its ``[study]`` table.

The paper's C-GFB has its own plan (the paper's speeds, voltages and protocol,
:mod:`foilbearing.study.paper`). Every other bearing (a passive gas foil bearing, a
shimmed one, a rigid gas journal bearing) gets the plan below; a ``[study]``
table in the case file sets any part of it (docs/case-format.md):

=====================  =====================================================  =========================
key                    meaning                                                default
=====================  =====================================================  =========================
``speed_range``        [START, STOP, STEP]: static, coefficients, stability    10 % of the case speed to
                       map and the orbit's speed-up                           the case speed, 10 steps
``loads``              loads of the load-capacity curve at the case speed     the case load doubled
                                                                              until the film closes
``frequency_speeds``   speeds of the coefficients against frequency           the case speed
``map_speeds``         speeds of the film and pressure maps (case load)       the case speed
``onset_top``          the onset scan goes on up to this speed                ``operation.max_speed``
``orbit``              run the speed-up (true/false)                          true
``orbit_acceleration`` its rate                                               500 rad/s² (the paper's)
``shim_scales``        shimmed bearing: onset against the shims' thickness,   0, 0.5, 1, 1.5 (those
                       as multiples of the case's                             below 0.9 C)
``voltages``           C-GFB: onset against the actuators' voltage (all the   0, 1/3, 2/3 and 1 of
                       same), and the voltage schedule over ``speed_range``   ``max_voltage``
``orbit_voltage_ramp`` C-GFB: the speed-up's voltages go from the case's to    the case's voltages
                       ``voltage`` between ``start`` and ``end`` (a table)    held
``[study.identification]`` C-GFB: ``no_load`` and ``stiffness`` stack test    none
                       files (CSV, relative to the case file) to identify
                       D33,1, D33,2 and K_p from
``[study.reference]``  measured values to compare with (:data:`REFERENCE_KEYS`: none
                       onset, whirl, divergence; static readouts and the
                       synchronous coefficients at the case speed)
=====================  =====================================================  =========================

Every check is made before any work and fails with one line naming the file
and the field.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Any

from foilbearing.case import Case, TableReader
from foilbearing.constants import RPM
from foilbearing.errors import InputError

__all__ = [
    "CASE_POINT_KEYS",
    "REFERENCE_KEYS",
    "StudyPlan",
    "check_load_is_carried",
    "study_plan",
]

_STAGE_KEYS = ("onset_speed", "whirl_frequency", "divergence_speed")

#: Reference values a case may declare, with their kind of quantity and what they are
#: compared with.
REFERENCE_KEYS = {
    "onset_speed": ("speed", "linear onset speed of instability"),
    "whirl_frequency": ("frequency", "whirl frequency at the linear onset"),
    "divergence_speed": ("speed", "divergence speed of the speed-up orbit"),
    "eccentricity": ("dimensionless", "eccentricity ratio at the case speed and load"),
    "attitude_angle": ("angle", "attitude angle at the case speed and load"),
    "min_film": ("length", "minimum film at the case speed and load"),
    "power_loss": ("power", "film power loss at the case speed and load"),
    **{
        f"{kind}_{a}{b}": (
            "stiffness" if kind == "K" else "damping",
            f"synchronous {'stiffness' if kind == 'K' else 'damping'} {kind}{a.upper()}"
            f"{b.upper()} at the case speed",
        )
        for kind in "KC"
        for a in "xy"
        for b in "xy"
    },
}
#: Reference values read at the case speed and load (the rest come from the stages).
CASE_POINT_KEYS = tuple(k for k in REFERENCE_KEYS if k not in _STAGE_KEYS)
MAX_AUTO_LOADS = 12  # doublings of the automatic load-capacity curve


@dataclass(frozen=True)
class StudyPlan:
    """What the study runs on one case; speeds rad/s, loads N, accelerations rad/s².

    Attributes
    ----------
    kind
        Bearing kind (:attr:`foilbearing.case.Case.kind`).
    speeds
        Speeds of the static sweep, the synchronous coefficients, the stability
        map and the orbit's speed-up (from the first to the last).
    onset_top
        The onset scan continues above ``speeds`` up to this speed.
    loads
        Loads of the load-capacity curve at the case speed; empty: automatic
        (the case load halved, then doubled until the film closes).
    frequency_speeds, map_speeds
        Speeds of the coefficients against frequency and of the film maps.
    orbit, orbit_acceleration
        Whether to run the speed-up, and its rate.
    shim_scales
        Shimmed bearing: multiples of the case's shim thicknesses for the onset
        against thickness (empty for other bearings).
    voltages
        C-GFB: the voltages of the onset and of the static readouts against
        voltage, V (empty for other bearings).
    orbit_voltage_ramp
        C-GFB: (start s, end s, voltage V) of the speed-up's voltage ramp from
        the case's voltages; None holds the case's voltages.
    identification
        C-GFB: the no-load and stiffness test files (absolute paths) to identify
        the stacks from; None: no identification.
    reference
        Measured values to put beside ours, SI (rad/s, Hz, rad, m, W, N/m,
        N·s/m), by key of :data:`REFERENCE_KEYS`.
    """

    kind: str
    speeds: tuple[float, ...]
    onset_top: float
    loads: tuple[float, ...]
    frequency_speeds: tuple[float, ...]
    map_speeds: tuple[float, ...]
    orbit: bool
    orbit_acceleration: float
    reference: dict[str, float] = field(default_factory=dict)
    shim_scales: tuple[float, ...] = ()
    voltages: tuple[float, ...] = ()
    orbit_voltage_ramp: tuple[float, float, float] | None = None
    identification: tuple[str, str] | None = None

    def onset_scan(self) -> list[float]:
        """The onset scan: the plan's speeds, continued at their step up to ``onset_top``."""
        w = list(self.speeds)
        step = w[1] - w[0] if len(w) > 1 else w[0]
        while w[-1] + step <= self.onset_top * (1 + 1e-9):
            w.append(w[-1] + step)
        return w

    def describe(self) -> dict[str, Any]:
        """The plan with unit-named keys (report and JSON)."""
        return {
            "bearing_kind": self.kind,
            "speeds_rpm": [w / RPM for w in self.speeds],
            "onset_scan_top_rpm": self.onset_top / RPM,
            "loads_N": list(self.loads) or "automatic: halved, then doubled until the film closes",
            "frequency_speeds_rpm": [w / RPM for w in self.frequency_speeds],
            "map_speeds_rpm": [w / RPM for w in self.map_speeds],
            "orbit": self.orbit,
            "orbit_acceleration_rad_per_s2": self.orbit_acceleration,
            "shim_scales": list(self.shim_scales),
            "voltages_V": list(self.voltages),
            "orbit_voltage_ramp": (
                None
                if self.orbit_voltage_ramp is None
                else dict(
                    zip(("start_s", "end_s", "voltage_V"), self.orbit_voltage_ramp, strict=True)
                )
            ),
            "identification": (
                None
                if self.identification is None
                else dict(zip(("no_load", "stiffness"), self.identification, strict=True))
            ),
            "reference": {key: shown_reference(key, v)[0] for key, v in self.reference.items()},
        }


def shown_reference(key: str, value: float) -> tuple[float, str]:
    """A reference value (SI) in the unit the report shows it in, and that unit."""
    kind = REFERENCE_KEYS[key][0]
    scale, unit = _SHOWN[kind]
    return value * scale, unit


_SHOWN = {
    "speed": (1.0 / RPM, "rpm"),
    "frequency": (1.0, "Hz"),
    "dimensionless": (1.0, "-"),
    "angle": (180.0 / math.pi, "deg"),
    "length": (1e6, "um"),
    "power": (1.0, "W"),
    "stiffness": (1.0, "N/m"),
    "damping": (1.0, "N*s/m"),
}


def _values(t: TableReader, key: str, kind: str, example: str) -> tuple[float, ...] | None:
    """List field ``key`` of ``[study]`` as sorted SI values, or None when absent."""
    from foilbearing.units import parse_quantity

    raw = t.raw(key, default=None)
    if raw is None:
        return None
    if not isinstance(raw, list) or not raw:
        raise t.error(key, raw, f"a non-empty list, e.g. {example}")
    return tuple(
        sorted(
            parse_quantity(v, kind, field=f"{t.prefix}{key}[{i}]", source=t.source)
            for i, v in enumerate(raw)
        )
    )


def _speeds(t: TableReader, key: str, default: float, top: float) -> tuple[float, ...]:
    values = _values(t, key, "speed", "['50000 rpm']")
    if values is None:
        return (default,)
    if not (0.0 < values[0] and values[-1] <= top * (1 + 1e-12)):
        raise t.error(
            key, t.data[key], f"speeds above 0 and up to operation.max_speed = {top / RPM:.0f} rpm"
        )
    return values


def study_plan(case: Case) -> StudyPlan:
    """The plan of ``case`` (see the module docstring); checks the ``[study]`` table.

    Raises
    ------
    InputError
        An unknown key, a bad value, a speed beyond ``operation.max_speed``; one line.
    """
    from foilbearing.sweep.analyses import speed_scan

    data = json.loads(case.study_table) if case.study_table else {}
    t = TableReader(data, "study", case.source)
    top = case.operation.max_speed
    speed = case.operation.speed
    raw = t.raw("speed_range", default=None)
    if raw is None:
        speeds = [speed * (k / 10.0) for k in range(1, 11)]  # the last is the case speed
    else:
        speeds = speed_scan(raw, "study.speed_range", case.source or "the case")
        if speeds[-1] > top * (1 + 1e-12):
            raise InputError(
                f"study.speed_range = {raw!r}: goes beyond operation.max_speed = "
                f"{top / RPM:.0f} rpm; lower STOP or raise max_speed",
                source=case.source,
            )
    onset_top = t.positive("onset_top", "speed", default=top)
    if onset_top > top * (1 + 1e-12):
        raise t.error(
            "onset_top", data["onset_top"], f"at most operation.max_speed = {top / RPM:.0f} rpm"
        )
    loads = _values(t, "loads", "force", "['5 N', '10 N']") or ()
    if loads and loads[0] < 0.0:
        raise t.error("loads", data["loads"], "loads >= 0 N")
    frequency_speeds = _speeds(t, "frequency_speeds", speed, top)
    map_speeds = _speeds(t, "map_speeds", speed, top)
    orbit = t.raw("orbit", default=True)
    if not isinstance(orbit, bool):
        raise t.error("orbit", orbit, "true or false")
    accel = t.positive("orbit_acceleration", "angular_acceleration", default=500.0)
    scales: tuple[float, ...] = ()
    raw_scales = t.raw("shim_scales", default=None)
    if case.shims is not None:
        thickest = max(case.shims.thicknesses)
        if raw_scales is None:
            scales = tuple(
                k for k in (0.0, 0.5, 1.0, 1.5) if k * thickest < 0.9 * case.bearing.clearance
            )
        else:
            ok = (
                isinstance(raw_scales, list)
                and raw_scales
                and all(
                    isinstance(k, int | float) and not isinstance(k, bool) and k >= 0
                    for k in raw_scales
                )
            )
            if not ok or max(raw_scales) * thickest >= case.bearing.clearance:
                raise t.error(
                    "shim_scales",
                    raw_scales,
                    "a list of multiples >= 0 of the shims' thickness, each shim below the "
                    f"clearance ({case.bearing.clearance * 1e6:g} um)",
                )
            scales = tuple(sorted(float(k) for k in raw_scales))
    elif raw_scales is not None:
        raise t.error("shim_scales", raw_scales, "nothing: this bearing has no [shims]")
    given = _values(t, "voltages", "voltage", "['0 V', '150 V']")
    voltages: tuple[float, ...] = ()
    if case.actuators is not None:
        top_v = case.actuators.max_voltage
        voltages = given or tuple(top_v * k / 3.0 for k in range(4))
        if voltages[0] < 0.0 or voltages[-1] > top_v:
            raise t.error(
                "voltages", data["voltages"], f"voltages from 0 to max_voltage = {top_v:g} V"
            )
    elif given is not None:
        raise t.error("voltages", data["voltages"], "nothing: this bearing has no [actuators]")
    reference: dict[str, float] = {}
    if "reference" in data:
        ref = t.table("reference")
        for key, (kind, _) in REFERENCE_KEYS.items():
            signed = kind in ("stiffness", "damping", "angle")  # cross terms, attitude
            value = (ref.quantity if signed else ref.positive)(key, kind, default=None)
            if value is not None:
                reference[key] = float(value)
        ref.done()
    ramp = _orbit_voltage_ramp(t, case)
    identification = _identification_files(t, case)
    t.done()
    return StudyPlan(
        kind=case.kind,
        speeds=tuple(speeds),
        onset_top=float(onset_top),
        loads=loads,
        frequency_speeds=frequency_speeds,
        map_speeds=map_speeds,
        orbit=orbit,
        orbit_acceleration=float(accel),
        reference=reference,
        shim_scales=scales,
        voltages=voltages,
        orbit_voltage_ramp=ramp,
        identification=identification,
    )


def _orbit_voltage_ramp(t: TableReader, case: Case) -> tuple[float, float, float] | None:
    """``orbit_voltage_ramp = {start, end, voltage}``: checked against the stack's limits."""
    if t.raw("orbit_voltage_ramp", default=None) is None:
        return None
    if case.actuators is None:
        raise t.error(
            "orbit_voltage_ramp", t.data["orbit_voltage_ramp"], "nothing: this bearing has no "
            "[actuators]"
        )  # fmt: skip
    r = t.table("orbit_voltage_ramp")
    start = r.nonnegative("start", "time")
    end = r.nonnegative("end", "time")
    volts = r.nonnegative("voltage", "voltage")
    r.done()
    if end < start:
        raise r.error("end", r.data["end"], f"a time at or after start = {r.data['start']!r}")
    if volts > case.actuators.max_voltage:
        raise r.error(
            "voltage", r.data["voltage"], f"0 to max_voltage = {case.actuators.max_voltage:g} V"
        )
    return float(start), float(end), float(volts)


def _identification_files(t: TableReader, case: Case) -> tuple[str, str] | None:
    """``[study.identification]``: both stack test files, read now so a bad one fails
    before any work (paths relative to the case file)."""
    from pathlib import Path

    from foilbearing.identification import read_no_load, read_stiffness

    if t.raw("identification", default=None) is None:
        return None
    if case.actuators is None:
        raise t.error(
            "identification", t.data["identification"], "nothing: this bearing has no [actuators]"
        )
    r = t.table("identification")
    base = Path(case.source).parent if case.source else Path.cwd()
    paths = []
    for key, read in (("no_load", read_no_load), ("stiffness", read_stiffness)):
        name = r.string(key, "")
        if not name:
            raise r.error(key, None, "the path of a CSV file (relative to the case file)")
        path = (base / name).resolve()
        if not path.is_file():
            raise r.error(key, name, f"an existing file (looked for {path})")
        read(path)
        paths.append(str(path))
    r.done()
    return paths[0], paths[1]


def check_load_is_carried(case: Case, plan: StudyPlan) -> None:
    """A one-line error when the case load has no equilibrium at the plan's top speed.

    A gas bearing carries more as it turns faster; if the top speed cannot carry the
    load, no speed of the plan can, and the study would only collect failures.
    """
    from foilbearing.analysis.equilibrium import solve_equilibrium

    top = plan.speeds[-1]
    st = solve_equilibrium(case, speed=top)
    if not st.converged:
        raise InputError(
            f"operation.load = {case.operation.load:g} N: no equilibrium even at the top speed "
            f"{top / RPM:.0f} rpm ({st.message}); lower the load or raise the speeds",
            source=case.source,
        )
