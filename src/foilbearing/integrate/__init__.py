"""A variable-order BDF integrator of implicit systems ``dQ(y)/dt = f(y, t)`` over callables.

The integrator is given the problem as callables and arrays (its arguments at t, its
storage Q, a factorised Newton matrix that also iterates the residual, the nominal
step), what to record after each accepted step and when to stop (stop events, the
user's interrupt, the end time); it knows nothing of the problem, its units or its
words. The orbit of one bearing (:mod:`foilbearing.orbit.stepper`) and the rotor on
its bearings (:mod:`foilbearing.rotor.stepper`) are two problems it integrates. It
imports nothing from the rest of the package.

=====================  =====================================================================
Module                 Responsibility
=====================  =====================================================================
``integrator.py``      :func:`integrate`: the step loop (nominal or error-controlled step,
                       start-up, order restart, history), the record callback, the stop
                       events and the checkpoints; the :class:`Problem`, :class:`State`,
                       :class:`StepControl` and :class:`Solution`.
``newton.py``          The one modified-Newton policy: convergence, too slow, diverged,
                       refresh (compiled, called from inside compiled iterations; its
                       Python originals serve iterations written in Python), and the
                       step's keep / refresh / restart / give up (:func:`solve_step`).
``bdf.py``             The variable-step BDF coefficients, history, predictor and error
                       weights of one step, and its local error estimate (compiled).
``events.py``          How a run ends (:class:`Status`), stop events, the step collapse
                       and Ctrl-C held to a step boundary.
=====================  =====================================================================
"""

from foilbearing.integrate.bdf import bdf_error, bdf_setup
from foilbearing.integrate.events import (
    Event,
    Status,
    StepCollapsed,
    interrupt_at_step_boundary,
)
from foilbearing.integrate.integrator import (
    MAX_ORDER,
    Problem,
    Solution,
    State,
    StepControl,
    integrate,
)
from foilbearing.integrate.newton import Factor, NewtonRule, Switching, solve_step

__all__ = [
    "MAX_ORDER",
    "Event",
    "Factor",
    "NewtonRule",
    "Problem",
    "Solution",
    "State",
    "Status",
    "StepCollapsed",
    "StepControl",
    "Switching",
    "bdf_error",
    "bdf_setup",
    "integrate",
    "interrupt_at_step_boundary",
    "solve_step",
]
