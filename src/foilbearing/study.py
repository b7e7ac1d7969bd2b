"""The paper's analysis end to end on one case: the README's main job.

Stages run in the paper's order and each writes its figures and results into
the output folder as it finishes, so an interrupted study keeps what it did.
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

from foilbearing.case import Case
from foilbearing.io import write_text

__all__ = ["run_study"]

REPO_EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "data"


def run_study(case: Case, out: Path, *, progress: bool = True) -> dict[str, Any]:
    """Run every stage available on ``case`` and write ``out/summary.json``.

    Parameters
    ----------
    case
        The bearing case (the paper's C-GFB by default on the command line).
    out
        Output folder, created if needed.
    progress
        Print a line per stage to stderr.

    Returns
    -------
    The headline numbers of every stage, unit-named keys.
    """
    from foilbearing.cli import (
        structure_summary,
        write_identification_figures,
        write_structure_figures,
    )
    from foilbearing.summary import case_summary, format_summary

    out.mkdir(parents=True, exist_ok=True)
    results: dict[str, Any] = {}
    t0 = time.perf_counter()

    def stage(name: str) -> None:
        if progress:
            print(f"[{time.perf_counter() - t0:6.1f} s] {name}", flush=True)

    stage("case")
    results["case"] = case_summary(case)
    if progress:
        print(format_summary(results["case"]))

    no_load = REPO_EXAMPLES / "stack_no_load.csv"
    stiffness = REPO_EXAMPLES / "stack_stiffness.csv"
    if case.actuators is not None and no_load.exists() and stiffness.exists():
        stage("identification of the PZT stacks from examples/data (synthetic measurements)")
        from foilbearing.identification import identify

        ident = identify(no_load, stiffness, case.actuators.contact_area)
        results["identification"] = ident.headline()
        results["identification"]["figures"] = [
            str(p) for p in write_identification_figures(ident, out)
        ]

    stage("structure: k_b, k_assy, base preloads; Figs. 7-8")
    results["structure"] = structure_summary(case, [0.0, 50.0, 100.0, 150.0])
    results["structure"]["figures"] = [str(p) for p in write_structure_figures(case, out)]

    write_text(out / "summary.json", json.dumps(results, indent=2, default=_plain))
    stage(f"done: results in {out}/")
    return results


def _plain(x: Any) -> Any:
    if hasattr(x, "tolist"):
        return x.tolist()
    return str(x)
