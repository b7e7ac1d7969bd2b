"""Settings of the orbit integrator: the step rule, the Newton iteration, sampling and stopping."""

from __future__ import annotations

import math
from dataclasses import dataclass

from foilbearing.errors import InputError
from foilbearing.integrate import MAX_ORDER, NewtonRule

__all__ = [
    "ADAPTIVE_MAX_STEP_REV",
    "MAX_ORDER",
    "STEP_KINDS",
    "NewtonRule",
    "OrbitSettings",
    "Sampling",
    "StepRule",
    "StopRule",
]

#: The kinds of time step: a fixed number a revolution, or error-controlled.
STEP_KINDS = ("fixed", "adaptive")

#: The longest error-controlled step, in revolutions: the orbit sees every revolution.
ADAPTIVE_MAX_STEP_REV = 0.1


@dataclass(frozen=True)
class StepRule:
    """The time-step rule of the stepper (see :class:`OrbitSettings`).

    Attributes
    ----------
    steps_per_rev
        Time steps per rotor revolution (Δt = 2π/(ω · steps_per_rev)).
    order
        Order of the variable-step BDF (1 to :data:`MAX_ORDER`).
    max_step
        Largest time step, s.
    rtol
        Relative tolerance of the local error test of error-controlled steps (None: fixed
        steps of ``steps_per_rev`` a revolution; with it, ``steps_per_rev`` sets the first).
    """

    steps_per_rev: int
    order: int
    max_step: float
    rtol: float | None = None


@dataclass(frozen=True)
class Sampling:
    """The output of a run (see :class:`OrbitSettings`).

    Attributes
    ----------
    sample_rate
        Output sampling rate, Hz.
    """

    sample_rate: float


@dataclass(frozen=True)
class StopRule:
    """When a run ends before the end of its speed profile.

    Attributes
    ----------
    contact_film
        Contact: the run stops when the minimum film falls below this fraction of C.
    stop_time
        The run stops at this simulated time, s (None: at the end of the profile).
    """

    contact_film: float
    stop_time: float | None = None


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
        orbit's extent on the benchmark segment, see ``docs/development/orbit-performance.md``);
        BDF2 needs about 40 steps per revolution for the same. BDF3 is not
        A-stable (A(86°)), but its stability wedge holds the film's decaying
        modes, and the 1X and whirl motions (ωΔt <= 0.26) lie where it is
        accurate.
    max_step
        Largest time step, s.
    steps
        ``"fixed"`` (the default): ``steps_per_rev`` steps a revolution; ``"adaptive"``:
        variable steps chosen by the local error test at ``step_rtol``
        (:class:`foilbearing.integrate.StepControl`), at most
        :data:`ADAPTIVE_MAX_STEP_REV` of a revolution and ``max_step``, the first one of
        ``steps_per_rev`` a revolution; the samples are then interpolated by the cubic
        through the four steps around them instead of linearly.
    step_rtol
        Relative tolerance of the adaptive steps' local error test (the absolute
        tolerances ``atol_*`` scaled by ``step_rtol/rtol``).
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
    refresh_after
        After a step of more than this many Newton iterations the next step takes a
        fresh factor at its predictor instead of the kept one (None, the default: the
        factor is kept until it fails or asks for a refresh). 4-6 makes a step 1.3-2.2
        times cheaper on a 6-cell axial grid; on 96 × 12 it gains a few per cent on large
        orbits and nothing on a whole 1 g·mm speed-up; the solution is the same to the
        Newton tolerance (``benchmarks/bench_orbit_steps.py --refresh``;
        docs/development/orbit-performance.md, "Route 4").

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
    reaches the clearance, and without a disturbance that whirl starts from a
    seed that is partly numerical, so their divergence speed moves by up to 2 %
    with the tolerance (4 % with the old defaults, 5 % with 3/0.1: 23.25)
    (``tests/test_orbit.py::test_newton_tolerance_does_not_move_the_divergence``).
    A case's ``[disturbance]`` (the default case has one) is a defined seed: with
    it the 0 V, 1 g·mm speed-up diverges at 52.7 krpm within 0.15 % of the step
    and the tolerance (docs/development/orbit-performance.md).
    The orbit error left at constant speed is below 1 % of the time-step error
    (``test_newton_error_is_well_below_the_time_step_error``).
    """

    steps_per_rev: int = 24
    order: int = 3
    max_step: float = 1e-3
    steps: str = "fixed"
    step_rtol: float = 1e-3
    sample_rate: float = 10_000.0
    contact_film: float = 0.005
    newton_tol: float = 0.3
    rtol: float = 1e-4
    atol_pressure: float = 1e-5
    atol_position: float = 1e-5
    max_newton: int = 10
    newton_fraction: float = 0.001
    refresh_after: int | None = None

    @property
    def step_rule(self) -> StepRule:
        """The settings of the time-step rule."""
        rtol = self.step_rtol if self.steps == "adaptive" else None
        return StepRule(self.steps_per_rev, self.order, self.max_step, rtol)

    @property
    def newton_rule(self) -> NewtonRule:
        """The settings of the Newton iteration."""
        return NewtonRule(
            self.newton_tol, self.newton_fraction, self.max_newton, self.rtol, self.refresh_after
        )

    @property
    def sampling(self) -> Sampling:
        """The settings of the output."""
        return Sampling(self.sample_rate)

    def stop_rule(self, stop_time: float | None = None) -> StopRule:
        """The stop rule: contact at ``contact_film``, or ``stop_time`` (s) when given."""
        return StopRule(self.contact_film, stop_time)

    def check(self, max_speed: float) -> None:
        """Errors before any work for settings that cannot resolve the synchronous frequency."""
        f_sync = max_speed / (2 * math.pi)
        if self.steps_per_rev < 8:
            raise InputError(
                f"steps_per_rev = {self.steps_per_rev}: at least 8 resolve the 1X motion"
            )
        if self.order not in range(1, MAX_ORDER + 1):
            raise InputError(
                f"order = {self.order!r}: the BDF stepper has orders 1 to {MAX_ORDER} (default 3)"
            )
        if self.sample_rate < 4.0 * f_sync:
            raise InputError(
                f"sample_rate = {self.sample_rate:g} Hz cannot resolve the synchronous frequency "
                f"{f_sync:.0f} Hz at the top speed: use at least {4 * f_sync:.0f} Hz"
            )
        if self.steps not in STEP_KINDS:
            raise InputError(f"steps (--steps) = {self.steps!r}: one of {', '.join(STEP_KINDS)}")
        if not 1e-8 <= self.step_rtol <= 0.1:
            raise InputError(f"step_rtol (--rtol) = {self.step_rtol!r}: a tolerance in [1e-8, 0.1]")
        if not self.max_step > 0:
            raise InputError(f"max_step = {self.max_step!r} s: must be > 0")
        if self.refresh_after is not None and (
            isinstance(self.refresh_after, bool)
            or not isinstance(self.refresh_after, int)
            or self.refresh_after < 0
        ):
            raise InputError(
                f"refresh_after = {self.refresh_after!r}: an iteration count >= 0, or None "
                "(keep the factor until it fails)"
            )
        if not 0.0 < self.contact_film < 1.0:
            raise InputError(f"contact_film = {self.contact_film!r}: a fraction of C in (0, 1)")
