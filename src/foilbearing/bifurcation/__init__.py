"""Periodic orbits past a Hopf point: shooting, Floquet multipliers and continuation.

- ``shooting``: a periodic orbit of an autonomous system by Newton shooting with a
  phase condition, and its Floquet multipliers (dense, or matrix-free by Arnoldi).
- ``branch``: the branch of orbits born at a Hopf point, its type (super- or
  subcritical, from the side its small cycles live on) and its folds, by
  pseudo-arclength continuation.

The numerics take a :class:`~foilbearing.bifurcation.shooting.FlowMap` (callables:
the flow over a time, the vector field), not a bearing: they are checked on the
Hopf normal form and the van der Pol oscillator (``tests/test_bifurcation.py``).

============  ==================================================================================
module        responsibility
============  ==================================================================================
``shooting``  a periodic orbit of an autonomous system by Newton shooting, and its Floquet
              multipliers
``branch``    the branch of periodic orbits born at a Hopf point, by pseudo-arclength
              continuation
``bearing``   the whirl's limit cycles of a rotor on the bearing, past and before the linear
              onset
============  ==================================================================================
"""

from foilbearing.bifurcation.branch import Branch, HopfPoint, hopf_branch
from foilbearing.bifurcation.shooting import (
    FlowMap,
    PeriodicOrbit,
    ShootingError,
    floquet_multipliers,
    periodic_orbit,
)

__all__ = [
    "Branch",
    "FlowMap",
    "HopfPoint",
    "PeriodicOrbit",
    "ShootingError",
    "floquet_multipliers",
    "hopf_branch",
    "periodic_orbit",
]
