"""The bearing case: ``model`` (frozen dataclasses, SI) and ``toml`` (reading, validating and finding case files).

==========  ====================================================================================
module      responsibility
==========  ====================================================================================
``model``   the bearing case as frozen dataclasses, SI inside, validated on creation and on
            change
``schema``  every field of a case file declared once: TOML path, dimension, bounds, display unit
``toml``    reading, validating and finding case files
``record``  a case written back as the tables of a case file (the run record)
==========  ====================================================================================
"""

from foilbearing.case.model import (
    ACTUATOR_DYNAMICS,
    MAX_SPEED_DEFAULT,
    PRELOAD_RESPONSES,
    SUBAMBIENT_MODELS,
    Actuators,
    Bearing,
    BumpGeometry,
    Case,
    Disturbance,
    Foil,
    Gas,
    Grid,
    Operation,
    Rotor,
    Shims,
)
from foilbearing.case.toml import (
    TableReader,
    case_from_dict,
    default_case,
    default_case_path,
    is_default_case_file,
    load_case,
    per_item_quantities,
)

__all__ = [
    "ACTUATOR_DYNAMICS",
    "MAX_SPEED_DEFAULT",
    "PRELOAD_RESPONSES",
    "SUBAMBIENT_MODELS",
    "Actuators",
    "Bearing",
    "BumpGeometry",
    "Case",
    "Disturbance",
    "Foil",
    "Gas",
    "Grid",
    "Operation",
    "Rotor",
    "Shims",
    "TableReader",
    "case_from_dict",
    "default_case",
    "default_case_path",
    "is_default_case_file",
    "load_case",
    "per_item_quantities",
]
