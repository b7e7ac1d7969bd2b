"""Fast tests that kill the mutation survivors of issue 48 item 7 that matter: each
asserts the physical sense of a sign the survivors flipped."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Grid, default_case
from foilbearing.static import film_at_position


def test_a_compressed_stack_lowers_its_lobe_and_opens_the_film() -> None:
    """Lobe reading (docs/model.md §3.8): a stack compressed by D (units of C) lets its
    lobe of the foil down by D times the lobe's shape, so the rigid film gets thicker,
    most at that actuator (60 deg), by D at the lobe's crown; the other lobes stay. Killed
    survivor: ``h_rigid_loaded`` with the lobe term's sign flipped (the film thinner)."""
    case = default_case().with_voltages(150.0).with_actuator_reading("lobe", "held")
    case = replace(case, grid=Grid(n_theta=48, n_z=4, orbit_n_z=None, orbit_axial_order=None))
    m = film_at_position(case, 0.3, 0.2, speed=50e3 * math.pi / 30.0).model
    assert m.lobe_shapes is not None
    compression = np.array([0.05, 0.0, 0.0])
    opened = m.h_rigid_loaded(0.3, 0.2, compression) - m.h_rigid(0.3, 0.2)
    assert opened.min() >= 0.0
    crown = int(np.argmax(opened[:, 0]))
    assert m.grid.theta[crown] == pytest.approx(math.radians(60.0), abs=2 * math.pi / 48)
    assert opened.max() == pytest.approx(0.05 * m.lobe_shapes[0].max(), rel=1e-12)
    far = np.abs(np.angle(np.exp(1j * (m.grid.theta - math.radians(240.0))))) < 0.2
    np.testing.assert_allclose(opened[far], 0.0, atol=1e-12)


def test_a_held_run_started_at_its_equilibrium_stays_there() -> None:
    """Under ``dynamics = "held"`` the orbit's rigid film is the lobes less the stacks'
    held compression (``preload_at``): without imbalance or disturbance, a run started at
    the static equilibrium (solved by the static analysis, an independent route) stays
    at it, to the stepper's Newton tolerance. Killed survivor: the held reading's sign in
    ``orbit/system.py`` ``preload_at`` (the film closed by the compression instead)."""
    from foilbearing.constants import RPM
    from foilbearing.control import constant_speed
    from foilbearing.orbit import simulate

    case = default_case().with_voltages(150.0).with_actuator_reading("local", "held")
    grid = Grid(n_theta=32, n_z=4, orbit_n_z=None, orbit_axial_order=None)
    case = replace(case, grid=grid, disturbance=None)
    case = replace(case, rotor=replace(case.rotor, imbalance=0.0))
    run = simulate(case, constant_speed(50e3 * RPM, 0.004))
    assert run.status == "completed"
    drift = np.hypot(run.e_x - run.e_x[0], run.e_y - run.e_y[0]).max()
    assert drift < 1e-3 * case.bearing.clearance, drift / case.bearing.clearance
