"""Moved: this module is :mod:`foilbearing.design.schedule_search`.

This name of the module stays: it is the same module object (``sys.modules`` maps the old
name to the new), so an import from it, or a test that patches a name in it, keeps working.
"""

import sys

from foilbearing.design import schedule_search as _schedule_search
from foilbearing.design.schedule_search import (  # noqa: F401  (the names importable from here)
    DEFAULT_ACCELERATION,
    DEFAULT_MARGIN,
    DEFAULT_SLEW_RATE,
    SchedulePoint,
    SpeedSchedule,
    check_speed_range,
    evaluate_voltages,
    voltage_schedule,
)

__all__ = _schedule_search.__all__

sys.modules[__name__] = _schedule_search
