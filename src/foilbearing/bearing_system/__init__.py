"""One bearing, built once from a case: its scales, its film model and three verbs.

``BearingSystem.from_case(case)`` holds the case, its :class:`Scales` (p_a, R, C, L, μ,
σ, Λ per rad/s, the force scale p_a R²) and its film model (grid, k(θ), r_p(θ) and the
case's laws), and answers the three analyses of one bearing: ``equilibrium`` (static),
``coefficients``/``linearise`` (the force coefficients at whirl frequencies) and
``transient`` (the semi-discrete system the orbit's BDF steps)::

    from foilbearing.bearing_system import BearingSystem
    from foilbearing.case import load_case

    bearing = BearingSystem.from_case(load_case("examples/bump_foil_bearing.toml"))
    static = bearing.equilibrium("30 krpm")
    fc = bearing.linearise(static, [static.speed])
    system = bearing.transient()

The package is named for what it holds, the bearing as one system; ``orbit.system``
(the orbit's run) and ``film`` (the film model it holds) keep their names. Importing
:class:`Scales` loads no numerics (the case layer uses it); :class:`BearingSystem` is
imported on first use.

============  ==================================================================================
module        responsibility
============  ==================================================================================
``scales``    the scales of a bearing, computed once: p_a, R, C, L, μ, σ = 12 μ R²/(p_a C²), Λ
              per rad/s, the force scale p_a R² and the film force per unit rotor mass
``verbs``     ``BearingSystem``: the case's scales and film model, with the three verbs
              equilibrium, coefficients (linearise) and transient
============  ==================================================================================
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from foilbearing.bearing_system.scales import Scales

if TYPE_CHECKING:
    from foilbearing.bearing_system.verbs import BearingSystem

__all__ = ["BearingSystem", "Scales"]


def __getattr__(name: str) -> Any:
    if name != "BearingSystem":
        raise AttributeError(f"module 'foilbearing.bearing_system' has no attribute {name!r}")
    value = importlib.import_module("foilbearing.bearing_system.verbs").BearingSystem
    globals()[name] = value
    return value
