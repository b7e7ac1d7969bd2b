"""Pieces shared by the subcommands of the ``foilbearing`` command."""

from __future__ import annotations

import argparse
import errno
import functools
import json
import math
import re
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from foilbearing.case import Case

__all__ = [
    "Output",
    "add_case_arg",
    "add_dask_args",
    "add_load_arg",
    "add_overwrite_arg",
    "add_subambient_arg",
    "apply_subambient",
    "attach_negative_values",
    "check_dask_args",
    "check_plot_folder",
    "claim_output",
    "emit",
    "guard_outputs",
    "load_list",
    "over_loads",
    "parse_list",
    "positive_list",
    "positive_quantity",
    "refuse_run_options",
    "refuse_without_actuators",
    "strict_json",
    "voltage_list",
]

# A token that starts like a negative number: "-5rpm", "-0.3,0.2", "-.5", "-1e4Hz".
_NEGATIVE_START = re.compile(r"-\.?\d")


def command_help(doc: str | None) -> str | None:
    """A command's description for ``--help`` from its module docstring's second paragraph,
    without the docstring's reST literal quotes (``x`` → x)."""
    if not doc:
        return None
    return doc.split("\n\n")[1].replace("``", "")


def attach_negative_values(argv: Sequence[str]) -> list[str]:
    """``argv`` with ``--option -5rpm`` written ``--option=-5rpm``.

    argparse takes a token that begins with ``-`` for an option unless it is a
    bare negative number, so ``--speed -5rpm`` or ``--eccentricity -0.3,0.2``
    would end in "expected one argument". A token that starts like a negative
    number (``-``, then a digit or ``.digit``; no option of the command does)
    right after a long option without ``=`` is joined to it in the ``=`` form,
    which argparse documents for values that begin with ``-``. After ``--``
    nothing is changed. Joined to an option that takes no value, the token
    still ends in argparse's error, as it did alone.
    """
    tokens = list(argv)
    out: list[str] = []
    for k, token in enumerate(tokens):
        if token == "--":
            out.extend(tokens[k:])
            break
        prev = out[-1] if out else ""
        if (
            _NEGATIVE_START.match(token)
            and prev.startswith("--")
            and len(prev) > 2
            and "=" not in prev
        ):
            out[-1] = f"{prev}={token}"
        else:
            out.append(token)
    return out


def add_case_arg(p: argparse.ArgumentParser) -> None:
    """The optional positional CASE argument (default: the built-in case, see ``load_case``)."""
    p.add_argument(
        "case",
        nargs="?",
        type=Path,
        default=None,
        help="case file (TOML); default: the paper's C-GFB",
    )


def add_subambient_arg(p: argparse.ArgumentParser) -> None:
    """``--subambient lift-off|retained``: the film model where the pressure is sub-ambient."""
    p.add_argument(
        "--subambient",
        default=None,
        metavar="MODEL",
        help="film under a foil below ambient pressure: lift-off (the foil leaves the bumps, "
        "no suction; default for a foil bearing) or retained (suction held, for comparison); "
        "default: the case's [foil] subambient",
    )


def apply_subambient(case: Case, model: str | None) -> Case:
    """The case with ``--subambient`` applied (unchanged when the option is absent)."""
    return case if model is None else case.with_subambient(model)


def add_load_arg(p: argparse.ArgumentParser, *, several: bool = True) -> None:
    """``--load``: the static load along +X, N (one value, or with ``several`` a list).

    A list runs the command once per load (:func:`over_loads`); the rotor mass
    stays the case's (docs/case-format.md, "Load and rotor mass").
    """
    p.add_argument(
        "--load",
        default=None,
        help=(
            "static load along +X, e.g. 50N"
            + (" or 50,100,150N (a list runs one analysis per load)" if several else "")
            + "; default: the case's operation.load"
        ),
    )


def load_list(text: str | None, *, several: bool = True) -> list[float] | None:
    """``--load``'s loads, N, each finite and >= 0 (None: the option was not given).

    Without ``several`` one value only, else a one-line error.
    """
    import math

    from foilbearing.errors import InputError

    if text is None:
        return None
    loads = parse_list(text, "force", "--load")
    if not all(math.isfinite(w) and w >= 0.0 for w in loads):
        raise InputError(f"--load = {text!r}: a load must be >= 0 N")
    if not several and len(loads) > 1:
        raise InputError(f"--load = {text!r}: this command takes one load, e.g. 50N")
    return loads


def over_loads(
    command: Callable[[argparse.Namespace], int], args: argparse.Namespace, loads: list[float]
) -> int:
    """Run ``command`` once per load of ``loads`` (N) and combine the runs.

    Each run is the command with ``--load`` set to one value. ``--json`` prints
    ``{"loads": [...]}``, one object per load (the command's own, with ``load_N``);
    ``--out`` writes one NetCDF file with the runs' datasets along a ``load``
    dimension (N); ``--plot DIR`` puts each run's figures in ``DIR/load_<W>N``.
    Returns the largest exit code of the runs.
    """
    import contextlib
    import copy
    import io
    import tempfile

    from foilbearing.errors import SolverError

    out, plot = getattr(args, "out", None), getattr(args, "plot", None)
    target = claim_output(args, out)  # before any work starts
    code = 0
    entries: list[dict[str, Any]] = []
    datasets = []
    with tempfile.TemporaryDirectory() as tmp:
        for k, load in enumerate(loads):
            one = copy.copy(args)
            one._reservations, one._outputs = [], []  # the run's own, released when it ends
            one.load = f"{load!r} N"
            one.out = None if out is None else Path(tmp) / f"load_{k}.nc"
            one.plot = None if plot is None else plot / f"load_{load:g}N"
            try:
                if args.json:
                    captured = io.StringIO()
                    with contextlib.redirect_stdout(captured):
                        code = max(code, command(one))
                    entries.append({"load_N": load} | json.loads(captured.getvalue()))
                else:
                    print(f"load {load:g} N:")
                    code = max(code, command(one))
            except SolverError as exc:  # say which load of the list failed
                raise SolverError(f"at --load {load:g} N: {exc}") from None
            if one.out is not None:
                datasets.append(_with_load(one.out, load))
        if target is not None:
            _write_along_load(target, datasets)
    if args.json:
        emit({"loads": entries})
    return code


def _with_load(path: Path, load: float) -> Any:
    """The dataset of ``path`` with ``load`` (N) as its scalar coordinate ``load``."""
    import xarray as xr

    ds = xr.load_dataset(path)
    if "load" not in ds.coords:
        ds = ds.assign_coords(load=load)
    return ds


def _write_along_load(target: Output, datasets: list[Any]) -> None:
    """The per-load datasets along a new ``load`` dimension (N), written to ``target``."""
    import xarray as xr

    combined = xr.concat(datasets, dim="load", combine_attrs="drop_conflicts")
    combined["load"].attrs.update(units="N", long_name="static load W along +X")
    target.write(lambda tmp: combined.to_netcdf(tmp))


def add_dask_args(p: argparse.ArgumentParser, what: str) -> None:
    """``--scheduler``, ``--workers``, ``--dashboard`` and ``--resume``: where the points of ``what`` run."""
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        default=None,
        help="address of a running dask.distributed scheduler (default: a local cluster)",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        metavar="N",
        help="worker processes of the local cluster (default: one per core)",
    )
    p.add_argument(
        "--dashboard",
        action="store_true",
        help="start the local cluster's Dask dashboard on 127.0.0.1 and print its address "
        "(default: none)",
    )
    p.add_argument("--resume", action="store_true", help=f"continue {what}, skip finished points")


def check_dask_args(args: argparse.Namespace) -> None:
    """One-line errors for ``--workers`` below 1, or ``--workers``/``--dashboard`` with ``--scheduler``."""
    from foilbearing.errors import InputError

    if args.workers is not None and args.workers < 1:
        raise InputError(f"--workers {args.workers}: expected at least 1")
    if args.workers is not None and args.scheduler is not None:
        raise InputError("--workers sets the local cluster's size; with --scheduler leave it out")
    if args.dashboard and args.scheduler is not None:
        raise InputError(
            "--dashboard starts the local cluster's; with --scheduler use that scheduler's own"
        )


def parse_list(text: str, kind: str, field: str) -> list[float]:
    """Parse "0,50,100,150V" or "10000rpm,50000rpm" into SI floats.

    A unit written on the last item applies to bare numbers before it.
    """
    from foilbearing.errors import InputError
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


def positive_quantity(text: str, kind: str, field: str, what: str, *, zero: bool = False) -> float:
    """The quantity ``text`` in SI, > 0 (``zero``: >= 0), else a one-line error.

    ``what`` names it in the message, e.g. "--speed = '-5rpm': a speed must be > 0".
    """
    from foilbearing.errors import InputError
    from foilbearing.units import parse_quantity

    value = parse_quantity(text, kind, field=field)
    if not (value >= 0.0 if zero else value > 0.0):
        raise InputError(f"{field} = {text!r}: {what} must be {'>=' if zero else '>'} 0")
    return value


def positive_list(text: str, kind: str, field: str, what: str) -> list[float]:
    """:func:`parse_list` with every value > 0, else a one-line error naming ``what``."""
    from foilbearing.errors import InputError

    values = parse_list(text, kind, field)
    if not all(v > 0.0 for v in values):
        raise InputError(f"{field} = {text!r}: {what} must be > 0")
    return values


def voltage_list(text: str, case: Case, field: str = "--voltage") -> list[float]:
    """Voltages, V, from ``text`` (see :func:`parse_list`) within 0 to the case's ``max_voltage``.

    The one-line error names the option, not the case file; a case without
    ``[actuators]`` gets only the parse (the caller says what it needs).
    """
    from foilbearing.errors import InputError

    values = parse_list(text, "voltage", field)
    if case.actuators is not None:
        top = case.actuators.max_voltage
        if not all(0.0 <= v <= top for v in values):
            raise InputError(f"{field} = {text!r}: allowed 0 to {top:g} V (max_voltage)")
    return values


#: The kinds of bearing (``Case.kind``) in words, for the messages.
_KIND_WORDS = {
    "GFB": "passive gas foil bearing",
    "shimmed GFB": "shimmed gas foil bearing",
    "rigid": "rigid gas bearing",
}


def refuse_without_actuators(case: Case, option: str, text: Any = None) -> None:
    """A one-line error when ``option`` (a voltage, a voltage program) is given for a case
    without ``[actuators]``: such a bearing has no voltage, and 0 V would not make it one.

    Nothing happens for a C-GFB.
    """
    from foilbearing.errors import InputError

    if case.actuators is not None:
        return
    given = option if text is None else f"{option} {text!r}"
    raise InputError(
        f"{given}: this case is a {_KIND_WORDS.get(case.kind, case.kind)} with no [actuators], "
        f"so it has no voltage to set (0 V is a C-GFB's stack at rest, another bearing); "
        f"drop {option}",
        source=case.source,
    )


def refuse_run_options(args: argparse.Namespace, options: Sequence[tuple[str, str]]) -> None:
    """A one-line error for the first of ``options`` (destination, as written) given with
    ``--resume``: a resumed run continues the recorded run, so an option that would shape
    it (its case, speeds, voltages, load, steps) is refused rather than silently ignored.

    An option counts as given when its value is not None and not empty (these options
    default to None, or to an empty list for a repeated one).
    """
    from foilbearing.errors import InputError

    for dest, written in options:
        value = getattr(args, dest, None)
        if value is None or value == []:
            continue
        shown = " ".join(value) if isinstance(value, list) else value
        if written.isupper():  # the positional file
            raise InputError(
                f"--resume continues the recorded run on the case it recorded; leave out "
                f"{written} ({shown}), or start a new run to use it"
            )
        raise InputError(
            f"--resume continues the recorded run; start a new run to change {written} "
            f"(given: {written} {shown})"
        )


def print_fields(obj: dict[str, Any]) -> None:
    """Print ``obj`` as aligned ``key  value`` lines on stdout (the commands' text output),
    numbers and lists of numbers to six significant digits (``--json`` has them whole)."""
    for key, value in obj.items():
        print(f"  {key:<28} {_shown(value)}")


def _shown(value: Any) -> str:
    """A field's value as :func:`print_fields` prints it."""
    if isinstance(value, float):
        return format(value, ".6g")
    if isinstance(value, list | tuple):  # nested too: the sub-synchronous intervals
        return "[" + ", ".join(_shown(v) for v in value) + "]"
    return str(value)


def emit(obj: dict[str, Any]) -> None:
    """Print ``obj`` as one indented JSON object on stdout (see :func:`strict_json`)."""
    print(strict_json(obj))


def strict_json(obj: Any) -> str:
    """``obj`` as indented, strict JSON: arrays as lists, paths as text, and a value that
    is not finite (NaN, ±inf: "not defined here") as ``null``, since ``NaN`` and
    ``Infinity`` are not JSON and a strict reader refuses the whole document."""
    return json.dumps(_finite(obj), indent=2, allow_nan=False)


def _finite(x: Any) -> Any:
    if isinstance(x, float):
        return x if math.isfinite(x) else None
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_finite(v) for v in x]
    if isinstance(x, Path):
        return str(x)
    if hasattr(x, "tolist"):  # NumPy arrays and scalars
        return _finite(x.tolist())
    if x is None or isinstance(x, (str, int)):
        return x
    raise TypeError(f"not JSON serialisable: {type(x).__name__}")


#: The errors of a write that the storage refused: full, read-only, no permission, quota.
STORAGE_ERRNOS = frozenset(
    {errno.ENOSPC, errno.EROFS, errno.EACCES, errno.EPERM, errno.EDQUOT, errno.EIO, errno.EFBIG}
)


def add_overwrite_arg(p: argparse.ArgumentParser) -> None:
    """``--overwrite``: replace an existing ``--out`` file (refused without it)."""
    p.add_argument(
        "--overwrite", action="store_true", help="replace an existing --out file (default: refuse)"
    )


class Output:
    """An output file reserved for this run (:func:`claim_output`), written atomically.

    A write that the storage refuses (full, read-only) does not end the run: it is
    recorded in :attr:`failure` (one line), the file there stays as it was, and the
    command still reports its result; :func:`guard_outputs` then exits with 3.
    """

    def __init__(self, path: Path, option: str) -> None:
        self.path, self.option = path, option
        self.failure: str | None = None

    def write(self, writer: Callable[[Path], object]) -> bool:
        """``writer(tmp)`` moved over :attr:`path`; False (and :attr:`failure` set) on an
        ``OSError``. A later write that succeeds clears an earlier failure (a checkpoint)."""
        from foilbearing.io import write_with

        try:
            write_with(self.path, writer)
        except OSError as exc:
            kept = "; the file there is unchanged" if self.path.exists() else ""
            self.failure = f"{self.option} {self.path} not written: {_reason(exc)}{kept}"
            return False
        self.failure = None
        return True

    def write_text(self, text: str) -> bool:
        """:meth:`write` of UTF-8 ``text``."""
        return self.write(lambda tmp: tmp.write_text(text, encoding="utf-8"))


def _reason(exc: OSError) -> str:
    return exc.strerror or str(exc) or type(exc).__name__


def claim_output(
    args: argparse.Namespace,
    path: Path | str | None,
    *,
    option: str = "--out",
    may_exist: bool = False,
) -> Output | None:
    """Reserve ``path`` for this run before any work starts (None: no output asked for).

    The output is checked and reserved (:func:`foilbearing.io.reserve`): a folder that
    cannot be written, an output another run is writing, or, unless ``may_exist`` (a
    resumed run's own file, a results folder) or ``--overwrite``, an existing file are
    refused in one line. The reservation ends when the command does
    (:func:`guard_outputs`).

    Raises
    ------
    InputError
        One line naming the file and what to do.
    """
    from foilbearing.errors import InputError
    from foilbearing.io import OutputBusy, reserve

    if path is None:
        return None
    path = Path(path)
    if path.is_dir() and not may_exist:
        raise InputError(f"{option} {path} is a folder: give a file name")
    try:
        reservation = reserve(path)
    except OutputBusy as exc:
        raise InputError(
            f"{option} {path} is being written by another run ({exc.holder}): wait for it, "
            f"or give another {option}"
        ) from None
    except OSError as exc:
        folder = path.parent if str(path.parent) else Path(".")
        raise InputError(f"{option} {path}: cannot write in {folder}: {_reason(exc)}") from None
    _reservations(args).append(reservation)
    if path.exists() and not may_exist and not getattr(args, "overwrite", False):
        raise InputError(f"{option} {path} exists: give --overwrite to replace it")
    output = Output(path, option)
    _outputs(args).append(output)
    return output


def check_plot_folder(folder: Path | str) -> None:
    """A one-line error, before any work, when the figures cannot be written in ``folder``
    (``--plot DIR``): a file in its place or in its path, or a folder that cannot be
    written (read-only, no permission). A folder still to be made is not made here: the
    nearest one that exists is tried, with a probe file created and removed at once.

    Raises
    ------
    InputError
        One line naming ``--plot``, the folder and what is wrong.
    """
    import os
    import tempfile

    from foilbearing.errors import InputError

    folder = Path(folder)
    existing = folder
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        where = "is a file" if existing == folder else f"is under {existing}, a file"
        raise InputError(f"--plot {folder} {where}: give a folder for the figures")
    try:
        fd, probe = tempfile.mkstemp(prefix=".foilbearing-probe-", dir=existing)
    except OSError as exc:
        raise InputError(
            f"--plot {folder}: cannot write figures in {existing}: {_reason(exc)}"
        ) from None
    os.close(fd)
    os.unlink(probe)


def _reservations(args: argparse.Namespace) -> list[Any]:
    if not hasattr(args, "_reservations"):
        args._reservations = []
    return args._reservations


def _outputs(args: argparse.Namespace) -> list[Output]:
    if not hasattr(args, "_outputs"):
        args._outputs = []
    return args._outputs


def guard_outputs(cmd: Callable[[argparse.Namespace], int]) -> Callable[[argparse.Namespace], int]:
    """Run the command ``cmd``, then release the outputs it reserved (:func:`claim_output`).

    An output whose last write failed, or a write the storage refused anywhere in the
    command (a results folder's point, a figure), ends it with one line on stderr and
    exit code 3, after the command has printed its result; what was finished stays.
    """

    @functools.wraps(cmd)
    def run(args: argparse.Namespace) -> int:
        try:
            code = cmd(args)
        except OSError as exc:
            if exc.errno not in STORAGE_ERRNOS:
                raise
            claimed = [str(r.target) for r in _reservations(args)]
            where = f" {exc.filename}" if exc.filename else f" in {', '.join(claimed)}"
            where = "" if where == " in " else where
            print(
                f"foilbearing: error: cannot write{where}: {_reason(exc)}; "
                "what was finished before is kept",
                file=sys.stderr,
            )
            return 3
        finally:
            for reservation in _reservations(args):
                reservation.release()
            args._reservations = []
        failures = [o.failure for o in _outputs(args) if o.failure]
        args._outputs = []
        if failures:
            print(f"foilbearing: error: {'; '.join(failures)}", file=sys.stderr)
            return 3
        return code

    return run
