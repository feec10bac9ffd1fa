"""The deep-groove ball bearing's options, validated once: fidelity levels, the constants its
levels share, and :class:`DeepGrooveOptions` (the dynamic levels' options) with its groups
:class:`RingOptions` (drive and ring support), :class:`FilmOptions` (race contacts, traction and
the lubricant around the balls) and :class:`CageOptions` (pocket and land contacts)."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from bearingsim.components.dynamic.ring import check_loads
from bearingsim.errors import ParameterError
from bearingsim.physics.lubricant import Lubricant
from bearingsim.validation import check_choice, check_flag, check_number, check_range

__all__ = ["FIDELITIES", "FILM_DAMPING", "CageOptions", "DeepGrooveOptions", "FilmOptions",
           "RingOptions"]

FIDELITIES = ("quasi-static", "dynamic", "dynamic_massive_balls")
"""Fidelity levels, lowest first."""
_W_REG = 1e-2  # rad/s, regularization of the slip ratio at standstill
FILM_DAMPING = 1e-5
"""Damping of a lubricated race contact over its tangent stiffness [s] (Kramer 1993: rolling
bearings damp 0.25e-5 .. 2.5e-5 times their stiffness; see
:class:`~bearingsim.components.dynamic.RaceContact`)."""
WHERE = "deep_groove_ball_bearing"
"""The name the option checks give in their messages."""


def _check_numbers(options: Any, units: dict[str, tuple[str, float | None]]) -> None:
    """Each named field that is not None: a real number in ``[0, high]`` [unit] (the components
    check them too, but before they are named; name them here)."""
    for key, (unit, high) in units.items():
        value = getattr(options, key)
        if value is not None:
            check_number(value, key, unit, high, WHERE)


@dataclass(frozen=True)
class RingOptions:
    """How the rings are driven and supported.

    Attributes
    ----------
    drive : {"speed", "flange"}
        ``"speed"``: a speed source turns the inner ring at the bearing's ``speed``;
        ``"flange"`` leaves ``shaft`` (with the ring's polar inertia) for the user to drive.
    outer_ring : {"fixed", "flange"}
        ``"flange"``: the outer ring may rotate (its translations stay fixed); its rotation is
        the connector ``outer_flange`` (a nested bearing's middle ring). The epicyclic cage
        speed and the slip then use both ring speeds.
    ring_inertia : bool
        With ``drive="flange"``: whether the inner ring's polar inertia belongs to this bearing
        (False when an enclosing assembly models the ring's rotation, e.g. a nested bearing's
        middle ring).
    inner_ring : {"body", "frame"}
        ``"body"``: the inner ring is a 5-DOF ``RingBody`` (``ring``) loaded by the bearing's
        ``loads`` (``load``); ``"frame"``: no ring body and no load, the inner race contacts'
        ring frame is the connector ``inner_frame`` for an enclosing body (a nested bearing's
        middle ring); the loads must then be constants and only set the start values (the load
        the enclosing body passes on).
    outer_support : {"housing", "frame"}
        ``"housing"``: the outer race is fixed (``housing``); ``"frame"``: the outer race
        contacts' ring frame is the connector ``outer_frame`` for an enclosing body that may
        translate (the outer race contacts then use its velocity).
    outer_start : sequence of 3 float
        With ``outer_support="frame"``: start displacement (x, y, z) of the outer race [m]; the
        inner ring and the balls start shifted by it. Stored as a tuple of floats.
    free_tilt : bool
        Whether the inner ring tilts under the moments ``Mx, My``. With False the shaft holds
        it straight and takes the moments as a reaction (the bearing's ``loads`` may then give
        ``Mx, My`` only as 0).

    Raises
    ------
    ParameterError
        For a choice outside the ones above, a flag that is not True or False, or an
        ``outer_start`` that is not three numbers (nonzero only with ``outer_support="frame"``).
    """

    drive: str = "speed"
    outer_ring: str = "fixed"
    ring_inertia: bool = True
    inner_ring: str = "body"
    outer_support: str = "housing"
    outer_start: tuple[float, float, float] = (0.0, 0.0, 0.0)
    free_tilt: bool = False

    def __post_init__(self) -> None:
        check_choice(self.drive, "drive", ("speed", "flange"), WHERE)
        check_choice(self.outer_ring, "outer_ring", ("fixed", "flange"), WHERE)
        check_choice(self.inner_ring, "inner_ring", ("body", "frame"), WHERE)
        check_choice(self.outer_support, "outer_support", ("housing", "frame"), WHERE)
        try:
            offset = tuple(float(v) for v in self.outer_start)
        except (TypeError, ValueError):
            offset = ()
        if len(offset) != 3 or (self.outer_support == "housing" and any(offset)):
            raise ParameterError(f"{WHERE}: outer_start must be (x, y, z) [m], nonzero only "
                                 f"with outer_support='frame', got {self.outer_start!r}")
        object.__setattr__(self, "outer_start", offset)
        check_flag(self.ring_inertia, "ring_inertia", WHERE)
        check_flag(self.free_tilt, "free_tilt", WHERE)


@dataclass(frozen=True)
class FilmOptions:
    """The race contacts (damping, traction) and the lubricant around the balls.

    Attributes
    ----------
    damping : float
        Hunt-Crossley coefficient of the race contacts [s/m], >= 0.
    film_damping : float, optional
        Film damping time constant of the race contacts [s], >= 0 (damping = ``film_damping``
        times the tangent contact stiffness, see
        :class:`~bearingsim.components.dynamic.RaceContact`); default :data:`FILM_DAMPING`
        with a viscous lubricant, 0 dry. A value given with a ``Dry`` lubricant is applied
        (as stiffness-proportional contact damping).
    n_slices : int
        ``2 n + 1`` traction slices per contact, an integer >= 0 (checked by the race
        contact).
    traction_scale : float
        Multiplier of the race traction [-], >= 0 (0: frictionless races).
    drag : bool, optional
        Ball drag in the oil-air mixture; default: on with a viscous lubricant, off with
        ``Dry``. ``drag=True`` with a ``Dry`` lubricant raises
        :class:`~bearingsim.errors.ParameterError`.
    oil_fraction : float
        Oil volume fraction of the cavity mixture [-] (drag), in (0, 1].
    rolling_resistance : bool
        EHL hydrodynamic rolling resistance at every race contact (viscous lubricants only;
        see :class:`~bearingsim.components.dynamic.RaceContact`).
    ring_drag : bool
        A :class:`~bearingsim.components.dynamic.RingDrag` between the inner and outer ring
        rotations: the load-independent Palmgren ``M0`` less the viscous losses resolved at
        ball level (rolling resistance, ball drag, cage pockets and land), so that the
        bearing's viscous loss equals the torque level's (viscous lubricants only).

    Raises
    ------
    ParameterError
        For a number outside its range (naming it, its unit and range) or a flag that is not
        True or False.
    """

    damping: float = 1.0
    film_damping: float | None = None
    n_slices: int = 2
    traction_scale: float = 1.0
    drag: bool | None = None
    oil_fraction: float = 0.05
    rolling_resistance: bool = False
    ring_drag: bool = False

    def __post_init__(self) -> None:
        check_range(self.oil_fraction, "oil_fraction", "-", 0.0, 1.0, low_inclusive=False,
                    where=WHERE)
        _check_numbers(self, {"damping": ("s/m", None), "film_damping": ("s", None),
                              "traction_scale": ("1", None)})
        check_flag(self.drag, "drag", WHERE, allow_none=True)
        check_flag(self.rolling_resistance, "rolling_resistance", WHERE)
        check_flag(self.ring_drag, "ring_drag", WHERE)

    def for_lubricant(self, lubricant: Lubricant) -> FilmOptions:
        """These options with the lubricant's defaults filled in (``film_damping``, ``drag``).

        Parameters
        ----------
        lubricant : Lubricant
            The bearing's lubricant.

        Returns
        -------
        FilmOptions

        Raises
        ------
        ParameterError
            For ``rolling_resistance``, ``ring_drag`` or ``drag=True`` without a viscous
            lubricant.
        """
        viscous = lubricant.is_viscous
        if (self.rolling_resistance or self.ring_drag) and not viscous:
            raise ParameterError(f"{WHERE}: rolling_resistance and ring_drag need a viscous "
                                 f"lubricant, got {lubricant.describe()}")
        if self.drag and not viscous:
            raise ParameterError(f"{WHERE}: drag=True needs a viscous lubricant (the ball drag "
                                 f"is that of an oil-air mixture), got {lubricant.describe()}; "
                                 f"leave drag out or give drag=False")
        film_damping = (FILM_DAMPING if viscous else 0.0) if self.film_damping is None \
            else self.film_damping
        return dataclasses.replace(self, film_damping=film_damping,
                                   drag=viscous if self.drag is None else bool(self.drag))


@dataclass(frozen=True)
class CageOptions:
    """The cage's pocket and land contacts.

    Attributes
    ----------
    pocket_mu, land_mu : float, optional
        Coulomb coefficients of pocket and land contacts [-], in [0, 2]; default the ``mu``
        of a ``Dry`` lubricant, else 0.1 (the lubricant's ``contact_friction``).
    cage_damping : float
        Hunt-Crossley coefficient of the pocket and land contacts [s/m], >= 0.

    Raises
    ------
    ParameterError
        For a number outside its range, naming it, its unit and range.
    """

    pocket_mu: float | None = None
    land_mu: float | None = None
    cage_damping: float = 10.0

    def __post_init__(self) -> None:
        _check_numbers(self, {"pocket_mu": ("1", 2.0), "land_mu": ("1", 2.0),
                              "cage_damping": ("s/m", None)})

    def for_lubricant(self, lubricant: Lubricant) -> CageOptions:
        """These options with the lubricant's friction coefficient for the ones not given.

        Parameters
        ----------
        lubricant : Lubricant
            The bearing's lubricant.

        Returns
        -------
        CageOptions
        """
        mu = lubricant.contact_friction
        return dataclasses.replace(self, pocket_mu=mu if self.pocket_mu is None
                                   else self.pocket_mu,
                                   land_mu=mu if self.land_mu is None else self.land_mu)


_GROUPS = {"rings": RingOptions, "film": FilmOptions, "cage": CageOptions}
"""The option groups of :class:`DeepGrooveOptions`, by field name."""


@dataclass(frozen=True)
class DeepGrooveOptions:
    """The options of the dynamic levels (:class:`~bearingsim.assemblies.deep_groove.
    DeepGrooveBallBearing`), checked at construction.

    Attributes
    ----------
    massive_balls : bool
        Ball radial/axial motion with inertia (True) or quasi-static (False).
    speed : callable or float or None
        Inner-ring speed [rad/s] imposed through a speed source (``None``: an input
        ``shaft_speed``); ignored with ``rings.drive="flange"``. A constant is checked
        against the bearing's limiting speed when the bearing is built.
    loads : dict
        ``Fx, Fy, Fz`` [N], ``Mx, My`` [N m] on the inner ring: finite constants, functions of
        time or ``None`` for inputs (missing keys are inputs with default 0); any other key
        raises :class:`~bearingsim.errors.ParameterError`. With ``rings.free_tilt=False``
        ``Mx, My`` may only be 0 (missing ones are 0, not inputs that would have no effect);
        with ``rings.inner_ring="frame"`` every load must be a constant.
    rings : RingOptions
    film : FilmOptions
    cage : CageOptions

    Raises
    ------
    ParameterError
        For a load outside the ones above, a group of the wrong type, or (from the groups) a
        choice, flag or number outside its range, naming ``deep_groove_ball_bearing``, the
        option, its unit and valid range.

    Examples
    --------
    >>> from bearingsim.assemblies.deep_groove import DeepGrooveOptions, FilmOptions
    >>> options = DeepGrooveOptions(loads={"Fz": 100.0}, film=FilmOptions(n_slices=1))
    >>> options.rings.drive, options.film.n_slices
    ('speed', 1)
    >>> DeepGrooveOptions.from_keywords(loads={"Fz": 100.0}, n_slices=1) == options
    True
    """

    massive_balls: bool = False
    speed: Callable | float | None = None
    loads: dict[str, Any] = field(default_factory=dict)
    rings: RingOptions = field(default_factory=RingOptions)
    film: FilmOptions = field(default_factory=FilmOptions)
    cage: CageOptions = field(default_factory=CageOptions)

    def __post_init__(self) -> None:
        for name, group in _GROUPS.items():
            if not isinstance(getattr(self, name), group):
                raise ParameterError(f"{WHERE}: {name} must be a {group.__name__}, got "
                                     f"{type(getattr(self, name)).__name__}")
        check_flag(self.massive_balls, "massive_balls", WHERE)
        loads = check_loads(self.loads, WHERE)
        if not self.rings.free_tilt:
            for key in ("Mx", "My"):
                if key in loads and loads[key] != 0.0:
                    raise ParameterError(
                        f"{WHERE}: loads[{key!r}] = {loads[key]!r} [N.m] is not applied with "
                        f"free_tilt=False: the shaft holds the inner ring straight and takes "
                        f"the moments as a reaction; give free_tilt=True to tilt the ring, or "
                        f"{key} = 0 (or leave it out)")
        if self.rings.inner_ring == "frame" and len(self.constant_loads(loads)) != len(loads):
            raise ParameterError(f"{WHERE}: with inner_ring='frame' the loads only set the "
                                 f"start values and must be constants")
        object.__setattr__(self, "loads", loads)

    @staticmethod
    def constant_loads(loads: dict[str, Any]) -> dict[str, float]:
        """The loads given as constants (the ones that set the start values).

        Parameters
        ----------
        loads : dict
            Load name (``Fx``, ``Fy``, ``Fz``) -> constant [N], function of time or None.

        Returns
        -------
        dict of str to float
            The constant loads [N] by name.
        """
        return {k: v for k, v in loads.items() if isinstance(v, (int, float))}

    @classmethod
    def keyword_names(cls) -> tuple[str, ...]:
        """The flat keywords of :meth:`from_keywords` that go into a group, group by group.

        Returns
        -------
        tuple of str
        """
        return tuple(f.name for group in _GROUPS.values() for f in dataclasses.fields(group))

    @classmethod
    def from_keywords(cls, massive_balls: bool = False, speed: Callable | float | None = None,
                      loads: dict[str, Any] | None = None, **options: Any) -> DeepGrooveOptions:
        """The options from flat keywords (the factory's and scenes' form).

        Parameters
        ----------
        massive_balls, speed, loads
            As the attributes.
        **options
            The fields of the groups by name (:meth:`keyword_names`: ``drive``, ``damping``,
            ``n_slices``, ``pocket_mu``, ...).

        Returns
        -------
        DeepGrooveOptions

        Raises
        ------
        ParameterError
            For a keyword that is no field of a group, listing the accepted ones, and the
            checks of the groups and of this class.
        """
        unknown = sorted(set(options) - set(cls.keyword_names()))
        if unknown:
            raise ParameterError(f"{WHERE}: unknown option(s) {', '.join(map(repr, unknown))}; "
                                 f"accepted: {', '.join(cls.keyword_names())}")
        groups = {name: group(**{f.name: options[f.name] for f in dataclasses.fields(group)
                                 if f.name in options})
                  for name, group in _GROUPS.items()}
        return cls(massive_balls, speed, {} if loads is None else loads, **groups)
