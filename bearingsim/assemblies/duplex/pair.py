"""The duplex pair assembly (:class:`DuplexPair`) and its factory :func:`duplex_pair`."""

from __future__ import annotations

import math

from bearingsim.assemblies.duplex.preload import (
    ARRANGEMENTS,
    offset_preload,
    preload_force,
    preload_offset,
    preload_stiffness,
)
from bearingsim.assemblies.duplex.shaft import ShaftSpec, _shaft_spec
from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.ball_row import BallRow, axial_approach, row_parameters
from bearingsim.components.rings import (
    ConstantLoad,
    Housing,
    InnerRing,
    OuterRing,
    Shaft,
    Spacer,
)
from bearingsim.errors import ParameterError
from bearingsim.language import Assembly, connect
from bearingsim.physics.lubricant import Lubricant, as_lubricant
from bearingsim.validation import check_range


class DuplexPair(Assembly):
    """Duplex pair: shaft, two ball rows, inner and outer rings, spacers and housing.

    Parameters
    ----------
    bearing : str or BearingGeometry
        Bearing of both rows.
    arrangement : {"DF", "DB", "DT"}
    preload : {"light", "medium", "heavy"} or float, optional
        Preload class or axial preload [N], > 0 (default: "light", or for a DF/DB pair with
        ``spacer_offset`` the preload that offset gives). A class is the catalogued one, or for
        a bearing without catalogued classes a fraction of its C (:func:`preload_force`).
    speed : float
        Shaft (inner ring) speed [rad/s].
    shaft : ShaftSpec or dict, optional
    lubricant : str or Lubricant, optional
        Validated and kept as ``self.lubricant`` for friction post-processing; the quasi-static
        model itself has no friction.
    ball_position_angle : float
        Azimuth of ball 0 of both rows [rad].
    contact_angle : float, optional
        Free contact angle of both rows [rad] in [0, 45 deg] (default: the bearing's).
    spacer_offset : float, optional
        Spacer width difference [m]. For DF/DB pairs it replaces ``preload`` (give one or the
        other; ``preload_force`` is then the preload it gives, :func:`offset_preload`). For DT
        pairs it is a mismatch of the spacers (default 0): the spring still sets the preload,
        but the rows share it unequally.
    speed_effects : bool, optional
        Jones-Harris rows with centrifugal force and gyroscopic moment; default: on when a
        ``speed`` other than 0 is given (a speed without them would change nothing).
    housing_stiffness, housing_damping : sequence of 5 float, optional
        Spring-damper support of each outer ring (default: rigid housing).
    exact : bool
        Exact rigid-body kinematics (default) or the small-angle form.
    smooth : float
        Contact regularization length [m].
    axisymmetric : bool
        Solve one representative ball per row (valid for pure axial loads only: the shaft then
        has no radial or tilt load path; see ``BallRow(representative=True)``).
    damping_ratio : float, optional
        Viscous damping of the shaft against the housing as a damping ratio zeta [-] in
        [0, 1]: per degree of freedom ``c_i = 2 zeta sqrt(k_ii m_ii)`` (``Shaft(damping=...)``)
        with ``k_ii`` the pair's stiffness at its preload (:func:`preload_stiffness`: rigid
        housing, no speed effects) and ``m_ii`` the shaft's mass or transverse inertia, so
        each uncoupled mode of the unloaded pair decays with about this ratio. The quasi-static
        rows have no damping of their own, so without it (default None: no damper) a load
        step rings for ever; the damper exerts no load at rest, so equilibria do not change.
        The duplex study's loss factor (docs/studies.md, section B) ``eta = 0.005`` is
        ``zeta = 0.0025``.

    Attributes
    ----------
    preload_force : float
        Nominal preload [N]: the class or given value, or for a DF/DB pair built from
        ``spacer_offset`` the preload of that offset (rigid housing, no speed effects).
    preload : str or float or None
        The preload class or value the pair was built with (None for a DF/DB pair built from
        ``spacer_offset``).
    speed, ball_position_angle : float
        Shaft speed [rad/s] and azimuth of ball 0 [rad] the pair was built with.
    contact_angle, spacer_offset : float or None
        The free contact angle [rad] and spacer width difference [m] given (None: default).
    directions : tuple of int
        Loading direction of each row.
    shaft_spec : ShaftSpec
    """

    def __init__(self, bearing: str | BearingGeometry = "7020C", arrangement: str = "DF",
                 preload: str | float | None = None, speed: float = 0.0,
                 shaft: ShaftSpec | dict | None = None, lubricant: str | Lubricant | None = None,
                 ball_position_angle: float = 0.0, contact_angle: float | None = None,
                 spacer_offset: float | None = None, speed_effects: bool | None = None,
                 housing_stiffness=None, housing_damping=None, exact: bool = True,
                 smooth: float = 1e-9, axisymmetric: bool = False,
                 damping_ratio: float | None = None, name="pair"):
        super().__init__(name)
        g = resolve_bearing(bearing)
        if damping_ratio is not None:
            check_range(damping_ratio, "damping_ratio", "-", 0.0, 1.0, where="duplex_pair")
        if arrangement not in ARRANGEMENTS:
            raise ParameterError(f"duplex_pair: arrangement must be one of "
                                 f"{', '.join(ARRANGEMENTS)}, got {arrangement!r}")
        self.geometry = g
        self.arrangement = arrangement
        self.directions = ARRANGEMENTS[arrangement]
        self.shaft_spec = spec = _shaft_spec(shaft, g)
        self.lubricant = None if lubricant is None else as_lubricant(lubricant, "duplex_pair")
        if spacer_offset is not None and arrangement != "DT":
            if preload is not None:
                raise ParameterError(
                    f"duplex_pair: give either preload ({preload!r}) or spacer_offset "
                    f"({spacer_offset!r} m) for a {arrangement} pair: the spacer width "
                    "difference sets the preload"
                )
            offset = float(spacer_offset)
            self.preload_force = offset_preload(g, offset, arrangement, contact_angle)
        else:
            preload = "light" if preload is None else preload
            self.preload_force = preload_force(g, preload)
            if arrangement == "DT":
                offset = 0.0 if spacer_offset is None else float(spacer_offset)
            else:
                offset = preload_offset(g, self.preload_force, arrangement, contact_angle)
        self.preload = preload
        self.speed = float(speed)
        g.check_speed(self.speed, f"duplex_pair({g.designation})")
        if speed_effects is None:
            speed_effects = self.speed != 0.0
        self.contact_angle = None if contact_angle is None else float(contact_angle)
        self.ball_position_angle = float(ball_position_angle)
        self.spacer_offset = None if spacer_offset is None else float(spacer_offset)
        s0 = self.directions[0]
        if arrangement == "DT":
            delta0 = axial_approach(row_parameters(g, contact_angle), g.ball_count,
                                    0.5 * self.preload_force)
        else:
            delta0 = 0.5 * abs(offset)
        self.spacer_width_difference = offset
        self.damping_ratio = None if damping_ratio is None else float(damping_ratio)
        damping = None
        if damping_ratio is not None:
            k = preload_stiffness(g, self.directions, spec.positions, (delta0, delta0),
                                  contact_angle)
            mass = (spec.m,) * 3 + (spec.jt,) * 2
            damping = [2.0 * self.damping_ratio * math.sqrt(max(k_i, 0.0) * m_i)
                       for k_i, m_i in zip(k, mass, strict=True)]
        self.shaft = Shaft(spec.m, spec.jt, spec.jp, spec.positions, speed, exact,
                           q0=(0.0, 0.0, s0 * delta0, 0.0, 0.0), damping=damping)
        self.housing = Housing(2, housing_stiffness, housing_damping)
        self.inner_ring = [InnerRing(exact=exact) for _ in range(2)]
        self.outer_ring = [OuterRing(exact=exact) for _ in range(2)]
        self.inner_spacer = Spacer(width_difference=offset, exact=exact)
        self.outer_spacer = Spacer(exact=exact)
        self.row = [BallRow(g, s, contact_angle=contact_angle,
                            ball_position_angle=ball_position_angle,
                            speed_effects=speed_effects, exact=exact, smooth=smooth,
                            representative=axisymmetric)
                    for s in self.directions]
        for k in range(2):
            self.inner_ring[k].speed = self.shaft.speed
            self.row[k].inner_speed = self.inner_ring[k].speed
            self.row[k].outer_speed = self.outer_ring[k].speed
            connect(self.inner_ring[k].frame_b, self.row[k].inner)
            connect(self.outer_ring[k].frame_b, self.row[k].outer)
        connect(self.shaft.frame[0], self.inner_ring[0].frame_a)
        connect(self.shaft.frame[1], self.inner_spacer.frame_a)
        connect(self.inner_spacer.frame_b, self.inner_ring[1].frame_a)
        connect(self.housing.frame[0], self.outer_ring[0].frame_a)
        connect(self.housing.frame[1], self.outer_spacer.frame_a)
        connect(self.outer_spacer.frame_b, self.outer_ring[1].frame_a)
        if arrangement == "DT":
            self.spring = ConstantLoad(Fz=s0 * self.preload_force)
            connect(self.spring.frame, self.shaft.frame[0])


def duplex_pair(designation: str | BearingGeometry = "7020C", arrangement: str = "DF",
                preload: str | float | None = None, speed: float = 0.0,
                shaft: ShaftSpec | dict | None = None, lubricant=None,
                ball_position_angle: float = 0.0, **kwargs) -> DuplexPair:
    """Build a duplex pair assembly; see :class:`DuplexPair` for the parameters.

    Examples
    --------
    >>> from bearingsim.assemblies.duplex import duplex_pair
    >>> pair = duplex_pair("7020C", "DF", preload="medium")
    >>> round(pair.preload_force)
    1270
    """
    return DuplexPair(designation, arrangement, preload, speed, shaft, lubricant,
                      ball_position_angle, **kwargs)
