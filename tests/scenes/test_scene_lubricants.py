"""A scene's ``[lubricants]`` table (bearingsim.scenes.lubricant_table): lubricants defined or
overridden by the scene, their temperature, and bad input named by key, line, unit and range."""

from __future__ import annotations

import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.physics.lubricant import (
    LUBRICANTS,
    Grease,
    Oil,
    get_lubricant,
    unregister_lubricant,
)
from bearingsim.scenes import parse_scene
from bearingsim.scenes.scene import SceneError
from bearingsim.studies.double_layer import steady_ratio

ASSEMBLY = """
[assembly]
name = "double_layer_bearing"
inner = "61905"
outer = "61907"
lubrication = "{lubricant}"
[inputs]
shaft_speed = 100.0
[simulation]
t_end = 0.1
"""


@pytest.fixture(autouse=True)
def lubricant_registry():
    """The registry as it was before the test (scenes register their lubricants globally)."""
    before = dict(LUBRICANTS.items())
    yield
    for name in [n for n in LUBRICANTS if n not in before]:
        unregister_lubricant(name)
    for name, factory in before.items():
        if LUBRICANTS[name] is not factory:
            LUBRICANTS.register(name, factory, replace=True)


def test_a_scene_defines_an_oil_by_grade_with_its_temperature():
    scene = parse_scene("""
[lubricants."hot VG 68"]
grade = 68
temperature = "60 degC"
mu_bl = 0.12
""" + ASSEMBLY.format(lubricant="hot VG 68"), None)
    assert scene.args["lubrication"] == "hot VG 68"
    oil = get_lubricant("hot VG 68")
    assert oil.temperature == pytest.approx(333.15) and oil.mu_bl == 0.12
    reference = Oil.from_iso_vg(68, temperature=333.15)
    assert oil.kinematic_viscosity() == pytest.approx(reference.kinematic_viscosity(), rel=1e-12)


def test_the_scene_temperature_reaches_the_friction_of_the_assembly():
    parse_scene("""
[lubricants."VG 68 at 80 degC"]
base = "ISO VG 68"
temperature = "80 degC"
""" + ASSEMBLY.format(lubricant="VG 68 at 80 degC"), None)
    hot = double_layer_bearing("61905", "61907", lubrication="VG 68 at 80 degC")
    cold = double_layer_bearing("61905", "61907", lubrication="ISO VG 68")
    rs = [steady_ratio(assemble(b), 1000.0, loads=(200.0, 0.0))[0] for b in (hot, cold)]
    assert rs[0] != pytest.approx(rs[1], rel=1e-3)


def test_a_scene_overrides_the_temperature_of_a_known_lubricant():
    parse_scene("""
[lubricants."lithium grease"]
temperature = 343.15
fill_fraction = 0.5
""" + ASSEMBLY.format(lubricant="lithium grease"), None)
    grease = get_lubricant("lithium grease")
    assert isinstance(grease, Grease)
    assert grease.temperature == 343.15 and grease.fill_fraction == 0.5
    assert get_lubricant("lithium grease", temperature=300.0).temperature == 300.0


def test_a_scene_defines_an_oil_by_two_viscosities_and_a_grease_of_it():
    parse_scene("""
[lubricants."spindle oil"]
nu40 = "10 mm^2/s"
nu100 = "2.7 mm^2/s"
method = "oil_jet"
[lubricants."spindle grease"]
nu40 = "10 mm^2/s"
nu100 = "2.7 mm^2/s"
fill_fraction = 0.25
""" + ASSEMBLY.format(lubricant="spindle oil"), None)
    oil = get_lubricant("spindle oil")
    assert oil.kinematic_viscosity(313.15) == pytest.approx(10e-6, rel=1e-9)
    assert oil.method == "oil_jet"
    grease = get_lubricant("spindle grease", temperature=320.0)
    assert isinstance(grease, Grease) and grease.fill_fraction == 0.25
    assert grease.base_oil.kinematic_viscosity(373.15) == pytest.approx(2.7e-6, rel=1e-9)
    assert grease.temperature == 320.0 and grease.method == "grease"


@pytest.mark.parametrize(("table", "message"), [
    ('[lubricants."x"]\ngrade = 68\nmu_bl = 5.0\n',
     r"bad.toml:1: lubricants.x: Oil 'x': mu_bl = 5.0 \[-\] is outside the valid range \[0, 1\]"),
    ('[lubricants."x"]\ngrade = 68\ntemperature = "60 N"\n',
     r"lubricants.x: lubricants.x.temperature: 'N' is not a unit of K"),
    ('[lubricants."x"]\nbase = "ISO VG 86"\n',
     r"unknown lubricant 'ISO VG 86'.*did you mean 'ISO VG 68'"),
    ('[lubricants."x"]\ngrade = 68\nnu40 = "10 mm^2/s"\n', r"give grade or nu40 and nu100"),
    ('[lubricants."x"]\nnu40 = "10 mm^2/s"\n',  # before: "lubricants.x: lubricants.x: a new"
     r"bad.toml:1: lubricants.x: a new oil needs grade, or nu40 and nu100"),
    # before: named by the Oil's nu1_cst and nu2_cst, which the table does not have
    ('[lubricants."x"]\nnu40 = "10 mm^2/s"\nnu100 = "20 mm^2/s"\n',
     r"lubricants.x: Oil 'x': nu100 = 20.0 \[mm\^2/s\] is outside the valid range \(0, 10\)"),
    ('[lubricants."x"]\nnu40 = -3\nnu100 = 2\n', r"lubricants.x: Oil 'x': nu40 = -3000000.0 "),
    ('[lubricants."x"]\ngrade = 68\nviscosity = 3\n', r"unknown key 'viscosity'; give base"),
    ('[lubricants]\nx = 3\n', r"lubricants.x: must be a table"),
    ('[lubricants."x"]\nbase = "lithium grease"\nmu_bl = 0.1\n',
     r"\['mu_bl'\] do not all apply to 'lithium grease'"),
    ('[lubricants."x"]\ngrade = 33\n', r"unknown ISO VG grade 33"),
])
def test_bad_lubricant_tables_are_named(table, message):
    with pytest.raises(SceneError, match=message):
        parse_scene(table + ASSEMBLY.format(lubricant="ISO VG 68"), "bad.toml")
    assert "x" not in LUBRICANTS


def test_a_lubricant_the_scene_does_not_define_stays_unknown():
    with pytest.raises(SceneError, match=r"unknown lubricant 'hot oil'"):
        parse_scene(ASSEMBLY.format(lubricant="hot oil"), None)
