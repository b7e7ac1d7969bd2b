"""Nonlinear orbit of the journal during a speed-up, with the actuator voltage changed on the run.

The semi-discrete system of :mod:`foilbearing.reynolds.transient` (film, foil,
journal; docs/model.md §5) is integrated by a variable-step BDF (order 3
by default, ``OrbitSettings.order``) in physical time with a modified Newton
iteration: the sparse Jacobian is factorised once and reused over many steps,
refreshed only when the Newton iteration slows down. The time step is a fixed
fraction of the rotation period (``steps_per_rev``), so it shrinks as the
rotor speeds up. The run starts from the static equilibrium without imbalance
at the initial speed and voltages (the paper's procedure), then applies the
imbalance; while the history is shorter than the order, the order is lower
and each missing past state halves the step. It stops cleanly at
contact (minimum film below ``contact_film`` × C), on Ctrl-C or at the end of
the speed profile, and keeps every sample computed until then.
"""

from __future__ import annotations

import math
import signal
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.control import SpeedProfile, SubsyncController, VoltageSchedule
from foilbearing.errors import InputError, SolverError
from foilbearing.film import film_model
from foilbearing.reynolds._kernels import MAX_MOVED_KEPT
from foilbearing.reynolds.transient import (
    NEWTON_CONVERGED,
    NEWTON_REFRESH,
    Inputs,
    TransientSystem,
    bdf_setup,
)
from foilbearing.static import drag_torque, solve_equilibrium
from foilbearing.structure import base_preload, preload_shape

__all__ = ["OrbitResult", "OrbitSettings", "OrbitSimulation", "simulate"]

FloatArray = NDArray[np.float64]
#: Simulated time between two evaluations of the film's power loss, s (it is
#: averaged over runs of seconds; 1 ms keeps its cost below 1 % of a step's).
POWER_INTERVAL = 1e-3


@dataclass(frozen=True)
class OrbitSettings:
    """Integrator and output settings (safe defaults).

    Attributes
    ----------
    steps_per_rev
        Time steps per rotor revolution (Δt = 2π/(ω · steps_per_rev)).
    order
        Order of the variable-step BDF (1-4). The default, 3 at 24 steps per
        revolution, keeps the orbit within 1 % of a converged run (0.8 % of the
        orbit's extent on the benchmark segment, see ``docs/orbit-performance.md``);
        BDF2 needs about 40 steps per revolution for the same. BDF3 is not
        A-stable (A(86°)), but its stability wedge holds the film's decaying
        modes, and the 1X and whirl motions (ωΔt <= 0.26) lie where it is
        accurate.
    max_step
        Largest time step, s.
    sample_rate
        Output sampling rate, Hz (uniform samples, linear interpolation between steps).
    contact_film
        The run stops when the minimum film falls below this fraction of C.
    newton_tol
        Convergence of the Newton update in the weighted max-norm (1 = tolerance met).
    rtol, atol_pressure, atol_position
        Relative and absolute tolerances of the weighted norm (P; ε and U in units of C).
    max_newton
        Newton iterations per attempt before the Jacobian is refreshed.
    newton_fraction
        The Newton iteration also stops when its update is below this fraction of
        the first update (the predictor's miss), which scales with the step's
        truncation error.

    The Newton defaults (``newton_tol = 0.3``, ``newton_fraction = 0.001``,
    ``max_newton = 10``) converge the iteration far below the step's truncation
    error: what a partly converged iteration leaves acts as a small forcing that
    seeds the whirl (correcting the last update for the measured contraction,
    Aitken-style, does not remove it). Measured on the default case with
    BDF2 at 16 steps per revolution (the defaults before issue 13) and the
    suction retained, the paper's speed-up, divergence speed in krpm, by
    ``newton_tol/newton_fraction``
    (1/0.01: the defaults before 2026-11-22; last column: the defaults at 24
    steps per revolution):

    ===================================  ========  ========  =========  ======  ======
    run                                  0.3/1e-3  0.1/1e-4  0.01/1e-5  1/0.01  24/rev
    ===================================  ========  ========  =========  ======  ======
    0 V, 8.5 g·mm                        24.23     24.34     24.38      24.26   24.35
    0 V, 1 g·mm                          19.83     20.09     20.21      19.36   19.73
    150 V ramp before the onset, 1 g·mm  35.19     35.09     35.09      35.09   35.24
    100 V ramp before the onset, 1 g·mm  32.66     32.66     32.64      32.65   32.71
    ===================================  ========  ========  =========  ======  ======

    The controlled runs do not depend on the iteration (0.3 %). The
    uncontrolled ones end when a whirl that grows through the whole run
    reaches the clearance, and that whirl starts from a seed that is partly
    numerical, so their divergence speed moves by up to 2 % with the
    tolerance (4 % with the old defaults, 5 % with 3/0.1: 23.25)
    (``tests/test_orbit.py::test_newton_tolerance_does_not_move_the_divergence``).
    The orbit error left at constant speed is below 1 % of the time-step error
    (``test_newton_error_is_well_below_the_time_step_error``).
    """

    steps_per_rev: int = 24
    order: int = 3
    max_step: float = 1e-3
    sample_rate: float = 10_000.0
    contact_film: float = 0.005
    newton_tol: float = 0.3
    rtol: float = 1e-4
    atol_pressure: float = 1e-5
    atol_position: float = 1e-5
    max_newton: int = 10
    newton_fraction: float = 0.001

    def check(self, max_speed: float) -> None:
        """Errors before any work for settings that cannot resolve the synchronous frequency."""
        f_sync = max_speed / (2 * math.pi)
        if self.steps_per_rev < 8:
            raise InputError(
                f"steps_per_rev = {self.steps_per_rev}: at least 8 resolve the 1X motion"
            )
        if self.order not in range(1, _MAX_ORDER + 1):
            raise InputError(
                f"order = {self.order!r}: the BDF stepper has orders 1 to {_MAX_ORDER} (default 3)"
            )
        if self.sample_rate < 4.0 * f_sync:
            raise InputError(
                f"sample_rate = {self.sample_rate:g} Hz cannot resolve the synchronous frequency "
                f"{f_sync:.0f} Hz at the top speed: use at least {4 * f_sync:.0f} Hz"
            )
        if not self.max_step > 0:
            raise InputError(f"max_step = {self.max_step!r} s: must be > 0")
        if not 0.0 < self.contact_film < 1.0:
            raise InputError(f"contact_film = {self.contact_film!r}: a fraction of C in (0, 1)")


@dataclass
class OrbitResult:
    """Time series of a run (SI), its settings and how it ended.

    Attributes
    ----------
    time, e_x, e_y, speed, phase, min_film
        Uniform samples (s, m, m, rad/s, rad, m).
    voltages
        Applied voltage per actuator, V, shape (n_samples, n_actuators).
    power_loss
        Viscous power loss of the film, W: the drag law of the static analysis
        (:func:`foilbearing.static.drag_torque`) × speed, evaluated on the
        accepted states every :data:`POWER_INTERVAL` s and interpolated to the
        samples (None for runs saved before it was recorded).
    status
        "completed" (end of the speed profile), "stopped" (at ``stop_time``),
        "contact", "interrupted" or "failed".
    message
        How the run ended (contact time, speed and angle; what failed).
    """

    case: Case
    settings: OrbitSettings
    time: FloatArray
    e_x: FloatArray
    e_y: FloatArray
    speed: FloatArray
    phase: FloatArray
    min_film: FloatArray
    voltages: FloatArray
    status: str
    message: str
    wall_time: float
    steps: int
    factorizations: int
    newton_iterations: int
    contact: dict[str, float] | None = None
    checkpoint: dict[str, Any] = field(default_factory=dict, repr=False)
    power_loss: FloatArray | None = None

    def to_dataset(self) -> Any:
        """The run as an xarray Dataset (time series, settings, status, checkpoint)."""
        import xarray as xr

        n_act = self.voltages.shape[1] if self.voltages.ndim == 2 else 0
        ds = xr.Dataset(
            {
                "e_x": ("time", self.e_x * 1e6, {"units": "um", "long_name": "journal X (load)"}),
                "e_y": ("time", self.e_y * 1e6, {"units": "um", "long_name": "journal Y"}),
                "speed": ("time", self.speed / RPM, {"units": "rpm"}),
                "phase": ("time", self.phase, {"units": "rad", "long_name": "rotation angle"}),
                "min_film": ("time", self.min_film * 1e6, {"units": "um"}),
                "voltage": (
                    ("time", "actuator"),
                    self.voltages.reshape(self.time.size, n_act),
                    {"units": "V"},
                ),
            },
            coords={"time": ("time", self.time, {"units": "s"})},
        )
        if self.power_loss is not None:
            ds["power_loss"] = (
                "time",
                self.power_loss,
                {"units": "W", "long_name": "viscous power loss of the film"},
            )
        s = self.settings
        ds.attrs.update(
            status=self.status,
            message=self.message,
            wall_time_s=self.wall_time,
            steps=self.steps,
            factorizations=self.factorizations,
            newton_iterations=self.newton_iterations,
            steps_per_rev=s.steps_per_rev,
            bdf_order=s.order,
            max_step_s=s.max_step,
            sample_rate_Hz=s.sample_rate,
            contact_film=s.contact_film,
            clearance_um=self.case.bearing.clearance * 1e6,
            case_title=self.case.title,
            imbalance_g_mm=self.case.rotor.imbalance * 1e6,
            rotor_mass_kg=self.case.rotor.mass,
        )
        if self.contact:
            for k, v in self.contact.items():
                ds.attrs[f"contact_{k}"] = v
        for k, v in self.checkpoint.items():
            ds[f"checkpoint_{k}"] = (f"checkpoint_{k}_dim", np.atleast_1d(np.asarray(v, float)))
        return ds


class OrbitSimulation:
    """One run: the system, the programs, the stepper state and the output buffers."""

    def __init__(
        self,
        case: Case,
        speed: SpeedProfile,
        voltage: VoltageSchedule | SubsyncController | None = None,
        settings: OrbitSettings | None = None,
    ) -> None:
        self.case, self.profile = case, speed
        self.settings = settings or OrbitSettings()
        self.settings.check(float(np.max(speed.speeds)))
        act = case.actuators
        self.n_act = 0 if act is None else len(act.angles)
        if voltage is not None:
            if act is None:
                raise InputError("a voltage program needs a case with [actuators]")
            voltage.check(act.max_voltage, self.n_act)
        self.voltage = voltage
        self.model = film_model(case)
        g = self.model.grid
        b, gas = case.bearing, case.gas
        c_total = self.model.compliance
        if case.foil is not None:
            c_bump = np.full(
                g.n_theta, gas.ambient_pressure / (b.clearance * case.foil.bump_stiffness)
            )
            gamma = case.foil.loss_factor
        else:
            c_bump, gamma = np.zeros(g.n_theta), 0.0
        self.system = TransientSystem(
            g,
            sigma=12.0 * gas.viscosity * b.radius**2 / (gas.ambient_pressure * b.clearance**2),
            c_act=np.maximum(c_total - c_bump, 0.0),
            c_bump=c_bump,
            loss_factor=gamma,
            film_force_scale=gas.ambient_pressure * b.radius**2 / (case.rotor.mass * b.clearance),
            lift_off=self.model.lift_off,
        )
        # Unit preload lobes per actuator (or shim), so r_p follows the voltages in time.
        if act is not None:
            self.lobes = np.array(
                [
                    preload_shape(g.theta, act.angles, np.eye(self.n_act)[n])
                    for n in range(self.n_act)
                ]
            )
        else:
            self.lobes = np.zeros((0, g.n_theta))
        self.static_preload = self.model.preload if act is None else None
        self._preload_cache: tuple[bytes, FloatArray] | None = None
        self._lambda_per_speed = case.bearing_number(1.0)  # Λ ∝ ω
        self._atol: FloatArray | None = None

    # ------------------------------------------------------------------ inputs
    def volts(self, t: float) -> FloatArray:
        """Actuator voltages at t (V)."""
        if self.case.actuators is None:
            return np.zeros(0)
        if self.voltage is None:
            return np.asarray(self.case.actuators.voltages, float)
        v = np.asarray(self.voltage(t), float)
        if v.shape == (self.n_act,):
            return v.copy()
        if v.shape == (1,):
            return np.full(self.n_act, v[0])
        return np.broadcast_to(v, (self.n_act,)).copy()

    def preload(self, volts: FloatArray) -> FloatArray:
        """r_p(θ_i)/C for actuator voltages (static shims if no actuators)."""
        if self.static_preload is not None:
            return self.static_preload
        # Voltages are held most of the run: reuse the last preload (never written to).
        key = np.asarray(volts, float).tobytes()
        cached = self._preload_cache
        if cached is not None and cached[0] == key:
            return cached[1]
        act = self.case.actuators
        assert act is not None
        delta = base_preload(
            volts,
            act.d33_quadratic,
            act.d33_linear,
            act.k_p,
            act.holder_spring_stiffness,
            act.holder_pre_extension,
        )
        r_p = (delta @ self.lobes) / self.case.bearing.clearance
        self._preload_cache = (key, r_p)
        return r_p

    def inputs(self, t: float, volts: FloatArray, imbalance: bool = True) -> Inputs:
        """Inputs of the system at time t."""
        w, wd, phi = self.profile.state(t)
        case = self.case
        c, m = case.bearing.clearance, case.rotor.mass
        u = case.rotor.imbalance_radius if imbalance else 0.0
        cos_phi, sin_phi = math.cos(phi), math.sin(phi)
        fx = case.operation.load / m + u * (w * w * cos_phi + wd * sin_phi)
        fy = u * (w * w * sin_phi - wd * cos_phi)
        force = np.array([fx / c, fy / c])
        return Inputs(self._lambda_per_speed * w, w, self.preload(volts), force)

    # ------------------------------------------------------------ start state
    def initial_state(self) -> FloatArray:
        """Static equilibrium without imbalance at the initial speed and voltages, as a state."""
        case = self.case
        if case.actuators is not None:
            case = case.with_voltages(tuple(float(v) for v in self.volts(0.0)))
        st = solve_equilibrium(case, speed=self.profile.omega(0.0), model=None)
        if not st.converged:
            raise SolverError(
                f"no static equilibrium at the start of the run: {st.message}; start the "
                "run at a higher speed or a lower load"
            )
        sys_ = self.system
        q = np.maximum(st.P.mean(axis=1) - 1.0, 0.0)
        u = sys_.c_bump * q if sys_.dynamic_bump else np.zeros(sys_.nt)
        return np.concatenate([st.P.ravel(), u, [st.eps_x, st.eps_y, 0.0, 0.0]])

    def atol(self) -> FloatArray:
        """Absolute tolerances of the state (P; U and ε in C; v in C/s)."""
        s, sys_ = self.settings, self.system
        atol = self._atol
        if atol is None:
            atol = np.empty(sys_.size)
            atol[: sys_.n] = s.atol_pressure
            atol[sys_.n : -2] = s.atol_position
            atol[-2:] = s.atol_position * max(self.profile.speeds.max(), 1.0)
            self._atol = atol
        return atol

    def weights(self, y: FloatArray) -> FloatArray:
        """Error weights 1/(atol + rtol |y|) of the Newton convergence test."""
        return 1.0 / (self.atol() + self.settings.rtol * np.abs(y))


@dataclass
class _State:
    """Everything needed to continue a run: the last accepted state and those before it."""

    t: float
    y: FloatArray
    #: (step that led to the newer state, state) for the earlier accepted states, newest first.
    past: list[tuple[float, FloatArray]] = field(default_factory=list)

    def as_checkpoint(self) -> dict[str, Any]:
        out: dict[str, Any] = {"t": self.t, "y": self.y}
        for k, (h, y) in enumerate(self.past):
            suffix = "" if k == 0 else str(k + 1)
            out[f"y_prev{suffix}"], out[f"h_prev{suffix}"] = y, h
        return out

    @classmethod
    def from_checkpoint(cls, data: dict[str, Any]) -> _State:
        def scalar(key: str) -> float:
            return float(np.ravel(data[key])[0])

        past = []
        for k in range(_MAX_ORDER):
            suffix = "" if k == 0 else str(k + 1)
            if f"y_prev{suffix}" not in data:
                break
            past.append((scalar(f"h_prev{suffix}"), np.asarray(data[f"y_prev{suffix}"], float)))
        return cls(scalar("t"), np.asarray(data["y"], float), past)


def simulate(
    case: Case,
    speed: SpeedProfile,
    voltage: VoltageSchedule | SubsyncController | None = None,
    settings: OrbitSettings | None = None,
    *,
    progress: bool | Callable[[float, float], None] = False,
    stop_time: float | None = None,
    resume: OrbitResult | None = None,
    checkpoint: Callable[[OrbitResult], None] | None = None,
    checkpoint_every: float = 30.0,
) -> OrbitResult:
    """Integrate the orbit over the speed profile.

    Parameters
    ----------
    case
        Bearing case (rotor mass and imbalance from ``[rotor]``, load from ``[operation]``).
    speed
        Speed profile ω(t).
    voltage
        Open-loop schedule, closed-loop controller, or None (the case's voltages held).
    settings
        Integrator and output settings.
    progress
        True for a tqdm bar (simulated time, speed, time left); or a callable
        ``f(t, speed)`` called after every step.
    stop_time
        End the run at this simulated time (default: the end of the profile).
    resume
        A stopped run to continue from its checkpoint (same case and programs).
    checkpoint
        Called with the partial result every ``checkpoint_every`` seconds of
        wall time (e.g. to save it), so a crash loses little.
    """
    sim = OrbitSimulation(case, speed, voltage, settings)
    if resume is not None:
        if not resume.checkpoint:
            raise InputError("the run to resume has no checkpoint")
        state = _State.from_checkpoint(resume.checkpoint)
        if isinstance(voltage, SubsyncController) and "triggered_at" in resume.checkpoint:
            trig = float(np.ravel(resume.checkpoint["triggered_at"])[0])
            voltage.triggered_at = None if math.isnan(trig) else trig
        samples = _Samples.from_result(resume)
    else:
        state = _State(0.0, sim.initial_state())
        samples = _Samples(1.0 / sim.settings.sample_rate)
    with _interrupt_at_step_boundary() as interrupted:
        return _run(
            sim, state, samples, progress, stop_time, checkpoint, checkpoint_every, interrupted
        )


@contextmanager
def _interrupt_at_step_boundary() -> Iterator[Callable[[], bool]]:
    """Hold Ctrl-C until the step under way is committed; yields ``interrupted()``.

    A KeyboardInterrupt raised at an arbitrary line of a step (between the shift of
    the BDF history and the update of the current time, say) leaves a checkpoint
    whose state, time and history disagree, and the resumed run then departs from
    the uninterrupted one. In the main thread with Python's default handler, SIGINT
    only sets a flag that the stepper reads before each step; elsewhere (a worker
    thread, which never receives SIGINT, or a program with its own handler)
    nothing changes.
    """
    requested = [False]
    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    ):
        yield lambda: requested[0]
        return

    def hold(signum: int, frame: object) -> None:
        requested[0] = True

    signal.signal(signal.SIGINT, hold)
    try:
        yield lambda: requested[0]
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)


def _run(
    sim: OrbitSimulation,
    st: _State,
    out: _Samples,
    progress: bool | Callable[[float, float], None],
    stop_time: float | None,
    checkpoint: Callable[[OrbitResult], None] | None,
    checkpoint_every: float,
    interrupted: Callable[[], bool] = lambda: False,
) -> OrbitResult:
    s, sys_ = sim.settings, sim.system
    t_end = sim.profile.duration if stop_time is None else min(stop_time, sim.profile.duration)
    clock = time.perf_counter()
    last_checkpoint = clock
    bar = _progress_bar(progress, t_end, st.t)
    volts = sim.volts(st.t)
    inp = sim.inputs(st.t, volts)
    # Accepted states, newest first: times, states y and storages Q (the BDF history).
    depth = s.order + 1
    times, ys, qs = np.empty(depth), np.empty((depth, sys_.size)), np.empty((depth, sys_.size))
    count = 1 + min(len(st.past), s.order)
    times[0], ys[0] = st.t, st.y
    for j, (h_j, y_j) in enumerate(st.past[: count - 1]):
        times[j + 1], ys[j + 1] = times[j] - h_j, y_j
    for j in range(count):
        qs[j] = sys_.storage(ys[j], sim.inputs(times[j], sim.volts(float(times[j]))))
    out.add(st.t, st.y, sim, volts, inp)
    lu, lu_c0 = None, math.nan
    work = (np.empty(sys_.size), np.empty(sys_.size))  # Newton residual and update buffers
    guess, hist, weights = np.empty(sys_.size), np.empty(sys_.size), np.empty(sys_.size)
    atol = sim.atol()
    counters = [0, 0, 0]  # steps, factorizations, Newton iterations
    # Lift-off boundary coordinate at the last three accepted steps (None: unknown).
    lift_s: list[FloatArray | None] = [None, None, None]
    status, message, contact = "completed", "", None

    def result(status: str, message: str) -> OrbitResult:
        st.past = [(float(times[j] - times[j + 1]), ys[j + 1].copy()) for j in range(count - 1)]
        cp = st.as_checkpoint()
        if isinstance(sim.voltage, SubsyncController):
            trig = sim.voltage.triggered_at
            cp["triggered_at"] = math.nan if trig is None else trig
        t_s, e_x, e_y, speed, phase, h_min, volts_s, power = out.arrays(sim.n_act, sim.profile)
        return OrbitResult(
            sim.case,
            s,
            t_s,
            e_x,
            e_y,
            speed,
            phase,
            h_min,
            volts_s,
            power_loss=power,
            status=status,
            message=message,
            wall_time=time.perf_counter() - clock,
            steps=counters[0],
            factorizations=counters[1],
            newton_iterations=counters[2],
            contact=contact,
            checkpoint=cp,
        )

    try:
        while st.t < t_end - 1e-12:
            if interrupted():
                raise KeyboardInterrupt  # held by _interrupt_at_step_boundary
            t = st.t
            omega = sim.profile.state(t)[0]
            h = h_nominal = min(s.max_step, 2 * math.pi / (omega * s.steps_per_rev))
            if t_end - t < 2.0 * h:
                # Land on t_end in one step up to h, else in two equal ones: never longer
                # than the cap, and no sliver of a step, whose ratio to the next (after a
                # resume) would upset the BDF.
                h = t_end - t if t_end - t <= h else 0.5 * (t_end - t)
            if count <= s.order:
                # Start-up: the order rises with the history, and each missing past
                # state halves the step, so that the low-order first steps stay
                # below the error of the full-order ones.
                h *= 2.0 ** (count - 1 - s.order)
            while True:
                t_new = t + h
                volts = sim.volts(t_new)
                inp = sim.inputs(t_new, volts)
                c0 = bdf_setup(
                    t_new, times, ys, qs, count, s.order, atol, s.rtol, guess, hist, weights
                )
                branches = _predicted_branches(
                    lift_s[0], lift_s[1], lift_s[2], h,
                    t - times[1] if count > 1 else None,
                    times[1] - times[2] if count > 2 else None,
                )  # fmt: skip
                ok, y_new, its, lu, lu_c0, nf, q_new, h_min = _step_newton(
                    sim, guess, inp, c0, hist, weights, lu, lu_c0, work, branches
                )
                counters[2] += its
                counters[1] += nf
                if ok:
                    break
                h *= 0.5
                if count > 1 and h < 0.3 * h_nominal:
                    # Failed twice: restart the order from this state (BDF1, then the
                    # start-up), as a history that the film can no longer follow, e.g.
                    # across a lift-off switch near contact, can stall the iteration.
                    count = 1
                if h < 1e-9:
                    raise FloatingPointError(f"time step collapsed at t = {t:.6f} s")
            counters[0] += 1
            lift_s = [_lift_coordinate(lu, sys_._slack), lift_s[0], lift_s[1]]
            # Shift the history by one (rows are reused: no allocation).
            times[1:], ys[1:], qs[1:] = times[:-1], ys[:-1], qs[:-1]
            times[0], ys[0], qs[0] = t_new, y_new, q_new
            count = min(count + 1, depth)
            st.t, st.y = t_new, ys[0].copy()
            out.add(t_new, y_new, sim, volts, inp, min_film=h_min)
            if isinstance(sim.voltage, SubsyncController):
                for t_s, ex in out.new_samples():
                    sim.voltage.observe(t_s, ex, sim.profile.phase(t_s))
            if h_min < s.contact_film:
                w = sim.profile.omega(t_new)
                k = sys_.n + sys_.nt
                contact = {
                    "time_s": t_new,
                    "speed_rpm": w / RPM,
                    "angle_deg": math.degrees(math.atan2(y_new[k + 1], y_new[k])),
                    "min_film_um": h_min * sim.case.bearing.clearance * 1e6,
                }
                status = "contact"
                message = (
                    f"contact at t = {t_new:.4f} s, {w / RPM:.0f} rpm: minimum film "
                    f"{h_min:.3f} C < {s.contact_film} C, journal at "
                    f"{contact['angle_deg']:.1f} deg from +X"
                )
                break
            if bar is not None:
                bar(t_new, sim.profile.omega(t_new))
            if checkpoint is not None and time.perf_counter() - last_checkpoint > checkpoint_every:
                checkpoint(result("running", f"checkpoint at t = {t_new:.4f} s"))
                last_checkpoint = time.perf_counter()
    except KeyboardInterrupt:
        status, message = "interrupted", f"interrupted by the user at t = {st.t:.4f} s"
    except ArithmeticError as exc:  # a numerical failure (step collapse, singular factor)
        status, message = "failed", f"the integration failed at t = {st.t:.4f} s: {exc}"
    finally:
        if bar is not None:
            bar(None, None)
    if status == "completed":
        if st.t < sim.profile.duration - 1e-9:
            status = "stopped"  # at stop_time: the profile goes on, the run can be resumed
        message = (
            f"{status} at {st.t:.4f} s ({sim.profile.omega(st.t) / RPM:.0f} rpm) after "
            f"{counters[0]} steps"
        )
    return result(status, message)


#: Highest BDF order of the stepper.
_MAX_ORDER = 4


#: Factor refreshes at the iterate within one step before the step is retried or halved.
_MAX_REFRESH = 3


def _step_newton(
    sim: OrbitSimulation,
    y0: FloatArray,
    inp: Inputs,
    c0: float,
    hist: FloatArray,
    weights: FloatArray,
    lu: Any,
    lu_c0: float,
    work: tuple[FloatArray, FloatArray],
    branches: FloatArray | None = None,
) -> tuple[bool, FloatArray, int, Any, float, int, FloatArray, float]:
    """Modified Newton on c0·Q(y) + hist − f(y) = 0 from the guess y0, reusing the factor.

    The iterations with one factor are compiled
    (:meth:`~foilbearing.reynolds.transient.TransientFactor.newton_solve`). A
    factor that converges too slowly (stale, or fresh but contracting at a
    rate above 0.5) is refreshed at the current iterate and the iteration
    goes on from there, up to ``_MAX_REFRESH`` times a step; a fresh factor
    that fails (or a stale one whose iterate closes the film) restarts from
    the guess with a fresh factor, then gives up (the caller halves the step). The
    iteration stops at a fraction of the step's own change (predictor to
    corrector), as BDF codes do: the Newton error then stays well below the
    truncation error of the step. ``work`` holds two state-sized buffers
    (residual, update) reused across iterations. ``branches`` are the
    predicted lift-off branches of the step (:func:`_predicted_branches`): a
    kept factor takes them when few cells move, a new factor is taken with
    them otherwise. Returns ``(converged, y,
    iterations, factor, factor_c0, factorisations, Q(y), min film)``; on
    failure y is the guess and Q is empty.
    """
    s, sys_ = sim.settings, sim.system
    controls = (s.newton_tol, s.newton_fraction, s.max_newton)
    q_new = np.empty(sys_.size)
    buffers = (work[0], work[1], q_new)
    factorizations = 0
    its = 0
    refreshes = 0
    for attempt in range(2):
        y = y0.copy()
        fresh = lu is None or attempt == 1 or abs(c0 - lu_c0) > 0.2 * c0
        if not fresh and branches is not None and lu is not None:
            moved = np.count_nonzero((lu.lift_state > 0.0) != (branches > 0.0))
            if moved > MAX_MOVED_KEPT:
                fresh = True  # the factor's held cells are too far from this step's
            elif moved:
                lu.lift_state[:] = np.where(branches > 0.0, 1.0, -1.0) * np.abs(lu.lift_state)
        if fresh:
            # Lift-off branches: those predicted for the step, or decided afresh at
            # the guess when the step starts over.
            lu = sys_.factorize(y, inp, c0, hist, branches if attempt == 0 else None)
            lu_c0 = c0
            factorizations += 1
        first_change = math.inf
        while True:
            outcome, k, first_change, h_new = lu.newton_solve(
                y, inp, c0, hist, weights, buffers, controls, fresh, first_change
            )
            its += k
            if outcome == NEWTON_CONVERGED:
                return True, y, its, lu, lu_c0, factorizations, q_new, h_new
            if outcome != NEWTON_REFRESH or refreshes >= _MAX_REFRESH:
                break  # closed film, NaN, too slow or diverging: restart fresh, or give up
            refreshes += 1
            # A factor that will not converge in time: refresh it here (with the
            # lift-off branches the iteration has reached), go on from y.
            lu = sys_.factorize(y, inp, c0, hist, lu.lift_state)
            lu_c0 = c0
            factorizations += 1
            fresh = True
        if fresh:
            break
    return False, y0, its, None, math.nan, factorizations, np.empty(0), math.nan


def _lift_coordinate(lu: Any, slack: FloatArray) -> FloatArray | None:
    """The signed distance of each cell from the lift-off boundary at a converged step.

    ``P − 1 − G/d``: ``P − 1 >= 0`` on a free cell, ``−G/d <= 0`` on a held one
    (the slack of the residual kernel, sign-corrected); it moves smoothly as
    the boundary moves, so its extrapolation predicts the next step's branches.
    None without lift-off.
    """
    if lu is None or not np.any(lu.lift_state):
        return None
    return np.where(lu.lift_state > 0.0, slack, -slack)


def _predicted_branches(
    s0: FloatArray | None,
    s1: FloatArray | None,
    s2: FloatArray | None,
    h: float,
    h1: float | None,
    h2: float | None,
) -> FloatArray | None:
    """Lift-off branches predicted for a step of h: +1 held, −1 free (None: no history).

    Extrapolates the boundary coordinate of the last accepted steps (t_n, t_n − h1,
    t_n − h1 − h2) to t_n + h with the predictor's Lagrange weights.
    """
    if s0 is None:
        return None
    if s1 is None or h1 is None:
        pred = s0
    elif s2 is None or h2 is None:
        pred = s0 + (h / h1) * (s0 - s1)
    else:
        t1, t2 = -h1, -h1 - h2
        l0 = (h - t1) * (h - t2) / (t1 * t2)
        l1 = h * (h - t2) / (t1 * (t1 - t2))
        l2 = h * (h - t1) / (t2 * (t2 - t1))
        pred = l0 * s0 + l1 * s1 + l2 * s2
    return np.where(pred < 0.0, 1.0, -1.0)


class _Samples:
    """Uniformly sampled output, by linear interpolation between accepted steps.

    The accepted states are recorded (time, journal position, minimum film,
    voltages); the uniform samples are interpolated from them at once when the
    result is made (vectorised), and one step at a time only for a controller
    that watches the signal as it comes (:meth:`new_samples`). A sample takes
    the minimum film and voltages of the first step at or after it.
    """

    def __init__(self, dt: float) -> None:
        self.dt = dt
        self.start = 0.0  # time of the first sample to come from the recorded steps
        self.next = 0.0  # next sample for new_samples()
        self.done: tuple[FloatArray, ...] | None = None  # samples of the run resumed
        self.t: list[float] = []
        self.ex: list[float] = []
        self.ey: list[float] = []
        self.h_min: list[float] = []
        self.volts: list[FloatArray] = []
        self.power_t: list[float] = []  # times of the power-loss evaluations, s
        self.power: list[float] = []  # W
        self.next_power = 0.0

    def add(
        self,
        t: float,
        y: FloatArray,
        sim: OrbitSimulation,
        volts: FloatArray,
        inp: Inputs,
        min_film: float | None = None,
    ) -> None:
        """Record the accepted state y at t; ``min_film`` (h/C of y) if known."""
        sys_ = sim.system
        c = sim.case.bearing.clearance
        k = sys_.n + sys_.nt
        if min_film is None:
            min_film = sys_.min_film(y, inp.preload)
        self.t.append(t)
        self.ex.append(float(y[k]) * c)
        self.ey.append(float(y[k + 1]) * c)
        self.h_min.append(min_film * c)
        self.volts.append(volts)
        if t >= self.next_power:
            w = sim.profile.state(t)[0]
            P = sys_.split(y)[0]
            H = sys_.film(y, inp.preload)[0]
            self.power_t.append(t)
            self.power.append(drag_torque(sim.case, sys_.grid, P, H, w) * w)
            self.next_power = t + POWER_INTERVAL

    @classmethod
    def from_result(cls, res: OrbitResult) -> _Samples:
        """Continue the samples of a stopped run."""
        out = cls(1.0 / res.settings.sample_rate)
        out.done = (
            res.time,
            res.e_x,
            res.e_y,
            res.speed,
            res.phase,
            res.min_film,
            np.asarray(res.voltages, float),
            np.full(res.time.size, np.nan) if res.power_loss is None else res.power_loss,
        )
        out.start = float(res.time[-1]) + out.dt if res.time.size else 0.0
        out.next = out.next_power = out.start
        return out

    def new_samples(self) -> list[tuple[float, float]]:
        """(time, e_X) of the samples between the last two recorded steps (for a controller)."""
        fresh: list[tuple[float, float]] = []
        t1, x1 = self.t[-1], self.ex[-1]
        t0, x0 = (self.t[-2], self.ex[-2]) if len(self.t) > 1 else (t1, x1)
        while self.next <= t1 + 1e-12:
            ts = self.next
            w = (ts - t0) / (t1 - t0) if t1 > t0 else 1.0
            fresh.append((ts, (1 - w) * x0 + w * x1))
            self.next = ts + self.dt
        return fresh

    def arrays(self, n_act: int, profile: SpeedProfile) -> tuple[FloatArray, ...]:
        """Samples (time, e_x, e_y, speed, phase, min_film, voltages, power_loss), SI.

        A run interrupted (Ctrl-C) inside :meth:`add` leaves the last step recorded in
        some lists only: the step is dropped from all of them.
        """
        n = min(len(self.t), len(self.ex), len(self.ey), len(self.h_min), len(self.volts))
        del self.t[n:], self.ex[n:], self.ey[n:], self.h_min[n:], self.volts[n:]
        m = min(len(self.power_t), len(self.power))
        del self.power_t[m:], self.power[m:]
        t = np.asarray(self.t, dtype=float)
        if t.size and t[-1] + 1e-12 >= self.start:
            count = math.floor((t[-1] + 1e-12 - self.start) / self.dt) + 1
        else:
            count = 0
        ts: FloatArray = self.start + self.dt * np.arange(count, dtype=np.float64)
        ex = np.interp(ts, t, np.asarray(self.ex)) if count else np.empty(0)
        ey = np.interp(ts, t, np.asarray(self.ey)) if count else np.empty(0)
        at = np.searchsorted(t, ts - 1e-12, side="left")
        h_min = np.asarray(self.h_min, dtype=float)[at] if count else np.empty(0)
        volts = (
            np.asarray(self.volts, dtype=float).reshape(len(self.volts), n_act)[at]
            if n_act
            else np.zeros((count, 0))
        )
        speed, phase = profile.speed_and_phase(ts)
        power = np.interp(ts, self.power_t, self.power) if self.power_t else np.full(count, np.nan)
        new = (ts, ex, ey, speed, phase, h_min, volts, power)
        if self.done is None:
            return new
        return tuple(
            np.concatenate([old, fresh]) for old, fresh in zip(self.done, new, strict=True)
        )


def _progress_bar(
    progress: bool | Callable[[float, float], None], t_end: float, t_start: float = 0.0
) -> Callable[[float | None, float | None], None] | None:
    if progress is False:
        return None
    if callable(progress):
        cb = progress

        def call(t: float | None, w: float | None) -> None:
            if t is not None and w is not None:
                cb(t, w)

        return call
    from tqdm import tqdm

    bar = tqdm(
        total=t_end,
        unit="s",
        unit_scale=False,
        desc="orbit",
        dynamic_ncols=True,
        bar_format="{l_bar}{bar}| {n:.3f}/{total:.3f} s simulated [{elapsed}<{remaining}{postfix}]",
    )
    last = [t_start]

    def update(t: float | None, w: float | None) -> None:
        if t is None:
            bar.close()
            return
        if t - last[0] >= 0.002 * t_end:
            bar.update(t - last[0])
            last[0] = t
            bar.set_postfix_str(f"{(w or 0.0) / RPM:,.0f} rpm")

    return update
