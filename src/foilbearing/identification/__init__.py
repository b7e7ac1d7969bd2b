"""Identification of the PZT stack parameters from measured stack data (paper section 4).

Two tests identify the stack model of Eqs. (1)-(2), ``δ = F/K_p + D33,1 V² + D33,2 V``:

- the no-load test (paper Fig. 5b) gives D33,1 and D33,2 from a least-squares fit
  through the origin of ``δ = D33,1 V² + D33,2 V``, per stack and pooled;
- the stiffness test (paper Figs. 6b-c) gives the stack stiffness K_p from the
  slope ``−1/K_p`` of displacement against compressive load at each voltage;
  ``k_p = K_p / A_c`` (N/m³) with A_c the stinger-foil contact area.

Files are CSV with a header line; lines starting with ``#`` are comments, and
comments of the form ``# key: value`` are kept as metadata. Columns:

- no-load: ``voltage_V``, then one ``stack<label>_um`` column per stack (µm);
- stiffness (long format): ``stack``, ``voltage_V``, ``load_N`` (≥ 0,
  compressive), ``displacement_um``.

Everything inside is SI (m, V, N); the fit objects offer µm views for reports.
R² is everywhere the usual ``1 − SS_res/SS_tot`` with SS_tot the sum of squares
about the mean, also for the fits through the origin (where it may be negative).

==============  ================================================================================
module          responsibility
==============  ================================================================================
``stack_data``  measured PZT-stack data: the no-load and stiffness test files (CSV)
``fits``        fits of the stack model of Eqs. (1)-(2): D33,1, D33,2 and K_p
``case_file``   the identified parameters written into a case file, its comments and layout kept
==============  ================================================================================
"""

from __future__ import annotations

from foilbearing.identification.case_file import (
    case_values,
    update_case_file,
)
from foilbearing.identification.fits import (
    MANUFACTURER_D33,
    Identification,
    LinearFit,
    LineFit,
    NoLoadFit,
    QuadraticFit,
    StiffnessFit,
    fit_no_load,
    fit_stiffness,
    identify,
)
from foilbearing.identification.stack_data import (
    NoLoadData,
    StiffnessData,
    example_measurements,
    read_no_load,
    read_stiffness,
)

__all__ = [
    "MANUFACTURER_D33",
    "Identification",
    "LineFit",
    "LinearFit",
    "NoLoadData",
    "NoLoadFit",
    "QuadraticFit",
    "StiffnessData",
    "StiffnessFit",
    "case_values",
    "example_measurements",
    "fit_no_load",
    "fit_stiffness",
    "identify",
    "read_no_load",
    "read_stiffness",
    "update_case_file",
]
