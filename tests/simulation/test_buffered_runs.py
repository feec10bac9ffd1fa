"""What repeated runs on one system keep (integrator buffers, checked settings, output grids,
kernel look-ups) must not leak from one run into the next: runs that differ in parameters,
inputs or times give their own results, a repeated run gives the same numbers and counts bit
for bit, a failed run leaves nothing behind, threads do not share buffers, and a changed
``BEARINGSIM_CACHE`` still moves the kernel libraries.

Speed is measured in ``bench/per_call.py``, never asserted here.
"""

from __future__ import annotations

import threading

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.errors import BudgetExceededError, ParameterError
from bearingsim.simulation import simulate, steady_state
from bearingsim.simulation.inputs import input_signal
from bearingsim.simulation.sundials_integrators import clear_integrator_cache, normalized_grid

SPEED = {"shaft_speed": 100.0, "Fr": 200.0, "Fa": 50.0}
COUNTS = ("nsteps", "nfevals", "njevals", "nlinsetups", "nniters", "netfails")


@pytest.fixture(scope="module")
def system():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque"))


def _run(system, t_end=0.05, **kwargs):
    kwargs.setdefault("inputs", SPEED)
    kwargs.setdefault("method", "cvodes")
    return simulate(system, t_end, n_points=5, compiled=False, **kwargs)


def _in_threads(work, n: int) -> None:
    """Run ``work(k)`` for k = 0 .. n - 1, each in its own thread, all at once."""
    threads = [threading.Thread(target=work, args=(k,)) for k in range(n)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()


def _same(a, b):
    return (np.array_equal(a.t, b.t) and a.values.shape == b.values.shape
            and np.array_equal(a.values.view(np.int64), b.values.view(np.int64)))


@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_a_repeated_run_reports_the_counts_of_its_own_call(system, method):
    """The oracle's counters in a reused integrator memory add up over the calls; each run
    reports its own (the Jacobian count doubled on the second run when they were read as
    they are)."""
    first = _run(system, method=method)
    assert first.stats["njevals"] > 0
    for _ in range(2):
        again = _run(system, method=method)
        assert {k: again.stats[k] for k in COUNTS} == {k: first.stats[k] for k in COUNTS}
        assert _same(again, first)
        assert again.stats["rhs_time"] < 10 * first.stats["rhs_time"] + 0.05


def test_a_failed_run_leaves_the_next_runs_counts_and_numbers_alone(system):
    first = _run(system)
    with pytest.raises(BudgetExceededError):
        _run(system, max_steps=3)
    after = _run(system)
    assert {k: after.stats[k] for k in COUNTS} == {k: first.stats[k] for k in COUNTS}
    assert _same(after, first)


def test_runs_sharing_an_integrator_give_the_results_of_a_new_one(system):
    """Parameters, constant inputs and the time span are numbers of one kept integrator; each
    run's result is the one an integrator built for it alone gives."""
    runs = [dict(parameters={"inner_layer.omega_reg": 0.2}),
            dict(parameters={"inner_layer.omega_reg": 0.4}),
            dict(inputs={**SPEED, "Fr": 300.0}),
            dict(t_start=0.01, t_end=0.03),
            dict()]
    kept = [_run(system, **run) for run in runs]
    assert not any(_same(kept[0], other) for other in kept[1:])
    for run, result in zip(runs, kept, strict=True):
        clear_integrator_cache()
        alone = _run(system, **run)
        assert not alone.stats["integrator_cached"]
        assert _same(result, alone)


def test_a_result_changed_by_its_user_changes_no_later_result(system):
    first = _run(system)
    expected_t, expected = first.t.copy(), first.values.copy()
    first.t[:] = -1.0
    first.values[:] = -1.0
    later = _run(system)
    np.testing.assert_array_equal(later.t, expected_t)
    np.testing.assert_array_equal(later.values, expected)


def test_the_kept_output_grid_is_read_only_and_found_anew_for_other_times():
    t_out, tau, key = normalized_grid(0.0, 1.0, np.array([0.0, 0.5, 1.0]))
    assert key == ("linspace", 2) and tau.tolist() == [0.5, 1.0]
    with pytest.raises(ValueError):
        t_out[0] = 2.0
    assert normalized_grid(0.0, 1.0, np.array([0.0, 0.5, 1.0]))[0].tolist() == [0.5, 1.0]
    t_out, tau, key = normalized_grid(0.0, 1.0, np.array([0.0, 0.25, 1.0]))
    assert key[0] == "grid" and tau.tolist() == [0.25, 1.0]
    t_out, tau, key = normalized_grid(-0.0, 2.0, np.array([0.5, 2.0]))
    assert t_out.tolist() == [0.5, 2.0] and tau.tolist() == [0.25, 1.0]


@pytest.mark.parametrize("bad", [dict(rtol=True), dict(rtol=0.0), dict(t_start=0.05),
                                 dict(method="CVODE"), dict(initial="steady_state")])
def test_a_bad_setting_raises_every_time_after_good_runs(system, bad):
    _run(system)
    for _ in range(2):
        with pytest.raises(ParameterError):
            _run(system, **bad)
    _run(system)


def test_a_setting_of_another_type_is_checked_on_its_own(system):
    """1 and True are equal keys to a plain memory: the checked settings keep types apart."""
    _run(system, t_end=1.0, progress=False)
    with pytest.raises(ParameterError, match="progress"):
        _run(system, t_end=1.0, progress=1)


def test_threads_running_one_system_at_once_get_the_results_of_runs_alone(system):
    runs = [dict(parameters={"inner_layer.omega_reg": 0.1 * (k + 1)}) for k in range(4)]
    alone = [_run(system, **run) for run in runs]
    together: list = [None] * len(runs)
    start = threading.Barrier(len(runs))

    def work(k):
        start.wait()
        for _ in range(3):
            together[k] = _run(system, **runs[k])

    _in_threads(work, len(runs))
    for mine, theirs in zip(alone, together, strict=True):
        assert _same(mine, theirs)
        assert {k: mine.stats[k] for k in COUNTS} == {k: theirs.stats[k] for k in COUNTS}


def test_a_changed_cache_variable_moves_the_kernel_library(system, kernel_cache,
                                                           monkeypatch, tmp_path_factory):
    first = simulate(system, 0.01, inputs=SPEED, n_points=3, method="cvodes", compiled=True)
    assert first.stats["library"].startswith(str(kernel_cache))
    other = tmp_path_factory.mktemp("other_cache")
    monkeypatch.setenv("BEARINGSIM_CACHE", str(other))
    second = simulate(system, 0.01, inputs=SPEED, n_points=3, method="cvodes", compiled=True)
    assert second.stats["library"].startswith(str(other))
    assert _same(first, second)


# ---------------------------------------------------------------- input bounds, steady states


def _slow_check(system, signal, times, monkeypatch):
    """check_input_ranges input by input (the vectorised test switched off): its error or
    its warnings."""
    from bearingsim.simulation import input_ranges as input_ranges_module

    monkeypatch.setattr(input_ranges_module, "numbers_valid", lambda *signal: False)
    try:
        return _outcome(lambda: input_ranges_module._check_signal(system, signal, times))
    finally:
        monkeypatch.undo()


def _outcome(check):
    try:
        return ("notes", check())
    except ParameterError as exc:
        return ("error", str(exc))


@pytest.mark.parametrize("speed", [0.0, -7958.7013890941425, 7958.7013890941425, 7958.71,
                                   -8000.0, 3979.3506945470713, 3979.36, 100.0])
@pytest.mark.parametrize("load", [0.0, -0.0, -1e-300, 5.0, (np.array([0.0, 1.0, 2.0]),
                                                             np.array([0.0, 10.0, -1.0]))])
def test_the_vectorised_bounds_test_agrees_with_the_input_by_input_check(
        system, speed, load, monkeypatch):
    """Bounds inclusive, the limiting speed (a warning above it, not at it), a table value
    below its range; the vectorised test passes exactly the signals the input by input check
    passes without a word."""
    from bearingsim.simulation.input_ranges import _check_signal

    signal = input_signal(system, {"shaft_speed": speed, "Fr": load})
    times = np.array([0.0, 1.0])
    fast = _outcome(lambda: _check_signal(system, signal, times))
    assert fast == _slow_check(system, signal, times, monkeypatch)


def test_steady_states_of_threads_and_systems_at_once_are_those_solved_alone(system):
    other = assemble(double_layer_bearing("61905", "61908", fidelity="torque"))
    points = [(s, {"shaft_speed": w}) for s in (system, other) for w in (50.0, 300.0, 900.0)]
    alone = [steady_state(s, inputs=inputs) for s, inputs in points]
    together: list = [None] * len(points)
    start = threading.Barrier(len(points))

    def work(k):
        start.wait()
        for _ in range(5):
            s, inputs = points[k]
            together[k] = steady_state(s, inputs=inputs)

    _in_threads(work, len(points))
    for mine, theirs in zip(alone, together, strict=True):
        np.testing.assert_array_equal(mine, theirs)


def test_a_steady_state_keeps_the_guess_of_the_states_it_does_not_solve_for(system):
    """The angles have no steady value: each solve keeps its own guess for them, whatever
    the solve before it was given."""
    guess = system.x0()
    angles = [k for k, name in enumerate(system.state_names) if name.endswith("phi")]
    for value in (1.0, -2.5, 1.0):
        guess[angles] = value
        x = steady_state(system, inputs={"shaft_speed": 100.0}, x_guess=guess)
        assert x[angles].tolist() == [value] * len(angles)
        np.testing.assert_array_equal(
            np.delete(x, angles),
            np.delete(steady_state(system, inputs={"shaft_speed": 100.0}), angles))


def test_an_integrator_call_gives_the_keyword_calls_numbers_and_counts_per_call():
    import casadi as ca

    from bearingsim.simulation.integrator_calls import IntegratorCall

    x, p = ca.MX.sym("x"), ca.MX.sym("p")
    integrator = ca.integrator("decay", "cvodes", {"x": x, "p": p, "ode": -p * x}, 0.0,
                               [0.5, 1.0], {})
    call = IntegratorCall(integrator)
    xf = np.empty(2)
    with pytest.raises(ValueError, match="needs 2 contiguous numbers"):
        call(np.array([1.0]), np.array([2.0]), None, np.empty(3), None)
    expected = integrator(x0=1.0, p=2.0)
    counts = integrator.stats()
    for _ in range(3):
        call(np.array([1.0]), np.array([2.0]), None, xf, None)
        assert xf.tolist() == np.asarray(expected["xf"]).ravel().tolist()
        stats = call.stats()
        assert stats["nsteps"] == counts["nsteps"] > 0
        assert stats["n_call_daeF"] == counts["n_call_daeF"] > 0
    np.testing.assert_allclose(xf, np.exp([-1.0, -2.0]), rtol=1e-4)
