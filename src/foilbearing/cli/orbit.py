"""``foilbearing orbit``: a speed-up run with voltage programs or the closed-loop controller.

Registered on the main parser by :func:`register`. The run's specification (case
file, programs, settings) is stored in the NetCDF output so that
``--resume FILE.nc`` continues a stopped run from its checkpoint.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from foilbearing.cli.common import add_case_arg, add_subambient_arg, apply_subambient
from foilbearing.errors import InputError

__all__ = ["register", "run_spec_from_args"]


def register(sub: Any) -> None:
    """Add the ``orbit`` subcommand to the main parser's subparsers."""
    p = sub.add_parser("orbit", help="nonlinear orbit during a speed-up (Figs. 13-15)")
    add_case_arg(p)
    p.add_argument(
        "--speed-ramp",
        default="3000rpm:90000rpm:500rad/s**2",
        help="START:STOP:ACCELERATION (default the paper's 3000rpm:90000rpm:500rad/s**2)",
    )
    p.add_argument(
        "--speed",
        default=None,
        help="constant speed instead of a ramp, e.g. 20000rpm (with --duration)",
    )
    p.add_argument("--duration", default="1 s", help="duration at constant --speed (default 1 s)")
    p.add_argument(
        "--voltage-ramp",
        default=None,
        metavar="T0:T1:V",
        help="ramp all actuators from their case voltage to V between T0 and T1, "
        "e.g. 6.0s:6.5s:150V (the paper's control)",
    )
    p.add_argument(
        "--controller",
        default=None,
        metavar="K=V,...",
        help="closed loop: threshold=2um,target=150V,slew=1000V/s,window=0.1s",
    )
    p.add_argument(
        "--voltage-schedule",
        default=None,
        metavar="SCHEDULE.toml",
        help="voltages per speed from a schedule file (foilbearing schedule --out), followed "
        "at the file's slew rate",
    )
    p.add_argument("--stop-time", default=None, help="end the run at this simulated time, e.g. 5s")
    p.add_argument(
        "--steps-per-rev",
        type=int,
        default=None,
        help="time steps per revolution (default 24: with BDF3, the orbit within 1 %% of a converged run)",
    )
    p.add_argument(
        "--order",
        type=int,
        default=None,
        choices=(1, 2, 3, 4),
        help="order of the BDF stepper (default 3)",
    )
    p.add_argument("--sample-rate", default="10000Hz", help="output sampling rate (default 10 kHz)")
    add_subambient_arg(p)
    p.add_argument("--out", type=Path, help="write the time series (NetCDF); checkpoints too")
    p.add_argument(
        "--checkpoint-every",
        default="30s",
        metavar="TIME",
        help="wall time between checkpoints written to --out (default 30s)",
    )
    p.add_argument("--resume", type=Path, metavar="FILE.nc", help="continue a stopped run")
    p.add_argument("--plot", metavar="DIR", type=Path, help="write the figures (PNG) to DIR")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=_cmd_orbit)


def run_spec_from_args(args: argparse.Namespace) -> dict[str, Any]:
    """The run's specification as plain strings (stored with the results for --resume)."""
    from foilbearing.orbit import OrbitSettings

    return {
        "case": None if args.case is None else str(args.case),
        "speed_ramp": args.speed_ramp,
        "speed": args.speed,
        "duration": args.duration,
        "voltage_ramp": args.voltage_ramp,
        "controller": args.controller,
        "voltage_schedule": _schedule_spec(args.voltage_schedule),
        "stop_time": args.stop_time,
        "steps_per_rev": (
            OrbitSettings.steps_per_rev if args.steps_per_rev is None else args.steps_per_rev
        ),
        "order": OrbitSettings.order if args.order is None else args.order,
        "sample_rate": args.sample_rate,
        "subambient": args.subambient,
    }


def _schedule_spec(path: str | None) -> dict[str, str] | None:
    """The schedule file's path and text: a resumed run uses the text it started with."""
    if path is None:
        return None
    from foilbearing.io import read_toml

    read_toml(Path(path), "schedule file")  # a missing or broken file fails here, in one line
    return {"path": str(path), "text": Path(path).read_text(encoding="utf-8")}


def _q(text: str, kind: str, field: str) -> float:
    from foilbearing.units import parse_quantity

    return parse_quantity(
        text.replace("s2", "s**2") if kind == "angular_acceleration" else text, kind, field=field
    )


def _build(spec: dict[str, Any]) -> tuple[Any, ...]:
    import numpy as np

    from foilbearing.case import load_case
    from foilbearing.control import (
        SubsyncController,
        constant_speed,
        linear_ramp,
        voltage_ramp,
    )
    from foilbearing.orbit import OrbitSettings

    case = apply_subambient(load_case(spec["case"]), spec.get("subambient"))
    if spec["speed"] is not None:
        profile = constant_speed(
            _q(spec["speed"], "speed", "--speed"), _q(spec["duration"], "time", "--duration")
        )
    else:
        parts = spec["speed_ramp"].split(":")
        if len(parts) != 3:
            raise InputError(
                f"--speed-ramp {spec['speed_ramp']!r}: expected START:STOP:ACCELERATION"
            )
        profile = linear_ramp(
            _q(parts[0], "speed", "--speed-ramp START"),
            _q(parts[1], "speed", "--speed-ramp STOP"),
            _q(parts[2], "angular_acceleration", "--speed-ramp ACCELERATION"),
        )
    program: Any = None
    chosen = [
        f"--{k.replace('_', '-')}"
        for k in ("voltage_ramp", "controller", "voltage_schedule")
        if spec.get(k) is not None
    ]
    if len(chosen) > 1:
        raise InputError(f"{' and '.join(chosen)}: choose one voltage program")
    if spec.get("voltage_schedule") is not None:
        import tomllib

        from foilbearing.schedule_file import parse_schedule

        given = spec["voltage_schedule"]
        schedule = parse_schedule(tomllib.loads(given["text"]), case, given["path"])
        program = schedule.program(profile)
    if spec["voltage_ramp"] is not None:
        parts = spec["voltage_ramp"].split(":")
        if len(parts) != 3:
            raise InputError(
                f"--voltage-ramp {spec['voltage_ramp']!r}: expected T0:T1:V, e.g. 6.0s:6.5s:150V"
            )
        if case.actuators is None:
            raise InputError("--voltage-ramp needs a case with [actuators]")
        program = voltage_ramp(
            _q(parts[0], "time", "--voltage-ramp T0"),
            _q(parts[1], "time", "--voltage-ramp T1"),
            _q(parts[2], "voltage", "--voltage-ramp V"),
            initial=np.asarray(case.actuators.voltages),
        )
    if spec["controller"] is not None:
        kwargs: dict[str, Any] = dict(_controller_args(spec["controller"]))
        program = SubsyncController(**kwargs)
    settings = OrbitSettings(
        steps_per_rev=int(spec["steps_per_rev"]),
        order=int(spec.get("order") or 2),  # runs saved before the order was stored: BDF2
        sample_rate=_q(spec["sample_rate"], "frequency", "--sample-rate"),
    )
    stop = None if spec["stop_time"] is None else _q(spec["stop_time"], "time", "--stop-time")
    return case, profile, program, settings, stop


def _controller_args(text: str) -> dict[str, float]:
    kinds = {
        "threshold": ("length", "threshold"),
        "target": ("voltage", "target"),
        "slew": ("slew_rate", "slew_rate"),
        "window": ("time", "window"),
        "period": ("time", "period"),
        "initial": ("voltage", "initial"),
    }
    out: dict[str, float] = {}
    for item in filter(None, (s.strip() for s in text.split(","))):
        key, _, value = item.partition("=")
        if key not in kinds or not value:
            raise InputError(
                f"--controller {item!r}: expected KEY=VALUE with KEY one of " + ", ".join(kinds)
            )
        kind, name = kinds[key]
        out[name] = _q(value, kind, f"--controller {key}")
    return out


def _cmd_orbit(args: argparse.Namespace) -> int:
    from foilbearing.io import write_with
    from foilbearing.orbit import simulate
    from foilbearing.orbit.analysis import analyse_orbit, write_orbit_figures
    from foilbearing.orbit.netcdf import load_orbit, to_netcdf

    resume = None
    if args.resume is not None:
        resume, spec = load_orbit(args.resume)
        spec["stop_time"] = args.stop_time  # a resumed run goes on to the end unless told
        out_path = args.out or args.resume
    else:
        spec = run_spec_from_args(args)
        out_path = args.out
    case, profile, program, settings, stop = _build(spec)

    def save(result: Any) -> None:
        if out_path is not None:
            write_with(out_path, lambda tmp: to_netcdf(result, spec, tmp))

    every = _q(args.checkpoint_every, "time", "--checkpoint-every")
    if not every > 0.0:
        raise InputError(f"--checkpoint-every {args.checkpoint_every!r}: expected a time > 0 s")
    result = simulate(
        case,
        profile,
        program,
        settings,
        progress=not args.json,
        stop_time=stop,
        resume=resume,
        checkpoint=save if out_path is not None else None,
        checkpoint_every=every,
    )
    save(result)
    analysis = analyse_orbit(result)
    out = analysis.headline(result)
    if out_path is not None:
        out["netcdf"] = str(out_path)
    if args.plot is not None:
        out["figures"] = [str(p) for p in write_orbit_figures(result, analysis, args.plot)]
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print(result.message, file=sys.stderr)
        for key, value in out.items():
            print(f"  {key:<28} {value}")
    return 0 if result.status in ("completed", "stopped", "contact") else 3
