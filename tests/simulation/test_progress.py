"""Progress bars (issue 16 item 4, issue 27 item 3): a bar observes a run and never changes it.

With and without a bar, on a terminal or piped, every method gives the same numbers bit for
bit: CVODES and IDAS run in one integrator call either way (the bar is moved by a clock in the
oracle that returns exactly 0.0), compiled_bdf and scipy's methods observe their own steps.
Before issue 27 a run with a bar was cut into 20 CVODES calls and differed from the piped run
(``pocket[0].F`` -0.000248212 vs -0.000249371 N in ``deep_groove_duty1``): the
``assert_array_equal`` below fail on that code. ``bearingsim run`` shows the solver's bar on a
terminal only.
"""

from __future__ import annotations

import io

import casadi as ca
import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.scenes import parse_scene, run_scene
from bearingsim.simulation import simulate, sundials
from bearingsim.simulation.c_compiler import c_compiler
from bearingsim.simulation.progress import DELAY
from bearingsim.simulation.sundials_integrators import clear_integrator_cache
from tests.models import Pendulum

TOL = {"rtol": 1e-8, "atol": 1e-10}


class FakeBar:
    """Stands in for ``tqdm.tqdm``: records the bars made and their updates."""

    made: list[FakeBar] = []

    def __init__(self, total, delay, **kwargs):
        self.total, self.delay, self.n, self.updates, self.closed = total, delay, 0.0, 0, False
        FakeBar.made.append(self)

    def update(self, dt):
        assert dt >= 0.0
        self.n += dt
        self.updates += 1

    def close(self):
        self.closed = True


class Terminal(io.StringIO):
    """Standard error as a terminal."""

    def isatty(self):
        return True


@pytest.fixture()
def bars(monkeypatch):
    """The bars made during a test (``tqdm.tqdm`` replaced by :class:`FakeBar`)."""
    import tqdm

    FakeBar.made = []
    monkeypatch.setattr(tqdm, "tqdm", FakeBar)
    return FakeBar.made


@pytest.fixture()
def builds(monkeypatch):
    """Integrators built during a test (from an empty integrator cache)."""
    clear_integrator_cache()
    made, build = [], ca.integrator

    def counting(*args):
        made.append(args[4])  # the output grid
        return build(*args)

    monkeypatch.setattr(sundials.ca, "integrator", counting)
    yield made
    clear_integrator_cache()


@pytest.fixture(scope="module")
def pendulum():
    return assemble(Pendulum())  # IDAS integrates its semi-explicit DAE form


def _identical(a, b):
    """Same output times, values and step counts, bit for bit."""
    np.testing.assert_array_equal(a.t, b.t)
    np.testing.assert_array_equal(a.values, b.values)
    for count in ("nsteps", "nfevals", "njevals", "nfev"):
        assert a.stats.get(count) == b.stats.get(count)


@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_a_bar_moves_to_the_end_time_and_the_numbers_are_bit_identical(pendulum, method, bars,
                                                                       builds):
    single = simulate(pendulum, 2.0, method=method, compiled=False, progress=False, **TOL)
    assert len(builds) == 1 and not bars and not single.stats["progress_observed"]
    shown = simulate(pendulum, 2.0, method=method, compiled=False, progress=True, **TOL)
    (bar,) = bars
    assert bar.total == 2.0 and bar.delay == 0.0 and bar.closed
    assert bar.updates > 10  # moved during the run, not only at its end
    assert bar.n == pytest.approx(2.0, rel=1e-12)
    assert shown.stats["progress_observed"] and len(builds) == 2  # the observed integrator
    _identical(single, shown)
    simulate(pendulum, 3.0, t_start=1.0, method=method, compiled=False, progress=True, **TOL)
    assert len(builds) == 2  # another span, same grid: the cached observed integrator


@pytest.mark.parametrize("kwargs", [{"n_points": 4}, {"n_points": 38},
                                    {"t_eval": np.array([0.0, 0.05, 0.3, 0.31, 1.2, 2.0])}])
def test_any_output_grid_gives_the_same_numbers_with_a_bar(pendulum, kwargs, bars):
    single = simulate(pendulum, 2.0, method="cvodes", compiled=False, progress=False, **TOL,
                      **kwargs)
    shown = simulate(pendulum, 2.0, method="cvodes", compiled=False, progress=True, **TOL,
                     **kwargs)
    _identical(single, shown)
    assert bars[0].n == pytest.approx(2.0, rel=1e-12)


@pytest.mark.parametrize("method", ["BDF", "RK45"])
def test_scipy_methods_observe_their_steps(pendulum, method, bars):
    single = simulate(pendulum, 1.0, method=method, progress=False, **TOL)
    shown = simulate(pendulum, 1.0, method=method, progress=True, **TOL)
    _identical(single, shown)
    assert bars[0].n == pytest.approx(1.0, rel=1e-12)


def test_not_a_terminal_no_bar_on_a_terminal_a_delayed_bar_same_numbers(pendulum, bars,
                                                                         monkeypatch, capsys):
    quiet = simulate(pendulum, 1.0, method="cvodes", compiled=False, **TOL)
    assert not bars and capsys.readouterr().err == ""
    assert not quiet.stats["progress_observed"]
    monkeypatch.setattr("sys.stderr", Terminal())
    on_terminal = simulate(pendulum, 1.0, method="cvodes", compiled=False, **TOL)
    assert [b.delay for b in bars] == [DELAY]
    assert on_terminal.stats["progress_observed"]
    _identical(quiet, on_terminal)


def test_a_real_tqdm_bar_counts_simulated_seconds(pendulum, capsys):
    simulate(pendulum, 1.0, method="idas", compiled=False, progress=True, **TOL)
    assert "/1 s [" in capsys.readouterr().err  # bar_format: simulated seconds of 1 s


SCENE = """
title = "progress"
outputs = ["Rs"]
[assembly]
name = "double_layer_bearing"
[inputs]
shaft_speed = "rpm(1000) * ramp(0, 0.1)"
[simulation]
t_end = 0.2
method = "{method}"
n_points = 21
"""


@pytest.mark.parametrize("method", ["cvodes", "compiled_bdf"])
def test_a_scene_gives_the_same_numbers_piped_and_on_a_terminal(tmp_path, bars, capsys,
                                                                monkeypatch, method):
    if method == "compiled_bdf" and c_compiler() is None:
        pytest.skip("compiled_bdf needs a C compiler")
    scene = parse_scene(SCENE.format(method=method))
    piped = run_scene(scene, tmp_path / "a")  # not a terminal
    assert not bars and capsys.readouterr().err == ""
    shown = run_scene(scene, tmp_path / "b", progress=True)
    (bar,) = bars
    t = shown.result.t
    assert bar.closed and bar.n == pytest.approx(t[-1] - t[0], rel=1e-12)
    monkeypatch.setattr("sys.stderr", Terminal())
    terminal = run_scene(scene, tmp_path / "c")
    for run in (shown, terminal):
        _identical(piped.result, run.result)
        for name, series in piped.series.items():
            np.testing.assert_array_equal(series, run.series[name])
