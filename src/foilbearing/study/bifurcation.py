"""Is the whirl past the onset bounded? The limit-cycle branches as a study stage (issue 31).

For each voltage of the paper's plan, under the case's reading of the actuator and the
paper's (lobe + held, docs/model.md §3.8), the Hopf bifurcation's type and the branch of
limit cycles from the linear onset (:func:`~foilbearing.bifurcation.bearing.whirl_branch_headline`).
Each reading is a sweep over the voltages, each branch one point run on Dask
(``analysis = "bifurcation"``, :mod:`foilbearing.sweep`); the sweep files are written
beside the results, so that ``foilbearing sweep`` reruns or extends them (a finer grid,
longer branches). The branches are on the case's orbit grid, the grid of its speed-ups
(under lift-off the type near the onset changes between 48 × 6 and 96 × 12:
docs/bifurcation.md), and short, for the stage's time.

With ``theta_refine`` > 1 every branch is run again on that many times the θ cells, and
each row's readouts (the Hopf speed and whirl, the speed limit, the largest stable cycle)
carry the two grids' difference as their error (:func:`cycle_errors`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from foilbearing.case import Case, Grid

__all__ = [
    "BIFURCATION_STEPS",
    "READINGS",
    "amplitude_at",
    "bifurcation_stage",
    "cycle_errors",
    "passive_bifurcation_stage",
]

#: Cycles of each branch after the two first ones (which decide the type).
BIFURCATION_STEPS = 3
#: The readings of the actuator the stage compares: the case's default and the paper's.
READINGS = (("local", "compliant"), ("lobe", "held"))
#: The onset scan: a 150 V C-GFB cannot carry the load at 5 krpm on the coarse grid.
SCAN = ("15000 rpm", "120000 rpm", "2500 rpm")


def _sweep_file(
    case: Case,
    voltages: Sequence[float],
    reading: tuple[str, str],
    steps: int,
    grid: Grid,
) -> str:
    """The stage's sweep file: the case file with the orbit's grid as its whole grid
    (shape, axial order, lift-off smoothing), so that the file alone reruns the stage."""
    volts = ", ".join(f'"{v:g} V"' for v in voltages)
    speeds = ", ".join(f'"{s}"' for s in SCAN)
    (n_theta, n_z), order = grid.orbit_shape, grid.orbit_order
    return f'''# The whirl's limit cycles under the reading {reading[0]} + {reading[1]}: a stage of
# `foilbearing study`; rerun or extend it with `foilbearing sweep THIS_FILE --out RESULT`.
title = "Hopf type and limit cycles against voltage, {reading[0]} + {reading[1]}"
case = "{Path(str(case.source)).resolve().as_posix()}"
analysis = "bifurcation"

[set]  # the orbit's grid, for the static and linear analyses too
"grid.n_theta" = {n_theta}
"grid.n_z" = {n_z}
"grid.axial_order" = {order}
"grid.orbit_n_theta" = {n_theta}
"grid.orbit_n_z" = {n_z}
"grid.orbit_axial_order" = {order}
"grid.lift_off_smoothing" = {grid.lift_off_smoothing!r}
"actuators.preload_response" = "{reading[0]}"
"actuators.dynamics" = "{reading[1]}"

[bifurcation]
speed_range = [{speeds}]
steps = {steps}

[parameters]
voltage = [{volts}]
'''


def bifurcation_stage(
    case: Case,
    out: Path,
    stage: Callable[[str], None],
    voltages: Sequence[float] = (0.0, 50.0, 100.0, 150.0),
    steps: int = BIFURCATION_STEPS,
    grid: tuple[int, int] | None = None,
    theta_refine: int = 1,
) -> dict[str, Any]:
    """Run the branches of every voltage under both readings; their table and figure.

    ``grid`` (n_theta, n_z) replaces the shape of the case's orbit grid (None: the
    case's), which keeps its axial order and lift-off smoothing. ``theta_refine`` > 1:
    every branch again on that many times the θ cells (its sweep files beside the
    others, ``..._theta2x.toml``), each row with ``theta_refined``
    (:func:`cycle_errors`).

    Returns the stage's summary: ``rows`` (reading, voltage, type, onset, speed limit,
    the largest stable cycle, status), ``branches`` (each point's headline by reading and
    voltage), the grid, the sweep files and the figure; refined, ``refined_grid`` and
    ``refined_branches`` too.
    """
    from foilbearing.io import save_figure
    from foilbearing.output.plots.bifurcation import plot_whirl_branches
    from foilbearing.sweep.runner import _client

    g = case.orbit_case().grid
    n_theta, n_z = grid or g.orbit_shape
    on = replace(g.orbit_grid, n_theta=n_theta, n_z=n_z)
    stage(
        f"whirl limit cycles: Hopf type and branch at {len(voltages)} voltages under "
        f"{len(READINGS)} readings ({on.orbit_label}, "
        f"{steps + 2} cycles a branch) on a local Dask cluster"
    )
    finer = replace(on, n_theta=n_theta * theta_refine)
    files: list[str] = []
    with _client(None, None) as client:
        branches = _branches(case, out, stage, voltages, steps, on, client, "", files)
        if theta_refine > 1:
            stage(f"  every branch again on {finer.n_theta} θ cells, for the grid's error")
            fine = _branches(
                case, out, stage, voltages, steps, finer, client, f"_theta{theta_refine}x", files
            )
    rows = []
    for reading in READINGS:
        name = f"{reading[0]}+{reading[1]}"
        for volts in voltages:
            rec, head = branches[name][f"{volts:g}"]
            row = _row(name, volts, rec, head)
            if theta_refine > 1:
                row["theta_refined"] = cycle_errors(head, fine[name][f"{volts:g}"][1])
            rows.append(row)
    heads = _heads(branches)
    fig = save_figure(plot_whirl_branches(heads), out / "whirl_branches.png")
    summary: dict[str, Any] = {
        "rows": rows,
        "branches": heads,
        "grid": [on.n_theta, on.n_z],
        "grid_label": on.orbit_label,
        "steps": steps,
        "sweep_files": files,
        "figures": [str(fig)],
    }
    if theta_refine > 1:
        summary |= {"refined_grid": [finer.n_theta, finer.n_z], "refined_branches": _heads(fine)}
    return summary


_Records = dict[str, dict[str, tuple[dict[str, Any], dict[str, Any]]]]


def _heads(branches: _Records) -> dict[str, dict[str, Any]]:
    """The branch headlines by reading and voltage, without their sweep records."""
    return {name: {v: head for v, (_, head) in by.items()} for name, by in branches.items()}


def _branches(
    case: Case,
    out: Path,
    stage: Callable[[str], None],
    voltages: Sequence[float],
    steps: int,
    on: Grid,
    client: Any,
    suffix: str,
    files: list[str],
) -> _Records:
    """Each reading's sweep over the voltages on the orbit grid ``on`` (written as
    ``bifurcation_READING{suffix}.toml``, its file appended to ``files``): by reading and
    voltage, each point's sweep record and its branch headline."""
    from foilbearing.io import write_text
    from foilbearing.sweep.runner import done_points, load_sweep, output_paths, run_sweep

    branches: _Records = {}
    for reading in READINGS:
        name = f"{reading[0]}+{reading[1]}"
        tag = f"bifurcation_{reading[0]}-{reading[1]}{suffix}"
        path = write_text(out / f"{tag}.toml", _sweep_file(case, voltages, reading, steps, on))
        files.append(str(path))
        spec = load_sweep(path)
        summary = run_sweep(spec, out / tag, client=client, resume=_resumable(spec, out / tag))
        stage(
            f"  {name}: {summary['n_ok']} of {summary['n_points']} branches "
            f"({summary['wall_time_s']:.0f} s)"
        )
        records = done_points(output_paths(out / tag)[0])
        branches[name] = {}
        for i, volts in enumerate(voltages):
            rec = records.get(i, {"status": "missing"})
            branches[name][f"{volts:g}"] = (rec, rec.get("result") or {})
    return branches


def _resumable(spec: Any, out: Path) -> bool:
    """Whether the stage's results folder holds this very sweep (an interrupted study's:
    continue it); one of another plan is the study's own older output, removed."""
    import shutil

    from foilbearing.sweep.runner import output_paths, stored_fingerprint

    folder = output_paths(out)[0]
    if not folder.exists():
        return False
    if stored_fingerprint(folder) == spec.fingerprint():
        return True
    shutil.rmtree(folder)
    return False


def _row(reading: str, volts: float, rec: dict[str, Any], head: dict[str, Any]) -> dict[str, Any]:
    """One branch as a table row."""
    amps = head.get("amplitude_um") or []
    stable = head.get("stable") or []
    bounded = [
        (a, w) for a, w, s in zip(amps, head.get("speeds_rpm") or [], stable, strict=False) if s
    ]
    hopf = head.get("hopf_speed_rpm", head.get("onset_speed_rpm"))
    largest = max(bounded) if bounded else None
    return {
        "reading": reading.replace("+", " + "),
        "voltage_V": volts,
        "bifurcation_type": head.get("bifurcation_type"),
        "hopf_speed_rpm": hopf,
        "linear_whirl_frequency_Hz": head.get(
            "linear_whirl_frequency_Hz", head.get("whirl_frequency_Hz")
        ),
        "speed_limit_rpm": head.get("speed_limit_rpm"),
        "largest_stable_cycle_um": None if largest is None else largest[0],
        # its distance past the Hopf point, a fraction of the Hopf speed
        "largest_stable_cycle_past_onset": (
            None if largest is None or not hopf else largest[1] / hopf - 1.0
        ),
        "cycles": len(amps),
        "status": rec.get("status"),
        "message": rec.get("error") or head.get("message", ""),
    }


#: The readouts of a row that carry a grid error: key, name, unit and scale to the unit.
#: The onsets' least relative error applies to the speeds and frequencies of a linear
#: onset, none to a cycle's amplitude (:data:`_AMPLITUDES`: its two-grid difference alone).
_CYCLE_READOUTS = (
    ("hopf_speed_rpm", "Hopf", "krpm", 1e-3),
    ("linear_whirl_frequency_Hz", "whirl", "Hz", 1.0),
    ("speed_limit_rpm", "speed limit", "krpm", 1e-3),
    ("largest_stable_cycle_um", "largest stable cycle", "µm", 1.0),
)
_AMPLITUDES = ("largest_stable_cycle_um",)


#: How far past a branch's last cycle :func:`amplitude_at` extends its last segment, in
#: that segment's lengths: the refined branches of the study's stage end 1-2 segments
#: short of the coarse ones' relative distance past the onset (0 V, 2026-12-06).
EXTEND_LAST = 2.0


def amplitude_at(head: dict[str, Any], speed_rpm: float) -> float | None:
    """The amplitude of the branch ``head`` (a :meth:`WhirlBranch.headline
    <foilbearing.bifurcation.bearing.WhirlBranch.headline>`) at ``speed_rpm``, µm.

    The branch is read from its Hopf point (amplitude 0) cycle by cycle, and the first of
    its segments whose speeds span ``speed_rpm`` is interpolated linearly in the
    amplitude's square: exact for the Hopf normal form, A² ∝ (ω − ω_H). A speed on the
    other side of the Hopf point than the branch's first cycle has no cycle there (0: the
    equilibrium is stable); past the last cycle the last segment is extended by at most
    :data:`EXTEND_LAST` of its length. None: out of the branch's reach, or no branch.
    """
    hopf = head.get("hopf_speed_rpm")
    speeds, amps = head.get("speeds_rpm") or [], head.get("amplitude_um") or []
    if hopf is None or not speeds:
        return None
    w = [float(hopf), *map(float, speeds)]
    a2 = [0.0, *(float(a) ** 2 for a in amps)]
    for i in range(len(w) - 1):
        lo, hi = sorted((w[i], w[i + 1]))
        if lo <= speed_rpm <= hi and hi > lo:
            t = (speed_rpm - w[i]) / (w[i + 1] - w[i])
            return float(max(a2[i] + t * (a2[i + 1] - a2[i]), 0.0) ** 0.5)
    way = w[1] - w[0]  # the side of the Hopf point the branch leaves to
    if (speed_rpm - w[0]) * way < 0.0 and all((s - w[0]) * way >= 0.0 for s in w[1:]):
        return 0.0
    if w[-1] != w[-2]:
        t = (speed_rpm - w[-2]) / (w[-1] - w[-2])
        if 1.0 < t <= 1.0 + EXTEND_LAST:
            return float(max(a2[-2] + t * (a2[-1] - a2[-2]), 0.0) ** 0.5)
    return None


def cycle_errors(coarse: dict[str, Any], fine: dict[str, Any]) -> dict[str, Any]:
    """A branch's readouts with their grid error from the same branch on finer θ cells.

    ``coarse`` and ``fine`` are the two branches' headlines. The Hopf speed, its whirl and
    the speed limit: the two grids' difference, or the published onsets' least relative
    error (:data:`~foilbearing.study.converged.RESIDUAL_FLOOR`) if that is larger. The
    largest stable cycle is read at its distance past the Hopf point relative to the Hopf
    speed (the continuation's steps choose the speed), and its error is the difference to
    the finer branch's amplitude at the same relative distance past its own Hopf point
    (:func:`amplitude_at`): the Hopf point's own move is the onset's error, and near it a
    cycle grows as the square root of that distance, so that comparing at one speed
    would charge the onset's error to the amplitude many times over. A readout found on
    one grid only, or a cycle out of the finer branch's reach, has no error (None; its
    text says so).

    Returns
    -------
    dict
        ``grid`` (the finer grid), each readout's finer value (its key, and
        ``bifurcation_type``), ``errors``,
        ``texts`` (key → the coarse value with its error, in krpm, Hz or µm,
        :func:`~foilbearing.study.converged.with_error`) and ``text``, e.g. "grid error
        from 192 θ cells: Hopf 79.1 ± 0.6 krpm, ..., largest stable cycle 5.1 ± 0.1 µm".
    """
    from foilbearing.study.converged import RESIDUAL_FLOOR, two_grid_readouts

    row1, row2 = _row("", 0.0, {}, coarse), _row("", 0.0, {}, fine)
    past = row1["largest_stable_cycle_past_onset"]
    hopf = row2["hopf_speed_rpm"]
    reach = None if past is None or hopf is None else amplitude_at(fine, hopf * (1.0 + past))
    row2["largest_stable_cycle_um"] = reach
    grid = fine.get("grid")
    n = (grid or ["?"])[0]

    def error(key: str, f1: float, f2: float) -> float:
        return max(abs(f1 - f2), 0.0 if key in _AMPLITUDES else RESIDUAL_FLOOR * abs(f1))

    out, named = two_grid_readouts(_CYCLE_READOUTS, row1, row2, error, n, lost="out of reach")
    out["grid"] = grid
    kind = out["bifurcation_type"] = fine.get("bifurcation_type")
    if kind != coarse.get("bifurcation_type"):
        named.append(f"the Hopf bifurcation {kind} on {n} θ cells")
    out["text"] = f"grid error from {n} θ cells: " + ", ".join(named) if named else None
    return out


#: The passive stage's onset scan on the orbit grid: this fraction either side of the
#: onset the linear stage found on the static grid (the two grids' onsets differ by a
#: few percent at most, docs/numerics.md).
PASSIVE_BRACKET = 0.1


def passive_bifurcation_stage(
    case: Case,
    out: Path,
    stage: Callable[[str], None],
    onset_rpm: float | None,
    theta_refine: int = 1,
) -> dict[str, Any]:
    """A bearing without actuators: the Hopf type and the first limit cycles at its onset.

    The branch of :func:`~foilbearing.bifurcation.bearing.whirl_branch_headline` (what
    ``foilbearing bifurcation CASE`` prints), on the case's orbit grid, from the onset
    found in a scan of ±:data:`PASSIVE_BRACKET` around ``onset_rpm`` (the linear
    stage's onset, rpm), with :data:`BIFURCATION_STEPS` cycles after the first two. Run
    in this process (one branch: no Dask). Without an onset, says so and runs nothing.
    ``theta_refine`` > 1: the branch again on that many times the θ cells, its readouts'
    errors in ``theta_refined`` (:func:`cycle_errors`).

    Returns
    -------
    dict
        The branch's headline, with ``figures`` (``whirl_branch.png``) and ``rows`` (the
        report's one row, as the paper's stage has them), or a ``message``.
    """
    from foilbearing.bifurcation.bearing import whirl_branch_headline
    from foilbearing.bifurcation.shooting import ShootingError
    from foilbearing.constants import RPM
    from foilbearing.errors import InputError, SolverError
    from foilbearing.io import save_figure
    from foilbearing.output.plots.bifurcation import plot_whirl_branch

    if onset_rpm is None:
        stage("bifurcation: no linear onset in the plan's scan, so no Hopf point to start from")
        return {"bifurcation_type": None, "message": "no linear onset: no branch"}
    stage(f"bifurcation: Hopf type and the first limit cycles near {onset_rpm:.0f} rpm")
    low, high = (1 - PASSIVE_BRACKET) * onset_rpm, (1 + PASSIVE_BRACKET) * onset_rpm
    scan = [float(w) * RPM for w in (low, 0.5 * (low + high), high)]
    try:
        head, branch = whirl_branch_headline(case, scan, BIFURCATION_STEPS)
    except (ShootingError, SolverError, InputError) as exc:  # the study goes on without it
        stage(f"  bifurcation: {exc}")
        return {"bifurcation_type": None, "message": str(exc)}
    if branch is not None:
        fig = plot_whirl_branch(head, case.title)
        head["figures"] = [str(save_figure(fig, out / "whirl_branch.png"))]
        kind = head["bifurcation_type"]
        stage(f"  bifurcation: {kind} at {head['hopf_speed_rpm']:.0f} rpm ({head['message']})")
    else:
        stage(f"  bifurcation: {head['message']}")
    head["scan_rpm"] = [w / RPM for w in scan]
    if branch is None:
        return head
    head["rows"] = [_row("", 0.0, {"status": "ok"}, head)]
    if theta_refine > 1:
        n_theta = case.grid.orbit_shape[0] * theta_refine
        finer = replace(case, grid=replace(case.grid, orbit_n_theta=n_theta))
        try:
            fine, _ = whirl_branch_headline(finer, scan, BIFURCATION_STEPS)
        except (ShootingError, SolverError, InputError) as exc:  # the branch stays
            stage(f"  bifurcation on {n_theta} θ cells: {exc}; no grid error")
            return head
        head["theta_refined"] = head["rows"][0]["theta_refined"] = cycle_errors(head, fine)
        stage(f"  bifurcation on {n_theta} θ cells: {head['theta_refined']['text']}")
    return head
