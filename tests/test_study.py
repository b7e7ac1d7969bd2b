"""The main job: `foilbearing study` on the default case writes every figure and the comparison."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import xarray as xr

from foilbearing.cli.main import main


@pytest.mark.slow
def test_study_writes_figures_results_and_comparison(tmp_path: Path, capsys) -> None:
    argv = ["study", "--out", str(tmp_path), "--orbits", "none", "--uncertainty", "none"]
    argv += ["--schedule", "none"]
    assert main([*argv, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    for name in (
        "fig05b_stack_displacement.png",
        "fig06_stack_stiffness.png",
        "fig07_stiffness_function.png",
        "fig08_preloads.png",
        "fig09_midplane.png",
        "fig10_actuator_pressure.png",
        "fig11_preload.png",
        "fig12_eccentricity.png",
    ):
        assert (tmp_path / name).stat().st_size > 10_000, name
    ds = xr.open_dataset(tmp_path / "static_sweep.nc")
    assert bool(ds.converged.all())
    assert ds.sizes["speed"] == 9 and ds.sizes["voltage"] == 4
    rows = {r["quantity"]: r for r in summary["paper_comparison"]}
    assert "k_assy (N/m³)" in rows
    assert (tmp_path / "paper_comparison.md").read_text().count("|") > 50
    assert json.loads((tmp_path / "summary.json").read_text())["structure"]["k_b_N_per_m3"] > 0
    onsets = [e["onset_speed_rpm"] for e in summary["stability"]["C-GFB"]]
    assert all(o is not None and o > 5000 for o in onsets)
