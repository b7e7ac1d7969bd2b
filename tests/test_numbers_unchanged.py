"""Today's numbers, recorded before the laws moved into ``foilbearing.laws`` (issue 46).

Moving a law into its own module must not change what any analysis computes. The
values below were recorded at 175027a on the built-in default case on a coarse grid,
32 x 4, with the case's smoothed lift-off edge (κ = 0.1) and, where stated, the sharp
edge (κ = 0): the equilibrium at three (speed, voltage) points, the force
coefficients at one point and frequency, the linear onset speed at 0 and 150 V under
two actuator readings (local compliant, lobe held), and the first samples of two very
short orbits. They must hold to 1e-9 relative: a moved formula may round differently in
its last bit (a product regrouped), and these analyses amplify that by well under 1e3
(Newton tolerances 1e-10 and below, Brent's bracket to 1e-4 of the speed, which moves
the onset continuously with its inputs). The orbit samples hold to 1e-9 of the orbit's
extent: 20 steps of a converged Newton iteration on a fixed grid carry the same
round-off.

Regenerate (only when a change of the numbers is intended and explained in the commit)::

    PYTHONPATH=src python tests/test_numbers_unchanged.py

which prints the ``RECORDED`` dictionary to paste below.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np
import pytest

from foilbearing.case import Case, Grid, default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.control import constant_speed
from foilbearing.orbit import simulate
from foilbearing.stability import onset_speed
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0
RTOL = 1e-9
KAPPA = 0.1  # the default case's lift-off smoothing
EQUILIBRIA = [(20e3, 0.0, KAPPA), (50e3, 150.0, KAPPA), (90e3, 100.0, KAPPA), (50e3, 150.0, 0.0)]
ONSETS = [(0.0, "local", "compliant"), (150.0, "local", "compliant"),
          (0.0, "lobe", "held"), (150.0, "lobe", "held")]  # fmt: skip
SCAN = [s * 1e3 * RPM for s in range(10, 130, 10)]
ORBIT_SAMPLES = 12


def coarse(volts: float, kappa: float = KAPPA) -> Case:
    """The default case at ``volts`` on 32 x 4 (static, linear and orbit), no disturbance."""
    case = default_case().with_voltages(volts)
    # one grid for every analysis, as Grid(32, 4) meant when these were recorded
    grid = Grid(32, 4, lift_off_smoothing=kappa, orbit_n_z=None, orbit_axial_order=None)
    return replace(case, grid=grid, disturbance=None)


def equilibrium(rpm: float, volts: float, kappa: float) -> list[float]:
    """Eccentricity, attitude (rad), minimum film (m) and drag torque (N·m)."""
    st = solve_equilibrium(coarse(volts, kappa), speed=rpm * RPM)
    assert st.converged, st.message
    return [st.eccentricity, st.attitude_angle, st.min_film, st.drag_torque]


def coefficients() -> list[float]:
    """K (N/m) and C (N·s/m), row-major, at 50 krpm, 150 V, whirl at half the speed."""
    st = solve_equilibrium(coarse(150.0), speed=50e3 * RPM)
    fc = force_coefficients(st, 0.5 * st.speed)
    return [float(v) for v in (*fc.K[0].ravel(), *fc.C[0].ravel())]


def onset(volts: float, response: str, dynamics: str) -> float:
    """The linear onset speed, rad/s."""
    case = coarse(volts).with_actuator_reading(response, dynamics)
    result = onset_speed(case, SCAN)
    assert result.onset_speed is not None, result.message
    return float(result.onset_speed)


def orbit(kappa: float) -> dict[str, list[float]]:
    """The first samples of 2 ms at 20 krpm, 100 V, from the equilibrium (8.5 g·mm imbalance)."""
    result = simulate(coarse(100.0, kappa), constant_speed(20e3 * RPM, 2e-3))
    return {
        "time": [float(v) for v in result.time[:ORBIT_SAMPLES]],
        "e_x": [float(v) for v in result.e_x[:ORBIT_SAMPLES]],
        "e_y": [float(v) for v in result.e_y[:ORBIT_SAMPLES]],
    }


def record() -> dict[str, Any]:
    """Every recorded number, computed now."""
    return {
        "equilibrium": {
            f"{r:g} rpm {v:g} V k{k:g}": equilibrium(r, v, k) for r, v, k in EQUILIBRIA
        },
        "coefficients": coefficients(),
        "onset": {f"{v:g} V {a} {b}": onset(v, a, b) for v, a, b in ONSETS},
        "orbit": {f"k{k:g}": orbit(k) for k in (KAPPA, 0.0)},
    }


# Recorded at 175027a (twice, in separate processes: identical to the last digit).
RECORDED: dict[str, Any] = {
    "equilibrium": {
        "20000 rpm 0 V k0.1": [
            0.8272152872534249,
            0.48060515027157497,
            1.8630389224962146e-05,
            0.0013340705121310894,
        ],
        "50000 rpm 150 V k0.1": [
            0.20400879446355982,
            0.428643445193767,
            2.0307426512855284e-05,
            0.0038041659219918964,
        ],
        "90000 rpm 100 V k0.1": [
            0.19913893037268482,
            0.5347926233275648,
            3.0118325490028873e-05,
            0.005510121454587408,
        ],
        "50000 rpm 150 V k0": [
            0.20492240185588412,
            0.42426599044412405,
            2.0087895668932748e-05,
            0.0038154995890316394,
        ],
    },
    "coefficients": [
        562736.415804315,
        47246.06176461208,
        -179339.89271584584,
        345272.0288811075,
        52.708072630561766,
        -17.530151762296867,
        3.7269850817567156,
        54.00487927405425,
    ],
    "onset": {
        "0 V local compliant": 4311.009992214226,
        "150 V local compliant": 5404.007975788747,
        "0 V lobe held": 4238.607383634062,
        "150 V lobe held": 7659.968959229259,
    },
    "orbit": {
        "k0.1": {
            "time": [
                0.0,
                0.0001,
                0.0002,
                0.00030000000000000003,
                0.0004,
                0.0005,
                0.0006000000000000001,
                0.0007,
                0.0008,
                0.0009000000000000001,
                0.001,
                0.0011,
            ],
            "e_x": [
                3.401753851370094e-05,
                3.424156347206964e-05,
                3.48866247625096e-05,
                3.5852738358988684e-05,
                3.710857882479716e-05,
                3.8601160279185254e-05,
                4.0273263347119657e-05,
                4.199658617176042e-05,
                4.36489906154263e-05,
                4.514238199415929e-05,
                4.638973767757706e-05,
                4.724839463570937e-05,
            ],
            "e_y": [
                2.4625542517239295e-05,
                2.4644713605469817e-05,
                2.476766265165004e-05,
                2.5055035109264955e-05,
                2.556218310923595e-05,
                2.6337659312724393e-05,
                2.7467951854054042e-05,
                2.902045771474822e-05,
                3.092667355141497e-05,
                3.3173279868081945e-05,
                3.573685844979415e-05,
                3.860731663155773e-05,
            ],
        },
        "k0": {
            "time": [
                0.0,
                0.0001,
                0.0002,
                0.00030000000000000003,
                0.0004,
                0.0005,
                0.0006000000000000001,
                0.0007,
                0.0008,
                0.0009000000000000001,
                0.001,
                0.0011,
            ],
            "e_x": [
                3.4042386631097665e-05,
                3.4266429484056094e-05,
                3.4911497157512103e-05,
                3.5877271437517105e-05,
                3.713221904978768e-05,
                3.8623103494263336e-05,
                4.02921159993223e-05,
                4.201017860657993e-05,
                4.365519423141368e-05,
                4.5138991417740574e-05,
                4.637456947979385e-05,
                4.721919188704225e-05,
            ],
            "e_y": [
                2.5631088055861264e-05,
                2.565025984632589e-05,
                2.577314377744941e-05,
                2.60601583738271e-05,
                2.6566449793572535e-05,
                2.7340332524263593e-05,
                2.846780625966761e-05,
                3.0015536849099683e-05,
                3.191486322005744e-05,
                3.4152102243990876e-05,
                3.670346695397296e-05,
                3.9557991997335297e-05,
            ],
        },
    },
}


@pytest.mark.parametrize(("rpm", "volts", "kappa"), EQUILIBRIA)
def test_equilibrium_unchanged(rpm: float, volts: float, kappa: float) -> None:
    want = RECORDED["equilibrium"][f"{rpm:g} rpm {volts:g} V k{kappa:g}"]
    np.testing.assert_allclose(equilibrium(rpm, volts, kappa), want, rtol=RTOL, atol=0.0)


def test_coefficients_unchanged() -> None:
    want = np.array(RECORDED["coefficients"])
    got = np.array(coefficients())
    # Each matrix to 1e-9 of its largest entry (a near-zero cross term has no relative digits).
    for part in (slice(0, 4), slice(4, 8)):
        scale = np.abs(want[part]).max()
        np.testing.assert_allclose(got[part], want[part], rtol=0.0, atol=RTOL * scale)


@pytest.mark.parametrize(("volts", "response", "dynamics"), ONSETS)
def test_onset_unchanged(volts: float, response: str, dynamics: str) -> None:
    want = RECORDED["onset"][f"{volts:g} V {response} {dynamics}"]
    np.testing.assert_allclose(onset(volts, response, dynamics), want, rtol=RTOL, atol=0.0)


@pytest.mark.parametrize("kappa", [KAPPA, 0.0])
def test_orbit_samples_unchanged(kappa: float) -> None:
    want = RECORDED["orbit"][f"k{kappa:g}"]
    got = orbit(kappa)
    np.testing.assert_array_equal(got["time"], want["time"])
    for key in ("e_x", "e_y"):
        extent = np.ptp(want[key])
        np.testing.assert_allclose(got[key], want[key], rtol=0.0, atol=RTOL * extent)


if __name__ == "__main__":
    import pprint

    pprint.pprint(record(), width=100, sort_dicts=False)
