"""Rotors on foil bearings: a shaft of beam elements with disks, on two C-GFBs.

This is the flexible shaft (a ``RotorCase``, read from a rotor file). A bearing case's
``Case.rotor`` (its ``[rotor]`` table) is something else: the rigid mass and imbalance that
one bearing carries, its journal (:class:`foilbearing.case.Rotor`).

- :mod:`.model`: the rotor (:class:`RotorCase`) and the weight each bearing carries;
- :mod:`.toml`: the rotor file (:func:`load_rotor`);
- :mod:`.linear`: modes, log decrements and the onset speed on ROSS with matched whirl
  (:func:`rotor_modes`, :func:`rotor_onset`; ROSS is the ``ross`` extra);
- :mod:`.response`: the unbalance response at the bearings and disks and the mode shapes,
  on ROSS (:func:`unbalance_response`, :func:`mode_shapes`);
- :mod:`.reduced`: the rotor reduced to its journals and a few shaft modes (Craig-Bampton),
  the basis of the nonlinear rotor (:func:`reduce_rotor`, :func:`reduced_onset`);
- :mod:`.nonlinear`: the nonlinear rotor, both bearings' films integrated with the reduced
  rotor (``RotorOrbitSystem``; imported from there, it brings the orbit's kernels).

=============  =================================================================================
module         responsibility
=============  =================================================================================
``model``      the rotor: shaft of beam elements, rigid disks, bearings at nodes; the weight
               each carries
``toml``       the rotor file, read into a ``RotorCase``
``linear``     modes, log decrements and the onset speed on ROSS with matched whirl
``response``   the unbalance response and the mode shapes, on ROSS
``reduced``    the rotor reduced to its journals and a few shaft modes
``nonlinear``  the nonlinear rotor: every bearing's film and foil integrated with the reduced
               rotor
``stepper``    the nonlinear rotor on the orbit's stepper: every film's compiled kernels, one
               rotor solve
``record``     the rotor orbit's run record: the rotor and its bearing cases as data, with a
               sha256
=============  =================================================================================
"""

from foilbearing.rotor.linear import RotorModes, ross_rotor, rotor_modes, rotor_onset
from foilbearing.rotor.model import BearingSite, Disk, Material, RotorCase, ShaftElement
from foilbearing.rotor.reduced import ReducedRotor, reduce_rotor, reduced_modes, reduced_onset
from foilbearing.rotor.response import (
    ModeShapes,
    UnbalanceResponse,
    mode_shapes,
    unbalance_response,
)
from foilbearing.rotor.toml import load_rotor, rotor_from_dict

__all__ = [
    "BearingSite",
    "Disk",
    "Material",
    "ModeShapes",
    "ReducedRotor",
    "RotorCase",
    "RotorModes",
    "ShaftElement",
    "UnbalanceResponse",
    "load_rotor",
    "mode_shapes",
    "reduce_rotor",
    "reduced_modes",
    "reduced_onset",
    "ross_rotor",
    "rotor_from_dict",
    "rotor_modes",
    "rotor_onset",
    "unbalance_response",
]
