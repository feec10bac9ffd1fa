"""The curves of an analysis or sweep figure (found by a new-user trial of the sweep figures):
a sweep over load x speed drew every point as one line against speed, zig-zagging between the
loads; a grid given out of order zig-zagged along its own axis; a life (L10h, spanning decades)
sat on a linear axis; a sampled sweep drew a legend entry per point."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.scenes import parse_scene, prepare
from bearingsim.scenes.library import builtin_scene_path
from bearingsim.scenes.plots import MAX_CURVES, characteristic_figures
from bearingsim.scenes.sweep_results import sweep_figures

UNITS = {"shaft_speed": "rad/s", "Fr": "N", "Rs": "1", "inner_layer.L10h": "h"}


@pytest.fixture(scope="module")
def prep():
    return prepare(parse_scene(builtin_scene_path("double_layer_friction").read_text(
        encoding="utf-8")))


def _rows(speeds, loads):
    return [{"shaft_speed": w, "Fr": f, "Rs": 1e-3 * w / (1 + f),
             "inner_layer.L10h": 1e12 / (w * (1 + f) ** 3), "status": "ok"}
            for f in loads for w in speeds]


def _lines(fig):
    return [[line for line in ax.get_lines() if len(line.get_xdata())] for ax in fig.axes]


def test_one_curve_per_other_key_in_order_along_the_axis(prep):
    speeds = [300.0, 100.0, 200.0]  # out of order, as a user's grid may be
    [(_, fig)] = characteristic_figures(prep, _rows(speeds, [10.0, 100.0]), ["shaft_speed", "Fr"],
                                        UNITS, ["Rs", "inner_layer.L10h"], "steady")
    rs_lines, life_lines = _lines(fig)
    assert len(rs_lines) == 2 and len(life_lines) == 2  # one per load
    for line in rs_lines + life_lines:
        x = np.asarray(line.get_xdata(), dtype=float)
        assert np.all(np.diff(x) > 0) and line.get_linestyle() != "None"
    assert fig.axes[0].get_yscale() == "linear" and fig.axes[1].get_yscale() == "log"
    assert fig.axes[0].get_legend() is not None


def test_a_sampled_sweep_is_drawn_as_markers_without_a_legend(prep):
    rng = np.random.default_rng(1)
    rows = _rows([], [])
    for w, f in zip(rng.uniform(100, 1000, 20), rng.uniform(0, 500, 20), strict=True):
        rows += _rows([float(w)], [float(f)])
    assert len(rows) > MAX_CURVES
    [(_, fig)] = characteristic_figures(prep, rows, ["shaft_speed", "Fr"], UNITS, ["Rs"],
                                        "steady")
    panel, bar = fig.axes  # the markers and their colour bar
    [markers] = panel.collections
    x = markers.get_offsets()[:, 0]
    assert len(x) == 20 and np.all(np.diff(x) > 0) and not _lines(fig)[0]
    assert panel.get_legend() is None
    # coloured by the load in kN, as every force is shown (a sample showed nothing of its
    # second key before)
    loads = sorted((row["shaft_speed"], row["Fr"]) for row in rows)
    assert np.allclose(markers.get_array(), [1e-3 * f for _, f in loads])
    assert bar.get_ylabel().endswith("[kN]")
    assert "20 points, coloured by Fr)" in fig.texts[0].get_text()


def test_a_transient_sweep_draws_the_same_curves(prep):
    """The transient sweep figure had its own code: all points of a load x speed grid in one
    line sorted by speed."""
    rows = _rows([100.0, 200.0, 300.0], [10.0, 100.0])
    [(name, fig)] = sweep_figures(prep, rows, ["shaft_speed", "Fr"], ["Rs", "inner_layer.L10h"],
                                  UNITS, "sweep")
    assert name == "sweep.png"
    rs_lines, life_lines = _lines(fig)
    assert len(rs_lines) == 2 and fig.axes[1].get_yscale() == "log"


def test_a_long_legend_stands_beside_the_curves_on_the_figure(prep):
    """The duplex modes figure (5 modes and 2 speeds: 7 entries) put its legend over the
    axial mode's curve; a legend of more than 4 entries now stands right of the axes, and
    still on the figure."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    modes = ["radial x", "radial y", "axial", "tilt about x", "tilt about y"]
    rows = [{"shaft_speed": w, "Fr": f, **{m: (k + 1) * 100.0 + f for k, m in enumerate(modes)}}
            for f in (0.0, 50.0) for w in (100.0, 200.0, 300.0)]
    [(_, fig)] = characteristic_figures(prep, rows, ["shaft_speed", "Fr"],
                                        {**UNITS, **dict.fromkeys(modes, "Hz")}, modes, "modes")
    FigureCanvasAgg(fig).draw()
    renderer = fig.canvas.get_renderer()
    [ax] = fig.axes
    legend = ax.get_legend().get_window_extent(renderer)
    assert len(ax.get_legend().get_texts()) == 7
    assert legend.x0 >= ax.get_window_extent(renderer).x1  # beside the curves
    assert legend.x1 <= fig.bbox.width  # on the figure


def test_one_legend_for_the_panels_and_no_key_every_point_sets_alike(prep):
    """A sweep over load x speed with ``simulation.t_end`` in every point (the same value)
    drew the same 8-entry legend beside each of its 4 panels, every entry ending in
    ``simulation.t_end = 0.002``, and named t_end in the title as if it varied (found in the
    sweep benchmark's figure; drawing the 32 legend entries took most of the sweep's write
    time)."""
    rows = [{**row, "simulation.t_end": 0.002} for row in _rows([100.0, 200.0], [10.0, 100.0])]
    [(_, fig)] = characteristic_figures(prep, rows, ["shaft_speed", "Fr", "simulation.t_end"],
                                        UNITS, ["Rs", "inner_layer.L10h"], "steady")
    first, second = fig.axes
    labels = [t.get_text() for t in first.get_legend().get_texts()]
    assert len(labels) == 2 and all("Fr = " in label for label in labels)
    assert not any("t_end" in label for label in labels)
    assert second.get_legend() is None
    assert len(_lines(fig)[1]) == 2  # the second panel still draws a curve per load
    assert "one curve per Fr\n" in fig.texts[0].get_text() + "\n"


def test_a_sweep_over_speed_expressions_is_drawn_against_the_speed_the_runs_end_at(prep):
    """A sweep over ``rpm(N) * ramp(0, 0.5)`` with ``simulation.t_end`` one value drew every
    point at t_end, on an axis labelled ``simulation.t_end [-]``, one single-point curve per
    expression: the axis is now the speed at the end of each run (a key that varies before
    one that does not), in r/min."""
    speeds = (1000, 2000, 4000)
    rows = [{"inputs.shaft_speed": f"rpm({n}) * ramp(0, 0.5)", "simulation.t_end": 0.25,
             "Rs": 1e-6 * n, "status": "ok"} for n in speeds]
    [(_, fig)] = sweep_figures(prep, rows, ["inputs.shaft_speed", "simulation.t_end"], ["Rs"],
                               {"inputs.shaft_speed": "rad/s", "simulation.t_end": "s",
                                "Rs": "1"}, "sweep")
    [ax] = fig.axes
    [line] = _lines(fig)[0]
    np.testing.assert_allclose(line.get_xdata(), [n * 0.5 for n in speeds])  # r/min
    assert ax.get_xlabel() == "imposed shaft speed at t_end [r/min]"  # the input's words
    assert ax.get_legend() is None


def test_a_numeric_key_that_varies_is_the_axis_before_one_that_does_not(prep):
    rows = [{**row, "simulation.t_end": 0.002} for row in _rows([100.0, 200.0], [10.0, 100.0])]
    [(_, fig)] = sweep_figures(prep, rows, ["simulation.t_end", "shaft_speed", "Fr"], ["Rs"],
                               {**UNITS, "simulation.t_end": "s"}, "sweep")
    assert fig.axes[0].get_xlabel() == "imposed shaft speed [r/min]"


def test_values_not_settled_at_t_end_are_drawn_hollow(prep):
    """A transient sweep's table flags a point whose output had not settled by t_end
    (``settled`` False, the output named in ``unsettled``); its figure drew that value as
    every other. Now hollow, on the panels of the outputs that had not settled, and the title
    says so."""
    rows = _rows([100.0, 200.0, 300.0], [10.0])
    rows[2]["unsettled"] = "Rs"
    [(_, fig)] = sweep_figures(prep, rows, ["shaft_speed", "Fr"], ["Rs", "inner_layer.L10h"],
                               UNITS, "sweep")
    rs_panel, life_panel = fig.axes
    [hollow] = rs_panel.collections
    assert hollow.get_offsets().shape == (1, 2)
    assert np.allclose(hollow.get_facecolor()[0], [1, 1, 1, 1])  # white inside
    assert not life_panel.collections
    assert "hollow markers: not settled at t_end" in fig.texts[0].get_text()
    [(_, settled)] = sweep_figures(prep, _rows([100.0, 200.0, 300.0], [10.0]),
                                   ["shaft_speed", "Fr"], ["Rs"], UNITS, "sweep")
    assert "hollow" not in settled.texts[0].get_text()


def test_a_sampled_modes_sweep_names_its_modes_and_its_keys():
    """A new-user trial: ``bearingsim sweep duplex_modes --sample assembly.preload_force=...
    --sample assembly.speed=...`` drew the five modes in five colours with no legend (a
    sample's markers had none, and the modes' names were in it), its axis and title said
    ``assembly.preload_force`` where the scene's own figure says "axial preload", and the
    title read "assembly.speed vary too". A sweep's legend and title name its keys as an
    analysis scene's figures do: ``Fr = 0.5 kN``, not ``inputs.Fr = 0.5 kN``."""
    modes = prepare(parse_scene(builtin_scene_path("duplex_modes").read_text(encoding="utf-8")))
    names = ["radial x", "radial y", "axial", "tilt about x", "tilt about y"]
    rng = np.random.default_rng(2)
    rows = [{"assembly.preload_force": float(f), "assembly.speed": float(w), "status": "ok",
             **{n: 300.0 + 100.0 * k + 1e-3 * f for k, n in enumerate(names)}}
            for f, w in zip(rng.uniform(500, 3000, 16), rng.uniform(0, 600, 16), strict=True)]
    units = {"assembly.preload_force": "N", "assembly.speed": "rad/s", **dict.fromkeys(names,
                                                                                  "Hz")}
    [(_, fig)] = characteristic_figures(modes, rows, ["assembly.preload_force",
                                                      "assembly.speed"], units, names, "modes")
    legend = fig.axes[0].get_legend()
    assert legend is not None and [t.get_text() for t in legend.get_texts()] == names
    rows = [{"inputs.shaft_speed": w, "inputs.Fr": f, "Rs": 1e-3 * w / (1 + f), "status": "ok"}
            for f in (0.0, 500.0) for w in (100.0, 200.0)]
    [(_, curves)] = characteristic_figures(
        modes, rows, ["inputs.shaft_speed", "inputs.Fr"],
        {"inputs.shaft_speed": "rad/s", "inputs.Fr": "N", "Rs": "1"}, ["Rs"], "steady")
    assert [t.get_text() for t in curves.axes[0].get_legend().get_texts()] == [
        "Fr = 0 kN", "Fr = 0.5 kN"]
    assert "one curve per Fr" in curves._suptitle.get_text()
    assert fig.axes[0].get_xlabel() == "axial preload [kN]"
    title = fig.texts[0].get_text() if fig.texts else fig._suptitle.get_text()
    assert "against axial preload (16 points; speed varies too)" in title


def test_a_statics_sweep_draws_the_statics_columns_with_the_iso_76_limit():
    """A statics sweep drew every column of its table (displacements, stiffness, moments: a
    roller bearing's eight panels, three of them flat at 0) and no ISO 76 limit; it draws the
    columns a statics scene draws, the pressure with its assembly's limit (4000 MPa for
    roller bearings)."""
    prep = prepare(parse_scene('analysis = "statics"\n[assembly]\n'
                               'name = "cylindrical_roller_bearing"\nfidelity = "quasi-static"\n'
                               '[inputs]\n"load.Fx" = 2000.0\n'))
    columns = ["Q_max", "p_max", "x", "y", "k_radial", "Mx", "My", "L10r", "L10h"]
    units = {"load.Fx": "N", "Q_max": "N", "p_max": "Pa", "x": "m", "y": "m", "k_radial": "N/m",
             "Mx": "N.m", "My": "N.m", "L10r": "Mrev", "L10h": "h"}
    rows = [{"load.Fx": f, "status": "ok", "Q_max": 0.5 * f, "p_max": 1e9 + 1e5 * f,
             "x": 1e-8 * f, "y": 0.0, "k_radial": 4e8, "Mx": 0.0, "My": 0.0,
             "L10r": 1e12 / f ** 3, "L10h": "not defined at zero speed"}
            for f in (2000.0, 8000.0, 20000.0)]
    [(_, fig)] = sweep_figures(prep, rows, ["load.Fx"], columns, units, "sweep")
    assert len(fig.axes) == 3  # L10r (at rest), Q_max, p_max
    limit = [line for line in fig.axes[2].get_lines() if len(line.get_xdata()) == 2]
    assert [line.get_ydata()[0] for line in limit] == [pytest.approx(4000.0)]
