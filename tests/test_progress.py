"""Progress bars (issue 16 item 4): CVODES and IDAS in chunks with a bar, one call without;
``bearingsim run`` shows the solver's bar on a terminal only."""

from __future__ import annotations

import io

import casadi as ca
import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.scenes import parse_scene, run_scene
from bearingsim.simulation import simulate, sundials
from bearingsim.simulation.progress import DELAY
from bearingsim.simulation.sundials import PROGRESS_CHUNKS, clear_integrator_cache
from tests.models import Pendulum

TOL = {"rtol": 1e-8, "atol": 1e-10}


class FakeBar:
    """Stands in for ``tqdm.tqdm``: records the bars made and their updates."""

    made: list[FakeBar] = []

    def __init__(self, total, delay, **kwargs):
        self.total, self.delay, self.n, self.updates, self.closed = total, delay, 0.0, 0, False
        FakeBar.made.append(self)

    def update(self, dt):
        self.n += dt
        self.updates += 1

    def close(self):
        self.closed = True


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


def _agree(a, b, tol=1e-5):
    """Same output times; values equal within ``tol`` of each variable's range."""
    np.testing.assert_array_equal(a.t, b.t)
    scale = np.ptp(a.values, axis=1)[:, None] + 1e-12
    assert np.max(np.abs(a.values - b.values) / scale) < tol


@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_a_bar_moves_chunk_by_chunk_to_the_end_time_with_the_same_values(pendulum, method,
                                                                          bars, builds):
    single = simulate(pendulum, 2.0, method=method, compiled=False, progress=False, **TOL)
    assert single.stats["chunks"] == 1 and len(builds) == 1 and not bars
    shown = simulate(pendulum, 2.0, method=method, compiled=False, progress=True, **TOL)
    (bar,) = bars
    assert bar.total == 2.0 and bar.delay == 0.0 and bar.closed
    assert bar.updates == shown.stats["chunks"] == PROGRESS_CHUNKS
    assert bar.n == pytest.approx(2.0, rel=1e-12)
    assert len(builds) == 2  # 500 output intervals, 20 calls of 25: one more integrator
    assert shown.stats["nsteps"] >= single.stats["nsteps"]  # counts summed over the calls
    _agree(single, shown)
    simulate(pendulum, 3.0, t_start=1.0, method=method, compiled=False, progress=True, **TOL)
    assert len(builds) == 2  # another span with equal chunks: the cached chunk integrator


@pytest.mark.parametrize("kwargs", [{"n_points": 4}, {"n_points": 38},
                                    {"t_eval": np.array([0.0, 0.05, 0.3, 0.31, 1.2, 2.0])}])
def test_chunks_of_any_output_grid_return_the_same_times_and_values(pendulum, kwargs, bars,
                                                                     builds):
    single = simulate(pendulum, 2.0, method="cvodes", compiled=False, progress=False, **TOL,
                      **kwargs)
    shown = simulate(pendulum, 2.0, method="cvodes", compiled=False, progress=True, **TOL,
                     **kwargs)
    _agree(single, shown)
    assert bars[0].n == pytest.approx(2.0, rel=1e-12)
    if "n_points" in kwargs:  # equal intervals: calls of m or m + 1 intervals
        assert len(builds) <= 3


def test_not_a_terminal_no_bar_and_one_call_on_a_terminal_a_delayed_bar(pendulum, bars,
                                                                         monkeypatch, capsys):
    quiet = simulate(pendulum, 1.0, method="cvodes", compiled=False, **TOL)
    assert quiet.stats["chunks"] == 1 and not bars and capsys.readouterr().err == ""

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    monkeypatch.setattr("sys.stderr", Terminal())
    monkeypatch.setattr(sundials, "DELAY", 1e9)  # every run short: no bar would appear
    short = simulate(pendulum, 1.0, method="cvodes", compiled=False, **TOL)
    assert [b.delay for b in bars] == [DELAY]
    # the first of 20 calls says the run is short: the rest in one call
    assert short.stats["chunks"] == 2 and bars[0].n == pytest.approx(1.0, rel=1e-12)
    _agree(quiet, short)
    monkeypatch.setattr(sundials, "DELAY", 0.0)  # every run long
    long = simulate(pendulum, 1.0, method="cvodes", compiled=False, **TOL)
    assert long.stats["chunks"] == PROGRESS_CHUNKS
    _agree(quiet, long)


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
method = "cvodes"
n_points = 21
"""


def test_a_scene_run_shows_the_solvers_bar_only_when_asked(tmp_path, bars, capsys):
    scene = parse_scene(SCENE)
    run_scene(scene, tmp_path / "a")  # not a terminal
    assert not bars and capsys.readouterr().err == ""
    run = run_scene(scene, tmp_path / "b", progress=True)
    (bar,) = bars
    t = run.result.t
    assert bar.closed and bar.n == pytest.approx(t[-1] - t[0], rel=1e-12)
    assert run.result.stats["chunks"] == PROGRESS_CHUNKS

