"""Kill rate of `make mutation`: mutmut's results, less the mutants shown equivalent.

Reads ``mutants/mutmut-cicd-stats.json`` (``mutmut export-cicd-stats``) and the
survivors (``mutmut results``), subtracts the equivalent mutants listed with their
reasons in ``tests/mutation_equivalent.toml``, prints the kill rate over the
non-equivalent mutants and every survivor nobody has explained, and exits 1 when
the rate is below the target (90 %, issue 18).

Run from the repository root after ``mutmut run``.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

TARGET = 0.90


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
    known = tomllib.loads(Path("tests/mutation_equivalent.toml").read_text(encoding="utf-8"))
    equivalent = {name for name in survivors if name in known.get("equivalent", {})}
    unexplained = [name for name in survivors if name not in equivalent]
    total = int(stats["total"]) - len(equivalent) - int(stats.get("skipped", 0))
    killed = int(stats["killed"]) + int(stats.get("timeout", 0))
    rate = killed / total if total else float("nan")
    print(
        f"mutants: {stats['total']}, killed {stats['killed']} (+{stats.get('timeout', 0)} by "
        f"timeout), survived {stats['survived']} ({len(equivalent)} shown equivalent), no tests "
        f"{stats.get('no_tests', 0)}"
    )
    print(
        f"kill rate over the non-equivalent mutants: {100 * rate:.1f} % (target {100 * TARGET:.0f} %)"
    )
    for name in unexplained:
        print(f"  survived, not explained: {name}  (mutmut show {name})")
    return 0 if rate >= TARGET else 1


if __name__ == "__main__":
    raise SystemExit(main())
