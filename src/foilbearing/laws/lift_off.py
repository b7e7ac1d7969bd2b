"""Top-foil lift-off: the film under the top foil cannot fall below ambient pressure.

Where the Reynolds equation would draw the film below ambient, the top foil lifts off
its bumps and lets ambient gas in: the cell is held at ``P = 1`` instead (docs/model.md
§3.6, docs/lift-off.md). Each cell obeys the complementarity of its gauge pressure
``x = P − 1`` and its net outflow ``y`` (in pressure units)::

    sharp edge (κ = 0):     min(x, y) = 0
    smoothed edge (κ > 0):  x·y = w²,  w = δ√Λ,  δ = κ Δθ²

solved in the form ``φ(x, y) = x + y − √((x − y)² + 4w²) = 0``, which has no branches
and tends to ``2 min(x, y)`` as w → 0. The width is measured on the cell (δ = κΔθ²)
and scales with the bearing number Λ, since the outflow of a lifted film is its Couette
flow (docs/lift-off.md, "The smoothed edge").

Two forms, one law:

- :class:`LiftOff`, the law as the case states it (κ), with its width on a grid at a
  bearing number; the film grid carries it (``FilmGrid.lift_off``).
- :func:`smoothed_edge`, the row ``φ/2`` and its weight ``α = ∂(φ/2)/∂y``
  (``∂(φ/2)/∂x = 1 − α``), written once: called on arrays by ``reynolds/assembly.py``,
  and compiled as :data:`smoothed_edge_kernel`, which every kernel that writes a
  smoothed row inlines (the steady rows of ``reynolds/_kernels/flux.py``, the BDF
  rows of ``reynolds/_kernels/bdf.py`` and ``bdf_linear.py``).

The NumPy twin of the row (``foilbearing.testing.twins.smoothed_lift_off_py``) is an
independent test oracle and does not import this module; the SciPy fallback of the
transient Newton (``reynolds/fallback.py``) calls :func:`smoothed_edge`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["LiftOff", "smoothed_edge"]


# Not mutated (`make mutation`): numba compiles this function into the kernels, and cannot
# compile mutmut's trampoline around it; tests/test_lift_off_smoothing.py checks the row
# against its NumPy twin.
def smoothed_edge(x: Any, y: Any, width2: Any) -> tuple[Any, Any]:  # pragma: no mutate block
    """The smoothed lift-off row ``φ/2`` and its weight α, for floats or NumPy arrays.

    The formula is written once, here; :func:`smoothed_edge_kernel` is this function
    compiled for the kernels to inline (called from Python on arrays, this plain form
    avoids a compilation in every process).

    ``φ(x, y) = x + y − √((x − y)² + 4 width2)``: zero on the branch ``x·y = width2``
    (x, y > 0), ``2 min(x, y)`` when width2 = 0.

    Parameters
    ----------
    x : float or ndarray
        Gauge pressure ``P − 1`` of the cell (dimensionless).
    y : float or ndarray
        The cell's net outflow in the same units as ``x`` (its Reynolds or BDF row
        divided by the row's scale).
    width2 : float or ndarray
        The law's squared width w² in those units (``(δ√Λ)²``, times the ratio of
        scales where the row is measured on another scale than d_ref), > 0.

    Returns
    -------
    half_phi : float or ndarray
        ``φ/2``; a caller writes its row as ``± scale · φ/2``.
    alpha : float or ndarray
        ``∂(φ/2)/∂y = (1 + (x − y)/√(…))/2`` in [0, 1]: 1 where the film is free, 0
        where it is held at ambient; ``∂(φ/2)/∂x = 1 − α``.
    """
    root = np.sqrt((x - y) * (x - y) + 4.0 * width2)
    return 0.5 * (x + y - root), 0.5 * (1.0 + (x - y) / root)


# Not mutated either: it runs once, when a kernel module is imported, before mutmut's
# switch between mutants can reach it (its mutants survive unexercised, broken or not).
def __getattr__(name: str) -> Any:  # pragma: no mutate block
    """``smoothed_edge_kernel``: :func:`smoothed_edge` compiled for the kernels to inline,
    made on first use so that importing the laws (every case does) does not import numba."""
    if name == "smoothed_edge_kernel":
        from numba import njit

        kernel = njit(cache=True, inline="always")(smoothed_edge)
        globals()[name] = kernel
        return kernel
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@dataclass(frozen=True)
class LiftOff:
    """The top-foil lift-off law of a case: the sharp edge, or the smoothed one.

    Parameters
    ----------
    smoothing : float
        κ >= 0, the smoothing of the lifted-off edge (``grid.lift_off_smoothing`` of the
        case file): δ = κ Δθ², in cells² of the circumferential grid. 0 is the sharp
        complementarity ``min(P − 1, y) = 0``.
    """

    smoothing: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.smoothing) and self.smoothing >= 0.0):
            raise ValueError(
                f"LiftOff.smoothing (kappa) must be finite and >= 0, got {self.smoothing!r}"
            )

    @property
    def sharp(self) -> bool:
        """The sharp edge ``min(P − 1, y) = 0`` (κ = 0): cells switch between branches."""
        return self.smoothing == 0.0

    @property
    def smoothed(self) -> bool:
        """The smoothed edge ``(P − 1)·y = (δ√Λ)²`` (κ > 0): no branches."""
        return self.smoothing > 0.0

    def delta(self, d_theta: float) -> float:
        """δ = κ Δθ² on a grid of circumferential cell width ``d_theta`` (rad); 0: sharp."""
        return float(self.smoothing * d_theta**2)

    def width(self, d_theta: float, lam: float) -> float:
        """``w = δ √|Λ|``: the law ``(P − 1)·y = w²`` at bearing number ``lam``.

        The outflow of the lifted-off film is the Couette flow, proportional to Λ, and
        the gauge pressure is set by the load: so the law measures the outflow in units
        of Λ, ``(P − 1)·y/Λ = δ²``, and its blend spans the same share of a cell at
        every speed (docs/lift-off.md, "The smoothed edge").
        """
        return float(self.delta(d_theta) * np.sqrt(abs(lam)))
