"""The rotor as data: what a rotor orbit's file records so that ``rotor --resume`` stands alone.

:func:`rotor_to_dict` writes a :class:`~foilbearing.rotor.model.RotorCase` as the
tables of a rotor file, every number an exact SI quantity string (``"0.05 m"``, read
back by a factor of 1) and each bearing's case written in full as its own tables
(:func:`foilbearing.case.record.case_to_dict`, its voltages included) in place of the
case file's name. :func:`rotor_from_dict_record` reads them back to the same rotor,
field for field, with no file needed. :class:`RotorRecord` is what a run stores: the
tables, their sha256 and the sha256 of the rotor file's own rotor (its bearing case
files read through it) when the run started, by which a resumed run tells that the
rotor file or a bearing's case file has changed since (:meth:`RotorRecord.changes`).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from foilbearing.case.record import case_digest, case_to_dict, table_differences
from foilbearing.errors import InputError
from foilbearing.rotor.model import RotorCase

__all__ = [
    "RUN_FORMAT",
    "RotorRecord",
    "read_rotor_run",
    "rotor_digest",
    "rotor_from_dict_record",
    "rotor_to_dict",
]


def _q(value: float, unit: str) -> str:
    """``value`` (SI) as the shortest string that reads back to the same float."""
    return f"{float(value)!r} {unit}"


def rotor_to_dict(rotor: RotorCase) -> dict[str, Any]:
    """The tables of a rotor file that read back to ``rotor`` (all but its ``source``),
    each bearing's ``case`` being the case's own tables (:func:`case_to_dict`).

    Parameters
    ----------
    rotor
        A validated rotor.

    Returns
    -------
    dict
        JSON types only; dimensional values as exact SI quantity strings.
    """
    return {
        "title": rotor.title,
        "gravity": _q(rotor.gravity, "m/s**2"),
        "material": {
            "density": _q(rotor.material.density, "kg/m**3"),
            "youngs_modulus": _q(rotor.material.youngs_modulus, "Pa"),
            "poisson_ratio": float(rotor.material.poisson_ratio),
        },
        "shaft": {
            "lengths": [_q(e.length, "m") for e in rotor.shaft],
            "outer_diameters": [_q(e.outer_diameter, "m") for e in rotor.shaft],
            "inner_diameters": [_q(e.inner_diameter, "m") for e in rotor.shaft],
        },
        "disks": [
            {
                "node": d.node,
                "mass": _q(d.mass, "kg"),
                "polar_inertia": _q(d.polar_inertia, "kg*m**2"),
                "diametral_inertia": _q(d.diametral_inertia, "kg*m**2"),
            }
            for d in rotor.disks
        ],
        "bearings": [
            {"node": b.node, "label": b.label, "case": case_to_dict(b.case)} for b in rotor.bearings
        ],
    }


def rotor_digest(tables: dict[str, Any]) -> str:
    """sha256 (hex) of the canonical JSON of a rotor's tables (:func:`rotor_to_dict`)."""
    return case_digest(tables)


def rotor_from_dict_record(tables: dict[str, Any], source: str | None = None) -> RotorCase:
    """The rotor of :func:`rotor_to_dict`'s tables, read through the rotor file's own
    reader (its checks) with each bearing's recorded case in place of a file.

    Raises
    ------
    InputError
        Tables that do not read as a rotor (one line).
    """
    from foilbearing.case.toml import case_from_dict
    from foilbearing.rotor.toml import rotor_from_dict

    data = copy.deepcopy(tables)
    bearings = data.get("bearings")
    if not isinstance(bearings, list) or not all(
        isinstance(b, dict) and isinstance(b.get("case"), dict) for b in bearings
    ):
        raise InputError("the recorded rotor has no bearing cases as tables", source=source)
    cases = [b.pop("case") for b in bearings]
    if not data.get("disks"):
        data.pop("disks", None)
    rotor = rotor_from_dict(data, source=source)  # each bearing on the built-in case here
    sites = tuple(
        replace(site, case=case_from_dict(case, source=source))
        for site, case in zip(rotor.bearings, cases, strict=True)
    )
    return replace(rotor, bearings=sites)


def _file_digest(path: str | None) -> str | None:
    """:func:`rotor_digest` of the rotor file at ``path`` as it reads now, or None (no
    file, gone, broken, or a bearing's case file that does not read)."""
    if path is None:
        return None
    from foilbearing.rotor.toml import load_rotor

    try:
        return rotor_digest(rotor_to_dict(load_rotor(path)))
    except InputError:
        return None


@dataclass(frozen=True)
class RotorRecord:
    """A rotor run's rotor as data: what ``rotor --resume`` rebuilds it from.

    Attributes
    ----------
    tables
        The rotor's tables (:func:`rotor_to_dict`), its bearings' cases in full.
    file_sha256
        :func:`rotor_digest` of the rotor file's rotor (its case files read through it)
        when the run started; None when there was no file to read.
    """

    tables: dict[str, Any] = field(hash=False)
    file_sha256: str | None = None

    @classmethod
    def of(cls, rotor: RotorCase, path: str | None) -> RotorRecord:
        """The record of ``rotor``, read from the rotor file ``path`` (None: not from one)."""
        return cls(rotor_to_dict(rotor), _file_digest(path))

    @property
    def sha256(self) -> str:
        """:func:`rotor_digest` of the tables."""
        return rotor_digest(self.tables)

    def rotor(self, source: str | None) -> RotorCase:
        """The recorded rotor, its ``source`` set to ``source``."""
        return rotor_from_dict_record(self.tables, source)

    def to_dict(self) -> dict[str, Any]:
        """Plain data: the tables, their sha256 and the file's."""
        return {"tables": self.tables, "sha256": self.sha256, "file_sha256": self.file_sha256}

    @classmethod
    def from_dict(cls, data: Any) -> RotorRecord:
        """The record of :meth:`to_dict`'s data, its tables checked against their sha256.

        Raises
        ------
        ValueError
            Not such data, or tables that do not match their sha256 (altered or damaged).
        """
        if not isinstance(data, dict) or not isinstance(data.get("tables"), dict):
            raise ValueError("the recorded rotor is not a table of tables")
        record = cls(data["tables"], data.get("file_sha256"))
        if record.sha256 != data.get("sha256"):
            raise ValueError(
                "the recorded rotor does not match its sha256 (the record was altered or damaged)"
            )
        return record

    def changes(self, path: str | Path | None) -> str | None:
        """One line saying how the rotor file at ``path`` (or a bearing case file it names)
        has changed since the run started, or None: unchanged, gone, unreadable, or no
        digest recorded to compare with."""
        if path is None:
            return None
        now = _file_digest(str(path))
        if self.file_sha256 is None or now is None or now == self.file_sha256:
            return None
        from foilbearing.rotor.toml import load_rotor

        diffs = table_differences(self.tables, rotor_to_dict(load_rotor(path)))
        shown = "; ".join(f"{k}: {a} recorded, {b} now" for k, a, b in diffs[:3])
        more = f" and {len(diffs) - 3} more" if len(diffs) > 3 else ""
        return (
            f"rotor file {path} or a bearing case file it names has changed since the run "
            f"started ({shown}{more}); the run goes on with the rotor it recorded (start a "
            "new run to use the new files)"
        )


#: The format of a rotor run's record (the NetCDF attribute ``rotor_run``); files of the
#: first form (no ``format``) held the rotor file's text and read the bearings' case files.
RUN_FORMAT = "foilbearing.rotor.RotorRun/2"

#: The run's options in its record, with the types they must have.
_OPTION_TYPES: dict[str, tuple[type, ...]] = {
    "orbit": (str,),
    "unbalance": (list,),
    "voltage_ramp": (str, type(None)),
    "controller": (str, type(None)),
    "shaft_modes": (int,),
}


def _notice(line: str) -> None:
    import sys

    print(f"foilbearing: note: {line}", file=sys.stderr)


def read_rotor_run(
    text: Any, source: str, notice: Any = _notice
) -> tuple[dict[str, Any], RotorCase]:
    """The run's options and its rotor from a rotor run's record (``rotor_run``).

    The rotor is the recorded one (its tables checked against their sha256); a rotor
    file or bearing case file changed since the run started is reported by one line to
    ``notice`` (default: stderr). A record of the first form is rebuilt from the rotor
    file's text it holds, its bearing cases read from their files.

    Raises
    ------
    InputError
        One line naming the file (``source``) and what of the record is damaged.
    """
    import json
    import tomllib

    from foilbearing.rotor.toml import rotor_from_dict

    def damaged(what: str) -> InputError:
        return InputError(f"the run's record (rotor_run) is damaged: {what}", source=source)

    try:
        spec = json.loads(text)
    except (TypeError, ValueError):
        raise damaged("not valid JSON") from None
    if not isinstance(spec, dict):
        raise damaged("not a table")
    for key, kinds in _OPTION_TYPES.items():
        if key not in spec:
            raise damaged(f"{key!r} missing")
        value = spec[key]
        if isinstance(value, bool) or not isinstance(value, kinds):
            raise damaged(f"{key} = {value!r}")
    if not all(isinstance(u, str) for u in spec["unbalance"]) or spec["shaft_modes"] < 1:
        raise damaged(f"unbalance = {spec['unbalance']!r}, shaft_modes = {spec['shaft_modes']!r}")
    file = spec.get("rotor_file")
    if file is not None and not isinstance(file, str):
        raise damaged(f"rotor_file = {file!r}")
    if "rotor_record" in spec:
        if spec.get("format") != RUN_FORMAT:
            raise damaged(f"format = {spec.get('format')!r}, expected {RUN_FORMAT!r}")
        try:
            record = RotorRecord.from_dict(spec["rotor_record"])
        except ValueError as exc:
            raise damaged(str(exc)) from None
        try:
            rotor = record.rotor(file)
        except InputError as exc:
            raise damaged(f"its rotor does not read ({exc})") from None
        line = record.changes(None if file in (None, "None") else file)
        if line is not None:
            notice(line)
        return spec, rotor
    # the first form: the rotor file's text; the bearing cases are read from their files now
    if not isinstance(spec.get("rotor_text"), str) or not isinstance(file, str):
        raise damaged("neither the recorded rotor nor the rotor file's text")
    try:
        data = tomllib.loads(spec["rotor_text"])
    except tomllib.TOMLDecodeError as exc:
        raise damaged(f"the rotor file's text is not valid TOML ({exc})") from None
    path = Path(file)
    return spec, rotor_from_dict(data, source=str(path), folder=path.parent)
