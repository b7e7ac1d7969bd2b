"""Moved: the orbit's solve_ivp reference is a test oracle, :mod:`foilbearing.testing.ivp_orbit`.

Importing a name from here fails with one line naming its new home (a forwarding import
would put the test oracle back on the production path)."""

from __future__ import annotations

#: Each name this module held, and where it lives now.
MOVED = {
    name: f"foilbearing.testing.ivp_orbit.{name}"
    for name in ("HOLD_TIME", "reference_orbit", "state_derivative", "state_sparsity")
}


def __getattr__(name: str) -> object:
    if name in MOVED:
        raise ImportError(f"{__name__}.{name} has moved to {MOVED[name]}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
