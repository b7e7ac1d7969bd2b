"""Speed and voltage programs in time: the speed the rotor follows, the voltages the actuators
follow (open loop, or closed loop on the displacement), and the file that carries a schedule.

All times in s, speeds in rad/s, voltages in V. A program answers "what is the value at time
t" from what has happened up to t only: the closed-loop controller sees the displacement
samples the simulation has produced so far, never the future (no look-ahead).

The package's names are those of the module ``foilbearing.control`` was before it became a
package (``from foilbearing.control import linear_ramp`` keeps working); the schedule file is
imported from its module, ``foilbearing.control.schedule_file`` (its old name,
``foilbearing.schedule_file``, is the same module).

==================  ============================================================================
module              responsibility
==================  ============================================================================
``profiles``        speed profiles ω(t): constant speed and the linear ramp, with the rotation
                    angle φ(t)
``programs``        voltage programs in time: the protocol the orbit asks of one, and the
                    open-loop ``VoltageSchedule`` (piecewise linear V_n(t), ``voltage_ramp``)
``controller``      the closed-loop preload controller: raise the voltage when sub-synchronous
                    motion appears
``speed_schedule``  the voltage schedule in speed, V_n(Ω): what a controller follows as the
                    rotor speeds up, turned into a program in time through the slew rate
``schedule_file``   the voltage-schedule file (speed → voltages, TOML) a controller, or
                    ``foilbearing orbit``, reads
``options``         the option strings of speed and voltage programs, read once for
                    ``foilbearing orbit`` and ``foilbearing rotor --orbit``
==================  ============================================================================
"""

from foilbearing.control.controller import SubsyncController
from foilbearing.control.profiles import SpeedProfile, constant_speed, linear_ramp
from foilbearing.control.programs import VoltageProgram, VoltageSchedule, voltage_ramp

__all__ = [
    "SpeedProfile",
    "SubsyncController",
    "VoltageProgram",
    "VoltageSchedule",
    "constant_speed",
    "linear_ramp",
    "voltage_ramp",
]
