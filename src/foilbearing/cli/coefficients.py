"""``foilbearing coefficients``: dynamic stiffness (N/m) and damping (N s/m) vs frequency.

The static equilibrium at one speed and voltage, then the force coefficients of
the film and foil at the excitation frequencies (Hz; default 20 ratios 0.1-2.0 of
the rotor speed).
"""

from __future__ import annotations

import argparse
import math
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
    refuse_without_actuators,
    voltage_list,
)
from foilbearing.cli.reading import add_reading_args, apply_reading
from foilbearing.errors import SolverError
from foilbearing.output.summary import grid_line, grid_used

__all__ = ["cmd_coefficients", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``coefficients`` subcommand to the main parser's subparsers ``sub``."""
    coef = sub.add_parser("coefficients", help="dynamic stiffness and damping vs frequency")
    add_case_arg(coef)
    coef.add_argument(
        "--speed",
        default=None,
        help="rotor speed(s), e.g. 50000rpm; a list (10000,30000rpm) gives the coefficients "
        "at each speed, about its own equilibrium, along a 'speed' dimension",
    )
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
    speeds = (
        positive_list(args.speed, "speed", "--speed", "a speed") if args.speed is not None else []
    )
    if len(speeds) == 1:
        case = case.with_speed(speeds[0])
    if args.voltage is not None:
        refuse_without_actuators(case, "--voltage", args.voltage)
        (volt,) = voltage_list(args.voltage, case)
        case = case.with_voltages(volt)
    if args.shimmed:
        case = case.shimmed()
    given = (
        None
        if args.frequency is None
        else 2
        * np.pi
        * np.array(positive_list(args.frequency, "frequency", "--frequency", "a frequency"))
    )
    if len(speeds) > 1:
        return _over_speeds(case, speeds, given, args)
    freqs = np.linspace(0.1, 2.0, 20) * case.operation.speed if given is None else given
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
        _print_table(fc)
        print(f"  {grid_line(case)}")
    return 0


def _print_table(fc: Any) -> None:
    print(
        "  f (Hz)      K_XX      K_XY      K_YX      K_YY (MN/m)"
        "     C_XX      C_XY      C_YX      C_YY (kN s/m)"
    )
    for w, k, c in zip(fc.frequencies, fc.K, fc.C, strict=True):
        ks = " ".join(f"{x / 1e6:9.4f}" for x in k.ravel())
        cs = " ".join(f"{x / 1e3:9.4f}" for x in c.ravel())
        print(f"  {w / (2 * math.pi):7.1f} {ks}   {cs}")


def _over_speeds(case: Any, speeds: list[float], freqs: Any, args: argparse.Namespace) -> int:
    """The coefficients at each speed of a ``--speed`` list (:func:`~foilbearing.coefficients.
    coefficients_over_speeds`): one dataset along ``speed``, one JSON object per speed."""
    from foilbearing.analysis.coefficients import coefficients_over_speeds
    from foilbearing.io import save_figure

    target = claim_output(args, args.out)
    sweep = coefficients_over_speeds(case, speeds, freqs)
    if target is not None:
        target.write(lambda tmp: sweep.to_dataset().to_netcdf(tmp))
    out = sweep.headline() | grid_used(case)
    if args.plot is not None:
        out["figures"] = [str(save_figure(sweep.plot(), args.plot / "coefficients_vs_speed.png"))]
        for fc in sweep.points:
            name = f"speed_{fc.static.speed * 30 / math.pi:.0f}rpm/coefficients.png"
            out["figures"].append(str(save_figure(fc.plot(), args.plot / name)))
    if args.json:
        emit(out)
    else:
        for fc, entry in zip(sweep.points, out["speeds"], strict=True):
            print(
                f"speed {entry['speed_rpm']:.0f} rpm, load {entry['load_N']:g} N, "
                f"eccentricity {entry['eccentricity']:.4f}"
            )
            _print_table(fc)
        print(f"  {grid_line(case)}")
    return 0
