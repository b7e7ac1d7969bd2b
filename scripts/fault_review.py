"""Re-run the fault table of issue 48 through the command line and print what survives.

Each fault of the issue's table is provoked again, in a temporary folder, on the command
line as a user meets it (``python -m foilbearing ...`` in a subprocess, on a coarse 32 x 4
grid with runs of a few revolutions), and each trial records:

- the exit code, and whether stderr is one line (a fault the user must act on is one line
  naming the file or field; exit 2 for bad input, 3 for a failed write);
- whether a Python traceback reached the user;
- whether data was lost: a finished point, checkpoint or result gone or changed, a damaged
  file rewritten, or a run that ends on a silently wrong result (a resume off the
  uninterrupted run by more than 1e-3 C, a zero load not centred, NaN in JSON).

It prints a markdown table (fault | tried | as intended | one-line errors | tracebacks |
data-loss events) and the totals; ``--verbose`` prints each trial's stderr too. A read-only
folder is a read-only tmpfs mount where the process may mount (root in a container), else
an immutable folder (``chattr +i``), else a ``chmod 555`` folder (a user other than root);
the same tiny tmpfs, full, gives the disk-full row. Rows that cannot be provoked here say
so. A Dask worker lost for good (``KilledWorker``) is not re-run: killing a worker at a
chosen point takes the test suite's hook (``tests/test_sweep_records.py``).

Usage (from the repository root; 12 minutes on 2 busy cores, the kernels compiled)::

    PYTHONPATH=src python scripts/fault_review.py [--verbose]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import tomlkit
import xarray as xr

from foilbearing.case import default_case_path
from foilbearing.io import lock_path

ROOT = Path(__file__).resolve().parent.parent
#: A coarse, short orbit: 4 revolutions at 12 krpm (16 steps a revolution), stopped after 2.
RUN = ["--speed", "12000rpm", "--duration", "0.02s", "--steps-per-rev", "16"]
STOP = ["--stop-time", "0.01s"]
#: A run long enough for a second one to start while it runs (60 revolutions).
LONG = ["--speed", "12000rpm", "--duration", "0.3s", "--steps-per-rev", "16"]
CLEARANCE = 100e-6  # m, the default case's
#: A stability sweep of two points on 24 x 4 (its result holds onset_speed_rpm).
SWEEP = """analysis = "stability"
[set]
grid.n_theta = 24
grid.n_z = 4
[stability]
speed_range = ["20000 rpm", "140000 rpm", "20000 rpm"]
[parameters]
"actuators.voltages" = ["0 V", "150 V"]
"""


@dataclass
class Trial:
    """One provocation of a fault and what the user saw."""

    what: str
    rc: int
    err: str
    expect_error: bool
    lost: bool = False
    wrong: str = ""

    @property
    def one_line(self) -> bool:
        return len(self.err.strip().splitlines()) == 1

    @property
    def traceback(self) -> bool:
        return "Traceback (most recent call last)" in self.err

    @property
    def as_intended(self) -> bool:
        if self.traceback or self.lost or self.wrong:
            return False
        if self.expect_error:
            return self.rc in (2, 3) and self.one_line
        return self.rc == 0


@dataclass
class Fault:
    name: str
    trials: list[Trial] = field(default_factory=list)
    note: str = ""


def cli(*argv: str, cwd: Path | None = None, timeout: float = 600.0) -> tuple[int, str, str]:
    """``python -m foilbearing argv`` with this checkout's source: (rc, stdout, stderr)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "FOILBEARING_COMPILE_NOTICE": "0"}
    p = subprocess.run(
        [sys.executable, "-m", "foilbearing", *argv],
        capture_output=True,
        text=True,
        env=env,
        cwd=cwd,
        timeout=timeout,
    )
    return p.returncode, p.stdout, p.stderr


def write_case(
    folder: Path, edit: Callable[[Any], None] | None = None, name: str = "c", n_theta: int = 32
) -> Path:
    """The default case on n_theta x 4, with ``edit(toml document)`` applied, as
    folder/name.toml."""
    data = tomlkit.parse(default_case_path().read_text(encoding="utf-8"))
    data["grid"]["n_theta"], data["grid"]["n_z"] = n_theta, 4
    if edit is not None:
        edit(data)
    path = folder / f"{name}.toml"
    path.write_text(tomlkit.dumps(data), encoding="utf-8")
    return path


def strict_json(text: str) -> Any:
    """``json.loads`` that refuses NaN and Infinity."""

    def refuse(token: str) -> Any:
        raise ValueError(f"{token} is not JSON")

    return json.loads(text, parse_constant=refuse)


def off_by(a: Path, b: Path) -> float:
    """Largest |e_x| and |e_y| difference of two finished orbit files, in units of C."""
    x, y = xr.load_dataset(a), xr.load_dataset(b)
    if x.time.size != y.time.size:
        return float("inf")
    return float(max(np.abs(x.e_x - y.e_x).max(), np.abs(x.e_y - y.e_y).max())) / CLEARANCE


# --------------------------------------------------------------------------- read-only


@contextlib.contextmanager
def guarded_folder(where: Path, kind: str) -> Iterator[tuple[Path, str]]:
    """A folder that refuses writes (``kind`` "read-only") or a 64 kB one that fills
    ("full"), and how it was made; the how is "" when this machine cannot make one."""
    folder = where / kind
    folder.mkdir()
    how = ""
    size = "size=64k" if kind == "full" else "size=64k,ro"
    if shutil.which("mount") and os.geteuid() == 0:
        p = subprocess.run(["mount", "-t", "tmpfs", "-o", size, "tmpfs", str(folder)], check=False)
        how = f"tmpfs -o {size}" if p.returncode == 0 else ""
    if not how and kind == "read-only":
        if os.geteuid() != 0:
            folder.chmod(0o555)
            how = "chmod 555"
        elif shutil.which("chattr"):
            p = subprocess.run(["chattr", "+i", str(folder)], check=False)
            how = "chattr +i" if p.returncode == 0 else ""
    try:
        yield folder, how
    finally:
        if how.startswith("tmpfs"):
            subprocess.run(["umount", str(folder)], check=False)
        elif how == "chattr +i":
            subprocess.run(["chattr", "-i", str(folder)], check=False)
        folder.chmod(0o755)


def fill(folder: Path) -> None:
    """Fill a small file system to its last byte (a filler file written until ENOSPC)."""
    for p in folder.iterdir():
        shutil.rmtree(p) if p.is_dir() else p.unlink()
    with contextlib.suppress(OSError), open(folder / "filler", "wb") as f:
        while True:
            f.write(b"\0" * 1024)
            f.flush()


def out_into_guarded(tmp: Path, case: Path, sweep: Path) -> list[Fault]:
    commands = {
        "orbit": ["orbit", str(case), *RUN, "--json", "--out"],
        "static": ["static", str(case), "--eccentricity", "0.3,0.2", "--json", "--out"],
        "sweep": ["sweep", str(sweep), "--workers", "1", "--out"],
    }
    faults = []
    for kind in ("read-only", "full"):
        fault = Fault(f"`--out` in a {kind} folder (orbit, static, sweep)")
        with guarded_folder(tmp, kind) as (folder, how):
            if not how:
                fault.note = f"not tried: no {kind} folder can be made here"
            for name, argv in commands.items():
                if not how:
                    break
                if kind == "full":
                    fill(folder)
                out = folder / ("res" if name == "sweep" else f"{name}.nc")
                rc, stdout, err = cli(*argv, str(out))
                t = Trial(name, rc, err, expect_error=True)
                leftovers = [p.name for p in folder.iterdir()]
                if kind == "full" and name != "sweep" and rc == 3:
                    # a failed save still prints the result (--json); nothing half-written
                    t.lost = not stdout.strip() or any(n.endswith(".part") for n in leftovers)
                fault.note = fault.note or f"made by {how}"
                fault.trials.append(t)
        faults.append(fault)
    return faults


# --------------------------------------------------------------------------- orbit records


def resume_faults(tmp: Path) -> list[Fault]:
    case = write_case(tmp)
    whole, part = tmp / "whole.nc", tmp / "part.nc"
    for argv in (["--out", str(whole)], [*STOP, "--out", str(part)]):
        rc, _, err = cli("orbit", str(case), *RUN, *argv)
        assert rc == 0, err
    # The reference: the same stop resumed on the unchanged case (a stop moves the later
    # steps by part of a step, so a stopped run differs from the run in one go by its time
    # discretisation: docs/validation.md).
    reference = tmp / "reference.nc"
    shutil.copy(part, reference)
    rc, _, err = cli("orbit", "--resume", str(reference))
    assert rc == 0, err
    sampling = off_by(reference, whole)
    edited = Fault("the case file edited (clearance 100 -> 90 um) before `orbit --resume`")
    write_case(tmp, edit=lambda d: d["bearing"].update(clearance="90 um"))
    rc, _, err = cli("orbit", "--resume", str(part))
    t = Trial("resume", rc, err, expect_error=False)
    off = off_by(part, reference) if rc == 0 else float("inf")
    t.wrong = "" if off < 1e-6 else f"ends {off:.2g} C off the resume on the unchanged case"
    notes = [ln for ln in err.splitlines() if "bearing.clearance" in ln]
    t.wrong = t.wrong or ("" if len(notes) == 1 else "the edit is not reported in one line")
    edited.trials.append(t)
    edited.note = (
        f"ends {off:.1e} C off the same stop resumed on the unchanged case ({sampling:.1e} C "
        "off the run in one go: the stop's step); one line names the field"
    )
    write_case(tmp)  # restored

    held = Fault(
        "`--resume` of a run made under `--preload-response lobe --actuator-dynamics held`"
    )
    reading = ["--preload-response", "lobe", "--actuator-dynamics", "held"]
    lobe_whole, lobe_part = tmp / "lobe_whole.nc", tmp / "lobe_part.nc"
    for argv in (["--out", str(lobe_whole)], [*STOP, "--out", str(lobe_part)]):
        rc, _, err = cli("orbit", str(case), *RUN, *reading, *argv)
        assert rc == 0, err
    rc, _, err = cli("orbit", "--resume", str(lobe_part))
    t = Trial("resume", rc, err, expect_error=False)
    # Resumed under the recorded reading, it ends as near the lobe + held run in one go as
    # a stopped run does (the stop's step, above); under "local compliant" (a record
    # without the reading) it would end where the local run does.
    off = off_by(lobe_part, lobe_whole) if rc == 0 else float("inf")
    other = off_by(lobe_part, reference) if rc == 0 else float("inf")
    spec = json.loads(xr.load_dataset(lobe_part).attrs["run_spec"])
    acts = spec["recorded_case"]["tables"]["actuators"]
    recorded = (acts.get("preload_response"), acts.get("dynamics"))
    t.wrong = "" if off <= 2.0 * sampling + 1e-4 else f"ends {off:.2g} C off the lobe + held run"
    t.wrong = t.wrong or ("" if recorded == ("lobe", "held") else f"recorded {recorded}")
    held.trials.append(t)
    held.note = (
        f"record holds {recorded}; ends {off:.1e} C off the lobe + held run in one go, "
        f"{other:.1e} C off the local + compliant one"
    )

    two = Fault("two orbits on one `--out` (and `static --out` on an existing file)")
    shared = tmp / "shared.nc"
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "FOILBEARING_COMPILE_NOTICE": "0"}
    first = subprocess.Popen(
        [sys.executable, "-m", "foilbearing", "orbit", str(case), *LONG, "--out", str(shared)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    deadline = time.monotonic() + 120.0
    while not lock_path(shared).exists() and time.monotonic() < deadline:
        time.sleep(0.2)
    rc, _, err = cli("orbit", str(case), *RUN, "--out", str(shared), "--overwrite")
    two.trials.append(Trial("second orbit while the first runs", rc, err, expect_error=True))
    first.communicate(timeout=600)
    done = xr.load_dataset(shared) if shared.exists() else None
    intact = first.returncode == 0 and done is not None and done.attrs["status"] == "completed"
    two.trials[-1].lost = not intact
    before = shared.read_bytes()
    rc, _, err = cli("orbit", str(case), *RUN, "--out", str(shared))
    two.trials.append(
        Trial("orbit on the finished file", rc, err, True, shared.read_bytes() != before)
    )
    static_out = tmp / "static.nc"
    rc, _, err = cli("static", str(case), "--eccentricity", "0.3,0.2", "--out", str(static_out))
    before = static_out.read_bytes()
    rc, _, err = cli("static", str(case), "--eccentricity", "0.1,0", "--out", str(static_out))
    lost = static_out.read_bytes() != before
    two.trials.append(Trial("static on an existing file", rc, err, True, lost))
    return [edited, held, two, damaged_checkpoints(tmp, part)]


def _set(name: str, change: Callable[[np.ndarray], np.ndarray]) -> Callable[[xr.Dataset], None]:
    def apply(ds: xr.Dataset) -> None:
        values = change(np.array(ds[name].values, float))
        ds[name] = (ds[name].dims[0], values)

    return apply


def _at(i: int, value: float) -> Callable[[np.ndarray], np.ndarray]:
    def change(a: np.ndarray) -> np.ndarray:
        a[i] = value
        return a

    return change


def damaged_checkpoints(tmp: Path, finished: Path) -> Fault:
    """Damage a stopped run's file (re-made from the finished one's case) and resume it."""
    case = write_case(tmp, name="ckpt")
    stopped = tmp / "stopped.nc"
    rc, _, err = cli("orbit", str(case), *RUN, *STOP, "--out", str(stopped))
    assert rc == 0, err
    damage: dict[str, Callable[[xr.Dataset], None]] = {
        "NaN state": _set("checkpoint_y", _at(3, np.nan)),
        "NaN past state": _set("checkpoint_y_prev", _at(0, np.nan)),
        "garbage state (1e300)": _set("checkpoint_y", _at(1, 1e300)),
        "short state": _set("checkpoint_y", lambda a: a[:-5]),
        "negative step": _set("checkpoint_h_prev", lambda a: -a),
        "infinite sample": _set("e_x", _at(2, np.inf)),
        "cut run_spec": lambda ds: ds.attrs.update(run_spec=ds.attrs["run_spec"][:400]),
        "garbage run_spec": lambda ds: ds.attrs.update(run_spec="\x8f\xff not json"),
        "unknown status": lambda ds: ds.attrs.update(status="paused"),
        "checkpoint_t beyond the end": _set("checkpoint_t", lambda a: a + 1.0),
        "checkpoint_t before the samples": _set("checkpoint_t", lambda a: a * 0.5),
    }
    fault = Fault("damaged orbit checkpoints, then `orbit --resume`")
    for what, apply in damage.items():
        ds = xr.load_dataset(stopped)
        apply(ds)
        path = tmp / "damaged.nc"
        ds.to_netcdf(path)
        before = path.read_bytes()
        rc, _, err = cli("orbit", "--resume", str(path))
        t = Trial(what, rc, err, expect_error=True, lost=path.read_bytes() != before)
        t.wrong = "" if str(path) in err else "the message does not name the file"
        fault.trials.append(t)
        path.unlink()
    garbage = tmp / "garbage.nc"
    garbage.write_bytes(os.urandom(4096))
    rc, _, err = cli("orbit", "--resume", str(garbage))
    fault.trials.append(Trial("random bytes for a file", rc, err, expect_error=True))
    return fault


# --------------------------------------------------------------------------- sweep records


def sweep_faults(tmp: Path) -> tuple[Path, Fault]:
    """Run the two-point sweep once, then damage copies of its results folder."""
    sweep = tmp / "sweep.toml"
    sweep.write_text(SWEEP, encoding="utf-8")
    rc, _, err = cli("sweep", str(sweep), "--workers", "1", "--out", str(tmp / "res"), cwd=tmp)
    assert rc == 0, err
    finished = tmp / "res.d"
    good = json.loads((finished / "points" / "000001.json").read_text(encoding="utf-8"))

    def edit(change: Callable[[dict[str, Any]], None]) -> Callable[[str], str]:
        def apply(text: str) -> str:
            rec = json.loads(text)
            change(rec)
            return json.dumps(rec, indent=1)

        return apply

    point_damage: dict[str, Callable[[str], str]] = {
        "truncated": lambda t: t[: len(t) // 2],
        "empty": lambda t: "",
        "random bytes": lambda t: b"\x8f\xff\x00\x13\xfe binary".decode("latin-1"),
        "missing key (status)": edit(lambda r: r.pop("status")),
        "missing key (result)": edit(lambda r: r.pop("result")),
        'onset_speed_rpm: "fast"': edit(lambda r: r["result"].update(onset_speed_rpm="fast")),
        "NaN onset": lambda t: t.replace('"onset_speed_rpm": ', '"onset_speed_rpm": NaN, "x": '),
    }
    fault = Fault("damaged sweep files, then `sweep --assemble` (and `--resume`)")
    run = tmp / "run"
    for what, damage in point_damage.items():
        for flag in (
            ("--assemble", "--resume") if what == 'onset_speed_rpm: "fast"' else ("--assemble",)
        ):
            shutil.rmtree(run, ignore_errors=True)
            run.mkdir()
            shutil.copy(sweep, run / "sweep.toml")
            shutil.copytree(finished, run / "res.d")
            path = run / "res.d" / "points" / "000001.json"
            path.write_text(damage(path.read_text(encoding="utf-8")), encoding="latin-1")
            damaged = path.read_bytes()
            argv = ["sweep", str(run / "sweep.toml"), "--out", str(run / "res"), flag]
            rc, _, err = cli(*argv, *(["--workers", "1"] if flag == "--resume" else []))
            if flag == "--assemble":
                t = Trial(f"{what} ({flag})", rc, err, True, lost=path.read_bytes() != damaged)
            else:  # set aside and computed again: rc 0, the point as it was
                t = Trial(f"{what} ({flag})", rc, err, expect_error=False)
                again = json.loads(path.read_text(encoding="utf-8")) if path.exists() else {}
                ok = again.get("result", {}).get("onset_speed_rpm") == good["result"].get(
                    "onset_speed_rpm"
                )
                kept = path.with_name("000001.json.damaged").read_bytes() == damaged
                t.lost = not (ok and kept)
                ds = xr.load_dataset(run / "res.nc")
                t.wrong = "" if ds["onset_speed_rpm"].dtype.kind == "f" else "strings assembled"
            t.wrong = t.wrong or ("" if str(path) in err else "the message does not name the file")
            fault.trials.append(t)
    for what in ("stray JSON (notes.json)", "deleted sweep.json", "cut sweep.json"):
        shutil.rmtree(run, ignore_errors=True)
        run.mkdir()
        shutil.copy(sweep, run / "sweep.toml")
        shutil.copytree(finished, run / "res.d")
        points = run / "res.d" / "points"
        manifest = run / "res.d" / "sweep.json"
        if what.startswith("stray"):
            (points / "notes.json").write_text(json.dumps(good), encoding="utf-8")
        elif what.startswith("deleted"):
            manifest.unlink()
        else:
            manifest.write_text(manifest.read_text(encoding="utf-8")[:40], encoding="utf-8")
        before = sorted((p.name, p.read_bytes()) for p in points.iterdir())
        rc, _, err = cli("sweep", str(run / "sweep.toml"), "--out", str(run / "res"), "--assemble")
        t = Trial(
            what,
            rc,
            err,
            True,
            sorted((p.name, p.read_bytes()) for p in points.iterdir()) != before,
        )
        t.wrong = "called another sweep" if "another sweep" in err else ""
        fault.trials.append(t)
    return sweep, fault


# --------------------------------------------------------------------------- inputs, edges


def input_faults(tmp: Path) -> list[Fault]:
    # 48 cells: the three lobes (120 deg apart) fall alike on the grid, so the unloaded
    # film is symmetric under a turn of 120 deg and its force at the centre is zero.
    zero = write_case(tmp, lambda d: d["operation"].update(load="0 N"), "zero", n_theta=48)
    fault = Fault('`operation.load = "0 N"` (allowed: a centred journal)')
    rc, out, err = cli("static", str(zero), "--json")
    t = Trial("static", rc, err, expect_error=False)
    if rc == 0:
        r = strict_json(out)
        t.wrong = (
            ""
            if r["converged"] and r["eccentricity"] < 1e-6
            else f"eccentricity {r['eccentricity']}"
        )
    fault.trials.append(t)
    for argv in (
        ["orbit", *RUN, "--json"],
        ["stability", "--voltage", "0V", "--speed-range", "20000rpm:140000rpm:20000rpm", "--json"],
        ["coefficients", "--json"],
    ):
        rc, out, err = cli(argv[0], str(zero), *argv[1:])
        fault.trials.append(Trial(argv[0], rc, err, expect_error=False))
        if rc == 0:
            with contextlib.suppress(ValueError):
                strict_json(out)
                continue
            fault.trials[-1].wrong = "not strict JSON"
    faults = [fault]
    bad = {
        "lengths of 1e-300 m, a clearance of 1e-12 m": [
            ("bearing", "radius", "1e-300 m"),
            ("bearing", "length", "1e-300 m"),
            ("bearing", "clearance", "1e-12 m"),
        ],
        '`ambient_pressure = "1e300 Pa"`': [("gas", "ambient_pressure", "1e300 Pa")],
        '`loss_factor = "0.1 deg"`': [("foil", "loss_factor", "0.1 deg")],
    }
    for name, edits in bad.items():
        fault = Fault(name)
        for table, key, value in edits:
            path = write_case(tmp, lambda d, t=table, k=key, v=value: d[t].update({k: v}), "bad")
            for command in ("case", "static"):
                argv = ["case", "show", str(path)] if command == "case" else ["static", str(path)]
                rc, _, err = cli(*argv)
                t = Trial(f"{key} = {value} ({command})", rc, err, expect_error=True)
                t.wrong = "" if f"{table}.{key}" in err or key in err else "the field is not named"
                fault.trials.append(t)
        faults.append(fault)
    case = write_case(tmp)
    fault = Fault("`static --eccentricity 0,0 --json`")
    rc, out, err = cli("static", str(case), "--eccentricity", "0,0", "--json")
    t = Trial("static", rc, err, expect_error=False)
    try:
        strict_json(out)
    except ValueError as e:
        t.wrong = str(e)
    fault.trials.append(t)
    faults.append(fault)
    shaken = write_case(tmp, lambda d: d["rotor"].update(imbalance="20000 g*mm"), "shaken")
    fault = Fault("an orbit that touches at its first sample")
    rc, out, err = cli("orbit", str(shaken), "--speed", "12000rpm", "--duration", "0.05s", "--json")
    t = Trial("orbit", rc, err, expect_error=False)
    if rc == 0:
        status = strict_json(out).get("status")
        t.wrong = "" if status == "contact" else f"status {status!r}"
    fault.trials.append(t)
    faults.append(fault)
    return faults


def table(faults: list[Fault]) -> str:
    lines = [
        "| fault | tried | as intended | one-line errors | tracebacks | data-loss events | notes |",
        "|---|---|---|---|---|---|---|",
    ]
    sums = [0, 0, 0, 0, 0, 0]
    for f in faults:
        n = len(f.trials)
        wanted = [t for t in f.trials if t.expect_error]
        row = [
            n,
            sum(t.as_intended for t in f.trials),
            sum(t.rc in (2, 3) and t.one_line for t in wanted),
            sum(t.traceback for t in f.trials),
            sum(t.lost or bool(t.wrong and not t.expect_error) for t in f.trials),
            len(wanted),
        ]
        sums = [a + b for a, b in zip(sums, row, strict=True)]
        errors = f"{row[2]}/{row[5]}" if wanted else "n/a (runs)"
        wrong = "; ".join(f"{t.what}: {t.wrong}" for t in f.trials if t.wrong)
        note = "; ".join(s for s in (f.note, wrong) if s)
        lines.append(f"| {f.name} | {n} | {row[1]}/{n} | {errors} | {row[3]} | {row[4]} | {note} |")
    n, ok, one, tb, lost, wanted_n = sums
    lines.append(f"| **total** | {n} | {ok}/{n} | {one}/{wanted_n} | {tb} | {lost} | |")
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--verbose", action="store_true", help="print each trial's stderr")
    args = parser.parse_args()
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="fault_review_") as where:
        tmp = Path(where)
        for sub in ("sweep", "guarded"):
            (tmp / sub).mkdir()
        faults = resume_faults(tmp)
        sweep, swept = sweep_faults(tmp / "sweep")
        faults += [swept]
        faults += out_into_guarded(tmp / "guarded", write_case(tmp), sweep)
        faults += input_faults(tmp)
    if args.verbose:
        for f in faults:
            for t in f.trials:
                print(f"[{f.name}] {t.what}: rc {t.rc}: {t.err.strip()[:600]}", file=sys.stderr)
    print(table(faults))
    print(f"\n{time.monotonic() - started:.0f} s; {time.strftime('%Y-%m-%d')}")
    bad = sum(t.traceback or t.lost or bool(t.wrong) for f in faults for t in f.trials)
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
