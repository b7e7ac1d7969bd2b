"""Load as an input like speed: ``Case.with_load``, ``--load`` on the analyses, its coordinate."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from foilbearing.case import load_case
from foilbearing.cli.main import main
from foilbearing.errors import InputError
from foilbearing.static import solve_equilibrium

#: The loads of the tests, N: from a light to a heavy film on the default bearing at 50 krpm.
LOADS = (4.0, 8.8, 20.0)


@pytest.fixture(scope="module")
def coarse_case(write_case) -> Path:
    """The default case on a 32 × 4 grid (a fast film; the balance does not depend on it)."""
    return write_case("load_coarse", n_theta=32, n_z=4)


def _json(capsys: pytest.CaptureFixture[str], argv: list[str]) -> tuple[int, dict]:
    code = main(argv)
    return code, json.loads(capsys.readouterr().out)


def test_with_load_sets_the_load_and_keeps_the_rotor_mass(coarse_case: Path) -> None:
    case = load_case(coarse_case)
    heavier = case.with_load(20.0)
    assert heavier.operation.load == 20.0
    assert heavier.rotor == case.rotor
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(InputError, match=r"operation\.load"):
            case.with_load(bad)


def test_a_load_list_gives_the_single_runs_points_and_each_film_carries_its_load(
    coarse_case: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``static --load`` over three loads equals three single runs (the same solve, so to
    round-off, 1e-12), and each equilibrium's film force balances its load: the solver
    stops when |F + W|/W < 1e-8 (``EquilibriumOptions.force_tol``); we ask 1e-7 of W.
    The NetCDF file carries the loads as the ``load`` coordinate in N."""
    nc = tmp_path / "loads.nc"
    argv = ["static", str(coarse_case), "--speed", "50000rpm", "--json"]
    code, swept = _json(capsys, [*argv, "--load", "4,8.8,20N", "--out", str(nc)])
    assert code == 0
    assert [e["load_N"] for e in swept["loads"]] == list(LOADS)
    for load, entry in zip(LOADS, swept["loads"], strict=True):
        code, single = _json(capsys, [*argv, "--load", f"{load}N"])
        assert code == 0
        assert single["load_N"] == load
        for key in ("eccentricity", "attitude_deg", "min_film_um"):
            assert entry[key] == pytest.approx(single[key], rel=1e-12)
        f_x, f_y = entry["force_N"]
        assert abs(f_x + load) <= 1e-7 * load  # the film pushes against +X
        assert abs(f_y) <= 1e-7 * load
    ds = xr.load_dataset(nc)
    assert ds["load"].attrs["units"] == "N"
    np.testing.assert_array_equal(ds["load"].values, LOADS)
    np.testing.assert_allclose(-ds["force"].sel(axis="X").values, LOADS, rtol=1e-7)
    # the heavier the load, the larger the eccentricity
    assert np.all(np.diff(ds["eccentricity"].values) > 0)


def test_the_api_and_a_speed_sweep_agree_on_a_load(
    coarse_case: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A speed list under a load list gives, at each (load, speed), the API's equilibrium of
    ``with_load(load)`` at that speed (1e-9: the sweep starts each speed from the last)."""
    argv = ["static", str(coarse_case), "--speed", "30000,50000rpm", "--load", "4,20N", "--json"]
    code, swept = _json(capsys, argv)
    assert code == 0
    case = load_case(coarse_case)
    for entry in swept["loads"]:
        for point in entry["points"]:
            res = solve_equilibrium(
                case.with_load(entry["load_N"]), speed=point["speed_rpm"] * np.pi / 30
            )
            assert point["eccentricity"] == pytest.approx(res.eccentricity, rel=1e-6)
            assert -point["force_N"][0] == pytest.approx(entry["load_N"], rel=1e-6)


def test_coefficients_over_loads_stack_along_the_load_coordinate(
    coarse_case: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    nc = tmp_path / "coef.nc"
    argv = ["coefficients", str(coarse_case), "--frequency", "800Hz", "--json"]
    code, swept = _json(capsys, [*argv, "--load", "4,20N", "--out", str(nc)])
    assert code == 0
    code, single = _json(capsys, [*argv, "--load", "20N"])
    np.testing.assert_allclose(swept["loads"][1]["K_N_per_m"], single["K_N_per_m"], rtol=1e-12)
    ds = xr.load_dataset(nc)
    assert ds["stiffness"].dims[0] == "load"
    # a heavier load stiffens the film: K_XX grows with the eccentricity
    k_xx = ds["stiffness"].sel(i="X", j="X").values[:, 0]
    assert k_xx[1] > k_xx[0]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["static", "--load", "50"], "--load"),
        (["static", "--load", "-5N"], ">= 0 N"),
        (["orbit", "--load", "5,10N"], "one load"),
    ],
)
def test_a_bad_load_is_a_one_line_error(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err


def test_a_case_with_only_the_load_or_only_the_mass_gets_the_other_by_its_weight(
    write_case,
) -> None:
    """W = m g with the standard gravity when one of them is left out (docs/case-format.md)."""
    only_load = load_case(write_case("only_load", edit=lambda d: d.remove("rotor")))
    assert only_load.rotor.mass == pytest.approx(8.8 / 9.80665, rel=1e-15)
    assert only_load.rotor.imbalance == 0.0
    only_mass = load_case(write_case("only_mass", edit=lambda d: d["operation"].remove("load")))
    assert only_mass.operation.load == pytest.approx(0.897 * 9.80665, rel=1e-15)

    def neither(d) -> None:
        d.remove("rotor")
        d["operation"].remove("load")

    with pytest.raises(InputError, match="both missing"):
        load_case(write_case("neither", edit=neither))


def test_stability_over_loads_equals_single_runs(
    coarse_case: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = [
        "stability",
        str(coarse_case),
        "--voltage",
        "0V",
        "--speed-range",
        "20000rpm:80000rpm:20000rpm",
        "--json",
    ]
    code, swept = _json(capsys, [*argv, "--load", "4,20N"])
    assert code == 0 and [e["load_N"] for e in swept["loads"]] == [4.0, 20.0]
    for entry in swept["loads"]:
        code, single = _json(capsys, [*argv, "--load", f"{entry['load_N']}N"])
        assert single["load_N"] == entry["load_N"] and single["rotor_mass_kg"] == 0.897
        assert single["voltages"] == entry["voltages"]


def test_an_orbit_keeps_its_load_in_the_run_spec() -> None:
    """``orbit --load`` is stored with the run, so that ``--resume`` continues under it."""
    from foilbearing.orbit.spec import RunSpec

    spec = RunSpec.from_cli_strings({"speed": "30000rpm", "duration": "0.01s", "load": "20N"})
    again = RunSpec.from_json(spec.to_json())
    assert again.load == 20.0 and again.load_case().operation.load == 20.0
    assert RunSpec.from_cli_strings({"speed": "30000rpm"}).load_case().operation.load == 8.8
