"""The rotor reduced to a few coordinates: the bearings' journals and N shaft modes.

The nonlinear rotor (issue 32, item 4) integrates every bearing's film with the rotor, so
the rotor must be small: a Craig-Bampton reduction of ROSS's lateral beam model. Its
coordinates are

- the journal displacements X, Y at each bearing node (the boundary), whose constraint
  modes (static modes) are the shaft's static shape under a unit displacement of one
  journal with the others held: for two bearings they span the rigid rotor's translation
  and tilt;
- the amplitudes of the first N modes of the shaft with its journals held
  (fixed-interface modes): its bending.

The bearings act on the boundary coordinates alone, so a bearing's force enters the reduced
equations unchanged. ``M q̈ + (C_b + Ω G) q̇ + (K + K_b) q = F`` in the reduced coordinates.

:func:`reduced_modes` gives the linear modes of the reduced rotor on its bearings, each
with its coefficients at its own whirl frequency (matched whirl, as ``rotor_modes`` on
ROSS's full model), from the same ROSS bearing elements. As N grows the reduced modes
converge on the full model's (``tests/test_rotor.py``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sla
from numpy.typing import NDArray

from foilbearing.errors import InputError, SolverError
from foilbearing.rotor.linear import RotorModes, refine_onset

__all__ = ["ReducedRotor", "lateral_dofs", "reduce_rotor", "reduced_modes", "reduced_onset"]

FloatArray = NDArray[np.float64]

#: ROSS's degrees of freedom per node: x, y, z, α, β, θ. The lateral ones are x, y, α, β.
_DOF_PER_NODE = 6
_LATERAL = (0, 1, 3, 4)

_WHIRL_RTOL = 1e-6
_WHIRL_MAX_ITER = 50


def lateral_dofs(n_nodes: int) -> NDArray[np.int64]:
    """ROSS's indices of the lateral degrees of freedom (x, y, α, β) of every node, node
    by node: the rows of :attr:`ReducedRotor.basis`."""
    return np.array([_DOF_PER_NODE * n + k for n in range(n_nodes) for k in _LATERAL])


@dataclass(frozen=True)
class ReducedRotor:
    """The rotor's lateral dynamics on a Craig-Bampton basis.

    Attributes
    ----------
    mass, stiffness, gyroscopic
        Reduced matrices, shape (m, m): kg, N/m and kg (the gyroscopic one multiplies the
        speed Ω in rad/s), in the coordinates ``q = (X_1, Y_1, X_2, Y_2, ..., η_1 .. η_N)``
        (journal displacements in m, then the modes' amplitudes).
    basis
        The lateral displacements of every node from ``q``, shape (4 n_nodes, m): rows
        ``4 n + (0, 1, 2, 3)`` are node n's x, y (m), α, β (rad).
    bearing_nodes
        The node of each bearing, in the order of the boundary coordinates.
    mode_frequencies
        The fixed-interface modes' natural frequencies, Hz, shape (N,).
    """

    mass: FloatArray
    stiffness: FloatArray
    gyroscopic: FloatArray
    basis: FloatArray
    bearing_nodes: tuple[int, ...]
    mode_frequencies: FloatArray

    @property
    def n_modes(self) -> int:
        """N, the shaft modes kept."""
        return int(self.mode_frequencies.size)

    @property
    def size(self) -> int:
        """m = 2 × bearings + N."""
        return int(self.mass.shape[0])


def reduce_rotor(model: Any, bearing_nodes: Sequence[int], n_modes: int) -> ReducedRotor:
    """Craig-Bampton reduction of a ROSS rotor's shaft and disks (bearings left out).

    Parameters
    ----------
    model
        A ``ross.Rotor`` (:func:`foilbearing.rotor.ross_rotor`); its ``M0``, ``K0`` and
        ``G0`` hold the shaft and disks alone.
    bearing_nodes
        The bearings' nodes: at least two, so that holding the journals holds the rotor.
    n_modes
        N, fixed-interface modes kept (0 leaves the static modes alone: a rigid rotor).
    """
    nodes = len(model.nodes)
    bearing_nodes = tuple(int(n) for n in bearing_nodes)
    if len(bearing_nodes) < 2:
        raise InputError(
            f"a reduced rotor needs two bearings or more (got {len(bearing_nodes)}): with one "
            "the rotor can tilt freely about it"
        )
    lateral = lateral_dofs(nodes)
    n_lat = lateral.size
    if not 0 <= n_modes <= n_lat - 2 * len(bearing_nodes):
        raise InputError(
            f"n_modes = {n_modes}: allowed 0 to {n_lat - 2 * len(bearing_nodes)} for a shaft "
            f"of {nodes} nodes on {len(bearing_nodes)} bearings"
        )
    take = np.ix_(lateral, lateral)
    m_full = np.asarray(model.M0, float)[take]
    k_full = np.asarray(model.K0, float)[take]
    g_full = np.asarray(model.G0, float)[take]

    boundary = np.array([4 * n + k for n in bearing_nodes for k in (0, 1)])
    interior = np.setdiff1d(np.arange(n_lat), boundary)
    k_ii = k_full[np.ix_(interior, interior)]
    k_ib = k_full[np.ix_(interior, boundary)]
    m_ii = m_full[np.ix_(interior, interior)]
    constraint = -np.linalg.solve(k_ii, k_ib)
    if n_modes > 0:
        w2, phi = sla.eigh(k_ii, m_ii, subset_by_index=(0, n_modes - 1))
    else:
        w2, phi = np.zeros(0), np.zeros((interior.size, 0))
    nb = boundary.size
    basis = np.zeros((n_lat, nb + n_modes))
    basis[boundary, :nb] = np.eye(nb)
    basis[np.ix_(interior, np.arange(nb))] = constraint
    basis[np.ix_(interior, nb + np.arange(n_modes))] = phi

    def project(a: FloatArray) -> FloatArray:
        return np.asarray(basis.T @ a @ basis, float)

    return ReducedRotor(
        mass=project(m_full),
        stiffness=project(k_full),
        gyroscopic=project(g_full),
        basis=basis,
        bearing_nodes=bearing_nodes,
        mode_frequencies=np.sqrt(np.maximum(w2, 0.0)) / (2.0 * math.pi),
    )


_COEFFICIENTS = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")


class _BearingTables:
    """The ROSS bearing elements' X, Y stiffness and damping tables, to be taken at one
    speed (rad/s) as functions of the whirl frequency (rad/s): :meth:`at`.

    A table over speed and frequency is ROSS's own interpolation: along the speed (each
    frequency's column), then along the frequency. Here the columns' interpolants are built
    once and the row's once a speed, each a ROSS 1-D table; ROSS builds both at every call,
    which made the matched whirl's iterations cost 0.5 ms a coefficient."""

    def __init__(self, bearings: Sequence[Any]) -> None:
        from ross.bearing_seal_element import BearingCoefficient

        self._tables: list[dict[str, tuple[Any, list[Any] | None]]] = []
        for element in bearings:
            table: dict[str, tuple[Any, list[Any] | None]] = {}
            for name in _COEFFICIENTS:
                coefficient = getattr(element, f"{name}_interpolated")
                columns = None
                if coefficient.kind == "grid":
                    values = np.asarray(coefficient.values, float)
                    columns = [
                        BearingCoefficient(
                            values[:, j],
                            speed=coefficient.speed,
                            interpolation=coefficient.interpolation,
                        )
                        for j in range(values.shape[1])
                    ]
                table[name] = (coefficient, columns)
            self._tables.append(table)

    def at(self, speed: float) -> list[dict[str, Any]]:
        """Each bearing's coefficients at ``speed``, by name, as functions of the
        frequency."""
        from ross.bearing_seal_element import BearingCoefficient

        out = []
        for table in self._tables:
            at: dict[str, Any] = {}
            for name, (coefficient, columns) in table.items():
                if columns is None:
                    at[name] = lambda f, c=coefficient: c(frequency=f, speed=speed)
                else:
                    row = np.array([float(column(speed=speed)) for column in columns])
                    at[name] = BearingCoefficient(
                        row,
                        frequency=coefficient.frequency,
                        interpolation=coefficient.interpolation,
                    )
            out.append(at)
        return out


def _bearing_matrices(
    reduced: ReducedRotor, tables: Sequence[dict[str, Any]], frequency: float
) -> tuple[FloatArray, FloatArray]:
    """The bearings' stiffness and damping on the reduced coordinates at a whirl frequency
    (rad/s), from their tables at one speed (:meth:`_BearingTables.at`: the ROSS bearing
    elements' X, Y rows)."""
    k = np.zeros((reduced.size, reduced.size))
    c = np.zeros_like(k)
    for b, at in enumerate(tables):
        s = slice(2 * b, 2 * b + 2)
        k[s, s] = [
            [float(at[n](frequency)) for n in row] for row in (("kxx", "kxy"), ("kyx", "kyy"))
        ]
        c[s, s] = [
            [float(at[n](frequency)) for n in row] for row in (("cxx", "cxy"), ("cyx", "cyy"))
        ]
    return k, c


def _eigen(
    reduced: ReducedRotor, tables: Sequence[dict[str, Any]], frequency: float, speed: float
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Eigenvalues (1/s) and vectors of the state matrix with the bearings' tables at
    ``speed`` (:meth:`_BearingTables.at`) taken at ``frequency``: those whirling forward or backward
    with Im s > 0, ascending in Im s."""
    kb, cb = _bearing_matrices(reduced, tables, frequency)
    m = reduced.size
    mass_inv = np.linalg.inv(reduced.mass)
    a = np.zeros((2 * m, 2 * m))
    a[:m, m:] = np.eye(m)
    a[m:, :m] = -mass_inv @ (reduced.stiffness + kb)
    a[m:, m:] = -mass_inv @ (cb + speed * reduced.gyroscopic)
    values, vectors = np.linalg.eig(a)
    keep = np.flatnonzero(values.imag > 0.0)
    order = keep[np.argsort(values.imag[keep])]
    return values[order], vectors[:m, order]


def _mac(u: NDArray[np.complex128], v: NDArray[np.complex128]) -> float:
    return float(abs(np.vdot(u, v)) ** 2 / (np.vdot(u, u).real * np.vdot(v, v).real))


def _matched(
    reduced: ReducedRotor, bearings: _BearingTables, speed: float, num_modes: int
) -> tuple[FloatArray, FloatArray, NDArray[np.bool_]]:
    """(whirl frequency rad/s, log decrement, forward) of the ``num_modes`` lowest modes,
    each iterated to its own whirl frequency (the same fixed point and mode tracking by the
    modal assurance criterion as ROSS's ``run_modal(matched_whirl=True)``)."""
    tables = bearings.at(speed)
    values0, vectors0 = _eigen(reduced, tables, speed, speed)
    count = min(num_modes, values0.size)
    wd = np.zeros(count)
    dec = np.zeros(count)
    forward = np.zeros(count, bool)
    for i in range(count):
        value, vector = values0[i], vectors0[:, i]
        whirl = value.imag
        for _ in range(_WHIRL_MAX_ITER):
            values, vectors = _eigen(reduced, tables, whirl, speed)
            j = int(np.argmax([_mac(vector, vectors[:, c]) for c in range(values.size)]))
            value, vector = values[j], vectors[:, j]
            done = abs(value.imag - whirl) <= _WHIRL_RTOL * value.imag
            whirl = value.imag
            if done:
                break
        else:
            raise SolverError(
                f"the reduced rotor's mode {i} at {speed:.1f} rad/s: the whirl frequency did "
                f"not converge in {_WHIRL_MAX_ITER} iterations; widen the coefficient tables' "
                "frequencies"
            )
        wd[i] = value.imag
        dec[i] = -2.0 * math.pi * value.real / value.imag
        forward[i] = _forward(reduced, vector)
    order = np.argsort(wd)
    return wd[order], dec[order], forward[order]


def _forward(reduced: ReducedRotor, vector: NDArray[np.complex128]) -> bool:
    """Whether the mode whirls forward at the journal that moves most, in ROSS's frame: the
    journal moves from x towards y, as the rotor turns (Y lags X by a quarter period,
    Im(X̄ Y) < 0 for e^{st}, s = iω)."""
    journals = vector[: 2 * len(reduced.bearing_nodes)].reshape(-1, 2)
    k = int(np.argmax(np.abs(journals).sum(axis=1)))
    x, y = journals[k]
    return bool((np.conj(x) * y).imag < 0.0)


def _bearings_of(model: Any, reduced: ReducedRotor) -> _BearingTables:
    by_node = {int(e.n): e for e in model.bearing_elements}
    missing = [n for n in reduced.bearing_nodes if n not in by_node]
    if missing:
        raise InputError(f"bearing_nodes {missing}: the ROSS rotor has no bearing there")
    return _BearingTables([by_node[n] for n in reduced.bearing_nodes])


def reduced_modes(
    model: Any,
    bearing_nodes: Sequence[int],
    speeds: Sequence[float],
    *,
    n_modes: int,
    num_modes: int = 4,
) -> RotorModes:
    """The reduced rotor's ``num_modes`` lowest modes at each speed (rad/s), matched whirl.

    The bearings are ROSS's elements in ``model`` (:func:`foilbearing.rotor.ross_rotor`),
    in the order of ``bearing_nodes``: the same interpolated tables ROSS's own modal
    analysis uses, so the two differ by the reduction alone.
    """
    reduced = reduce_rotor(model, bearing_nodes, n_modes)
    return _modes_on(reduced, _bearings_of(model, reduced), speeds, num_modes)


def _modes_on(
    reduced: ReducedRotor, bearings: _BearingTables, speeds: Sequence[float], num_modes: int
) -> RotorModes:
    rows = [_matched(reduced, bearings, float(w), num_modes) for w in speeds]
    return RotorModes(
        np.asarray(speeds, float),
        np.array([r[0] for r in rows]) / (2.0 * math.pi),
        np.array([r[1] for r in rows]),
        np.array([r[2] for r in rows]),
    )


def reduced_onset(
    model: Any,
    bearing_nodes: Sequence[int],
    speeds: Sequence[float],
    *,
    n_modes: int,
    num_modes: int = 4,
) -> tuple[float | None, float | None, RotorModes]:
    """The reduced rotor's onset speed (rad/s), its whirl frequency (Hz) and its modes on
    ``speeds``, as :func:`foilbearing.rotor.rotor_onset` on the full model."""
    reduced = reduce_rotor(model, bearing_nodes, n_modes)
    bearings = _bearings_of(model, reduced)
    modes = _modes_on(reduced, bearings, speeds, num_modes)
    onset, whirl = refine_onset(modes, lambda w: _matched(reduced, bearings, w, num_modes))
    return onset, whirl, modes
