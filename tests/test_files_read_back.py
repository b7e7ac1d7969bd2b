"""Every file the analyses write reads back, for every kind of bearing (issue 47, item 3).

``tests/test_own_bearing.py`` reopens the static, coefficients, orbit and sweep files of the
example cases; here the remaining writers: the ``bifurcation`` analysis (the command prints
it, a sweep with ``analysis = "bifurcation"`` writes it), ``uncertainty`` and the rotor's
nonlinear run (``rotor --orbit --out``, stopped and resumed), over the four kinds of
bearing: the built-in C-GFB, the first-generation bump foil bearing, the shimmed GFB and
the rigid gas bearing, each on a coarse grid (32 x 4, the shims 48 x 4: see
``tests/test_own_bearing.py``); and the study of a passive bearing. Each file reopens
(``xarray.load_dataset``, ``json.loads``) and holds the numbers the command prints with
``--json``. Where an option does not apply (a voltage on a bearing without actuators),
the answer is the one-line error.

The sweeps and the sample run on an in-process Dask cluster (``--scheduler``), so that
its worker reuses this process's compiled kernels.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import tomlkit
import xarray as xr

from foilbearing.case import default_case_path, load_case
from foilbearing.cli.main import main

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SOURCES = {
    "cgfb": default_case_path(),
    "bump_foil_bearing": EXAMPLES / "bump_foil_bearing.toml",
    "shimmed_gfb": EXAMPLES / "shimmed_gfb.toml",
    "rigid_gas_bearing": EXAMPLES / "rigid_gas_bearing.toml",
}
#: A three-speed onset scan bracketing each bearing's onset on its coarse grid (42.5,
#: 61.2, 88.4 and 10.4 krpm; the whole default scan finds the same ones).
SCANS = {
    "cgfb": "37500rpm:47500rpm:5000rpm",
    "bump_foil_bearing": "55000rpm:65000rpm:5000rpm",
    "shimmed_gfb": "85000rpm:95000rpm:5000rpm",
    "rigid_gas_bearing": "7500rpm:12500rpm:2500rpm",
}
#: The words of a Hopf bifurcation's type (``foilbearing.bifurcation.branch``).
TYPES = ("supercritical", "subcritical", "degenerate")


@pytest.fixture(scope="module")
def coarse(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """Each kind of bearing on 32 x 4 (the shims on 48 x 4), written as a case file."""
    folder = tmp_path_factory.mktemp("cases")
    paths = {}
    for name, source in SOURCES.items():
        data = tomlkit.parse(source.read_text(encoding="utf-8"))
        data["grid"]["n_theta"] = 48 if name == "shimmed_gfb" else 32
        data["grid"]["n_z"] = 4
        paths[name] = folder / f"{name}.toml"
        paths[name].write_text(tomlkit.dumps(data), encoding="utf-8")
    return paths


@pytest.fixture(scope="module")
def scheduler() -> Any:
    """The address of a one-thread Dask cluster in this process."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        processes=False, n_workers=1, threads_per_worker=1, dashboard_address=None
    ) as cluster:
        yield cluster.scheduler_address


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> Any:
    assert main([*argv, "--json"]) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


def _one_line_error(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    assert main(argv) == 2
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert captured.out == "" and len(err.splitlines()) == 1, err
    return err


def _nan(value: Any) -> float:
    """A number as printed (JSON ``null`` is NaN)."""
    return math.nan if value is None else float(value)


@pytest.mark.parametrize("name", list(SOURCES))
def test_bifurcation_sweep_file_holds_the_branch_the_command_prints(
    name: str, coarse: dict[str, Path], scheduler: str, tmp_path: Path, capsys
) -> None:
    """``bifurcation CASE --json`` and a one-point sweep of the same case and options
    (``analysis = "bifurcation"``, the rotor's own mass as the swept value): the sweep's
    ``.nc`` reopens and holds the command's branch. The onset (a scan and Brent's method on
    a smooth function) agrees to 1e-9. The cycles agree to 1e-4: near the onset the branch
    is so flat that the speed of a cycle of given amplitude is set to about 2e-5 only (on
    the bump foil bearing, the onset perturbed in its 13th digit by another scan moves
    both cycles by 1 rpm of 61 krpm, and the two-cycle type from super- to subcritical).
    So the words are compared where their margin is above that: the type where the two
    cycles' speeds are more than 2e-4 apart (the C-GFB's, 30 rpm of 42 krpm), each
    cycle's stability where its largest multiplier is more than 1e-4 from 1."""
    path = coarse[name]
    case = load_case(path)
    printed = _run(["bifurcation", str(path), "--speed-range", SCANS[name], "--steps", "0"], capsys)
    assert printed["bifurcation_type"] in TYPES
    start, stop, step = SCANS[name].split(":")
    sweep = tmp_path / "sweep.toml"
    sweep.write_text(
        f'analysis = "bifurcation"\ncase = "{path.as_posix()}"\n'
        f'[bifurcation]\nspeed_range = ["{start}", "{stop}", "{step}"]\nsteps = 0\n'
        f'[parameters]\n"rotor.mass" = ["{case.rotor.mass!r} kg"]\n',
        encoding="utf-8",
    )
    summary = _run(
        ["sweep", str(sweep), "--out", str(tmp_path / "res"), "--scheduler", scheduler], capsys
    )
    assert summary["n_ok"] == summary["n_points"] == 1
    point = xr.load_dataset(tmp_path / "res.nc").isel(rotor_mass=0)
    assert float(point["rotor_mass"]) == case.rotor.mass
    assert point["grid"].values.tolist() == printed["grid"]
    for key in ("hopf_speed_rpm", "linear_whirl_frequency_Hz", "speed_limit_rpm"):
        assert float(point[key]) == pytest.approx(_nan(printed[key]), rel=1e-9, nan_ok=True), key
    for key in ("speeds_rpm", "amplitude_um", "min_film_um", "whirl_frequency_Hz"):
        np.testing.assert_allclose(point[key].values, printed[key], rtol=1e-4, err_msg=key)
    multipliers = np.array(printed["largest_multiplier"])
    np.testing.assert_allclose(point["largest_multiplier"].values, multipliers, rtol=1e-4)
    decided = np.abs(multipliers - 1.0) > 1e-4
    stable = point["stable"].values
    assert stable[decided].tolist() == np.array(printed["stable"])[decided].tolist()
    speeds = printed["speeds_rpm"]
    if abs(speeds[1] - speeds[0]) > 2e-4 * printed["hopf_speed_rpm"]:
        assert str(point["bifurcation_type"].values) == printed["bifurcation_type"]
    else:
        assert str(point["bifurcation_type"].values) in TYPES


@pytest.mark.parametrize("name", ["bump_foil_bearing", "shimmed_gfb", "rigid_gas_bearing"])
def test_bifurcation_at_a_voltage_without_actuators_is_one_line_saying_why(
    name: str, coarse: dict[str, Path], capsys
) -> None:
    err = _one_line_error(["bifurcation", str(coarse[name]), "--voltage", "0V"], capsys)
    assert "with no [actuators]" in err and "drop --voltage" in err


def _uncertainty_file(folder: Path, case: Path, voltages: str = "") -> Path:
    """A two-input plan on ``case``: viscosity and clearance (the case's ± 5 %), 32 Saltelli
    points (the least for two inputs), the static readouts at 60 krpm."""
    c_um = load_case(case).bearing.clearance * 1e6
    path = folder / "uq.toml"
    path.write_text(
        f'title = "two inputs"\ncase = "{case.as_posix()}"\n'
        'samples = 32\nsampler = "sobol"\nestimator = "sobol"\nseed = 1\n[inputs]\n'
        '"gas.viscosity" = { distribution = "uniform", low = "1.8e-5 Pa*s", high = "2.1e-5 Pa*s" }\n'
        f'"bearing.clearance" = {{ distribution = "uniform", low = "{0.95 * c_um:.6g} um", high = "{1.05 * c_um:.6g} um" }}\n'
        f'[outputs.static]\nspeeds = ["60000 rpm"]\n{voltages}',
        encoding="utf-8",
    )
    return path


@pytest.mark.parametrize("name", list(SOURCES))
def test_uncertainty_file_holds_the_envelopes_and_indices_the_command_prints(
    name: str, coarse: dict[str, Path], scheduler: str, tmp_path: Path, capsys
) -> None:
    """The sample's ``uncertainty.nc`` reopens: every sample is a point, each output's
    percentiles and first-order and total indices are the printed ones, digit for digit
    (the same numbers, written twice); the film's minimum moves with them (its total
    indices above 0)."""
    path = _uncertainty_file(tmp_path, coarse[name])
    out = tmp_path / "r"
    printed = _run(["uncertainty", str(path), "--out", str(out), "--scheduler", scheduler], capsys)
    assert printed["n_ok"] == printed["n_points"] == 32
    ds = xr.load_dataset(out / "uncertainty.nc")
    assert ds.sizes["sample"] == 32 and (ds["status"] == "ok").all()
    assert ds["input"].values.tolist() == ["gas.viscosity", "bearing.clearance"]
    assert set(ds["output"].values.tolist()) == set(printed["outputs"])
    for output, numbers in printed["outputs"].items():
        row = ds.sel(output=output)
        got = row["percentile"].sel(quantile=[5.0, 50.0, 95.0]).values
        np.testing.assert_array_equal(got, [_nan(numbers[q]) for q in ("p5", "p50", "p95")])
        for index in ("first_order", "total_order"):
            for source, value in numbers[index].items():
                assert float(row[index].sel(input=source)) == pytest.approx(
                    _nan(value), rel=0, abs=0, nan_ok=True
                ), (output, index, source)
    film = ds.sel(output=[o for o in printed["outputs"] if o.startswith("min_film_um")])
    assert (film["total_order"] > 0).all()


@pytest.mark.parametrize("name", ["bump_foil_bearing", "rigid_gas_bearing"])
def test_uncertainty_over_voltages_without_actuators_is_one_line_saying_why(
    name: str, coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    path = _uncertainty_file(tmp_path, coarse[name], voltages='voltages = ["0 V"]\n')
    err = _one_line_error(["uncertainty", str(path), "--out", str(tmp_path / "r")], capsys)
    assert "outputs.static.voltages" in err and "no [actuators]" in err
    assert not (tmp_path / "r").exists()


def _rotor_file(folder: Path, case: Path) -> Path:
    """The rigid symmetric rotor of ``examples/`` on two copies of ``case``, at the
    case's own voltages."""
    text = (EXAMPLES / "rotor_rigid_symmetric.toml").read_text(encoding="utf-8")
    text = text.replace('case = "default"', f'case = "{case.as_posix()}"')
    text = "\n".join(line for line in text.splitlines() if not line.startswith("voltages ="))
    path = folder / "rotor.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("name", list(SOURCES))
def test_rotor_run_file_holds_the_excursion_the_command_prints_and_resumes(
    name: str, coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    """``rotor ROTOR.toml --orbit 40000rpm:5ms --out``: the file reopens, its journals give
    the printed largest excursions (each journal's largest distance from its mean
    position) to round-off (1e-12); a run stopped at 2.5 ms resumes from its file to the
    same end, one increasing time series."""
    pytest.importorskip("ross")
    rotor = _rotor_file(tmp_path, coarse[name])
    out = tmp_path / "run.nc"
    common = ["rotor", str(rotor), "--orbit", "40000rpm:0.005s", "--shaft-modes", "2"]
    printed = _run([*common, "--unbalance", "1:1g*mm", "--out", str(out)], capsys)["orbit"]
    assert printed["status"] == "completed"
    ds = xr.load_dataset(out)
    assert float(ds["time"][-1]) == pytest.approx(0.005)
    assert ds["bearing"].values.tolist() == list(printed["largest_excursion_um"])
    assert ds["axis"].values.tolist() == ["X", "Y"]
    journal = ds["journal"].values
    centred = journal - journal.mean(axis=2, keepdims=True)
    excursion = 1e6 * np.hypot(centred[:, 0], centred[:, 1]).max(axis=1)
    printed_um = list(printed["largest_excursion_um"].values())
    np.testing.assert_allclose(excursion, printed_um, rtol=1e-12, atol=0)
    part = tmp_path / "part.nc"
    stopped = _run([*common, "--stop-time", "0.0025s", "--out", str(part)], capsys)["orbit"]
    assert stopped["status"] == "stopped"
    assert _run(["rotor", "--resume", str(part)], capsys)["orbit"]["status"] == "completed"
    resumed = xr.load_dataset(part)
    assert float(resumed["time"][-1]) == pytest.approx(0.005)
    assert np.all(np.diff(resumed["time"].values) > 0)


@pytest.mark.parametrize(
    "option", [["--voltage-ramp", "0s:1ms:100V"], ["--controller", "threshold=1um"]]
)
def test_a_voltage_program_for_a_rotor_without_actuators_is_one_line_saying_why(
    option: list[str], coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    pytest.importorskip("ross")
    rotor = _rotor_file(tmp_path, coarse["bump_foil_bearing"])
    argv = ["rotor", str(rotor), "--orbit", "40000rpm:0.005s", *option]
    err = _one_line_error(argv, capsys)
    assert err.endswith(f"{option[0]}: no bearing of the rotor has actuators")


def test_the_study_of_a_passive_bearing_writes_the_summary_it_prints(
    coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    """``study BUMP.toml --orbits none --json`` on the bump foil bearing: its
    ``summary.json`` reads back as the object printed, every figure it names is in the
    folder, and the onset it reports is the one ``stability`` prints (the same scan)."""
    path = str(coarse["bump_foil_bearing"])
    out = tmp_path / "study"
    argv = ["study", path, "--out", str(out), "--orbits", "none", "--bifurcation", "none"]
    printed = _run(argv, capsys)
    assert json.loads((out / "summary.json").read_text(encoding="utf-8")) == printed
    assert (out / "report.html").stat().st_size > 1000
    names = [name for stage in printed["figures"].values() for name in stage]
    assert "log_decrement.png" in names and all((out / name).is_file() for name in names)
    linear = _run(["stability", path], capsys)
    study = printed["bearing_stability"]["onset"]
    for key in ("onset_speed_rpm", "whirl_frequency_Hz"):
        assert study[key] == linear[key], key
    assert "bifurcation" not in printed  # --bifurcation none


@pytest.mark.slow  # 15 s of CPU: a study and a bifurcation on 32 x 4
def test_the_study_of_a_passive_bearing_runs_the_bifurcation_command_s_branch(
    coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    """``study RIGID.toml`` (a bearing without actuators) has a bifurcation stage: the Hopf
    point and first cycles that ``bifurcation`` prints for the same scan (the Hopf speed
    to 1e-9, the first cycles to the shooting's 1e-4), and its figure."""
    path = str(coarse["rigid_gas_bearing"])
    out = tmp_path / "study"
    printed = _run(["study", path, "--out", str(out), "--orbits", "none"], capsys)
    names = [name for stage in printed["figures"].values() for name in stage]
    # the branch 'bifurcation' prints for the study's own scan
    # (on the orbit grid, ±10 % around the linear stage's onset)
    branch = printed["bifurcation"]
    assert branch["bifurcation_type"] in TYPES, branch["message"]
    low, _, high = branch["scan_rpm"]
    assert low < branch["hopf_speed_rpm"] < high
    assert "whirl_branch.png" in names
    # the CLI's default --theta-refine 2: the branch again on 64 θ cells, the onset's
    # error at least the two grids' difference
    fine = branch["theta_refined"]
    assert fine["grid"] == [64, 4]
    moved = abs(fine["hopf_speed_rpm"] - branch["hopf_speed_rpm"])
    assert fine["errors"]["hopf_speed_rpm"] >= moved
    scan = f"{low!r}rpm:{high!r}rpm:{(high - low) / 2!r}rpm"
    direct = _run(["bifurcation", path, "--speed-range", scan, "--steps", "3"], capsys)
    assert direct["hopf_speed_rpm"] == pytest.approx(branch["hopf_speed_rpm"], rel=1e-9)
    assert len(direct["amplitude_um"]) == len(branch["amplitude_um"])
    # the two first cycles to 1e-4, as the read-back above; not the type's word, which on a
    # nearly degenerate branch flips on the scan's round-off (the scan here
    # is text, in the study floats; seen on the bump case), nor the later cycles (7e-4
    # apart on the bump case, 32 x 4)
    np.testing.assert_allclose(direct["amplitude_um"][:2], branch["amplitude_um"][:2], rtol=1e-4)
