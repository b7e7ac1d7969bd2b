"""Linear stability of a rigid rotor on the bearing: whirl eigenvalues and onset speed.

The rotor mass carried by the bearing, m, moves in X and Y under the film's
linearised force: ``m s² + C(ω_e) s + K(ω_e) = 0`` (2 × 2). The coefficients
depend on the whirl frequency they are taken at, so each eigenvalue is iterated
to consistency, ``ω_e = Im s`` (docs/model.md §4). The least stable whirl
mode decides stability; its logarithmic decrement ``δ = −2π Re s / Im s``
changes sign at the onset speed of instability, found by bracketing on a speed
grid and refining with Brent's method.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import brentq

from foilbearing.analysis.coefficients import force_coefficients
from foilbearing.analysis.equilibrium import StaticResult
from foilbearing.bearing_system import Scales
from foilbearing.bearing_system.verbs import BearingSystem
from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import InputError, SolverError
from foilbearing.film import FilmModel
from foilbearing.output.display import Summarised
from foilbearing.reynolds import Workspace
from foilbearing.units import as_si, as_si_array

__all__ = [
    "OnsetResult",
    "WhirlMode",
    "case_at_voltage",
    "onset_at_voltage",
    "onset_speed",
    "onsets_per_voltage",
    "stability_map",
    "whirl_mode",
]


@dataclass(frozen=True)
class WhirlMode:
    """The least stable whirl mode at one speed.

    Attributes
    ----------
    speed
        Rotor speed ω, rad/s.
    eigenvalue
        s = σ + jω_d, 1/s (ω_d > 0).
    log_decrement
        δ = −2πσ/ω_d (> 0 stable).
    whirl_ratio
        ω_d/ω.
    K, C
        Coefficients at ω_e = ω_d (N/m, N·s/m).
    iterations
        Frequency iterations to consistency.
    """

    speed: float
    eigenvalue: complex
    log_decrement: float
    whirl_ratio: float
    K: np.ndarray
    C: np.ndarray
    iterations: int
    static: StaticResult

    @property
    def whirl_frequency(self) -> float:
        """ω_d in rad/s."""
        return self.eigenvalue.imag


def _whirl_eigenvalues(mass: float, K: np.ndarray, C: np.ndarray) -> np.ndarray:
    """Eigenvalues with Im > 0 of m s² + C s + K = 0 (the whirl modes), 1/s."""
    a = np.zeros((4, 4))
    a[0:2, 2:4] = np.eye(2)
    a[2:4, 0:2] = -K / mass
    a[2:4, 2:4] = -C / mass
    eig = np.linalg.eigvals(a)
    return eig[eig.imag > 0.0]


def _track(
    static: StaticResult, mass: float, s0: complex, ws: Workspace, tol: float, max_iter: int
) -> tuple[complex, Any, int]:
    """Follow one whirl mode until its eigenvalue and the coefficients' frequency agree."""
    s, w_e, fc = s0, abs(s0.imag), None
    it = 0
    for it in range(1, max_iter + 1):
        fc = force_coefficients(static, w_e, workspace=ws)
        eig = _whirl_eigenvalues(mass, fc.K[0], fc.C[0])
        if eig.size == 0:
            break
        s = complex(eig[np.argmin(np.abs(eig - s))])  # the same mode: the nearest eigenvalue
        new = s.imag
        if abs(new - w_e) <= tol * max(w_e, 1e-12):
            break
        w_e = 0.5 * (w_e + new) if it > 10 else new  # damp a slow two-cycle
    return s, fc, it


def whirl_mode(
    static: StaticResult,
    mass: Any,
    *,
    workspace: Workspace | None = None,
    tol: float = 1e-6,
    max_iter: int = 40,
) -> WhirlMode:
    """Least stable whirl mode at a static point, with the coefficients at its own frequency.

    The eigenvalues at half-frequency whirl seed each mode; each is followed to
    consistency (coefficients at its own whirl frequency) and the one with the
    smallest logarithmic decrement is returned. ``mass``: the rotor mass on the
    bearing, kg as a float, or a quantity (``"0.9 kg"``).
    """
    mass = as_si(mass, "mass", field="mass")
    omega = static.speed
    ws = workspace or Workspace(static.model.grid)
    fc0 = force_coefficients(static, 0.5 * omega, workspace=ws)
    seeds = _whirl_eigenvalues(mass, fc0.K[0], fc0.C[0])
    if seeds.size == 0:
        seeds = np.array([complex(0.0, 0.5 * omega)])
    best: tuple[float, complex, Any, int] | None = None
    for seed in seeds:
        s, fc, it = _track(static, mass, complex(seed), ws, tol, max_iter)
        if fc is None or s.imag <= 0:
            continue
        dec = -2.0 * math.pi * s.real / s.imag
        if best is None or dec < best[0]:
            best = (dec, s, fc, it)
    if best is None:
        raise SolverError(
            f"no whirl mode found at {omega / RPM:.0f} rpm (over-damped rotor, or the "
            "eigenvalue iteration did not converge from any seed): try another speed"
        )
    dec, s, fc, it = best
    return WhirlMode(
        speed=omega,
        eigenvalue=s,
        log_decrement=dec,
        whirl_ratio=s.imag / omega,
        K=fc.K[0],
        C=fc.C[0],
        iterations=it,
        static=static,
    )


@dataclass(frozen=True, repr=False)
class OnsetResult(Summarised):
    """Onset speed of instability for one bearing configuration.

    Printed, it shows the onset, the whirl there and the scan in a few lines (a table
    in a notebook); :meth:`plot` draws the log decrement against speed.
    """

    onset_speed: float | None  # rad/s, None if stable over the range
    whirl_ratio: float | None
    whirl_frequency: float | None  # rad/s
    speeds: np.ndarray  # rad/s, the scan
    log_decrement: np.ndarray
    whirl_ratios: np.ndarray
    message: str

    def headline(self) -> dict[str, Any]:
        """Unit-named keys (``--json``)."""
        onset = self.onset_speed
        return {
            "onset_speed_rpm": None if onset is None else onset / RPM,
            "whirl_frequency_Hz": (
                None if self.whirl_frequency is None else self.whirl_frequency / (2 * math.pi)
            ),
            "whirl_ratio": self.whirl_ratio,
            "message": self.message,
        }

    def _summary(self) -> tuple[str, dict[str, Any], None]:
        scan = {
            "scan_speeds_rpm": [self.speeds[0] / RPM, self.speeds[-1] / RPM],
            "scan_points": int(self.speeds.size),
        }
        return "Linear stability onset (least stable whirl mode)", self.headline() | scan, None

    def plot(self) -> Any:
        """Log decrement of the least stable whirl mode against speed, with the onset
        (:func:`~foilbearing.output.plots.bearing.plot_log_decrement`); returns the Figure."""
        from foilbearing.output.plots.bearing import plot_log_decrement

        modes = [
            {"speed_rpm": w / RPM, "log_decrement": float(d)}
            for w, d in zip(self.speeds, self.log_decrement, strict=True)
            if np.isfinite(d)
        ]
        onset = self.onset_speed
        return plot_log_decrement(modes, None if onset is None else onset / RPM)


class _Scanner:
    """Equilibria and whirl modes of one bearing system along increasing speed, each
    started from the last (the system, and so its film model, built once per case)."""

    def __init__(self, system: BearingSystem) -> None:
        self.system = system
        self.ws = Workspace(system.grid)
        self.start: tuple[float, float, Any] | None = None

    def mode(self, speed: float) -> WhirlMode:
        st = self.system.equilibrium(speed, start=self.start)
        if not st.converged:
            st = self.system.equilibrium(speed)
        if not st.converged:
            raise SolverError(
                f"no static equilibrium at {speed / RPM:.0f} rpm ({st.message}); the linear "
                "stability analysis needs one: narrow the speed range"
            )
        self.start = (st.eps_x, st.eps_y, st.P)
        return whirl_mode(st, self.system.case.rotor.mass, workspace=self.ws)


def onset_speed(
    case: Case,
    speeds: Sequence[float] | None = None,
    *,
    model: FilmModel | None = None,
    progress: Callable[[str], None] | None = None,
    rel_tol: float = 1e-4,
) -> OnsetResult:
    """Lowest speed at which the least stable whirl mode's log decrement becomes negative.

    Parameters
    ----------
    case
        Bearing case (rotor mass per bearing from ``[rotor]``).
    speeds
        Increasing scan speeds, rad/s, or quantities (``["20 krpm", "40 krpm"]``; default 5
        to 150 krpm in 5 krpm steps).
    model
        Film model of the case (built if omitted); the scan runs on the
        :class:`~foilbearing.bearing_system.BearingSystem` of the case and this model,
        built once and reused at every speed.
    rel_tol
        Brent's tolerance on the onset, relative to the bracket's upper speed.
    """
    if speeds is None:
        top = case.operation.max_speed * (1 + 1e-12)
        speeds = [rpm * RPM for rpm in range(5_000, 150_001, 5_000) if rpm * RPM <= top]
    speeds_arr = np.sort(as_si_array(speeds, "speed", field="speeds"))
    if speeds_arr.size < 2 or speeds_arr[0] <= 0:
        raise InputError("the onset search needs at least two speeds > 0")
    case.check_speeds(speeds_arr, "onset scan")
    system = (
        BearingSystem.from_case(case)
        if model is None
        else BearingSystem(case, model, Scales.from_case(case))
    )
    scan = _Scanner(system)
    dec, ratio = [], []
    prev_mode = None
    for k, w in enumerate(speeds_arr):
        mode = scan.mode(float(w))
        dec.append(mode.log_decrement)
        ratio.append(mode.whirl_ratio)
        if progress is not None:
            progress(
                f"{w / RPM:8.0f} rpm: log dec {mode.log_decrement:+.4f}, "
                f"whirl ratio {mode.whirl_ratio:.3f}"
            )
        if mode.log_decrement < 0.0:
            if k == 0:
                return OnsetResult(
                    float(w),
                    mode.whirl_ratio,
                    mode.whirl_frequency,
                    speeds_arr[:1],
                    np.array(dec),
                    np.array(ratio),
                    "unstable already at the lowest speed of the scan",
                )
            assert prev_mode is not None
            lo, hi = float(speeds_arr[k - 1]), float(w)
            # Brent evaluates the bracket's ends first and the root last: keep the modes;
            # each new equilibrium starts from the one nearest in speed.
            modes = {lo: prev_mode, hi: mode}

            def f(x: float, modes: dict[float, WhirlMode] = modes) -> float:
                if x not in modes:
                    near = modes[min(modes, key=lambda s: abs(s - x))].static
                    scan.start = (near.eps_x, near.eps_y, near.P)
                    modes[x] = scan.mode(x)
                return modes[x].log_decrement

            onset = brentq(f, lo, hi, xtol=rel_tol * hi, rtol=1e-6)
            f(onset)
            at = modes[onset]
            return OnsetResult(
                onset,
                at.whirl_ratio,
                at.whirl_frequency,
                speeds_arr[: k + 1],
                np.array(dec),
                np.array(ratio),
                f"onset between {lo / RPM:.0f} and {hi / RPM:.0f} rpm, refined by Brent's method",
            )
        prev_mode = mode
    return OnsetResult(
        None,
        None,
        None,
        speeds_arr,
        np.array(dec),
        np.array(ratio),
        f"stable up to {speeds_arr[-1] / RPM:.0f} rpm",
    )


def case_at_voltage(case: Case, volt: float, shimmed: bool = False) -> Case:
    """``case`` with every actuator at ``volt`` (V), or its shimmed twin there (shims of
    that voltage's base preload)."""
    at_volt = case.with_voltages(float(volt))
    return at_volt.shimmed() if shimmed else at_volt


def onset_at_voltage(
    case: Case, volt: float, speeds: Sequence[float], shimmed: bool = False
) -> OnsetResult:
    """The onset of :func:`case_at_voltage` on the scan ``speeds`` (rad/s) of
    :func:`onset_speed`: one entry of :func:`onsets_per_voltage`, a job for a worker."""
    return onset_speed(case_at_voltage(case, volt, shimmed), speeds)


def onsets_per_voltage(
    case: Case,
    voltages: Sequence[float],
    speeds: Sequence[float],
    *,
    shimmed: bool = False,
    progress: Callable[[str], None] | None = None,
) -> dict[float, OnsetResult]:
    """The onset speed at each common actuator voltage (V), on the C-GFB or its shimmed twin.

    Parameters
    ----------
    case
        A case with ``[actuators]``; each voltage is applied to all of them
        (``shimmed``: shims of the base preload's thickness instead).
    voltages
        Voltages, V.
    speeds
        Scan speeds of :func:`onset_speed`, rad/s.
    progress
        Called with one line per voltage.
    """
    if case.actuators is None:
        raise InputError("the onset over voltages needs a case with [actuators]")
    out: dict[float, OnsetResult] = {}
    for volt in voltages:
        out[float(volt)] = onset_at_voltage(case, volt, speeds, shimmed)
        if progress is not None:
            progress(f"{volt:g} V: {out[float(volt)].message}")
    return out


def stability_map(
    case: Case,
    speeds: Any,
    voltages: Any,
    *,
    shimmed: bool = False,
    progress: Callable[[str], None] | None = None,
) -> Any:
    """Log decrement and whirl ratio over speed × voltage (xarray Dataset).

    ``speeds`` in rad/s and ``voltages`` in V as floats, or quantities
    (``["30 krpm", "50 krpm"]``, ``"150 V"``, pint quantities)."""
    import xarray as xr

    if case.actuators is None:
        raise InputError("a stability map over voltages needs a case with [actuators]")
    speeds = sorted(float(w) for w in as_si_array(speeds, "speed", field="speeds"))
    voltages = [float(v) for v in as_si_array(voltages, "voltage", field="voltages")]
    case.check_speeds(speeds, "stability map speeds")
    dec = np.full((len(voltages), len(speeds)), np.nan)
    ratio = np.full_like(dec, np.nan)
    for v, volt in enumerate(voltages):
        c = case.with_voltages(float(volt))
        if shimmed:
            c = c.shimmed()
        scan = _Scanner(BearingSystem.from_case(c))
        for s, w in enumerate(speeds):
            try:
                mode = scan.mode(float(w))
            except SolverError:
                scan.start = None
                continue
            dec[v, s], ratio[v, s] = mode.log_decrement, mode.whirl_ratio
        if progress is not None:
            progress(f"stability map: {volt:g} V done")
    return xr.Dataset(
        {
            "log_decrement": (("voltage", "speed"), dec),
            "whirl_ratio": (("voltage", "speed"), ratio),
        },
        coords={
            "voltage": ("voltage", np.asarray(voltages, float), {"units": "V"}),
            "speed": ("speed", np.asarray(speeds) / RPM / 1e3, {"units": "krpm"}),
        },
        attrs={"bearing": "shimmed" if shimmed else "C-GFB", "rotor_mass_kg": case.rotor.mass},
    )
