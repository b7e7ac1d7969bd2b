"""``foilbearing orbit``: a speed-up run with voltage programs or the closed-loop controller.

Registered on the main parser by :func:`register`. The run's specification (case
file, programs, settings) is stored in the NetCDF output so that
``--resume FILE.nc`` continues a stopped run from its checkpoint.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from foilbearing.cli.common import (
    add_case_arg,
    add_load_arg,
    add_overwrite_arg,
    add_subambient_arg,
    claim_output,
    emit,
    guard_outputs,
    load_list,
    positive_quantity,
    print_fields,
    refuse_run_options,
)
from foilbearing.cli.reading import add_reading_args
from foilbearing.cli.run_args import add_run_control_args, add_voltage_program_args

if TYPE_CHECKING:
    from foilbearing.orbit.spec import RunSpec

__all__ = ["register", "run_spec_from_args"]


def register(sub: Any) -> None:
    """Add the ``orbit`` subcommand to the main parser's subparsers."""
    p = sub.add_parser("orbit", help="nonlinear orbit during a speed-up (Figs. 13-15)")
    add_case_arg(p)
    p.add_argument(
        "--speed-ramp",
        default=None,
        help="START:STOP:ACCELERATION (default the paper's 3000rpm:90000rpm:500rad/s**2)",
    )
    p.add_argument(
        "--speed",
        default=None,
        help="constant speed instead of a ramp, e.g. 20000rpm (with --duration)",
    )
    p.add_argument("--duration", default=None, help="duration at constant --speed (default 1 s)")
    add_voltage_program_args(
        p,
        ramp_example="6.0s:6.5s:150V (the paper's control)",
        controller_example="threshold=2um,target=150V,slew=1000V/s,window=0.1s",
    )
    p.add_argument(
        "--voltage-schedule",
        default=None,
        metavar="SCHEDULE.toml",
        help="voltages per speed from a schedule file (foilbearing schedule --out), followed "
        "at the file's slew rate",
    )
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
    p.add_argument(
        "--steps",
        default=None,
        choices=("fixed", "adaptive"),
        help="fixed steps a revolution (default) or variable, error-controlled steps "
        "(at most a tenth of a revolution; --steps-per-rev sets the first)",
    )
    p.add_argument(
        "--rtol",
        type=float,
        default=None,
        help="relative tolerance of the adaptive steps' local error test (default 1e-3: "
        "the orbit within 1.2 %% of 128 steps a revolution)",
    )
    p.add_argument("--sample-rate", default=None, help="output sampling rate (default 10 kHz)")
    add_load_arg(p, several=False)
    add_subambient_arg(p)
    add_reading_args(p)
    p.add_argument("--out", type=Path, help="write the time series (NetCDF); checkpoints too")
    add_overwrite_arg(p)
    add_run_control_args(p)
    p.add_argument(
        "--resume",
        type=Path,
        metavar="FILE.nc",
        help="continue a stopped run from its file alone: the case and the run's options are "
        "the recorded ones, so CASE and the options that shape the run (--speed-ramp, "
        "--speed, --duration, the voltage programs, --steps-per-rev, --order, --steps, --rtol, "
        "--sample-rate, "
        "--load, --subambient and the actuator reading) are refused; --stop-time (default: "
        "to the end), --out (default: FILE.nc itself), --overwrite, --checkpoint-every, "
        "--plot and --json apply",
    )
    p.add_argument("--plot", metavar="DIR", type=Path, help="write the figures (PNG) to DIR")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=_cmd_orbit)


#: The options that shape a run (destination, as written): its file records them, so
#: ``--resume``, which continues the recorded run, refuses them rather than ignore them.
RUN_OPTIONS = (
    ("case", "CASE"),
    ("speed_ramp", "--speed-ramp"),
    ("speed", "--speed"),
    ("duration", "--duration"),
    ("voltage_ramp", "--voltage-ramp"),
    ("controller", "--controller"),
    ("voltage_schedule", "--voltage-schedule"),
    ("steps_per_rev", "--steps-per-rev"),
    ("order", "--order"),
    ("steps", "--steps"),
    ("rtol", "--rtol"),
    ("sample_rate", "--sample-rate"),
    ("load", "--load"),
    ("subambient", "--subambient"),
    ("preload_response", "--preload-response"),
    ("actuator_dynamics", "--actuator-dynamics"),
)


def run_spec_from_args(args: argparse.Namespace) -> RunSpec:
    """The run's specification from the options (stored with the results for --resume);
    an option left out (None) takes the command's default.

    Raises
    ------
    InputError
        One line naming the option whose string does not parse.
    """
    from foilbearing.orbit.settings import OrbitSettings
    from foilbearing.orbit.spec import RunSpec

    strings = {
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
        "steps": args.steps,
        "step_rtol": args.rtol,
        "sample_rate": args.sample_rate,
        "subambient": args.subambient,
        "preload_response": args.preload_response,
        "actuator_dynamics": args.actuator_dynamics,
        "load": args.load,
    }
    # None is "not given": from_cli_strings fills the command's defaults for what is left out
    return RunSpec.from_cli_strings({k: v for k, v in strings.items() if v is not None})


def _schedule_spec(path: str | None) -> dict[str, str] | None:
    """The schedule file's path and text: a resumed run uses the text it started with."""
    if path is None:
        return None
    from foilbearing.io import read_toml

    read_toml(Path(path), "schedule file")  # a missing or broken file fails here, in one line
    return {"path": str(path), "text": Path(path).read_text(encoding="utf-8")}


def _same_file(a: Path, b: Path) -> bool:
    """Whether paths ``a`` and ``b`` name one file (``--resume run.nc --out ./run.nc``)."""
    return Path(a).resolve() == Path(b).resolve()


def _check_positive(args: argparse.Namespace) -> None:
    """One-line errors for a speed, duration, stop time or sample rate that is not > 0."""
    checks = (
        (args.speed, "speed", "--speed", "a speed"),
        (args.duration if args.speed is not None else None, "time", "--duration", "a duration"),
        (args.stop_time, "time", "--stop-time", "a time"),
        (args.sample_rate, "frequency", "--sample-rate", "a frequency"),
    )
    for text, kind, field, what in checks:
        if text is not None:
            positive_quantity(text, kind, field, what)
    load_list(args.load, several=False)


@guard_outputs
def _cmd_orbit(args: argparse.Namespace) -> int:
    from foilbearing.control.options import positive_time
    from foilbearing.orbit import RunStatus, simulate
    from foilbearing.orbit.analysis import analyse_orbit, write_orbit_figures
    from foilbearing.orbit.netcdf import load_orbit, to_netcdf

    resume = None
    if args.resume is not None:
        refuse_run_options(args, RUN_OPTIONS)
        resume, spec = load_orbit(args.resume)
        stop_time = None  # a resumed run goes on to the end unless told
        if args.stop_time is not None:
            stop_time = positive_quantity(args.stop_time, "time", "--stop-time", "a time")
        spec = dataclasses.replace(spec, stop_time=stop_time)
        out_path = args.out or args.resume
    else:
        _check_positive(args)
        spec = run_spec_from_args(args)
        out_path = args.out
    case, profile, program, settings, stop = spec.build()
    every = positive_time(args.checkpoint_every, "--checkpoint-every")
    own_file = args.resume is not None and _same_file(out_path, args.resume)
    target = claim_output(args, out_path, may_exist=own_file)

    def save(result: Any) -> None:
        if target is not None:
            target.write(lambda tmp: to_netcdf(result, spec, tmp))

    result = simulate(
        case,
        profile,
        program,
        settings,
        progress=not args.json,
        stop_time=stop,
        resume=resume,
        checkpoint=save if target is not None else None,
        checkpoint_every=every,
    )
    save(result)
    analysis = analyse_orbit(result)
    out = analysis.headline(result)
    if target is not None and target.failure is None:
        out["netcdf"] = str(out_path)
    if args.plot is not None:
        out["figures"] = [str(p) for p in write_orbit_figures(result, analysis, args.plot)]
    if result.status.advice:  # what to try next, for a run that did not complete
        out["advice"] = result.status.advice
    if args.json:
        emit(out)
    else:
        print(result.message, file=sys.stderr)
        print_fields(out)
    return 0 if result.status in (RunStatus.COMPLETED, RunStatus.STOPPED, RunStatus.CONTACT) else 3
