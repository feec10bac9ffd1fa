"""Double-layer bearings (docs/studies.md, section A): speed ratio theories emerging from the
torque-level simulation, lubrication trends, energy balance and rigid middle-ring joins."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid

from bearingsim import Assembly, Input, Variable, connect
from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing, motor_drive
from bearingsim.catalog import get_bearing
from bearingsim.components.bearing_torque import PalmgrenBearing, PureRollingLayer
from bearingsim.components.middle_ring import middle_ring_bodies
from bearingsim.components.rotational import Fixed, Inertia, SpeedSource
from bearingsim.errors import ParameterError
from bearingsim.physics.double_layer_theory import (
    design_report,
    optimal_speed_ratio,
    speed_ratio_palmgren,
    speed_ratio_pure_rolling,
)
from bearingsim.physics.lubricant import Grease, Oil, get_lubricant
from bearingsim.simulation import simulate, steady_state
from bearingsim.units import rpm_to_rad_s

W_SHAFT = rpm_to_rad_s(10_000)


def _steady_rs(system, speed=W_SHAFT, parameters=None):
    x = steady_state(system, inputs={"shaft_speed": speed}, parameters=parameters)
    u = np.zeros(len(system.input_names))
    u[system.input_names.index("shaft_speed")] = speed
    return system.observe(0.0, x, u, system.p0(parameters))["Rs"]


@pytest.mark.parametrize("outer", ["61907", "61908", "61909"])
def test_torque_model_with_palmgren_m0_converges_to_dp45_law(outer):
    bearing = double_layer_bearing("61905", outer, layer_options={
        "smooth": False, "load_dependent": False})
    system = assemble(bearing)
    expected = speed_ratio_palmgren("61905", outer)
    assert _steady_rs(system) == pytest.approx(expected, rel=1e-6)


def test_torque_model_time_stepping_reaches_the_same_ratio():
    system = assemble(double_layer_bearing("61905", "61907", layer_options={
        "smooth": False, "load_dependent": False}))
    res = simulate(system, 20.0, inputs={"shaft_speed": W_SHAFT}, rtol=1e-10, atol=1e-12)
    assert res.final("Rs") == pytest.approx(speed_ratio_palmgren("61905", "61907"), rel=1e-6)


@pytest.mark.parametrize("exact", [True, False])
def test_kinematic_model_returns_pure_rolling_formula(exact):
    fidelity = "kinematic" if exact else "kinematic_approx"
    system = assemble(double_layer_bearing("61905", "61908", fidelity=fidelity))
    expected = speed_ratio_pure_rolling("61905", "61908", exact=exact)
    assert _steady_rs(system) == pytest.approx(expected, rel=1e-10)
    g1, g2 = get_bearing("61905"), get_bearing("61908")
    if not exact:
        assert expected == pytest.approx(
            g1.pitch_diameter / (g1.pitch_diameter + g2.pitch_diameter), rel=1e-12)


class _EqualLayers(Assembly):
    """Two equal layer elements in series through a free ring: the PDR = 1 limit of docs/studies.md
    A, which no real double-layer bearing reaches (the inner bearing sits inside the outer)."""

    def __init__(self, layer):
        super().__init__("equal")
        self.drive = SpeedSource(None)
        self.inner_layer, self.outer_layer = layer(), layer()
        self.middle = Inertia(1e-4)
        self.housing = Fixed()
        self.shaft_speed = Input(0.0, "rad/s", "shaft speed")
        self.Rs = Variable(unit="1", description="speed ratio")
        connect(self.drive.flange, self.inner_layer.inner)
        connect(self.inner_layer.outer, self.middle.flange_a)
        connect(self.middle.flange_b, self.outer_layer.inner)
        connect(self.outer_layer.outer, self.housing.flange)

    def equations(self):
        return [self.drive.w_in == self.shaft_speed,
                self.Rs == self.middle.w / self.shaft_speed]


@pytest.mark.parametrize("fidelity", ["kinematic", "torque"])
def test_equal_pitch_diameters_give_one_half(fidelity):
    def layer():
        if fidelity == "torque":
            return PalmgrenBearing("61905", "ISO VG 32", smooth=False, load_dependent=False)
        return PureRollingLayer("61905")

    system = assemble(_EqualLayers(layer))
    assert _steady_rs(system) == pytest.approx(0.5, rel=1e-6)


@pytest.mark.parametrize(("inner", "outer"), [("61905", "61905"), ("61909", "61905")])
def test_an_inner_bearing_that_does_not_fit_inside_the_outer_is_rejected(inner, outer):
    """Two equal bearings, or the larger inside the smaller, built a bearing without a word."""
    with pytest.raises(ParameterError, match=r"must be smaller than the outer one"):
        double_layer_bearing(inner, outer, structure="Z")


def test_more_friction_in_inner_layer_raises_ratio():
    system = assemble(double_layer_bearing("61905", "61907", layer_options={
        "load_dependent": False}))
    base = _steady_rs(system)
    f0 = system.p0()[system.parameter_names.index("inner_layer.f0")]
    more = _steady_rs(system, parameters={"inner_layer.f0": 2.0 * f0})
    less = _steady_rs(system, parameters={"outer_layer.f0": 2.0 * f0})
    assert less < base < more


def test_grease_fill_in_inner_layer_raises_ratio():
    oil = Oil.from_iso_vg(32)
    ratios = []
    for fill in (0.2, 0.5, 0.9):
        lub = (Grease(oil, fill_fraction=fill), Grease(oil, fill_fraction=0.2))
        system = assemble(double_layer_bearing("61905", "61907", lubrication=lub,
                                               layer_options={"load_dependent": False}))
        ratios.append(_steady_rs(system))
    assert ratios[0] < ratios[1] < ratios[2]


def test_oil_and_grease_layers_drive_ratio_towards_the_extremes():
    oil = Oil.from_iso_vg(32, method="oil_mist")
    grease = Grease(Oil.from_iso_vg(100), fill_fraction=0.5)
    kw = {"layer_options": {"load_dependent": False}}
    both_oil = _steady_rs(assemble(double_layer_bearing(lubrication=(oil, oil), **kw)))
    grease_in = _steady_rs(assemble(double_layer_bearing(lubrication=(grease, oil), **kw)))
    grease_out = _steady_rs(assemble(double_layer_bearing(lubrication=(oil, grease), **kw)))
    assert grease_in > both_oil > grease_out
    assert grease_in > 0.5 and grease_out < 0.1


def test_lubricant_swap_is_a_parameter_change():
    system = assemble(double_layer_bearing("61905", "61907", layer_options={
        "load_dependent": False}))
    thin = Oil.from_iso_vg(10)
    rs_default = _steady_rs(system)
    rs_thin = _steady_rs(system, parameters={
        "inner_layer.nu": float(thin.kinematic_viscosity())})
    assert rs_thin < rs_default


def test_load_dependent_friction_changes_ratio_with_load():
    system = assemble(double_layer_bearing("61905", "61909", structure="I"))
    x = steady_state(system, inputs={"shaft_speed": 100.0, "Fr": 2000.0})
    light = steady_state(system, inputs={"shaft_speed": 100.0, "Fr": 0.0})
    obs_heavy = system.observe(0.0, x, np.array([2000.0, 0.0, 100.0]))
    obs_light = system.observe(0.0, light, np.array([0.0, 0.0, 100.0]))
    assert obs_heavy["Rs"] != pytest.approx(obs_light["Rs"], rel=1e-3)
    assert abs(obs_heavy["M_shaft"]) > abs(obs_light["M_shaft"])


@pytest.mark.parametrize("motor", ["dc", "pmsm"])
def test_motor_drive_energy_balance(motor):
    drive = motor_drive(double_layer_bearing(drive="flange"), motor=motor, speed_ref=300.0)
    system = assemble(drive)
    res = simulate(system, 1.0, rtol=1e-9, atol=1e-11, n_points=20001)
    assert res.final("shaft.w") == pytest.approx(300.0, rel=1e-3)
    work = cumulative_trapezoid(res["motor.motor.P_mech"], res.t)[-1]
    losses = cumulative_trapezoid(
        res["bearing.inner_layer.P_loss"] + res["bearing.outer_layer.P_loss"], res.t)[-1]
    p = dict(zip(system.parameter_names, system.p0(), strict=True))
    j_rot = p["motor.motor.J"] + p["shaft.J"]
    j_mid = sum(p[f"bearing.middle.{part}.J"] for part in (
        "inner_ring_of_inner_bearing", "sleeve", "outer_ring_of_outer_bearing"))
    kinetic = 0.5 * j_rot * res["shaft.w"] ** 2 + 0.5 * j_mid * res["bearing.middle.w"] ** 2
    assert work == pytest.approx(losses + kinetic[-1] - kinetic[0], rel=1e-6)


def test_motor_drive_follows_ramp_and_load_step():
    drive = motor_drive(double_layer_bearing(drive="flange"), motor="pmsm",
                        speed_ref=lambda t: 400.0 * _ramp(t, 0.2),
                        load_torque=lambda t: -0.05 * _step(t, 0.6))
    system = assemble(drive)
    res = simulate(system, 1.0, rtol=1e-8, atol=1e-10, n_points=1001)
    w = res["shaft.w"]
    # a PI loop follows a ramp with a bounded lag
    assert w[res.t.searchsorted(0.1)] == pytest.approx(200.0, rel=0.2)
    assert res.final("shaft.w") == pytest.approx(400.0, rel=2e-3)
    # after the load step the motor carries bearing friction plus the 0.05 N m load, through
    # the q current alone (id = 0): tau = 3/2 p psi iq
    tau_em = res.final("motor.motor.tau_em")
    assert tau_em == pytest.approx(0.05 - res.final("bearing.M_shaft"), rel=1e-2)
    assert res.final("motor.motor.iq") == pytest.approx(tau_em / (1.5 * 2 * 0.02), rel=1e-9)
    assert abs(res.final("motor.motor.id")) < 1e-9


def _ramp(t, t1):
    import casadi as ca

    return ca.fmin(t / t1, 1.0)


def _step(t, t1):
    import casadi as ca

    return ca.if_else(t >= t1, 1.0, 0.0)


def test_middle_ring_rigid_joins_equal_hand_merged_inertia():
    gi, go = get_bearing("61905"), get_bearing("61907")
    bodies = middle_ring_bodies(gi, go, "Z")

    class HandMerged(Assembly):
        def __init__(self):
            super().__init__("merged")
            self.drive = SpeedSource(W_SHAFT)
            self.inner_layer = PalmgrenBearing(gi, load_dependent=False)
            self.middle = Inertia(sum(b.inertia for b in bodies))
            self.outer_layer = PalmgrenBearing(go, load_dependent=False)
            self.housing = Fixed()
            connect(self.drive.flange, self.inner_layer.inner)
            connect(self.inner_layer.outer, self.middle.flange_a)
            connect(self.middle.flange_b, self.outer_layer.inner)
            connect(self.outer_layer.outer, self.housing.flange)

    composite = assemble(double_layer_bearing("61905", "61907", speed=W_SHAFT,
                                              layer_options={"load_dependent": False}))
    merged = assemble(HandMerged())
    assert composite.n_states == merged.n_states == 3
    a = simulate(composite, 0.5, rtol=1e-10, atol=1e-12)
    b = simulate(merged, 0.5, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(a["middle.w"], b["middle.w"], rtol=1e-8, atol=1e-9)


def test_i_type_requires_the_inner_bearing_to_fit():
    with pytest.raises(ParameterError, match="I-type"):
        double_layer_bearing("61905", "61907", structure="I")
    assert double_layer_bearing("61905", "61909").structure == "I"
    assert double_layer_bearing("61905", "61907").structure == "Z"


def test_optimal_ratio_and_design_report():
    gi, go = get_bearing("61905"), get_bearing("61907")
    ni, no = gi.limiting_speed, go.limiting_speed
    assert optimal_speed_ratio(gi, go) == pytest.approx(no / (ni + no))
    rep = design_report("61905", "61907")
    assert rep.max_shaft_speed <= rep.max_shaft_speed_optimal * (1 + 1e-12)
    assert 0 < rep.speed_utilisation <= 1
    optimal = design_report("61905", "61907", rs=rep.rs_optimal)
    assert optimal.speed_utilisation == pytest.approx(1.0)


def test_unknown_fidelity_is_a_clear_error():
    with pytest.raises(ParameterError, match="fidelity"):
        double_layer_bearing(fidelity="ball-level")


# ------------------------------------------------------------------ zero load (issue 15)
def test_palmgren_at_zero_load_gives_the_load_free_ratio():
    """Palmgren's M0 does not depend on the load: at zero load Rs is the M0 balance."""
    from bearingsim.studies.double_layer import steady_ratio

    system = assemble(double_layer_bearing("61905", "61907", fidelity="torque"))
    rs, torque, _ = steady_ratio(system, rpm_to_rad_s(10_000), loads=(0.0, 0.0))
    assert rs == pytest.approx(speed_ratio_palmgren("61905", "61907"), rel=2e-3)
    assert torque < 0.0


def test_skf_at_zero_load_is_a_named_error_not_the_start_guess():
    """The SKF model without seals or drag has no torque at zero load in either layer; the
    steady solver used to return its start guess (Rs = 0) as the answer."""
    from bearingsim.errors import SimulationError
    from bearingsim.studies.double_layer import steady_ratio

    system = assemble(double_layer_bearing("61905", "61907", fidelity="torque",
                                           friction_model="skf"))
    with pytest.raises(SimulationError, match=r"not unique.*middle\..*w.*SKF without seals"):
        steady_ratio(system, rpm_to_rad_s(10_000), loads=(0.0, 0.0))
    rs, _, _ = steady_ratio(system, rpm_to_rad_s(10_000), loads=(100.0, 0.0))
    assert 0.1 < rs < 0.4


def test_a_steady_state_that_is_not_unique_raises_unless_any_will_do():
    from bearingsim.errors import SimulationError
    from bearingsim.simulation import steady_state
    from tests.models import DampersInSeries

    system = assemble(DampersInSeries())  # any common speed of both inertias is steady
    with pytest.raises(SimulationError, match=r"not unique.*j\d\.w"):
        steady_state(system)
    x = steady_state(system, require_unique=False)
    assert x[system.state_names.index("j1.w")] == pytest.approx(
        x[system.state_names.index("j2.w")])


def test_oil_bath_level_reaches_each_layer_from_its_own_lowest_ball():
    """Issue 15 item 5: one bath level, measured from the outer layer's lowest ball centre; the
    inner layer sits (dm2 - dm1)/2 = 5.75 mm higher (61905/61907). At 2 mm only the outer
    layer's balls are immersed (drag, no starvation): more torque outside, lower Rs. At 10 mm
    both are. SKF model only (the drag term); before, the level given through layer_options
    failed to assemble (a symbolic pitch diameter in a range check)."""
    from bearingsim.studies.double_layer import steady_ratio

    def rs(level):
        system = assemble(double_layer_bearing("61905", "61907", friction_model="skf",
                                               oil_level=level))
        return steady_ratio(system, 1000.0, (200.0, 0.0))[0]

    dry_bath, outer_only, both = rs(None), rs(0.002), rs(0.010)
    assert outer_only < dry_bath < both
    bearing = double_layer_bearing("61905", "61907", friction_model="skf", oil_level=0.002)
    assert "oil_level" not in bearing.inner_layer._options
    assert bearing.outer_layer._options["oil_level"] == 0.002
    with pytest.raises(ParameterError, match="friction_model='skf'"):
        double_layer_bearing("61905", "61907", oil_level=0.01)
    with pytest.raises(ParameterError, match="once"):
        double_layer_bearing("61905", "61907", friction_model="skf", oil_level=0.01,
                             layer_options={"oil_level": 0.01})


def test_lubrication_method_per_layer_sets_each_layers_f0():
    """Oil bath inside, oil mist outside: Schaeffler HR 1 p. 58, 619 series: f0 1.7 and 1.1."""
    system = assemble(double_layer_bearing("61905", "61907",
                                           lubrication_method=("oil_bath", "oil_mist")))
    p = dict(zip(system.parameter_names, system.p0(), strict=True))
    assert (p["inner_layer.f0"], p["outer_layer.f0"]) == (1.7, 1.1)
    with pytest.raises(ParameterError, match="lubrication_method"):
        double_layer_bearing("61905", "61907", lubrication_method="splash")


def test_middle_ring_drag_is_a_couette_damper_to_the_housing():
    """Issue 15 item 5: the middle ring's own drag in the oil. At the steady state the torque the
    inner layer passes on equals the outer layer's plus c w_middle (c: the laminar Couette
    coefficient); the drag slows the middle ring, so Rs falls."""
    from bearingsim.physics.drag import couette_damping, taylor_number
    from bearingsim.studies.double_layer import steady_ratio

    gap = {"radius": 0.0225, "gap": 0.5e-3, "length": 0.01}
    plain = assemble(double_layer_bearing("61905", "61907"))
    dragged = assemble(double_layer_bearing("61905", "61907", middle_ring_drag=gap))
    rs_plain = steady_ratio(plain, 1000.0, (200.0, 0.0))[0]
    rs, _, x = steady_ratio(dragged, 1000.0, (200.0, 0.0))
    assert rs < rs_plain
    u = dragged.u_default()
    u[dragged.input_names.index("shaft_speed")] = 1000.0
    u[dragged.input_names.index("Fr")] = 200.0
    v = dragged.observe(0.0, x, u)
    oil = get_lubricant("ISO VG 32")
    c = couette_damping(0.0225, 0.5e-3, 0.01, float(oil.dynamic_viscosity()))
    balance = -v["inner_layer.M"] - (-v["outer_layer.M"]) - c * v["w_middle"]
    assert abs(balance) < 1e-9 * abs(v["inner_layer.M"])
    assert v["middle_Ta"] == pytest.approx(
        taylor_number(v["w_middle"], 0.0225, 0.5e-3, float(oil.kinematic_viscosity())))
    with pytest.raises(ParameterError, match="needs gap"):
        double_layer_bearing("61905", "61907", middle_ring_drag={"radius": 0.02, "length": 0.01})


def test_speed_ratio_is_exact_at_creep_speeds_and_zero_at_rest():
    """Issue 16 item 4: Rs = w_middle w_shaft / (w_shaft^2 + 1e-6) was the 0/0 at rest
    regularized at 1e-3 rad/s, so below ~0.01 rad/s (the first save points of a spin-up from
    rest) it showed a ratio near 0 instead of w_middle / w_shaft: 0.004 instead of the
    pure-rolling 0.43 at 1e-4 rad/s. It is now regularized at 1e-6 rad/s (exact to 1e-4 from
    1e-4 rad/s) and 0 at rest (a still middle ring: the limit of a spin-up from rest)."""
    from bearingsim.physics.double_layer_theory import speed_ratio_pure_rolling

    system = assemble(double_layer_bearing(fidelity="kinematic"))
    creep = simulate(system, 20.0, inputs={"shaft_speed": 1e-4}, n_points=5)
    rs = speed_ratio_pure_rolling("61905", "61907")
    assert creep.final("w_middle") / creep.final("w_shaft") == pytest.approx(rs, rel=1e-6)
    assert creep.final("Rs") == pytest.approx(rs, rel=1e-4)
    assert creep["Rs"][0] == 0.0  # at t = 0 the middle ring is still: Rs = 0, finite
    ramp = simulate(system, 0.01, inputs={"shaft_speed": lambda t: 0.1 * t}, n_points=11)
    w_s, w_m = ramp["w_shaft"][1:], ramp["w_middle"][1:]
    assert np.all(w_s < 2e-3)
    assert ramp["Rs"][1:] == pytest.approx(w_m / w_s, rel=1e-3)
