"""The command line: subcommands, JSON with unit-named keys, one-line errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from foilbearing.cli import main, parse_list
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
