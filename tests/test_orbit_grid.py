"""The orbit's own grid (``[grid] orbit_n_theta``, ``orbit_n_z``; issue 30).

The orbit runs on it and says so; the static and linear analyses keep ``[grid]``; the
orbit's partner on one grid is the analysis of ``Case.orbit_case()``. Coarse grids: each
test runs in seconds.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from foilbearing.case import Grid, case_from_dict, default_case, default_case_path
from foilbearing.control import constant_speed
from foilbearing.errors import InputError
from foilbearing.orbit import simulate
from foilbearing.orbit.analysis import analyse_orbit
from foilbearing.output.report.sections import _grid_text
from foilbearing.stability import whirl_mode
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0
SPEED = constant_speed(30e3 * RPM, 0.004)


#: A 48 x 6 grid under the sharp law, the orbit on it unless a test gives its own.
_SHARP_SINGLE = {
    "n_theta": 48,
    "n_z": 6,
    "orbit_n_z": None,
    "orbit_axial_order": None,
    "lift_off_smoothing": 0.0,
}


def _case(**grid: int):
    base = replace(default_case().with_voltages(100.0), disturbance=None)
    return replace(base, grid=Grid(**(_SHARP_SINGLE | grid)))


def _case_data() -> dict:
    with default_case_path().open("rb") as fh:
        return tomllib.load(fh)


def test_the_orbit_runs_on_its_own_grid_as_a_case_on_that_grid_would() -> None:
    """An orbit grid of 36 x 3 under a 48 x 6 case grid gives, sample for sample, the run
    of a case whose only grid is 36 x 3 (the same semi-discrete system), and not the run on
    48 x 6 (the orbit does not ignore its grid); the result's case and its JSON readouts
    name the grid it ran on."""
    own = simulate(_case(orbit_n_theta=36, orbit_n_z=3), SPEED)
    plain = simulate(_case(n_theta=36, n_z=3), SPEED)
    main = simulate(_case(), SPEED)
    np.testing.assert_array_equal(own.e_x, plain.e_x)
    np.testing.assert_array_equal(own.e_y, plain.e_y)
    assert own.steps == plain.steps
    assert np.max(np.abs(own.e_x - main.e_x)) > 1e-3 * np.ptp(main.e_x)
    assert (own.case.grid.n_theta, own.case.grid.n_z) == (36, 3)
    assert analyse_orbit(own).headline(own)["grid"] == [36, 3]
    ds = own.to_dataset()
    assert (ds.attrs["grid_n_theta"], ds.attrs["grid_n_z"]) == (36, 3)


def test_the_linear_partner_of_an_orbit_grid_is_the_analysis_on_that_grid() -> None:
    """``orbit_case()`` puts the static and linear analyses on the orbit's grid: its whirl
    eigenvalue is that of a case on that grid (to round-off), while the case's own
    analysis stays on ``[grid]``; without an orbit grid it is the case itself."""
    case = _case(orbit_n_theta=36, orbit_n_z=3)

    def mode(c):
        return whirl_mode(solve_equilibrium(c, speed=40e3 * RPM), c.rotor.mass)

    partner, plain, main = mode(case.orbit_case()), mode(_case(n_theta=36, n_z=3)), mode(case)
    assert partner.eigenvalue == pytest.approx(plain.eigenvalue, rel=1e-12)
    assert abs(main.eigenvalue - partner.eigenvalue) > 1e-4 * abs(partner.eigenvalue)
    plain_case = _case()
    assert plain_case.orbit_case() is plain_case


def test_orbit_grid_fields_in_the_case_file_with_one_line_errors() -> None:
    """The TOML fields set the orbit's grid (defaults: the built-in case's orbit grid,
    n_z = 4 at axial order 4; one grid for all when stated); an out-of-range value
    names the field and the range; a grid with under 2 cells across the stinger arc is
    an error of the orbit before any work, naming the field and the smallest n_theta."""
    data = _case_data()
    case = case_from_dict(data | {"grid": {"n_theta": 96, "n_z": 12, "orbit_n_z": 6}})
    assert case.grid.orbit_shape == (96, 6) and case.grid.orbit_is_own
    default = case_from_dict(data | {"grid": {"n_theta": 96, "n_z": 12}}).grid
    assert default.orbit_shape == (96, 4) and default.orbit_order == 4
    one = {"n_theta": 96, "n_z": 12, "orbit_n_z": 12, "orbit_axial_order": 2}
    assert not case_from_dict(data | {"grid": one}).grid.orbit_is_own
    with pytest.raises(InputError, match=r"grid\.orbit_n_z = 1.*integer from 2 to 256"):
        case_from_dict(data | {"grid": {"orbit_n_z": 1}})
    coarse = case_from_dict(data | {"grid": {"orbit_n_theta": 24}})
    with pytest.raises(InputError) as err:
        simulate(coarse, SPEED)
    message = str(err.value)
    assert "grid.orbit_n_theta = 24" in message and "n_theta >= 26" in message
    assert "\n" not in message


def test_a_run_resumed_on_another_orbit_grid_is_refused(tmp_path: Path) -> None:
    """A checkpoint holds the state of its grid: resuming it with a case whose orbit grid
    differs is a one-line error, not a shape error deep in the stepper."""
    first = simulate(_case(), constant_speed(30e3 * RPM, 0.004), stop_time=0.001)
    with pytest.raises(InputError, match="resume it with the case it started with"):
        simulate(_case(orbit_n_z=3), constant_speed(30e3 * RPM, 0.004), resume=first)


def test_a_run_on_an_orbit_order_of_its_own_resumes_to_the_whole_run() -> None:
    """An orbit of axial order 4 under a case grid of order 2 resumes with its own case, as
    `foilbearing orbit --resume` gives it (the check compares the orbit's grid, not the
    static one: the CLI refused every such run before) and ends where the
    uninterrupted run ends (to 1e-3 C, as the CLI's resume: the step history restarts)."""
    case = _case(orbit_n_z=4, orbit_axial_order=4)
    speed = constant_speed(30e3 * RPM, 0.004)
    whole = simulate(case, speed)
    first = simulate(case, speed, stop_time=0.002)
    first = replace(first, case=case)  # as `--resume` loads it: the case file's whole case
    resumed = simulate(case, speed, resume=first)
    assert resumed.case.grid.orbit_order == 4 and resumed.status == whole.status
    clearance = case.bearing.clearance
    np.testing.assert_allclose(resumed.e_x[-1], whole.e_x[-1], rtol=0, atol=1e-3 * clearance)


def test_the_report_names_the_orbits_grid() -> None:
    """The report's grid line adds the orbits' grid only where it is their own."""
    assert _grid_text({"n_theta": 96, "n_z": 12, "orbit_n_theta": 96, "orbit_n_z": 12}) == (
        "96 × 12 (θ × half length)"
    )
    assert _grid_text({"n_theta": 96, "n_z": 12, "orbit_n_theta": 96, "orbit_n_z": 6}).endswith(
        "; the orbits run on 96 × 6"
    )
