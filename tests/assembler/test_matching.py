"""The matching pass alone: each equation is paired with the unknown it determines; equations
that cannot all be paired raise an error naming them."""

from __future__ import annotations

import pytest

from bearingsim.assembler.passes import matching
from bearingsim.errors import SingularBlockError
from tests.assembler.hand_dae import dae, eq, state_of, state_var, var


def test_each_equation_is_matched_to_the_only_unknown_it_can_determine():
    x, dx = state_var("x", 1.0)
    y, z = var("y"), var("z")
    e_der, e_y, e_z = (eq(dx.sym + z.sym, "der(x) = -z"), eq(y.sym - x.sym**2, "y = x^2"),
                       eq(z.sym - y.sym * x.sym, "z = x y"))
    state = state_of(dae([x, dx, y, z], [e_der, e_y, e_z]))
    matching.run(state)
    assert state.matching == {e_der: dx, e_y: y, e_z: z}


def test_a_structurally_singular_system_names_the_unpaired_equation_and_unknown():
    x, dx = state_var("x", 1.0)
    y, z = var("y"), var("z")
    e_twice = eq(y.sym - 2 * x.sym, "y = 2 x again")
    model = dae([x, dx, y, z], [eq(dx.sym + y.sym, "der(x) = -y"), eq(y.sym - x.sym, "y = x"),
                                e_twice])
    with pytest.raises(SingularBlockError, match="cannot be paired") as err:
        matching.run(state_of(model))
    assert err.value.unknowns == ["z"]
    assert len(err.value.equations) == 1
    assert err.value.equations[0] in ("hand: y = x", "hand: y = 2 x again")
