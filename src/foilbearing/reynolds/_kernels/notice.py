"""One line on stderr when a run must compile the film kernels (a cold numba cache).

The kernels are compiled by numba on first use and cached on disk
(``__pycache__/*.nbi`` and ``*.nbc`` beside them); a later process loads them in
well under a second. The first run after an install or a change of the kernels
compiles them, about 40 s, and would look hung. numba raises its
``"numba:compile"`` event only when a function is really compiled (after the
on-disk cache had no entry for it), never when it is loaded from the cache: a
listener on that event says so once per process, at the first of our kernels,
and never when the cache is warm. It writes to stderr only, so ``--json`` keeps
its stdout clean. ``FOILBEARING_COMPILE_NOTICE=0`` silences it (the test suite
does, so that its one-line error checks do not depend on the cache).
"""

from __future__ import annotations

import os
import sys
from typing import Any

from numba.core import event

__all__ = ["COMPILE_NOTICE", "CompileNotice", "install"]

#: What a run that must compile the kernels says, once, on stderr.
COMPILE_NOTICE = "foilbearing: compiling the film kernels once (about 40 s); later runs reuse them"


class CompileNotice(event.Listener):
    """Prints :data:`COMPILE_NOTICE` at the first compilation of a foilbearing kernel."""

    def __init__(self) -> None:
        self.told = False

    def on_start(self, event: Any) -> None:
        if self.told or os.environ.get("FOILBEARING_COMPILE_NOTICE") == "0":
            return
        dispatcher = (event.data or {}).get("dispatcher")
        module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
        if module.startswith("foilbearing."):
            self.told = True
            print(COMPILE_NOTICE, file=sys.stderr, flush=True)

    def on_end(self, event: Any) -> None:
        pass


_listener: CompileNotice | None = None


def install() -> CompileNotice:
    """Install the listener once per process (later calls return the same one)."""
    global _listener
    if _listener is None:
        _listener = CompileNotice()
        event.register("numba:compile", _listener)  # for the whole process
    return _listener
