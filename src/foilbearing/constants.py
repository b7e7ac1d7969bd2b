"""Conversion constants used across the package (everything inside it is SI)."""

from __future__ import annotations

import math

__all__ = ["RPM", "STANDARD_GRAVITY"]

#: Angular speed of one revolution per minute, rad/s: ``omega = rpm * RPM``, ``rpm = omega / RPM``.
RPM = math.pi / 30.0

#: Standard acceleration of gravity, m/s² (the SI's conventional value): a case that gives
#: only one of the rotor mass and the static load gets the other as ``W = m g``.
STANDARD_GRAVITY = 9.80665
