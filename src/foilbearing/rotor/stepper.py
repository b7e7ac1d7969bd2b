"""The nonlinear rotor on the BDF integrator: every film's compiled kernels, one rotor solve.

:class:`RotorStepper` hands the rotor on its bearings to the generic variable-order BDF
(:func:`foilbearing.integrate.integrate`, the orbit's integrator) as a
:class:`~foilbearing.integrate.Problem`, with the films' lift-off branches
(:class:`~foilbearing.orbit.stepper.LiftOffBranches`) and the contact as a stop event: the
same state and equations as :class:`~foilbearing.rotor.nonlinear.RotorOrbitSystem` (each bearing's film and foil, then the reduced rotor's q and q̇), in the
implicit form ``d Q(y)/dt = f(y, t)`` with ``Q = [P_b H_b, U_b, ..., q, q̇]``.

A Newton matrix is factorised by block elimination:

- each bearing's film and foil block A_b, with its journal held, is the factor of the
  single-bearing stepper (:meth:`~foilbearing.reynolds.transient.TransientSystem.factorize`)
  with its journal's border left out; its solve is the compiled ``transient_solve``;
- the journals couple each film to the rotor through ``Y_b = A_b⁻¹ a_b`` (two columns: the
  film's response to its journal's ε);
- the rotor's Schur complement, m × m,
  ``S = K + c0² M + c0 Ω G + Σ_b B_bᵀ R W_b Y_b T_b``, with T_b the journal's ε from q,
  W_b the film force per unit P and R the map to ROSS's frame, is factorised densely.

A Newton iteration evaluates each film's BDF residual (the compiled
``transient_residual``, with the lift-off branches of the single-bearing stepper), the
rotor's, and solves: ``δq`` from S, ``δq̇ = c0 δq − g_q``, each film's
``δy_b = A_b⁻¹ g_b − Y_b T_b δq``. The iteration's convergence test, refreshes and
outcomes are the integrator's one Newton policy (:mod:`foilbearing.integrate.newton`),
which the single-bearing kernel
(:func:`~foilbearing.reynolds._kernels.transient_newton_solve`) calls too.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.errors import InputError
from foilbearing.integrate import (
    Problem,
    Solution,
    State,
    Status,
    integrate,
    interrupt_at_step_boundary,
)
from foilbearing.integrate import newton as policy
from foilbearing.orbit.result import RunStatus
from foilbearing.orbit.sampling import progress_bar
from foilbearing.orbit.settings import OrbitSettings
from foilbearing.orbit.stepper import LiftOffBranches, ending
from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds.transient import Inputs
from foilbearing.reynolds.transient_factor import TransientFactor
from foilbearing.rotor.nonlinear import RotorOrbit, RotorOrbitSystem

__all__ = ["RotorStepper", "run_rotor"]

FloatArray = NDArray[np.float64]

#: The BDF order of the rotor's runs and their steps a revolution (see RotorStepper).
ROTOR_ORDER = 2
ROTOR_STEPS_PER_REV = 48

_ROSS = np.array([[0.0, 1.0], [-1.0, 0.0]])  # ROSS (x, y) = (Y, −X) from ours (X, Y)

#: The integrator's Newton policy, in Python: this iteration is Python (a step couples
#: several films' compiled kernels), and calls no compiled dispatcher for a verdict.
_progress = policy.newton_progress.py_func
_verdict = policy.newton_verdict.py_func
_switch = policy.switch_verdict.py_func


class _RotorInputs:
    """The inputs at one instant: each bearing's, the rotor's speed and external force (N,
    on the reduced coordinates)."""

    __slots__ = ("bearings", "force", "omega")

    def __init__(self, bearings: list[Inputs], omega: float, force: FloatArray) -> None:
        self.bearings, self.omega, self.force = bearings, omega, force


class _Bearing:
    """One bearing's share of the stepper: its system, slices of the state and buffers."""

    def __init__(self, stepper: RotorStepper, b: int) -> None:
        orbit = stepper.system
        self.sim = orbit.sims[b]
        self.sys = self.sim.system
        self.n, self.nt = self.sys.n, self.sys.nt
        self.lo, self.hi = int(orbit.offsets[b]), int(orbit.offsets[b + 1])
        self.c = self.sim.case.bearing.clearance
        m = orbit.m
        # ε = T q (units of C); the film force on the rotor, ROSS's frame, N per unit P.
        self.T = np.zeros((2, m))
        self.T[0, 2 * b + 1] = -1.0 / self.c
        self.T[1, 2 * b] = 1.0 / self.c
        self.force = _ROSS @ orbit.force_per_pressure[b]  # (2, n)
        self.rows = slice(2 * b, 2 * b + 2)
        self.x = 2 * b  # the journal's x in q
        size = self.sys.size
        self.y = np.zeros(size)
        self.hist = np.zeros(size)
        self.g = np.empty(size)
        self.out = np.empty(size)
        self.q_out = np.empty(size)
        self.film = np.empty(self.sys.grid.shape)
        self.res = np.empty(self.sys.grid.shape)
        self.slack = np.zeros(self.n)
        self.work = np.empty((self.n, 1))

    def state(self, y: FloatArray, q: FloatArray, qd: FloatArray) -> FloatArray:
        """The single-bearing state [P, U, ε, v] of this bearing (ε = T q, v = T q̇)."""
        k = self.hi - self.lo
        ys, x, c = self.y, self.x, self.c
        ys[:k] = y[self.lo : self.hi]
        ys[k] = -q[x + 1] / c
        ys[k + 1] = q[x] / c
        ys[k + 2] = -qd[x + 1] / c
        ys[k + 3] = qd[x] / c
        return ys


class _RotorFactor:
    """A factorised Newton matrix of the rotor's step (module docstring) and its iteration."""

    def __init__(
        self,
        stepper: RotorStepper,
        y: FloatArray,
        inp: _RotorInputs,
        c0: float,
        hist: FloatArray,
        branches: FloatArray | None,
    ) -> None:
        self.st = stepper
        orbit = stepper.system
        red = orbit.reduced
        self.factors: list[TransientFactor] = []
        self.groups: list[tuple[Any, Any, Any]] = []
        self.cols: list[FloatArray] = []
        schur = red.stiffness + c0 * c0 * red.mass + c0 * inp.omega * red.gyroscopic
        q, qd = stepper.split_rotor(y)
        for b, br in enumerate(stepper.bearings):
            yb = br.state(y, q, qd)
            br.hist[: br.hi - br.lo] = hist[br.lo : br.hi]
            br.hist[br.hi - br.lo :] = 0.0
            branch = None if branches is None else branches[stepper.cells[b] : stepper.cells[b + 1]]
            fac = br.sys.factorize(yb, inp.bearings[b], c0, br.hist, branch)
            if fac.arrays.fac is None:
                raise ArithmeticError("a film's block factorisation fell back to SuperLU")
            arrays = fac.arrays._replace(s_vp=np.zeros_like(fac.arrays.s_vp))
            groups = (tuple(arrays), br.sys.kernel_groups[0], br.sys.kernel_groups[1])
            # Y_b: the film's response to its journal's ε, two columns: the pressures' is
            # the single-bearing factor's border times c0², the bumps' follows from it.
            col = np.empty((br.hi - br.lo, 2))
            col[: br.n] = arrays.y_border * (c0 * c0)
            mean = br.sys.grid.axial_mean(col[: br.n].reshape(br.nt, -1, 2))
            gain = arrays.rate * br.sys.c_bump * arrays.active / (c0 + arrays.rate)
            col[br.n :] = gain[:, None] * mean
            schur[br.rows, :] += (br.force @ col[: br.n]) @ br.T
            self.factors.append(fac)
            self.groups.append(groups)
            self.cols.append(col)
        self.schur_inv = np.linalg.inv(schur)
        self.c0, self.omega = c0, inp.omega
        self.damping = c0 * red.mass + inp.omega * red.gyroscopic  # of g_q in the Schur rhs
        self._lift = np.concatenate([f.lift_state for f in self.factors])

    @property
    def lift_state(self) -> FloatArray:
        """The bearings' lift-off branches, one after the other (the stepper moves them)."""
        return self._lift

    def _scatter_lift(self) -> None:
        for b, f in enumerate(self.factors):
            f.lift_state[:] = self._lift[self.st.cells[b] : self.st.cells[b + 1]]

    def _gather_lift(self) -> None:
        for b, f in enumerate(self.factors):
            self._lift[self.st.cells[b] : self.st.cells[b + 1]] = f.lift_state
            self.st.lift_slack[self.st.cells[b] : self.st.cells[b + 1]] = self.st.bearings[b].slack

    def _residual(
        self,
        y: FloatArray,
        inp: _RotorInputs,
        c0: float,
        hist: FloatArray,
        g: FloatArray,
        steps: list[tuple[Any, ...]],
    ) -> float:
        """G(y) into g; the minimum film. ``steps``: each bearing's step inputs."""
        st = self.st
        orbit = st.system
        red = orbit.reduced
        q, qd = st.split_rotor(y)
        force = inp.force.copy()
        h_min = math.inf
        for b, br in enumerate(st.bearings):
            yb = br.state(y, q, qd)
            h = kern.transient_residual(
                yb, steps[b], br.sys.kernel_groups[0], self.factors[b].lift_state,
                br.film, br.res, br.g, br.slack,
            )  # fmt: skip
            h_min = min(h_min, float(h))
            g[br.lo : br.hi] = br.g[: br.hi - br.lo]
            force[br.rows] += br.force @ (yb[: br.n] - 1.0)
        n_f, m = orbit.n_film, orbit.m
        g[n_f : n_f + m] = c0 * q + hist[n_f : n_f + m] - qd
        accel = orbit.mass_inv @ (force - red.stiffness @ q - inp.omega * red.gyroscopic @ qd)
        g[n_f + m :] = c0 * qd + hist[n_f + m :] - accel
        return h_min

    def _solve(self, g: FloatArray, dy: FloatArray) -> None:
        """dy with J dy = g (block elimination, module docstring)."""
        st = self.st
        orbit = st.system
        red = orbit.reduced
        n_f, m = orbit.n_film, orbit.m
        g_q, g_qd = g[n_f : n_f + m], g[n_f + m :]
        rhs = red.mass @ g_qd + self.damping @ g_q
        for b, br in enumerate(st.bearings):
            k = br.hi - br.lo
            br.g[:k] = g[br.lo : br.hi]
            br.g[k:] = 0.0
            fac, model, pattern = self.groups[b]
            kern.transient_solve(br.g, fac, model, pattern, br.work, br.out)
            dy[br.lo : br.hi] = br.out[:k]
            rhs[br.rows] += br.force @ br.out[: br.n]
        d_q = self.schur_inv @ rhs
        dy[n_f : n_f + m] = d_q
        dy[n_f + m :] = self.c0 * d_q - g_q
        for b, br in enumerate(st.bearings):
            e = (-d_q[br.x + 1] / br.c, d_q[br.x] / br.c)
            dy[br.lo : br.hi] -= self.cols[b] @ e

    def newton_solve(
        self,
        y: FloatArray,
        inp: _RotorInputs,
        c0: float,
        hist: FloatArray,
        weights: FloatArray,
        work: tuple[FloatArray, FloatArray, FloatArray],
        controls: tuple[float, float, int],
        fresh: bool,
        first_change: float,
    ) -> tuple[int, int, float, float]:
        """Modified-Newton iterations with this factor: the single-bearing kernel's loop
        (:func:`~foilbearing.reynolds._kernels.transient_newton_solve`) on the rotor's
        block elimination, under the integrator's one Newton policy
        (:mod:`foilbearing.integrate.newton`)."""
        newton_tol, newton_fraction, max_newton = controls
        g, dy, q_out = work
        st = self.st
        self._scatter_lift()
        steps = []
        for b, br in enumerate(st.bearings):
            br.hist[: br.hi - br.lo] = hist[br.lo : br.hi]
            br.hist[br.hi - br.lo :] = 0.0
            steps.append(tuple(br.sys.step_inputs(inp.bearings[b], c0, br.hist)))
        prev = math.inf
        k = since = switches = 0
        smoothed = any(br.sys.lift_delta > 0.0 for br in st.bearings)
        try:
            while True:
                k += 1
                since += 1
                h_min = self._residual(y, inp, c0, hist, g, steps)
                if not h_min > 0.0:
                    return kern.NEWTON_FILM_CLOSED, k, first_change, math.nan
                self._solve(g, dy)
                # y −= dy, the weighted max-norm of dy and each film's smallest pressure.
                err, p_min = 0.0, math.inf
                for lo, hi, n in st.segments:
                    e, p = kern.newton_update(y[lo:hi], dy[lo:hi], weights[lo:hi], n)
                    err, p_min = max(err, e) if e == e else math.nan, min(p_min, p)
                if not math.isfinite(err) or p_min <= 0.0:
                    return policy.NEWTON_NOT_FINITE, k, first_change, math.nan
                converged, conv, tol, first_change = _progress(
                    err, prev, since, first_change, newton_tol, newton_fraction
                )
                if converged:
                    flipped = sum(
                        kern.switch_branches(f.lift_state, br.slack, weights[br.lo : br.lo + br.n])
                        for f, br in zip(self.factors, st.bearings, strict=True)
                    )
                    verdict = _switch(flipped, switches, kern.MAX_SWITCHES, kern.MAX_MOVED_KEPT)
                    if verdict == policy.NEWTON_CONVERGED:
                        h_new = st.storage_into(y, inp, q_out)
                        if h_new > 0.0:
                            return policy.NEWTON_CONVERGED, k, first_change, h_new
                    elif verdict == policy.NEWTON_SWITCHED:
                        switches += 1
                        since = 0
                        prev = math.inf
                        continue
                    else:
                        return policy.NEWTON_REFRESH, k, first_change, math.nan
                verdict = _verdict(err, conv, tol, since, max_newton, fresh, switches > 0, smoothed)
                if verdict == policy.NEWTON_RETREAT:
                    y += dy  # the smoothed law's kink: back to the better iterate
                    return policy.NEWTON_REFRESH, k, first_change, math.nan
                if verdict != policy.NEWTON_CONTINUE:
                    return verdict, k, first_change, math.nan
                prev = err
        finally:
            self._gather_lift()


class RotorStepper:
    """The rotor on its bearings as the integrator's problem (module docstring).

    Parameters
    ----------
    system
        The rotor and its bearings (:class:`~foilbearing.rotor.nonlinear.RotorOrbitSystem`):
        its state, reduction, forces and start.
    settings
        Steps per revolution, tolerances and Newton controls (the bearings' orbit
        settings by default).
    """

    def __init__(self, system: RotorOrbitSystem, settings: OrbitSettings | None = None) -> None:
        self.system = system
        if settings is None:
            # BDF3 is not A-stable: a lightly damped mode of the shaft or of a journal on its
            # film, at kHz, whose hω falls in its unstable lobe grows (measured: the flexible
            # example at 37 krpm diverges at 48 steps a revolution). BDF2 is A-stable.
            settings = replace(
                system.sims[0].settings, order=ROTOR_ORDER, steps_per_rev=ROTOR_STEPS_PER_REV
            )
        self.settings = settings
        self.bearings = [_Bearing(self, b) for b in range(len(system.sims))]
        self.cells = np.concatenate([[0], np.cumsum([br.n for br in self.bearings])]).astype(int)
        self.lift_slack = np.zeros(int(self.cells[-1]))
        # (start, end, pressures at its start) of the state's pieces, for the update.
        self.segments = [(br.lo, br.hi, br.n) for br in self.bearings]
        self.segments.append((system.n_film, system.size, 0))
        self._atol = system.atol()
        self._times: list[float] = []
        self._q: list[FloatArray] = []
        self._last: FloatArray | None = None
        #: The bearings whose voltage program reads the run (a closed-loop controller).
        self._observers = [
            (b, sim.voltage)
            for b, sim in enumerate(system.sims)
            if sim.voltage is not None and sim.voltage.observes
        ]

    def split_rotor(self, y: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Views (q, q̇) of a state."""
        n_f, m = self.system.n_film, self.system.m
        return y[n_f : n_f + m], y[n_f + m :]

    def inputs(self, t: float) -> tuple[_RotorInputs, FloatArray]:
        """The inputs at t and the bearings' voltages (V, one after the other)."""
        volts = [sim.volts(t) for sim in self.system.sims]
        bearings = [
            sim.inputs(t, v, imbalance=False)
            for sim, v in zip(self.system.sims, volts, strict=True)
        ]
        force = self.system.gravity + self.system.unbalance_force(t)
        return _RotorInputs(bearings, self.system.speed.omega(t), force), np.concatenate(volts)

    def storage_into(self, y: FloatArray, inp: _RotorInputs, out: FloatArray) -> float:
        """Q(y) into ``out``; the minimum film."""
        q, qd = self.split_rotor(y)
        h_min = math.inf
        for b, br in enumerate(self.bearings):
            yb = br.state(y, q, qd)
            h = kern.transient_storage(
                yb, inp.bearings[b].preload, br.sys.kernel_groups[0], br.q_out
            )
            h_min = min(h_min, float(h))
            out[br.lo : br.hi] = br.q_out[: br.hi - br.lo]
        n_f = self.system.n_film
        out[n_f:] = y[n_f:]
        return h_min

    def storage(self, y: FloatArray, inp: _RotorInputs) -> FloatArray:
        out = np.empty(self.system.size)
        self.storage_into(y, inp, out)
        return out

    def factorize(
        self,
        y: FloatArray,
        inp: _RotorInputs,
        c0: float,
        hist: FloatArray,
        branches: FloatArray | None,
    ) -> _RotorFactor:
        return _RotorFactor(self, y, inp, c0, hist, branches)

    def record(
        self,
        t: float,
        y: FloatArray,
        inp: _RotorInputs,
        volts: FloatArray,
        min_film: float | None,
        order: int,
    ) -> None:
        """Keep the accepted state; hand each closed-loop program its journal's X (m) at
        the output's sample times since the last state (linear between the two)."""
        q = self.split_rotor(y)[0].copy()
        if self._observers and self._times:
            dt = 1.0 / self.settings.sample_rate
            t0, q0 = self._times[-1], self._q[-1]
            for k in range(math.floor(t0 / dt + 1e-9) + 1, math.floor(t / dt + 1e-9) + 1):
                ts = k * dt
                w = (ts - t0) / (t - t0)
                phase = self.system.speed.phase(ts)
                for b, program in self._observers:
                    x = self.bearings[b].x
                    e_x = -((1.0 - w) * q0[x + 1] + w * q[x + 1])  # X = −y in ROSS's frame
                    program.observe(ts, e_x, phase)
        self._times.append(t)
        self._q.append(q)
        self._last = y

    def make_result(self, sol: Solution, state: State, clock: float, t_end: float) -> RotorOrbit:
        """The run sampled at the settings' rate (linear between the accepted steps), from
        the integrator's ending ``sol`` at ``state``, with the wall time since ``clock``
        (``time.perf_counter()``) and ``t_end`` the end of the speed profile (s)."""
        if sol.status == Status.EVENT and self._last is not None:
            status, message = RunStatus.CONTACT, self._contact_message(state.t, self._last)
        else:
            status, message = ending(sol, state.t, t_end, self.system.speed.omega)
        steps = np.asarray(self._times)
        q = np.asarray(self._q).T  # (m, steps)
        dt = 1.0 / self.settings.sample_rate
        # on the run's sample grid k dt (a resumed part starts between two samples)
        first = math.ceil(steps[0] / dt - 1e-9) * dt
        times = np.arange(first, steps[-1] + 1e-12, dt)
        q = np.vstack([np.interp(times, steps, row) for row in q])
        orbit = self.system
        nb = len(orbit.sims)
        journals = np.stack([np.stack([-q[2 * b + 1], q[2 * b]]) for b in range(nb)])
        lateral = orbit.reduced.basis @ q
        nodes = np.stack([lateral[0::4], lateral[1::4]], axis=1)
        wall = time.perf_counter() - clock
        return RotorOrbit(
            times, journals, nodes, orbit.labels, wall, message,
            steps=sol.steps, factorizations=sol.factorizations,
            newton_iterations=sol.newton_iterations, status=str(status),
            speed=orbit.speed.speed_and_phase(times)[0],
            checkpoint={**state.as_checkpoint(), **self.program_checkpoint()},
        )  # fmt: skip

    def program_checkpoint(self) -> dict[str, Any]:
        """Each bearing's voltage program's state (a controller's latch), keys prefixed
        ``program<b>_``."""
        out: dict[str, Any] = {}
        for b, sim in enumerate(self.system.sims):
            if sim.voltage is not None:
                for key, value in sim.voltage.checkpoint().items():
                    out[f"program{b}_{key}"] = value
        return out

    def restore_programs(self, checkpoint: dict[str, Any]) -> None:
        """Give each bearing's program its state from a checkpoint."""
        for b, sim in enumerate(self.system.sims):
            prefix = f"program{b}_"
            if sim.voltage is not None:
                sim.voltage.restore(
                    {
                        k.removeprefix(prefix): v
                        for k, v in checkpoint.items()
                        if k.startswith(prefix)
                    }
                )

    def _contact_message(self, t: float, y: FloatArray) -> str:
        """Where the film closed: the bearing, its minimum film and the journal's angle
        from its +X (the stepper's own message reads a single bearing's state)."""
        q, qd = self.split_rotor(y)
        inp = self.inputs(t)[0]
        films = []
        for b, br in enumerate(self.bearings):
            yb = br.state(y, q, qd)
            films.append(br.sys.min_film(yb, inp.bearings[b].preload))
        b = int(np.argmin(films))
        br = self.bearings[b]
        eps = br.state(y, q, qd)[br.hi - br.lo : br.hi - br.lo + 2]
        angle = math.degrees(math.atan2(eps[1], eps[0]))
        rpm = self.system.speed.omega(t) * 30.0 / math.pi
        return (
            f"contact at t = {t:.4f} s, {rpm:.0f} rpm at {self.system.labels[b]}: minimum film "
            f"{films[b] * br.c * 1e6:.2f} µm, journal at {angle:.1f} deg from its +X"
        )

    def problem(self) -> Problem:
        """The rotor as the integrator sees it: its step from the speed, its inputs, storage
        and factor, and the films' lift-off branches."""
        omega = self.system.speed.omega
        rule = self.settings.step_rule
        steps_per_rev, max_step = rule.steps_per_rev, rule.max_step

        def step_size(t: float) -> float:
            return min(max_step, 2 * math.pi / (omega(t) * steps_per_rev))

        return Problem(
            size=self.system.size,
            step_size=step_size,
            inputs=self.inputs,
            storage=self.storage,
            factorize=self.factorize,
            atol=self._atol,
            switching=LiftOffBranches(self.lift_slack),
        )


def run_rotor(
    system: RotorOrbitSystem,
    t_end: float,
    *,
    y0: FloatArray | None = None,
    settings: OrbitSettings | None = None,
    progress: bool = False,
    stop_time: float | None = None,
    resume: RotorOrbit | None = None,
    checkpoint: Callable[[RotorOrbit], None] | None = None,
    checkpoint_every: float = 30.0,
) -> RotorOrbit:
    """Integrate the rotor on its bearings from t = 0 (the static state, or ``y0``) to
    ``t_end`` (s) on the BDF integrator (module docstring).

    ``stop_time`` (s) ends the run there, resumable. ``resume``: a stopped or interrupted
    run of the same system, continued from its checkpoint; the result holds both parts.
    ``checkpoint`` is called with the run so far every ``checkpoint_every`` seconds of wall
    time. Ctrl-C ends the run at a step boundary, keeping what it computed."""
    stepper = RotorStepper(system, settings)
    s = stepper.settings
    if resume is not None:
        if not resume.resumable or resume.checkpoint is None:
            raise InputError(f"the run already ended ({resume.message}): nothing to resume")
        state = State.from_checkpoint(resume.checkpoint)
        if state.y.shape != (system.size,):
            raise InputError(
                f"the checkpoint holds {state.y.size} states, this rotor {system.size}: resume "
                "with the rotor file and options the run started with"
            )
        stepper.restore_programs(resume.checkpoint)
    else:
        start = system.initial_state() if y0 is None else np.asarray(y0, float)
        state = State(0.0, start.copy())

    def joined(part: RotorOrbit) -> RotorOrbit:
        return part if resume is None else resume.joined(part)

    clock = time.perf_counter()
    contact_film = s.contact_film

    def contact(t: float, y: FloatArray, min_film: float) -> bool:
        return min_film < contact_film

    def save(sol: Solution) -> None:
        if checkpoint is not None:
            checkpoint(joined(stepper.make_result(sol, state, clock, t_end)))

    t1 = t_end if stop_time is None else min(stop_time, t_end)
    omega = system.speed.omega
    bar = progress_bar(progress, t1, state.t)
    try:
        with interrupt_at_step_boundary() as interrupted:
            sol = integrate(
                stepper.problem(),
                state,
                t1,
                s.order,
                s.newton_rule,
                stepper.record,
                events=(contact,),
                progress=None if bar is None else lambda t: bar(t, omega(t)),
                checkpoint=save if checkpoint is not None else None,
                checkpoint_every=checkpoint_every,
                interrupted=interrupted,
            )
    finally:
        if bar is not None:
            bar(None, None)
    return joined(stepper.make_result(sol, state, clock, t_end))
