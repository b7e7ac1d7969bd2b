"""Moved: the static analysis is :mod:`foilbearing.analysis.equilibrium`.

This name of the module stays: it is the same module object (``sys.modules`` maps the old
name to the new), so an import from it, or a test that patches a name in it, keeps working.
"""

import sys

from foilbearing.analysis import equilibrium as _equilibrium
from foilbearing.analysis.equilibrium import (  # noqa: F401  (the names importable from here)
    STATIC_HEADLINE,
    EquilibriumOptions,
    StaticResult,
    _Equilibrium,
    drag_torque,
    film_at_position,
    solve_equilibrium,
)

__all__ = _equilibrium.__all__

sys.modules[__name__] = _equilibrium
