"""The duplex pair's options, validated once (:class:`DuplexOptions`): bearing and arrangement,
preload or spacer offset, shaft, speed, rows and housing support, and the preload they give."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from bearingsim.assemblies.duplex.limits import check_pair_speed
from bearingsim.assemblies.duplex.preload import (
    ARRANGEMENTS,
    offset_preload,
    preload_force,
    preload_offset,
)
from bearingsim.assemblies.duplex.shaft import ShaftSpec, _shaft_spec
from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.errors import ParameterError
from bearingsim.physics.lubricant import Lubricant, as_lubricant
from bearingsim.validation import check_flag, check_quantity, check_range

__all__ = ["DuplexOptions", "si_option"]

WHERE = "duplex_pair"
"""The name the option checks give in their messages."""


def si_option(value: Any, name: str, unit: str, where: str = WHERE) -> float:
    """An option given as a number in ``unit`` or as a number with a unit (``"3000 rpm"``, a
    :class:`pint.Quantity`), in ``unit``, as every entry point takes them
    (:func:`bearingsim.validation.check_quantity`, with this model's name and as a float).

    Parameters
    ----------
    value : float, str or pint.Quantity
        The option's value.
    name : str
        The option, for messages.
    unit : str
        Its SI unit (model notation, ``"rad/s"``).
    where : str
        The model, for messages.

    Returns
    -------
    float
        The value in ``unit``.

    Raises
    ------
    ParameterError
        For a value that is not a finite number, a unit of another quantity
        (:class:`~bearingsim.units.UnitError`), naming the option and its unit.
    """
    return float(check_quantity(value, name, unit, where=where))


@dataclass(frozen=True)
class DuplexOptions:
    """Everything a duplex pair is built from (:class:`~bearingsim.assemblies.duplex.
    DuplexPair`); checked at construction.

    Attributes
    ----------
    bearing : str or BearingGeometry
        Bearing of both rows; resolved to ``geometry``.
    arrangement : {"DF", "DB", "DT"}
    preload : {"light", "medium", "heavy"} or float or str, optional
        Preload class or axial preload [N] (or "500 N"), > 0 (default: "light", or for a
        DF/DB pair with ``spacer_offset`` the preload that offset gives). A class is the
        catalogued one, or for a bearing without catalogued classes a fraction of its C
        (:func:`~bearingsim.assemblies.duplex.preload_force`).
    speed : float or str
        Shaft (inner ring) speed [rad/s], or a number with a unit ("3000 rpm", as every length,
        angle and force option here takes); warned above the pair's limiting speed, refused
        beyond twice it (:func:`~bearingsim.assemblies.duplex.limits.check_pair_speed`).
    shaft : ShaftSpec or dict, optional
        Resolved to ``shaft_spec`` (default: a solid steel shaft of the bearing's bore, four
        bores long, rows three bores apart).
    lubricant : str or Lubricant, optional
        Validated and kept for friction post-processing; the quasi-static model itself has no
        friction.
    ball_position_angle : float
        Azimuth of ball 0 of both rows [rad].
    contact_angle : float, optional
        Free contact angle of both rows [rad] in [0, 45 deg] (default: the bearing's).
    spacer_offset : float, optional
        Spacer width difference [m]. For DF/DB pairs it replaces ``preload`` (give one or the
        other; ``preload_force`` is then the preload it gives,
        :func:`~bearingsim.assemblies.duplex.offset_preload`). For DT pairs it is a mismatch of
        the spacers (default 0): the spring still sets the preload, but the rows share it
        unequally.
    speed_effects : bool, optional
        Jones-Harris rows with centrifugal force and gyroscopic moment; default: on when a
        ``speed`` other than 0 is given (a speed without them would change nothing). Resolved
        to True or False.
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
        [0, 1] (see :class:`~bearingsim.assemblies.duplex.DuplexPair`); None: no damper.
    geometry : BearingGeometry
        Derived from ``bearing``.
    shaft_spec : ShaftSpec
        Derived from ``shaft``.
    preload_force : float
        Derived: nominal preload [N], the class or given value, or for a DF/DB pair built from
        ``spacer_offset`` the preload of that offset (rigid housing, no speed effects).
    spacer_width_difference : float
        Derived: the inner spacer's width difference [m] that gives the preload (DF/DB), or
        the DT spacers' mismatch.

    Raises
    ------
    ParameterError
        For an arrangement, preload, speed, damping ratio, contact angle or shaft outside the
        ones above (naming ``duplex_pair``, the option, its unit and range), or both
        ``preload`` and ``spacer_offset`` for a DF/DB pair.

    Examples
    --------
    >>> from bearingsim.assemblies.duplex import DuplexOptions
    >>> options = DuplexOptions("7020C", "DB", preload="medium", damping_ratio=0.0025)
    >>> round(options.preload_force), options.speed_effects
    (1270, False)
    """

    bearing: str | BearingGeometry = "7020C"
    arrangement: str = "DF"
    preload: str | float | None = None
    speed: float = 0.0
    shaft: ShaftSpec | dict | None = None
    lubricant: str | Lubricant | None = None
    ball_position_angle: float = 0.0
    contact_angle: float | None = None
    spacer_offset: float | None = None
    speed_effects: bool | None = None
    housing_stiffness: Any = None
    housing_damping: Any = None
    exact: bool = True
    smooth: float = 1e-9
    axisymmetric: bool = False
    damping_ratio: float | None = None
    geometry: BearingGeometry = field(init=False, repr=False, compare=False)
    shaft_spec: ShaftSpec = field(init=False, repr=False, compare=False)
    preload_force: float = field(init=False, repr=False, compare=False)
    spacer_width_difference: float = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        g = resolve_bearing(self.bearing)
        if self.damping_ratio is not None:
            check_range(self.damping_ratio, "damping_ratio", "-", 0.0, 1.0, where=WHERE)
        if self.arrangement not in ARRANGEMENTS:
            raise ParameterError(f"{WHERE}: arrangement must be one of "
                                 f"{', '.join(ARRANGEMENTS)}, got {self.arrangement!r}")
        self._set(geometry=g, shaft_spec=_shaft_spec(self.shaft, g),
                  lubricant=None if self.lubricant is None
                  else as_lubricant(self.lubricant, WHERE))
        self._set(**{name: si_option(getattr(self, name), name, unit)
                     for name, unit in (("contact_angle", "rad"), ("spacer_offset", "m"))
                     if getattr(self, name) is not None})
        self._resolve_preload()
        speed = si_option(self.speed, "speed", "rad/s")
        check_pair_speed(g, speed, f"duplex_pair({g.designation})", self.preload_force)
        for name in ("exact", "axisymmetric"):
            check_flag(getattr(self, name), name, WHERE)
        check_flag(self.speed_effects, "speed_effects", WHERE, allow_none=True)
        self._set(speed=speed,
                  ball_position_angle=si_option(self.ball_position_angle, "ball_position_angle",
                                                "rad"),
                  smooth=si_option(self.smooth, "smooth", "m"),
                  speed_effects=speed != 0.0 if self.speed_effects is None
                  else self.speed_effects,
                  damping_ratio=None if self.damping_ratio is None
                  else float(self.damping_ratio))

    def _resolve_preload(self) -> None:
        """The preload force and the spacer width difference (from the class or force, or from
        the spacer offset of a DF/DB pair)."""
        g, arrangement, angle = self.geometry, self.arrangement, self.contact_angle
        if self.spacer_offset is not None and arrangement != "DT":
            if self.preload is not None:
                raise ParameterError(
                    f"{WHERE}: give either preload ({self.preload!r}) or spacer_offset "
                    f"({self.spacer_offset!r} m) for a {arrangement} pair: the spacer width "
                    "difference sets the preload"
                )
            offset = self.spacer_offset
            self._set(preload_force=offset_preload(g, offset, arrangement, angle),
                      spacer_width_difference=offset)
            return
        force = preload_force(g, "light" if self.preload is None else self.preload)
        if arrangement == "DT":
            offset = 0.0 if self.spacer_offset is None else self.spacer_offset
        else:
            offset = preload_offset(g, force, arrangement, angle)
        self._set(preload_force=force, spacer_width_difference=offset)

    def _set(self, **values: Any) -> None:
        for key, value in values.items():
            object.__setattr__(self, key, value)
