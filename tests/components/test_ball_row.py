"""Quasi-static ball row (issue 4): closed-form Jones/Harris relations, Stribeck's radial load
distribution, exact Jacobian against differences, Jones-Harris form, invalid input."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import scipy.optimize

from bearingsim import Assembly, connect
from bearingsim.assembler import assemble
from bearingsim.catalog import get_bearing
from bearingsim.components.ball_row import (
    BallRow,
    axial_approach,
    row_loads,
    row_parameters,
    row_stiffness,
)
from bearingsim.components.rings import Housing, InnerRing, OuterRing, Shaft
from bearingsim.errors import ParameterError
from bearingsim.physics.hertz import combined_load_deflection_constant
from bearingsim.simulation import steady_state
from bearingsim.units import deg, rpm_to_rad_s


class SingleRow(Assembly):
    """A shaft in one ball row with a rigid housing (loads at the row's plane)."""

    def __init__(self, bearing, **row_options):
        super().__init__("single")
        self.shaft = Shaft(mass=1.0, transverse_inertia=1e-3, polar_inertia=1e-3,
                           positions=(0.0,))
        self.inner_ring = InnerRing()
        self.outer_ring = OuterRing()
        self.housing = Housing(1)
        self.row = BallRow(bearing, **row_options)
        connect(self.shaft.frame[0], self.inner_ring.frame_a)
        connect(self.inner_ring.frame_b, self.row.inner)
        connect(self.housing.frame[0], self.outer_ring.frame_a)
        connect(self.outer_ring.frame_b, self.row.outer)


def _solve(system, loads, guess=(0.0,) * 5, parameters=None):
    x0 = system.x0()
    x0[:5] = guess
    inputs = {f"shaft.{k}": v for k, v in loads.items()}
    x = steady_state(system, inputs=inputs, x_guess=x0, parameters=parameters,
                     residual_tol=1e-6)
    u = system.u_default()
    for k, v in inputs.items():
        u[system.input_names.index(k)] = v
    return x, system.observe(0.0, x, u, system.p0(parameters))


def _per_ball(obs, key, z):
    return np.array([obs[f"row.{key}[{j}]"] for j in range(z)])


def jones_contact_angle(fa, z, k, a, alpha0):
    """Solve ``Fa = Z K A^1.5 sin a (cos a0 / cos a - 1)^1.5`` for a (Jones 1960; Harris)."""

    def f(alpha):
        return z * k * a**1.5 * math.sin(alpha) * (math.cos(alpha0) / math.cos(alpha) - 1) ** 1.5 \
            - fa

    return scipy.optimize.brentq(f, alpha0 + 1e-12, math.radians(89.0), xtol=1e-15, rtol=1e-15)


def _closed_form(bearing, fa, reference="touching"):
    g = get_bearing(bearing) if isinstance(bearing, str) else bearing
    p = row_parameters(g)
    k = combined_load_deflection_constant(p.K_i, p.K_o)
    a = (g.fi + g.fo - 1.0) * g.ball_diameter
    alpha = jones_contact_angle(fa, g.ball_count, k, a, p.alpha0)
    shift = 0.0 if reference == "touching" else a * math.sin(p.alpha0)
    return alpha, a * (math.cos(p.alpha0) * math.tan(alpha) - math.sin(p.alpha0)) + shift


@pytest.fixture(scope="module")
def acbb_row():
    return assemble(SingleRow("7020C"))


def test_axial_load_deflection_matches_jones_closed_form(acbb_row):
    for fa in (200.0, 540.0, 1270.0, 2550.0, 6000.0):
        alpha, dz = _closed_form("7020C", fa)
        x, obs = _solve(acbb_row, {"Fz": fa}, (0, 0, 1.2 * dz, 0, 0))
        assert x[2] == pytest.approx(dz, rel=1e-6)
        assert _per_ball(obs, "alpha_i", 20) == pytest.approx(np.full(20, alpha), rel=1e-6)
        assert np.sum(_per_ball(obs, "Q_i", 20) * np.sin(alpha)) == pytest.approx(fa, rel=1e-6)


def test_numeric_row_agrees_with_closed_form_and_component():
    p = row_parameters("7020C")
    alpha, dz = _closed_form("7020C", 1270.0)
    assert axial_approach(p, 20, 1270.0) == pytest.approx(dz, rel=1e-9)


@pytest.mark.parametrize("bearing, force", [("7020C", 540.0), ("7014C", 3000.0)])
def test_axial_approach_solves_one_ball_and_the_whole_row_carries_the_force(bearing, force,
                                                                            monkeypatch):
    """A purely axial approach loads every ball alike, so the solve evaluates one ball per
    iterate: the row of all Z balls at the approach found carries the force. Before, every
    iterate evaluated all Z balls in Python: 0.5-1 s per call, about 90 % of the time of the
    duplex_modes scene, which builds a pair (and solves its preload offset) per point."""
    from bearingsim.components.ball_row import loads

    p, z = row_parameters(bearing), get_bearing(bearing).ball_count
    calls = []
    counted = loads.contact_load
    monkeypatch.setattr(loads, "contact_load", lambda *a: calls.append(1) or counted(*a))
    dz = axial_approach(p, z, force)
    assert len(calls) < 3 * z  # one ball per iterate (before: Z per iterate, 20-25 iterates)
    monkeypatch.undo()
    carried = -row_loads(p, [0.0, 0.0, dz, 0.0, 0.0], [0.0] * 5, z).inner_load[2]
    assert float(carried) == pytest.approx(force, rel=1e-9)


def test_row_parameters_keeps_the_contact_constants_of_each_angle_and_method():
    """The Hertz constants are kept per bearing, materials, angle and method: each call gives
    what the constants' own function gives for its arguments."""
    from bearingsim.physics.hertz import bearing_load_deflection_constants
    from bearingsim.physics.materials import STEEL

    g = get_bearing("7020C")
    for angle in (math.radians(15.0), math.radians(25.0), math.radians(15.0)):
        for method in ("exact", "hamrock_brewe"):
            p = row_parameters(g, angle, method=method)
            k_i, k_o, _ = bearing_load_deflection_constants(g, STEEL, STEEL, angle, method)
            assert (p.K_i, p.K_o) == (float(k_i), float(k_o))
    assert row_parameters(g, math.radians(15.0)).K_i != row_parameters(g, math.radians(25.0)).K_i


def test_deep_groove_radial_load_follows_stribeck():
    g = dataclasses.replace(get_bearing("6204"), diametral_clearance=0.0)
    system = assemble(SingleRow(g, reference="centred"))
    fr, z = 2000.0, g.ball_count
    _, obs = _solve(system, {"Fx": fr}, (5e-6, 0, 0, 0, 0))
    q = _per_ball(obs, "Q_i", z)
    psi = 2 * np.pi * np.arange(z) / z
    exact = fr / np.sum(np.cos(psi[np.cos(psi) > 0]) ** 2.5)  # zero clearance: Q ~ cos^1.5
    assert q.max() == pytest.approx(exact, rel=1e-5)
    assert q.max() == pytest.approx(4.37 * fr / z, rel=0.02)  # Stribeck's constant


def test_deep_groove_contact_angle_grows_with_axial_load_as_jones_predicts():
    g = get_bearing("6204")  # clearance 12.5 um: free contact angle about 10 deg
    system = assemble(SingleRow(g, reference="centred"))
    angles = []
    for fa in (100.0, 500.0, 2000.0):
        alpha, dz = _closed_form(g, fa, reference="centred")
        x, obs = _solve(system, {"Fz": fa}, (0, 0, dz * (1 + 1e-3), 0, 0))
        assert x[2] == pytest.approx(dz, rel=1e-6)
        assert _per_ball(obs, "alpha_i", 8).mean() == pytest.approx(alpha, rel=1e-6)
        angles.append(alpha)
    assert g.free_contact_angle < angles[0] < angles[1] < angles[2]


def test_exact_jacobian_equals_difference_of_load_deflection_curve():
    p = row_parameters("7020C")
    dz = axial_approach(p, 20, 1270.0)
    op = (2e-6, -1e-6, dz, 1e-5, 2e-5)
    k = row_stiffness(p, 20, op)

    def loads(q):
        return -np.array(row_loads(p, list(q), [0.0] * 5, 20).inner_load, dtype=float)

    h = (1e-9, 1e-9, 1e-9, 1e-8, 1e-8)
    for j in range(5):
        qp, qm = np.array(op), np.array(op)
        qp[j] += h[j]
        qm[j] -= h[j]
        fd = (loads(qp) - loads(qm)) / (2 * h[j])
        assert k[:, j] == pytest.approx(fd, rel=1e-5, abs=1e-6 * np.abs(k).max())


def test_small_angle_kinematics_agree_for_small_tilts():
    p = row_parameters("7020C")
    q = [0.0, 0.0, axial_approach(p, 20, 540.0), 1e-5, -1e-5]
    exact = np.array(row_loads(p, q, [0.0] * 5, 20).inner_load, dtype=float)
    small = np.array(row_loads(p, q, [0.0] * 5, 20, exact=False).inner_load, dtype=float)
    assert small == pytest.approx(exact, rel=1e-4, abs=1e-3)


def test_jones_harris_form_reduces_to_classic_at_rest_and_splits_angles_at_speed():
    system = assemble(SingleRow("7020C", speed_effects=True))
    report = system.report["blocks"]
    assert "nonlinear" in report
    alpha, dz = _closed_form("7020C", 1270.0)
    x, obs = _solve(system, {"Fz": 1270.0}, (0, 0, dz, 0, 0))
    assert x[2] == pytest.approx(dz, rel=1e-6)
    assert _per_ball(obs, "alpha_o", 20) == pytest.approx(np.full(20, alpha), rel=1e-6)
    w = rpm_to_rad_s(12_000.0)
    x, obs = _solve(system, {"Fz": 1270.0}, x[:5], parameters={"row.inner_speed": w})
    a_i, a_o = _per_ball(obs, "alpha_i", 20), _per_ball(obs, "alpha_o", 20)
    q_i, q_o = _per_ball(obs, "Q_i", 20), _per_ball(obs, "Q_o", 20)
    assert np.all(a_i > alpha) and np.all(a_o < alpha)  # Jones: centrifugal force splits them
    assert np.all(q_o > q_i)
    assert np.sum(q_i * np.sin(a_i)) == pytest.approx(1270.0, rel=1e-6)


@pytest.mark.parametrize("kwargs", [{"contact_angle": deg(50.0)}, {"contact_angle": -0.1},
                                    {"direction": 0}, {"reference": "loose"},
                                    {"smooth": 0.0}])
def test_invalid_row_input_raises(kwargs):
    with pytest.raises(ParameterError):
        BallRow("7020C", **kwargs)


def test_axial_approach_rejects_negative_force():
    with pytest.raises(ParameterError, match="force"):
        axial_approach(row_parameters("7020C"), 20, -10.0)
