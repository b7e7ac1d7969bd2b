"""Units where a person types a number: a bare number for a dimension is refused, a unit on
a dimensionless field too, in every file the package reads and on the command line."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from foilbearing.case import case_from_dict, load_case
from foilbearing.cli.main import main
from foilbearing.errors import InputError
from foilbearing.rotor.toml import load_rotor
from foilbearing.schedule_file import load_schedule
from foilbearing.sweep.spec import load_sweep
from foilbearing.uncertainty.spec import load_uncertainty
from foilbearing.units import SI_UNITS, parse_quantity, si_text

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            lambda d: d["operation"].update(speed=10000),
            "operation.speed = 10000: add a unit, e.g. '10000 rpm'",
        ),
        (
            lambda d: d["foil"].update(loss_factor="0.1 deg"),
            "foil.loss_factor is dimensionless: write 0.1, not '0.1 deg'",
        ),
    ],
)
def test_the_cli_refuses_a_bare_speed_and_a_unit_on_a_loss_factor(
    write_case, edit, message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    """Exit 2, one line on stderr naming the file, the field and the value."""
    path = write_case("units_bad", edit=edit)
    assert main(["case", "show", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0, err
    assert str(path) in err and message in err


def test_a_bare_number_on_the_command_line_asks_for_a_unit(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["static", "--speed", "10000"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--speed = '10000': add a unit, e.g. '10000 rpm'" in err and "\n" not in err


@pytest.mark.parametrize(
    ("kind", "value", "message"),
    [
        ("length", 1e-4, "add a unit, e.g. '0.0001 m'"),
        ("angle", "60", "add a unit, e.g. '60 deg'"),
        ("force", "8.8", "add a unit, e.g. '8.8 N'"),
        ("dimensionless", "5 percent", "dimensionless: write 0.05"),
        ("dimensionless", "0.3 rad", "dimensionless: write 0.3"),
        ("frequency", "60 rpm", "give a frequency in Hz"),  # pint: 60 rpm = 2π Hz
    ],
)
def test_parse_quantity_refuses_what_would_be_read_as_something_else(
    kind: str, value: object, message: str
) -> None:
    with pytest.raises(InputError, match=message):
        parse_quantity(value, kind, field="f")


@pytest.mark.parametrize("kind", [k for k, u in SI_UNITS.items() if u])
def test_si_text_reads_back_to_the_same_float(kind: str) -> None:
    """What the uncertainty analysis writes into a case for a sample reads back exactly."""
    for value in (1.0, 1.85e-5, math.pi / 3, 8.69e9, -2.8e-9):
        text = si_text(value, kind)
        assert isinstance(text, str) and parse_quantity(text, kind, field="f") == value


def _write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def test_sweep_uncertainty_schedule_and_rotor_files_refuse_bare_numbers(tmp_path: Path) -> None:
    cases = [
        (
            lambda: load_sweep(
                _write(tmp_path, "s.toml", "[parameters]\nspeed = [10000, 20000]\n")
            ),
            r"parameters\.speed\[0\] = 10000: add a unit",
        ),
        (
            lambda: load_sweep(
                _write(
                    tmp_path,
                    "s2.toml",
                    '[set]\n"operation.load" = 8.8\n[parameters]\nspeed = ["10 krpm"]\n',
                )
            ),
            r"operation\.load = 8\.8: add a unit",
        ),
        (
            lambda: load_uncertainty(
                _write(
                    tmp_path,
                    "u.toml",
                    '[inputs]\n"bearing.clearance" = { distribution = "uniform", '
                    "low = 8e-5, high = 1.2e-4 }\n",
                )
            ),
            r"inputs\.bearing\.clearance\[0\] = 8e-05: add a unit",
        ),
        (
            lambda: load_uncertainty(
                _write(
                    tmp_path,
                    "u2.toml",
                    '[inputs]\n"foil.loss_factor" = { distribution = "uniform", '
                    'low = "0.05 deg", high = 0.2 }\n',
                )
            ),
            r"loss_factor\[0\] is dimensionless: write 0\.05",
        ),
        (
            lambda: load_schedule(
                _write(tmp_path, "sch.toml", '[[point]]\nspeed = 20000\nvoltages = "0 V"\n'),
                load_case(None),
            ),
            r"point\[0\]\.speed = 20000: add a unit, e\.g\. '20000 rpm'",
        ),
        (
            lambda: load_rotor(
                _write(
                    tmp_path,
                    "r.toml",
                    (EXAMPLES / "rotor_rigid_symmetric.toml")
                    .read_text(encoding="utf-8")
                    .replace('mass = "0.8074 kg"', "mass = 0.8074"),
                )
            ),
            r"mass = 0\.8074: add a unit, e\.g\. '0\.8074 kg'",
        ),
    ]
    for read, pattern in cases:
        with pytest.raises(InputError, match=pattern) as info:
            read()
        assert "\n" not in str(info.value) and str(tmp_path) in str(info.value)


def test_every_shipped_file_is_valid_under_the_strict_reading() -> None:
    """The built-in case, the example files and the uncertainty file's sample points."""
    load_case(None)
    for name in ("sweep_voltage_speed.toml", "sweep_bifurcation.toml"):
        load_sweep(EXAMPLES / name)
    for name in ("rotor_rigid_symmetric.toml", "rotor_two_disk.toml"):
        load_rotor(EXAMPLES / name)
    spec = load_uncertainty(EXAMPLES / "uncertainty_paper.toml", samples=56)
    case = case_from_dict(spec.point_data(0), source="point 0")
    by_name = {"bearing.clearance": case.bearing.clearance, "gas.viscosity": case.gas.viscosity}
    for k, inp in enumerate(spec.inputs):
        if inp.name in by_name:
            assert by_name[inp.name] == spec.design[0, k]  # exact: written in SI with its unit


def test_the_python_api_takes_quantities_and_floats_stay_si(write_case) -> None:
    """``"30 krpm"``, a pint Quantity and the SI float give the same case and the same
    solutions, within round-off (1e-14: pint's prefixes multiply the factors in another
    order); a frequency in Hz is an excitation of 2π times as many rad/s."""
    import numpy as np
    import pint

    from foilbearing.coefficients import force_coefficients
    from foilbearing.constants import RPM
    from foilbearing.control import constant_speed, linear_ramp
    from foilbearing.static import solve_equilibrium

    user = pint.UnitRegistry()  # the user's own registry, not ours
    case = load_case(write_case("api_units", n_theta=32, n_z=4))
    assert (
        case.with_load("50 N") == case.with_load(50.0) == case.with_load(user.Quantity(0.05, "kN"))
    )
    assert case.with_speed("30 krpm").operation.speed == pytest.approx(30_000 * RPM, rel=1e-14)
    by_text = solve_equilibrium(case, speed="30 krpm")
    by_float = solve_equilibrium(case, speed=30_000 * RPM)
    by_pint = solve_equilibrium(case, speed=user.Quantity(30_000, "rpm"))
    for other in (by_text, by_pint):
        assert other.eccentricity == pytest.approx(by_float.eccentricity, rel=1e-12)
    in_hz = force_coefficients(by_float, ["100 Hz", user.Quantity(0.5, "kHz")])
    in_rad_s = force_coefficients(by_float, 2 * np.pi * np.array([100.0, 500.0]))
    np.testing.assert_allclose(in_hz.K, in_rad_s.K, rtol=1e-12)
    np.testing.assert_allclose(in_hz.C, in_rad_s.C, rtol=1e-12)
    ramp, ramp_si = (
        linear_ramp("3 krpm", "9 krpm", "500 rad/s**2"),
        linear_ramp(3000 * RPM, 9000 * RPM, 500.0),
    )
    np.testing.assert_allclose(ramp.times, ramp_si.times, rtol=1e-14)
    np.testing.assert_allclose(ramp.speeds, ramp_si.speeds, rtol=1e-14)
    steady = constant_speed("30 krpm", "0.5 s")
    np.testing.assert_allclose(steady.speeds, [30_000 * RPM] * 2, rtol=1e-14)
    assert steady.times[-1] == 0.5
    for call, message in (
        (lambda: case.with_load("5 kg"), r"operation\.load = '5 kg': wrong dimension"),
        (lambda: case.with_speed("500 Hz"), r"not Hz"),
        (lambda: solve_equilibrium(case, speed=user.Quantity(3, "m")), r"speed = .*wrong dim"),
    ):
        with pytest.raises(InputError, match=message) as info:
            call()
        assert "\n" not in str(info.value)


def test_voltages_mass_and_map_speeds_take_quantities_too(write_case) -> None:
    """The rest of the API's audit: ``Case.with_voltages``, ``whirl_mode``'s mass and
    ``stability_map``'s speeds and voltages give, for quantities, what the SI floats
    give (the same floats, so the same numbers); a wrong dimension is one line."""
    import numpy as np
    import pint

    from foilbearing.constants import RPM
    from foilbearing.stability import stability_map, whirl_mode
    from foilbearing.static import solve_equilibrium

    user = pint.UnitRegistry()
    case = load_case(write_case("api_units_more", n_theta=32, n_z=4))
    assert case.with_voltages("150 V") == case.with_voltages(150.0)
    assert case.with_voltages(user.Quantity(0.15, "kV")) == case.with_voltages(150.0)
    n_act = len(case.actuators.angles)
    volts = [f"{50 * k} V" for k in range(n_act)]
    assert case.with_voltages(volts) == case.with_voltages(tuple(50.0 * k for k in range(n_act)))
    static = solve_equilibrium(case, speed=40_000 * RPM)
    mass = case.rotor.mass
    by_float = whirl_mode(static, mass)
    assert whirl_mode(static, f"{mass * 1000!r} g").eigenvalue == pytest.approx(
        by_float.eigenvalue, rel=1e-12
    )
    by_text = stability_map(case, ["30 krpm", "40 krpm"], ["0 V", "150 V"])
    by_si = stability_map(case, [30_000 * RPM, 40_000 * RPM], [0.0, 150.0])
    np.testing.assert_allclose(by_text.log_decrement, by_si.log_decrement, rtol=1e-12)
    for call, message in (
        (lambda: case.with_voltages("150 N"), r"actuators\.voltages = '150 N': wrong dim"),
        (lambda: whirl_mode(static, "3 N"), r"mass = '3 N': wrong dim"),
        (lambda: stability_map(case, ["30 kHz"], [0.0]), r"speeds.*not Hz"),
    ):
        with pytest.raises(InputError, match=message) as info:
            call()
        assert "\n" not in str(info.value)
