"""The bearing case as frozen dataclasses, SI inside, validated on creation and on change.

The tables of a case file (docs/case-format.md) map one to one onto these
classes; :mod:`foilbearing.case.toml` reads and checks a file into them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from foilbearing.bearing_system.scales import Scales
from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.laws.actuator import ACTUATOR_DYNAMICS, PRELOAD_RESPONSES, ActuatorReading
from foilbearing.laws.foil_damping import FoilDamping, ViscousBump
from foilbearing.structure import (
    actuator_stiffness,
    assembly_stiffness,
    base_preload,
    iordanoff_bump_stiffness,
    stack_displacement,
    walowit_anno_bump_stiffness,
)
from foilbearing.units import QuantityLike, as_si, as_si_array

__all__ = [
    "ACTUATOR_DYNAMICS",
    "MAX_LIFT_OFF_SMOOTHING",
    "MAX_SPEED_DEFAULT",
    "PRELOAD_RESPONSES",
    "SUBAMBIENT_MODELS",
    "Actuators",
    "Bearing",
    "BumpGeometry",
    "Case",
    "Disturbance",
    "Foil",
    "Gas",
    "Grid",
    "Operation",
    "Rotor",
    "Shims",
    "check_actuators",
    "per_item",
    "require",
]


#: Largest smoothing κ of the lifted-off edge a case may ask for (δ = κΔθ², the law
#: (P − 1)·y/Λ = δ²): at 0.5 the smoothing's own error moves the 0 V onset on 96 θ cells
#: by 5 %, beyond the grid's (docs/lift-off.md, "The smoothed edge").
MAX_LIFT_OFF_SMOOTHING = 1.0
#: Default top of the speeds an analysis may be asked for, rad/s (150 000 rpm, the top
#: of the default onset scan); a case sets its own with ``[operation] max_speed``.
MAX_SPEED_DEFAULT = 150_000 * RPM


@dataclass(frozen=True)
class Bearing:
    """Journal and bearing geometry, m."""

    radius: float
    length: float
    clearance: float


@dataclass(frozen=True)
class Gas:
    """Isothermal, isoviscous ideal gas."""

    viscosity: float  # Pa·s
    ambient_pressure: float  # Pa


@dataclass(frozen=True)
class BumpGeometry:
    """Bump-foil geometry and material, SI."""

    thickness: float  # t_b, m
    height: float  # h_b, m
    pitch: float  # s, m
    half_length: float  # l_0, m
    youngs_modulus: float  # E, Pa
    poisson_ratio: float  # ν
    friction_coefficient: float = 0.0  # μ_f at the bump feet (Iordanoff)
    top_foil_thickness: float | None = None  # m, informational
    formula: str = "iordanoff"  # or "walowit-anno"

    def stiffness(self) -> float:
        """Bump stiffness per unit area from the geometry, N/m³."""
        if self.formula == "walowit-anno":
            return walowit_anno_bump_stiffness(
                self.thickness,
                self.pitch,
                self.half_length,
                self.youngs_modulus,
                self.poisson_ratio,
            )
        return iordanoff_bump_stiffness(
            self.thickness,
            self.height,
            self.pitch,
            self.half_length,
            self.youngs_modulus,
            self.poisson_ratio,
            self.friction_coefficient,
        )


#: How a foil bearing treats sub-ambient film pressure (docs/model.md §3).
SUBAMBIENT_MODELS = ("lift-off", "retained")

# The actuator readings' words (docs/model.md §3.8) are the law's: foilbearing.laws.actuator.


@dataclass(frozen=True)
class Foil:
    """Compliant foil: an elastic foundation of stiffness k_b per unit area with loss factor γ.

    ``subambient`` says what the film does where its pressure falls below
    ambient (docs/model.md §3): ``"lift-off"`` (default) — the top foil,
    which only rests on the bumps, is pulled off them towards the journal
    until the suction is relieved, so the film holds no sub-ambient pressure
    (``P ≥ 1`` as a complementarity condition); ``"retained"`` — the foil
    stays on the bumps and the film keeps its sub-ambient pressure, as a rigid
    surface would (the model before lift-off, kept for comparison).

    The foil damping law is :attr:`damping_law`: the viscous bump of ``loss_factor``
    unless another law is given as ``damping`` (:mod:`foilbearing.laws.foil_damping`).
    """

    bump_stiffness: float  # k_b, N/m³
    loss_factor: float  # γ
    bump: BumpGeometry | None = None
    subambient: str = "lift-off"
    #: The foil damping law in place of the viscous bump of ``loss_factor`` (None: that
    #: law); e.g. :class:`foilbearing.laws.NoFoilDamping` to try the spring alone.
    damping: FoilDamping | None = None

    @property
    def damping_law(self) -> FoilDamping:
        """The foil damping law every analysis uses: ``damping``, or
        :class:`~foilbearing.laws.ViscousBump` of ``loss_factor``."""
        return self.damping if self.damping is not None else ViscousBump(self.loss_factor)

    @property
    def lift_off(self) -> bool:
        """Whether sub-ambient film pressure lifts the top foil (no suction held)."""
        return self.subambient == "lift-off"


@dataclass(frozen=True)
class Actuators:
    """PZT actuators pushing the foil through stingers (paper section 2-3)."""

    angles: tuple[float, ...]  # θ_n, rad
    stinger_arc: float  # θ_s, rad
    contact_area: float  # A_c, m²
    d33_quadratic: float  # D33,1, m/V²
    d33_linear: float  # D33,2, m/V
    stack_stiffness: float  # K_p, N/m
    holder_spring_stiffness: float  # k_sp per unit area, each of four, N/m³
    holder_pre_extension: float  # δ_pre, m
    voltages: tuple[float, ...]  # V per actuator
    max_voltage: float  # V
    smoothness: float = 50.0  # α of k(θ), 1/rad
    #: How the stack's compression enters the film statically, one of PRELOAD_RESPONSES.
    preload_response: str = "local"
    #: How the stack's compliance acts during the motion, one of ACTUATOR_DYNAMICS.
    dynamics: str = "compliant"

    @property
    def reading(self) -> ActuatorReading:
        """The actuator reading in the film (:class:`foilbearing.laws.ActuatorReading`)."""
        return ActuatorReading(self.preload_response, self.dynamics)

    @property
    def k_p(self) -> float:
        """Stack stiffness per unit contact area, N/m³."""
        return self.stack_stiffness / self.contact_area

    @property
    def stiffness(self) -> float:
        """Actuator stiffness per unit area k_p + 4k_sp, N/m³."""
        return actuator_stiffness(self.k_p, self.holder_spring_stiffness)

    def stack_strokes(self) -> np.ndarray:
        """Free stroke of each stack at its voltage, m (Eq. 2)."""
        return stack_displacement(np.array(self.voltages), self.d33_quadratic, self.d33_linear)

    def base_preloads(self) -> np.ndarray:
        """Base piezoelectric preload of each actuator at its voltage, m (Eq. 3b, p_A = 0)."""
        return base_preload(
            np.array(self.voltages),
            self.d33_quadratic,
            self.d33_linear,
            self.k_p,
            self.holder_spring_stiffness,
            self.holder_pre_extension,
        )


@dataclass(frozen=True)
class Shims:
    """Rigid shims under the foil: the shimmed GFB."""

    angles: tuple[float, ...]  # rad
    arc: float  # rad
    thicknesses: tuple[float, ...]  # m, one per shim


@dataclass(frozen=True)
class Rotor:
    """Rigid rotor mass carried by this bearing and its imbalance: the journal of one bearing
    (``Case.rotor``, the case file's ``[rotor]``).

    Not the flexible shaft of :mod:`foilbearing.rotor` (a ``RotorCase`` of beam elements
    and disks on two bearings, each a ``Case`` whose ``rotor`` is the share it carries).
    """

    mass: float  # kg
    imbalance: float  # kg·m (mass times radius)

    @property
    def imbalance_radius(self) -> float:
        """u_im = imbalance / mass, m."""
        return self.imbalance / self.mass


@dataclass(frozen=True)
class Disturbance:
    """Random force on the rotor besides the imbalance: rig vibration, flow noise (orbits only).

    A sum of ``tones`` sinusoids per direction (X and Y), of equal amplitude, at
    frequencies drawn uniformly in [min_frequency, max_frequency] and random phases,
    from the generator seeded by ``seed`` (:mod:`foilbearing.orbit.disturbance`). It
    seeds the growth of a whirl past its onset: without it the seed is whatever the
    numerics leave, and a speed-up's divergence speed depends on the solver's
    tolerances (docs/development/orbit-performance.md).
    """

    force_rms: float  # N, RMS of the force along each of X and Y
    min_frequency: float  # Hz
    max_frequency: float  # Hz
    seed: int = 1
    tones: int = 256


@dataclass(frozen=True)
class Operation:
    """Operating point: static load along +X and rotor speed, and the speeds analyses may use."""

    load: float  # N
    speed: float  # rad/s
    max_speed: float = MAX_SPEED_DEFAULT  # rad/s, the top of any speed range asked for


#: Fewest θ cells across a stinger arc (or a shim) on an orbit's grid: the stinger's
#: compliance and its mean pressure are taken over the cells of its arc, and a coarser
#: grid sees the actuator in one cell or none (docs/development/orbit-performance.md, "The orbit's grid").
MIN_CELLS_PER_STINGER = 2


@dataclass(frozen=True)
class Grid:
    """Finite-volume grid of the film: cells around the bearing and axially over half its length.

    ``n_theta`` × ``n_z`` set the static and linear analyses. The orbit runs on
    ``orbit_n_theta`` × ``orbit_n_z`` where they are given (None: the same), and a
    linear analysis on that grid is its by-construction partner (:meth:`Case.orbit_case`).
    ``axial_order`` (2 or 4) is the order of the axial discretisation
    (:class:`foilbearing.reynolds.grid.FilmGrid`); ``orbit_axial_order`` the orbit's
    (None: the same). ``lift_off_smoothing`` (κ >= 0) smooths the lifted-off edge of the
    film on a length tied to the cell, the same law in every analysis (0: the sharp
    complementarity; :class:`foilbearing.reynolds.grid.FilmGrid`).

    The defaults are the numerics the project has validated, those of the built-in case
    (docs/case-format.md, ``[grid]``): 96 × 12 at second order, κ = 0.1, the orbit on
    96 × 4 at fourth order. A case file's ``[grid]`` (or a field it leaves out) and
    ``Grid()`` both get them; the sharp law is ``lift_off_smoothing=0.0`` and one grid for
    every analysis ``orbit_n_z=None, orbit_axial_order=None``, stated where wanted.
    """

    n_theta: int = 96
    n_z: int = 12
    orbit_n_theta: int | None = None
    orbit_n_z: int | None = 4
    axial_order: int = 2
    orbit_axial_order: int | None = 4
    lift_off_smoothing: float = 0.1

    @property
    def orbit_shape(self) -> tuple[int, int]:
        """(n_theta, n_z) of the orbit's grid."""
        return (self.orbit_n_theta or self.n_theta, self.orbit_n_z or self.n_z)

    @property
    def orbit_order(self) -> int:
        """Axial order of the orbit's grid."""
        return self.orbit_axial_order or self.axial_order

    @property
    def orbit_is_own(self) -> bool:
        """The orbit runs on another grid than the static and linear analyses."""
        return (*self.orbit_shape, self.orbit_order) != (self.n_theta, self.n_z, self.axial_order)

    @property
    def orbit_grid(self) -> Grid:
        """The orbit's grid as a grid of its own, the same for every analysis."""
        n_theta, n_z = self.orbit_shape
        # the orbit fields stated, not None: a case file (and a run record) reads them back
        return Grid(
            n_theta,
            n_z,
            orbit_n_z=n_z,
            axial_order=self.orbit_order,
            orbit_axial_order=self.orbit_order,
            lift_off_smoothing=self.lift_off_smoothing,
        )

    @property
    def orbit_label(self) -> str:
        """The orbit's grid in words, e.g. ``"96 × 4 (axial order 4)"``."""
        n_theta, n_z = self.orbit_shape
        notes = [f"axial order {self.orbit_order}"] if self.orbit_order != 2 else []
        if self.lift_off_smoothing:
            notes.append(f"lift-off smoothing {self.lift_off_smoothing:g}")
        return f"{n_theta} × {n_z}" + (f" ({', '.join(notes)})" if notes else "")


@dataclass(frozen=True)
class Case:
    """A bearing case. All fields SI; see the module docstring for the file format."""

    bearing: Bearing
    gas: Gas
    rotor: Rotor
    operation: Operation
    grid: Grid = field(default_factory=Grid)
    foil: Foil | None = None
    actuators: Actuators | None = None
    shims: Shims | None = None
    title: str = ""
    source: str | None = None
    #: The optional ``[study]`` table as JSON text, read and checked by
    #: :func:`foilbearing.study.plan.study_plan` (it belongs to the study, not the bearing).
    study_table: str | None = None
    #: Random force on the rotor in the orbits (``[disturbance]``); None: none.
    disturbance: Disturbance | None = None

    @property
    def kind(self) -> str:
        """``"C-GFB"`` (actuators), ``"shimmed GFB"``, ``"GFB"`` (passive foil) or ``"rigid"``."""
        if self.foil is None:
            return "rigid"
        if self.actuators is not None:
            return "C-GFB"
        return "shimmed GFB" if self.shims is not None else "GFB"

    def bearing_number(self, speed: float | None = None) -> float:
        """Λ = 6 μ ω R² / (p_a C²) at ``speed`` (rad/s; default: the operating speed), from
        the bearing's :class:`~foilbearing.bearing_system.scales.Scales`."""
        omega = self.operation.speed if speed is None else speed
        return Scales.from_parts(self.bearing, self.gas).bearing_number(omega)

    def assembly_stiffness(self) -> float | None:
        """k_assy under a stinger, N/m³ (Eq. 7); None without foil or actuators."""
        if self.foil is None or self.actuators is None:
            return None
        return assembly_stiffness(
            self.foil.bump_stiffness, self.actuators.k_p, self.actuators.holder_spring_stiffness
        )

    def with_voltages(self, voltages: Any) -> Case:
        """The same case with new actuator voltages (one for all, or one per actuator), validated.

        Volts as floats, or quantities: ``"150 V"``, ``["0 V", "150 V", ...]``, a pint
        ``Quantity``."""
        if self.actuators is None:
            raise InputError(
                "this case has no [actuators]: a voltage cannot be set", source=self.source
            )
        magnitude = getattr(voltages, "magnitude", None)
        if isinstance(voltages, str) or (magnitude is not None and np.ndim(magnitude) == 0):
            voltages = as_si(voltages, "voltage", field="actuators.voltages")
        elif not isinstance(voltages, int | float):
            field_name = "actuators.voltages"
            voltages = tuple(float(v) for v in as_si_array(voltages, "voltage", field=field_name))
        volts = per_item(voltages, len(self.actuators.angles), "actuators.voltages", self.source)
        act = replace(self.actuators, voltages=volts)
        check_actuators(act, self.bearing, self.source)
        return replace(self, actuators=act)

    def with_subambient(self, model: str) -> Case:
        """The same case with another sub-ambient film model: ``"lift-off"`` or ``"retained"``.

        Only a bearing with a ``[foil]`` has the choice: rigid surfaces hold suction.
        """
        if model not in SUBAMBIENT_MODELS:
            raise InputError(
                f"subambient = {model!r}: expected one of "
                + ", ".join(repr(m) for m in SUBAMBIENT_MODELS),
                source=self.source,
            )
        if self.foil is None:
            raise InputError(
                f"subambient = {model!r}: this bearing has no [foil]; a rigid surface holds "
                "sub-ambient pressure (add a [foil] table, or drop the option)",
                source=self.source,
            )
        return replace(self, foil=replace(self.foil, subambient=model))

    def with_actuator_reading(
        self, preload_response: str | None = None, dynamics: str | None = None
    ) -> Case:
        """The same case with another reading of the actuator in the film (docs/model.md §3.8).

        Parameters
        ----------
        preload_response
            ``"local"`` (the stack's compression carves a pocket under the stinger) or
            ``"lobe"`` (it lowers the whole preload lobe); None keeps the case's.
        dynamics
            ``"compliant"`` (the stack's compliance acts at the motion's frequency) or
            ``"held"`` (the stinger keeps its quasi-static position); None keeps the case's.
        """
        act = self.actuators
        for name, value, allowed in (
            ("preload_response", preload_response, PRELOAD_RESPONSES),
            ("dynamics", dynamics, ACTUATOR_DYNAMICS),
        ):
            if value is None:
                continue
            if value not in allowed:
                raise InputError(
                    f"actuators.{name} = {value!r}: expected one of "
                    + ", ".join(repr(a) for a in allowed),
                    source=self.source,
                )
            if act is None:
                raise InputError(
                    f"actuators.{name} = {value!r}: this case has no [actuators] (a shimmed, "
                    "passive or rigid bearing has no stack); drop the option",
                    source=self.source,
                )
        if act is None:
            return self
        return replace(
            self,
            actuators=replace(
                act,
                preload_response=preload_response or act.preload_response,
                dynamics=dynamics or act.dynamics,
            ),
        )

    def check_speeds(self, speeds: Any, field: str = "speed") -> None:
        """A one-line error for any speed (rad/s) outside ``(0, operation.max_speed]``.

        Every analysis checks its speeds here before any work: no bearing of this case is
        meant to run faster, and a film solved at, say, 1e7 rpm is no answer.
        """
        w = np.atleast_1d(np.asarray(speeds, float))
        top = self.operation.max_speed
        if w.size and np.all(np.isfinite(w)) and w.min() > 0.0 and w.max() <= top * (1 + 1e-12):
            return
        rpm = 1.0 / RPM
        if w.size == 0:
            shown = "empty"
        elif w.min() == w.max():
            shown = f"= {w[0] * rpm:.6g} rpm"
        else:
            shown = f"{w.min() * rpm:.6g}-{w.max() * rpm:.6g} rpm"
        raise InputError(
            f"{field} {shown}: allowed above 0 and up to operation.max_speed = "
            f"{top * rpm:.0f} rpm (raise [operation] max_speed to go faster)",
            source=self.source,
        )

    def orbit_case(self) -> Case:
        """The same case on the orbit's grid (``[grid] orbit_n_theta``, ``orbit_n_z``).

        Every orbit runs on it, and a static or linear analysis of the returned case is
        the orbit's partner on one grid (its whirl eigenvalue and onset). The case itself
        when the orbit has no grid of its own.

        Raises
        ------
        InputError
            The orbit grid cannot carry the case: fewer than
            :data:`MIN_CELLS_PER_STINGER` θ cells across a stinger arc or a shim.
        """
        g = self.grid
        n_theta = g.orbit_shape[0]
        arc = None
        if self.actuators is not None:
            arc = self.actuators.stinger_arc
        elif self.shims is not None:
            arc = self.shims.arc
        if arc is not None and arc * n_theta / (2.0 * math.pi) < MIN_CELLS_PER_STINGER:
            field_name = "orbit_n_theta" if g.orbit_n_theta is not None else "n_theta"
            need = math.ceil(MIN_CELLS_PER_STINGER * 2.0 * math.pi / arc)
            raise InputError(
                f"grid.{field_name} = {n_theta}: the orbit needs at least "
                f"{MIN_CELLS_PER_STINGER} cells across the {math.degrees(arc):.1f} deg stinger "
                f"arc to resolve the actuators, so n_theta >= {need}",
                source=self.source,
            )
        if not g.orbit_is_own:
            return self
        return replace(self, grid=g.orbit_grid)

    def with_speed(self, speed: QuantityLike) -> Case:
        """The same case at another rotor speed (> 0): rad/s as a float, or a quantity
        (``"30 krpm"``, a pint ``Quantity``)."""
        speed = as_si(speed, "speed", field="operation.speed")
        require(speed > 0.0, "operation.speed", speed, "> 0 rad/s", self.source)
        return replace(self, operation=replace(self.operation, speed=speed))

    def with_load(self, load: QuantityLike) -> Case:
        """The same case under another static load along +X (>= 0, finite), validated.

        ``load`` in N as a float, or a quantity: ``"50 N"``, a pint ``Quantity``.

        The load is an input like the speed: the rotor mass (``[rotor] mass``) is not
        changed with it. The mass is the rotor's inertia in the orbits and the rigid
        rotor's stability; the load is the static force the film carries
        (docs/case-format.md, "Load and rotor mass").
        """
        value = as_si(load, "force", field="operation.load")
        require(
            math.isfinite(value) and value >= 0.0, "operation.load", load, ">= 0 N", self.source
        )
        return replace(self, operation=replace(self.operation, load=value))

    def shimmed(self) -> Case:
        """The shimmed GFB equivalent to this C-GFB (paper Fig. 8).

        Rigid shims at the actuator angles, of the stinger arc, as thick as the
        base piezoelectric preloads at the present voltages; no actuators.
        """
        if self.actuators is None:
            raise InputError("this case has no [actuators] to replace by shims", source=self.source)
        act = self.actuators
        shims = Shims(act.angles, act.stinger_arc, tuple(float(x) for x in act.base_preloads()))
        return replace(self, actuators=None, shims=shims, title=f"{self.title} (shimmed)")


def check_actuators(act: Actuators, bearing: Bearing, source: str | None) -> None:
    for i, v in enumerate(act.voltages):
        if not 0.0 <= v <= act.max_voltage:
            raise InputError(
                f"actuators.voltages[{i}] = {v:g} V: allowed 0 to max_voltage = {act.max_voltage:g} V",
                source=source,
            )
    base = act.base_preloads()
    for i, d in enumerate(base):
        if d < 0.0:
            raise InputError(
                f"actuators.holder_pre_extension = {act.holder_pre_extension * 1e6:g} um at "
                f"voltages[{i}] = {act.voltages[i]:g} V gives a negative base preload "
                f"({d * 1e6:.2f} um): the stinger would leave the foil; lower the pre-extension",
                source=source,
            )
        if d >= bearing.clearance:
            raise InputError(
                f"actuators.voltages[{i}] = {act.voltages[i]:g} V gives a base preload of "
                f"{d * 1e6:.2f} um, at or beyond the clearance {bearing.clearance * 1e6:.2f} um: "
                "lower the voltage or enlarge the clearance",
                source=source,
            )


def per_item(value: Any, n: int, field: str, source: str | None) -> tuple[float, ...]:
    if isinstance(value, int | float):
        return (float(value),) * n
    items = tuple(float(v) for v in value)
    if len(items) != n:
        raise InputError(
            f"{field}: {len(items)} values given, expected 1 or {n} (one per actuator)",
            source=source,
        )
    return items


def require(ok: bool, field: str, value: float, allowed: str, source: str | None) -> None:
    if not ok:
        raise InputError(f"{field} = {value!r}: expected {allowed}", source=source)
