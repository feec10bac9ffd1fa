"""A time derivative carries the same unit in Python results as in an FMU's model description
(``der(j1.w)`` was ``(rad/s)/s`` in ``System.outputs`` and ``Result.units`` but ``rad/s2`` in
the FMU): one spelling, :func:`bearingsim.units.fmi.derivative_unit`."""

from __future__ import annotations

from bearingsim.assembler import assemble
from bearingsim.simulation import simulate
from bearingsim.units.fmi import derivative_unit
from bearingsim.units.registry import si_factor
from tests.models import TwoInertiaDrive


def test_derivative_units_are_written_simply_in_the_system_and_its_results():
    system = assemble(TwoInertiaDrive())
    units = {o.name: o.unit for o in system.outputs}
    assert units["der(j1.w)"] == units["der(j2.w)"] == "rad/s2"
    for state in system.states:
        name = f"der({state.name})"
        if name in units:
            assert units[name] == derivative_unit(state.unit)
    result = simulate(system, 0.01, n_points=3, progress=False)
    assert result.units["der(j2.w)"] == "rad/s2"


def test_the_simple_spelling_is_the_same_quantity():
    assert si_factor("rad/s2", "(rad/s)/s") == (1.0, 0.0)
    assert derivative_unit("rad") == "rad/s" and derivative_unit("1") == "1/s"
    assert derivative_unit("N.m/s") == "N.m/s2"
