"""What the orbit's stepper integrates: callables and arrays, no case, programs or settings.

:class:`StepperProblem` is the interface between the domain side of a run
(:class:`~foilbearing.orbit.system.OrbitSimulation`: the case, the speed profile,
the voltage program, the output) and the numerics of
:func:`foilbearing.orbit.stepper.run` (the orbit on the generic BDF integrator,
:mod:`foilbearing.integrate`, and its modified Newton), as ``diffrax.diffeqsolve`` takes ``f(t, y, args)``: the stepper calls
these and reads nothing else. Its settings come apart from it, by role
(:mod:`foilbearing.orbit.settings`: ``StepRule``, ``NewtonRule``, ``StopRule``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from foilbearing.integrate.newton import Factor as IntegratorFactor
from foilbearing.orbit.result import OrbitResult, RunStatus
from foilbearing.orbit.sampling import Samples
from foilbearing.reynolds.transient import Inputs

__all__ = ["Factor", "RunStats", "StepperProblem"]

FloatArray = NDArray[np.float64]


class Factor(IntegratorFactor, Protocol):
    """The integrator's factor (:class:`foilbearing.integrate.newton.Factor`: a factorised
    Newton matrix of one step and its compiled modified-Newton iteration, whose monitor is
    here the minimum film h/C) that also holds the lift-off branches.

    :class:`~foilbearing.reynolds.transient_factor.TransientFactor` is one.
    """

    @property
    def lift_state(self) -> FloatArray:
        """Lift-off branch of each pressure cell held by the factor: > 0 held, < 0 free, 0
        none (an array the stepper may change in place)."""


@dataclass(frozen=True)
class RunStats:
    """How a run went, for its result.

    Attributes
    ----------
    clock
        ``time.perf_counter()`` at the start of the run, s (the result's wall time
        runs from it to when the result is made).
    steps, factorizations, newton_iterations
        Accepted steps, Jacobian factorisations and Newton iterations.
    contact
        Where the film closed (time_s, speed_rpm, angle_deg, min_film_um), or None.
    checkpoint
        Everything needed to resume the run (stepper state and history, the
        voltage program's own state).
    """

    clock: float
    steps: int
    factorizations: int
    newton_iterations: int
    contact: dict[str, float] | None
    checkpoint: dict[str, Any]


@dataclass(frozen=True)
class StepperProblem:
    """The semi-discrete system dQ(y)/dt = f(y, t) of a run, as the stepper sees it.

    The state y is nondimensional (pressures P, bump deflections U and the
    journal ε in units of C, its velocity v in C/s); time is in s.

    Attributes
    ----------
    size
        Length of the state y.
    t_end
        End of the speed profile, s.
    speed
        ``speed(t)``: rotor speed ω at t, rad/s (sets the time step).
    inputs
        ``inputs(t)``: the inputs of the system at t (speed, preload, forces) and
        the actuator voltages at t (V, shape (n_act,)); called in time order, as a
        closed-loop program's voltages follow the samples it has seen.
    storage
        ``storage(y, inputs)``: the stored quantity Q(y) of the BDF history.
    factorize
        ``factorize(y, inputs, c0, hist, branches)``: the factorised Newton matrix
        of c0·Q(y) + hist − f(y) at y (a :class:`Factor`, which also iterates the
        residual to convergence: the residual and the solve are compiled
        together); ``branches`` are the lift-off branches to take (+1 held,
        −1 free) or None to decide them at y.
    lift_slack
        The residual's lift-off slack of each cell (−G/d on a held cell, P − 1 on
        a free one) at the last iterate, an array the residual writes in place.
    atol
        Absolute tolerances of the state (same shape as y) of the error weights.
    journal
        Index of ε_X in y (ε_Y follows).
    clearance
        Radial clearance C, m (for the contact report).
    record
        ``record(out, t, y, volts, inputs, min_film)``: add the accepted state y at
        t to the output ``out`` (``min_film``: minimum film h/C of y, or None).
    observe
        ``observe(t, e_x)``: hand an output sample of e_X (m) at t to a
        closed-loop voltage program; None when the program does not read them.
    program_checkpoint
        The voltage program's own state, to resume it (an empty dict without one).
    make_result
        ``make_result(out, status, message, stats)``: the result of the run from
        its output ``out`` (:class:`~foilbearing.orbit.result.OrbitResult`).
    on_step
        ``on_step(t, y, order)``: called after each accepted step with its time, state
        and the BDF order it took (the start-up's included); None: not called. The
        run's derivative with respect to its start reads the steps so
        (:mod:`foilbearing.orbit.tangent`).
    """

    size: int
    t_end: float
    speed: Callable[[float], float]
    inputs: Callable[[float], tuple[Inputs, FloatArray]]
    storage: Callable[[FloatArray, Inputs], FloatArray]
    factorize: Callable[[FloatArray, Inputs, float, FloatArray, FloatArray | None], Factor]
    lift_slack: FloatArray
    atol: FloatArray
    journal: int
    clearance: float
    record: Callable[[Samples, float, FloatArray, FloatArray, Inputs, float | None], None]
    observe: Callable[[float, float], None] | None
    program_checkpoint: Callable[[], dict[str, Any]]
    make_result: Callable[[Samples, RunStatus, str, RunStats], OrbitResult]
    on_step: Callable[[float, FloatArray, int], None] | None = None
