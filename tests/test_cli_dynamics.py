"""The coefficients and stability commands: JSON keys with units, errors before work."""

from __future__ import annotations

import json

import pytest

from foilbearing.cli.main import main


def test_coefficients_json(capsys) -> None:
    argv = [
        "coefficients",
        "--speed",
        "50000rpm",
        "--voltage",
        "150V",
        "--frequency",
        "100,800Hz",
        "--json",
    ]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert len(out["K_N_per_m"]) == 2 and len(out["K_N_per_m"][0]) == 2
    assert out["frequency_Hz"] == pytest.approx([100.0, 800.0])
    assert out["K_N_per_m"][0][0][0] > 0  # direct stiffness is positive


def test_stability_json(capsys) -> None:
    argv = [
        "stability",
        "--voltage",
        "0,150V",
        "--speed-range",
        "10000rpm:80000rpm:10000rpm",
        "--json",
    ]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    entries = out["voltages"]
    assert [e["voltage_V"] for e in entries] == [0.0, 150.0]
    for e in entries:
        assert {"onset_speed_rpm", "whirl_frequency_Hz", "whirl_ratio"} <= set(e)
        assert 10000 < e["onset_speed_rpm"] < 80000


@pytest.mark.parametrize(
    ("argv", "text"),
    [
        (["coefficients", "--frequency", "0Hz"], "--frequency = '0Hz': a frequency must be > 0"),
        (["coefficients", "--speed", "2000Hz"], "not Hz"),
        (["stability", "--speed-range", "9000rpm:1000rpm:10rpm"], "START < STOP"),
        (["stability", "--voltage", "300V"], "--voltage = '300V': allowed 0 to 150 V"),
        (["static", "--subambient", "gumbel"], "subambient = 'gumbel': expected one of"),
    ],
)
def test_bad_arguments(argv, text, capsys) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert text in err and "Traceback" not in err


def test_subambient_option_on_a_rigid_bearing_is_a_one_line_error(tmp_path, capsys) -> None:
    # A bearing without [foil] holds sub-ambient pressure: asking it for lift-off is refused
    # with one line naming the option, the value and the file, before any work.
    import tomlkit

    from foilbearing.case import default_case_path

    data = tomlkit.parse(default_case_path().read_text())
    for table in ("foil", "actuators"):
        del data[table]
    path = tmp_path / "rigid.toml"
    path.write_text(tomlkit.dumps(data))
    assert main(["static", str(path), "--subambient", "lift-off", "--json"]) == 2
    err = capsys.readouterr().err.strip()
    assert "subambient = 'lift-off'" in err and "no [foil]" in err and "rigid.toml" in err
    assert len(err.splitlines()) == 1
