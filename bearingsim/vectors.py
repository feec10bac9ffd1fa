"""3-vectors and rigid-body rotations for floats, numpy arrays and CasADi symbols alike.

A vector is a tuple of three scalars (floats, arrays of the same shape, or CasADi SX) in the
fixed frame; z is the bearing axis. Every function works through :mod:`bearingsim.symbolic`, so
the same code builds equations and evaluates numbers.

A ring frame's tilts ``(tx, ty)`` define the rotation ``R = Rx(tx) Ry(ty)`` of the body (rotation
about z is not part of the frame). A body point at ``p`` in the reference configuration moves to
``u + R p``, ``u`` the displacement of the frame's reference point; so the body's axis is
``R e_z = (sin ty, -sin tx cos ty, cos tx cos ty)`` and, for small tilts, a point at
``(0, 0, L)`` moves by ``(L ty, -L tx, 0)`` (the convention of the duplex-pair study,
docs/studies.md, section B). ``exact=False`` gives the linearised rotation ``I + [theta]x``,
``theta = (tx, ty, 0)``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from bearingsim import symbolic as op

__all__ = ["Vec", "add", "sub", "scale", "dot", "cross", "norm", "azimuth_frame", "rotation",
           "rotate", "body_point"]

Vec = tuple[Any, Any, Any]
"""A 3-vector: three floats, arrays or CasADi scalars."""


def add(*vectors: Sequence[Any]) -> Vec:
    """Sum of 3-vectors.

    Parameters
    ----------
    *vectors : sequence of 3 entries
        The vectors.

    Returns
    -------
    tuple
        Their sum.
    """
    return tuple(sum(v[i] for v in vectors) for i in range(3))  # type: ignore[return-value]


def sub(a: Sequence[Any], b: Sequence[Any]) -> Vec:
    """``a - b``.

    Parameters
    ----------
    a, b : sequence of 3 entries
        The vectors.

    Returns
    -------
    tuple
        ``a - b``.
    """
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(s: Any, a: Sequence[Any]) -> Vec:
    """``s a`` for a scalar ``s``.

    Parameters
    ----------
    s : float, array or CasADi symbol
        The scalar.
    a : sequence of 3 entries
        The vector.

    Returns
    -------
    tuple
        ``s a``.
    """
    return (s * a[0], s * a[1], s * a[2])


def dot(a: Sequence[Any], b: Sequence[Any]) -> Any:
    """Scalar product.

    Parameters
    ----------
    a, b : sequence of 3 entries
        The vectors.

    Returns
    -------
    float, array or CasADi symbol
        ``a . b``.
    """
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Sequence[Any], b: Sequence[Any]) -> Vec:
    """Vector product ``a x b``.

    Parameters
    ----------
    a, b : sequence of 3 entries
        The vectors.

    Returns
    -------
    tuple
        ``a x b``.
    """
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a: Sequence[Any], eps: float = 0.0) -> Any:
    """``sqrt(|a|^2 + eps^2)`` (smooth at 0 for ``eps > 0``).

    Parameters
    ----------
    a : sequence of 3 entries
        The vector.
    eps : float
        Smoothing length (same unit as ``a``), >= 0.

    Returns
    -------
    float, array or CasADi symbol
        The (smoothed) length.
    """
    return op.sqrt(dot(a, a) + eps * eps)


def azimuth_frame(theta: Any) -> tuple[Vec, Vec, Vec]:
    """Unit vectors ``(e_r, e_t, e_z)`` at azimuth ``theta`` [rad].

    Parameters
    ----------
    theta : float, array or CasADi symbol
        Azimuth [rad].

    Returns
    -------
    tuple of three tuples
        ``e_r``, ``e_t``, ``e_z``.
    """
    c, s = op.cos(theta), op.sin(theta)
    return (c, s, 0.0), (-s, c, 0.0), (0.0, 0.0, 1.0)


def rotation(tx: Any, ty: Any, exact: bool = True) -> tuple[Vec, Vec, Vec]:
    """Rotation matrix of a frame tilted by ``tx`` about x and then ``ty`` about y.

    Parameters
    ----------
    tx, ty : float or SX
        Tilts about x and y [rad].
    exact : bool
        ``R = Rx(tx) Ry(ty)`` (default) or its first-order form ``I + [theta]x``.

    Returns
    -------
    tuple of three rows of three entries
    """
    if not exact:
        return ((1.0, 0.0, ty), (0.0, 1.0, -tx), (-ty, tx, 1.0))
    cx, sx, cy, sy = op.cos(tx), op.sin(tx), op.cos(ty), op.sin(ty)
    return ((cy, 0.0, sy), (sx * sy, cx, -sx * cy), (-cx * sy, sx, cx * cy))


def rotate(r: Sequence[Sequence[Any]], p: Sequence[Any]) -> Vec:
    """Matrix-vector product ``R p``.

    Parameters
    ----------
    r : sequence of three rows of three entries
        The matrix ``R``.
    p : sequence of 3 entries
        The vector.

    Returns
    -------
    tuple
        ``R p``.
    """
    return tuple(r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2]  # type: ignore[return-value]
                 for i in range(3))


def body_point(u: Sequence[Any], r: Sequence[Sequence[Any]], p: Sequence[Any]) -> Vec:
    """Current position ``u + R p`` of the body point ``p`` (relative to the frame's reference
    position) for a frame displaced by ``u`` and rotated by ``R``.

    Parameters
    ----------
    u : sequence of 3 entries
        Displacement of the frame [m].
    r : sequence of three rows of three entries
        Its rotation matrix.
    p : sequence of 3 entries
        The point relative to the frame's reference position [m].

    Returns
    -------
    tuple
        The point's position [m].
    """
    return add(u, rotate(r, p))
