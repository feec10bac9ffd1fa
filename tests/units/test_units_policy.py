"""Issue 27 item 4: one unit policy, one units library (pint), at every edge: scene values, sweep
grid values, API arguments, display (docs/units.md). A bare number is the SI value, echoed in
engineering units; a speed above a bearing's limiting speed warns and above twice it is refused,
in every assembly; the API refuses to run without a required input, as scenes do."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing, duplex_pair
from bearingsim.assemblies.double_layer import shaft_speed_limit
from bearingsim.assemblies.motor_drive import motor_drive
from bearingsim.catalog import resolve_bearing
from bearingsim.catalog.geometry import SPEED_LIMIT_MULTIPLE
from bearingsim.errors import ParameterError, SpeedLimitWarning
from bearingsim.scenes import load_scene
from bearingsim.scenes.expressions import ExpressionError, compile_expression, constant_value
from bearingsim.scenes.scene import SceneError, scene_from_dict
from bearingsim.simulation import simulate, steady_state
from bearingsim.units import (
    UnitError,
    engineering,
    parse_quantity,
    quantity_to_si,
    registry,
    rpm_to_rad_s,
    to_display,
    to_si,
)

RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def torque_system():
    return assemble(double_layer_bearing("61905", "61907"))


def _scene(**inputs):
    d = load_scene("double_layer_rs").to_dict()  # a steady scene: made a short transient here
    d.update(analysis="transient", inputs=inputs)
    for key in ("grid", "cases", "statics"):
        d.pop(key, None)
    d["simulation"].update(t_end=0.05, n_points=3)
    return scene_from_dict(d)


# ------------------------------------------------------------------ parsing: one library
@pytest.mark.parametrize(("text", "si", "unit"), [
    ("10000 rpm", 10000 * RPM, "rad/s"), ("500rpm", 500 * RPM, "rad/s"),
    ("1000 r/min", 1000 * RPM, "rad/s"), ("2 kN", 2000.0, "N"), ("25 µm", 25e-6, "m"),
    ("25 um", 25e-6, "m"), ("30 N mm", 0.03, "N.m"), ("30 N.mm", 0.03, "N.m"),
    ("80 °C", 353.15, "K"), ("32 mm^2/s", 32e-6, "m2/s"), ("15 deg", math.radians(15), "rad"),
])
def test_numbers_with_units_read_to_si(text, si, unit):
    value, got = parse_quantity(text)
    assert value == pytest.approx(si, rel=1e-12) and got == unit


@given(st.floats(-1e6, 1e6, allow_nan=False), st.sampled_from(["rpm", "r/min", "rad/s", "kN",
                                                                 "N", "µm", "mm", "N mm"]))
def test_parse_and_display_invert_each_other(x, unit):
    """Reading ``x unit`` into SI and showing the SI value in its display unit, then reading
    that back, gives the same SI value (pint on both sides)."""
    si, si_unit = parse_quantity(f"{x!r} {unit}")
    shown, label = to_display(si, si_unit)
    back, _ = parse_quantity(f"{shown!r} {label}")
    assert back == pytest.approx(si, rel=1e-12, abs=1e-300)


@pytest.mark.parametrize("text", ["nan N", "inf rpm", "1e999 N", "-inf kN"])
def test_non_finite_numbers_with_units_are_named_errors(text):
    """Issue 30 item 3: "nan N", "inf rpm", "1e999 N" were accepted as scene inputs."""
    assert parse_quantity(text) is None
    with pytest.raises(ExpressionError, match="not finite"):
        compile_expression(text, "inputs.Fr")
    with pytest.raises(UnitError, match="not a finite number"):
        to_si(text, "N" if text.endswith("N") else "rad/s", "Fr")
    with pytest.raises(SceneError, match="not finite"):
        _scene(shaft_speed="rpm(1000)", Fr=text)


@pytest.mark.parametrize("text", ["1/0", "2**1e308", "exp(1000)", "1e308 * 10", "-1/0"])
def test_constant_expressions_must_be_finite(text):
    """Issue 30 item 3: 1/0 and 2**1e308 compiled to inf."""
    with pytest.raises(ExpressionError, match="is not a finite number"):
        compile_expression(text, "inputs.shaft_speed")


@given(st.floats(-1e6, 1e6, allow_nan=False),
       st.sampled_from(["1/min", "min^-1", "min⁻¹", "min-1"]))
def test_revolutions_per_minute_in_every_spelling_of_the_standards(x, spelling):
    """ISO 15312 and DIN catalogues write speeds in min⁻¹ (1/min): ``"1000 1/min"`` and
    ``"1000 min⁻¹"`` were not read as numbers with a unit (refused as expressions with
    invalid syntax), and ``"1000 min^-1"`` was read as a frequency (16.7 Hz) and refused for a
    speed, although the units library takes ``1/min`` as r/min. Each now reads as r/min."""
    value, unit = parse_quantity(f"{x!r} {spelling}")
    assert unit == "rad/s" and value == pytest.approx(x * RPM, rel=1e-12, abs=1e-12)


def test_a_frequency_for_a_speed_is_refused_saying_what_to_write(torque_system):
    """``"1000 Hz"`` (or ``1/s``) for a speed: cycles without their angle, refused with the
    units that carry it (before: only that Hz is not a unit of rad/s quantities)."""
    hint = (r"Hz counts cycles, not their angle: give a rotational speed in r/min, rpm, 1/min "
            r"or rev/s \(revolutions carry the angle\), or in rad/s")
    with pytest.raises(UnitError, match=r"'Hz' is not a unit of rad/s quantities \(it is "
                                        r"second\^-1\); " + hint):
        to_si("1000 Hz", "rad/s", "shaft_speed")
    with pytest.raises(SceneError, match=r"input shaft_speed is in rad/s, but its value is "
                                         r"given in Hz; " + hint):
        from bearingsim.scenes.preparation import prepare

        prepare(_scene(shaft_speed="1000 1/s"))
    same = [simulate(torque_system, 0.01, inputs={"shaft_speed": v}).final("w_shaft")
            for v in ("3000 min⁻¹", "3000 rpm")]
    assert same[0] == same[1] == pytest.approx(3000 * RPM, rel=1e-9)


def test_wrong_quantity_is_refused_with_both_units():
    with pytest.raises(UnitError, match="'kN' is not a unit of rad/s"):
        to_si("2 kN", "rad/s", "shaft_speed")
    assert to_si(registry().Quantity(2.0, "kN"), "N", "Fr") == 2000.0
    assert to_si(5.0, "N", "Fr") == 5.0  # a bare number is SI


# ------------------------------------------------------------------ API = scenes
def test_api_refuses_a_missing_shaft_speed(torque_system):
    """Old code: simulate(system, 2.0) ran at shaft speed 0 and returned Rs 0.0 (docs: "a
    forgotten shaft speed never runs at 0")."""
    with pytest.raises(ParameterError, match=r"not given: shaft_speed \[rad/s\]"):
        simulate(torque_system, 2.0)
    with pytest.raises(ParameterError, match="not given: shaft_speed"):
        steady_state(torque_system, inputs={"Fr": 100.0})
    # the loads stay optional, as in scenes
    assert simulate(torque_system, 0.05, inputs={"shaft_speed": 100.0}, n_points=3).final(
        "Fr") == 0.0


def test_required_inputs_match_the_scene_rules(torque_system):
    """The system's required inputs are exactly those a scene may not leave out."""
    from bearingsim.assemblies.registry import REGISTRY

    spec = REGISTRY["double_layer_bearing"]
    required = {s.name for s in torque_system.inputs if s.required}
    assert required == {n for n in torque_system.input_names if not spec.is_optional_input(n)}
    drive = assemble(motor_drive())
    spec = REGISTRY["motor_drive"]
    required = {s.name for s in drive.inputs if s.required}
    assert required == {n for n in drive.input_names if not spec.is_optional_input(n)} \
        == {"motor.w_ref"}


def test_api_takes_numbers_with_units(torque_system):
    """Old code: "10000 rpm" was rejected by the API but accepted by scenes."""
    text = simulate(torque_system, 0.05, inputs={"shaft_speed": "10000 rpm", "Fr": "0.2 kN"},
                    n_points=3)
    quantity = simulate(torque_system, 0.05, inputs={
        "shaft_speed": registry().Quantity(10000, "rpm"), "Fr": registry().Quantity(200, "N")},
        n_points=3)
    si = simulate(torque_system, 0.05, inputs={"shaft_speed": rpm_to_rad_s(10000.0),
                                               "Fr": 200.0}, n_points=3)
    assert text.inputs["shaft_speed"] == pytest.approx(10000 * RPM, rel=1e-15)
    assert np.array_equal(text.values, si.values) and np.array_equal(quantity.values, si.values)
    table = simulate(torque_system, 0.05, n_points=3, inputs={
        "shaft_speed": ([0.0, 0.05], registry().Quantity(np.array([0.0, 1000.0]), "rpm"))})
    assert table.final("shaft_speed") == pytest.approx(1000 * RPM, rel=1e-12)
    with pytest.raises(ParameterError, match="not a number with a unit"):
        simulate(torque_system, 0.05, inputs={"shaft_speed": "fast"})


def test_simulate_times_and_start_values_take_numbers_with_units(torque_system):
    """A scene took ``t_end = "50 ms"`` and ``[initial]`` values with a unit; ``simulate``
    refused both ("t_end must be a number in s", "must be a number in rad/s")."""
    w = quantity_to_si("100 rpm", "rad/s", "w")
    with_units = simulate(torque_system, "10 ms", t_start="0 s", max_step="1 ms", timeout="1 min",
                          inputs={"shaft_speed": "1000 rpm"}, n_points=3,
                          x0={"middle.sleeve.w": registry().Quantity(100.0, "rpm")})
    si = simulate(torque_system, 0.01, t_start=0.0, max_step=1e-3, timeout=60.0,
                  inputs={"shaft_speed": "1000 rpm"}, n_points=3, x0={"middle.sleeve.w": w})
    assert with_units.t.tolist() == [0.0, 0.005, 0.01]
    assert np.array_equal(with_units.values, si.values)
    with pytest.raises(ParameterError, match=r"simulate: t_end: 'rpm' is not a unit of s"):
        simulate(torque_system, "10 rpm", inputs={"shaft_speed": 1.0})
    with pytest.raises(ParameterError, match=r"initial value: middle.sleeve.w: 'm' is not a unit"):
        simulate(torque_system, 0.01, inputs={"shaft_speed": 1.0}, x0={"middle.sleeve.w": "3 m"})


def test_linearize_steady_state_and_speed_ratio_take_numbers_with_units(torque_system):
    """linearize refused the inputs simulate and steady_state take ("shaft_speed must be a
    number in rad/s, got '5000 rpm'") and a time with a unit; steady_state's time and
    speed_ratio's speed and run length alike."""
    from bearingsim.simulation import linearize
    from bearingsim.studies.double_layer import speed_ratio

    with_units = linearize(torque_system, inputs={"shaft_speed": "5000 rpm", "Fr": "0.2 kN"},
                           t="2 ms")
    si = linearize(torque_system, inputs={"shaft_speed": 5000 * RPM, "Fr": 200.0}, t=0.002)
    assert np.array_equal(with_units.A, si.A) and np.array_equal(with_units.u_op, si.u_op)
    with pytest.raises(ParameterError, match=r"linearize: inputs: shaft_speed: 'kN' is not a "
                                             r"unit of rad/s quantities"):
        linearize(torque_system, inputs={"shaft_speed": "5 kN"})
    x = steady_state(torque_system, inputs={"shaft_speed": "5000 rpm"}, t="1 ms")
    assert np.array_equal(x, steady_state(torque_system, inputs={"shaft_speed": 5000 * RPM},
                                          t=0.001))
    with pytest.raises(ParameterError, match=r"speed_ratio: w_shaft: 'kg' is not a unit"):
        speed_ratio(None, torque_system, "5000 kg")
    # converted, then refused for this system (the torque level has no M_middle)
    with pytest.raises(ParameterError, match=r"speed_ratio: assemble the bearing as the root"):
        speed_ratio(None, torque_system, "5000 rpm", t_run="20 ms")


def test_api_load_arguments_take_numbers_with_units():
    """A new-user trial: ``deep_groove_ball_bearing("6304", ..., speed="1730 rpm",
    loads={"Fx": "938 N"})`` took the speed with its unit and refused the load ("must be a
    number in N"), and ``deep_groove_statics`` did the same. Loads now take what inputs take;
    the cylindrical roller bearing converts them before its Newton start and static check."""
    from bearingsim.assemblies import cylindrical_roller_bearing, deep_groove_ball_bearing
    from bearingsim.studies.deep_groove_statics import deep_groove_statics

    for text in ("938 N", "0.938 kN", registry().Quantity(938.0, "N")):
        assert deep_groove_statics("6304", {"Fx": text}).max_pressure == pytest.approx(
            deep_groove_statics("6304", {"Fx": 938.0}).max_pressure, rel=1e-12)
        with_unit = assemble(deep_groove_ball_bearing("6304", "quasi-static",
                                                      loads={"Fx": text}))
        assert with_unit.u_default().tolist() == assemble(deep_groove_ball_bearing(
            "6304", "quasi-static", loads={"Fx": 938.0})).u_default().tolist()
    roller = cylindrical_roller_bearing("NU206", loads={"Fx": "10 kN"})
    assert roller.options.loads == {"Fx": 10000.0}
    assert roller.start.inner.tolist() == cylindrical_roller_bearing(
        "NU206", loads={"Fx": 10000.0}).start.inner.tolist()
    dynamic = deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed="1730 rpm",
                                       loads={"Fx": "938 N", "Fz": "0.1 kN"}, n_slices=0)
    assert dynamic.options.loads == {"Fx": 938.0, "Fz": 100.0}
    with pytest.raises(ParameterError, match=r"loads\['Fx'\]: 'rpm' is not a unit of N"):
        deep_groove_ball_bearing("6304", "quasi-static", loads={"Fx": "938 rpm"})
    with pytest.raises(ParameterError, match="not a number with a unit; write e.g. '2 kN'"):
        deep_groove_statics("6304", {"Fx": "heavy"})


def test_every_assembly_argument_with_a_unit_takes_a_number_with_a_unit():
    """A new-user trial: the API took a speed, a load or a deep-groove clearance with its
    unit, and refused the roller bearing's clearance and misalignment, the spindle's roller
    distance, the double-layer bearing's oil level and middle-ring gap, the motor drive's
    shaft inertia and constant load torque, and any component's parameter ("must be a number
    in m"). Each now gives the model of the same SI number."""
    from bearingsim.assemblies import (
        cylindrical_roller_bearing,
        double_layer_bearing,
        motor_drive,
        spindle,
    )
    from bearingsim.components.rotational import Inertia

    def same(build, with_unit, si):
        a, b = assemble(build(**with_unit)), assemble(build(**si))
        assert a.parameter_names == b.parameter_names and a.input_names == b.input_names
        np.testing.assert_allclose(a.p0(), b.p0(), rtol=1e-14, err_msg=str(with_unit))
        np.testing.assert_allclose(a.u_default(), b.u_default(), rtol=1e-14)

    same(cylindrical_roller_bearing, {"clearance": "20 um", "misalignment": ("0.5 mrad", 0)},
         {"clearance": 20e-6, "misalignment": (0.5e-3, 0.0)})
    same(spindle, {"roller_distance": "250 mm"}, {"roller_distance": 0.25})
    same(motor_drive, {"shaft_inertia": "2e-3 kg m^2", "load_torque": "-50 N mm"},
         {"shaft_inertia": 2e-3, "load_torque": -0.05})
    gap = {"radius": "30 mm", "gap": "0.1 mm", "length": "10 mm"}
    same(double_layer_bearing, {"middle_ring_drag": gap},
         {"middle_ring_drag": {"radius": 0.03, "gap": 1e-4, "length": 0.01}})
    assert Inertia(registry().Quantity(3.0, "g m^2")).parameter("J").value == pytest.approx(
        3e-3, rel=1e-15)
    with pytest.raises(ParameterError, match=r"motor_drive: shaft_inertia: 'kg' is not a unit"):
        motor_drive(shaft_inertia="0.002 kg")
    with pytest.raises(ParameterError, match=r"misalignment\[0\] = 0.05 \[rad\] is outside"):
        cylindrical_roller_bearing(misalignment=("50 mrad", 0.0))


# ------------------------------------------------------------------ limiting speeds
def test_bare_number_speed_in_a_scene_is_refused_far_above_the_limit():
    """Old code: shaft_speed = 10000 (rad/s, 95 493 r/min; limiting speeds 22 000 and 16 000
    r/min) ran with exit code 0 and no warning."""
    from bearingsim.scenes import run_scene

    with pytest.raises(ParameterError, match=r"(above its valid maximum|outside its valid range)"
                                             r".*limiting speed.*a bare number is in rad/s"):
        run_scene(_scene(shaft_speed=10000), write=False)


def test_speed_above_the_limit_warns_and_is_echoed_in_both_units(torque_system):
    limit = shaft_speed_limit(resolve_bearing("61905"), resolve_bearing("61907"))
    assert limit / RPM == pytest.approx(22000 + 16000)
    with pytest.warns(SpeedLimitWarning, match=r"47746 r/min \(5000 rad/s\).*38000 r/min"):
        simulate(torque_system, 0.05, inputs={"shaft_speed": 5000.0}, n_points=3)
    with warnings.catch_warnings():
        warnings.simplefilter("error", SpeedLimitWarning)
        simulate(torque_system, 0.05, inputs={"shaft_speed": "30000 rpm"}, n_points=3)
    assert engineering(5000.0, "rad/s", both=True) == "47746 r/min (5000 rad/s)"


@pytest.mark.parametrize(("build", "limit_rpm"), [
    (lambda w: double_layer_bearing("61905", "61907", speed=w), 22000 + 16000),
    # a pair at light preload: 0.8 x one 7014C's 19 000 r/min (SKF General Catalogue 6000
    # p. 414; NSK Super Precision p. 170: less at higher preloads)
    (lambda w: duplex_pair("7014C", preload="light", speed=w), 15200),
    (lambda w: motor_drive(speed_ref=w), 22000 + 16000),
], ids=["double layer", "duplex pair", "motor drive"])
def test_every_assembly_checks_its_limiting_speed(build, limit_rpm):
    """Old code: the double-layer and motor-drive models never checked a limiting speed."""
    limit = limit_rpm * RPM
    with warnings.catch_warnings():
        warnings.simplefilter("error", SpeedLimitWarning)
        build(0.9 * limit)  # below: silent
    with pytest.warns(SpeedLimitWarning, match=f"{limit_rpm} r/min"):
        build(1.5 * limit)
    with pytest.raises(ParameterError, match=f"more than {SPEED_LIMIT_MULTIPLE:g} x"):
        build(1.01 * SPEED_LIMIT_MULTIPLE * limit)


def test_motor_reference_input_is_bounded_by_the_bearing():
    drive = assemble(motor_drive())
    w_ref = next(s for s in drive.inputs if s.name == "motor.w_ref")
    assert w_ref.warn_above == pytest.approx(38000 * RPM)
    assert w_ref.high == pytest.approx(SPEED_LIMIT_MULTIPLE * 38000 * RPM)



def test_motor_drive_speed_ref_takes_units_and_refuses_nan():
    """Old code: motor_drive(speed_ref="3000 rpm") was built without a check and failed at
    assemble with ValueError: could not convert string to float: '3000 rpm' (and "3000" ran at
    3000 rad/s past the limiting-speed check); speed_ref=nan was built and failed in CVODES
    with a SimulationError (NaN in the right-hand side)."""
    def run(speed_ref):
        return simulate(assemble(motor_drive(speed_ref=speed_ref)), 0.01, n_points=3)

    si = run(3000 * RPM)
    assert np.array_equal(run("3000 rpm").values, si.values)
    assert np.array_equal(run(registry().Quantity(3000, "rpm")).values, si.values)
    with pytest.raises(ParameterError, match=f"more than {SPEED_LIMIT_MULTIPLE:g} x"):
        motor_drive(speed_ref="80000 rpm")  # beyond twice the 38000 r/min limit
    for bad, match in [(float("nan"), r"motor_drive: speed_ref must be finite, got nan \[rad/s\]"),
                       (float("inf"), r"motor_drive: speed_ref must be finite"),
                       ("3000", r"motor_drive: speed_ref: '3000' is not a number with a unit; "
                                r"write e.g. '10000 rpm' or a number in rad/s"),
                       ("3 kN", r"motor_drive: speed_ref: 'kN' is not a unit of rad/s"),
                       ([3000.0], r"motor_drive: speed_ref must be a number \[rad/s\], a number "
                                  r"with a unit \(e.g. '3000 rpm'\), a function of time")]:
        with pytest.raises(ParameterError, match=match):
            motor_drive(speed_ref=bad)

# ------------------------------------------------------------------ CLI grid values
def test_grid_values_take_units_and_the_table_stores_si():
    """--grid inputs.shaft_speed=500rpm,1000rpm and rpm(500) give the same SI input; the sweep
    table stores SI numbers under its [rad/s] header, not the text rpm(2000)."""
    from bearingsim.scenes.sweep import parse_sample
    from bearingsim.scenes.sweep_grid import parse_grid, point_scene, si_values

    scene = _scene(shaft_speed="rpm(1000)")
    grid = parse_grid(["inputs.shaft_speed=500rpm,rpm(1000),52.5"])
    values = [point_scene(scene, {"inputs.shaft_speed": v}).inputs["shaft_speed"]
              for v in grid["inputs.shaft_speed"]]
    assert values[0] == pytest.approx(500 * RPM) and values[2] == 52.5
    assert compile_expression(values[1])(0.0) == pytest.approx(1000 * RPM)
    assert si_values({"inputs.shaft_speed": "rpm(2000)", "assembly.inner": "61905"}) == {
        "inputs.shaft_speed": pytest.approx(2000 * RPM), "assembly.inner": "61905"}
    assert constant_value("rpm(2000) * t") is None
    assert parse_sample(["inputs.shaft_speed=500rpm:1000 r/min"])["inputs.shaft_speed"] == (
        pytest.approx(500 * RPM), pytest.approx(1000 * RPM), "rad/s")


def test_fmi_units_come_from_the_same_library():
    from bearingsim.fmu.units import parse_unit

    assert parse_unit("N.m/rad").exponents == {"kg": 1, "m": 2, "s": -2, "rad": -1}
    assert parse_unit("kg.m2").exponents == {"kg": 1, "m": 2}
    deg_c = parse_unit("degC")
    assert deg_c.exponents == {"K": 1} and deg_c.offset == pytest.approx(273.15)
    assert parse_unit("rev").factor == pytest.approx(2 * math.pi)
    assert parse_unit("no_such_unit").exponents is None


def test_parameters_take_units_too(torque_system):
    names = torque_system.parameter_names
    p = torque_system.p0({"inner_layer.nu": "32 mm^2/s", "inner_layer.dm": "33.5 mm",
                          "housing.phi0": registry().Quantity(90, "deg")})
    assert p[names.index("inner_layer.nu")] == pytest.approx(32e-6, rel=1e-12)
    assert p[names.index("inner_layer.dm")] == pytest.approx(0.0335, rel=1e-12)
    assert p[names.index("housing.phi0")] == pytest.approx(math.pi / 2, rel=1e-12)
    with pytest.raises(UnitError, match="parameter inner_layer.nu"):
        torque_system.p0({"inner_layer.nu": "32 rpm"})


@given(st.text(alphabet="0123456789 .eE+-*/^()rpmkNuµmsdegCK°[]{}%$#@!~`'\"\\\n\t_", max_size=20)
       | st.text(max_size=15))
def test_unit_parsers_give_a_value_none_or_a_unit_error_on_any_text(text):
    """Malformed text made pint raise TokenError, SyntaxError and others."""
    from bearingsim.fmu.units import parse_unit
    from bearingsim.units import split_quantity

    split_quantity(text)
    parse_quantity(text)
    assert parse_unit(text).name == text
    try:
        value = to_si(text, "rad/s", "x")
    except UnitError:
        return
    assert value == text or math.isfinite(value)  # not a quantity: left to the caller


def test_sweep_table_stores_si_under_its_unit_header(tmp_path):
    """Issue 27: the sweep CSV header said [rad/s] above the text rpm(2000)."""
    import csv

    from bearingsim.scenes.sweep import grid_points, run_sweep

    pytest.importorskip("dask.distributed")
    d = load_scene("double_layer_rs").to_dict()  # steady: made a short transient here
    d["analysis"] = "transient"
    for key in ("grid", "cases", "statics"):
        d.pop(key, None)
    d["assembly"]["fidelity"] = "kinematic"
    d["inputs"] = {}  # the kinematic level has no load inputs; the grid gives the speed
    d["outputs"] = ["Rs"]
    d["simulation"].update(t_end=0.05, n_points=3)
    points = grid_points({"inputs.shaft_speed": ["500rpm", "rpm(1000)"]})
    run_sweep(scene_from_dict(d), points, n_workers=1, out=tmp_path, progress=False)
    rows = list(csv.DictReader((tmp_path / "double_layer_bearing.sweep.csv").open()))
    assert [float(r["inputs.shaft_speed [rad/s]"]) for r in rows] == pytest.approx(
        [500 * RPM, 1000 * RPM], rel=1e-12)


def test_console_echoes_a_bare_number_in_both_units(tmp_path, capsys):
    """A bare number is SI and never silent: the run prints it in r/min and rad/s."""
    from bearingsim.cli import main

    scene = tmp_path / "bare.toml"
    scene.write_text('[assembly]\nname = "double_layer_bearing"\nfidelity = "torque"\n'
                     'inner = "61905"\nouter = "61907"\n[inputs]\nshaft_speed = 1000\n'
                     '[simulation]\nt_end = 0.05\nn_points = 3\n[output]\nplots = false\n',
                     encoding="utf-8")
    assert main(["run", str(scene), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    assert "input shaft_speed = 9549.3 r/min (1000 rad/s) at t_end" in capsys.readouterr().out


def test_one_formatter_for_a_value_in_its_display_unit():
    """The console's values (``scenes.plots.display_text``) and the echoes of inputs
    (``units.engineering``) were formatted by two functions: the console printed a life of
    801 863 h as ``8.0186e+05 h``, and ``engineering`` showed a life in millions of
    revolutions as ``Mrev`` where the figures and the console say ``10⁶ rev``. One formatter
    now; the console leaves ``[-]`` off a dimensionless value."""
    from bearingsim.scenes.plots import display_text
    from bearingsim.units import engineering

    assert display_text(801863.0, "h") == "801863 h"
    assert engineering(3319.0, "Mrev") == display_text(3319.0, "Mrev") == "3319 10⁶ rev"
    assert display_text(0.20948, "1") == "0.20948" and engineering(0.20948, "1") == "0.20948 [-]"
    for value, unit in [(104.72, "rad/s"), (2.108e9, "Pa"), (-0.0055, "N.m"), (1e-7, "N"),
                        (42.0, "Hz"), (1.7e-5, "m")]:
        assert display_text(value, unit) == engineering(value, unit)
