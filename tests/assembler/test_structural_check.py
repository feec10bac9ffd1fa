"""The structural check alone: a balanced DAE passes; an over- or under-determined one raises an
error naming the extra equation or the free unknowns."""

from __future__ import annotations

import pytest

from bearingsim.assembler.passes import structural_check
from bearingsim.errors import OverdeterminedError, UnderdeterminedError
from tests.assembler.hand_dae import dae, eq, state_of, state_var, var


def test_a_balanced_dae_passes():
    x, dx = state_var("x", 1.0)
    y = var("y")
    structural_check.run(state_of(dae([x, dx, y], [eq(dx.sym + y.sym, "der(x) = -y"),
                                                    eq(y.sym - 2 * x.sym, "y = 2 x")])))


def test_the_over_determined_dae_names_the_extra_equation():
    x, dx = state_var("x", 1.0)
    extra = eq(x.sym - 2.0, "x = 2")
    model = dae([x, dx], [eq(dx.sym + x.sym, "der(x) = -x"), extra])
    with pytest.raises(OverdeterminedError, match="2 equations for 1 unknowns") as err:
        structural_check.run(state_of(model))
    assert err.value.equations == ["hand: x = 2"] == [extra.describe()]
    assert err.value.unknowns == []  # the state x is known: nothing is left for this equation


def test_the_under_determined_dae_names_the_free_unknown():
    x, dx = state_var("x", 1.0)
    force, gap = var("force"), var("gap")
    model = dae([x, dx, force, gap], [eq(dx.sym - force.sym, "der(x) = force"),
                                       eq(force.sym - 3 * x.sym, "force = 3 x")])
    with pytest.raises(UnderdeterminedError, match="2 equations for 3 unknowns") as err:
        structural_check.run(state_of(model))
    assert err.value.unknowns == ["gap"]
