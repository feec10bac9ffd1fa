"""The bad-input probe of the public API as a test (issue 17): every call below is nonsense of
a kind users write (wrong types, NaN, infinities, units off by orders of magnitude,
contradictory options, a component where a system is wanted) and must raise a named
:class:`~bearingsim.errors.BearingsimError` whose message names the argument, never a bare
``TypeError``/``AttributeError`` from deep inside, a NaN or a silent default.

Each case: an id, the call, and a fragment the message must contain (the argument's name).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import (
    deep_groove_ball_bearing,
    double_layer_bearing,
    duplex_pair,
    motor_drive,
)
from bearingsim.catalog import get_bearing
from bearingsim.errors import BearingsimError
from bearingsim.physics import contact_curvature, contact_law, life, materials
from bearingsim.physics.friction import palmgren_torque
from bearingsim.physics.lubricant import Oil, get_lubricant
from bearingsim.scenes.expressions import compile_expression
from bearingsim.simulation import linearize, simulate, steady_state
from bearingsim.studies.deep_groove_statics import deep_groove_statics
from bearingsim.studies.double_layer import steady_ratio
from bearingsim.studies.duplex import DuplexModel

COMPONENT = double_layer_bearing("61905", "61907", fidelity="torque")
SYSTEM = assemble(double_layer_bearing("61905", "61907", fidelity="torque"),
                  outputs=["Rs", "M_shaft"])
SP = {"shaft_speed": 100.0}
NAN, INF = float("nan"), float("inf")
G = get_bearing("6304")



def _sweep(points, **kwargs):
    from bearingsim.scenes.sweep import run_sweep

    return run_sweep("scenes/deep_groove_radial.toml", points, **kwargs)


@functools.cache
def _result():
    return simulate(SYSTEM, 0.01, inputs=SP)


def _sampling():
    from bearingsim.scenes import sampling

    return sampling


def _scenes():
    import bearingsim.scenes

    return bearingsim.scenes


CASES = [
    # --- simulate: times, tolerances, sizes
    ("simulate t_end text", lambda: simulate(SYSTEM, "1", inputs=SP), "t_end"),
    ("simulate t_end bool", lambda: simulate(SYSTEM, True, inputs=SP), "t_end"),
    ("simulate t_end nan", lambda: simulate(SYSTEM, NAN, inputs=SP), "t_end"),
    ("simulate t_end before start", lambda: simulate(SYSTEM, -1.0, inputs=SP), "t_end"),
    ("simulate rtol 0", lambda: simulate(SYSTEM, 1.0, inputs=SP, rtol=0.0), "rtol"),
    ("simulate atol inf", lambda: simulate(SYSTEM, 1.0, inputs=SP, atol=INF), "atol"),
    ("simulate n_points float", lambda: simulate(SYSTEM, 1.0, inputs=SP, n_points=2.5),
     "n_points"),
    ("simulate n_points 1e12", lambda: simulate(SYSTEM, 1.0, inputs=SP, n_points=10**12),
     "n_points"),
    ("simulate max_step 0", lambda: simulate(SYSTEM, 1.0, inputs=SP, max_step=0.0),
     "max_step"),
    ("simulate max_step tiny", lambda: simulate(SYSTEM, 1.0, inputs=SP, max_step=1e-12),
     "max_step"),
    ("simulate t_eval text", lambda: simulate(SYSTEM, 1.0, inputs=SP, t_eval="0 1"), "t_eval"),
    ("simulate t_eval decreasing", lambda: simulate(SYSTEM, 1.0, inputs=SP,
                                                    t_eval=[0.5, 0.2]), "t_eval"),
    ("simulate method int", lambda: simulate(SYSTEM, 1.0, inputs=SP, method=3), "method"),
    ("simulate method unknown", lambda: simulate(SYSTEM, 1.0, inputs=SP, method="euler"),
     "method"),
    ("simulate method of other backend", lambda: simulate(SYSTEM, 1.0, inputs=SP,
                                                          backend="casadi", method="BDF"),
     "method"),
    ("simulate initial unknown", lambda: simulate(SYSTEM, 1.0, inputs=SP, initial="rest"),
     "initial"),
    ("simulate progress text", lambda: simulate(SYSTEM, 1.0, inputs=SP, progress="yes"),
     "progress"),
    ("simulate unknown keyword", lambda: simulate(SYSTEM, 1.0, inputs=SP, tend=2.0), "t_end"),
    # --- simulate: what is simulated
    ("simulate a component", lambda: simulate(COMPONENT, 1.0, inputs=SP), "assemble"),
    ("simulate text", lambda: simulate("system", 1.0), "System"),
    ("simulate inputs list", lambda: simulate(SYSTEM, 1.0, inputs=["a"]), "inputs"),
    ("simulate unknown input", lambda: simulate(SYSTEM, 1.0, inputs={"speed": 1.0}), "speed"),
    ("simulate bool input", lambda: simulate(SYSTEM, 1.0, inputs={"shaft_speed": True}),
     "shaft_speed"),
    ("simulate nan input", lambda: simulate(SYSTEM, 1.0, inputs={"shaft_speed": NAN}),
     "shaft_speed"),
    ("simulate table infinite time", lambda: simulate(
        SYSTEM, 1.0, inputs={"shaft_speed": ([0.0, INF], [1.0, 2.0])}), "times"),
    ("simulate table text values", lambda: simulate(
        SYSTEM, 1.0, inputs={"shaft_speed": ([0.0, 1.0], ["a", "b"])}), "values"),
    ("simulate table decreasing", lambda: simulate(
        SYSTEM, 1.0, inputs={"shaft_speed": ([1.0, 0.0], [1.0, 2.0])}), "increasing"),
    ("simulate negative load", lambda: simulate(SYSTEM, 1.0, inputs={**SP, "Fr": -5.0}), "Fr"),
    ("simulate parameters list", lambda: simulate(SYSTEM, 1.0, inputs=SP, parameters=[1.0]),
     "parameters"),
    ("simulate unknown parameter", lambda: simulate(SYSTEM, 1.0, inputs=SP,
                                                    parameters={"f0": 1.0}), "f0"),
    ("simulate parameter nan", lambda: simulate(SYSTEM, 1.0, inputs=SP,
                                                parameters={"inner_layer.nu": NAN}),
     "inner_layer.nu"),
    ("simulate x0 text", lambda: simulate(SYSTEM, 1.0, inputs=SP, x0="abc"), "x0"),
    ("simulate x0 unknown state", lambda: simulate(SYSTEM, 1.0, inputs=SP, x0={"w": 1.0}),
     "'w'"),
    ("simulate input pole between outputs", lambda: simulate(
        SYSTEM, 1.0, inputs={"shaft_speed": compile_expression("1e-9/(t - 0.1234567)")},
        n_points=3), "division by zero"),
    # --- steady_state, linearize, assemble
    ("steady tol 0", lambda: steady_state(SYSTEM, inputs=SP, tol=0.0), "tol"),
    ("steady tol nan", lambda: steady_state(SYSTEM, inputs=SP, tol=NAN), "tol"),
    ("steady residual_tol -1", lambda: steady_state(SYSTEM, inputs=SP, residual_tol=-1.0),
     "residual_tol"),
    ("steady residual_tol inf", lambda: steady_state(SYSTEM, inputs=SP, residual_tol=INF),
     "residual_tol"),
    ("steady t nan", lambda: steady_state(SYSTEM, inputs=SP, t=NAN), "t"),
    ("steady x_guess length", lambda: steady_state(SYSTEM, inputs=SP,
                                                   x_guess=np.zeros(SYSTEM.n_states + 2)),
     "x_guess"),
    ("steady x_guess text", lambda: steady_state(SYSTEM, inputs=SP, x_guess="0"), "x_guess"),
    ("steady a component", lambda: steady_state(COMPONENT, inputs=SP), "assemble"),
    ("linearize op keyword", lambda: linearize(SYSTEM, op="steady"), "op"),
    ("linearize a component", lambda: linearize(COMPONENT), "assemble"),
    ("linearize operating point text", lambda: linearize(SYSTEM, "steady"), "operating_point"),
    ("linearize operating point length", lambda: linearize(SYSTEM, [1.0, 2.0, 3.0, 4.0]),
     "operating_point"),
    ("linearize unknown input", lambda: linearize(SYSTEM, inputs={"speed": 1.0}), "speed"),
    ("assemble text", lambda: assemble("bearing"), "assemble"),
    ("assemble outputs text", lambda: assemble(COMPONENT, outputs="Rs"), "outputs"),
    ("assemble newton_tol -1", lambda: assemble(COMPONENT, newton_tol=-1.0), "newton_tol"),
    ("assemble newton_tol nan", lambda: assemble(COMPONENT, newton_tol=NAN), "newton_tol"),
    ("assemble rootfinder", lambda: assemble(COMPONENT, rootfinder="kinsol"), "rootfinder"),
    # --- assemblies
    ("double layer fidelity", lambda: double_layer_bearing(fidelity="exact"), "fidelity"),
    ("double layer structure", lambda: double_layer_bearing(structure="X"), "structure"),
    ("double layer I that does not fit", lambda: double_layer_bearing(
        "61905", "61907", structure="I"), "structure='Z'"),
    ("double layer same bearings", lambda: double_layer_bearing("61905", "61905"),
     "smaller than the outer"),
    ("double layer inner larger", lambda: double_layer_bearing("61909", "61905"),
     "smaller than the outer"),
    ("double layer lubricant", lambda: double_layer_bearing(lubrication="olive oil"),
     "olive oil"),
    ("double layer layer_options list", lambda: double_layer_bearing(layer_options=["x"]),
     "layer_options"),
    ("double layer unknown layer option", lambda: double_layer_bearing(
        layer_options={"smoothing": True}), "smoothing"),
    ("double layer unknown keyword", lambda: double_layer_bearing(speeed=1.0), "speeed"),
    ("double layer friction model", lambda: double_layer_bearing(friction_model="coulomb"),
     "friction_model"),
    ("deep groove fidelity", lambda: deep_groove_ball_bearing("6304", "exact"), "fidelity"),
    ("deep groove loads list", lambda: deep_groove_ball_bearing(
        "6304", "quasi-static", loads=[1.0, 2.0]), "loads"),
    ("deep groove load key", lambda: deep_groove_ball_bearing(
        "6304", "quasi-static", loads={"Fr": 1.0}), "Fr"),
    ("deep groove load nan", lambda: deep_groove_ball_bearing(
        "6304", "quasi-static", loads={"Fx": NAN}), "Fx"),
    ("deep groove clearance negative", lambda: deep_groove_ball_bearing(
        "6304", "quasi-static", clearance=-1e-6), "clearance"),
    ("deep groove speed function at rest level", lambda: deep_groove_ball_bearing(
        "6304", "quasi-static", speed=lambda t: t), "speed"),
    ("deep groove unknown option", lambda: deep_groove_ball_bearing(
        "6304", "dynamic", n_slice=3), "n_slice"),
    ("duplex arrangement", lambda: duplex_pair("7020C", arrangement="XX"), "arrangement"),
    ("duplex preload class", lambda: duplex_pair("7020C", preload="extreme"), "preload"),
    ("duplex pair_options list", lambda: DuplexModel("7020C", pair_options=["x"]),
     "pair_options"),
    ("motor drive motor", lambda: motor_drive(motor="steam"), "motor"),
    ("unknown designation", lambda: get_bearing("6304ZZ-X"), "6304ZZ-X"),
    ("geometry in millimetres", lambda: dataclasses.replace(
        G, bore=20.0, outside_diameter=52.0, width=15.0, ball_diameter=9.525,
        pitch_diameter=36.0), "did you pass mm?"),
    ("rating in kN", lambda: dataclasses.replace(G, dynamic_load_rating=16.8), "kN"),
    ("C0 ten times C", lambda: dataclasses.replace(
        G, dynamic_load_rating=4000.0, static_load_rating=40000.0), "static_load_rating"),
    # --- physics functions
    ("Young's modulus in GPa", lambda: materials.Material("steel", 208.0, 0.3), "GPa"),
    ("oil viscosity in m^2/s", lambda: Oil(32e-6, 40.0, 5.4e-6, 100.0), "did you pass m^2/s?"),
    ("pressure-viscosity coefficient in 1/GPa", lambda: Oil(32, 40.0, 5.4, 100.0, alpha=20.0),
     "alpha"),
    ("Poisson ratio 0.5", lambda: materials.Material("rubber", 2e9, 0.5), "poisson_ratio"),
    ("contact load nan approach", lambda: contact_law.contact_load(1e10, NAN), "delta"),
    ("raceway radii swapped race",
     lambda: contact_curvature.raceway_radii(0.01, 0.04, 0.52, 0.0, "mid"), "race"),
    ("rating life negative load", lambda: life.rating_life(1e4, -1.0), "p"),
    ("life hours at rest", lambda: life.life_hours(100.0, 0.0), "speed"),
    ("Palmgren bearing type", lambda: palmgren_torque(100.0, 0.03, get_lubricant("ISO VG 32"),
                                                      "spherical_plain"), "bearing type"),
    ("dynamic rating rows 1.5", lambda: life.dynamic_load_rating(0.01, 0.04, 8, rows=1.5),
     "rows"),
    # --- scene expressions
    ("expression tan pole", lambda: compile_expression("tan(pi/2)", "inputs.x"), "tan"),
    ("expression ramp backwards", lambda: compile_expression("ramp(1, 0)", "inputs.x"),
     "ramp"),
    ("expression ramp of zero length", lambda: compile_expression("ramp(0.5, 0.5)", "inputs.x"),
     "ramp"),
    ("expression units in text", lambda: compile_expression("1000 rpm", "inputs.x"), "rpm("),
    ("expression unknown function", lambda: compile_expression("gamma(t)", "inputs.x"),
     "gamma"),
    ("expression attribute access", lambda: compile_expression("t.__class__", "inputs.x"),
     "Attribute"),
    # --- studies
    ("statics unknown load", lambda: deep_groove_statics("6304", {"Fa": 1.0}), "Fa"),
    ("statics method", lambda: deep_groove_statics("6304", {"Fx": 1.0}, method="iso"),
     "method"),
    ("steady ratio a component", lambda: steady_ratio(COMPONENT, 100.0), "assemble"),
]


RESULT = simulate(SYSTEM, 0.01, inputs=SP, n_points=3)

# issue 30: each raised TypeError, OverflowError or AttributeError, or was accepted, before
CASES += [
    ("steady ratio speed list", lambda: steady_ratio(SYSTEM, [1.0]), "speed must be float"),
    ("steady ratio speed 10**400", lambda: steady_ratio(SYSTEM, 10**400), "speed"),
    ("simulate t_end 10**400", lambda: simulate(SYSTEM, 10**400, inputs=SP), "t_end"),
    ("simulate input 10**400", lambda: simulate(SYSTEM, 1.0, inputs={"shaft_speed": 10**400}),
     "shaft_speed"),
    ("dgbb speed 10**400", lambda: deep_groove_ball_bearing("6304", "quasi-static",
                                                            speed=10**400), "speed"),
    ("motor_drive bearing name", lambda: motor_drive(bearing="61905"), "bearing must be"),
    ("Result.final number", lambda: RESULT.final(5), "name must be str"),
    ("assembly name empty", lambda: double_layer_bearing("61905", "61907", name=""), "name"),
    ("assembly name dotted", lambda: double_layer_bearing("61905", "61907", name="a.b"),
     "identifier"),
    ("assembly name digit", lambda: double_layer_bearing("61905", "61907", name="1abc"),
     "identifier"),
    ("layer option bool as text", lambda: double_layer_bearing(
        "61905", "61907", fidelity="torque", layer_options={"smooth": "no"}),
     "layer_options['smooth'] must be bool"),
    ("newton_tol 1e6", lambda: assemble(COMPONENT, newton_tol=1e6), "newton_tol"),
    ("simulate atol 1e300", lambda: simulate(SYSTEM, 1.0, inputs=SP, atol=1e300), "atol"),
    ("simulate rtol 0.5", lambda: simulate(SYSTEM, 1.0, inputs=SP, rtol=0.5), "rtol"),
    ("nu in mm2/s as parameter", lambda: simulate(SYSTEM, 1.0, inputs=SP,
                                                  parameters={"inner_layer.nu": 32.0}),
     "mm^2/s"),
    ("palmgren m0 nu in mm2/s", lambda: __import__(
        "bearingsim.physics.friction", fromlist=["x"]).palmgren_m0(32.0, 100.0, 0.04, 2.0),
     "mm^2/s"),
    ("dgbb speed 1e9 rad/s", lambda: deep_groove_ball_bearing("6304", "quasi-static",
                                                              speed=1e9), "limiting speed"),
    ("dgbb load 1e12 N", lambda: deep_groove_ball_bearing("6304", "quasi-static",
                                                          loads={"Fx": 1e12}), "static load"),
    ("palmgren f1 P0 1e12 N", lambda: __import__(
        "bearingsim.physics.friction", fromlist=["x"]).palmgren_f1(
        "deep_groove_ball", 1e12, 7800.0), "P0"),
    ("grid of 10^12 points", lambda: __import__(
        "bearingsim.scenes.sweep", fromlist=["x"]).grid_points(
        {f"inputs.k{i}": list(range(1000)) for i in range(4)}), "grid_points"),
    ("sweep n_workers 0", lambda: __import__("bearingsim.scenes.sweep", fromlist=["x"])
     .run_sweep("scenes/deep_groove_radial.toml", [{}], n_workers=0), "n_workers"),
    # before: a TypeError, a ValueError from unpacking the key, or dask's TypeError after the
    # sweep's table was created
    ("sweep points text", lambda: _sweep("abc"), "points must be Sequence[Mapping"),
    # (beartype or check_point_keys, by the item beartype samples: both say "must be")
    ("sweep points numbers", lambda: _sweep([{}, 2]), "must be"),
    # a tuple of points passes the type check (stopped at the next check, the timeout)
    ("sweep points as a tuple run", lambda: _sweep(({}, {}), timeout=-1.0), "--timeout"),
    ("sweep key without section", lambda: _sweep([{"x": 1}]), "must start with inputs."),
    ("sweep timeout text", lambda: _sweep([{}], timeout="1"), "timeout must be float"),
    ("sweep scheduler number", lambda: _sweep([{}], scheduler=5), "scheduler"),
    ("sweep out number", lambda: _sweep([{}], out=5), "out must be str | Path"),
    ("grid_points text", lambda: _sampling().grid_points("abc"), "must be a dict"),
    ("grid_points one value", lambda: _sampling().grid_points({"inputs.x": 5}),
     "expected a list of values"),
    ("grid_points no values", lambda: _sampling().grid_points({"inputs.x": []}), "no values"),
    ("grid_points key without section", lambda: _sampling().grid_points({"x": [1]}),
     "must start with inputs."),
    ("sample_points reversed range", lambda: _sampling().sample_points({"inputs.x": (2, 1)}, 4),
     "low < high"),
    ("sample_points range text", lambda: _sampling().sample_points({"inputs.x": "1:2"}, 4),
     "low < high"),
    ("parse_scene bytes", lambda: _scenes().parse_scene(b"title = 'x'"), "text must be str"),
    ("load_scene number", lambda: _scenes().load_scene(5), "path must be str | Path"),
    ("run_scene out number", lambda: _scenes().run_scene("scenes/deep_groove_radial.toml", out=5),
     "out must be str | Path"),
    # before: TypeError / ValueError from pathlib
    ("Result.to_csv path number", lambda: _result().to_csv(5), "path must be str | Path"),
    ("Result.plot path number", lambda: _result().plot("Rs", path=5), "path must be"),
    ("Result.to_npz into a folder", lambda: _result().to_npz("."), "a folder, not a file path"),
    ("export_fmu into a folder", lambda: __import__("bearingsim.fmu", fromlist=["x"])
     .export_fmu(SYSTEM, "."), "path must be a file path ending in .fmu"),
    ("simulate max_steps 0", lambda: simulate(SYSTEM, 1.0, inputs=SP, max_steps=0),
     "max_steps"),
    ("export_fmu nu in mm2/s", lambda: __import__("bearingsim.fmu", fromlist=["x"])
     .export_fmu(SYSTEM, "never_written.fmu", parameters={"inner_layer.nu": 32.0}), "mm^2/s"),
]


@pytest.mark.parametrize(("call", "fragment"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_input_raises_a_named_error(call, fragment):
    with pytest.raises(BearingsimError) as err:
        call()
    assert fragment in str(err.value), str(err.value)


def test_the_probe_covers_every_public_entry_class():
    """At least 90 cases over simulate, steady_state, linearize, assemble, the four assemblies,
    the catalogue, physics functions, scene expressions and the studies."""
    assert len(CASES) >= 90
