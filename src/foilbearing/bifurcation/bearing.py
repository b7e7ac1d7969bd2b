"""The whirl's limit cycles of a rotor on the bearing, past and before the linear onset.

The autonomous system is the orbit's (:mod:`foilbearing.orbit`): film, foil and
journal at a constant speed, the case's voltages held, no imbalance and no
disturbance, integrated by the orbit's own stepper and compiled kernels. Its flow
over a time is one stepper run from a state (:func:`bearing_flow`); shooting and
continuation (:mod:`foilbearing.bifurcation.branch`) find the branch of periodic
orbits born at the linear onset, the Hopf point, with the parameter the rotor
speed. The Hopf point and its eigenvector come from the semi-discrete system's
own linearisation at the static equilibrium (a generalised eigenproblem of its
Jacobian and storage matrix), seeded by the onset of :func:`~foilbearing.analysis.stability.onset_speed`
on the same grid.

The state is scaled for shooting: pressures in p_a, bump deflections and ε in C,
the journal's velocity in C·ω_H (so that each part of a whirl is of order its
amplitude). The flow's derivative with respect to the state, the monodromy of
shooting, is exact: the variational equations of the stepper's own BDF steps
(:mod:`foilbearing.orbit.tangent`), one run factored per (state, period, speed) and
applied to any number of directions. Finite differences of stepper runs with a
tight Newton tolerance (``SHOOTING_SETTINGS``) remain for the derivatives in the
period and the speed; under top-foil lift-off the flow is only piecewise smooth,
so those need a larger step (``fd_step``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.bifurcation.branch import Branch, HopfPoint, hopf_branch
from foilbearing.bifurcation.shooting import FlowMap, PeriodicOrbit
from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.output.display import Summarised

__all__ = [
    "SHOOTING_SETTINGS",
    "SHOOTING_TOL",
    "WhirlBranch",
    "bearing_flow",
    "whirl_branch",
    "whirl_branch_headline",
]

FloatArray = NDArray[np.float64]

#: Orbit settings of the flow's runs: the Newton iteration converged far below the
#: shooting's tolerance (``newton_tol`` 3000 times tighter than an orbit's). A step's
#: iteration stops at a tolerance, so the flow jumps by up to it where round-off flips a
#: decision (one more iteration, a refreshed factor), and near the Hopf point (nontrivial
#: multiplier 0.9996) the cycle carries that jump round. Measured on the first cycles of
#: the 32 x 4 branches of the default case with suction retained, the onset moved by
#: 1e-14: their amplitudes spread by 1.5e-4 at 1e-3 (a Dask worker, its BLAS single-
#: threaded, and the main process disagreed by 1.4e-4), 6e-6 at 1e-4, 1.5e-7 at 1e-5;
#: the flow's Newton iterations a step on the default grid's branch 1.53, 1.73, 2.31. At
#: 1e-3 the noise also cost shooting iterations (up to 10 for a cycle, 2 at 1e-4).
SHOOTING_SETTINGS: dict[str, Any] = {
    "newton_tol": 1e-4,
    "newton_fraction": 1e-9,
    "max_newton": 30,
    "sample_rate": 20_000.0,
}

#: The shooting's tolerance on ``‖φ_T(y₀) − y₀‖/(1 + ‖y₀‖)`` (scaled state): a cycle is
#: known to about ``SHOOTING_TOL (1 + ‖y₀‖)`` in the state's units (C for the journal).
SHOOTING_TOL = 1e-7

#: Speeds whose simulations :class:`BearingFlow` keeps (a Newton step needs two or three).
_KEPT_SPEEDS = 8

#: Largest state whose monodromy shooting forms densely (exact columns, one block solve a
#: step); larger ones take GMRES and Arnoldi on exact products. Measured on the 0 V branch
#: of five cycles under the smoothed law (docs/bifurcation.md, "Cost"): the same on 32 x 4
#: (164 states, 8.7 s), the products 2.1 times faster on 64 x 4 (324) and 3.4 times on
#: 96 x 4 (484).
DENSE_STATES = 200


@dataclass
class BearingFlow:
    """The flow of a case at constant speeds, scaled for shooting (see the module)."""

    case: Case
    scale: FloatArray
    journal: int
    settings: Any
    #: Simulations and their static equilibria by speed, the most recent last.
    _sims: dict[float, Any] = field(default_factory=dict)
    _equilibria: dict[float, FloatArray] = field(default_factory=dict)
    #: The last run factored for its derivative: (state bytes, period, speed) and it.
    _tangent: tuple[tuple[bytes, float, float], Any] | None = None

    def simulation(self, speed: float) -> Any:
        from foilbearing.control import constant_speed
        from foilbearing.orbit.system import OrbitSimulation

        key = round(float(speed), 9)
        if key not in self._sims:
            if len(self._sims) >= _KEPT_SPEEDS:  # continuation visits a new speed per step
                oldest = next(iter(self._sims))
                del self._sims[oldest]
                self._equilibria.pop(oldest, None)
            self._sims[key] = OrbitSimulation(
                self.case, constant_speed(speed, 1e3), settings=self.settings
            )
        return self._sims[key]

    def run(self, y_scaled: FloatArray, duration: float, speed: float) -> Any:
        """One stepper run from a scaled state; the result (its checkpoint holds the end)."""
        from foilbearing.orbit.sampling import Samples
        from foilbearing.orbit.stepper import State, run

        sim, s = self.simulation(speed), self.settings
        start = State(0.0, np.asarray(y_scaled, float) * self.scale)
        samples = Samples(1.0 / s.sample_rate)
        return run(sim.problem(), start, samples, s.step_rule, s.newton_rule, s.stop_rule(duration))

    def reaches(self, speed: float) -> bool:
        """Whether the case runs at ``speed`` (``(0, operation.max_speed]``): a corrector's
        iterate outside has no flow, and its NaN ends that Newton iteration."""
        return 0.0 < speed <= self.case.operation.max_speed

    def advance(self, y_scaled: FloatArray, duration: float, speed: float) -> FloatArray:
        if not self.reaches(speed):
            return np.full(self.scale.size, np.nan)
        res = self.run(y_scaled, duration, speed)
        if res.status not in ("stopped", "completed"):
            return np.full(self.scale.size, np.nan)  # contact or failure: no flow there
        return np.asarray(res.checkpoint["y"], float) / self.scale

    def tangent(
        self, y_scaled: FloatArray, duration: float, speed: float, v: FloatArray
    ) -> FloatArray:
        """∂φ/∂y₀ · v of the scaled flow, exact (:func:`~foilbearing.orbit.tangent.run_tangent`);
        v of shape (n,) or (n, m). NaN where the run does not end (contact)."""
        from foilbearing.orbit.tangent import run_tangent

        y = np.asarray(y_scaled, float)
        if not self.reaches(speed):
            return np.full(np.shape(v), np.nan)
        key = (y.tobytes(), float(duration), float(speed))
        if self._tangent is None or self._tangent[0] != key:
            self._tangent = (key, run_tangent(self.simulation(speed), y * self.scale, duration))
        rt = self._tangent[1]
        v = np.asarray(v, float)
        if rt is None:
            return np.full(v.shape, np.nan)
        grow = self.scale if v.ndim == 1 else self.scale[:, None]
        return rt.apply(v * grow) / grow

    def field(self, y_scaled: FloatArray, speed: float) -> FloatArray:
        """dy/dt by a run over 1/96 of a revolution (the section's normal and ∂φ/∂T)."""
        dt = 2.0 * math.pi / (speed * 96.0)
        return (self.advance(y_scaled, dt, speed) - y_scaled) / dt

    def equilibrium(self, speed: float) -> FloatArray:
        """The static equilibrium at ``speed`` as a scaled state (solved once per speed)."""
        sim, key = self.simulation(speed), round(float(speed), 9)
        if key not in self._equilibria:
            state = np.asarray(sim.initial_state(), float) / self.scale
            state.flags.writeable = False  # shared by every caller at this speed
            self._equilibria[key] = state
        return self._equilibria[key]


def bearing_flow(
    case: Case, whirl: float, fd_step: float, steps_per_rev: int | None = None
) -> tuple[FlowMap, BearingFlow]:
    """The case's autonomous orbit system as a :class:`FlowMap` (and its parts).

    ``case`` is put on its orbit grid, without imbalance or disturbance; ``whirl``
    (rad/s) scales the journal's velocity; ``steps_per_rev`` sets the stepper's time step
    (default the orbit's, 24 a revolution).
    """
    from foilbearing.orbit import OrbitSettings

    case = case.orbit_case()
    case = replace(case, rotor=replace(case.rotor, imbalance=0.0), disturbance=None)
    step: dict[str, Any] = {} if steps_per_rev is None else {"steps_per_rev": steps_per_rev}
    settings = OrbitSettings(**SHOOTING_SETTINGS, **step)
    probe = BearingFlow(case, np.ones(1), 0, settings)
    system = probe.simulation(case.operation.speed).system
    scale = np.ones(system.size)
    journal = system.n + system.nt
    scale[journal + 2 :] = whirl
    parts = BearingFlow(case, scale, journal, settings)
    flow = FlowMap(
        advance=parts.advance,
        field=parts.field,
        tangent=parts.tangent,
        fd_step=fd_step,
        dense_max=DENSE_STATES,
        krylov_rtol=1e-6,
        krylov_accept=0.1,
        tangent_blocks=True,
    )
    return flow, parts


def _hopf_eigenvector(parts: BearingFlow, speed: float, whirl: float) -> tuple[complex, Any]:
    """The eigenvalue of the semi-discrete system nearest i·whirl at the equilibrium, and
    its eigenvector (scaled state): ``(∂f/∂y) q = λ (∂Q/∂y) q``.

    Under lift-off one set of branches, decided once at the equilibrium, serves both
    matrices: the held cells' rows (``d (P − 1) = 0``) have no storage, algebraic
    constraints of the eigenproblem. (Deciding them apart for each matrix let a cell on
    the lift-off boundary, P = 1 with no net flow, fall on either side and gave spurious
    eigenvalues: an unstable 38 Hz pair at the 150 V onset on 32 × 4.)
    """
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    sim = parts.simulation(speed)
    system = sim.system
    y = np.asarray(sim.initial_state(), float)
    inputs = sim.inputs(0.0, sim.volts(0.0), imbalance=False)
    zero = np.zeros(system.size)
    branches = system.lift_state(y, inputs, 0.0, zero)
    held = np.zeros(system.size)
    held[: system.n] = branches > 0.0
    storage = sp.diags(1.0 - held) @ system.storage_jacobian(y, inputs.preload)
    stiffness = -system.jacobian(y, inputs, 0.0, zero, lift_state=branches)
    # Shift-invert about i·whirl: the eigenvalues ν of (A − σM)⁻¹M are 1/(λ − σ), the
    # largest the λ nearest σ (sparse; the dense problem took 6 s on 96 × 12).
    sigma = 1j * whirl
    lu = spla.splu(sp.csc_matrix(stiffness - sigma * storage, dtype=complex))
    op = spla.LinearOperator(
        stiffness.shape, matvec=lambda v: lu.solve(storage @ np.asarray(v)), dtype=complex
    )
    # A fixed start vector: ARPACK's default is random, and the branch's first section
    # (along the eigenvector) should not change from run to run.
    nu, vectors = spla.eigs(op, k=1, which="LM", v0=np.ones(system.size, dtype=complex))
    return complex(sigma + 1.0 / nu[0]), vectors[:, 0] / parts.scale


@dataclass(frozen=True, repr=False)
class WhirlBranch(Summarised):
    """The branch of whirl limit cycles from the linear onset, with its readouts.

    Printed, it shows the Hopf type and speed, the speed limit and the first
    cycles in a few lines (a table in a notebook); :meth:`plot` draws the branch.

    Attributes
    ----------
    case
        The case on its orbit grid, at the voltages held.
    hopf_speed, whirl_frequency
        The linear onset (rad/s) and its whirl frequency (rad/s), on the same grid.
    eigenvalue
        The semi-discrete system's eigenvalue at the onset (1/s), nearest i·whirl.
    branch
        The periodic orbits (:class:`~foilbearing.bifurcation.branch.Branch`).
    amplitude
        Half the largest extent of e_X and e_Y over each orbit, m.
    min_film
        Smallest film over each orbit, m.
    """

    case: Case
    hopf_speed: float
    whirl_frequency: float
    eigenvalue: complex
    branch: Branch
    amplitude: FloatArray
    min_film: FloatArray

    @property
    def speed_limit(self) -> float | None:
        """Where the whirl stops being safe, rad/s, or None where the branch ended first.

        A subcritical branch: its lowest fold below the onset (below the onset a large
        enough disturbance already throws the journal beyond the unstable cycle).
        Otherwise, or without such a fold, the first fold above the onset (past it no
        bounded cycle is left: the whirl jumps away), or the speed of a cycle whose film
        closed (contact)."""
        folds = self.branch.folds
        below = [f for f in folds if f < self.hopf_speed]
        above = [f for f in folds if f >= self.hopf_speed]
        if self.branch.bifurcation_type == "subcritical" and below:
            return float(min(below))
        if above:
            return float(above[0])
        if "contact" in self.branch.message and self.branch.orbits:
            return float(self.branch.orbits[-1].parameter)
        return None

    def _summary(self) -> tuple[str, dict[str, Any], None]:
        head = self.headline()
        head.pop("largest_multiplier")
        n = len(self.branch.orbits)
        title = f"Whirl branch of the {self.case.kind}: {n} limit cycles from the Hopf point"
        return title, head, None

    def plot(self) -> Any:
        """Limit-cycle amplitude (µm) and whirl frequency (Hz) against speed, stable
        cycles solid (:func:`~foilbearing.output.plots.bifurcation.plot_whirl_branch`);
        returns the matplotlib Figure."""
        from foilbearing.output.plots.bifurcation import plot_whirl_branch

        return plot_whirl_branch(self.headline(), self.case.title)

    def headline(self) -> dict[str, Any]:
        """Unit-named keys (``--json``)."""
        orbits = self.branch.orbits
        limit = self.speed_limit
        return {
            "bifurcation_type": self.branch.bifurcation_type,
            "hopf_speed_rpm": self.hopf_speed / RPM,
            "linear_whirl_frequency_Hz": self.whirl_frequency / (2.0 * math.pi),
            "speed_limit_rpm": None if limit is None else limit / RPM,
            "speeds_rpm": [float(o.parameter / RPM) for o in orbits],
            "amplitude_um": [float(a) * 1e6 for a in self.amplitude],
            "min_film_um": [float(h) * 1e6 for h in self.min_film],
            "whirl_frequency_Hz": [float(1.0 / o.period) for o in orbits],
            "stable": [bool(o.stable) for o in orbits],
            "largest_multiplier": [float(np.max(np.abs(o.nontrivial_multipliers))) for o in orbits],
            "message": self.branch.message,
            "grid": [self.case.grid.n_theta, self.case.grid.n_z],
        }


def whirl_branch(
    case: Case,
    *,
    scan: list[float] | None = None,
    onset: Any = None,
    steps: int = 8,
    amplitude: float = 0.02,
    ds: float = 1.0,
    fd_step: float | None = None,
    tol: float = SHOOTING_TOL,
    progress: Callable[[str], None] | None = None,
    steps_per_rev: int | None = None,
) -> WhirlBranch:
    """The whirl's limit cycles from the linear onset of ``case`` (its voltages held).

    Parameters
    ----------
    case
        The bearing case; its orbit grid is used throughout.
    scan
        Speeds of the onset search, rad/s (default that of
        :func:`~foilbearing.analysis.stability.onset_speed`).
    onset
        The onset already found on the case's orbit grid (an
        :class:`~foilbearing.analysis.stability.OnsetResult`); then ``scan`` is not used.
    steps
        Orbits after the two first ones.
    amplitude
        The first orbit's amplitude on the section, in the scaled state (about C/50).
    ds
        Arclength step (scaled; :func:`~foilbearing.bifurcation.branch.hopf_branch`).
    fd_step
        Relative step of the flow's differences; default 1e-4 under lift-off (the
        flow is piecewise smooth there), 1e-5 with suction retained.
    tol
        Shooting tolerance on ``‖φ_T(y₀) − y₀‖/(1 + ‖y₀‖)``.
    progress
        Called with a line per orbit.
    steps_per_rev
        The stepper's time steps a revolution (default the orbit's; a step convergence
        check takes more).

    Raises
    ------
    InputError
        No onset in the scan (stable throughout, or unstable from its start).
    """
    from foilbearing.analysis.stability import onset_speed

    on_grid = case.orbit_case()
    if onset is None:
        onset = onset_speed(on_grid, scan)
    if onset.onset_speed is None or onset.whirl_frequency is None:
        raise InputError(f"no Hopf point to start from: {onset.message}")
    if onset.onset_speed <= onset.speeds[0]:
        raise InputError(
            f"unstable from the start of the scan ({onset.speeds[0] / RPM:.0f} rpm): start "
            "the scan lower"
        )
    lift = case.foil is not None and case.foil.lift_off
    step = fd_step if fd_step is not None else (1e-4 if lift else 1e-5)
    flow, parts = bearing_flow(on_grid, onset.whirl_frequency, step, steps_per_rev)
    value, vector = _hopf_eigenvector(parts, onset.onset_speed, onset.whirl_frequency)
    hopf = HopfPoint(onset.onset_speed, abs(value.imag), vector, 1)
    paths: dict[int, tuple[float, float]] = {}
    c = parts.case.bearing.clearance

    def path(orbit: PeriodicOrbit) -> tuple[float, float]:
        if id(orbit) not in paths:
            res = parts.run(orbit.state, orbit.period, orbit.parameter)
            extent = max(np.ptp(res.e_x), np.ptp(res.e_y)) / 2.0
            paths[id(orbit)] = (float(extent), float(np.min(res.min_film)))
            if progress is not None:
                progress(
                    f"  {orbit.parameter / RPM:8.0f} rpm: cycle {extent * 1e6:7.3f} µm, "
                    f"{1.0 / orbit.period:6.1f} Hz, {'stable' if orbit.stable else 'unstable'}"
                )
        return paths[id(orbit)]

    contact = parts.settings.contact_film * c
    branch = hopf_branch(
        flow,
        hopf,
        parts.equilibrium,
        amplitude=amplitude,
        steps=steps,
        ds=ds,
        p_scale=0.01 * onset.onset_speed,
        p_bounds=(0.5 * onset.onset_speed, float(on_grid.operation.max_speed)),
        measure=lambda o: path(o)[0],
        stop=lambda o: path(o)[1] <= contact,
        tol=tol,
        describe=lambda speed: f"{speed / RPM:.0f} rpm",
    )
    if "(the stop condition)" in branch.message:
        what = f"(a cycle's film fell below {parts.settings.contact_film:g} C: contact)"
        branch = replace(branch, message=branch.message.replace("(the stop condition)", what))
    amp = np.array([path(o)[0] for o in branch.orbits])
    film = np.array([path(o)[1] for o in branch.orbits])
    return WhirlBranch(
        parts.case, onset.onset_speed, onset.whirl_frequency, value, branch, amp, film
    )


def whirl_branch_headline(
    case: Case,
    scan: list[float],
    steps: int,
    progress: Callable[[str], None] | None = None,
) -> tuple[dict[str, Any], WhirlBranch | None]:
    """The branch's headline (:meth:`WhirlBranch.headline`), or the linear readouts when the
    scan holds no Hopf point (stable throughout, or unstable from its start), with
    ``bifurcation_type`` None (``onset_speed_rpm``, ``linear_whirl_frequency_Hz``,
    ``whirl_ratio``, ``message``); and the branch (None without a Hopf point).

    The linear onset is found once, on the case's orbit grid. Raises
    :class:`~foilbearing.bifurcation.shooting.ShootingError` when the first cycles from
    the onset do not converge (its message says how far it got).
    """
    from foilbearing.analysis.stability import onset_speed

    onset = onset_speed(case.orbit_case(), scan)
    if onset.onset_speed is None or onset.onset_speed <= scan[0]:
        linear = onset.headline()
        out: dict[str, Any] = {
            "bifurcation_type": None,
            "onset_speed_rpm": linear["onset_speed_rpm"],
            "linear_whirl_frequency_Hz": linear["whirl_frequency_Hz"],
            "whirl_ratio": linear["whirl_ratio"],
            "message": f"no Hopf point in {scan[0] / RPM:.0f}-{scan[-1] / RPM:.0f} rpm: "
            + ("unstable from its start" if onset.onset_speed else onset.message),
        }
        return out, None
    from foilbearing.bifurcation.shooting import ShootingError

    try:
        wb = whirl_branch(case, onset=onset, steps=steps, progress=progress)
    except ShootingError as exc:
        at = f"{onset.onset_speed / RPM:.0f} rpm"
        raise ShootingError(f"the first cycles from the linear onset at {at}: {exc}") from exc
    return wb.headline(), wb
