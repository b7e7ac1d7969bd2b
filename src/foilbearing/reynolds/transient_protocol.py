"""The transient system, its inputs and its factor as the Newton solves see them.

:class:`~foilbearing.reynolds.transient_factor.TransientFactor` and the SciPy fallback
(:mod:`foilbearing.reynolds.fallback`) take a
:class:`~foilbearing.reynolds.transient.TransientSystem`, which builds them; naming it
through these protocols keeps the modules' imports one way (transient → transient_factor →
fallback → here), with no import back, not even for type checking. Units as in
:mod:`foilbearing.reynolds.transient`: time in s, c0 and rates in 1/s, the rest
dimensionless (P = p/p_a, H = h/C).
"""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds.assembly import Workspace
from foilbearing.reynolds.grid import FilmGrid

__all__ = ["FactorLike", "InputsLike", "SystemLike"]

FloatArray = NDArray[np.float64]


class InputsLike(Protocol):
    """The inputs at one instant (:class:`~foilbearing.reynolds.transient.Inputs`)."""

    @property
    def lam(self) -> float: ...  # bearing number Λ(t)
    @property
    def omega(self) -> float: ...  # rotor speed, rad/s
    @property
    def preload(self) -> FloatArray: ...  # r_p(θ_i, t)/C, (n_theta,)
    @property
    def force(self) -> FloatArray: ...  # external force on the journal / (m C), 1/s², (2,)


class SystemLike(Protocol):
    """A :class:`~foilbearing.reynolds.transient.TransientSystem`: its sizes, constants,
    the buffers it shares with the kernels, and the pieces of its BDF equations."""

    grid: FilmGrid
    n: int  # film cells
    nt: int  # θ-rows
    size: int  # state size, n + nt + 4
    area: float  # ΔθΔZ
    sigma: float  # σ, s
    gamma: float  # loss factor γ of the bump
    dynamic_bump: bool
    c_bump: FloatArray  # bump compliance per θ-row, (nt,)
    force_scale: float  # film force per unit Σ w(P − 1), 1/s²
    w: FloatArray  # force weights, (2, n)
    s_vp: FloatArray  # force_scale · w, (2, n)
    lobe_mean: FloatArray  # ∂D/∂P per unit gain, (n_lobe, n)
    lift_delta: float  # δ of the smoothed lift-off law (0: none)
    smooth_scale: float  # s of the smoothed law, 1/s
    ws: Workspace
    kernel_groups: tuple[tuple[Any, ...], tuple[Any, ...]]  # (constants, pattern)
    _axial: tuple[Any, ...]
    _res: FloatArray
    _H: FloatArray
    _slack: FloatArray
    _work: FloatArray

    def split(self, y: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]: ...
    def film(self, y: FloatArray, preload: FloatArray) -> tuple[FloatArray, FloatArray]: ...
    def lift_state(self, y: FloatArray, inputs: Any, c0: float, hist: FloatArray) -> FloatArray: ...
    def smoothed_scales(self, lift_state: FloatArray | None = None) -> FloatArray: ...
    def storage_min_film(
        self, y: FloatArray, preload: FloatArray, out: FloatArray | None = None
    ) -> tuple[FloatArray, float]: ...
    def step_inputs(self, inputs: Any, c0: float, hist: FloatArray) -> kern.StepInputs: ...


class FactorLike(Protocol):
    """A :class:`~foilbearing.reynolds.transient_factor.TransientFactor`: the system, the
    LU of the pressure block (a SuperLU-like ``solve``) and the factor's arrays."""

    sys: SystemLike
    lu: object
    arrays: kern.FactorArrays

    @property
    def lift_state(self) -> FloatArray: ...
    @property
    def jh(self) -> Any: ...
