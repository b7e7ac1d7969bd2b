"""Assembly of the orbit's semi-discrete system: the case, the programs, the preload and the inputs.

The film, foil and journal of :mod:`foilbearing.reynolds.transient`
(docs/model.md §5) under the speed profile and the voltage program of a run:
the preload lobes at the present voltages, the imbalance and load inputs at a
time, the initial static equilibrium and the error weights.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.bearing_system.verbs import BearingSystem
from foilbearing.case import Case
from foilbearing.control import SpeedProfile, VoltageProgram
from foilbearing.errors import InputError, SolverError
from foilbearing.orbit.disturbance import DisturbanceForce
from foilbearing.orbit.held import HeldStingers
from foilbearing.orbit.problem import RunStats, StepperProblem
from foilbearing.orbit.result import OrbitResult, RunStatus
from foilbearing.orbit.sampling import Samples
from foilbearing.orbit.settings import OrbitSettings
from foilbearing.reynolds.transient import (
    Inputs,
    TransientSystem,
)
from foilbearing.structure import base_preload, preload_shape

__all__ = ["OrbitSimulation"]

FloatArray = NDArray[np.float64]


class OrbitSimulation:
    """One run: the system, the programs, the stepper state and the output buffers.

    The run is on the orbit's grid (:meth:`~foilbearing.case.Case.orbit_case`): ``case``
    is the case on that grid, and so is the case of its result.
    """

    def __init__(
        self,
        case: Case,
        speed: SpeedProfile,
        voltage: VoltageProgram | None = None,
        settings: OrbitSettings | None = None,
    ) -> None:
        # The orbit's own grid ([grid] orbit_n_theta, orbit_n_z), checked before any work.
        case = case.orbit_case()
        self.case, self.profile = case, speed
        self.settings = settings or OrbitSettings()
        case.check_speeds(speed.speeds, "speed profile")
        self.settings.check(float(np.max(speed.speeds)))
        act = case.actuators
        self.n_act = 0 if act is None else len(act.angles)
        if voltage is not None:
            if act is None:
                raise InputError("a voltage program needs a case with [actuators]")
            voltage.check(act.max_voltage, self.n_act)
        held = act is not None and act.reading.held
        if held and voltage is not None and voltage.observes:
            raise InputError(
                "actuators.dynamics = 'held' with a closed-loop controller: the held stingers "
                "follow the equilibrium of voltages known ahead of time; use a voltage ramp "
                "or schedule, or dynamics = 'compliant'",
                source=case.source,
            )
        self.voltage = voltage
        #: The bearing as one system (scales, film model); the run steps its transient verb.
        self.bearing = BearingSystem.from_case(case)
        self.model = self.bearing.film
        g = self.model.grid
        self.system: TransientSystem = self.bearing.transient()
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
        self._lambda_per_speed = self.bearing.scales.lambda_per_speed  # Λ ∝ ω
        # The case's voltages, held where no program sets them: one read-only array a run.
        self._fixed_volts = np.array(case.actuators.voltages if case.actuators else (), float)
        self._fixed_volts.flags.writeable = False
        self.held = HeldStingers(case, speed.omega, self.volts, speed.duration) if held else None
        d = case.disturbance
        self.disturbance = None if d is None or d.force_rms == 0.0 else DisturbanceForce(d)
        self._atol: FloatArray | None = None

    # ------------------------------------------------------------------ inputs
    def volts(self, t: float) -> FloatArray:
        """Actuator voltages at t (V)."""
        if self.case.actuators is None:
            return np.zeros(0)
        if self.voltage is None:
            return self._fixed_volts
        v = np.asarray(self.voltage(t), float)
        if v.shape == (self.n_act,):
            return v.copy()
        return np.broadcast_to(v, (self.n_act,)).copy()  # one voltage for every actuator

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

    def preload_at(self, t: float, volts: FloatArray) -> FloatArray:
        """The rigid film's preload r_p/C at time t: the lobes at ``volts``, less the held
        stacks' quasi-static compression under ``dynamics = "held"``."""
        r_p = self.preload(volts)
        return r_p if self.held is None else r_p - self.held(t)

    def inputs(self, t: float, volts: FloatArray, imbalance: bool = True) -> Inputs:
        """Inputs of the system at time t: the load, and the imbalance and disturbance forces
        (``imbalance=False``: the load only)."""
        w, wd, phi = self.profile.state(t)
        case = self.case
        c, m = case.bearing.clearance, case.rotor.mass
        u = case.rotor.imbalance_radius if imbalance else 0.0
        cos_phi, sin_phi = math.cos(phi), math.sin(phi)
        fx = case.operation.load / m + u * (w * w * cos_phi + wd * sin_phi)
        fy = u * (w * w * sin_phi - wd * cos_phi)
        if imbalance and self.disturbance is not None:
            dx, dy = self.disturbance.components(t)
            force = np.array([fx / c + dx / (m * c), fy / c + dy / (m * c)])
        else:
            force = np.array([fx / c, fy / c])
        return Inputs(self._lambda_per_speed * w, w, self.preload_at(t, volts), force)

    # ------------------------------------------------------------ start state
    def initial_state(self) -> FloatArray:
        """Static equilibrium without imbalance at the initial speed and voltages, as a state."""
        volts = None
        if self.case.actuators is not None:
            volts = tuple(float(v) for v in self.volts(0.0))
        st = self.bearing.equilibrium(self.profile.omega(0.0), voltages=volts)
        if not st.converged:
            raise SolverError(
                f"no static equilibrium at the start of the run: {st.message}; start the "
                "run at a higher speed or a lower load"
            )
        sys_ = self.system
        q = np.maximum(sys_.grid.gauge_mean(st.P), 0.0)
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

    # ---------------------------------------------------------------- stepper
    def problem(self) -> StepperProblem:
        """The run as the stepper sees it: callables and arrays (:mod:`~foilbearing.orbit.problem`)."""
        sys_, profile, voltage = self.system, self.profile, self.voltage

        def inputs(t: float) -> tuple[Inputs, FloatArray]:
            volts = self.volts(float(t))
            return self.inputs(t, volts), volts

        def record(
            out: Samples,
            t: float,
            y: FloatArray,
            volts: FloatArray,
            inp: Inputs,
            min_film: float | None,
        ) -> None:
            out.add(t, y, sys_, self.case, volts, inp, min_film=min_film)

        observe = None
        if voltage is not None and voltage.observes:
            program = voltage

            def observe(t: float, e_x: float) -> None:
                program.observe(t, e_x, profile.phase(t))

        def program_checkpoint() -> dict[str, Any]:
            return {} if voltage is None else dict(voltage.checkpoint())

        def make_result(
            out: Samples, status: RunStatus, message: str, stats: RunStats
        ) -> OrbitResult:
            t_s, e_x, e_y, speed, phase, h_min, volts_s, power = out.arrays(self.n_act, profile)
            return OrbitResult(
                self.case,
                self.settings,
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
                wall_time=time.perf_counter() - stats.clock,
                steps=stats.steps,
                factorizations=stats.factorizations,
                newton_iterations=stats.newton_iterations,
                contact=stats.contact,
                checkpoint={**stats.checkpoint, **out.checkpoint()},
            )

        return StepperProblem(
            size=sys_.size,
            t_end=profile.duration,
            speed=profile.omega,
            inputs=inputs,
            storage=sys_.storage,
            factorize=sys_.factorize,
            lift_slack=sys_._slack,
            atol=self.atol(),
            journal=sys_.n + sys_.nt,
            clearance=self.case.bearing.clearance,
            record=record,
            observe=observe,
            program_checkpoint=program_checkpoint,
            make_result=make_result,
        )
