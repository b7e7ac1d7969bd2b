"""The orbit part of the paper's study (Figs. 13-15): speed-ups from 3 to 90 krpm.

The paper's protocol: 0 V throughout, and ramps of all actuators from 0 to
50/100/150 V between 6.0 and 6.5 s (32.6 krpm), "at the initiation of unstable
motions", just before its 0 V run diverges (~33 krpm), during the speed-up at
500 rad/s². The 0 V run goes first. A controlled run is identical to it until
its ramp starts, so if our 0 V run diverges before the paper's control time
(our viscosity, rotor mass and imbalance are assumptions, docs/model.md §1)
the protocol's controlled runs would diverge with it; they are not run and the
study says so. Two labelled variants then keep what the protocol was for:

- *control before our divergence*: the case's imbalance, the same 0.5 s ramp
  ending 0.3 s before our 0 V run's sub-synchronous onset (or, if its
  sub-synchronous motion lasts too short to count as an onset, before its
  contact);
- *1 g·mm*: the protocol as published (0 V, and the ramps at 6.0-6.5 s) with
  a lighter imbalance; if our 0 V run diverges before 6 s with it too, the
  ramps are placed as in the first variant.

The runs go on worker processes, one per core, through the study's queue
(:class:`foilbearing.study.queue.OrbitQueue`): the 0 V run first, the runs it
decides as soon as it ends; each writes its NetCDF as it finishes.

The 1 µm sub-synchronous onset of a speed-up depends on the random disturbance that seeds
the whirl: five seeds spread it by 3-9 % (issue 49). With ``seeds`` > 1 each 0 V run is
repeated with the disturbance's seeds after the case's (seed + 1, ...), and its headline
carries the onset over the seeds and their range (``subsync_onset_seeds``). The repeats
decide nothing and write no figures; each is a speed-up as long as its 0 V run. A
controlled run is run under the case's seed alone and states the largest range measured
over three seeds on the built-in case's controlled runs (:data:`SEED_SPREAD`,
:func:`seed_floor`): running them over three seeds would add about 520 s of CPU to the
stage's 650 s on the built-in case.

With ``theta_refine`` > 1 each 0 V run (the case's seed) is also run on its orbit grid with
that many times the θ cells, the axial cells, order and κ held: the direction that moves
the readouts (on the built-in case's 0 V, 1 g·mm run, twice the axial cells moved them by
0.04 % at most; θ and the refined grids: docs/development/orbit-performance.md, "The
speed-ups' readouts with their grid error"). Its headline carries the readouts on both
grids and each one's estimated error (:func:`readout_errors`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

from foilbearing.case import Case
from foilbearing.study.queue import OrbitQueue
from foilbearing.study.runs import OrbitRun, run_one

__all__ = [
    "PAPER_ORBITS",
    "READOUT_FLOOR",
    "REFINED_MARGIN_S",
    "SEED_SPREAD",
    "OrbitRun",
    "floor_errors",
    "paper_orbit_runs",
    "readout_errors",
    "refined_stop",
    "run_one",
    "seed_floor",
]

#: Final voltage of the ramp of each of the paper's runs (0: no control).
PAPER_ORBITS = (0.0, 50.0, 100.0, 150.0)
RAMP = (6.0, 6.5)  # s, the paper's
SENSITIVITY_IMBALANCE = 1e-6  # kg·m (1 g·mm)

#: The readouts a refined run checks: key, name, unit printed and the factor to it.
_READOUTS = (
    ("onset_speed_rpm", "onset", "krpm", 1e-3),
    ("whip_frequency_Hz", "whip", "Hz", 1.0),
    ("divergence_speed_rpm", "divergence", "krpm", 1e-3),
)

#: How long a refined run goes on after the coarse run's divergence, s: 4.8 krpm at the
#: protocol's 500 rad/s², five times the largest move of the 1 g·mm divergence measured
#: from 96 to 384 θ cells (1.7 %, 0.9 krpm).
REFINED_MARGIN_S = 1.0

#: The least relative error stated for a speed-up readout, beside the two-grid difference:
#: the largest move measured on the built-in case's 0 V, 1 g·mm run from 192 to 384 θ cells
#: (seeds 1 and 2, κ = 0.1), where 96 and 192 agree to 0.3 %: onset −7.9 %, whip −1.8 %,
#: divergence −1.6 %, rounded up (docs/development/orbit-performance.md, "The speed-ups'
#: readouts with their grid error"). The two-grid difference alone would understate them.
READOUT_FLOOR = {"onset_speed_rpm": 0.08, "whip_frequency_Hz": 0.02, "divergence_speed_rpm": 0.02}

#: The largest range of a controlled speed-up's readouts over three seeds of the
#: disturbance, of their mean, measured on the built-in case: its ramps to 50, 100 and 150 V
#: at 6.0-6.5 s (1 g·mm) under the case's reading and the paper's, its 150 V held from the
#: start and its 8.5 g·mm ramps at 0.08-0.58 s: onset 5.7 % (the paper's reading, 50 V),
#: whip 0.8 %, divergence 1.8 % (the case's reading, 100 V), rounded up
#: (``python benchmarks/bench_orbit_seeds.py``; docs/development/orbit-performance.md, "The
#: controlled runs over seeds"). What a controlled run, run under the case's seed alone,
#: states for the seeds it was not run under (:func:`seed_floor`).
SEED_SPREAD = {"onset_speed_rpm": 0.06, "whip_frequency_Hz": 0.01, "divergence_speed_rpm": 0.02}


def _early_ramp(zero_run: dict[str, Any]) -> tuple[float, float]:
    """A 0.5 s ramp ending 0.3 s before the 0 V run's sub-synchronous onset, or its contact."""
    onset = zero_run["analysis"].onset
    contact = zero_run["result"].contact
    end = onset.onset_time_s if onset is not None else contact["time_s"]
    return (max(end - 0.8, 0.0), max(end - 0.3, 0.0))


def paper_orbit_runs(
    case: Case,
    out: Path,
    stage: Callable[[str], None],
    *,
    workers: int | None = None,
    stop_time: float | None = None,
    results: dict[str, Any] | None = None,
    tag: str = "",
    seeds: int = 1,
    theta_refine: int = 1,
) -> dict[str, Any]:
    """Run the speed-ups (see the module docstring), write their figures and Fig. 15.

    ``results``, if given, receives each run by its label, as :func:`run_one` returns it
    (``"result"``, ``"analysis"``, ``"headline"``), with the ``"figures"`` written of it.
    ``tag`` prefixes every run's label and file names (and Fig. 15's), so that the runs of
    another reading of the case can share the folder. The runs go on ``workers`` processes
    (:class:`~foilbearing.study.queue.OrbitQueue`; :func:`queue_paper_orbits` puts them on
    a queue the caller shares with other stages). ``seeds``: the 0 V runs over that many
    seeds of the disturbance; ``theta_refine``: each 0 V run again with that many times the
    θ cells, for its readouts' error (the module docstring).
    """
    queue = OrbitQueue(workers)
    summary = queue_paper_orbits(
        queue, case, out, stage, stop_time=stop_time, results=results, tag=tag, seeds=seeds,
        theta_refine=theta_refine,
    )  # fmt: skip
    queue.drain()
    return summary()


def queue_paper_orbits(
    queue: Any,
    case: Case,
    out: Path,
    stage: Callable[[str], None],
    *,
    stop_time: float | None = None,
    results: dict[str, Any] | None = None,
    tag: str = "",
    seeds: int = 1,
    theta_refine: int = 1,
) -> Callable[[], dict[str, Any]]:
    """Put the protocol's speed-ups on ``queue``; returns the stage's summary, to call once
    the queue has drained (the arguments as :func:`paper_orbit_runs`).

    The 0 V run goes first; when it ends, the runs it decides are asked for (and, where
    the 0 V run diverges before the paper's control, the 1 g·mm 0 V run, whose own
    controlled runs follow it in turn).
    """
    from foilbearing.orbit.analysis import write_orbit_figures

    imb = case.rotor.imbalance
    done: dict[str, dict[str, Any]] = {}
    zeros: list[str] = []  # the 0 V runs, then the controlled ones: the protocol's order
    ramps: list[str] = []
    notes: list[str] = []
    repeats: dict[str, list[dict[str, Any]]] = {}  # a 0 V run's label → its other seeds
    finer: dict[str, list[dict[str, Any]]] = {}  # a 0 V run's label → it on θ cells × refine
    first_seed = None if case.disturbance is None else case.disturbance.seed
    if seeds > 1 and first_seed is None:
        stage("  seeds: the case has no [disturbance] to draw again; one run per 0 V speed-up")

    def finish(run: dict[str, Any]) -> None:
        done[run["label"]] = run
        h = run["headline"]
        stage(f"  orbit {h['description']}: {h['message']} ({h['wall_time_s']:.0f} s)")
        run["figures"] = write_orbit_figures(
            run["result"], run["analysis"], out, f"orbit_{run['label']}"
        )

    def ask(run: OrbitRun, then: Callable[[dict[str, Any]], None] = finish) -> None:
        (zeros if run.ramp is None else ramps).append(run.label)
        priority = 0 if run.ramp is None else 1  # a 0 V run decides what follows it
        if run.ramp is None and theta_refine > 1:
            then = _and_refine(run, then)
        queue.submit(case, run, out, then, priority=priority, stop_time=stop_time)
        if run.ramp is None and first_seed is not None:
            for k in range(1, seeds):
                other = replace(run, seed=first_seed + k)
                queue.submit(
                    case, other, out, repeats.setdefault(run.label, []).append, priority=2,
                    stop_time=stop_time,
                )  # fmt: skip

    def _and_refine(
        run: OrbitRun, then: Callable[[dict[str, Any]], None]
    ) -> Callable[[dict[str, Any]], None]:
        """``then``, and the run again on θ cells × ``theta_refine``, to the end of the
        coarse run's divergence window (:func:`refined_stop`)."""

        def done_then_refine(first: dict[str, Any]) -> None:
            then(first)
            queue.submit(
                case, replace(run, theta_refine=theta_refine), out,
                finer.setdefault(run.label, []).append, priority=2,
                stop_time=refined_stop(first["analysis"].divergence, stop_time),
            )  # fmt: skip

        return done_then_refine

    def after_zero(first: dict[str, Any]) -> None:
        finish(first)
        contact = first["result"].contact
        if contact is None or contact["time_s"] >= RAMP[0]:
            for v in PAPER_ORBITS[1:]:
                ask(OrbitRun(v, RAMP, imb, "paper protocol", tag=tag))
            notes.append("the paper's protocol ran as published")
            return
        note = (
            f"our 0 V run diverges at {contact['time_s']:.2f} s ({contact['speed_rpm']:.0f} "
            f"rpm), before the paper's control at {RAMP[0]}-{RAMP[1]} s: the protocol's "
            "controlled runs are identical to it until then and were not run"
        )
        notes.append(note)
        stage("  " + note)
        early = _early_ramp(first)
        for v in PAPER_ORBITS[1:]:
            ask(OrbitRun(v, early, imb, "control before our divergence", tag=tag))
        if abs(imb - SENSITIVITY_IMBALANCE) > 1e-12:
            ask(OrbitRun(0.0, None, SENSITIVITY_IMBALANCE, "1 g·mm", tag=tag), after_light)

    def after_light(light: dict[str, Any]) -> None:
        finish(light)
        c_light = light["result"].contact
        ramp = RAMP if c_light is None or c_light["time_s"] >= RAMP[0] else _early_ramp(light)
        for v in PAPER_ORBITS[1:]:
            ask(OrbitRun(v, ramp, SENSITIVITY_IMBALANCE, "1 g·mm", tag=tag))

    zero = OrbitRun(0.0, None, imb, "paper protocol", tag=tag)
    ask(zero, after_zero)

    def summary() -> dict[str, Any]:
        for label, others in repeats.items():
            done[label]["headline"]["subsync_onset_seeds"] = _over_seeds(
                first_seed, done[label], others
            )
        for label, (refined,) in finer.items():
            done[label]["headline"]["theta_refined"] = readout_errors(
                done[label]["headline"], refined["headline"], theta_refine
            )
        if theta_refine > 1:  # the runs not refined: the floor measured on those that were
            for run in done.values():
                if "theta_refined" not in run["headline"]:
                    run["headline"]["grid_floor"] = floor_errors(run["headline"])
        if first_seed is not None:  # a controlled run ran under the case's seed alone
            for label in ramps:
                done[label]["headline"]["seed_floor"] = seed_floor(done[label]["headline"])
        return _protocol_summary(out, done, [*zeros, *ramps], zero.label, notes, results, tag)

    return summary


def _over_seeds(
    first: int | None, run: dict[str, Any], others: list[dict[str, Any]]
) -> dict[str, Any]:
    """The 1 µm sub-synchronous onset of a run and of its repeats over seeds, and its range."""
    by_seed = sorted(
        [(first, run["headline"])]
        + [(o["headline"]["disturbance_seed"], o["headline"]) for o in others],
        key=lambda sh: sh[0] or 0,
    )
    onsets = [h.get("onset_speed_rpm") for _, h in by_seed]
    found = [o for o in onsets if o is not None]
    return {
        "seeds": [s for s, _ in by_seed],
        "onset_speed_rpm": onsets,
        "range_rpm": [min(found), max(found)] if found else None,
        "divergence_speed_rpm": [h.get("divergence_speed_rpm") for _, h in by_seed],
    }


def _protocol_summary(
    out: Path,
    done: dict[str, dict[str, Any]],
    planned: list[str],
    zero_label: str,
    notes: list[str],
    results: dict[str, Any] | None,
    tag: str,
) -> dict[str, Any]:
    """The protocol stage's summary and its Fig. 15, once every run has ended."""
    from foilbearing.io import save_figure
    from foilbearing.output.plots.orbit import plot_subsync

    # The protocol's order, not the order the parallel runs finished in.
    order = list(dict.fromkeys(planned))
    if results is not None:
        results.update(done)
    figures = []
    for series in dict.fromkeys(done[k]["headline"]["series"] for k in order):
        keys = [
            k
            for k in order
            if done[k]["headline"]["series"] == series or (series != "1 g·mm" and k == zero_label)
        ]
        subs = {
            done[k]["headline"]["description"]: done[k]["analysis"].subsync
            for k in keys
            if done[k]["analysis"].subsync is not None
        }
        onsets = {
            done[k]["headline"]["description"]: done[k]["analysis"].onset
            for k in keys
            if done[k]["analysis"].onset is not None
        }
        own = [k for k in keys if k != zero_label or series == "paper protocol"]
        if any(done[k]["analysis"].subsync is not None for k in own):
            # A series whose own runs are all too short for a sub-synchronous trace (contact
            # within the first second) would draw the 0 V run alone again, the same figure.
            suffix = {"paper protocol": "", "1 g·mm": "_1gmm"}.get(series, "_control")
            name = f"{tag}fig15_subsync{suffix}"
            figures.append(str(save_figure(plot_subsync(subs, onsets), out / f"{name}.png")))
    return {
        "runs": [done[k]["headline"] for k in order],
        "note": notes[0],
        "paper_control_ramp_s": list(RAMP),
        "figures": figures,
    }


def refined_stop(divergence: Any, stop_time: float | None) -> float | None:
    """Where the refined run of a speed-up stops (s): :data:`REFINED_MARGIN_S` after the
    coarse run's ``divergence`` (a :class:`foilbearing.signals.Divergence`, or None), or
    ``stop_time`` (None: the profile's end) if that comes first or the coarse run did not
    diverge. Past its divergence a whirl can circle the bearing
    at about 1.5 C with a film of a fraction of a micrometre for many seconds before it
    touches (on 384 θ cells the 0 V, 1 g·mm run did not touch in 20 minutes of CPU), and
    nothing read from that orbit is a readout of the bearing."""
    if divergence is None:
        return stop_time
    end = divergence.time_s + REFINED_MARGIN_S
    return end if stop_time is None else min(end, stop_time)


def readout_errors(coarse: dict[str, Any], fine: dict[str, Any], factor: int) -> dict[str, Any]:
    """A speed-up's readouts on its grid and on ``factor`` times the θ cells, with errors.

    Each readout's error on the case's grid is the two-grid estimate at order 1 (the
    lift-off edge crosses cells: docs/lift-off.md), |f₁ − f₂|/(factor − 1), or
    :data:`READOUT_FLOOR` of f₁ if that is larger. A readout found on one grid only (a run
    that diverged on one and not on the other) has no error: its text says so.

    Parameters
    ----------
    coarse, fine
        The two runs' headlines (:meth:`foilbearing.orbit.analysis.OrbitAnalysis.headline`).
    factor
        How many times the θ cells of ``coarse`` ``fine`` has.

    Returns
    -------
    dict
        ``grid`` (the finer grid), each readout's value on it (its key), ``errors`` (key →
        error in the key's unit, or None), ``texts`` (key → the case's value with its
        error, in krpm or Hz, :func:`~foilbearing.study.converged.with_error`) and ``text``,
        the line the report prints: e.g. "grid error from 192 θ cells: onset 48 ± 4 krpm,
        whip 63.0 ± 1.3 Hz, divergence 52.7 ± 1.1 krpm".
    """
    from foilbearing.study.converged import two_grid_readouts

    n_theta = (fine.get("grid") or ["?"])[0]

    def error(key: str, f1: float, f2: float) -> float:
        return max(abs(f1 - f2) / (factor - 1), READOUT_FLOOR[key] * abs(f1))

    out, named = two_grid_readouts(_READOUTS, coarse, fine, error, n_theta)
    out["grid"] = fine.get("grid")
    out["text"] = f"grid error from {n_theta} θ cells: " + ", ".join(named) if named else None
    return out


def seed_floor(head: dict[str, Any]) -> dict[str, Any] | None:
    """What a speed-up run under one seed of the disturbance states for the others: the
    largest range over three seeds measured on the built-in case's controlled runs
    (:data:`SEED_SPREAD`) for each readout the run has; None if it has none.

    ``spread`` (readout key → the range, a fraction of the readout), ``texts`` (readout key
    → "up to 6 %") and ``text``: "one seed of the disturbance; over three seeds, the built-in
    case's controlled runs ranged by up to: onset 6 %, divergence 2 %".
    """
    spread = {key: SEED_SPREAD[key] for key, *_ in _READOUTS if head.get(key) is not None}
    if not spread:
        return None
    texts = {key: f"up to {100 * f:.0f} %" for key, f in spread.items()}
    named = [f"{name} {100 * spread[key]:.0f} %" for key, name, *_ in _READOUTS if key in spread]
    return {
        "spread": spread,
        "texts": texts,
        "text": "one seed of the disturbance; over three seeds, the built-in case's controlled "
        "runs ranged by up to: " + ", ".join(named),
    }


def floor_errors(head: dict[str, Any]) -> dict[str, Any]:
    """A speed-up's readouts with the least error stated for any (:data:`READOUT_FLOOR`),
    for a run that was not run again on a refined grid (a controlled run of the protocol, a
    run of the voltage schedule's verification).

    The floor is the largest move measured from 192 to 384 θ cells, where 96 and 192 agreed
    to 0.3 %: on the built-in case's 0 V, 1 g·mm run (onset 7.9 %, whip 1.8 %, divergence
    1.6 %) and its 150 V ramp (docs/development/orbit-performance.md, "The speed-ups'
    readouts with their grid error"); a refined 0 V run's own two-grid difference has so
    far been below it. Returns the layout of :func:`readout_errors` without the finer
    grid's values: ``errors``, ``texts`` and ``text`` (e.g. "grid error, the floor of the
    refined runs: onset 60 ± 5 krpm, whip 117.0 ± 2.4 Hz, divergence 59.0 ± 1.2 krpm").
    """
    from foilbearing.study.converged import two_grid_readouts

    def error(key: str, f1: float, _f2: float) -> float:
        return READOUT_FLOOR[key] * abs(f1)

    both, named = two_grid_readouts(_READOUTS, head, head, error, None)
    out = {"errors": both["errors"], "texts": both["texts"], "source": "floor"}
    out["text"] = (
        "grid error, the floor of the refined runs: " + ", ".join(named) if named else None
    )
    return out
