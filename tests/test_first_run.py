"""The first minute: a run that must compile the kernels says so once, on stderr only; a warm
cache says nothing; the set-up's warm-up runs."""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
from contextlib import redirect_stderr
from pathlib import Path
from types import SimpleNamespace

from numba import njit
from numba.core import event

from foilbearing.reynolds._kernels import residual
from foilbearing.reynolds._kernels.notice import COMPILE_NOTICE, CompileNotice, install


def _compile_event(dispatcher: object) -> SimpleNamespace:
    return SimpleNamespace(data={"dispatcher": dispatcher})


def test_the_notice_is_said_once_and_only_for_our_kernels(monkeypatch) -> None:
    monkeypatch.delenv("FOILBEARING_COMPILE_NOTICE", raising=False)
    notice = CompileNotice()
    err = io.StringIO()
    with redirect_stderr(err):
        notice.on_start(_compile_event(njit(lambda x: x)))  # not ours: a user's own numba
        assert err.getvalue() == ""
        notice.on_start(_compile_event(residual))
        notice.on_start(_compile_event(residual))
    assert err.getvalue() == COMPILE_NOTICE + "\n"
    monkeypatch.setenv("FOILBEARING_COMPILE_NOTICE", "0")
    quiet, err = CompileNotice(), io.StringIO()
    with redirect_stderr(err):
        quiet.on_start(_compile_event(residual))
    assert err.getvalue() == "" and not quiet.told


def test_numba_tells_the_notice_when_it_compiles_and_not_when_it_has_the_function(
    monkeypatch,
) -> None:
    """numba's own "numba:compile" event, on a function of a ``foilbearing.`` module: raised
    at the first call (compiled), not at the second (already there)."""
    monkeypatch.delenv("FOILBEARING_COMPILE_NOTICE", raising=False)
    monkeypatch.setattr(install(), "told", True)  # the process's own listener keeps quiet

    def twice(x: float) -> float:
        return 2.0 * x

    twice.__module__ = "foilbearing.probe"
    probe = njit(twice)
    notice = CompileNotice()
    err = io.StringIO()
    with event.install_listener("numba:compile", notice), redirect_stderr(err):
        assert probe(1.5) == 3.0
        assert err.getvalue() == COMPILE_NOTICE + "\n"
        notice.told = False
        assert probe(2.5) == 5.0
    assert err.getvalue() == COMPILE_NOTICE + "\n"


def test_a_run_on_a_warm_cache_says_nothing_and_json_stays_clean(write_case) -> None:
    """Two ``static --json`` processes: the first compiles whatever the cache lacks (then the
    notice is one line of its stderr), the second finds everything cached and says nothing;
    stdout is one JSON object in both. On a cold cache the first process pays the kernels'
    compilation (about 40 s) that the rest of the suite then loads from disk."""
    path = write_case("first_run", n_theta=32, n_z=4)
    env = {k: v for k, v in os.environ.items() if k != "FOILBEARING_COMPILE_NOTICE"}
    src = str(Path(__file__).resolve().parents[1] / "src")
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    argv = [sys.executable, "-m", "foilbearing", "static", str(path), "--json"]
    runs = [subprocess.run(argv, capture_output=True, text=True, env=env) for _ in range(2)]
    for run in runs:
        assert run.returncode == 0, run.stderr
        assert 0.0 < json.loads(run.stdout)["eccentricity"] < 1.0  # stdout: JSON only
    assert runs[0].stderr.count(COMPILE_NOTICE) <= 1
    assert COMPILE_NOTICE not in runs[1].stderr


def test_the_set_up_s_warm_up_runs(capsys) -> None:
    """``python -m foilbearing.warmup`` (the end of scripts/setup_venv.sh) completes: a static
    solve, coefficients, a whirl mode and two short orbits on a coarse grid, in this process
    and as its two parts in two processes at once."""
    from foilbearing.warmup import compile_kernels, main

    assert compile_kernels() > 0.0
    assert main([]) == 0
    assert "film kernels ready" in capsys.readouterr().err
