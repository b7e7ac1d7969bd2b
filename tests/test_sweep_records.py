"""A sweep's results folder read back: damaged files, points lost to the cluster, Ctrl-C.

Issue 48: every damaged point record or manifest is one line naming the file and what is
wrong (or, for a point record on ``--resume``, set aside and computed again); a point lost
to the cluster is not a result and ``--resume`` computes it; Ctrl-C prints one line.
One tiny sweep (static analysis on a 24 x 4 grid, 2 points, about 0.1 s a point) on a
one-worker cluster for the module.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import shutil
import signal
from pathlib import Path
from typing import Any

import pytest
import xarray as xr

from foilbearing.cli.main import main
from foilbearing.cli.sweep import register
from foilbearing.errors import InputError, SolverError
from foilbearing.sweep import runner
from foilbearing.sweep.runner import load_sweep, run_point, run_sweep

SWEEP = """
[set]
grid.n_theta = 24
grid.n_z = 4
[parameters]
speed = ["40000 rpm", "50000 rpm"]
"""


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(
            n_workers=1, threads_per_worker=1, processes=True, dashboard_address="127.0.0.1:0"
        ) as cluster,
        distributed.Client(cluster) as cl,
    ):
        yield cl


@pytest.fixture(scope="module")
def finished(tmp_path_factory: pytest.TempPathFactory, client) -> Path:
    """A finished run of the tiny sweep: ``sweep.toml``, ``res.d/``, ``res.nc``."""
    folder = tmp_path_factory.mktemp("finished")
    (folder / "sweep.toml").write_text(SWEEP, encoding="utf-8")
    summary = run_sweep(load_sweep(folder / "sweep.toml"), folder / "res", client=client)
    assert summary["n_ok"] == 2
    return folder


@pytest.fixture
def run(tmp_path: Path, finished: Path) -> Path:
    """A copy of the finished run to damage."""
    shutil.copy(finished / "sweep.toml", tmp_path / "sweep.toml")
    shutil.copytree(finished / "res.d", tmp_path / "res.d")
    return tmp_path


def _record(run: Path, index: int = 1) -> dict[str, Any]:
    return json.loads((run / "res.d" / "points" / f"{index:06d}.json").read_text())


def _edit(change):
    def damage(text: str) -> str:
        rec = json.loads(text)
        change(rec)
        return json.dumps(rec, indent=1)

    return damage


#: Damage to point 1's record: (how, words the message must hold).
DAMAGE = {
    "truncated": (lambda t: t[: len(t) // 2], "not valid JSON (cut short?)"),
    "empty": (lambda t: "", "the file is empty"),
    "random bytes": (lambda t: b"\x8f\xff\x00\x13\xfe binary".decode("latin-1"), "not JSON"),
    "not an object": (lambda t: "[1, 2]", "expected a JSON object"),
    "missing key": (_edit(lambda r: r.pop("status")), "missing key(s) status"),
    "a string for a number": (
        _edit(lambda r: r["result"].update(eccentricity="fast")),
        "result.eccentricity = 'fast': expected a finite number",
    ),
    "NaN": (lambda t: t.replace('"eccentricity": ', '"eccentricity": NaN, "x": '), "NaN"),
    "overflow": (
        lambda t: t.replace('"min_film_um": ', '"min_film_um": 1e999, "x": '),
        "result.min_film_um = inf",
    ),
    "a number for a flag": (
        _edit(lambda r: r["result"].update(converged=1)),
        "result.converged = 1: expected true or false",
    ),
    "another index": (_edit(lambda r: r.update(index=0)), "index = 0, but the file is point 1's"),
    "another point's parameters": (
        _edit(lambda r: r["parameters"].update(speed="45000 rpm")),
        "parameters.speed = '45000 rpm': point 1 has '50000 rpm'",
    ),
}


def test_a_record_cut_short_at_any_byte_is_called_cut_short(tmp_path: Path) -> None:
    """A point record cut at every position (inside a number's exponent, a sign, ``true``,
    a key) is reported as not valid JSON and cut short: the damage test above cuts at half
    the file, whose length varies with the record's numbers, so it once cut inside
    ``1.2e-05`` and the message lost its "(cut short?)". A whole document with a stray word
    after it is not called cut short."""
    from foilbearing.sweep.records import _load_json

    text = json.dumps(
        {"onset_speed_rpm": -1.25e-05, "converged": True, "note": None, "f": [3.5e7, 2]},
        indent=1,
    )
    path = tmp_path / "000001.json"
    for cut in range(1, len(text)):
        path.write_text(text[:cut], encoding="utf-8")
        data, problem = _load_json(path)
        assert data is None and problem is not None, cut
        assert problem.startswith("not valid JSON (cut short?)"), (text[:cut], problem)
    path.write_text(text + " extra", encoding="utf-8")
    data, problem = _load_json(path)
    assert problem is not None and "cut short" not in problem


@pytest.mark.parametrize("kind", list(DAMAGE))
def test_a_damaged_point_record_is_named_or_set_aside_and_computed_again(
    kind: str, run: Path, finished: Path, client, capsys
) -> None:
    damage, words = DAMAGE[kind]
    path = run / "res.d" / "points" / "000001.json"
    path.write_text(damage(path.read_text(encoding="utf-8")), encoding="latin-1")
    damaged = path.read_bytes()
    spec = load_sweep(run / "sweep.toml")
    # Nothing to compute (--assemble): one line naming the file and what is wrong.
    with pytest.raises(InputError) as info:
        run_sweep(spec, run / "res", client=client, resume=True, compute=False)
    message = str(info.value)
    assert message.startswith(str(path)) and words in message and "\n" not in message
    assert "--resume" in message and path.read_bytes() == damaged  # left as it was
    # --resume: set aside, said in one line, the point computed again as it was.
    summary = run_sweep(spec, run / "res", client=client, resume=True)
    assert (summary["n_computed"], summary["n_skipped"], summary["n_ok"]) == (1, 1, 2)
    err = capsys.readouterr().err
    assert f"{path}: damaged point record" in err and words in err and "set aside" in err
    assert path.with_name("000001.json.damaged").read_bytes() == damaged
    original = json.loads((finished / "res.d" / "points" / "000001.json").read_text())
    again = _record(run)
    assert again["parameters"] == original["parameters"] == {"speed": "50000 rpm"}
    assert again["result"]["eccentricity"] == pytest.approx(
        original["result"]["eccentricity"], rel=1e-12
    )
    ds = xr.load_dataset(run / "res.nc")
    assert ds["eccentricity"].dtype.kind == "f" and (ds["status"] == "ok").all()


@pytest.mark.parametrize("name", ["notes.json", "000007.json"])
def test_a_json_file_that_is_no_point_of_the_sweep_is_named_not_moved(
    name: str, run: Path, client
) -> None:
    stray = run / "res.d" / "points" / name
    stray.write_text(json.dumps(_record(run, 0)), encoding="utf-8")
    for compute in (False, True):
        with pytest.raises(InputError, match="not a point of this sweep") as info:
            run_sweep(
                load_sweep(run / "sweep.toml"),
                run / "res",
                client=client,
                resume=True,
                compute=compute,
            )
        assert str(info.value).startswith(str(stray)) and "000001.json" in str(info.value)
    assert stray.exists()


def _cli(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="foilbearing")
    register(parser.add_subparsers())
    return parser.parse_args(argv)


@pytest.mark.parametrize(
    ("damage", "words"),
    [
        (None, "sweep.json is missing, yet"),
        (lambda t: t[:40], "damaged manifest: not valid JSON (cut short?)"),
        (lambda t: t.replace('"fingerprint": "', '"fingerprint": "zz'), "fingerprint = 'zz"),
        (lambda t: "", "damaged manifest: the file is empty"),
    ],
)
def test_a_missing_or_damaged_manifest_is_one_line_exit_2(
    damage, words: str, run: Path, client, capsys
) -> None:
    manifest = run / "res.d" / "sweep.json"
    if damage is None:
        manifest.unlink()
    else:
        manifest.write_text(damage(manifest.read_text(encoding="utf-8")), encoding="utf-8")
    before = sorted(p.name for p in (run / "res.d" / "points").iterdir())
    address = client.scheduler.address
    argv = ["sweep", str(run / "sweep.toml"), "--out", str(run / "res"), "--resume"]
    assert main([*argv, "--scheduler", address]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and "another sweep" not in err
    assert "cannot be guessed" in err
    assert sorted(p.name for p in (run / "res.d" / "points").iterdir()) == before


def test_a_point_an_earlier_version_stored_as_lost_to_the_cluster_is_computed(
    run: Path, client, capsys
) -> None:
    path = run / "res.d" / "points" / "000001.json"
    lost = {
        "index": 1,
        "status": "failed",
        "error": "KilledWorker: Attempted to run task 'sweep-point-1-ab' on 4 different workers",
        "result": {},
        "parameters": {"speed": "50000 rpm"},
    }
    path.write_text(json.dumps(lost), encoding="utf-8")
    summary = run_sweep(load_sweep(run / "sweep.toml"), run / "res", client=client, resume=True)
    assert (summary["n_computed"], summary["n_ok"]) == (1, 2)
    assert "point 1 was lost to the cluster (KilledWorker" in capsys.readouterr().err


# --------------------------------------------------------------------------- lost points


def _lose(point: int, exc: BaseException):
    """``runner._gather`` that loses ``point`` to ``exc``, as the cluster would."""
    gather = runner._gather

    def lossy(future):
        if future.key.startswith(f"sweep-point-{point}-"):
            raise exc
        return gather(future)

    return lossy


def _killed_worker() -> BaseException:
    from types import SimpleNamespace

    from distributed import KilledWorker

    return KilledWorker("sweep-point-1-x", SimpleNamespace(address="tcp://127.0.0.1:1"), 3)


@pytest.mark.parametrize(
    "exc",
    [_killed_worker, lambda: TimeoutError("no answer in 30 s"), asyncio.CancelledError],
    ids=["KilledWorker", "TimeoutError", "CancelledError"],
)
def test_a_point_lost_to_the_cluster_is_not_stored_and_resume_computes_it(
    exc, tmp_path: Path, client, capsys, monkeypatch
) -> None:
    (tmp_path / "sweep.toml").write_text(SWEEP, encoding="utf-8")
    spec = load_sweep(tmp_path / "sweep.toml")
    error = exc()
    with monkeypatch.context() as m:
        m.setattr(runner, "_gather", _lose(1, error))
        summary = run_sweep(spec, tmp_path / "res", client=client)
    assert (summary["n_ok"], summary["n_failed"], summary["n_missing"]) == (1, 0, 1)
    assert not (tmp_path / "res.d" / "points" / "000001.json").exists()
    err = capsys.readouterr().err
    assert f"point 1 lost to the cluster ({type(error).__name__}" in err
    summary = run_sweep(spec, tmp_path / "res", client=client, resume=True)
    assert (summary["n_computed"], summary["n_skipped"], summary["n_ok"]) == (1, 1, 2)


def test_the_machine_failing_is_raised_the_physics_failing_is_a_result(tmp_path: Path) -> None:
    (tmp_path / "sweep.toml").write_text(SWEEP, encoding="utf-8")
    spec = load_sweep(tmp_path / "sweep.toml")
    data, source = spec.point_data(0), spec.point_source(0)

    def no_memory(case, options):
        raise MemoryError

    def no_equilibrium(case, options):
        raise SolverError("equilibrium not found in 50 Newton iterations")

    with pytest.raises(MemoryError):
        run_point(0, data, source, no_memory, {})
    rec = run_point(0, data, source, no_equilibrium, {})
    assert rec["status"] == "failed" and rec["error"].startswith("SolverError: equilibrium")


# --------------------------------------------------------------------------- Ctrl-C


def test_ctrl_c_prints_one_line_and_keeps_the_points(
    tmp_path: Path, client, capfd, monkeypatch
) -> None:
    # The sweep's own local cluster (one worker): Ctrl-C raised from the progress loop
    # while point 1 comes in; the cluster closes without a word from distributed.
    (tmp_path / "sweep.toml").write_text(SWEEP, encoding="utf-8")
    out = tmp_path / "res"
    argv = ["sweep", str(tmp_path / "sweep.toml"), "--out", str(out), "--workers", "1", "--json"]
    gather, seen = runner._gather, []

    def interrupted(future):  # Ctrl-C as the second point comes in
        seen.append(future.key)
        if len(seen) == 2:
            raise KeyboardInterrupt
        return gather(future)

    with monkeypatch.context() as m:
        m.setattr(runner, "_gather", interrupted)
        args = _cli(argv)
        assert args.func(args) == 130
    captured = capfd.readouterr()
    assert captured.out == ""
    assert captured.err == (
        f"foilbearing: interrupted: 1 of 2 points kept in {out}.d; run again with --resume\n"
    )
    assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, [])
    summary = run_sweep(load_sweep(tmp_path / "sweep.toml"), out, client=client, resume=True)
    assert (summary["n_computed"], summary["n_skipped"], summary["n_ok"]) == (1, 1, 2)


def test_an_uncertainty_run_sets_a_damaged_point_aside_and_computes_it(
    tmp_path: Path, client, capsys
) -> None:
    # The uncertainty analysis reads its points as a sweep does: an output that is a word
    # is damage, named in one line and computed again on --resume.
    from foilbearing.uncertainty import load_uncertainty, run_uncertainty

    path = tmp_path / "uq.toml"
    path.write_text(
        "samples = 24\n" + SWEEP.split("[parameters]")[0] + "[inputs]\n"
        '"gas.viscosity" = { distribution = "uniform", low = "1.8e-5 Pa*s", high = "2.1e-5 Pa*s" }\n'
        '[outputs.static]\nspeeds = ["60000 rpm"]\n',
        encoding="utf-8",
    )
    spec = load_uncertainty(path)
    _, summary = run_uncertainty(spec, tmp_path / "r", client=client)
    assert summary["n_ok"] == spec.n_points
    point = tmp_path / "r" / "points" / "000002.json"
    rec = json.loads(point.read_text())
    name = next(iter(rec["result"]["outputs"]))
    good = rec["result"]["outputs"][name]
    rec["result"]["outputs"][name] = "fast"
    point.write_text(json.dumps(rec), encoding="utf-8")
    with pytest.raises(InputError, match=r"result\.outputs\[.*\] = 'fast'") as info:
        run_uncertainty(spec, tmp_path / "r", client=client, resume=True, compute=False)
    assert str(info.value).startswith(str(point))
    _, summary = run_uncertainty(spec, tmp_path / "r", client=client, resume=True)
    assert (summary["n_computed"], summary["n_ok"]) == (1, spec.n_points)
    assert "set aside as 000002.json.damaged" in capsys.readouterr().err
    assert json.loads(point.read_text())["result"]["outputs"][name] == pytest.approx(
        good, rel=1e-12
    )


# ------------------------------------------------- the case recorded in the manifest


@pytest.fixture(scope="module")
def finished_own_case(tmp_path_factory: pytest.TempPathFactory, client) -> Path:
    """A finished run of the tiny sweep of a case file of its own: ``case.toml``,
    ``sweep.toml``, ``res.d/``."""
    from foilbearing.case import default_case_path

    folder = tmp_path_factory.mktemp("own_case")
    shutil.copy(default_case_path(), folder / "case.toml")
    (folder / "sweep.toml").write_text('case = "case.toml"\n' + SWEEP, encoding="utf-8")
    summary = run_sweep(load_sweep(folder / "sweep.toml"), folder / "res", client=client)
    assert summary["n_ok"] == 2
    return folder


@pytest.fixture
def own(tmp_path: Path, finished_own_case: Path) -> Path:
    """A copy of that run with point 1 lost (to be computed by --resume)."""
    for name in ("case.toml", "sweep.toml"):
        shutil.copy(finished_own_case / name, tmp_path / name)
    shutil.copytree(finished_own_case / "res.d", tmp_path / "res.d")
    (tmp_path / "res.d" / "points" / "000001.json").unlink()
    return tmp_path


def _resume(run: Path, client, *extra: str) -> int:
    argv = ["sweep", str(run / "sweep.toml"), "--out", str(run / "res"), *extra]
    return main([*argv, "--scheduler", client.scheduler.address])


def test_the_manifest_records_the_case_the_points_start_from(finished_own_case: Path) -> None:
    from foilbearing.case import load_case
    from foilbearing.case.record import CaseRecord

    manifest = json.loads((finished_own_case / "res.d" / "sweep.json").read_text())
    record = CaseRecord.from_dict(manifest["base_case"])
    case = record.case(source="record")
    # the [set] edits are in, the swept speed is the case file's own (not a point's)
    assert (case.grid.n_theta, case.grid.n_z) == (24, 4)
    assert case.operation.speed == load_case(finished_own_case / "case.toml").operation.speed
    assert case.bearing.clearance == pytest.approx(100e-6, rel=1e-15)


@pytest.mark.parametrize("flag", ["--resume", "--assemble"])
def test_resume_after_the_case_file_was_edited_refuses_in_one_line(
    flag: str, own: Path, client, capsys
) -> None:
    # Points computed on two clearances would be one Dataset of two bearings: refused.
    case = own / "case.toml"
    case.write_text(case.read_text().replace('"100 um"', '"90 um"', 1), encoding="utf-8")
    before = sorted(p.name for p in (own / "res.d" / "points").iterdir())
    assert _resume(own, client, flag) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert f"case file {case} has changed since the run" in err
    assert "bearing.clearance: 9.999999999999999e-05 m recorded, 8.999999999999999e-05 m now" in err
    assert "give a new --out to run the edited case, or restore the file" in err
    assert sorted(p.name for p in (own / "res.d" / "points").iterdir()) == before
    assert not (own / "res.nc").exists()


def test_resume_with_the_case_file_unchanged_computes_the_lost_point(
    own: Path, client, finished_own_case: Path
) -> None:
    assert _resume(own, client, "--resume") == 0
    got = _record(own)["result"]
    want = _record(finished_own_case)["result"]
    assert got["eccentricity"] == pytest.approx(want["eccentricity"], rel=1e-9)


def test_a_manifest_of_an_earlier_version_without_the_case_still_resumes(own: Path, client) -> None:
    manifest = own / "res.d" / "sweep.json"
    data = json.loads(manifest.read_text())
    del data["base_case"]
    manifest.write_text(json.dumps(data, indent=1), encoding="utf-8")
    summary = run_sweep(load_sweep(own / "sweep.toml"), own / "res", client=client, resume=True)
    assert (summary["n_computed"], summary["n_skipped"], summary["n_ok"]) == (1, 1, 2)


def test_a_recorded_case_that_does_not_match_its_digest_is_one_line_exit_2(
    own: Path, client, capsys
) -> None:
    manifest = own / "res.d" / "sweep.json"
    data = json.loads(manifest.read_text())
    data["base_case"]["tables"]["bearing"]["clearance"] = "9e-05 m"
    manifest.write_text(json.dumps(data, indent=1), encoding="utf-8")
    assert _resume(own, client, "--resume") == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert f"{manifest}: damaged manifest: base_case: the recorded case does not match" in err
    assert not (own / "res.d" / "points" / "000001.json").exists()


def test_an_uncertainty_run_records_its_case_and_refuses_an_edited_one(tmp_path: Path) -> None:
    # The uncertainty analysis keeps its points in a results folder of the same kind
    # (run_points' sweep.json), so the same record and check cover it.
    from foilbearing.case import default_case_path
    from foilbearing.sweep.runner import run_points
    from foilbearing.uncertainty import load_uncertainty
    from foilbearing.uncertainty.evaluate import evaluate_sample

    shutil.copy(default_case_path(), tmp_path / "case.toml")
    path = tmp_path / "uq.toml"
    path.write_text(
        'case = "case.toml"\nsamples = 24\n' + SWEEP.split("[parameters]")[0] + "[inputs]\n"
        '"gas.viscosity" = { distribution = "uniform", low = "1.8e-5 Pa*s", high = "2.1e-5 Pa*s" }\n'
        '[outputs.static]\nspeeds = ["60000 rpm"]\n',
        encoding="utf-8",
    )
    folder = tmp_path / "r"
    run_points(load_uncertainty(path), folder, evaluate_sample, compute=False)  # the manifest
    assert "base_case" in json.loads((folder / "sweep.json").read_text())
    again = run_points(load_uncertainty(path), folder, evaluate_sample, resume=True, compute=False)
    assert again["n_skipped"] == 0
    case = tmp_path / "case.toml"
    case.write_text(case.read_text().replace('"100 um"', '"90 um"', 1), encoding="utf-8")
    with pytest.raises(InputError, match=r"bearing\.clearance: 9\.99.*e-05 m recorded") as info:
        run_points(load_uncertainty(path), folder, evaluate_sample, resume=True, compute=False)
    assert "\n" not in str(info.value) and "give a new --out" in str(info.value)


def test_a_case_file_edited_without_changing_the_case_resumes(
    own: Path, client, finished_own_case: Path
) -> None:
    # "100.0 um" reads to the same float as "100 um": the same bearing, so the same sweep.
    case = own / "case.toml"
    case.write_text(case.read_text().replace('"100 um"', '"100.0 um"', 1), encoding="utf-8")
    summary = run_sweep(load_sweep(own / "sweep.toml"), own / "res", client=client, resume=True)
    assert (summary["n_computed"], summary["n_skipped"], summary["n_ok"]) == (1, 1, 2)
    got, want = _record(own)["result"], _record(finished_own_case)["result"]
    assert got["eccentricity"] == pytest.approx(want["eccentricity"], rel=1e-9)
