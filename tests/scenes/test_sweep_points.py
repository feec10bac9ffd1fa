"""Sweeps give, at every point, what a single run of the same point gives: every shipped scene
over two points (post-processed quantities included), and the crash of issue 32
(``bearingsim sweep scenes/double_layer_friction.toml --grid assembly.outer=61907,61909``:
``TypeError: _total_loss() takes 1 positional argument but 2 were given``, no table)."""

from __future__ import annotations

import csv
import dataclasses
import json
from pathlib import Path

import pytest

from bearingsim.scenes import load_scene, run_scene
from bearingsim.scenes.operating_points import operating_points, point_label
from bearingsim.scenes.sweep import SweepError, grid_points, run_sweep
from bearingsim.scenes.sweep_grid import parse_grid

distributed = pytest.importorskip("distributed")

SCENES = sorted((Path(__file__).resolve().parents[2] / "scenes").glob("*.toml"))
T_SHORT = 0.04
"""Simulated time of the points [s] (short: the test compares, it does not study)."""



def _single(scene, t_end, **args):
    sim = dataclasses.replace(scene.simulation, t_end=t_end)
    changed = scene.replace(simulation=sim, args={**scene.args, **args}) if args else \
        scene.replace(simulation=sim)
    return run_scene(changed, write=False).series


def _single_point(scene, point):
    """The table row of a single run of an analysis scene at one operating point."""
    one = scene.replace(grid={k: [v] for k, v in point.items()}, cases=[])
    [row] = run_scene(one, write=False).rows
    return row


@pytest.mark.parametrize("path", SCENES, ids=[p.stem for p in SCENES])
def test_every_shipped_scene_sweeps_as_it_runs(path, client, tmp_path):
    """Each row equals the single run of its point, with the same result columns: a
    transient's final values with ``settled`` and its time constant (a transient on purpose
    without them), an analysis's table row
    (steady outputs, natural frequencies by mode, statics columns)."""
    scene = load_scene(path)
    if scene.analysis == "transient":
        t_end = min(scene.simulation.t_end, T_SHORT)
        times = [t_end / 2, t_end]
        points = grid_points(parse_grid([f"simulation.t_end={times[0]!r},{times[1]!r}"]))
    else:  # two operating points: the scene's first, and its first key 25 % higher
        first = {k: v for k, v in operating_points(scene)[0].items() if k != "name"}
        key = next(iter(first))
        points = [first, {**first, key: first[key] * 1.25}]
    res = run_sweep(scene, points, client=client, out=tmp_path, progress=False)
    assert [r["status"] for r in res.rows] == ["ok", "ok"], res.failures
    results = [k for k in res.rows[0] if k not in ("point", *points[0], "status",
                                                   "wall_s", "error")]
    assert results
    for k, row in enumerate(res.rows):
        if scene.analysis == "transient":
            single = {n: float(y[-1]) for n, y in _single(scene, times[k]).items()}
            if scene.transient_on_purpose:  # not checked for settling, as in a single run
                assert set(results) == set(single)
            else:
                assert set(results) == set(single) | {"settled", "time_constant", "unsettled"}
                assert isinstance(row["settled"], bool)
        else:
            labels = {point_label(key) for key in points[k]} | {"name"}
            single = {n: v for n, v in _single_point(scene, points[k]).items()
                      if n not in labels}
            assert set(results) == set(single)
        for name, value in single.items():
            assert row[name] == pytest.approx(value, rel=1e-12, abs=0.0, nan_ok=True), name
    table = list(csv.DictReader((tmp_path / f"{path.stem}.sweep.csv").open()))
    assert [r["point"] for r in table] == ["0", "1"]
    assert (tmp_path / f"{path.stem}.sweep.json").is_file()
    assert res.plot_failures == []


def test_a_statics_sweep_at_rest_draws_its_figure(client, tmp_path, monkeypatch, capsys):
    """A statics sweep whose cases are at rest has the text "not defined at zero speed" in
    its L10h column: its figure failed ("could not convert string to float"), and `bearingsim
    sweep` said nothing (the failure only in the summary) and exited 0. The figure now leaves
    the text column out; a figure that fails is printed and the command exits with 1."""
    from bearingsim.cli import main
    from bearingsim.scenes import sweep as sweep_module

    scene = load_scene("deep_groove_statics")
    points = grid_points(parse_grid(["inputs.load.Fx=500,1000", "inputs.shaft_speed=0"]))
    res = run_sweep(scene, points, client=client, out=tmp_path / "rest", progress=False)
    assert [r["L10h"] for r in res.rows] == ["not defined at zero speed"] * 2
    assert res.plot_failures == []
    assert (tmp_path / "rest" / "deep_groove_statics.sweep.png").is_file()

    def broken(*args):
        raise ValueError("no figure today")

    monkeypatch.setattr(sweep_module, "sweep_figures", broken)
    assert main(["sweep", "deep_groove_statics", "--grid", "inputs.load.Fx=500,1000",
                 "--grid", "inputs.shaft_speed=0", "--workers", "1",
                 "--out", str(tmp_path / "cli"), "--no-progress"]) == 1
    assert ("bearingsim sweep: plot failed: all figures: ValueError: no figure today (the table "
            "and summary are written)") in capsys.readouterr().err
    assert (tmp_path / "cli" / "deep_groove_statics.sweep.csv").is_file()


def test_issue_32_structural_grid_with_post_processed_quantities(client, tmp_path):
    """The issue's command: two bearings (two models), five outputs of which three are computed
    after the integration (total friction power, two ISO 281 lives); each row equals the single
    run of its point and the table is written."""
    scene = load_scene(SCENES[0].parent / "double_layer_friction.toml")
    points = grid_points(parse_grid(["assembly.outer=61907,61909",
                                     f"simulation.t_end={T_SHORT!r}"]))
    res = run_sweep(scene, points, client=client, out=tmp_path, progress=False)
    assert res.models_built == 2 and len(res.ok) == 2, res.failures
    for row, outer in zip(res.rows, ("61907", "61909"), strict=True):
        single = _single(scene, T_SHORT, outer=outer)
        for name in ("Rs", "M_shaft", "P_loss_total", "inner_layer.L10h", "outer_layer.L10h"):
            assert row[name] == pytest.approx(float(single[name][-1]), rel=1e-12), name
        assert row["P_loss_total"] > 0
    assert res.rows[0]["outer_layer.L10h"] != res.rows[1]["outer_layer.L10h"]
    assert (tmp_path / "double_layer_friction.sweep.csv").is_file()


def test_analysis_sweep_names_a_grid_input_left_without_value(client):
    """A sweep replaces an analysis scene's grid: an input only the grid gave is named."""
    scene = load_scene(SCENES[0].parent / "double_layer_rs.toml")
    with pytest.raises(SweepError, match=r"inputs\.shaft_speed then has no value"):
        run_sweep(scene, grid_points(parse_grid(["inputs.Fr=0,100"])), client=client,
                  progress=False)


def test_analysis_sweep_names_an_input_only_the_load_cases_gave(client, tmp_path):
    """A sweep replaces a statics scene's load cases too. Before, a sweep of
    deep_groove_statics over the bearing (6304, 6305), the loads left to the cases,
    ran every point at zero load (loads of ~1e-6 N from the regularisation, life "inf") and
    said nothing; now the inputs only the cases set are named, as the grid's are."""
    scene = load_scene("deep_groove_statics")
    with pytest.raises(SweepError, match=r"the sweep replaces the load cases of this statics "
                                         r"scene, and inputs\.load\.Fx, inputs\.shaft_speed then "
                                         r"have no value"):
        run_sweep(scene, grid_points(parse_grid(["assembly.bearing=6304,6305"])),
                  client=client, out=tmp_path, progress=False)
    assert not list(tmp_path.glob("*.*"))
    # given under [inputs], the scene's values stand for the cases' (as for a grid)
    given = scene.replace(inputs={"load.Fx": 900.0, "shaft_speed": 300.0})
    res = run_sweep(given, grid_points(parse_grid(["assembly.bearing=6304,6305"])),
                    client=client, out=tmp_path, progress=False)
    assert len(res.ok) == 2, res.failures
    assert all(row["Q_max"] > 200.0 for row in res.rows)  # 900 N shared by a few balls


def test_points_that_set_other_keys_are_refused_before_anything_runs(tmp_path):
    """Before: run_sweep(scene, [{"inputs.Fr": 100}, {"inputs.Fa": 20}]) ran both points and
    wrote a table whose only swept column was inputs.Fr, empty in row 1: nothing said that
    point 1 had run with Fa = 20 N."""
    scene = SCENES[0].parent / "double_layer_friction.toml"
    with pytest.raises(SweepError, match=r"sweep point 1 sets inputs\.Fa, point 0 inputs\.Fr: "
                                         r"every point of a sweep sets the same keys"):
        run_sweep(scene, [{"inputs.Fr": 100.0}, {"inputs.Fa": 20.0}], out=tmp_path / "o",
                  progress=False)
    with pytest.raises(SweepError, match=r"sweep point 2 sets inputs\.Fa, inputs\.Fr, point 0 "
                                         r"inputs\.Fr"):
        run_sweep(scene, [{"inputs.Fr": 100.0}, {"inputs.Fr": 200.0},
                          {"inputs.Fr": 300.0, "inputs.Fa": 20.0}], progress=False)
    assert not list((tmp_path / "o").glob("*.*"))  # no table, summary or figure


def test_a_misspelt_input_is_pointed_at_beside_the_grid_inputs_left_without_value(client):
    """A misspelt input (``Fx`` for the double-layer bearing's ``Fr``) was answered with
    ``inputs.Fr, inputs.shaft_speed then has no value``, not pointing at the misspelling."""
    scene = load_scene(SCENES[0].parent / "double_layer_rs.toml")
    with pytest.raises(SweepError, match=r"inputs\.Fr, inputs\.shaft_speed then have no "
                                         r"value: sweep them .* \(inputs\.Fx: not in the "
                                         r"scene's grid or \[inputs\]; check the spelling"):
        run_sweep(scene, grid_points(parse_grid(["inputs.Fx=100,200"])), client=client,
                  progress=False)


def test_modes_sweep_plots_one_curve_per_value_of_the_second_key(client, tmp_path):
    """A modes sweep over preload and speed: the mode frequencies as columns, and a figure
    with one curve per speed (natural frequencies in one panel)."""
    scene = load_scene(SCENES[0].parent / "duplex_modes.toml")
    points = grid_points(parse_grid(["assembly.preload_force=500,1000",
                                     "assembly.speed=0,200"]))
    res = run_sweep(scene, points, client=client, out=tmp_path, progress=False)
    assert len(res.ok) == 4, res.failures
    assert "shaft.x" not in res.rows[0] and "radial x" in res.rows[0]
    with (tmp_path / "duplex_modes.sweep.csv").open(encoding="utf-8") as table:
        header = next(csv.reader(table))
    # the assembly arguments with their units (the header and the figure had none)
    assert header[1:3] == ["assembly.preload_force [N]", "assembly.speed [rad/s]"]
    png = tmp_path / "duplex_modes.sweep.png"
    assert png.is_file()
    summary = json.loads((tmp_path / "duplex_modes.sweep.json").read_text())
    assert summary["analysis"] == "modes"
    assert {f["name"] for f in summary["files"]} >= {"duplex_modes.sweep.csv", png.name}


def test_parametric_points_are_not_built_on_the_client(monkeypatch):
    """A sweep over a parametric argument (a duplex pair's preload) builds the assembly on the
    client once, for the model of its structure: each point derives its parameter overrides
    where it runs. Before, the plan built the pair for every point (27 ms a point of
    duplex_modes, serial in the client: as long as the points themselves on 2 workers)."""
    from bearingsim.scenes import preparation, registry, sweep_plan

    scene = load_scene(SCENES[0].parent / "duplex_modes.toml")
    builds = []
    build = registry.build_component

    def counted(spec, args, fidelity):
        builds.append(args)
        return build(spec, args, fidelity)

    monkeypatch.setattr(registry, "build_component", counted)  # point_model's
    monkeypatch.setattr(preparation, "build_component", counted)  # prepare's
    points = grid_points(parse_grid(["assembly.preload_force=500,1000,1500,2000",
                                     "assembly.speed=0,419"]))
    plan = sweep_plan.plan_sweep(scene, points)
    assert len(plan.jobs) == 8 and len(plan.prepared) == 1 and len(builds) == 1


def test_a_parametric_value_the_assembly_refuses_fails_its_point_only(client, tmp_path):
    """A preload no row can carry passes the argument's own range (> 0 N) and is refused by
    the assembly where the point runs: that point fails naming why, the others run and equal
    their single runs."""
    scene = load_scene(SCENES[0].parent / "duplex_modes.toml")
    points = [{"assembly.preload_force": 1000.0, "assembly.speed": 0.0},
              {"assembly.preload_force": 1e9, "assembly.speed": 0.0}]
    res = run_sweep(scene, points, client=client, out=tmp_path, progress=False)
    assert [r["status"] for r in res.rows] == ["ok", "failed"]
    assert "cannot carry 1e+09 N axially" in res.failures[0]["error"]
    single = _single_point(scene, points[0])
    for name, value in single.items():
        if name in res.rows[0] and isinstance(value, float):
            assert res.rows[0][name] == pytest.approx(value, rel=1e-12), name


def test_a_sweep_whose_every_point_failed_writes_its_table_without_a_figure(client, tmp_path):
    """Every point failed (SKF friction without load: no torque holds the middle ring): the
    figure failed with "IndexError: list index out of range", which the command printed as a
    plot failure and counted in its exit status. There is nothing to draw: the table and
    summary say why each point failed."""
    from bearingsim.scenes import parse_scene

    scene = parse_scene('title = "skf"\nanalysis = "steady"\noutputs = ["Rs"]\n[assembly]\n'
                        'name = "double_layer_bearing"\nfriction_model = "skf"\n[inputs]\n'
                        'shaft_speed = "6000 rpm"\n')
    res = run_sweep(scene, grid_points(parse_grid(["inputs.Fr=0,0"])), client=client,
                    out=tmp_path, progress=False)
    assert [r["status"] for r in res.rows] == ["failed", "failed"]
    assert "steady state not unique" in res.rows[0]["error"]
    assert res.plot_failures == []
    assert not list(tmp_path.glob("*.png")) and list(tmp_path.glob("*.sweep.csv"))
