"""foilbearing: gas foil bearings with piezoelectric preload control.

Reproduces and extends Park, Kim and Sim (2021), "Rotordynamic Analysis of
Piezoelectric Gas Foil Bearings with a Mechanical Preload Control Based on
Structural Parameter Identifications". Conventions: ``../shared/MODEL.md``.
SI units inside; quantities with units only at the edges (case files, CLI,
reports).
"""

from foilbearing.case import Case, default_case, load_case
from foilbearing.errors import InputError, SolverError

__all__ = ["Case", "InputError", "SolverError", "default_case", "load_case"]
__version__ = "0.1.0"
