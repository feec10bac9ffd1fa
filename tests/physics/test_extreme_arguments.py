"""No NaN or infinity from a public physics function (issue 30, item 3).

Each function is called with valid arguments, then with one numeric argument at a time replaced
by NaN, +-inf, +-1e308 or 1e-308: the answer is finite or a named
:class:`~bearingsim.errors.BearingsimError`, never a NaN, an infinity, a bare
``OverflowError`` or a ``RuntimeWarning``. The same functions keep building CasADi expressions.
"""

from __future__ import annotations

import dataclasses
import inspect
import warnings

import casadi as ca
import numpy as np
import pytest

from bearingsim.errors import BearingsimError
from bearingsim.physics import contact_law, drag, film, friction, hertz, life, rolling, traction
from bearingsim.physics.lubricant import get_lubricant

OIL = get_lubricant("ISO VG 68")
SKF_62 = {"C0": 7800.0, "d": 0.025, "D": 0.052}

# name -> (function, valid keyword arguments)
CALLS = {
    "palmgren_p1": (friction.palmgren_p1, {"Fr": 1000.0, "Fa": 200.0,
                                           "bearing_type": "deep_groove_ball"}),
    "palmgren_f1": (friction.palmgren_f1, {"bearing_type": "deep_groove_ball", "P0": 1000.0,
                                           "C0": 7800.0}),
    "palmgren_m0": (friction.palmgren_m0, {"nu": 32e-6, "n_abs": 100.0, "dm": 0.04,
                                           "f0": 2.0}),
    "palmgren_torque": (friction.palmgren_torque, {
        "omega_rel": 100.0, "dm": 0.04, "lubricant": OIL, "bearing_type": "deep_groove_ball",
        "load_P1": 1000.0, "P0": 1000.0, "C0": 7800.0}),
    "skf_friction_torque": (friction.skf_friction_torque, {
        "omega_rel": 100.0, "dm": 0.0385, "lubricant": OIL, "series": "62", "Fr": 1000.0,
        "Fa": 100.0, **SKF_62}),
    "ehl_traction": (traction.ehl_traction, {"slip_speed": 0.1}),
    "regularized_coulomb": (traction.regularized_coulomb, {"slip_speed": 0.1, "mu": 0.1}),
    "ball_drag_force": (drag.ball_drag_force, {"v": 5.0, "Dw": 0.008, "rho": 870.0,
                                               "eta": 0.03}),
    "orbital_drag_force": (drag.orbital_drag_force, {"omega_orbit": 100.0, "dm": 0.04,
                                                     "Dw": 0.008, "rho": 870.0, "eta": 0.03}),
    "spin_drag_moment": (drag.spin_drag_moment, {"omega": 300.0, "Dw": 0.008, "rho": 870.0,
                                                 "eta": 0.03}),
    "sphere_drag_coefficient": (drag.sphere_drag_coefficient, {"Re": 100.0}),
    "couette_damping": (drag.couette_damping, {"radius": 0.02, "gap": 1e-4, "length": 0.01,
                                               "eta": 0.03}),
    "taylor_number": (drag.taylor_number, {"omega": 100.0, "radius": 0.02, "gap": 1e-4,
                                           "nu": 3e-5}),
    "hamrock_dowson": (film.hamrock_dowson, {"Q": 500.0, "u": 5.0, "Rx": 0.004, "Ry": 0.05,
                                             "E_eff": 2.3e11, "eta0": 0.03, "alpha": 2e-8}),
    "dimensionless_speed": (film.dimensionless_speed, {"eta0": 0.03, "u": 5.0,
                                                       "E_eff": 2.3e11, "Rx": 0.004}),
    "dimensionless_load": (film.dimensionless_load, {"Q": 500.0, "E_eff": 2.3e11, "Rx": 0.004}),
    "minimum_film_thickness": (film.minimum_film_thickness, {"U": 1e-11, "G": 4600.0,
                                                             "W": 1e-4, "k": 5.0, "Rx": 0.004}),
    "central_film_thickness": (film.central_film_thickness, {"U": 1e-11, "G": 4600.0,
                                                             "W": 1e-4, "k": 5.0, "Rx": 0.004}),
    "rolling_resistance": (rolling.rolling_resistance, {
        "Q": 500.0, "u": 5.0, "Rx": 0.004, "Ry": 0.05, "E_eff": 2.3e11, "eta0": 0.03,
        "alpha": 2e-8}),
    "hertz_contact": (hertz.hertz_contact, {"load": 500.0, "rx": 0.004, "ry": 0.05,
                                            "e_eff": 2.3e11}),
    "contact_load": (contact_law.contact_load, {"k_const": 1e10, "delta": 1e-5}),
    "rating_life": (life.rating_life, {"c": 20000.0, "p": 2000.0}),
    "life_hours": (life.life_hours, {"life": 1000.0, "speed": 100.0}),
    "contact_life": (life.contact_life, {"capacity": 20000.0, "load": 2000.0}),
    "dynamic_load_rating": (life.dynamic_load_rating, {
        "ball_diameter": 0.008, "pitch_diameter": 0.04, "ball_count": 8}),
    "static_load_rating": (life.static_load_rating, {
        "ball_diameter": 0.008, "pitch_diameter": 0.04, "ball_count": 8}),
}

EXTREMES = [np.nan, np.inf, -np.inf, 1e308, -1e308, 1e-308]


def _numeric_args(kwargs):
    return [k for k, v in kwargs.items()
            if isinstance(v, (int, float)) and not isinstance(v, bool)]


CASES = [(name, arg, value) for name, (_, kw) in CALLS.items() for arg in _numeric_args(kw)
         for value in EXTREMES]


def _finite(result):
    if dataclasses.is_dataclass(result):
        return all(_finite(getattr(result, f.name)) for f in dataclasses.fields(result)
                   if isinstance(getattr(result, f.name), (int, float, np.ndarray)))
    if isinstance(result, tuple):
        return all(_finite(r) for r in result)
    return bool(np.all(np.isfinite(np.asarray(result, dtype=float))))


@pytest.mark.parametrize("name", list(CALLS))
def test_valid_arguments_give_finite_answers(name):
    func, kwargs = CALLS[name]
    assert _finite(func(**kwargs))


@pytest.mark.parametrize(("name", "arg", "value"), CASES,
                         ids=[f"{n}-{a}-{v:g}" for n, a, v in CASES])
def test_extreme_argument_gives_a_finite_answer_or_a_named_error(name, arg, value):
    func, kwargs = CALLS[name]
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        try:
            result = func(**{**kwargs, arg: value})
        except BearingsimError as exc:  # its own check, an inner function's, or the result's
            assert str(exc)
            return
    if func.__module__.startswith("bearingsim.physics.life") and np.isinf(value):
        # an infinite capacity or zero load has an infinite life: inf is the answer there
        assert not np.any(np.isnan(np.asarray(result, dtype=float))), result
        return
    assert _finite(result), f"{name}({arg}={value}) returned {result!r}"


@pytest.mark.parametrize("name", ["palmgren_p1", "ehl_traction", "ball_drag_force",
                                  "hamrock_dowson", "rating_life", "contact_load"])
def test_functions_still_build_casadi_expressions(name):
    func, kwargs = CALLS[name]
    first = _numeric_args(kwargs)[0]
    x = ca.SX.sym("x")
    out = func(**{**kwargs, first: x})
    parts = [getattr(out, f.name) for f in dataclasses.fields(out)] if \
        dataclasses.is_dataclass(out) else [out]
    symbolic = [p for p in parts if isinstance(p, ca.SX)]
    assert symbolic, out
    value = ca.Function("f", [x], [symbolic[0]])(kwargs[first])
    assert np.isfinite(float(value))
    assert inspect.signature(func).parameters[first]  # the wrapper keeps the signature
