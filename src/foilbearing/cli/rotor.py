"""``foilbearing rotor``: a rotor on foil bearings, its modes (matched whirl on ROSS) and onset."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from foilbearing.cli.common import (
    add_overwrite_arg,
    claim_output,
    emit,
    guard_outputs,
    refuse_run_options,
)
from foilbearing.cli.run_args import add_run_control_args, add_voltage_program_args
from foilbearing.units import speed_text

__all__ = ["cmd_rotor", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``rotor`` subcommand to the main parser's subparsers ``sub``."""
    rot = sub.add_parser(
        "rotor",
        help="a rotor on foil bearings: modes, log decrements and onset (ROSS, matched whirl)",
    )
    rot.add_argument(
        "rotor",
        type=Path,
        nargs="?",
        help="rotor file (TOML; docs/rotor-format.md); not with --resume, which uses the "
        "file's text the run started with",
    )
    rot.add_argument(
        "--speed-range",
        default=None,
        help="speeds START:STOP:STEP of the bearings' tables and the modes (default "
        "30000rpm:60000rpm:2500rpm, or none with --orbit; about 500rpm apart near the onset "
        "reads it to 0.1 %%)",
    )
    rot.add_argument(
        "--orbit",
        default=None,
        metavar="SPEC",
        help="a nonlinear run of the rotor with both bearings' films: SPEED:DURATION "
        "(constant, e.g. 40000rpm:0.2s) or START:STOP:ACCELERATION (a speed-up, e.g. "
        "30000rpm:60000rpm:500rad/s**2)",
    )
    rot.add_argument(
        "--unbalance",
        action="append",
        default=[],
        metavar="NODE:MAGNITUDE[:PHASE]",
        help="an unbalance: the linear unbalance response over --speed-range (JSON "
        "unbalance_response, unbalance_response.png) and the --orbit run, e.g. 1:8.5g*mm or "
        "1:8.5g*mm:90deg (phase from "
        "the bearings' +X, the load, in the sense of rotation); repeat for several",
    )
    add_voltage_program_args(
        rot,
        during="during --orbit, ",
        whose="every bearing's actuators",
        ramp_example="0.5s:1.0s:150V",
        controller_example="threshold=1um,target=150V,slew=5000V/s,window=0.03s (one on each bearing with "
        "actuators)",
    )
    rot.add_argument(
        "--shaft-modes",
        type=int,
        default=None,
        help="shaft modes kept in the --orbit rotor's reduction (default 8; "
        "docs/rotor-format.md shows the convergence)",
    )
    rot.add_argument(
        "--out", type=Path, help="write the --orbit run (NetCDF), with checkpoints as it goes"
    )
    add_overwrite_arg(rot)
    add_run_control_args(rot, run="the --orbit run", stop_example="1s")
    rot.add_argument(
        "--resume",
        type=Path,
        metavar="FILE.nc",
        help="continue a stopped --orbit run from its file alone: ROTOR and the options that "
        "shape the run (--orbit, --unbalance, --voltage-ramp, --controller, --shaft-modes, "
        "--speed-range, --modes) are refused; --stop-time (default: to the end), --out "
        "(default: FILE.nc itself), --overwrite, --checkpoint-every, --plot and --json apply",
    )
    rot.add_argument("--modes", type=int, default=None, help="modes kept at each speed (default 4)")
    rot.add_argument("--plot", metavar="DIR", type=Path, help="write campbell.png to DIR")
    rot.add_argument("--json", action="store_true", help="print one JSON object")
    rot.set_defaults(func=cmd_rotor)
    return rot


@guard_outputs
def cmd_rotor(args: argparse.Namespace) -> int:
    """Run ``rotor``; returns the exit code (0)."""
    from foilbearing.constants import RPM
    from foilbearing.errors import InputError
    from foilbearing.export.ross import _import_ross
    from foilbearing.io import save_figure
    from foilbearing.rotor import load_rotor
    from foilbearing.units import parse_speed_range

    # Before any work (a coefficient table takes minutes): the core install has no ROSS.
    _import_ross("the rotor command")
    resume = None
    if args.resume is not None:
        resume, rotor = _resume(args)
    elif args.rotor is None:
        raise InputError("give a rotor file (or --resume FILE.nc)")
    else:
        rotor = load_rotor(args.rotor)
    if args.out is not None and args.orbit is None:
        raise InputError("--out writes the --orbit run: give --orbit too")
    own_file = args.resume is not None and Path(args.out).resolve() == args.resume.resolve()
    target = claim_output(args, args.out, may_exist=own_file)
    args.modes = 4 if args.modes is None else args.modes
    if not 1 <= args.modes <= 20:
        raise InputError(f"--modes {args.modes}: allowed 1 to 20")
    text = args.speed_range or (None if args.orbit else "30000rpm:60000rpm:2500rpm")
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    out: dict[str, Any] = {
        "title": rotor.title,
        "mass_kg": rotor.mass,
        "bearings": [
            {"label": b.label, "node": b.node, "load_N": load}
            for b, load in zip(rotor.bearings, rotor.bearing_loads(), strict=True)
        ],
    }
    figures: list[str] = []
    lines: list[str] = []
    if text is not None:
        speeds = parse_speed_range(text, field="--speed-range")
        if len(speeds) < 2:
            raise InputError(f"--speed-range {text!r}: need at least two speeds")
        from foilbearing.rotor import ross_rotor, rotor_modes
        from foilbearing.rotor.linear import modes_at, refine_onset
        from foilbearing.rotor.response import table_frequencies

        unbalances = _unbalances(args.unbalance)
        # With unbalances, the tables hold each speed as a frequency: exact synchronous values.
        freqs = list(table_frequencies(speeds)) if unbalances else None
        model = ross_rotor(rotor, speeds, freqs, progress)
        modes = rotor_modes(rotor, speeds, num_modes=args.modes, model=model)
        onset, whirl = refine_onset(modes, lambda w: modes_at(model, w, args.modes))
        out["onset_speed_rpm"] = None if onset is None else onset / RPM
        out["whirl_frequency_Hz"] = whirl
        out["modes"] = modes.headline()
        response = None
        if unbalances:
            from foilbearing.rotor import unbalance_response

            triples = [(u.node, u.magnitude, u.phase) for u in unbalances]
            response = unbalance_response(rotor, speeds, triples, model=model)
            out["unbalance_response"] = response.headline()
        if onset is None:
            lines.append(f"  stable up to {speeds[-1] / RPM:.0f} rpm")
        else:
            lines.append(f"  onset {speed_text(onset / RPM)}, whirl {whirl:.1f} Hz")
        if args.plot is not None:
            from foilbearing.output.plots.rotor import (
                plot_campbell,
                plot_mode_shapes,
                plot_unbalance_response,
            )
            from foilbearing.rotor import mode_shapes

            fig = plot_campbell(modes, onset, rotor.title)
            figures.append(str(save_figure(fig, args.plot / "campbell.png")))
            at = speeds[-1] if onset is None else onset
            shapes = mode_shapes(rotor, at, model=model, num_modes=args.modes)
            fig = plot_mode_shapes(shapes, f"{rotor.title}: modes at {at / RPM:,.0f} rpm")
            figures.append(str(save_figure(fig, args.plot / "mode_shapes.png")))
            if response is not None:
                fig = plot_unbalance_response(response, rotor.title)
                figures.append(str(save_figure(fig, args.plot / "unbalance_response.png")))
    if args.orbit is not None:
        out["orbit"] = _orbit(args, rotor, figures, lines, resume, target)
    if figures:
        out["figures"] = figures
    if args.json:
        emit(out)
        return 0
    for b in out["bearings"]:
        print(f"  {b['label']} (node {b['node']}): carries {b['load_N']:.2f} N")
    for line in lines:
        print(line)
    return 0


def _orbit_profile(text: str) -> Any:
    """The speed profile of ``--orbit``: SPEED:DURATION or START:STOP:ACCELERATION."""
    from foilbearing.control.options import speed_program

    return speed_program(text, "--orbit")


def _programs(args: argparse.Namespace, rotor: Any, profile: Any) -> list[Any] | None:
    """The bearings' voltage programs: ``--voltage-ramp`` or ``--controller`` (one each)."""
    from foilbearing.errors import InputError

    if args.voltage_ramp is not None and args.controller is not None:
        raise InputError("--voltage-ramp and --controller: give one voltage program")
    if args.controller is None:
        return _voltage_ramps(args.voltage_ramp, rotor)
    from foilbearing.control.options import controller_args
    from foilbearing.orbit.spec import ControllerParams

    params = ControllerParams(**controller_args(args.controller))
    acts = [b.case.actuators for b in rotor.bearings]
    if all(a is None for a in acts):
        raise InputError("--controller: no bearing of the rotor has actuators")
    return [
        None if a is None else params.program(b.case, profile)
        for a, b in zip(acts, rotor.bearings, strict=True)
    ]


def _voltage_ramps(text: str | None, rotor: Any) -> list[Any] | None:
    """``--voltage-ramp T0:T1:V``: one ramp per bearing with actuators, from its voltages."""
    if text is None:
        return None
    from foilbearing.control import voltage_ramp
    from foilbearing.control.options import voltage_ramp_times
    from foilbearing.errors import InputError

    t0, t1, volts = voltage_ramp_times(text)
    acts = [b.case.actuators for b in rotor.bearings]
    if all(a is None for a in acts):
        raise InputError("--voltage-ramp: no bearing of the rotor has actuators")
    return [
        None if a is None else voltage_ramp(t0, t1, volts, initial=list(a.voltages)) for a in acts
    ]


def _unbalances(texts: list[str]) -> list[Any]:
    from foilbearing.errors import InputError
    from foilbearing.rotor.nonlinear import Unbalance
    from foilbearing.units import parse_quantity

    out = []
    for text in texts:
        parts = text.split(":")
        if len(parts) not in (2, 3) or not parts[0].strip().isdigit():
            raise InputError(
                f"--unbalance {text!r}: write NODE:MAGNITUDE[:PHASE], e.g. 1:8.5g*mm:90deg"
            )
        magnitude = parse_quantity(parts[1], "mass_length", field="--unbalance MAGNITUDE")
        phase = (
            parse_quantity(parts[2], "angle", field="--unbalance PHASE") if len(parts) == 3 else 0.0
        )
        out.append(Unbalance(int(parts[0]), magnitude, phase))
    return out


#: The options of an --orbit run kept in its file (attribute ``rotor_run``) for --resume.
_RUN_OPTIONS = ("orbit", "unbalance", "voltage_ramp", "controller", "shaft_modes")

#: What --resume refuses (destination, as written): the run's own options and the rotor
#: file are the recorded ones, and the linear part (speed range, modes) is not run.
_REFUSED_ON_RESUME = (
    ("rotor", "ROTOR"),
    *((key, f"--{key.replace('_', '-')}") for key in _RUN_OPTIONS),
    ("speed_range", "--speed-range"),
    ("modes", "--modes"),
)


def _resume(args: argparse.Namespace) -> tuple[Any, Any]:
    """``--resume FILE.nc``: the stopped run, and its rotor from the run's record (the
    rotor and both bearing cases as data; a file of the first form, the rotor file's
    text); the run's options go back into ``args``."""
    from foilbearing.errors import InputError
    from foilbearing.rotor.nonlinear import load_rotor_orbit
    from foilbearing.rotor.record import read_rotor_run

    refuse_run_options(args, _REFUSED_ON_RESUME)
    run, attrs = load_rotor_orbit(args.resume)
    if "rotor_run" not in attrs or not run.resumable:
        why = "no checkpoint" if "rotor_run" not in attrs else f"it ended ({run.message})"
        raise InputError(f"nothing to resume: {why}", source=str(args.resume))
    spec, rotor = read_rotor_run(attrs["rotor_run"], str(args.resume))
    for key in _RUN_OPTIONS:
        setattr(args, key, spec[key])
    args.out = args.out or args.resume
    args.speed_range = None
    args.rotor_run = spec  # the record the run started with, written again as it goes
    return run, rotor


def _orbit(
    args: argparse.Namespace,
    rotor: Any,
    figures: list[str],
    lines: list[str],
    resume: Any = None,
    target: Any = None,
) -> dict[str, Any]:
    """Run ``--orbit`` (or continue ``resume``); its JSON part (and figures, printed lines)."""
    import json

    from foilbearing.control.options import positive_time
    from foilbearing.io import save_figure
    from foilbearing.rotor.nonlinear import RotorOrbitSystem
    from foilbearing.rotor.stepper import run_rotor

    stop_time = None if args.stop_time is None else positive_time(args.stop_time, "--stop-time")
    every = positive_time(args.checkpoint_every, "--checkpoint-every")
    if args.shaft_modes is None:
        args.shaft_modes = 8  # the default, written into the run's record
    spec = getattr(args, "rotor_run", None)  # set by --resume
    if spec is None:  # the run's options, and its rotor and bearing cases as data
        from foilbearing.rotor.record import RUN_FORMAT, RotorRecord

        spec = {key: getattr(args, key) for key in _RUN_OPTIONS}
        spec["format"] = RUN_FORMAT
        spec["rotor_file"] = rotor.source
        spec["rotor_record"] = RotorRecord.of(rotor, rotor.source).to_dict()

    def save(run: Any) -> None:
        if target is not None:
            data = run.to_dataset(rotor.title)
            data.attrs["rotor_run"] = json.dumps(spec)
            target.write(data.to_netcdf)

    profile = _orbit_profile(args.orbit)
    system = RotorOrbitSystem(
        rotor,
        None,
        profile,
        n_modes=args.shaft_modes,
        voltages=_programs(args, rotor, profile),
        unbalances=_unbalances(args.unbalance),
    )
    run = run_rotor(
        system,
        profile.duration,
        progress=not args.json,
        stop_time=stop_time,
        resume=resume,
        checkpoint=save if target is not None else None,
        checkpoint_every=every,
    )
    save(run)
    amplitude = run.amplitude()
    part: dict[str, Any] = {
        "status": run.status,
        "message": run.message,
        "grid": [list(s.case.grid.orbit_shape) for s in system.sims],
        "shaft_modes": args.shaft_modes,
        "steps": run.steps,
        "wall_time_s": run.wall_time,
        "largest_excursion_um": {
            label: float(a * 1e6) for label, a in zip(run.labels, amplitude, strict=True)
        },
    }
    found = run.subsynchronous_onset(profile) if profile.speeds[-1] > profile.speeds[0] else None
    if found is not None:
        part["onset_speed_rpm"] = found.onset_speed_rpm
        part["whirl_frequency_Hz"] = found.whirl_frequency_hz
    lines.append(f"  orbit: {run.message}; wall {run.wall_time:.1f} s")
    for label, a in zip(run.labels, amplitude, strict=True):
        lines.append(f"    {label}: largest excursion {a * 1e6:.2f} µm")
    if part.get("onset_speed_rpm") is not None:
        onset_text = speed_text(part["onset_speed_rpm"])
        lines.append(f"    sub-synchronous onset at bearing A: {onset_text}")
    if target is not None and target.failure is None:
        part["out"] = str(args.out)
    if run.resumable:
        part["advice"] = f"continue with: foilbearing rotor --resume {args.out or 'FILE.nc'}"
    if args.plot is not None:
        from foilbearing.output.plots.rotor_orbit import plot_rotor_orbit

        fig = plot_rotor_orbit(run, rotor.title)
        figures.append(str(save_figure(fig, args.plot / "rotor_orbit.png")))
    return part
