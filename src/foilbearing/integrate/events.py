"""How a run ends: its status, the user's interrupt held to a step boundary, a step collapse.

The integrator stops at the end time it is given (``COMPLETED``), at the first stop
event that fires after an accepted step (``EVENT``, with the event's index), when the
user interrupts (``INTERRUPTED``) or when the step collapses or a factorisation fails
(``FAILED``); a checkpoint taken on the way is ``RUNNING``. What each means to the problem (a contact, a run to resume) is the
caller's to say.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from enum import StrEnum

import numpy as np
from numpy.typing import NDArray

__all__ = ["Event", "Status", "StepCollapsed", "interrupt_at_step_boundary"]

#: A stop event: ``event(t, y, monitor)`` after each accepted step, True to stop there
#: (``monitor``: the problem's scalar of the accepted state, from its Newton solve).
Event = Callable[[float, NDArray[np.float64], float], bool]


class Status(StrEnum):
    """How :func:`~foilbearing.integrate.integrator.integrate` ended."""

    #: At the end time.
    COMPLETED = "completed"
    #: A stop event fired (``Solution.event`` says which).
    EVENT = "event"
    #: The user interrupted, at a step boundary.
    INTERRUPTED = "interrupted"
    #: The step collapsed or a factorisation failed (``Solution.error``).
    FAILED = "failed"
    #: The run goes on (a checkpoint's).
    RUNNING = "running"


class StepCollapsed(FloatingPointError):
    """The step was halved below its floor without a converged Newton iteration.

    Attributes
    ----------
    t
        The time of the last accepted state.
    """

    def __init__(self, t: float) -> None:
        super().__init__(f"time step collapsed at t = {t:.6f}")
        self.t = t


@contextmanager
def interrupt_at_step_boundary() -> Iterator[Callable[[], bool]]:
    """Hold Ctrl-C until the step under way is committed; yields ``interrupted()``.

    A KeyboardInterrupt raised at an arbitrary line of a step (between the shift of
    the BDF history and the update of the current time, say) leaves a checkpoint
    whose state, time and history disagree, and the resumed run then departs from
    the uninterrupted one. In the main thread with Python's default handler, SIGINT
    only sets a flag that the integrator reads before each step; elsewhere (a worker
    thread, which never receives SIGINT, or a program with its own handler)
    nothing changes.
    """
    requested = [False]
    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    ):
        yield lambda: requested[0]
        return

    def hold(signum: int, frame: object) -> None:
        requested[0] = True

    signal.signal(signal.SIGINT, hold)
    try:
        yield lambda: requested[0]
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)
