"""Moved: the kernels' NumPy twins are test oracles, :mod:`foilbearing.testing.twins`; the
SciPy fallback of the transient Newton is :mod:`foilbearing.reynolds.fallback`.

Importing a name from here fails with one line naming its new home (a forwarding import
would put the test oracles back on the production path)."""

from __future__ import annotations

_TWINS = "foilbearing.testing.twins"
_FALLBACK = "foilbearing.reynolds.fallback"

#: Each name this module held, and where it lives now.
MOVED = {
    name: f"{_TWINS}.{name}"
    for name in (
        "adopt_branches_py",
        "bdf_setup_py",
        "bernoulli_deriv_py",
        "bernoulli_py",
        "block_cyclic_factor_py",
        "block_cyclic_solve_py",
        "coupled_jacobian_py",
        "jacobian_H_py",
        "jacobian_P_py",
        "jacobian_blocks_py",
        "lift_coordinate_py",
        "lift_off_rows_py",
        "predict_branches_py",
        "residual_py",
    )
} | {
    name: f"{_FALLBACK}.{name.removesuffix('_py')} (twin: {_TWINS}.{name})"
    for name in (
        "border_py",
        "lobe_correct_py",
        "newton_residual_py",
        "newton_solve_py",
        "newton_step_py",
        "newton_update_py",
        "smoothed_lift_off_py",
        "solve_py",
        "switch_branches_py",
    )
}


def __getattr__(name: str) -> object:
    if name in MOVED:
        raise ImportError(f"{__name__}.{name} has moved to {MOVED[name]}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
