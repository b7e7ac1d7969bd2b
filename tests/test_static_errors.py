"""The study's static table and coefficients carry an error that holds under refinement
(issue 49, item 1: every number the study prints).

The study prints the equilibria it shows (10, 50 and 90 krpm) and the dynamic coefficients
at 50 krpm and 150 V on the case's grid (96 × 12), each with its error: the difference to
the same solve on 192 × 24 (:func:`foilbearing.study.static.static_errors`,
:func:`foilbearing.study.converged.refined_coefficients`). The tests solve the next
refinement, 384 × 48, independently and ask that the 192 × 24 value moves by less than
the error printed with the 96 × 12 one: the two-level estimate at order 1 is an upper
bound wherever the scheme converges at order 1 or better (second order in θ and Z,
docs/numerics.md).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from foilbearing.analysis.coefficients import force_coefficients
from foilbearing.analysis.equilibrium import solve_equilibrium
from foilbearing.case import default_case
from foilbearing.check import refined
from foilbearing.constants import RPM
from foilbearing.output.summary import sweep_points
from foilbearing.study.converged import COEFFICIENT_FLOOR, refined_coefficients
from foilbearing.study.static import (
    MIN_FILM_FLOOR,
    SHOWN_SPEEDS_RPM,
    static_errors,
    static_sweep,
)


@pytest.fixture(scope="module")
def sweeps() -> list[list[dict]]:
    """The shown speeds at 150 V, C-GFB and shimmed, on 96 × 12 and 192 × 24 (the study's
    sweeps) and on 384 × 48, each point there solved cold (grid sequencing: about 2 s)."""
    case = default_case()
    speeds = [s * RPM for s in SHOWN_SPEEDS_RPM]
    levels = [sweep_points(static_sweep(refined(case, f), speeds, [150.0])) for f in (1, 2)]
    finest = []
    for p in levels[0]:
        c = refined(case.with_voltages(150.0), 4)
        c = c.shimmed() if p["bearing"] == "shimmed" else c
        res = solve_equilibrium(c, speed=p["speed_rpm"] * RPM)
        point = {"converged": res.converged, "min_film_um": res.min_film * 1e6,
                 "eccentricity": res.eccentricity, "drag_torque_Nm": res.drag_torque,
                 "attitude_deg": math.degrees(res.attitude_angle),
                 "preload_um": list(res.preload * 1e6),
                 "actuator_pressure_kPa": list(res.actuator_pressure / 1e3)}  # fmt: skip
        finest.append(point)
    return [*levels, finest]


def test_the_static_table_s_error_bounds_the_next_refinement(sweeps) -> None:
    coarse, fine, finest = sweeps
    static_errors(coarse, fine, [192, 24])
    checked = 0
    for p, f, g in zip(coarse, fine, finest, strict=True):
        assert p["converged"] and f["converged"] and g["converged"]
        refined_ = p["grid_refined"]
        assert refined_["grid"] == [192, 24]
        for key in ("eccentricity", "attitude_deg", "min_film_um", "drag_torque_Nm"):
            err = refined_["errors"][key]
            floor = MIN_FILM_FLOOR * p[key] if key == "min_film_um" else 0.0
            assert err == max(abs(p[key] - f[key]), floor)
            assert abs(f[key] - g[key]) < err, (p["bearing"], p["speed_rpm"], key)
            assert " ± " in refined_["texts"][key]
            checked += 1
        for key in ("preload_um", "actuator_pressure_kPa"):
            moves = np.abs(np.subtract(f[key], g[key]))
            errs = np.asarray(refined_["errors"][key])
            if p["bearing"] == "shimmed" and key == "preload_um":  # a shim's thickness
                assert np.all(errs == 0.0) and " ± " not in refined_["texts"][key]
                continue
            assert np.all(moves < errs), (p["bearing"], p["speed_rpm"], key, moves, errs)
    assert checked == 4 * 2 * len(SHOWN_SPEEDS_RPM)


def test_the_coefficients_error_bounds_the_next_refinement() -> None:
    case = default_case().with_voltages(150.0)
    frequencies = [f * 50e3 * RPM for f in (0.5, 1.0, 1.5, 2.0)]  # 1.5: K_YY's floor
    fc = force_coefficients(solve_equilibrium(case, speed=50e3 * RPM), frequencies)
    got = refined_coefficients(fc)
    assert got["grid"] == [192, 24]
    finest = force_coefficients(solve_equilibrium(refined(case, 4), speed=50e3 * RPM), frequencies)
    for name, err_key in (("K_N_per_m", "K_error_N_per_m"), ("C_Ns_per_m", "C_error_Ns_per_m")):
        fine, err = np.asarray(got[name]), np.asarray(got[err_key])
        coarse = np.asarray(fc.K if name[0] == "K" else fc.C)
        assert np.all(err >= COEFFICIENT_FLOOR * np.abs(coarse))
        move = np.abs(fine - np.asarray(finest.K if name[0] == "K" else finest.C))
        assert np.all(move < err), (name, move, err)
    assert " ± " in got["K_texts_MN_per_m"][1][0][0]
