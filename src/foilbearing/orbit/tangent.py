"""The derivative of an orbit run with respect to its start state: the BDF steps' own
variational equations.

A run of the stepper (:mod:`foilbearing.orbit.stepper`) is a map from its start
state y₀ to its end state, step by step: each accepted state solves the BDF
equations ``c0 Q(y_{i+1}) + Σ_j w_j Q(y_{i−j}) − f(y_{i+1}) = 0`` over the last k
states (k the order the step took, c0 and w_j the variable-step coefficients of
:func:`~foilbearing.reynolds._kernels.bdf_setup`). Differentiating them gives the
derivative of the run, exactly (to the Newton tolerance of the states), for the
steps the run took:

    J_{i+1} δy_{i+1} = −Σ_j w_j (∂Q/∂y)(y_{i−j}) δy_{i−j},     δy_0 = V,

with ``J = c0 ∂Q/∂y − ∂f/∂y`` the Newton matrix at the accepted state, factorised
afresh there by the orbit's own compiled factorisation
(:meth:`~foilbearing.reynolds.transient.TransientSystem.factorize`, whose solve equals
one with :meth:`~foilbearing.reynolds.transient.TransientSystem.jacobian`). Under top-foil
lift-off a cell held at ambient has the equation ``d (P − 1) = 0``, which holds no
history: its row of J is ``d e_k`` and its right-hand side 0, so its pressure does
not vary (the generalised derivative of the complementarity, branches fixed at each
step). A cell that is held or set free between steps changes its equation there,
which is the event's own linearisation (its pressure is 1 at the switch either way).
Under the smoothed lift-off law (docs/lift-off.md, "The smoothed edge") a film cell's
equation is ``G(P − 1, g) = 0`` of its BDF row g, so its history enters times
``α = ∂G/∂g`` (:meth:`~foilbearing.reynolds.transient.TransientSystem.smoothed_weights`):
0 where the foil has lifted, 1 where the film is above ambient and obeys Reynolds.

For a periodic orbit this is the monodromy ``M = ∂φ_T/∂y₀`` of shooting
(:mod:`foilbearing.bifurcation`): exact products ``M V`` where finite differences of
the piecewise-smooth flow scatter by percent (docs/bifurcation.md). Time in s; the
state as in :mod:`foilbearing.reynolds.transient`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["RunTangent", "run_tangent"]

FloatArray = NDArray[np.float64]


#: Past states a step can look back on (BDF orders up to 5, and one more).
_KEEP = 6


@dataclass(frozen=True)
class _Step:
    """One accepted step as its variational equation needs it."""

    factor: Any  # the Newton matrix factorised at the new state (a TransientFactor)
    history: FloatArray  # ∂(row)/∂(history) of each row: 1, 0 held, α smoothed
    weights: FloatArray  # w_j of the k past storages, newest first


@dataclass(frozen=True)
class RunTangent:
    """A run and its derivative with respect to its start state.

    Attributes
    ----------
    result
        The run (:class:`~foilbearing.orbit.result.OrbitResult`).
    end
        Its end state, shape (size,).
    steps
        Each accepted step's factorised variational equation.
    storage
        ``storage(i, dy)``: ``(∂Q/∂y) dy`` at the run's state i (0: the start).
    """

    result: Any
    end: FloatArray
    steps: tuple[_Step, ...]
    storage: Callable[[int, FloatArray], FloatArray]

    def apply(self, directions: FloatArray) -> FloatArray:
        """``∂y_end/∂y₀ · V`` for directions V, shape (size,) or (size, m)."""
        v = np.asarray(directions, float)
        block = np.array(v.reshape(v.shape[0], -1))
        # ∂Q/∂y · δy of the states the next steps look back on, newest first.
        past = [self.storage(0, block)]
        dy = block
        for i, step in enumerate(self.steps):
            rhs = -sum(w * q for w, q in zip(step.weights, past, strict=False))
            rhs *= step.history[:, None]
            if rhs.shape[1] == 1:  # one direction (a Krylov product): the compiled solve
                dy = step.factor.solve(np.ascontiguousarray(rhs[:, 0]))[:, None]
            else:
                dy = step.factor.solve_block(rhs)
            past = [self.storage(i + 1, dy), *past][:_KEEP]
        return dy.reshape(v.shape)


def _weights(t_new: float, times: list[float]) -> tuple[float, FloatArray]:
    """c0 and the history weights w_j of a variable-step BDF step, newest first.

    The stepper's own formula (:func:`~foilbearing.reynolds._kernels.bdf_setup`), read off
    by giving it unit storages: its history ``Σ_j w_j Q_j`` is then the weights.
    """
    from foilbearing.reynolds.transient import bdf_setup

    k = len(times)
    out = np.empty(k), np.empty(k), np.empty(k)  # predictor, history, error weights
    past = (np.array(times, float), np.zeros((k, k)), np.eye(k), k)
    c0 = bdf_setup(t_new, past, k, np.ones(k), 0.0, *out)
    return float(c0), out[1].copy()


def run_tangent(sim: Any, y0: FloatArray, duration: float) -> RunTangent | None:
    """Run ``sim`` (an :class:`~foilbearing.orbit.system.OrbitSimulation`) from y₀ at t = 0
    for ``duration`` s, and factor the variational equation of each of its steps.

    Returns None when the run does not end where asked (contact or a failure): there
    is no derivative of a flow that stopped.
    """
    from foilbearing.orbit.sampling import Samples
    from foilbearing.orbit.stepper import State, run

    system, s = sim.system, sim.settings
    times, states, orders = [0.0], [np.array(y0, float)], [0]

    def on_step(t: float, y: FloatArray, order: int) -> None:
        times.append(float(t))
        states.append(np.array(y, float))
        orders.append(int(order))

    problem = replace(sim.problem(), on_step=on_step)
    result = run(
        problem,
        State(0.0, np.array(y0, float)),
        Samples(1.0 / s.sample_rate),
        s.step_rule,
        s.newton_rule,
        s.stop_rule(duration),
    )
    if result.status not in ("stopped", "completed"):
        return None
    inputs = [problem.inputs(t)[0] for t in times]
    storage = [system.storage(y, inp) for y, inp in zip(states, inputs, strict=True)]
    steps = []
    for i in range(1, len(times)):
        k = orders[i]
        past = list(range(i - 1, i - 1 - k, -1))
        c0, w = _weights(times[i], [times[j] for j in past])
        hist = sum(wj * storage[j] for wj, j in zip(w, past, strict=True))
        # A fresh factor at the accepted state, its lift-off branches decided there.
        factor = system.factorize(states[i], inputs[i], c0, hist)
        history = system.smoothed_weights(states[i], inputs[i], c0, hist, factor.lift_state)
        history[: system.n][factor.lift_state > 0.0] = 0.0
        steps.append(_Step(factor, history, w))

    products = [
        system.storage_operator(y, inp.preload) for y, inp in zip(states, inputs, strict=True)
    ]

    def storage_at(i: int, dy: FloatArray) -> FloatArray:
        return products[i](dy)

    return RunTangent(result, states[-1], tuple(steps), storage_at)
