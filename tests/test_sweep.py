"""Parameter sweeps: the sweep file, validation of every point, and runs on a real Dask cluster.

The cluster tests start one ``LocalCluster`` of two single-thread worker
processes for the module; points use coarse grids so each costs 20-150 ms.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import signal
import urllib.error
import urllib.request
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from foilbearing.case import default_case
from foilbearing.cli.sweep import register
from foilbearing.errors import InputError
from foilbearing.static import solve_equilibrium
from foilbearing.sweep.runner import ANALYSES, load_sweep, output_paths, run_point, run_sweep
from foilbearing.units import parse_quantity

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "sweep_voltage_speed.toml"
NUMERIC = ("eccentricity", "attitude_deg", "min_film_um", "drag_torque_Nm", "bearing_number")


def _write(tmp_path: Path, body: str, name: str = "sweep.toml") -> Path:
    path = tmp_path / name
    path.write_text(body, encoding="utf-8")
    return path


def _cli(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="foilbearing")
    register(parser.add_subparsers())
    return parser.parse_args(argv)


def _direct(n_theta: int, n_z: int, speed: str, voltage: str, **bearing: str) -> dict:
    """The headline of a direct ``solve_equilibrium`` call, without the sweep machinery."""
    case = default_case()
    b = {k: parse_quantity(v, "length", field=k) for k, v in bearing.items()}
    grid = replace(case.grid, n_theta=n_theta, n_z=n_z)  # the case file's law and orbit grid
    case = replace(case, grid=grid, bearing=replace(case.bearing, **b))
    case = case.with_voltages(parse_quantity(voltage, "voltage", field="v"))
    return solve_equilibrium(case, speed=parse_quantity(speed, "speed", field="s")).headline()


# --------------------------------------------------------------------------- parsing, validation


def test_example_sweep_file_is_valid() -> None:
    bif = load_sweep(EXAMPLE.with_name("sweep_bifurcation.toml"))
    assert bif.analysis == "bifurcation" and bif.n_points == 8
    spec = load_sweep(EXAMPLE)
    assert spec.analysis == "static"
    assert spec.n_points == math.prod(spec.shape) > 1


def test_grid_is_the_cartesian_product(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        """
        [parameters]
        speed = ["30000 rpm", "60000 rpm"]
        voltage = ["0 V", "100 V", "150 V"]
        bearing.clearance = ["80 um", "0.1 mm"]
        """,
    )
    spec = load_sweep(path)
    assert spec.shape == (2, 3, 2)
    assert [p.dim for p in spec.parameters] == ["speed", "voltage", "bearing_clearance"]
    assert [p.unit for p in spec.parameters] == ["rpm", "V", "um"]
    assert spec.parameters[2].coords == pytest.approx((80.0, 100.0))
    # point 7 = (1, 0, 1) in C order: the last parameter varies fastest
    assert spec.point_values(7) == {
        "speed": "60000 rpm",
        "voltage": "0 V",
        "bearing.clearance": "0.1 mm",
    }
    case = spec.point_case(7)
    assert case.operation.speed == pytest.approx(60000 * math.pi / 30)
    assert case.bearing.clearance == pytest.approx(1e-4)


def test_voltage_of_one_actuator(tmp_path: Path) -> None:
    path = _write(tmp_path, '[parameters]\n"voltage[1]" = ["0 V", "120 V"]\n')
    case = load_sweep(path).point_case(1)
    assert case.actuators is not None and case.actuators.voltages == (0.0, 120.0, 0.0)


@pytest.mark.parametrize(
    ("body", "words"),
    [
        ('[parameters]\n"bearing.clearence" = ["80 um"]\n', ["bearing.clearence", "unknown"]),
        (
            '[parameters]\n"bearing.clearance" = ["80 um", "5 kg"]\n',
            ["bearing.clearance[1]", "5 kg"],
        ),
        (
            '[parameters]\nspeed = ["50000 rpm"]\n"bearing.clearance" = ["80 um", "-5 um"]\n',
            ["point 1", "bearing.clearance", "-5 um"],
        ),
        ('[parameters]\nvoltage = ["0 V", "100 V", "200 V"]\n', ["point 2", "voltage", "200"]),
        ('[parameters]\n"voltage[3]" = ["0 V"]\n', ["voltage[3]", "3 actuators"]),
        ('[parameters]\nvoltage = ["0 V"]\n"voltage[1]" = ["0 V"]\n', ["voltage[1]", "voltage"]),
        ('analysis = "orbits"\n[parameters]\nspeed = ["1 rpm"]\n', ["orbits", "static"]),
        ('analysis = "stability"\n[parameters]\nspeed = ["1 rpm"]\n', ["speed", "cannot be swept"]),
        ("[parameters]\n", ["nothing to sweep"]),
        ('[parameters]\nspeed = "50000 rpm"\n', ["speed", "list"]),
    ],
)
def test_bad_sweep_is_one_input_error_before_any_work(
    tmp_path: Path, body: str, words: list[str]
) -> None:
    path = _write(tmp_path, body)
    with pytest.raises(InputError) as info:
        args = _cli(["sweep", str(path), "--out", str(tmp_path / "res")])
        args.func(args)
    message = str(info.value)
    assert message.startswith(str(path)) and "\n" not in message
    for word in words:
        assert word in message
    assert not (tmp_path / "res.d").exists() and not (tmp_path / "res.nc").exists()


def test_a_failing_evaluator_is_a_failed_record() -> None:
    def boom(case, options):
        raise ValueError("no film")

    data = json.loads(json.dumps(load_sweep(EXAMPLE).point_data(0)))
    rec = run_point(0, data, "here", boom, {})
    assert rec["status"] == "failed" and rec["error"] == "ValueError: no film"
    assert set(ANALYSES) >= {"static", "coefficients", "stability"}


def test_output_paths() -> None:
    assert output_paths("out/run") == (Path("out/run.d"), Path("out/run.nc"))
    assert output_paths("out/run.nc") == (Path("out/run.d"), Path("out/run.nc"))


# --------------------------------------------------------------------------- on a real cluster


def _listening(pid: int) -> set[str]:
    """The addresses a process and its children listen on (TCP)."""
    import psutil

    procs = [psutil.Process(pid), *psutil.Process(pid).children(recursive=True)]
    return {
        c.laddr.ip
        for p in procs
        for c in p.net_connections(kind="tcp")
        if c.status == psutil.CONN_LISTEN
    }


def _loopback(ip: str) -> bool:
    import ipaddress

    return ipaddress.ip_address(ip).is_loopback


@pytest.mark.parametrize("dashboard", [False, True])
def test_the_local_cluster_listens_on_loopback_only(dashboard: bool, capsys) -> None:
    # A sweep's own cluster (the runner's _client, one worker): its scheduler and its
    # HTTP server (the dashboard when asked for, else only health and metrics) must
    # not be reachable from the network; LocalCluster's dashboard_address=":0" bound
    # the HTTP server to 0.0.0.0.
    pytest.importorskip("distributed")
    from foilbearing.sweep.runner import _client

    with _client(None, 1, dashboard=dashboard) as cl:
        http = cl.cluster.scheduler.http_server
        addresses = _listening(os.getpid())
        link = cl.cluster.dashboard_link  # .../status: the dashboard (or, without bokeh, a stub)
        try:
            status = urllib.request.urlopen(link, timeout=5).status
        except urllib.error.HTTPError as exc:
            status = exc.code
    assert _loopback(http.address), http.address
    assert addresses and all(_loopback(ip) for ip in addresses), addresses
    assert link.startswith("http://127.0.0.1:")
    err = capsys.readouterr().err
    if dashboard:
        assert status == 200 and f"dashboard: {link}" in err
    else:
        # Not a status check: once a cluster in this process has served the dashboard,
        # distributed keeps its routes for later ones (seen under xdist after the
        # uncertainty tests); what matters is that the server listens on loopback only.
        assert "dashboard" not in err


def test_dashboard_belongs_to_the_local_cluster() -> None:
    args = _cli(["sweep", str(EXAMPLE), "--scheduler", "tcp://127.0.0.1:1", "--dashboard"])
    with pytest.raises(InputError, match="--dashboard starts the local cluster's"):
        args.func(args)


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address="127.0.0.1:0"
        ) as cluster,
        distributed.Client(cluster) as cl,
    ):
        yield cl


@pytest.mark.slow
def test_dataset_dims_coords_and_values(tmp_path: Path, client) -> None:
    path = _write(
        tmp_path,
        """
        title = "dims"
        [set]
        grid.n_theta = 48
        [parameters]
        speed = ["30000 rpm", "60000 rpm"]
        voltage = ["0 V", "100 V", "150 V"]
        "bearing.clearance" = ["80 um", "100 um"]
        """,
    )
    summary = run_sweep(load_sweep(path), tmp_path / "res", client=client)
    assert summary["n_ok"] == summary["n_points"] == 12
    ds = xr.load_dataset(tmp_path / "res.nc")
    assert ds["eccentricity"].dims == ("speed", "voltage", "bearing_clearance")
    assert ds["speed"].values.tolist() == [30000.0, 60000.0] and ds["speed"].units == "rpm"
    assert ds["voltage"].values.tolist() == [0.0, 100.0, 150.0] and ds["voltage"].units == "V"
    assert ds["bearing_clearance"].attrs == {"units": "um", "parameter": "bearing.clearance"}
    assert ds["preload_um"].dims[-1] == "actuator" and ds["force_N"].dims[-1] == "axis"
    assert (ds["status"] == "ok").all() and (ds["error"] == "").all()
    point = ds.sel(speed=60000.0, voltage=100.0, bearing_clearance=100.0)
    direct = _direct(48, 12, "60000 rpm", "100 V", clearance="100 um")
    # A worker may round differently (its BLAS is single-threaded): the equilibrium agrees to
    # the solver's convergence, |F + W| <= 1e-8 |W|, not bit for bit.
    for key in NUMERIC:
        assert float(point[key]) == pytest.approx(direct[key], rel=1e-6), key
    np.testing.assert_allclose(point["preload_um"].values, direct["preload_um"], rtol=1e-6)


def test_a_bifurcation_sweep_runs_branches_on_dask_as_the_api_does(tmp_path: Path, client) -> None:
    # Each point a branch of limit cycles (issue 31), the reading of the actuator a swept
    # choice: the Dataset holds the API's branch, cycle by cycle, and the readings as words.
    from foilbearing.bifurcation.bearing import SHOOTING_TOL, whirl_branch_headline

    path = _write(
        tmp_path,
        """
        analysis = "bifurcation"
        [set]
        grid.n_theta = 32
        grid.n_z = 4
        "foil.subambient" = "retained"
        [bifurcation]
        speed_range = ["5000 rpm", "30000 rpm", "2500 rpm"]
        steps = 0
        [parameters]
        "actuators.dynamics" = ["compliant", "held"]
        """,
    )
    spec = load_sweep(path)
    summary = run_sweep(spec, tmp_path / "res", client=client)
    assert summary["n_ok"] == summary["n_points"] == 2
    ds = xr.load_dataset(tmp_path / "res.nc")
    assert ds["actuators_dynamics"].values.tolist() == ["compliant", "held"]
    assert ds["amplitude_um"].dims == ("actuators_dynamics", "cycle")
    case = default_case()
    case = replace(case, grid=replace(case.grid, n_theta=32, n_z=4)).with_subambient("retained")
    scan = spec.options["speeds_rad_s"]
    for dynamics in ("compliant", "held"):
        direct, wb = whirl_branch_headline(case.with_actuator_reading(dynamics=dynamics), scan, 0)
        assert wb is not None
        point = ds.sel(actuators_dynamics=dynamics)
        assert str(point["bifurcation_type"].values) == direct["bifurcation_type"]
        # A worker rounds differently (its BLAS is single-threaded), so the two agree to
        # what the solvers guarantee, not to round-off. The shooting stops at
        # ‖φ_T(y₀) − y₀‖ <= SHOOTING_TOL (1 + ‖y₀‖), pressures in p_a and the journal in C:
        # the cycles' extents to that many C, 1.2e-4 µm (1.8e-4 of the first, 0.69 µm; the
        # other reading's is 0.66 % off). Round-off moves them by 6e-6 of themselves.
        y0 = max(np.linalg.norm(o.state) for o in wb.branch.orbits)
        atol_um = SHOOTING_TOL * (1.0 + y0) * wb.case.bearing.clearance * 1e6
        np.testing.assert_allclose(
            point["amplitude_um"].values, direct["amplitude_um"], rtol=0, atol=atol_um
        )
        # Each onset within Brent's tolerance of the root, 1e-4 of its bracket's upper speed
        # (15000 rpm): two runs within twice it (the other reading's is 190 rpm off).
        assert float(point["hopf_speed_rpm"]) == pytest.approx(direct["hopf_speed_rpm"], abs=3.0)


def test_bad_bifurcation_options_are_one_line_errors(tmp_path: Path) -> None:
    head = 'analysis = "bifurcation"\n[parameters]\nvoltage = ["0 V"]\n[bifurcation]\n'
    for body, match in (
        ("steps = -1\n", r"bifurcation.steps = -1: cycles after the two first, 0 to 100"),
        ("steps = 2.5\n", r"bifurcation.steps = 2.5"),
        ("order = 3\n", r"the options are speed_range and steps"),
        ('speed_range = ["5000 rpm"]\n', r"expected \[START, STOP, STEP\]"),
    ):
        with pytest.raises(InputError, match=match):
            load_sweep(_write(tmp_path, head + body))
    speed = 'analysis = "bifurcation"\n[parameters]\nspeed = ["10000 rpm"]\n'
    with pytest.raises(InputError, match="set by this analysis"):
        load_sweep(_write(tmp_path, speed, "speed.toml"))


def test_a_swept_choice_must_be_a_word_the_case_allows(tmp_path: Path) -> None:
    bad = _write(tmp_path, '[parameters]\n"actuators.dynamics" = ["compliant", "frozen"]\n')
    with pytest.raises(InputError, match=r"dynamics = 'frozen': expected one of"):
        load_sweep(bad)
    number = _write(tmp_path, '[parameters]\n"foil.subambient" = [1.0]\n', "n.toml")
    with pytest.raises(InputError, match=r"expected a word"):
        load_sweep(number)


@pytest.mark.slow
def test_a_lost_worker_loses_no_point(tmp_path: Path, client) -> None:
    path = _write(
        tmp_path,
        """
        [set]
        grid.n_theta = 256
        grid.n_z = 16
        [parameters]
        voltage = ["0 V", "50 V", "100 V", "150 V"]
        speed = ["30000 rpm", "50000 rpm", "70000 rpm"]
        """,
    )
    spec = load_sweep(path)
    pids = client.run(os.getpid)  # worker address -> process id
    killed: list[str] = []
    seen: list[int] = []

    def kill_one(record: dict) -> None:
        seen.append(record["index"])
        if len(seen) == 2:
            busy = [w for w, keys in client.processing().items() if keys]
            killed.append(busy[0])
            os.kill(pids[busy[0]], signal.SIGKILL)  # a hard loss, mid-task

    summary = run_sweep(spec, tmp_path / "res", client=client, on_point=kill_one)
    assert killed
    assert sorted(seen) == list(range(12))  # each point reported exactly once
    assert summary["n_ok"] == 12 and summary["n_missing"] == 0
    files = sorted((tmp_path / "res.d" / "points").glob("*.json"))
    assert [json.loads(f.read_text())["index"] for f in files] == list(range(12))
    ds = xr.load_dataset(tmp_path / "res.nc")
    for i in (0, 5, 11):
        vals = spec.point_values(i)
        direct = _direct(256, 16, vals["speed"], vals["voltage"])
        point = ds.isel(voltage=i // 3, speed=i % 3)
        for key in NUMERIC:
            assert float(point[key]) == direct[key], (i, key)


class _Stop(Exception):
    pass


@pytest.mark.slow
def test_resume_computes_only_the_missing_points(tmp_path: Path, client) -> None:
    path = _write(
        tmp_path,
        """
        [set]
        grid.n_theta = 48
        [parameters]
        voltage = ["0 V", "50 V", "100 V", "150 V"]
        speed = ["30000 rpm", "60000 rpm"]
        """,
    )
    spec = load_sweep(path)

    def stop_after_3(record: dict) -> None:
        if len(list((tmp_path / "res.d" / "points").glob("*.json"))) == 3:
            raise _Stop

    with pytest.raises(_Stop):
        run_sweep(spec, tmp_path / "res", client=client, on_point=stop_after_3)
    files = sorted((tmp_path / "res.d" / "points").glob("*.json"))
    assert len(files) == 3
    mtimes = {f.name: f.stat().st_mtime_ns for f in files}
    with pytest.raises(InputError, match="--resume"):
        run_sweep(spec, tmp_path / "res", client=client)
    summary = run_sweep(spec, tmp_path / "res", client=client, resume=True)
    assert (summary["n_computed"], summary["n_skipped"], summary["n_ok"]) == (5, 3, 8)
    assert {f.name: f.stat().st_mtime_ns for f in files} == mtimes
    assert (xr.load_dataset(tmp_path / "res.nc")["status"] == "ok").all()
    other = _write(tmp_path, path.read_text().replace("150 V", "140 V"), "other.toml")
    with pytest.raises(InputError, match="another sweep"):
        run_sweep(load_sweep(other), tmp_path / "res", client=client, resume=True)


@pytest.mark.slow
def test_failed_point_is_recorded_and_the_rest_complete(tmp_path: Path, client, capsys) -> None:
    path = _write(
        tmp_path,
        """
        [set]
        grid.n_theta = 48
        [parameters]
        "operation.load" = ["8.8 N", "2000 N", "20 N"]
        """,
    )
    address = client.scheduler.address
    args = _cli(
        ["sweep", str(path), "--out", str(tmp_path / "res"), "--scheduler", address, "--json"]
    )
    assert args.func(args) == 3
    out = json.loads(capsys.readouterr().out)
    assert (out["n_points"], out["n_ok"], out["n_failed"]) == (3, 2, 1)
    assert out["dataset"] == str(tmp_path / "res.nc") and out["wall_time_s"] > 0
    ds = xr.load_dataset(tmp_path / "res.nc")
    assert ds["status"].values.tolist() == ["ok", "failed", "ok"]
    assert "equilibrium not found" in str(ds["error"].values[1])
    assert np.isnan(ds["eccentricity"].values[1]) and not np.isnan(ds["eccentricity"].values[2])
    record = json.loads((tmp_path / "res.d" / "points" / "000001.json").read_text())
    assert record["parameters"] == {"operation.load": "2000 N"}


@pytest.mark.slow
def test_cli_on_its_own_local_cluster(tmp_path: Path, capsys) -> None:
    path = _write(
        tmp_path, '[set]\ngrid.n_theta = 48\n[parameters]\nspeed = ["40000 rpm", "50000 rpm"]\n'
    )
    args = _cli(["sweep", str(path), "--out", str(tmp_path / "r"), "--workers", "1", "--json"])
    assert args.func(args) == 0
    assert json.loads(capsys.readouterr().out)["n_ok"] == 2
    args = _cli(["sweep", str(path), "--out", str(tmp_path / "r"), "--assemble", "--json"])
    assert args.func(args) == 0
    assert json.loads(capsys.readouterr().out)["n_computed"] == 0


def _certificates(folder: Path) -> dict[str, str]:
    """A throw-away CA and one certificate it signs for 127.0.0.1 (openssl), as PEM files."""
    import subprocess

    def ssl(*args: str) -> None:
        subprocess.run(["openssl", *args], cwd=folder, check=True, capture_output=True)

    ssl(
        "req",
        "-x509",
        "-newkey",
        "rsa:2048",
        "-nodes",
        "-days",
        "1",
        "-subj",
        "/CN=test-ca",
        "-keyout",
        "ca-key.pem",
        "-out",
        "ca.pem",
    )
    ssl(
        "req",
        "-newkey",
        "rsa:2048",
        "-nodes",
        "-subj",
        "/CN=127.0.0.1",
        "-keyout",
        "key.pem",
        "-out",
        "req.pem",
    )
    (folder / "ext.cnf").write_text("subjectAltName=IP:127.0.0.1\n")
    ssl(
        "x509",
        "-req",
        "-in",
        "req.pem",
        "-CA",
        "ca.pem",
        "-CAkey",
        "ca-key.pem",
        "-CAcreateserial",
        "-days",
        "1",
        "-extfile",
        "ext.cnf",
        "-out",
        "cert.pem",
    )
    return {name: str(folder / f"{name}.pem") for name in ("ca", "cert", "key")}


def test_a_tls_scheduler_takes_the_clients_certificates_from_dask_config(tmp_path: Path) -> None:
    # Issue 33: `--scheduler tls://...` with the certificate files in Dask's configuration
    # (a config file or DASK_* variables): the client connects, encrypted, and a task runs;
    # without them, one line naming the keys, before any work.
    import shutil

    if shutil.which("openssl") is None:
        pytest.skip("openssl is needed to make the test's certificates")
    dask = pytest.importorskip("dask")
    distributed = pytest.importorskip("distributed")
    from foilbearing.sweep.runner import _client

    pem = _certificates(tmp_path)
    files = {"tls_ca_file": pem["ca"]}
    for role in ("scheduler", "worker", "client"):
        files |= {f"tls_{role}_cert": pem["cert"], f"tls_{role}_key": pem["key"]}
    security = distributed.Security(require_encryption=True, **files)
    with distributed.LocalCluster(
        n_workers=1,
        processes=False,
        protocol="tls",
        host="127.0.0.1",
        security=security,
        dashboard_address="127.0.0.1:0",
    ) as cluster:
        address = cluster.scheduler_address
        assert address.startswith("tls://")
        with pytest.raises(InputError, match=r"distributed\.comm\.tls\.ca-file.*DASK_"):
            with _client(address, None):
                pass
        config = {
            "distributed.comm.tls.ca-file": pem["ca"],
            "distributed.comm.tls.client.cert": pem["cert"],
            "distributed.comm.tls.client.key": pem["key"],
        }
        with dask.config.set(config), _client(address, None) as client:
            assert client.submit(lambda x: x + 1, 41).result(timeout=20) == 42
        with dask.config.set(config | {"distributed.comm.tls.ca-file": str(tmp_path / "no.pem")}):
            with pytest.raises(InputError, match="no such file"):
                with _client(address, None):
                    pass
