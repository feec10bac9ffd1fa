"""Axisymmetric reduction (issue 8): under a pure axial load one representative ball per row
gives the same answer as the full row, and the scene layer chooses and reports it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import duplex_pair
from bearingsim.scenes import run_scene
from bearingsim.scenes.preparation import prepare
from bearingsim.scenes.scene import load_scene, parse_scene
from bearingsim.simulation import simulate

OUTPUTS = ["shaft.z", "row[0].Q_i[0]", "row[1].Q_i[5]", "row[0].alpha_i[0]"]
SCENES = Path(__file__).resolve().parents[2] / "scenes"


@pytest.fixture(scope="module")
def results():
    out = {}
    for axisymmetric in (False, True):
        system = assemble(duplex_pair("7020C", "DB", preload="medium",
                                      axisymmetric=axisymmetric), outputs=OUTPUTS)
        out[axisymmetric] = (system, simulate(system, 0.005, inputs={"shaft.Fz": 1500.0},
                                              rtol=1e-10, atol=1e-15, n_points=51))
    return out


def test_representative_ball_matches_the_full_row(results):
    full, reduced = results[False][1], results[True][1]
    for name in OUTPUTS:
        scale = np.max(np.abs(full[name]))
        np.testing.assert_allclose(reduced[name], full[name], atol=1e-7 * scale)


def test_reduced_model_is_smaller(results):
    assert results[True][0].n_states < results[False][0].n_states


def test_scene_with_pure_axial_load_uses_and_reports_the_reduction():
    prep = prepare(load_scene(SCENES / "duplex_pair_pure_axial.toml"))
    assert prep.args["axisymmetric"] is True
    assert any("representative ball" in note for note in prep.symmetry)


def test_scene_with_radial_load_keeps_every_ball():
    text = (SCENES / "duplex_pair_pure_axial.toml").read_text().replace(
        '"shaft.Fz" = "3000 * step(0.002)"', '"shaft.Fz" = 3000.0\n"shaft.Fx" = 500.0')
    prep = prepare(parse_scene(text))
    assert not prep.args.get("axisymmetric")
    assert not prep.symmetry


def test_steady_analysis_under_a_pure_axial_load_solves_the_full_pair():
    """A steady scene of a preloaded pair with no radial load ran the axisymmetric reduction,
    whose representative balls carry no radial load: its radial state had no stiffness, and
    every point failed ("steady state not unique: no derivative depends on shaft.vx"). The
    steady analysis keeps every ball, as modes do; its axial displacement is the settled end
    of a damped run in time under the same preload (the reduced model, as a transient runs)."""
    steady = parse_scene("""
analysis = "steady"
outputs = ["shaft.x", "shaft.z", "shaft.ty"]
[assembly]
name = "duplex_pair"
bearing = "7014C"
arrangement = "DB"
damping_ratio = 0.3
[grid]
"assembly.preload_force" = ["200 N", "1 kN"]
""")
    prep = prepare(steady)
    assert not prep.args.get("axisymmetric") and not prep.symmetry
    rows = run_scene(steady, write=False).rows
    transient = parse_scene(
        "outputs = [\"shaft.z\"]\n[assembly]\nname = \"duplex_pair\"\nbearing = \"7014C\"\n"
        "arrangement = \"DB\"\ndamping_ratio = 0.3\npreload_force = 1000.0\n"
        "[simulation]\nt_end = 0.05\nrtol = 1e-9\natol = 1e-14\nmethod = \"LSODA\"\n")
    assert prepare(transient).args["axisymmetric"] is True
    settled = run_scene(transient, write=False).summary["outputs"]["shaft.z"]["final"]
    assert [row["preload_force"] for row in rows] == [200.0, 1000.0]
    assert all(abs(row["shaft.x"]) < 1e-12 and abs(row["shaft.ty"]) < 1e-12 for row in rows)
    assert rows[1]["shaft.z"] == pytest.approx(settled, rel=1e-6)
    assert rows[0]["shaft.z"] != pytest.approx(rows[1]["shaft.z"], rel=1e-3)
