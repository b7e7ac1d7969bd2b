"""A factorised Newton matrix of the transient system and the solves with it.

:class:`TransientFactor` is what
:meth:`~foilbearing.reynolds.transient.TransientSystem.factorize` returns: the
block cyclic factors of the pressure block B (or a SuperLU fallback), the
eliminated bump and journal blocks and the Woodbury border of the film force.
It solves ``J Δy = g`` and runs the modified-Newton iteration of a BDF step on
them, compiled (:mod:`foilbearing.reynolds._kernels`) on the block cyclic
factors, with the SciPy path of :mod:`foilbearing.reynolds.fallback` on the
SuperLU fallback. Time in s, c0 and rates in 1/s; the state as in
:mod:`foilbearing.reynolds.transient`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds import fallback
from foilbearing.reynolds.transient_protocol import InputsLike, SystemLike

__all__ = ["TransientFactor"]

FloatArray = NDArray[np.float64]

#: The storage buffer of a single Newton step, which does not fill it.
_NO_STORAGE = np.empty(0)


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
    arrays : FactorArrays
        The factor as the compiled kernels take it (:mod:`foilbearing.reynolds._kernels.groups`):
        the block cyclic factors of ``lu`` (its ``_fac``; None for the
        fallback, which uses the NumPy twins), the scaled film Jacobian
        ``c0·diag(P) − ∂R/∂H/(Aσ)`` (stencil data, 1/s), ``jh ∂H/∂ε`` (n, 2),
        the film force per unit P (2, n), 1/s², the Woodbury border
        ``B⁻¹ a_pe/c0²`` (n, 2) with ``(I + s_vp y_border)⁻¹``, c0 and ω/γ of
        the bump at factorisation (1/s), the engaged θ-rows and the lift-off
        branches (``d`` held, ``−d`` free, 0 without lift-off), 1/s.
    """

    def __init__(self, system: SystemLike, lu: object, arrays: kern.FactorArrays) -> None:
        self.sys, self.lu, self.arrays = system, lu, arrays
        self._jh: sp.csr_matrix | None = None
        #: CSR data of the factorised pressure block B (on the coupled pattern).
        self.coupled_data: FloatArray | None = None
        # The compiled solve needs the block cyclic factors (not the SuperLU fallback).
        self._fac = arrays.fac
        #: The film constants, stencil pattern and this factor as the kernels take them.
        self._groups = (*system.kernel_groups, tuple(arrays))

    @property
    def lift_state(self) -> FloatArray:
        """Lift-off branch of each cell (``d`` held, ``−d`` free, 0 without lift-off): those of
        the factorisation, then moved in place by the Newton iterations that use it."""
        return self.arrays.lift_state

    @property
    def jh(self) -> sp.csr_matrix:
        """The scaled film Jacobian ``c0·diag(P) − ∂R/∂H/(Aσ)`` as a CSR matrix (built lazily)."""
        if self._jh is None:
            s = self.sys
            self._jh = sp.csr_matrix(
                (self.arrays.jh_data, s.ws.indices, s.ws.indptr), shape=(s.n, s.n)
            )
        return self._jh

    def newton_step(
        self,
        y: FloatArray,
        inputs: InputsLike,
        c0: float,
        hist: FloatArray,
        weights: FloatArray,
        g: FloatArray,
        dy: FloatArray,
    ) -> tuple[float, float, float]:
        """One modified-Newton iteration on the BDF equations, y updated in place.

        Compiled (:func:`~foilbearing.reynolds._kernels.transient_newton_step`) on the
        block cyclic factors; :func:`~foilbearing.reynolds.fallback.newton_step`
        (its NumPy form) with the SuperLU fallback.

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
            return fallback.newton_step(self, y, inputs, c0, hist, weights, g, dy)
        s = self.sys
        buf = (s._H, s._res, g, s._slack, s._work, dy, _NO_STORAGE)  # a NewtonBuffers
        step = tuple(s.step_inputs(inputs, c0, hist))
        h_min, err, p_min = kern.transient_newton_step(y, step, *self._groups, buf, weights)
        return float(h_min), float(err), float(p_min)

    def newton_solve(
        self,
        y: FloatArray,
        inputs: InputsLike,
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
        :func:`~foilbearing.reynolds.fallback.newton_solve`
        (its NumPy form) with the SuperLU fallback.

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
            return fallback.newton_solve(
                self, y, inputs, c0, hist, weights, work, controls, fresh, first_change
            )
        s = self.sys
        g, dy, q_out = work
        outcome, its, first, h_min = kern.transient_newton_solve(
            y,
            tuple(s.step_inputs(inputs, c0, hist)),
            *self._groups,
            (s._H, s._res, g, s._slack, s._work, dy, q_out),  # a NewtonBuffers
            weights,
            tuple(controls),  # a NewtonControls
            fresh,
            first_change,
        )
        return int(outcome), int(its), float(first), float(h_min)

    def solve_block(self, g: FloatArray) -> FloatArray:
        """ΔY with J ΔY = G for a block of right-hand sides G, shape (size, m): one solve of
        the pressure block for all columns (:func:`~foilbearing.reynolds.fallback.solve`
        on blocks; equal to :meth:`solve` column by column)."""
        return fallback.solve(self, np.asarray(g, float))

    def solve(self, g: FloatArray, out: FloatArray | None = None) -> FloatArray:
        """Δy with J Δy = g (J the Newton matrix at factorisation).

        Compiled (:func:`~foilbearing.reynolds._kernels.transient_solve`) on the
        block cyclic factors; :func:`~foilbearing.reynolds.fallback.solve` (its
        NumPy form) with the SuperLU fallback.

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
            d = fallback.solve(self, g)
            if out is None:
                return d
            out[:] = d
            return out
        if out is None:
            out = np.empty_like(g)
        s = self.sys
        kern.transient_solve(g, self._groups[2], *s.kernel_groups, s._work, out)
        return out
