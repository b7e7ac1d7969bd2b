"""The result of an orbit run: sampled time series, the run's status and its checkpoint."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.case import Case
from foilbearing.orbit.settings import OrbitSettings
from foilbearing.output.display import Summarised

__all__ = ["OrbitResult", "RunStatus", "synchronous_amplitude"]

FloatArray = NDArray[np.float64]


class RunStatus(StrEnum):
    """How an orbit run ended, with what to try next (:attr:`advice`).

    A ``str`` (:class:`enum.StrEnum`): ``status == "contact"``, JSON and the
    NetCDF attribute hold the plain word, and a file's plain string loads back
    as the member (``RunStatus("stopped")``).
    """

    #: The end of the speed profile.
    COMPLETED = "completed"
    #: At ``stop_time``: the profile goes on.
    STOPPED = "stopped"
    #: The minimum film fell below ``contact_film`` × C.
    CONTACT = "contact"
    #: Ctrl-C at a step boundary: every sample until then is kept.
    INTERRUPTED = "interrupted"
    #: A numerical failure (step collapse, singular factor).
    FAILED = "failed"
    #: A checkpoint written while the run goes on.
    RUNNING = "running"

    @property
    def advice(self) -> str:
        """What to try next, one line ("" for a completed run)."""
        return _ADVICE[self]

    @property
    def resumable(self) -> bool:
        """Whether ``--resume FILE.nc`` can continue the run (it has not ended)."""
        return self not in (RunStatus.COMPLETED, RunStatus.CONTACT)


_ADVICE = {
    RunStatus.COMPLETED: "",
    RunStatus.STOPPED: "stopped at --stop-time: resume with --resume FILE.nc to go on",
    RunStatus.CONTACT: (
        "the rotor touched the bearing: this is a result (instability or overload), not an "
        "error; for a longer run try a smaller imbalance, a lower load or a voltage program"
    ),
    RunStatus.INTERRUPTED: "resume with --resume FILE.nc: the run goes on from its checkpoint",
    RunStatus.FAILED: (
        "the integration failed: try more --steps-per-rev (smaller steps), tighter "
        "tolerances (OrbitSettings), or check the case (load, clearance, grid)"
    ),
    RunStatus.RUNNING: (
        "a checkpoint of a run that did not end (killed?): resume with --resume FILE.nc"
    ),
}


@dataclass(repr=False)
class OrbitResult(Summarised):
    """Time series of a run (SI), its settings and how it ended.

    Printed, it shows how the run ended, its speeds, largest excursion, smallest film
    and (at constant speed) the 1X amplitude in a few lines (a table in a notebook);
    :meth:`plot` draws the journal's motion and the speed against time. The signal
    analysis (waterfall, onset): :func:`foilbearing.orbit.analysis.analyse_orbit`.

    Attributes
    ----------
    time, e_x, e_y, speed, phase, min_film
        Uniform samples (s, m, m, rad/s, rad, m).
    voltages
        Applied voltage per actuator, V, shape (n_samples, n_actuators); n_actuators is 0
        for a bearing without actuators.
    power_loss
        Viscous power loss of the film, W: the drag law of the static analysis
        (:func:`foilbearing.analysis.equilibrium.drag_torque`) × speed, evaluated on the
        accepted states every :data:`~foilbearing.orbit.sampling.POWER_INTERVAL` s and interpolated to the
        samples (None for runs saved before it was recorded).
    status
        How the run ended (:class:`RunStatus`, a ``str``): "completed" (end of the
        speed profile), "stopped" (at ``stop_time``), "contact", "interrupted",
        "failed", or "running" in a checkpoint; a plain string is converted.
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
    status: RunStatus
    message: str
    wall_time: float
    steps: int
    factorizations: int
    newton_iterations: int
    contact: dict[str, float] | None = None
    checkpoint: dict[str, Any] = field(default_factory=dict, repr=False)
    power_loss: FloatArray | None = None

    def __post_init__(self) -> None:
        self.status = RunStatus(self.status)

    def summary(self) -> dict[str, Any]:
        """The run at a glance, unit-named keys: status, duration, speeds, largest
        eccentricity |e|/C, smallest film, 1X amplitude (0-pk, X and Y) of a
        constant-speed run, steps and wall time. Cheap: no waterfall."""
        rpm = 30.0 / np.pi
        n = self.time.size
        c = self.case.bearing.clearance
        sync = synchronous_amplitude(self) if n >= 2 else None
        return {
            "status": self.status.value,
            "duration_s": float(self.time[-1] - self.time[0]) if n else 0.0,
            "start_speed_rpm": float(self.speed[0]) * rpm if n else None,
            "end_speed_rpm": float(self.speed[-1]) * rpm if n else None,
            "max_eccentricity": float(np.max(np.hypot(self.e_x, self.e_y)) / c) if n else None,
            "min_film_um": float(np.min(self.min_film)) * 1e6 if n else None,
            **({} if sync is None else {"one_x_amplitude_0pk_um": [a * 1e6 for a in sync[0]]}),
            "steps": self.steps,
            "wall_time_s": self.wall_time,
            "message": self.message,
        }

    def _summary(self) -> tuple[str, dict[str, Any], None]:
        from foilbearing.output.summary import grid_line

        title = f"Orbit of {self.case.title or 'case'}; {grid_line(self.case)}"
        return title, self.summary(), None

    def plot(self) -> Any:
        """The journal's e_X, e_Y (µm) and the speed against time (:func:`~foilbearing.
        output.plots.orbit.plot_transient`); returns the matplotlib Figure. The
        waterfall and orbit figures: :func:`foilbearing.orbit.analysis.write_orbit_figures`."""
        from foilbearing.output.plots.orbit import plot_transient

        c = self.case.bearing.clearance
        return plot_transient(self.time, self.e_x, self.e_y, self.speed, c)

    def to_dataset(self) -> Any:
        """The run as an xarray Dataset in SI units (time series, settings, status, checkpoint).

        Every variable carries its ``units`` attribute; a reader converts with it
        (:func:`foilbearing.orbit.netcdf.load_orbit` does). A bearing without actuators
        has no ``voltage`` variable: a NetCDF 3 file cannot hold the empty ``actuator``
        dimension after ``time`` (``xarray.load_dataset`` would fail on it).
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
            },
            coords={
                "time": ("time", self.time, {"units": "s"}),
                "load": (
                    (),
                    self.case.operation.load,
                    {"units": "N", "long_name": "static load W along +X"},
                ),
            },
        )
        if n_act:  # a bearing without actuators has no voltage (and NetCDF 3 no empty dimension)
            ds["voltage"] = (
                ("time", "actuator"),
                self.voltages.reshape(self.time.size, n_act),
                {"units": "V"},
            )
        if self.power_loss is not None:
            ds["power_loss"] = (
                "time",
                self.power_loss,
                {"units": "W", "long_name": "viscous power loss of the film"},
            )
        s = self.settings
        ds.attrs.update(
            status=self.status.value,
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
            grid_n_theta=self.case.grid.n_theta,
            grid_n_z=self.case.grid.n_z,
            grid_axial_order=self.case.grid.axial_order,
            grid_lift_off_smoothing=self.case.grid.lift_off_smoothing,
        )
        if s.steps == "adaptive":
            ds.attrs.update(time_steps=s.steps, step_rtol=s.step_rtol)
        d = self.case.disturbance
        if d is not None:
            ds.attrs.update(
                disturbance_N_rms=d.force_rms,
                disturbance_band_Hz=[d.min_frequency, d.max_frequency],
                disturbance_seed=d.seed,
                disturbance_tones=d.tones,
            )
        if self.contact:
            for k, v in self.contact.items():
                ds.attrs[f"contact_{k}"] = v
        for k, v in self.checkpoint.items():
            ds[f"checkpoint_{k}"] = (f"checkpoint_{k}_dim", np.atleast_1d(np.asarray(v, float)))
        return ds


def synchronous_amplitude(
    result: OrbitResult,
) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The 1X amplitudes (0-pk, m) in X and Y of a constant-speed run, and their window (s).

    Read over the whole revolutions of the run's second half (the first half lets the
    start from the equilibrium without imbalance die out) by least squares on
    1, cos φ, sin φ, φ the rotor's angle: a whirl at another frequency is rejected over
    the window's revolutions. None for a run whose speed changes, or with fewer than two
    revolutions in its second half.
    """
    t, w = result.time, result.speed
    if t.size < 8 or np.ptp(w) > 1e-9 * float(np.max(w)):
        return None
    phase = result.phase
    start = int(np.searchsorted(t, 0.5 * (t[0] + t[-1])))
    turns = math.floor((phase[-1] - phase[start]) / (2 * math.pi))
    if turns < 2:
        return None
    keep = np.zeros(t.size, dtype=bool)  # whole revolutions from the middle of the run
    keep[start:] = phase[start:] - phase[start] < turns * 2 * math.pi
    basis = np.column_stack([np.ones(keep.sum()), np.cos(phase[keep]), np.sin(phase[keep])])
    amps = []
    for x in (result.e_x, result.e_y):
        coef = np.linalg.lstsq(basis, x[keep], rcond=None)[0]
        amps.append(float(np.hypot(coef[1], coef[2])))
    return (amps[0], amps[1]), (float(t[keep][0]), float(t[keep][-1]))
