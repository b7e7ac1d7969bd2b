"""One pool of speed-ups for the whole study: a run starts as soon as a core is free.

The study's speed-ups come in stages whose runs depend on one another: a protocol's
controlled runs are planned from its 0 V run (:mod:`foilbearing.study.orbits`), the
schedule's from the schedule (:mod:`foilbearing.study.schedule`). Run stage by stage,
each stage waits for its slowest run and a core idles while a 0 V run decides what comes
next. The queue takes every stage's runs at once instead:

- a run is handed to a worker process as soon as one is free, the runs that others wait
  for (``priority`` 0) before the rest, and in the order they came within a priority;
- when a run finishes, the callbacks of whoever asked for it run in this process (they
  write its figures, and may ask for the runs it decides), while the workers go on;
- a run asked for twice (the same label in the same folder: the schedule's 0 V run is the
  protocol's 1 g·mm one) is run once, and each asker sees it under its own series.

A run that fails stops the queue: the runs under way are finished and kept (each writes
its NetCDF as it ends), those not started are dropped, and the error is raised.

Its workers, and those of the study's other pool of independent solves, are forked from a
clean server process (:func:`worker_pool`), not from the study's own.
"""

from __future__ import annotations

import heapq
import multiprocessing
import os
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from foilbearing.case import Case
from foilbearing.study.runs import run_one

__all__ = ["OrbitQueue", "worker_pool"]

Done = Callable[[dict[str, Any]], None]

#: What the pools' server process imports once, so that each worker forked from it has it.
_PRELOAD = ("foilbearing.study.runs", "foilbearing.study.converged", "foilbearing.check")


def worker_pool(workers: int) -> ProcessPoolExecutor:
    """A pool of ``workers`` processes for the study's independent runs.

    The workers are forked from a server process (``forkserver``) that started clean and
    imported the study's runs once, not from the study's process: that one has threads by
    then (BLAS's, the Dask client's), and a child forked from a process with threads can
    inherit a lock another thread held and hang (Python warns of it, and makes forkserver
    its default from 3.14). It costs no more: four short orbits on two workers took 1.11 s
    forked from either (1.50 s from fresh interpreters, spawn). Where the platform has no
    forkserver, the default start method.
    """
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return ProcessPoolExecutor(max_workers=workers)
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(list(_PRELOAD))
    return ProcessPoolExecutor(max_workers=workers, mp_context=context)


@dataclass
class _Task:
    case: Case
    run: Any  # foilbearing.study.runs.OrbitRun
    out: Path
    stop_time: float | None
    priority: int
    #: (the run as its asker planned it, the asker's callback)
    askers: list[tuple[Any, Done]] = field(default_factory=list)


class OrbitQueue:
    """Speed-ups of :func:`foilbearing.study.runs.run_one` on ``workers`` processes."""

    def __init__(self, workers: int | None = None) -> None:
        self.workers = workers or (os.cpu_count() or 1)
        self._pool: ProcessPoolExecutor | None = None
        self._ready: list[tuple[int, int, str]] = []  # heap of (priority, order, label)
        self._tasks: dict[str, _Task] = {}  # asked for, not finished
        self._done: dict[str, dict[str, Any]] = {}  # finished, by label
        self._running: dict[Future[dict[str, Any]], str] = {}
        self._order = 0

    def submit(
        self,
        case: Case,
        run: Any,
        out: Path,
        then: Done,
        *,
        priority: int = 1,
        stop_time: float | None = None,
    ) -> bool:
        """Ask for the speed-up ``run`` of ``case``; ``then(result)`` is called when it ends.

        ``result`` is what :func:`~foilbearing.study.runs.run_one` returns, its headline's
        ``series`` and ``description`` those of this ``run``. Returns False when the run
        was already asked for (it is not run again).
        """
        label = run.label
        if label in self._done:
            then(_seen_as(self._done[label], run))
            return False
        if label in self._tasks:
            task = self._tasks[label]
            if task.out != out or task.stop_time != stop_time:
                raise ValueError(f"orbit {label} asked for twice with different outputs")
            task.askers.append((run, then))
            if priority < task.priority and label not in self._running.values():
                task.priority = priority  # the entry of its old priority is skipped
                self._push(priority, label)
                self._dispatch()
            return False
        self._tasks[label] = _Task(case, run, out, stop_time, priority, [(run, then)])
        self._push(priority, label)
        self._dispatch()
        return True

    def _push(self, priority: int, label: str) -> None:
        heapq.heappush(self._ready, (priority, self._order, label))
        self._order += 1

    def drain(self) -> None:
        """Run until every run asked for, and every run their callbacks ask for, has ended."""
        try:
            while self._running:
                finished, _ = wait(self._running, return_when=FIRST_COMPLETED)
                ended = []
                for fut in finished:
                    label = self._running.pop(fut)
                    ended.append((label, fut.result()))
                self._dispatch()  # the freed workers go on while the callbacks write figures
                for label, result in ended:
                    task = self._tasks.pop(label)
                    self._done[label] = result
                    for run, then in task.askers:
                        then(_seen_as(result, run))
        except BaseException:
            self._ready.clear()
            if self._pool is not None:
                self._pool.shutdown(wait=True, cancel_futures=True)
                self._pool = None
            raise
        if self._pool is not None:
            self._pool.shutdown()
            self._pool = None

    def _dispatch(self) -> None:
        while self._ready and len(self._running) < self.workers:
            if self._pool is None:
                self._pool = worker_pool(self.workers)
            priority, _, label = heapq.heappop(self._ready)
            task = self._tasks.get(label)
            if task is None or task.priority != priority or label in self._running.values():
                continue  # an entry left by a raised priority
            fut = self._pool.submit(run_one, task.case, task.run, task.out, task.stop_time)
            self._running[fut] = label


def _seen_as(result: dict[str, Any], run: Any) -> dict[str, Any]:
    """``result`` with the headline's series and description of the asker's ``run``."""
    head = result["headline"]
    if head["series"] == run.series and head["description"] == run.describe():
        return result
    return result | {"headline": head | {"series": run.series, "description": run.describe()}}
