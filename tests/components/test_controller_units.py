"""Units of the PI controller's integral state and gain."""

import pytest

from bearingsim.components.blocks import PIController
from bearingsim.units.registry import base_exponents


def _product(*units: str) -> dict[str, float]:
    out: dict[str, float] = {}
    for unit in units:
        for base, power in base_exponents(unit)[0]:
            out[base] = out.get(base, 0.0) + power
    return {k: v for k, v in out.items() if v != 0.0}


@pytest.mark.parametrize(("unit_e", "unit_y", "xi"), [
    ("rad/s", "V", "rad"), ("rad/s", "A", "rad"), ("A", "V", "A.s"), ("1", "1", "s"),
    ("m/s2", "N", "(m/s2).s")])
def test_the_integral_state_reads_one_way(unit_e, unit_y, xi):
    """The motor drive's speed controllers integrate a speed error in rad/s: the integral's
    unit was written ``rad/s.s`` (in the CSV header, the FMU's unit names, the component
    reference), which reads as rad/s^2 as well as rad; the integral gain ``(V)/(rad/s.s)``
    alike. Now ``rad`` and ``(V)/(rad)``, and each still multiplies out to the right unit."""
    units = {name: d.unit for name, d in PIController(0.5, 10.0, unit_e, unit_y)
             .declarations.items()}
    assert units["xi"] == xi
    assert _product(units["xi"]) == _product(unit_e, "s")
    assert _product(units["ki"], units["xi"]) == _product(unit_y)
    assert _product(units["kp"], unit_e) == _product(unit_y)
