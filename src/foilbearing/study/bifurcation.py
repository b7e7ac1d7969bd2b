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
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from foilbearing.case import Case, Grid

__all__ = ["BIFURCATION_STEPS", "READINGS", "bifurcation_stage", "passive_bifurcation_stage"]

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
) -> dict[str, Any]:
    """Run the branches of every voltage under both readings; their table and figure.

    ``grid`` (n_theta, n_z) replaces the shape of the case's orbit grid (None: the
    case's), which keeps its axial order and lift-off smoothing.

    Returns the stage's summary: ``rows`` (reading, voltage, type, onset, speed limit,
    the largest stable cycle, status), ``branches`` (each point's headline by reading and
    voltage), the grid, the sweep files and the figure.
    """
    from foilbearing.io import save_figure, write_text
    from foilbearing.output.plots.bifurcation import plot_whirl_branches
    from foilbearing.sweep.runner import _client, done_points, load_sweep, output_paths, run_sweep

    g = case.orbit_case().grid
    n_theta, n_z = grid or g.orbit_shape
    on = replace(g.orbit_grid, n_theta=n_theta, n_z=n_z)
    stage(
        f"whirl limit cycles: Hopf type and branch at {len(voltages)} voltages under "
        f"{len(READINGS)} readings ({on.orbit_label}, "
        f"{steps + 2} cycles a branch) on a local Dask cluster"
    )
    rows: list[dict[str, Any]] = []
    branches: dict[str, dict[str, Any]] = {}
    files = []
    with _client(None, None) as client:
        for reading in READINGS:
            name = f"{reading[0]}+{reading[1]}"
            tag = f"bifurcation_{reading[0]}-{reading[1]}"
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
                head = rec.get("result") or {}
                branches[name][f"{volts:g}"] = head
                rows.append(_row(name, volts, rec, head))
    fig = save_figure(plot_whirl_branches(branches), out / "whirl_branches.png")
    return {
        "rows": rows,
        "branches": branches,
        "grid": [on.n_theta, on.n_z],
        "grid_label": on.orbit_label,
        "steps": steps,
        "sweep_files": files,
        "figures": [str(fig)],
    }


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
    bounded = [a for a, s in zip(amps, stable, strict=False) if s]
    return {
        "reading": reading.replace("+", " + "),
        "voltage_V": volts,
        "bifurcation_type": head.get("bifurcation_type"),
        "hopf_speed_rpm": head.get("hopf_speed_rpm", head.get("onset_speed_rpm")),
        "linear_whirl_frequency_Hz": head.get(
            "linear_whirl_frequency_Hz", head.get("whirl_frequency_Hz")
        ),
        "speed_limit_rpm": head.get("speed_limit_rpm"),
        "largest_stable_cycle_um": max(bounded) if bounded else None,
        "cycles": len(amps),
        "status": rec.get("status"),
        "message": rec.get("error") or head.get("message", ""),
    }


#: The passive stage's onset scan on the orbit grid: this fraction either side of the
#: onset the linear stage found on the static grid (the two grids' onsets differ by a
#: few percent at most, docs/numerics.md).
PASSIVE_BRACKET = 0.1


def passive_bifurcation_stage(
    case: Case, out: Path, stage: Callable[[str], None], onset_rpm: float | None
) -> dict[str, Any]:
    """A bearing without actuators: the Hopf type and the first limit cycles at its onset.

    The branch of :func:`~foilbearing.bifurcation.bearing.whirl_branch_headline` (what
    ``foilbearing bifurcation CASE`` prints), on the case's orbit grid, from the onset
    found in a scan of ±:data:`PASSIVE_BRACKET` around ``onset_rpm`` (the linear
    stage's onset, rpm), with :data:`BIFURCATION_STEPS` cycles after the first two. Run
    in this process (one branch: no Dask). Without an onset, says so and runs nothing.

    Returns
    -------
    dict
        The branch's headline, with ``figures`` (``whirl_branch.png``), or a ``message``.
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
    return head
