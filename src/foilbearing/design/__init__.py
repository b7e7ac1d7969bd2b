"""Design: what the stack's stiffness buys, the actuator voltages chosen by optimisation, and
the speed schedule of voltages a controller follows (beyond the paper).

The package's names are those of the module ``foilbearing.design`` was before it became a
package (the stack stiffness: ``from foilbearing.design import stack_design`` keeps
working). The old modules ``foilbearing.optimize`` and ``foilbearing.schedule`` are the same
modules as ``voltages`` and ``schedule_search`` under their old names. The schedule a search
makes, ``SpeedSchedule``, is a program a controller follows: it lives in
:mod:`foilbearing.control.speed_schedule` (and is importable from ``schedule_search``).

===================  ===========================================================================
module               responsibility
===================  ===========================================================================
``stack``            what the stack's stiffness buys: the 150 V onset against k_p under each
                     reading
``voltages``         actuator voltages chosen by optimisation, beyond the paper's equal
                     voltages: the largest onset, or the least drag
``schedule_search``  the search for a voltage schedule in speed: the least-drag voltages that
                     keep the rotor stable, speed by speed
===================  ===========================================================================
"""

from foilbearing.design.stack import READINGS, StackDesign, stack_design

__all__ = ["READINGS", "StackDesign", "stack_design"]
