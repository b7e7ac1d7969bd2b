"""Export to other rotordynamics tools: ``ross`` builds a ROSS ``BearingElement``.

========  ======================================================================================
module    responsibility
========  ======================================================================================
``ross``  the bearing's force coefficients as a ROSS ``BearingElement``
========  ======================================================================================
"""
