"""Fits of the stack model of Eqs. (1)-(2) to the tests: D33,1 and D33,2 (no load) and K_p (stiffness)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from foilbearing.errors import InputError
from foilbearing.identification.stack_data import (
    _UM,
    FloatArray,
    NoLoadData,
    PathLike,
    StiffnessData,
    read_no_load,
    read_stiffness,
)

__all__ = [
    "MANUFACTURER_D33",
    "Identification",
    "LineFit",
    "LinearFit",
    "NoLoadFit",
    "QuadraticFit",
    "StiffnessFit",
    "fit_no_load",
    "fit_stiffness",
    "identify",
]


#: Manufacturer's linear piezoelectric coefficient of the stacks, m/V (paper Table 1).
MANUFACTURER_D33 = 0.467e-6


def _least_squares(
    design: FloatArray, y: FloatArray
) -> tuple[FloatArray, FloatArray, float, float]:
    """Least squares ``y ≈ design @ c``: coefficients, standard errors, R², residual SD.

    Standard errors are ``sqrt(diag(s² (XᵀX)⁻¹))`` with ``s² = SS_res/(n − p)``,
    NaN when n = p; R² = 1 − SS_res/SS_tot, SS_tot about the mean of ``y``.
    """
    n, p = design.shape
    coef = np.asarray(np.linalg.lstsq(design, y, rcond=None)[0], dtype=np.float64)
    ss_res = float(np.sum((y - design @ coef) ** 2))
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - ss_res / ss_tot if ss_tot > 0.0 else math.nan
    s2 = ss_res / (n - p) if n > p else math.nan
    se: FloatArray = np.sqrt(s2 * np.diag(np.linalg.pinv(design.T @ design)))
    return coef, se, r2, math.sqrt(s2)


@dataclass(frozen=True)
class QuadraticFit:
    """``δ = D33,1 V² + D33,2 V`` fitted through the origin (paper Eq. 2), SI units."""

    d33_1: float  #: m/V²
    d33_2: float  #: m/V
    d33_1_se: float  #: standard error of d33_1, m/V²
    d33_2_se: float  #: standard error of d33_2, m/V
    r_squared: float
    residual_std: float  #: sqrt(SS_res/(n − 2)), m
    n_points: int

    @property
    def d33_1_um_per_V2(self) -> float:
        """D33,1 in µm/V²."""
        return self.d33_1 / _UM

    @property
    def d33_2_um_per_V(self) -> float:
        """D33,2 in µm/V."""
        return self.d33_2 / _UM

    def displacement(self, voltage: npt.ArrayLike) -> FloatArray:
        """Fitted no-load displacement (m) at ``voltage`` (V), any shape."""
        v = np.asarray(voltage, dtype=float)
        return np.asarray(self.d33_1 * v**2 + self.d33_2 * v)


@dataclass(frozen=True)
class LinearFit:
    """``δ = D33 V`` through the origin, to compare with the manufacturer's 0.467 µm/V."""

    d33: float  #: m/V
    d33_se: float  #: m/V
    r_squared: float

    @property
    def d33_um_per_V(self) -> float:
        """D33 in µm/V."""
        return self.d33 / _UM


@dataclass(frozen=True)
class NoLoadFit:
    """No-load identification: pooled and per-stack quadratic fits, pooled linear fit."""

    pooled: QuadraticFit
    stacks: dict[str, QuadraticFit]
    linear: LinearFit
    source: str = ""


def fit_no_load(data: NoLoadData) -> NoLoadFit:
    """Fit ``δ = D33,1 V² + D33,2 V`` through the origin, per stack and pooled (Eq. 2).

    The pooled fit treats the readings of all stacks as one data set (the
    paper's representative curve, R² = 0.9926 there); so is the linear fit
    ``δ = D33 V``. With all stacks at the same voltages the pooled coefficients
    are the mean of the per-stack ones.
    """

    def quadratic(v: FloatArray, y: FloatArray) -> QuadraticFit:
        c, se, r2, sd = _least_squares(np.column_stack([v**2, v]), y)
        return QuadraticFit(float(c[0]), float(c[1]), float(se[0]), float(se[1]), r2, sd, y.size)

    v_all = np.tile(data.voltage, len(data.stacks))
    y_all = data.displacement.ravel()
    c, se, r2, _ = _least_squares(v_all[:, None], y_all)
    return NoLoadFit(
        pooled=quadratic(v_all, y_all),
        stacks={
            s: quadratic(data.voltage, data.displacement[i]) for i, s in enumerate(data.stacks)
        },
        linear=LinearFit(float(c[0]), float(se[0]), r2),
        source=data.source,
    )


@dataclass(frozen=True)
class LineFit:
    """Straight line ``δ = δ0 + slope·F`` of one stack at one voltage (Fig. 6b)."""

    stack: str
    voltage: float  #: V
    slope: float  #: dδ/dF, m/N
    slope_se: float  #: m/N; NaN for two loads
    intercept: float  #: δ0, displacement at zero load, m
    r_squared: float
    n_points: int

    @property
    def stiffness(self) -> float:
        """K_p = −1/slope, N/m."""
        return -1.0 / self.slope

    @property
    def stiffness_se(self) -> float:
        """Standard error of K_p to first order, ``slope_se/slope²``, N/m."""
        return self.slope_se / self.slope**2


@dataclass(frozen=True)
class StiffnessFit:
    """Stack stiffness identification (paper Figs. 6b-c).

    ``stack_stiffness[s]`` is K_p of stack ``s`` (N/m), the mean of −1/slope over
    its voltages; ``contact_area`` is A_c (m²).
    """

    lines: tuple[LineFit, ...]
    stack_stiffness: dict[str, float]
    stack_stiffness_se: dict[str, float]
    contact_area: float
    source: str = ""

    @property
    def mean_stiffness(self) -> float:
        """K_p averaged over the stacks, N/m (0.46e6 N/m in the paper)."""
        return float(np.mean(list(self.stack_stiffness.values())))

    @property
    def mean_stiffness_se(self) -> float:
        """Standard error of :attr:`mean_stiffness` (stacks independent), N/m."""
        se = np.array(list(self.stack_stiffness_se.values()))
        return float(np.sqrt(np.sum(se**2)) / se.size)

    @property
    def k_p(self) -> float:
        """Stack stiffness per unit contact area K_p/A_c, N/m³ (1.30e9 in the paper)."""
        return self.mean_stiffness / self.contact_area


def _check_area(contact_area: float) -> float:
    if not (math.isfinite(contact_area) and contact_area > 0.0):
        raise InputError(f"contact_area = {contact_area!r} m²: must be a positive finite area")
    return float(contact_area)


def fit_stiffness(data: StiffnessData, contact_area: float) -> StiffnessFit:
    """Fit the slope −1/K_p of displacement against load per stack and voltage.

    ``contact_area`` is the stinger-foil contact area A_c, m² (3.54e-4 m² in the paper).

    Raises
    ------
    InputError
        If a displacement does not fall with load (slope ≥ 0), or the area is not positive.
    """
    area = _check_area(contact_area)
    fits = []
    for s, v, mask in data.groups():
        f, y = data.load[mask], data.displacement[mask]
        c, se, r2, _ = _least_squares(np.column_stack([np.ones_like(f), f]), y)
        if not c[1] < 0.0:
            slope = f"slope {c[1] / _UM:+.4g} um/N"
            message = f"stack {s} at {v:g} V: displacement does not fall with load ({slope})"
            raise InputError(message + "; K_p needs a negative slope", source=data.source)
        fits.append(LineFit(s, v, float(c[1]), float(se[1]), float(c[0]), r2, int(f.size)))
    stiffness, stiffness_se = {}, {}
    for s in data.stacks:
        mine = [fit for fit in fits if fit.stack == s]
        stiffness[s] = float(np.mean([fit.stiffness for fit in mine]))
        stiffness_se[s] = math.sqrt(sum(fit.stiffness_se**2 for fit in mine)) / len(mine)
    return StiffnessFit(tuple(fits), stiffness, stiffness_se, area, data.source)


@dataclass(frozen=True)
class Identification:
    """Both identifications with their data, ready for reports and the case file."""

    no_load_data: NoLoadData
    no_load: NoLoadFit
    stiffness_data: StiffnessData
    stiffness: StiffnessFit

    def headline(self) -> dict[str, Any]:
        """Headline values with unit-named keys (JSON-ready); pooled values at top level."""
        p, st = self.no_load.pooled, self.stiffness
        per_stack: dict[str, dict[str, float]] = {
            s: {
                "d33_1_um_per_V2": q.d33_1_um_per_V2,
                "d33_2_um_per_V": q.d33_2_um_per_V,
                "r_squared": q.r_squared,
                "stroke_150V_um": float(q.displacement(150.0)) / _UM,
            }
            for s, q in self.no_load.stacks.items()
        }
        for s, k in st.stack_stiffness.items():
            per_stack.setdefault(s, {})["stack_stiffness_N_per_m"] = k
        return {
            "d33_1_um_per_V2": p.d33_1_um_per_V2,
            "d33_1_se_um_per_V2": p.d33_1_se / _UM,
            "d33_2_um_per_V": p.d33_2_um_per_V,
            "d33_2_se_um_per_V": p.d33_2_se / _UM,
            "r_squared": p.r_squared,
            "d33_linear_um_per_V": self.no_load.linear.d33_um_per_V,
            "d33_linear_r_squared": self.no_load.linear.r_squared,
            "d33_manufacturer_um_per_V": MANUFACTURER_D33 / _UM,
            "stack_stiffness_N_per_m": st.mean_stiffness,
            "stack_stiffness_se_N_per_m": st.mean_stiffness_se,
            "contact_area_m2": st.contact_area,
            "k_p_N_per_m3": st.k_p,
            "per_stack": per_stack,
            "no_load_file": self.no_load.source,
            "stiffness_file": st.source,
        }


def identify(
    no_load_path: PathLike, stiffness_path: PathLike, contact_area: float
) -> Identification:
    """Read both test files (formats in the module docstring) and identify D33,1, D33,2,
    K_p and k_p = K_p/A_c; ``contact_area`` is A_c, m² (3.54e-4 m² in the paper)."""
    area = _check_area(contact_area)
    no_load_data, stiffness_data = read_no_load(no_load_path), read_stiffness(stiffness_path)
    return Identification(
        no_load_data, fit_no_load(no_load_data), stiffness_data, fit_stiffness(stiffness_data, area)
    )
