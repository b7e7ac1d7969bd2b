"""Export to ROSS: coefficient tables, the frame mapping, and the onset speed of a rigid rotor.

The ROSS tests need ``ross-rotordynamics >= 3.0`` (the ``ross`` extra, which ``make test``
installs in the project's one environment, Python >= 3.13) and are skipped without it.

Frame mapping under test (``foilbearing.export.ross``): x_ROSS = Y, y_ROSS = −X,
i.e. ``K_ROSS = T K Tᵀ`` with ``T = [[0, 1], [−1, 0]]``. It is proved three
ways: (1) ROSS's "Forward" label is the sense of its own spin (gyroscopic
stiffening); (2) a bearing whose cross-coupling drives whirl from +X towards +Y
in our frame (the journal's sense of rotation) is exported and ROSS finds the
unstable mode Forward; (3) for the real bearing above its onset speed, ROSS's
unstable mode shape at the bearing, mapped back, is our own eigenvector, which
orbits from +X towards +Y.
"""

from __future__ import annotations

import math
import sys
import warnings
from typing import Any

import numpy as np
import pytest
from scipy.optimize import brentq

from foilbearing.case import default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.errors import InputError
from foilbearing.export.ross import coefficient_table, to_ross_bearing
from foilbearing.stability import onset_speed
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0
T = np.array([[0.0, 1.0], [-1.0, 0.0]])  # q_ROSS = T q_ours
# Table around the onset at 150 V (about 24 krpm, whirl at about 700 rad/s): 8 speeds
# 5 krpm apart, 6 frequencies spanning the whirl frequencies of the two lowest modes
# (600 to 1,050 rad/s over these speeds).
SPEEDS = np.arange(35e3, 70e3 + 1, 5e3) * RPM  # around our 150 V onset, 55.0 krpm
FREQUENCIES = np.geomspace(400.0, 1600.0, 6)
# ROSS interpolates the table (PCHIP) between nodes 5 krpm apart, where the log
# decrement crosses zero; in a trial the two onsets agreed to 0.5 %. The bound also
# covers the shaft's residual flexibility (shaft 1e4 times stiffer than the film).
ONSET_RTOL = 0.05


@pytest.fixture(scope="module")
def ross() -> Any:
    return pytest.importorskip("ross", minversion="3.0")


@pytest.fixture(scope="module")
def case() -> Any:
    return default_case().with_voltages(150.0)


@pytest.fixture(scope="module")
def table(case: Any) -> Any:
    return coefficient_table(case, SPEEDS, FREQUENCIES)


def rigid_rotor(ross: Any, bearings: list[Any], mass: float, Id: float, Ip: float) -> Any:
    """Two bearings 0.1 m apart at nodes 0 and 2, a disk at node 1 carrying (almost) all ``mass``.

    The shaft is 100 times stiffer than steel and nearly massless, so the rotor
    moves rigidly and each bearing carries half the mass in the cylindrical mode.
    """
    material = ross.Material(name="rigid_light", rho=1.0, E=2.1e13, Poisson=0.3)
    length, diameter = 0.05, 0.03
    shaft = [
        ross.ShaftElement(L=length, idl=0.0, odl=diameter, material=material, n=i) for i in range(2)
    ]
    shaft_mass = 2 * material.rho * math.pi * diameter**2 / 4 * length
    disk = ross.DiskElement(n=1, m=mass - shaft_mass, Id=Id, Ip=Ip)
    return ross.Rotor(shaft, [disk], bearings)


def modes(rotor: Any, speed: float) -> Any:
    """The two lowest modes with matched whirl (coefficients at each mode's own frequency)."""
    with warnings.catch_warnings():
        # ROSS starts the whirl iteration from synchronous coefficients, extrapolated.
        warnings.filterwarnings("ignore", message="Extrapolating")
        return rotor.run_modal(speed, num_modes=4, matched_whirl=True)


def first_forward(modal: Any) -> int:
    """Index of the lowest mode ROSS labels Forward."""
    forward = [k for k, d in enumerate(modal.whirl_direction()) if d == "Forward"]
    assert forward, f"no forward mode among {modal.whirl_direction()}"
    return min(forward, key=lambda k: modal.wd[k])


# --- coefficient tables (no ROSS needed) ---------------------------------------------


def test_table_has_our_coefficients_at_each_speed(case: Any, table: Any) -> None:
    assert bool(table["converged"].all())
    assert table["stiffness"].dims == ("speed", "frequency", "i", "j")
    k = 3
    st = solve_equilibrium(case, speed=float(SPEEDS[k]))
    assert st.eps_x == pytest.approx(float(table["eps_x"][k]), rel=1e-6)
    fc = force_coefficients(st, FREQUENCIES)
    np.testing.assert_allclose(table["stiffness"][k].values, fc.K, rtol=1e-5)
    np.testing.assert_allclose(table["damping"][k].values, fc.C, rtol=1e-5)


def test_table_over_ratios_has_frequency_per_speed(case: Any) -> None:
    tab = coefficient_table(case, SPEEDS[:2], ratios=[0.5, 1.0])
    assert tab["stiffness"].dims == ("speed", "ratio", "i", "j")
    np.testing.assert_allclose(tab["frequency"].values, np.outer(SPEEDS[:2], [0.5, 1.0]))
    with pytest.raises(InputError, match="not both"):
        coefficient_table(case, SPEEDS[:2], [100.0], ratios=[0.5])
    with pytest.raises(InputError, match="speeds"):
        coefficient_table(case, [-1.0, 100.0])


def test_missing_ross_says_how_to_install(table: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "ross", None)  # `import ross` raises ImportError
    with pytest.raises(InputError, match=r"pip install 'foilbearing\[ross\]'"):
        to_ross_bearing(table, 0)


# --- the exported element ---------------------------------------------------------------


def test_element_reproduces_table_at_nodes_in_ross_frame(ross: Any, table: Any) -> None:
    b = to_ross_bearing(table, 0, tag="fb")
    assert isinstance(b, ross.BearingElement) and b.tag == "fb"
    K, C = table["stiffness"].values, table["damping"].values
    for s, w in enumerate(SPEEDS):
        for f, we in enumerate(FREQUENCIES):
            expect_k = T @ K[s, f] @ T.T  # [[K_YY, -K_YX], [-K_XY, K_XX]]
            expect_c = T @ C[s, f] @ T.T
            np.testing.assert_allclose(b.K(frequency=we, speed=w)[:2, :2], expect_k, rtol=1e-9)
            np.testing.assert_allclose(b.C(frequency=we, speed=w)[:2, :2], expect_c, rtol=1e-9)
    # Vertical (y_ROSS) direct stiffness is our X (load) direction.
    assert b.K(frequency=FREQUENCIES[2], speed=SPEEDS[2])[1, 1] == K[2, 2, 0, 0]


def test_element_from_case_and_refusals(ross: Any, case: Any) -> None:
    b = to_ross_bearing(case, 3, speeds=SPEEDS[:5], frequencies=FREQUENCIES)
    assert b.n == 3 and np.array_equal(b.speed, SPEEDS[:5])
    with pytest.raises(InputError, match="absolute frequencies"):
        to_ross_bearing(coefficient_table(case, SPEEDS[:2], ratios=[0.5, 1.0]), 0)
    with pytest.raises(InputError, match="needs speeds"):
        to_ross_bearing(case, 0)


def test_ross_forward_is_its_spin_direction(ross: Any) -> None:
    # Gyroscopics stiffen the conical mode whose orbit ROSS calls forward (orbit
    # parameter κ > 0 at the bearing: from +x towards +y) and soften the other:
    # so ROSS's forward is its sense of spin.
    mass, k, Id = 1.8, 1e6, 0.01
    b = [ross.BearingElement(n=n, kxx=k, cxx=10.0) for n in (0, 2)]
    rotor = rigid_rotor(ross, b, mass=mass, Id=Id, Ip=2 * Id)
    cylindrical = math.sqrt(2 * k / mass)
    conical = math.sqrt(2 * k * 0.05**2 / Id)  # at rest

    m = rotor.run_modal(3000.0, num_modes=8)
    split = {}
    for i, wd in enumerate(m.wd):
        if abs(wd / cylindrical - 1) > 0.05:
            split[float(np.sign(m.shapes[i].orbits[0].kappa))] = float(wd)
    assert split[1.0] > 1.5 * conical
    assert split[-1.0] < conical / 1.5


def test_cross_coupling_towards_rotation_gives_forward_whirl_in_ross(ross: Any, table: Any) -> None:
    # Ours: K_XY = q, K_YX = -q pushes the journal from +X towards +Y (the
    # journal's rotation); with too little damping this whirl goes unstable.
    k0, q, c0 = 5e5, 3e5, 20.0
    syn = table.copy(deep=True)
    syn["stiffness"][:] = np.array([[k0, q], [-q, k0]])
    syn["damping"][:] = c0 * np.eye(2)
    b = [to_ross_bearing(syn, n) for n in (0, 2)]
    rotor = rigid_rotor(ross, b, mass=1.794, Id=2e-4, Ip=4e-4)
    m = rotor.run_modal(float(SPEEDS[4]), num_modes=4)
    unstable = [k for k in range(len(m.wd)) if m.log_dec[k] < 0]
    assert unstable, m.log_dec
    assert all(m.whirl_direction()[k] == "Forward" for k in unstable)


def test_onset_speed_matches_ours(ross: Any, case: Any, table: Any) -> None:
    bearings = [to_ross_bearing(table, n) for n in (0, 2)]
    # Total mass 2 × 0.897 kg: each bearing carries the case's rotor mass in the
    # cylindrical mode; a small Id keeps the conical mode light, fast and stable.
    rotor = rigid_rotor(ross, bearings, mass=2 * case.rotor.mass, Id=2e-4, Ip=4e-4)
    ours = onset_speed(case, list(SPEEDS))
    assert ours.onset_speed is not None

    def log_dec(speed: float) -> float:
        m = modes(rotor, speed)
        return float(m.log_dec[first_forward(m)])

    modal = [modes(rotor, float(w)) for w in SPEEDS]
    scan = np.array([m.log_dec[first_forward(m)] for m in modal])
    # At the table's speeds ROSS sees our coefficients exactly (interpolated only
    # in frequency), so it finds our whirl mode: same frequency, same log decrement.
    for m, w, ratio, dec in zip(modal, SPEEDS, ours.whirl_ratios, ours.log_decrement, strict=False):
        i = int(np.argmin(np.abs(m.wd - ratio * w)))
        assert m.wd[i] == pytest.approx(ratio * w, rel=2e-3)
        assert m.log_dec[i] == pytest.approx(dec, abs=0.01)
    k = int(np.argmax(scan < 0))
    assert k > 0 and scan[k - 1] > 0 and np.all(scan[k:] < 0)
    ross_onset = brentq(log_dec, float(SPEEDS[k - 1]), float(SPEEDS[k]), rtol=1e-6)
    assert ross_onset == pytest.approx(ours.onset_speed, rel=ONSET_RTOL)

    # The unstable mode above the onset: forward in ROSS, and the same orbit as ours.
    w = float(SPEEDS[k + 1])
    m = modes(rotor, w)
    i = first_forward(m)
    assert m.log_dec[i] < 0
    v_ross = m.evectors[[0, 1], i]  # (x, y) of node 0, a bearing
    st = solve_equilibrium(case, speed=w)
    ours_mode = _our_mode(st, case.rotor.mass, m.wd[i])
    mac = abs(np.vdot(T @ ours_mode, v_ross)) ** 2 / (
        np.vdot(ours_mode, ours_mode).real * np.vdot(v_ross, v_ross).real
    )
    assert mac > 0.99
    # Our eigenvector (X, Y) ∝ (1, −j·a) with a > 0 orbits from +X towards +Y.
    assert (np.conj(ours_mode[0]) * ours_mode[1]).imag < 0


def _our_mode(static: Any, mass: float, whirl: float) -> np.ndarray:
    """Eigenvector (X, Y) of m s² + C s + K with Im s > 0 nearest ``whirl``, coefficients there."""
    fc = force_coefficients(static, whirl)
    a = np.zeros((4, 4))
    a[:2, 2:] = np.eye(2)
    a[2:, :2] = -fc.K[0] / mass
    a[2:, 2:] = -fc.C[0] / mass
    vals, vecs = np.linalg.eig(a)
    j = int(np.argmin(np.where(vals.imag > 0, np.abs(vals.imag - whirl), np.inf)))
    return vecs[:2, j]
