"""Benchmark of an orbit's step: what it costs, how its Newton iteration and factor refresh
behave, and where its time goes. Prints its figures.

Run: .venv/bin/python benchmarks/bench_orbit_steps.py [--steps] [--newton] [--refresh]
     [--readings] [--profile] [--floor] [--pieces] [--dump FILE] [--same A B]


- ``--steps`` (the default): the cost of a step on a smooth orbit (C-GFB, 0 V, 1 g·mm, 30 krpm: the kind
  of step most of a speed-up is made of) and on a large one (shimmed GFB, 150 V, 8.5 g·mm,
  50 krpm), 0.05 s each, best of 3, with the iterations and factorisations and e_X at the
  end (to compare two versions of the stepper: the same orbit must give the same e_X).
- ``--newton``: the modified Newton iteration of the full speed-up's orbit at 50 krpm
  (0.05 s) under lift-off and with suction retained: calls of the compiled iteration by
  fresh/kept factor and outcome, mean iterations, and the cost per step (about 10 s).

The cost model behind these figures and every route tried towards the 60 s target:
docs/development/orbit-performance.md.
- ``--refresh``: route 4 of issue 30, a fresh factor at the start of a step after a step
  that took more than T iterations (T = 0: a fresh factor every step), on three orbits of
  0.05 s and on 96 x 12 and 96 x 6: iterations and factorisations per step, the cost by
  the measured cost of each, and e_X at the end (about 3 minutes).
- ``--readings``: the orbit's cost under each reading of the actuator in the film
  (docs/model.md §3.8): the C-GFB at 150 V, 8.5 g·mm, 0.05 s at 50 krpm, ms per step,
  iterations and factorisations per step, best of 3 (about 1 minute).
- ``--profile``: where a step's time goes, per compiled kernel and in Python (cProfile of
  0.05 s of the full speed-up's orbit at 50 krpm; about 10 s).
- ``--pieces``: µs of the pieces of a step on the same two orbits (the BDF residual, the
  solve with a factor, a factorisation), each timed on the last call of 10 ms of the
  orbit (about 30 s).
- ``--dump FILE``: e_X, e_Y, the minimum film, the power loss, the sample times and the
  counts of three short runs (the two orbits of ``--steps`` for 0.05 s, 0.3 s of the
  paper's speed-up under lobe + held at 100 V) into FILE (.npz); ``--same A B`` says
  whether two such files are equal to the bit: run ``--dump`` in two checkouts to check
  that a change of the step's code left every number as it was (about 20 s).
- ``--floor``: the floor of today's step, what a compiled step loop could not remove: on
  the smooth and the large orbit of ``--steps`` (0.1 s each), the wall time a step (best of
  3) and the time inside the compiled kernels (every numba function called from Python,
  timed by a wrapper), the rest being the Python around them (about 20 s).

The cost model behind these figures and every route tried towards the 60 s target:
docs/development/orbit-performance.md.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

from foilbearing.case import Case, default_case
from foilbearing.control import constant_speed
from foilbearing.orbit import OrbitSettings, simulate

sys.path.insert(0, str(Path(__file__).parent))
from bench_orbit import (
    RPM,
)


def _step_orbits() -> dict[str, tuple[Case, float]]:
    """The smooth and the large orbit of ``--steps`` and ``--floor``: label → (case, rpm)."""
    base = default_case()
    return {
        "C-GFB, 0 V, 1 g·mm, 30 krpm (smooth)": (
            replace(base, rotor=replace(base.rotor, imbalance=1e-6)),
            30e3,
        ),
        "shimmed GFB, 150 V, 8.5 g·mm, 50 krpm (large)": (
            base.with_voltages(150.0).shimmed(),
            50e3,
        ),
    }


def _warmed_step_orbits() -> Iterator[tuple[str, Case, float]]:
    """``(label, case, rpm)`` of the orbits of ``_step_orbits``, each after a 2 ms run that
    compiles and warms up its kernels."""
    for name, (case, rpm) in _step_orbits().items():
        simulate(case, constant_speed(rpm * RPM, 2e-3), progress=False)
        yield name, case, rpm


@contextmanager
def _swapped(replacements: list[tuple[object, str, object]]) -> Iterator[None]:
    """Set each ``(module, name, value)`` while the block runs, then put the old back."""
    saved = [(module, name, getattr(module, name)) for module, name, _ in replacements]
    for module, name, value in replacements:
        setattr(module, name, value)
    try:
        yield
    finally:
        for module, name, value in saved:
            setattr(module, name, value)


def step_costs() -> None:
    """ms a step on a smooth and a large orbit, best of 3 (0.05 s each, after a warm-up)."""
    print(
        f"cost of a step, 0.05 s of each orbit, orbit grid {default_case().grid.orbit_label}, "
        "default settings, best of 3:"
    )
    for name, case, rpm in _warmed_step_orbits():
        costs = []
        for _ in range(3):
            res = simulate(case, constant_speed(rpm * RPM, 0.05))
            costs.append(1e3 * res.wall_time / res.steps)
        print(
            f"  {name}: {min(costs):.3f} ms a step (runs {', '.join(f'{c:.3f}' for c in costs)}); "
            f"{res.steps} steps, {res.newton_iterations} iterations, {res.factorizations} "
            f"factorisations; e_X at the end {res.e_x[-1]:.9e} m"
        )


def newton_statistics() -> None:
    """Calls of the compiled Newton iteration by factor age and outcome (lift-off's cost)."""
    import collections

    from foilbearing.reynolds import _kernels as kern

    calls: list[tuple[bool, int, int]] = []
    compiled = kern.transient_newton_solve

    def counted(*args):
        r = compiled(*args)
        calls.append((bool(args[8]), int(r[0]), int(r[1])))
        return r

    kern.transient_newton_solve = counted
    names = {0: "converged", 3: "too slow", 4: "diverged", 5: "refresh asked"}
    print(
        "Newton iteration: full speed-up's orbit (shimmed GFB, 150 V, 8.5 g·mm), 0.05 s at 50 krpm"
    )
    for model in ("lift-off", "retained"):
        case = default_case().with_voltages(150.0).shimmed().with_subambient(model)
        simulate(case, constant_speed(50e3 * RPM, 5e-4))  # compile, warm up
        calls.clear()
        res = simulate(case, constant_speed(50e3 * RPM, 0.05))
        print(
            f"  {model}: {1e3 * res.wall_time / res.steps:.3f} ms per step, "
            f"{res.newton_iterations / res.steps:.2f} iterations and "
            f"{res.factorizations / res.steps:.3f} factorisations per step"
        )
        groups: dict[tuple[bool, int], list[int]] = collections.defaultdict(list)
        for fresh, outcome, its in calls:
            groups[fresh, outcome].append(its)
        for (fresh, outcome), counts in sorted(groups.items()):
            print(
                f"    {'fresh' if fresh else 'kept'} factor, {names.get(outcome, outcome)}: "
                f"{len(counts)} calls, {sum(counts) / len(counts):.2f} iterations each"
            )
    kern.transient_newton_solve = compiled


def reading_costs() -> None:
    """Cost per step of one orbit under each reading of the actuator (best of 3)."""
    print("Orbit cost by reading: C-GFB, 150 V, 8.5 g·mm, 0.05 s at 50 krpm, 96 x 12")
    for response, dynamics in (
        ("local", "compliant"),
        ("local", "held"),
        ("lobe", "compliant"),
        ("lobe", "held"),
    ):
        case = default_case().with_voltages(150.0).with_actuator_reading(response, dynamics)
        simulate(case, constant_speed(50e3 * RPM, 5e-4))  # compile, warm up
        runs = [simulate(case, constant_speed(50e3 * RPM, 0.05)) for _ in range(3)]
        res = min(runs, key=lambda r: r.wall_time)
        print(
            f"  {response} + {dynamics:<9}: {1e3 * res.wall_time / res.steps:.3f} ms per step "
            f"({res.steps} steps, {res.newton_iterations / res.steps:.2f} iterations and "
            f"{res.factorizations / res.steps:.3f} factorisations per step, status {res.status})"
        )


#: Orbits of ``--refresh``: (label, case maker, speed rpm, imbalance kg·m or None: the case's).
REFRESH_RUNS = (
    (
        "shimmed GFB, 150 V, 8.5 g·mm, 50 krpm",
        lambda: default_case().with_voltages(150.0).shimmed(),
        50e3,
        None,
    ),
    ("C-GFB, 0 V, 8.5 g·mm, 10 krpm", default_case, 10e3, None),
    ("C-GFB, 0 V, 1 g·mm, 40 krpm", default_case, 40e3, 1e-6),
)


def refresh_policy() -> None:
    """A fresh factor at the start of a step after a step of more than T iterations
    (``OrbitSettings.refresh_after``)."""
    from foilbearing.case import Grid

    print(
        "route 4: a fresh factor after a step of more than T iterations (T = none: today's "
        "rule; T = 0: a fresh factor every step), 0.05 s at constant speed"
    )
    for n_z in (12, 6):
        for label, make, rpm, imbalance in REFRESH_RUNS:
            case = replace(make(), grid=Grid(96, n_z))
            if imbalance is not None:
                case = replace(case, rotor=replace(case.rotor, imbalance=imbalance))
            profile = constant_speed(rpm * RPM, 0.05)
            simulate(case, constant_speed(rpm * RPM, 5e-4))  # compile, warm up
            for threshold in (None, 6, 4, 2, 0):
                res = simulate(case, profile, settings=OrbitSettings(refresh_after=threshold))
                print(
                    f"  96 x {n_z:2d}, {label}, T = {threshold}: "
                    f"{res.newton_iterations / res.steps:.2f} iterations and "
                    f"{res.factorizations / res.steps:.3f} factorisations per step, "
                    f"{1e3 * res.wall_time / res.steps:.3f} ms per step, e_X at the end "
                    f"{res.e_x[-1] * 1e6:.4f} µm",
                    flush=True,
                )


#: The compiled kernels --profile times, and the modules that call them by name.
_PROFILED_KERNELS = (
    "transient_newton_solve",
    "block_cyclic_factor",
    "transient_jacobian",
    "transient_border",
    "bdf_setup",
)


@contextmanager
def _kernels_seen_by_cprofile() -> Iterator[None]:
    """Wrap the profiled kernels in Python functions of their own names while the block runs.

    On Python 3.13 cProfile does not see a call into a numba dispatcher: its time goes to
    the Python caller, and a breakdown by kernel reads nothing. A thin wrapper (well under
    a microsecond a call) is a Python frame cProfile records under the kernel's name."""
    import foilbearing.integrate.integrator as stepper_module
    from foilbearing.reynolds import _kernels

    def wrapped(name: str, kernel: Callable[..., object]) -> Callable[..., object]:
        def call(*args: object) -> object:
            return kernel(*args)

        call.__code__ = call.__code__.replace(co_name=name, co_qualname=name)
        return call

    with _swapped(
        [
            (module, name, wrapped(name, getattr(module, name)))
            for module in (_kernels, stepper_module)
            for name in _PROFILED_KERNELS
            if hasattr(module, name)
        ]
    ):
        yield


def step_profile() -> None:
    """Where a step's time goes: cProfile of the full speed-up's orbit at 50 krpm, per kernel."""
    import cProfile
    import pstats

    case = default_case().with_voltages(150.0).shimmed()
    simulate(case, constant_speed(50e3 * RPM, 2e-3), progress=False)  # compile, warm up
    plain = simulate(case, constant_speed(50e3 * RPM, 0.05), progress=False)
    prof = cProfile.Profile()
    with _kernels_seen_by_cprofile():
        prof.enable()
        res = simulate(case, constant_speed(50e3 * RPM, 0.05), progress=False)
        prof.disable()
    stats = pstats.Stats(prof).stats  # type: ignore[attr-defined]
    parts = {
        "transient_newton_solve": "compiled Newton iterations",
        "block_cyclic_factor": "block-cyclic LU",
        "transient_jacobian": "Newton-matrix blocks (with lift-off)",
        "transient_border": "Woodbury border",
        "bdf_setup": "BDF set-up",
    }
    total = sum(tottime for (_cc, _calls, tottime, _cum, _callers) in stats.values())
    print(
        f"profile: shimmed GFB, 150 V, 8.5 g·mm, 0.05 s at 50 krpm, default settings: "
        f"{res.steps} steps, {1e3 * plain.wall_time / plain.steps:.3f} ms per step unprofiled, "
        f"{res.newton_iterations / res.steps:.2f} iterations and "
        f"{res.factorizations / res.steps:.3f} factorisations per step"
    )
    compiled = 0.0
    for (_file, _line, name), (_cc, calls, tottime, _cum, _callers) in sorted(stats.items()):
        if name in parts:
            compiled += tottime
            print(
                f"  {parts[name]:<38} {1e3 * tottime / res.steps:.3f} ms per step "
                f"({calls / res.steps:.2f} calls)"
            )
    python = 1e3 * (total - compiled) / res.steps
    print(f"  {'Python around them':<38} {python:.3f} ms per step (cProfile's own cost included)")


@contextmanager
def _compiled_calls_timed(spent: list[float]) -> Iterator[None]:
    """While the block runs, add the wall time of every call from Python into a compiled
    (numba) function of foilbearing to ``spent[0]``, s. Calls from one compiled function
    into another are inside the first and are not seen twice."""
    import time

    from numba.core.dispatcher import Dispatcher

    clock = time.perf_counter

    def timed(kernel: Callable[..., object]) -> Callable[..., object]:
        def call(*args: object, **kwargs: object) -> object:
            start = clock()
            try:
                return kernel(*args, **kwargs)
            finally:
                spent[0] += clock() - start

        return call

    modules = [m for n, m in sys.modules.items() if n.startswith("foilbearing")]
    with _swapped(
        [
            (module, name, timed(value))
            for module in modules
            for name, value in list(vars(module).items())
            if isinstance(value, Dispatcher)
        ]
    ):
        yield


def compiled_floor() -> None:
    """The step's wall time against the time inside its compiled kernels (the floor)."""
    print(
        f"the floor of a step, 0.1 s of each orbit, orbit grid {default_case().grid.orbit_label}, "
        "default settings: ms a step (best of 3) = compiled kernels + the Python around them"
    )
    for name, case, rpm in _warmed_step_orbits():
        plain = min(
            (simulate(case, constant_speed(rpm * RPM, 0.1), progress=False) for _ in range(3)),
            key=lambda r: r.wall_time,
        )
        spent = [0.0]
        with _compiled_calls_timed(spent):
            timed = simulate(case, constant_speed(rpm * RPM, 0.1), progress=False)
        step = 1e3 * plain.wall_time / plain.steps
        compiled = 1e3 * spent[0] / timed.steps
        print(
            f"  {name}: {step:.3f} ms a step = {compiled:.3f} compiled "
            f"({100 * compiled / step:.0f} %) + {step - compiled:.3f} Python; "
            f"{plain.newton_iterations / plain.steps:.2f} iterations and "
            f"{plain.factorizations / plain.steps:.3f} factorisations a step; a compiled "
            f"step loop could take it to {compiled:.3f} ms at best ({step / compiled:.2f} times)"
        )


def piece_costs() -> None:
    """µs of each piece of a step on the orbits of ``--steps`` (:func:`_pieces`)."""
    print("the pieces of a step, µs (the orbits' grid, default settings):")
    for name, case, rpm in _warmed_step_orbits():
        r, s_, f = _pieces(case, rpm)
        print(f"  {name}: residual {r:.1f}, solve {s_:.1f}, factorisation {f:.1f}")


def _pieces(case: Case, rpm: float) -> tuple[float, float, float]:
    """The BDF residual and the solve with a factor (compiled loops of 2000 calls) and a
    whole factorisation (``TransientSystem.factorize`` from Python, 300 calls), µs, best
    of 3, each on the last Newton call and factorisation of 10 ms of the orbit."""
    import copy
    import time

    from numba import njit

    from foilbearing.reynolds import _kernels as kern
    from foilbearing.reynolds import transient, transient_factor

    @njit
    def residuals(count, y, step, model, lift_state, film, res, g, slack):  # type: ignore[no-untyped-def]
        for _ in range(count):
            kern.transient_residual(y, step, model, lift_state, film, res, g, slack)

    @njit
    def solves(count, g, factor, model, pattern, work, dy):  # type: ignore[no-untyped-def]
        for _ in range(count):
            kern.transient_solve(g, factor, model, pattern, work, dy)

    def best(call: Callable[[], object], count: int) -> float:
        spans = []
        for _ in range(3):
            t = time.perf_counter()
            call()
            spans.append((time.perf_counter() - t) / count)
        return 1e6 * min(spans)

    seen: dict[str, object] = {}
    solve, factorize = kern.transient_newton_solve, transient.TransientSystem.factorize

    def newton(*args: object) -> object:
        seen["newton"] = copy.deepcopy(args)
        return solve(*args)  # type: ignore[operator]

    def factor(self: object, *args: object) -> object:
        seen["factor"] = (self, copy.deepcopy(args))
        return factorize(self, *args)  # type: ignore[arg-type]

    with _swapped([(transient_factor.kern, "transient_newton_solve", newton),
                   (transient.TransientSystem, "factorize", factor)]):  # fmt: skip
        simulate(case, constant_speed(rpm * RPM, 0.01), progress=False)
    y, step, model, pattern, fac, buf, *_ = seen["newton"]  # type: ignore[misc]
    film, res, g, slack, work, dy, _q = buf
    residuals(1, y, step, model, fac[9], film, res, g, slack)  # compile
    solves(1, g, fac, model, pattern, work, dy)
    system, args = seen["factor"]  # type: ignore[misc]
    return (
        best(lambda: residuals(2000, y, step, model, fac[9], film, res, g, slack), 2000),
        best(lambda: solves(2000, g, fac, model, pattern, work, dy), 2000),
        best(lambda: [system.factorize(*args) for _ in range(300)], 300),
    )


def dump_runs(path: str) -> None:
    """Write the outputs of three short runs to ``path`` (.npz), to compare two checkouts."""
    import numpy as np

    from foilbearing.control import linear_ramp

    base = default_case()
    (smooth, smooth_rpm), (large, large_rpm) = _step_orbits().values()
    runs = {
        "smooth": (smooth, constant_speed(smooth_rpm * RPM, 0.05), None),
        "large": (large, constant_speed(large_rpm * RPM, 0.05), None),
        "ramp": (
            base.with_actuator_reading("lobe", "held").with_voltages(100.0),
            linear_ramp(3e3 * RPM, 90e3 * RPM, 500.0),
            0.3,
        ),
    }
    out = {}
    for key, (case, profile, stop) in runs.items():
        res = simulate(case, profile, progress=False, stop_time=stop)
        for name in ("e_x", "e_y", "min_film", "power_loss", "time"):
            out[f"{key}_{name}"] = np.asarray(getattr(res, name))
        out[f"{key}_counts"] = np.array([res.steps, res.newton_iterations, res.factorizations])
    np.savez(path, **out)
    print(f"wrote {path}: {', '.join(sorted(out))}")


def same_runs(a: str, b: str) -> None:
    """Whether two ``--dump`` files hold the same numbers, to the bit."""
    import numpy as np

    with np.load(a) as x, np.load(b) as y:
        differ = [k for k in x.files if not np.array_equal(x[k], y[k], equal_nan=True)]
        missing = sorted(set(x.files) ^ set(y.files))
    print("the same to the bit" if not differ and not missing else f"differ: {differ + missing}")


if __name__ == "__main__":
    if "--dump" in sys.argv:
        dump_runs(sys.argv[sys.argv.index("--dump") + 1])
    elif "--same" in sys.argv:
        i = sys.argv.index("--same")
        same_runs(sys.argv[i + 1], sys.argv[i + 2])
    elif "--pieces" in sys.argv:
        piece_costs()
    elif "--floor" in sys.argv:
        compiled_floor()
    elif "--profile" in sys.argv:
        step_profile()
    elif "--newton" in sys.argv:
        newton_statistics()
    elif "--refresh" in sys.argv:
        refresh_policy()
    elif "--readings" in sys.argv:
        reading_costs()
    else:
        step_costs()
