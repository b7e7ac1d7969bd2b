"""Export of the bearing's force coefficients to ROSS (``ross-rotordynamics`` >= 3.0).

:func:`coefficient_table` computes stiffness and damping over rotor speed ×
excitation (whirl) frequency, the equilibria taken in increasing speed, each
started from the last. :func:`to_ross_bearing` turns such a table into a
``ross.BearingElement`` with 2-D coefficient tables, shape
``(len(speed), len(frequency))``, which ROSS interpolates at the rotor speed
and at each mode's whirl frequency (``Rotor.run_modal(speed,
matched_whirl=True)``, ``Rotor.run_campbell(..., matched_whirl=True)``).

**Pass ``matched_whirl=True``.** ROSS's default takes every bearing's coefficients at the
running speed (synchronous). A foil bearing's coefficients change strongly with the whirl
frequency, and its unstable whirl is sub-synchronous, so the default overstates this
bearing's stability badly: on examples/rotor_rigid_symmetric.toml at 150 V, with tables
4 krpm apart, the synchronous default turns unstable between 84 and 88 krpm, where the
matched whirl finds 55.1 krpm (our own ``stability``, 55.0; measured 2026-12-03).
:mod:`foilbearing.rotor` always passes it (docs/rotor-format.md). The unbalance response
is synchronous by nature and ROSS takes it at frequency = speed.

Frame mapping
-------------
Ours (docs/model.md §2): X along the static load (gravity, pointing down), Y
horizontal, the journal rotating from +X towards +Y (θ grows from −X in that
sense). ROSS: x horizontal, y vertical and pointing up (its gravity acts along
−y), rotation and forward whirl from +x towards +y (its orbit parameter κ > 0).
Keeping the sense of rotation and the direction of gravity fixes the map

    x_ROSS = Y,    y_ROSS = −X,

a rotation by 90° (proper, so forward whirl stays forward). With this
orthogonal T, ``q_ROSS = T q``, the coefficient matrices transform as
``K_ROSS = T K Tᵀ``:

    kxx = K_YY,   kxy = −K_YX,   kyx = −K_XY,   kyy = K_XX,

and the same for the damping. Both frames define ``K_ij = −∂F_i/∂q_j``
(force on the journal), so no other sign enters.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.analysis.coefficients import force_coefficients
from foilbearing.analysis.equilibrium import StaticResult, solve_equilibrium
from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.film import FilmModel, film_model
from foilbearing.reynolds import Workspace

__all__ = ["coefficient_table", "ross_coefficients", "to_ross_bearing"]

ROSS_MIN_VERSION = (3, 0)
_INSTALL_HINT = (
    "pip install 'foilbearing[ross]' (ross-rotordynamics >= 3.0; `make test` and `make run` "
    "install it in the project's .venv)"
)


def coefficient_table(
    case: Case,
    speeds: Sequence[float] | NDArray[np.float64],
    frequencies: Sequence[float] | NDArray[np.float64] | None = None,
    *,
    ratios: Sequence[float] | NDArray[np.float64] | None = None,
    model: FilmModel | None = None,
    loss_factor: float | None = None,
    progress: Callable[[str], None] | None = None,
) -> Any:
    """Stiffness and damping of the bearing over rotor speed × excitation frequency.

    Parameters
    ----------
    case
        Bearing case (load from ``case.operation.load``; voltages as set in the case).
    speeds
        Rotor speeds ω, rad/s, > 0; sorted increasingly. The equilibrium at each
        speed starts from the one at the previous speed (continuation).
    frequencies
        Excitation (whirl) frequencies ω_e, rad/s, > 0, shared by all speeds: the
        table ROSS takes. Default (with ``ratios`` also None): 10 points spaced
        geometrically from 0.1 × the lowest speed to the highest speed.
    ratios
        Instead of ``frequencies``: frequency ratios ν = ω_e/ω, so that the
        absolute frequency varies with speed (dimension ``ratio``, with a 2-D
        coordinate ``frequency``). Such a table is for plots; ROSS needs
        ``frequencies``.
    model
        Film model of the case (built if omitted).
    loss_factor
        Override of the bump's loss factor γ (default: the case's).
    progress
        Called with one line per speed.

    Returns
    -------
    xarray.Dataset
        ``stiffness`` (N/m) and ``damping`` (N·s/m) with dims
        ``(speed, frequency, i, j)`` (or ``(speed, ratio, i, j)``), i, j in
        ``["X", "Y"]`` (our frame: X along the load); ``eps_x``, ``eps_y``
        (units of C) and ``converged`` per speed. Coordinates ``speed`` and
        ``frequency`` in rad/s. Rows at speeds without an equilibrium are NaN
        and ``attrs["message"]`` names them.
    """
    import xarray as xr

    w = _axis(speeds, "speeds", sort=True)
    if frequencies is not None and ratios is not None:
        raise InputError("give either frequencies (rad/s) or ratios (ω_e/ω), not both")
    if ratios is not None:
        nu = _axis(ratios, "ratios", sort=False)
        freq = np.outer(w, nu)
        fdim = "ratio"
    else:
        if frequencies is None:
            frequencies = np.geomspace(0.1 * w[0], w[-1], 10)
        freq1 = _axis(frequencies, "frequencies", sort=True)
        freq = np.broadcast_to(freq1, (w.size, freq1.size))
        fdim = "frequency"

    model = model or film_model(case)
    ws = Workspace(model.grid)
    K = np.full((w.size, freq.shape[1], 2, 2), np.nan)
    C = np.full_like(K, np.nan)
    eps = np.full((w.size, 2), np.nan)
    ok = np.zeros(w.size, dtype=bool)
    start: tuple[float, float, Any] | None = None
    for k, speed in enumerate(w):
        st = _equilibrium(case, float(speed), model, start)
        if st is None:
            start = None
            if progress is not None:
                progress(f"{speed / RPM:8.0f} rpm: no equilibrium")
            continue
        start = (st.eps_x, st.eps_y, st.P)
        fc = force_coefficients(st, freq[k], loss_factor=loss_factor, workspace=ws)
        K[k], C[k], eps[k], ok[k] = fc.K, fc.C, (st.eps_x, st.eps_y), True
        if progress is not None:
            progress(f"{speed / RPM:8.0f} rpm: eccentricity {st.eccentricity:.3f}")

    failed = w[~ok]
    message = (
        "all equilibria converged"
        if failed.size == 0
        else "no equilibrium at " + ", ".join(f"{s / RPM:.0f}" for s in failed) + " rpm"
    )
    dims4 = ("speed", fdim, "i", "j")
    coords: dict[str, Any] = {
        "speed": ("speed", w, {"units": "rad/s", "long_name": "rotor speed"}),
        "i": ["X", "Y"],
        "j": ["X", "Y"],
    }
    if fdim == "ratio":
        coords["ratio"] = ("ratio", nu, {"units": "1", "long_name": "ω_e/ω"})
        coords["frequency"] = (("speed", "ratio"), freq, {"units": "rad/s"})
    else:
        coords["frequency"] = (
            "frequency",
            freq[0].copy(),
            {"units": "rad/s", "long_name": "excitation (whirl) frequency"},
        )
    return xr.Dataset(
        {
            "stiffness": (dims4, K, {"units": "N/m", "long_name": "K_ij = -dF_i/dq_j"}),
            "damping": (dims4, C, {"units": "N s/m", "long_name": "C_ij"}),
            "eps_x": ("speed", eps[:, 0], {"units": "1", "long_name": "e_X/C"}),
            "eps_y": ("speed", eps[:, 1], {"units": "1", "long_name": "e_Y/C"}),
            "converged": ("speed", ok),
        },
        coords=coords,
        attrs={
            "frame": "X along the static load, Y horizontal, rotation from +X towards +Y",
            "rotor_mass_kg": case.rotor.mass,
            "load_N": case.operation.load,
            "message": message,
        },
    )


def ross_coefficients(K: NDArray[np.float64], C: NDArray[np.float64]) -> dict[str, Any]:
    """Our K, C (indices [X, Y], shape (..., 2, 2)) as ROSS's kxx ... cyx (module docstring).

    Returns
    -------
    dict
        ``kxx, kxy, kyx, kyy`` (N/m) and ``cxx, cxy, cyx, cyy`` (N·s/m), each of
        shape ``K.shape[:-2]``, in ROSS's frame (x = Y, y = −X).
    """
    K, C = np.asarray(K, dtype=float), np.asarray(C, dtype=float)
    out: dict[str, Any] = {}
    for name, A in (("k", K), ("c", C)):
        out[f"{name}xx"] = A[..., 1, 1]
        out[f"{name}xy"] = -A[..., 1, 0]
        out[f"{name}yx"] = -A[..., 0, 1]
        out[f"{name}yy"] = A[..., 0, 0]
    return out


def to_ross_bearing(
    table_or_case: Any,
    n: int,
    *,
    tag: str | None = None,
    speeds: Sequence[float] | NDArray[np.float64] | None = None,
    frequencies: Sequence[float] | NDArray[np.float64] | None = None,
    n_link: int | None = None,
    interpolation: str = "pchip",
    scale_factor: float = 1.0,
) -> Any:
    """A ``ross.BearingElement`` with this bearing's coefficients over speed × frequency.

    Parameters
    ----------
    table_or_case
        A table from :func:`coefficient_table` (with a ``frequency`` dimension),
        or a :class:`~foilbearing.case.Case`, whose table is then computed over
        ``speeds`` and ``frequencies``.
    n
        ROSS node the bearing sits at.
    tag
        ROSS element tag (default ``"foil bearing <n>"``).
    speeds, frequencies
        Table axes in rad/s when a case is given (see :func:`coefficient_table`).
    n_link
        ROSS node the bearing connects to (default: ground).
    interpolation
        ROSS's interpolation along each axis, ``"pchip"`` or ``"linear"``.
    scale_factor
        ROSS drawing scale of the element.

    Returns
    -------
    ross.BearingElement
        Coefficients in ROSS's frame (x = Y, y = −X, module docstring), 2-D
        tables of shape ``(len(speed), len(frequency))``, axes in rad/s.
        ROSS evaluates them with ``K(frequency, speed)``.

    Raises
    ------
    InputError
        ROSS is not installed, the table is over frequency ratios, or it has
        speeds without an equilibrium.
    """
    ross = _import_ross()
    if isinstance(table_or_case, Case):
        if speeds is None:
            raise InputError("to_ross_bearing(case, ...) needs speeds= (rad/s) for the table")
        table = coefficient_table(table_or_case, speeds, frequencies)
    else:
        if speeds is not None or frequencies is not None:
            raise InputError("speeds= and frequencies= are for a case; a table has its own axes")
        table = table_or_case
    if "frequency" not in table.dims:
        raise InputError(
            "ROSS needs a table over absolute frequencies: "
            "coefficient_table(case, speeds, frequencies=...) rather than ratios="
        )
    if not bool(table["converged"].all()):
        raise InputError(
            f"the table has speeds without an equilibrium ({table.attrs.get('message', '')}): "
            "drop them from speeds"
        )
    K = table["stiffness"].transpose("speed", "frequency", "i", "j").values
    C = table["damping"].transpose("speed", "frequency", "i", "j").values
    if not (np.all(np.isfinite(K)) and np.all(np.isfinite(C))):
        raise InputError("the table has non-finite coefficients")
    return ross.BearingElement(
        n=n,
        **ross_coefficients(K, C),
        speed=np.asarray(table["speed"].values, dtype=float),
        frequency=np.asarray(table["frequency"].values, dtype=float),
        tag=tag if tag is not None else f"foil bearing {n}",
        n_link=n_link,
        interpolation=interpolation,
        scale_factor=scale_factor,
    )


def _import_ross(what: str = "the ROSS export") -> Any:
    """ROSS, or an InputError saying that ``what`` needs it and how to install it: the core
    install (``pip install foilbearing``) has no ROSS, the ``ross`` extra adds it."""
    try:
        ross = _quiet_import("ross")
    except ImportError as exc:
        raise InputError(f"{what} needs ROSS: {_INSTALL_HINT}") from exc
    version = getattr(ross, "__version__", "0")
    parts = tuple(int(p) for p in version.split(".")[:2] if p.isdigit())
    if parts < ROSS_MIN_VERSION:
        raise InputError(
            f"ROSS {version} is too old for 2-D speed × frequency tables: {_INSTALL_HINT}"
        )
    return ross


def _quiet_import(name: str) -> Any:
    """Import ``name`` with its output to stdout dropped, Python's and the C libraries': ROSS's
    property libraries announce at import that REFPROP is missing, which would break the
    one JSON object a ``--json`` command prints. Their warning that names the missing
    library's path is dropped too (it would show on every page that imports ROSS)."""
    import contextlib
    import importlib
    import io
    import os
    import sys
    import warnings

    if name in sys.modules:
        return importlib.import_module(name)
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with (
            open(os.devnull, "w") as null,
            contextlib.redirect_stdout(io.StringIO()),
            warnings.catch_warnings(),
        ):
            warnings.filterwarnings("ignore", message=r"[\s\S]*REFPROP", category=UserWarning)
            os.dup2(null.fileno(), 1)
            try:
                return importlib.import_module(name)
            finally:
                sys.stdout.flush()
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def _axis(values: Any, name: str, *, sort: bool) -> NDArray[np.float64]:
    """A 1-D, finite, positive, strictly increasing axis (sorted if ``sort``)."""
    a = np.atleast_1d(np.asarray(values, dtype=float))
    if a.ndim != 1 or a.size == 0 or not np.all(np.isfinite(a)) or np.any(a <= 0):
        raise InputError(f"{name} = {a.tolist()!r}: need a 1-D list of finite values > 0")
    if sort:
        a = np.sort(a)
    if np.any(np.diff(a) <= 0):
        raise InputError(f"{name} = {a.tolist()!r}: values must be distinct and increasing")
    return a


def _equilibrium(
    case: Case, speed: float, model: FilmModel, start: tuple[float, float, Any] | None
) -> StaticResult | None:
    """Equilibrium from ``start``, retried from the centre; None if neither converges."""
    st = solve_equilibrium(case, speed=speed, model=model, start=start)
    if not st.converged and start is not None:
        st = solve_equilibrium(case, speed=speed, model=model)
    return st if st.converged else None
