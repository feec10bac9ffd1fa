"""Where a ball touches the groove of a displaced, tilted ring: approach and contact normal.

Exact rigid-ring kinematics for floats, numpy arrays and CasADi symbols alike (Jones 1960;
Harris & Kotzalas, *Advanced Concepts*, ch. "Distribution of internal loading").
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from bearingsim import symbolic as op
from bearingsim.vectors import Vec, norm, scale, sub

__all__ = ["groove_contact"]


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
