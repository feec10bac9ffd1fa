"""The pruning pass alone: two independent subsystems; an output of one keeps only that one.

    der(x1) = -x1,  y1 = 2 x1          der(x2) = -x2,  y2 = x2^2

with ``w1 = y1`` and ``w2 = -x2`` already eliminated as aliases.
"""

from __future__ import annotations

import pytest

from bearingsim.assembler.dae import Alias
from bearingsim.assembler.passes import pruning
from bearingsim.errors import ModelError
from tests.assembler.hand_dae import dae, eq, state_of, state_var, var


def _two_subsystems():
    x1, dx1 = state_var("x1", 1.0)
    x2, dx2 = state_var("x2", 2.0)
    y1, y2 = var("y1"), var("y2")
    eqs = [eq(dx1.sym + x1.sym, "der(x1) = -x1"), eq(y1.sym - 2 * x1.sym, "y1 = 2 x1"),
           eq(dx2.sym + x2.sym, "der(x2) = -x2"), eq(y2.sym - x2.sym**2, "y2 = x2^2")]
    model = dae([x1, dx1, x2, dx2, y1, y2], eqs)
    model.aliases = {"w1": Alias("w1", 1.0, y1, 0.0), "w2": Alias("w2", -1.0, x2, 0.0),
                     "k": Alias("k", 0.0, None, 4.0)}
    matched = dict(zip(eqs, [dx1, y1, dx2, y2], strict=True))
    return model, matched


@pytest.mark.parametrize("output", ["y1", "w1"])
def test_an_output_keeps_only_the_equations_and_states_it_depends_on(output):
    model, matched = _two_subsystems()
    state = state_of(model, [output], matching=matched)
    pruning.run(state)
    assert [v.name for v in model.vars] == ["x1", "der(x1)", "y1"]
    assert [e.text for e in model.eqs] == ["der(x1) = -x1", "y1 = 2 x1"]
    assert [e.text for e in state.matching] == ["der(x1) = -x1", "y1 = 2 x1"]
    assert sorted(model.aliases) == ["k", "w1"]  # w2 followed x2 out; constants stay
    assert model.skipped == ["1 state(s) not needed: x2",
                             "2 equation(s) not needed by the requested outputs"]
    model.check_balance("pruning")


def test_without_outputs_nothing_is_pruned():
    model, matched = _two_subsystems()
    pruning.run(state_of(model, None, matching=matched))
    assert len(model.vars) == 6 and len(model.eqs) == 4 and model.skipped == []


def test_an_unknown_output_name_is_refused_with_a_suggestion():
    model, matched = _two_subsystems()
    with pytest.raises(ModelError, match=r"unknown output variable 'y1x' \(did you mean y1\?\)"):
        pruning.run(state_of(model, ["y1x"], matching=matched))


def test_every_unknown_output_name_is_named_at_once():
    """Two misspelt outputs were refused one at a time (fix one, run again, meet the next)."""
    model, matched = _two_subsystems()
    with pytest.raises(ModelError, match=r"^unknown output variable 'y1x' \(did you mean y1\?\); "
                                         r"unknown output variable 'qqq'$"):
        pruning.run(state_of(model, ["y1x", "y1", "qqq"], matching=matched))
