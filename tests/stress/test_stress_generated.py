"""The generated bad-input half of the stress suite: derandomized arguments over every public
physics function, the scene parser and expression language, and every assembly and fidelity
level, most of them outside the valid ranges (NaN, infinities, negative loads, bogus names).
Each case runs under its own wall-clock bound and must either be refused with a named
:class:`~bearingsim.errors.BearingsimError` (counted as *invalid refused*) or, where the draw
happens to be valid, give finite numbers (counted apart). The valid operating points with their
invariants are in ``test_stress_valid.py``; both counts are printed at the end of the run
(``tests/conftest.py``).
"""

from __future__ import annotations

import importlib
import inspect
import math
import pkgutil
import time
from contextlib import contextmanager
from functools import cache

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import bearingsim.physics
from bearingsim.catalog import get_bearing, list_bearings
from bearingsim.errors import BearingsimError
from bearingsim.physics.lubricant import get_lubricant, known_lubricants
from tests.stress.conftest import CASE_LIMIT_S, STRESS, _count, time_limit

__all__ = ["STRESS"]  # this process's counts of both kinds, read by tests/conftest.py


def _settings(n: int):
    return settings(max_examples=n, deadline=None, derandomize=True, database=None,
                    suppress_health_check=list(HealthCheck))


@contextmanager
def case():
    """One generated bad-input case: timed, bounded; counted by :func:`outcome`."""
    with time_limit(CASE_LIMIT_S):
        yield


def _finite(value, allow_inf: bool = False) -> None:
    """No NaN (and no infinity unless allowed) anywhere in a result."""
    if isinstance(value, (str, bytes, bool, type(None))):
        return
    if isinstance(value, dict):
        for v in value.values():
            _finite(v, allow_inf)
        return
    if isinstance(value, (tuple, list)):
        for v in value:
            _finite(v, allow_inf)
        return
    if hasattr(value, "__dataclass_fields__"):
        for name in value.__dataclass_fields__:
            _finite(getattr(value, name), allow_inf)
        return
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return
    assert not np.any(np.isnan(arr)), f"NaN in {value!r:.200}"
    if not allow_inf:
        assert np.all(np.isfinite(arr)), f"inf in {value!r:.200}"


def outcome(call, allow_inf: bool = False):
    """Run one bad-input case: a named error with a message (counted as invalid refused), or
    finite numbers (counted as accepted)."""
    start = time.perf_counter()
    with case():
        try:
            result = call()
        except BearingsimError as exc:
            assert str(exc).strip(), f"{type(exc).__name__} without a message"
            _count("invalid", start)
            return None
        _finite(result, allow_inf)
    _count("invalid_accepted", start)
    return result


# ------------------------------------------------------------------ physics functions
NUMBERS = st.one_of(
    st.floats(1e-9, 1e6), st.floats(-1e6, -1e-9), st.sampled_from([0.0, 1.0, -1.0, 1e-300]),
    st.sampled_from([math.nan, math.inf, -math.inf]),
)
"""A scalar argument: magnitudes of both signs from 1e-9 to 1e6 in SI units (beyond any
bearing's quantity by orders of magnitude at both ends), edge values and non-finite ones."""
GEOMETRIES = [get_bearing(d) for d in list_bearings()]
SPECIAL = {
    "race": st.sampled_from(["inner", "outer", "middle"]),
    "method": st.sampled_from(["exact", "hamrock_brewe", "grease", "oil_bath", "bogus"]),
    "bearing_type": st.sampled_from(["deep_groove_ball", "angular_contact_ball", "bogus"]),
    "series": st.sampled_from(["62", "619", "72B", "bogus"]),
    "rows": st.sampled_from([1, 2, 3, 0, 1.5, True]),
    "ball_count": st.sampled_from([3, 7, 20, 2, 7.5]),
    "n": st.sampled_from([0, 1, 3, 5, -1, 2.5]),
    "rotating": st.booleans(), "inner_rotating": st.booleans(), "smooth": st.booleans(),
    "exact": st.booleans(),
    "geometry": st.sampled_from(GEOMETRIES),
    "inner": st.sampled_from(["61905", "6204", "6304"]),
    "outer": st.sampled_from(["61907", "61909", "6206"]),
    "designation": st.sampled_from(["6304", "61905", "7014C", "bogus"]),
    "lubricant": st.sampled_from(list(known_lubricants())).map(get_lubricant),
    "name": st.sampled_from(list(known_lubricants()) + ["bogus"]),
    "loads": st.lists(NUMBERS, min_size=1, max_size=8),
    "loads_inner": st.lists(NUMBERS, min_size=3, max_size=3),
    "loads_outer": st.lists(NUMBERS, min_size=3, max_size=3),
    "displacement": st.lists(st.floats(-1e-4, 1e-4), min_size=5, max_size=5),
}
SKIP = {"static_state", "get_lubricant", "known_lubricants", "bearing_design",
        "design_report", "slice_traction", "groove_contact", "combined_contact_life",
        "hertz_slice_weights", "ring_loads", "effective_modulus",
        "bearing_load_deflection_constants", "contact_spring_constant"}
REGISTRY_FUNCTIONS = {"register_lubricant", "unregister_lubricant"}
"""Functions that change the lubricant registry (global state shared by the other tests),
tested in tests/physics/test_lubricant_registry.py."""
SKIP |= REGISTRY_FUNCTIONS
"""Functions with structured arguments, covered by their own tests and the model cases, and the
registry functions."""
ALLOW_INF = {"contact_life", "bearing_life", "rating_life", "reference_rating_life",
             "life_hours", "raceway_equivalent_load", "lambda_ratio", "basic_rating_life_hours",
             "roller_reference_rating_life"}
"""Functions whose documented result is infinite for some valid inputs (e.g. no load)."""


def _physics_functions():
    out = []
    for info in pkgutil.iter_modules(bearingsim.physics.__path__):
        module = importlib.import_module(f"bearingsim.physics.{info.name}")
        for name in getattr(module, "__all__", []):
            fn = getattr(module, name)
            if inspect.isfunction(fn) and name not in SKIP:
                out.append(pytest.param(fn, id=f"{info.name}.{name}"))
    return out


KEYWORDS = {"skf_friction_torque": {"C0": NUMBERS, "d": NUMBERS, "D": NUMBERS}}
"""Keyword arguments a function takes through ``**kwargs`` (drawn like the others)."""


def _arguments(fn):
    strategies = dict(KEYWORDS.get(fn.__name__, {}))
    for name, p in inspect.signature(fn).parameters.items():
        if p.kind in (p.VAR_KEYWORD, p.VAR_POSITIONAL):
            continue
        if name in SPECIAL:
            strategies[name] = SPECIAL[name]
        elif p.default is not inspect.Parameter.empty and not isinstance(p.default,
                                                                          (int, float)):
            continue  # keep structured defaults (materials, None options)
        else:
            strategies[name] = NUMBERS
    return st.fixed_dictionaries(strategies)


@pytest.mark.parametrize("fn", _physics_functions())
def test_physics_functions_give_finite_numbers_or_named_errors(fn):
    @_settings(30)
    @given(_arguments(fn))
    def run(kwargs):
        outcome(lambda: fn(**kwargs), allow_inf=fn.__name__ in ALLOW_INF)

    run()


# ------------------------------------------------------------------ scenes and expressions
EXPR_ATOMS = st.sampled_from(["t", "1", "0", "-2.5", "pi", "1e308", "0.1234567", "(", ")",
                              "min(", "max(", ",", "+", "-", "*", "/", "**", "<", " if ",
                              " else ", "sqrt(", "log(", "tan(", "exp(", "step(", "ramp(",
                              "rpm(", "abs(", "sin("])


@_settings(300)
@given(st.lists(EXPR_ATOMS, max_size=14).map("".join), st.floats(0.01, 10.0))
def test_expressions_compile_and_run_or_raise_named_errors(text, t_end):
    """A generated input expression either fails to compile with its name in the message, or
    its values over [0, t_end] are checked (poles, overflow between the output points)."""
    import casadi as ca

    from bearingsim.scenes.expressions import compile_expression
    from bearingsim.simulation.intervals import locate_problem

    def run():
        f = compile_expression(text, "inputs.u")
        t = ca.SX.sym("t")
        fn = ca.Function("f", [t], [ca.SX(f(t))])
        problem = locate_problem(fn, 0.0, t_end)
        values = np.asarray(fn.map(5)(np.linspace(0.0, t_end, 5)[None, :]))
        if problem is None:
            return values  # no problem located: every sampled value must be finite
        return problem.reason

    outcome(run)


SCALARS = st.one_of(st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True),
                    st.booleans(), st.text(max_size=12), st.lists(st.integers(), max_size=3))
SECTIONS = st.sampled_from(["assembly", "inputs", "parameters", "initial", "simulation",
                            "output"])
KEYS = st.sampled_from(["name", "fidelity", "inner", "outer", "lubrication", "structure",
                        "shaft_speed", "Fr", "Fa", "t_end", "rtol", "method", "n_points",
                        "max_step", "folder", "plots", "inner_layer.nu", "bogus"])


@_settings(300)
@given(st.dictionaries(SECTIONS, st.dictionaries(KEYS, SCALARS, max_size=4), max_size=4))
def test_generated_scenes_parse_or_name_every_problem(d):
    from bearingsim.scenes.scene import SceneError, scene_from_dict

    d.setdefault("assembly", {}).setdefault("name", "double_layer_bearing")

    def run():
        try:
            return scene_from_dict(d)
        except SceneError as exc:
            assert all(p.key for p in exc.problems)
            raise

    outcome(run)


# ------------------------------------------------------------------ assemblies and levels
@cache
def torque_system(friction_model: str):
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing

    return assemble(double_layer_bearing("61905", "61907", fidelity="torque",
                                         friction_model=friction_model),
                    outputs=["Rs", "M_shaft"])


@_settings(100)
@given(st.sampled_from(["palmgren", "skf"]), st.floats(-2000.0, 2000.0),
       st.floats(-100.0, 5000.0), st.floats(-100.0, 5000.0),
       st.sampled_from(["ISO VG 32", "ISO VG 150", "lithium grease"]))
def test_torque_level_steady_ratio(friction_model, speed, fr, fa, lubricant):
    from bearingsim.studies.double_layer import steady_ratio

    system = torque_system(friction_model)
    params = {}
    if friction_model == "palmgren":
        nu = float(get_lubricant(lubricant).kinematic_viscosity())
        params = {"inner_layer.nu": nu, "outer_layer.nu": nu}
    outcome(lambda: steady_ratio(system, speed, loads=(fr, fa), parameters=params)[:2])


@cache
def kinematic_system(fidelity: str):
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing

    return assemble(double_layer_bearing("61905", "61908", fidelity=fidelity),
                    outputs=["Rs", "w_middle"])


@_settings(40)
@given(st.sampled_from(["kinematic", "kinematic_approx"]), st.floats(-3000.0, 3000.0),
       st.floats(1e-3, 0.5))
def test_kinematic_levels_run(fidelity, speed, t_end):
    from bearingsim.simulation import simulate

    system = kinematic_system(fidelity)
    outcome(lambda: simulate(system, t_end, inputs={"shaft_speed": speed}, n_points=5).values)


LOAD = st.one_of(st.floats(-5000.0, 5000.0), st.sampled_from([0.0, math.nan, 1e7]))


@_settings(60)
@given(st.sampled_from(["6304", "6204", "61905", "7014C"]), LOAD, LOAD, LOAD,
       st.floats(-20.0, 20.0), st.floats(-20.0, 20.0),
       st.sampled_from([None, 0.0, 5e-6, 30e-6, -1e-6]),
       st.sampled_from(["exact", "iso_ts_16281"]))
def test_deep_groove_statics(bearing, fx, fy, fz, mx, my, clearance, method):
    import warnings

    from bearingsim.studies.deep_groove_statics import deep_groove_statics

    def run():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # plastic deformation at the large loads
            res = deep_groove_statics(bearing, {"Fx": fx, "Fy": fy, "Fz": fz, "Mx": mx,
                                                "My": my}, clearance=clearance, method=method)
        return res.state, res.ball_loads, res.stiffness

    outcome(run)


@cache
def quasi_static_level(speed: float):
    import warnings

    from bearingsim.assembler import assemble
    from bearingsim.assemblies import deep_groove_ball_bearing

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return assemble(deep_groove_ball_bearing("6304", "quasi-static", speed=speed))


@_settings(60)
@given(st.sampled_from([0.0, 500.0, 2000.0]), st.floats(0.0, 4000.0), st.floats(-3000.0, 3000.0),
       st.floats(-1500.0, 1500.0))
def test_quasi_static_level_at_speed_with_load_inputs(speed, fx, fy, fz):
    from bearingsim.simulation import simulate

    system = quasi_static_level(speed)
    inputs = {"load.Fx": fx, "load.Fy": fy, "load.Fz": fz}
    outcome(lambda: simulate(system, 1e-3, inputs=inputs, n_points=2).values)


@cache
def duplex_model(bearing: str, arrangement: str):
    from bearingsim.studies.duplex import DuplexModel

    return DuplexModel(bearing, arrangement=arrangement)


@_settings(30)
@given(st.sampled_from(["7020C", "7020A"]), st.sampled_from(["DF", "DB", "DT"]),
       st.floats(-3000.0, 3000.0), st.floats(-3000.0, 3000.0), st.floats(-50.0, 50.0))
def test_duplex_pair_equilibrium(bearing, arrangement, fx, fz, my):
    import warnings

    model = duplex_model(bearing, arrangement)

    def run():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # an unloaded row is a warning, not an answer
            eq = model.equilibrium({"Fx": fx, "Fz": fz, "My": my})
        return eq.displacement, model.stiffness(eq)

    outcome(run)


@cache
def ball_level(fidelity: str):
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import deep_groove_ball_bearing

    return assemble(deep_groove_ball_bearing("6304", fidelity, loads={"Fx": None, "Fy": 0.0,
                                                                       "Fz": 0.0, "Mx": 0.0,
                                                                       "My": 0.0},
                                             n_slices=0))


@_settings(4)
@given(st.sampled_from(["dynamic_massive_balls", "dynamic"]), st.floats(0.0, 400.0),
       st.floats(50.0, 1500.0))
def test_ball_levels_start_up(fidelity, speed, load):
    from bearingsim.simulation import simulate

    system = ball_level(fidelity)
    outcome(lambda: simulate(system, 2e-4, inputs={"shaft_speed": speed, "load.Fx": load},
                             method="cvodes", rtol=1e-5, atol=1e-8, n_points=3).values)
