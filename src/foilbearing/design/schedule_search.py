"""The search for a voltage schedule in speed: the least-drag actuator voltages that keep
the rotor stable, speed by speed (beyond the paper). The schedule it returns, a
:class:`~foilbearing.control.speed_schedule.SpeedSchedule`, is what a controller follows.

The paper ramps its three actuators to one voltage at one moment. A controller
needs, at each speed, the voltage of each actuator. At every speed Ω of a grid,
:func:`voltage_schedule` chooses the voltages v (each in ``[0, max_voltage]``)
that

- minimise the power loss P(v) = T_drag(v) · Ω of the static equilibrium, subject
  to a stability margin: the logarithmic decrement δ(v) of the least stable
  whirl mode of the rotor on the bearing (:func:`foilbearing.analysis.stability.whirl_mode`,
  the linear analysis of docs/model.md §4) is at least ``margin``;
- where no voltages meet the margin, the most stable voltages found (largest δ).

The search is the optimiser of :mod:`foilbearing.design.voltages` (the paper's equal
voltages, a seeded Latin hypercube and the previous speed's voltages as starts,
then a bounded Nelder-Mead) on a merit that ranks every voltage set meeting the
margin by its power loss, ahead of every set that misses it, which are ranked
by how far they miss. Nelder-Mead compares merits only, so the jump between the
two ranks does not disturb it.

**Smoothness.** An amplifier follows a voltage at most at its slew rate S (V/s).
During a speed-up at α (rad/s²) the schedule then changes by at most k = S/α
volts per rad/s. The optimum of each speed is raised to the smallest k-Lipschitz
envelope above it, V_s(Ω) = max_j [V(Ω_j) − k |Ω − Ω_j|]: a voltage rises
early and falls late, never later or lower than the optimum asks. Where the
envelope changes a voltage, the point is evaluated again, so the power loss and
log decrement reported are those of the voltages scheduled.

**Between the grid speeds** the voltages are interpolated linearly; the log
decrement is evaluated again halfway between consecutive speeds, at the
interpolated voltages, since a least stable mode can change in between.

**Limit speed.** The speed above which no voltage keeps the rotor stable: the
first zero of the scheduled log decrement along the grid speeds and the
midpoints, by linear interpolation between the two around it (None when it
stays ≥ 0 up to the top speed).

**Grid error** (:func:`schedule_grid_check`). The schedule is searched on the case's grid;
its points (the scheduled voltages at every grid speed and midpoint) are evaluated again on
a grid with ``factor`` times the cells in θ and in Z, and each readout's error is the
difference, as ``foilbearing check`` states it. Whether the margin holds is then read on
both grids.

All quantities in SI (rad/s, V, W) unless a name says otherwise.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.control.speed_schedule import DEFAULT_SLEW_RATE, SpeedSchedule
from foilbearing.design.voltages import (
    FAILED_MERIT,
    EvaluationCache,
    local_search,
    start_points,
    voltage_box,
)
from foilbearing.errors import InputError, SolverError

__all__ = [
    "DEFAULT_ACCELERATION",
    "DEFAULT_MARGIN",
    "DEFAULT_SLEW_RATE",
    "SchedulePoint",
    "SpeedSchedule",
    "check_speed_range",
    "evaluate_voltages",
    "schedule_grid_check",
    "voltage_schedule",
]

FloatArray = NDArray[np.float64]
Voltages = tuple[float, ...]

DEFAULT_MARGIN = 0.1  # least log decrement of the least stable whirl mode
#: Speed-up rate the schedule's smoothness is set for, rad/s²: the paper's 500 rad/s².
DEFAULT_ACCELERATION = 500.0
#: V: the paper's constant voltage, the schedule's comparison (``power_loss_reference``).
PAPER_CONSTANT_VOLTAGE = 150.0
REFERENCE_VOLTAGE = PAPER_CONSTANT_VOLTAGE  # its old name
_MISSED = 1e6  # merit offset of a voltage set that misses the margin (W ≪ this)


@dataclass(frozen=True)
class SchedulePoint:
    """The rotor on the bearing at one speed and one set of actuator voltages.

    Attributes
    ----------
    speed
        Rotor speed, rad/s.
    voltages
        Voltage of each actuator, V.
    power_loss
        Viscous power loss of the static equilibrium, W (drag torque × speed).
    log_decrement
        δ of the least stable whirl mode (> 0 stable).
    whirl_frequency
        Its damped frequency, rad/s.
    min_film
        Minimum film of the equilibrium, m.
    """

    speed: float
    voltages: Voltages
    power_loss: float
    log_decrement: float
    whirl_frequency: float
    min_film: float


def evaluate_voltages(
    case: Case, speed: float, voltages: Sequence[float], start: Any = None
) -> tuple[SchedulePoint | None, Any]:
    """Static equilibrium and least stable whirl mode at ``speed`` (rad/s) and ``voltages`` (V).

    ``start`` is an ``(eps_x, eps_y, P)`` initial guess of the equilibrium.
    Returns the point (None where the case rejects the voltages, or no
    equilibrium or whirl mode is found) and the equilibrium as a start for the
    next evaluation.
    """
    from foilbearing.analysis.equilibrium import solve_equilibrium
    from foilbearing.analysis.stability import whirl_mode
    from foilbearing.film import film_model

    volts = tuple(float(v) for v in voltages)
    try:
        c = case.with_voltages(volts)
        model = film_model(c)
        st = solve_equilibrium(c, speed=speed, model=model, start=start)
        if not st.converged and start is not None:
            st = solve_equilibrium(c, speed=speed, model=model)
        if not st.converged:
            return None, start
        mode = whirl_mode(st, c.rotor.mass)
    except (InputError, SolverError):
        return None, start
    point = SchedulePoint(
        speed=speed,
        voltages=volts,
        power_loss=st.power_loss,
        log_decrement=mode.log_decrement,
        whirl_frequency=mode.whirl_frequency,
        min_film=st.min_film,
    )
    return point, (st.eps_x, st.eps_y, st.P)


def check_speed_range(case: Case, speeds: Sequence[float], field: str = "--speed-range") -> None:
    """A one-line error for speeds outside ``(0, operation.max_speed]`` of the case
    (:meth:`foilbearing.case.Case.check_speeds`)."""
    case.check_speeds(speeds, field)


def _envelope(speeds: FloatArray, volts: FloatArray, slope: float) -> FloatArray:
    """Smallest function ≥ ``volts`` whose slope is at most ``slope`` (V per rad/s), per column."""
    gap = np.abs(speeds[:, None] - speeds[None, :])  # (i, j)
    return np.asarray(np.max(volts[None, :, :] - slope * gap[:, :, None], axis=1), dtype=float)


def _limit_speed(speeds: FloatArray, dec: FloatArray) -> float | None:
    """First zero of the log decrement along speed, linear between grid speeds."""
    for k, d in enumerate(dec):
        if not (d < 0.0):  # stable, or NaN (no result): go on
            continue
        if k == 0:
            return float(speeds[0])
        d0 = dec[k - 1]
        if not math.isfinite(d0):
            return float(speeds[k])
        return float(speeds[k - 1] + (speeds[k] - speeds[k - 1]) * d0 / (d0 - d))
    return None


def voltage_schedule(
    case: Case,
    speeds: Sequence[float],
    *,
    margin: float = DEFAULT_MARGIN,
    slew_rate: float = DEFAULT_SLEW_RATE,
    acceleration: float = DEFAULT_ACCELERATION,
    max_evaluations: int = 40,
    n_random: int = 4,
    progress: Callable[[str], None] | None = None,
) -> SpeedSchedule:
    """Least-drag voltages with a stability margin at each speed (see the module docstring).

    Parameters
    ----------
    case
        Bearing case with ``[actuators]`` (rotor mass per bearing from ``[rotor]``).
    speeds
        Grid speeds, rad/s, increasing, within ``(0, operation.max_speed]``.
    margin
        Least log decrement of the least stable whirl mode (≥ 0).
    slew_rate
        Amplifier slew-rate limit, V/s (> 0).
    acceleration
        Speed-up rate the smoothness is set for, rad/s² (> 0).
    max_evaluations
        Cap on the equilibria per speed (starts included).
    n_random
        Latin-hypercube starts per speed, besides the equal voltages and the
        previous speed's optimum.
    progress
        Called with one line per speed.

    Raises
    ------
    InputError
        Bad input, before any work: no actuators, speeds outside the case's
        limits or not increasing, a negative margin, a slew rate or
        acceleration ≤ 0.
    SolverError
        No equilibrium at some speed for any voltage evaluated.
    """
    lo, hi = voltage_box(case, None, "Nelder-Mead", max_evaluations)
    w = np.asarray(speeds, dtype=float)
    check_speed_range(case, w.tolist())
    if w.size < 1 or np.any(np.diff(w) <= 0.0):
        raise InputError("--speed-range: the speeds must increase", source=case.source)
    if not (math.isfinite(margin) and margin >= 0.0):
        raise InputError(f"--margin {margin!r}: expected a log decrement >= 0", source=case.source)
    for name, value, unit in (
        ("slew_rate", slew_rate, "V/s"),
        ("acceleration", acceleration, "rad/s²"),
    ):
        if not (math.isfinite(value) and value > 0.0):
            raise InputError(f"{name} = {value!r} {unit}: expected > 0", source=case.source)
    equal, extra = start_points(lo, hi, n_random)
    ref_key = tuple(min(PAPER_CONSTANT_VOLTAGE, float(h)) for h in hi)
    chosen: list[SchedulePoint] = []
    reference: list[float] = []
    total = 0
    previous: Voltages | None = None
    start: list[Any] = [None]
    for speed in w:
        found: dict[Voltages, SchedulePoint] = {}

        def evaluate(
            v: Voltages, speed: float = float(speed), found: dict = found
        ) -> tuple[float, float]:
            point, start[0] = evaluate_voltages(case, speed, v, start[0])
            if point is None:
                return math.nan, FAILED_MERIT
            found[v] = point
            if point.log_decrement >= margin:
                return point.power_loss, point.power_loss
            return point.power_loss, _MISSED + 10.0 * (margin - point.log_decrement)

        cache = EvaluationCache(evaluate, lo, hi, max_evaluations, None, str)
        # the equal voltages include ref_key, so the constant-voltage reference is evaluated
        starts = ([previous] if previous is not None else []) + equal + extra
        local_search(cache, starts, "Nelder-Mead", xatol=0.5, fatol=1e-3)
        total += len(cache.points)
        if not found:
            raise SolverError(
                f"schedule: no equilibrium at {speed / RPM:.0f} rpm for any of the "
                f"{len(cache.points)} voltage sets tried: narrow --speed-range or check the load"
            )
        best = cache.best(list(found))
        previous = best
        chosen.append(found[best])
        ref = found.get(cache.key(ref_key))
        reference.append(math.nan if ref is None else ref.power_loss)
        if progress is not None:
            p = found[best]
            progress(
                f"{speed / RPM:8.0f} rpm: {'/'.join(f'{v:.1f}' for v in best)} V, "
                f"log dec {p.log_decrement:+.3f}, power loss {p.power_loss:.2f} W "
                f"({len(cache.points)} evaluations)"
            )
    volts = np.array([p.voltages for p in chosen], dtype=float)
    smooth = np.clip(_envelope(w, volts, slew_rate / acceleration), lo, hi)
    for k in np.flatnonzero(np.any(np.abs(smooth - volts) > 1e-3, axis=1)).tolist():
        point, start[0] = evaluate_voltages(case, float(w[k]), tuple(smooth[k]), start[0])
        total += 1
        if point is None:
            raise SolverError(
                f"schedule: no equilibrium at {w[k] / RPM:.0f} rpm for the slew-limited voltages "
                f"{smooth[k].round(1).tolist()} V: raise the slew rate or lower the acceleration"
            )
        chosen[k] = point
    dec = np.array([p.log_decrement for p in chosen])
    # Between grid speeds the voltages are interpolated: check the midpoints too.
    mid_w = 0.5 * (w[1:] + w[:-1])
    mid_dec = np.full(mid_w.size, np.nan)
    for k, wm in enumerate(mid_w):
        point, start[0] = evaluate_voltages(
            case, float(wm), tuple(0.5 * (smooth[k] + smooth[k + 1])), start[0]
        )
        total += 1
        if point is not None:
            mid_dec[k] = point.log_decrement
    both_w = np.empty(w.size + mid_w.size)
    both_w[0::2], both_w[1::2] = w, mid_w
    both_dec = np.empty_like(both_w)
    both_dec[0::2], both_dec[1::2] = dec, mid_dec
    return SpeedSchedule(
        speeds=w,
        voltages=smooth,
        slew_rate=slew_rate,
        acceleration=acceleration,
        margin=margin,
        power_loss=np.array([p.power_loss for p in chosen]),
        log_decrement=dec,
        whirl_frequency=np.array([p.whirl_frequency for p in chosen]),
        min_film=np.array([p.min_film for p in chosen]),
        power_loss_reference=np.array(reference),
        midpoint_log_decrement=mid_dec,
        limit_speed=_limit_speed(both_w, both_dec),
        evaluations=total,
        source=case.source,
    )


def schedule_grid_check(
    case: Case,
    schedule: SpeedSchedule,
    factor: int = 2,
    progress: Callable[[str], None] | None = None,
) -> dict[str, Any]:
    """The schedule's points evaluated again on ``factor`` times the cells in θ and in Z (the
    axial order and the lift-off smoothing κ held, :func:`foilbearing.check.refined`): the
    scheduled voltages at every grid speed and midpoint, as searched on ``case``'s grid.

    Returns
    -------
    dict
        ``grid`` and ``refined_grid`` ([n_θ, n_z]); per grid speed, on the refined grid,
        ``log_decrement``, ``whirl_frequency_Hz`` and ``power_loss_W`` and their ``errors``
        (the schedule's value less the refined one, None where either is missing);
        ``midpoint_log_decrement``; ``limit_speed_rpm`` on the refined grid (None: stable to
        the top speed) and its error (None unless both grids have one); ``below_margin``:
        the speeds (rpm) whose refined log decrement misses the margin by more than 1e-3
        where the schedule met it; ``wall_time_s``.
    """
    import time

    from foilbearing.check import refined

    if schedule.log_decrement is None:
        raise InputError("the schedule has no log decrements to check: compute it first")
    t0 = time.perf_counter()
    fine = refined(case, factor)
    w = np.asarray(schedule.speeds, dtype=float)
    volts = np.asarray(schedule.voltages, dtype=float)
    start: Any = None
    points: list[SchedulePoint | None] = []
    for k, speed in enumerate(w):
        point, start = evaluate_voltages(fine, float(speed), tuple(volts[k]), start)
        points.append(point)
        if progress is not None:
            shown = "no equilibrium" if point is None else f"log dec {point.log_decrement:+.3f}"
            progress(f"{speed / RPM:8.0f} rpm on {fine.grid.n_theta} x {fine.grid.n_z}: {shown}")
    mid = np.full(max(w.size - 1, 0), np.nan)
    for k in range(mid.size):
        wm, vm = 0.5 * (w[k] + w[k + 1]), tuple(0.5 * (volts[k] + volts[k + 1]))
        point, start = evaluate_voltages(fine, float(wm), vm, start)
        if point is not None:
            mid[k] = point.log_decrement

    def values(get: Callable[[SchedulePoint], float]) -> list[float | None]:
        return [None if p is None else float(get(p)) for p in points]

    fine_dec = values(lambda p: p.log_decrement)
    fine_hz = values(lambda p: p.whirl_frequency / (2.0 * math.pi))
    fine_power = values(lambda p: p.power_loss)
    coarse = schedule.headline()

    def errors(key: str, refined_values: list[float | None]) -> list[float | None]:
        mine = coarse[key] or [None] * len(refined_values)  # None: not in the schedule file
        return [
            None if a is None or b is None else a - b
            for a, b in zip(mine, refined_values, strict=True)
        ]

    both_w = np.empty(w.size + mid.size)
    both_w[0::2], both_w[1::2] = w, 0.5 * (w[1:] + w[:-1])
    both_dec = np.empty_like(both_w)
    both_dec[0::2] = [math.nan if d is None else d for d in fine_dec]
    both_dec[1::2] = mid
    limit = _limit_speed(both_w, both_dec)
    limit_rpm = None if limit is None else limit / RPM
    coarse_limit = coarse["limit_speed_rpm"]
    margin = schedule.margin if schedule.margin is not None else 0.0
    below = [
        float(speed / RPM)
        for speed, a, b in zip(w, coarse["log_decrement"] or [None] * w.size, fine_dec, strict=True)
        if a is not None and b is not None and a >= margin - 1e-12 and b < margin - 1e-3
    ]
    return {
        "grid": [case.grid.n_theta, case.grid.n_z],
        "refined_grid": [fine.grid.n_theta, fine.grid.n_z],
        "log_decrement": fine_dec,
        "whirl_frequency_Hz": fine_hz,
        "power_loss_W": fine_power,
        "errors": {
            "log_decrement": errors("log_decrement", fine_dec),
            "whirl_frequency_Hz": errors("whirl_frequency_Hz", fine_hz),
            "power_loss_W": errors("power_loss_W", fine_power),
        },
        "midpoint_log_decrement": [float(d) if math.isfinite(d) else None for d in mid],
        "limit_speed_rpm": limit_rpm,
        "limit_speed_error_rpm": None
        if limit_rpm is None or coarse_limit is None
        else coarse_limit - limit_rpm,
        "below_margin_rpm": below,
        "wall_time_s": time.perf_counter() - t0,
    }
