"""The ``foilbearing`` command: a thin layer over the library.

Every subcommand that computes something takes ``--json`` and then prints its
headline results as one JSON object on stdout, keys named with their units.
Bad input ends with a one-line error on stderr and exit code 2, never a
traceback; a solver failure with exit code 3.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from foilbearing.cli.common import add_case_arg, add_subambient_arg, apply_subambient
from foilbearing.errors import InputError, SolverError

if TYPE_CHECKING:
    from foilbearing.case import Case

__all__ = ["main"]


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code."""
    parser = _parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    try:
        return int(args.func(args) or 0)
    except InputError as exc:
        print(f"foilbearing: error: {exc}", file=sys.stderr)
        return 2
    except SolverError as exc:
        print(f"foilbearing: solver failed: {exc}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("foilbearing: interrupted", file=sys.stderr)
        return 130


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="foilbearing",
        description="Gas foil bearings with piezoelectric preload control (C-GFB).",
    )
    sub = p.add_subparsers(title="subcommands", metavar="COMMAND")

    case_p = sub.add_parser("case", help="show a bearing case and its derived quantities")
    case_sub = case_p.add_subparsers(title="case commands", metavar="ACTION")
    show = case_sub.add_parser("show", help="print the case: inputs, k_b, k_assy, base preloads, Λ")
    add_case_arg(show)
    show.add_argument("--json", action="store_true", help="print one JSON object")
    show.set_defaults(func=_cmd_case_show)

    st = sub.add_parser("structure", help="structure models: k_b, k_assy, preloads; Figs. 7-8")
    add_case_arg(st)
    st.add_argument("--voltage", default="0,50,100,150V", help="voltages, e.g. 0,50,100,150V")
    st.add_argument("--plot", metavar="DIR", type=Path, help="write the figures (PNG) to DIR")
    st.add_argument("--json", action="store_true", help="print one JSON object")
    st.set_defaults(func=_cmd_structure)

    ident = sub.add_parser("identify", help="identify PZT parameters from measured stack data")
    ident.add_argument("no_load", type=Path, nargs="?", help="no-load CSV (voltage_V, stackN_um)")
    ident.add_argument(
        "stiffness",
        type=Path,
        nargs="?",
        help="stiffness CSV (stack, voltage_V, load_N, displacement_um)",
    )
    ident.add_argument(
        "--contact-area",
        default="3.54e-4 m**2",
        help="stinger-foil contact area (default 3.54e-4 m**2)",
    )
    ident.add_argument(
        "--update",
        metavar="CASE.toml",
        type=Path,
        help="write the identified D33 and K_p into this case file",
    )
    ident.add_argument("--plot", metavar="DIR", type=Path, help="write Figs. 5b, 6b-c (PNG) to DIR")
    ident.add_argument("--json", action="store_true", help="print one JSON object")
    ident.set_defaults(func=_cmd_identify)

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
    add_subambient_arg(stat)
    stat.add_argument("--out", type=Path, help="write the results to FILE.nc (NetCDF)")
    stat.add_argument("--plot", metavar="DIR", type=Path, help="write the figures (PNG) to DIR")
    stat.add_argument("--json", action="store_true", help="print one JSON object")
    stat.set_defaults(func=_cmd_static)

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
    add_subambient_arg(coef)
    coef.add_argument("--out", type=Path, help="write the coefficients to FILE.nc")
    coef.add_argument("--plot", metavar="DIR", type=Path, help="write the figure (PNG) to DIR")
    coef.add_argument("--json", action="store_true", help="print one JSON object")
    coef.set_defaults(func=_cmd_coefficients)

    stab = sub.add_parser("stability", help="linear stability: onset speed and whirl frequency")
    add_case_arg(stab)
    stab.add_argument("--voltage", default="0,50,100,150V", help="voltages, e.g. 0,50,100,150V")
    stab.add_argument("--shimmed", action="store_true", help="the shimmed GFB twins")
    stab.add_argument(
        "--speed-range",
        default="5000rpm:150000rpm:5000rpm",
        help="scan START:STOP:STEP (default 5000rpm:150000rpm:5000rpm)",
    )
    add_subambient_arg(stab)
    stab.add_argument(
        "--plot", metavar="DIR", type=Path, help="write the stability map (PNG) to DIR"
    )
    stab.add_argument("--json", action="store_true", help="print one JSON object")
    stab.set_defaults(func=_cmd_stability)

    from foilbearing.cli.optimize import register as register_optimize
    from foilbearing.cli.orbit import register as register_orbit
    from foilbearing.cli.schedule import register as register_schedule
    from foilbearing.cli.sweep import register as register_sweep
    from foilbearing.cli.uncertainty import register as register_uncertainty

    register_orbit(sub)
    register_sweep(sub)
    register_uncertainty(sub)
    register_optimize(sub)
    register_schedule(sub)

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
        help="envelopes of what the paper leaves open, on the paper's case: quick (56 "
        "evaluations, ~3 min on 2 cores), full (256) or none (default quick)",
    )
    study.add_argument(
        "--schedule",
        choices=("full", "none"),
        default="full",
        help="the voltage schedule for a controller (C-GFB), verified in speed-ups when "
        "--orbits full (default full)",
    )
    study.add_argument("--json", action="store_true", help="print one JSON object")
    study.set_defaults(func=_cmd_study)
    return p


def parse_list(text: str, kind: str, field: str) -> list[float]:
    """Parse "0,50,100,150V" or "10000rpm,50000rpm" into SI floats.

    A unit written on the last item applies to bare numbers before it.
    """
    from foilbearing.units import parse_quantity

    items = [s.strip() for s in text.split(",") if s.strip()]
    if not items:
        raise InputError(f"{field} = {text!r}: expected one or more values")
    last = items[-1]
    unit = last.lstrip("+-0123456789.eE ")
    out = []
    for item in items:
        bare = item.lstrip("+-").replace(".", "", 1).replace("e", "", 1).replace("E", "", 1)
        value = (
            f"{item} {unit}" if unit and bare.replace("-", "").replace("+", "").isdigit() else item
        )
        out.append(parse_quantity(value, kind, field=field))
    return out


def _emit(obj: dict[str, Any]) -> None:
    print(json.dumps(obj, indent=2, default=_json_default))


def _json_default(x: Any) -> Any:
    if hasattr(x, "tolist"):
        return x.tolist()
    if isinstance(x, Path):
        return str(x)
    raise TypeError(f"not JSON serialisable: {type(x).__name__}")


def _cmd_case_show(args: argparse.Namespace) -> int:
    from foilbearing.case import load_case
    from foilbearing.output.summary import case_summary, format_summary

    case = load_case(args.case)
    summary = case_summary(case)
    if args.json:
        _emit(summary)
    else:
        print(f"Case: {case.title or case.source}")
        print(format_summary(summary))
    return 0


def _cmd_structure(args: argparse.Namespace) -> int:
    from foilbearing.case import load_case
    from foilbearing.output.figures import write_structure_figures
    from foilbearing.output.summary import structure_summary

    case = load_case(args.case)
    voltages = parse_list(args.voltage, "voltage", "--voltage")
    if case.actuators is not None:
        for v in voltages:
            if not 0.0 <= v <= case.actuators.max_voltage:
                raise InputError(
                    f"--voltage {v:g} V: allowed 0 to {case.actuators.max_voltage:g} V (max_voltage)"
                )
    out = structure_summary(case, voltages)
    if args.plot is not None:
        out["figures"] = [str(p) for p in write_structure_figures(case, args.plot)]
    if args.json:
        _emit(out)
    else:
        for key, value in out.items():
            print(f"  {key:<20} {value}")
    return 0


def _cmd_identify(args: argparse.Namespace) -> int:
    from foilbearing import identification as ident
    from foilbearing.output.figures import write_identification_figures
    from foilbearing.units import parse_quantity

    example_no_load, example_stiffness = ident.example_measurements()
    no_load = args.no_load or example_no_load
    stiffness = args.stiffness or example_stiffness
    area = parse_quantity(args.contact_area, "area", field="--contact-area")
    if area <= 0.0:
        raise InputError(f"--contact-area {args.contact_area!r}: must be > 0")
    result = ident.identify(no_load, stiffness, area)
    out = dict(result.headline())
    if args.plot is not None:
        out["figures"] = [str(p) for p in write_identification_figures(result, args.plot)]
    if args.update is not None:
        ident.update_case_file(args.update, result)
        out["updated_case"] = str(args.update)
    if args.json:
        _emit(out)
    else:
        for key, value in out.items():
            print(f"  {key:<28} {value}")
    return 0


def _cmd_static(args: argparse.Namespace) -> int:
    from foilbearing.case import load_case
    from foilbearing.io import write_with

    case = apply_subambient(load_case(args.case), args.subambient)
    speeds = parse_list(args.speed, "speed", "--speed") if args.speed else [case.operation.speed]
    for s in speeds:
        if s <= 0.0:
            raise InputError(f"--speed {s:g} rad/s: a speed must be > 0 (e.g. 50000rpm)")
    volts: list[float | None] = [None]
    if args.voltage is not None:
        if case.actuators is None:
            raise InputError("--voltage given but the case has no [actuators]")
        given = parse_list(args.voltage, "voltage", "--voltage")
        for v in given:
            case.with_voltages(v)  # validates the range with a clear message
        volts = list(given)
    if len(speeds) > 1 or len(volts) > 1 or args.compare:
        return _static_sweep_cli(case, speeds, volts, args)
    if volts[0] is not None:
        case = case.with_voltages(float(volts[0]))
    if args.shimmed:
        case = case.shimmed()
    result = _static_point(case, speeds[0], args.eccentricity)
    if args.out is not None:
        write_with(args.out, lambda tmp: result.to_dataset().to_netcdf(tmp))
    out = result.headline()
    if args.plot is not None:
        from foilbearing.io import save_figure
        from foilbearing.output.plots.static import plot_point

        out["figures"] = [str(save_figure(plot_point(result), args.plot / "static_point.png"))]
    if args.json:
        _emit(out)
    else:
        _print_static(out)
    return 0 if result.converged else 3


def _static_point(case: Case, speed: float, eccentricity: str | None) -> Any:
    from foilbearing.static import film_at_position, solve_equilibrium

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
        if isinstance(value, float):
            value = f"{value:.5g}"
        elif isinstance(value, list):
            value = ", ".join(f"{v:.4g}" for v in value)
        print(f"  {key:<24} {value}")


def _static_sweep_cli(
    case: Case, speeds: list[float], volts: list[float | None], args: argparse.Namespace
) -> int:
    from foilbearing.io import write_with
    from foilbearing.output.figures import write_static_figures
    from foilbearing.output.summary import sweep_points
    from foilbearing.study.static import static_sweep

    if case.actuators is None:
        raise InputError("a static sweep over voltages needs a case with [actuators]")
    voltages = [float(case.actuators.voltages[0]) if v is None else float(v) for v in volts]
    bearings = (
        ("C-GFB", "shimmed") if args.compare else (("shimmed",) if args.shimmed else ("C-GFB",))
    )
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    ds = static_sweep(case, speeds, voltages, bearings=bearings, progress=progress)
    if args.out is not None:
        write_with(args.out, lambda tmp: ds.to_netcdf(tmp))
    out: dict[str, Any] = {"points": sweep_points(ds)}
    if args.plot is not None:
        out["figures"] = [str(p) for p in write_static_figures(ds, args.plot)]
    if args.json:
        _emit(out)
    else:
        for point in out["points"]:
            print(
                f"  {point['bearing']:<8} {point['voltage_V']:6.1f} V {point['speed_rpm']:8.0f} rpm"
                f"  ε={point['eccentricity']:.4f}  φ={point['attitude_deg']:6.2f}°"
                f"  h_min={point['min_film_um']:6.2f} µm  preload="
                + ", ".join(f"{x:.2f}" for x in point["preload_um"])
                + " µm"
            )
    return 0 if all(p["converged"] for p in out["points"]) else 3


def _cmd_coefficients(args: argparse.Namespace) -> int:
    import numpy as np

    from foilbearing.case import load_case
    from foilbearing.coefficients import force_coefficients
    from foilbearing.io import save_figure, write_with
    from foilbearing.static import solve_equilibrium

    case = apply_subambient(load_case(args.case), args.subambient)
    if args.speed is not None:
        (speed,) = parse_list(args.speed, "speed", "--speed")
        case = case.with_speed(speed)
    if args.voltage is not None:
        (volt,) = parse_list(args.voltage, "voltage", "--voltage")
        case = case.with_voltages(volt)
    if args.shimmed:
        case = case.shimmed()
    if args.frequency is None:
        freqs = np.linspace(0.1, 2.0, 20) * case.operation.speed
    else:
        freqs = 2 * np.pi * np.array(parse_list(args.frequency, "frequency", "--frequency"))
    static = solve_equilibrium(case)
    if not static.converged:
        raise SolverError(static.message)
    fc = force_coefficients(static, freqs)
    out = fc.headline()
    if args.out is not None:
        write_with(args.out, lambda tmp: fc.to_dataset().to_netcdf(tmp))
    if args.plot is not None:
        from foilbearing.output.plots.dynamics import plot_coefficients

        out["figures"] = [str(save_figure(plot_coefficients(fc), args.plot / "coefficients.png"))]
    if args.json:
        _emit(out)
    else:
        print(f"  speed {out['speed_rpm']:.0f} rpm, eccentricity {out['eccentricity']:.4f}")
        print(
            "  f (Hz)      K_XX      K_XY      K_YX      K_YY (MN/m)"
            "     C_XX      C_XY      C_YX      C_YY (kN s/m)"
        )
        for f, k, c in zip(out["frequency_Hz"], fc.K, fc.C, strict=True):
            ks = " ".join(f"{x / 1e6:9.4f}" for x in k.ravel())
            cs = " ".join(f"{x / 1e3:9.4f}" for x in c.ravel())
            print(f"  {f:7.1f} {ks}   {cs}")
    return 0


def _cmd_stability(args: argparse.Namespace) -> int:
    from foilbearing.case import load_case
    from foilbearing.constants import RPM
    from foilbearing.io import save_figure
    from foilbearing.stability import onsets_per_voltage, stability_map
    from foilbearing.units import parse_speed_range

    case = apply_subambient(load_case(args.case), args.subambient)
    speeds = parse_speed_range(args.speed_range, field="--speed-range")
    voltages = parse_list(args.voltage, "voltage", "--voltage")
    if case.actuators is None:
        raise InputError("the stability study over voltages needs a case with [actuators]")
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    per_volt = onsets_per_voltage(case, voltages, speeds, shimmed=args.shimmed, progress=progress)
    bearing = "shimmed" if args.shimmed else "C-GFB"
    entries = [{"voltage_V": v, "bearing": bearing} | r.headline() for v, r in per_volt.items()]
    onsets = [None if r.onset_speed is None else r.onset_speed / RPM for r in per_volt.values()]
    out: dict[str, Any] = {"rotor_mass_kg": case.rotor.mass, "voltages": entries}
    if args.plot is not None:
        from foilbearing.output.plots.dynamics import plot_stability_map

        ds = stability_map(case, speeds, voltages, shimmed=args.shimmed, progress=progress)
        name = "stability_map_shimmed.png" if args.shimmed else "stability_map.png"
        out["figures"] = [str(save_figure(plot_stability_map(ds, onsets), args.plot / name))]
    if args.json:
        _emit(out)
    else:
        for e in entries:
            onset = e["onset_speed_rpm"]
            text = (
                "stable over the scan"
                if onset is None
                else (
                    f"onset {onset:8.0f} rpm, whirl {e['whirl_frequency_Hz']:.1f} Hz "
                    f"(ratio {e['whirl_ratio']:.3f})"
                )
            )
            print(f"  {e['bearing']} {e['voltage_V']:6.1f} V: {text}")
    return 0


def _cmd_study(args: argparse.Namespace) -> int:
    from foilbearing.case import load_case
    from foilbearing.study.paper import run_study

    case = load_case(args.case)
    summary = run_study(
        case,
        args.out,
        progress=not args.json,
        orbits=args.orbits == "full",
        uncertainty=args.uncertainty,
        schedule=args.schedule == "full",
    )
    if args.json:
        _emit(summary)
    return 0
