"""Lubricants as plug-ins: the registry (register_lubricant), the one converter (as_lubricant)
and the properties that replace duck typing (is_viscous, contact_friction)."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.errors import CatalogError, ParameterError
from bearingsim.physics.lubricant import (
    Dry,
    Grease,
    Lubricant,
    Oil,
    as_lubricant,
    get_lubricant,
    known_lubricants,
    register_lubricant,
    unregister_lubricant,
)
from bearingsim.studies.double_layer import steady_ratio


def _spindle_oil(**kw):
    # 10 mm^2/s at 40 degC, 2.7 mm^2/s at 100 degC: a light spindle oil
    return Oil(10.0, 40.0, 2.7, 100.0, **{"name": "spindle oil 10", **kw})


@pytest.fixture
def spindle_oil():
    register_lubricant("spindle oil 10", _spindle_oil)
    yield "spindle oil 10"
    unregister_lubricant("spindle oil 10")


def test_a_registered_lubricant_is_known_everywhere(spindle_oil, capsys):
    from bearingsim.cli import main

    assert spindle_oil in known_lubricants()
    oil = get_lubricant("Spindle_Oil-10", temperature=343.15)  # names match loosely
    assert oil.name == "spindle oil 10" and oil.temperature == 343.15
    assert as_lubricant(spindle_oil).kinematic_viscosity(313.15) == pytest.approx(10e-6)
    main(["list"])
    assert "spindle oil 10" in capsys.readouterr().out


def test_a_registered_lubricant_drives_an_assembly_and_a_scene(spindle_oil):
    from bearingsim.scenes import parse_scene

    light = double_layer_bearing("61905", "61907", lubrication=spindle_oil)
    heavy = double_layer_bearing("61905", "61907", lubrication="ISO VG 68")
    rs = [steady_ratio(assemble(b), 1000.0, loads=(200.0, 0.0))[0] for b in (light, heavy)]
    assert rs[0] != pytest.approx(rs[1], rel=1e-3)  # the viscosity reaches the friction torque
    scene = parse_scene(f"""
[assembly]
name = "double_layer_bearing"
inner = "61905"
outer = "61907"
lubrication = "{spindle_oil}"
[inputs]
shaft_speed = 100.0
[simulation]
t_end = 0.1
""", None)
    assert scene.args["lubrication"] == spindle_oil


def test_registration_errors_are_named(spindle_oil):
    with pytest.raises(ParameterError, match="already registered"):
        register_lubricant("SPINDLE OIL 10", _spindle_oil)
    register_lubricant("spindle oil 10", _spindle_oil, replace=True)
    with pytest.raises(ParameterError, match="callable"):
        register_lubricant("x", 3.0)
    with pytest.raises(ParameterError, match="non-empty"):
        register_lubricant(" - ", _spindle_oil)
    with pytest.raises(CatalogError, match="unknown lubricant 'nothing'"):
        unregister_lubricant("nothing")
    # the factory's lubricant is checked when it is registered (not when it is first used)
    with pytest.raises(ParameterError, match="must be a Lubricant .*got int"):
        register_lubricant("not a lubricant", lambda **kw: 42)
    assert "not a lubricant" not in known_lubricants()


def test_as_lubricant_takes_objects_and_names_and_nothing_else():
    oil = Oil.from_iso_vg(32)
    assert as_lubricant(oil) is oil
    assert isinstance(as_lubricant("lithium grease"), Grease)
    with pytest.raises(CatalogError, match="known: ISO VG 10"):
        as_lubricant("ISO VG 33")
    with pytest.raises(ParameterError, match="my_bearing: a lubricant must be"):
        as_lubricant(32, "my_bearing")


def test_viscosity_and_contact_friction_are_properties():
    assert Oil.from_iso_vg(32).is_viscous and get_lubricant("lithium grease").is_viscous
    dry = Dry(mu=0.25)
    assert not dry.is_viscous
    assert dry.contact_friction == 0.25 and Oil.from_iso_vg(32).contact_friction == 0.1
    assert issubclass(Dry, Lubricant)
    assert np.isfinite(Oil.from_iso_vg(32).dynamic_viscosity())
