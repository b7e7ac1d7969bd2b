"""The nonlinear rotor on ``scipy.integrate.solve_ivp``: the reference the compiled rotor
stepper (:func:`foilbearing.rotor.stepper.run_rotor`) is checked against. A test oracle:
tests and benchmarks import it, production never does.

:class:`RotorIVP` writes a :class:`~foilbearing.rotor.nonlinear.RotorOrbitSystem` explicitly,
``dy/dt`` of every bearing's film and foil (:func:`foilbearing.testing.ivp_orbit.
state_derivative`, the single bearing's reference rates, each film seeing its journal from
the rotor's coordinates) and of the reduced rotor,

    M q̈ + Ω(t) G q̇ + K q = Σ_b B_bᵀ F_b(P_b) + f_gravity + f_unbalance(t),

and integrates it with solve_ivp's BDF, the films' Jacobian by grouped differences and the
rotor's exact (:meth:`RotorIVP.jacobian`): slow, and independent of the stepper's Newton.
SI units: time in s, displacements in m, forces in N.
"""

from __future__ import annotations

import functools
import math
import time

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from foilbearing.errors import InputError, SolverError
from foilbearing.rotor.nonlinear import RotorOrbit, RotorOrbitSystem
from foilbearing.testing.ivp_orbit import state_derivative, state_sparsity

__all__ = ["RotorIVP"]

FloatArray = NDArray[np.float64]
IndexArray = NDArray[np.intp]


class RotorIVP:
    """A :class:`~foilbearing.rotor.nonlinear.RotorOrbitSystem` as solve_ivp takes it: its
    derivative, the derivative's sparsity and Jacobian, and a run.

    Parameters
    ----------
    system
        The rotor on its bearings (its state, tolerances and initial state are used).
    """

    def __init__(self, system: RotorOrbitSystem) -> None:
        self.system = system

    def _journal_state(self, b: int, y: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Bearing b's ε (units of C) and dε/dt (1/s), in its frame, from q and q̇."""
        c = self.system.sims[b].case.bearing.clearance
        q = y[self.system.n_film : self.system.n_film + self.system.m]
        qd = y[self.system.n_film + self.system.m :]
        x, yy = q[2 * b], q[2 * b + 1]
        vx, vy = qd[2 * b], qd[2 * b + 1]
        return np.array([-yy, x]) / c, np.array([-vy, vx]) / c

    def derivative(self, t: float, y: FloatArray) -> FloatArray:
        """dy/dt of the whole system (module docstring)."""
        out = np.empty_like(y)
        force = self.system.gravity + self.system.unbalance_force(t)
        for b, sim in enumerate(self.system.sims):
            lo, hi = self.system.offsets[b], self.system.offsets[b + 1]
            eps, vel = self._journal_state(b, y)
            y_b = np.concatenate([y[lo:hi], eps, vel])
            out[lo:hi] = state_derivative(sim, t, y_b)[: hi - lo]
            P = y[lo : lo + sim.system.n]
            f_x, f_y = self.system.force_per_pressure[b] @ (P - 1.0)  # ours: X, Y
            force[2 * b] += f_y  # ROSS x = Y
            force[2 * b + 1] -= f_x  # ROSS y = −X
        q = y[self.system.n_film : self.system.n_film + self.system.m]
        qd = y[self.system.n_film + self.system.m :]
        omega = self.system.speed.omega(t)
        red = self.system.reduced
        out[self.system.n_film : self.system.n_film + self.system.m] = qd
        out[self.system.n_film + self.system.m :] = self.system.mass_inv @ (
            force - red.stiffness @ q - omega * red.gyroscopic @ qd
        )
        return out

    def sparsity(self) -> sp.csr_matrix:
        """The Jacobian's sparsity: each film on its own journal's x, y and rates; the rotor
        on every film's pressure and on itself."""
        m, nf = self.system.m, self.system.n_film
        rows: list[sp.spmatrix] = []
        for b, sim in enumerate(self.system.sims):
            single = state_sparsity(sim)
            k = self.system.film_sizes[b]
            film = single[:k, :k]
            journal = single[:k, k : k + 4]  # ε_X, ε_Y, v_X, v_Y
            cols = sp.lil_matrix((k, 2 * m))
            for j, c in enumerate((2 * b + 1, 2 * b, m + 2 * b + 1, m + 2 * b)):
                cols[:, c] = journal[:, j].toarray()
            blocks = [
                film if a == b else sp.csr_matrix((k, self.system.film_sizes[a]))
                for a in range(len(self.system.sims))
            ]
            rows.append(sp.hstack([*blocks, cols.tocsr()]))
        top = sp.hstack([sp.csr_matrix((m, nf)), sp.csr_matrix((m, m)), sp.eye(m)])
        pressure = np.zeros(nf)
        for b, sim in enumerate(self.system.sims):
            pressure[self.system.offsets[b] : self.system.offsets[b] + sim.system.n] = 1.0
        bottom = sp.hstack(
            [sp.csr_matrix(np.outer(np.ones(m), pressure)), sp.csr_matrix(np.ones((m, 2 * m)))]
        )
        return sp.vstack([*rows, top, bottom]).tocsr()

    def jacobian(self, t: float, y: FloatArray) -> sp.csr_matrix:
        """The Jacobian of :meth:`derivative` for solve_ivp.

        The films' rows are forward differences, their columns grouped so that no two
        columns of a group share a film row: a cell's rate depends only on its neighbours'
        rows, its foil and its journal. The rotor's rows are exact, for they are linear in
        the pressures and in q, q̇. Left to solve_ivp, the differences would take one
        derivative a column: the rotor's rows join every column, so no two columns share a
        group. The Jacobian only steers solve_ivp's Newton iterations; the run solves
        :meth:`derivative` to its tolerances whatever it is.
        """
        f0 = self.derivative(t, y)
        nf, m = self.system.n_film, self.system.m
        step = math.sqrt(np.finfo(float).eps) * np.maximum(np.abs(y), self.system.atol())
        rows, cols, vals = [], [], []
        for members, (r, c) in self._film_groups:
            dy = np.zeros_like(y)
            dy[members] = step[members]
            df = self.derivative(t, y + dy)[:nf] - f0[:nf]
            rows.append(r)
            cols.append(c)
            vals.append(df[r] / step[c])
        films = sp.csr_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(self.system.size, self.system.size),
        )
        rotor = np.zeros((2 * m, self.system.size))
        rotor[:m, nf + m :] = np.eye(m)
        for b, sim in enumerate(self.system.sims):
            lo = self.system.offsets[b]
            f_x, f_y = self.system.force_per_pressure[b]  # ours: X, Y; ROSS x = Y, y = −X
            rotor[m:, lo : lo + sim.system.n] = np.outer(self.system.mass_inv[:, 2 * b], f_y)
            rotor[m:, lo : lo + sim.system.n] -= np.outer(self.system.mass_inv[:, 2 * b + 1], f_x)
        rotor[m:, nf : nf + m] = -self.system.mass_inv @ self.system.reduced.stiffness
        rotor[m:, nf + m :] = (
            -self.system.speed.omega(t) * self.system.mass_inv @ self.system.reduced.gyroscopic
        )
        return (
            films + sp.vstack([sp.csr_matrix((nf, self.system.size)), sp.csr_matrix(rotor)]).tocsr()
        )

    @functools.cached_property
    def _film_groups(self) -> list[tuple[IndexArray, tuple[IndexArray, IndexArray]]]:
        """The columns of :meth:`jacobian`'s differences in groups (greedy colouring of the
        films' rows of :meth:`sparsity`), each with the (row, column) pairs it fills."""
        films = self.sparsity()[: self.system.n_film].tocsc()
        taken: list[NDArray[np.bool_]] = []
        members: list[list[int]] = []
        for j in range(films.shape[1]):
            r = films.indices[films.indptr[j] : films.indptr[j + 1]]
            if r.size == 0:
                continue
            for mask, group in zip(taken, members, strict=True):
                if not mask[r].any():
                    mask[r] = True
                    group.append(j)
                    break
            else:
                mask = np.zeros(films.shape[0], bool)
                mask[r] = True
                taken.append(mask)
                members.append([j])
        groups: list[tuple[IndexArray, tuple[IndexArray, IndexArray]]] = []
        for group in members:
            cols = np.asarray(group, np.intp)
            sub = films[:, cols].tocoo()
            groups.append((cols, (sub.row.astype(np.intp), cols[sub.col])))
        return groups

    def run(
        self,
        t_end: float,
        *,
        y0: FloatArray | None = None,
        sample_rate: float = 10_000.0,
        rtol: float = 1e-6,
        atol_factor: float = 1.0,
    ) -> RotorOrbit:
        """Integrate from t = 0 (the static state, or ``y0``) to ``t_end`` (s) with
        solve_ivp's BDF; sampled at ``sample_rate`` (Hz). The absolute tolerances are the
        bearings' orbit settings' (:meth:`RotorOrbitSystem.atol`) times ``atol_factor``."""
        if any(s.voltage is not None and s.voltage.observes for s in self.system.sims):
            raise InputError(
                "a closed-loop controller reads the run's samples, which solve_ivp does not "
                "hand it: run the rotor on its stepper (foilbearing.rotor.stepper.run_rotor)"
            )
        start = self.system.initial_state() if y0 is None else np.asarray(y0, float)
        times = np.arange(0.0, t_end + 1e-12, 1.0 / sample_rate)
        times = np.minimum(times, t_end)
        clock = time.perf_counter()
        sol = solve_ivp(
            self.derivative,
            (0.0, t_end),
            start,
            method="BDF",
            t_eval=times,
            rtol=rtol,
            atol=self.system.atol() * atol_factor,
            jac=self.jacobian,
        )
        wall = time.perf_counter() - clock
        if not sol.success:
            raise SolverError(
                f"the nonlinear rotor run stopped at t = {sol.t[-1]:.4g} s: {sol.message}; "
                "try a shorter run or a coarser orbit grid"
            )
        q = sol.y[self.system.n_film : self.system.n_film + self.system.m]
        nb = len(self.system.sims)
        journals = np.stack([np.stack([-q[2 * b + 1], q[2 * b]]) for b in range(nb)])
        lateral = self.system.reduced.basis @ q
        nodes = np.stack([lateral[0::4], lateral[1::4]], axis=1)
        return RotorOrbit(sol.t, journals, nodes, self.system.labels, wall, str(sol.message))
