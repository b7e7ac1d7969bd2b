"""Actuator voltages chosen by optimisation: beyond the paper's equal-voltage choice.

The paper drives its three PZT actuators with one voltage (0, 50, 100 or
150 V). Here each actuator gets its own voltage in ``[0, max_voltage]`` and a
derivative-free, bounded search picks the three that

- maximise the linear onset speed of instability (:func:`maximize_onset`), or
- minimise the drag torque at a given speed and load, keeping a minimum film
  (:func:`minimize_drag`).

Both searches start from the paper's equal-voltage choices, so the result is
never worse than the best of them (the *baseline*, reported beside it).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any, Literal

import numpy as np
from scipy.optimize import minimize
from scipy.stats import qmc

from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import InputError, SolverError

__all__ = [
    "FAILED_MERIT",
    "PAPER_VOLTAGES",
    "EvaluationCache",
    "VoltageOptimum",
    "local_search",
    "maximize_onset",
    "minimize_drag",
    "start_points",
    "voltage_box",
]

PAPER_VOLTAGES = (0.0, 50.0, 100.0, 150.0)  # V, the paper's equal-voltage choices
FAILED_MERIT = 1e30  # merit of a point without a result; finite so that Powell's line search copes
Voltages = tuple[float, ...]


@dataclass(frozen=True)
class VoltageOptimum:
    """The best actuator voltages found for one objective.

    Attributes
    ----------
    objective
        ``"onset"`` (maximise the onset speed, ``value`` in rad/s) or ``"drag"``
        (minimise the drag torque, ``value`` in N·m).
    voltages
        Voltage of each actuator, V, in the order of ``case.actuators.angles``.
    value
        Objective at ``voltages``: onset speed, rad/s, or drag torque, N·m.
    baseline_voltages, baseline_value
        The best of the paper's equal-voltage choices (0/50/100/150 V, clipped to
        the bounds), evaluated the same way: V and rad/s or N·m.
    evaluations
        Number of distinct voltage sets evaluated (the physics was run this often).
    history
        ``(voltages, value)`` in evaluation order; ``value`` is NaN where the
        point had no result (no equilibrium, or the film constraint violated).
    converged, message
        Whether the local search met its tolerances within the evaluation budget.
    speed, min_film
        Drag objective: rotor speed, rad/s, and minimum film at the optimum, m.
    stable_over_scan
        Onset objective: the optimum is stable over the whole scan; ``value`` is
        then the scan's top speed, a lower bound of the onset.
    """

    objective: Literal["onset", "drag"]
    voltages: Voltages
    value: float
    baseline_voltages: Voltages
    baseline_value: float
    evaluations: int
    history: tuple[tuple[Voltages, float], ...]
    converged: bool
    message: str
    speed: float | None = None
    min_film: float | None = None
    stable_over_scan: bool = False

    @property
    def improvement_percent(self) -> float:
        """Gain over the baseline, % (positive: a higher onset or a lower drag); NaN without one."""
        gain = self.value - self.baseline_value
        if self.objective == "drag":
            gain = -gain
        return 100.0 * gain / abs(self.baseline_value) + 0.0 if self.baseline_value else math.nan

    def headline(self) -> dict[str, Any]:
        """Headline numbers with unit-named keys (the CLI's ``--json``)."""
        if self.objective == "onset":
            key, scale = "onset_speed_rpm", 1.0 / RPM
        else:
            key, scale = "drag_torque_Nm", 1.0
        out: dict[str, Any] = {
            "objective": self.objective,
            "voltages_V": list(self.voltages),
            key: self.value * scale,
            "baseline_voltages_V": list(self.baseline_voltages),
            f"baseline_{key}": _finite(self.baseline_value * scale),
            "improvement_percent": _finite(self.improvement_percent),
            "evaluations": self.evaluations,
            "converged": self.converged,
            "message": self.message,
        }
        if self.objective == "onset":
            out["stable_over_scan"] = self.stable_over_scan
        else:
            out["speed_rpm"] = None if self.speed is None else self.speed / RPM
            out["min_film_um"] = None if self.min_film is None else self.min_film * 1e6
        return out


def _finite(x: float) -> float | None:
    return x if math.isfinite(x) else None


class _BudgetSpent(Exception):
    """Raised inside the local search when the evaluation budget is used up."""


class EvaluationCache:
    """Evaluations by voltage set (rounded to 1 mV), with a hard cap on their number.

    ``evaluate(v)`` returns ``(value, merit)``: the objective in SI (NaN if the
    point has no result) and the number the search minimises.
    """

    def __init__(
        self,
        evaluate: Callable[[Voltages], tuple[float, float]],
        lo: np.ndarray,
        hi: np.ndarray,
        max_evaluations: int,
        progress: Callable[[str], None] | None,
        show: Callable[[float], str],
    ) -> None:
        self.evaluate, self.lo, self.hi = evaluate, lo, hi
        self.max_evaluations, self.progress, self.show = max_evaluations, progress, show
        self.points: dict[Voltages, tuple[float, float]] = {}

    def key(self, x: Sequence[float]) -> Voltages:
        return tuple(round(float(v), 3) for v in np.clip(x, self.lo, self.hi))

    def merit(self, x: Sequence[float]) -> float:
        v = self.key(x)
        if v not in self.points:
            if len(self.points) >= self.max_evaluations:
                raise _BudgetSpent
            value, merit = self.evaluate(v)
            self.points[v] = (value, merit if math.isfinite(merit) else FAILED_MERIT)
            if self.progress is not None:
                self.progress(f"{len(self.points):3d}: {list(v)} V -> {self.show(value)}")
        return self.points[v][1]

    def best(self, among: Sequence[Voltages] | None = None) -> Voltages:
        keys = list(self.points) if among is None else [self.key(v) for v in among]
        return min(keys, key=lambda v: self.points[v][1])


def local_search(
    cache: EvaluationCache, starts: Sequence[Voltages], method: str, xatol: float, fatol: float
) -> tuple[bool, str]:
    """Evaluate ``starts``, then a bounded local search from the best; returns (converged, msg).

    Nelder-Mead is restarted with a fresh simplex from where it stopped until a restart
    no longer improves the merit (a simplex collapsed against a bound, e.g. at a corner
    of the voltage box, stops short of a descent along a diagonal). The budget of
    ``cache`` bounds the restarts.
    """
    lo, hi = cache.lo, cache.hi
    try:
        for v in starts:
            cache.merit(v)
        x0 = np.array(cache.best(), dtype=float)
        bounds = list(zip(lo, hi, strict=True))
        options: dict[str, Any]
        if method != "Nelder-Mead":
            options = {"xtol": xatol / max(float(np.max(hi - lo)), 1.0), "ftol": 1e-6}
            res = minimize(cache.merit, x0, method=method, bounds=bounds, options=options)
            return bool(res.success), f"{method}: {res.message}"
        while True:
            # A simplex a quarter of the box wide, pointing inwards from x0.
            step = 0.25 * (hi - lo)
            simplex = [x0]
            for i in range(x0.size):
                x = x0.copy()
                x[i] += step[i] if x0[i] + step[i] <= hi[i] else -step[i]
                simplex.append(x)
            options = {"xatol": xatol, "fatol": fatol, "initial_simplex": np.array(simplex)}
            before = cache.merit(tuple(x0.tolist()))
            res = minimize(cache.merit, x0, method=method, bounds=bounds, options=options)
            x0 = np.array(cache.best(), dtype=float)
            if not (res.success and cache.merit(tuple(x0.tolist())) < before - fatol):
                return bool(res.success), f"{method}: {res.message}"
    except _BudgetSpent:
        return False, (
            f"stopped at the budget of {cache.max_evaluations} evaluations before the "
            f"{method} tolerances were met: raise max_evaluations to go on"
        )


def voltage_box(
    case: Case, bounds: Sequence[tuple[float, float]] | None, method: str, max_evaluations: int
) -> tuple[np.ndarray, ...]:
    """Lower and upper voltage bounds, V, after checking the inputs (before any work)."""
    if method not in ("Nelder-Mead", "Powell"):
        raise InputError(f"method = {method!r}: allowed 'Nelder-Mead' or 'Powell'")
    if max_evaluations < len(PAPER_VOLTAGES):
        raise InputError(
            f"max_evaluations = {max_evaluations}: expected at least {len(PAPER_VOLTAGES)} "
            "(the paper's equal voltages are evaluated first)"
        )
    act = case.actuators
    if act is None:
        raise InputError("this case has no [actuators]: there are no voltages to optimise")
    n = len(act.angles)
    if bounds is None:
        bounds = [(0.0, act.max_voltage)] * n
    if len(bounds) != n:
        raise InputError(f"bounds: {len(bounds)} pairs given, the case has {n} actuators")
    lo, hi = np.array([float(b[0]) for b in bounds]), np.array([float(b[1]) for b in bounds])
    if np.any(lo < 0.0) or np.any(hi > act.max_voltage) or np.any(lo > hi):
        raise InputError(
            f"bounds = {list(bounds)}: each pair (low, high) needs "
            f"0 <= low <= high <= max_voltage = {act.max_voltage:g} V"
        )
    return lo, hi


def start_points(lo: np.ndarray, hi: np.ndarray, n_random: int) -> tuple[list[Voltages], ...]:
    """The paper's equal voltages clipped to the box, then a seeded Latin hypercube."""
    equal = list(dict.fromkeys(tuple(np.clip(v, lo, hi).tolist()) for v in PAPER_VOLTAGES))
    lhs = qmc.scale(qmc.LatinHypercube(d=lo.size, seed=0).random(n_random), lo, hi + 1e-12)
    return equal, [tuple(np.minimum(x, hi).tolist()) for x in lhs]


def _with_voltages(case: Case, v: Voltages) -> Case | None:
    """The case at voltages ``v``, V; None where the case rejects them (e.g. a too large preload)."""
    try:
        return case.with_voltages(v)
    except InputError:
        return None


def _onset_of(case: Case, speeds: np.ndarray) -> tuple[float, bool]:
    """Linear onset speed of ``case``, rad/s, and whether it is stable over the whole scan.

    NaN when the stability analysis finds no equilibrium on the scan. This is the
    one place the onset objective touches the physics (tests replace it).
    """
    from foilbearing.analysis.stability import onset_speed

    try:
        res = onset_speed(case, list(speeds))
    except (InputError, SolverError):
        return math.nan, False
    if res.onset_speed is None:
        return float(speeds[-1]), True
    return float(res.onset_speed), False


def maximize_onset(
    case: Case,
    *,
    bounds: Sequence[tuple[float, float]] | None = None,
    speeds: Sequence[float] | None = None,
    method: str = "Nelder-Mead",
    max_evaluations: int = 60,
    n_random: int = 8,
    progress: Callable[[str], None] | None = None,
) -> VoltageOptimum:
    """Actuator voltages that maximise the linear onset speed of instability.

    The onset (:func:`foilbearing.analysis.stability.onset_speed`, refined by Brent's
    method) is continuous in the voltages but only piecewise smooth: it kinks
    where the least stable mode changes. Each evaluation costs about 0.5 s, so
    the search is derivative-free and frugal: the paper's equal voltages and
    ``n_random`` Latin-hypercube points (seeded: the result is reproducible)
    are evaluated, then a bounded Nelder-Mead (or Powell) runs from the best of
    them. Nelder-Mead is the default: with three variables it moves with one or
    two evaluations per step, where Powell spends ten or more on each line
    search; finite-difference gradients would be spoiled by the kinks, and
    ``differential_evolution`` needs hundreds of evaluations. Every evaluation
    is cached and their number is capped at ``max_evaluations``.

    Parameters
    ----------
    case
        Bearing case with ``[actuators]``.
    bounds
        ``(low, high)`` per actuator, V (default ``(0, max_voltage)`` each).
    speeds
        Increasing scan speeds of the onset search, rad/s (default 5-150 krpm in
        5 krpm steps). A point stable over the whole scan counts as an onset at
        the top speed (``stable_over_scan`` in the result says so).
    method
        ``"Nelder-Mead"`` or ``"Powell"`` (scipy, with bounds).
    max_evaluations
        Hard cap on the onset analyses run.
    n_random
        Latin-hypercube starts besides the equal voltages.
    progress
        Called with one line per evaluation.

    Returns
    -------
    VoltageOptimum with ``value`` the onset speed, rad/s.
    """
    lo, hi = voltage_box(case, bounds, method, max_evaluations)
    default = [r * RPM for r in range(5_000, 150_001, 5_000)]
    scan = np.asarray(sorted(default if speeds is None else speeds), dtype=float)
    if scan.size < 2 or not scan[0] > 0.0 or not np.all(np.isfinite(scan)):
        raise InputError(f"speeds: {scan.size} given; the onset scan needs two or more, > 0 rad/s")
    stable: dict[Voltages, bool] = {}

    def evaluate(v: Voltages) -> tuple[float, float]:
        c = _with_voltages(case, v)
        onset, stable[v] = (math.nan, False) if c is None else _onset_of(c, scan)
        return onset, -onset / (1000.0 * RPM)  # minimise −onset in krpm

    cache = EvaluationCache(
        evaluate, lo, hi, max_evaluations, progress, lambda x: f"{x / RPM:.0f} rpm"
    )
    equal, extra = start_points(lo, hi, n_random)
    converged, message = local_search(cache, equal + extra, method, xatol=0.5, fatol=1e-3)
    return _optimum("onset", cache, equal, converged, message, stable=stable)


def minimize_drag(
    case: Case,
    speed: float,
    *,
    load: float | None = None,
    bounds: Sequence[tuple[float, float]] | None = None,
    min_film_fraction: float = 0.05,
    method: str = "Nelder-Mead",
    max_evaluations: int = 120,
    n_random: int = 8,
    progress: Callable[[str], None] | None = None,
) -> VoltageOptimum:
    """Actuator voltages that minimise the drag torque at one speed and load.

    Constraints: the static equilibrium converges and the minimum film is at
    least ``min_film_fraction`` of the clearance C. A violated film constraint
    is penalised in proportion to the violation (so the search is led back to
    the feasible set); a point without equilibrium gets a large constant. The
    search is the one of :func:`maximize_onset` (equal voltages and a Latin
    hypercube, then bounded Nelder-Mead): an evaluation costs ~10-25 ms, but the
    penalty makes the merit non-smooth at the constraint, where SLSQP with
    finite differences would stall. Only feasible points can be the optimum.

    Parameters
    ----------
    case
        Bearing case with ``[actuators]``.
    speed
        Rotor speed, rad/s (> 0).
    load
        Static load along +X, N (default ``case.operation.load``).
    bounds
        ``(low, high)`` per actuator, V (default ``(0, max_voltage)`` each).
    min_film_fraction
        Least allowed minimum film, in units of C.
    method, max_evaluations, n_random, progress
        As in :func:`maximize_onset`.

    Returns
    -------
    VoltageOptimum with ``value`` the drag torque, N·m, and ``min_film``, m.
    """
    from foilbearing.analysis.equilibrium import solve_equilibrium
    from foilbearing.film import film_model

    lo, hi = voltage_box(case, bounds, method, max_evaluations)
    if not (math.isfinite(speed) and speed > 0.0):
        raise InputError(f"speed = {speed!r} rad/s: expected a finite speed > 0")
    if load is not None:
        if not (math.isfinite(load) and load >= 0.0):
            raise InputError(f"load = {load!r} N: expected a finite load >= 0")
        case = replace(case, operation=replace(case.operation, load=float(load)))
    if not 0.0 <= min_film_fraction < 1.0:
        raise InputError(f"min_film_fraction = {min_film_fraction!r}: allowed 0 to < 1 (of C)")
    h_req = min_film_fraction * case.bearing.clearance
    films: dict[Voltages, float] = {}

    def evaluate(v: Voltages) -> tuple[float, float]:
        c = _with_voltages(case, v)
        try:
            st = None if c is None else solve_equilibrium(c, speed=speed, model=film_model(c))
        except SolverError:
            st = None
        if st is None or not st.converged:
            return math.nan, FAILED_MERIT
        films[v] = st.min_film
        deficit = max(0.0, (h_req - st.min_film) / case.bearing.clearance)
        merit = st.drag_torque * 1e3 * (1.0 + 100.0 * deficit) + 10.0 * deficit  # mN·m
        return (st.drag_torque if deficit == 0.0 else math.nan), merit

    cache = EvaluationCache(
        evaluate, lo, hi, max_evaluations, progress, lambda x: f"{x * 1e3:.5f} mN·m"
    )
    equal, extra = start_points(lo, hi, n_random)
    converged, message = local_search(cache, equal + extra, method, xatol=0.5, fatol=1e-5)
    return _optimum("drag", cache, equal, converged, message, speed=speed, films=films)


def _optimum(
    objective: Literal["onset", "drag"],
    cache: EvaluationCache,
    equal: Sequence[Voltages],
    converged: bool,
    message: str,
    *,
    stable: dict[Voltages, bool] | None = None,
    speed: float | None = None,
    films: dict[Voltages, float] | None = None,
) -> VoltageOptimum:
    feasible = [v for v, (value, _) in cache.points.items() if math.isfinite(value)]
    if not feasible:
        raise SolverError(
            f"{objective}: none of the {len(cache.points)} voltage sets evaluated has a result "
            "(no equilibrium, or the film constraint violated): relax the constraint or the load"
        )
    # the best equal choice with a result; NaN value if none has one
    base = [cache.key(e) for e in equal]
    best, baseline = cache.best(feasible), cache.best([v for v in base if v in feasible] or base)
    stable_flag = bool(stable and stable.get(best, False))
    if stable_flag:
        message += "; stable over the whole scan: the onset is at least the scan's top speed"
    return VoltageOptimum(
        objective=objective,
        voltages=best,
        value=cache.points[best][0],
        baseline_voltages=baseline,
        baseline_value=cache.points[baseline][0],
        evaluations=len(cache.points),
        history=tuple((v, value) for v, (value, _) in cache.points.items()),
        converged=converged,
        message=message,
        speed=speed,
        min_film=None if films is None else films.get(best),
        stable_over_scan=stable_flag,
    )
