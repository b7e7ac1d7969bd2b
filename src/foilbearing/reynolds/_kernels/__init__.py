"""Compiled kernels of the finite-volume Reynolds equation (the only numba code).

Discretisation of the steady, dimensionless, isothermal Reynolds equation
(Eq. (4) of the paper, docs/model.md §4, written in conservative flux form)::

    ∂q_θ/∂θ + ∂q_Z/∂Z = 0,
    q_θ = P H³ ∂P/∂θ − Λ P H,      q_Z = P H³ ∂P/∂Z,

on the cell-centred grid of :class:`foilbearing.reynolds.grid.FilmGrid` (fields of
shape ``(n_theta, n_z)``, unknown ``k = i*n_z + j``).

Scaling of the residual
-----------------------
``R[i, j]`` is the left side integrated over cell ``(i, j)``, i.e. the net
outflow of the flux ``q`` through its four faces::

    R[i, j] = ΔZ (q_θ[i+1/2, j] − q_θ[i−1/2, j]) + Δθ (q_Z[i, j+1/2] − q_Z[i, j−1/2])

so ``R/(Δθ ΔZ)`` is the cell average of the left side of Eq. (4).

Face fluxes
-----------
θ-face ``i+1/2`` between cells ``a = (i, j)`` and ``b = (i+1, j)`` (periodic):
``D = P_f H_f³``, ``V = Λ H_f``, with arithmetic face means ``P_f``, ``H_f``;
grid Péclet number ``Pe = V Δθ / D = Λ Δθ / (P_f H_f²)``; exponentially fitted
(Scharfetter–Gummel / Il'in–Allen–Southwell) flux::

    q_θ = (D/Δθ) [B(Pe) P_b − B(−Pe) P_a]  =  (D/Δθ) B(Pe) (P_b − P_a) − V P_a,

``B(x) = x/(eˣ − 1)`` (Bernoulli function; ``B(−x) = B(x) + x``). It is exact
for constant coefficients, reduces to central differences for ``Pe → 0`` and
to upwinding for ``|Pe| → ∞``, so no oscillation appears at the grid Péclet
numbers reached when the local bearing number Λ/H² is 50 or more.

Z-faces: pure diffusion, ``q_Z = P_f H_f³ (P_b − P_a)/ΔZ``; zero flux on the
mid-plane face ``j = −1/2``; on the end face ``P = 1`` at ``ΔZ/2`` from the
last centre, ``q_Z = P_f H³ (1 − P)/(ΔZ/2)`` with ``P_f = (P + 1)/2`` and the
last cell's ``H``.

Jacobians
---------
``dR/dP`` and ``dR/dH`` share one fixed CSR pattern (5-point stencil, periodic
in θ, column indices sorted within rows), built once per grid by
:func:`stencil_pattern`; the kernels fill only the ``data`` array. The coupled
foil Jacobian has dense ``n_z × n_z`` blocks on three θ block-diagonals
(:func:`coupled_pattern`, :func:`coupled_jacobian`); that matrix is
factorised by block cyclic elimination (:func:`block_cyclic_factor`,
:func:`block_cyclic_solve`; wrapped by :mod:`foilbearing.reynolds.blocksolve`).

Every kernel has a plain-NumPy twin (suffix ``_py``, the same signature; the
twins of the transient Newton iteration take the ``TransientSystem`` or
``TransientFactor`` as first argument) in :mod:`foilbearing.testing.twins`;
``tests/test_kernels.py``, ``tests/test_block_solver.py`` and
``tests/test_transient_kernels.py`` check each kernel against its twin.

Modules
-------
===============  ===============================================================================
module           responsibility
===============  ===============================================================================
``faces``        the flux through one cell face: Bernoulli function, θ-, Z- and end faces with
                 their derivatives, the order-4 axial flux
``patterns``     CSR sparsity patterns of the stencil and of the foil-coupled Jacobian
``flux``         the steady residual of Eq. (4), dR/dP, dR/dH, the coupled Jacobian and the
                 lift-off rows
``blockcyclic``  the block cyclic LU of the coupled Jacobian
``film_rows``    the film rows of a transient state (mean gauge pressure, H per row)
``bdf``          the BDF equations of the transient system: residual, storage, set-up
``bdf_linear``   the linear system of a BDF Newton step: Jacobian blocks, border, solve
``newton``       the Newton iteration on the BDF equations, with lift-off branch switching
``groups``       the named argument groups the kernels take
``notice``       the one-line notice on a cold cache
``_cache``       drops the on-disk caches when any kernel or inlined law changes
===============  ===============================================================================

Each module's names stay importable from the module that held them before
(``flux`` re-exports ``faces`` and ``patterns``, ``bdf`` re-exports ``film_rows``
and ``bdf_linear``); all the kernels' names are here. The laws they inline live in
:mod:`foilbearing.laws` (:data:`foilbearing.laws.lift_off.smoothed_edge_kernel`);
:mod:`._cache` drops the on-disk caches when any of these sources changes. The Newton
policy (refresh / too slow / diverged) that :mod:`.newton` calls is the integrator's
(:mod:`foilbearing.integrate.newton`).
"""

from foilbearing.integrate import newton as _newton_policy
from foilbearing.laws import lift_off as _lift_off_law
from foilbearing.reynolds._kernels import _cache
from foilbearing.reynolds._kernels import bdf as _bdf
from foilbearing.reynolds._kernels import bdf_linear as _bdf_linear
from foilbearing.reynolds._kernels import blockcyclic as _blockcyclic
from foilbearing.reynolds._kernels import faces as _faces
from foilbearing.reynolds._kernels import film_rows as _film_rows
from foilbearing.reynolds._kernels import flux as _flux
from foilbearing.reynolds._kernels import groups as _groups
from foilbearing.reynolds._kernels import newton as _newton
from foilbearing.reynolds._kernels import patterns as _patterns
from foilbearing.reynolds._kernels.bdf import (
    bdf_setup,
    lobe_correct,
    transient_border,
    transient_jacobian,
    transient_residual,
    transient_solve,
    transient_storage,
)
from foilbearing.reynolds._kernels.blockcyclic import (
    BC_NOT_FINITE,
    BC_OK,
    BC_ZERO_PIVOT,
    block_cyclic_alloc,
    block_cyclic_chains,
    block_cyclic_factor,
    block_cyclic_solve,
)
from foilbearing.reynolds._kernels.flux import (
    _jacobian_both,
    bernoulli,
    bernoulli_deriv,
    coupled_jacobian,
    coupled_pattern,
    jacobian_H,
    jacobian_P,
    lift_off_rows,
    residual,
    stencil_pattern,
)
from foilbearing.reynolds._kernels.groups import (
    BdfHistory,
    FactorArrays,
    FilmConstants,
    JacobianBlocks,
    NewtonBuffers,
    NewtonControls,
    StencilPattern,
    StepInputs,
)
from foilbearing.reynolds._kernels.newton import (
    MAX_MOVED_KEPT,
    MAX_SWITCHES,
    NEWTON_CONVERGED,
    NEWTON_DIVERGED,
    NEWTON_FILM_CLOSED,
    NEWTON_NOT_FINITE,
    NEWTON_REFRESH,
    NEWTON_TOO_SLOW,
    adopt_branches,
    lift_coordinate,
    newton_update,
    predict_branches,
    switch_branches,
    transient_newton_solve,
    transient_newton_step,
)
from foilbearing.reynolds._kernels.notice import install as _install_compile_notice

_install_compile_notice()  # a cold cache says so once on stderr (notice.py), before compiling

# numba reuses a kernel's cache if its own file is unchanged, even when a function it
# inlines from another file (a law of ``foilbearing.laws``, a BDF row) changed: drop the
# caches whenever any of these sources changed (docs/numerics.md §3).
_cache.drop_stale_caches(
    (_bdf, _bdf_linear, _blockcyclic, _faces, _film_rows, _flux, _groups, _newton, _patterns),
    (_lift_off_law, _newton_policy),
)

__all__ = [
    "BC_NOT_FINITE",
    "BC_OK",
    "BC_ZERO_PIVOT",
    "MAX_MOVED_KEPT",
    "MAX_SWITCHES",
    "NEWTON_CONVERGED",
    "NEWTON_DIVERGED",
    "NEWTON_FILM_CLOSED",
    "NEWTON_NOT_FINITE",
    "NEWTON_REFRESH",
    "NEWTON_TOO_SLOW",
    "BdfHistory",
    "FactorArrays",
    "FilmConstants",
    "JacobianBlocks",
    "NewtonBuffers",
    "NewtonControls",
    "StencilPattern",
    "StepInputs",
    "_jacobian_both",
    "adopt_branches",
    "bdf_setup",
    "bernoulli",
    "bernoulli_deriv",
    "block_cyclic_alloc",
    "block_cyclic_chains",
    "block_cyclic_factor",
    "block_cyclic_solve",
    "coupled_jacobian",
    "coupled_pattern",
    "jacobian_H",
    "jacobian_P",
    "lift_coordinate",
    "lift_off_rows",
    "lobe_correct",
    "newton_update",
    "predict_branches",
    "residual",
    "stencil_pattern",
    "switch_branches",
    "transient_border",
    "transient_jacobian",
    "transient_newton_solve",
    "transient_newton_step",
    "transient_residual",
    "transient_solve",
    "transient_storage",
]
