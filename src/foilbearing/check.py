"""How far to trust a case's numbers: its headline readouts on its grid and on refined grids.

``foilbearing check CASE`` (:func:`grid_check`) solves the case's headline readouts
(the static equilibrium at its operating point, the direct stiffness and damping at the
synchronous frequency, and the linear onset and whirl frequency where the case's
``[study] speed_range`` or the caller gives a scan) on the case's grid and on grids
refined by 2 (and 4) in both θ and Z, the axial order and the lift-off smoothing κ held
(κ's smoothing length δ = κΔθ² shrinks with the cell, so the law converges to the sharp
one as the grid is refined: docs/lift-off.md).

Each readout's discretisation error on the case's grid is estimated from the levels
(:func:`error_estimate`): with two, the difference to the finer grid; with three,
Richardson extrapolation at the observed order p = log2(|f1 − f2| / |f2 − f3|), the
error being the case's value against the extrapolated one. Where the differences change
sign or p is outside :data:`RELIABLE_ORDER` the order is not trusted, and the error is
the largest distance of the case's value from the finer ones.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import InputError, SolverError
from foilbearing.output.display import Summarised

__all__ = [
    "READOUTS",
    "RELIABLE_ORDER",
    "GridCheck",
    "error_estimate",
    "grid_check",
    "onset_near",
    "refined",
]

#: The readouts of the check: key (unit-named), label, and the factor from SI to that unit.
READOUTS: tuple[tuple[str, str, float], ...] = (
    ("eccentricity", "eccentricity ε₀", 1.0),
    ("min_film_um", "minimum film, µm", 1e6),
    ("attitude_deg", "attitude angle, deg", 180.0 / math.pi),
    ("drag_torque_Nm", "drag torque, N m", 1.0),
    ("K_XX_MN_per_m", "K_XX at 1X, MN/m", 1e-6),
    ("K_YY_MN_per_m", "K_YY at 1X, MN/m", 1e-6),
    ("C_XX_kNs_per_m", "C_XX at 1X, kN s/m", 1e-3),
    ("C_YY_kNs_per_m", "C_YY at 1X, kN s/m", 1e-3),
    ("onset_speed_rpm", "linear onset, rpm", 1.0 / RPM),
    ("whirl_frequency_Hz", "whirl frequency, Hz", 1.0 / (2.0 * math.pi)),
)

#: Observed orders trusted for Richardson extrapolation: the film's scheme is second order
#: in θ and Z (docs/numerics.md §2); the lift-off boundary crossing cells gives orders down
#: to about 1 in the onsets (docs/lift-off.md), and above 4 the differences are round-off
#: or a cancellation.
RELIABLE_ORDER = (0.7, 4.0)

#: Relative half-width of the onset bracket scanned on a refined grid around the onset of
#: the coarser one (the full scan again where the onset is not inside it).
ONSET_BRACKET = 0.15


def refined(case: Case, factor: int) -> Case:
    """The case on its grid with ``factor`` times the cells in θ and in Z (order and κ held).

    The orbit's own grid is left as it is: the check is of the static and linear analyses.
    """
    g = case.grid
    return replace(case, grid=replace(g, n_theta=g.n_theta * factor, n_z=g.n_z * factor))


def onset_near(
    case: Case,
    speeds: Sequence[float],
    near: float | None,
    *,
    rel_tol: float = 1e-6,
    bracket: float = ONSET_BRACKET,
) -> Any:
    """The linear onset on the case's grid, scanned first in a bracket around ``near``.

    Parameters
    ----------
    case
        The case, on the grid to solve (a refined level: :func:`refined`).
    speeds
        The full scan, rad/s, increasing: used where ``near`` is None or the onset is not
        inside the bracket.
    near
        The onset on a coarser grid, rad/s (None: the full scan at once).
    rel_tol
        Brent's tolerance (:func:`foilbearing.analysis.stability.onset_speed`).
    bracket
        Relative half-width of the bracket around ``near``.

    Returns
    -------
    OnsetResult
    """
    from foilbearing.analysis.stability import onset_speed

    if near is not None:
        top = min(near * (1 + bracket), case.operation.max_speed)
        on = onset_speed(case, [near * (1 - bracket), top], rel_tol=rel_tol)
        if on.onset_speed is not None and on.speeds.size >= 2:  # inside the bracket
            return on
    return onset_speed(case, speeds, rel_tol=rel_tol)


def _readouts(
    case: Case, onset_speeds: Sequence[float] | None, near_onset: float | None
) -> dict[str, float | None]:
    """The readouts of :data:`READOUTS` on the case's grid, in their units.

    ``near_onset`` (rad/s): scan only a bracket around it first (a refined level).
    """
    from foilbearing.analysis.coefficients import force_coefficients
    from foilbearing.analysis.equilibrium import solve_equilibrium

    st = solve_equilibrium(case)
    if not st.converged:
        grid = f"{case.grid.n_theta} × {case.grid.n_z}"
        raise SolverError(
            f"check: the equilibrium on {grid} did not converge ({st.message}); "
            "try `foilbearing static` on the case (a load beyond the film's capacity fails "
            "there too), or fewer --levels"
        )
    fc = force_coefficients(st, [st.speed])
    k, c = fc.K[0], fc.C[0]
    si: dict[str, float | None] = {
        "eccentricity": st.eccentricity,
        "min_film_um": st.min_film,
        "attitude_deg": st.attitude_angle,
        "drag_torque_Nm": st.drag_torque,
        "K_XX_MN_per_m": float(k[0, 0]),
        "K_YY_MN_per_m": float(k[1, 1]),
        "C_XX_kNs_per_m": float(c[0, 0]),
        "C_YY_kNs_per_m": float(c[1, 1]),
        "onset_speed_rpm": None,
        "whirl_frequency_Hz": None,
    }
    if onset_speeds is not None:
        on = onset_near(case, onset_speeds, near_onset, rel_tol=1e-6)
        si["onset_speed_rpm"] = on.onset_speed
        si["whirl_frequency_Hz"] = on.whirl_frequency
    out: dict[str, float | None] = {}
    for key, _, factor in READOUTS:
        value = si[key]
        out[key] = None if value is None else value * factor
    return out


def error_estimate(values: Sequence[float | None]) -> dict[str, Any]:
    """The discretisation error of ``values[0]`` (the case's grid) from its refinements.

    Parameters
    ----------
    values
        The readout on the case's grid and on grids refined by 2 (and 4); None where it
        has no value (no onset in the scan).

    Returns
    -------
    dict
        ``method`` ("difference to the x2 grid" or "Richardson"), ``error`` (the case's
        value minus the reference, in the readout's unit), ``relative_error`` (over the
        reference), ``reference`` (the finer value or the extrapolated one) and, with
        three levels, ``order`` (observed p, None where the differences vanish) and
        ``order_reliable``.
    """
    if any(v is None for v in values) or len(values) < 2:
        return {"method": None, "error": None, "relative_error": None, "reference": None}
    f = [float(v) for v in values]  # type: ignore[arg-type]
    if len(f) == 2:
        ref = f[1]
        out: dict[str, Any] = {"method": "difference to the x2 grid", "reference": ref}
    else:
        f1, f2, f3 = f[:3]
        d12, d23 = f1 - f2, f2 - f3
        order = math.log2(abs(d12) / abs(d23)) if d12 != 0.0 and d23 != 0.0 else None
        reliable = (
            order is not None
            and d12 * d23 > 0.0
            and RELIABLE_ORDER[0] <= order <= RELIABLE_ORDER[1]
        )
        if reliable:
            assert order is not None
            ref = f3 - d23 / (2.0**order - 1.0)  # f3 + (f3 - f2) / (2^p - 1)
            out = {"method": "Richardson", "reference": ref}
        else:  # the worst distance to a finer value, referred to the finest
            far = max(f2, f3, key=lambda x: abs(f1 - x))
            return {
                "method": "largest difference to a finer grid (order unreliable)",
                "reference": far,
                "error": f1 - far,
                "relative_error": (f1 - far) / far if far != 0.0 else None,
                "order": order,
                "order_reliable": False,
            }
        out |= {"order": order, "order_reliable": True}
    out["error"] = f[0] - ref
    out["relative_error"] = (f[0] - ref) / ref if ref != 0.0 else None
    return out


@dataclass(frozen=True, repr=False)
class GridCheck(Summarised):
    """The readouts of a case on its grid and on refined grids, with their error estimates.

    Printed, it shows :meth:`table`; in a notebook, the same as an HTML table.

    Attributes
    ----------
    grids
        (n_theta, n_z) of each level, the case's first.
    axial_order, lift_off_smoothing
        Held on every level.
    lift_off_law
        "smoothed edge", "sharp edge" or "none" (:func:`foilbearing.output.summary.grid_used`).
    values
        ``{key: [value per level]}`` in the units the key names (:data:`READOUTS`).
    wall_times
        Seconds each level took.
    """

    title: str
    grids: tuple[tuple[int, int], ...]
    axial_order: int
    lift_off_smoothing: float
    lift_off_law: str
    values: dict[str, list[float | None]]
    wall_times: tuple[float, ...]

    def estimates(self) -> dict[str, dict[str, Any]]:
        """:func:`error_estimate` of each readout."""
        return {key: error_estimate(v) for key, v in self.values.items()}

    def __repr__(self) -> str:
        return f"{self._summary()[0]}\n{self.table()}"

    def _summary(self) -> tuple[str, dict[str, Any], None]:
        grids = ", ".join(f"{n} × {m}" for n, m in self.grids)
        title = f"Grid check of {self.title or 'case'}: grids {grids}, lift-off {self.lift_off_law}"
        rows: dict[str, Any] = {}
        for key, est in self.estimates().items():
            if all(v is None for v in self.values[key]):
                continue
            rel = est["relative_error"]
            note = "error –" if rel is None else f"error {100 * rel:+.2f} %"
            rows[key] = [*self.values[key], note]
        return title, rows, None

    def headline(self) -> dict[str, Any]:
        """Unit-named keys (the CLI's ``--json``)."""
        est = self.estimates()
        return {
            "title": self.title,
            "grids": [list(g) for g in self.grids],
            "axial_order": self.axial_order,
            "lift_off_smoothing": self.lift_off_smoothing,
            "lift_off_law": self.lift_off_law,
            "wall_time_s": list(self.wall_times),
            "readouts": {
                key: {"values": self.values[key]} | est[key]
                for key, _, _ in READOUTS
                if any(v is not None for v in self.values[key])
            },
        }

    def table(self) -> str:
        """The readouts as a text table: one row each, a column per grid and the error."""
        est = self.estimates()
        grids = [f"{n}×{m}" for n, m in self.grids]
        head = (
            f"  {'readout':<24}"
            + "".join(f"{g:>13}" for g in grids)
            + "   error of the case's grid"
        )
        lines = [head]
        for key, label, _ in READOUTS:
            vals = self.values[key]
            if all(v is None for v in vals):
                continue
            cells = "".join(f"{'-':>13}" if v is None else f"{v:>13.6g}" for v in vals)
            e = est[key]
            if e["relative_error"] is None:
                note = "-" if e["error"] is None else f"{e['error']:+.3g}"
            else:
                note = f"{100 * e['relative_error']:+.2f} %"
            if e.get("order") is not None and e.get("order_reliable"):
                note += f" (Richardson, p = {e['order']:.2f})"
            elif "order_reliable" in e:
                p = "-" if e.get("order") is None else f"{e['order']:.2f}"
                note += f" (order unreliable, p = {p}: largest difference to a finer grid)"
            lines.append(f"  {label:<24}{cells}   {note}")
        if len(self.grids) == 2:
            lines.append(
                "  error: the case's grid against the ×2 grid (the finer is not converged "
                "either; --levels 3 extrapolates)"
            )
        return "\n".join(lines)


def grid_check(
    case: Case,
    levels: int = 2,
    *,
    onset_speeds: Sequence[float] | None = None,
    progress: Callable[[str], None] | None = None,
) -> GridCheck:
    """The case's readouts on its grid and on ``levels - 1`` refinements by 2.

    Parameters
    ----------
    case
        The case, on the grid it runs on.
    levels
        2 (the case's grid and ×2) or 3 (and ×4, for Richardson extrapolation).
    onset_speeds
        Scan of the linear onset, rad/s, increasing (None: no onset readout).
    progress
        Called with a line as each level starts and ends.
    """
    import time

    from foilbearing.output.summary import grid_used

    if levels not in (2, 3):
        raise InputError(f"--levels {levels}: allowed 2 or 3")
    g = case.grid
    values: dict[str, list[float | None]] = {key: [] for key, _, _ in READOUTS}
    grids, times = [], []
    near = None
    for level in range(levels):
        c = refined(case, 2**level)
        shape = (c.grid.n_theta, c.grid.n_z)
        if progress is not None:
            progress(f"check: grid {shape[0]} × {shape[1]} ({level + 1} of {levels})")
        t0 = time.perf_counter()
        got = _readouts(c, onset_speeds, near)
        times.append(time.perf_counter() - t0)
        if got["onset_speed_rpm"] is not None:
            near = got["onset_speed_rpm"] * RPM
        for key, v in got.items():
            values[key].append(v)
        grids.append(shape)
        if progress is not None:
            progress(f"check: grid {shape[0]} × {shape[1]} done in {times[-1]:.1f} s")
    return GridCheck(
        case.title,
        tuple(grids),
        g.axial_order,
        g.lift_off_smoothing,
        grid_used(case)["lift_off_law"],
        values,
        tuple(times),
    )
