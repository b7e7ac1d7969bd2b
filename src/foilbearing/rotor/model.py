"""A rotor on foil bearings: a shaft of beam elements, rigid disks, and bearings at nodes.

Every number is SI. The shaft's elements run from node 0 along the axis, element k
between nodes k and k + 1; disks and bearings sit at nodes. Each bearing is a bearing
case (:class:`foilbearing.case.Case`, with its own voltages and grid) whose static load
is not its own ``[operation] load`` but the share of the rotor's weight that the bearing
carries (:meth:`RotorCase.bearing_loads`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from foilbearing.case import Case
from foilbearing.errors import InputError

__all__ = ["STANDARD_GRAVITY", "BearingSite", "Disk", "Material", "RotorCase", "ShaftElement"]

STANDARD_GRAVITY = 9.80665  # m/s²


@dataclass(frozen=True)
class Material:
    """The shaft's material: density (kg/m³), Young's modulus (Pa), Poisson's ratio."""

    density: float
    youngs_modulus: float
    poisson_ratio: float


@dataclass(frozen=True)
class ShaftElement:
    """A beam element of the shaft: length, outer and inner diameters, m."""

    length: float
    outer_diameter: float
    inner_diameter: float = 0.0

    def mass(self, material: Material) -> float:
        """kg."""
        area = math.pi / 4.0 * (self.outer_diameter**2 - self.inner_diameter**2)
        return material.density * area * self.length


@dataclass(frozen=True)
class Disk:
    """A rigid disk at a node: mass (kg), polar and diametral moments of inertia (kg·m²)."""

    node: int
    mass: float
    polar_inertia: float
    diametral_inertia: float


@dataclass(frozen=True)
class BearingSite:
    """A bearing at a node: its bearing case (the load is set by the rotor) and a label."""

    node: int
    case: Case
    label: str


@dataclass(frozen=True)
class RotorCase:
    """The rotor: shaft, disks, bearings and gravity (m/s², acting along the bearings' +X).

    Attributes
    ----------
    title
        A name for reports.
    material, shaft, disks, bearings
        As their classes say; ``shaft`` from node 0.
    gravity
        m/s², acting along each bearing's +X (docs/model.md §2: X is the load's direction).
    source
        The rotor file, if read from one (for error messages).
    """

    title: str
    material: Material
    shaft: tuple[ShaftElement, ...]
    disks: tuple[Disk, ...]
    bearings: tuple[BearingSite, ...]
    gravity: float = STANDARD_GRAVITY
    source: str | None = None

    def __post_init__(self) -> None:
        nodes = len(self.shaft) + 1
        at: list[tuple[str, int]] = [(f"disks[{k}]", d.node) for k, d in enumerate(self.disks)]
        at += [(f"bearings[{k}]", b.node) for k, b in enumerate(self.bearings)]
        for name, node in at:
            if not 0 <= node < nodes:
                raise InputError(
                    f"{name}.node = {node}: the shaft has nodes 0 to {nodes - 1}",
                    source=self.source,
                )
        if len({b.node for b in self.bearings}) != len(self.bearings):
            raise InputError("bearings: two bearings at one node", source=self.source)

    @property
    def positions(self) -> np.ndarray:
        """Axial position of each node, m (node 0 at 0)."""
        return np.concatenate([[0.0], np.cumsum([e.length for e in self.shaft])])

    @property
    def mass(self) -> float:
        """The rotor's mass, shaft and disks, kg."""
        return sum(e.mass(self.material) for e in self.shaft) + sum(d.mass for d in self.disks)

    def weights(self) -> tuple[np.ndarray, np.ndarray]:
        """(axial positions, m; weights, N) of the shaft's elements and the disks."""
        z = self.positions
        at = [0.5 * (z[k] + z[k + 1]) for k in range(len(self.shaft))]
        w = [e.mass(self.material) * self.gravity for e in self.shaft]
        at += [z[d.node] for d in self.disks]
        w += [d.mass * self.gravity for d in self.disks]
        return np.array(at), np.array(w)

    def bearing_loads(self) -> tuple[float, ...]:
        """The weight each bearing carries, N, in the order of ``bearings``.

        Two bearings: the reactions of a beam on two supports, from the balance of forces
        and of moments (exact, whatever the shaft's stiffness). One bearing carries the whole
        weight. More than two share it according to the shaft's stiffness, which this does
        not compute: an InputError.
        """
        at, w = self.weights()
        if len(self.bearings) == 1:
            return (float(w.sum()),)
        if len(self.bearings) != 2:
            raise InputError(
                f"bearings: {len(self.bearings)} bearings; the static loads are computed for "
                "one or two bearings (more share the weight by the shaft's stiffness)",
                source=self.source,
            )
        z = self.positions
        za, zb = z[self.bearings[0].node], z[self.bearings[1].node]
        rb = float(np.sum(w * (at - za)) / (zb - za))
        return (float(w.sum()) - rb, rb)

    def loaded_cases(self) -> tuple[Case, ...]:
        """Each bearing's case with its ``[operation] load`` set to the weight it carries."""
        out = []
        for site, load in zip(self.bearings, self.bearing_loads(), strict=True):
            if load <= 0.0:
                raise InputError(
                    f"bearing {site.label!r} at node {site.node} would carry {load:.3g} N: the "
                    "rotor's centre of mass lies outside the bearings, which a foil bearing "
                    "cannot hold down",
                    source=self.source,
                )
            out.append(replace(site.case, operation=replace(site.case.operation, load=load)))
        return tuple(out)
