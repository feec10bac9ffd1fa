"""Scenes that ask the engineer's question (issue 27, items 1, 2 and 6): the analysis kinds
steady, modes and statics, the settling check of transient scenes, and the figures of every
shipped scene."""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from bearingsim.errors import SimulationError
from bearingsim.scenes import SceneError, load_scene, parse_scene, run_scene
from bearingsim.scenes.analyses import NotSettledWarning, run_operating_point, settling_check
from bearingsim.scenes.library import DEMO_SCENES, builtin_scenes
from bearingsim.scenes.scene import Settling
from bearingsim.units import rpm_to_rad_s

# the transient scene double_layer_rs was before issue 27: a spin-up to 10 000 r/min that ends
# at 1 s, before the middle ring has settled (Rs 0.172 against a settled 0.2095)
SPIN_UP = """
title = "spin-up"
outputs = ["w_middle", "Rs"]
[assembly]
name = "double_layer_bearing"
fidelity = "torque"
[inputs]
shaft_speed = "rpm(10000) * ramp(0, 0.5)"
[simulation]
t_end = {t_end}
rtol = 1e-7
atol = 1e-9
n_points = 201
"""


# --------------------------------------------------------------------------- steady
def test_rs_scene_equals_the_steady_torque_level_rs():
    """Must show: the Rs scene's answer equals the steady torque-level Rs (steady_ratio of
    the study, an independently assembled torque-level bearing) to 1e-6 at every operating
    point; 0.2095 at 10 000 r/min without load (README)."""
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.studies.double_layer import steady_ratio

    run = run_scene("double_layer_rs", write=False)
    assert run.result is None and run.summary["analysis"] == "steady"
    assert run.prepared.fidelity == "torque"
    assert len(run.rows) == 6 * 3
    system = assemble(double_layer_bearing("61905", "61907", fidelity="torque"),
                      outputs=["Rs", "M_shaft"])
    for row in run.rows:
        rs, _, _ = steady_ratio(system, row["shaft_speed"], (row["Fr"], 0.0))
        assert row["Rs"] == pytest.approx(rs, rel=1e-6, abs=1e-9)
        assert row["w_middle"] == pytest.approx(rs * row["shaft_speed"], rel=1e-6)
    top = next(r for r in run.rows if r["Fr"] == 0.0
               and r["shaft_speed"] == pytest.approx(rpm_to_rad_s(10000)))
    assert round(top["Rs"], 4) == 0.2095
    # a load slows the middle ring: Rs falls with the radial load at every speed
    by_load = {fr: [r["Rs"] for r in run.rows if r["Fr"] == fr] for fr in (0.0, 200.0, 1000.0)}
    assert np.all(np.array(by_load[1000.0]) < np.array(by_load[200.0]))
    assert np.all(np.array(by_load[200.0]) < np.array(by_load[0.0]))


def test_steady_table_and_figure_are_written(tmp_path):
    scene = load_scene("double_layer_rs")
    scene.grid = {"inputs.shaft_speed": [rpm_to_rad_s(2000), rpm_to_rad_s(4000)],
                  "inputs.Fr": [0.0, 500.0]}
    run = run_scene(scene, tmp_path)
    names = sorted(p.name for p in run.files)
    assert names == ["double_layer_rs.csv", "double_layer_rs.steady.png",
                     "double_layer_rs.summary.json"]
    lines = (tmp_path / "double_layer_rs.csv").read_text().splitlines()
    assert lines[0] == "shaft_speed [rad/s],Fr [N],Rs [-],w_middle [rad/s],M_shaft [N.m]"
    assert len(lines) == 1 + 4
    first = [float(v) for v in lines[1].split(",")]
    assert first[:2] == [pytest.approx(rpm_to_rad_s(2000)), 0.0]


# --------------------------------------------------------------------------- modes
def test_modes_scene_matches_the_duplex_study():
    """The modes of the scene (linearize at the equilibrium) are those of the duplex study
    (exact static stiffness and K phi = w^2 M phi) at the same preload, mode by mode."""
    from bearingsim.studies.duplex import DuplexModel

    model = DuplexModel("7020C", "DF")
    light = model.preload_force("light")
    scene = load_scene("duplex_modes")
    scene.grid = {"assembly.preload_force": [light, 2.0 * light]}
    run = run_scene(scene, write=False)
    for row, force in zip(run.rows, (light, 2.0 * light), strict=True):
        expected = model.modes(preload=force).by_name()
        assert set(expected) <= set(row)
        for name, f in expected.items():
            assert row[name] == pytest.approx(f, rel=1e-6), name
    assert run.rows[1]["axial"] > run.rows[0]["axial"]  # preload stiffens the pair


def test_spindle_modes_are_named_as_the_duplex_pairs():
    """The spindle's modes are named after the pair's shaft degrees of freedom ("radial x",
    "tilt about y"), as a duplex pair's are; they were "x of the centre of mass". Without a
    radial load the NU bearing's clearance leaves it unloaded: the modes are the same at every
    roller distance, radial x and y equal; a radial load in x loads it in x only."""
    scene = parse_scene("""
analysis = "modes"
[assembly]
name = "spindle"
[grid]
"assembly.roller_distance" = [0.2, 0.4]
"inputs.pair.shaft.Fx" = [0.0, 2000.0]
""")
    rows = run_scene(scene, write=False).rows
    names = ("radial x", "radial y", "axial", "tilt about x", "tilt about y")
    assert all(set(names) <= set(row) for row in rows)
    free, loaded = rows[:2], rows[2:]
    for name in names:
        assert free[0][name] == pytest.approx(free[1][name], rel=1e-6), name
    assert free[0]["radial x"] == pytest.approx(free[0]["radial y"], rel=1e-6)
    assert all(row["radial x"] > 2.0 * row["radial y"] for row in loaded)
    # alone, the last point solves from the spindle's unloaded start (Newton needs 14 steps;
    # 12 were allowed, then MINPACK stalled: "steady state not found"), as the grid found it
    [alone] = run_scene(parse_scene("""
analysis = "modes"
[assembly]
name = "spindle"
roller_distance = 0.4
[inputs]
"pair.shaft.Fx" = 2000.0
"""), write=False).rows
    for name in names:
        assert alone[name] == pytest.approx(rows[3][name], rel=1e-6), name


_SKF_STEADY = """
title = "SKF friction at zero load"
analysis = "steady"
outputs = ["Rs"]
[assembly]
name = "double_layer_bearing"
friction_model = "skf"
[inputs]
shaft_speed = "6000 rpm"
[grid]
"inputs.Fr" = {loads}
"""


def test_a_point_without_an_answer_is_a_row_that_says_why(tmp_path, capsys):
    """SKF's rolling and sliding friction vanish without load: at Fr = 0 no torque acts on the
    middle ring, and its steady speed is not determined. The steady scene stopped at that
    point with no table and no word of which point failed. Now that point's row carries the
    message (column ``error``), the other points are answered as if solved alone, the
    figure leaves it out and says so, a PointFailedWarning names it, and ``bearingsim run``
    writes everything and exits with 1."""
    from bearingsim.cli import main
    from bearingsim.scenes.analyses import PointFailedWarning

    with pytest.warns(PointFailedWarning, match=r"1 of 3 operating point\(s\).*First: Fr = 0 "
                                                r"kN: steady state not unique"):
        run = run_scene(parse_scene(_SKF_STEADY.format(loads="[0.0, 500.0, 1000.0]")),
                        write=False)
    assert set(run.rows[0]) == {"Fr", "error"} and "middle.sleeve.w" in run.rows[0]["error"]
    assert run.summary["failed"] == [{"point": 0, "error": run.rows[0]["error"]}]
    alone = run_scene(parse_scene(_SKF_STEADY.format(loads="[500.0, 1000.0]")), write=False)
    assert [row["Rs"] for row in run.rows[1:]] == pytest.approx(
        [row["Rs"] for row in alone.rows], rel=1e-9)
    assert 0.2 < alone.rows[0]["Rs"] < 0.3
    scene = tmp_path / "skf.toml"
    scene.write_text(_SKF_STEADY.format(loads="[0.0, 500.0]"))
    assert main(["run", str(scene), "--out", str(tmp_path / "out")]) == 1
    said = capsys.readouterr()
    assert "  Fr = 0 kN: FAILED: steady state not unique" in said.out
    assert "warning: PointFailedWarning: 1 of 2 operating point(s)" in said.err
    table = (tmp_path / "out" / "skf.csv").read_text().splitlines()
    assert table[0] == "Fr [N],error,Rs [-]" and table[1].startswith("0.0,\"steady state not")
    assert (tmp_path / "out" / "skf.steady.png").is_file()
    with pytest.raises(SimulationError, match=r"no operating point found an answer; the first, "
                                              r"Fr = 0 kN: steady state not unique"):
        run_scene(parse_scene(_SKF_STEADY.format(loads="[0.0, 0.0]")), write=False)
    with pytest.raises(SimulationError, match=r"^the operating point \(Fr = 0 kN\) found no "
                                              r"answer: steady state not unique"):
        run_scene(parse_scene(_SKF_STEADY.format(loads="[0.0]")), write=False)
    # a scene of [inputs] alone: its one point has no keys to name (it said "the first, :")
    alone = _SKF_STEADY.format(loads="[0.0]").replace('[grid]\n"inputs.Fr" = [0.0]', "Fr = 0.0")
    assert "[grid]" not in alone
    with pytest.raises(SimulationError, match=r"^the operating point found no answer: steady "
                                              r"state not unique"):
        run_scene(parse_scene(alone), write=False)


def test_a_modes_scene_without_oscillating_modes_says_so(tmp_path, capsys):
    """The double-layer bearing's torque level has one state (the middle ring's speed): its
    linearized model has one real eigenvalue and no natural frequency. The modes scene printed
    its grid points and nothing else; now each row says so and a NoModesWarning explains."""
    from bearingsim.cli import main
    from bearingsim.scenes.analyses import NoModesWarning

    text = ('analysis = "modes"\n[assembly]\nname = "double_layer_bearing"\n[inputs]\n'
            'shaft_speed = "3000 rpm"\n[grid]\n"inputs.Fr" = [100.0, 500.0]\n')
    with pytest.warns(NoModesWarning, match="no oscillating mode at any operating point: every "
                                            "eigenvalue of the linearized model is real"):
        run = run_scene(parse_scene(text), write=False)
    assert [set(row) for row in run.rows] == [{"Fr"}, {"Fr"}]
    scene = tmp_path / "modes.toml"
    scene.write_text(text)
    assert main(["run", str(scene), "--out", str(tmp_path / "out")]) == 0
    said = capsys.readouterr()
    assert "  Fr = 0.1 kN: no oscillating mode\n  Fr = 0.5 kN: no oscillating mode" in said.out
    assert "NoModesWarning" in said.err


def test_a_structural_argument_in_a_grid_assembles_its_own_model():
    """A preload is a parameter of the assembled pair; an arrangement is not (it changes the
    equations' signs): a grid over it assembles each arrangement's model instead of running
    the first one's with other parameter values."""
    from bearingsim.studies.duplex import DuplexModel

    scene = load_scene("duplex_modes")
    scene.grid = {"assembly.arrangement": ["DF", "DB"]}
    scene.args["preload"] = "light"
    run = run_scene(scene, write=False)
    for row in run.rows:
        expected = DuplexModel("7020C", row["arrangement"]).modes(preload="light").by_name()
        assert row["tilt about x"] == pytest.approx(expected["tilt about x"], rel=1e-6)
    # back to back holds the tilt stiffer than face to face
    assert run.rows[1]["tilt about x"] > 1.1 * run.rows[0]["tilt about x"]



_AT_REST = """
analysis = "{analysis}"
{outputs}
[assembly]
name = "double_layer_bearing"
fidelity = "torque"
[inputs]
Fa = 0.0
Fr = 200.0
{speed}
{simulation}"""


def _at_rest(analysis: str, speed: str, outputs: str) -> str:
    """The scene _AT_REST; a transient one with its end time (a steady one has none)."""
    simulation = "[simulation]\nt_end = 0.05\n" if analysis == "transient" else ""
    return _AT_REST.format(analysis=analysis, speed=speed, outputs=outputs,
                           simulation=simulation)


@pytest.mark.parametrize(("analysis", "speed", "outputs", "key"), [
    ("steady", '[grid]\n"inputs.shaft_speed" = [0.0, "1000 rpm"]', 'outputs = ["Rs"]', "grid"),
    ("transient", 'shaft_speed = "0 rpm"', "", "inputs.shaft_speed"),  # default outputs: Rs
    ("steady", "shaft_speed = 0.0", 'outputs = ["M_shaft", "inner_layer.L10h"]',
     "inputs.shaft_speed"),
])
def test_outputs_without_a_value_at_rest_are_refused(analysis, speed, outputs, key):
    """Rs = w_middle / w_shaft is 0/0 and a life in hours undefined at rest. Old code: Rs = 0
    (the regularized ratio) reported as the steady answer, or as settled at the end of a
    transient, and inner_layer.L10h = inf ("None" / "inf/nan" on the console)."""
    text = _at_rest(analysis, speed, outputs)
    with pytest.raises(SceneError, match=r"input shaft_speed = 0 rad/s holds the shaft at rest, "
                       r"where the outputs .* have no value: .*valid range of shaft_speed: other "
                       r"than 0 \[rad/s\]") as err:
        run_scene(parse_scene(text), write=False)
    assert err.value.key == key
    assert ("Rs = w_middle / w_shaft is 0/0" in str(err.value)) == ("L10h" not in outputs)


def test_a_bearing_at_rest_answers_what_has_a_value_there():
    text = _at_rest("steady", "shaft_speed = 0.0", 'outputs = ["w_middle", "M_shaft"]')
    row = run_scene(parse_scene(text), write=False).rows[0]
    assert row["w_middle"] == 0.0 and row["M_shaft"] == 0.0

# --------------------------------------------------------------------------- statics
def test_statics_scene_matches_deep_groove_statics():
    """Each load case's row is deep_groove_statics of that load; the life in hours is the
    reference life L10r [10^6 rev] at the case's speed."""
    from bearingsim.studies.deep_groove_statics import deep_groove_statics

    run = run_scene("deep_groove_statics", write=False)
    assert [r["name"][:2] for r in run.rows] == ["1:", "2:", "3:", "4:"]
    for row in run.rows:
        ref = deep_groove_statics("6304", {"Fx": row["load.Fx"]})
        assert row["Q_max"] == pytest.approx(ref.ball_loads.max(), rel=1e-9)
        assert row["p_max"] == pytest.approx(ref.max_pressure, rel=1e-9)
        assert row["L10r"] == pytest.approx(ref.reference_life, rel=1e-9)
        revolutions_per_hour = row["shaft_speed"] / (2 * math.pi) * 3600
        assert row["L10h"] == pytest.approx(row["L10r"] * 1e6 / revolutions_per_hour, rel=1e-12)
    # the study's finding: the life falls with the load and with the speed
    life = {r["name"][0]: r["L10h"] for r in run.rows}
    assert life["1"] < life["3"] and life["2"] < life["1"] and life["4"] < life["3"]



def test_statics_life_in_hours_at_rest_is_said_to_be_undefined(tmp_path, capsys):
    """A load case at rest (shaft speed 0 or not given) has a life in revolutions but none in
    hours. Old code: L10h = nan in the row and CSV, null in the summary, "L10h = None" on the
    console."""
    import csv
    import json

    from bearingsim.cli import main

    scene = tmp_path / "rest.toml"
    scene.write_text('analysis = "statics"\n[assembly]\nname = "deep_groove_ball_bearing"\n'
                     'bearing = "6304"\nfidelity = "quasi-static"\n'
                     '[[cases]]\nname = "at rest"\n"inputs.shaft_speed" = 0.0\n'
                     '"inputs.load.Fx" = 938.0\n'
                     '[[cases]]\nname = "no speed"\n"inputs.load.Fx" = 938.0\n'
                     '[[cases]]\nname = "running"\n"inputs.shaft_speed" = "1730 rpm"\n'
                     '"inputs.load.Fx" = 938.0\n[output]\nfolder = "out"\n')
    assert main(["run", str(scene)]) == 0
    console = capsys.readouterr().out
    assert console.count("L10h = not defined at zero speed") == 2 and "None" not in console
    rows = list(csv.DictReader((tmp_path / "out" / "rest.csv").open()))
    summary = json.loads((tmp_path / "out" / "rest.summary.json").read_text())["rows"]
    for table in (rows, summary):
        assert [r["L10h [h]" if table is rows else "L10h"] for r in table[:2]] == [
            "not defined at zero speed"] * 2
        assert float(table[0]["L10r [Mrev]" if table is rows else "L10r"]) == pytest.approx(
            3319.04, rel=1e-5)  # the life in revolutions is still given
    running = summary[2]
    assert running["L10h"] == pytest.approx(running["L10r"] * 1e6 / (1730 * 60), rel=1e-12)

def test_statics_of_an_assembly_without_statics_is_refused():
    text = ('analysis = "statics"\n[assembly]\nname = "duplex_pair"\n'
            '[[cases]]\n"inputs.shaft.Fz" = 100.0\n')
    with pytest.raises(SceneError, match="no statics analysis for the assembly duplex_pair"):
        run_scene(parse_scene(text), write=False)


# --------------------------------------------------------------------------- validation
@pytest.mark.parametrize("text, key, match", [
    ('analysis = "static"\n', "analysis", "not an analysis"),
    ('[grid]\n"inputs.Fr" = [0.0]\n[simulation]\nt_end = 1.0\n', "grid",
     "for the analyses steady, modes and statics"),
    ('analysis = "steady"\n[inputs]\nshaft_speed = "100 * t"\n', "inputs.shaft_speed",
     "holds every input constant"),
    ('analysis = "steady"\n[grid]\n"inputs.Fr" = []\n', "grid.inputs.Fr", "non-empty list"),
    ('analysis = "steady"\n[grid]\n"simulation.rtol" = [1e-6]\n', "grid.simulation.rtol",
     "not an operating-point key"),
    ('analysis = "steady"\n[grid]\n"inputs.Fr" = [0.0]\n[[cases]]\n"inputs.Fr" = 1.0\n',
     "cases", "either as a grid or as cases"),
    ('analysis = "steady"\ntransient_on_purpose = true\n', "transient_on_purpose",
     "transient scenes only"),
    ('[settling]\nwindow = 1.5\n[simulation]\nt_end = 1.0\n', "settling.window",
     "out of range"),
    # were read and then left unused: an rtol that could not tighten a steady solve
    ('analysis = "steady"\n[simulation]\nrtol = 1e-9\n', "simulation.rtol",
     r"simulation\.rtol applies to transient scenes only \(a steady analysis solves each "
     r"point directly, not in time\)"),
    ('analysis = "modes"\n[simulation]\nt_end = 2.0\n', "simulation.t_end",
     "transient scenes only"),
    # a statics scene solves its bearing by designation: a groove curvature fi of 0.56 gave
    # the answer of the catalogue's 0.52 without a word
    ('analysis = "statics"\n[parameters]\n"row.fi" = 0.56\n', "parameters",
     r"a statics scene solves its bearing from the designation and the assembly arguments, "
     r"not from the model's parameters or start values, which it would leave unused; "
     r"allowed: the bearing's values in a datasheet"),
    ('analysis = "statics"\n[grid]\n"parameters.row.fi" = [0.52, 0.56]\n', "grid",
     "not from the model's parameters"),
    ('analysis = "statics"\n[[cases]]\n"parameters.row.fi" = 0.56\n', "cases",
     "not from the model's parameters"),
    ('analysis = "steady"\n[output]\nplot_groups = [["Rs"]]\n', "output.plot_groups",
     r"output\.plot_groups applies to transient scenes only \(the steady figure draws its "
     r"own columns; outputs chooses them\)"),
])
def test_analysis_keys_are_validated(text, key, match):
    base = '[assembly]\nname = "double_layer_bearing"\n'
    with pytest.raises(SceneError, match=match) as info:
        parse_scene(text + base)
    assert any(p.key == key for p in info.value.problems), [p.key for p in info.value.problems]


def test_a_steady_scene_keeps_its_time_budget_and_copies_without_time_settings():
    """simulation.timeout (a sweep point's budget) is the one simulation setting of an
    analysis scene; its TOML form (to_dict, replace) holds no other, so a copy is valid."""
    scene = parse_scene('analysis = "steady"\n[simulation]\ntimeout = "2 s"\n'
                        '[assembly]\nname = "double_layer_bearing"\n[inputs]\n'
                        'shaft_speed = "1000 rpm"\n')
    assert scene.simulation.timeout == 2.0
    assert scene.to_dict()["simulation"] == {"timeout": 2.0}
    assert scene.replace(title="a copy").simulation.timeout == 2.0


def test_grid_values_take_units_and_the_first_key_varies_fastest():
    from bearingsim.scenes.operating_points import operating_points

    scene = parse_scene('analysis = "steady"\n[assembly]\nname = "double_layer_bearing"\n'
                        '[grid]\n"inputs.shaft_speed" = ["1000 rpm", 200.0]\n'
                        '"inputs.Fr" = [0.0, 5.0]\n')
    assert scene.grid["inputs.shaft_speed"] == [pytest.approx(rpm_to_rad_s(1000)), 200.0]
    points = operating_points(scene)
    assert [(p["inputs.shaft_speed"], p["inputs.Fr"]) for p in points] == [
        (pytest.approx(rpm_to_rad_s(1000)), 0.0), (200.0, 0.0),
        (pytest.approx(rpm_to_rad_s(1000)), 5.0), (200.0, 5.0)]


# --------------------------------------------------------------------------- settled or not
@given(tau=st.floats(0.05, 2.0), amplitude=st.floats(-1e3, 1e3).filter(lambda a: abs(a) > 1e-3),
       offset=st.floats(-1e3, 1e3))
def test_settling_check_recovers_an_exponential_approach(tau, amplitude, offset):
    """y = offset + amplitude (1 - exp(-t / tau)): the time constant and the settled value
    are those of the exponential (exact for three grid points of the window), and the output
    counts as settled exactly when its range over the last 20 % is within 1e-3 of the
    final magnitude."""
    # differences in the window resolvable in double precision
    assume(abs(amplitude) * math.exp(-0.8 / tau) > 1e-7 * (abs(offset) + abs(amplitude)))
    t = np.linspace(0.0, 1.0, 1001)
    y = offset + amplitude * (1.0 - np.exp(-t / tau))
    check = settling_check(t, {"y": y}, Settling())
    out = check["outputs"]["y"]
    assert out["time_constant"] == pytest.approx(tau, rel=1e-6)
    assert out["extrapolated"] == pytest.approx(offset + amplitude, rel=1e-6,
                                                abs=1e-6 * abs(amplitude))
    window = np.ptp(y[t >= 0.8 - 1e-12])
    scale = max(abs(y[-1]), 1e-3 * np.max(np.abs(y)))
    assert out["settled"] == (window / scale <= 1e-3)
    assert check["settled"] == out["settled"]


def test_settling_check_of_constant_and_oscillating_outputs():
    t = np.linspace(0.0, 10.0, 2001)
    check = settling_check(t, {"zero": np.zeros_like(t), "ring": 1.0 + 0.01 * np.sin(20 * t)},
                           Settling(window=0.2, tolerance=1e-3))
    assert check["outputs"]["zero"]["settled"]
    assert not check["outputs"]["ring"]["settled"]
    assert math.isnan(check["outputs"]["ring"]["time_constant"])
    assert check["unsettled"] == ["ring"]
    # a life that is infinite while unloaded: settled once it keeps one value
    life = np.where(t < 5.0, np.inf, 1e4)
    assert settling_check(t, {"life": life}, Settling())["settled"]
    late = np.where(t < 9.0, 1e4, np.inf)
    assert not settling_check(t, {"life": late}, Settling())["settled"]


def test_a_change_below_the_resolution_counts_as_settled():
    """Round-off of a state that symmetry keeps at zero (1e-19 m, changing by many times
    itself) has settled when its resolution (the run's atol, 1e-8 m) is given; a real drift
    above the resolution has not."""
    t = np.linspace(0.0, 1.0, 501)
    noise = 3e-19 * np.sin(50.0 * t)
    drift = 1e-6 * t
    check = settling_check(t, {"x": noise, "z": drift}, Settling(), {"x": 1e-8, "z": 1e-8})
    assert check["outputs"]["x"]["settled"] and check["outputs"]["x"]["change"] > 1.0
    assert not check["outputs"]["z"]["settled"]
    assert not settling_check(t, {"x": noise}, Settling())["settled"]


DB_MOMENT = """
title = "DB pair, axial load and a moment"
outputs = ["shaft.z", "shaft.x"]
[assembly]
name = "duplex_pair"
bearing = "7020C"
arrangement = "DB"
preload_force = "1.5 kN"
damping_ratio = 0.1
[inputs]
"shaft.Fz" = "2 kN"
"shaft.Mx" = "5 N m"
[simulation]
t_end = 0.05
"""


def test_a_displacement_zero_by_symmetry_does_not_make_a_run_unsettled():
    """A moment about x tilts the shaft about x and moves it along y, never along x: shaft.x
    is round-off (about 1e-19 m), which changed by several times itself over the last 20 %.
    The run reported ``settled: NO`` and warned; the settled value it named was round-off
    too. Also: an assembly argument with a unit (preload_force = "1.5 kN", which was refused:
    "must be a number in SI units")."""
    scene = parse_scene(DB_MOMENT)
    assert scene.args["preload_force"] == 1500.0
    with warnings.catch_warnings():
        warnings.simplefilter("error", NotSettledWarning)
        run = run_scene(scene, write=False)
    assert run.summary["settled"] is True
    assert abs(run.series["shaft.x"][-1]) < 1e-15
    assert run.series["shaft.z"][-1] == pytest.approx(-16.207e-6, rel=1e-3)
    # the printed value says it is zero to the run's resolution; shaft.z is a result
    from bearingsim.scenes.runner import console_lines

    lines = {line.split(" = ")[0].strip(): line for line in console_lines(run.summary)}
    assert lines["shaft.x"].endswith("(zero to the run's resolution, atol = 0.01 µm)")
    assert "resolution" not in lines["shaft.z"]
    assert run.summary["outputs"]["shaft.x"]["resolution"] == 1e-8


BALLS_AT_SPEED = """
title = "6304 balls at speed"
outputs = ["w_cage", "inner[0].Q"]
[assembly]
name = "deep_groove_ball_bearing"
bearing = "6304"
fidelity = "dynamic_massive_balls"
[inputs]
shaft_speed = "1730 rpm"
"load.Fx" = 938.0
[simulation]
t_end = 0.01
rtol = 1e-5
atol = 1e-8
"""


def test_a_run_without_a_steady_state_is_not_told_to_ask_for_one():
    """A ball-level bearing at speed runs periodically (its balls and cage turn): the warning
    of a run that had not settled told the user to ask analysis = "steady", which then failed
    (steady state not found). Now it says that no steady state was found."""
    with pytest.warns(NotSettledWarning) as caught:
        run = run_scene(parse_scene(BALLS_AT_SPEED), write=False)
    text = str(caught[0].message)
    assert run.summary["settled"] is False
    assert 'ask analysis = "steady"' not in text
    assert "no steady state was found from the final state" in text


def test_a_transient_that_has_not_settled_says_so():
    """Issue 27: the spin-up scene ended at 1 s with Rs 0.172 against a settled 0.2095, and
    nothing warned. Now the warning names Rs with its steady value, and the summary and the
    sweep row carry settled = False and the time constant (fails on the old code: no
    warning, no 'settled' in the summary)."""
    from bearingsim.scenes.runner import console_lines

    scene = parse_scene(SPIN_UP.format(t_end=1.0))
    with pytest.warns(NotSettledWarning) as record:
        run = run_scene(scene, write=False)
    text = str(record[0].message)
    assert "Rs = 0.1716" in text and "steady value 0.2094" in text and "w_middle" in text
    s = run.summary
    assert s["settled"] is False and 0.1 < s["time_constant_s"] < 1.0
    assert s["outputs"]["Rs"]["settled"] is False
    assert s["outputs"]["Rs"]["steady"] == pytest.approx(0.20949, abs=1e-5)
    assert any("NOT settled; steady 0.2094" in line for line in console_lines(s))
    row = run_operating_point(run.prepared)
    assert row["settled"] is False and row["unsettled"] == "w_middle Rs"
    assert row["time_constant"] == pytest.approx(s["time_constant_s"])
    assert row["Rs"] == pytest.approx(s["outputs"]["Rs"]["final"])


def test_a_settled_transient_and_one_on_purpose_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error", NotSettledWarning)
        run = run_scene(parse_scene(SPIN_UP.format(t_end=12.0)), write=False)
        assert run.summary["settled"] is True
        assert run.summary["outputs"]["Rs"]["final"] == pytest.approx(0.20949, abs=2e-5)
        purpose = parse_scene("transient_on_purpose = true\n" + SPIN_UP.format(t_end=1.0))
        assert run_scene(purpose, write=False).summary["settled"] is None


SHIPPED_TRANSIENTS = [n for n in builtin_scenes()
                      if load_scene(n).analysis == "transient"]


@pytest.mark.parametrize("name", SHIPPED_TRANSIENTS)
def test_every_shipped_transient_settles_or_says_it_is_on_purpose(name):
    scene = load_scene(name)
    if scene.transient_on_purpose:
        assert "transient" in (scene.text or "").split("transient_on_purpose")[0][-400:]
        return
    with warnings.catch_warnings():
        warnings.simplefilter("error", NotSettledWarning)
        run = run_scene(scene, write=False)
    assert run.summary["settled"] is True


def test_the_demo_runs_one_scene_per_study_question():
    kinds = {n: load_scene(n).analysis for n in DEMO_SCENES}
    assert kinds["double_layer_rs"] == "steady" and kinds["duplex_modes"] == "modes"
    assert kinds["deep_groove_statics"] == "statics"


# --------------------------------------------------------------------------- figures
DISPLAY_UNITS = {"r/min", "µm", "deg", "kN", "N mm", "MPa", "N/µm", "h", "10⁶ rev", "Hz",
                 "-", "s", "W", "A", "°C"}
_DOTTED = re.compile(r"[a-z_]+\[?\d*\]?\.[a-z_]")
_SHORT = {"deep_groove_duty1": 0.002, "deep_groove_radial": 1.5, "double_layer_friction": 3.0,
          "duplex_pair_axial": 0.02, "duplex_pair_pure_axial": 0.001,
          "motor_drive_spinup": 4.0, "cylindrical_roller_radial": 1.25, "spindle_radial": 0.03}


def _figures(name):
    from bearingsim.scenes.analysis_figures import analysis_figures
    from bearingsim.scenes.analysis_table import analysis_units
    from bearingsim.scenes.run_figures import scene_figures

    scene = load_scene(name)
    if scene.analysis != "transient":
        scene.grid = {k: v[:3] for k, v in scene.grid.items()}  # the same figure, sooner
        run = run_scene(scene, write=False)
        keys = run.summary["keys"]
        return run, dict(analysis_figures(run.prepared, run.rows, keys,
                                          analysis_units(run.prepared, run.rows)))
    scene.simulation.t_end = _SHORT[name]
    scene.transient_on_purpose = True
    if name == "deep_groove_duty1":
        scene.args["n_slices"] = 0
    run = run_scene(scene, write=False)
    units = {**run.result.units, **{n: q.unit for n, q in run.prepared.post.items()}}
    return run, dict(scene_figures(run.prepared, run.result, run.series, name, units))


@pytest.mark.parametrize("name", builtin_scenes())
def test_every_shipped_figure_reads_as_a_report(name):
    """Every axis of every shipped scene's figures: labelled with a description (no dotted
    model name) and a display unit (µm, not um; N mm for every torque), loads on linear axes
    that show 0, and no curve plotting a variable against itself."""
    _, figures = _figures(name)
    assert figures
    for file, fig in figures.items():
        for ax in fig.axes:
            if not ax.lines and not ax.patches:
                continue
            for label in (ax.get_xlabel(), ax.get_ylabel()):
                if not label or label == "load case":  # categorical: the cases' names
                    continue
                flat = label.replace("\n", " ").replace("\u00a0", " ")
                unit = re.fullmatch(r".*\[([^\]]*)\]", flat)
                assert unit and unit.group(1) in DISPLAY_UNITS, (file, label)
                assert not _DOTTED.search(flat.split("[")[0]), (file, label)
            assert ax.get_ylabel(), file
            unit = re.fullmatch(r".*\[([^\]]*)\]", ax.get_ylabel().replace("\n", " ")
                                .replace("\u00a0", " ")).group(1)
            if unit in ("kN", "N mm"):
                low, high = ax.get_ylim()
                assert ax.get_yscale() == "linear" and low <= 0.0 <= high, (file, unit)
            for line in ax.lines:
                x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
                if x.size > 2 and x.shape == y.shape:
                    assert not np.allclose(x, y), (file, line.get_label())


def test_the_load_step_is_drawn_above_the_torque_it_drives():
    _, figures = _figures("double_layer_friction")
    axes = figures["double_layer_friction.png"].axes
    load = axes[0]
    assert load.get_ylabel().startswith("input: radial load")
    t, fr = (np.asarray(v, float) for v in load.lines[0].get_data())
    assert fr[t < 1.49].max() == pytest.approx(0.2) and fr[-1] == pytest.approx(1.0)  # kN
    torque = next(ax for ax in axes if "friction torque" in ax.get_ylabel())
    t2, m = (np.asarray(v, float) for v in torque.lines[0].get_data())
    assert np.allclose(t, t2)
    jump = np.argmax(np.abs(np.diff(m)))
    assert t[jump] == pytest.approx(1.5, abs=0.02)  # the torque steps where the load does


def test_the_steady_figure_draws_one_curve_per_load():
    _, figures = _figures("double_layer_rs")
    ax = figures["steady"].axes[0]
    assert figures["steady"].axes[-1].get_xlabel() == "imposed shaft speed [r/min]"
    assert ax.get_ylabel().replace("\n", " ").startswith("speed distribution ratio")
    assert [line.get_label() for line in ax.lines] == ["Fr = 0 kN", "Fr = 0.2 kN", "Fr = 1 kN"]
    x = ax.lines[0].get_xdata()
    assert list(x) == pytest.approx([1000.0, 2000.0, 4000.0])  # the first three speeds


def test_auto_rejects_the_kinematic_rs_of_a_steady_scene_without_loads():
    """Without a load the kinematic level provides Rs, but its measured error (up to 350 %)
    exceeds the 5 % tolerance: a steady scene gets the torque level, as a transient does."""
    from bearingsim.scenes.preparation import prepare

    scene = parse_scene('analysis = "steady"\noutputs = ["Rs"]\n[assembly]\n'
                        'name = "double_layer_bearing"\n[grid]\n'
                        '"inputs.shaft_speed" = ["5000 rpm"]\n')
    prep = prepare(scene)
    assert prep.fidelity == "torque"
    assert prep.fidelity_rejected[0].startswith("kinematic: Rs off by")


# --------------------------------------------------------------------------- levels
def test_the_double_layer_quasi_static_level_is_a_statics_scene():
    """Issue 27: the double layer's quasi-static level was API-only. The shipped load-sharing
    scene runs it; each case's row is nested_equilibrium of that load."""
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.studies.nested_equilibrium import nested_equilibrium

    run = run_scene("double_layer_load_sharing", write=False)
    assert run.prepared.fidelity == "quasi-static"
    system = assemble(double_layer_bearing("61905", "61907", fidelity="quasi-static"))
    for row in run.rows:
        eq = nested_equilibrium(system, row["shaft.Fx"], row.get("shaft.Fz", 0.0))
        assert row["Q_max_inner"] == pytest.approx(eq.inner_ball_loads.max(), rel=1e-6)
        assert row["x_middle"] == pytest.approx(eq.middle_displacement[0], rel=1e-6)
    # the layers in series: the middle ring moves about half as far as the shaft
    assert 0.3 < run.rows[1]["x_middle"] / run.rows[1]["x_shaft"] < 0.7


def test_the_nested_ball_level_is_reachable_from_a_scene():
    """The ball and cage dynamics of both layers (fidelity "dynamic") build from scene
    arguments, with the shaft speed and the shaft loads as inputs (assembling it takes
    minutes, so only the component is checked here)."""
    from bearingsim.assemblies.double_layer import DynamicDoubleLayerBearing
    from bearingsim.scenes.registry import build_component

    scene = parse_scene('outputs = ["Rs"]\n[assembly]\nname = "double_layer_bearing"\n'
                        'fidelity = "dynamic"\n[inputs]\nshaft_speed = "1000 rpm"\n'
                        '"inner_layer.load.Fx" = 200.0\n[simulation]\nt_end = 0.01\n')
    spec = scene.spec
    component = build_component(spec, spec.with_defaults(scene.args), scene.fidelity)
    assert isinstance(component, DynamicDoubleLayerBearing)
    assert spec.is_optional_input("inner_layer.load.Fy")
    assert "dynamic" in spec.fidelities and "dynamic" not in spec.auto_fidelities


def test_a_steady_figure_never_plots_a_variable_against_itself():
    """w_shaft is the imposed shaft speed, the x axis: its panel would be the identity
    (issue 27: one sweep panel plotted w_shaft against itself); the figure leaves it out and
    keeps the table column."""
    from bearingsim.scenes.analysis_figures import analysis_figures
    from bearingsim.scenes.analysis_table import analysis_units

    scene = parse_scene('analysis = "steady"\noutputs = ["w_shaft", "Rs"]\n[assembly]\n'
                        'name = "double_layer_bearing"\nfidelity = "torque"\n[grid]\n'
                        '"inputs.shaft_speed" = ["1000 rpm", "3000 rpm", "5000 rpm"]\n')
    run = run_scene(scene, write=False)
    assert [r["w_shaft"] for r in run.rows] == pytest.approx([r["shaft_speed"] for r in run.rows])
    (name, fig), = analysis_figures(run.prepared, run.rows, ["shaft_speed"],
                                    analysis_units(run.prepared, run.rows))
    labels = [ax.get_ylabel().replace("\n", " ") for ax in fig.axes]
    assert len(labels) == 1 and labels[0].startswith("speed distribution ratio")


def test_a_point_whose_solve_fails_from_the_previous_state_starts_again_from_its_own():
    """A modes grid over the arrangement (DB, then DT): the DT point started its steady solve
    from the DB pair's solved state, a state of another model with as many states, and failed
    ("steady state not found", shaft.vz 40.5 m/s2) though DT alone solves. A solve that fails
    from the previous point's state is now made again from the model's own start; each row
    equals its arrangement alone."""
    text = """
title = "arrangements"
analysis = "modes"
[assembly]
name = "duplex_pair"
bearing = "7020C"
preload_force = "1 kN"
[grid]
"assembly.arrangement" = ["DB", "DT"]
"""
    rows = run_scene(parse_scene(text), write=False).rows
    assert [r.get("error") for r in rows] == [None, None]
    for row in rows:
        alone = parse_scene(text.replace('[grid]\n"assembly.arrangement" = ["DB", "DT"]',
                                         f'arrangement = "{row["arrangement"]}"'))
        [single] = run_scene(alone, write=False).rows
        for mode in ("radial x", "axial", "tilt about x"):
            assert row[mode] == pytest.approx(single[mode], rel=1e-9), (row["arrangement"], mode)
    assert rows[0]["tilt about x"] != pytest.approx(rows[1]["tilt about x"], rel=1e-3)


def test_a_statics_grid_is_drawn_along_its_load_with_the_iso_76_limit():
    """A statics scene with a grid drew one bar per point labelled 1, 2, 3 ... "load case"
    (the values of its keys nowhere); it is now drawn as a steady grid is: against its first
    load that varies, one curve per value of the others, the contact pressure with ISO 76's
    limit of the assembly."""
    from bearingsim.scenes.analysis_figures import analysis_figures
    from bearingsim.scenes.analysis_table import analysis_units

    run = run_scene(parse_scene("""
title = "6304 over load"
analysis = "statics"
[assembly]
name = "deep_groove_ball_bearing"
bearing = "6304"
fidelity = "quasi-static"
[inputs]
shaft_speed = "3000 rpm"
[grid]
"inputs.load.Fx" = ["0.5 kN", "2 kN", "5 kN"]
"inputs.load.Fz" = [0.0, 1000.0]
"""), write=False)
    [(name, fig)] = analysis_figures(run.prepared, run.rows, run.summary["keys"],
                                     analysis_units(run.prepared, run.rows))
    life, ball, pressure = fig.axes
    assert name == "statics" and not pressure.patches  # curves, no bars
    curves = [line for line in ball.get_lines() if len(line.get_xdata()) == 3]
    assert len(curves) == 2  # one per axial load, along the radial one (the first key)
    np.testing.assert_allclose(curves[0].get_xdata(), [0.5, 2.0, 5.0])  # [kN]
    np.testing.assert_allclose(curves[0].get_ydata(),
                               [r["Q_max"] / 1e3 for r in run.rows if r["load.Fz"] == 0.0])
    limit = [line for line in pressure.get_lines() if len(line.get_xdata()) == 2]
    assert [line.get_ydata()[0] for line in limit] == [pytest.approx(4200.0)]
    assert life.get_yscale() == "log"


def test_a_nested_bearing_without_load_is_a_point_without_an_answer():
    """The double layer's load sharing at zero load: nothing seats the balls of a bearing with
    clearance, and its solver refuses the point (a ParameterError). That stopped the whole
    statics scene, every other point lost; now that point's row says why."""
    run = run_scene(parse_scene("""
title = "load sharing"
analysis = "statics"
[assembly]
name = "double_layer_bearing"
fidelity = "quasi-static"
[grid]
"inputs.shaft.Fx" = [0.0, 500.0]
"""), write=False)
    assert "needs an axial load" in run.rows[0]["error"]
    assert "error" not in run.rows[1] and run.rows[1]["Q_max_inner"] > 100.0


def test_a_steady_scene_starts_its_solve_from_its_initial_values(monkeypatch):
    """A steady or modes scene checked its [initial] state names and then solved from the
    model's own start values: the start it gave (to reach another equilibrium, or to help a
    hard one converge) was left unused. Its first point now starts there; the steady Rs is
    the same (it is unique), reached from the given middle-ring speed."""
    import bearingsim.simulation as simulation

    text = ('analysis = "steady"\noutputs = ["Rs"]\n[assembly]\nname = "double_layer_bearing"\n'
            '[inputs]\nshaft_speed = "1000 rpm"\n')
    plain = run_scene(parse_scene(text), write=False).rows[0]["Rs"]
    guesses = []
    solve = simulation.steady_state

    def spy(system, **kwargs):
        guesses.append((system.state_names, np.array(kwargs.get("x_guess"))))
        return solve(system, **kwargs)

    monkeypatch.setattr(simulation, "steady_state", spy)
    row = run_scene(parse_scene(text + '[initial]\n"middle.sleeve.w" = "200 rpm"\n'),
                    write=False).rows[0]
    names, guess = guesses[0]
    assert guess[names.index("middle.sleeve.w")] == pytest.approx(rpm_to_rad_s(200), rel=1e-15)
    assert row["Rs"] == pytest.approx(plain, rel=1e-9)
