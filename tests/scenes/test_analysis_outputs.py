"""``outputs`` of a statics or modes scene name the columns of its solution: before, they were
checked against the model's variables (``Q_max`` refused as an unknown output) and a model
variable that passed (``row.Q_i[0]``) was then left out of the table without a word."""

from __future__ import annotations

import pytest

from bearingsim.scenes import parse_scene, run_scene
from bearingsim.scenes.preparation import validate_scene
from bearingsim.scenes.scene import SceneError

STATICS = """
analysis = "statics"
{outputs}
[assembly]
name = "deep_groove_ball_bearing"
bearing = "6304"
fidelity = "quasi-static"
[[cases]]
name = "low speed, high load"
"inputs.shaft_speed" = "1730 rpm"
"inputs.load.Fx" = 938.0
[[cases]]
name = "at rest"
"inputs.shaft_speed" = 0.0
"inputs.load.Fx" = 206.0
"""

MODES = """
analysis = "modes"
{outputs}
[assembly]
name = "duplex_pair"
bearing = "7020C"
arrangement = "DF"
[grid]
"assembly.preload_force" = [500.0, 2000.0]
"""


def _rows(text: str, outputs: str = "", **kwargs):
    return run_scene(parse_scene(text.format(outputs=outputs)), write=False, **kwargs).rows


def test_a_statics_scene_keeps_the_columns_its_outputs_name_in_their_order():
    every = _rows(STATICS)
    chosen = _rows(STATICS, 'outputs = ["L10h", "k_radial", "Q_max"]')
    for full, row in zip(every, chosen, strict=True):
        assert list(row) == ["name", "shaft_speed", "load.Fx", "L10h", "k_radial", "Q_max"]
        assert row == {n: full[n] for n in row}
    assert chosen[1]["L10h"] == "not defined at zero speed"


def test_a_statics_scene_refuses_outputs_that_are_not_its_columns():
    with pytest.raises(SceneError, match=r"outputs: a statics scene's outputs are its statics "
                                         r"columns, not model variables: unknown statics column "
                                         r"'row\.Q_i\[0\]'; allowed: Q_max, p_max, x, y, z, "
                                         r"k_radial, k_axial, L10r, L10h"):
        validate_scene(parse_scene(STATICS.format(outputs='outputs = ["row.Q_i[0]"]')))


def test_a_statics_figure_draws_the_chosen_columns_and_none_for_text_alone(tmp_path):
    """outputs = ["L10h"] with a case at rest: no number to draw in every case (the life in
    hours at rest is text, the life in revolutions not chosen), so no statics figure rather
    than a figure of no panels or a crash; with Q_max chosen too, its panel alone."""
    scene = parse_scene(STATICS.format(outputs='outputs = ["L10h"]'))
    run_scene(scene, out=tmp_path / "life")
    assert (tmp_path / "life" / "deep_groove_ball_bearing.csv").is_file()
    assert not list((tmp_path / "life").glob("*.statics.png"))
    scene = parse_scene(STATICS.format(outputs='outputs = ["L10h", "Q_max"]'))
    run_scene(scene, out=tmp_path / "load")
    assert len(list((tmp_path / "load").glob("*.statics.png"))) == 1


def test_a_modes_scene_keeps_the_modes_its_outputs_name():
    every = _rows(MODES)
    chosen = _rows(MODES, 'outputs = ["axial", "radial x"]')
    for full, row in zip(every, chosen, strict=True):
        assert list(row) == ["preload_force", "axial", "radial x"]
        assert row == {n: full[n] for n in row}
    assert chosen[1]["axial"] > chosen[0]["axial"] > 0.0  # stiffer with more preload


def test_a_modes_scene_refuses_a_mode_the_assembly_does_not_name():
    with pytest.raises(SceneError, match=r"unknown mode 'radial z'; allowed: radial x, radial y, "
                                         r"axial, tilt about x, tilt about y"):
        validate_scene(parse_scene(MODES.format(outputs='outputs = ["radial z"]')))
    nested = parse_scene("""
analysis = "modes"
outputs = ["axial"]
[assembly]
name = "double_layer_bearing"
[inputs]
shaft_speed = "1000 rpm"
""")
    with pytest.raises(SceneError, match=r"a modes scene of double_layer_bearing cannot select "
                                         r"modes by name"):
        validate_scene(nested)


def test_validate_lists_what_the_outputs_of_a_statics_or_modes_scene_name(tmp_path, capsys):
    """``bearingsim validate --variables`` of a statics scene listed the model's variables
    only, none of which its outputs could name; validate of a modes scene said "outputs" and
    the model's default outputs, which its table does not have."""
    from bearingsim.cli import main

    statics = tmp_path / "statics.toml"
    statics.write_text(STATICS.format(outputs=""))
    assert main(["validate", "--variables", str(statics)]) == 0
    text = capsys.readouterr().out
    assert text.startswith("statics columns (this scene's outputs name these):\n"
                           "  Q_max [N]: largest ball load\n")
    assert "  L10h [h]: " in text
    modes = tmp_path / "modes.toml"
    modes.write_text(MODES.format(outputs='outputs = ["axial", "radial x"]'))
    assert main(["validate", str(modes)]) == 0
    assert "10 states; modes axial, radial x\n" in capsys.readouterr().out
    assert main(["validate", "--variables", str(modes)]) == 0
    assert ("modes columns (this scene's outputs name these):\n  radial x [Hz]: natural "
            "frequency of the radial x mode\n") in capsys.readouterr().out
