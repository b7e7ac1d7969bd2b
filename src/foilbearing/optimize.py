"""Moved: this module is :mod:`foilbearing.design.voltages`.

This name of the module stays: it is the same module object (``sys.modules`` maps the old
name to the new), so an import from it, or a test that patches a name in it, keeps working.
"""

import sys

from foilbearing.design import voltages as _voltages
from foilbearing.design.voltages import (  # noqa: F401  (the names importable from here)
    FAILED_MERIT,
    PAPER_VOLTAGES,
    EvaluationCache,
    VoltageOptimum,
    local_search,
    maximize_onset,
    minimize_drag,
    start_points,
    voltage_box,
)

__all__ = _voltages.__all__

sys.modules[__name__] = _voltages
