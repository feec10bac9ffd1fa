"""The roller ratings and lives have the NaN/overflow guard of every life function
(:func:`bearingsim.checks.guard_public_functions`): an overflow raises a named error instead of
returning inf, while an unloaded bearing's life stays infinite."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.errors import ParameterError
from bearingsim.physics.life import (
    roller_dynamic_load_rating,
    roller_reference_rating_life,
    roller_static_load_rating,
    slice_equivalent_load,
)


@pytest.mark.parametrize("call", [
    lambda: roller_dynamic_load_rating(0.008, 0.05, 12, 1e308),
    lambda: roller_dynamic_load_rating(0.008, 0.05, 12, 0.01, 1, 1e308),
    lambda: roller_static_load_rating(0.008, 0.05, 12, 1e308),
    lambda: slice_equivalent_load([1e308, 1.0, 2.0], True),
    lambda: roller_reference_rating_life([[100.0]] * 12, [[100.0]] * 12, 1e308, 0.2),
], ids=["dynamic-length", "dynamic-bm", "static-length", "slice-load", "life-c"])
def test_an_overflow_is_a_named_error_not_inf(call):
    with pytest.raises(ParameterError, match="not finite"):
        call()


@pytest.mark.parametrize("loads", [[[0.0, 0.0]] * 12, np.zeros((12, 2))], ids=["lists", "array"])
def test_an_unloaded_bearing_still_has_an_infinite_life(loads):
    assert roller_reference_rating_life(loads, loads, 3e4, 0.2) == math.inf


def test_a_loaded_bearing_has_the_same_life_from_lists_and_arrays():
    loads = [[100.0 * (12 - j), 50.0 * (12 - j)] for j in range(12)]
    from_lists = roller_reference_rating_life(loads, loads, 3e4, 0.2)
    assert math.isfinite(from_lists)
    assert roller_reference_rating_life(np.array(loads), np.array(loads), 3e4, 0.2) == \
        pytest.approx(from_lists, rel=1e-14)
