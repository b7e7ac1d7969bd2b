"""The sample design and the sensitivity estimators.

Two estimators, both from SALib, chosen by the sample budget:

``sobol``
    Variance-based first-order and total indices from the Saltelli design:
    two independent unit samples A and B (N rows, D inputs) and the D hybrids
    AB_i (A with column i from B), N (D + 2) evaluations in all. First order
    by the estimator of Saltelli et al. (2010), total by Jansen's (1999), as
    ``SALib.analyze.sobol`` computes them, with bootstrap confidence intervals.
    An input the output does not depend on gets exactly 0 for both.
``rbd_fast``
    First-order indices only, from any sample (random balance design, EASI
    ordering, bias correction of Tissot and Prieur 2012): cheaper per index,
    no total index.

Neither estimate is bounded by construction: at a small sample the Sobol'
estimator's first order can come out above 1 or below 0 (its numerator and the
variance it divides by are estimated from the same few rows), RBD-FAST's bias
correction can take a small index below 0. :func:`screen` keeps every reported
index in [0, 1]: one outside it whose 95 % half-width reaches back into [0, 1]
is clipped to the nearer end (``clipped``), one whose interval lies wholly
outside is ``not estimable`` (NaN) at that sample size; the raw estimates are
kept beside them.

The unit sample is drawn by :mod:`scipy.stats.qmc`: a scrambled Sobol'
sequence or a Latin hypercube, seeded, so a file gives the same sample on any
machine and ``--resume`` finds the same points.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
from scipy.stats import qmc

__all__ = [
    "ESTIMATORS",
    "INDEX_STATUS",
    "SAMPLERS",
    "describe_estimator",
    "indices",
    "minimum_samples",
    "screen",
    "unit_sample",
]

SAMPLERS = ("sobol", "lhs")
ESTIMATORS = ("sobol", "rbd_fast")
#: Base rows N of the Saltelli design below which the bootstrap intervals mean little.
MIN_BASE = 8
#: Harmonics M of RBD-FAST; its bias correction needs N > 2M, its half-size bootstrap N > 4M.
#: 4, not SALib's 10: on the study's quick plan (64 points, Latin hypercube) M = 4 gives
#: indices as close to the full run's as M = 10 with half the bootstrap half-width, and a
#: bias correction 2M/N of 0.125 instead of 0.31 (docs/uncertainty.md, issue 33).
RBD_HARMONICS = 4
#: What :func:`screen` says of each index.
INDEX_STATUS = ("ok", "clipped", "not estimable")
_ROUNDING = 1e-12  # an index this far outside [0, 1] is rounding, not the estimator's noise
_U_CLIP = 1e-12  # probabilities kept inside (0, 1): a normal's inverse CDF is infinite at 0 and 1


def minimum_samples(estimator: str, n_inputs: int) -> int:
    """The least number of model evaluations the estimator accepts."""
    if estimator == "sobol":
        return MIN_BASE * (n_inputs + 2)
    return 6 * RBD_HARMONICS + 4  # 28: the half-size bootstrap keeps N/2 > 2M + 2


def unit_sample(n_inputs: int, samples: int, sampler: str, estimator: str, seed: int) -> np.ndarray:
    """Points of the unit hypercube, shape (n, n_inputs), in evaluation order.

    For ``sobol`` the rows come in groups of D + 2 per base row k:
    ``A[k], AB_1[k], …, AB_D[k], B[k]`` (SALib's order without second-order
    indices), n = (samples // (D + 2)) (D + 2). Otherwise n = samples.
    """
    d = n_inputs
    if estimator == "sobol":
        n_base = samples // (d + 2)
        ab = _draw(2 * d, n_base, sampler, seed)
        a, b = ab[:, :d], ab[:, d:]
        rows = np.empty((n_base, d + 2, d))
        rows[:, 0] = a
        for i in range(d):
            rows[:, 1 + i] = a
            rows[:, 1 + i, i] = b[:, i]
        rows[:, d + 1] = b
        u = rows.reshape(n_base * (d + 2), d)
    else:
        u = _draw(d, samples, sampler, seed)
    return np.clip(u, _U_CLIP, 1.0 - _U_CLIP)


def _draw(d: int, n: int, sampler: str, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    if sampler == "lhs":
        return np.asarray(qmc.LatinHypercube(d=d, rng=rng).random(n))
    m = max(int(np.ceil(np.log2(max(n, 1)))), 0)
    return np.asarray(qmc.Sobol(d=d, scramble=True, rng=rng).random_base2(m)[:n])


def indices(
    estimator: str, names: list[str], x: np.ndarray, y: np.ndarray, seed: int
) -> dict[str, Any]:
    """Sensitivity indices of one output to each input.

    Parameters
    ----------
    estimator
        ``"sobol"`` or ``"rbd_fast"``.
    names
        The inputs, in the columns' order.
    x
        The design, shape (n, D) (any units: only ranks and groups are used).
    y
        The output at each row, NaN where it failed. With ``sobol``, a group of
        D + 2 rows with a NaN is left out whole; with ``rbd_fast``, the row.

    Returns
    -------
    dict
        ``first_order``, ``first_order_conf`` (95 % half-width, bootstrap) and,
        for ``sobol``, ``total_order`` and ``total_order_conf``, each a list
        per input; ``n_used`` the evaluations used. NaN throughout when fewer
        than the estimator's minimum remain, or the output is constant.
    """
    from SALib.analyze import rbd_fast, sobol

    d = len(names)
    problem = {"num_vars": d, "names": names, "bounds": [[0.0, 1.0]] * d}
    nan = [float("nan")] * d
    if estimator == "sobol":
        groups = y.reshape(-1, d + 2)
        keep = np.isfinite(groups).all(axis=1)
        yy = groups[keep].ravel()
        out: dict[str, Any] = {"n_used": int(yy.size)}
        if keep.sum() < MIN_BASE or np.ptp(yy) == 0.0:
            return {
                **out,
                "first_order": nan,
                "first_order_conf": nan,
                "total_order": nan,
                "total_order_conf": nan,
            }
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            si = sobol.analyze(problem, yy, calc_second_order=False, seed=seed + 1)
        return {
            **out,
            "first_order": [float(v) for v in si["S1"]],
            "first_order_conf": [float(v) for v in si["S1_conf"]],
            "total_order": [float(v) for v in si["ST"]],
            "total_order_conf": [float(v) for v in si["ST_conf"]],
        }
    keep = np.isfinite(y)
    out = {"n_used": int(keep.sum())}
    if keep.sum() < minimum_samples("rbd_fast", d) or np.ptp(y[keep]) == 0.0:
        return {**out, "first_order": nan, "first_order_conf": nan}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        si = rbd_fast.analyze(problem, x[keep], y[keep], M=RBD_HARMONICS, seed=seed + 1)
    return {
        **out,
        "first_order": [float(v) for v in si["S1"]],
        "first_order_conf": [float(v) for v in si["S1_conf"]],
    }


def screen(raw: np.ndarray, conf: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Indices as reported: every value in [0, 1], or NaN and ``not estimable``.

    Parameters
    ----------
    raw, conf
        The estimator's indices and their 95 % half-widths (any shape, NaN
        where there were too few points or the output was constant).

    Returns
    -------
    (value, conf, status)
        ``value`` is ``raw`` where it lies in [0, 1] (``ok``), clipped to the
        nearer end where it lies outside but its interval ``raw ± conf`` reaches
        into [0, 1] (``clipped``), NaN where the interval lies wholly outside or
        the estimate is NaN (``not estimable``); ``conf`` is NaN there too.
    """
    raw = np.asarray(raw, dtype=float)
    conf = np.asarray(conf, dtype=float)
    finite = np.isfinite(raw)
    # rounding (an exact 0 computed as -1e-17) is inside
    inside = finite & (raw >= -_ROUNDING) & (raw <= 1.0 + _ROUNDING)
    c = np.where(np.isfinite(conf), conf, 0.0)
    reaches = finite & ~inside & (raw + c >= 0.0) & (raw - c <= 1.0)
    value = np.where(inside | reaches, np.clip(raw, 0.0, 1.0), np.nan)
    status = np.where(inside, "ok", np.where(reaches, "clipped", "not estimable")).astype(object)
    return value, np.where(inside | reaches, conf, np.nan), status


def describe_estimator(estimator: str, n_points: int, n_inputs: int) -> str:
    """One line naming the estimator and the sample behind the indices."""
    if estimator == "sobol":
        return (
            f"Sobol' (Saltelli 2010 first order, Jansen total) from {n_points} evaluations "
            f"({n_points // (n_inputs + 2)} base rows of {n_inputs + 2})"
        )
    return f"RBD-FAST first order ({RBD_HARMONICS} harmonics) from {n_points} evaluations"
