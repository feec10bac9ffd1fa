"""Measured errors of the lower fidelity levels against the reference level, per quantity: the
numbers ``fidelity = "auto"`` decides with (:attr:`~bearingsim.assemblies.spec.AssemblySpec.
level_errors`), stored in ``bearingsim/assemblies/fidelity_errors.json``.

The file is written by this module from the models themselves, never by hand::

    python -m bearingsim.studies.fidelity_errors

and ``tests/studies/test_fidelity_errors.py`` re-measures every entry. Each declared error is the
largest
relative deviation ``|q_level - q_reference| / |q_reference|`` over the operating points of
:data:`DOUBLE_LAYER_POINTS`, rounded up to two significant digits.
"""

from __future__ import annotations

import itertools
import json
import math
import sys
from pathlib import Path
from typing import Any

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.assemblies.spec import FIDELITY_ERRORS_FILE
from bearingsim.files import atomic_path
from bearingsim.studies.double_layer import steady_ratio
from bearingsim.units import rpm_to_rad_s

__all__ = ["DOUBLE_LAYER_POINTS", "double_layer_errors", "measure_all", "round_up",
           "write_fidelity_errors"]

DOUBLE_LAYER_POINTS: dict[str, Any] = {
    "pairings": [("61905", "61907"), ("61905", "61908"), ("61905", "61909")],
    "lubrications": ["ISO VG 32", "lithium grease"],
    "speeds_rpm": [1000.0, 10000.0],
    "radial_loads_N": [0.0, 1000.0],
}
"""Operating points of the double-layer measurement: the three pairings of docs/studies.md, section
A (Z, Z and I type), oil and grease, 1000 and 10 000 r/min, no load and 1 kN radial load; steady
state of each level (Palmgren friction at the torque level, the scene default)."""


def round_up(value: float, digits: int = 2) -> float:
    """``value`` >= 0 rounded up to ``digits`` significant digits (0 stays 0).

    Parameters
    ----------
    value : float
        A non-negative number.
    digits : int
        Significant digits kept.

    Returns
    -------
    float
        The rounded value.
    """
    if value <= 0.0:
        return 0.0
    scale = 10.0 ** (digits - 1 - math.floor(math.log10(value)))
    return math.ceil(value * scale - 1e-9) / scale


def double_layer_errors(points: dict[str, Any] | None = None) -> dict[str, dict[str, float]]:
    """Largest relative error of the kinematic levels' steady ``Rs`` (and so of the middle-ring
    speed) and shaft speed against the torque level over the operating points.

    Parameters
    ----------
    points : dict, optional
        Operating points like :data:`DOUBLE_LAYER_POINTS` (default).

    Returns
    -------
    dict
        Level -> quantity name pattern -> error [-] (unrounded).
    """
    pts = points or DOUBLE_LAYER_POINTS
    worst: dict[str, float] = {"kinematic": 0.0, "kinematic_approx": 0.0}
    for (inner, outer), lubrication in itertools.product(pts["pairings"], pts["lubrications"]):
        systems = {level: assemble(double_layer_bearing(inner, outer, fidelity=level,
                                                        lubrication=lubrication))
                   for level in ("torque", *worst)}
        for rpm, load in itertools.product(pts["speeds_rpm"], pts["radial_loads_N"]):
            speed = rpm_to_rad_s(rpm)
            reference = steady_ratio(systems["torque"], speed, (load, 0.0))[0]
            for level in worst:
                rs = steady_ratio(systems[level], speed, (load, 0.0))[0]
                worst[level] = max(worst[level], abs(rs - reference) / abs(reference))
    # w_middle = Rs w_shaft with the shaft speed imposed (exact at every level)
    return {level: {"Rs": err, "w_middle": err, "middle.*": err, "der(*phi)": err,
                    "w_shaft": 0.0, "shaft_speed": 0.0, "shaft.phi": 0.0, "drive.*": 0.0}
            for level, err in worst.items()}


def measure_all() -> dict[str, Any]:
    """Every assembly's declared errors as stored in the file (rounded up).

    Returns
    -------
    dict
        The contents of the fidelity errors file.
    """
    return {
        "double_layer_bearing": {
            "reference": "torque",
            "measured_over": DOUBLE_LAYER_POINTS | {"pairings": [
                "/".join(p) for p in DOUBLE_LAYER_POINTS["pairings"]]},
            "errors": {level: {q: round_up(e) for q, e in quantities.items()}
                       for level, quantities in double_layer_errors().items()},
        },
    }


def write_fidelity_errors(path: str | Path = FIDELITY_ERRORS_FILE) -> Path:
    """Measure and write the file; returns its path.

    Parameters
    ----------
    path : str or Path
        The JSON file (default: the package's).

    Returns
    -------
    Path
        The path written.
    """
    path = Path(path)
    with atomic_path(path) as tmp:
        Path(tmp).write_text(json.dumps(measure_all(), indent=2) + "\n", encoding="utf-8")
    return path


if __name__ == "__main__":
    print(f"wrote {write_fidelity_errors(*sys.argv[1:2])}")
