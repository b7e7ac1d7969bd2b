"""The random force of a case's ``[disturbance]``: its RMS, its band, and its seed."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.signal import welch

from foilbearing.case import Disturbance, default_case
from foilbearing.constants import RPM
from foilbearing.control import constant_speed
from foilbearing.orbit import OrbitSimulation
from foilbearing.orbit.disturbance import DisturbanceForce

FS = 2000.0  # Hz, four samples a period of the band's top


def _signal(d: Disturbance, duration: float = 30.0) -> np.ndarray:
    """(F_X, F_Y) sampled at FS over ``duration`` s, N, shape (2, n)."""
    force = DisturbanceForce(d)
    return np.array([force(t) for t in np.arange(0.0, duration, 1.0 / FS)]).T


def test_force_has_its_rms_in_each_direction_and_a_flat_band() -> None:
    d = Disturbance(force_rms=0.01, min_frequency=5.0, max_frequency=500.0, seed=1)
    f = _signal(d)
    # Distinct tones are orthogonal over a long time: the RMS is F_rms (the cross terms
    # of 256 tones over 30 s leave about 1 %).
    assert np.sqrt(np.mean(f**2, axis=1)) == pytest.approx([0.01, 0.01], rel=0.03)
    freq, psd = welch(f, fs=FS, nperseg=4096)
    df = freq[1] - freq[0]
    band = (freq >= 5.0) & (freq <= 500.0)
    power = psd.sum(axis=1) * df
    assert np.all(psd[:, band].sum(axis=1) * df > 0.99 * power)  # the band holds the power
    # ... spread evenly: the level of a flat spectrum, F²/(f_max − f_min), within the
    # scatter of 256 random tones over 496 Hz (each 50 Hz holds about 26 of them).
    level = 0.01**2 / 495.0
    for lo in range(50, 450, 50):
        sel = (freq >= lo) & (freq < lo + 50)
        assert psd[:, sel].mean(axis=1) == pytest.approx([level, level], rel=0.4)


def test_the_seed_sets_the_force() -> None:
    d = Disturbance(force_rms=0.05, min_frequency=10.0, max_frequency=200.0, seed=7)
    again = DisturbanceForce(d)
    other = DisturbanceForce(Disturbance(0.05, 10.0, 200.0, seed=8))
    for t in (0.0, 0.123, 4.56):
        assert np.array_equal(DisturbanceForce(d)(t), again(t))  # the same in every run
        assert not np.allclose(other(t), again(t))
    assert np.all((again.frequencies >= 10.0) & (again.frequencies <= 200.0))


def test_orbit_inputs_carry_the_force_per_unit_mass_and_clearance() -> None:
    case = default_case()
    assert case.disturbance is not None and case.disturbance.force_rms == pytest.approx(0.01)
    sim = OrbitSimulation(case, constant_speed(20e3 * RPM, 0.1))
    volts = sim.volts(0.0)
    quiet = OrbitSimulation(replace(case, disturbance=None), constant_speed(20e3 * RPM, 0.1))
    m, c = case.rotor.mass, case.bearing.clearance
    force = DisturbanceForce(case.disturbance)
    for t in (0.01, 0.0371):
        extra = sim.inputs(t, volts).force - quiet.inputs(t, volts).force
        np.testing.assert_allclose(extra * m * c, force(t), rtol=1e-12, atol=1e-15)
    # The imbalance-free inputs (the load alone) carry no disturbance either.
    np.testing.assert_array_equal(
        sim.inputs(0.01, volts, imbalance=False).force,
        quiet.inputs(0.01, volts, imbalance=False).force,
    )


@pytest.mark.parametrize("tones", [1, 7, 8, 13, 128, 129, 256, 300, 1000])
def test_the_compiled_force_is_numpys_sum_to_the_bit(tones: int) -> None:
    """The force a time step evaluates (compiled) is the NumPy form a Σ cos(ω t + φ) to the
    last bit: the runs before it was compiled are unchanged. Tone counts on each side of
    the pairwise summation's block sizes (8 and 128) and past two halvings."""
    force = DisturbanceForce(Disturbance(0.01, 5.0, 500.0, seed=tones, tones=tones))
    omega = 2.0 * np.pi * force.frequencies
    for t in np.random.default_rng(tones).uniform(0.0, 20.0, 200):
        numpy_form = force.amplitude * np.cos(omega * t + force.phases).sum(axis=1)
        assert np.array_equal(force(t), numpy_form)
