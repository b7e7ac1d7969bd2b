"""κ honest: the smoothed lift-off edge's effect at the published grid, and its order under
refinement, for the statics and for the linear onsets at the study's voltages. Prints its
tables.

Run: .venv/bin/python benchmarks/bench_lift_off_order.py [--fine-voltages 50] [--fine-readings default]

The law: each cell obeys (P − 1)·y/Λ = δ², δ = κΔθ² (``[grid] lift_off_smoothing = κ``;
docs/lift-off.md, "The smoothed edge"). κ's *effect* on a readout f is f(κ = 0.1) − f(κ = 0)
on one grid; as δ shrinks with the cell it should vanish under refinement, and its order
is p = log2(|effect on n| / |effect on 2n|). The grid's own order at κ = 0.1 is printed
beside it (three levels: p = log2(|f1 − f2| / |f2 − f3|)).

- Statics: the equilibrium eccentricity ε and minimum film h_min of the default case at
  50 V, 50 krpm on 96 × 12, 192 × 24 and 384 × 48 (order 2), κ = 0 and 0.1.
- Onsets: the linear onset of the default reading (local + compliant) and the paper's
  (lobe + held) at 0/50/100/150 V on 96 × 12 (the study's scan, 5-150 krpm every 2.5 krpm)
  and 192 × 24 (a bracket of ±15 % around the 96 × 12 onset, :func:`foilbearing.check.onset_near`),
  κ = 0 and 0.1; on 384 × 48 only at ``--fine-voltages`` for ``--fine-readings`` (86-132 s
  an onset on an idle core; "none" skips them).

About 4 minutes without the 384 × 48 onsets, 8-10 with one voltage of one reading.
The figures and what they mean: docs/lift-off.md, "The smoothing's order, measured".
"""

from __future__ import annotations

import argparse
import itertools
import math
import time
from dataclasses import replace

from foilbearing.analysis.equilibrium import solve_equilibrium
from foilbearing.case import Case, default_case
from foilbearing.check import onset_near, refined
from foilbearing.constants import RPM
from foilbearing.errors import SolverError

KAPPAS = (0.0, 0.1)
VOLTAGES = (0.0, 50.0, 100.0, 150.0)
READINGS = {"default": None, "lobe+held": ("lobe", "held")}
#: The study's onset scan (rpm): foilbearing.study.paper's stability stage.
SCAN = [s * RPM for s in range(5_000, 150_001, 2_500)]
STATIC_POINT = (50.0, 50e3)  # V, rpm


def _case(kappa: float, volts: float, reading: str, factor: int) -> Case:
    case = default_case().with_voltages(volts)
    if READINGS[reading] is not None:
        case = case.with_actuator_reading(*READINGS[reading])  # type: ignore[misc]
    case = replace(case, grid=replace(case.grid, lift_off_smoothing=kappa))
    return refined(case, factor)


def _order(a: float | None, b: float | None) -> str:
    if a is None or b is None or a == 0.0 or b == 0.0:
        return "-"
    return f"{math.log2(abs(a) / abs(b)):.2f}"


def _effect(values: dict[float, float | None]) -> float | None:
    on, off = values.get(0.1), values.get(0.0)
    return None if on is None or off is None else on - off


def _fmt(x: float | None, spec: str) -> str:
    return "failed" if x is None else format(x, spec)


def statics(factors: tuple[int, ...]) -> None:
    """ε and h_min at one point against the grid and κ."""
    volts, rpm = STATIC_POINT
    print(f"Statics, default case at {volts:g} V, {rpm / 1e3:g} krpm (order 2):")
    rows: dict[str, list[dict[float, float | None]]] = {"ε": [], "h_min (µm)": []}
    for factor in factors:
        eps: dict[float, float | None] = {}
        hmin: dict[float, float | None] = {}
        for kappa in KAPPAS:
            t0 = time.perf_counter()
            st = solve_equilibrium(_case(kappa, volts, "default", factor), speed=rpm * RPM)
            ok = st.converged
            eps[kappa] = st.eccentricity if ok else None
            hmin[kappa] = st.min_film * 1e6 if ok else None
            print(
                f"  {96 * factor} × {12 * factor}, κ = {kappa:g}: ε = {_fmt(eps[kappa], '.5f')}, "
                f"h_min = {_fmt(hmin[kappa], '.4f')} µm ({time.perf_counter() - t0:.1f} s)",
                flush=True,
            )
        rows["ε"].append(eps)
        rows["h_min (µm)"].append(hmin)
    _table(rows, factors, ".5f")


def _table(
    rows: dict[str, list[dict[float, float | None]]], factors: tuple[int, ...], spec: str
) -> None:
    grids = [f"{96 * f}×{12 * f}" for f in factors]
    print(
        f"  {'readout':<28}"
        + "".join(f"{'κ=0.1 ' + g:>18}" for g in grids)
        + "".join(f"{'effect ' + g:>26}" for g in grids)
        + "   order of the effect   grid order (κ=0.1)"
    )
    for name, levels in rows.items():
        vals = [lv.get(0.1) for lv in levels]
        effects = [_effect(lv) for lv in levels]
        rel = [
            None if e is None or v is None else 100 * e / v
            for e, v in zip(effects, vals, strict=True)
        ]
        orders = " / ".join(_order(a, b) for a, b in itertools.pairwise(effects))
        grid_order = "-"
        if len(vals) >= 3 and None not in vals[:3]:
            d12, d23 = vals[0] - vals[1], vals[1] - vals[2]  # type: ignore[operator]
            grid_order = _order(d12, d23) + ("" if d12 * d23 > 0 else " (sign change)")
        print(
            f"  {name:<28}"
            + "".join(f"{_fmt(v, spec):>18}" for v in vals)
            + "".join(
                f"{'-' if e is None else f'{e:+.4g} ({r:+.2f} %)':>26}"
                for e, r in zip(effects, rel, strict=True)
            )
            + f"   {orders:<21} {grid_order}",
            flush=True,
        )


def onsets(fine_voltages: tuple[float, ...], fine_readings: tuple[str, ...]) -> None:
    """The linear onsets against the grid and κ."""
    print("Linear onsets (krpm), order 2:")
    rows: dict[str, list[dict[float, float | None]]] = {}
    for reading in READINGS:
        for volts in VOLTAGES:
            levels: list[dict[float, float | None]] = []
            factors = (1, 2, 4) if volts in fine_voltages and reading in fine_readings else (1, 2)
            near: dict[float, float | None] = {}
            for factor in factors:
                got: dict[float, float | None] = {}
                for kappa in KAPPAS:
                    t0 = time.perf_counter()
                    try:
                        res = onset_near(
                            _case(kappa, volts, reading, factor),
                            SCAN,
                            near.get(kappa),
                            rel_tol=1e-6,
                        )
                        got[kappa] = (
                            None if res.onset_speed is None else res.onset_speed / RPM / 1e3
                        )
                    except SolverError:
                        got[kappa] = None
                    if got[kappa] is not None:
                        near[kappa] = got[kappa] * 1e3 * RPM  # type: ignore[operator]
                    print(
                        f"  {reading} {volts:g} V, {96 * factor} × {12 * factor}, κ = {kappa:g}: "
                        f"{_fmt(got[kappa], '.3f')} krpm ({time.perf_counter() - t0:.1f} s)",
                        flush=True,
                    )
                levels.append(got)
            rows[f"{reading} {volts:g} V"] = levels
    print("Linear onsets (krpm): κ = 0.1, κ's effect f(0.1) − f(0) per grid, and its order:")
    _table({k: v for k, v in rows.items() if len(v) == 2}, (1, 2), ".3f")
    fine = {k: v for k, v in rows.items() if len(v) == 3}
    if fine:
        _table(fine, (1, 2, 4), ".3f")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fine-voltages", default="50", help="voltages with 384 × 48 onsets, or none")
    ap.add_argument("--fine-readings", default="default", help="default, lobe+held or both")
    ap.add_argument("--no-statics", action="store_true")
    args = ap.parse_args()
    fine_v = (
        ()
        if args.fine_voltages == "none"
        else tuple(float(v) for v in args.fine_voltages.split(","))
    )
    readings = tuple(READINGS) if args.fine_readings == "both" else (args.fine_readings,)
    t0 = time.perf_counter()
    if not args.no_statics:
        statics((1, 2, 4))
    onsets(fine_v, readings)
    print(f"total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
