"""Dynamic force coefficients: stiffness and damping against excitation frequency.

Perturbation of the static solution (docs/model.md §4): a small harmonic
journal motion at ω_e = ν ω gives ``K_ij + j ω_e C_ij = −∂F_i/∂e_j``, from the
complex pressure response of :mod:`foilbearing.reynolds.perturbed`. The foil
enters as a complex stiffness per unit area: the bump, a spring k_b in
parallel with the viscous damper ``c_b = γ k_b/ω`` (the loss factor's
equivalent at the running speed ω; the orbit integrates the same Kelvin-Voigt
bump, so linear and nonlinear analyses share one foil damping law, docs/model.md
section 3), ``k_b (1 + jγ ω_e/ω)``, in series with the purely elastic actuator
under each stinger,

    1/k'(θ) = 1/(k_b (1 + jγν)) + φ(θ)/(k_p + 4k_sp),

where φ(θ) = (k_p + 4k_sp)(1/k(θ) − 1/k_b) is the stinger fraction of the
smoothed stiffness function (1 under a stinger, 0 away from it), so that with
γ = 0 the compliance is the static 1/k(θ) of Eq. (8). The shimmed GFB has
φ = 0 (rigid shims). Where the steady foil is not engaged (p̄ ≤ 0) it does not
respond (bumps carry no tension), as in the static model. The loss of this law
at a sub-synchronous whirl is γν, a fraction of γ: the structural
(hysteretic) ``k_b(1 + jγ)`` would give γ at every frequency, but it has no
causal time-domain counterpart the orbit could integrate with the same
states; ``docs/lift-off.md`` gives the onsets measured with each.

The actuator's share follows the case's reading (docs/model.md §3.8):

- ``dynamics = "compliant"``: the stack's compliance acts at ω_e, as above under
  ``preload_response = "local"``; under ``"lobe"`` its compression lowers the
  lobes, ``ΔD_n = p_a Δq(θ_n)/(C (k_p + 4k_sp))`` where the stack is loaded,
  taken as n_act further film columns ∂H/∂D_n (the unit lobes) and eliminated
  (:func:`_with_lobes`);
- ``dynamics = "held"``: the stinger keeps its quasi-static position, so φ = 0
  and ΔD = 0: the bump alone responds.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.analysis.equilibrium import StaticResult
from foilbearing.bearing_system.scales import Scales
from foilbearing.errors import InputError, SolverError
from foilbearing.film import FilmModel
from foilbearing.headline import Field, headline_view
from foilbearing.laws.foil_damping import ViscousBump
from foilbearing.output.display import Summarised
from foilbearing.reynolds import Workspace
from foilbearing.units import QuantityLike, as_si_array

__all__ = [
    "CoefficientSweep",
    "ForceCoefficients",
    "coefficients_over_speeds",
    "dynamic_compliance",
    "force_coefficients",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, repr=False)
class ForceCoefficients(Summarised):
    """Linearised film force coefficients about one static point.

    Printed, it shows its headline in a few lines (a table in a notebook);
    :meth:`plot` draws K and C against the excitation frequency.

    Attributes
    ----------
    static
        The equilibrium (or prescribed position) they linearise about.
    frequencies
        Excitation frequencies ω_e, rad/s, shape (n_f,).
    K
        Stiffness, N/m, shape (n_f, 2, 2), indices [X, Y] × [X, Y].
    C
        Damping, N·s/m, shape (n_f, 2, 2).
    """

    static: StaticResult
    frequencies: FloatArray
    K: FloatArray
    C: FloatArray

    def headline(self) -> dict[str, Any]:
        """Unit-named keys for ``--json``, one entry per frequency: a view of
        :meth:`to_dataset` (:data:`COEFFICIENT_HEADLINE`)."""
        return headline_view(self.to_dataset(), COEFFICIENT_HEADLINE)

    def _summary(self) -> tuple[str, dict[str, Any], None]:
        title = f"Force coefficients at {self.frequencies.size} frequencies about: "
        return title + repr(self.static).splitlines()[0], self.headline(), None

    def plot(self) -> Any:
        """Stiffness and damping against excitation frequency (:func:`~foilbearing.output.
        plots.dynamics.plot_coefficients`); returns the matplotlib Figure."""
        from foilbearing.output.plots.dynamics import plot_coefficients

        return plot_coefficients(self)

    def to_dataset(self) -> Any:
        """xarray Dataset in SI with dims (frequency, i, j), and the static point it is about."""
        import xarray as xr

        st = self.static
        coords = {
            "frequency": (
                "frequency",
                self.frequencies / (2 * math.pi),
                {"units": "Hz", "long_name": "excitation frequency ω_e/2π"},
            ),
            "i": ["X", "Y"],
            "j": ["X", "Y"],
            "load": (
                (),
                st.case.operation.load,
                {"units": "N", "long_name": "static load W along +X"},
            ),
        }
        ds = xr.Dataset(
            {
                "stiffness": (("frequency", "i", "j"), self.K, {"units": "N/m"}),
                "damping": (("frequency", "i", "j"), self.C, {"units": "N s/m"}),
                "frequency_ratio": (
                    "frequency",
                    self.frequencies / st.speed,
                    {"units": "1", "long_name": "ω_e/ω"},
                ),
                "speed": ((), st.speed, {"units": "rad/s", "long_name": "rotor speed ω"}),
                "eccentricity": ((), st.eccentricity, {"units": "1", "long_name": "ε₀ = e/C"}),
                "attitude_angle": (
                    (),
                    st.attitude_angle,
                    {"units": "rad", "long_name": "attitude angle φ₀ from +X"},
                ),
            },
            coords=coords,
        )
        return ds


#: The coefficients' headline, read off :meth:`ForceCoefficients.to_dataset`.
COEFFICIENT_HEADLINE: tuple[Field, ...] = (
    ("speed_rpm", "speed", "rpm"),
    ("load_N", "load", None),
    ("frequency_Hz", "frequency", None),
    ("frequency_ratio", "frequency_ratio", None),
    ("K_N_per_m", "stiffness", None),
    ("C_Ns_per_m", "damping", None),
    ("eccentricity", "eccentricity", None),
    ("attitude_deg", "attitude_angle", "deg"),
)


def dynamic_compliance(
    static: StaticResult, frequency: float, loss_factor: float | None = None
) -> NDArray:
    """Complex foil compliance c_i = p_a/(C k'(θ_i)) where the steady foil is engaged, else 0.

    Parameters
    ----------
    static
        The static point (its speed ω sets the bump's damper γ k_b/ω).
    frequency
        Excitation frequency ω_e, rad/s: the bump's loss there is γ ω_e/ω.
    loss_factor
        Override of the case's γ.
    """
    case, model = static.case, static.model
    if case.foil is None:
        if loss_factor:
            raise InputError("foil damping (loss factor) asked for a case without [foil]")
        return np.zeros(model.grid.n_theta, dtype=complex)
    law = model.foil_damping
    if loss_factor is not None:
        if loss_factor < 0:
            raise InputError(f"loss factor = {loss_factor!r}: must be >= 0")
        law = ViscousBump(loss_factor)
    # The bump under the foil damping law, in series with the actuator's springs unless
    # the stinger is held.
    compliance = law.compliance(model.bump_compliance, frequency, static.speed)
    compliance = compliance + model.actuator.motion_compliance(model.actuator_compliance)
    engaged = model.grid.gauge_mean(static.P) > 0.0
    return np.where(engaged, compliance, 0.0).astype(complex)


def force_coefficients(
    static: StaticResult,
    frequencies: Any,
    *,
    loss_factor: float | None = None,
    workspace: Workspace | None = None,
) -> ForceCoefficients:
    """Stiffness and damping of the film (with the foil) at excitation frequencies ω_e.

    Parameters
    ----------
    static
        Static result to linearise about (equilibrium or prescribed position).
    frequencies
        Excitation frequencies ω_e in rad/s (> 0), scalar or array; or quantities:
        ``"100 Hz"`` is ω_e = 2π·100 rad/s, ``["100 Hz", "500 Hz"]``, a pint ``Quantity``.
    loss_factor
        Override of the bump's loss factor γ (default: the case's); the bump's
        damper is γ k_b/ω at the static point's speed ω.

    Returns
    -------
    ForceCoefficients with K in N/m and C in N·s/m.
    """
    omega_e = as_si_array(frequencies, "angular_frequency", field="frequencies")
    if omega_e.size == 0 or not np.all(np.isfinite(omega_e)) or np.any(omega_e <= 0):
        raise InputError(
            f"excitation frequency {omega_e.tolist()!r} rad/s: every frequency must be > 0"
        )
    if not static.converged:
        raise SolverError(
            f"the static point did not converge ({static.message}): the coefficients "
            "need a converged equilibrium"
        )
    case, model = static.case, static.model
    dh = _journal_columns(model)
    w_x, w_y = (w.ravel() for w in model.grid.force_weights())
    scales = Scales.from_case(case)
    scale = -scales.force / scales.clearance  # N/m per unit ∂(∫∫P w)/∂ε
    ws = workspace if workspace is not None else Workspace(model.grid)
    lobes = model.lobe and model.actuator.lobes_move
    if lobes:
        dh = np.column_stack([dh, _lobe_columns(model)])
    K = np.empty((omega_e.size, 2, 2))
    C = np.empty((omega_e.size, 2, 2))
    for n, w_e in enumerate(omega_e):
        dp = model.perturbed_pressure(
            static.P,
            static.H,
            static.bearing_number,
            w_e / static.speed,
            dynamic_compliance(static, w_e, loss_factor),
            dh,
            ws,
        )
        if lobes:
            dp = _with_lobes(model, static.P, dp)
        z = scale * np.array([[w_x @ dp[:, 0], w_x @ dp[:, 1]], [w_y @ dp[:, 0], w_y @ dp[:, 1]]])
        K[n] = z.real
        C[n] = z.imag / w_e
    return ForceCoefficients(static, omega_e, K, C)


def _lobe_columns(model: FilmModel) -> FloatArray:
    """∂H/∂D_n: the unit lobe of each actuator on every cell, shape (n, n_act)."""
    assert model.lobe_shapes is not None
    return np.repeat(model.lobe_shapes, model.grid.n_z, axis=1).T


def _with_lobes(model: FilmModel, P: FloatArray, dp: NDArray) -> NDArray:
    """ΔP per unit ε with the lobes following the stacks' compression (``"lobe"``, compliant).

    ``dp`` holds the responses to the journal's two columns and to the n_act lobe
    columns. With ΔP = X_ε + X_D ΔD and ΔD = M ΔP, where M = c_s ∂q(θ_n)/∂P on the
    loaded stacks: ΔD = (I − M X_D)⁻¹ M X_ε.
    """
    g = model.grid
    assert model.actuator_rows is not None
    rows = g.mean_rows(model.actuator_rows)
    loaded = rows @ (np.ravel(P) - 1.0) > 0.0
    M = model.stack_compliance * loaded[:, None] * rows
    x_e, x_d = dp[:, :2], dp[:, 2:]
    d_d = np.linalg.solve(np.eye(x_d.shape[1]) - M @ x_d, M @ x_e)
    return x_e + x_d @ d_d


def _journal_columns(model: FilmModel) -> FloatArray:
    """∂H/∂ε_X = cos θ and ∂H/∂ε_Y = sin θ on every cell, shape (n, 2)."""
    g = model.grid
    cos_t = np.repeat(np.cos(g.theta)[:, None], g.n_z, axis=1).ravel()
    sin_t = np.repeat(np.sin(g.theta)[:, None], g.n_z, axis=1).ravel()
    return np.column_stack([cos_t, sin_t])


@dataclass(frozen=True, repr=False)
class CoefficientSweep(Summarised):
    """Force coefficients at a list of rotor speeds, each about its own equilibrium.

    Printed, it shows K and C at the first excitation frequency against speed;
    :meth:`plot` draws them; :meth:`to_dataset` stacks the points along ``speed``.

    Attributes
    ----------
    points
        One :class:`ForceCoefficients` per speed, in the order given.
    frequency_ratios
        ω_e/ω of every point when the frequencies scale with the speed (the same
        ratios at each speed), else None: the same frequencies (rad/s) at each.
    """

    points: tuple[ForceCoefficients, ...]
    frequency_ratios: FloatArray | None = None

    @property
    def speeds(self) -> FloatArray:
        """The rotor speeds ω, rad/s, shape (n_speed,)."""
        return np.array([fc.static.speed for fc in self.points])

    def to_dataset(self) -> Any:
        """xarray Dataset in SI with dims (speed, frequency, i, j).

        The frequency dimension is ``frequency_ratio`` (ω_e/ω) when the frequencies
        scale with the speed, with ``frequency`` (Hz) a variable over (speed,
        frequency_ratio); else ``frequency`` (Hz), the same at every speed.
        """
        import xarray as xr

        parts = []
        for fc in self.points:
            ds = fc.to_dataset()
            if self.frequency_ratios is not None:
                # the ratios as given, not ω_e/ω recomputed (which differs in round-off)
                ds = ds.swap_dims(frequency="frequency_ratio").assign_coords(
                    frequency_ratio=(
                        "frequency_ratio",
                        self.frequency_ratios,
                        {"units": "1", "long_name": "ω_e/ω"},
                    )
                )
                ds = ds.reset_coords("frequency")
            parts.append(ds.set_coords("speed"))
        combined = xr.concat(parts, dim="speed", combine_attrs="drop_conflicts")
        combined["speed"].attrs.update(units="rad/s", long_name="rotor speed ω")
        return combined

    def headline(self) -> dict[str, Any]:
        """Unit-named keys for ``--json``: the bearing, load, grid and one
        :meth:`ForceCoefficients.headline` per speed under ``speeds``."""
        first = self.points[0].static
        return {
            "bearing": first.case.kind,
            "load_N": first.case.operation.load,
            "speeds": [fc.headline() for fc in self.points],
        }

    def _summary(self) -> tuple[str, dict[str, Any], None]:
        first = self.points[0]
        f0 = first.frequencies[0]
        at = (
            f"ω_e/ω = {self.frequency_ratios[0]:.3g}"
            if self.frequency_ratios is not None
            else f"{f0 / (2 * math.pi):.4g} Hz"
        )
        title = (
            f"Force coefficients of the {first.static.case.kind} at {len(self.points)} speeds, "
            f"{first.static.case.operation.load:.4g} N, at {at}"
        )
        speeds = [fc.static.speed * 30 / math.pi for fc in self.points]
        rows: dict[str, Any] = {"speed_rpm": speeds}
        rows["eccentricity"] = [fc.static.eccentricity for fc in self.points]
        for name, i, j in (("XX", 0, 0), ("XY", 0, 1), ("YX", 1, 0), ("YY", 1, 1)):
            rows[f"K_{name}_MN_per_m"] = [fc.K[0, i, j] / 1e6 for fc in self.points]
        for name, i, j in (("XX", 0, 0), ("XY", 0, 1), ("YX", 1, 0), ("YY", 1, 1)):
            rows[f"C_{name}_kNs_per_m"] = [fc.C[0, i, j] / 1e3 for fc in self.points]
        return title, rows, None

    def plot(self) -> Any:
        """K_ij (MN/m) and C_ij (kN·s/m) against rotor speed at the first excitation
        frequency (:func:`~foilbearing.output.plots.dynamics.plot_coefficients_over_speed`);
        returns the matplotlib Figure."""
        from foilbearing.output.plots.dynamics import plot_coefficients_over_speed

        return plot_coefficients_over_speed(self)


def coefficients_over_speeds(
    case: Any,
    speeds: Sequence[QuantityLike],
    frequencies: Any = None,
    *,
    frequency_ratios: Any = None,
) -> CoefficientSweep:
    """Force coefficients at each rotor speed of ``speeds``, about its own equilibrium.

    Each speed is solved on its own, as a single run at that speed (the same
    equilibrium and coefficients to round-off).

    Parameters
    ----------
    case
        The bearing (:class:`~foilbearing.case.Case`), any kind.
    speeds
        Rotor speeds: rad/s as floats, or quantities (``"30 krpm"``).
    frequencies
        Excitation frequencies, the same at every speed: rad/s as floats, or
        quantities (``"100 Hz"``). Give this or ``frequency_ratios``.
    frequency_ratios
        Excitation frequencies as ratios ω_e/ω of each speed (> 0); default, when
        neither is given, 20 ratios 0.1-2.0.

    Raises
    ------
    InputError
        An empty list, a speed not > 0, or both ``frequencies`` and ``frequency_ratios``.
    SolverError
        The equilibrium at a speed did not converge (the message names the speed).
    """
    from foilbearing.analysis.equilibrium import solve_equilibrium

    omegas = as_si_array(speeds, "speed", field="speeds")
    if omegas.size == 0:
        raise InputError("speeds = []: give at least one rotor speed")
    if frequencies is not None and frequency_ratios is not None:
        raise InputError("give frequencies or frequency_ratios, not both")
    ratios = None
    if frequencies is None:
        default = np.linspace(0.1, 2.0, 20)
        ratios = default if frequency_ratios is None else np.atleast_1d(frequency_ratios)
        ratios = np.asarray(ratios, dtype=float)
        if ratios.size == 0 or not np.all(np.isfinite(ratios) & (ratios > 0)):
            raise InputError(f"frequency_ratios = {ratios.tolist()!r}: every ratio must be > 0")
    points = []
    for omega in omegas:
        static = solve_equilibrium(case.with_speed(float(omega)))
        if not static.converged:
            raise SolverError(
                f"at {omega * 30 / math.pi:.0f} rpm the equilibrium did not converge "
                f"({static.message})"
            )
        freqs = frequencies if ratios is None else ratios * static.speed
        points.append(force_coefficients(static, freqs))
    return CoefficientSweep(tuple(points), ratios)
