"""The modelling laws of the bearing: one law per module, each in every form the analyses use.

A law is an object. The case states it (``Case.grid.lift_off_smoothing``,
``Case.foil.damping_law``, ``Case.actuators.reading``), the film model carries it (:class:`foilbearing.film.FilmModel`,
:class:`foilbearing.reynolds.grid.FilmGrid`), and every analysis — the equilibrium,
the force coefficients, the orbit — takes it from there; a compiled kernel inlines the
law's kernel form. So changing a law is one module and its tests, and trying another
is passing another object (no patching).

================  ==============================================================================
module            responsibility
================  ==============================================================================
``lift_off``      top-foil lift-off: the sharp or smoothed edge (κ) as ``LiftOff`` (its width
                  δ√Λ on a grid), and the smoothed row ``smoothed_edge`` (φ/2 and its weight α),
                  compiled as ``smoothed_edge_kernel`` for the steady and BDF kernels
``foil_damping``  the bump's damping: ``ViscousBump`` (γ, damper γ k_b/ω) and its peer
                  ``NoFoilDamping``; the frequency-domain compliance of the bump (coefficients)
                  and the rate of its state U (orbit)
``actuator``      the actuator reading (``ActuatorReading``, local or lobe × compliant or held):
                  the stack's share of the static compliance, its lobe compliance c_s, and the
                  share that acts during the motion (coefficients and orbit alike); the four
                  ``READINGS``
================  ==============================================================================

This package is the bottom layer: it imports numpy, and numba only where a kernel asks
for a law's compiled form (``lift_off.smoothed_edge_kernel``), so that reading a case
does not load the compiler. A new law is a new
module here (or a new peer class in the module of its kind) with the same forms; a
law with a compiled form is listed in ``reynolds/_kernels/__init__.py`` so that a change
of it drops the kernels' on-disk caches (docs/development/architecture.md, "Laws").
"""

from foilbearing.laws.actuator import READINGS, ActuatorReading
from foilbearing.laws.foil_damping import FoilDamping, NoFoilDamping, ViscousBump, foil_damping_law
from foilbearing.laws.lift_off import LiftOff, smoothed_edge

__all__ = [
    "READINGS",
    "ActuatorReading",
    "FoilDamping",
    "LiftOff",
    "NoFoilDamping",
    "ViscousBump",
    "foil_damping_law",
    "smoothed_edge",
]
