"""A factorised Newton matrix of the transient system and the solves with it.

:class:`TransientFactor` is what
:meth:`~foilbearing.reynolds.transient.TransientSystem.factorize` returns: the
block cyclic factors of the pressure block B (or a SuperLU fallback), the
eliminated bump and journal blocks and the Woodbury border of the film force.
It solves ``J Δy = g`` and runs the modified-Newton iteration of a BDF step on
them, compiled (:mod:`foilbearing.reynolds._kernels`) on the block cyclic
factors, with the NumPy twins of :mod:`foilbearing.reynolds.reference` on the
fallback. Time in s, c0 and rates in 1/s; the state as in
:mod:`foilbearing.reynolds.transient`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds.reference import newton_solve_py, newton_step_py, solve_py

if TYPE_CHECKING:
    from foilbearing.reynolds.transient import Inputs, TransientSystem

__all__ = ["TransientFactor"]

FloatArray = NDArray[np.float64]


class TransientFactor:
    """A factorised Newton matrix (see
    :meth:`~foilbearing.reynolds.transient.TransientSystem.factorize`).

    Parameters
    ----------
    system : TransientSystem
        The system whose Newton matrix this is.
    lu : object
        LU of the pressure block B: a ``BlockCyclicLU``, or any LU with a
        SuperLU-like ``solve`` (the fallback).
    fac : ndarray or None
        The block cyclic factors of ``lu`` (its ``_fac``) for the compiled
        solves; None for the fallback, which uses the NumPy twins.
    jh_data, a_pe, s_vp, y_border, small_inv
        Scaled film Jacobian ``c0·diag(P) − ∂R/∂H/(Aσ)`` (stencil data, 1/s),
        ``jh ∂H/∂ε`` (n, 2), film force per unit P (2, n), 1/s², and the
        Woodbury border ``B⁻¹ a_pe/c0²`` (n, 2) with ``(I + s_vp y_border)⁻¹``.
    c0, rate : float
        BDF leading coefficient and ω/γ of the bump at factorisation, 1/s.
    active : ndarray, shape (n_theta,)
        1.0 on engaged θ-rows, else 0.0.
    lift_state : ndarray, shape (n,)
        Lift-off branches (``d`` held, ``−d`` free, 0 without lift-off), 1/s.
    """

    def __init__(
        self,
        system: TransientSystem,
        lu: object,
        fac: FloatArray | None,
        jh_data: FloatArray,
        a_pe: FloatArray,
        s_vp: FloatArray,
        y_border: FloatArray,
        small_inv: FloatArray,
        c0: float,
        rate: float,
        active: FloatArray,
        lift_state: FloatArray,
    ) -> None:
        self.sys, self.lu, self.jh_data, self.a_pe = system, lu, jh_data, a_pe
        self.s_vp, self.y_border, self.small_inv = s_vp, y_border, small_inv
        self.c0, self.rate, self.active = c0, rate, active
        #: Lift-off branch of each cell (``d`` held, ``−d`` free, 0 without lift-off):
        #: those of the factorisation, then moved by the Newton iterations that use it.
        self.lift_state = lift_state
        self._jh: sp.csr_matrix | None = None
        #: CSR data of the factorised pressure block B (on the coupled pattern).
        self.coupled_data: FloatArray | None = None
        # The compiled solve needs the block cyclic factors (not the SuperLU fallback).
        self._fac = fac
        # Arguments of the compiled Newton iteration that do not change with the inputs.
        s, g = system, system.grid
        self._args_sys: tuple[Any, ...] = (
            s.cos_t,
            s.sin_t,
            s.c_act,
            s.c_bump,
            lift_state,
            s.w,
            s.force_scale,
            s.area * s.sigma,
            g.d_theta,
            g.d_z,
            s._H,
            s._res,
        )
        self._args_fac: tuple[Any, ...] = (
            self._fac,
            jh_data,
            s.jh_rows,
            s.ws.indptr,
            a_pe,
            s_vp,
            y_border,
            small_inv,
            c0,
            rate,
            active,
            s._work,
        )

    @property
    def jh(self) -> sp.csr_matrix:
        """The scaled film Jacobian ``c0·diag(P) − ∂R/∂H/(Aσ)`` as a CSR matrix (built lazily)."""
        if self._jh is None:
            s = self.sys
            self._jh = sp.csr_matrix((self.jh_data, s.ws.indices, s.ws.indptr), shape=(s.n, s.n))
        return self._jh

    def _step_args(
        self,
        y: FloatArray,
        inputs: Inputs,
        c0: float,
        hist: FloatArray,
        weights: FloatArray,
        g: FloatArray,
        dy: FloatArray,
    ) -> tuple[Any, ...]:
        """Arguments of the compiled Newton step (:func:`~foilbearing.reynolds._kernels.transient_newton_step`)."""
        s = self.sys
        return (
            y,
            c0,
            hist,
            inputs.lam,
            s.rate(inputs),
            inputs.preload,
            inputs.force,
            *self._args_sys,
            g,
            s._slack,
            *self._args_fac,
            dy,
            weights,
        )

    def newton_step(
        self,
        y: FloatArray,
        inputs: Inputs,
        c0: float,
        hist: FloatArray,
        weights: FloatArray,
        g: FloatArray,
        dy: FloatArray,
    ) -> tuple[float, float, float]:
        """One modified-Newton iteration on the BDF equations, y updated in place.

        Compiled (:func:`~foilbearing.reynolds._kernels.transient_newton_step`) on the
        block cyclic factors; :func:`~foilbearing.reynolds.reference.newton_step_py`
        (its NumPy twin) with the SuperLU fallback.

        Parameters
        ----------
        y : ndarray, shape (size,)
            Iterate (C-contiguous float64), ``y −= Δy`` unless the film is closed.
        inputs : Inputs
            Inputs at the new time.
        c0 : float
            BDF leading coefficient of the step (the factor may be older), 1/s.
        hist : ndarray, shape (size,)
            History part of the BDF equations.
        weights : ndarray, shape (size,)
            Error weights of the convergence norm.
        g, dy : ndarray, shape (size,)
            Buffers, filled with the residual G(y) and the update Δy.

        Returns
        -------
        h_min : float
            Minimum film of y before the update.
        err : float
            Weighted max-norm of Δy (NaN when ``h_min <= 0``: y is left as it was).
        p_min : float
            Smallest pressure after the update (NaN when not updated).
        """
        if self._fac is None:
            return newton_step_py(self, y, inputs, c0, hist, weights, g, dy)
        args = self._step_args(y, inputs, c0, hist, weights, g, dy)
        h_min, err, p_min = kern.transient_newton_step(*args)
        return float(h_min), float(err), float(p_min)

    def newton_solve(
        self,
        y: FloatArray,
        inputs: Inputs,
        c0: float,
        hist: FloatArray,
        weights: FloatArray,
        work: tuple[FloatArray, FloatArray, FloatArray],
        controls: tuple[float, float, int],
        fresh: bool,
        first_change: float,
    ) -> tuple[int, int, float, float]:
        """Modified-Newton iterations with this factor until they converge or must stop.

        Compiled (:func:`~foilbearing.reynolds._kernels.transient_newton_solve`, which
        documents the outcomes) on the block cyclic factors;
        :func:`~foilbearing.reynolds.reference.newton_solve_py`
        (its twin) with the SuperLU fallback.

        Parameters
        ----------
        y : ndarray, shape (size,)
            Iterate, updated in place.
        inputs, c0, hist, weights
            As in :meth:`newton_step`.
        work : tuple of three ndarrays, shape (size,)
            Buffers for the residual, the update and Q(y) of the converged y.
        controls : tuple
            ``(newton_tol, newton_fraction, max_newton)`` (see ``OrbitSettings``).
        fresh : bool
            Whether the factor was taken at this step.
        first_change : float
            The step's first update so far (``inf`` at the start of a step).

        Returns
        -------
        tuple
            ``(outcome, iterations, first_change, h_min)``.
        """
        if self._fac is None:
            return newton_solve_py(
                self, y, inputs, c0, hist, weights, work, controls, fresh, first_change
            )
        g, dy, q_out = work
        args: tuple[Any, ...] = (
            *self._step_args(y, inputs, c0, hist, weights, g, dy),
            q_out,
            *controls,
            fresh,
            first_change,
        )
        outcome, its, first, h_min = kern.transient_newton_solve(*args)
        return int(outcome), int(its), float(first), float(h_min)

    def solve(self, g: FloatArray, out: FloatArray | None = None) -> FloatArray:
        """Δy with J Δy = g (J the Newton matrix at factorisation).

        Compiled (:func:`~foilbearing.reynolds._kernels.transient_solve`) on the
        block cyclic factors; :func:`~foilbearing.reynolds.reference.solve_py` (its
        NumPy twin) with the SuperLU fallback.

        Parameters
        ----------
        g : ndarray, shape (size,)
            Right-hand side.
        out : ndarray, shape (size,), optional
            Buffer for Δy (a new array if None; not ``g`` itself).

        Returns
        -------
        ndarray, shape (size,)
            Δy.
        """
        if self._fac is None:
            d = solve_py(self, g)
            if out is None:
                return d
            out[:] = d
            return out
        if out is None:
            out = np.empty_like(g)
        s = self.sys
        kern.transient_solve(
            g,
            self._fac,
            self.jh_data,
            s.jh_rows,
            s.ws.indptr,
            self.a_pe,
            self.s_vp,
            self.y_border,
            self.small_inv,
            self.c0,
            self.rate,
            self.active,
            s.c_bump,
            s._work,
            out,
        )
        return out
