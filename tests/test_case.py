"""Loading and validating case files: units at the edges, one-line errors naming file and field."""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

import pytest
import tomlkit
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from foilbearing.case import case_from_dict, default_case, default_case_path, load_case
from foilbearing.cli.main import main
from foilbearing.errors import InputError

DEFAULT = tomllib.loads(default_case_path().read_text())


def _write(tmp_path: Path, data: dict) -> Path:
    path = tmp_path / "case.toml"
    path.write_text(tomlkit.dumps(data))
    return path


def _edited(table: str, key: str, value: object) -> dict:
    data = tomllib.loads(default_case_path().read_text())
    target = data
    for part in filter(None, table.split(".")):
        target = target[part]
    if value is None:
        del target[key]
    else:
        target[key] = value
    return data


def test_default_case_is_si_inside() -> None:
    case = default_case()
    assert case.bearing.radius == pytest.approx(0.020)
    assert case.bearing.clearance == pytest.approx(100e-6)
    assert case.operation.speed == pytest.approx(50000 * 2 * math.pi / 60)
    assert case.rotor.imbalance == pytest.approx(8.5e-6)  # 8.5 g*mm in kg*m
    assert case.actuators is not None
    assert case.actuators.angles == pytest.approx(tuple(math.radians(a) for a in (60, 180, 300)))
    assert case.actuators.d33_quadratic == pytest.approx(-0.0028e-6)
    # docs/model.md §4: Λ = 0.046 at 10 krpm and 0.41 at 90 krpm.
    assert case.bearing_number(10000 * math.pi / 30) == pytest.approx(0.046, abs=5e-4)
    assert case.bearing_number(90000 * math.pi / 30) == pytest.approx(0.41, abs=5e-3)


def test_si_quantity_strings_equal_the_usual_units(tmp_path: Path) -> None:
    data = _edited("bearing", "clearance", "1e-4 m")
    data["actuators"]["angles"] = [f"{a!r} rad" for a in (math.pi / 3, math.pi, 5 * math.pi / 3)]
    case = load_case(_write(tmp_path, data))
    ref = default_case()
    assert case.bearing.clearance == pytest.approx(ref.bearing.clearance)
    assert case.actuators is not None and ref.actuators is not None
    assert case.actuators.angles == pytest.approx(ref.actuators.angles)


def test_rigid_case_without_foil(tmp_path: Path) -> None:
    data = _edited("", "foil", None)
    del data["actuators"]
    case = load_case(_write(tmp_path, data))
    assert case.foil is None and case.actuators is None and case.assembly_stiffness() is None


BAD = [
    (
        "bearing",
        "clearance",
        "5 N",
        r"bearing\.clearance = '5 N': wrong dimension, expected length",
    ),
    ("bearing", "clearance", None, r"bearing\.clearance is missing"),
    ("bearing", "radius", "-20 mm", r"bearing\.radius = '-20 mm': expected a value > 0"),
    ("bearing", "length", "0 mm", r"bearing\.length = '0 mm': expected a value > 0"),
    # a bare number where a dimension is expected, and a unit where there is none
    ("operation", "speed", 10000, r"operation\.speed = 10000: add a unit, e\.g\. '10000 rpm'$"),
    ("bearing", "clearance", "100", r"bearing\.clearance = '100': add a unit, e\.g\. '100 m'$"),
    ("actuators", "angles", [1.0, 3.0, 5.0], r"actuators\.angles\[0\] = 1\.0: add a unit"),
    ("operation", "load", 8.8, r"operation\.load = 8\.8: add a unit, e\.g\. '8\.8 N'$"),
    ("foil", "loss_factor", "0.1 deg", r"foil\.loss_factor is dimensionless: write 0\.1,"),
    ("foil", "loss_factor", "10 %", r"foil\.loss_factor is dimensionless: write 0\.1,"),
    ("foil.bump", "poisson_ratio", "0.29 rad", r"foil\.bump\.poisson_ratio is dimensionless"),
    (
        "actuators",
        "angles",
        ["60 deg", "400 deg", "300 deg"],
        r"actuators\.angles\[1\].*0 to below 360",
    ),
    ("actuators", "stinger_arc", "130 deg", r"actuators\.stinger_arc.*arcs overlap"),
    (
        "actuators",
        "voltages",
        "200 V",
        r"actuators\.voltages\[0\] = 200 V: allowed 0 to max_voltage",
    ),
    ("actuators", "voltages", ["1 V", "2 V"], r"actuators\.voltages.*1 or 3 values"),
    ("foil", "loss_factor", -0.1, r"foil\.loss_factor = -0\.1: expected a value >= 0"),
    ("foil", "loss_fator", 0.1, r"unknown field 'loss_fator' in \[foil\]"),
    ("gas", "viscosity", "1.85e-5 Pa", r"gas\.viscosity.*wrong dimension"),
    ("grid", "n_theta", 3, r"grid\.n_theta = 3: expected an integer from 24"),
    ("operation", "speed", "0 rpm", r"operation\.speed = '0 rpm': expected a value > 0"),
    (
        "disturbance",
        "force_rms",
        "-0.1 N",
        r"disturbance\.force_rms = '-0\.1 N': expected a value >= 0",
    ),
    (
        "disturbance",
        "max_frequency",
        "2 Hz",
        r"disturbance\.max_frequency = '2 Hz': expected above min_frequency \(5 Hz\)",
    ),
    ("disturbance", "tones", 0, r"disturbance\.tones = 0: expected an integer from 1 to 4096"),
    ("disturbance", "force", "1 N", r"unknown field 'force' in \[disturbance\]"),
    (
        "bearing",
        "clearance",
        "50 um",
        r"base preload of 72\.94 um, at or beyond the clearance 50\.00",
    ),
]


@pytest.mark.parametrize(("table", "key", "value", "pattern"), BAD)
def test_bad_case_gives_one_line_error(tmp_path: Path, table, key, value, pattern) -> None:
    data = _edited(table, key, value)
    if pattern.startswith("base preload"):
        data["actuators"]["voltages"] = "150 V"
    path = _write(tmp_path, data)
    with pytest.raises(InputError) as info:
        load_case(path)
    message = str(info.value)
    assert message.startswith(str(path))
    assert "\n" not in message
    assert re.search(pattern, message), message


def test_cli_reports_bad_case_without_traceback(tmp_path: Path, capsys) -> None:
    path = _write(tmp_path, _edited("bearing", "clearance", "5 N"))
    assert main(["case", "show", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and "bearing.clearance" in err
    assert main(["case", "show", str(tmp_path / "missing.toml")]) == 2
    assert "case file not found" in capsys.readouterr().err
    (tmp_path / "broken.toml").write_text("[bearing\nradius = ")
    assert main(["case", "show", str(tmp_path / "broken.toml")]) == 2
    assert "not valid TOML" in capsys.readouterr().err


# Values a malformed case may carry: wrong types, wrong units, nonsense strings, extremes.
junk = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-(10**6), 10**6),
    st.floats(allow_nan=True),
    st.text(max_size=12),
    st.sampled_from(
        [
            "5 N",
            "1 m",
            "-3 mm",
            "nan",
            "inf um",
            "1e400 m",
            "60 deg",
            "0",
            "kg*m",
            "150 V",
            "3 rpm",
            "1/0",
        ]
    ),
    st.lists(st.sampled_from(["60 deg", "1 m", 3, "x"]), max_size=4),
    st.dictionaries(st.text(max_size=5), st.integers(), max_size=2),
)
FIELDS = [(t, k) for t, v in DEFAULT.items() if isinstance(v, dict) for k in v] + [("", "title")]


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(edits=st.lists(st.tuples(st.sampled_from(FIELDS), junk), min_size=1, max_size=3))
def test_malformed_cases_always_give_input_error(edits) -> None:
    data = tomllib.loads(default_case_path().read_text())
    for (table, key), value in edits:
        target = data[table] if table else data
        if value is None:
            target.pop(key, None)
        else:
            target[key] = value
    try:
        case = case_from_dict(data, source="fuzz.toml")
    except InputError as exc:
        assert str(exc).startswith("fuzz.toml: ") and "\n" not in str(exc)
    else:
        # Whatever loads must be physically sensible.
        b = case.bearing
        assert b.radius > 0 and b.length > 0 and b.clearance > 0
        if case.actuators is not None:
            assert all(0 <= d < b.clearance for d in case.actuators.base_preloads())


@pytest.mark.parametrize(
    "text", ["100", "7", "-3", "+2", "0", "-0", "0.127", "3.54e-4", "5.", "1E3"]
)
def test_quantities_parsed_without_pint_equal_pint_to_the_bit(text: str) -> None:
    """The fast path of ``parse_quantity`` (plain "value unit" strings of known units) gives
    the float that pint gives, for every unit it knows, with and without a space."""
    from foilbearing.units import _FAST_UNITS, SI_UNITS, _fast_quantity, ureg

    for unit, (kind, factor) in _FAST_UNITS.items():
        assert ureg.Quantity(1, unit).to(SI_UNITS[kind]).magnitude == factor
        for value in (f"{text} {unit}", f"{text}{unit}", f" {text}  {unit} "):
            fast = _fast_quantity(value, kind)
            want = float(ureg.Quantity(value).to(SI_UNITS[kind]).magnitude)
            assert fast is not None
            assert math.copysign(1.0, fast) == math.copysign(1.0, want)
            assert fast == want, (value, fast, want)


def test_from_si_agrees_with_pint_and_inverts_the_parser() -> None:
    """``from_si`` (the headlines' conversion out of SI) against pint for every unit of the fast
    path, and the round trip through ``parse_quantity``; mixed kinds are a pint error."""
    import numpy as np
    import pint

    from foilbearing.units import _FAST_UNITS, SI_UNITS, from_si, parse_quantity, ureg

    values = np.array([3.7e-5, 0.127, 1.0, 42.0, 9.3e4])
    for unit, (kind, _factor) in _FAST_UNITS.items():
        si = SI_UNITS[kind]
        want = ureg.Quantity(values, si).to(unit).magnitude
        np.testing.assert_allclose(from_si(values, unit, si), want, rtol=4e-16, atol=0)
        back = parse_quantity(f"{from_si(0.127, unit, si)!r} {unit}", kind, field="x")
        assert back == pytest.approx(0.127, rel=4e-16)
    # a unit outside the fast path goes through pint; the same unit is no conversion
    assert from_si(2.0, "N*mm", "N*m") == pytest.approx(2000.0, rel=1e-15)
    assert from_si(values, "m", "m") is values
    with pytest.raises(pint.DimensionalityError):
        from_si(1.0, "um", "rad/s")


def test_the_default_case_loads_without_pint() -> None:
    """``foilbearing case show`` starts quickly: the built-in case's quantities need no pint
    (its registry takes longer to build than the whole command)."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from foilbearing.case import load_case\n"
        "load_case(None)\n"
        "print('pint' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
