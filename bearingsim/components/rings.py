"""Rigid rings, spacers, shaft and housing of the 5-DOF ring-frame domain.

Bodies move with exact rigid-body kinematics (:mod:`bearingsim.vectors`): a frame at
body position ``p`` of a body whose reference point is displaced by ``u`` and tilted by
``R = Rx(tx) Ry(ty)`` sits at ``u + R p`` (relative to its reference position). Loads are
transported with the lever ``R p`` of the current configuration, so static equilibria and their
Jacobians (stiffness matrices) are exact for finite tilts. The shaft's inertia terms use the
linear rotor-dynamics form (tilt rates as angular velocities), which is exact at equilibrium
and for the small vibrations that the stiffness and modal studies need.

Flows of a :class:`~bearingsim.components.connectors.RingFrame` are the loads acting on the
body that owns the connector.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from bearingsim.components.connectors import FRAME_FLOWS, FRAME_POTENTIALS, RingFrame
from bearingsim.errors import ParameterError
from bearingsim.language import Component, Input, Parameter, Variable, der
from bearingsim.vectors import body_point, cross, rotate, rotation

__all__ = ["PartialRigidLink", "InnerRing", "OuterRing", "Spacer", "Shaft", "Housing",
           "ConstantLoad", "frame_lever_moment"]

_EZ = (0.0, 0.0, 1.0)


def frame_lever_moment(lever, frame: RingFrame):
    """(x, y) components of ``lever x F`` for the force ``F`` of ``frame`` [N m].

    Parameters
    ----------
    lever : sequence of 3 entries
        Lever from the frame's point [m].
    frame : RingFrame
        The frame whose force acts at the lever's end.

    Returns
    -------
    tuple
        The moment's x and y components [N m].
    """
    m = cross(lever, [frame.Fx, frame.Fy, frame.Fz])
    return m[0], m[1]


class PartialRigidLink(Component):
    """Base of massless rigid bodies joining ``frame_a`` to ``frame_b``.

    ``frame_b``'s point lies at the body position ``(0, 0, length)`` from ``frame_a``'s point
    and is moved along the body axis by ``shift`` (a mounting offset: it displaces ``frame_b``
    but is no part of the reference geometry). Both frames share the tilts; the loads balance
    (``F_a + F_b = 0``, ``M_a + M_b + r x F_b = 0`` with ``r = R (0, 0, length + shift)``).

    Parameters
    ----------
    exact : bool
        Exact rotation (default) or the small-angle form.
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    frame_a, frame_b : RingFrame
    """

    def __init__(self, exact: bool = True, name=None):
        super().__init__(name)
        self.frame_a = RingFrame()
        self.frame_b = RingFrame()
        self._exact = exact

    def link_equations(self, length, shift):
        """The ten kinematic and load-balance equations for a link of ``length`` and ``shift``.

        Parameters
        ----------
        length : float or SX
            Distance of ``frame_b``'s point along the body axis [m].
        shift : float or SX
            Mounting offset along the axis [m].

        Returns
        -------
        list
            The ten equations.
        """
        a, b = self.frame_a, self.frame_b
        r = rotation(a.tx, a.ty, self._exact)
        lever = rotate(r, [0.0, 0.0, length + shift])
        pos_b = body_point([a.x, a.y, a.z], r, [0.0, 0.0, length + shift])
        mx, my = frame_lever_moment(lever, b)
        return [
            b.x == pos_b[0],
            b.y == pos_b[1],
            b.z == pos_b[2] - length,
            b.tx == a.tx,
            b.ty == a.ty,
            a.Fx + b.Fx == 0,
            a.Fy + b.Fy == 0,
            a.Fz + b.Fz == 0,
            a.Mx + b.Mx + mx == 0,
            a.My + b.My + my == 0,
        ]


class _Ring(PartialRigidLink):
    """A rigid ring: seat frame, raceway frame at ``groove_offset``, rotational speed.

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    _which = "ring"

    def __init__(self, speed: float = 0.0, groove_offset: float = 0.0, exact: bool = True,
                 name=None):
        super().__init__(exact, name)
        self.speed = Parameter(speed, "rad/s", f"{self._which} ring speed")
        self.groove_offset = Parameter(groove_offset, "m", "raceway plane from the seat point")

    def equations(self):
        return self.link_equations(self.groove_offset, 0.0)


class InnerRing(_Ring):  # numpydoc ignore=PR02
    """Rigid inner ring: seat on the shaft (``frame_a``) and raceway frame (``frame_b``).

    The ring's mass belongs to the shaft it is mounted on (the assembly adds it there).

    Parameters
    ----------
    speed : float
        Rotational speed of the ring about the bearing axis [rad/s] (centrifugal and gyroscopic
        effects of the ball row); usually bound to the shaft speed by the assembly.
    groove_offset : float
        Axial position of the raceway's reference plane from the seat point [m].
    exact : bool
        Exact rigid-ring kinematics (default) or the small-angle form.

    Connectors
    ----------
    frame_a : RingFrame (seat), frame_b : RingFrame (raceway, to the ball row)
    """

    _which = "inner"


class OuterRing(_Ring):  # numpydoc ignore=PR02
    """Rigid outer ring: seat in the housing (``frame_a``) and raceway frame (``frame_b``).

    Parameters
    ----------
    speed : float
        Rotational speed of the ring [rad/s] (0 for a ring fixed in the housing).
    groove_offset : float
        Axial position of the raceway's reference plane from the seat point [m].
    exact : bool
        Exact rigid-ring kinematics (default) or the small-angle form.

    Connectors
    ----------
    frame_a : RingFrame (seat), frame_b : RingFrame (raceway, to the ball row)
    """

    _which = "outer"


class Spacer(PartialRigidLink):
    """Rigid spacer: a ring of axial ``width`` whose ``width_difference`` preloads a pair.

    In a duplex pair the inner and outer spacers differ in width; after clamping, the second
    row's ring sits ``width_difference`` further along the axis than the reference position in
    which its balls just touch. The spacer carries the second row's load; with no external load
    its axial force is the preload.

    Parameters
    ----------
    width : float
        Axial distance between the two frames [m], >= 0 (0: the spacer is represented by its
        mounting offset only).
    width_difference : float
        Axial mounting offset of ``frame_b`` [m].
    exact : bool
        Exact kinematics (default) or the small-angle form.
    name : str
        Instance name (the prefix of its variables' dotted names).

    Variables
    ---------
    force [N] : axial force the spacer exerts on the body at ``frame_b`` (``-frame_b.Fz``)

    Connectors
    ----------
    frame_a, frame_b : RingFrame
    """

    def __init__(self, width: float = 0.0, width_difference: float = 0.0, exact: bool = True,
                 name=None):
        super().__init__(exact, name)
        self.width = Parameter(width, "m", "spacer width", low=0.0)
        self.width_difference = Parameter(width_difference, "m",
                                          "spacer width difference (axial mounting offset)")
        self.force = Variable(unit="N", description="axial force on the body at frame_b")

    def equations(self):
        return self.link_equations(self.width, self.width_difference) + [
            self.force == -self.frame_b.Fz
        ]


class Shaft(Component):
    """Rigid shaft with five degrees of freedom and frames at the bearing positions.

    ``M q'' + G q' = F_ext + sum_k T_k^T f_k`` with ``q = (x, y, z, tx, ty)`` of the centre of
    mass, ``M = diag(m, m, m, Jt, Jt)``, the gyroscopic coupling ``Jp Omega`` between the tilts
    (``Jt tx'' + Jp Omega ty' = Mx``, ``Jt ty'' - Jp Omega tx' = My``; Genta, *Dynamics of
    Rotating Systems*, 2005, chapter 4) and the loads ``f_k`` of the frames moved to the centre of
    mass with the exact lever ``R (0, 0, z_k)``.

    Parameters
    ----------
    mass : float
        Mass including the mounted inner rings [kg], > 0.
    transverse_inertia : float
        Moment of inertia about a transverse axis through the centre of mass [kg m^2], > 0.
    polar_inertia : float
        Moment of inertia about the shaft axis [kg m^2], >= 0.
    positions : sequence of float
        Axial positions of the frames (bearing rows) from the centre of mass [m].
    speed : float
        Spin speed Omega [rad/s].
    exact : bool
        Exact rigid-body kinematics of the frames (default) or the small-angle form.
    q0 : sequence of 5 float
        Initial displacement (x, y, z, tx, ty) [m, rad] (also the guess of equilibria).
    damping : sequence of 5 float, optional
        Viscous damping of the centre of mass against the ground (the housing) in (x, y, z,
        tx, ty) [N s/m, N s/m, N s/m, N m s/rad, N m s/rad], >= 0: a damper in parallel with
        the bearings, adding ``-c_i q_i'`` to the loads. It exerts no load at rest, so
        equilibria and stiffness do not change. ``None`` (default): no damping and no
        parameters ``c_x`` ... ``c_ty``.
    name : str
        Instance name (the prefix of its variables' dotted names).
    bounds : dict, optional
        Load name (``Fx`` ... ``My``) -> keywords of its input (``low``, ``high``,
        ``warn_above``, ``limit``: e.g. a duplex pair's static load rating); default: unbounded.

    Variables
    ---------
    x, y, z [m], tx, ty [rad] : displacement of the centre of mass; vx, vy, vz [m/s],
    wx, wy [rad/s] : their rates.
    Inputs Fx, Fy, Fz [N], Mx, My [N m] : external load at the centre of mass (default 0).

    Connectors
    ----------
    frame[k] : RingFrame at ``positions[k]``
    """

    def __init__(self, mass: float = 10.0, transverse_inertia: float = 0.05,
                 polar_inertia: float = 0.02, positions: Sequence[float] = (0.05, -0.05),
                 speed: float = 0.0, exact: bool = True, q0: Sequence[float] = (0.0,) * 5,
                 damping: Sequence[float] | None = None, name=None,
                 bounds: Mapping[str, Mapping[str, Any]] | None = None):
        super().__init__(name)
        if len(positions) < 1 or len(q0) != 5:
            raise ParameterError(f"{type(self).__name__}: positions [m] needs at least one entry "
                                 f"and q0 five (x, y, z, tx, ty) [m, rad]")
        if damping is not None and len(damping) != 5:
            raise ParameterError(f"{type(self).__name__}: damping needs 5 values (x, y, z, tx, "
                                 f"ty) [N s/m, N m s/rad], got {len(damping)}")
        self.mass = Parameter(mass, "kg", "shaft mass", low=0.0, low_inclusive=False)
        self.transverse_inertia = Parameter(transverse_inertia, "kg.m2",
                                            "transverse moment of inertia", low=0.0,
                                            low_inclusive=False)
        self.polar_inertia = Parameter(polar_inertia, "kg.m2", "polar moment of inertia", low=0.0)
        self.speed = Parameter(speed, "rad/s", "shaft spin speed")
        self._exact = exact
        self.positions = [self.add(f"position_{k}", Parameter(z, "m", f"axial position of "
                                                                     f"frame[{k}]"))
                          for k, z in enumerate(positions)]
        self.frame = [RingFrame() for _ in positions]
        for key, unit, start in zip(FRAME_POTENTIALS, ("m", "m", "m", "rad", "rad"), q0,
                                    strict=True):
            self.add(key, Variable(float(start), unit, f"{key} of the centre of mass"))
        for key, unit in zip(("vx", "vy", "vz", "wx", "wy"), ("m/s",) * 3 + ("rad/s",) * 2,
                             strict=True):
            self.add(key, Variable(0.0, unit, f"rate {key}"))
        for key, unit in zip(FRAME_FLOWS, ("N",) * 3 + ("N.m",) * 2, strict=True):
            self.add(key, Input(0.0, unit, f"external load {key} at the centre of mass",
                                **(bounds or {}).get(key, {})))
        units = ("N.s/m",) * 3 + ("N.m.s/rad",) * 2
        self._c = [] if damping is None else [
            self.add(f"c_{p}", Parameter(c, u, f"viscous damping of {p} against the ground",
                                         low=0.0))
            for p, c, u in zip(FRAME_POTENTIALS, damping, units, strict=True)]

    def equations(self):
        r = rotation(self.tx, self.ty, self._exact)
        eqs = []
        total = [getattr(self, k) for k in FRAME_FLOWS]
        if self._c:
            rates = (self.vx, self.vy, self.vz, self.wx, self.wy)
            total = [t - c * v for t, c, v in zip(total, self._c, rates, strict=True)]
        for frame, z_k in zip(self.frame, self.positions, strict=True):
            pos = body_point([self.x, self.y, self.z], r, [0.0, 0.0, z_k])
            eqs += [frame.x == pos[0], frame.y == pos[1], frame.z == pos[2] - z_k,
                    frame.tx == self.tx, frame.ty == self.ty]
            mx, my = frame_lever_moment(rotate(r, [0.0, 0.0, z_k]), frame)
            loads = (frame.Fx, frame.Fy, frame.Fz, frame.Mx + mx, frame.My + my)
            total = [t + f for t, f in zip(total, loads, strict=True)]
        m, jt, gyro = self.mass, self.transverse_inertia, self.polar_inertia * self.speed
        return eqs + [
            der(self.x) == self.vx,
            der(self.y) == self.vy,
            der(self.z) == self.vz,
            der(self.tx) == self.wx,
            der(self.ty) == self.wy,
            m * der(self.vx) == total[0],
            m * der(self.vy) == total[1],
            m * der(self.vz) == total[2],
            jt * der(self.wx) + gyro * self.wy == total[3],
            jt * der(self.wy) - gyro * self.wx == total[4],
        ]


class Housing(Component):
    """Housing: rigid (fixed frames) or a linear spring-damper support per degree of freedom.

    Parameters
    ----------
    n_frames : int
        Number of seats (frames), >= 1.
    stiffness : sequence of 5 float, optional
        Support stiffness of each seat in (x, y, z, tx, ty) [N/m, N/m, N/m, N m/rad, N m/rad],
        > 0; ``None`` makes the housing rigid.
    damping : sequence of 5 float, optional
        Support damping in the same order [N s/m, N m s/rad], >= 0 (default 0).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    frame[k] : RingFrame
    """

    def __init__(self, n_frames: int = 2, stiffness: Sequence[float] | None = None,
                 damping: Sequence[float] | None = None, name=None):
        super().__init__(name)
        if isinstance(n_frames, bool) or not isinstance(n_frames, int) or n_frames < 1:
            raise ParameterError(f"{type(self).__name__}: n_frames [-] must be an integer >= 1, "
                                 f"got {n_frames!r}")
        self.frame = [RingFrame() for _ in range(n_frames)]
        self._rigid = stiffness is None
        if self._rigid:
            if damping is not None:
                raise ParameterError(f"{type(self).__name__}: damping needs a stiffness (a rigid "
                                     "housing has no damping)")
            return
        damping = (0.0,) * 5 if damping is None else damping
        for name_, values in (("stiffness", stiffness), ("damping", damping)):
            if len(values) != 5:
                raise ParameterError(f"{type(self).__name__}: {name_} needs 5 values (x, y, z, "
                                     f"tx, ty), got {len(values)}")
        units = ("N/m",) * 3 + ("N.m/rad",) * 2
        self._k = [self.add(f"k_{p}", Parameter(v, u, f"support stiffness {p}", low=0.0,
                                                low_inclusive=False))
                   for p, v, u in zip(FRAME_POTENTIALS, stiffness, units, strict=True)]
        self._c = [self.add(f"c_{p}", Parameter(v, u + ".s", f"support damping {p}", low=0.0))
                   for p, v, u in zip(FRAME_POTENTIALS, damping, units, strict=True)]

    def equations(self):
        eqs = []
        for frame in self.frame:
            for k, (pot, flow) in enumerate(zip(FRAME_POTENTIALS, FRAME_FLOWS, strict=True)):
                u = getattr(frame, pot)
                if self._rigid:
                    eqs.append(u == 0)
                else:
                    eqs.append(getattr(frame, flow) == self._k[k] * u + self._c[k] * der(u))
        return eqs


class ConstantLoad(Component):
    """A constant load (e.g. a spring preload) acting on the body its frame is connected to.

    Parameters
    ----------
    Fx, Fy, Fz : float
        Force on the body [N].
    Mx, My : float
        Moment on the body [N m].
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    frame : RingFrame
    """

    def __init__(self, Fx: float = 0.0, Fy: float = 0.0, Fz: float = 0.0,  # noqa: N803
                 Mx: float = 0.0, My: float = 0.0, name=None):  # noqa: N803
        super().__init__(name)
        self.frame = RingFrame()
        units = ("N",) * 3 + ("N.m",) * 2
        self._values = [self.add(k, Parameter(v, u, f"applied load {k}"))
                        for k, v, u in zip(FRAME_FLOWS, (Fx, Fy, Fz, Mx, My), units, strict=True)]

    def equations(self):
        # the frame's flows are the loads on this component: minus the loads it applies
        return [f == -v for f, v in zip(self.frame.loads(), self._values, strict=True)]
