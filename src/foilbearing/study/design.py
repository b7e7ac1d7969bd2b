"""The stack-design stage of the paper's study: what the stack's stiffness buys at 150 V
(the paper's conclusion, docs/model.md §3.8), each onset of its table with its error.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.study.converged import (
    STUDY_SCAN_RPM,
    onset_errors,
    refine_onset,
    with_error,
)

__all__ = ["design_errors", "design_stage"]


def design_stage(case: Case, out: Path, stage: Any, published: Any) -> dict[str, Any]:
    """What the stack's stiffness buys at 150 V (docs/model.md §3.8): the default reading
    and the paper's (lobe + held) at K_p × 0.3, 1, 3 and 10, beside the shimmed GFB; the
    stiffness for 90 % of its onset interpolated in log K_p (``stability --design``
    refines it and scans all four readings)."""
    from foilbearing.design import stack_design
    from foilbearing.io import save_figure
    from foilbearing.output.plots.dynamics import plot_stack_design

    stage("the stack's stiffness: 150 V onset against K_p, default and paper's reading")
    design = stack_design(
        case,
        150.0,
        factors=(0.3, 1.0, 3.0, 10.0),
        readings=(("local", "compliant"), ("lobe", "held")),
        refine=False,
        progress=lambda line: stage(line),
    )
    fig = save_figure(plot_stack_design(design), out / "stack_design.png")
    head = design.headline()
    if published:  # the table's onsets with their error, as the stability stage's
        design_errors(case, head["table"], published, 150.0, [s * RPM for s in STUDY_SCAN_RPM])
    return head | {"figures": [str(fig)]}


def design_errors(
    case: Case,
    table: list[dict[str, Any]],
    published: Mapping[str, Mapping[float, Mapping[str, Any]]],
    voltage: float,
    scan: Sequence[float],
) -> None:
    """Set on each row of the stack-design table (:meth:`StackDesign.table
    <foilbearing.design.stack.StackDesign.table>` at ``voltage``) its onset's error as the
    published onsets state theirs: ``onset_error_rpm``, ``onset_text_krpm`` and
    ``onset_refined_rpm``. The shimmed GFB's row and those at K_p × 1 under the case's
    reading or the paper's take the stability stage's (``published``: kind → voltage →
    :func:`~foilbearing.study.converged.onset_table`'s errors, the same onsets); the others
    are solved at the published resolution here (:func:`refine_onset`,
    :func:`onset_errors`) on the design's bearing (:func:`stack_case`).
    """
    from foilbearing.design.stack import stack_case

    act = case.actuators
    own = None if act is None else f"{act.preload_response}+{act.dynamics}"
    for row in table:
        coarse = row.get("onset_speed_rpm")
        reading, factor = row.get("reading"), row.get("stiffness_factor")
        if coarse is None:
            continue
        kind = "shimmed" if reading is None else None
        if factor == 1.0:
            kind = {own: "C-GFB", "lobe+held": "C-GFB, lobe+held"}.get(reading)
        known = dict(published.get(kind, {}).get(voltage, {})) if kind else {}
        if "onset_text_krpm" not in known:
            if reading is None or factor is None:
                continue
            variant = stack_case(case, voltage, factor, tuple(reading.split("+")))
            known = refine_onset(variant, coarse * RPM, scan)
            if "onset_refined_rpm" not in known:
                continue
            err = onset_errors(coarse, known["onset_refined_rpm"], known["onset_same_kappa_rpm"])
            known |= {
                "onset_error_rpm": err["error"],
                "onset_text_krpm": with_error(coarse / 1e3, err["error"] / 1e3),
            }
        row |= {k: known[k] for k in ("onset_error_rpm", "onset_text_krpm", "onset_refined_rpm")}
