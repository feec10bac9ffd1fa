"""The cheap paths of the per-call work agree with the full ones: ``check_range``'s test for
plain numbers accepts exactly what its numpy path accepts, and ``entry_point``'s binding test
says yes exactly when ``inspect.Signature.bind`` binds; a scene expression is evaluated once
per text, any other function of time on every run."""

from __future__ import annotations

import inspect

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.entry_points import _binding_rule
from bearingsim.errors import ParameterError
from bearingsim.validation import _plain_in_range, check_count, check_range

NUMBERS = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                    st.integers(min_value=-(10**400), max_value=10**400), st.booleans())
BOUNDS = st.one_of(st.none(), st.floats(-1e6, 1e6), st.integers(-1000, 1000))


def _numpy_accepts(value, low, high, low_inclusive, high_inclusive) -> bool:
    """check_range's rule on its numpy path."""
    if isinstance(value, bool):
        return False
    try:
        arr = np.asarray(value, dtype=float)
    except OverflowError:
        return False
    if not np.isfinite(arr):
        return False
    lo = low is None or (arr >= low if low_inclusive else arr > low)
    hi = high is None or (arr <= high if high_inclusive else arr < high)
    return bool(lo and hi)


@settings(max_examples=400, deadline=None)
@given(NUMBERS, BOUNDS, BOUNDS, st.booleans(), st.booleans())
def test_the_plain_number_path_accepts_only_what_the_numpy_path_accepts(
        value, low, high, low_inclusive, high_inclusive):
    fast = _plain_in_range(value, low, high, low_inclusive, high_inclusive)
    if fast:
        assert _numpy_accepts(value, low, high, low_inclusive, high_inclusive)
    elif type(value) in (float, int) and abs(value) <= 2**53:  # a plain number it refused
        assert not _numpy_accepts(value, low, high, low_inclusive, high_inclusive)
    accepted = _numpy_accepts(value, low, high, low_inclusive, high_inclusive)
    try:
        assert check_range(value, "x", "s", low, high, low_inclusive=low_inclusive,
                           high_inclusive=high_inclusive, where="f") is value
        assert accepted
    except ParameterError:
        assert not accepted


@pytest.mark.parametrize("value", [0, -1, 10**400, True, 2.5, float("nan")])
def test_check_count_refuses_what_it_refused(value):
    with pytest.raises(ParameterError, match="n"):
        check_count(value, "n", 1, "f")


@pytest.mark.parametrize("value", [1, 7, 2**53, 2**60, 2.0, np.int64(3)])
def test_check_count_accepts_counts(value):
    assert check_count(value, "n", 1, "f") is value


def _plain(a, b=1, *, c, d=2):
    return a, b, c, d


def _method_like(self, x, y=0):
    return x, y


@settings(max_examples=300, deadline=None)
@given(st.lists(st.integers(), max_size=4),
       st.dictionaries(st.sampled_from(["a", "b", "c", "d", "e", "self", "x", "y"]),
                       st.integers(), max_size=4),
       st.sampled_from([_plain, _method_like]))
def test_the_binding_test_agrees_with_signature_bind(args, kwargs, func):
    signature = inspect.signature(func)
    binds = _binding_rule(signature)
    try:
        signature.bind(*args, **kwargs)
        bound = True
    except TypeError:
        bound = False
    assert binds(tuple(args), kwargs) == bound


def test_signatures_with_star_arguments_keep_signature_bind():
    def star(a, *rest, **named):
        return a

    def positional_only(a, /, b):
        return a

    assert _binding_rule(inspect.signature(star)) is None
    assert _binding_rule(inspect.signature(positional_only)) is None


def test_a_function_of_time_is_evaluated_per_run_a_scene_expression_once_per_text():
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.scenes.expressions import compile_expression
    from bearingsim.simulation import simulate

    system = assemble(double_layer_bearing("61905", "61907", fidelity="torque"))
    gain = [300.0]

    def speed(t):  # reads a value that changes between the runs
        return gain[0] + 0 * t

    first = simulate(system, 0.01, inputs={"shaft_speed": speed}, n_points=3)
    gain[0] = 400.0
    second = simulate(system, 0.01, inputs={"shaft_speed": speed}, n_points=3)
    assert (first.inputs["shaft_speed"], second.inputs["shaft_speed"]) == (300.0, 400.0)

    expression = compile_expression("311.25 + 0 * t")
    calls = []

    def counted(t):
        calls.append(t)
        return expression(t)

    counted.expression = expression.expression
    runs = [simulate(system, 0.01, inputs={"shaft_speed": counted}, n_points=3)
            for _ in range(3)]
    assert len(calls) == 1
    assert [run.inputs["shaft_speed"] for run in runs] == [311.25] * 3
