"""The nonlinear rotor: every bearing's film and foil integrated with the reduced rotor.

The state is each bearing's film and foil (the states of :mod:`foilbearing.orbit`, less its
journal) and the reduced rotor's coordinates and their rates
(:func:`foilbearing.rotor.reduce_rotor`: the journals' x, y in ROSS's frame, then N shaft
modes):

    y = [P_1, U_1, P_2, U_2, ..., q, q̇],

    M q̈ + Ω(t) G q̇ + K q = Σ_b B_bᵀ F_b(P_b) + f_gravity + f_unbalance(t).

Each bearing's film sees its journal ``ε_X = −y_b/C, ε_Y = x_b/C`` (ROSS's x = Y,
y = −X; :mod:`foilbearing.export.ross`) and gives the film force F_b = p_a R² Σ w (P − 1)
back, turned into ROSS's frame. Gravity is ROSS's −y: each bearing's +X, its load. The
films' rates are those of the single bearing (the same semi-discrete film, foil, actuators
and lift-off law). The rotor's angular acceleration enters only through the unbalance force
(ROSS's Ksdt, the shaft's own, is left out).

The compiled stepper runs it (:func:`foilbearing.rotor.stepper.run_rotor`). The reference
it is checked against, the whole system on ``scipy.integrate.solve_ivp`` (BDF, the films'
Jacobian by grouped differences and the rotor's exact), is a test oracle:
:class:`foilbearing.testing.ivp_rotor.RotorIVP`. At small amplitude its free whirl is the
linear analysis' mode (``tests/test_rotor_nonlinear.py``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.control import SpeedProfile, VoltageProgram
from foilbearing.errors import InputError
from foilbearing.orbit import OrbitSimulation
from foilbearing.orbit.settings import OrbitSettings
from foilbearing.rotor.model import RotorCase
from foilbearing.rotor.reduced import ReducedRotor, lateral_dofs, reduce_rotor

__all__ = ["RotorOrbit", "RotorOrbitSystem", "Unbalance", "load_rotor_orbit"]

FloatArray = NDArray[np.float64]

#: The solve_ivp reference's methods, now :class:`foilbearing.testing.ivp_rotor.RotorIVP`'s.
_IVP_METHODS = frozenset({"derivative", "jacobian", "run", "sparsity"})

#: The shortest run (s) whose sub-synchronous onset the signal analysis reads.
READ_AFTER = 1.0


@dataclass(frozen=True)
class Unbalance:
    """An unbalance at a node: magnitude (kg·m) and phase (rad): its angle at rotation
    angle 0 from the bearings' +X (the load), in the sense of rotation (as in
    :func:`foilbearing.rotor.unbalance_response`)."""

    node: int
    magnitude: float
    phase: float = 0.0


@dataclass(frozen=True)
class RotorOrbit:
    """A nonlinear rotor run.

    Attributes
    ----------
    time
        s, shape (k,).
    journals
        Each bearing's journal displacement in its own frame (X along its load, Y), m,
        shape (n_bearings, 2, k), from the rotor's axis at rest.
    nodes
        Every node's lateral displacement in ROSS's frame (x, y), m, shape (n_nodes, 2, k).
    labels
        The bearings' labels.
    wall_time
        s.
    message
        The integrator's.
    steps, factorizations, newton_iterations
        The stepper's counts (0 from solve_ivp).
    status
        How the run ended (``completed``, ``contact``, ``interrupted``, ...).
    speed
        Rotor speed at each sample, rad/s (None if not recorded).
    """

    time: FloatArray
    journals: FloatArray
    nodes: FloatArray
    labels: tuple[str, ...]
    wall_time: float
    message: str
    steps: int = 0
    factorizations: int = 0
    newton_iterations: int = 0
    status: str = "completed"
    speed: FloatArray | None = None
    checkpoint: dict[str, Any] | None = None

    @property
    def resumable(self) -> bool:
        """Whether the run can go on (stopped or interrupted, with a checkpoint)."""
        return self.checkpoint is not None and self.status not in ("completed", "contact")

    def joined(self, later: RotorOrbit) -> RotorOrbit:
        """This run followed by ``later``, its continuation (samples after this one's end)."""
        new = later.time > self.time[-1] + 1e-12
        speed = None
        if self.speed is not None and later.speed is not None:
            speed = np.concatenate([self.speed, later.speed[new]])
        return RotorOrbit(
            np.concatenate([self.time, later.time[new]]),
            np.concatenate([self.journals, later.journals[:, :, new]], axis=2),
            np.concatenate([self.nodes, later.nodes[:, :, new]], axis=2),
            later.labels,
            self.wall_time + later.wall_time,
            later.message,
            self.steps + later.steps,
            self.factorizations + later.factorizations,
            self.newton_iterations + later.newton_iterations,
            later.status,
            speed,
            later.checkpoint,
        )

    def subsynchronous_onset(self, profile: SpeedProfile) -> Any:
        """Sustained sub-synchronous motion of bearing A's X, read as the single-bearing
        speed-ups are (:func:`foilbearing.signals.onset`): an ``Onset``, or None for a run
        shorter than :data:`READ_AFTER` (the analysis' windows need it)."""
        from foilbearing.signals import onset, subsynchronous_amplitude

        if self.time[-1] - self.time[0] < READ_AFTER:
            return None
        speed, phase = profile.speed_and_phase(self.time)
        return onset(subsynchronous_amplitude(self.time, self.journals[0, 0], speed, phase))

    def amplitude(self) -> FloatArray:
        """Each bearing's largest journal excursion from its mean position, m,
        shape (n_bearings,)."""
        centred = self.journals - self.journals.mean(axis=2, keepdims=True)
        return np.asarray(np.hypot(centred[:, 0], centred[:, 1]).max(axis=1), float)

    def to_dataset(self, title: str = "") -> Any:
        """The run as an ``xarray.Dataset`` (SI units in attributes)."""
        import xarray as xr

        data: dict[str, Any] = {
            "journal": (("bearing", "axis", "time"), self.journals,
                        {"units": "m", "long_name": "journal displacement in the bearing's "
                         "frame (X along its load)"}),
            "node_displacement": (("node", "ross_axis", "time"), self.nodes,
                                  {"units": "m", "long_name": "lateral displacement, ROSS's "
                                   "frame (x = Y, y = -X)"}),
        }  # fmt: skip
        if self.speed is not None:
            data["speed"] = (("time",), self.speed, {"units": "rad/s"})
        for key, value in (self.checkpoint or {}).items():
            arr = np.asarray(value, float)
            dims = tuple(f"checkpoint_{key}_{k}" for k in range(arr.ndim))
            data[f"checkpoint_{key}"] = (dims, arr)
        return xr.Dataset(
            data,
            coords={
                "time": ("time", self.time, {"units": "s"}),
                "bearing": list(self.labels),
                "axis": ["X", "Y"],
                "ross_axis": ["x", "y"],
                "node": np.arange(self.nodes.shape[0]),
            },
            attrs={
                "title": title,
                "status": self.status,
                "message": self.message,
                "steps": self.steps,
                "factorizations": self.factorizations,
                "newton_iterations": self.newton_iterations,
                "wall_time_s": self.wall_time,
            },
        )


class RotorOrbitSystem:
    """The rotor on its bearings as one semi-discrete system (module docstring).

    Parameters
    ----------
    rotor
        The rotor; each bearing runs on its case's orbit grid
        (:meth:`foilbearing.case.Case.orbit_case`) at the load the rotor puts on it.
    model
        Its ROSS rotor (:func:`foilbearing.rotor.ross_rotor`); only the shaft and disks are
        used, not the bearings' tables. None: the shaft and disks alone
        (:func:`~foilbearing.rotor.linear.ross_shaft`).
    speed
        The speed profile.
    n_modes
        Shaft modes kept in the reduction (``tests/test_rotor.py`` shows the convergence).
    voltages
        One voltage program per bearing (None: the case's voltages held): a ramp, a
        schedule, or a closed-loop controller reading its own journal's X motion (on the
        stepper, :func:`foilbearing.rotor.stepper.run_rotor`).
    unbalances
        Unbalances at nodes.
    settings
        The bearings' orbit settings (their tolerances are used).
    """

    def __init__(
        self,
        rotor: RotorCase,
        model: Any | None,
        speed: SpeedProfile,
        *,
        n_modes: int = 8,
        voltages: Sequence[VoltageProgram | None] | None = None,
        unbalances: Sequence[Unbalance] = (),
        settings: OrbitSettings | None = None,
    ) -> None:
        if voltages is None:
            voltages = [None] * len(rotor.bearings)
        if model is None:
            from foilbearing.rotor.linear import ross_shaft

            model = ross_shaft(rotor)
        if len(voltages) != len(rotor.bearings):
            raise InputError(
                f"voltages: {len(voltages)} programs for {len(rotor.bearings)} bearings"
            )
        n_nodes = len(rotor.shaft) + 1
        for u in unbalances:
            if not 0 <= u.node < n_nodes:
                raise InputError(
                    f"unbalance at node {u.node}: the shaft has nodes 0 to {n_nodes - 1}",
                    source=rotor.source,
                )
        self.rotor, self.speed = rotor, speed
        self.labels = tuple(b.label for b in rotor.bearings)
        self.reduced: ReducedRotor = reduce_rotor(model, [b.node for b in rotor.bearings], n_modes)
        self.sims = [
            OrbitSimulation(case, speed, program, settings)
            for case, program in zip(rotor.loaded_cases(), voltages, strict=True)
        ]
        self.film_sizes = [s.system.n + s.system.nt for s in self.sims]
        self.offsets = np.concatenate([[0], np.cumsum(self.film_sizes)]).astype(int)
        self.n_film = int(self.offsets[-1])
        self.m = self.reduced.size
        self.size = self.n_film + 2 * self.m
        self.mass_inv = np.linalg.inv(self.reduced.mass)
        self.unbalances = tuple(unbalances)
        # Gravity along ROSS's −y on the consistent mass: each node's share of the weight.
        n_lat = self.reduced.basis.shape[0]
        accel = np.zeros(n_lat)
        accel[1::4] = -rotor.gravity
        lateral = lateral_dofs(n_nodes)
        m_lat = np.asarray(model.M0, float)[np.ix_(lateral, lateral)]
        self.gravity = self.reduced.basis.T @ (m_lat @ accel)
        self.force_per_pressure = [s.bearing.scales.force * s.system.w for s in self.sims]

    # ------------------------------------------------------------------ pieces
    def unbalance_force(self, t: float) -> FloatArray:
        """The unbalances' force on the reduced coordinates at t, N."""
        if not self.unbalances:
            return np.zeros(self.m)
        w, wd, phi = self.speed.state(t)
        f = np.zeros(self.reduced.basis.shape[0])
        for u in self.unbalances:
            angle = phi + u.phase - 0.5 * math.pi  # from ROSS's +x; our +X is its −y
            c, s = math.cos(angle), math.sin(angle)
            f[4 * u.node] += u.magnitude * (w * w * c + wd * s)
            f[4 * u.node + 1] += u.magnitude * (w * w * s - wd * c)
        return np.asarray(self.reduced.basis.T @ f, float)

    def initial_state(self) -> FloatArray:
        """Each bearing's static equilibrium at the start, the shaft bent by its weight."""
        y = np.zeros(self.size)
        q = np.zeros(self.m)
        for b, sim in enumerate(self.sims):
            single = sim.initial_state()
            k = self.film_sizes[b]
            y[self.offsets[b] : self.offsets[b + 1]] = single[:k]
            c = sim.case.bearing.clearance
            eps_x, eps_y = single[k], single[k + 1]
            q[2 * b], q[2 * b + 1] = eps_y * c, -eps_x * c
        nb = 2 * len(self.sims)
        red = self.reduced
        # The shaft modes' rows are uncoupled from the journals' in K (Craig-Bampton).
        q[nb:] = np.linalg.solve(red.stiffness[nb:, nb:], self.gravity[nb:])
        y[self.n_film : self.n_film + self.m] = q
        return y

    def atol(self) -> FloatArray:
        """Absolute tolerances: the bearings' on their films, theirs on position (in C) on
        the rotor's coordinates (m, and m/s times the top speed for the rates)."""
        parts = [s.atol()[:k] for s, k in zip(self.sims, self.film_sizes, strict=True)]
        sim = self.sims[0]
        c = sim.case.bearing.clearance
        pos = sim.settings.atol_position * c
        top = max(float(self.speed.speeds.max()), 1.0)
        return np.concatenate([*parts, np.full(self.m, pos), np.full(self.m, pos * top)])

    if not TYPE_CHECKING:  # the type checker still sees no such attributes

        def __getattr__(self, name: str) -> Any:
            if name in _IVP_METHODS:
                raise AttributeError(
                    f"RotorOrbitSystem.{name} moved to the test oracles: "
                    f"foilbearing.testing.ivp_rotor.RotorIVP(system).{name}"
                )
            raise AttributeError(f"'RotorOrbitSystem' object has no attribute '{name}'")


def _check_run(ds: Any, checkpoint: dict[str, Any], source: str) -> None:
    """One-line errors for a rotor run whose status, series or checkpoint is damaged:
    what a resume would read, checked before it integrates from it."""
    from foilbearing.orbit.result import RunStatus

    status = ds.attrs.get("status", "completed")
    if status not in {s.value for s in RunStatus}:
        raise InputError(f"status = {status!r}: not a run's status (damaged)", source=source)
    for name in ("time", "journal", "node_displacement"):
        if not np.all(np.isfinite(ds[name].values)):
            raise InputError(f"{name} holds values that are not finite (damaged)", source=source)
    if np.any(np.diff(ds["time"].values) <= 0.0):
        raise InputError("time is not increasing (damaged)", source=source)
    for key, value in checkpoint.items():
        if not np.all(np.isfinite(np.asarray(value, float))):
            raise InputError(
                f"checkpoint_{key} holds values that are not finite (damaged)", source=source
            )
    if not checkpoint:
        return
    t, time = float(np.ravel(checkpoint.get("t", [np.nan]))[0]), ds["time"].values
    spacing = float(time[1] - time[0]) if time.size > 1 else np.inf
    if not time[-1] - 1e-12 <= t < time[-1] + spacing + 1e-12:
        raise InputError(
            f"checkpoint_t = {t!r} s: expected the last step's time, from the last sample "
            f"({time[-1]!r} s) to one sample after it (damaged)",
            source=source,
        )


def load_rotor_orbit(path: Any) -> tuple[RotorOrbit, dict[str, Any]]:
    """Read a rotor run written by :meth:`RotorOrbit.to_dataset`: the run (with its
    checkpoint) and the dataset's attributes.

    Raises
    ------
    InputError
        Not a rotor run (one line, naming the file).
    """
    import xarray as xr

    try:
        ds = xr.load_dataset(path)
    except (OSError, ValueError) as exc:
        raise InputError(
            f"cannot read the run ({exc.__class__.__name__})", source=str(path)
        ) from None
    if "journal" not in ds or "node_displacement" not in ds:
        raise InputError("not a foilbearing rotor run", source=str(path))
    checkpoint = {
        str(k).removeprefix("checkpoint_"): np.asarray(ds[k].values)
        for k in ds.data_vars
        if str(k).startswith("checkpoint_")
    }
    a = ds.attrs
    _check_run(ds, checkpoint, str(path))
    run = RotorOrbit(
        np.asarray(ds["time"].values, float),
        np.asarray(ds["journal"].values, float),
        np.asarray(ds["node_displacement"].values, float),
        tuple(str(b) for b in ds["bearing"].values),
        float(a.get("wall_time_s", 0.0)),
        str(a.get("message", "")),
        int(a.get("steps", 0)),
        int(a.get("factorizations", 0)),
        int(a.get("newton_iterations", 0)),
        str(a.get("status", "completed")),
        np.asarray(ds["speed"].values, float) if "speed" in ds else None,
        checkpoint or None,
    )
    return run, dict(a)
