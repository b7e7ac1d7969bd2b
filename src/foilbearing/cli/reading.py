"""``--preload-response`` and ``--actuator-dynamics``: the reading of the actuator in the film."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from foilbearing.case import Case

__all__ = ["add_reading_args", "apply_reading"]


def add_reading_args(p: argparse.ArgumentParser) -> None:
    """The two options of the actuator reading (docs/model.md §3.8); default: the case's."""
    p.add_argument(
        "--preload-response",
        default=None,
        metavar="local|lobe",
        help="how the stack's compression enters the film: local (a pocket under the "
        "stinger) or lobe (the whole preload lobe lowered); default: the case's "
        "[actuators] preload_response",
    )
    p.add_argument(
        "--actuator-dynamics",
        default=None,
        metavar="compliant|held",
        help="whether the stack's compliance acts during the motion (compliant: an elastic "
        "stack under open-loop voltage) or the stinger keeps its quasi-static position "
        "(held: a positioner); default: the case's [actuators] dynamics",
    )


def apply_reading(case: Case, args: argparse.Namespace) -> Case:
    """The case with the two options applied (unchanged when both are absent)."""
    response, dynamics = args.preload_response, args.actuator_dynamics
    if response is None and dynamics is None:
        return case
    return case.with_actuator_reading(response, dynamics)
