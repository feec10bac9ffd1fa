"""The rolling-element seam: what a bearing product needs to know about its rolling elements.

A new element type is a new set of implementations of these interfaces, not edits on every
floor:

* **Geometry** (:class:`ElementGeometry`): the catalogue face of a bearing (bore, pitch
  diameter, element count and diameter, ratings, speeds, ``bearing_type``, ``rolling_element``,
  ``contact``). Implementations: the ball :class:`~bearingsim.catalog.geometry.BearingGeometry`
  and the roller :class:`~bearingsim.catalog.rollers.RollerBearingGeometry`.
* **Contact law** (:class:`ContactLaw`): the load of one element between both raceways at its
  total elastic approach. Implementations: :class:`PointContact` (Hertz, ``Q = K delta^1.5``,
  the ball's :func:`~bearingsim.physics.contact_law.contact_load`) and :class:`LineContact`
  (Palmgren, two line contacts in series, sliced: :mod:`bearingsim.physics.line_contact`).
* **Row** (:class:`ElementRow`): a component with an inner and an outer
  :class:`~bearingsim.components.connectors.RingFrame` that puts the elements' loads on them.
  Implementations: :class:`~bearingsim.components.ball_row.BallRow` and
  :class:`~bearingsim.components.roller_row.RollerRow`.
* **Table keys and standards by element** (:func:`element_of`, :func:`friction_key`,
  :func:`static_equivalent_load`, :func:`resolve_geometry`): the one place where the ball and
  the roller differ for the friction tables (``f"{type}_ball"`` for balls, the roller's own
  type), ISO 76 (ball: X0/Y0 of the type; radial roller bearing with ``a = 0``: ``P0 = Fr``)
  and the catalogue lookup.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.catalog.rollers import RollerBearingGeometry, get_roller_bearing
from bearingsim.checks import MAX_STATIC_LOAD_FACTOR
from bearingsim.errors import CatalogError, ParameterError, PlasticDeformationWarning
from bearingsim.physics import line_contact
from bearingsim.physics.contact_law import contact_load
from bearingsim.physics.life import pair_static_load_rating, static_load_factors
from bearingsim.physics.life import static_equivalent_load as ball_static_equivalent_load
from bearingsim.validation import check_count, check_range

__all__ = [
    "ContactLaw",
    "ElementGeometry",
    "ElementRow",
    "LineContact",
    "PointContact",
    "check_static_rating",
    "element_of",
    "friction_key",
    "load_input_bounds",
    "magnitude_input_bounds",
    "resolve_geometry",
    "static_equivalent_load",
    "static_load_bounds",
]


@runtime_checkable
class ElementGeometry(Protocol):
    """The catalogue face of a rolling bearing, SI units."""

    designation: str
    bore: float
    outside_diameter: float
    pitch_diameter: float
    contact_angle: float
    dynamic_load_rating: float | None
    static_load_rating: float | None
    limiting_speed: float | None

    @property
    def bearing_type(self) -> str:
        """Type name, e.g. "deep_groove" (ball) or "cylindrical_roller"."""

    def check_speed(self, speed: float, where: str) -> None:
        """Warn above the catalogue limiting speed.

        Parameters
        ----------
        speed : float
            Speed of the rotating ring [rad/s].
        where : str
            Who checks, for messages.
        """


@runtime_checkable
class ContactLaw(Protocol):
    """Load of one rolling element between both raceways at its total elastic approach."""

    kind: str
    """"point" or "line"."""

    def load(self, approach: Any, smooth: float | None = None) -> Any:
        """Element load [N] at the total approach [m] (negative: a gap, no load).

        Parameters
        ----------
        approach : float, array or CasADi symbol
            Total elastic approach of the element [m] (negative: a gap, no load).
        smooth : float, optional
            Smoothing length of ``max(approach, 0)`` [m], > 0 (None: exact).

        Returns
        -------
        float, array or CasADi symbol
            Element load [N].
        """

    def approach(self, load: float) -> float:
        """Total approach [m] at the element load [N] (the inverse of :meth:`load`).

        Parameters
        ----------
        load : float
            Element load [N], >= 0.

        Returns
        -------
        float
            Total approach [m].
        """


@runtime_checkable
class ElementRow(Protocol):
    """A row of rolling elements between an inner and an outer ring frame."""

    inner: Any
    outer: Any

    def output_names(self, key: str) -> list[str]:
        """Dotted names of a per-element variable, in element order.

        Parameters
        ----------
        key : str
            A per-element variable.

        Returns
        -------
        list of str
            Its dotted names, in element order.
        """


@dataclass(frozen=True)
class PointContact:
    """Hertz point contact of a ball between both raceways, ``Q = K delta^1.5``.

    Attributes
    ----------
    stiffness : float
        Combined load-deflection constant K of both contacts in series [N/m^1.5], > 0
        (:func:`~bearingsim.physics.hertz.combined_load_deflection_constant`).
    """

    stiffness: float
    kind = "point"

    def __post_init__(self) -> None:
        check_range(self.stiffness, "stiffness", "N/m^1.5", 0.0, low_inclusive=False,
                    where="PointContact")

    def load(self, approach: Any, smooth: float | None = None) -> Any:
        """Ball load [N] (:func:`~bearingsim.physics.contact_law.contact_load`).

        Parameters
        ----------
        approach : float, array or CasADi symbol
            Total elastic approach of the element [m] (negative: a gap, no load).
        smooth : float, optional
            Smoothing length of ``max(approach, 0)`` [m], > 0 (None: exact).

        Returns
        -------
        float, array or CasADi symbol
            Ball load [N].
        """
        return contact_load(self.stiffness, approach, smooth)

    def approach(self, load: float) -> float:
        """Total approach [m], ``(Q/K)^(2/3)``.

        Parameters
        ----------
        load : float
            Element load [N], >= 0.

        Returns
        -------
        float
            Total approach [m].
        """
        check_range(load, "load", "N", 0.0, where="PointContact.approach")
        return (load / self.stiffness) ** (2.0 / 3.0)


@dataclass(frozen=True)
class LineContact:
    """Line contacts of a roller on both raceways (Palmgren), in series, sliced.

    Palmgren's law does not depend on the radii, so both contacts of a free roller take half the
    total approach of every slice (:mod:`bearingsim.physics.line_contact`).

    Attributes
    ----------
    length : float
        Effective roller length Lwe [m], > 0.
    n_slices : int
        Number of slices, >= 1.
    """

    length: float
    n_slices: int = 1
    kind = "line"

    def __post_init__(self) -> None:
        check_range(self.length, "length", "m", 0.0, low_inclusive=False, where="LineContact")
        check_count(self.n_slices, "n_slices", 1, where="LineContact")

    def slice_loads(self, approaches, smooth: float | None = None) -> list:
        """Loads of the slices [N] at their total approaches [m] (one entry per slice).

        Parameters
        ----------
        approaches : sequence
            Total approach of each slice [m].
        smooth : float, optional
            Smoothing length of ``max(approach, 0)`` [m], > 0 (None: exact).

        Returns
        -------
        list
            Slice loads [N].
        """
        return line_contact.slice_loads([0.5 * a for a in approaches], self.length, smooth)

    def load(self, approach: Any, smooth: float | None = None) -> Any:
        """Roller load [N] at a uniform total approach [m].

        Parameters
        ----------
        approach : float, array or CasADi symbol
            Total elastic approach of the element [m] (negative: a gap, no load).
        smooth : float, optional
            Smoothing length of ``max(approach, 0)`` [m], > 0 (None: exact).

        Returns
        -------
        float, array or CasADi symbol
            Roller load [N].
        """
        return line_contact.palmgren_load(0.5 * approach, self.length, smooth)

    def approach(self, load: float) -> float:
        """Total approach [m] of both contacts, ``2 c Q^0.9 / l^0.8``.

        Parameters
        ----------
        load : float
            Element load [N], >= 0.

        Returns
        -------
        float
            Total approach [m].
        """
        return 2.0 * float(line_contact.palmgren_deflection(load, self.length))


def element_of(geometry: Any) -> str:
    """The rolling element of a geometry: "roller" or "ball" (the ball geometry predates the
    seam and has no ``rolling_element``).

    Parameters
    ----------
    geometry : ElementGeometry

    Returns
    -------
    str
    """
    return getattr(geometry, "rolling_element", "ball")


def friction_key(geometry: Any) -> str:
    """Key of the friction tables (:data:`~bearingsim.physics.friction.PALMGREN_F1`, f0):
    ``f"{bearing_type}_ball"`` for balls, the roller's own type ("cylindrical_roller").

    Parameters
    ----------
    geometry : ElementGeometry

    Returns
    -------
    str
    """
    if element_of(geometry) == "ball":
        return f"{geometry.bearing_type}_ball"
    return geometry.bearing_type


def static_equivalent_load(Fr: Any, Fa: Any, geometry: Any,  # noqa: N803
                           arrangement: str | None = None) -> Any:
    """ISO 76 static equivalent load [N] of a ball or roller geometry.

    Ball bearings: :func:`bearingsim.physics.life.static_equivalent_load` (of one bearing, or
    of a DB, DF or DT pair of angular contact ball bearings). Radial roller bearings with
    ``a = 0`` (cylindrical, NU type: no axial load path): ``P0 = Fr`` (ISO 76:2006, radial
    roller bearings).

    Parameters
    ----------
    Fr, Fa : float, array or SX
        Radial and axial load [N], >= 0.
    geometry : ElementGeometry
    arrangement : {"DB", "DF", "DT"}, optional
        A pair of two such ball bearings rated as one (None: one bearing).

    Returns
    -------
    float, array or SX
        P0 [N].

    Raises
    ------
    ParameterError
        For an arrangement of roller bearings.
    """
    if element_of(geometry) == "ball":
        return ball_static_equivalent_load(Fr, Fa, geometry, arrangement)
    if arrangement is not None:
        raise ParameterError(f"static_equivalent_load: ISO 76 rates pairs of angular contact "
                             f"ball bearings, not {arrangement} pairs of {geometry.designation}")
    check_range(Fr, "Fr", "N", 0.0, where="static_equivalent_load")
    check_range(Fa, "Fa", "N", 0.0, where="static_equivalent_load")
    return Fr + 0.0 * Fa


def _rating(geometry: Any, arrangement: str | None) -> tuple[float, str] | None:
    """The static load rating [N] of one bearing or of a pair of them, and its words for
    messages ("C0 = 77000 N of 7020C", "C0 = 2 x 63570 N of a DF pair of 7020C"); None
    without a rating. A rating the geometry lists as estimated says so."""
    c0 = geometry.static_load_rating
    if c0 is None:
        return None
    estimated = "C0" in geometry.estimated
    if arrangement is None:
        note = " (estimated: ISO 76 of its ball set)" if estimated else ""
        return c0, f"C0 = {c0:.0f} N of {geometry.designation}{note}"
    note = "; one bearing's C0 estimated by ISO 76 from its ball set" if estimated else ""
    return (pair_static_load_rating(c0),
            f"C0 = 2 x {c0:.0f} N of a {arrangement} pair of {geometry.designation} "
            f"(ISO 76{note})")


def static_load_bounds(load: float) -> dict[str, Any]:
    """The :class:`~bearingsim.language.Input` keywords of a load input that warns above
    ``load`` and is refused beyond :data:`~bearingsim.checks.MAX_STATIC_LOAD_FACTOR` times it,
    in either direction.

    Parameters
    ----------
    load : float
        The load [N, or N m for a moment] that alone brings the static equivalent load to the
        static load rating, > 0.

    Returns
    -------
    dict
        ``low``, ``high``, ``warn_above`` and ``limit`` (``"static load"``).
    """
    check_range(load, "load", "N", 0.0, low_inclusive=False, where="static_load_bounds")
    return {"low": -MAX_STATIC_LOAD_FACTOR * load, "high": MAX_STATIC_LOAD_FACTOR * load,
            "warn_above": load, "limit": "static load"}


def load_input_bounds(*geometries: Any, arrangement: str | None = None
                      ) -> dict[str, dict[str, Any]]:
    """The bounds of the load inputs ``Fx``, ``Fy`` (radial) and ``Fz`` (axial) of bearings
    that each carry the whole load (one bearing, or the layers of a nested bearing in series),
    as :class:`~bearingsim.language.Input` keywords: each warns above the load that alone makes
    the ISO 76 static equivalent load of one of them reach its static load rating C0
    (``Fr = C0``; a ball bearing's ``Fa = C0 / Y0``; a radial roller bearing takes no axial
    load) and is refused beyond :data:`~bearingsim.checks.MAX_STATIC_LOAD_FACTOR` times it, as
    constant loads are (:func:`static_load_bounds`). With ``arrangement`` each geometry is a
    DB, DF or DT pair of angular contact ball bearings rated as one bearing by ISO 76: C0 of
    the pair twice one bearing's, X0 and Y0 of the pair
    (:func:`~bearingsim.physics.life.static_load_factors`): ``Fr = 2 C0`` and ``Fa = C0 / Y0``
    (DB, DF: one bearing carries each axial direction) or ``2 C0 / Y0`` (DT: both share it).

    Parameters
    ----------
    *geometries : ElementGeometry
        The bearings; one without a static load rating bounds nothing.
    arrangement : {"DB", "DF", "DT"}, optional
        Each bearing is a pair in this arrangement (None: one bearing).

    Returns
    -------
    dict
        Load name -> ``low``, ``high``, ``warn_above`` [N] and ``limit`` (``"static load"``).
    """
    alone: dict[str, float] = {}
    for g in geometries:
        rating = _rating(g, arrangement)
        if rating is None:
            continue
        c0 = rating[0]
        loads = {"Fx": c0, "Fy": c0}
        if element_of(g) == "ball":
            loads["Fz"] = c0 / static_load_factors(g, arrangement)[1]
        for key, load in loads.items():
            alone[key] = min(load, alone.get(key, math.inf))
    return {key: static_load_bounds(load) for key, load in alone.items()}


def check_static_rating(geometry: Any, forces: Any, where: str,
                        arrangement: str | None = None) -> None:
    """Warn when the ISO 76 static equivalent load of constant forces ``(Fx, Fy, Fz)`` [N]
    exceeds the static load rating C0 (4 200 MPa at the most loaded ball contact, permanent
    deformation beyond); refuse it beyond :data:`~bearingsim.checks.MAX_STATIC_LOAD_FACTOR`
    times C0 (beyond the strength of bearing steel: a unit slip).

    Parameters
    ----------
    geometry : ElementGeometry
        The bearing; without a static load rating nothing is checked.
    forces : sequence of float
        ``(Fx, Fy, Fz)`` [N].
    where : str
        The model, for messages.
    arrangement : {"DB", "DF", "DT"}, optional
        The forces act on a pair of two such bearings in this arrangement, rated as one by
        ISO 76 (:func:`load_input_bounds`); None: on one bearing.

    Raises
    ------
    ParameterError
        Beyond ``MAX_STATIC_LOAD_FACTOR`` times C0.

    Warns
    -----
    PlasticDeformationWarning
        Above C0.
    """
    rating = _rating(geometry, arrangement)
    if rating is None:
        return
    c0, words = rating
    p0 = float(static_equivalent_load(math.hypot(forces[0], forces[1]), abs(forces[2]),
                                      geometry, arrangement))
    if p0 > MAX_STATIC_LOAD_FACTOR * c0:
        raise ParameterError(
            f"{where}: the static equivalent load {p0:.4g} N is more than "
            f"{MAX_STATIC_LOAD_FACTOR:g} x the static load rating {words}: beyond the "
            f"strength of bearing steel (N given for kN?)")
    if p0 > c0:
        warnings.warn(f"{where}: the static equivalent load {p0:.0f} N exceeds the static load "
                      f"rating {words}: the raceways deform permanently",
                      PlasticDeformationWarning, stacklevel=3)


def magnitude_input_bounds(*geometries: Any) -> dict[str, dict[str, Any]]:
    """:func:`load_input_bounds` of the inputs ``Fr`` (radial load) and ``Fa`` (axial load),
    magnitudes >= 0 (the torque-level models).

    Parameters
    ----------
    *geometries : ElementGeometry
        The bearings, each carrying the whole load.

    Returns
    -------
    dict
        ``"Fr"`` and ``"Fa"`` -> ``low`` (0) and, where a static load rating bounds the load,
        ``high``, ``warn_above`` [N] and ``limit``.
    """
    bounds = load_input_bounds(*geometries)
    return {name: {**bounds.get(key, {}), "low": 0.0}
            for name, key in (("Fr", "Fx"), ("Fa", "Fz"))}


def resolve_geometry(bearing: Any) -> BearingGeometry | RollerBearingGeometry:
    """A geometry, or a designation looked up in the ball catalogue, then the roller one.

    Parameters
    ----------
    bearing : str or ElementGeometry

    Returns
    -------
    BearingGeometry or RollerBearingGeometry

    Raises
    ------
    CatalogError
        For a designation in neither catalogue (naming both).
    """
    if isinstance(bearing, (BearingGeometry, RollerBearingGeometry)):
        return bearing
    try:
        return resolve_bearing(bearing)
    except CatalogError as ball_error:
        try:
            return get_roller_bearing(bearing)
        except CatalogError as roller_error:
            raise CatalogError(f"{ball_error}; {roller_error}") from None
