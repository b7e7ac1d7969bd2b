"""Finite-volume solvers of the compressible Reynolds equation (Eq. (4) of the paper).

Array-in/array-out numerics: a :class:`FilmGrid`, fields of shape
``(n_theta, n_z)`` on the half bearing (mid-plane symmetry), dimensionless
``P = p/p_a``, ``H = h/C`` and bearing number ``Λ = 6 μ ω R²/(p_a C²)``.

======================  ========================================================================
module                  responsibility
======================  ========================================================================
``grid``                the cell-centred finite-volume grid of the half bearing, its axial
                        stencil and lift-off law
``assembly``            film thickness, film force and the foil-coupled system of the steady
                        equation
``steady``              the steady film at a journal position: Newton on the foil-coupled
                        equation
``blocksolve``          the direct solver of the foil-coupled matrix: block cyclic LU, SuperLU
                        fallback
``perturbed``           first-order (complex) perturbation of the film about a steady one
``transient``           the semi-discrete unsteady system (film, foil, journal) as the BDF
                        steppers see it
``transient_matrices``  the transient system's matrices in SciPy sparse form: Newton matrix,
                        storage Jacobian
``transient_factor``    a factorised Newton matrix of the transient system and the solves with
                        it
``transient_protocol``  the transient system, its inputs and its factor as the Newton solves see
                        them
``fallback``            the SciPy path of the transient Newton where the block LU cannot pivot
``reference``           moved: names the new homes of the twins and the fallback
``_kernels/``           the compiled kernels (the only numba code)
======================  ========================================================================
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
