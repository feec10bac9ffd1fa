"""User bearings from a datasheet (issue 16 item 6): CSV or TOML in catalogue units, registered
so that assemblies, scenes and bearingsim list accept the designation."""

from __future__ import annotations

import textwrap

import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import deep_groove_ball_bearing
from bearingsim.catalog import (
    datasheet,
    get_bearing,
    list_bearings,
    load_datasheet,
    register_bearing,
    unregister_bearing,
)
from bearingsim.catalog.datasheet import read_datasheet
from bearingsim.errors import CatalogError

TOML = textwrap.dedent(datasheet.__doc__.split("::\n", 1)[1].split("\n\n", 1)[0])
"""The example of the module docstring (so the documented example is the one tested)."""

CSV = """designation,d_mm,D_mm,B_mm,Z,Dw_mm,dm_mm,alpha_deg
MY7005,25,47,12,14,5.556,36,15
"""


@pytest.fixture
def registered(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text(TOML)
    names = load_datasheet(path)
    yield names
    for name in names:
        unregister_bearing(name)


def test_toml_datasheet_in_catalogue_units(registered):
    assert registered == ["MY6005"] and "MY6005" in list_bearings()
    g = get_bearing("my6005")
    assert (g.bore, g.ball_diameter, g.diametral_clearance) == pytest.approx(
        (0.025, 6.35e-3, 12e-6))
    assert g.dynamic_load_rating == pytest.approx(11200.0)
    assert g.limiting_speed == pytest.approx(19000 * 3.141592653589793 / 30)
    assert set(g.estimated) == {"fi", "fo", "alpha_deg"} and "mine.toml" in g.source
    system = assemble(deep_groove_ball_bearing("MY6005", "quasi-static", loads={"Fx": 500.0}))
    assert system.n_states >= 0


def test_csv_datasheet_and_the_angular_contact_defaults(tmp_path):
    path = tmp_path / "mine.csv"
    path.write_text(CSV)
    (g,) = read_datasheet(path)
    assert (g.fi, g.fo) == (0.525, 0.515) and g.contact_angle == pytest.approx(0.2617993878)


def test_a_scene_loads_its_datasheet(tmp_path):
    from bearingsim.scenes import parse_scene

    (tmp_path / "mine.toml").write_text(TOML)
    scene = tmp_path / "scene.toml"
    scene.write_text('bearings = "mine.toml"\n[assembly]\nname = "deep_groove_ball_bearing"\n'
                     'bearing = "MY6005"\nfidelity = "quasi-static"\n[simulation]\nt_end = 0.1\n')
    try:
        assert parse_scene(scene.read_text(), str(scene)).args["bearing"] == "MY6005"
    finally:
        unregister_bearing("MY6005")


@pytest.mark.parametrize(("text", "match"), [
    ("[[bearing]]\ndesignation = 'X'\nd_mm = 25\n", "missing D_mm, B_mm, Z, Dw_mm, dm_mm"),
    (TOML.replace("Pd_um", "clearance_um"), "unknown key"),
    (TOML.replace("d_mm = 25", "d_mm = 40"), "balls do not fit"),
    (TOML.replace("Z = 10", "Z = 'ten'"), "not a number"),
    ("", "no bearings"),
])
def test_bad_datasheets_are_named(tmp_path, text, match):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(CatalogError, match=match):
        read_datasheet(path)


def test_registration_does_not_shadow_the_catalogue(registered):
    with pytest.raises(CatalogError, match="catalogue bearing"):
        register_bearing(get_bearing("6304"))
    with pytest.raises(CatalogError, match="already registered"):
        register_bearing(get_bearing("MY6005"))


def test_a_sweep_ships_the_registered_bearings_its_points_name(registered, monkeypatch):
    """What a sweep ships to its workers: the bearings registered in this process that its
    scene and points name (:meth:`Registry.registered`), not the catalogue's; an unregistered
    one leaves the list; a worker registers what it gets."""
    import pickle

    from bearingsim.catalog import BEARINGS
    from bearingsim.scenes import sweep_worker
    from bearingsim.scenes.sweep_worker import registrations, restore_registrations

    assert registrations(["6304", "ISO VG 32"]) == b""  # catalogue names: nothing to ship
    shipped = registrations(["my6005", "6304"])
    assert pickle.loads(shipped) == {"bearing": {"MY6005": get_bearing("MY6005")},
                                     "process": sweep_worker.process_token()}
    unregister_bearing("MY6005")
    assert "MY6005" not in BEARINGS.registered() and "MY6005" not in list_bearings()
    monkeypatch.setattr(sweep_worker, "process_token", lambda: "a worker's process")
    restore_registrations(shipped)  # as a worker does
    assert get_bearing("my6005") == pickle.loads(shipped)["bearing"]["MY6005"]


def test_a_registration_the_sweep_does_not_name_stays_in_the_client():
    """A sweep shipped every registration of the client's process, the unrelated ones too:
    one the workers could not load (a lubricant whose factory lives in a module only the
    client can import, as a test's or a plug-in's in a temporary folder) stopped the sweep's
    model from reaching the workers, and the sweep waited for ever. Only the entries its
    points name travel now; one that cannot load fails its points with why."""
    import types

    from bearingsim.physics.lubricant import register_lubricant, unregister_lubricant
    from bearingsim.scenes.sweep_worker import registrations, restore_registrations

    module = types.ModuleType("client_only_oils")  # importable nowhere but here
    exec("from bearingsim.physics.lubricant import Oil\n"
         "def oil(**kw):\n    return Oil.from_iso_vg(46, name='client only oil')\n",
         module.__dict__)
    module.oil.__module__ = "client_only_oils"
    import sys

    sys.modules["client_only_oils"] = module
    register_lubricant("client only oil", module.oil)
    try:
        assert registrations(["ISO VG 32", "6304"]) == b""
        data = registrations(["client only oil"])
        del sys.modules["client_only_oils"]  # a worker, where that module is not
        with pytest.raises(RuntimeError, match="cannot be loaded in this worker: "
                                               "ModuleNotFoundError"):
            restore_registrations(data)
    finally:
        sys.modules.pop("client_only_oils", None)
        unregister_lubricant("client only oil")


def test_a_scene_runs_with_its_own_datasheet_whatever_was_read_since(tmp_path):
    """Two scenes whose datasheets define one designation differently (a dynamic load rating
    C of 11.2 kN in one folder, 5.6 kN in the other): a scene read first and run after the
    second was read ran with the second's bearing, and its life was the other bearing's. A
    scene now registers its own again when it is prepared; its life follows C^3 (ISO 281:
    half the rating, an eighth of the life)."""
    from bearingsim.scenes import load_scene, run_scene

    lives = {}
    for folder, rating in (("a", "11.2"), ("b", "5.6")):
        (tmp_path / folder).mkdir()
        (tmp_path / folder / "mine.toml").write_text(TOML.replace("C_kN = 11.2",
                                                                  f"C_kN = {rating}"))
        (tmp_path / folder / "scene.toml").write_text(
            'analysis = "statics"\nbearings = "mine.toml"\noutputs = ["L10h"]\n'
            '[assembly]\nname = "deep_groove_ball_bearing"\nbearing = "MY6005"\n'
            'fidelity = "quasi-static"\n[inputs]\n"load.Fx" = "1 kN"\n'
            'shaft_speed = "1000 rpm"\n')
    try:
        first = load_scene(tmp_path / "a" / "scene.toml")
        second = load_scene(tmp_path / "b" / "scene.toml")
        lives["b"] = run_scene(second, write=False).rows[0]["L10h"]
        lives["a"] = run_scene(first, write=False).rows[0]["L10h"]
        assert get_bearing("MY6005").dynamic_load_rating == pytest.approx(11200.0)
        copy = first.replace(title="a copy")  # through the scene's TOML form
        assert copy.bearings == ["mine.toml"]
        assert run_scene(copy, write=False).rows[0]["L10h"] == lives["a"]
    finally:
        unregister_bearing("MY6005")
    assert lives["a"] == pytest.approx(8.0 * lives["b"], rel=1e-9)
