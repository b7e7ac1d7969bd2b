"""The rotor's unbalance response and its mode shapes, on ROSS.

Both work on the ROSS rotor of :func:`foilbearing.rotor.linear.ross_rotor`, whose bearings
carry our coefficient tables over speed × whirl frequency.

**The unbalance response** is ROSS's ``Rotor.run_unbalance_response``. An unbalance
excites the rotor at its own speed, so every bearing's coefficients must be those at
whirl frequency = speed. ROSS 3.1 does this: its synchronous sweep evaluates the transfer
matrix ``(K(Ω, Ω) + iΩ (C(Ω, Ω) + Ω G) − Ω² M)⁻¹`` with ``BearingElement.K(frequency=Ω,
speed=Ω)``, the tables interpolated along the speed axis and then the frequency axis at the
same value (``rotor_assembly.py``: ``_run_freq_response`` → ``transfer_matrix(speed=s)``;
``bearing_seal_element.py``: ``BearingCoefficient.__call__``). ``tests/test_rotor_response.py``
checks it against our own single-bearing coefficients at (Ω, Ω): near the rigid rotor's
synchronous critical, coefficients taken at half the speed would move the response 19 %.
On the speeds of its table and with each speed among the table's frequencies
(:func:`table_frequencies`), the response uses our coefficients exactly.

**The mode shapes** are ROSS's eigenvectors with matched whirl (as in :func:`rotor_modes`),
interpolated along each beam element by its cubic Hermite functions.

Frame: ours (docs/model.md §2; :mod:`foilbearing.export.ross`): X along the static load, Y
horizontal, rotation from +X towards +Y; ROSS's x = Y, y = −X. A harmonic quantity is
``Re(A e^{iΩt})``. An unbalance's phase is its angle at t = 0 from +X, in the sense of
rotation.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.rotor.linear import DEFAULT_FREQUENCIES, ross_rotor
from foilbearing.rotor.model import RotorCase

__all__ = [
    "ModeShapes",
    "UnbalanceResponse",
    "major_semi_axis",
    "mode_shapes",
    "table_frequencies",
    "unbalance_response",
]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
Values = Sequence[float] | FloatArray

#: Points per beam element on which a mode shape is drawn (the nodes included).
_POINTS_PER_ELEMENT = 9


def major_semi_axis(X: Any, Y: Any) -> Any:
    """The major semi-axis of the ellipse ``(Re(X e^{iωt}), Re(Y e^{iωt}))``: the sum of
    its forward and backward circles' radii, ``(|X + iY| + |X − iY|)/2``, in the unit of X
    and Y (any frame: a rotation leaves it unchanged)."""
    X, Y = np.asarray(X), np.asarray(Y)
    return 0.5 * (np.abs(X + 1j * Y) + np.abs(X - 1j * Y))


@dataclass(frozen=True)
class UnbalanceResponse:
    """The rotor's steady response to its unbalances, at the bearing and disk nodes.

    Attributes
    ----------
    speeds
        rad/s, shape (n,).
    nodes, labels
        The nodes reported, ascending (each bearing's and disk's), and their names
        ("bearing A", "disk at node 1").
    displacement
        Complex amplitudes (X, Y) of each node's journal, m, shape (n, len(nodes), 2), our
        frame: ``X(t) = Re(displacement[..., 0] e^{iΩt})``.
    unbalances
        The (node, magnitude kg·m, phase rad) excitations; phases from +X in the sense of
        rotation.
    """

    speeds: FloatArray
    nodes: tuple[int, ...]
    labels: tuple[str, ...]
    displacement: ComplexArray
    unbalances: tuple[tuple[int, float, float], ...]

    def amplitude_um(self) -> FloatArray:
        """The major semi-axis of each node's orbit, µm, shape (n, len(nodes))."""
        return np.asarray(
            1e6 * major_semi_axis(self.displacement[..., 0], self.displacement[..., 1]), float
        )

    def phase_deg(self) -> FloatArray:
        """How far each node's forward whirl lags the first unbalance, degrees in [0, 360),
        shape (n, len(nodes)): about 0 well below a critical speed, 90 at it, 180 well
        above."""
        forward = self.displacement[..., 0] + 1j * self.displacement[..., 1]
        lag = self.unbalances[0][2] - np.angle(forward)
        return np.asarray(np.degrees(np.mod(lag, 2.0 * math.pi)), float)

    def headline(self) -> list[dict[str, Any]]:
        """The response by speed and node, unit-named keys (``--json``)."""
        amp, phase = self.amplitude_um(), self.phase_deg()
        out = []
        for k, w in enumerate(self.speeds):
            for j, (node, label) in enumerate(zip(self.nodes, self.labels, strict=True)):
                out.append({
                    "speed_rpm": float(w / RPM),
                    "node": node,
                    "label": label,
                    "amplitude_um": float(amp[k, j]),
                    "phase_deg": float(phase[k, j]),
                })  # fmt: skip
        return out


@dataclass(frozen=True)
class ModeShapes:
    """The rotor's lowest modes at one speed, matched whirl, and their shapes.

    Attributes
    ----------
    speed
        rad/s.
    positions
        Axial position of each node, m, shape (nodes,).
    bearing_nodes, bearing_labels
        Where the bearings sit, and their names.
    frequency
        Damped natural frequency of each mode, Hz, ascending, shape (m,).
    log_decrement
        Shape (m,).
    forward
        Whether ROSS labels the mode's whirl forward, shape (m,).
    axial
        Positions along the shaft where the shapes are drawn, m, shape (p,), the nodes
        among them.
    displacement
        Complex (X, Y) of the shaft's centre at ``axial``, shape (m, p, 2), our frame,
        scaled so that the largest major semi-axis is 1 and the largest component at that
        point is real and positive.
    """

    speed: float
    positions: FloatArray
    bearing_nodes: tuple[int, ...]
    bearing_labels: tuple[str, ...]
    frequency: FloatArray
    log_decrement: FloatArray
    forward: NDArray[np.bool_]
    axial: FloatArray
    displacement: ComplexArray

    def amplitude_along(self) -> FloatArray:
        """Each mode's shape at ``axial``, shape (m, p): the major semi-axis of the orbit
        (largest 1), positive where the point moves in phase with the point of the largest
        orbit and negative in anti-phase. A cylindrical mode is one-signed, a conical one
        changes sign once."""
        X, Y = self.displacement[..., 0], self.displacement[..., 1]
        major = major_semi_axis(X, Y)
        ref = np.argmax(major, axis=1)
        rows = np.arange(X.shape[0])
        Xr, Yr = X[rows, ref][:, None], Y[rows, ref][:, None]
        sign = np.where((X * np.conj(Xr) + Y * np.conj(Yr)).real < 0.0, -1.0, 1.0)
        return np.asarray(sign * major, float)

    def amplitude(self) -> FloatArray:
        """``amplitude_along`` at the nodes, shape (m, nodes)."""
        at = np.arange(self.positions.size) * (_POINTS_PER_ELEMENT - 1)
        return self.amplitude_along()[:, at]


def table_frequencies(speeds: Values, frequencies: Values | None = None) -> FloatArray:
    """Whirl frequencies (rad/s) of a bearing table that serves both the modes and the
    unbalance response: ``frequencies`` (default :data:`DEFAULT_FREQUENCIES`) and the
    ``speeds`` (rad/s) themselves, so that the synchronous coefficients at each table speed
    are ours, not interpolated. Frequencies within 1 % of a speed are dropped."""
    w = np.asarray(speeds, float)
    base = DEFAULT_FREQUENCIES if frequencies is None else np.asarray(frequencies, float)
    near = np.array([np.any(np.abs(f / w - 1.0) < 0.01) for f in base], bool)
    return np.unique(np.concatenate([base[~near], w]))


def unbalance_response(
    rotor: RotorCase,
    speeds: Values,
    unbalances: Sequence[tuple[int, float, float]],
    *,
    model: Any = None,
    frequencies: Values | None = None,
    progress: Callable[[str], None] | None = None,
) -> UnbalanceResponse:
    """The steady response to unbalances at each speed, at the bearing and disk nodes.

    Parameters
    ----------
    rotor
        The rotor.
    speeds
        Rotor speeds, rad/s, > 0, increasing.
    unbalances
        (node, magnitude kg·m, phase rad) of each unbalance; the phase is its angle at
        t = 0 from +X (the load's direction) in the sense of rotation.
    model
        A ROSS rotor from :func:`ross_rotor` whose tables span ``speeds`` (ROSS
        interpolates between its table speeds and warns when it extrapolates). Built over
        ``speeds`` × :func:`table_frequencies` if omitted: exact at every speed.
    frequencies
        Whirl frequencies (rad/s) of that table besides the speeds (default
        :data:`DEFAULT_FREQUENCIES`, so that the model serves :func:`mode_shapes` too).
    progress
        Called with a line per bearing table.

    Returns
    -------
    UnbalanceResponse
        In our frame (module docstring).

    Raises
    ------
    InputError
        An unbalance at a node the shaft does not have, a negative or non-finite magnitude
        or phase, or speeds that are not positive and increasing.
    """
    w = _speeds(speeds)
    nodes = len(rotor.shaft) + 1
    if len(unbalances) == 0:
        raise InputError("unbalances: give at least one (node, magnitude kg*m, phase rad)")
    checked = []
    for k, item in enumerate(unbalances):
        if len(item) != 3:
            raise InputError(
                f"unbalances[{k}] = {item!r}: need (node, magnitude kg*m, phase rad)",
                source=rotor.source,
            )
        node, magnitude, phase = item
        if not (isinstance(node, int | np.integer) and 0 <= node < nodes):
            raise InputError(
                f"unbalances[{k}].node = {node}: the shaft has nodes 0 to {nodes - 1}",
                source=rotor.source,
            )
        if not (math.isfinite(magnitude) and magnitude >= 0.0 and math.isfinite(phase)):
            raise InputError(
                f"unbalances[{k}] = ({magnitude}, {phase}): need a magnitude >= 0 kg*m and "
                "a finite phase in rad",
                source=rotor.source,
            )
        checked.append((int(node), float(magnitude), float(phase)))
    if model is None:
        model = ross_rotor(rotor, list(w), list(table_frequencies(w, frequencies)), progress)

    # Our phase is measured from +X = ROSS's −y, which lies at −π/2 from ROSS's x.
    result = model.run_unbalance_response(
        [u[0] for u in checked],
        [u[1] for u in checked],
        [u[2] - 0.5 * math.pi for u in checked],
        speed_range=list(w),
    )
    resp = np.asarray(result.forced_resp)  # (ndof, n), ROSS's frame
    report = {b.node: b.label for b in rotor.bearings}
    for d in rotor.disks:
        report.setdefault(d.node, f"disk at node {d.node}")
    at = sorted(report)
    nd = model.number_dof
    x = np.stack([resp[nd * n] for n in at], axis=-1)
    y = np.stack([resp[nd * n + 1] for n in at], axis=-1)
    return UnbalanceResponse(
        speeds=w,
        nodes=tuple(at),
        labels=tuple(report[n] for n in at),
        displacement=np.stack([-y, x], axis=-1),
        unbalances=tuple(checked),
    )


def mode_shapes(
    rotor: RotorCase,
    speed: float,
    *,
    model: Any = None,
    num_modes: int = 4,
    frequencies: Values | None = None,
) -> ModeShapes:
    """The ``num_modes`` lowest modes at ``speed`` (rad/s), matched whirl, and their shapes.

    ``model``: a ROSS rotor from :func:`ross_rotor` whose tables span ``speed`` and the
    modes' whirl frequencies (built at ``speed`` over ``frequencies``, default
    :data:`DEFAULT_FREQUENCIES`, if omitted).
    """
    if not (math.isfinite(speed) and speed > 0.0):
        raise InputError(f"speed = {speed} rad/s: need a finite speed > 0")
    if model is None:
        freqs = None if frequencies is None else list(np.asarray(frequencies, float))
        model = ross_rotor(rotor, [float(speed)], freqs)
    if len(model.nodes) != len(rotor.shaft) + 1:
        raise InputError(
            f"the ROSS model has {len(model.nodes)} nodes, the rotor {len(rotor.shaft) + 1}: "
            "build it with ross_rotor(rotor, ...)"
        )
    with warnings.catch_warnings():
        # ROSS starts each mode's whirl iteration from coefficients it may extrapolate.
        warnings.filterwarnings("ignore", message="Extrapolating")
        modal = model.run_modal(float(speed), num_modes=2 * num_modes, matched_whirl=True)
    wd = np.asarray(modal.wd, float)
    order = np.argsort(wd)[:num_modes]
    forward = np.array([d == "Forward" for d in modal.whirl_direction()])
    vectors = np.asarray(modal.evectors)[: model.ndof, order]
    axial, xy = _along_shaft(rotor, vectors.T, model.number_dof)
    return ModeShapes(
        speed=float(speed),
        positions=np.asarray(rotor.positions, float),
        bearing_nodes=tuple(b.node for b in rotor.bearings),
        bearing_labels=tuple(b.label for b in rotor.bearings),
        frequency=wd[order] / (2.0 * math.pi),
        log_decrement=np.asarray(modal.log_dec, float)[order],
        forward=forward[order],
        axial=axial,
        displacement=_normalised(xy),
    )


def _along_shaft(
    rotor: RotorCase, vectors: ComplexArray, number_dof: int
) -> tuple[FloatArray, ComplexArray]:
    """Each vector's (X, Y) along the shaft, our frame: shape (m, p, 2), at the positions
    returned (m). Each element's lateral motion is the cubic Hermite interpolation of its
    end nodes' displacements and rotations, as ROSS draws its shapes (``Shape._calculate``:
    x uses the rotation β, y the rotation α with the opposite sign)."""
    z = rotor.positions
    zeta = np.linspace(0.0, 1.0, _POINTS_PER_ELEMENT)
    h = np.stack([
        1.0 - 3.0 * zeta**2 + 2.0 * zeta**3,
        zeta - 2.0 * zeta**2 + zeta**3,
        3.0 * zeta**2 - 2.0 * zeta**3,
        -(zeta**2) + zeta**3,
    ], axis=1)  # fmt: skip
    alpha, beta = number_dof // 2, number_dof // 2 + 1
    axial, xs, ys = [], [], []
    for k, element in enumerate(rotor.shaft):
        a, b = number_dof * k, number_dof * (k + 1)
        L = element.length
        x = h @ np.stack([vectors[:, a], L * vectors[:, a + beta],
                          vectors[:, b], L * vectors[:, b + beta]])  # fmt: skip
        y = h @ np.stack([vectors[:, a + 1], -L * vectors[:, a + alpha],
                          vectors[:, b + 1], -L * vectors[:, b + alpha]])  # fmt: skip
        keep = slice(0 if k == 0 else 1, None)  # each interior node once
        axial.append(z[k] + L * zeta[keep])
        xs.append(x[keep])
        ys.append(y[keep])
    x_ross, y_ross = np.concatenate(xs).T, np.concatenate(ys).T
    return np.concatenate(axial), np.stack([-y_ross, x_ross], axis=-1)


def _normalised(xy: ComplexArray) -> ComplexArray:
    """Each mode (first axis) scaled so that its largest major semi-axis is 1 and the
    larger component at that point is real and positive."""
    out = np.empty_like(xy)
    for i, mode in enumerate(xy):
        major = major_semi_axis(mode[:, 0], mode[:, 1])
        p = int(np.argmax(major))
        c = mode[p, int(np.argmax(np.abs(mode[p])))]
        out[i] = mode / (major[p] * c / abs(c))
    return out


def _speeds(speeds: Values) -> FloatArray:
    w = np.atleast_1d(np.asarray(speeds, float))
    if w.ndim != 1 or w.size == 0 or not np.all(np.isfinite(w)) or np.any(w <= 0.0):
        raise InputError(f"speeds = {w.tolist()!r} rad/s: need a 1-D list of finite speeds > 0")
    if np.any(np.diff(w) <= 0.0):
        raise InputError(f"speeds = {w.tolist()!r} rad/s: the speeds must be increasing")
    return w
