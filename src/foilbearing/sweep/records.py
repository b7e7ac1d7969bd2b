"""The results folder of a sweep or sample: its manifest and point records, checked as read.

A results folder holds ``sweep.json`` (the manifest: the fingerprint of the sweep and
what it was made of) and ``points/NNNNNN.json``, one record per finished point. Both
are read back on ``--resume`` and ``--assemble``; nothing read is trusted:

- the manifest defines the sweep, so a missing or damaged one is an
  :class:`~foilbearing.errors.InputError` (it cannot be guessed from the points);
- a damaged point record (not JSON, empty or cut short, a missing key, a value of the
  wrong type or not finite, an index or parameters that are not the point's of this
  sweep) is set aside as ``NNNNNN.json.damaged`` and computed again on ``--resume``
  (points are pure functions of the manifest, so the new record is the one that was
  lost), with one line saying so; when nothing is to be computed (``--assemble``, a
  summary) it is an ``InputError`` naming the file and what is wrong;
- a JSON file in ``points/`` that is no point of this sweep (another name, an index
  beyond the grid) is an ``InputError``: it is not ours to move.

Records written by earlier versions for a point lost to the Dask cluster
(``KilledWorker``, no ``elapsed_s``) are not results: they are removed and the point is
computed again.

The manifest records the case the points start from as data (``base_case``, a
:class:`~foilbearing.case.record.CaseRecord`: the case's tables before the swept values
are written in, their sha256, and that of the case file's own case). A sweep's points
must all come from one case, so a folder whose recorded case is not the one the files
give now is not resumed (:func:`case_change`); manifests of earlier versions, without
it, resume as before.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
import re
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from foilbearing.case.record import CaseRecord, case_to_dict, file_digest, table_differences
from foilbearing.case.toml import case_from_dict
from foilbearing.errors import InputError
from foilbearing.sweep.analyses import FLAG_KEYS, TEXT_KEYS

__all__ = [
    "MANIFEST",
    "base_record",
    "case_change",
    "done_points",
    "notice",
    "point_file",
    "point_problem",
    "read_manifest",
    "same_sweep",
    "stored_fingerprint",
]

#: The manifest's file name in a results folder.
MANIFEST = "sweep.json"
_POINT_NAME = re.compile(r"^(\d{6})\.json$")
_FINGERPRINT = re.compile(r"^[0-9a-f]{64}$")
#: Keys of every point record (``run_point`` and the runner write them).
RECORD_KEYS = ("index", "status", "error", "result", "elapsed_s", "parameters")
#: What earlier versions stored when the cluster, not the point, failed.
_LEGACY_LOST = ("KilledWorker", "CancelledError", "FutureCancelledError", "TimeoutError")


def notice(message: str) -> None:
    """One line on stderr about the results folder (a point set aside, a point lost)."""
    print(f"foilbearing: {message}", file=sys.stderr, flush=True)


def point_file(folder: Path, index: int) -> Path:
    """The record of point ``index`` in results folder ``folder``."""
    return folder / "points" / f"{index:06d}.json"


#: What a file cut short leaves after the place its parse fails: nothing, or part of one
#: number or literal (``1.5e``, ``-``, ``tr``). A cut anywhere else (inside a string, between
#: tokens) is an unterminated string or ends at the end of the text.
_PARTIAL_TOKEN = re.compile(r"[-+.0-9eE]*|[a-z]*")


def _reject_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a finite number")


def _load_json(path: Path) -> tuple[Any, str | None]:
    """The JSON document of ``path``, or what makes it unreadable (one line)."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        return None, f"cannot read it ({exc.strerror or exc})"
    if not raw.strip():
        return None, "the file is empty"
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        return None, "not JSON text (bytes that are not UTF-8)"
    try:
        return json.loads(text, parse_constant=_reject_constant), None
    except json.JSONDecodeError as exc:
        short = exc.msg.startswith("Unterminated") or (
            exc.msg != "Extra data" and _PARTIAL_TOKEN.fullmatch(text[exc.pos :].rstrip())
        )
        cut = " (cut short?)" if short else ""
        return None, f"not valid JSON{cut}: {exc.msg} at line {exc.lineno} column {exc.colno}"
    except ValueError as exc:
        return None, f"not valid JSON: {exc}"


def read_manifest(folder: Path) -> dict[str, Any]:
    """The manifest of results folder ``folder``, checked (a fingerprint of 64 hex digits).

    Raises
    ------
    InputError
        Missing, unreadable or damaged: it defines the sweep and is never guessed.
    """
    path = folder / MANIFEST
    if not path.exists():
        n = len(list((folder / "points").glob("*.json")))
        raise InputError(
            f"{path} is missing, yet {folder / 'points'} holds {n} point file(s): the manifest "
            "says which sweep they belong to and cannot be guessed; restore it, or move "
            f"{folder} aside and run the sweep again"
        )
    data, problem = _load_json(path)
    if problem is None and not isinstance(data, dict):
        problem = "expected a JSON object"
    elif problem is None:
        fp = data.get("fingerprint")
        if not isinstance(fp, str) or not _FINGERPRINT.match(fp):
            problem = f"fingerprint = {fp!r}: expected 64 hexadecimal digits"
        elif "base_case" in data:
            try:
                CaseRecord.from_dict(data["base_case"])
            except ValueError as exc:
                problem = f"base_case: {exc}"
    if problem is not None:
        raise InputError(
            f"damaged manifest: {problem}; it defines the sweep and cannot be guessed: restore "
            f"it, or move {folder} aside and run the sweep again",
            source=str(path),
        )
    return data


def stored_fingerprint(folder: Path) -> str | None:
    """The fingerprint of the sweep whose results ``folder`` holds (None: none readable)."""
    try:
        return str(read_manifest(folder)["fingerprint"])
    except InputError:
        return None


def base_record(points: Any) -> CaseRecord:
    """The case the points of a sweep or sample start from, as data.

    ``points`` has ``base`` (the case file's tables with the fixed ``[set]`` edits, before
    any point's values are written in) and ``case_file`` (the file they were read from);
    the record's ``file_sha256`` is the digest of that file's own case.
    """
    case = case_from_dict(copy.deepcopy(points.base), source=str(points.case_file))
    return CaseRecord(case_to_dict(case), file_digest(str(points.case_file)))


def case_change(manifest: Mapping[str, Any], points: Any, folder: Path) -> str | None:
    """One line saying how the case ``points`` start from differs from the one recorded in
    ``manifest`` (read by :func:`read_manifest`), or None: the same case, or a manifest of
    an earlier version that recorded none.

    The fields named are those where the case now differs from the recorded one; the line
    says what to do (a new ``--out`` for the edited case, or restore the file).
    """
    data = manifest.get("base_case")
    if data is None:
        return None
    recorded = CaseRecord.from_dict(data)
    now = base_record(points)
    if now.sha256 == recorded.sha256:
        return None
    diffs = table_differences(recorded.tables, now.tables)
    shown = "; ".join(f"{k}: {a} recorded, {b} now" for k, a, b in diffs[:3])
    more = f" and {len(diffs) - 3} more" if len(diffs) > 3 else ""
    if recorded.file_sha256 is not None and now.file_sha256 != recorded.file_sha256:
        what, restore = f"case file {points.case_file}", "restore the file"
    else:
        what, restore = f"the case of {points.source} (its [set] table)", "restore the table"
    return (
        f"{what} has changed since the run in {folder} started ({shown}{more}): its points "
        f"must all come from one case; give a new --out to run the edited case, or {restore} "
        "to resume"
    )


def same_sweep(manifest: Mapping[str, Any], points: Any) -> bool:
    """Whether ``manifest`` (read by :func:`read_manifest`) is of the sweep or sample
    ``points``, whose case :func:`case_change` found unchanged.

    The same fingerprint; or, for a manifest that records its case, the same once the
    case's tables as written when the run started (``case``) are put back: the case file
    was edited without changing the case (a value written another way that reads to the
    same float), and the points computed now are those of the recorded case.
    """
    if manifest["fingerprint"] == points.fingerprint():
        return True
    written = manifest.get("case")
    if "base_case" not in manifest or not isinstance(written, dict):
        return False
    if not dataclasses.is_dataclass(points) or isinstance(points, type):
        return False
    as_written: Any = dataclasses.replace(points, base=written)
    return bool(as_written.fingerprint() == manifest["fingerprint"])


def _finite_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)


def _value_problem(key: str, v: Any) -> str | None:
    """What is wrong with result value ``v`` of ``key`` (None: nothing).

    Words only under :data:`TEXT_KEYS`, true/false only under :data:`FLAG_KEYS`, finite
    numbers (or null) elsewhere, as scalars or lists; a table (an uncertainty point's
    ``outputs``) holds numbers.
    """
    if v is None:
        return None
    if key in TEXT_KEYS:
        return None if isinstance(v, str) else f"result.{key} = {v!r}: expected text"
    if isinstance(v, dict):
        for k, x in v.items():
            if x is not None and not _finite_number(x):
                return f"result.{key}[{k!r}] = {x!r}: expected a finite number or null"
        return None
    want, ok = (
        ("true or false", lambda x: isinstance(x, bool))
        if key in FLAG_KEYS
        else ("a finite number", _finite_number)
    )
    items = v if isinstance(v, list) else [v]
    for x in items:
        if x is not None and not ok(x):
            return f"result.{key} = {v!r}: expected {want} or null" + (
                " in each place" if isinstance(v, list) else ""
            )
    return None


def point_problem(rec: Any, index: int, parameters: Mapping[str, Any] | None) -> str | None:
    """What makes ``rec`` no valid record of point ``index`` (None: it is one).

    ``parameters`` are the point's values as this sweep writes them (None: unchecked).
    """
    if not isinstance(rec, dict):
        return f"expected a JSON object (a point record), not {type(rec).__name__}"
    missing = [k for k in RECORD_KEYS if k not in rec]
    if missing:
        return f"missing key(s) {', '.join(missing)}"
    i = rec["index"]
    if isinstance(i, bool) or not isinstance(i, int) or i != index:
        return f"index = {i!r}, but the file is point {index}'s"
    if rec["status"] not in ("ok", "failed"):
        return f"status = {rec['status']!r}: expected 'ok' or 'failed'"
    if not isinstance(rec["error"], str):
        return f"error = {rec['error']!r}: expected text"
    elapsed = rec["elapsed_s"]
    if elapsed is not None and not (_finite_number(elapsed) and elapsed >= 0.0):
        return f"elapsed_s = {elapsed!r}: expected a time >= 0 s"
    result = rec["result"]
    if not isinstance(result, dict):
        return f"result = {result!r}: expected a table of values"
    for key, v in result.items():
        problem = _value_problem(key, v)
        if problem is not None:
            return problem
    if parameters is not None and rec["parameters"] != parameters:
        got = rec["parameters"]
        if not isinstance(got, dict):
            return f"parameters = {got!r}: expected a table"
        for name, want in parameters.items():
            if got.get(name) != want:
                return f"parameters.{name} = {got.get(name)!r}: point {index} has {want!r}"
        return f"parameters {sorted(got)}: point {index} has {sorted(parameters)}"
    return None


def _legacy_lost(rec: Any) -> bool:
    """A record an earlier version stored for a point the cluster lost: not a result."""
    return (
        isinstance(rec, dict)
        and rec.get("status") == "failed"
        and "elapsed_s" not in rec
        and str(rec.get("error", "")).startswith(_LEGACY_LOST)
    )


def done_points(
    folder: Path, points: Any = None, *, set_aside: bool = False
) -> dict[int, dict[str, Any]]:
    """The valid point records of results folder ``folder``, by index.

    Parameters
    ----------
    folder
        The results folder (``RESULT.d``, an uncertainty run's folder).
    points
        The sweep or sample (a :class:`~foilbearing.sweep.runner.PointSet`): each record's
        index must be one of its points and its parameters that point's (None: unchecked).
    set_aside
        A damaged record is renamed ``*.damaged``, with one line on stderr, and left
        out (its point is computed again); without it, damage is an ``InputError``.

    Raises
    ------
    InputError
        A file in ``points/`` that is no point of the sweep, or (without ``set_aside``)
        a damaged record: the message names the file and what is wrong.
    """
    done: dict[int, dict[str, Any]] = {}
    n_points = None if points is None else points.n_points
    for f in sorted((folder / "points").glob("*.json")):
        m = _POINT_NAME.match(f.name)
        if m is None or (n_points is not None and int(m.group(1)) >= n_points):
            allowed = (
                "NNNNNN.json" if n_points is None else f"000000.json to {n_points - 1:06d}.json"
            )
            raise InputError(
                f"not a point of this sweep (point files are {allowed}): move it out of "
                f"{folder / 'points'}",
                source=str(f),
            )
        index = int(m.group(1))
        rec, problem = _load_json(f)
        if problem is None and _legacy_lost(rec):
            if set_aside:
                notice(f"point {index} was lost to the cluster ({rec['error']}): computed again")
                f.unlink()
                continue
            problem = f"point lost to the cluster ({rec['error']}), not a result"
        if problem is None:
            expected = None
            if points is not None:
                expected = json.loads(json.dumps(points.point_values(index), default=str))
            problem = point_problem(rec, index, expected)
        if problem is None:
            done[index] = rec
            continue
        if not set_aside:
            raise InputError(
                f"damaged point record: {problem}; run again with --resume to set it aside "
                "and compute the point again",
                source=str(f),
            )
        f.replace(f.with_name(f.name + ".damaged"))
        notice(
            f"{f}: damaged point record ({problem}): set aside as {f.name}.damaged, computed again"
        )
    return done
