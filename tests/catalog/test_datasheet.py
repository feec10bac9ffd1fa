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


def test_the_registered_bearings_are_listed_for_other_processes(registered):
    """What a sweep ships to its workers (:meth:`Registry.registered`): the bearings registered
    in this process, not the catalogue's; an unregistered one leaves the list."""
    from bearingsim.catalog import BEARINGS
    from bearingsim.scenes.sweep_worker import registrations, restore_registrations

    shipped = registrations()
    assert "MY6005" in shipped["bearing"] and "6304" not in shipped["bearing"]
    geometry = shipped["bearing"]["MY6005"]
    unregister_bearing("MY6005")
    assert "MY6005" not in BEARINGS.registered() and "MY6005" not in list_bearings()
    restore_registrations(shipped)  # as a worker does
    assert get_bearing("my6005") is geometry
    restore_registrations(shipped)  # again: the same entry, nothing replaced
    assert BEARINGS.registered()["MY6005"] is geometry
