"""The README and the getting-started page print what the code prints.

Both open with the same first result on `examples/bump_foil_bearing.toml`: a Python
snippet with its output, and command lines (``$ foilbearing ...``) with theirs. Each is run
here and its output compared line by line with the page's: the words exactly, each number
to one unit in its last printed digit (a different machine's round-off may flip a
last digit; nothing else may change).
"""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = ("README.md", "docs/getting-started.md")
NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def _blocks(text: str) -> list[tuple[str, str]]:
    """The page's fenced blocks: (language, body)."""
    return re.findall(r"^```(\w*)\n(.*?)^```$", text, re.S | re.M)


def _snippet(page: str) -> tuple[str, str]:
    """The first Python block of ``page`` and the plain block after it (its output)."""
    blocks = _blocks((ROOT / page).read_text(encoding="utf-8"))
    i = next(i for i, (lang, _) in enumerate(blocks) if lang == "python")
    return blocks[i][1], blocks[i + 1][1]


def _commands(page: str) -> list[tuple[str, str]]:
    """Each ``$ foilbearing ...`` line of ``page``'s first block that has them, with the
    lines printed after it."""
    for _, body in _blocks((ROOT / page).read_text(encoding="utf-8")):
        if body.startswith("$ foilbearing"):
            parts = re.split(r"^\$ ", body, flags=re.M)[1:]
            return [(p.split("\n", 1)[0], p.split("\n", 1)[1]) for p in parts]
    raise AssertionError(f"{page} shows no command line")


@cache
def _run(argv: tuple[str, ...]) -> str:
    proc = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout


def _same(shown: str, printed: str) -> None:
    """``printed`` is ``shown``: the same words, each number within a unit of its last
    shown digit."""
    lines, got = shown.rstrip("\n").splitlines(), printed.rstrip("\n").splitlines()
    assert len(got) == len(lines), printed
    for want, line in zip(lines, got, strict=True):
        assert NUMBER.sub("#", line.rstrip()) == NUMBER.sub("#", want.rstrip()), line
        for a, b in zip(NUMBER.findall(want), NUMBER.findall(line), strict=True):
            mantissa = a.lower().split("e")[0]
            unit = 10.0 ** -len(mantissa.partition(".")[2])
            scale = 10.0 ** int(a.lower().split("e")[1]) if "e" in a.lower() else 1.0
            assert abs(float(a) - float(b)) <= 1.01 * unit * scale, (want, line)


@pytest.mark.parametrize("page", PAGES)
def test_the_python_snippet_prints_what_the_page_shows(page: str) -> None:
    code, shown = _snippet(page)
    assert "examples/bump_foil_bearing.toml" in code
    _same(shown, _run((sys.executable, "-c", code)))


@pytest.mark.parametrize("page", PAGES)
def test_the_command_lines_print_what_the_page_shows(page: str) -> None:
    commands = _commands(page)
    assert len(commands) >= 2
    for line, shown in commands:
        argv = shlex.split(line)
        assert argv[0] == "foilbearing"
        _same(shown, _run((sys.executable, "-m", "foilbearing", *argv[1:])))
