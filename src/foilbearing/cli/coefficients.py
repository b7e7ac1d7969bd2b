"""``foilbearing coefficients``: dynamic stiffness (N/m) and damping (N s/m) vs frequency.

The static equilibrium at one speed and voltage, then the force coefficients of
the film and foil at the excitation frequencies (Hz; default 20 ratios 0.1-2.0 of
the rotor speed).
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from foilbearing.cli.common import (
    add_case_arg,
    add_load_arg,
    add_overwrite_arg,
    add_subambient_arg,
    apply_subambient,
    claim_output,
    emit,
    guard_outputs,
    load_list,
    over_loads,
    positive_list,
    positive_quantity,
    refuse_without_actuators,
    voltage_list,
)
from foilbearing.cli.reading import add_reading_args, apply_reading
from foilbearing.errors import InputError, SolverError
from foilbearing.output.summary import grid_line, grid_used

__all__ = ["cmd_coefficients", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``coefficients`` subcommand to the main parser's subparsers ``sub``."""
    coef = sub.add_parser("coefficients", help="dynamic stiffness and damping vs frequency")
    add_case_arg(coef)
    coef.add_argument("--speed", default=None, help="rotor speed, e.g. 50000rpm")
    coef.add_argument("--voltage", default=None, help="actuator voltage, e.g. 150V")
    coef.add_argument("--shimmed", action="store_true", help="the shimmed GFB twin")
    coef.add_argument(
        "--frequency",
        default=None,
        help="excitation frequencies in Hz, e.g. 100,500,1000Hz "
        "(default: 20 ratios 0.1-2.0 of the rotor speed)",
    )
    add_load_arg(coef)
    add_subambient_arg(coef)
    add_reading_args(coef)
    coef.add_argument("--out", type=Path, help="write the coefficients to FILE.nc")
    add_overwrite_arg(coef)
    coef.add_argument("--plot", metavar="DIR", type=Path, help="write the figure (PNG) to DIR")
    coef.add_argument("--json", action="store_true", help="print one JSON object")
    coef.set_defaults(func=cmd_coefficients)
    return coef


@guard_outputs
def cmd_coefficients(args: argparse.Namespace) -> int:
    """Run ``coefficients``; returns the exit code (0).

    Raises
    ------
    SolverError
        The static equilibrium did not converge.
    """
    import numpy as np

    from foilbearing.analysis.coefficients import force_coefficients
    from foilbearing.analysis.equilibrium import solve_equilibrium
    from foilbearing.case import load_case
    from foilbearing.io import save_figure

    loads = load_list(args.load)
    if loads is not None and len(loads) > 1:
        return over_loads(cmd_coefficients, args, loads)
    case = apply_reading(apply_subambient(load_case(args.case), args.subambient), args)
    if loads is not None:
        case = case.with_load(loads[0])
    if args.speed is not None:
        if len(positive_list(args.speed, "speed", "--speed", "a speed")) > 1:
            raise InputError(
                f"--speed {args.speed!r}: coefficients takes one speed (against speed: a sweep "
                "file with analysis = 'coefficients', or study)"
            )
        case = case.with_speed(positive_quantity(args.speed, "speed", "--speed", "a speed"))
    if args.voltage is not None:
        refuse_without_actuators(case, "--voltage", args.voltage)
        (volt,) = voltage_list(args.voltage, case)
        case = case.with_voltages(volt)
    if args.shimmed:
        case = case.shimmed()
    if args.frequency is None:
        freqs = np.linspace(0.1, 2.0, 20) * case.operation.speed
    else:
        given = positive_list(args.frequency, "frequency", "--frequency", "a frequency")
        freqs = 2 * np.pi * np.array(given)
    target = claim_output(args, args.out)
    static = solve_equilibrium(case)
    if not static.converged:
        raise SolverError(static.message)
    fc = force_coefficients(static, freqs)
    out = fc.headline() | grid_used(case)
    if target is not None:
        target.write(lambda tmp: fc.to_dataset().to_netcdf(tmp))
    if args.plot is not None:
        from foilbearing.output.plots.dynamics import plot_coefficients

        out["figures"] = [str(save_figure(plot_coefficients(fc), args.plot / "coefficients.png"))]
    if args.json:
        emit(out)
    else:
        print(
            f"  speed {out['speed_rpm']:.0f} rpm, load {out['load_N']:g} N, "
            f"eccentricity {out['eccentricity']:.4f}"
        )
        print(
            "  f (Hz)      K_XX      K_XY      K_YX      K_YY (MN/m)"
            "     C_XX      C_XY      C_YX      C_YY (kN s/m)"
        )
        for f, k, c in zip(out["frequency_Hz"], fc.K, fc.C, strict=True):
            ks = " ".join(f"{x / 1e6:9.4f}" for x in k.ravel())
            cs = " ".join(f"{x / 1e3:9.4f}" for x in c.ravel())
            print(f"  {f:7.1f} {ks}   {cs}")
        print(f"  {grid_line(case)}")
    return 0
