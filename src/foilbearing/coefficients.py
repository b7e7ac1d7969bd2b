"""Moved: the force coefficients are :mod:`foilbearing.analysis.coefficients`.

This name of the module stays: it is the same module object (``sys.modules`` maps the old
name to the new), so an import from it, or a test that patches a name in it, keeps working.
"""

import sys

from foilbearing.analysis import coefficients as _coefficients
from foilbearing.analysis.coefficients import (  # noqa: F401  (the names importable from here)
    ForceCoefficients,
    _journal_columns,
    dynamic_compliance,
    force_coefficients,
)

__all__ = _coefficients.__all__

sys.modules[__name__] = _coefficients
