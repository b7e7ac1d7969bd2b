"""Rotors on foil bearings (issue 32): the rotor file, the weight each bearing carries, and
the rigid limit of the linear analysis on ROSS against our single-bearing ``stability``."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from foilbearing.errors import InputError
from foilbearing.rotor import load_rotor, rotor_from_dict

RPM = math.pi / 30.0
EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "rotor_rigid_symmetric.toml"


def _rotor(**changes):  # type: ignore[no-untyped-def]
    data = {
        "title": "offset disk",
        "material": {"density": "7850 kg/m**3", "youngs_modulus": "211 GPa", "poisson_ratio": 0.29},
        "shaft": {"lengths": ["40 mm", "60 mm", "50 mm"], "outer_diameters": ["30 mm"] * 3},
        "disks": [
            {"node": 1, "mass": "2 kg", "polar_inertia": "1e-3 kg*m**2",
             "diametral_inertia": "5e-4 kg*m**2"},
        ],
        "bearings": [{"node": 0}, {"node": 2}],
    }  # fmt: skip
    data.update(changes)
    return rotor_from_dict(data, source="rotor.toml")


def test_two_bearings_carry_the_weight_by_the_balance_of_moments() -> None:
    # A disk 40 mm from bearing A on a 100 mm span, a shaft overhanging 50 mm past B: the
    # reactions balance the forces and the moments about either bearing, so an offset disk
    # loads the bearings unequally.
    rotor = _rotor()
    at, w = rotor.weights()
    ra, rb = rotor.bearing_loads()
    assert ra + rb == pytest.approx(w.sum(), rel=1e-12)
    assert rb * 0.1 == pytest.approx(np.sum(w * at), rel=1e-12)  # moments about A
    disk = 2.0 * rotor.gravity
    assert ra > disk * 0.6 - 1e-9 and rb > disk * 0.4  # the disk's share by the lever rule
    cases = rotor.loaded_cases()
    assert [c.operation.load for c in cases] == [ra, rb]
    assert rotor.mass == pytest.approx(2.0 + 7850 * math.pi / 4 * 0.03**2 * 0.15, rel=1e-12)


def test_bad_rotor_input_is_one_line_naming_the_file_and_field(tmp_path: Path) -> None:
    with pytest.raises(
        InputError, match=r"rotor.toml: bearings\[1\].node = 7: the shaft has nodes 0 to 3"
    ):
        _rotor(bearings=[{"node": 0}, {"node": 7}])
    with pytest.raises(InputError, match=r"unknown field 'colour' in \[disks\[0\]\]"):
        _rotor(disks=[{"node": 1, "mass": "2 kg", "polar_inertia": "0 kg*m**2",
                       "diametral_inertia": "0 kg*m**2", "colour": "red"}])  # fmt: skip
    with pytest.raises(InputError, match=r"material.youngs_modulus"):
        _rotor(material={"density": "7850 kg/m**3", "youngs_modulus": "211 kg",
                         "poisson_ratio": 0.29})  # fmt: skip
    with pytest.raises(InputError, match=r"case file not found"):
        rotor_from_dict({**_rotor_data_min(), "bearings": [{"node": 0, "case": "nope.toml"}]},
                        source="rotor.toml", folder=tmp_path)  # fmt: skip
    with pytest.raises(InputError, match=r"centre of mass lies outside the bearings"):
        # all the weight beyond bearing B: bearing A would have to pull the shaft down
        _rotor(bearings=[{"node": 0}, {"node": 1}],
               disks=[{"node": 3, "mass": "5 kg", "polar_inertia": "0 kg*m**2",
                       "diametral_inertia": "0 kg*m**2"}]).loaded_cases()  # fmt: skip
    with pytest.raises(InputError, match=r"rotor file not found"):
        load_rotor(tmp_path / "missing.toml")


def _rotor_data_min() -> dict:
    return {
        "material": {"density": "7850 kg/m**3", "youngs_modulus": "211 GPa", "poisson_ratio": 0.3},
        "shaft": {"lengths": ["50 mm"], "outer_diameters": ["30 mm"]},
    }


@pytest.mark.slow
def test_rigid_symmetric_rotor_is_the_single_bearing_model() -> None:
    """The rigid limit (examples/rotor_rigid_symmetric.toml): a stiff, symmetric rotor on two
    copies of the built-in bearing at 0 V, each carrying the single-bearing model's mass.

    - Its cylindrical mode's onset and whirl frequency, from ROSS with matched whirl on
      tables 0.5 krpm apart, equal our single-bearing ``stability`` within 1 % (measured:
      0.1 %; the rest is ROSS's interpolation between the table's speeds).
    - The forward conical mode whirls at the frequency of the rigid body's tilt,
      Id ω² − Ip Ω ω − k_θ = 0, with k_θ = 2 k a² from the cylindrical mode's stiffness
      k = M ω_c²/2: within 3 % (the film is stiffer at the conical mode's frequency than at
      the cylindrical one's, and the formula leaves out its damping).
    """
    pytest.importorskip("ross", minversion="3.0")
    from foilbearing.rotor import rotor_onset
    from foilbearing.stability import onset_speed

    rotor = load_rotor(EXAMPLE)
    speeds = list(np.arange(40e3, 47.01e3, 500.0) * RPM)
    onset, whirl, modes = rotor_onset(rotor, speeds)
    ours = onset_speed(rotor.loaded_cases()[0], speeds)
    assert onset is not None and ours.onset_speed is not None and ours.whirl_frequency is not None
    assert onset == pytest.approx(ours.onset_speed, rel=0.01)
    assert whirl == pytest.approx(ours.whirl_frequency / (2 * math.pi), rel=0.01)

    # At the lowest speed, the cylindrical forward whirl is the second mode of the four and
    # the forward conical mode, stiffened by the gyroscopic moment, the highest.
    k = 0
    assert modes.forward[k, 1]
    cyl, con = (2 * math.pi * modes.frequency[k, i] for i in (1, -1))
    shaft = rotor.shaft[0]
    m_shaft = 2 * shaft.mass(rotor.material)
    r = shaft.outer_diameter / 2
    disk = rotor.disks[0]
    span = 2 * shaft.length
    i_d = disk.diametral_inertia + m_shaft * (span**2 / 12 + r**2 / 4)
    i_p = disk.polar_inertia + m_shaft * r**2 / 2
    k_film = rotor.mass * cyl**2 / 2
    k_tilt = 2 * k_film * (span / 2) ** 2
    g = i_p * modes.speeds[k]
    tilt = (g + math.sqrt(g * g + 4 * i_d * k_tilt)) / (2 * i_d)
    assert con == pytest.approx(tilt, rel=0.03)


@pytest.mark.slow
def test_rotor_command_prints_modes_onset_and_campbell(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    # `foilbearing rotor ... --json`: one JSON object on stdout (ROSS's import noise kept
    # off it), each mode with its speed, frequency, log decrement and whirl, and the onset
    # read on tables 2 krpm apart: within 1 % of our stability (0.5 % measured).
    import json

    from foilbearing.cli.main import main
    from foilbearing.stability import onset_speed

    pytest.importorskip("ross", minversion="3.0")
    argv = ["rotor", str(EXAMPLE), "--speed-range", "40000rpm:46000rpm:2000rpm"]
    assert main([*argv, "--json", "--plot", str(tmp_path), "--unbalance", "1:1g*mm"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert {"speed_rpm", "frequency_Hz", "log_decrement", "whirl"} <= set(out["modes"][0])
    assert len(out["modes"]) == 4 * 4
    rotor = load_rotor(EXAMPLE)
    ours = onset_speed(rotor.loaded_cases()[0], list(np.arange(40e3, 46.01e3, 2e3) * RPM))
    assert out["onset_speed_rpm"] == pytest.approx(ours.onset_speed / RPM, rel=0.01)
    assert sum(b["load_N"] for b in out["bearings"]) == pytest.approx(rotor.mass * 9.80665)
    assert (tmp_path / "campbell.png").stat().st_size > 10_000
    for name in ("mode_shapes.png", "unbalance_response.png"):
        assert (tmp_path / name).stat().st_size > 10_000
    # the unbalance response at each speed and node: both bearings of the symmetric rotor
    # move alike under an unbalance at its middle
    response = out["unbalance_response"]
    assert {"speed_rpm", "node", "amplitude_um", "phase_deg"} <= set(response[0])
    by = {(r["speed_rpm"], r["node"]): r["amplitude_um"] for r in response}
    for speed in {r["speed_rpm"] for r in response}:
        assert by[(speed, 0)] == pytest.approx(by[(speed, 2)], rel=1e-6)
    assert main(["rotor", str(tmp_path / "none.toml")]) == 2
    assert "rotor file not found" in capsys.readouterr().err


@pytest.mark.slow
def test_the_reduced_rotor_converges_on_the_full_model_with_its_modes() -> None:
    """Modal convergence (examples/rotor_two_disk.toml, a flexible rotor on two C-GFBs at
    150 V): the Craig-Bampton rotor, the journals and N shaft modes with the journals held,
    on the same ROSS bearing elements and matched whirl, approaches ROSS's full beam model
    as N grows. Its onset error falls from over 0.5 % with the static modes alone (1.3 %
    measured) to under 0.05 % with 8 modes (0.03 %) and under 0.01 % with 16 (0.002 %).

    On the stiff rigid example the static modes alone are the rigid body (translation and
    tilt): their log decrements equal the full model's within 1e-4 (1.5e-5 measured with 4
    shaft modes; the static modes alone leave the shaft's 4 kHz bending out of the
    conical mode)."""
    pytest.importorskip("ross", minversion="3.0")
    from foilbearing.rotor import ross_rotor, rotor_modes
    from foilbearing.rotor.linear import modes_at, refine_onset
    from foilbearing.rotor.reduced import reduced_onset

    rotor = load_rotor(EXAMPLE.with_name("rotor_two_disk.toml"))
    speeds = list(np.arange(42e3, 50.01e3, 2e3) * RPM)
    model = ross_rotor(rotor, speeds)
    full = rotor_modes(rotor, speeds, model=model)
    onset, whirl = refine_onset(full, lambda w: modes_at(model, w, 4))
    assert onset is not None and whirl is not None
    nodes = [b.node for b in rotor.bearings]
    error = {}
    for n in (0, 4, 8, 16):
        reduced, reduced_whirl, _ = reduced_onset(model, nodes, speeds, n_modes=n)
        assert reduced is not None and reduced_whirl is not None
        error[n] = abs(reduced / onset - 1.0)
    assert error[0] > 5e-3
    assert error[0] > error[4] > error[8] > error[16]
    assert error[8] < 5e-4 and error[16] < 1e-4
    assert reduced_whirl == pytest.approx(whirl, rel=1e-4)

    rigid = load_rotor(EXAMPLE)
    at = list(np.array([40e3, 44e3]) * RPM)
    model = ross_rotor(rigid, at)
    full = rotor_modes(rigid, at, model=model)
    from foilbearing.rotor.reduced import reduced_modes

    reduced = reduced_modes(model, [0, 2], at, n_modes=4)
    assert np.allclose(reduced.log_decrement, full.log_decrement, atol=1e-4)
    assert np.allclose(reduced.frequency, full.frequency, rtol=1e-3)


@pytest.mark.slow
def test_study_of_a_rotor_file_writes_its_report(tmp_path: Path, write_case, capsys) -> None:  # type: ignore[no-untyped-def]
    # `foilbearing study ROTOR.toml`: a rotor file in place of a bearing case runs the
    # rotor's stage (docs/rotor-format.md): the bearings' loads balance the rotor's weight,
    # the reduced rotor's error falls with its shaft modes, and report.html has the section
    # with its Campbell diagram, mode shapes and unbalance response.
    import json

    from foilbearing.cli.main import main

    case = write_case("coarse", n_theta=32, n_z=4)
    text = EXAMPLE.with_name("rotor_two_disk.toml").read_text(encoding="utf-8")
    rotor_file = tmp_path / "rotor.toml"
    rotor_file.write_text(text.replace('case = "default"', f'case = "{case.as_posix()}"'))
    out = tmp_path / "out"
    assert main(["study", str(rotor_file), "--out", str(out), "--orbits", "none", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)["rotor"]
    rotor = load_rotor(rotor_file)
    loads = sum(b["load_N"] for b in summary["bearings"])
    assert loads == pytest.approx(rotor.mass * rotor.gravity, rel=1e-12)
    errors = [abs(r["error_percent"]) for r in summary["reduction"]]
    assert errors[0] > errors[-1] and errors[-1] < 0.01
    assert 30e3 < summary["onset_speed_rpm"] < 60e3
    html = (out / "report.html").read_text(encoding="utf-8")
    assert "A rotor on two foil bearings" in html and "data:image/png;base64" in html
    for name in ("campbell.png", "mode_shapes.png", "unbalance_response.png"):
        assert (out / name).stat().st_size > 10_000
    # 1 g·mm at the heavier disk: a response of µm at most, inside the clearance
    c = rotor.bearings[0].case.bearing.clearance
    assert 0.0 < summary["unbalance_response"]["peak_amplitude_um"] < 1e6 * c
