"""``foilbearing study``: the paper's analysis on a case (the main job).

Static, dynamic and stability results, the speed-up orbits, the uncertainty
envelopes and the voltage schedule, written with a report to the output folder.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from foilbearing.cli.common import add_case_arg, claim_output, emit, guard_outputs

__all__ = ["MAX_SEEDS", "MAX_THETA_REFINE", "cmd_study", "register"]

#: The most seeds of ``--seeds``: each adds a speed-up per 0 V run.
MAX_SEEDS = 20

#: The largest ``--theta-refine``: a 0 V run on 4 times the θ cells costs about 10 times.
MAX_THETA_REFINE = 4


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``study`` subcommand to the main parser's subparsers ``sub``."""
    study = sub.add_parser("study", help="the paper's analysis on a case (the main job)")
    add_case_arg(study)
    study.add_argument("--out", type=Path, default=Path("out"), help="output folder (default out/)")
    study.add_argument(
        "--orbits",
        choices=("full", "none"),
        default="full",
        help="run the four speed-up orbits of Figs. 13-15 (default full)",
    )
    study.add_argument(
        "--uncertainty",
        choices=("quick", "full", "none"),
        default="quick",
        help="envelopes of what the paper leaves open, on the paper's case: quick (64 "
        "evaluations, RBD-FAST first-order indices, about 1 min on 2 cores), full (252, Sobol' "
        "first-order and total indices) or none (default quick)",
    )
    study.add_argument(
        "--schedule",
        choices=("full", "none"),
        default="full",
        help="the voltage schedule for a controller (C-GFB), verified in speed-ups when "
        "--orbits full (default full)",
    )
    study.add_argument(
        "--bifurcation",
        choices=("full", "none"),
        default="full",
        help="is the whirl past the onset bounded? The Hopf type and limit-cycle branch at "
        "each voltage, the case's reading and the paper's, on Dask (paper's case; under a "
        "minute on 2 cores); a bearing without actuators: the branch at its onset, as "
        "'foilbearing bifurcation CASE' gives it (default full)",
    )
    study.add_argument(
        "--paper-reading",
        choices=("full", "none"),
        nargs="?",
        const="full",
        default="full",
        help="also run the speed-ups of Figs. 13-15 under the paper's reading of the actuator "
        "in the film (lobe + held, 1 g·mm; docs/model.md §3.8): the paper's own protocol, "
        "about a minute more on 2 cores (paper's case, with --orbits full; default full)",
    )
    study.add_argument(
        "--seeds",
        type=int,
        default=3,
        metavar="N",
        help="each 0 V speed-up over N seeds of the case's disturbance (the case's and the "
        "next N - 1), its sub-synchronous onset and divergence given as ranges over them "
        "(default 3; 1: the case's seed alone; each further seed adds a speed-up per 0 V "
        "run, about 50 s of CPU on the paper's case)",
    )
    study.add_argument(
        "--theta-refine",
        type=int,
        default=2,
        metavar="N",
        help="each 0 V speed-up of the paper's protocol (the case's seed), or a bearing's "
        "own speed-up, again on its orbit grid with N times the θ cells, so that its onset, "
        "whip and divergence carry their estimated grid error; every limit-cycle branch "
        "too, for its onset, whirl and largest stable cycle; above 1 also the static "
        "table's shown speeds, the coefficients, the voltage schedule's points and the "
        "uncertainty outputs at the centre of their inputs (or a bearing's case point and "
        "onset) on twice the cells in θ and Z (default 2; 1: none; about twice the runs' CPU)",
    )
    study.add_argument("--json", action="store_true", help="print one JSON object")
    study.set_defaults(func=cmd_study)
    return study


@guard_outputs
def cmd_study(args: argparse.Namespace) -> int:
    """Run ``study``; returns the exit code (0)."""
    from foilbearing.case import load_case
    from foilbearing.study.paper import run_study
    from foilbearing.study.rotor import is_rotor_file

    if not 1 <= args.seeds <= MAX_SEEDS:
        from foilbearing.errors import InputError

        raise InputError(f"--seeds {args.seeds}: allowed 1 to {MAX_SEEDS}")
    if not 1 <= args.theta_refine <= MAX_THETA_REFINE:
        from foilbearing.errors import InputError

        raise InputError(f"--theta-refine {args.theta_refine}: allowed 1 to {MAX_THETA_REFINE}")
    claim_output(args, args.out, may_exist=True)  # a folder of results, rewritten by a new run
    if is_rotor_file(args.case):
        from foilbearing.export.ross import _import_ross
        from foilbearing.rotor import load_rotor
        from foilbearing.study.rotor import run_rotor_study

        _import_ross("the study of a rotor")  # before any stage: the core install has no ROSS
        result = run_rotor_study(
            load_rotor(args.case), args.out, progress=not args.json, orbits=args.orbits == "full"
        )
        if args.json:
            emit(result.summary)
        return 0
    case = load_case(args.case)
    summary = run_study(
        case,
        args.out,
        progress=not args.json,
        orbits=args.orbits == "full",
        uncertainty=args.uncertainty,
        schedule=args.schedule == "full",
        paper_reading=args.paper_reading == "full",
        bifurcation=args.bifurcation == "full",
        seeds=args.seeds,
        theta_refine=args.theta_refine,
    )
    if args.json:
        emit(summary)
    return 0
