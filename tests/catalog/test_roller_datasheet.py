"""Cylindrical roller bearings from a user's datasheet: a bearing with an effective roller
length ``Lwe_mm`` is an NU bearing, registered in the roller catalogue's registry
(``ROLLER_BEARINGS``, the one registry pattern of the ball bearings and lubricants). Before, a
datasheet knew ball bearings only, and a scene could not use a roller bearing the 18-row
catalogue lacks."""

from __future__ import annotations

import pytest

import bearingsim.assemblies.cylindrical_roller.scene  # noqa: F401 - its specs made first
from bearingsim.catalog import load_datasheet
from bearingsim.catalog.datasheet import read_datasheet
from bearingsim.catalog.rollers import (
    ROLLER_BEARINGS,
    RollerBearingGeometry,
    get_roller_bearing,
    list_roller_bearings,
    unregister_roller_bearing,
)
from bearingsim.errors import CatalogError
from tests.catalog.datasheets import NU206_AS_MINE


@pytest.fixture
def mine(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text(NU206_AS_MINE)
    names = load_datasheet(path)
    yield path, names
    for name in names:
        if name in ROLLER_BEARINGS.registered():
            unregister_roller_bearing(name)


def test_a_datasheet_roller_is_the_catalogues_bearing_of_the_same_numbers(mine):
    path, names = mine
    assert names == ["MYNU206"] and "MYNU206" in list_roller_bearings()
    g, catalogue = get_roller_bearing("my nu 206"), get_roller_bearing("NU206")
    assert isinstance(g, RollerBearingGeometry) and g.source == "datasheet mine.toml"
    for field in ("bore", "outside_diameter", "width", "pitch_diameter", "roller_count",
                  "roller_diameter", "roller_length", "diametral_clearance",
                  "dynamic_load_rating", "static_load_rating", "fatigue_load_limit",
                  "limiting_speed", "explorer"):
        assert getattr(g, field) == pytest.approx(getattr(catalogue, field), rel=1e-12), field
    with pytest.raises(CatalogError, match="catalogue bearing"):  # never replaced
        ROLLER_BEARINGS.register("NU206", g, replace=True)
    unregister_roller_bearing("MY NU206")
    assert "MYNU206" not in list_roller_bearings()
    with pytest.raises(CatalogError, match="not a registered cylindrical roller bearing"):
        unregister_roller_bearing("NU206")


def test_a_scene_runs_its_own_roller_bearing_as_the_catalogues(mine):
    from bearingsim.scenes import parse_scene, run_scene

    path, _ = mine
    scene = path.with_name("scene.toml")
    text = ('title = "NU"\nanalysis = "statics"\nbearings = "mine.toml"\n[assembly]\n'
            'name = "cylindrical_roller_bearing"\nbearing = "{b}"\nfidelity = "quasi-static"\n'
            '[inputs]\n"load.Fx" = "5 kN"\n')
    scene.write_text(text.format(b="my nu206"))
    own = parse_scene(scene.read_text(), str(scene))
    assert own.args["bearing"] == "MYNU206"  # spelled as registered
    [row] = run_scene(own, write=False).rows
    [catalogue] = run_scene(parse_scene(text.format(b="NU206").replace(
        'bearings = "mine.toml"\n', "")), write=False).rows
    for column in ("Q_max", "p_max", "x", "k_radial", "L10r"):
        assert row[column] == pytest.approx(catalogue[column], rel=1e-12), column


@pytest.mark.parametrize(("change", "match"), [
    (("Pu_kN = 4.55", "fi = 0.5"), r"unknown key\(s\) fi; keys of a roller bearing"),
    (("Dw_mm = 9.0\n", ""), r"missing Dw_mm \(mm, roller bearings\)"),
    (("Lwe_mm = 9.52", "Lwe_mm = 'long'"), "Lwe_mm is not a number"),
    (("dm_mm = 46.5", "dm_mm = 80"), "MY NU206"),  # rollers outside the rings: named
])
def test_bad_roller_entries_are_named(tmp_path, change, match):
    path = tmp_path / "bad.toml"
    path.write_text(NU206_AS_MINE.replace(*change))
    with pytest.raises(CatalogError, match=match):
        read_datasheet(path)


def test_a_misspelt_designation_lists_the_registered_rollers_too(mine):
    """The scene's message listed the roller catalogue as it was when the assembly was
    registered (a tuple made at import): a bearing of the scene's datasheet was accepted but
    never listed."""
    from bearingsim.scenes import parse_scene
    from bearingsim.scenes.scene import SceneError

    path, _ = mine
    scene = path.with_name("scene.toml")
    scene.write_text('bearings = "mine.toml"\n[assembly]\nname = "cylindrical_roller_bearing"\n'
                     'bearing = "MY NU 207"\n[simulation]\nt_end = 0.1\n')
    with pytest.raises(SceneError, match=r"unknown bearing designation 'MY NU 207'; allowed: "
                                         r"NU204, .*NU312, MYNU206"):
        parse_scene(scene.read_text(), str(scene))


def test_register_bearing_takes_a_roller_bearing_as_its_docstring_says():
    """register_bearing's docstring took a RollerBearingGeometry; the function refused one
    ("expected a BearingGeometry"). It registers it in the roller catalogue's registry."""
    import dataclasses

    from bearingsim.catalog import register_bearing

    mine = dataclasses.replace(get_roller_bearing("NU206"), designation="NU206 B")
    assert register_bearing(mine) is mine
    try:
        assert get_roller_bearing("nu 206 b") is mine
    finally:
        unregister_roller_bearing("NU206B")
