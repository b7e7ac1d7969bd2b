"""The rotor's linear analysis on ROSS: modes, log decrements and the onset speed.

Each bearing's force coefficients are tabulated over speed × whirl frequency at the load
it carries (:meth:`RotorCase.loaded_cases`,
:func:`foilbearing.export.ross.coefficient_table`) and exported as a ROSS
``BearingElement``. ROSS then solves the rotor's modes with each mode's coefficients at
its own damped whirl frequency, ``Rotor.run_modal(speed, matched_whirl=True)``: the
nonlinear eigenproblem of a foil bearing, whose coefficients depend strongly on
frequency. ROSS's default (coefficients at the running speed) overstates this bearing's
stability badly; it is not used.

ROSS interpolates each table between its speeds. At the table's own speeds the modes use
our coefficients exactly (interpolated in frequency only). So the onset is bracketed on the
table's speeds and refined between two of them, where it carries the interpolation's error:
``tests/test_rotor.py`` measures it against our own single-bearing ``stability`` on a rigid
rotor.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.rotor.model import RotorCase

__all__ = [
    "DEFAULT_FREQUENCIES",
    "RotorModes",
    "modes_at",
    "refine_onset",
    "ross_rotor",
    "ross_shaft",
    "rotor_modes",
    "rotor_onset",
]

FloatArray = NDArray[np.float64]

#: Whirl frequencies of the bearings' tables, rad/s: 10 Hz to 1 kHz (a rotor's modes on foil
#: bearings whirl at 0.1-0.6 of the running speed, 10-900 Hz up to 90 krpm).
DEFAULT_FREQUENCIES = 2.0 * np.pi * np.geomspace(10.0, 1000.0, 12)


@dataclass(frozen=True)
class RotorModes:
    """The rotor's lowest modes at each speed, with matched whirl.

    Attributes
    ----------
    speeds
        rad/s, shape (n,).
    frequency
        Damped natural frequency of each mode, Hz, shape (n, m), ascending at each speed.
    log_decrement
        Shape (n, m).
    forward
        Whether ROSS labels the mode's whirl forward, shape (n, m).
    """

    speeds: FloatArray
    frequency: FloatArray
    log_decrement: FloatArray
    forward: NDArray[np.bool_]

    def least_stable(self) -> FloatArray:
        """The lowest log decrement at each speed, over every mode kept. (Not over the
        forward ones only: ROSS reads a mode's whirl direction from its orbits, which a
        conical mode barely has at the rotor's middle, and its label can flip with speed.)"""
        return np.asarray(self.log_decrement.min(axis=1), float)

    def headline(self) -> list[dict[str, Any]]:
        """The modes by speed, unit-named keys (``--json``)."""
        out = []
        for k, w in enumerate(self.speeds):
            for f, d, fw in zip(
                self.frequency[k], self.log_decrement[k], self.forward[k], strict=True
            ):
                out.append({
                    "speed_rpm": float(w / RPM),
                    "frequency_Hz": float(f),
                    "log_decrement": float(d),
                    "whirl": "forward" if fw else "backward",
                })  # fmt: skip
        return out


def ross_shaft(rotor: RotorCase, bearings: Sequence[Any] = ()) -> Any:
    """The ROSS ``Rotor`` of the shaft's beam elements and the disks, with ``bearings``
    (ROSS bearing elements; none: the free rotor, whose matrices the nonlinear rotor
    reduces)."""
    from foilbearing.export.ross import _import_ross

    ross = _import_ross()
    m = rotor.material
    material = ross.Material(
        name="shaft", rho=m.density, E=m.youngs_modulus, Poisson=m.poisson_ratio
    )
    shaft = [
        ross.ShaftElement(L=e.length, idl=e.inner_diameter, odl=e.outer_diameter,
                          material=material, n=k)
        for k, e in enumerate(rotor.shaft)
    ]  # fmt: skip
    disks = [
        ross.DiskElement(n=d.node, m=d.mass, Id=d.diametral_inertia, Ip=d.polar_inertia)
        for d in rotor.disks
    ]
    return ross.Rotor(shaft, disks, list(bearings))


def ross_rotor(
    rotor: RotorCase,
    speeds: Sequence[float],
    frequencies: Sequence[float] | None = None,
    progress: Callable[[str], None] | None = None,
) -> Any:
    """The ROSS ``Rotor``: the shaft's beam elements, the disks, and each bearing's exported
    coefficient table over ``speeds`` (rad/s) × ``frequencies`` (rad/s) at its load."""
    from foilbearing.export.ross import _import_ross, coefficient_table, to_ross_bearing

    _import_ross("the rotor's ROSS model")  # before the tables, which take minutes
    freqs = DEFAULT_FREQUENCIES if frequencies is None else np.asarray(frequencies, float)
    bearings = []
    for site, case in zip(rotor.bearings, rotor.loaded_cases(), strict=True):
        if progress is not None:
            progress(f"{site.label}: coefficients at {case.operation.load:.2f} N, "
                     f"{len(speeds)} speeds x {len(freqs)} frequencies")  # fmt: skip
        table = coefficient_table(case, list(speeds), list(freqs))
        if not bool(table["converged"].all()):
            raise InputError(
                f"bearing {site.label!r}: no static equilibrium at some speeds "
                f"({table.attrs.get('message', '')}); raise the lowest speed",
                source=rotor.source,
            )
        bearings.append(to_ross_bearing(table, site.node, tag=site.label))
    return ross_shaft(rotor, bearings)


def modes_at(model: Any, speed: float, num_modes: int) -> tuple[FloatArray, FloatArray, Any]:
    """The ``num_modes`` lowest modes of the ROSS rotor ``model`` at ``speed`` (rad/s), each
    with its coefficients at its own whirl frequency: (damped frequencies, rad/s; log
    decrements; whether ROSS labels each forward), ascending in frequency."""
    with warnings.catch_warnings():
        # ROSS starts each mode's whirl iteration from coefficients it may extrapolate.
        warnings.filterwarnings("ignore", message="Extrapolating")
        modal = model.run_modal(float(speed), num_modes=2 * num_modes, matched_whirl=True)
    wd = np.asarray(modal.wd, float)
    dec = np.asarray(modal.log_dec, float)
    forward = np.array([d == "Forward" for d in modal.whirl_direction()])
    order = np.argsort(wd)[:num_modes]
    return wd[order], dec[order], forward[order]


def rotor_modes(
    rotor: RotorCase,
    speeds: Sequence[float],
    *,
    frequencies: Sequence[float] | None = None,
    num_modes: int = 4,
    model: Any = None,
    progress: Callable[[str], None] | None = None,
) -> RotorModes:
    """The ``num_modes`` lowest modes at each speed (rad/s), matched whirl (Campbell diagram).

    ``model``: a ROSS rotor built by :func:`ross_rotor` whose tables span ``speeds`` (built
    on ``speeds`` if omitted).
    """
    speeds_arr = np.asarray(speeds, float)
    if model is None:
        model = ross_rotor(rotor, list(speeds_arr), frequencies, progress)
    rows = [modes_at(model, w, num_modes) for w in speeds_arr]
    return RotorModes(
        speeds_arr,
        np.array([r[0] for r in rows]) / (2.0 * math.pi),
        np.array([r[1] for r in rows]),
        np.array([r[2] for r in rows]),
    )


def rotor_onset(
    rotor: RotorCase,
    speeds: Sequence[float],
    *,
    frequencies: Sequence[float] | None = None,
    num_modes: int = 4,
    progress: Callable[[str], None] | None = None,
) -> tuple[float | None, float | None, RotorModes]:
    """The lowest speed (rad/s) where a mode's log decrement turns negative, its whirl
    frequency (Hz), and the modes on ``speeds``; (None, None, modes) if stable over them.

    Bracketed on ``speeds`` (the bearings' table speeds) and refined by Brent's method
    between two of them, on ROSS's interpolation of the tables.
    """
    model = ross_rotor(rotor, speeds, frequencies, progress)
    modes = rotor_modes(rotor, speeds, num_modes=num_modes, model=model)
    onset, whirl = refine_onset(modes, lambda w: modes_at(model, w, num_modes))
    return onset, whirl, modes


def refine_onset(
    modes: RotorModes,
    modes_of: Callable[[float], tuple[FloatArray, FloatArray, Any]],
) -> tuple[float | None, float | None]:
    """The lowest speed (rad/s) where the least stable of ``modes`` turns unstable, and its
    whirl frequency (Hz); (None, None) if none does on ``modes.speeds``.

    Bracketed on ``modes.speeds`` and refined by Brent's method on ``modes_of(speed)``,
    which gives (whirl frequencies rad/s, log decrements, forward) of the modes at a speed.
    """
    speeds = modes.speeds
    low = modes.least_stable()
    unstable = np.flatnonzero(low < 0.0)
    if unstable.size == 0:
        return None, None
    k = int(unstable[0])
    if k == 0:
        raise InputError(
            f"the rotor is already unstable at the lowest speed, {speeds[0] / RPM:.0f} rpm: "
            "start the speeds lower"
        )

    def least(w: float) -> float:
        return float(np.min(modes_of(w)[1]))

    onset = float(brentq(least, float(speeds[k - 1]), float(speeds[k]), rtol=1e-7))
    wd, dec, _fw = modes_of(onset)
    i = int(np.argmin(dec))
    return onset, float(wd[i] / (2.0 * math.pi))
