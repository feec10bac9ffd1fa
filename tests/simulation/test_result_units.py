"""``Result.final(name, unit)``: the last value in a unit a person asks for, converted by the
units registry (a speed in rpm, a temperature in degC with its offset), and a unit of another
quantity refused naming the variable. Before, ``final`` took the name only ("too many
positional arguments")."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from bearingsim.simulation import Result
from bearingsim.units.registry import UnitError


def _result(w: float = 5000 * math.pi / 30, temperature: float = 313.15) -> Result:
    t = np.array([0.0, 1.0])
    return Result(t, ["w_shaft", "T_oil", "M"],
                  np.array([[0.0, w], [293.15, temperature], [0.0, 0.05]]),
                  {"w_shaft": "rad/s", "T_oil": "K", "M": "N.m"})


def test_the_last_value_in_the_unit_asked_for():
    res = _result()
    assert res.final("w_shaft") == pytest.approx(523.598775598, rel=1e-12)
    assert res.final("w_shaft", "rpm") == pytest.approx(5000.0, rel=1e-12)
    assert res.final("w_shaft", "r/min") == pytest.approx(5000.0, rel=1e-12)
    assert res.final("T_oil", "degC") == pytest.approx(40.0, rel=1e-12)
    assert res.final("M", "N mm") == pytest.approx(50.0, rel=1e-12)


def test_a_unit_of_another_quantity_is_refused_naming_the_variable():
    with pytest.raises(UnitError, match=r"Result\.final: w_shaft \[rad/s\]: 'N' is not a unit"):
        _result().final("w_shaft", "N")


@given(st.floats(-1e6, 1e6, allow_nan=False), st.floats(1.0, 1e4))
def test_converting_back_gives_the_si_value(w, kelvin):
    res = _result(w, kelvin)
    assert res.final("w_shaft", "rpm") * math.pi / 30 == pytest.approx(w, rel=1e-12,
                                                                          abs=1e-9)
    assert res.final("T_oil", "degC") + 273.15 == pytest.approx(kelvin, rel=1e-12)


def test_a_unit_for_a_dimensionless_variable_is_refused_in_words():
    """``final("Rs", "rpm")`` said "Rs [1]: 'rpm' is not a unit of - quantities (it is radian
    second^-1, '1' is dimensionless)"; a dimensionless variable is labelled [-] as everywhere
    else, and the message says dimensionless."""
    res = Result(np.array([0.0, 1.0]), ["Rs"], np.array([[0.2, 0.21]]), {"Rs": "1"})
    with pytest.raises(UnitError) as err:
        res.final("Rs", "rpm")
    assert str(err.value) == ("Result.final: Rs [-]: 'rpm' is not a unit of dimensionless "
                              "quantities (it is radian second^-1); give a pure number")
    assert res.final("Rs", "percent") == pytest.approx(21.0, rel=1e-12)
