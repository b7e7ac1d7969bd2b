"""``foilbearing static``: static analysis (equilibrium, film, preloads; Figs. 9-12).

One equilibrium (or the film at a given journal position, in units of C), or a
sweep over speeds (rad/s, given e.g. in rpm) and actuator voltages (V) of the
C-GFB and/or its shimmed twin, with NetCDF output and figures.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

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
from foilbearing.errors import InputError
from foilbearing.output.summary import grid_line, grid_used

if TYPE_CHECKING:
    from foilbearing.case import Case
    from foilbearing.cli.common import Output

__all__ = ["cmd_static", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``static`` subcommand to the main parser's subparsers ``sub``."""
    stat = sub.add_parser(
        "static", help="static analysis: equilibrium, film, preloads (Figs. 9-12)"
    )
    add_case_arg(stat)
    stat.add_argument(
        "--speed", default=None, help="speed(s), e.g. 50000rpm or 10000,50000,90000rpm"
    )
    stat.add_argument(
        "--voltage", default=None, help="actuator voltage(s), e.g. 150V or 0,50,100,150V"
    )
    stat.add_argument(
        "--shimmed",
        action="store_true",
        help="the shimmed GFB with shims as thick as the base preloads",
    )
    stat.add_argument(
        "--compare",
        action="store_true",
        help="sweep both the C-GFB and the shimmed GFB (Figs. 10-12)",
    )
    stat.add_argument(
        "--eccentricity",
        default=None,
        metavar="EX,EY",
        help="film at this journal position (units of C), no equilibrium search",
    )
    add_load_arg(stat)
    add_subambient_arg(stat)
    add_reading_args(stat)
    stat.add_argument("--out", type=Path, help="write the results to FILE.nc (NetCDF)")
    add_overwrite_arg(stat)
    stat.add_argument("--plot", metavar="DIR", type=Path, help="write the figures (PNG) to DIR")
    stat.add_argument("--json", action="store_true", help="print one JSON object")
    stat.set_defaults(func=cmd_static)
    return stat


@guard_outputs
def cmd_static(args: argparse.Namespace) -> int:
    """Run ``static``; returns the exit code (0, or 3 when a solve did not converge or
    ``--out`` could not be written)."""
    from foilbearing.case import load_case

    loads = load_list(args.load)
    if loads is not None and len(loads) > 1:
        return over_loads(cmd_static, args, loads)
    case = apply_reading(apply_subambient(load_case(args.case), args.subambient), args)
    if loads is not None:
        case = case.with_load(loads[0])
    speeds = (
        positive_list(args.speed, "speed", "--speed", "a speed")
        if args.speed
        else [case.operation.speed]
    )
    volts: list[float | None] = [None]
    if args.voltage is not None:
        refuse_without_actuators(case, "--voltage", args.voltage)
        volts = list(voltage_list(args.voltage, case))
    target = claim_output(args, args.out)
    if case.actuators is None and len(speeds) > 1 and not (args.compare or args.shimmed):
        return _speed_sweep_cli(case, speeds, args, target)
    if len(speeds) > 1 or len(volts) > 1 or args.compare:
        return _static_sweep_cli(case, speeds, volts, args, target)
    if volts[0] is not None:
        case = case.with_voltages(float(volts[0]))
    if args.shimmed:
        case = case.shimmed()
    result = _static_point(case, speeds[0], args.eccentricity)
    if target is not None:
        target.write(lambda tmp: result.to_dataset().to_netcdf(tmp))
    out = result.headline() | grid_used(case)
    if args.plot is not None:
        from foilbearing.io import save_figure
        from foilbearing.output.plots.static import plot_point

        out["figures"] = [str(save_figure(plot_point(result), args.plot / "static_point.png"))]
    if args.json:
        emit(out)
    else:
        _print_static(out)
        print(f"  {grid_line(case)}")
    return 0 if result.converged else 3


def _static_point(case: Case, speed: float, eccentricity: str | None) -> Any:
    from foilbearing.analysis.equilibrium import film_at_position, solve_equilibrium

    if eccentricity is None:
        return solve_equilibrium(case, speed=speed)
    try:
        ex, ey = (float(x) for x in eccentricity.split(","))
    except ValueError:
        raise InputError(
            f"--eccentricity {eccentricity!r}: expected two numbers EX,EY in units of C"
        ) from None
    return film_at_position(case, ex, ey, speed=speed)


def _print_static(out: dict[str, Any]) -> None:
    keys = (
        "speed_rpm",
        "voltages_V",
        "bearing",
        "eccentricity",
        "attitude_deg",
        "min_film_um",
        "min_film_angle_deg",
        "force_N",
        "preload_um",
        "actuator_pressure_kPa",
        "drag_torque_Nm",
        "power_loss_W",
        "iterations",
        "message",
    )
    for key in keys:
        value = out[key]
        if value == []:  # no actuators or shims: no voltages, preloads, arc pressures
            continue
        if isinstance(value, float):
            value = f"{value:.5g}"
        elif isinstance(value, list):
            value = ", ".join(f"{v:.4g}" for v in value)
        print(f"  {key:<24} {value}")


def _static_sweep_cli(
    case: Case,
    speeds: list[float],
    volts: list[float | None],
    args: argparse.Namespace,
    target: Output | None,
) -> int:
    from foilbearing.output.figures import write_static_figures
    from foilbearing.output.summary import sweep_points
    from foilbearing.study.static import static_sweep

    if case.actuators is None:
        raise InputError(
            "--compare and --shimmed set a C-GFB beside (or in place of) its shimmed twin: "
            "this case has no [actuators]; drop the option",
            source=case.source,
        )
    voltages = [float(case.actuators.voltages[0]) if v is None else float(v) for v in volts]
    bearings = (
        ("C-GFB", "shimmed") if args.compare else (("shimmed",) if args.shimmed else ("C-GFB",))
    )
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    ds = static_sweep(case, speeds, voltages, bearings=bearings, progress=progress)
    ds = ds.assign_coords(load=((), case.operation.load, {"units": "N"}))
    if target is not None:
        target.write(lambda tmp: ds.to_netcdf(tmp))
    out: dict[str, Any] = {"load_N": case.operation.load, "points": sweep_points(ds)} | grid_used(
        case
    )
    if args.plot is not None:
        out["figures"] = [str(p) for p in write_static_figures(ds, args.plot)]
    if args.json:
        emit(out)
    else:
        for point in out["points"]:
            print(
                f"  {point['bearing']:<8} {point['voltage_V']:6.1f} V {point['speed_rpm']:8.0f} rpm"
                f"  ε={point['eccentricity']:.4f}  φ={point['attitude_deg']:6.2f}°"
                f"  h_min={point['min_film_um']:6.2f} µm  preload="
                + ", ".join(f"{x:.2f}" for x in point["preload_um"])
                + " µm"
            )
        print(f"  {grid_line(case)}")
    return 0 if all(p["converged"] for p in out["points"]) else 3


def _speed_sweep_cli(
    case: Case, speeds: list[float], args: argparse.Namespace, target: Output | None
) -> int:
    """The equilibria of a bearing without actuators over ``--speed`` (a list)."""
    from foilbearing.output.summary import speed_sweep_points
    from foilbearing.study.static import speed_sweep

    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    ds = speed_sweep(case, speeds, progress=progress)
    if target is not None:
        target.write(lambda tmp: ds.to_netcdf(tmp))
    out: dict[str, Any] = {
        "bearing": case.kind,
        "load_N": case.operation.load,
        "points": speed_sweep_points(ds),
    } | grid_used(case)
    if args.plot is not None:
        from foilbearing.io import save_figure
        from foilbearing.output.plots.bearing import plot_against

        fig = plot_against(out["points"], "speed_rpm")
        out["figures"] = [str(save_figure(fig, args.plot / "static_vs_speed.png"))]
    if args.json:
        emit(out)
    else:
        for p in out["points"]:
            if not p["converged"]:
                print(f"  {case.kind:<8} {p['speed_rpm']:8.0f} rpm  no equilibrium")
                continue
            print(
                f"  {case.kind:<8} {p['speed_rpm']:8.0f} rpm  ε={p['eccentricity']:.4f}"
                f"  φ={p['attitude_deg']:6.2f}°  h_min={p['min_film_um']:6.2f} µm"
                f"  power loss {p['power_loss_W']:.4g} W"
            )
        print(f"  {grid_line(case)}")
    return 0 if all(p["converged"] for p in out["points"]) else 3
