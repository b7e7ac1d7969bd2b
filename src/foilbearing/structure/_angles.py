"""Angle helpers shared by the structure models."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["wrap_angle"]


def wrap_angle(angle: ArrayLike) -> NDArray:
    """Wrap angles (rad) into [−π, π)."""
    return (np.asarray(angle, dtype=float) + np.pi) % (2.0 * np.pi) - np.pi
