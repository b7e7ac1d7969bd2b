"""Shared fixtures (the default case file, edited, written where a test can read it) and the
suite's time budget."""

from __future__ import annotations

import os
import signal
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import tomlkit

from foilbearing.case import default_case_path

# The cold-cache notice (foilbearing.reynolds._kernels.notice) would add a line to the stderr
# of whichever test compiles first: silenced here, and in the commands the tests start, so that
# no test's outcome depends on the kernel cache; tests/test_first_run.py checks the notice.
os.environ["FOILBEARING_COMPILE_NOTICE"] = "0"


@pytest.fixture(scope="session")
def write_case(tmp_path_factory: pytest.TempPathFactory) -> Callable[..., Path]:
    """``write_case(name, n_theta=, n_z=, edit=)``: the default case file on another grid
    and with ``edit(data)`` applied to its TOML document, in a fresh folder."""

    def write(
        name: str,
        *,
        n_theta: int | None = None,
        n_z: int | None = None,
        edit: Callable[[Any], None] | None = None,
    ) -> Path:
        data = tomlkit.parse(default_case_path().read_text(encoding="utf-8"))
        if n_theta is not None:
            data["grid"]["n_theta"] = n_theta
        if n_z is not None:
            data["grid"]["n_z"] = n_z
        if edit is not None:
            edit(data)
        path = tmp_path_factory.mktemp("cases") / f"{name}.toml"
        path.write_text(tomlkit.dumps(data), encoding="utf-8")
        return path

    return write


#: What one test may take on 2 cores, s (issue 28); a test that must take longer says why in
#: its docstring. pyproject's ``timeout`` fails a test past 5 times this.
TEST_BUDGET_S = 120


@pytest.hookimpl(tryfirst=True)
def pytest_timeout_set_timer(item: pytest.Item, settings: Any) -> bool | None:
    """pytest-timeout's SIGALRM timer, failing with one line that names the test and its
    budget instead of a dump of every thread's stack."""
    if not hasattr(signal, "SIGALRM") or threading.current_thread() is not threading.main_thread():
        return None  # pytest-timeout's own thread method
    timeout = float(settings.timeout)

    def handler(signum: int, frame: Any) -> None:
        __tracebackhide__ = True
        pytest.fail(
            f"{item.nodeid} ran past the {timeout:g} s timeout, {timeout / TEST_BUDGET_S:.1f} "
            f"times the {TEST_BUDGET_S} s budget of a test on 2 cores (tests/conftest.py): "
            "run it alone with --durations=0 to see its time, and make it cheaper or say in "
            "its docstring why it must be long",
            pytrace=False,
        )

    def cancel() -> None:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, signal.SIG_DFL)

    item.cancel_timeout = cancel  # type: ignore[attr-defined]  # read by pytest-timeout
    signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    return True
