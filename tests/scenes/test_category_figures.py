"""Figures of points that differ by text (a lubricant comparison, the product's own question:
"swap lubrication without rewriting anything"). Before, a steady scene whose grid or cases set
``assembly.lubrication`` ran, then its figure failed ("could not convert string to float:
'ISO VG 32'"; the command exited 1), and a sweep over lubricants wrote no figure and said
nothing. Such points are now bars, one per point; with a number that varies besides (a
speed), the number is the axis and each lubricant a curve."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.scenes import parse_scene, run_scene
from bearingsim.scenes.analysis_figures import analysis_figures
from bearingsim.scenes.analysis_table import analysis_units
from bearingsim.scenes.sweep import run_sweep

SCENE = """
title = "oils"
analysis = "{analysis}"
{outputs}
[assembly]
name = "double_layer_bearing"
fidelity = "torque"
{points}
[inputs]
{inputs}
Fr = "500 N"
Fa = 50.0
"""
OILS = ["ISO VG 32", "ISO VG 68", "lithium grease"]


def _scene(points: str, analysis: str = "steady", speed: bool = True):
    return parse_scene(SCENE.format(
        analysis=analysis, points=points, inputs='shaft_speed = "6000 rpm"' if speed else "",
        outputs='outputs = ["Rs", "M_shaft"]' if analysis == "steady" else ""))


def _figures(run):
    return analysis_figures(run.prepared, run.rows, run.summary["keys"],
                            analysis_units(run.prepared, run.rows))


def _bars(ax):
    return [p.get_height() for p in ax.patches]


def test_a_grid_of_lubricants_is_drawn_as_bars_of_the_table_values():
    run = run_scene(_scene(f'[grid]\n"assembly.lubrication" = {OILS!r}'.replace("'", '"')),
                    write=False)
    [(name, fig)] = _figures(run)
    assert name == "steady" and len(fig.axes) == 2
    rs, torque = fig.axes
    assert _bars(rs) == pytest.approx([row["Rs"] for row in run.rows], rel=1e-12)
    # the friction torque in N mm, as every figure shows it
    assert _bars(torque) == pytest.approx([1e3 * row["M_shaft"] for row in run.rows],
                                          rel=1e-12)
    assert [t.get_text() for t in torque.get_xticklabels()] == OILS
    assert torque.get_xlabel() == "lubrication" and "[N mm]" in torque.get_ylabel()
    assert len({round(h, 6) for h in _bars(torque)}) == 3  # the oils differ
    assert "per lubrication" in fig.texts[0].get_text()


def test_named_cases_are_the_bars_names():
    cases = "".join(f'[[cases]]\nname = "oil {k}"\n"assembly.lubrication" = "{oil}"\n'
                    for k, oil in enumerate(OILS[:2]))
    run = run_scene(_scene(cases), write=False)
    [(_, fig)] = _figures(run)
    assert [t.get_text() for t in fig.axes[-1].get_xticklabels()] == ["oil 0", "oil 1"]
    assert fig.axes[-1].get_xlabel() == "case"


def test_with_a_speed_besides_the_speed_is_the_axis_and_each_oil_a_curve():
    grid = ('[grid]\n"assembly.lubrication" = ["ISO VG 32", "ISO VG 68"]\n'
            '"inputs.shaft_speed" = ["3000 rpm", "6000 rpm", "9000 rpm"]')
    run = run_scene(_scene(grid, speed=False), write=False)
    assert run.summary["keys"] == ["lubrication", "shaft_speed"]  # lubrication first
    [(_, fig)] = _figures(run)
    lines = [line for line in fig.axes[0].get_lines() if len(line.get_xdata())]
    assert len(lines) == 2
    for line in lines:
        np.testing.assert_allclose(line.get_xdata(), [3000.0, 6000.0, 9000.0], rtol=1e-9)
    assert "r/min" in fig.axes[-1].get_xlabel()


def test_a_sweep_over_lubricants_draws_its_bars(client, tmp_path):
    scene = _scene("")
    res = run_sweep(scene, [{"assembly.lubrication": oil} for oil in OILS], client=client,
                    out=tmp_path, progress=False)
    assert len(res.ok) == 3 and res.plot_failures == []
    [png] = tmp_path.glob("*.sweep.png")
    assert png.stat().st_size > 0


def test_modes_per_arrangement_are_grouped_bars_named_by_one_legend():
    run = run_scene(parse_scene("""
title = "arrangements"
analysis = "modes"
[assembly]
name = "duplex_pair"
bearing = "7020C"
preload_force = "1 kN"
[grid]
"assembly.arrangement" = ["DF", "DB"]
"""), write=False)
    [(name, fig)] = _figures(run)
    [ax] = fig.axes
    modes = [n for n in run.rows[0] if n != "arrangement"]
    assert name == "modes" and len(ax.patches) == 2 * len(modes)
    assert [t.get_text() for t in ax.get_legend().get_texts()] == modes
    # bars in point order, each mode's bar of a point: its frequency in Hz
    heights = {(round(p.get_x() + p.get_width() / 2), round(p.get_height(), 6))
               for p in ax.patches}
    assert (0, round(run.rows[0]["tilt about x"], 6)) in heights
    assert (1, round(run.rows[1]["tilt about x"], 6)) in heights


def test_values_not_settled_are_hatched_and_lives_start_a_decade_below():
    """A transient sweep over lubricants: its final values had not settled (the row's
    ``unsettled``), which the bars did not say; and the lives' log axis started just below the
    least value, so that 221 861 h and 229 328 h looked like a bar and nothing."""
    from bearingsim.scenes import prepare
    from bearingsim.scenes.bar_figures import category_figures

    prep = prepare(_scene('[grid]\n"assembly.lubrication" = ["ISO VG 32", "ISO VG 68"]'))
    rows = [{"lubrication": "ISO VG 32", "Rs": 0.067, "L10h": 221861.0, "unsettled": "Rs"},
            {"lubrication": "ISO VG 68", "Rs": 0.097, "L10h": 229328.0, "unsettled": ""}]
    [(_, fig)] = category_figures(prep, rows, ["lubrication"], {"Rs": "1", "L10h": "h"},
                                  ["Rs", "L10h"], "steady")
    rs, life = fig.axes
    assert [p.get_hatch() for p in rs.patches] == ["///", None]
    assert life.get_yscale() == "log" and life.get_ylim()[0] == pytest.approx(1e4)
    assert _bars(life) == pytest.approx([221861.0, 229328.0])
    assert "hatched: not settled at t_end" in fig.texts[0].get_text()


def test_a_round_off_zero_is_written_as_0():
    """A displacement that symmetry makes 0 comes out as round-off (-1.89e-12 µm) and was
    written so above its bar; below 1e-9 of the panel's largest value it reads 0."""
    from bearingsim.scenes import prepare
    from bearingsim.scenes.bar_figures import category_figures

    prep = prepare(_scene('[grid]\n"assembly.lubrication" = ["ISO VG 32", "ISO VG 68"]'))
    rows = [{"lubrication": "ISO VG 32", "Rs": -1.89e-18},
            {"lubrication": "ISO VG 68", "Rs": 0.25}]
    [(_, fig)] = category_figures(prep, rows, ["lubrication"], {"Rs": "1"}, ["Rs"], "steady")
    assert [t.get_text() for t in fig.axes[0].texts] == ["0", "0.25"]
