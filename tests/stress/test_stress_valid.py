"""The numerical-stability half of the stress suite: over 10^4 *valid* operating points (speed,
load, lubricant, temperature, clearance, preload) across the physics functions and every
assembly and fidelity level, each checked against an invariant that can fail:

* power balance: friction torque opposes the speed (``M w < 0``), drag opposes the velocity;
* symmetry: torque and traction odd in the speed, the speed ratio even; statics mirrored loads
  give mirrored displacements;
* monotone trends: more load, more viscosity or more speed give more friction, a thicker film
  or a larger displacement;
* exact scaling laws (Hertz ``delta ~ Q^(2/3)``, ``p_max = 3 Q / (2 pi a b)``, rating life
  ``(C/P)^3``);
* agreement between fidelity levels where they overlap (ISO/TS 16281 against the exact statics,
  the kinematic speed ratio against the pure-rolling formula, the torque level's transient end
  value against its steady state);
* Newton residuals of the steady states.

Each case must succeed: a named error is a failure here (the bad inputs, which must be refused,
are in ``test_stress_generated.py``). Every case is counted (``tests/stress/conftest.py``) and
bounded in time; cases are drawn with a seeded generator so a failure reproduces.
``test_mutation_*`` replace a solver or a physics function by one that raises or lies and check
that these checks then fail.
"""

from __future__ import annotations

import importlib
import math
import warnings
from functools import cache

import numpy as np
import pytest

from bearingsim.catalog import get_bearing
from bearingsim.physics import drag, film, friction, hertz, life, traction
from bearingsim.physics.lubricant import get_lubricant, known_lubricants
from tests.stress.conftest import valid_case

OILS = [name for name in known_lubricants() if name.startswith("ISO VG")]
LUBRICANTS = [get_lubricant(name) for name in known_lubricants()]
SKF_BEARINGS = ["6304", "6204", "61905", "61907"]


def rng(seed: int) -> np.random.Generator:
    return np.random.default_rng(seed)


def log_uniform(r: np.random.Generator, low: float, high: float) -> float:
    return float(np.exp(r.uniform(np.log(low), np.log(high))))


# ------------------------------------------------------------------ physics functions
# Each check draws a batch of n operating points and evaluates them as arrays (the functions are
# vectorized); every point must pass (np.all), and each counts as one valid case.
def log_uniform_n(r: np.random.Generator, low: float, high: float, n: int) -> np.ndarray:
    return np.exp(r.uniform(np.log(low), np.log(high), n))


def check_palmgren(r: np.random.Generator, n: int) -> None:
    g = get_bearing(str(r.choice(SKF_BEARINGS)))
    oil = LUBRICANTS[r.integers(len(LUBRICANTS))]
    w = log_uniform_n(r, 1.0, 0.9 * g.limiting_speed, n)
    c0 = g.static_load_rating
    p1 = r.uniform(10.0, 0.9 * c0, n)
    temp = r.uniform(273.15 + 20.0, 273.15 + 90.0, n)

    def torque(speed, load=p1, t=temp):
        return friction.palmgren_torque(speed, g.pitch_diameter, oil, "deep_groove_ball",
                                        load_P1=load, P0=load, C0=c0, T=t)

    m = torque(w)
    assert np.all(m * w < 0.0), "friction power >= 0"
    np.testing.assert_allclose(torque(-w), -m, rtol=1e-12)
    assert np.all(np.abs(torque(w, 1.1 * p1)) > np.abs(m))  # load-dependent term grows
    assert np.all(np.abs(torque(w, t=temp - 10.0)) >= np.abs(m))  # colder oil, more viscous


def check_skf(r: np.random.Generator, n: int) -> None:
    g = get_bearing(str(r.choice(SKF_BEARINGS)))
    oil = get_lubricant(str(r.choice(OILS)))
    w = log_uniform_n(r, 1.0, 0.9 * g.limiting_speed, n)
    fr = r.uniform(10.0, 0.5 * g.static_load_rating, n)
    fa = r.uniform(0.0, 0.2, n) * fr
    kw = {"C0": g.static_load_rating, "d": g.bore, "D": g.outside_diameter}

    def torque(speed, radial=fr):
        return friction.skf_friction_torque(speed, g.pitch_diameter, oil, g.series, radial,
                                            fa, **kw)

    m = torque(w)
    assert np.all(m * w < 0.0), "friction power >= 0"
    np.testing.assert_allclose(torque(-w), -m, rtol=1e-12)
    assert np.all(np.abs(torque(w, 1.2 * fr)) > np.abs(m))


def check_hertz(r: np.random.Generator, n: int) -> None:
    rx = log_uniform_n(r, 5e-4, 2e-2, n)
    ry = rx * log_uniform_n(r, 1.0, 50.0, n)
    q = log_uniform_n(r, 1.0, 1e4, n)
    e = r.uniform(1.5e11, 3.2e11)
    c = hertz.hertz_contact(q, rx, ry, e)
    np.testing.assert_allclose(c.max_pressure, 3.0 * q / (2.0 * math.pi * c.a * c.b),
                               rtol=1e-9)
    assert np.all(c.a >= c.b) and np.all(c.b > 0.0)
    c8 = hertz.hertz_contact(8.0 * q, rx, ry, e)
    np.testing.assert_allclose(c8.approach, 4.0 * c.approach, rtol=1e-9)  # delta ~ Q^(2/3)
    np.testing.assert_allclose(c8.a, 2.0 * c.a, rtol=1e-9)  # a ~ Q^(1/3)


def check_film(r: np.random.Generator, n: int) -> None:
    rx = log_uniform_n(r, 1e-3, 2e-2, n)
    ry = rx * log_uniform_n(r, 2.0, 30.0, n)
    q = log_uniform_n(r, 10.0, 5e3, n)
    u = log_uniform_n(r, 0.05, 30.0, n)
    eta = log_uniform_n(r, 1e-3, 0.5, n)
    alpha = r.uniform(1e-8, 3e-8, n)
    e = 2.3e11
    f = film.hamrock_dowson(q, u, rx, ry, e, eta, alpha)
    assert np.all(f.h_min > 0.0) and np.all(f.h_min < f.h_c)
    np.testing.assert_allclose(f.U, eta * u / (e * rx), rtol=1e-12)
    assert np.all(film.hamrock_dowson(q, 1.5 * u, rx, ry, e, eta, alpha).h_min > f.h_min)
    assert np.all(film.hamrock_dowson(q, u, rx, ry, e, 1.5 * eta, alpha).h_min > f.h_min)
    assert np.all(film.hamrock_dowson(2.0 * q, u, rx, ry, e, eta, alpha).h_min < f.h_min)


def check_traction_and_drag(r: np.random.Generator, n: int) -> None:
    s = log_uniform_n(r, 1e-5, 10.0, n) * r.choice([-1.0, 1.0], n)
    mu = traction.ehl_traction(s)
    np.testing.assert_allclose(traction.ehl_traction(-s), -mu, rtol=1e-12)
    assert np.all(mu * s > 0.0) and np.all(np.abs(mu) <= traction.ehl_traction_peak()
                                           * (1 + 1e-12))
    mu_c = r.uniform(0.01, 0.3)
    c = traction.regularized_coulomb(s, mu_c)
    assert np.all(c * s > 0.0) and np.all(np.abs(c) <= mu_c)
    v = log_uniform_n(r, 1e-3, 50.0, n)
    dw = r.uniform(2e-3, 3e-2)
    rho, eta = r.uniform(800.0, 950.0), log_uniform(r, 1e-3, 0.5)
    fd = drag.ball_drag_force(v, dw, rho, eta)
    assert np.all(fd * v < 0.0), "drag must oppose the velocity"
    np.testing.assert_allclose(drag.ball_drag_force(-v, dw, rho, eta), -fd, rtol=1e-12)
    assert np.all(np.abs(drag.ball_drag_force(1.5 * v, dw, rho, eta)) > np.abs(fd))


def check_life(r: np.random.Generator, n: int) -> None:
    c = log_uniform_n(r, 1e3, 1e6, n)
    p = c * log_uniform_n(r, 0.01, 1.0, n)
    life10 = life.rating_life(c, p)
    np.testing.assert_allclose(life10, (c / p) ** 3, rtol=1e-12)
    np.testing.assert_allclose(life.rating_life(c, p / 2.0), 8.0 * life10, rtol=1e-12)
    w = log_uniform_n(r, 1.0, 1e3, n)
    np.testing.assert_allclose(life.life_hours(life10, w),
                               life10 * 1e6 / (w * 60.0 / (2.0 * math.pi)) / 60.0, rtol=1e-9)


PHYSICS = {"palmgren_torque": (check_palmgren, 24, 100),
           "skf_friction_torque": (check_skf, 24, 100),
           "hertz_contact": (check_hertz, 8, 40),
           "hamrock_dowson": (check_film, 20, 100),
           "traction_and_drag": (check_traction_and_drag, 20, 100),
           "rating_life": (check_life, 15, 100)}
"""Invariant check, number of batches and batch size per physics function family."""


@pytest.mark.parametrize("name", list(PHYSICS))
def test_physics_invariants_on_valid_arguments(name):
    check, batches, n = PHYSICS[name]
    r = rng(sum(map(ord, name)))
    for _ in range(batches):
        with valid_case(n):
            check(r, n)


# ------------------------------------------------------------------ steady and quasi-static
@cache
def torque_system(friction_model: str):
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing

    return assemble(double_layer_bearing("61905", "61907", fidelity="torque",
                                         friction_model=friction_model),
                    outputs=["Rs", "M_shaft"])


def check_steady_torque_level(r: np.random.Generator, friction_model: str) -> None:
    from bearingsim.studies.double_layer import steady_ratio

    system = torque_system(friction_model)
    w = log_uniform(r, 5.0, 1000.0)
    fr, fa = r.uniform(200.0, 3000.0), r.uniform(0.0, 300.0)
    params = {}
    if friction_model == "palmgren":
        nu = float(get_lubricant(str(r.choice(OILS))).kinematic_viscosity(
            r.uniform(293.0, 363.0)))
        params = {"inner_layer.nu": nu, "outer_layer.nu": nu}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the SKF model's other branch (tested on its own)
        rs, m, x = steady_ratio(system, w, loads=(fr, fa), parameters=params)
    assert 0.0 < rs < 1.0, f"Rs = {rs}"
    assert m * w < 0.0, f"shaft friction power {m * w} W >= 0"
    u = system.u_default()
    u[system.input_names.index("shaft_speed")] = w
    u[system.input_names.index("Fr")], u[system.input_names.index("Fa")] = fr, fa
    residual = system.rhs(0.0, x, u, system.p0(params))
    assert np.max(np.abs(residual)) <= 1e-6 * max(1.0, w), f"Newton residual {residual}"
    if friction_model == "palmgren":  # one branch: even in the speed, torque odd
        rs_neg, m_neg, _ = steady_ratio(system, -w, loads=(fr, fa), parameters=params)
        assert rs_neg == pytest.approx(rs, rel=1e-7, abs=1e-9)
        assert m_neg == pytest.approx(-m, rel=1e-7)
        _, m_fast, _ = steady_ratio(system, 1.5 * w, loads=(fr, fa), parameters=params)
        assert abs(m_fast) > abs(m)


@pytest.mark.parametrize(("friction_model", "n"), [("palmgren", 40), ("skf", 60)])
def test_torque_level_steady_states(friction_model, n):
    r = rng(11 if friction_model == "palmgren" else 12)
    for _ in range(n):
        with valid_case():
            check_steady_torque_level(r, friction_model)


def check_deep_groove_statics(r: np.random.Generator) -> None:
    from bearingsim.studies.deep_groove_statics import deep_groove_statics

    bearing = str(r.choice(["6304", "6204", "61905"]))
    c0 = get_bearing(bearing).static_load_rating
    fx = r.uniform(0.05, 0.5) * c0
    fz = r.uniform(0.0, 0.2) * fx
    clearance = float(r.choice([0.0, 5e-6, 15e-6]))
    loads = {"Fx": fx, "Fy": 0.0, "Fz": fz, "Mx": 0.0, "My": 0.0}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        exact = deep_groove_statics(bearing, loads, clearance=clearance)
        mirrored = deep_groove_statics(bearing, {**loads, "Fz": -fz}, clearance=clearance)
        more = deep_groove_statics(bearing, {**loads, "Fx": 1.3 * fx}, clearance=clearance)
        iso = deep_groove_statics(bearing, loads, clearance=clearance, method="iso_ts_16281")
    d = exact.state
    assert d[0] > 0.0 and abs(d[1]) < 1e-9 * max(1e-6, abs(d[0])) + 1e-15
    assert mirrored.state[2] == pytest.approx(-d[2], rel=1e-6, abs=1e-12)
    assert mirrored.state[0] == pytest.approx(d[0], rel=1e-6)
    assert more.state[0] > d[0]
    assert np.all(np.linalg.eigvalsh(0.5 * (exact.stiffness + exact.stiffness.T))[:3] > -1e-6
                  * np.max(np.abs(exact.stiffness)))
    # ISO/TS 16281 and the exact contact geometry overlap for moderate loads: within 5 %
    assert iso.state[0] == pytest.approx(d[0], rel=0.05)


def test_deep_groove_statics_valid_loads():
    r = rng(21)
    for _ in range(12):
        with valid_case():
            check_deep_groove_statics(r)


@cache
def duplex(arrangement: str):
    from bearingsim.studies.duplex import DuplexModel

    return DuplexModel("7020C", arrangement=arrangement)


def test_duplex_pair_equilibria_are_monotone():
    r = rng(31)
    for arrangement in ("DF", "DB"):
        model = duplex(arrangement)
        for _ in range(2):
            with valid_case():
                fz = r.uniform(200.0, 3000.0)
                fx = r.uniform(0.0, 1000.0)
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    eq = model.equilibrium({"Fx": fx, "Fz": fz, "My": 0.0})
                    eq_more = model.equilibrium({"Fx": fx, "Fz": 1.5 * fz, "My": 0.0})
                # more axial load, more axial displacement (whatever the preload's offset)
                assert eq_more.displacement[2] > eq.displacement[2]
                k = model.stiffness(eq)
                assert np.all(np.diag(k)[[0, 2]] > 0.0)


# ------------------------------------------------------------------ transient runs
@cache
def kinematic_system(fidelity: str):
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing

    return assemble(double_layer_bearing("61905", "61908", fidelity=fidelity),
                    outputs=["Rs", "w_middle"])


@pytest.mark.parametrize("fidelity", ["kinematic", "kinematic_approx"])
def test_kinematic_levels_settle_on_the_pure_rolling_ratio(fidelity):
    from bearingsim.physics.double_layer_theory import speed_ratio_pure_rolling
    from bearingsim.simulation import simulate

    system = kinematic_system(fidelity)
    expected = speed_ratio_pure_rolling(get_bearing("61905"), get_bearing("61908"),
                                        exact=fidelity == "kinematic")
    r = rng(41)
    for _ in range(8):
        with valid_case():
            w = log_uniform(r, 10.0, 1000.0)
            res = simulate(system, 0.5, inputs={"shaft_speed": w}, n_points=5,
                           initial="steady")
            assert res.final("Rs") == pytest.approx(expected, rel=1e-6)


def test_torque_level_transient_ends_at_its_steady_state():
    from bearingsim.simulation import simulate
    from bearingsim.studies.double_layer import steady_ratio

    system = torque_system("palmgren")
    r = rng(51)
    for _ in range(6):
        with valid_case():
            w = log_uniform(r, 50.0, 500.0)
            loads = (r.uniform(200.0, 2000.0), r.uniform(0.0, 200.0))
            rs, _, _ = steady_ratio(system, w, loads=loads)
            res = simulate(system, 5.0, n_points=3, method="cvodes",
                           inputs={"shaft_speed": w, "Fr": loads[0], "Fa": loads[1]})
            assert res.final("Rs") == pytest.approx(rs, rel=1e-3)


def valid_scene(r: np.random.Generator):
    """A generated valid scene: the double-layer bearing at the torque level, a speed ramp to
    a drawn speed, drawn loads and lubricant, a short run."""
    from bearingsim.scenes.scene import scene_from_dict

    w = log_uniform(r, 20.0, 800.0)
    return scene_from_dict({
        "title": "generated",
        "assembly": {"name": "double_layer_bearing", "fidelity": "torque",
                     "inner": "61905", "outer": str(r.choice(["61907", "61908"])),
                     "lubrication": str(r.choice(OILS))},
        "inputs": {"shaft_speed": f"{w!r} * ramp(0, 0.05)",
                   "Fr": float(r.uniform(100.0, 2000.0)), "Fa": float(r.uniform(0.0, 200.0))},
        "outputs": ["Rs", "M_shaft", "w_shaft"],
        "simulation": {"t_end": 0.2, "n_points": 21, "method": str(r.choice(["BDF",
                                                                             "cvodes"]))},
    }), w


def test_generated_valid_scenes_run():
    from bearingsim.scenes.preparation import prepare
    from bearingsim.scenes.scene_simulation import output_series, run_simulation

    r = rng(61)
    for _ in range(5):
        with valid_case():
            scene, w = valid_scene(r)
            prep = prepare(scene)
            series = output_series(prep, run_simulation(prep))
            assert series["w_shaft"][-1] == pytest.approx(w, rel=1e-9)
            power = series["M_shaft"] * series["w_shaft"]
            assert np.all(power[1:] < 0.0), "friction must take power from the shaft"
            assert np.all((series["Rs"][1:] > 0.0) & (series["Rs"][1:] < 1.0))


# ------------------------------------------------------------------ mutation checks
def test_mutation_a_raising_steady_state_fails_the_checks(monkeypatch):
    """With the steady-state solver replaced by one that raises, the valid-case checks fail
    (the old suite counted such runs as 'a named error' and passed)."""
    import bearingsim.studies.double_layer as study
    from bearingsim.errors import BearingsimError, SimulationError

    def broken(*args, **kwargs):
        raise SimulationError("mutant: no steady state")

    monkeypatch.setattr(study, "steady_state", broken)
    with pytest.raises(BearingsimError):
        check_steady_torque_level(rng(1), "palmgren")


def test_mutation_a_raising_integrator_fails_the_checks(monkeypatch):
    from bearingsim.errors import BearingsimError, SimulationError
    from bearingsim.simulation import integrators

    def broken(self, problem):
        raise SimulationError("mutant: integrator failed")

    for cls in (integrators.ScipyIntegrator, integrators.SundialsIntegrator):
        monkeypatch.setattr(cls, "run", broken)
    with pytest.raises(BearingsimError):
        test_torque_level_transient_ends_at_its_steady_state()
    with pytest.raises(BearingsimError):
        test_generated_valid_scenes_run()


@pytest.mark.parametrize(("module", "name", "check", "mutant"), [
    (friction, "palmgren_m0", check_palmgren, lambda *a, **k: -1.0),  # drives the shaft
    (friction, "skf_friction_components", check_skf, None),
    (hertz, "hertz_contact", check_hertz, None),
    (film, "minimum_film_thickness", check_film, lambda *a, **k: 1e-7),
    (traction, "ehl_traction", check_traction_and_drag, lambda s, *a, **k: abs(s)),
    (life, "rating_life", check_life, lambda c, p, exponent=3.0: (c / p) ** 3.3),
])
def test_mutation_wrong_or_raising_physics_fails_the_checks(monkeypatch, module, name, check,
                                                          mutant):
    """Each physics check fails when its function lies (a constant, a wrong exponent, an even
    traction) or raises."""
    from bearingsim.errors import BearingsimError, ParameterError

    def raising(*args, **kwargs):
        raise ParameterError("mutant")

    # the package that re-exports the function and the module that defines it (whose other
    # functions call it by that module's global)
    homes = {module, importlib.import_module(getattr(module, name).__module__)}
    for replacement in ([raising] if mutant is None else [raising, mutant]):
        for home in homes:
            monkeypatch.setattr(home, name, replacement)
        with pytest.raises((AssertionError, BearingsimError)):
            check(rng(3), 50)


# ------------------------------------------------------------------ the time limits themselves
def test_case_limit_and_test_limit_both_fire():
    """A case's limit fires inside a test's; the test's clock keeps running through its cases
    (the old case limit re-armed nothing, so a test of many cases had no limit); a case whose
    limit is longer than the test's remaining time ends at the test's limit."""
    import time

    from tests.stress.conftest import Hang, time_limit

    with time_limit(5.0):
        with pytest.raises(Hang, match="exceeded 0.1 s"):
            with time_limit(0.1):
                time.sleep(2.0)
    with pytest.raises(Hang, match="exceeded 0.3 s"):
        with time_limit(0.3):
            with time_limit(10.0):
                pass  # a quick case
            time.sleep(2.0)
    start = time.monotonic()
    with pytest.raises(Hang, match="enclosing limit|exceeded 0.2 s"):
        with time_limit(0.2):
            with time_limit(10.0):
                time.sleep(2.0)
    assert time.monotonic() - start < 1.0
