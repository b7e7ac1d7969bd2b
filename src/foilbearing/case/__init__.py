"""The bearing case: ``model`` (frozen dataclasses, SI) and ``toml`` (reading, validating and finding case files)."""

from foilbearing.case.model import (
    MAX_SPEED_DEFAULT,
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
    "MAX_SPEED_DEFAULT",
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
