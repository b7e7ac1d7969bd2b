"""Finite-volume solvers of the compressible Reynolds equation (Eq. (4) of the paper).

Array-in/array-out numerics: a :class:`FilmGrid`, fields of shape
``(n_theta, n_z)`` on the half bearing (mid-plane symmetry), dimensionless
``P = p/p_a``, ``H = h/C`` and bearing number ``Λ = 6 μ ω R²/(p_a C²)``.
"""

from foilbearing.reynolds.assembly import Workspace, coupled_system, film_force, film_thickness
from foilbearing.reynolds.grid import FilmGrid
from foilbearing.reynolds.steady import NewtonOptions, SteadyFilm, solve_steady

__all__ = [
    "FilmGrid",
    "NewtonOptions",
    "SteadyFilm",
    "Workspace",
    "coupled_system",
    "film_force",
    "film_thickness",
    "solve_steady",
]
