"""Moved: this module is :mod:`foilbearing.design.speed_schedule`.

This name of the module stays: it is the same module object (``sys.modules`` maps the old
name to the new), so an import from it, or a test that patches a name in it, keeps working.
"""

import sys

from foilbearing.design import speed_schedule as _speed_schedule
from foilbearing.design.speed_schedule import (  # noqa: F401  (the names importable from here)
    DEFAULT_ACCELERATION,
    DEFAULT_MARGIN,
    DEFAULT_SLEW_RATE,
    SchedulePoint,
    SpeedSchedule,
    check_speed_range,
    evaluate_voltages,
    voltage_schedule,
)

__all__ = _speed_schedule.__all__

sys.modules[__name__] = _speed_schedule
