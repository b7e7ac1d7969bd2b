"""The options of an orbit run that the orbit and rotor commands share: the voltage
programs (``--voltage-ramp``, ``--controller``) and the run's control (``--stop-time``,
``--checkpoint-every``). Their values are parsed in :mod:`foilbearing.control.options`."""

from __future__ import annotations

import argparse

__all__ = ["add_run_control_args", "add_voltage_program_args"]


def add_voltage_program_args(
    p: argparse.ArgumentParser,
    *,
    during: str = "",
    whose: str = "all actuators",
    ramp_example: str,
    controller_example: str,
) -> None:
    """``--voltage-ramp T0:T1:V`` and ``--controller K=V,...``: the voltage programs of an
    orbit run (parsed by :mod:`foilbearing.control.options`); ``during`` prefixes the help
    (e.g. ``"during --orbit, "``), ``whose`` names what is ramped, and the examples are
    the command's own."""
    p.add_argument(
        "--voltage-ramp",
        default=None,
        metavar="T0:T1:V",
        help=f"{during}ramp {whose} from their case voltage to V between T0 and T1, "
        f"e.g. {ramp_example}",
    )
    p.add_argument(
        "--controller",
        default=None,
        metavar="K=V,...",
        help=f"{during}a closed-loop controller reading the journal: {controller_example}",
    )


def add_run_control_args(
    p: argparse.ArgumentParser, *, run: str = "the run", stop_example: str = "5s"
) -> None:
    """``--stop-time`` (simulated time) and ``--checkpoint-every`` (wall time between
    checkpoints to ``--out``, default 30 s) of an orbit run."""
    p.add_argument(
        "--stop-time", default=None, help=f"end {run} at this simulated time, e.g. {stop_example}"
    )
    p.add_argument(
        "--checkpoint-every",
        default="30s",
        metavar="TIME",
        help="wall time between checkpoints written to --out (default 30s)",
    )
