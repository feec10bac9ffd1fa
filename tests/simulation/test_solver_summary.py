"""What a run says about its solver. A model without states integrates nothing: its run said
``solver: ?`` in ``bearingsim run``'s summary (``Result.stats`` had no ``method``), and a given
method was reported as if it had run (found by a new-user run of the shipped cylindrical
roller scene)."""

from __future__ import annotations

import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import deep_groove_ball_bearing
from bearingsim.scenes import load_scene, run_scene
from bearingsim.scenes.library import builtin_scene_path
from bearingsim.scenes.runner import console_lines
from bearingsim.simulation import simulate
from bearingsim.simulation.simulate import NO_STATES


@pytest.fixture(scope="module")
def quasi_static():
    system = assemble(deep_groove_ball_bearing("6304", fidelity="quasi-static"))
    assert system.n_states == 0
    return system


def test_a_model_without_states_names_no_method(quasi_static):
    res = simulate(quasi_static, 0.01, inputs={"load.Fx": 500.0}, n_points=3)
    assert res.stats["method"] == "none" and res.stats["method_reason"] == NO_STATES
    given = simulate(quasi_static, 0.01, inputs={"load.Fx": 500.0}, n_points=3, method="BDF")
    assert given.stats["method"] == "none"
    assert given.stats["method_reason"] == f"method='BDF' given; {NO_STATES}"
    assert given.values == pytest.approx(res.values, rel=1e-12)


def test_the_scene_summary_says_so(tmp_path):
    run = run_scene(load_scene(builtin_scene_path("cylindrical_roller_radial")),
                    out=tmp_path)
    assert run.summary["simulation"]["stats"]["method"] == "none"
    assert f"  solver: none ({NO_STATES})" in console_lines(run.summary)


def test_the_solver_line_gives_a_reason_once():
    """The motor drive's summary said the tiny-model reason twice: ``solver: cvodes (CVODES on
    CasADi's VM (tiny model ...)); evaluator CasADi VM (tiny model ...)``."""
    tiny = "tiny model (191 instructions): the VM costs less than compiling"
    summary = {"simulation": {"stats": {
        "method": "cvodes", "method_reason": f"CVODES on CasADi's VM ({tiny})",
        "backend": "CasADi VM", "backend_reason": tiny}}, "outputs": {}}
    assert console_lines(summary)[0] == (f"  solver: cvodes (CVODES on CasADi's VM ({tiny})); "
                                         "evaluator CasADi VM")
    summary["simulation"]["stats"]["method_reason"] = "method='cvodes' given"
    assert console_lines(summary)[0].endswith(f"; evaluator CasADi VM ({tiny})")
