"""The command line: subcommands, JSON with unit-named keys, one-line errors."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from foilbearing.cli.main import main, parse_list
from foilbearing.errors import InputError


def _json(capsys) -> dict:
    return json.loads(capsys.readouterr().out)


def test_help_lists_subcommands(capsys) -> None:
    with pytest.raises(SystemExit) as info:
        main(["--help"])
    assert info.value.code == 0
    text = capsys.readouterr().out
    for name in ("case", "structure", "identify", "study"):
        assert name in text


def test_every_command_s_help_is_plain_text(capsys) -> None:
    """Each subcommand's --help reads as text: no reST quotes (``x``) from the docstrings
    a description is taken from."""
    with pytest.raises(SystemExit):
        main(["--help"])
    listing = capsys.readouterr().out
    names = re.findall(r"^ {4}([a-z]+)\b", listing, flags=re.MULTILINE)  # the subcommands
    assert {"sweep", "uncertainty", "optimize", "schedule", "study"} <= set(names)
    for name in names:
        with pytest.raises(SystemExit) as info:
            main([name, "--help"])
        assert info.value.code == 0
        text = capsys.readouterr().out
        assert "``" not in text, name


def test_a_command_s_text_output_shows_six_digits(capsys) -> None:
    """The commands' text output (orbit, bifurcation, identify) prints numbers and lists of
    numbers to six significant digits; --json keeps them whole."""
    from foilbearing.cli.common import print_fields

    print_fields({"hopf_speed_rpm": 64837.5299338583, "bifurcation_type": "supercritical",
                  "amplitude_um": [0.06257075150328023, 8.063568675744774],
                  "stable": [True, False], "message": None, "steps": 8})  # fmt: skip
    lines = [line.split(None, 1) for line in capsys.readouterr().out.splitlines()]
    assert dict(lines) == {
        "hopf_speed_rpm": "64837.5",
        "bifurcation_type": "supercritical",
        "amplitude_um": "[0.0625708, 8.06357]",
        "stable": "[True, False]",
        "message": "None",
        "steps": "8",
    }


def test_case_show_json(capsys) -> None:
    assert main(["case", "show", "--json"]) == 0
    out = _json(capsys)
    assert out["clearance_um"] == pytest.approx(100.0)
    assert out["k_assy_N_per_m3"] == pytest.approx(1.14e9, rel=5e-3)
    assert out["bearing_number"] == pytest.approx(0.229, abs=1e-3)  # Λ at 50 krpm


def test_structure_json_and_figures(tmp_path: Path, capsys) -> None:
    assert main(["structure", "--voltage", "50,100,150V", "--plot", str(tmp_path), "--json"]) == 0
    out = _json(capsys)
    assert out["stack_stroke_um"] == pytest.approx([38.61, 63.22, 73.83], abs=0.005)
    assert out["base_preload_um"] == pytest.approx([38.15, 62.36, 72.92], rel=2e-3)
    for fig in out["figures"]:
        assert Path(fig).stat().st_size > 10_000  # a real PNG, written atomically
    assert not list(tmp_path.glob(".*.part"))


def test_structure_rejects_voltage_beyond_stack_limit(capsys) -> None:
    assert main(["structure", "--voltage", "200V"]) == 2
    assert "allowed 0 to 150 V" in capsys.readouterr().err


def test_parse_list_units() -> None:
    assert parse_list("0,50,100,150V", "voltage", "--voltage") == [0.0, 50.0, 100.0, 150.0]
    rpm = 2 * 3.141592653589793 / 60
    assert parse_list("10000,90000rpm", "speed", "--speed") == pytest.approx(
        [10000 * rpm, 90000 * rpm]
    )
    assert parse_list("1krpm,2000rpm", "speed", "--speed") == pytest.approx(
        [1000 * rpm, 2000 * rpm]
    )
    with pytest.raises(InputError, match="wrong dimension"):
        parse_list("10000 N", "speed", "--speed")


def test_static_writes_a_film_that_carries_the_load_and_fails_with_exit_code_3(
    write_case, tmp_path: Path, capsys
) -> None:
    """The NetCDF of `foilbearing static`, read back through its units attributes, holds a
    pressure field whose integral is the load (8.8 N along X, a force balance computed
    here, not by the code). A load the film cannot carry exits with 3 and says what to
    try."""
    import numpy as np
    import xarray as xr

    from foilbearing.units import ureg

    nc = tmp_path / "static.nc"
    assert (
        main(["static", "--speed", "50000rpm", "--voltage", "150V", "--json", "--out", str(nc)])
        == 0
    )
    head = json.loads(capsys.readouterr().out)
    ds = xr.load_dataset(nc)
    assert float(ds["eccentricity"]) == head["eccentricity"] and head["converged"]

    def si(name: str, unit: str) -> np.ndarray:
        return np.asarray(
            ureg.Quantity(ds[name].values, ds[name].attrs["units"]).to(unit).magnitude
        )

    gauge = si("pressure", "Pa") - 101325.0
    theta, z = si("theta", "rad"), si("z", "m")
    radius = 0.02
    dz = 2 * z[0]  # cell-centred: the first centre is half a cell from the mid-plane
    d_area = 2 * radius * (2 * np.pi / theta.size) * dz  # x 2: both halves of the bearing
    fx = float((gauge * np.cos(theta)[:, None]).sum() * d_area)
    fy = float((gauge * np.sin(theta)[:, None]).sum() * d_area)
    assert abs(fx) == pytest.approx(8.8, rel=1e-6) and abs(fy) < 1e-6 * 8.8

    def heavy(d) -> None:
        del d["actuators"], d["foil"]
        d["operation"]["load"] = "5000 N"

    path = write_case("heavy", n_theta=32, n_z=4, edit=heavy)
    assert main(["static", str(path), "--speed", "50000rpm", "--json"]) == 3
    out = json.loads(capsys.readouterr().out)
    assert not out["converged"] and "Try:" in out["message"]


def test_identify_recovers_the_papers_coefficients_from_the_example_data(capsys) -> None:
    """`foilbearing identify` on the shipped (synthetic) measurements returns the paper's
    identified values (D33,1 = -0.0028 um/V², D33,2 = 0.9122 um/V, K_p = 0.46e6 N/m, so
    k_p = 1.30e9 N/m³) within three of its own standard errors: the files carry noise."""
    assert main(["identify", "--json"]) == 0
    head = json.loads(capsys.readouterr().out)
    for key, paper in (("d33_1_um_per_V2", -0.0028), ("d33_2_um_per_V", 0.9122)):
        se = head[key.replace("_um", "_se_um")]
        assert abs(head[key] - paper) < 3 * se, (key, head[key], se)
    assert head["k_p_N_per_m3"] == pytest.approx(1.30e9, rel=0.01)


def test_a_closed_stdout_ends_the_command_quietly() -> None:
    # ``foilbearing case show --json | head -0``: stdout is a pipe whose reader has gone, so
    # the command's first write (here the interpreter's flush) fails with EPIPE.
    import os
    import subprocess
    import sys

    read_end, write_end = os.pipe()
    os.close(read_end)  # no reader from the start: deterministic, unlike racing a real `head`
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).parents[1] / "src"))
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "foilbearing", "case", "show", "--json"],
            stdout=write_end,
            stderr=subprocess.PIPE,
            env=env,
            timeout=60,
        )
    finally:
        os.close(write_end)
    err = proc.stderr.decode()
    assert "Traceback" not in err and "BrokenPipeError" not in err, err
    assert proc.returncode == 141  # 128 + SIGPIPE, as a shell reports `yes | head`


@pytest.mark.parametrize("argv", [["--speed", "-5rpm"], ["--speed=-5rpm"]])
def test_a_negative_speed_is_one_line_naming_the_option(argv: list[str], capsys) -> None:
    # argparse alone reads "-5rpm" after --speed as an unknown option ("expected one argument").
    assert main(["static", *argv]) == 2
    err = capsys.readouterr().err
    assert err == "foilbearing: error: --speed = '-5rpm': a speed must be > 0\n"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["coefficients", "--speed", "-5rpm"], "--speed = '-5rpm': a speed must be > 0"),
        (
            ["coefficients", "--frequency", "-100,200Hz"],
            "--frequency = '-100,200Hz': a frequency must be > 0",
        ),
        (["static", "--voltage", "-50V"], "--voltage = '-50V': allowed 0 to 150 V (max_voltage)"),
        (
            ["stability", "--voltage", "-50,0V"],
            "--voltage = '-50,0V': allowed 0 to 150 V (max_voltage)",
        ),
        (["orbit", "--speed", "-5rpm"], "--speed = '-5rpm': a speed must be > 0"),
        (
            ["orbit", "--speed", "5000rpm", "--duration", "-1s"],
            "--duration = '-1s': a duration must be > 0",
        ),
        (["orbit", "--stop-time", "-1s"], "--stop-time = '-1s': a time must be > 0"),
        (["orbit", "--sample-rate", "-1e4Hz"], "--sample-rate = '-1e4Hz': a frequency must be > 0"),
        (
            ["optimize", "--objective", "drag", "--speed", "-5rpm"],
            "--speed = '-5rpm': a speed must be > 0",
        ),
        (
            ["optimize", "--objective", "drag", "--speed", "5000rpm", "--load", "-5N"],
            "--load = '-5N': a load must be >= 0",
        ),
        (["schedule", "--margin", "-0.1"], "--margin -0.1: expected a log decrement >= 0"),
        (["identify", "--contact-area", "-3e-4m**2"], "--contact-area '-3e-4m**2': must be > 0"),
    ],
)
def test_negative_quantities_reach_the_parser_and_get_a_range_error(
    argv: list[str], message: str, capsys
) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err, err


def test_a_negative_eccentricity_is_a_value_not_an_option(capsys) -> None:
    assert main(["static", "--eccentricity", "-0.3,0.2", "--speed", "50000rpm", "--json"]) == 0
    out = _json(capsys)
    assert out["eccentricity"] == pytest.approx((0.3**2 + 0.2**2) ** 0.5)


def test_attach_negative_values_joins_only_a_negative_after_a_long_option() -> None:
    from foilbearing.cli.common import attach_negative_values

    argv = ["static", "--speed", "-5rpm", "--eccentricity", "-.3,0.2", "--out", "-x.nc"]
    assert attach_negative_values(argv) == [
        "static",
        "--speed=-5rpm",
        "--eccentricity=-.3,0.2",
        "--out",
        "-x.nc",  # not a number: argparse's own error stays
    ]
    assert attach_negative_values(["--voltage=-5V", "-1", "--", "--speed", "-5rpm"]) == [
        "--voltage=-5V",
        "-1",
        "--",
        "--speed",
        "-5rpm",
    ]


@pytest.mark.parametrize(
    "argv",
    [
        ["static", "--speed=1e7rpm", "--json"],
        ["coefficients", "--speed=5e6rpm"],
        ["stability", "--voltage", "150V", "--speed-range", "100000rpm:200000rpm:50000rpm"],
        ["orbit", "--speed", "200000rpm", "--duration", "0.01s"],
    ],
    ids=["static", "coefficients", "stability", "orbit"],
)
def test_a_speed_above_the_cases_max_speed_is_refused_before_any_work(argv, capsys) -> None:
    # Issue 33: a film solved at 21 km/s surface speed is no answer. Every analysis refuses
    # speeds above [operation] max_speed (150 krpm here) in one line naming the field.
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "operation.max_speed = 150000 rpm" in err[0]
