"""Deep-groove bearing, ``dynamic`` level (docs/studies.md, section C): balls without radial
and axial inertia (quasi-static, as in the study) against balls with mass.

Balls in force balance turn the ball positions into a DAE that the assembler reduces: the
balances are solved for the balls' radial and axial velocities (the contacts' damping depends
on them) by Newton with a line search. Both levels must give the same cage slip and contact
loads, since the balls' radial/axial inertia (3.5 g) barely matters next to the contacts."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.studies.deep_groove import duty_condition

RUN = {"t_end": 0.03, "ramp": 0.01, "n_slices": 0, "n_points": 61}


@pytest.fixture(scope="module")
def condition_1():
    """Condition 1 (1730 r/min, 938 N, oil), both ball levels."""
    return {f: duty_condition(1, fidelity=f, **RUN)[0]
            for f in ("dynamic", "dynamic_massive_balls")}


@pytest.mark.slow
def test_quasi_static_balls_run_through_start_up_with_a_line_search(condition_1):
    res = condition_1["dynamic"]
    assert res.t[-1] == pytest.approx(RUN["t_end"])
    assert np.all(np.isfinite(res["slip"]))


@pytest.mark.slow
def test_quasi_static_and_massive_balls_give_the_same_slip_and_loads(condition_1):
    qs, massive = condition_1["dynamic"], condition_1["dynamic_massive_balls"]
    tail = qs.t > 0.015
    assert np.mean(qs["slip"][tail]) == pytest.approx(np.mean(massive["slip"][tail]), abs=2e-3)
    assert qs.final("w_cage") == pytest.approx(massive.final("w_cage"), rel=2e-3)
    q_qs = np.array([qs[f"inner[{j}].Q"][tail] for j in range(7)])
    q_massive = np.array([massive[f"inner[{j}].Q"][tail] for j in range(7)])
    assert q_qs.max() == pytest.approx(q_massive.max(), rel=0.01)
    np.testing.assert_allclose(q_qs.sum(axis=0), q_massive.sum(axis=0), rtol=0.01)


@pytest.mark.slow
def test_idas_on_the_dae_form_gives_the_cvodes_result(condition_1):
    """IDAS iterates on the balls' velocities itself (the semi-explicit DAE form) instead of a
    Newton solve inside every right-hand side."""
    res, _ = duty_condition(1, fidelity="dynamic", method="idas", **RUN)
    assert res.stats["algebraic_states"] == 14  # vr, vz of the 7 balls
    cvodes = condition_1["dynamic"]
    assert res.final("w_cage") == pytest.approx(cvodes.final("w_cage"), rel=1e-3)
    tail = res.t > 0.015
    assert np.mean(res["slip"][tail]) == pytest.approx(np.mean(cvodes["slip"][tail]), abs=1e-3)
