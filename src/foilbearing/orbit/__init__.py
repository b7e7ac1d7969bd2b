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

===============  ===============================================================================
module           responsibility
===============  ===============================================================================
``spec``         the specification of an orbit run as plain data (SI): what a file stores to be
                 resumed
``settings``     settings of the integrator: step rule, Newton iteration, sampling, stopping
``system``       assembly of the orbit's system from the case, the programs, the preload and the
                 inputs
``problem``      what the stepper integrates: callables and arrays, no case, programs or
                 settings
``stepper``      the variable-step BDF stepper, its modified Newton iteration and its checkpoint
``held``         held stingers: the stacks' quasi-static compression along a run
``disturbance``  the random force on the rotor of a case's ``[disturbance]``, against time
``sampling``     the samples at a fixed rate, interpolated between steps, and the progress bar
``result``       the result of a run: sampled time series, status and checkpoint
``analysis``     what a run shows: waterfall, sub-synchronous amplitude, onset, whip, divergence
``tangent``      the derivative of a run with respect to its start state (the BDF steps'
                 variational equations)
``netcdf``       orbit runs on disk: NetCDF with the time series, the run specification and the
                 checkpoint
``reference``    moved: names the new home of the ``solve_ivp`` reference
===============  ===============================================================================
"""

from __future__ import annotations

from collections.abc import Callable

from foilbearing.case import Case
from foilbearing.case.record import case_to_dict, table_differences
from foilbearing.control import SpeedProfile, VoltageProgram
from foilbearing.errors import InputError
from foilbearing.orbit.result import OrbitResult, RunStatus
from foilbearing.orbit.sampling import Samples
from foilbearing.orbit.settings import OrbitSettings
from foilbearing.orbit.spec import RunSpec
from foilbearing.orbit.stepper import State, interrupt_at_step_boundary, run
from foilbearing.orbit.system import OrbitSimulation

__all__ = ["OrbitResult", "OrbitSettings", "OrbitSimulation", "RunSpec", "RunStatus", "simulate"]


def simulate(
    case: Case,
    speed: SpeedProfile,
    voltage: VoltageProgram | None = None,
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
        A stopped run to continue from its checkpoint, on the case it ran on (any other
        is refused, naming the fields that differ) and with the same programs.
    checkpoint
        Called with the partial result every ``checkpoint_every`` seconds of
        wall time (e.g. to save it), so a crash loses little.
    """
    sim = OrbitSimulation(case, speed, voltage, settings)
    if resume is not None:
        if not resume.checkpoint:
            raise InputError("the run to resume has no checkpoint")
        state = State.from_checkpoint(resume.checkpoint)
        g, here = resume.case.grid, sim.system.grid  # the run's case: its orbit's grid
        (n_theta, n_z), order = g.orbit_shape, g.orbit_order
        if (
            state.y.size != sim.system.size
            or order != here.axial_order
            or g.lift_off_smoothing != here.lift_off_smoothing
        ):
            raise InputError(
                f"the run to resume was on a {n_theta} x {n_z} grid of axial order "
                f"{order}, lift-off smoothing {g.lift_off_smoothing:g}; this case's "
                f"orbit runs on {here.n_theta} x {here.n_z} of order {here.axial_order}, "
                f"smoothing {here.lift_off_smoothing:g}: resume it with the case it started with",
                source=case.source,
            )
        diffs = table_differences(case_to_dict(resume.case.orbit_case()), case_to_dict(sim.case))
        if diffs:
            shown = "; ".join(f"{k}: {a} then, {b} now" for k, a, b in diffs[:3])
            more = f" and {len(diffs) - 3} more" if len(diffs) > 3 else ""
            raise InputError(
                f"the run to resume ran on another case ({shown}{more}): resume it with the "
                "case it started with",
                source=case.source,
            )
        if voltage is not None:
            voltage.restore(resume.checkpoint)
        samples = Samples.from_result(resume)
        counts = (resume.steps, resume.factorizations, resume.newton_iterations)
    else:
        state = State(0.0, sim.initial_state())
        samples = Samples(1.0 / sim.settings.sampling.sample_rate, sim.settings.steps == "adaptive")
        counts = (0, 0, 0)
    s = sim.settings
    with interrupt_at_step_boundary() as interrupted:
        return run(
            sim.problem(),
            state,
            samples,
            s.step_rule,
            s.newton_rule,
            s.stop_rule(stop_time),
            progress,
            checkpoint,
            checkpoint_every,
            interrupted,
            counts,
        )
