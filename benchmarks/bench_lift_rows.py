"""Prototype: does a rank-k (Woodbury) correction of the factor for the lift-off cells that
switched branch pay? Prints its figures; not used by the package.

Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_lift_rows.py   (about 1.5 minutes)

Under top-foil lift-off the modified Newton iteration keeps its factor when up to
``MAX_MOVED_KEPT`` cells change branch, although the factor's rows for those cells are
those of the old branch. Here the compiled loop ``transient_newton_solve`` is replaced by
a Python copy (monkeypatched ``TransientFactor.newton_solve``) that calls the compiled
pieces (``transient_newton_step``, or ``transient_residual``/``transient_solve``/
``newton_update``) and, when k <= K_MAX cells are on another branch than the factor was
built with, solves with the corrected matrix ``J' = J + E (R_new − R_old)`` by the
Woodbury identity on the factor's own solve. R are the cells' rows of the full Newton
matrix at factorisation: ``d e_k`` (held) or the Reynolds row of
``TransientSystem.jacobian`` at the factor's (y, inputs, c0) with lift-off off (free).

Variants, on two 0.05 s runs (shimmed GFB at 150 V and 50 krpm; 0 V default case at
20 krpm; both 8.5 g·mm):

- ``compiled``: the package as it is (the reference for the counts and e_X);
- ``copy``: the Python copy of the current rule (must reproduce ``compiled`` exactly);
- ``wbK``: Woodbury-corrected solves while up to K cells are off their factorised
  branch (more: the factor as it is); a switch of more than 8 cells still refreshes;
- ``wbK+keepK``: also keeps the factor for up to K cells flipped at once (in the loop
  and in the stepper's move of a kept factor to the predicted branches);
- ``pred``: a fresh factor at a step's start decides its branches at the predictor guess
  (``factorize(..., branches=None)``) instead of taking the extrapolated
  ``_predicted_branches``; ``pred+wb16`` both.

Cost per step = iterations × µs per compiled Newton step + factorisations × µs per
factorisation + the Woodbury overhead (one factor solve per new correction column, and
the rank-k update per corrected iteration, both timed as compiled calls). The figures are
counted (iterations, factorisations: deterministic) and the per-call times measured here.
|Δe_X| is the largest difference of the sampled e_X from the compiled run's, and from a
run with 30-100x tighter Newton tolerances (the scale of the Newton error), in units of
the compiled run's peak-to-peak e_X. Columns: ``wb ms`` the Woodbury overhead per step,
``cols`` correction columns solved per step, ``corr its`` corrected iterations per step,
``>K`` iterations with more than K cells off their branch (solved uncorrected).
"""

from __future__ import annotations

import collections
import math
import re
import time

import numpy as np
import scipy.sparse as sp
from numba import njit

from foilbearing.case import default_case
from foilbearing.control import constant_speed
from foilbearing.orbit import OrbitSettings, simulate
from foilbearing.orbit import stepper as stp
from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds._kernels import newton as nw
from foilbearing.reynolds._kernels.bdf import transient_residual, transient_solve
from foilbearing.reynolds._kernels.blockcyclic import block_cyclic_solve
from foilbearing.reynolds.transient import TransientSystem
from foilbearing.reynolds.transient_factor import TransientFactor

RPM = math.pi / 30.0
CONVERGED, CLOSED, NOT_FINITE, TOO_SLOW, DIVERGED, REFRESH = 0, 1, 2, 3, 4, 5


@njit(cache=True)
def woodbury_apply(dy, v, z, c_inv):  # type: ignore[no-untyped-def]
    """dy −= Z C⁻¹ V dy (V: k × m rows, Z: m × k columns J⁻¹ e_j, C = I + V Z)."""
    k, m = v.shape
    t = np.zeros(k)
    for a in range(k):
        acc = 0.0
        for r in range(m):
            acc += v[a, r] * dy[r]
        t[a] = acc
    s = c_inv @ t
    for r in range(m):
        acc = 0.0
        for a in range(k):
            acc += z[r, a] * s[a]
        dy[r] -= acc


@njit(cache=True)
def repeat_solve(g, factor, model, pattern, work, out, reps):  # type: ignore[no-untyped-def]
    """``reps`` factor solves inside compiled code (no dispatch per call)."""
    for _ in range(reps):
        transient_solve(g, factor, model, pattern, work, out)


@njit(cache=True)
def repeat_step(y, y0, step, model, pattern, factor, buf, weights, reps):  # type: ignore[no-untyped-def]
    """``reps`` Newton steps from y0 inside compiled code (y reset each time)."""
    for _ in range(reps):
        y[:] = y0
        nw.transient_newton_step(y, step, model, pattern, factor, buf, weights)


@njit(cache=True)
def repeat_apply(dy, v, z, c_inv, reps):  # type: ignore[no-untyped-def]
    """``reps`` rank-k updates inside compiled code."""
    for _ in range(reps):
        woodbury_apply(dy, v, z, c_inv)


class Config:
    """The variant in use (module state read by the patched methods)."""

    correct = False  # Woodbury-correct the rows of cells off their factorised branch
    k_max = 8  # most such cells corrected (more: solve with the factor as it is)
    keep = nw.MAX_MOVED_KEPT  # most cells flipped at once that keep the factor
    predictor = False  # fresh step factors decide their branches at the guess


class Stats:
    """Counters and timers of one run."""

    def __init__(self) -> None:
        self.why: collections.Counter[str] = collections.Counter()
        self.step_t = self.step_n = 0.0
        self.fac_t = self.fac_n = 0.0
        self.cols = 0  # correction columns solved (J⁻¹ e_k)
        self.rank_sum = 0  # Σ k over corrected iterations
        self.corrected_its = 0
        self.over_k = 0  # iterations with more than k_max cells off their branch
        self.jac_checks: list[float] = []


ST = Stats()
_factorize = TransientSystem.factorize


def factorize(self, y, inputs, c0, hist, branches=None):  # type: ignore[no-untyped-def]
    """TransientSystem.factorize, timed, keeping what the factor was built from."""
    if Config.predictor and branches is not None and np.all(np.abs(branches) == 1.0):
        branches = None  # _predicted_branches (±1), not a refresh (±d): decide at the guess
    t = time.perf_counter()
    f = _factorize(self, y, inputs, c0, hist, branches)
    ST.fac_t += time.perf_counter() - t
    ST.fac_n += 1
    f._built = (y.copy(), inputs, c0, hist.copy(), f.lift_state > 0.0)
    f._rows = None  # the free (Reynolds) rows at factorisation, sparse CSR
    f._cols: dict[int, np.ndarray] = {}
    return f


def free_rows(f: TransientFactor) -> sp.csr_matrix:
    """The Newton matrix at factorisation with every cell on the free branch (CSR)."""
    if f._rows is None:
        s = f.sys
        y, inputs, c0, hist, _held = f._built
        s.lift_off = False
        try:
            f._rows = sp.csr_matrix(s.jacobian(y, inputs, c0, hist))
        finally:
            s.lift_off = True
    return f._rows


def factor_matrix(f: TransientFactor) -> sp.csr_matrix:
    """The factor's own Newton matrix J: held rows d e_k on its factorised branches."""
    held = np.zeros(f.sys.size)
    d = np.zeros(f.sys.size)
    held[: f.sys.n] = f._built[4]
    d[: f.sys.n] = np.abs(f.lift_state) * f._built[4]
    return sp.csr_matrix(sp.diags(1.0 - held) @ free_rows(f) + sp.diags(d))


def correction(f: TransientFactor, cells: np.ndarray):  # type: ignore[no-untyped-def]
    """V (k × m), Z (m × k) and C⁻¹ of the Woodbury solve for these cells off their branch."""
    s = f.sys
    rows = free_rows(f)[cells].toarray()
    unit = np.zeros((cells.size, s.size))
    unit[np.arange(cells.size), cells] = np.abs(f.lift_state[cells])
    held0 = f._built[4][cells]
    v = np.where(held0[:, None], rows - unit, unit - rows)  # R_new − R_old
    z = np.empty((s.size, cells.size))
    e = np.zeros(s.size)
    for a, k in enumerate(cells):
        col = f._cols.get(int(k))
        if col is None:
            e[k] = 1.0
            col = f.solve(e)  # costed by count (µs per factor solve)
            e[k] = 0.0
            f._cols[int(k)] = col
            ST.cols += 1
        z[:, a] = col
    c_inv = np.linalg.inv(np.eye(cells.size) + v @ z)
    return np.ascontiguousarray(v), np.ascontiguousarray(z), c_inv


def newton_solve(self, y, inputs, c0, hist, weights, work, controls, fresh, first_change):  # type: ignore[no-untyped-def]
    """Python copy of the compiled ``transient_newton_solve``, with the Woodbury option."""
    s = self.sys
    g, dy, q_out = work
    step = tuple(s.step_inputs(inputs, c0, hist))
    model, pattern, factor = self._groups
    buf = (s._H, s._res, g, s._slack, s._work, dy, q_out)
    film, res, _g, slack, wk, _dy, _q = buf
    newton_tol, newton_fraction, max_newton = controls
    lift_state = self.lift_state
    n = s.n
    preload = step[4]
    tag = "fresh" if fresh else "kept"

    def update_correction():  # type: ignore[no-untyped-def]
        if not Config.correct:
            return None
        cells = np.flatnonzero((lift_state > 0.0) != self._built[4])
        if cells.size == 0:
            return None
        if cells.size > Config.k_max:
            ST.over_k += 1
            return None
        return correction(self, cells)

    wb = update_correction()
    prev = np.inf
    k = since = switches = 0
    while True:
        k += 1
        since += 1
        t = time.perf_counter()
        if wb is None:
            h_min, err, p_min = kern.transient_newton_step(
                y, step, model, pattern, factor, buf, weights
            )
        else:
            h_min = transient_residual(y, step, model, lift_state, film, res, g, slack)
            if h_min > 0.0:
                transient_solve(g, factor, model, pattern, wk, dy)
                woodbury_apply(dy, *wb)
                err, p_min = nw.newton_update(y, dy, weights, n)
                ST.rank_sum += wb[0].shape[0]
                ST.corrected_its += 1
        ST.step_t += time.perf_counter() - t
        ST.step_n += 1
        if h_min <= 0.0:
            ST.why[f"{tag}: film closed"] += 1
            return CLOSED, k, first_change, np.nan
        if not np.isfinite(err) or p_min <= 0.0:
            ST.why[f"{tag}: not finite"] += 1
            return NOT_FINITE, k, first_change, np.nan
        if first_change == np.inf:
            first_change = err
        tol = max(newton_tol, newton_fraction * first_change)
        conv = err / prev if since > 1 else np.nan
        if err <= tol or (conv < 1.0 and conv / (1.0 - conv) * err <= tol):
            flipped = nw.switch_branches(lift_state, slack, weights)
            if flipped == 0:
                h_new = kern.transient_storage(y, preload, model, q_out)
                if h_new > 0.0:
                    ST.why[f"{tag}: converged after {switches} switches"] += 1
                    return CONVERGED, k, first_change, h_new
            elif switches < nw.MAX_SWITCHES and flipped <= Config.keep:
                switches += 1
                since = 0
                prev = np.inf
                wb = update_correction()
                continue
            else:
                why = "> keep" if flipped > Config.keep else "too many switches"
                ST.why[f"{tag}: refresh, {why} flipped"] += 1
                return REFRESH, k, first_change, np.nan
        if fresh:
            if since >= max_newton or conv >= 1.0:
                if switches > 0:
                    ST.why[f"{tag}: refresh, diverging after a switch"] += 1
                    return REFRESH, k, first_change, np.nan
                ST.why[f"{tag}: too slow"] += 1
                return TOO_SLOW, k, first_change, np.nan
            if conv > 0.5:
                ST.why[f"{tag}: refresh, rate > 0.5 after {switches} switches"] += 1
                return REFRESH, k, first_change, np.nan
        elif since >= max_newton or conv >= 1.0:
            ST.why[f"{tag}: diverged"] += 1
            return DIVERGED, k, first_change, np.nan
        elif conv ** (max_newton - since) / (1.0 - conv) * err > tol:
            ST.why[f"{tag}: refresh, slow"] += 1
            return REFRESH, k, first_change, np.nan
        prev = err


def check_factor_matrix(case, prof) -> float:  # type: ignore[no-untyped-def]
    """max over a few factors with held cells of |J_rebuilt · solve(g) − g| / |g|."""
    worst = [0.0]
    seen = [0]
    orig = TransientFactor.newton_solve

    def probe(self, *args):  # type: ignore[no-untyped-def]
        if seen[0] < 5 and np.any(self._built[4]):
            g = np.random.default_rng(seen[0]).standard_normal(self.sys.size)
            x = self.solve(g)
            r = factor_matrix(self) @ x - g
            worst[0] = max(worst[0], float(np.max(np.abs(r)) / np.max(np.abs(g))))
            seen[0] += 1
        return orig(self, *args)

    TransientFactor.newton_solve = probe
    simulate(case, prof)
    TransientFactor.newton_solve = orig
    return worst[0]


def run_variant(case, prof, name):  # type: ignore[no-untyped-def]
    """One run with the variant ``name``; (result, stats)."""
    global ST
    ST = Stats()
    wb = re.search(r"wb(\d+)", name)
    keep = re.search(r"keep(\d+)", name)
    Config.correct = wb is not None
    Config.k_max = int(wb.group(1)) if wb else 0
    Config.keep = int(keep.group(1)) if keep else nw.MAX_MOVED_KEPT
    Config.predictor = name.startswith("pred")
    stp.MAX_MOVED_KEPT = Config.keep
    saved = TransientFactor.newton_solve
    if name != "compiled":
        TransientFactor.newton_solve = newton_solve
    try:
        res = simulate(case, prof)
    finally:
        TransientFactor.newton_solve = saved
        stp.MAX_MOVED_KEPT = nw.MAX_MOVED_KEPT
    return res, ST


def per_call_times(case, prof, omega) -> dict[str, float]:  # type: ignore[no-untyped-def]
    """µs per compiled Newton step, factorisation, factor solve and rank-k update (k=1,8,32)."""
    _res, st = run_variant(case, prof, "copy")
    out = {"step": 1e6 * st.step_t / st.step_n, "factorize": 1e6 * st.fac_t / st.fac_n}
    # A factor solve and the rank-k update, on a factor of this run.
    holder: list[TransientFactor] = []
    orig = TransientFactor.newton_solve

    def grab(self, y, inputs, c0, hist, weights, *args):  # type: ignore[no-untyped-def]
        if not holder:
            holder.append((self, y.copy(), inputs, c0, hist.copy(), weights.copy()))
        return orig(self, y, inputs, c0, hist, weights, *args)

    TransientFactor.newton_solve = grab
    simulate(case, constant_speed(omega, 2e-3))
    TransientFactor.newton_solve = orig
    f, y0, inputs, c0, hist, weights = holder[0]
    s = f.sys
    model, pattern, factor = f._groups
    g = np.random.default_rng(0).standard_normal(s.size)
    dy = np.empty_like(g)
    reps = 500
    step = tuple(s.step_inputs(inputs, c0, hist))
    buf = (s._H, s._res, np.empty(s.size), s._slack, s._work, dy, np.empty(s.size))
    for r in (1, reps):  # compile, then time
        t = time.perf_counter()
        repeat_step(y0.copy(), y0, step, model, pattern, factor, buf, weights, r)
    out["step_kernel"] = 1e6 * (time.perf_counter() - t) / reps
    for r in (1, reps):
        t = time.perf_counter()
        repeat_solve(g, factor, model, pattern, s._work, dy, r)
    out["solve"] = 1e6 * (time.perf_counter() - t) / reps
    for k in (1, 8):  # the pressure block's solve, one column and eight at once
        w = np.random.default_rng(1).standard_normal((s.n, k))
        t = time.perf_counter()
        for _ in range(reps // 4):
            block_cyclic_solve(factor[0], w, w)
        out[f"block{k}"] = 1e6 * (time.perf_counter() - t) / (reps // 4)
    for k in (1, 8, 32):
        v, z, c = np.ones((k, s.size)), np.ones((s.size, k)) * 1e-9, np.eye(k)
        for r in (1, reps):
            t = time.perf_counter()
            repeat_apply(dy, v, z, c, r)
        out[f"apply{k}"] = 1e6 * (time.perf_counter() - t) / reps
    return out


def main() -> None:
    TransientSystem.factorize = factorize  # keeps (y, c0, branches) of each factor
    cases = [
        (
            "shimmed GFB, 150 V, 50 krpm",
            default_case().with_voltages(150.0).shimmed(),
            50e3 * RPM,
        ),
        ("default GFB, 0 V, 20 krpm", default_case(), 20e3 * RPM),
    ]
    variants = [
        "compiled",
        "copy",
        "wb8",
        "wb16",
        "wb32",
        "wb16+keep16",
        "wb32+keep32",
        "pred",
        "pred+wb16",
    ]
    for title, case, omega in cases:
        prof = constant_speed(omega, 0.05)
        simulate(case, constant_speed(omega, 5e-4))  # compile, warm up
        times = per_call_times(case, prof, omega)
        mismatch = check_factor_matrix(case, constant_speed(omega, 5e-3))
        print(f"\n{title}, 0.05 s (8.5 g·mm)")
        print(
            f"  per call: Newton step {times['step_kernel']:.0f} µs in-kernel ({times['step']:.0f} µs "
            f"called from Python), factorisation "
            f"{times['factorize']:.0f} µs, factor solve {times['solve']:.0f} µs (block solve "
            f"{times['block1']:.0f} µs, 8 columns {times['block8']:.0f} µs), rank-k update "
            f"{times['apply1']:.1f}/{times['apply8']:.1f}/{times['apply32']:.1f} µs (k=1/8/32); "
            f"rebuilt J vs factor: |J x − g|/|g| = {mismatch:.1e}"
        )
        print(
            f"  {'variant':13s} {'its/step':>8s} {'fac/step':>8s} {'ms/step':>8s} "
            f"{'wb ms':>6s} {'cols':>6s} {'corr its':>8s} {'>K':>5s} {'|Δe_X|/pp':>10s} {'vs tight':>9s}"
        )
        # The Newton error's scale: the compiled run with 30-100x tighter tolerances.
        tight = simulate(case, prof, settings=OrbitSettings(newton_tol=0.01, newton_fraction=1e-5))
        ref = None
        whys = {}
        for name in variants:
            res, st = run_variant(case, prof, name)
            n = res.steps
            its, facs = res.newton_iterations / n, res.factorizations / n
            wb_ms = 1e-3 * (
                st.cols * times["solve"]
                + (st.rank_sum - st.corrected_its) * (times["apply8"] - times["apply1"]) / 7.0
                + st.corrected_its * times["apply1"]
            )
            cost = 1e-3 * (its * times["step_kernel"] + facs * times["factorize"]) + wb_ms / n
            if ref is None:
                ref = res
                pp = float(np.ptp(ref.e_x))
            if res.time.shape == ref.time.shape and np.allclose(res.time, ref.time):
                de = float(np.max(np.abs(res.e_x - ref.e_x)))
            else:
                de = float(np.max(np.abs(np.interp(ref.time, res.time, res.e_x) - ref.e_x)))
            dt = float(np.max(np.abs(np.interp(tight.time, res.time, res.e_x) - tight.e_x)))
            print(
                f"  {name:13s} {its:8.3f} {facs:8.3f} {cost:8.3f} {wb_ms / n:6.3f} "
                f"{st.cols / n:6.2f} {st.corrected_its / n:8.2f} {st.over_k:5d} {de / pp:10.1e} {dt / pp:9.1e}"
                + (
                    f"   ({n} steps, measured {1e3 * res.wall_time / n:.2f} ms/step)"
                    if name == "compiled"
                    else ""
                )
            )
            whys[name] = st.why
        print("  fresh-factor outcomes (calls):")
        keys = sorted({k for w in whys.values() for k in w if k.startswith("fresh")})
        names = [v for v in variants if v != "compiled"]
        print("    " + " " * 44 + "".join(f"{v:>12s}" for v in names))
        for key in keys:
            print(f"    {key:44s}" + "".join(f"{whys[v][key]:12d}" for v in names))
        kept = sorted({k for w in whys.values() for k in w if k.startswith("kept")})
        for key in kept:
            print(f"    {key:44s}" + "".join(f"{whys[v][key]:12d}" for v in names))


if __name__ == "__main__":
    main()
