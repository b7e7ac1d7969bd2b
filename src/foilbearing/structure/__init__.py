"""Structure models: PZT stack and actuator springs, bump foil, stiffness function, preload shape.

Paper Eqs. (1)-(3) and (6)-(8); conventions of docs/model.md §3. Every function
takes and returns SI values (per-unit-area stiffnesses in N/m³).

=============  =================================================================================
module         responsibility
=============  =================================================================================
``pzt``        the PZT stack and actuator springs: stiffness and preload (Eqs. (1)-(3))
``bump``       bump-foil stiffness per unit area from the foil geometry
``stiffness``  assembly stiffness under a stinger and the structural stiffness function k(θ)
``preload``    the preload shape r_p(θ): the sinusoidal lobe of Eq. (6)
``_angles``    angle helpers shared by the structure models
=============  =================================================================================
"""

from foilbearing.structure.bump import iordanoff_bump_stiffness, walowit_anno_bump_stiffness
from foilbearing.structure.preload import preload_shape
from foilbearing.structure.pzt import (
    actuator_stiffness,
    base_preload,
    piezoelectric_preload,
    stack_displacement,
)
from foilbearing.structure.stiffness import assembly_stiffness, stiffness_function

__all__ = [
    "actuator_stiffness",
    "assembly_stiffness",
    "base_preload",
    "iordanoff_bump_stiffness",
    "piezoelectric_preload",
    "preload_shape",
    "stack_displacement",
    "stiffness_function",
    "walowit_anno_bump_stiffness",
]
