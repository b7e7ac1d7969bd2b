"""The quick plan's sensitivity indices against the full run's, on the same outputs.

Reads finished runs of the built-in uncertainty file (their ``points/`` folders;
nothing is computed again):

FULL
    ``foilbearing uncertainty --out FULL``: the file's own plan, 252 evaluations,
    the Sobol' estimator on 36 base rows (``foilbearing study --uncertainty full``).
QUICK
    ``foilbearing uncertainty --estimator rbd_fast --sampler lhs --samples 64 --out QUICK``
    (``foilbearing study``'s default, ``--uncertainty quick``).
--sobol-sample DIR (optional)
    the same with ``--sampler sobol`` (the file's sampler): RBD-FAST on a
    64-point scrambled Sobol' sequence.

and prints, for each estimator at the quick size, the share of its raw
first-order indices outside [0, 1], the largest and smallest, the share the
report marks not estimable, how far its indices (as reported, in [0, 1]) lie
from the full run's (mean and largest absolute difference over every output
and input the full run resolves) and how often it ranks the same input first.
The old quick plan (the Sobol' estimator on 8 base rows, 56 evaluations) is
the full run's first 56 points: its design is their prefix. RBD-FAST is read
with M = 2, 4, 6 and 10 harmonics, on the 64 points and on their first 56.
Not a test.

Run: .venv/bin/python benchmarks/compare_uncertainty_indices.py FULL QUICK [--sobol-sample DIR]
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.uncertainty.design import screen


def _y(spec: Any, folder: Path) -> tuple[np.ndarray, list[str]]:
    from foilbearing.sweep.runner import done_points
    from foilbearing.uncertainty import summarise

    ds = summarise(spec, done_points(folder))
    return np.asarray(ds["y"].values), [str(o) for o in ds["output"].values]


def _rbd(x: np.ndarray, y: np.ndarray, m: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    from SALib.analyze import rbd_fast

    d = x.shape[1]
    problem = {"num_vars": d, "names": [f"x{i}" for i in range(d)], "bounds": [[0, 1]] * d}
    s1, c1 = np.full((y.shape[1], d), np.nan), np.full((y.shape[1], d), np.nan)
    for j in range(y.shape[1]):
        keep = np.isfinite(y[:, j])
        if keep.sum() < 4 * m + 4 or np.ptp(y[keep, j]) == 0.0:
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            si = rbd_fast.analyze(problem, x[keep], y[keep, j], M=m, seed=seed + 1)
        s1[j], c1[j] = si["S1"], si["S1_conf"]
    return s1, c1


def _sobol(spec: Any, y: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    from foilbearing.uncertainty.design import indices

    names = [i.name for i in spec.inputs]
    rows = [
        indices("sobol", names, spec.design[:n], y[:n, j], spec.seed) for j in range(y.shape[1])
    ]
    s1 = np.array([r["first_order"] for r in rows])
    c1 = np.array([r["first_order_conf"] for r in rows])
    st = np.array([r["total_order"] for r in rows])
    return s1, c1, st


def _compare(label: str, s1: np.ndarray, c1: np.ndarray, ref: np.ndarray, ok: np.ndarray) -> None:
    raw = s1[ok]
    outside = np.isfinite(raw) & ((raw < 0.0) | (raw > 1.0))
    value, _, status = screen(s1, c1)
    v, r = value[ok], ref[ok]
    both = np.isfinite(v) & np.isfinite(r)
    diff = np.abs(v - r)[both]
    top_same = np.mean(
        [
            np.nanargmax(np.where(np.isfinite(a), a, -1.0)) == np.nanargmax(b)
            for a, b in zip(v, r, strict=True)
        ]
    )
    print(
        f"{label:<40} {outside.mean() * 100:5.1f} %  {np.nanmax(raw):6.2f} {np.nanmin(raw):6.2f}"
        f"  {(status[ok] == 'not estimable').mean() * 100:5.1f} %"
        f"  {diff.mean():5.3f} {diff.max():5.3f}  {top_same * 100:5.1f} %"
        f"  {np.nanmedian(c1[ok]):5.2f}"
    )


def main() -> None:
    from foilbearing.uncertainty import load_uncertainty

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("full", type=Path)
    ap.add_argument("quick", type=Path)
    ap.add_argument("--sobol-sample", type=Path, default=None)
    args = ap.parse_args()

    full = load_uncertainty()
    yf, names = _y(full, args.full)
    s1f, c1f, _ = _sobol(full, yf, full.n_points)
    # outputs the full run resolves: some input's first-order index is clear of 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # constant outputs: NaN
        ok = np.nanmax(s1f - c1f, axis=1) > 0.0
    print(
        f"full run: {full.n_points} points, {int(np.isfinite(yf).all(axis=1).sum())} with every "
        f"output; {ok.sum()} of {len(names)} outputs with a first-order index clear of 0; "
        f"its raw first order from {np.nanmin(s1f[ok]):.2f} to {np.nanmax(s1f[ok]):.2f}"
    )
    ref = screen(s1f, c1f)[0]
    print(
        f"\n{'estimator at the quick size':<40} {'raw∉[0,1]':>7} {'max':>6} {'min':>6}"
        f"  {'n.est.':>7}  {'|Δ|mean':>5} {'max':>5}  {'top same':>7}  {'±med':>5}"
    )
    s1, c1, _ = _sobol(full, yf, 56)
    _compare("Sobol', 8 base rows, 56 (old quick)", s1, c1, ref, ok)
    runs = [("LHS", args.quick, "lhs")]
    if args.sobol_sample is not None:
        runs.append(("Sobol' seq.", args.sobol_sample, "sobol"))
    for label, folder, sampler in runs:
        quick = load_uncertainty(samples=64, estimator="rbd_fast", sampler=sampler)
        yq, _ = _y(quick, folder)
        for n in (56, 64):
            for m in (2, 4, 6, 10):
                if n < 4 * m + 4:
                    continue
                s1, c1 = _rbd(quick.design[:n], yq[:n], m, quick.seed)
                _compare(f"RBD-FAST M={m}, {label} {n}", s1, c1, ref, ok)


if __name__ == "__main__":
    main()
