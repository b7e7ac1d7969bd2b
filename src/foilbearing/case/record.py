"""The case as data: a :class:`~foilbearing.case.model.Case` written back as the tables of a case file.

:func:`case_to_dict` gives the tables :func:`~foilbearing.case.toml.case_from_dict`
reads, so that ``case_from_dict(case_to_dict(case), source=case.source) == case``
field for field: a run's record holds its whole case (the actuator reading, the
grid, the lift-off smoothing, the sub-ambient model...) and is rebuilt from it
alone. Every dimensional value is written as an exact SI quantity string, the
shortest decimal that reads back to the same float and its SI unit
(``"0.0001 m"``), which the reader converts by a factor of 1: the round trip is
exact. :func:`case_digest` is the sha256 of the tables' canonical JSON, the
record's fingerprint; :class:`CaseRecord` is what a run stores: the tables, their
digest, and the digest of its case file's own case, by which a resumed run tells that
the file has changed since (:meth:`CaseRecord.changes`).

The fields are written from the dataclasses' own fields against the table
:data:`FIELD_UNITS` of each one's SI unit, derived from the case schema
(:mod:`foilbearing.case.schema`): a field added to a class of
:mod:`foilbearing.case.model` and not to the schema stops the writer (and the
round-trip tests) instead of being left out of the record.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field, fields
from typing import Any

from foilbearing.case.model import Case, Grid
from foilbearing.case.schema import FIELD_UNITS, FILE_NAMES
from foilbearing.errors import InputError

__all__ = [
    "FIELD_UNITS",
    "CaseRecord",
    "case_digest",
    "case_to_dict",
    "file_digest",
    "table_differences",
]

#: Fields whose None ("the same as the static grid's") is not the reader's default: the
#: record writes the value they stand for (the static grid's), which runs the same orbit.
_EFFECTIVE = {(Grid, "orbit_n_z"): "n_z", (Grid, "orbit_axial_order"): "axial_order"}

#: Fields of :class:`Case` that are not tables of the file: the title (written at the top
#: level), where the case was read from (the reader's ``source``, not data of the bearing)
#: and the study table (written back as the ``[study]`` table).
_CASE_OWN = ("title", "source", "study_table")


def case_to_dict(case: Case) -> dict[str, Any]:
    """The tables of a case file that read back to ``case`` (all but its ``source``).

    Parameters
    ----------
    case
        A validated case.

    Returns
    -------
    dict
        ``{"title": ..., "bearing": {...}, "gas": {...}, ...}`` with dimensional values
        as exact SI quantity strings (``"0.0001 m"``), lists for the per-actuator values,
        and only the optional tables the case has; JSON and TOML types only.
    """
    out: dict[str, Any] = {"title": case.title}
    for f in fields(Case):
        if f.name in _CASE_OWN:
            continue
        value = getattr(case, f.name)
        if value is not None:
            out[f.name] = _table(value)
    if case.study_table is not None:
        out["study"] = json.loads(case.study_table)
    return out


def case_digest(tables: dict[str, Any]) -> str:
    """sha256 (hex) of the canonical JSON of a case's tables (:func:`case_to_dict`)."""
    text = json.dumps(tables, sort_keys=True, separators=(",", ":"), ensure_ascii=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _table(obj: Any) -> dict[str, Any]:
    """One dataclass of the case as its table (None fields left out: the reader's default)."""
    units = FIELD_UNITS[type(obj)]
    table: dict[str, Any] = {}
    for f in fields(obj):
        if f.name not in units:
            raise KeyError(
                f"{type(obj).__name__}.{f.name} has no unit in foilbearing.case.record."
                "FIELD_UNITS: declare it in foilbearing.case.schema so the run record keeps it"
            )
        value = getattr(obj, f.name)
        if value is None and (type(obj), f.name) in _EFFECTIVE:
            value = getattr(obj, _EFFECTIVE[type(obj), f.name])
        if value is None:
            continue
        unit = units[f.name]
        name = FILE_NAMES.get((type(obj), f.name), f.name)
        if unit == "law":
            raise InputError(
                f"{type(obj).__name__.lower()}.{f.name} = {value!r}: a law given in Python has "
                "no case-file form, so this run cannot be recorded for --resume; run it "
                "without a file, or state the law through the case file's fields"
            )
        if unit == "table":
            table[name] = _table(value)
        elif isinstance(value, tuple):
            table[name] = [_quantity(v, unit) for v in value]
        else:
            table[name] = _quantity(value, unit)
    return table


def _quantity(value: Any, unit: str) -> Any:
    """A value as the file writes it: ``"<repr> <unit>"`` for a dimensional float (read back
    exactly, by a factor of 1), the plain value otherwise."""
    if not unit or isinstance(value, str | bool | int):
        return value
    return f"{float(value)!r} {unit}"


def file_digest(path: str | None) -> str | None:
    """:func:`case_digest` of the case file at ``path`` as it reads now (None: the built-in
    case), or None when it does not read as a case (gone, broken)."""
    from foilbearing.case.toml import load_case

    try:
        return case_digest(case_to_dict(load_case(path)))
    except InputError:
        return None


@dataclass(frozen=True)
class CaseRecord:
    """A run's case as data: what a resumed run is rebuilt from, with no file needed.

    Attributes
    ----------
    tables
        The case's tables (:func:`case_to_dict`), the run's overrides applied.
    file_sha256
        :func:`case_digest` of the case file's own case (as read, before any override)
        when the run started; None when there was no file to read.
    """

    tables: dict[str, Any] = field(hash=False)
    file_sha256: str | None = None

    @classmethod
    def of(cls, case: Case, path: str | None) -> CaseRecord:
        """The record of ``case``, which was made from the case file ``path`` (None: the
        built-in case), read now for its digest."""
        return cls(case_to_dict(case), file_digest(path))

    @property
    def sha256(self) -> str:
        """:func:`case_digest` of the tables."""
        return case_digest(self.tables)

    def case(self, source: str | None) -> Case:
        """The recorded case, its ``source`` set to ``source``."""
        from foilbearing.case.toml import case_from_dict

        return case_from_dict(self.tables, source=source)

    def to_dict(self) -> dict[str, Any]:
        """Plain data: the tables, their sha256 and the file's."""
        return {"tables": self.tables, "sha256": self.sha256, "file_sha256": self.file_sha256}

    @classmethod
    def from_dict(cls, data: Any) -> CaseRecord:
        """The record of :meth:`to_dict`'s data, its tables checked against their sha256.

        Raises
        ------
        ValueError
            Not such data, or tables that do not match their sha256 (altered or damaged).
        """
        if not isinstance(data, dict) or not isinstance(data.get("tables"), dict):
            raise ValueError("the recorded case is not a table of tables")
        record = cls(data["tables"], data.get("file_sha256"))
        if record.sha256 != data.get("sha256"):
            raise ValueError(
                "the recorded case does not match its sha256 (the record was altered or damaged)"
            )
        return record

    def changes(self, path: str | None) -> str | None:
        """One line saying how the case file at ``path`` has changed since the run started,
        or None: unchanged, gone, unreadable, or no digest recorded to compare with.

        The fields named are those where the file's case now differs from the recorded
        case (the run's overrides, such as an actuator reading, show there too).
        """
        now = file_digest(path)
        if self.file_sha256 is None or now is None or now == self.file_sha256:
            return None
        from foilbearing.case.toml import load_case

        diffs = table_differences(self.tables, case_to_dict(load_case(path)))
        shown = "; ".join(f"{k}: {a} recorded, {b} now" for k, a, b in diffs[:3])
        more = f" and {len(diffs) - 3} more" if len(diffs) > 3 else ""
        name = "the built-in case" if path is None else f"case file {path}"
        return (
            f"{name} has changed since the run started ({shown}{more}); the run goes on "
            "with the case it recorded (start a new run to use the new case)"
        )


def table_differences(a: Any, b: Any, prefix: str = "") -> list[tuple[str, Any, Any]]:
    """(field, value in a, value in b) of every leaf where two cases' tables differ, the
    field dotted as in a case file (``"bearing.clearance"``)."""
    if isinstance(a, dict) and isinstance(b, dict):
        out: list[tuple[str, Any, Any]] = []
        for key in sorted(set(a) | set(b)):
            out += table_differences(a.get(key), b.get(key), f"{prefix}{key}.")
        return out
    return [] if a == b else [(prefix.rstrip("."), a, b)]
