"""What the stack's stiffness buys: the 150 V onset against k_p under each actuator reading.

The paper's conclusion asks for it ("the PZT stack stiffness should be carefully
designed"). A stack is a spring in series with the bump: the film's pressure
shortens it, by a pocket under the stinger or by lowering the whole lobe, and an
elastic stack also yields during the whirl (docs/model.md §3.8). The answer is
read off the linear onset (:func:`foilbearing.analysis.stability.onset_speed`, coefficients
at the whirl's own frequency) on the case's grid:

- the shimmed GFB, rigid shims as thick as the base preloads: an ideal positioner
  at the base stroke, the bound no stack reaches;
- the case's bearing under each of the four readings, at the identified stack
  stiffness K_p and at multiples of it;
- the stiffness at which each reading first reaches a fraction (90 %) of the
  shimmed GFB's onset, by Brent's method in log k_p between the scan's points.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy.optimize import brentq

from foilbearing.analysis.stability import onset_speed
from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.laws.actuator import READINGS as ACTUATOR_READINGS
from foilbearing.units import speed_text

__all__ = ["READINGS", "StackDesign", "stack_case", "stack_design"]

#: The four readings (preload_response, dynamics), the case's default first
#: (:data:`foilbearing.laws.actuator.READINGS` as words).
READINGS: tuple[tuple[str, str], ...] = tuple(
    (r.preload_response, r.dynamics) for r in ACTUATOR_READINGS
)


@dataclass(frozen=True)
class StackDesign:
    """Onsets against the stack stiffness at one voltage. SI: rad/s, N/m (K_p).

    Attributes
    ----------
    voltage
        Voltage on every actuator, V.
    stack_stiffness
        The case's (identified) stack stiffness K_p, N/m.
    factors
        Multiples of K_p scanned, shape (n,).
    onsets, whirl_frequencies
        Per reading "response+dynamics": onset speed and whirl frequency (rad/s) at
        each factor, NaN where stable over the speed scan.
    shimmed_onset, shimmed_whirl
        The shimmed GFB's onset and whirl frequency, rad/s (None: stable over the scan).
    target
        The fraction of the shimmed onset asked for.
    required_factor
        Per reading, the least multiple of K_p whose onset reaches ``target`` times the
        shimmed one (None where none in the scan does).
    max_speed
        The scan's top speed, rad/s.
    """

    voltage: float
    stack_stiffness: float
    factors: np.ndarray
    onsets: dict[str, np.ndarray]
    whirl_frequencies: dict[str, np.ndarray]
    shimmed_onset: float | None
    shimmed_whirl: float | None
    target: float
    required_factor: dict[str, float | None]
    max_speed: float

    def table(self) -> list[dict[str, Any]]:
        """The design table of issue 29: shimmed, lobe+held, and the default at K_p × 1, 3, 10;
        each row names its ``reading`` ("local+compliant") and ``stiffness_factor`` (None
        for the shimmed GFB), the case of :func:`stack_case`."""
        rows: list[dict[str, Any]] = [
            _row(
                "shimmed GFB (ideal positioner at the base stroke)",
                None,
                self.shimmed_onset,
                self.shimmed_whirl,
            )
            | {"reading": None, "stiffness_factor": None}
        ]
        wanted = [
            ("lobe+held", 1.0),
            ("local+compliant", 1.0),
            ("local+compliant", 3.0),
            ("local+compliant", 10.0),
        ]
        for key, factor in wanted:
            i = int(np.argmin(np.abs(self.factors - factor)))
            if not math.isclose(self.factors[i], factor):
                continue
            on, wh = self.onsets[key][i], self.whirl_frequencies[key][i]
            rows.append(
                _row(
                    f"{key} at K_p × {factor:g}",
                    self.stack_stiffness * factor,
                    None if math.isnan(on) else float(on),
                    None if math.isnan(wh) else float(wh),
                )
                | {"reading": key, "stiffness_factor": factor}
            )
        return rows

    def headline(self) -> dict[str, Any]:
        """Unit-named keys (``--json``)."""
        return {
            "voltage_V": self.voltage,
            "stack_stiffness_N_per_m": self.stack_stiffness,
            "target_fraction_of_shimmed_onset": self.target,
            "table": self.table(),
            "stiffness_factors": self.factors.tolist(),
            "onset_rpm": {
                k: [None if math.isnan(x) else x / RPM for x in v] for k, v in self.onsets.items()
            },
            "required_stack_stiffness_N_per_m": {
                k: None if f is None else f * self.stack_stiffness
                for k, f in self.required_factor.items()
            },
            "max_speed_rpm": self.max_speed / RPM,
        }


def _row(label: str, k_p: float | None, onset: float | None, whirl: float | None) -> dict[str, Any]:
    return {
        "bearing": label,
        "stack_stiffness_N_per_m": k_p,
        "onset_speed_rpm": None if onset is None else onset / RPM,
        "whirl_frequency_Hz": None if whirl is None else whirl / (2 * math.pi),
    }


def stack_case(case: Case, voltage: float, factor: float, reading: tuple[str, str]) -> Case:
    """``case`` at ``voltage`` (V on every actuator) with its stack stiffness K_p times
    ``factor``, under ``reading`` (preload_response, dynamics): a bearing of the design."""
    base = case.with_voltages(voltage)
    if base.actuators is None:
        raise InputError("the stack design needs a case with [actuators]", source=case.source)
    stack = replace(base.actuators, stack_stiffness=base.actuators.stack_stiffness * factor)
    return replace(base, actuators=stack).with_actuator_reading(*reading)


def stack_design(
    case: Case,
    voltage: float = 150.0,
    *,
    factors: Sequence[float] = (0.3, 1.0, 3.0, 10.0, 30.0, 100.0),
    speeds: Sequence[float] | None = None,
    target: float = 0.9,
    readings: Sequence[tuple[str, str]] = READINGS,
    refine: bool = True,
    progress: Callable[[str], None] | None = None,
) -> StackDesign:
    """Onsets of the case at ``voltage`` against its stack stiffness, under every reading.

    Parameters
    ----------
    case
        A C-GFB case (with ``[actuators]``); its own reading does not matter, all four run.
    voltage
        Voltage on every actuator, V.
    factors
        Multiples of the case's stack stiffness K_p to scan (> 0, 1 included for the table).
    speeds
        Onset scan speeds, rad/s (default 5 krpm to the case's max_speed in 5 krpm steps).
    target
        Fraction of the shimmed GFB's onset that ``required_factor`` asks for, in (0, 1].
    readings
        The readings (preload_response, dynamics) to scan (default all four).
    refine
        Refine the required stiffness by Brent's method (a few onsets more per reading);
        otherwise interpolate the onset linearly in log k_p between the scan's points.
    progress
        Called with one line per onset found.
    """
    act = case.actuators
    if act is None:
        raise InputError("the stack design needs a case with [actuators]", source=case.source)
    if not 0.0 < target <= 1.0:
        raise InputError(f"target = {target!r}: expected a fraction in (0, 1]")
    f = np.array(sorted(float(x) for x in factors))
    if f.size == 0 or f[0] <= 0.0:
        raise InputError(f"stiffness factors {list(factors)!r}: expected values > 0")
    if speeds is None:
        top = int(case.operation.max_speed / RPM // 5000 * 5000)
        speeds = [rpm * RPM for rpm in range(5_000, top + 1, 5_000)]
    base = case.with_voltages(voltage)
    known: dict[tuple[float, tuple[str, str]], tuple[float, float]] = {}

    def at(factor: float, reading: tuple[str, str]) -> tuple[float, float]:
        factor = float(f[np.argmin(np.abs(f - factor))]) if np.isclose(f, factor).any() else factor
        if (factor, reading) in known:  # Brent's method starts at the scan's points
            return known[factor, reading]
        r = onset_speed(stack_case(case, voltage, factor, reading), speeds)
        if progress is not None:
            text = "stable" if r.onset_speed is None else speed_text(r.onset_speed / RPM)
            progress(f"  {'+'.join(reading):16s} K_p × {factor:<7.3g} onset {text}")
        found = (math.nan, math.nan)
        if r.onset_speed is not None and r.whirl_frequency is not None:
            found = (r.onset_speed, r.whirl_frequency)
        known[factor, reading] = found
        return found

    shim = onset_speed(base.shimmed(), speeds)
    onsets, whirls, required = {}, {}, {}
    goal = None if shim.onset_speed is None else target * shim.onset_speed
    for reading in readings:
        key = "+".join(reading)
        pairs = [at(x, reading) for x in f]
        onsets[key] = np.array([p[0] for p in pairs])
        whirls[key] = np.array([p[1] for p in pairs])
        required[key] = _first_crossing(
            f,
            onsets[key],
            goal,
            speeds[-1],
            functools.partial(_onset_of, at, reading) if refine else None,
        )
    return StackDesign(
        voltage=float(voltage),
        stack_stiffness=act.stack_stiffness,
        factors=f,
        onsets=onsets,
        whirl_frequencies=whirls,
        shimmed_onset=shim.onset_speed,
        shimmed_whirl=shim.whirl_frequency,
        target=target,
        required_factor=required,
        max_speed=float(speeds[-1]),
    )


def _onset_of(
    at: Callable[[float, tuple[str, str]], tuple[float, float]],
    reading: tuple[str, str],
    factor: float,
) -> float:
    return at(factor, reading)[0]


def _first_crossing(
    factors: np.ndarray,
    onsets: np.ndarray,
    goal: float | None,
    top: float,
    onset_at: Callable[[float], float] | None,
) -> float | None:
    """The least factor whose onset reaches ``goal`` (stable over the scan counts as above it),
    refined by Brent's method in log10 of the factor to 1 % (``onset_at`` given), or
    interpolated linearly in log10 of the factor between the scan's points."""
    if goal is None:
        return None
    y = np.where(np.isnan(onsets), top, onsets)
    reached = y >= goal
    if not reached.any():
        return None
    i = int(np.argmax(reached))
    if i == 0:
        return float(factors[0])
    lo, hi = math.log10(factors[i - 1]), math.log10(factors[i])
    if onset_at is None:
        frac = (goal - y[i - 1]) / (y[i] - y[i - 1])
        return float(10.0 ** (lo + frac * (hi - lo)))

    def gap(log_f: float) -> float:
        on = onset_at(10.0**log_f)
        return (top if math.isnan(on) else on) - goal

    return float(10.0 ** brentq(gap, lo, hi, xtol=0.004))
