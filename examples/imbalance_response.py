"""The imbalance orbit at constant speed, with the voltage changed while the rotor runs.

The C-GFB of the paper at 15 krpm with a small imbalance (0.5 g·mm): 0.25 s at 0 V,
then the three actuators are ramped to 150 V in 10 ms and the run goes on for 0.25 s.
The synchronous (1X) amplitude of each half is read from the orbit and set beside the
linear imbalance response of the bearing's force coefficients at that voltage,
``(K − m ω² + jω C) X = m u ω² (1, −j)``: the nonlinear orbit and the linearised
film are the same discretised equations, so at small amplitude they must agree.

    python examples/imbalance_response.py          (about 10 s)
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

import foilbearing as fb


def one_x_amplitude(t: np.ndarray, x: np.ndarray, phase: np.ndarray, t0: float, t1: float) -> float:
    """Amplitude of the 1X component of x between t0 and t1 (least squares on 1, cos φ, sin φ)."""
    k = (t >= t0) & (t <= t1)
    basis = np.column_stack([np.ones(k.sum()), np.cos(phase[k]), np.sin(phase[k])])
    coef = np.linalg.lstsq(basis, x[k], rcond=None)[0]
    return float(np.hypot(coef[1], coef[2]))


def linear_response(case: fb.Case, speed: float) -> tuple[float, float]:
    """|X|, |Y| of the linear imbalance response at ``speed`` (m), from K and C at 1X."""
    st = fb.solve_equilibrium(case, speed=speed)
    fc = fb.force_coefficients(st, [speed])
    m, u = case.rotor.mass, case.rotor.imbalance_radius
    a = fc.K[0] - m * speed**2 * np.eye(2) + 1j * speed * fc.C[0]
    x = np.linalg.solve(a, m * u * speed**2 * np.array([1.0, -1.0j]))
    return float(abs(x[0])), float(abs(x[1]))


def main() -> dict[str, float]:
    base = fb.default_case()
    case = replace(base, rotor=replace(base.rotor, imbalance=0.5e-6))  # 0.5 g·mm
    speed = 15_000 * fb.RPM
    run = fb.simulate(
        case,
        fb.constant_speed(speed, 0.51),
        fb.voltage_ramp(0.25, 0.26, 150.0),
        progress=False,
    )
    out: dict[str, float] = {}
    print(f"imbalance response at 15 krpm, 0.5 g·mm ({run.message})")
    for volts, (t0, t1) in ((0.0, (0.15, 0.25)), (150.0, (0.41, 0.51))):
        orbit = one_x_amplitude(run.time, run.e_x, run.phase, t0, t1)
        linear = linear_response(case.with_voltages(volts), speed)[0]
        out[f"orbit_1x_um_{volts:.0f}V"] = orbit * 1e6
        out[f"linear_1x_um_{volts:.0f}V"] = linear * 1e6
        print(
            f"  {volts:5.0f} V: 1X amplitude in X {orbit * 1e6:.4f} µm (orbit), "
            f"{linear * 1e6:.4f} µm (linear, K and C at 1X)"
        )
    return out


if __name__ == "__main__":
    main()
