"""Deep-groove bearing, dynamic level (docs/studies.md, section C): cage slip against the
epicyclic speed, dynamic vs quasi-static contact loads, spin without traction, energy
conservation, duty-cycle trends and a long run."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
from bearingsim.physics.ball_equilibrium import static_state
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.physics.lubricant import Dry
from bearingsim.simulation import simulate
from bearingsim.studies.deep_groove import DUTY_CYCLE, duty_condition, post_process

FAST = {"t_end": 0.03, "ramp": 0.01, "n_slices": 0, "n_points": 61}


@pytest.fixture(scope="module")
def duty_runs():
    """Conditions 1 (low speed, high load) and 4 (high speed, light load), short runs."""
    return {k: duty_condition(k, **FAST) for k in (1, 4)}


def test_cage_runs_near_the_epicyclic_speed_at_high_load_low_speed(duty_runs):
    res, design = duty_runs[1]
    tail = res.t > 0.02
    ratio = res["w_cage"][tail] / res["w_inner"][tail]
    assert np.mean(ratio) == pytest.approx(design.epicyclic_ratio, rel=0.03)
    assert abs(np.mean(res["slip"][tail])) < 0.03


def test_slip_is_larger_at_light_load_and_high_speed(duty_runs):
    s1 = post_process(*duty_runs[1], "ISO VG 32", DUTY_CYCLE[0][1], window=0.3)
    s4 = post_process(*duty_runs[4], "ISO VG 32", DUTY_CYCLE[3][1], window=0.3)
    assert s4.slip > s1.slip
    # lives: lower at the higher load (Lundberg-Palmgren and ISO 281 alike), film at speed
    assert s1.life_lp < s4.life_lp and s1.life_iso281 < s4.life_iso281
    assert s1.h_min > 0 and s4.h_min > 0


def test_dynamic_contact_loads_equal_quasi_static_ones(duty_runs):
    res, design = duty_runs[1]
    q_dyn = np.array([res[f"inner[{j}].Q"][-1] for j in range(7)])
    q_qs = static_state(design, {"Fx": DUTY_CYCLE[0][1]}, w_cage=res.final("w_cage"),
                        theta0=res.final("ball[0].theta")).q_inner
    assert q_dyn.max() == pytest.approx(q_qs.max(), rel=0.05)
    assert np.sum(q_dyn) == pytest.approx(np.sum(q_qs), rel=0.05)


def _frictionless(**kw):
    return deep_groove_ball_bearing(
        "6304", "dynamic_massive_balls", lubricant=Dry(0.0), speed=0.0, traction_scale=0.0,
        pocket_mu=0.0, land_mu=0.0, **kw)


def test_without_traction_the_ball_spin_keeps_its_initial_value():
    system = assemble(_frictionless(loads={"Fx": 500.0}),
                      outputs=["ball[0].wr", "ball[0].wt", "ball[0].wz", "ball[0].w_orbit"])
    spin = {"ball[0].wr": 30.0, "ball[0].wt": -20.0, "ball[0].wz": 400.0}
    res = simulate(system, 0.005, x0=spin, method="cvodes", rtol=1e-8, atol=1e-10,
                   n_points=21, progress=False)
    w = np.sqrt(res["ball[0].wr"] ** 2 + res["ball[0].wt"] ** 2 + res["ball[0].wz"] ** 2)
    assert np.allclose(w, np.linalg.norm(list(spin.values())), rtol=1e-6)
    assert np.allclose(res["ball[0].wz"], 400.0, rtol=1e-6)


def _hertz_energy(k, delta, smooth=2e-8):
    u = 0.5 * (delta + np.sqrt(delta**2 + smooth**2))
    return k * (0.4 * u**2.5 + 0.5 * smooth**2 * np.sqrt(u))


def test_energy_is_conserved_without_friction_drag_and_damping():
    load = 500.0
    bearing = _frictionless(loads={"Fx": load}, damping=0.0, cage_damping=0.0)
    design = bearing.design
    system = assemble(bearing)
    x_start = system.x0()
    x0 = {"ring.x_um": x_start[system.state_names.index("ring.x_um")] + 3.0}
    res = simulate(system, 0.003, x0=x0, method="cvodes", rtol=1e-9, atol=1e-11,
                   n_points=61, progress=False)
    m_b, j_b = design.ball_mass, design.ball_inertia
    energy = 0.5 * design.ring_mass * (res["ring.vx"] ** 2 + res["ring.vy"] ** 2
                                        + res["ring.vz"] ** 2) - load * res["ring.x"]
    for j in range(7):
        b = f"ball[{j}]"
        energy = energy + 0.5 * m_b * (res[f"{b}.vr"] ** 2 + (res[f"{b}.r"] * res[
            f"{b}.w_orbit"]) ** 2 + res[f"{b}.vz"] ** 2) + 0.5 * j_b * (
            res[f"{b}.wr"] ** 2 + res[f"{b}.wt"] ** 2 + res[f"{b}.wz"] ** 2)
        energy = energy + _hertz_energy(design.k_inner, res[f"inner[{j}].delta"])
        energy = energy + _hertz_energy(design.k_outer, res[f"outer[{j}].delta"])
    kinetic = 0.5 * design.ring_mass * res["ring.vx"] ** 2
    assert kinetic.max() > 1e-4  # the ring really oscillates
    assert np.ptp(energy) < 1e-3 * kinetic.max()


LONG_REVOLUTIONS = 300


@pytest.mark.slow
def test_long_run_without_drift():
    """Condition 1 over 300 inner-ring revolutions (10.4 s, about 1 min): cage speed, ball loads
    and the kinetic energy of balls and cage stay bounded and periodic (no drift)."""
    n_rpm, load = DUTY_CYCLE[0]
    t_end = LONG_REVOLUTIONS * 60.0 / n_rpm
    res, design = duty_condition(1, t_end=t_end, ramp=0.02, n_slices=0, n_points=2001)
    assert res.t[-1] == pytest.approx(t_end)
    steady = res.t > 0.5
    m_b, j_b = design.ball_mass, design.ball_inertia
    r_p = 0.5 * design.geometry.pitch_diameter
    kinetic = sum(0.5 * m_b * (r_p * res[f"ball[{j}].w_orbit"]) ** 2 + 0.5 * j_b * (
        res[f"ball[{j}].wr"] ** 2 + res[f"ball[{j}].wt"] ** 2 + res[f"ball[{j}].wz"] ** 2)
        for j in range(7)) + 0.5 * design.cage.inertia * res["w_cage"] ** 2
    q = np.array([res[f"inner[{j}].Q"] for j in range(7)])
    series = {"w_cage": res["w_cage"], "q_max": q.max(axis=0), "kinetic": kinetic,
              "slip": res["slip"]}
    for name, y in series.items():
        y = y[steady]
        assert np.all(np.isfinite(y)), name
        thirds = [np.mean(c) for c in np.array_split(y, 3)]
        scale = abs(np.mean(y)) if name != "slip" else 1.0
        assert np.ptp(thirds) < 2e-3 * scale, (name, thirds)
    assert abs(np.mean(res["slip"][steady])) < 0.05
    assert q[:, steady].max() < 1.2 * static_state(design, {"Fx": load}).q_inner.max()
    eccentricity = np.hypot(res["cage.x"], res["cage.y"])[steady]
    assert eccentricity.max() < 1.05 * design.cage.guide_clearance


def test_design_constants_follow_harris_geometry():
    d = bearing_design("6304")
    g = d.geometry
    assert d.rho_inner > 0.5 * g.pitch_diameter > d.rho_outer
    assert d.rho_inner - d.rho_outer == pytest.approx(
        g.groove_centre_distance - 0.5 * g.diametral_clearance)
    # groove bottoms of docs/studies.md, section C: 22.77 and 13.24 mm (within rounding of the
    # clearance split)
    assert d.rho_outer + g.fo * g.ball_diameter == pytest.approx(22.77e-3, abs=1e-5)
    assert d.rho_inner - g.fi * g.ball_diameter == pytest.approx(13.24e-3, abs=1e-5)
