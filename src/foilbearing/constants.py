"""Conversion constants used across the package (everything inside it is SI)."""

from __future__ import annotations

import math

__all__ = ["RPM"]

#: Angular speed of one revolution per minute, rad/s: ``omega = rpm * RPM``, ``rpm = omega / RPM``.
RPM = math.pi / 30.0
