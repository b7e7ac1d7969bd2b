"""The rotor's unbalance response and mode shapes (issue 32), on the rigid limit
(examples/rotor_rigid_symmetric.toml): a stiff, symmetric rotor whose bearings each carry
the single-bearing model's mass."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from foilbearing.errors import InputError
from foilbearing.rotor import load_rotor, mode_shapes, unbalance_response

RPM = math.pi / 30.0
EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "rotor_rigid_symmetric.toml"
#: 10 krpm lies near the rigid rotor's synchronous critical, where the film sets the
#: response; at 20 and 30 krpm the rotor's mass does (below the onset, 43.6 krpm).
SPEEDS = np.array([10e3, 20e3, 30e3]) * RPM
UNBALANCE = 1e-6  # kg·m: 1 g·mm, within balance grade G2.5 at 30 krpm on this 1.8 kg rotor


@pytest.fixture(scope="module")
def rigid() -> tuple[Any, Any]:
    """The example and its ROSS rotor over SPEEDS, each speed among its table's frequencies."""
    pytest.importorskip("ross", minversion="3.0")
    from foilbearing.rotor import ross_rotor
    from foilbearing.rotor.response import table_frequencies

    rotor = load_rotor(EXAMPLE)
    return rotor, ross_rotor(rotor, list(SPEEDS), list(table_frequencies(SPEEDS)))


def _single_bearing(case: Any, speed: float, mass: float, frequency: float) -> Any:
    """The rigid journal's complex (X, Y), m, on one bearing under half the unbalance force,
    the film's K, C taken at ``frequency`` (rad/s): (K + iΩC − mΩ² I) x = (uΩ²/2)(1, −i), the
    force along +X at t = 0 and turning from +X towards +Y with the rotor."""
    from foilbearing.coefficients import force_coefficients
    from foilbearing.static import solve_equilibrium

    fc = force_coefficients(solve_equilibrium(case, speed=speed), frequency)
    K, C = fc.K[0], fc.C[0]
    force = 0.5 * UNBALANCE * speed**2 * np.array([1.0, -1.0j])
    return np.linalg.solve(K + 1j * speed * C - mass * speed**2 * np.eye(2), force)


@pytest.mark.slow
def test_unbalance_response_at_a_bearing_is_the_single_bearing_response(
    rigid: tuple[Any, Any],
) -> None:
    """Two independent methods: ROSS's beam model of the whole rotor on our tables, and one
    rigid journal on one bearing with our coefficients at (Ω, Ω). An unbalance at the mid
    disk of a symmetric rotor loads each bearing with half its force and excites no tilt,
    so a rigid shaft moves each journal as one bearing moves its share of the mass.

    The example's shaft is stiff, not rigid (1.3e9 N/m at mid-span against the film's
    ~1e6 N/m), and near the synchronous critical (10 krpm) the response magnifies a
    change of stiffness about fourfold: the journals agree within 1 % (measured 0.42 %, 0.10 %,
    0.28 % at 10, 20, 30 krpm). On the same bearing tables, a shaft 1000 times stiffer cuts
    the difference 1000-fold (to 4e-6 measured; within 1e-5): it is the shaft's bending
    alone. Near the critical, the film's coefficients taken at half the speed instead of
    the speed would move the response by 19 %, so ROSS does take them at whirl frequency =
    speed."""
    from foilbearing.rotor.linear import ross_shaft

    rotor, model = rigid
    response = unbalance_response(rotor, SPEEDS, [(1, UNBALANCE, 0.0)], model=model)
    assert response.nodes == (0, 1, 2)
    assert response.labels == ("bearing A", "disk at node 1", "bearing B")
    stiff = replace(rotor, material=replace(rotor.material, youngs_modulus=211e12))
    rigid_response = unbalance_response(
        stiff, SPEEDS, [(1, UNBALANCE, 0.0)], model=ross_shaft(stiff, model.bearing_elements)
    )

    case = rotor.loaded_cases()[0]
    mass = case.operation.load / rotor.gravity
    assert mass == pytest.approx(0.897, abs=5e-4)
    for k, speed in enumerate(SPEEDS):
        ours = _single_bearing(case, speed, mass, speed)
        for j in (0, 2):
            for result, tol in ((response, 1e-2), (rigid_response, 1e-5)):
                error = np.linalg.norm(result.displacement[k, j] - ours) / np.linalg.norm(ours)
                assert error < tol, (speed / RPM, j, error, tol)
    wrong = _single_bearing(case, SPEEDS[0], mass, 0.5 * SPEEDS[0])
    ours = _single_bearing(case, SPEEDS[0], mass, SPEEDS[0])
    assert np.linalg.norm(wrong - ours) / np.linalg.norm(ours) > 0.1

    # Above the critical the journal lags the unbalance by more than 90°, tending to 180°:
    # the centre of mass stays put.
    amp, phase = response.amplitude_um(), response.phase_deg()
    assert 90.0 < phase[0, 0] < phase[1, 0] < phase[2, 0] < 180.0
    assert amp[0, 0] > 2 * amp[2, 0]
    row = response.headline()[1]
    assert row["label"] == "disk at node 1" and row["speed_rpm"] == pytest.approx(10e3)
    assert row["amplitude_um"] == pytest.approx(amp[0, 1])

    # Linear in the unbalance, and an unbalance turned by 90° turns the orbit with it.
    turned = unbalance_response(rotor, SPEEDS, [(1, 2 * UNBALANCE, 0.5 * math.pi)], model=model)
    assert np.allclose(turned.amplitude_um(), 2 * amp, rtol=1e-9)
    assert np.allclose(turned.phase_deg(), phase, atol=1e-6)


@pytest.mark.slow
def test_modes_of_the_symmetric_rotor_are_cylindrical_or_conical(
    rigid: tuple[Any, Any], tmp_path: Path
) -> None:
    """A symmetric rotor's modes are symmetric or antisymmetric about its middle. On the
    stiff example the lowest forward mode translates it (both journals and the disk alike,
    within 2 %; measured 0.02 %), and two of the four tilt it about the disk, which stays
    still (the conical modes: the journals' signed amplitudes opposite)."""
    from foilbearing.output.plots.rotor import plot_mode_shapes, plot_unbalance_response

    rotor, model = rigid
    shapes = mode_shapes(rotor, float(SPEEDS[-1]), model=model)
    a = shapes.amplitude()  # (modes, nodes): bearing A, disk, bearing B
    assert np.all(np.diff(shapes.frequency) > 0)
    cylindrical = np.abs(a[:, 0] - a[:, 2]) < 0.02
    conical = np.abs(a[:, 0] + a[:, 2]) < 0.02
    assert np.all(cylindrical ^ conical), a
    first = int(np.flatnonzero(shapes.forward)[0])
    assert cylindrical[first]
    assert a[first] == pytest.approx([1.0, 1.0, 1.0], abs=0.02)
    assert conical.sum() == 2
    assert np.all(np.abs(a[conical, 1]) < 0.02)
    assert np.all(np.abs(np.abs(a[conical][:, [0, 2]]) - 1.0) < 0.02)

    fig = plot_mode_shapes(shapes, rotor.title)
    fig.savefig(tmp_path / "modes.png")
    response = unbalance_response(rotor, SPEEDS, [(1, UNBALANCE, 0.0)], model=model)
    plot_unbalance_response(response).savefig(tmp_path / "unbalance.png")
    for name in ("modes.png", "unbalance.png"):
        assert (tmp_path / name).stat().st_size > 10_000


def test_an_unbalance_off_the_shaft_is_one_line_naming_the_node_and_range() -> None:
    rotor = load_rotor(EXAMPLE)
    with pytest.raises(
        InputError, match=r"rotor_rigid_symmetric.toml: unbalances\[1\].node = 5: the shaft "
        r"has nodes 0 to 2$"
    ):  # fmt: skip
        unbalance_response(rotor, SPEEDS, [(1, UNBALANCE, 0.0), (5, UNBALANCE, 0.0)])
    with pytest.raises(InputError) as error:
        unbalance_response(rotor, SPEEDS, [(3, UNBALANCE, 0.0)])
    assert "\n" not in str(error.value)
    with pytest.raises(InputError, match=r"unbalances\[0\].node = -1"):
        unbalance_response(rotor, SPEEDS, [(-1, UNBALANCE, 0.0)])
    with pytest.raises(InputError, match=r"magnitude >= 0"):
        unbalance_response(rotor, SPEEDS, [(1, -UNBALANCE, 0.0)])
    with pytest.raises(InputError, match=r"increasing"):
        unbalance_response(rotor, SPEEDS[::-1], [(1, UNBALANCE, 0.0)])
