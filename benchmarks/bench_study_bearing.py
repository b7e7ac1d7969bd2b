"""Benchmark of the study of a passive gas foil bearing: the paper's bearing without
its actuators, on the default plan (5-50 krpm, the case's 8.5 g·mm imbalance).

Targets (issue 17): without orbits at most 1 minute on 2 cores, with its orbit at
most 5 minutes. Times ``foilbearing study`` end to end in a fresh process each
(imports, numba cache loading and the report included), and prints the stages'
own timings from its progress lines. Prints its figures; not a test.

Run: .venv/bin/python benchmarks/bench_study_bearing.py
"""

from __future__ import annotations

import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def _passive_case(folder: Path) -> Path:
    import tomlkit

    from foilbearing.case import default_case_path

    data = tomlkit.parse(default_case_path().read_text(encoding="utf-8"))
    del data["actuators"]
    data["title"] = "passive GFB: the paper's bearing without actuators"
    path = folder / "gfb.toml"
    path.write_text(tomlkit.dumps(data), encoding="utf-8")
    return path


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        case = _passive_case(Path(tmp))
        for label, extra, target in (
            ("without orbits", ["--orbits", "none"], 60.0),
            ("with its orbit", [], 300.0),
        ):
            out = Path(tmp) / label.replace(" ", "_")
            cmd = [sys.executable, "-m", "foilbearing", "study", str(case), "--out", str(out)]
            t0 = time.perf_counter()
            run = subprocess.run(cmd + extra, capture_output=True, text=True, check=True)
            wall = time.perf_counter() - t0
            peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
            print(f"passive GFB study {label}: {wall:.1f} s (target {target:.0f} s), "
                  f"peak memory of the largest run so far {peak:.0f} MB")  # fmt: skip
            for line in run.stdout.splitlines():
                if line.startswith("[") and "orbit: t =" not in line:
                    print("   ", line)


if __name__ == "__main__":
    main()
