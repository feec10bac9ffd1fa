"""Connectors of the dynamic ball bearing and small 3-vector helpers.

Coordinates: z is the bearing axis. A ball is described in its own azimuthal frame
``(e_r, e_t, e_z)`` at its orbital angle ``theta`` (``e_r`` radial outwards, ``e_t`` along the
orbit). Vectors are tuples of three scalars (floats or CasADi SX) in the fixed frame.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from bearingsim import symbolic as op
from bearingsim.language import Connector, Flow, Potential

__all__ = ["BallFrame", "CageFrame", "Vec", "add", "sub", "scale", "dot", "cross", "norm",
           "azimuth_frame", "groove_contact"]

Vec = tuple[Any, Any, Any]


class BallFrame(Connector):
    """Position, velocity and spin of a ball centre; force and moment on the ball.

    Connectors
    ----------
    r, z : Potential [m]
        Radial and axial position of the ball centre.
    theta : Potential [rad]
        Orbital (azimuth) angle.
    vr, vz : Potential [m/s]
        Radial and axial velocity (zero for quasi-static balls).
    w_orbit : Potential [rad/s]
        Orbital speed ``d theta / dt``.
    wr, wt, wz : Potential [rad/s]
        Absolute angular velocity of the ball in its azimuthal frame.
    Fr, Ft, Fz : Flow [N]
        Force on the ball along ``e_r, e_t, e_z``.
    Mr, Mt, Mz : Flow [N m]
        Moment on the ball about its centre along ``e_r, e_t, e_z``.
    """

    r = Potential(unit="m", description="radial position of the ball centre")
    theta = Potential(unit="rad", description="orbital angle")
    z = Potential(unit="m", description="axial position of the ball centre")
    vr = Potential(unit="m/s", description="radial velocity")
    vz = Potential(unit="m/s", description="axial velocity")
    w_orbit = Potential(unit="rad/s", description="orbital speed")
    wr = Potential(unit="rad/s", description="ball angular velocity along e_r")
    wt = Potential(unit="rad/s", description="ball angular velocity along e_t")
    wz = Potential(unit="rad/s", description="ball angular velocity along e_z")
    Fr = Flow(unit="N", description="force on the ball along e_r")
    Ft = Flow(unit="N", description="force on the ball along e_t")
    Fz = Flow(unit="N", description="force on the ball along e_z")
    Mr = Flow(unit="N.m", description="moment on the ball along e_r")
    Mt = Flow(unit="N.m", description="moment on the ball along e_t")
    Mz = Flow(unit="N.m", description="moment on the ball along e_z")


class CageFrame(Connector):
    """Planar position and rotation of the cage; force and moment on the cage.

    Connectors
    ----------
    x, y : Potential [m]
        Cage centre.
    phi : Potential [rad]
        Cage rotation angle about z.
    Fx, Fy : Flow [N]
        Force on the cage.
    Mz : Flow [N m]
        Moment on the cage about its centre.
    """

    x = Potential(unit="m", description="cage centre x")
    y = Potential(unit="m", description="cage centre y")
    phi = Potential(unit="rad", description="cage angle")
    Fx = Flow(unit="N", description="force x on the cage")
    Fy = Flow(unit="N", description="force y on the cage")
    Mz = Flow(unit="N.m", description="moment about z on the cage")


def add(*vs: Vec) -> Vec:
    """Sum of vectors."""
    return tuple(sum(c) for c in zip(*vs, strict=True))  # type: ignore[return-value]


def sub(a: Vec, b: Vec) -> Vec:
    """``a - b``."""
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(s: Any, a: Vec) -> Vec:
    """``s a``."""
    return (s * a[0], s * a[1], s * a[2])


def dot(a: Vec, b: Vec) -> Any:
    """Scalar product."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Vec, b: Vec) -> Vec:
    """Vector product ``a x b``."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a: Vec, eps: float = 0.0) -> Any:
    """``sqrt(|a|^2 + eps^2)`` (smooth for ``eps > 0``)."""
    return op.sqrt(dot(a, a) + eps * eps)


def azimuth_frame(theta: Any) -> tuple[Vec, Vec, Vec]:
    """Unit vectors ``(e_r, e_t, e_z)`` at azimuth ``theta``."""
    c, s = op.cos(theta), op.sin(theta)
    return (c, s, 0.0), (-s, c, 0.0), (0.0, 0.0, 1.0)


def groove_contact(p_ball: Vec, ring: Sequence[Any], rho: Any, groove_factor: Any,
                   ball_diameter: Any) -> tuple[Any, Vec, Vec]:
    """Approach and contact normal of a ball in the groove of a displaced, tilted ring.

    The groove curvature centre nearest the ball is ``O = c + rho e' + rho (tx e'_y - ty e'_x)
    e_z`` with ``c = (x, y, z)`` the ring centre, ``e'`` the unit radial direction from the ring
    axis to the ball centre and ``(tx, ty)`` small tilts (rigid-ring kinematics of Jones 1960;
    Harris & Kotzalas, *Advanced Concepts*, ch. "Distribution of internal loading"). With
    ``d = p_ball - O`` the approach is ``delta = |d| - (f - 0.5) Dw`` and ``n = d / |d|`` points
    from the ball centre to the contact, for inner and outer grooves alike.

    Parameters
    ----------
    p_ball : Vec
        Ball centre [m].
    ring : sequence
        Ring displacement (x, y, z, tx, ty) [m, m, m, rad, rad].
    rho : float or SX
        Radius of the groove curvature-centre circle [m].
    groove_factor : float or SX
        f [-].
    ball_diameter : float or SX
        Dw [m].

    Returns
    -------
    (delta [m], n, e') : tuple
    """
    x, y, z, tx, ty = ring
    dx, dy = p_ball[0] - x, p_ball[1] - y
    rad = op.sqrt(dx * dx + dy * dy)
    ep = (dx / rad, dy / rad, 0.0 * rad)
    o = (x + rho * ep[0], y + rho * ep[1], z + rho * (tx * ep[1] - ty * ep[0]))
    d = sub(p_ball, o)
    dist = norm(d)
    return dist - (groove_factor - 0.5) * ball_diameter, scale(1.0 / dist, d), ep
