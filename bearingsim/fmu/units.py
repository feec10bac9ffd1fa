"""FMI unit definitions: see :mod:`bearingsim.units.fmi` (one units module for the package)."""

from bearingsim.units.fmi import (
    BASE_UNITS,
    UnitDefinition,
    derivative_unit,
    normalize_unit,
    parse_unit,
)

__all__ = ["BASE_UNITS", "UnitDefinition", "derivative_unit", "normalize_unit", "parse_unit"]
