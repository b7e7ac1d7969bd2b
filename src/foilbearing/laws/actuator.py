"""The actuator in the film: how the stack's compression and compliance reach the film.

A PZT stack pushes the foil through a stinger; the film pressure compresses the stack
(stiffness k_p + 4k_sp per unit area, in series with the bump). How that compression
shapes the film, and whether the stack yields during the journal's motion, are two
choices of reading (docs/model.md §3.8), four readings in all:

- preload response: ``"local"`` — the compression carves a pocket under the stinger
  (the actuator's compliance joins the bump's under it); ``"lobe"`` — it lowers the
  whole preload lobe of that actuator (a stack compliance c_s per unit gauge
  pressure at the stinger).
- dynamics: ``"compliant"`` — the stack's compliance acts at the motion's frequency;
  ``"held"`` — the stinger keeps its quasi-static position (a positioner), so only
  the bump responds to the motion, and the orbit prescribes the held compression.

:class:`ActuatorReading` holds one reading and gives each analysis its form: the
static film (:meth:`~ActuatorReading.static_compliance`,
:meth:`~ActuatorReading.stack_compliance`), and the motion, the same in the force
coefficients and the orbit (:meth:`~ActuatorReading.motion_compliance`,
:attr:`~ActuatorReading.lobes_move`, :attr:`~ActuatorReading.held`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["ACTUATOR_DYNAMICS", "PRELOAD_RESPONSES", "READINGS", "ActuatorReading"]

#: How the stack's compression under the film pressure shapes the film: a pocket under
#: the stinger, or the whole preload lobe lowered.
PRELOAD_RESPONSES = ("local", "lobe")

#: How the stack's compliance acts during the journal's motion: at the motion's
#: frequency (an elastic stack under open-loop voltage), or not at all (a positioner).
ACTUATOR_DYNAMICS = ("compliant", "held")


@dataclass(frozen=True)
class ActuatorReading:
    """One reading of the actuator in the film (docs/model.md §3.8).

    Parameters
    ----------
    preload_response : str
        ``"local"`` (default) or ``"lobe"``, one of :data:`PRELOAD_RESPONSES`.
    dynamics : str
        ``"compliant"`` (default) or ``"held"``, one of :data:`ACTUATOR_DYNAMICS`.
    """

    preload_response: str = "local"
    dynamics: str = "compliant"

    def __post_init__(self) -> None:
        for name, value, allowed in (
            ("preload_response", self.preload_response, PRELOAD_RESPONSES),
            ("dynamics", self.dynamics, ACTUATOR_DYNAMICS),
        ):
            if value not in allowed:
                raise ValueError(
                    f"ActuatorReading.{name} = {value!r}: expected one of "
                    + ", ".join(repr(a) for a in allowed)
                )

    @property
    def lobe(self) -> bool:
        """The stack's compression lowers the whole lobe (``"lobe"``)."""
        return self.preload_response == "lobe"

    @property
    def held(self) -> bool:
        """The stinger keeps its quasi-static position during the motion (``"held"``)."""
        return self.dynamics == "held"

    @property
    def compliant(self) -> bool:
        """The stack yields at the motion's frequency (``"compliant"``)."""
        return self.dynamics == "compliant"

    @property
    def lobes_move(self) -> bool:
        """The lobes follow the stacks' compression during the motion (lobe + compliant)."""
        return self.lobe and self.compliant

    @property
    def label(self) -> str:
        """``"response+dynamics"``, e.g. ``"local+compliant"``."""
        return f"{self.preload_response}+{self.dynamics}"

    def static_compliance(self, actuator_compliance: NDArray[Any]) -> NDArray[Any]:
        """The actuators' share of the foil compliance in the static film, per θ-row:
        in series with the bump under ``"local"``; none under ``"lobe"`` (the
        compression lowers the lobe instead, :meth:`stack_compliance`)."""
        if self.lobe:
            return np.zeros_like(actuator_compliance)
        return actuator_compliance

    def stack_compliance(
        self, ambient_pressure: float, clearance: float, stiffness: float
    ) -> float:
        """c_s = p_a/(C (k_p + 4k_sp)), the lobe's lowering per unit gauge pressure at the
        stinger in units of C, under ``"lobe"``; 0 under ``"local"``."""
        return ambient_pressure / (clearance * stiffness) if self.lobe else 0.0

    def motion_compliance(self, actuator_compliance: NDArray[Any]) -> NDArray[Any]:
        """The actuators' compliance that acts during the motion (coefficients and orbit):
        the static share when compliant, none when held."""
        if self.held:
            return np.zeros_like(actuator_compliance)
        return actuator_compliance


#: The four readings, the case's default first.
READINGS: tuple[ActuatorReading, ...] = tuple(
    ActuatorReading(r, d) for r in PRELOAD_RESPONSES for d in ACTUATOR_DYNAMICS
)
