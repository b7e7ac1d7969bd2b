"""The coefficients and stability commands: JSON keys with units, errors before work."""

from __future__ import annotations

import json

import pytest

from foilbearing.cli import main


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
        "5000rpm:40000rpm:5000rpm",
        "--json",
    ]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    entries = out["voltages"]
    assert [e["voltage_V"] for e in entries] == [0.0, 150.0]
    for e in entries:
        assert {"onset_speed_rpm", "whirl_frequency_Hz", "whirl_ratio"} <= set(e)
        assert 5000 < e["onset_speed_rpm"] < 40000


@pytest.mark.parametrize(
    ("argv", "text"),
    [
        (["coefficients", "--frequency", "0Hz"], "every frequency must be > 0"),
        (["coefficients", "--speed", "2000Hz"], "not Hz"),
        (["stability", "--speed-range", "9000rpm:1000rpm:10rpm"], "START < STOP"),
        (["stability", "--voltage", "300V"], "allowed 0 to max_voltage"),
    ],
)
def test_bad_arguments(argv, text, capsys) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert text in err and "Traceback" not in err
