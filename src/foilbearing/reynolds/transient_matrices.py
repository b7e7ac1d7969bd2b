"""The transient system's matrices in SciPy sparse form: the BDF Newton matrix, the storage
Jacobian ∂Q/∂y and its dense operator, and the film's derivatives they are built from.

The steppers do not use them: they factorise the same Newton matrix by block elimination in
compiled code (:meth:`~foilbearing.reynolds.transient.TransientSystem.factorize`), which the
tests check against :func:`newton_matrix`. The linearisations use them: the bifurcation's
Jacobian at an equilibrium (:mod:`foilbearing.bifurcation.bearing`) and the Floquet tangent's
storage operator (:mod:`foilbearing.orbit.tangent`). Each function takes the
:class:`~foilbearing.reynolds.transient.TransientSystem` and is also its method of the same
name (``jacobian`` for :func:`newton_matrix`). Units as in
:mod:`foilbearing.reynolds.transient`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds.transient_protocol import InputsLike

__all__ = ["film_derivatives", "newton_matrix", "storage_jacobian", "storage_operator"]

FloatArray = NDArray[np.float64]
#: A :class:`~foilbearing.reynolds.transient.TransientSystem` (which imports this module, so
#: it is not imported back, not even for type checking).
TransientSystem = Any


def film_derivatives(system: TransientSystem, P: FloatArray) -> tuple[Any, Any, Any, Any]:
    """∂q/∂P (n_theta, n) and ∂H/∂P, ∂H/∂U, ∂H/∂ε per cell, sparse, at pressures P."""
    g = system.grid
    active = (g.gauge_mean(P) > 0.0).astype(float)
    dq_dp = sp.diags(active) @ system.mean  # (nt, n)
    # ∂H/∂P through the actuator compliance (and the lobes that follow their stacks)
    dh_dp = system.expand @ sp.diags(system.c_act) @ dq_dp
    if system.n_lobe:  # D_n = c_s max(q(θ_n), 0)
        dd_dp = system.lobe_gain(P)[:, None] * system.lobe_mean  # (n_lobe, n)
        dh_dp = dh_dp + sp.csr_matrix(np.repeat(system.lobes.T, g.n_z, axis=0) @ dd_dp)
    return dq_dp, dh_dp, system.expand, sp.csr_matrix(system.dh_de)


def storage_jacobian(system: TransientSystem, y: FloatArray, preload: FloatArray) -> sp.csr_matrix:
    """∂Q/∂y at y (sparse CSR): ``∂(PH)/∂y`` on the pressure rows, the identity on U, ε, v."""
    P = system.split(y)[0]
    H, _q = system.film(y, preload)
    _dq_dp, dh_dp, dh_du, dh_de = film_derivatives(system, P)
    p_diag = sp.diags(P.ravel())
    n, rest = system.n, system.size - system.n
    top = sp.hstack(
        [
            sp.diags(H.ravel()) + p_diag @ dh_dp,
            p_diag @ dh_du,
            p_diag @ dh_de,
            sp.csr_matrix((n, 2)),
        ]
    )
    bottom = sp.hstack([sp.csr_matrix((rest, n)), sp.eye(rest)])
    return sp.vstack([top, bottom], format="csr")


def storage_operator(system: TransientSystem, y: FloatArray, preload: FloatArray) -> Any:
    """``dy -> (∂Q/∂y) dy`` at y for blocks dy of shape (size, m), dense and vectorised
    (:func:`storage_jacobian` is the same matrix, sparse), its state-dependent parts
    computed once (a run's derivative applies it at every step for every block)."""
    g = system.grid
    n, nt, nz = system.n, system.nt, g.n_z
    P = np.array(system.split(y)[0])
    h_row = system.film(y, preload)[0][:, 0]
    active = (g.gauge_mean(P) > 0.0).astype(float)
    c_eff = (system.c_act * active)[:, None]
    lobe_at = (
        system.lobes.T @ (system.lobe_gain(P)[:, None] * system.lobe_rows)
        if system.n_lobe
        else None
    )
    cos_t, sin_t = system.cos_t[:, None], system.sin_t[:, None]

    def apply(dy: FloatArray) -> FloatArray:
        m = dy.shape[1]
        d_p = dy[:n].reshape(nt, nz, m)
        mean = g.axial_mean(d_p)  # (nt, m)
        d_h = cos_t * dy[n + nt] + sin_t * dy[n + nt + 1] + dy[n : n + nt] + c_eff * mean
        if lobe_at is not None:
            d_h = d_h + lobe_at @ mean
        out = np.empty_like(dy)
        out[:n] = (h_row[:, None, None] * d_p + P[:, :, None] * d_h[:, None, :]).reshape(n, m)
        out[n:] = dy[n:]
        return out

    return apply


def newton_matrix(
    system: TransientSystem,
    y: FloatArray,
    inputs: InputsLike,
    c0: float,
    hist: FloatArray,
    lift_state: FloatArray | None = None,
) -> sp.csc_matrix:
    """∂/∂y of c0·Q(y) − f(y, t) (the BDF Newton matrix, c0 = α₀/Δt), sparse CSC.

    Under lift-off the rows of the cells held at ambient (decided with
    ``hist``, or given by ``lift_state``, a :meth:`~foilbearing.reynolds.transient.TransientSystem.lift_state`) are ``d e_k`` (the
    generalised derivative of ``min(d (P − 1), G)``).
    """
    P, _U, _eps, _v = system.split(y)
    H, _q = system.film(y, inputs.preload)
    g = system.grid
    Pc = np.ascontiguousarray(P)
    kern.jacobian_P(Pc, H, inputs.lam, g.d_theta, g.d_z, tuple(g.axial), system.ws.jp)
    kern.jacobian_H(Pc, H, inputs.lam, g.d_theta, g.d_z, tuple(g.axial), system.ws.jh)
    n = system.n
    j_p = sp.csr_matrix((system.ws.jp, system.ws.indices, system.ws.indptr), shape=(n, n))
    j_h = sp.csr_matrix((system.ws.jh, system.ws.indices, system.ws.indptr), shape=(n, n))
    dq_dp, dh_dp, dh_du, dh_de = film_derivatives(system, P)
    scale = 1.0 / (system.area * system.sigma)
    p_diag = sp.diags(P.ravel())
    # Reynolds rows: c0 ∂(PH)/∂y − ∂R/∂y /(Aσ)
    rp_p = c0 * (sp.diags(H.ravel()) + p_diag @ dh_dp) - scale * (j_p + j_h @ dh_dp)
    rp_u = c0 * (p_diag @ dh_du) - scale * (j_h @ dh_du)
    rp_e = c0 * (p_diag @ dh_de) - scale * (j_h @ dh_de)
    zeros_2 = sp.csr_matrix((n, 2))
    # Foil rows
    if system.dynamic_bump:
        rate = system.rate(inputs)
        fu_p = -rate * sp.diags(system.c_bump) @ dq_dp
        fu_u = sp.diags(np.full(system.nt, c0 + rate))
    else:
        fu_p = sp.csr_matrix((system.nt, n))
        fu_u = sp.diags(np.full(system.nt, c0))
    # Journal rows: c0 ε − v ; c0 v − accel
    je_v = sp.diags([-1.0, -1.0])
    je_e = sp.diags([c0, c0])
    jv_p = sp.csr_matrix(-system.force_scale * system.w)
    jv_v = sp.diags([c0, c0])
    blocks = [
        [rp_p, rp_u, rp_e, zeros_2],
        [fu_p, fu_u, None, None],
        [None, None, je_e, je_v],
        [jv_p, None, None, jv_v],
    ]
    full = sp.bmat(blocks, format="csr")
    if system.lift_delta > 0.0:
        # The smoothed law: each pressure row times α, plus (1 − α) s_k on its diagonal
        # (s_k a factor's own where ``lift_state`` is a factor's).
        a = system.smoothed_weights(y, inputs, c0, hist, lift_state)
        s = np.zeros(system.size)
        s[:n] = system.smoothed_scales(lift_state)
        full = sp.diags(a) @ full + sp.diags((1.0 - a) * s)
    if system.lift_off:
        d = np.zeros(system.size)
        if lift_state is None:
            lift_state = system.lift_state(y, inputs, c0, hist)
        d[:n] = np.maximum(lift_state, 0.0)
        held = (d > 0.0).astype(float)
        full = sp.diags(1.0 - held) @ full + sp.diags(d)
    return sp.csc_matrix(full)
