"""Ball drag, spin drag moment, ball-pocket and cage guidance forces."""

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.errors import ParameterError
from bearingsim.physics.cage import (
    SIGMA_BALL,
    SIGMA_CAGE,
    ball_pocket_force,
    cage_guidance_force,
    journal_film_force,
    pocket_gap,
)
from bearingsim.physics.drag import (
    ball_drag_force,
    orbital_drag_force,
    rotating_sphere_moment_coefficient,
    sphere_drag_coefficient,
    spin_drag_moment,
)

DW, RHO, ETA = 9.52e-3, 870.0, 0.02


def test_sphere_drag_coefficient_white_fit():
    # White (1991): C_D = 24/Re + 6/(1 + sqrt(Re)) + 0.4; at Re = 1: 27.4; at Re = 1e4: 0.4617.
    assert sphere_drag_coefficient(1.0) == pytest.approx(27.4)
    assert sphere_drag_coefficient(1e4) == pytest.approx(0.0024 + 6 / 101 + 0.4)
    # Standard drag curve (Schlichting): C_D about 0.4-0.5 for 1e3 < Re < 1e5.
    assert 0.38 < sphere_drag_coefficient(1e5) < 0.5


def test_ball_drag_equals_half_cd_rho_v2_a_and_stokes_limit():
    v = 3.0
    re = RHO * v * DW / ETA
    expected = 0.5 * sphere_drag_coefficient(re) * RHO * v**2 * np.pi * DW**2 / 4
    assert ball_drag_force(v, DW, RHO, ETA) == pytest.approx(-expected, rel=1e-9)
    assert ball_drag_force(-v, DW, RHO, ETA) == pytest.approx(expected, rel=1e-9)
    tiny = 1e-7  # Stokes: F = 3 pi eta D v
    assert ball_drag_force(tiny, DW, RHO, ETA) == pytest.approx(-3 * np.pi * ETA * DW * tiny,
                                                                rel=1e-3)
    assert ball_drag_force(0.0, DW, RHO, ETA) == 0.0
    dm, w = 0.036, 200.0
    assert orbital_drag_force(w, dm, DW, RHO, ETA, 0.5) == pytest.approx(
        ball_drag_force(w * dm / 2, DW, RHO, ETA, 0.5))


def test_spin_moment_stokes_limit_and_coefficient():
    # Stokes limit (Lamb): M = 8 pi eta R^3 omega.
    w = 1e-6
    assert spin_drag_moment(w, DW, RHO, ETA) == pytest.approx(-8 * np.pi * ETA * (DW / 2) ** 3 * w,
                                                              rel=1e-3)
    w = 3000.0
    r = DW / 2
    re = w * r**2 * RHO / ETA
    cm = rotating_sphere_moment_coefficient(re)
    assert spin_drag_moment(w, DW, RHO, ETA) == pytest.approx(-0.5 * RHO * w**2 * r**5 * cm,
                                                              rel=1e-9)


@settings(max_examples=50, deadline=None)
@given(v=st.floats(-50.0, 50.0), eta=st.floats(1e-3, 1.0))
def test_drag_opposes_motion_and_is_finite(v, eta):
    f = ball_drag_force(v, DW, RHO, eta)
    m = spin_drag_moment(v * 100, DW, RHO, eta)
    assert np.isfinite(f) and np.isfinite(m) and f * v <= 0 and m * v <= 0
    assert abs(ball_drag_force(v, DW, RHO, eta * 2)) >= abs(f)


def test_pocket_gap_geometry():
    rb, rp, sp = 4.76e-3, 5.0e-3, 1.0e-3
    side = pocket_gap(0.2e-3, 0.1e-3, rb, rp, sp)  # faces a straight side
    assert side.gap == pytest.approx(rp - rb - 0.1e-3)
    assert (side.nx, side.ny, side.on_end) == pytest.approx((0.0, 1.0, 0.0))
    end = pocket_gap(sp / 2 + 0.3e-3, 0.4e-3, rb, rp, sp)  # faces a half circle
    assert end.gap == pytest.approx(rp - rb - 0.5e-3)
    assert (end.nx, end.ny, end.on_end) == pytest.approx((0.6, 0.8, 1.0))


def test_pocket_contact_and_film_regimes():
    kw = {"Rb": 4.76e-3, "Rp": 5.0e-3, "Sp": 0.5e-3, "width": 3e-3, "K": 1e9, "mu": 0.1,
          "eta": ETA}
    sigma = np.hypot(SIGMA_BALL, SIGMA_CAGE)
    clearance = kw["Rp"] - kw["Rb"]
    # Pressed 1 um into the side wall (y): Hertz K d^1.5 pushing back, friction against sliding.
    hit = ball_pocket_force(0.0, clearance + 1e-6, 0.0, 0.0, 0.5, 0.0, 0.0, **kw)
    assert hit.contact_weight > 0.99
    assert hit.fy == pytest.approx(-1e9 * 1e-9, rel=0.02)
    assert hit.fx * 0.5 * (-1.0) < 0  # tangent (-ny, nx) = (-1, 0); friction opposes slide_t
    # Far from the wall: film only, small, and it resists the approach (squeeze).
    film = ball_pocket_force(0.0, 0.5 * clearance, 0.0, 1e-3, 0.0, 0.0, 0.0, **kw)
    assert film.contact_weight < 1e-6 and film.fy < 0
    assert film.gap.gap > 3 * sigma


@settings(max_examples=50, deadline=None)
@given(y=st.floats(-0.3e-3, 0.3e-3), vy=st.floats(-0.1, 0.1), slide=st.floats(-2.0, 2.0))
def test_pocket_force_is_finite_everywhere(y, vy, slide):
    f = ball_pocket_force(1e-4, y, 0.0, vy, slide, 0.1 * slide, 50.0, Rb=4.76e-3, Rp=5e-3,
                          Sp=0.5e-3, width=3e-3, K=1e9, mu=0.1, eta=ETA)
    assert np.all(np.isfinite([f.fx, f.fy, f.fz, f.normal]))


def test_journal_film_matches_ocvirk_steady_solution():
    # Ocvirk short bearing: W_r = eta U L^3 eps^2 / (c^2 (1-eps^2)^2),
    # W_t = pi eta U L^3 eps / (4 c^2 (1-eps^2)^1.5), U = omega R.
    R, L, c, omega, eps = 0.02, 0.005, 50e-6, 300.0, 0.5
    f = journal_film_force(eps * c, 0.0, 0.0, 0.0, omega, ETA, R, L, c)
    U = omega * R
    one = 1 - eps**2
    assert f.radial == pytest.approx(-ETA * U * L**3 * eps**2 / (c**2 * one**2), rel=2e-4)
    assert f.tangential == pytest.approx(np.pi * ETA * U * L**3 * eps / (4 * c**2 * one**1.5),
                                         rel=2e-4)
    assert (f.fx, f.fy) == pytest.approx((f.radial, f.tangential))


def test_cage_guidance_petroff_and_proportional_to_speed():
    kw = {"Rg": 0.02, "Bg": 0.004, "Cg": 0.1e-3, "eta": ETA}
    g0 = cage_guidance_force(0.0, 0.0, 0.0, 0.0, 300.0, **kw)
    petroff = 2 * np.pi * ETA * 0.02**3 * 0.004 * 300.0 / 0.1e-3  # Petroff at eps = 0
    assert g0.moment == pytest.approx(-petroff, rel=1e-9)
    a = cage_guidance_force(0.05e-3, 0.0, 0.0, 0.0, 300.0, **kw)
    b = cage_guidance_force(0.05e-3, 0.0, 0.0, 0.0, 600.0, **kw)
    assert b.radial == pytest.approx(2 * a.radial) and b.moment == pytest.approx(2 * a.moment)
    assert a.radial < 0 < a.tangential and abs(a.moment) > abs(g0.moment)
    huge = cage_guidance_force(0.2e-3, 0.0, 0.0, 0.0, 300.0, **kw)  # beyond the clearance
    assert np.isfinite(huge.radial) and huge.eps < 0.981


def test_float_and_sx_agree():
    ex, ey, w = ca.SX.sym("ex"), ca.SX.sym("ey"), ca.SX.sym("w")
    kw = {"Rg": 0.02, "Bg": 0.004, "Cg": 0.1e-3, "eta": ETA}
    g = cage_guidance_force(ex, ey, 0.01, -0.02, w, **kw)
    f = ca.Function("f", [ex, ey, w], [g.fx, g.fy, g.moment])
    num = cage_guidance_force(3e-5, -2e-5, 0.01, -0.02, 250.0, **kw)
    np.testing.assert_allclose([float(v) for v in f(3e-5, -2e-5, 250.0)],
                               [num.fx, num.fy, num.moment], rtol=1e-12)
    y, s = ca.SX.sym("y"), ca.SX.sym("s")
    pk = {"Rb": 4.76e-3, "Rp": 5e-3, "Sp": 0.5e-3, "width": 3e-3, "K": 1e9, "mu": 0.1, "eta": ETA}
    p = ball_pocket_force(3e-4, y, 0.0, 0.01, s, 0.0, 80.0, **pk)
    h = ca.Function("h", [y, s], [p.fx, p.fy, p.fz])
    for yy in (0.0, 1e-4, 0.2395e-3, 0.2401e-3):
        pn = ball_pocket_force(3e-4, yy, 0.0, 0.01, 0.3, 0.0, 80.0, **pk)
        np.testing.assert_allclose([float(v) for v in h(yy, 0.3)], [pn.fx, pn.fy, pn.fz],
                                   rtol=1e-10, atol=1e-15)
    v = ca.SX.sym("v")
    d = ca.Function("d", [v], [ball_drag_force(v, DW, RHO, ETA), spin_drag_moment(v, DW, RHO, ETA)])
    vs = np.array([-4.0, 0.0, 1e-3, 10.0])
    arr = ball_drag_force(vs, DW, RHO, ETA)
    for i, x in enumerate(vs):
        out = [float(q) for q in d(x)]
        assert out[0] == pytest.approx(arr[i], rel=1e-12, abs=1e-18)
        assert out[1] == pytest.approx(spin_drag_moment(float(x), DW, RHO, ETA), rel=1e-12,
                                       abs=1e-18)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: sphere_drag_coefficient(0.0), r"Re = 0.0 \[-\]"),
        (lambda: ball_drag_force(1.0, -DW, RHO, ETA), r"Dw = -0.00952 \[m\]"),
        (lambda: ball_drag_force(1.0, DW, RHO, 0.0), r"eta = 0.0 \[Pa s\]"),
        (lambda: ball_drag_force(1.0, DW, RHO, ETA, area_fraction=1.5), "area_fraction"),
        (lambda: spin_drag_moment(np.nan, DW, RHO, ETA), "omega must be finite"),
        (lambda: pocket_gap(0.0, 0.0, 5e-3, 4e-3, 1e-3), r"Rp = 0.004 \[m\]"),
        (lambda: cage_guidance_force(0, 0, 0, 0, 1.0, Rg=0.02, Bg=0.004, Cg=0.0, eta=ETA),
         r"c = 0.0 \[m\]"),
    ],
)
def test_invalid_input_is_rejected(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_couette_damping_is_the_exact_laminar_solution():
    """M = 4 pi eta L R1^2 R2^2 / (R2^2 - R1^2) omega (Couette flow between concentric
    cylinders); in the narrow-gap limit 2 pi eta L R1^3 / d (a linear shear profile)."""
    from bearingsim.physics.drag import couette_damping, taylor_number

    eta, length, r1 = 0.03, 0.01, 0.0225
    wide = couette_damping(r1, 0.005, length, eta)
    r2 = r1 + 0.005
    assert wide == pytest.approx(4 * np.pi * eta * length * r1**2 * r2**2 / (r2**2 - r1**2))
    for gap in (1e-4, 1e-5):
        narrow = 2 * np.pi * eta * length * r1**3 / gap
        assert couette_damping(r1, gap, length, eta) == pytest.approx(narrow, rel=2 * gap / r1)
    assert couette_damping(r1, 0.001, length, eta, wetted=0.25) == pytest.approx(
        0.25 * couette_damping(r1, 0.001, length, eta))
    assert taylor_number(100.0, r1, 0.001, 3e-5) == pytest.approx(
        100.0 * r1 * 0.001 / 3e-5 * np.sqrt(0.001 / r1))
    with pytest.raises(ParameterError, match="wetted"):
        couette_damping(r1, 0.001, length, eta, wetted=0.0)
