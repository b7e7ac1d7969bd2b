"""Property-based fuzz of the case files: one-field mutations of each example case.

Each example case (the built-in C-GFB, the bump foil, shimmed and rigid bearings) on a
coarse grid, with one field deleted, set to zero, negative, huge, tiny, NaN, given a
wrong unit or a wrong type, or the file's text garbled, goes through ``case show`` and
``static`` in-process (the command line's ``main``). What a user relies on: no
traceback, exit 0 (done), 2 (bad input, one line) or 3 (a solve that failed, one line),
and every exit 0 of ``static`` a converged equilibrium whose numbers are all finite and
whose film carries the load.

The examples are drawn with ``derandomize=True`` and a fixed ``max_examples``: the same
mutations on every run and every machine, in about 30 s with the kernels compiled.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import tempfile
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import tomlkit

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from foilbearing.case import default_case_path  # noqa: E402
from foilbearing.cli.main import main  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SOURCES = {
    "cgfb": default_case_path(),
    "bump_foil_bearing": EXAMPLES / "bump_foil_bearing.toml",
    "shimmed_gfb": EXAMPLES / "shimmed_gfb.toml",
    "rigid_gas_bearing": EXAMPLES / "rigid_gas_bearing.toml",
}


def _coarse(name: str) -> dict[str, Any]:
    """The example's tables on 32 x 4 (the shims on 48 x 4, two cells across each)."""
    data = tomllib.loads(SOURCES[name].read_text(encoding="utf-8"))
    data["grid"]["n_theta"] = 48 if name == "shimmed_gfb" else 32
    data["grid"]["n_z"] = 4
    return data


BASES = {name: _coarse(name) for name in SOURCES}


def _leaves(table: dict[str, Any], prefix: tuple[str, ...] = ()) -> Iterator[tuple[str, ...]]:
    for key, value in table.items():
        if isinstance(value, dict):
            yield from _leaves(value, (*prefix, key))
        else:
            yield (*prefix, key)


LEAVES = {name: sorted(_leaves(data)) for name, data in BASES.items()}
MUTATIONS = ("delete", "zero", "negative", "huge", "tiny", "nan", "wrong unit", "wrong type")
DELETE = object()


def _unit(value: str) -> str:
    """The unit of a quantity string ("100 um" -> "um"; "lift-off" -> "")."""
    number, _, rest = value.strip().partition(" ")
    try:
        float(number)
    except ValueError:
        return ""
    return rest


def _mutated(value: Any, kind: str) -> Any:
    """``value`` of a case file mutated by ``kind`` (lists item by item)."""
    if kind == "delete":
        return DELETE
    if isinstance(value, list):
        return [_mutated(v, kind) for v in value] if value else [0]
    if kind == "wrong type":
        return "text" if isinstance(value, bool) else [True]
    number = {"zero": 0.0, "negative": -1.5, "huge": 1e300, "tiny": 1e-300, "nan": math.nan}
    if kind == "wrong unit":
        return "5 kg*m/s"
    if isinstance(value, str):
        unit = _unit(value)
        x = number[kind]
        if kind == "negative":
            try:
                x = -abs(float(value.split()[0]))
            except ValueError:
                pass
        return f"{x!r} {unit}".strip()
    if isinstance(value, bool):
        return not value
    if isinstance(value, int):
        return {"zero": 0, "negative": -value, "huge": 10**12, "tiny": 1, "nan": math.nan}[kind]
    x = number[kind]
    return -abs(value) if kind == "negative" and value else x


def _set(data: dict[str, Any], path: tuple[str, ...], value: Any) -> None:
    table = data
    for key in path[:-1]:
        table = table[key]
    if value is DELETE:
        del table[path[-1]]
    else:
        table[path[-1]] = value


@st.composite
def case_texts(draw: Any) -> tuple[str, str]:
    """(what was done, the mutated file's text) of one example case."""
    name = draw(st.sampled_from(sorted(BASES)))
    text = tomlkit.dumps(BASES[name])
    if draw(st.integers(0, 9)) == 0:  # garbled TOML: cut, or junk inserted
        at = draw(st.integers(0, len(text)))
        junk = draw(st.sampled_from(["", "= [", '"\n', "[grid]\n", "x = 1\nx = 2\n", "\x00"]))
        return f"{name}: garbled at {at} with {junk!r}", text[:at] + junk
    path = draw(st.sampled_from(LEAVES[name]))
    kind = draw(st.sampled_from(MUTATIONS))
    data = json.loads(json.dumps(BASES[name]))
    _set(data, path, _mutated(_get(data, path), kind))
    return f"{name}: {'.'.join(path)} {kind}", tomlkit.dumps(data)


def _get(data: dict[str, Any], path: tuple[str, ...]) -> Any:
    for key in path:
        data = data[key]
    return data


def _run(argv: list[str]) -> tuple[int, str, str]:
    """(exit code, stdout, stderr) of the command line run in this process."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse's own usage errors
            code = int(exc.code or 0)
    return code, out.getvalue(), err.getvalue()


def _finite(x: Any) -> bool:
    if isinstance(x, dict):
        return all(_finite(v) for v in x.values())
    if isinstance(x, list):
        return all(_finite(v) for v in x)
    return not isinstance(x, float) or math.isfinite(x)


def _check(what: str, argv: list[str]) -> tuple[int, str]:
    code, out, err = _run(argv)
    assert code in (0, 2, 3), f"{what}: {argv[0]} exit {code}\n{err}"
    assert "Traceback" not in err, f"{what}: {err}"
    if code == 3 and out:  # a failed solve reported in the --json result, saying what to try
        result = json.loads(out)
        assert result["converged"] is False and "Try" in result["message"], f"{what}: {out}"
    elif code:
        assert len(err.strip().splitlines()) == 1 and out == "", f"{what}: {err}"
    return code, out


@settings(
    max_examples=300,
    derandomize=True,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
@given(case_texts())
def test_a_one_field_mutation_is_handled_cleanly(mutation: tuple[str, str]) -> None:
    what, text = mutation
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "case.toml"
        path.write_text(text, encoding="utf-8")
        code, _ = _check(what, ["case", "show", str(path), "--json"])
        if code != 0:
            return
        code, out = _check(what, ["static", str(path), "--json"])
    if code == 0:
        result = json.loads(out)
        assert result["converged"] is True, f"{what}: {result['message']}"
        assert _finite(result), f"{what}: {result}"
        assert None not in (result["eccentricity"], result["min_film_um"]), what
        load = result["load_N"]
        assert math.hypot(*result["force_N"]) == pytest.approx(load, rel=1e-6, abs=1e-9), what
