"""SUNDIALS on a model whose rate is structurally zero: a free flywheel pruned to its speed has
``der(w) = 0`` with no nonzero, which CVODES refused ("DAE outputs must be dense") when the
method was CVODES (the default for such a model) — the flywheel example of the architecture
page failed this way."""

from __future__ import annotations

import pytest

from bearingsim.assembler import assemble
from bearingsim.components.rotational import Inertia
from bearingsim.simulation import simulate


@pytest.mark.parametrize("method", ["cvodes", None])
def test_a_free_flywheel_keeps_its_speed(method):
    system = assemble(Inertia(J=0.05, w0=100.0, name="flywheel"), outputs=["w"])
    result = simulate(system, 1.0, method=method)
    assert result.stats["method"] == "cvodes"
    assert result["w"][-1] == pytest.approx(100.0, rel=1e-12)
