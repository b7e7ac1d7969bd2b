"""The rotor file's errors, defaults and the rotor's static balance, fast (no solves).

Every bad rotor file is a one-line :class:`InputError` that names the file, the field
(its TOML path), the bad value and what is allowed: the tests compare the whole message,
so a changed word, a lost ``source`` or a moved bound fails them. Each test writes a
valid rotor file and breaks one field. The rotor's weights, its bearings' shares and the
mass of a hollow shaft element are checked against values computed by hand.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from foilbearing.errors import InputError
from foilbearing.rotor import load_rotor, rotor_from_dict
from foilbearing.rotor.model import (
    STANDARD_GRAVITY,
    BearingSite,
    Disk,
    Material,
    RotorCase,
    ShaftElement,
)

HOLD_DOWN = (
    "the rotor's centre of mass lies outside the bearings, which a foil bearing cannot hold down"
)

# A valid rotor: three elements (nodes 0 to 3), a disk at node 1, bearings at nodes 0 and 2.
BASE: dict[str, Any] = {
    "title": "test rotor",
    "material": {"density": "8000 kg/m**3", "youngs_modulus": "200 GPa", "poisson_ratio": 0.3},
    "shaft": {"lengths": ["40 mm", "60 mm", "50 mm"], "outer_diameters": ["30 mm"] * 3},
    "disks": [
        {
            "node": 1,
            "mass": "2 kg",
            "polar_inertia": "1e-3 kg*m**2",
            "diametral_inertia": "5e-4 kg*m**2",
        }
    ],
    "bearings": [{"node": 0}, {"node": 2}],
}


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, int | float):
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(v)


def _dump(data: dict[str, Any]) -> str:
    """TOML for the rotor's tables: scalars first, then [tables] and [[arrays of tables]]."""
    lines = []
    blocks = []
    for key, v in data.items():
        if isinstance(v, dict):
            blocks += ["", f"[{key}]"] + [f"{k} = {_value(x)}" for k, x in v.items()]
        elif isinstance(v, list) and v and all(isinstance(t, dict) for t in v):
            for t in v:
                blocks += ["", f"[[{key}]]"] + [f"{k} = {_value(x)}" for k, x in t.items()]
        else:
            lines.append(f"{key} = {_value(v)}")
    return "\n".join(lines + blocks) + "\n"


def _data(**changes: Any) -> dict[str, Any]:
    """BASE with fields changed: ``shaft__lengths=[...]``, ``disks__0__node=...``;
    ``...`` (Ellipsis) removes the field."""
    data = copy.deepcopy(BASE)
    for name, value in changes.items():
        *parents, last = name.split("__")
        target: Any = data
        for p in parents:
            target = target[int(p)] if p.isdigit() else target[p]
        if value is ...:
            del target[int(last) if last.isdigit() else last]
        else:
            target[int(last) if last.isdigit() else last] = value
    return data


def _write(folder: Path, **changes: Any) -> Path:
    path = folder / "rotor.toml"
    path.write_text(_dump(_data(**changes)), encoding="utf-8")
    return path


def _refused(folder: Path, detail: str, **changes: Any) -> None:
    """The rotor file with ``changes`` is refused with exactly ``<file>: <detail>``."""
    path = _write(folder, **changes)
    with pytest.raises(InputError) as info:
        load_rotor(path)
    assert str(info.value) == f"{path}: {detail}"
    assert info.value.source == str(path)
    assert info.value.detail == detail
    assert "\n" not in str(info.value)


# --- reading the file ---------------------------------------------------------------------


def test_a_valid_file_reads_every_field(tmp_path: Path) -> None:
    rotor = load_rotor(_write(tmp_path))
    assert rotor.title == "test rotor"
    assert rotor.source == str(tmp_path / "rotor.toml")
    assert rotor.material == Material(8000.0, 200e9, 0.3)
    assert rotor.shaft == (
        ShaftElement(0.04, 0.03, 0.0),
        ShaftElement(0.06, 0.03, 0.0),
        ShaftElement(0.05, 0.03, 0.0),
    )
    assert rotor.disks == (Disk(1, 2.0, 1e-3, 5e-4),)
    assert [(b.node, b.label) for b in rotor.bearings] == [
        (0, "bearing 0 (node 0)"),
        (2, "bearing 1 (node 2)"),
    ]
    assert rotor.gravity == STANDARD_GRAVITY == 9.80665


def test_defaults_title_gravity_disks_nodes_and_labels(tmp_path: Path) -> None:
    rotor = load_rotor(
        _write(tmp_path, title=..., disks=..., bearings=[{"label": "drive end"}, {"node": 3}])
    )
    assert rotor.title == "rotor"
    assert rotor.gravity == 9.80665
    assert rotor.disks == ()
    assert [(b.node, b.label) for b in rotor.bearings] == [
        (0, "drive end"),
        (3, "bearing 1 (node 3)"),
    ]
    # a disk without a node sits at node 0
    rotor = load_rotor(_write(tmp_path, disks__0__node=...))
    assert rotor.disks[0].node == 0


def test_gravity_in_any_acceleration_unit(tmp_path: Path) -> None:
    assert load_rotor(_write(tmp_path, gravity="1.62 m/s**2")).gravity == pytest.approx(1.62)
    assert load_rotor(_write(tmp_path, gravity="980.665 cm/s**2")).gravity == pytest.approx(
        9.80665, rel=1e-12
    )
    assert load_rotor(_write(tmp_path, gravity="0 m/s**2")).gravity == 0.0


def test_a_missing_file_or_a_folder_or_bad_bytes_or_bad_toml(tmp_path: Path) -> None:
    missing = tmp_path / "missing.toml"
    with pytest.raises(InputError) as info:
        load_rotor(missing)
    assert str(info.value) == f"{missing}: rotor file not found"

    with pytest.raises(InputError) as info:
        load_rotor(tmp_path)  # a folder: read_text raises IsADirectoryError
    assert str(info.value) == f"{tmp_path}: cannot read rotor file (IsADirectoryError)"

    latin1 = tmp_path / "latin1.toml"
    latin1.write_bytes(_dump(BASE).replace('"test rotor"', '"caf\xe9"').encode("latin-1"))
    with pytest.raises(InputError) as info:
        load_rotor(latin1)
    assert str(info.value) == f"{latin1}: cannot read rotor file (UnicodeDecodeError)"

    bad = tmp_path / "bad.toml"
    bad.write_text("title = \n", encoding="utf-8")
    with pytest.raises(InputError) as info:
        load_rotor(bad)
    assert str(info.value) == f"{bad}: not valid TOML: Invalid value (at line 1, column 9)"


def test_a_utf8_title_is_read_as_utf8(tmp_path: Path) -> None:
    path = tmp_path / "rotor.toml"
    path.write_bytes(_dump(BASE).replace("test rotor", "Läufer µ").encode("utf-8"))
    assert load_rotor(path).title == "Läufer µ"


def test_data_that_is_not_a_table() -> None:
    not_a_table: Any = [1]
    with pytest.raises(InputError) as info:
        rotor_from_dict(not_a_table, source="r.toml")
    assert str(info.value) == "r.toml: [] must be a table, got [1]"


# --- the top level and [material] -----------------------------------------------------------


@pytest.mark.parametrize(
    ("changes", "detail"),
    [
        ({"gravity": "9.8 m"}, "gravity = '9.8 m': wrong dimension, expected acceleration "
         "(in m/s**2, e.g. '9.81 m/s**2')"),
        ({"gravity": 9.8}, "gravity = 9.8: add a unit, e.g. '9.8 m/s**2'"),
        ({"gravity": "-1 m/s**2"}, "gravity = '-1 m/s**2': expected a value >= 0"),
        ({"title": 3}, "title = 3: expected a string"),
        ({"colour": "red"}, "unknown field 'colour' in the top level "
         "(allowed: bearings, disks, gravity, material, shaft, title)"),
        ({"material": ...}, "table [material] is missing"),
        ({"shaft": ...}, "table [shaft] is missing"),
        ({"material__density": "0 kg/m**3"}, "material.density = '0 kg/m**3': expected a value > 0"),
        ({"material__youngs_modulus": "211 kg"}, "material.youngs_modulus = '211 kg': wrong "
         "dimension, expected pressure (in Pa, e.g. '101325 Pa')"),
        ({"material__poisson_ratio": 0.5}, "material.poisson_ratio = 0.5: expected a number in [0, 0.5)"),
        ({"material__poisson_ratio": 0.7}, "material.poisson_ratio = 0.7: expected a number in [0, 0.5)"),
        ({"material__poisson_ratio": -0.1}, "material.poisson_ratio = -0.1: expected a number in [0, 0.5)"),
        ({"material__poisson_ratio": ...}, "material.poisson_ratio is missing"),
        ({"material__colour": "red"}, "unknown field 'colour' in [material] "
         "(allowed: density, poisson_ratio, youngs_modulus)"),
    ],
)  # fmt: skip
def test_bad_top_level_and_material(tmp_path: Path, changes: dict[str, Any], detail: str) -> None:
    _refused(tmp_path, detail, **changes)


def test_poisson_ratio_up_to_below_one_half(tmp_path: Path) -> None:
    assert load_rotor(_write(tmp_path, material__poisson_ratio=0.49)).material.poisson_ratio == 0.49
    assert load_rotor(_write(tmp_path, material__poisson_ratio=0)).material.poisson_ratio == 0.0


# --- [shaft] ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("changes", "detail"),
    [
        ({"shaft__lengths": "50 mm"}, "shaft.lengths = '50 mm': expected a non-empty list of "
         "lengths, e.g. ['50 mm', '50 mm']"),
        ({"shaft__lengths": []}, "shaft.lengths = []: expected a non-empty list of lengths, "
         "e.g. ['50 mm', '50 mm']"),
        ({"shaft__lengths": ...}, "shaft.lengths is missing"),
        ({"shaft__outer_diameters": ["30 mm"] * 2}, "shaft.outer_diameters = ['30 mm', '30 mm']: "
         "expected a list of 3 (one per element) of lengths, e.g. ['50 mm', '50 mm']"),
        ({"shaft__outer_diameters": ["30 mm"] * 4}, "shaft.outer_diameters = ['30 mm', '30 mm', "
         "'30 mm', '30 mm']: expected a list of 3 (one per element) of lengths, e.g. "
         "['50 mm', '50 mm']"),
        ({"shaft__outer_diameters": "30 mm"}, "shaft.outer_diameters = '30 mm': expected a "
         "list of 3 (one per element) of lengths, e.g. ['50 mm', '50 mm']"),
        ({"shaft__inner_diameters": ["10 mm"]}, "shaft.inner_diameters = ['10 mm']: expected "
         "a list of 3 (one per element) of lengths, e.g. ['50 mm', '50 mm']"),
        ({"shaft__lengths": ["40 mm", "3 kg", "50 mm"]}, "shaft.lengths[1] = '3 kg': wrong "
         "dimension, expected length (in m, e.g. '100 um')"),
        ({"shaft__lengths": ["40 mm", "-3 mm", "50 mm"]}, "shaft.lengths[1] = '-3 mm': "
         "expected a length >= 0"),
        ({"shaft__inner_diameters": ["0 mm", "0 mm", "-1 mm"]}, "shaft.inner_diameters[2] = "
         "'-1 mm': expected a length >= 0"),
        ({"shaft__outer_diameters": ["30 mm", 30, "30 mm"]}, "shaft.outer_diameters[1] = 30: "
         "add a unit, e.g. '30 m'"),
        ({"shaft__lengths": ["40 mm", "0 mm", "50 mm"]}, "shaft element 1: length 0 mm, "
         "diameters 30 / 0 mm: need a length > 0 and outer > inner"),
        ({"shaft__inner_diameters": ["0 mm", "0 mm", "30 mm"]}, "shaft element 2: length 50 mm, "
         "diameters 30 / 30 mm: need a length > 0 and outer > inner"),
        ({"shaft__inner_diameters": ["0 mm", "35 mm", "0 mm"]}, "shaft element 1: length 60 mm, "
         "diameters 30 / 35 mm: need a length > 0 and outer > inner"),
        ({"shaft__colour": "red", "shaft__inner_diameters": ["0 mm"] * 3}, "unknown field "
         "'colour' in [shaft] (allowed: inner_diameters, lengths, outer_diameters)"),
        ({"shaft__colour": "red"}, "unknown field 'colour' in [shaft] (allowed: "
         "inner_diameters, lengths, outer_diameters)"),  # the optional field listed when absent
    ],
)  # fmt: skip
def test_bad_shaft(tmp_path: Path, changes: dict[str, Any], detail: str) -> None:
    _refused(tmp_path, detail, **changes)


def test_a_hollow_element_s_mass_is_its_annulus_times_length(tmp_path: Path) -> None:
    steel = Material(8000.0, 200e9, 0.3)
    # ρ π/4 (D_o² − D_i²) L = 8000 · π/4 · (0.03² − 0.01²) · 0.05 = 0.08 π kg
    assert ShaftElement(0.05, 0.03, 0.01).mass(steel) == pytest.approx(0.08 * math.pi, rel=1e-12)
    assert ShaftElement(0.05, 0.03).mass(steel) == pytest.approx(0.09 * math.pi, rel=1e-12)
    # the same element from a file, with a zero inner diameter beside it
    rotor = load_rotor(
        _write(tmp_path, shaft__inner_diameters=["0 mm", "10 mm", "0 mm"], disks=...)
    )
    assert [e.inner_diameter for e in rotor.shaft] == [0.0, pytest.approx(0.01), 0.0]
    # 8000 π/4 (9e-4 · 0.04 + 8e-4 · 0.06 + 9e-4 · 0.05) = 2000 π · 1.29e-4 = 0.258 π kg
    assert rotor.mass == pytest.approx(0.258 * math.pi, rel=1e-12)


# --- [[disks]] and [[bearings]] -----------------------------------------------------------


@pytest.mark.parametrize(
    ("changes", "detail"),
    [
        ({"bearings": ...}, "bearings is missing"),
        ({"bearings": []}, "[[bearings]] must be one or more tables"),
        ({"bearings": 5}, "[[bearings]] must be one or more tables"),
        ({"bearings": "node 0"}, "[[bearings]] must be one or more tables"),
        ({"bearings": [0, 2]}, "[[bearings]] must be one or more tables"),
        ({"disks": []}, "[[disks]] must be one or more tables"),
        ({"disks": 5}, "[[disks]] must be one or more tables"),
        ({"disks": [1, 2]}, "[[disks]] must be one or more tables"),
        ({"disks__0__node": 10001}, "disks[0].node = 10001: expected an integer from 0 to 10000"),
        ({"disks__0__node": -1}, "disks[0].node = -1: expected an integer from 0 to 10000"),
        ({"disks__0__node": 10000}, "disks[0].node = 10000: the shaft has nodes 0 to 3"),
        ({"disks__0__node": 4}, "disks[0].node = 4: the shaft has nodes 0 to 3"),
        ({"disks__0__mass": "0 kg"}, "disks[0].mass = '0 kg': expected a value > 0"),
        ({"disks__0__mass": "2 m"}, "disks[0].mass = '2 m': wrong dimension, expected mass "
         "(in kg, e.g. '0.897 kg')"),
        ({"disks__0__polar_inertia": "-1 kg*m**2"}, "disks[0].polar_inertia = '-1 kg*m**2': "
         "expected a value >= 0"),
        ({"disks__0__diametral_inertia": "-1 kg*m**2"}, "disks[0].diametral_inertia = "
         "'-1 kg*m**2': expected a value >= 0"),
        ({"disks__0__colour": "red"}, "unknown field 'colour' in [disks[0]] "
         "(allowed: diametral_inertia, mass, node, polar_inertia)"),
        ({"bearings__1__node": 10001}, "bearings[1].node = 10001: expected an integer from 0 "
         "to 10000"),
        ({"bearings__1__node": 4}, "bearings[1].node = 4: the shaft has nodes 0 to 3"),
        ({"bearings__1__node": 0}, "bearings: two bearings at one node"),
        ({"bearings__1__label": 7}, "bearings[1].label = 7: expected a string"),
        ({"bearings__1__case": 7}, "bearings[1].case = 7: expected a string"),
        ({"bearings__1__colour": "red"}, "unknown field 'colour' in [bearings[1]] "
         "(allowed: case, label, node)"),
        ({"bearings__1__voltages": ["1 V", "2 V"]}, "bearings[1].voltages = ['1 V', '2 V']: "
         "expected one voltage, or a list of 3 (one per actuator)"),
        ({"bearings__1__voltages": ["1 V", "2 V", "3 kg"]}, "bearings[1].voltages = '3 kg': "
         "wrong dimension, expected voltage (in V, e.g. '150 V')"),
        ({"bearings__0__voltages": True}, "bearings[0].voltages = True: expected a number or "
         "a quantity"),
    ],
)  # fmt: skip
def test_bad_disks_and_bearings(tmp_path: Path, changes: dict[str, Any], detail: str) -> None:
    _refused(tmp_path, detail, **changes)


def test_voltages_one_for_all_or_one_per_actuator(tmp_path: Path) -> None:
    rotor = load_rotor(
        _write(
            tmp_path,
            bearings=[{"voltages": "150 V"}, {"node": 2, "voltages": ["0 V", "20 V", "150 V"]}],
        )
    )
    a, b = (site.case.actuators for site in rotor.bearings)
    assert a is not None and b is not None
    assert a.voltages == (150.0, 150.0, 150.0)
    assert b.voltages == (0.0, 20.0, 150.0)
    # without voltages, the built-in case's own (0 V)
    own = load_rotor(_write(tmp_path)).bearings[0].case.actuators
    assert own is not None and own.voltages == (0.0, 0.0, 0.0)


# A rigid gas bearing (no [foil], so no actuators), written out: mutmut's copy of the tests
# has no examples/ folder.
RIGID_CASE = """\
[bearing]
radius = "19.05 mm"
length = "38.1 mm"
clearance = "32 um"

[gas]
viscosity = "1.85e-5 Pa*s"
ambient_pressure = "101325 Pa"

[rotor]
mass = "2.04 kg"

[operation]
load = "20 N"
speed = "8000 rpm"
"""


def _rigid_case(folder: Path) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "rigid.toml"
    path.write_text(RIGID_CASE, encoding="utf-8")
    return path


def test_case_files_relative_to_the_rotor_file_or_absolute(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    rigid = _rigid_case(tmp_path / "cases")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    rotor = load_rotor(_write(tmp_path, bearings__1__case="cases/rigid.toml"))
    assert rotor.bearings[1].case.source == str(rigid)
    assert rotor.bearings[1].case.actuators is None
    assert rotor.bearings[0].case.actuators is not None  # the built-in C-GFB
    rotor = load_rotor(_write(elsewhere, bearings__1__case=str(rigid)))
    assert rotor.bearings[1].case.source == str(rigid)
    # without a folder, relative to the working directory
    monkeypatch.chdir(tmp_path)
    rotor = rotor_from_dict(_data(bearings__1__case="cases/rigid.toml"), source="r.toml")
    assert rotor.bearings[1].case.actuators is None
    # a case without actuators takes no voltages
    path = _write(tmp_path, bearings__1__case="cases/rigid.toml", bearings__1__voltages="0 V")
    with pytest.raises(InputError) as info:
        load_rotor(path)
    assert str(info.value) == (
        f"{path}: bearings[1].voltages = '0 V': expected no voltages: the bearing case has "
        "no actuators"
    )


# --- the rotor's weights and its bearings' shares ---------------------------------------------


def _hollow_rotor(tmp_path: Path, **changes: Any) -> RotorCase:
    """Four elements (nodes at 0, 30, 70, 120, 140 mm), hollow in the middle two, a 1.5 kg
    disk at node 2, bearings at nodes 1 and 3 (neither at z = 0), g = 10 m/s²."""
    data = {
        "gravity": "10 m/s**2",
        "shaft": {
            "lengths": ["30 mm", "40 mm", "50 mm", "20 mm"],
            "outer_diameters": ["30 mm", "30 mm", "30 mm", "20 mm"],
            "inner_diameters": ["0 mm", "10 mm", "10 mm", "0 mm"],
        },
        "disks": [{"node": 2, "mass": "1.5 kg", "polar_inertia": "0 kg*m**2",
                   "diametral_inertia": "0 kg*m**2"}],
        "bearings": [{"node": 1, "label": "A"}, {"node": 3, "label": "B"}],
    }  # fmt: skip
    data.update(changes)
    path = tmp_path / "hollow.toml"
    path.write_text(_dump({**_data(), **data}), encoding="utf-8")
    return load_rotor(path)


# by hand: ρ π/4 (D_o² − D_i²) L with ρ = 8000 kg/m³
HAND_MASSES = [
    8000 * math.pi / 4 * 9e-4 * 0.03,
    8000 * math.pi / 4 * 8e-4 * 0.04,
    8000 * math.pi / 4 * 8e-4 * 0.05,
    8000 * math.pi / 4 * 4e-4 * 0.02,
    1.5,
]
HAND_AT = [0.015, 0.05, 0.095, 0.13, 0.07]  # element mid-points, then the disk's node


def test_weights_sit_at_the_element_mid_points_and_the_disk_nodes(tmp_path: Path) -> None:
    rotor = _hollow_rotor(tmp_path)
    np.testing.assert_allclose(rotor.positions, [0.0, 0.03, 0.07, 0.12, 0.14], rtol=1e-12)
    at, w = rotor.weights()
    np.testing.assert_allclose(at, HAND_AT, rtol=1e-12)
    np.testing.assert_allclose(w, [10.0 * m for m in HAND_MASSES], rtol=1e-12)
    assert rotor.mass == pytest.approx(sum(HAND_MASSES), rel=1e-12)


def test_two_bearings_balance_forces_and_moments(tmp_path: Path) -> None:
    rotor = _hollow_rotor(tmp_path)
    za, zb = 0.03, 0.12
    weights = [10.0 * m for m in HAND_MASSES]
    total = sum(weights)
    rb = sum(w * (z - za) for w, z in zip(weights, HAND_AT, strict=True)) / (zb - za)
    ra = sum(w * (zb - z) for w, z in zip(weights, HAND_AT, strict=True)) / (zb - za)
    loads = rotor.bearing_loads()
    assert loads == (pytest.approx(ra, rel=1e-12), pytest.approx(rb, rel=1e-12))
    assert sum(loads) == pytest.approx(total, rel=1e-12)
    cases = rotor.loaded_cases()
    assert [c.operation.load for c in cases] == list(loads)
    # the rest of each case unchanged
    assert cases[0].operation.speed == rotor.bearings[0].case.operation.speed


def test_one_bearing_carries_the_whole_weight(tmp_path: Path) -> None:
    rotor = _hollow_rotor(tmp_path, bearings=[{"node": 2}])
    total = 10.0 * sum(HAND_MASSES)
    assert rotor.bearing_loads() == (pytest.approx(total, rel=1e-12),)
    assert rotor.loaded_cases()[0].operation.load == pytest.approx(total, rel=1e-12)


def test_three_bearings_are_refused(tmp_path: Path) -> None:
    rotor = load_rotor(_write(tmp_path, bearings=[{"node": 0}, {"node": 2}, {"node": 3}]))
    with pytest.raises(InputError) as info:
        rotor.bearing_loads()
    assert str(info.value) == (
        f"{tmp_path / 'rotor.toml'}: bearings: 3 bearings; the static loads are computed for "
        "one or two bearings (more share the weight by the shaft's stiffness)"
    )


def test_a_light_rotor_under_one_newton_is_held(tmp_path: Path) -> None:
    rotor = load_rotor(_write(tmp_path, gravity="0.1 m/s**2"))
    loads = rotor.bearing_loads()
    assert 0.0 < min(loads) and max(loads) < 1.0
    assert [c.operation.load for c in rotor.loaded_cases()] == list(loads)


def test_a_centre_of_mass_outside_the_bearings_cannot_be_held_down(tmp_path: Path) -> None:
    # all but a little of the weight beyond bearing B at node 1: A would pull down
    path = _write(tmp_path, bearings=[{"node": 0}, {"node": 1, "label": "B"}],
                  disks__0__node=3, disks__0__mass="5 kg")  # fmt: skip
    rotor = load_rotor(path)
    at, w = rotor.weights()
    zb = 0.04
    ra = float(np.sum(w * (zb - at)) / zb)
    assert ra < 0.0
    assert rotor.bearing_loads()[0] == pytest.approx(ra, rel=1e-12)
    with pytest.raises(InputError) as info:
        rotor.loaded_cases()
    assert str(info.value) == (
        f"{path}: bearing 'bearing 0 (node 0)' at node 0 would carry {ra:.3g} N: {HOLD_DOWN}"
    )


def test_without_gravity_no_bearing_carries_a_load(tmp_path: Path) -> None:
    path = _write(tmp_path, gravity="0 m/s**2", bearings__0__label="drive end")
    rotor = load_rotor(path)
    assert rotor.bearing_loads() == (0.0, 0.0)
    with pytest.raises(InputError) as info:
        rotor.loaded_cases()
    assert str(info.value) == (
        f"{path}: bearing 'drive end' at node 0 would carry 0 N: {HOLD_DOWN}"
    )


def test_a_rotor_built_in_code_checks_its_nodes() -> None:
    steel = Material(7850.0, 211e9, 0.29)
    shaft = (ShaftElement(0.05, 0.03), ShaftElement(0.05, 0.03))
    site = BearingSite(0, rotor_from_dict(_data()).bearings[0].case, "A")
    with pytest.raises(InputError) as info:
        RotorCase("r", steel, shaft, (Disk(3, 1.0, 0.0, 0.0),), (site,), source="code")
    assert str(info.value) == "code: disks[0].node = 3: the shaft has nodes 0 to 2"
    with pytest.raises(InputError) as info:
        RotorCase("r", steel, shaft, (), (site, BearingSite(0, site.case, "B")))
    assert str(info.value) == "bearings: two bearings at one node"
    rotor = RotorCase("r", steel, shaft, (Disk(2, 1.0, 0.0, 0.0),), (site,))
    assert rotor.gravity == STANDARD_GRAVITY and rotor.source is None
