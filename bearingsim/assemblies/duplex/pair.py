"""The duplex pair assembly (:class:`DuplexPair`) and its factory :func:`duplex_pair`."""

from __future__ import annotations

import math
from typing import Any

from bearingsim.assemblies.duplex.limits import pair_load_bounds
from bearingsim.assemblies.duplex.options import DuplexOptions
from bearingsim.assemblies.duplex.preload import ARRANGEMENTS, preload_stiffness
from bearingsim.assemblies.duplex.shaft import ShaftSpec
from bearingsim.catalog import BearingGeometry
from bearingsim.components.ball_row import BallRow, axial_approach, row_parameters
from bearingsim.components.rings import (
    ConstantLoad,
    Housing,
    InnerRing,
    OuterRing,
    Shaft,
    Spacer,
)
from bearingsim.language import Assembly, connect
from bearingsim.validation import check_options, keyword_names, options_object


class DuplexPair(Assembly):
    """Duplex pair: shaft, two ball rows, inner and outer rings, spacers and housing.

    Parameters
    ----------
    options : DuplexOptions, optional
        Bearing, arrangement, preload, shaft, speed, rows and housing, checked when it was
        built (:class:`~bearingsim.assemblies.duplex.options.DuplexOptions`); default: a
        7020C DF pair at light preload, at rest.
    name : str
        Instance name.
    shared_radial : bool
        Further supports of the shaft (a spindle's rear bearing) share its radial loads and
        moments: only the axial load input ``shaft.Fz`` is bounded by the pair's static load
        rating (:func:`~bearingsim.assemblies.duplex.limits.pair_load_bounds`); default False:
        every load input is.

    Notes
    -----
    ``damping_ratio`` zeta gives per degree of freedom ``c_i = 2 zeta sqrt(k_ii m_ii)``
    (``Shaft(damping=...)``) with ``k_ii`` the pair's stiffness at its preload
    (:func:`preload_stiffness`: rigid housing, no speed effects) and ``m_ii`` the shaft's mass
    or transverse inertia, so each uncoupled mode of the unloaded pair decays with about this
    ratio. The quasi-static rows have no damping of their own, so without it (None: no damper)
    a load step rings for ever; the damper exerts no load at rest, so equilibria do not change.
    The duplex study's loss factor (docs/studies.md, section B) ``eta = 0.005`` is
    ``zeta = 0.0025``.

    Attributes
    ----------
    options : DuplexOptions
    geometry : BearingGeometry
    arrangement : str
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
    spacer_width_difference : float
        The inner spacer's width difference [m] built in.
    damping_ratio : float or None
    lubricant : Lubricant or None
    directions : tuple of int
        Loading direction of each row.
    shaft_spec : ShaftSpec
    """

    def __init__(self, options: DuplexOptions | None = None, name="pair",
                 shared_radial: bool = False):
        super().__init__(name)
        options = options_object(options, DuplexOptions, "duplex_pair")
        self.options = options
        self.geometry = options.geometry
        self.arrangement = options.arrangement
        self.directions = ARRANGEMENTS[options.arrangement]
        self.shaft_spec = options.shaft_spec
        self.lubricant = options.lubricant
        self.preload_force = options.preload_force
        by_offset = options.spacer_offset is not None and options.arrangement != "DT"
        self.preload = options.preload if by_offset or options.preload is not None else "light"
        self.speed = options.speed
        self.contact_angle = options.contact_angle
        self.ball_position_angle = options.ball_position_angle
        self.spacer_offset = options.spacer_offset
        self.spacer_width_difference = options.spacer_width_difference
        self.damping_ratio = options.damping_ratio
        self._build_shaft(pair_load_bounds(options, radial=not shared_radial))
        self._build_rings_and_rows()
        self._connect()

    def _start_approach(self) -> float:
        """The axial approach of each row at the preload [m]: half the spacer offset (DF, DB)
        or the approach of half the spring force (DT)."""
        g, options = self.geometry, self.options
        if options.arrangement == "DT":
            return axial_approach(row_parameters(g, options.contact_angle), g.ball_count,
                                  0.5 * self.preload_force)
        return 0.5 * abs(self.spacer_width_difference)

    def _build_shaft(self, bounds: dict[str, dict[str, Any]]) -> None:
        """The shaft at its preloaded start, damped against the housing with
        ``damping_ratio``, its load inputs held to ``bounds``."""
        spec, options = self.shaft_spec, self.options
        delta0 = self._start_approach()
        damping = None
        if self.damping_ratio is not None:
            k = preload_stiffness(self.geometry, self.directions, spec.positions,
                                  (delta0, delta0), options.contact_angle)
            mass = (spec.m,) * 3 + (spec.jt,) * 2
            damping = [2.0 * self.damping_ratio * math.sqrt(max(k_i, 0.0) * m_i)
                       for k_i, m_i in zip(k, mass, strict=True)]
        self.shaft = Shaft(spec.m, spec.jt, spec.jp, spec.positions, options.speed,
                           options.exact, q0=(0.0, 0.0, self.directions[0] * delta0, 0.0, 0.0),
                           damping=damping, bounds=bounds)

    def _build_rings_and_rows(self) -> None:
        """Housing, rings, spacers (the inner one with the width difference) and ball rows."""
        options, exact = self.options, self.options.exact
        self.housing = Housing(2, options.housing_stiffness, options.housing_damping)
        self.inner_ring = [InnerRing(exact=exact) for _ in range(2)]
        self.outer_ring = [OuterRing(exact=exact) for _ in range(2)]
        self.inner_spacer = Spacer(width_difference=self.spacer_width_difference, exact=exact)
        self.outer_spacer = Spacer(exact=exact)
        self.row = [BallRow(self.geometry, s, contact_angle=options.contact_angle,
                            ball_position_angle=options.ball_position_angle,
                            speed_effects=options.speed_effects, exact=exact,
                            smooth=options.smooth, representative=options.axisymmetric)
                    for s in self.directions]

    def _connect(self) -> None:
        """Shaft, inner rings and rows; housing, outer rings and rows; a DT pair's spring."""
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
        if self.arrangement == "DT":
            self.spring = ConstantLoad(Fz=self.directions[0] * self.preload_force)
            connect(self.spring.frame, self.shaft.frame[0])


def duplex_pair(designation: str | BearingGeometry = "7020C", arrangement: str = "DF",
                preload: str | float | None = None, speed: float = 0.0,
                shaft: ShaftSpec | dict | None = None, lubricant=None,
                ball_position_angle: float = 0.0, name: str = "pair",
                shared_radial: bool = False, **options: Any) -> DuplexPair:
    """Build a duplex pair assembly from keywords.

    Parameters
    ----------
    designation : str or BearingGeometry
        Bearing of both rows.
    arrangement, preload, speed, shaft, lubricant, ball_position_angle
        As the fields of :class:`~bearingsim.assemblies.duplex.options.DuplexOptions`.
    name : str
        Instance name.
    shared_radial : bool
        As for :class:`DuplexPair`.
    **options
        The other fields of :class:`~bearingsim.assemblies.duplex.options.DuplexOptions`
        (``contact_angle``, ``spacer_offset``, ``speed_effects``, ``housing_stiffness``,
        ``housing_damping``, ``exact``, ``smooth``, ``axisymmetric``, ``damping_ratio``);
        another name raises :class:`~bearingsim.errors.ParameterError` listing them.

    Returns
    -------
    DuplexPair

    Examples
    --------
    >>> from bearingsim.assemblies.duplex import duplex_pair
    >>> pair = duplex_pair("7020C", "DF", preload="medium")
    >>> round(pair.preload_force)
    1270
    """
    check_options(options, keyword_names(DuplexOptions, (
        "bearing", "arrangement", "preload", "speed", "shaft", "lubricant",
        "ball_position_angle")), "duplex_pair", "option(s)",
        owner=duplex_pair)
    return DuplexPair(DuplexOptions(designation, arrangement, preload, speed, shaft, lubricant,
                                    ball_position_angle, **options), name, shared_radial)
