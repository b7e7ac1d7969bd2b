"""``foilbearing stability``: linear stability, onset speed (rpm) and whirl frequency (Hz).

The onset of instability per actuator voltage over a speed scan, optionally the
stability map as a PNG file.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from foilbearing.cli.common import (
    add_case_arg,
    add_load_arg,
    add_subambient_arg,
    apply_subambient,
    emit,
    load_list,
    over_loads,
    refuse_without_actuators,
    voltage_list,
)
from foilbearing.cli.reading import add_reading_args, apply_reading
from foilbearing.errors import InputError
from foilbearing.output.summary import grid_line, grid_used
from foilbearing.units import speed_text

__all__ = ["cmd_stability", "register"]

#: The onset scan of a C-GFB when ``--speed-range`` is not given.
DEFAULT_SCAN = "5000rpm:150000rpm:5000rpm"


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``stability`` subcommand to the main parser's subparsers ``sub``."""
    stab = sub.add_parser("stability", help="linear stability: onset speed and whirl frequency")
    add_case_arg(stab)
    stab.add_argument(
        "--voltage",
        default=None,
        help="voltages, e.g. 0,50,100,150V (default); with --design one voltage (default 150V)",
    )
    stab.add_argument(
        "--design",
        action="store_true",
        help="the stack-stiffness design answer: the onset against K_p under each reading of "
        "the actuator, beside the shimmed GFB, and the K_p for 90 %% of its onset",
    )
    stab.add_argument("--shimmed", action="store_true", help="the shimmed GFB twins")
    stab.add_argument(
        "--speed-range",
        default=None,
        help="scan START:STOP:STEP (default 5000rpm:150000rpm:5000rpm; for a bearing without "
        "actuators the study's onset scan, so that the onset is the study's)",
    )
    add_load_arg(stab)
    add_subambient_arg(stab)
    add_reading_args(stab)
    stab.add_argument(
        "--plot", metavar="DIR", type=Path, help="write the stability map (PNG) to DIR"
    )
    stab.add_argument("--json", action="store_true", help="print one JSON object")
    stab.set_defaults(func=cmd_stability)
    return stab


def cmd_stability(args: argparse.Namespace) -> int:
    """Run ``stability``; returns the exit code (0)."""
    from foilbearing.analysis.stability import onsets_per_voltage, stability_map
    from foilbearing.case import load_case
    from foilbearing.constants import RPM
    from foilbearing.io import save_figure
    from foilbearing.units import parse_speed_range

    loads = load_list(args.load)
    if loads is not None and len(loads) > 1:
        return over_loads(cmd_stability, args, loads)
    case = apply_reading(apply_subambient(load_case(args.case), args.subambient), args)
    if loads is not None:
        case = case.with_load(loads[0])
    if case.actuators is None:
        return _passive(case, args)
    speeds = parse_speed_range(args.speed_range or DEFAULT_SCAN, field="--speed-range")
    if args.design:
        return _design(case, args, speeds)
    voltages = voltage_list(args.voltage or "0,50,100,150V", case)
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    per_volt = onsets_per_voltage(case, voltages, speeds, shimmed=args.shimmed, progress=progress)
    bearing = "shimmed" if args.shimmed else "C-GFB"
    entries = [{"voltage_V": v, "bearing": bearing} | r.headline() for v, r in per_volt.items()]
    onsets = [None if r.onset_speed is None else r.onset_speed / RPM for r in per_volt.values()]
    out: dict[str, Any] = {
        "load_N": case.operation.load,
        "rotor_mass_kg": case.rotor.mass,
        "voltages": entries,
    }
    out |= grid_used(case)
    if args.plot is not None:
        from foilbearing.output.plots.dynamics import plot_stability_map

        ds = stability_map(case, speeds, voltages, shimmed=args.shimmed, progress=progress)
        name = "stability_map_shimmed.png" if args.shimmed else "stability_map.png"
        out["figures"] = [str(save_figure(plot_stability_map(ds, onsets), args.plot / name))]
    if args.json:
        emit(out)
    else:
        for e in entries:
            onset: Any = e["onset_speed_rpm"]
            text = (
                "stable over the scan"
                if onset is None
                else (
                    f"onset {speed_text(onset)}, whirl {e['whirl_frequency_Hz']:.1f} Hz "
                    f"(ratio {e['whirl_ratio']:.3f})"
                )
            )
            print(f"  {e['bearing']} {e['voltage_V']:6.1f} V: {text}")
        print(f"  {grid_line(case)}; {_check_hint(args)}")
    return 0


def _passive(case: Any, args: argparse.Namespace) -> int:
    """The onset of a bearing without actuators (passive, shimmed or rigid) as it is.

    Without ``--speed-range`` the scan is the study's (:meth:`StudyPlan.onset_scan`), so
    that ``stability`` and ``study`` report the same onset for the case.
    """
    from foilbearing.analysis.stability import onset_speed
    from foilbearing.constants import RPM
    from foilbearing.io import save_figure
    from foilbearing.study.plan import study_plan
    from foilbearing.units import parse_speed_range

    if args.voltage is not None:
        refuse_without_actuators(case, "--voltage", args.voltage)
    for flag, given in (("--shimmed", args.shimmed), ("--design", args.design)):
        if given:
            refuse_without_actuators(case, flag)
    if args.speed_range is None:
        speeds = study_plan(case).onset_scan()
    else:
        speeds = list(parse_speed_range(args.speed_range, field="--speed-range"))
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    result = onset_speed(case, speeds, progress=progress)
    step = speeds[1] - speeds[0] if len(speeds) > 1 else 0.0
    out: dict[str, Any] = (
        {
            "bearing": case.kind,
            "rotor_mass_kg": case.rotor.mass,
            "load_N": case.operation.load,
            "scan_rpm": [speeds[0] / RPM, speeds[-1] / RPM, step / RPM],
        }
        | result.headline()
        | grid_used(case)
    )
    if args.plot is not None:
        from foilbearing.output.plots.bearing import plot_log_decrement

        modes = [
            {"speed_rpm": w / RPM, "log_decrement": d}
            for w, d in zip(result.speeds, result.log_decrement, strict=True)
        ]
        fig = plot_log_decrement(modes, out["onset_speed_rpm"])
        out["figures"] = [str(save_figure(fig, args.plot / "log_decrement.png"))]
    if args.json:
        emit(out)
        return 0
    onset = out["onset_speed_rpm"]
    text = (
        result.message
        if onset is None
        else (
            f"onset {speed_text(onset)}, whirl {out['whirl_frequency_Hz']:.1f} Hz "
            f"(ratio {out['whirl_ratio']:.3f}); {result.message}"
        )
    )
    print(f"  {case.kind} at {case.operation.load:g} N, rotor {case.rotor.mass:g} kg: {text}")
    print(f"  {grid_line(case)}; {_check_hint(args)}")
    return 0


def _check_hint(args: argparse.Namespace) -> str:
    """Where the onset's discretisation error comes from: ``foilbearing check``."""
    case = f" {args.case}" if getattr(args, "case", None) else ""
    return f"its error on this grid: foilbearing check{case}"


def _design(case: Any, args: argparse.Namespace, speeds: Any) -> int:
    """``stability --design``: :func:`foilbearing.design.stack_design` at one voltage."""
    from foilbearing.design import stack_design
    from foilbearing.io import save_figure

    volts = voltage_list(args.voltage or "150V", case)
    if len(volts) != 1:
        raise InputError(f"--voltage {args.voltage!r}: --design takes one voltage")
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    design = stack_design(case, volts[0], speeds=speeds, progress=progress)
    out = design.headline()
    if args.plot is not None:
        from foilbearing.output.plots.dynamics import plot_stack_design

        path = save_figure(plot_stack_design(design), args.plot / "stack_design.png")
        out["figures"] = [str(path)]
    if args.json:
        emit(out)
        return 0
    print(f"What the stack's stiffness buys at {design.voltage:g} V (linear onset, rigid rotor):")
    for row in out["table"]:
        on = row["onset_speed_rpm"]
        text = (
            "stable over the scan"
            if on is None
            else (f"onset {speed_text(on)}, whirl {row['whirl_frequency_Hz']:.1f} Hz")
        )
        print(f"  {row['bearing']:52s} {text}")
    target = f"{design.target:.0%} of the shimmed GFB's onset"
    for key, k in out["required_stack_stiffness_N_per_m"].items():
        need = "not reached in the scan" if k is None else f"K_p = {k / 1e6:.3g} MN/m"
        print(f"  {target} under {key}: {need}")
    return 0
