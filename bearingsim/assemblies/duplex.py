"""Duplex pairs of angular contact ball bearings: DF, DB and DT (docs/studies.md, section B).

A rigid shaft runs in two quasi-static ball rows (:class:`~bearingsim.components.ball_row.
BallRow`). Each row's inner ring sits on the shaft, its outer ring in the housing. The rows lie
at ``z = L1`` (row 0) and ``z = -L2`` (row 1) from the shaft's centre of mass. Arrangements
(the axial direction ``s`` in which each row's inner ring must move to load it):

* **DB** (back-to-back, "O"): ``s = (-1, +1)``; the contact lines meet the axis outside the
  rows, at the pressure centres ``z = L1 + (dm/2) tan a`` and ``-L2 - (dm/2) tan a``.
* **DF** (face-to-face, "X"): ``s = (+1, -1)``; pressure centres ``L1 - (dm/2) tan a`` and
  ``-L2 + (dm/2) tan a``, so the tilt stiffness is lower than DB's.
* **DT** (tandem): ``s = (+1, +1)``; both rows carry thrust in +z and share it.

The inner and outer spacers between the rows differ in width; after clamping, row 1's inner
ring sits ``width_difference`` further along the axis than in the reference configuration in
which its balls just touch. The model represents the clamped stack exactly by a
:class:`~bearingsim.components.rings.Spacer` of zero lever between the shaft's row-1 frame and
row 1's inner ring, carrying the mounting offset (and the preload as its force). A DT pair is
preloaded by a constant axial (spring) force on the shaft instead.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

from bearingsim.assemblies.spec import ArgSpec, AssemblySpec, factory_default
from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.ball_row import BallRow, axial_approach, row_loads, row_parameters
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
from bearingsim.validation import check_choice, check_range

__all__ = ["ShaftSpec", "DuplexPair", "duplex_pair", "ARRANGEMENTS", "PRELOAD_CLASSES",
           "PRELOAD_FRACTIONS", "SCENE_SPEC", "preload_offset", "preload_force", "offset_preload",
           "preload_stiffness"]

ARRANGEMENTS = {"DF": (1, -1), "DB": (-1, 1), "DT": (1, 1)}
"""Axial loading direction ``s`` of (row 0, row 1) for each arrangement."""
PRELOAD_CLASSES = ("light", "medium", "heavy")
STEEL_DENSITY = 7850.0


@dataclass(frozen=True)
class ShaftSpec:
    """Shaft of a duplex pair: mass properties and row positions.

    The source study does not give them; the defaults describe a solid steel shaft of 100 mm
    diameter (the 7020 bore) and 400 mm length with the rows 300 mm apart, centred on the centre
    of mass. The tilt stiffness goes with ``(L -+ (dm/2) tan a)^2`` (pressure centres), so the
    study's finding that the contact angle changes the axial mode most holds only for rows far
    apart compared with ``(dm/2) tan a`` (17 to 36 mm for the 7020 series); with rows 100 mm
    apart the DF tilt modes change more.

    Attributes
    ----------
    diameter, length : float
        Of the solid cylinder that gives the default mass properties [m].
    row_spacing : float
        Axial distance between the two rows' centres [m], > 0.
    centre_offset : float
        Axial position of the midpoint between the rows from the centre of mass [m].
    mass, transverse_inertia, polar_inertia : float, optional
        Override the solid-cylinder values [kg, kg m^2, kg m^2]; include the inner rings.
    density : float
        Material density [kg/m^3].
    """

    diameter: float = 0.100
    length: float = 0.400
    row_spacing: float = 0.300
    centre_offset: float = 0.0
    mass: float | None = None
    transverse_inertia: float | None = None
    polar_inertia: float | None = None
    density: float = STEEL_DENSITY

    def __post_init__(self) -> None:
        for name in ("diameter", "length", "row_spacing", "density"):
            check_range(getattr(self, name), name, "m" if name != "density" else "kg/m3", 0.0,
                        low_inclusive=False, where="ShaftSpec")
        check_range(self.centre_offset, "centre_offset", "m", where="ShaftSpec")
        for name in ("mass", "transverse_inertia", "polar_inertia"):
            if getattr(self, name) is not None:
                check_range(getattr(self, name), name, "kg" if name == "mass" else "kg.m2", 0.0,
                            low_inclusive=False, where="ShaftSpec")

    @property
    def solid_mass(self) -> float:
        """Mass of the solid cylinder [kg]."""
        return self.density * math.pi * self.diameter**2 / 4.0 * self.length

    @property
    def m(self) -> float:
        """Shaft mass [kg]."""
        return self.solid_mass if self.mass is None else self.mass

    @property
    def jt(self) -> float:
        """Transverse moment of inertia about the centre of mass, ``m (3 r^2 + l^2) / 12``."""
        if self.transverse_inertia is not None:
            return self.transverse_inertia
        return self.m * (0.75 * self.diameter**2 + self.length**2) / 12.0

    @property
    def jp(self) -> float:
        """Polar moment of inertia, ``m r^2 / 2`` [kg m^2]."""
        return self.m * self.diameter**2 / 8.0 if self.polar_inertia is None else \
            self.polar_inertia

    @property
    def positions(self) -> tuple[float, float]:
        """Axial positions (L1, -L2) of row 0 and row 1 from the centre of mass [m]."""
        half = 0.5 * self.row_spacing
        return (self.centre_offset + half, self.centre_offset - half)


def _shaft_spec(shaft: ShaftSpec | dict | None, geometry: BearingGeometry) -> ShaftSpec:
    """The shaft: by default a solid steel shaft of the bearing's bore, four bores long, with
    the rows three bores apart (the 7020 default: 100 mm x 400 mm, rows 300 mm apart); a given
    shaft whose diameter is not the bore warns (its inner rings would not fit)."""
    if shaft is None:
        bore = geometry.bore
        return ShaftSpec(diameter=bore, length=4.0 * bore, row_spacing=3.0 * bore)
    if isinstance(shaft, dict):
        try:
            shaft = ShaftSpec(**shaft)
        except TypeError as exc:
            raise ParameterError(f"duplex_pair: bad shaft specification: {exc}") from None
    if not isinstance(shaft, ShaftSpec):
        raise ParameterError(f"duplex_pair: shaft must be a ShaftSpec or a dict, got {shaft!r}")
    if not math.isclose(shaft.diameter, geometry.bore, rel_tol=1e-6):
        warnings.warn(f"duplex_pair: the shaft diameter {shaft.diameter * 1e3:g} mm is not the "
                      f"bore of {geometry.designation} ({geometry.bore * 1e3:g} mm); its mass "
                      f"properties are those of the shaft given", UserWarning, stacklevel=4)
    return shaft


PRELOAD_FRACTIONS = {15.0: (0.0085, 0.020, 0.040), 25.0: (0.014, 0.033, 0.065),
                     30.0: (0.015, 0.048, 0.075)}
"""Preload rule for bearings without catalogued classes: free contact angle [deg] -> axial
preload of the light, medium and heavy class as a fraction of the basic dynamic load rating C
[-]; linear in the contact angle between the entries, the end entries outside them.

No published rule was found (catalogues tabulate preload classes per bearing, not as a
fraction of C), so the fractions are the ones the catalogue's own classes imply: the NSK
precision 7020 series of docs/studies.md, section B (7020C 15 deg: 540/1270/2550 N, 7020A5 25 deg:
830/1960/3920 N, 7020A 30 deg: 840/2750/4310 N) divided by the ISO 281 C of their ball set
(63.5, 59.9 and 57.5 kN), rounded to two digits; ``tests/test_duplex.py`` recomputes them. For
a 15 deg bearing that is about 1 %, 2 % and 4 % of C."""


def _class_fraction(level: str, contact_angle: float) -> float:
    """Fraction of C of a preload class at a contact angle [rad] (:data:`PRELOAD_FRACTIONS`)."""
    angles = sorted(PRELOAD_FRACTIONS)
    column = PRELOAD_CLASSES.index(level)
    alpha = min(max(math.degrees(contact_angle), angles[0]), angles[-1])
    for lo, hi in zip(angles, angles[1:], strict=False):
        if alpha <= hi:
            w = (alpha - lo) / (hi - lo)
            return (1.0 - w) * PRELOAD_FRACTIONS[lo][column] + w * PRELOAD_FRACTIONS[hi][column]
    return PRELOAD_FRACTIONS[angles[-1]][column]  # pragma: no cover - alpha is clamped


def preload_force(geometry: BearingGeometry, preload: str | float) -> float:
    """Axial preload [N] of a class name ("light", "medium", "heavy") or a number.

    A class is the bearing's catalogued preload of that class; for an angular contact bearing
    without catalogued classes but with a basic dynamic load rating C, it is the fraction
    :data:`PRELOAD_FRACTIONS` of C at the bearing's contact angle (e.g. 7014C, C = 48.5 kN:
    light 412 N, medium 970 N, heavy 1940 N).

    Raises
    ------
    ParameterError
        For an unknown class, a class of a bearing with neither catalogued classes nor (angular
        contact with) C, or a preload <= 0.
    """
    if isinstance(preload, str):
        check_choice(preload, "preload class", PRELOAD_CLASSES, "duplex_pair")
        if geometry.preload is not None:
            return geometry.preload[preload]
        if geometry.dynamic_load_rating is None or geometry.bearing_type != "angular_contact":
            missing = ("no dynamic load rating C" if geometry.bearing_type == "angular_contact"
                       else "a contact angle of 0 (the rule of C is for angular contact bearings)")
            raise ParameterError(
                f"duplex_pair: bearing {geometry.designation} has no catalogued preload classes "
                f"and {missing}, so preload {preload!r} is undefined; give the preload in N "
                "(a number > 0), or an angular contact bearing with preload classes or C "
                "(e.g. C_kN in its datasheet)")
        return _class_fraction(preload, geometry.contact_angle) * geometry.dynamic_load_rating
    check_range(preload, "preload", "N", 0.0, low_inclusive=False, where="duplex_pair")
    return float(preload)


def _spacer_arrangement(arrangement: str, where: str) -> tuple[float, float]:
    """The row directions of a DF or DB pair (those a spacer width difference preloads)."""
    if arrangement not in ("DF", "DB"):
        raise ParameterError(f"{where}: arrangement must be 'DF' or 'DB', got "
                             f"{arrangement!r} (a DT pair is preloaded by an axial force)")
    return ARRANGEMENTS[arrangement]


def preload_offset(bearing: str | BearingGeometry, preload: float, arrangement: str = "DF",
                   contact_angle: float | None = None) -> float:
    """Spacer width difference that preloads a DF or DB pair of identical rows [m].

    Each row must carry the axial ``preload``: its inner ring moves by the row's axial approach
    ``delta_a`` (:func:`~bearingsim.components.ball_row.axial_approach`, Jones's relation) along
    its loading direction, so the offset is ``s1 delta_a - s0 delta_a``.

    Parameters
    ----------
    bearing : str or BearingGeometry
    preload : float
        Axial preload [N], > 0.
    arrangement : {"DF", "DB"}
    contact_angle : float, optional
        Free contact angle [rad] (default: the bearing's).

    Returns
    -------
    float
        The width difference [m] (negative for DF, positive for DB).
    """
    s0, s1 = _spacer_arrangement(arrangement, "preload_offset")
    g = resolve_bearing(bearing)
    delta = axial_approach(row_parameters(g, contact_angle), g.ball_count, preload)
    return (s1 - s0) * delta


def offset_preload(bearing: str | BearingGeometry, offset: float, arrangement: str = "DF",
                   contact_angle: float | None = None) -> float:
    """Axial preload [N] that a spacer width difference gives a DF or DB pair of identical rows.

    The inverse of :func:`preload_offset`: each row's inner ring moves by ``|offset| / 2``
    along its loading direction and the row carries the axial load of that approach (classic
    row, rigid rings and housing, no speed effects).

    Parameters
    ----------
    bearing : str or BearingGeometry
    offset : float
        Spacer width difference [m]: < 0 for DF, > 0 for DB.
    arrangement : {"DF", "DB"}
    contact_angle : float, optional
        Free contact angle [rad] (default: the bearing's).

    Returns
    -------
    float
        Axial preload of each row [N], > 0.

    Raises
    ------
    ParameterError
        For a DT arrangement or an offset of the wrong sign (axial play).
    """
    s0, s1 = _spacer_arrangement(arrangement, "offset_preload")
    if not offset * (s1 - s0) > 0.0:
        raise ParameterError(
            f"duplex_pair: a spacer width difference of {offset:g} m leaves both rows of the "
            f"{arrangement} pair unloaded (axial play); valid range: "
            f"{'> 0' if s1 > s0 else '< 0'} m"
        )
    g = resolve_bearing(bearing)
    loads = row_loads(row_parameters(g, contact_angle), [0.0, 0.0, 0.5 * abs(offset), 0.0, 0.0],
                      [0.0] * 5, g.ball_count, 1)
    return -float(loads.inner_load[2])


def preload_stiffness(bearing: str | BearingGeometry, directions: tuple[int, int],
                      positions: tuple[float, float], approach: tuple[float, float],
                      contact_angle: float | None = None) -> list[float]:
    """Diagonal of the 5x5 stiffness of a shaft on two ball rows at rest, about its centre of
    mass [N/m, N/m, N/m, N m/rad, N m/rad].

    Each row's ``5 x 5`` stiffness is the central difference of its ring loads
    (:func:`~bearingsim.components.ball_row.row_loads`, classic rows: no speed effects) at the
    inner ring's axial ``approach`` along the row's loading direction; the rows are moved to
    the centre of mass with the levers of their ``positions`` (rigid housing).

    Parameters
    ----------
    bearing : str or BearingGeometry
    directions : (int, int)
        Loading direction of each row.
    positions : (float, float)
        Axial position of each row from the centre of mass [m].
    approach : (float, float)
        Axial approach of each row's inner ring along its loading direction [m], > 0.
    contact_angle : float, optional
        Free contact angle [rad] (default: the bearing's).

    Returns
    -------
    list of 5 float
    """
    g = resolve_bearing(bearing)
    rp = row_parameters(g, contact_angle)
    total = [[0.0] * 5 for _ in range(5)]
    for s, z_k, delta in zip(directions, positions, approach, strict=True):
        lever = [[1.0, 0.0, 0.0, 0.0, z_k], [0.0, 1.0, 0.0, -z_k, 0.0], [0.0, 0.0, 1.0, 0.0, 0.0],
                 [0.0, 0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 0.0, 1.0]]
        steps = (1e-3 * delta,) * 3 + (2e-3 * delta / g.pitch_diameter,) * 2
        row = [[0.0] * 5 for _ in range(5)]
        for j, h in enumerate(steps):
            loads = []
            for sign in (1.0, -1.0):
                u = [0.0, 0.0, s * delta, 0.0, 0.0]
                u[j] += sign * h
                loads.append(row_loads(rp, u, [0.0] * 5, g.ball_count, s).inner_load)
            for i in range(5):
                row[i][j] = -(float(loads[0][i]) - float(loads[1][i])) / (2.0 * h)
        for a in range(5):
            for b in range(5):
                total[a][b] += sum(lever[i][a] * row[i][j] * lever[j][b]
                                   for i in range(5) for j in range(5))
    return [total[k][k] for k in range(5)]


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


# --------------------------------------------------------------------------- scene spec
_RADIAL_INPUTS = ("shaft.Fx", "shaft.Fy", "shaft.Mx", "shaft.My")


def _duplex_from_scene(args: dict[str, Any], fidelity: str) -> DuplexPair:
    """Build the pair from the scene arguments of :data:`SCENE_SPEC` (defaults filled in;
    ``fidelity`` is unused: the pair has one level)."""
    keywords = {k: v for k, v in args.items()
                if v is not None and k not in ("bearing", "preload_force")}
    if args.get("preload_force") is not None:
        if args.get("preload") is not None:
            raise ParameterError(
                f"duplex_pair: give either preload ({args['preload']!r}, a class) or "
                f"preload_force ({args['preload_force']!r} N), not both")
        keywords["preload"] = float(args["preload_force"])
    return duplex_pair(args["bearing"], **keywords)


def _pure_axial(inputs: dict[str, Any]) -> bool:
    """Every radial force and moment input absent or the constant 0."""
    radial = [inputs.get(name, 0.0) for name in _RADIAL_INPUTS]
    return all(isinstance(v, (int, float)) and v == 0.0 for v in radial)


def _symmetry(args: dict[str, Any], inputs: dict[str, Any]) -> list[str]:
    if args.get("axisymmetric"):
        return ["pure axial load: one representative ball per row is solved (axisymmetric "
                "rows); the other balls equal it and the rows carry no radial load or moment"]
    return []


def _symmetric_args(args: dict[str, Any], inputs: dict[str, Any]) -> dict[str, Any]:
    return {"axisymmetric": True} if _pure_axial(inputs) else {}


SCENE_SPEC = AssemblySpec(
    name="duplex_pair",
    description="DF/DB/DT duplex pair of angular contact ball bearings on a rigid shaft "
                "(quasi-static ball rows); inputs shaft.Fx, Fy, Fz [N], Mx, My [N m]",
    build=_duplex_from_scene,
    args={
        "bearing": ArgSpec("bearing", factory_default(duplex_pair, "designation"),
                           "bearing of both rows"),
        "arrangement": ArgSpec("choice", factory_default(duplex_pair, "arrangement"),
                               "arrangement", choices=tuple(ARRANGEMENTS)),
        "preload": ArgSpec("choice", factory_default(duplex_pair, "preload"),
                           "preload class: catalogued, else a fraction of C (default: light)",
                           choices=PRELOAD_CLASSES),
        "preload_force": ArgSpec("float", None, "axial preload [N] instead of a class",
                                 low=0.0),
        "speed": ArgSpec("float", factory_default(duplex_pair, "speed"), "shaft speed [rad/s]",
                         low=-1e9),
        "speed_effects": ArgSpec("bool", factory_default(DuplexPair, "speed_effects"),
                                 "centrifugal and gyroscopic ball loads"),
        "damping_ratio": ArgSpec("float", factory_default(DuplexPair, "damping_ratio"),
                                 "damping ratio of the shaft against the housing [-], 0 to 1 "
                                 "(default: none, a load step rings for ever)"),
    },
    fidelities=("quasi-static",),
    auto_fidelities=("quasi-static",),
    output_fidelity=[],
    default_outputs=["shaft.x", "shaft.z", "shaft.ty"],
    symmetry=_symmetry,
    symmetric_args=_symmetric_args,
    # the preload (spacer width difference, DT spring force) and the speed (with speed effects
    # built in) are parameters of the assembled pair: a grid over them needs no re-assembly
    parametric_args={"preload": lambda args: True, "preload_force": lambda args: True,
                     "speed": lambda args: bool(args.get("speed_effects"))},
    fidelity_arg=None,
    optional_inputs=("shaft.*",),  # no external load (the preload alone)
)
"""The duplex pair as a scene assembly (:mod:`bearingsim.scenes`)."""
