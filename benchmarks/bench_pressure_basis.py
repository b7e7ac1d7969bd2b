"""How small a pressure basis would the orbit's film need? A measurement for issue 49's
route "a smaller film where it is enough (a reduced pressure basis)". Prints its figures.

Run: .venv/bin/python benchmarks/bench_pressure_basis.py [--duration S] [--speed-up]

The orbit's film is 96 × 4 pressure cells at axial order 4 (384 of the 484 unknowns of a
step). A Galerkin or least-squares reduced model would solve for the coefficients of k
basis vectors instead. The most a basis of k vectors can do is the proper orthogonal
decomposition of the pressures the orbit visits: this script records the pressure field at
every accepted step of the two orbits of ``bench_orbit_steps.py --steps`` (the smooth
C-GFB, 0 V, 1 g·mm at 30 krpm and the large shimmed GFB, 150 V, 8.5 g·mm at 50 krpm), after
a settling interval, and prints, for k basis vectors (the leading right singular vectors of
the snapshots about their mean):

- the relative error of the pressures projected onto them (Frobenius, of P − mean);
- the largest error of the film force so projected, relative to the force's
  peak-to-peak over the orbit (the readout the journal sees).

``--speed-up``: the same for the protocol's 0 V, 1 g·mm speed-up (the default case, 3 krpm
at 500 rad/s² to 50 krpm, just before its divergence; every 10th step recorded), with two
bases: the speed-up's own (in-sample) and one built from 0.02 s at each of 10, 20, 30, 40
and 50 krpm at constant speed (out of sample: what a basis built before the run gives).

It is an optimistic bound on a reduced model: the projection of the film the full model
computed, not a film a reduced model would compute itself; such a model would also need
the lift-off law and the residual evaluated on fewer cells (hyper-reduction) to run
faster than the full one, since today's step is its residual and its solve on all cells
(docs/development/orbit-performance.md, "The Newton iteration's own cost").
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from foilbearing.case import Case, default_case
from foilbearing.constants import RPM
from foilbearing.control import SpeedProfile, constant_speed, linear_ramp
from foilbearing.orbit import OrbitSettings
from foilbearing.orbit.sampling import Samples
from foilbearing.orbit.stepper import State, run
from foilbearing.orbit.system import OrbitSimulation

sys.path.insert(0, str(Path(__file__).parent))
from bench_orbit_steps import _step_orbits  # the two orbits of --steps

#: Basis sizes printed.
SIZES = (2, 5, 10, 20, 40, 80)


def snapshots(
    case: Case, speed: SpeedProfile, duration: float, start: float, stride: int = 1
) -> tuple[np.ndarray, np.ndarray, int]:
    """The pressures P − 1 (steps × cells) at every ``stride``-th accepted step from
    ``start`` s to ``duration`` s, the force weights (2 × cells) and the cells' count."""
    sim = OrbitSimulation(case, speed, None, OrbitSettings())
    n = sim.system.n
    kept: list[np.ndarray] = []
    count = [0]

    def on_step(t: float, y: np.ndarray, order: int) -> None:
        count[0] += 1
        if t >= start and count[0] % stride == 0:
            kept.append(np.array(y[:n], float) - 1.0)

    s = sim.settings
    result = run(
        replace(sim.problem(), on_step=on_step),
        State(0.0, sim.initial_state()),
        Samples(1.0 / s.sampling.sample_rate),
        s.step_rule,
        s.newton_rule,
        s.stop_rule(duration),
    )
    assert result.status in ("stopped", "completed"), result.message
    return np.asarray(kept), sim.system.w, n


def basis_errors(
    P: np.ndarray, w: np.ndarray, train: np.ndarray | None = None
) -> list[tuple[int, float, float]]:
    """(k, relative projection error of P − mean, largest force error over the force's
    peak-to-peak) for each k of :data:`SIZES`, the basis from ``train`` (default: P)."""
    train = P if train is None else train
    mean = train.mean(axis=0)
    vt = np.linalg.svd(train - mean, full_matrices=False)[2]
    X = P - mean
    force = P @ w.T  # (steps, 2), in units of p_a times the weights' area
    span = float(np.max(np.ptp(force, axis=0)))
    rows = []
    for k in SIZES:
        if k > vt.shape[0]:
            break
        V = vt[:k]
        Xk = (X @ V.T) @ V
        rel = float(np.linalg.norm(X - Xk) / np.linalg.norm(X - X.mean(axis=0)))
        fk = (Xk + mean) @ w.T
        rows.append((k, rel, float(np.max(np.abs(fk - force))) / span))
    return rows


def _print(rows: list[tuple[int, float, float]]) -> None:
    print(f"  {'k':>4}  {'P error':>10}  {'force error / peak-to-peak':>28}")
    for k, rel, f_err in rows:
        print(f"  {k:>4}  {rel:>10.2e}  {f_err:>28.2e}")


def speed_up() -> None:
    """The protocol's 0 V, 1 g·mm speed-up to 50 krpm, in-sample and out-of-sample bases."""
    base = default_case()
    case = replace(base, rotor=replace(base.rotor, imbalance=1e-6))
    t0 = time.perf_counter()
    train = [
        snapshots(case, constant_speed(krpm * 1e3 * RPM, 0.03), 0.03, 0.01)[0]
        for krpm in (10, 20, 30, 40, 50)
    ]
    ramp = linear_ramp(3e3 * RPM, 90e3 * RPM, 500.0)
    stop = (50e3 - 3e3) * RPM / 500.0
    P, w, n = snapshots(case, ramp, stop, 0.0, stride=10)
    took = time.perf_counter() - t0
    print(f"0 V, 1 g·mm speed-up to 50 krpm: {P.shape[0]} snapshots of {n} cells ({took:.0f} s)")
    print(" its own basis (in sample):")
    _print(basis_errors(P, w))
    print(" a basis from 0.02 s at each of 10-50 krpm, constant speed (out of sample):")
    _print(basis_errors(P, w, np.vstack(train)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=0.1, help="simulated s (0.1)")
    parser.add_argument("--speed-up", action="store_true", help="the protocol's speed-up")
    args = parser.parse_args()
    if args.speed_up:
        speed_up()
        return
    for label, (case, rpm) in _step_orbits().items():
        t0 = time.perf_counter()
        speed = constant_speed(rpm * RPM, args.duration)
        P, w, n = snapshots(case, speed, args.duration, args.duration / 3.0)
        took = time.perf_counter() - t0
        print(f"{label}: {P.shape[0]} snapshots of {n} pressure cells ({took:.1f} s)")
        _print(basis_errors(P, w))


if __name__ == "__main__":
    main()
