"""The case as data (``foilbearing.case.record``): every case reads back from its tables equal,
field for field, so a run's record can rebuild the case it ran on."""

from __future__ import annotations

import json
import tomllib
from dataclasses import fields, is_dataclass, replace
from pathlib import Path
from typing import get_args, get_type_hints

import pytest

from foilbearing.case import Case, Grid, case_from_dict, default_case, default_case_path
from foilbearing.case.record import FIELD_UNITS, case_digest, case_to_dict

ROOT = Path(__file__).resolve().parents[1]


def _bearing_case_files() -> list[Path]:
    """Every case file of the examples and the package that describes a bearing."""
    candidates = sorted((ROOT / "examples").glob("*.toml")) + sorted(
        default_case_path().parent.glob("*.toml")
    )
    return [p for p in candidates if "bearing" in tomllib.loads(p.read_text(encoding="utf-8"))]


def _variants() -> dict[str, Case]:
    base = default_case()
    act = base.actuators
    assert act is not None and base.foil is not None and base.foil.bump is not None
    return {
        "built-in": base,
        "lobe-held": base.with_actuator_reading("lobe", "held"),
        "lobe": base.with_actuator_reading("lobe"),
        "held": base.with_actuator_reading(dynamics="held"),
        "retained": base.with_subambient("retained"),
        "voltages": base.with_voltages((0.0, 37.5, 150.0)),
        "shimmed": base.shimmed(),
        "passive-no-bump": replace(
            base, actuators=None, foil=replace(base.foil, bump=None), disturbance=None
        ),
        "rigid": replace(base, foil=None, actuators=None),
        "walowit-anno": replace(
            base,
            foil=replace(
                base.foil,
                bump=replace(base.foil.bump, formula="walowit-anno", top_foil_thickness=None),
            ),
        ),
        "orbit-grid": replace(
            base,
            grid=Grid(64, 6, orbit_n_theta=48, orbit_n_z=3, axial_order=4, lift_off_smoothing=0.5),
        ),
        "orbit-case": base.orbit_case(),
        "study-table": replace(base, study_table=json.dumps({"speed_range": ["1 rpm", 2.5]})),
    }


@pytest.mark.parametrize("name", list(_variants()))
def test_a_case_reads_back_equal_from_its_tables(name: str) -> None:
    """``case_from_dict(case_to_dict(c)) == c`` for every field of every class: the reading,
    the sub-ambient model, the grids, the smoothing, per-actuator voltages, shims, none."""
    case = _variants()[name]
    tables = case_to_dict(case)
    back = case_from_dict(tables, source=case.source)
    g = case.grid
    # An orbit grid "the same as the static one" (None) reads back as the values it stands for
    want = replace(
        case,
        grid=replace(g, orbit_n_z=g.orbit_shape[1], orbit_axial_order=g.orbit_order),
    )
    assert back == want
    assert (back.grid.orbit_shape, back.grid.orbit_order) == (g.orbit_shape, g.orbit_order)
    # The tables are plain JSON: the record of a file is the same after a JSON round trip.
    assert case_from_dict(json.loads(json.dumps(tables)), source=case.source) == want


@pytest.mark.parametrize("path", _bearing_case_files(), ids=lambda p: p.name)
def test_every_bearing_case_file_reads_back_equal(path: Path) -> None:
    from foilbearing.case import load_case

    case = load_case(path)
    assert case_from_dict(case_to_dict(case), source=str(path)) == case


def test_dimensional_values_are_written_with_their_si_unit() -> None:
    """As a case file writes them: the shortest decimal of the SI float and the SI unit
    ("100 um" is the float 9.999999999999999e-05 m, and is written so)."""
    case = default_case()
    tables = case_to_dict(case)
    value, unit = tables["bearing"]["clearance"].split()
    assert unit == "m" and float(value) == case.bearing.clearance
    assert tables["operation"]["speed"].endswith(" rad/s")
    assert tables["actuators"]["angles"][0].endswith(" rad")
    assert tables["actuators"]["preload_response"] == "local"
    assert tables["grid"]["orbit_axial_order"] == 4


def test_every_field_of_the_case_has_its_place_in_the_record() -> None:
    """Every field of every class a case is made of (walked from the type hints of
    :class:`Case`) has its unit in the record's table: a field added to the case and not
    there fails here, and the writer raises rather than drop it."""
    seen: set[type] = set()

    def walk(cls: type) -> None:
        for name, hint in get_type_hints(cls).items():
            if cls is Case and name in ("title", "source", "study_table"):
                continue
            if cls is not Case:
                assert name in FIELD_UNITS[cls], f"{cls.__name__}.{name}"
            for part in get_args(hint) or (hint,):
                if is_dataclass(part) and part not in seen:
                    seen.add(part)
                    assert {f.name for f in fields(part)} == set(FIELD_UNITS[part]), part
                    walk(part)

    walk(Case)
    assert seen == set(FIELD_UNITS)
    units = FIELD_UNITS[Grid]
    FIELD_UNITS[Grid] = {k: v for k, v in units.items() if k != "lift_off_smoothing"}
    try:
        with pytest.raises(KeyError, match=r"Grid\.lift_off_smoothing"):
            case_to_dict(default_case())
    finally:
        FIELD_UNITS[Grid] = units


def test_the_digest_is_of_the_content_not_the_key_order() -> None:
    tables = case_to_dict(default_case())
    shuffled = dict(reversed(list(tables.items())))
    assert case_digest(shuffled) == case_digest(tables)
    other = case_to_dict(default_case().with_actuator_reading("lobe"))
    assert case_digest(other) != case_digest(tables)
    assert len(case_digest(tables)) == 64
