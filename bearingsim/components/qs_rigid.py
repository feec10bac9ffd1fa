"""Rigid-body kinematics of the 5-DOF ring frame, for floats and CasADi symbols alike.

A frame's tilts ``(tx, ty)`` define the rotation ``R = Rx(tx) Ry(ty)`` of the body (rotation
about z is not part of the frame). A body point at ``p`` in the reference configuration moves
to ``u + R p`` where ``u`` is the displacement of the frame's reference point; so the body's
axis ``R e_z = (sin ty, -sin tx cos ty, cos tx cos ty)`` and, for small tilts, a point at
``(0, 0, L)`` moves by ``(L ty, -L tx, 0)`` (the convention of models.md section B).
``exact=False`` uses the linearised rotation ``I + [theta]x`` with ``theta = (tx, ty, 0)``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from bearingsim import symbolic as op

__all__ = ["Vector", "rotation", "rotate", "cross", "add", "scale", "dot", "body_point"]

Vector = list
"""A 3-vector as a list of floats or CasADi scalars."""


def rotation(tx: Any, ty: Any, exact: bool = True) -> list[list[Any]]:
    """Rotation matrix of a frame tilted by ``tx`` about x and then ``ty`` about y.

    Parameters
    ----------
    tx, ty : float or SX
        Tilts about x and y [rad].
    exact : bool
        ``R = Rx(tx) Ry(ty)`` (default) or its first-order form ``I + [theta]x``.

    Returns
    -------
    list of three rows of three entries
    """
    if not exact:
        return [[1.0, 0.0, ty], [0.0, 1.0, -tx], [-ty, tx, 1.0]]
    cx, sx, cy, sy = op.cos(tx), op.sin(tx), op.cos(ty), op.sin(ty)
    return [[cy, 0.0, sy], [sx * sy, cx, -sx * cy], [-cx * sy, sx, cx * cy]]


def rotate(r: Sequence[Sequence[Any]], p: Sequence[Any]) -> Vector:
    """Matrix-vector product ``R p``."""
    return [r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] for i in range(3)]


def cross(a: Sequence[Any], b: Sequence[Any]) -> Vector:
    """Cross product ``a x b``."""
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def add(*vectors: Sequence[Any]) -> Vector:
    """Sum of 3-vectors."""
    return [sum(v[i] for v in vectors) for i in range(3)]


def scale(s: Any, v: Sequence[Any]) -> Vector:
    """``s v`` for a scalar ``s``."""
    return [s * v[i] for i in range(3)]


def dot(a: Sequence[Any], b: Sequence[Any]) -> Any:
    """Scalar product."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def body_point(u: Sequence[Any], r: Sequence[Sequence[Any]], p: Sequence[Any]) -> Vector:
    """Current position ``u + R p`` of the body point ``p`` (relative to the frame's reference
    position) for a frame displaced by ``u`` and rotated by ``R``."""
    return add(u, rotate(r, p))
