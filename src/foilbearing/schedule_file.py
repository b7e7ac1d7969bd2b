"""Moved: the voltage-schedule file is :mod:`foilbearing.control.schedule_file`.

This name of the module stays: it is the same module object (``sys.modules`` maps the old
name to the new), so an import from it, or a test that patches a name in it, keeps working.
"""

import sys

from foilbearing.control import schedule_file as _schedule_file
from foilbearing.control.schedule_file import (  # noqa: F401  (the names importable from here)
    load_schedule,
    parse_schedule,
    schedule_toml,
)

__all__ = _schedule_file.__all__

sys.modules[__name__] = _schedule_file
