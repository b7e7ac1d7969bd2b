"""The package of laws (foilbearing.laws): the bottom layer, and each law an object.

The laws import nothing of the package above them (so any analysis can take them
without a cycle), and a law object refuses a reading it does not have, in one line.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from foilbearing.case import default_case
from foilbearing.design import READINGS
from foilbearing.film import film_model
from foilbearing.laws import READINGS as LAW_READINGS
from foilbearing.laws import ActuatorReading, LiftOff


def test_the_laws_are_the_bottom_layer() -> None:
    # What importing the laws loads beyond the package's own __init__ (constants, errors).
    code = (
        "import sys, foilbearing; before = set(sys.modules); import foilbearing.laws; "
        "print(sorted(m for m in set(sys.modules) - before if m.startswith('foilbearing')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded = eval(out.stdout)  # a list of module names
    assert "foilbearing.laws.lift_off" in loaded
    assert all(m.startswith("foilbearing.laws") for m in loaded), loaded


def test_a_law_refuses_what_it_does_not_have_in_one_line() -> None:
    with pytest.raises(
        ValueError, match=r"preload_response = 'pocket': expected one of 'local', 'lobe'"
    ):
        ActuatorReading("pocket", "held")
    with pytest.raises(
        ValueError, match=r"dynamics = 'stiff': expected one of 'compliant', 'held'"
    ):
        ActuatorReading("lobe", "stiff")
    with pytest.raises(ValueError, match=r"kappa\) must be finite and >= 0"):
        LiftOff(-0.1)


def test_the_film_model_carries_the_cases_reading() -> None:
    # The four readings in the design study's words and order; the film model of a case
    # under each carries that reading's law object, and its forms follow it.
    assert READINGS == tuple((r.preload_response, r.dynamics) for r in LAW_READINGS)
    case = default_case()
    for law in LAW_READINGS:
        model = film_model(case.with_actuator_reading(law.preload_response, law.dynamics))
        assert model.actuator == law
        assert (model.stack_compliance > 0.0) == law.lobe
        assert (model.actuator_compliance.max() > 0.0) == (not law.lobe)
        moving = law.motion_compliance(model.actuator_compliance)
        assert (moving.max() > 0.0) == (not law.lobe and law.compliant)
