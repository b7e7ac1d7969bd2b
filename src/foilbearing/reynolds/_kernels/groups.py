"""The argument groups of the transient kernels (:mod:`.bdf`, :mod:`.newton`).

Each group is a :class:`typing.NamedTuple`, which names its fields, their
order and their units, and builds the group in Python. A kernel takes the
group as a plain tuple (``tuple(group)``) and unpacks it whole at its top, in
the order given here. The groups are:

- :class:`FilmConstants`: the bearing on its grid, fixed for a transient system;
- :class:`StencilPattern`: the sparsity of the film Jacobians, fixed per grid;
- :class:`StepInputs`: the BDF step and the inputs at its new time;
- :class:`FactorArrays`: one factorised Newton matrix, kept over several steps;
- :class:`JacobianBlocks`: the blocks a factorisation fills;
- :class:`NewtonBuffers`: the scratch of one Newton iteration;
- :class:`NewtonControls`: the convergence rule of the iteration;
- :class:`BdfHistory`: the accepted states a BDF step is built on.

Why plain tuples: numba types a plain tuple of arrays in its C dispatcher, and
a named tuple field by field in Python. Measured on one Newton step of an
8 × 2 grid (dispatch dominates), the old call with 35 separate arguments took
6.3 µs, the grouped call 8.8 µs with plain tuples and 13 µs with named tuples
(docs/development/orbit-performance.md, "Grouped kernel arguments").
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: A group as a kernel takes it: ``tuple(group)`` of one of the named tuples below.
Group = tuple[Any, ...]

__all__ = [
    "BdfHistory",
    "FactorArrays",
    "FilmConstants",
    "Group",
    "JacobianBlocks",
    "NewtonBuffers",
    "NewtonControls",
    "StencilPattern",
    "StepInputs",
]


class FilmConstants(NamedTuple):
    """The bearing on its grid, as the transient kernels see it (fixed per system).

    Attributes
    ----------
    cos_t, sin_t : ndarray, shape (n_theta,)
        cos θ_i, sin θ_i of the θ-rows.
    c_act, c_bump : ndarray, shape (n_theta,)
        Actuator and bump compliances per θ-row, p_a/(C k).
    w : ndarray, shape (2, n)
        Force weights (X, Y) of the cells, ``n = n_theta n_z``.
    force_scale : float
        p_a R²/(m C), 1/s².
    denom : float
        ``A σ = ΔθΔZ · 12 μ R²/(p_a C²)``, s.
    d_theta, d_z : float
        Cell sizes Δθ, ΔZ.
    n_z : int
        Cells per θ-row.
    lobes : ndarray, shape (n_lobe, n_theta)
        The unit preload lobe of each actuator whose compression lowers its whole lobe
        during the motion (``preload_response = "lobe"``, ``dynamics = "compliant"``);
        ``n_lobe = 0`` under every other reading.
    lobe_rows : ndarray, shape (n_lobe, n_theta)
        Periodic linear interpolation at each such actuator's angle: ``lobe_rows @ f``
        is a θ-row field f at θ_n.
    c_stack : float
        The stack's compliance ``p_a/(C (k_p + 4k_sp))``: the compression
        ``D_n = c_stack max(lobe_rows_n @ (p̄ − 1), 0)`` in units of C (0 without lobes).
    axial : AxialStencil (as a plain tuple)
        The axial discretisation and its mean weights
        (:attr:`foilbearing.reynolds.grid.FilmGrid.axial`).
    lift_delta : float
        δ of the smoothed lift-off law (:attr:`~foilbearing.reynolds.grid.FilmGrid.lift_off_delta`);
        0: no smoothed law (the sharp branches, or the suction retained).
    lift_scale : float
        ``s = d_ref/(A σ)``: a pressure cell's BDF equation G (1/s) per unit of the
        pressure it stands for (``d_ref = 2ΔZ/Δθ``); each cell obeys
        ``(s/2)(x + G/s − √((x − G/s)² + 4δ²Λ)) = 0``, x = P − 1, Λ the step's bearing
        number.
    """

    cos_t: FloatArray
    sin_t: FloatArray
    c_act: FloatArray
    c_bump: FloatArray
    w: FloatArray
    force_scale: float
    denom: float
    d_theta: float
    d_z: float
    n_z: int
    lobes: FloatArray
    lobe_rows: FloatArray
    c_stack: float
    axial: Group
    lift_delta: float
    lift_scale: float


class StencilPattern(NamedTuple):
    """Sparsity of the film Jacobians (the 5-point stencil, fixed per grid).

    Attributes
    ----------
    diag_slots : ndarray, shape (n,)
        Position of the diagonal entry of each row in the stencil data.
    jh_rows : ndarray, shape (nnz,)
        θ-row ``indices // n_z`` of each stencil column.
    indptr : ndarray, shape (n + 1,)
        Stencil row pointers.
    """

    diag_slots: IntArray
    jh_rows: IntArray
    indptr: IntArray


class StepInputs(NamedTuple):
    """One BDF step: its leading coefficient and history, and the inputs at its new time.

    Attributes
    ----------
    c0 : float
        BDF leading coefficient α₀/Δt, 1/s.
    hist : ndarray, shape (n + n_theta + 4,)
        History part of the BDF equations.
    lam : float
        Bearing number Λ(t).
    rate : float
        ω/γ of the viscoelastic bump, 1/s (0 for a purely elastic bump).
    preload : ndarray, shape (n_theta,)
        r_p(θ_i, t)/C.
    force : ndarray, shape (2,)
        External force on the journal in units of m·C, 1/s².
    """

    c0: float
    hist: FloatArray
    lam: float
    rate: float
    preload: FloatArray
    force: FloatArray


class FactorArrays(NamedTuple):
    """A factorised transient Newton matrix (block elimination, see :func:`.bdf.transient_solve`).

    Attributes
    ----------
    fac : ndarray, shape (n_theta, n_z, 5 n_z)
        Block cyclic factors of the pressure block B.
    jh_data : ndarray, shape (nnz,)
        Scaled film Jacobian ``c0·diag(P) − ∂R/∂H/(Aσ)`` (stencil data), 1/s.
    a_pe : ndarray, shape (n, 2)
        Its product with ``∂H/∂ε``.
    s_vp : ndarray, shape (2, n)
        Film force per unit P as an acceleration, 1/s².
    y_border : ndarray, shape (n, 2)
        ``B'⁻¹ a_pe / c0²``, B' the pressure block with the lobes' border (below).
    small_inv : ndarray, shape (2, 2)
        Inverse of the Woodbury matrix ``I + s_vp y_border``.
    c0, rate : float
        BDF leading coefficient and ω/γ of the bump at factorisation, 1/s.
    active : ndarray, shape (n_theta,)
        1.0 on θ-rows where the mean gauge pressure is engaged, else 0.0.
    lift_state : ndarray, shape (n,)
        Branch of each pressure cell under lift-off: ``d > 0`` held at ambient,
        ``−d < 0`` free (d the diagonal of its Newton row, 1/s), 0 where the
        film may hold sub-ambient pressure; moved by the Newton iterations.
    lobe_border : ndarray, shape (n, n_lobe)
        ``B⁻¹ a_pl``, ``a_pl = jh ∂H/∂D_n`` (the unit lobes as film columns): the
        pressure block with lobes following their stacks is ``B' = B + a_pl L``,
        ``L = ∂D/∂P`` (rank n_lobe, applied by Woodbury: :func:`.bdf.lobe_correct`).
    lobe_inv : ndarray, shape (n_lobe, n_lobe)
        Inverse of ``I + L lobe_border``.
    lobe_gain : ndarray, shape (n_lobe,)
        ``∂D_n/∂q(θ_n)``: ``c_stack`` where the stack is loaded, else 0.
    """

    fac: FloatArray
    jh_data: FloatArray
    a_pe: FloatArray
    s_vp: FloatArray
    y_border: FloatArray
    small_inv: FloatArray
    c0: float
    rate: float
    active: FloatArray
    lift_state: FloatArray
    lobe_border: FloatArray
    lobe_inv: FloatArray
    lobe_gain: FloatArray


class JacobianBlocks(NamedTuple):
    """The blocks :func:`.bdf.transient_jacobian` fills (all but the factorisation).

    Attributes
    ----------
    film : ndarray, shape (n_theta, n_z)
        The film h/C.
    jp, jh : ndarray, shape (nnz,)
        The scaled pressure and film Jacobians (stencil data).
    active : ndarray, shape (n_theta,)
        1.0 where the mean gauge pressure is engaged, else 0.0.
    jc : ndarray, shape (3 n_z · n,)
        The data of the pressure block B.
    a_pe : ndarray, shape (n, 2)
        The border ``jh ∂H/∂ε``.
    lift_state : ndarray, shape (n,)
        The branch of each cell (as :class:`FactorArrays`).
    a_pl : ndarray, shape (n, n_lobe)
        The lobes' border ``jh ∂H/∂D_n``.
    lobe_gain : ndarray, shape (n_lobe,)
        ``∂D_n/∂q(θ_n)`` (as :class:`FactorArrays`).
    """

    film: FloatArray
    jp: FloatArray
    jh: FloatArray
    active: FloatArray
    jc: FloatArray
    a_pe: FloatArray
    lift_state: FloatArray
    a_pl: FloatArray
    lobe_gain: FloatArray


class NewtonBuffers(NamedTuple):
    """Scratch of the Newton iteration of a BDF step.

    Attributes
    ----------
    film, res : ndarray, shape (n_theta, n_z)
        The film h/C and the finite-volume residual.
    g : ndarray, shape (n + n_theta + 4,)
        The BDF residual G.
    slack : ndarray, shape (n,)
        By how much each cell violates its lift-off branch.
    work : ndarray, shape (n, 1)
        The pressure right-hand side of the solve.
    dy : ndarray, shape (n + n_theta + 4,)
        The Newton update.
    q_out : ndarray, shape (n + n_theta + 4,)
        Q(y) of the converged iterate.
    """

    film: FloatArray
    res: FloatArray
    g: FloatArray
    slack: FloatArray
    work: FloatArray
    dy: FloatArray
    q_out: FloatArray


class NewtonControls(NamedTuple):
    """The convergence rule of the modified-Newton iteration (see ``OrbitSettings``).

    Attributes
    ----------
    tol : float
        Weighted update at which the iteration has converged.
    fraction : float
        ... or this fraction of the step's first update, if larger.
    max_iterations : int
        Iterations allowed with one factor.
    """

    tol: float
    fraction: float
    max_iterations: int


class BdfHistory(NamedTuple):
    """The accepted states of an orbit, newest first (rows reused from step to step).

    Attributes
    ----------
    times : ndarray, shape (order + 1,)
        Their times, s.
    ys : ndarray, shape (order + 1, size)
        The states.
    qs : ndarray, shape (order + 1, size)
        Their storages Q(y).
    accepted : int
        How many rows hold accepted states.
    """

    times: FloatArray
    ys: FloatArray
    qs: FloatArray
    accepted: int
