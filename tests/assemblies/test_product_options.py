"""The products' typed options: built from the factories' keywords or directly, checked once,
the classes built from them.

Deep-groove (:class:`DeepGrooveOptions` and its groups), double-layer
(:class:`DoubleLayerOptions`, :class:`DynamicDoubleLayerOptions`) and duplex
(:class:`DuplexOptions`).
"""

from __future__ import annotations

import dataclasses

import pytest

from bearingsim.assemblies.deep_groove import (
    FILM_DAMPING,
    CageOptions,
    DeepGrooveBallBearing,
    DeepGrooveOptions,
    FilmOptions,
    RingOptions,
    deep_groove_ball_bearing,
)
from bearingsim.assemblies.double_layer import (
    DoubleLayerBearing,
    DoubleLayerOptions,
    DynamicDoubleLayerOptions,
    LayerPairOptions,
    double_layer_bearing,
)
from bearingsim.assemblies.duplex import (
    DuplexOptions,
    DuplexPair,
    duplex_pair,
    preload_force,
    preload_offset,
)
from bearingsim.errors import ParameterError
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.physics.lubricant import Dry, get_lubricant

LOADS = {"Fx": 500.0, "Fz": 100.0}


# --------------------------------------------------------------------------- deep groove
def test_deep_groove_keywords_sort_into_the_option_groups():
    options = DeepGrooveOptions.from_keywords(loads=LOADS, drive="flange", n_slices=0,
                                              cage_damping=20.0, free_tilt=True)
    assert options == DeepGrooveOptions(loads=LOADS,
                                        rings=RingOptions(drive="flange", free_tilt=True),
                                        film=FilmOptions(n_slices=0),
                                        cage=CageOptions(cage_damping=20.0))
    assert set(DeepGrooveOptions.keyword_names()) == {
        f.name for group in (RingOptions, FilmOptions, CageOptions)
        for f in dataclasses.fields(group)}


def test_deep_groove_options_refuse_unknown_keywords_wrong_groups_and_flags():
    with pytest.raises(ParameterError, match=r"deep_groove_ball_bearing: unknown option\(s\) "
                                             r"'bogus'; accepted: drive, .*cage_damping"):
        DeepGrooveOptions.from_keywords(bogus=1)
    with pytest.raises(ParameterError, match="rings must be a RingOptions, got dict"):
        DeepGrooveOptions(rings={"drive": "flange"})
    with pytest.raises(ParameterError, match="massive_balls must be True or False"):
        DeepGrooveOptions(massive_balls="yes")
    with pytest.raises(ParameterError, match="outer_start must be"):
        RingOptions(outer_support="frame", outer_start=(0.0, 1e-6))
    with pytest.raises(ParameterError, match=r"options must be a DeepGrooveOptions"):
        DeepGrooveBallBearing(bearing_design("6304"), get_lubricant("ISO VG 32"),
                              {"n_slices": 0})
    with pytest.raises(dataclasses.FrozenInstanceError):
        DeepGrooveOptions().speed = 1.0


def test_deep_groove_factory_and_class_build_the_same_options_with_the_lubricant_defaults():
    oil = get_lubricant("ISO VG 32")
    direct = DeepGrooveBallBearing(bearing_design("6304"), oil, DeepGrooveOptions(
        massive_balls=True, speed=300.0, loads=LOADS, film=FilmOptions(n_slices=0)))
    built = deep_groove_ball_bearing("6304", "dynamic_massive_balls", oil, speed=300.0,
                                     loads=LOADS, n_slices=0)
    assert built.options == direct.options
    assert direct.options.film.film_damping == FILM_DAMPING and direct.options.film.drag
    assert direct.options.cage.pocket_mu == direct.options.cage.land_mu == 0.1
    assert len(direct.drag) == len(direct.ball) == 7
    dry = DeepGrooveBallBearing(bearing_design("6304"), Dry(0.05), DeepGrooveOptions(
        loads=LOADS, cage=CageOptions(land_mu=0.3)))
    assert dry.options.film.film_damping == 0.0 and dry.options.film.drag is False
    assert (dry.options.cage.pocket_mu, dry.options.cage.land_mu) == (0.05, 0.3)
    assert not hasattr(dry, "drag")


# --------------------------------------------------------------------------- double layer
def test_double_layer_options_resolve_the_pair_and_each_layer():
    options = DoubleLayerOptions(friction_model="skf", oil_level=0.0)
    assert options.structure == "Z"
    assert [g.designation for g in options.geometries] == ["61905", "61907"]
    inner, outer = options.layer_options_each
    assert "oil_level" not in inner and outer["oil_level"] == 0.0   # inner layer above the oil
    bearing = DoubleLayerBearing(options)
    assert bearing.options is options and bearing.structure == "Z"
    assert double_layer_bearing(friction_model="skf", oil_level=0.0).options == options
    assert LayerPairOptions().structure == "Z"   # the shared base resolves on its own too
    with pytest.raises(ParameterError, match="built by double_layer_bearing"):
        DoubleLayerOptions(fidelity="quasi-static")
    with pytest.raises(ParameterError, match="options must be a DoubleLayerOptions"):
        DoubleLayerBearing(DynamicDoubleLayerOptions())


def test_dynamic_double_layer_options_share_one_checked_layer_template():
    options = DynamicDoubleLayerOptions(loads={"Fz": 100.0}, layer_options={"n_slices": 0})
    layer = options.layer
    assert (layer.massive_balls, layer.film.drag, layer.rings.drive) == (True, False, "flange")
    assert layer.film.n_slices == 0 and layer.film.rolling_resistance and layer.film.ring_drag
    inner = options.for_layer({"Fz": 100.0}, outer_support="frame", outer_start=(0, 0, 1e-6))
    assert inner.rings.outer_start == (0.0, 0.0, 1e-6) and inner.film == layer.film
    with pytest.raises(ParameterError, match=r"deep_groove_ball_bearing: damping = -1.0"):
        DynamicDoubleLayerOptions(layer_options={"damping": -1.0})
    with pytest.raises(ParameterError, match="layer_options may not set 'drive'"):
        DynamicDoubleLayerOptions(layer_options={"drive": "speed"})
    nested = double_layer_bearing(fidelity="dynamic", loads={"Fz": 100.0},
                                  layer_options={"n_slices": 0})
    assert nested.options == options
    assert nested.inner_layer.options.film.n_slices == 0


# --------------------------------------------------------------------------- duplex
def test_duplex_options_derive_the_preload_and_speed_effects():
    options = DuplexOptions("7020C", "DB", preload="medium", speed=100.0)
    assert options.preload_force == preload_force(options.geometry, "medium") == pytest.approx(
        1270.0, abs=0.5)
    assert options.spacer_width_difference == pytest.approx(
        preload_offset("7020C", options.preload_force, "DB"))
    assert options.speed_effects is True
    assert DuplexOptions("7020C", "DT", spacer_offset=2e-6).spacer_width_difference == 2e-6
    pair = DuplexPair(options)
    assert pair.options is options and pair.preload == "medium"
    assert duplex_pair("7020C", "DB", "medium", 100.0).options == options


def test_duplex_pair_refuses_unknown_keywords_by_name():
    # an unknown keyword was a bare TypeError of DuplexPair.__init__
    with pytest.raises(ParameterError, match=r"duplex_pair: unknown option\(s\) 'dampng_ratio'"
                                             r".*accepted: .*damping_ratio"):
        duplex_pair("7020C", dampng_ratio=0.1)
    with pytest.raises(ParameterError, match="exact must be True or False"):
        DuplexOptions(exact="yes")


def test_a_misnamed_argument_is_named_with_the_arguments_listed():
    """``duplex_pair(preload_force=800)`` (the scene's name of the preload in N) was refused
    with a list of the other options only ("accepted: contact_angle, spacer_offset, ..."),
    which has no preload in it: the function's own arguments are listed too, and a near miss
    of an option or an argument is named."""
    with pytest.raises(ParameterError) as err:
        duplex_pair("7020C", preload_force=800.0)
    text = str(err.value)
    assert text.startswith("duplex_pair: unknown option(s) 'preload_force'; accepted: "
                           "contact_angle, ")
    assert "; and the arguments designation, arrangement, preload, speed, " in text
    assert text.endswith("; did you mean 'preload'?")
    assert duplex_pair("7020C", preload=800.0).preload_force == 800.0
    with pytest.raises(ParameterError, match=r"unknown option\(s\) 'lubricnt' at fidelity "
                                             r"'dynamic'; accepted: .*; and the arguments "
                                             r"designation, fidelity, lubricant.*; did you "
                                             r"mean 'lubricant'\?$"):
        deep_groove_ball_bearing("6304", "dynamic", lubricnt="ISO VG 32")
    with pytest.raises(ParameterError, match=r"unknown keyword\(s\) 'lubrcation' .*did you "
                                             r"mean 'lubrication'\?$"):
        double_layer_bearing(lubrcation="ISO VG 46")
