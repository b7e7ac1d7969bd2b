"""The result of an orbit run: sampled time series, the run's status and its checkpoint."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.case import Case
from foilbearing.orbit.settings import OrbitSettings

__all__ = ["OrbitResult"]

FloatArray = NDArray[np.float64]


@dataclass
class OrbitResult:
    """Time series of a run (SI), its settings and how it ended.

    Attributes
    ----------
    time, e_x, e_y, speed, phase, min_film
        Uniform samples (s, m, m, rad/s, rad, m).
    voltages
        Applied voltage per actuator, V, shape (n_samples, n_actuators).
    power_loss
        Viscous power loss of the film, W: the drag law of the static analysis
        (:func:`foilbearing.static.drag_torque`) × speed, evaluated on the
        accepted states every :data:`POWER_INTERVAL` s and interpolated to the
        samples (None for runs saved before it was recorded).
    status
        "completed" (end of the speed profile), "stopped" (at ``stop_time``),
        "contact", "interrupted" or "failed".
    message
        How the run ended (contact time, speed and angle; what failed).
    """

    case: Case
    settings: OrbitSettings
    time: FloatArray
    e_x: FloatArray
    e_y: FloatArray
    speed: FloatArray
    phase: FloatArray
    min_film: FloatArray
    voltages: FloatArray
    status: str
    message: str
    wall_time: float
    steps: int
    factorizations: int
    newton_iterations: int
    contact: dict[str, float] | None = None
    checkpoint: dict[str, Any] = field(default_factory=dict, repr=False)
    power_loss: FloatArray | None = None

    def to_dataset(self) -> Any:
        """The run as an xarray Dataset in SI units (time series, settings, status, checkpoint).

        Every variable carries its ``units`` attribute; a reader converts with it
        (:func:`foilbearing.orbit.netcdf.load_orbit` does).
        """
        import xarray as xr

        n_act = self.voltages.shape[1] if self.voltages.ndim == 2 else 0
        ds = xr.Dataset(
            {
                "e_x": ("time", self.e_x, {"units": "m", "long_name": "journal X (load)"}),
                "e_y": ("time", self.e_y, {"units": "m", "long_name": "journal Y"}),
                "speed": ("time", self.speed, {"units": "rad/s", "long_name": "rotor speed"}),
                "phase": ("time", self.phase, {"units": "rad", "long_name": "rotation angle"}),
                "min_film": ("time", self.min_film, {"units": "m", "long_name": "minimum film"}),
                "voltage": (
                    ("time", "actuator"),
                    self.voltages.reshape(self.time.size, n_act),
                    {"units": "V"},
                ),
            },
            coords={"time": ("time", self.time, {"units": "s"})},
        )
        if self.power_loss is not None:
            ds["power_loss"] = (
                "time",
                self.power_loss,
                {"units": "W", "long_name": "viscous power loss of the film"},
            )
        s = self.settings
        ds.attrs.update(
            status=self.status,
            message=self.message,
            wall_time_s=self.wall_time,
            steps=self.steps,
            factorizations=self.factorizations,
            newton_iterations=self.newton_iterations,
            steps_per_rev=s.steps_per_rev,
            bdf_order=s.order,
            max_step_s=s.max_step,
            sample_rate_Hz=s.sample_rate,
            contact_film=s.contact_film,
            clearance_m=self.case.bearing.clearance,
            case_title=self.case.title,
            imbalance_kg_m=self.case.rotor.imbalance,
            rotor_mass_kg=self.case.rotor.mass,
        )
        if self.contact:
            for k, v in self.contact.items():
                ds.attrs[f"contact_{k}"] = v
        for k, v in self.checkpoint.items():
            ds[f"checkpoint_{k}"] = (f"checkpoint_{k}_dim", np.atleast_1d(np.asarray(v, float)))
        return ds
