"""Moved: the linear stability analysis is :mod:`foilbearing.analysis.stability`.

This name of the module stays: it is the same module object (``sys.modules`` maps the old
name to the new), so an import from it, or a test that patches a name in it, keeps working.
"""

import sys

from foilbearing.analysis import stability as _stability
from foilbearing.analysis.stability import (  # noqa: F401  (the names importable from here)
    OnsetResult,
    WhirlMode,
    _Scanner,
    _whirl_eigenvalues,
    onset_speed,
    onsets_per_voltage,
    stability_map,
    whirl_mode,
)

__all__ = _stability.__all__

sys.modules[__name__] = _stability
