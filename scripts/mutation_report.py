"""Kill rate of `make mutation`: mutmut's results, less the mutants shown equivalent.

Reads ``mutants/mutmut-cicd-stats.json`` (``mutmut export-cicd-stats``) and the
survivors (``mutmut results``), subtracts the equivalent mutants listed with their
reasons in ``tests/mutation_equivalent.toml``, prints the kill rate over the
non-equivalent mutants and every survivor nobody has explained, and exits 1 when
the rate is below the target (90 %, issue 18) or an entry is stale. Survivors
listed as ``[explained]`` (a change below any tolerance a readout is held to)
stay in the rate as survivors.

mutmut numbers the mutants of a function in order, so an edit to the function
renumbers them. Each listed equivalent therefore records its mutated line
(``change``); an entry whose mutant now changes another line is reported as stale
and does not count. ``--changes`` prints every survivor with its mutated line, to
write new entries from.

Run from the repository root after ``mutmut run``.
"""

from __future__ import annotations

import ast
import difflib
import json
import subprocess
import sys
import tomllib
from functools import cache
from pathlib import Path

TARGET = 0.90
MUTANTS = Path("mutants/src")


@cache
def _functions(module: str) -> dict[str, str]:
    """Source of every function (and method) in mutmut's copy of ``module``, by name."""
    path = MUTANTS / (module.replace(".", "/") + ".py")
    if not path.exists():
        path = MUTANTS / module.replace(".", "/") / "__init__.py"
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    out = {}
    # Slices of the lines read once (ast.get_source_segment splits the whole text per call:
    # minutes for a module with a thousand mutants).
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.FunctionDef) and node.end_lineno is not None:
            out[node.name] = "\n".join(lines[node.lineno - 1 : node.end_lineno])
    return out


def change(name: str) -> str:
    """The lines a mutant changes (stripped, joined by " / "), from mutmut's copy."""
    module, _, function = name.rpartition(".")
    base = function.rpartition("__mutmut_")[0]
    funcs = _functions(module)
    if function not in funcs or f"{base}__mutmut_orig" not in funcs:
        return "?"
    orig = funcs[f"{base}__mutmut_orig"].splitlines()[1:]  # the def lines differ by name
    mutant = funcs[function].splitlines()[1:]
    added = [ln[2:].strip() for ln in difflib.ndiff(orig, mutant) if ln.startswith("+ ")]
    return " / ".join(added) or "(a line removed)"


def main() -> int:
    stats = json.loads(Path("mutants/mutmut-cicd-stats.json").read_text(encoding="utf-8"))
    listed = subprocess.run(
        [str(Path(sys.executable).with_name("mutmut")), "results"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    survivors = [
        line.split(":")[0].strip()
        for line in listed.splitlines()
        if line.strip().endswith("survived")
    ]
    if "--changes" in sys.argv[1:]:
        for name in survivors:
            print(f"{name}\t{change(name)}")
        return 0
    known = tomllib.loads(Path("tests/mutation_equivalent.toml").read_text(encoding="utf-8"))
    entries = known.get("equivalent", {})
    accepted = known.get("explained", {})
    equivalent, explained, stale = set(), set(), []
    for name in survivors:
        listed_in = entries if name in entries else accepted if name in accepted else None
        if listed_in is None:
            continue
        if listed_in[name]["change"] != change(name):
            stale.append(name)
        else:
            (equivalent if listed_in is entries else explained).add(name)
    unexplained = [n for n in survivors if n not in equivalent | explained and n not in stale]
    total = int(stats["total"]) - len(equivalent) - int(stats.get("skipped", 0))
    killed = int(stats["killed"]) + int(stats.get("timeout", 0))
    rate = killed / total if total else float("nan")
    print(
        f"mutants: {stats['total']}, killed {stats['killed']} (+{stats.get('timeout', 0)} by "
        f"timeout), survived {stats['survived']} ({len(equivalent)} shown equivalent, "
        f"{len(explained)} explained and counted), no tests {stats.get('no_tests', 0)}"
    )
    print(
        f"kill rate over the non-equivalent mutants: {100 * rate:.1f} % (target {100 * TARGET:.0f} %)"
    )
    for name in stale:
        print(f"  stale entry (the mutant now changes another line): {name}: {change(name)}")
    for name in unexplained:
        print(f"  survived, not explained: {name}: {change(name)}")
    return 0 if rate >= TARGET and not stale else 1


if __name__ == "__main__":
    raise SystemExit(main())
