"""The result of a static analysis: one operating point and its views.

:class:`StaticResult` holds the journal position, the film (pressure and thickness on
the grid), the film force, the actuators' preload and pressure and the solver's
outcome, in SI; it gives its headline (:data:`STATIC_HEADLINE`, the CLI's ``--json``),
its printed summary, an xarray Dataset and a plot. :func:`static_result` builds it
from a solved film: the force, the preload of Eq. (3b) and the drag torque.
The solvers that produce it live in :mod:`foilbearing.analysis.equilibrium`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.bearing_system.scales import Scales
from foilbearing.case import Case
from foilbearing.film import FilmModel, drag_torque
from foilbearing.headline import Field, headline_view
from foilbearing.output.display import Summarised
from foilbearing.reynolds import film_force

__all__ = ["STATIC_HEADLINE", "StaticResult", "static_result"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, repr=False)
class StaticResult(Summarised):
    """One static operating point. SI units unless stated; arrays on the half-bearing grid.

    Printed, it shows its headline (:meth:`headline`) in a few lines, in a notebook
    as a table; :meth:`plot` draws the pressure and film around the bearing.

    Attributes
    ----------
    speed
        Rotor speed, rad/s.
    bearing_number
        Λ = 6 μ ω R²/(p_a C²).
    eps_x, eps_y
        Journal position in units of C (X along the load).
    P, H
        Pressure p/p_a and film h/C, shape (n_theta, n_z), z from the mid-plane.
    force
        Film force (F_X, F_Y) on the journal, N.
    actuator_pressure
        Axially averaged gauge pressure p_A at each actuator/shim angle, Pa.
    preload
        Piezoelectric preload δ_PZT at each actuator (Eq. 3b), m; for shims the
        shim thickness (rigid).
    drag_torque
        Viscous torque on the journal, N·m; ``power_loss = drag_torque · speed``, W.
    converged, message, iterations, residual, force_residual
        Solver outcome: Reynolds residual max|R|/(ΔθΔZ) and |F + W|/|W|.
    """

    case: Case
    model: FilmModel
    speed: float
    bearing_number: float
    eps_x: float
    eps_y: float
    P: FloatArray
    H: FloatArray
    force: tuple[float, float]
    actuator_pressure: FloatArray
    preload: FloatArray
    drag_torque: float
    iterations: int
    residual: float
    force_residual: float
    converged: bool
    message: str
    equilibrium: bool

    @property
    def eccentricity(self) -> float:
        """ε₀ = √(ε_X² + ε_Y²)."""
        return math.hypot(self.eps_x, self.eps_y)

    @property
    def attitude_angle(self) -> float:
        """φ₀ = atan(ε_Y/ε_X), rad, measured from the load direction (+X)."""
        return math.atan2(self.eps_y, self.eps_x)

    @property
    def min_film(self) -> float:
        """Minimum film thickness, m."""
        return float(self.H.min()) * self.case.bearing.clearance

    @property
    def min_film_angle(self) -> float:
        """Angle θ of the minimum film thickness, rad."""
        i = int(np.argmin(self.H.min(axis=1)))
        return float(self.model.grid.theta[i])

    @property
    def power_loss(self) -> float:
        """Viscous power loss in the film, W."""
        return self.drag_torque * self.speed

    def headline(self) -> dict[str, Any]:
        """Headline numbers with unit-named keys (the CLI's ``--json``): a view of
        :meth:`to_dataset` (:data:`STATIC_HEADLINE`)."""
        return headline_view(self.to_dataset(), STATIC_HEADLINE)

    def _summary(self) -> tuple[str, dict[str, Any], tuple[str, ...]]:
        from foilbearing.output.summary import grid_line

        what = "Static equilibrium" if self.equilibrium else "Static point (position prescribed)"
        title = f"{what}, {self.case.title or 'case'}; {grid_line(self.case)}"
        return title, self.headline(), _SHOWN

    def plot(self) -> Any:
        """Pressure and film thickness around the bearing (:func:`~foilbearing.output.plots.
        static.plot_point`); returns the matplotlib Figure."""
        from foilbearing.output.plots.static import plot_point

        return plot_point(self)

    def to_dataset(self) -> Any:
        """The result as an xarray Dataset in SI, every variable with its ``units``.

        The fields on the grid (pressure, film, preload shape), the journal's
        equilibrium, film force, drag and the actuators' numbers as variables;
        the bearing kind and the solver's diagnostics as attributes.
        """
        import xarray as xr

        g = self.model.grid
        r = self.case.bearing.radius
        c = self.case.bearing.clearance
        pa = self.case.gas.ambient_pressure
        voltages = self.case.actuators.voltages if self.case.actuators is not None else ()
        coords = {
            "theta": ("theta", g.theta, {"units": "rad", "long_name": "θ from −X"}),
            "z": ("z", g.z * r, {"units": "m", "long_name": "z from the mid-plane"}),
            "axis": ("axis", ["X", "Y"], {"long_name": "X along the load, Y 90° after it"}),
            "load": (
                (),
                self.case.operation.load,
                {"units": "N", "long_name": "static load W along +X"},
            ),
        }
        scalars = {
            "speed": (self.speed, "rad/s", "rotor speed ω"),
            "bearing_number": (self.bearing_number, "1", "bearing number Λ"),
            "eccentricity": (self.eccentricity, "1", "ε₀ = e/C"),
            "eps_X": (self.eps_x, "1", "journal position ε_X (load direction)"),
            "eps_Y": (self.eps_y, "1", "journal position ε_Y"),
            "attitude_angle": (self.attitude_angle, "rad", "attitude angle φ₀ from +X"),
            "min_film": (self.min_film, "m", "minimum film thickness"),
            "min_film_angle": (self.min_film_angle, "rad", "θ of the minimum film"),
            "drag_torque": (self.drag_torque, "N m", "viscous drag torque of the film"),
            "power_loss": (self.power_loss, "W", "viscous power loss of the film"),
        }
        data: dict[str, Any] = {
            name: ((), value, {"units": unit, "long_name": label})
            for name, (value, unit, label) in scalars.items()
        }
        data |= {
            "pressure": (("theta", "z"), self.P * pa, {"units": "Pa", "long_name": "p"}),
            "gauge_pressure_mean": (
                "theta",
                self.model.grid.gauge_mean(self.P) * pa,
                {"units": "Pa", "long_name": "axially averaged gauge pressure p_A"},
            ),
            "film_thickness": (("theta", "z"), self.H * c, {"units": "m", "long_name": "h"}),
            "preload_shape": (
                "theta",
                self.model.preload * c,
                {"units": "m", "long_name": "r_p (base preload shape)"},
            ),
            "force": (
                "axis",
                np.asarray(self.force, float),
                {"units": "N", "long_name": "film force"},
            ),
            "voltage": (
                "actuator",
                np.asarray(voltages, float),
                {"units": "V", "long_name": "actuator voltage"},
            ),
            "stinger_preload": (
                "stinger",
                np.asarray(self.preload, float),
                {"units": "m", "long_name": "preload at each stinger (Eq. 3b)"},
            ),
            "actuator_pressure": (
                "stinger",
                np.asarray(self.actuator_pressure, float),
                {"units": "Pa", "long_name": "gauge pressure over each stinger's arc"},
            ),
        }
        ds = xr.Dataset(data, coords=coords)
        ds.attrs.update(
            bearing=self.case.kind,
            iterations=self.iterations,
            reynolds_residual=self.residual,
            force_residual=self.force_residual,
            converged=int(self.converged),
            message=self.message,
        )
        return ds


#: The static headline, read off :meth:`StaticResult.to_dataset`: key, source, unit.
STATIC_HEADLINE: tuple[Field, ...] = (
    ("speed_rpm", "speed", "rpm"),
    ("load_N", "load", None),
    ("voltages_V", "voltage", None),
    ("bearing", "@bearing", None),
    ("bearing_number", "bearing_number", None),
    ("eccentricity", "eccentricity", None),
    ("eps_X", "eps_X", None),
    ("eps_Y", "eps_Y", None),
    ("attitude_deg", "attitude_angle", "deg"),
    ("min_film_um", "min_film", "um"),
    ("min_film_angle_deg", "min_film_angle", "deg"),
    ("force_N", "force", None),
    ("preload_um", "stinger_preload", "um"),
    ("actuator_pressure_kPa", "actuator_pressure", "kPa"),
    ("drag_torque_Nm", "drag_torque", None),
    ("power_loss_W", "power_loss", None),
    ("iterations", "@iterations", None),
    ("reynolds_residual", "@reynolds_residual", None),
    ("force_residual", "@force_residual", None),
    ("converged", "@converged", "bool"),
    ("message", "@message", None),
)

#: The headline entries a printed :class:`StaticResult` shows.
_SHOWN = (
    "speed_rpm",
    "load_N",
    "voltages_V",
    "bearing",
    "eccentricity",
    "attitude_deg",
    "min_film_um",
    "preload_um",
    "power_loss_W",
    "converged",
    "iterations",
    "message",
)


def static_result(
    case: Case,
    model: FilmModel,
    omega: float,
    lam: float,
    eps_x: float,
    eps_y: float,
    P: FloatArray,
    H: FloatArray,
    iterations: int,
    residual: float,
    force_residual: float,
    converged: bool,
    message: str,
    equilibrium: bool,
) -> StaticResult:
    """The :class:`StaticResult` of a solved film at journal position (ε_X, ε_Y).

    Parameters
    ----------
    case, model
        The case and the film model the film was solved on.
    omega, lam
        Rotor speed, rad/s, and the bearing number Λ.
    eps_x, eps_y
        Journal position in units of C.
    P, H
        Pressure p/p_a and film h/C on the grid, shape (n_theta, n_z).
    iterations, residual, force_residual, converged, message
        The solver's outcome.
    equilibrium
        True for a solved equilibrium, False for a prescribed position.
    """
    g = model.grid
    scales = Scales.from_case(case)
    pa = scales.ambient_pressure
    fx, fy = film_force(g, P)
    p_mean = g.gauge_mean(P)
    angles = model.preload_angles
    p_act = model.at_angles(p_mean, angles) * pa if angles else np.zeros(0)
    base = np.asarray(model.base_preloads, dtype=float)
    if model.actuator_stiffness is not None:
        # Eq. (3b); sub-ambient pressure does not pull the foil, so it does not pull the stinger.
        preload = base - np.maximum(p_act, 0.0) / model.actuator_stiffness
    else:
        preload = base
    torque = drag_torque(case, g, P, H, omega)
    return StaticResult(
        case=case,
        model=model,
        speed=omega,
        bearing_number=lam,
        eps_x=eps_x,
        eps_y=eps_y,
        P=P,
        H=H,
        force=(fx * scales.force, fy * scales.force),
        actuator_pressure=p_act,
        preload=preload,
        drag_torque=torque,
        iterations=iterations,
        residual=residual,
        force_residual=force_residual,
        converged=converged,
        message=message,
        equilibrium=equilibrium,
    )
