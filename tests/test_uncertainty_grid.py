"""The grid's error of an uncertainty analysis, measured at the centre of its inputs
(:mod:`foilbearing.uncertainty.grid`): the centre is each input's median, the values on the
case's grid are the sample's own evaluation there, and the error is a discretisation error
(it shrinks under refinement at the statics' order)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from foilbearing.uncertainty import load_uncertainty
from foilbearing.uncertainty.evaluate import ONSET_REL_TOL, evaluate_sample
from foilbearing.uncertainty.grid import centre_case, grid_errors

INPUTS = (
    "[inputs]\n"
    '"bearing.clearance" = { distribution = "uniform", low = "80 um", high = "120 um" }\n'
    '"rotor.imbalance" = { distribution = "log-uniform", low = "1 g*mm", high = "9 g*mm" }\n'
)


def _spec(tmp_path: Path, n_theta: int, n_z: int, stability: bool):
    body = (
        f"samples = 32\n[set]\ngrid.n_theta = {n_theta}\ngrid.n_z = {n_z}\n"
        + INPUTS
        + '[outputs.static]\nspeeds = ["60000 rpm"]\nvoltages = ["150 V"]\n'
    )
    if stability:
        body += (
            '[outputs.stability]\nvoltages = ["150 V"]\n'
            'speed_range = ["10000 rpm", "150000 rpm", "10000 rpm"]\n'
        )
    path = tmp_path / f"uq_{n_theta}.toml"
    path.write_text(body, encoding="utf-8")
    return load_uncertainty(path)


def test_the_centre_is_each_input_s_median_and_its_values_are_the_sample_s(
    tmp_path: Path,
) -> None:
    """The centre's case has the uniform input at its mid-point and the log-uniform one at
    its geometric mean; its outputs on the case's grid are what the sample's evaluation
    gives there (the statics exactly, the onset to the sample's Brent tolerance)."""
    spec = _spec(tmp_path, 48, 6, stability=True)
    case = centre_case(spec)
    assert case.bearing.clearance == pytest.approx(100e-6, rel=1e-12)
    assert case.rotor.imbalance == pytest.approx(math.sqrt(1e-6 * 9e-6), rel=1e-12)
    check = grid_errors(spec)
    assert (check["grid"], check["refined_grid"]) == ([48, 6], [96, 12])
    assert check["centre"]["bearing.clearance"] == pytest.approx(100.0)
    assert check["centre_unit"]["bearing.clearance"] == "μm"
    sample = evaluate_sample(case, spec.options)["outputs"]
    assert set(check["outputs"]) == set(sample)
    for name, value in sample.items():
        tol = 2 * ONSET_REL_TOL if name.startswith(("onset", "whirl")) else 1e-12
        assert check["outputs"][name]["value"] == pytest.approx(value, rel=tol), name
        out = check["outputs"][name]
        assert out["error"] == pytest.approx(out["value"] - out["refined"], rel=1e-12), name


def test_the_grid_error_shrinks_at_the_statics_order(tmp_path: Path) -> None:
    """The error stated on 48 × 6 (against 96 × 12) and on 96 × 12 (against 192 × 24): the
    statics converge at order 2 (docs/numerics.md), so the finer grid's error is about a
    quarter of the coarser one's; at most 0.45 of it is asserted (order > 1.15), for the
    readouts whose difference is well above the solver's tolerance."""
    coarse = grid_errors(_spec(tmp_path, 48, 6, stability=False))["outputs"]
    finer = grid_errors(_spec(tmp_path, 96, 12, stability=False))["outputs"]
    for name in ("eccentricity_ratio[60 krpm, 150 V]", "power_loss_W[60 krpm, 150 V]"):
        e1, e2 = coarse[name]["error"], finer[name]["error"]
        assert abs(e1) > 1e-6 * abs(coarse[name]["value"]), name
        assert abs(e2) < 0.45 * abs(e1), (name, e1, e2)
        # the same value on 96 x 12 from both checks: the refined level of the first
        assert finer[name]["value"] == pytest.approx(coarse[name]["refined"], rel=1e-9)
