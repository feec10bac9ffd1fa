"""The double-layer bearing's options, validated once: fidelity levels, friction models, the layer
options each level takes, and the option objects of the levels, :class:`DoubleLayerOptions`
(kinematic and torque levels) and :class:`DynamicDoubleLayerOptions` (ball and cage dynamics),
which share the layer pair and its drive (:class:`LayerPairOptions`)."""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from bearingsim.assemblies.deep_groove.options import DeepGrooveOptions
from bearingsim.assemblies.double_layer.speed import _check_shaft_speed
from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.checks import check_arguments
from bearingsim.components.bearing_torque import PalmgrenBearing, SkfBearing
from bearingsim.components.middle_ring import middle_ring_structure, mounted_geometries
from bearingsim.errors import ParameterError
from bearingsim.physics.drag import couette_damping
from bearingsim.physics.friction import skf_friction_components
from bearingsim.physics.lubricant import Lubricant, as_lubricant
from bearingsim.physics.lubrication import LUBRICATION_METHODS
from bearingsim.validation import (
    check_choice,
    check_flag,
    check_mapping,
    check_options,
    check_quantity,
    check_range,
    keyword_names,
)

__all__ = ["FIDELITIES", "FRICTION_MODELS", "KINEMATIC_OPTIONS", "DoubleLayerOptions",
           "DynamicDoubleLayerOptions", "LayerPairOptions", "layer_option_names"]

WHERE = "double_layer_bearing"
"""The name the option checks give in their messages."""
FIDELITIES = ("kinematic_approx", "kinematic", "torque", "quasi-static", "dynamic")
"""Fidelity levels; the first three (lowest first) are built by :class:`DoubleLayerBearing`."""
KINEMATIC_OPTIONS = ("k",)
"""``layer_options`` of the kinematic levels (the drag coefficient of PureRollingLayer)."""

FRICTION_MODELS = ("palmgren", "skf")
_LAYER_SETS = ("bearing", "lubricant", "name")
"""Arguments of the torque-level layer elements that :class:`DoubleLayerBearing` sets."""
_SKF_SETS = ("omega_rel", "dm", "lubricant", "series", "Fr", "Fa", "C0", "d", "D",
             "omega_reg")
"""Arguments of ``skf_friction_components`` that :class:`SkfBearing` sets itself."""
_DYNAMIC_SETS = ("drive", "outer_ring", "ring_inertia", "speed", "loads", "drag",
                 "massive_balls", "inner_ring", "outer_support", "outer_start",
                 "rolling_resistance", "ring_drag")
"""Options of the layers' :class:`~bearingsim.assemblies.deep_groove.DeepGrooveBallBearing`
that the dynamic level sets."""
_DEFAULT_LUBRICATION = ("ISO VG 32", "ISO VG 32")


def layer_option_names(friction_model: str) -> tuple[str, ...]:
    """The ``layer_options`` a torque-level layer accepts (from the constructor signatures).

    Parameters
    ----------
    friction_model : {"palmgren", "skf"}
        Friction torque model.

    Returns
    -------
    tuple of str
        Keyword arguments of :class:`~bearingsim.components.bearing_torque.PalmgrenBearing`,
        or of :class:`~bearingsim.components.bearing_torque.SkfBearing` with the options it
        passes on to :func:`~bearingsim.physics.friction.skf_friction_components`.
    """
    if friction_model == "palmgren":
        return keyword_names(PalmgrenBearing, _LAYER_SETS)
    return keyword_names(SkfBearing, _LAYER_SETS) + keyword_names(skf_friction_components,
                                                                  _SKF_SETS)


_POSITIVE_OPTIONS = {"k": "N.s/m", "omega_reg": "rad/s"}
"""Numeric layer options (> 0), checked here so that the message names them."""


def _pair(lubrication) -> tuple[Any, Any]:
    if isinstance(lubrication, (tuple, list)):
        if len(lubrication) != 2:
            raise ParameterError(f"{WHERE}: lubrication must be one lubricant or an (inner, "
                                 f"outer) pair, got {len(lubrication)} items")
        return lubrication[0], lubrication[1]
    return lubrication, lubrication


@dataclass(frozen=True, kw_only=True)
class LayerPairOptions:
    """The two layers, their lubricants and the shaft's drive (every level with friction or
    dynamics); checked at construction. The base of the levels' options.

    Attributes
    ----------
    inner, outer : str or BearingGeometry
        Inner (shaft side) and outer (housing side) deep-groove bearing; resolved to
        ``geometries``.
    structure : {"I", "Z"} or None
        Middle ring type; None chooses "I" when the inner bearing fits in the outer bearing's
        bore (``D1 <= d2``), else "Z". Resolved (never None after construction).
    lubrication : lubricant or (lubricant, lubricant)
        Lubricant of both layers, or of the (inner, outer) layer; names or objects; resolved
        to ``lubricants``.
    drive : {"speed", "flange"}
        ``"speed"``: an internal speed source drives the shaft at ``speed`` (an input
        ``shaft_speed`` [rad/s] when ``speed`` is None); ``"flange"``: the shaft flange is left
        for a motor.
    speed : callable or float or None
        Shaft speed [rad/s] for ``drive="speed"``; a constant at most the sum of both layers'
        limiting speeds (:func:`~bearingsim.assemblies.double_layer.shaft_speed_limit`).
    geometries : (BearingGeometry, BearingGeometry)
        Derived: (inner, outer).
    lubricants : (Lubricant, Lubricant)
        Derived: (inner, outer).

    Raises
    ------
    ParameterError
        For a structure or drive outside the ones above, a lubrication that is not one
        lubricant or a pair, or a constant speed above the limit;
        :class:`~bearingsim.errors.CatalogError` for an unknown bearing or lubricant.
    """

    inner: str | BearingGeometry = "61905"
    outer: str | BearingGeometry = "61907"
    structure: str | None = None
    lubrication: Any = _DEFAULT_LUBRICATION
    drive: str = "speed"
    speed: Callable | float | None = None
    geometries: tuple[BearingGeometry, BearingGeometry] = field(init=False, repr=False,
                                                               compare=False)
    lubricants: tuple[Lubricant, Lubricant] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        # the levels' options run these steps in their own order, with their own checks
        self._resolve_geometries()
        self._resolve_structure()
        self._check_drive()
        self._resolve_lubricants()
        self._check_speed()

    def _resolve_geometries(self) -> None:
        self._set(geometries=(resolve_bearing(self.inner), resolve_bearing(self.outer)))

    def _resolve_structure(self) -> None:
        self._set(structure=middle_ring_structure(*self.geometries, self.structure))

    def _check_drive(self) -> None:
        check_choice(self.drive, "drive", ("speed", "flange"), WHERE)

    def _resolve_lubricants(self) -> None:
        self._set(lubricants=tuple(as_lubricant(x, WHERE) for x in _pair(self.lubrication)))

    def _check_speed(self) -> None:
        if self.drive == "speed" and self.speed is not None:
            if not callable(self.speed):  # "10000 rpm" -> rad/s, then against the limit
                self._set(speed=float(check_quantity(self.speed, "speed", "rad/s", where=WHERE)))
            _check_shaft_speed(self.speed, *self.geometries)

    def _set(self, **values: Any) -> None:
        for key, value in values.items():
            object.__setattr__(self, key, value)


@dataclass(frozen=True, kw_only=True)
class DoubleLayerOptions(LayerPairOptions):
    """The options of the kinematic and torque levels (:class:`~bearingsim.assemblies.
    double_layer.DoubleLayerBearing`), checked at construction.

    Attributes
    ----------
    inner, outer, structure, lubrication, drive, speed
        See :class:`LayerPairOptions`. ``lubrication`` is used at the torque level only: the
        kinematic levels have no friction and ignore it (it is still checked, so an unknown
        name raises :class:`~bearingsim.errors.CatalogError`); it is not an error there
        because a scene with ``fidelity = "auto"`` passes its lubricant to whichever level it
        picks.
    fidelity : {"kinematic", "kinematic_approx", "torque"}
        Pure rolling (exact with contact angles, or the ``Dp1/(Dp1+Dp2)`` approximation) or
        friction torque models.
    friction_model : {"palmgren", "skf"}
        Friction torque model of the torque level; checked but ignored at the kinematic levels
        (as ``lubrication``).
    lubrication_method : str or (str, str), optional
        Lubrication method of both layers or of the (inner, outer) layer, one of
        :data:`~bearingsim.physics.lubrication.LUBRICATION_METHODS` (default: each lubricant's
        own, ``oil_bath`` for the named oils, ``grease`` for the greases). It sets Palmgren's
        f0 and the SKF starvation constant of each layer (``lubricants`` carry it).
    oil_level : float, optional
        Oil bath level [m], >= 0, above the lowest point of the outer layer's pitch circle (the
        centre of its lowest ball), used by ``friction_model="skf"`` at the torque level (an
        error with Palmgren's model; checked but ignored at the kinematic levels). Each layer
        sees it from its own lowest ball: the inner layer's level is
        ``oil_level - (dm2 - dm1) / 2``. A layer whose level is >= 0 gets the drag of its
        immersed balls and no starvation factor; a layer above the oil (negative level) is a
        low-level bath (starvation factor, no drag; SKF "Rolling bearings" 10000/3, 2017,
        p. 102). Only layers lubricated by ``oil_bath`` take it.
    middle_ring_drag : dict, optional
        The middle ring's own viscous drag in the oil of the outer layer, at the torque level:
        a cylinder of ``radius`` [m] turning in a fixed bore ``gap`` [m] wider, over ``length``
        [m], on the ``wetted`` fraction of its circumference (default 1). The exact laminar
        Couette torque (:func:`~bearingsim.physics.drag.couette_damping`, a linear damper
        between the middle ring and the housing); the variable ``middle_Ta`` is the gap's
        Taylor number, which must stay below
        :data:`~bearingsim.physics.drag.TAYLOR_ONSET` (41.3) for the laminar torque to hold.
    layer_options : dict, optional
        Extra keyword arguments of the layer elements: at the torque level those of
        :class:`~bearingsim.components.bearing_torque.PalmgrenBearing` or
        :class:`~bearingsim.components.bearing_torque.SkfBearing` (e.g. ``smooth``,
        ``load_dependent``; SKF: ``series``, ``omega_reg`` and the options of
        :func:`~bearingsim.physics.friction.skf_friction_components` such as ``seal``,
        ``oil_level``; see :func:`layer_option_names`); at the kinematic levels only ``k``, the
        drag coefficient of :class:`~bearingsim.components.bearing_torque.PureRollingLayer`
        [N s/m]. Others raise :class:`~bearingsim.errors.ParameterError` naming the accepted
        ones.
    layer_options_each : (dict, dict)
        Derived: each layer's ``layer_options`` with its own oil level.
    gap : tuple of float or None
        Derived at the torque level with ``middle_ring_drag``: (radius, gap, length, wetted
        [m, m, m, -], eta [Pa s], nu [m^2/s]) of the middle ring's oil gap.

    Raises
    ------
    ParameterError
        For a fidelity, structure, drive, friction model, lubrication method, oil level,
        middle-ring gap, layer option or constant speed outside the ones above (naming
        ``double_layer_bearing``, the option, its unit and range).

    Examples
    --------
    >>> from bearingsim.assemblies.double_layer import DoubleLayerOptions
    >>> options = DoubleLayerOptions(friction_model="skf", layer_options={"seal": "none"})
    >>> options.structure, [g.designation for g in options.geometries]
    ('Z', ['61905', '61907'])
    """

    fidelity: str = "torque"
    friction_model: str = "palmgren"
    lubrication_method: str | tuple[str, str] | None = None
    oil_level: float | None = None
    middle_ring_drag: dict | None = None
    layer_options: dict | None = None
    layer_options_each: tuple[dict, dict] = field(init=False, repr=False, compare=False)
    gap: tuple[float, ...] | None = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        self._resolve_geometries()
        if self.fidelity not in FIDELITIES[:3]:
            raise ParameterError(
                f"{WHERE}: fidelity must be one of {', '.join(FIDELITIES)}, got "
                f"{self.fidelity!r} (the quasi-static and dynamic levels are built by "
                f"double_layer_bearing)"
            )
        self._resolve_structure()
        self._check_drive()
        check_choice(self.friction_model, "friction_model", FRICTION_MODELS, WHERE)
        self._resolve_lubricants()
        if self.lubrication_method is not None:
            self._set(lubricants=tuple(_with_method(lub, m) for lub, m in zip(
                self.lubricants, _pair(self.lubrication_method), strict=True)))
        opts = check_mapping(self.layer_options, "layer_options", WHERE, "option names")
        each = _bath_options(*self.geometries, self.lubricants, self.oil_level, self.friction_model,
                             self.fidelity, opts)
        for options in each:
            _check_layer_options(self.fidelity, self.friction_model, options)
        self._set(layer_options_each=each)
        self._check_speed()
        self._set(gap=_middle_ring_gap(self.middle_ring_drag, self.lubricants[1])
                  if self.middle_ring_drag is not None and self.fidelity == "torque" else None)


@dataclass(frozen=True, kw_only=True)
class DynamicDoubleLayerOptions(LayerPairOptions):
    """The options of the dynamic level (:class:`~bearingsim.assemblies.double_layer.
    DynamicDoubleLayerBearing`), checked at construction.

    Attributes
    ----------
    inner, outer, structure, lubrication, drive, speed
        See :class:`LayerPairOptions`; the lubricants must be viscous (oil or grease).
        ``drive="flange"`` leaves ``shaft`` with the inner ring's polar inertia for a motor.
    loads : dict, optional
        Loads on the shaft (the inner layer's inner ring), ``Fx, Fy, Fz`` [N], ``Mx, My`` [N m]
        (z is the axis); constants, functions of time or None, missing keys are inputs
        (``inner_layer.load.Fx``, ...). The constant ones set the start values. The shaft is
        held straight, so ``Mx, My`` may only be 0 (anything else raises
        :class:`~bearingsim.errors.ParameterError`; the missing ones stay inputs, without
        effect).
    massive_balls : bool
        Balls' radial and axial motion with inertia (True, the fast ODE level) or quasi-static.
    rolling_resistance, ring_drag : bool
        The EHL rolling resistance at every race contact and the ring drag between each
        layer's rings (with both, each layer's viscous loss is the torque level's M0 and the
        ratio follows its lubricant dependence).
    w_middle0 : float
        Initial middle ring speed [rad/s].
    fits : bool
        Mount both layers with the study's fits (k6 shaft seats, H7 bores): each layer's
        clearance becomes its operating clearance
        (:func:`~bearingsim.components.middle_ring.mounted_geometries`, then in
        ``geometries``); default False, the clearance before mounting (catalogue rows: the CN
        mean).
    layer_options : dict, optional
        Further options of both layers (``n_slices``, ``damping``, ...): the fields of
        :class:`~bearingsim.assemblies.deep_groove.DeepGrooveOptions`' groups that this level
        does not set; others raise :class:`~bearingsim.errors.ParameterError`.
    layer : DeepGrooveOptions
        Derived: the options both layers share (``layer_options`` and the ones this level
        sets: massive balls as given, no ball drag, a flange drive); each layer adds its loads
        and ring support.

    Raises
    ------
    ParameterError
        For a structure, drive, lubricant, load, layer option or constant speed outside the
        ones above.
    """

    loads: dict[str, Any] | None = None
    massive_balls: bool = True
    rolling_resistance: bool = True
    ring_drag: bool = True
    w_middle0: float = 0.0
    fits: bool = False
    layer_options: dict | None = None
    layer: DeepGrooveOptions = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        self._resolve_geometries()
        self._resolve_structure()
        check_flag(self.fits, "fits", WHERE)
        if self.fits:
            self._set(geometries=mounted_geometries(*self.geometries, self.structure))
        self._check_drive()
        self._resolve_lubricants()
        for lub in self.lubricants:
            if not lub.is_viscous:
                raise ParameterError(f"{WHERE}: the dynamic level needs viscous lubricants "
                                     f"(oil or grease), got {lub.describe()}")
        opts = _dynamic_layer_options(self.layer_options)
        loads = check_mapping(self.loads, "loads", WHERE, "load names")
        if not opts.get("free_tilt", False):
            for key in ("Mx", "My"):
                if key in loads and loads[key] != 0.0:
                    raise ParameterError(
                        f"{WHERE}: loads[{key!r}] = {loads[key]!r} [N.m] is not applied: the "
                        f"shaft and the middle ring are held straight (free_tilt=False) and "
                        f"the moments are reactions; give {key} = 0 or leave it out")
        self._set(loads=loads, layer=DeepGrooveOptions.from_keywords(
            massive_balls=self.massive_balls, drag=False,
            rolling_resistance=self.rolling_resistance, ring_drag=self.ring_drag,
            drive="flange", **opts))
        self._check_speed()

    def for_layer(self, loads: dict[str, Any], **rings: Any) -> DeepGrooveOptions:
        """A layer's options: the shared ``layer`` with the layer's loads and ring support.

        Parameters
        ----------
        loads : dict
            The layer's loads (see :class:`~bearingsim.assemblies.deep_groove.
            DeepGrooveOptions`).
        **rings
            Fields of the layer's :class:`~bearingsim.assemblies.deep_groove.RingOptions`.

        Returns
        -------
        DeepGrooveOptions
        """
        return dataclasses.replace(self.layer, loads=loads,
                                   rings=dataclasses.replace(self.layer.rings, **rings))


def _dynamic_layer_options(layer_options: Any) -> dict[str, Any]:
    """The dynamic level's ``layer_options``, checked by name (their values are the layers')."""
    opts = check_mapping(layer_options, "layer_options", WHERE, "option names")
    for key in _DYNAMIC_SETS:
        if key in opts:
            raise ParameterError(f"{WHERE}: layer_options may not set {key!r} (the nested "
                                 f"assembly sets it)")
    if "oil_fraction" in opts:
        raise ParameterError(f"{WHERE}: layer_options 'oil_fraction' is not used: the dynamic "
                             f"level has no ball drag (drag=False)")
    accepted = tuple(n for n in DeepGrooveOptions.keyword_names()
                     if n not in _DYNAMIC_SETS + ("oil_fraction",))
    check_options(opts, accepted, WHERE, "layer_options", "at the dynamic level")
    return opts


def _check_layer_options(fidelity: str, friction_model: str, options: dict) -> None:
    """A layer's ``layer_options`` at the kinematic or torque level: names and values."""
    for key, unit in _POSITIVE_OPTIONS.items():
        if key in options:
            check_range(options[key], f"layer_options[{key!r}]", unit, 0.0, None,
                        low_inclusive=False, where=WHERE)
    if fidelity in ("kinematic", "kinematic_approx"):
        unused = sorted(set(options) - set(KINEMATIC_OPTIONS))
        if unused:
            raise ParameterError(
                f"{WHERE}: layer_options {', '.join(map(repr, unused))} not used at "
                f"fidelity {fidelity!r}; its only option is 'k' (pure-rolling drag coefficient "
                f"[N s/m], > 0)"
            )
        return
    check_options(options, layer_option_names(friction_model), WHERE,
                  "layer_options", f"of the {friction_model!r} friction model (torque level)")
    layer = PalmgrenBearing if friction_model == "palmgren" else SkfBearing
    check_arguments(layer, (), {k: v for k, v in options.items()
                                if k in keyword_names(layer)},
                    WHERE, "layer_options[{name!r}]")


def _with_method(lubricant: Lubricant, method: str) -> Lubricant:
    """A copy of ``lubricant`` lubricating by ``method``."""
    check_choice(method, "lubrication_method", LUBRICATION_METHODS, WHERE)
    if not lubricant.is_viscous:
        raise ParameterError(f"{WHERE}: lubrication_method {method!r} needs an oil or grease, "
                             f"got {lubricant.describe()}")
    changed = copy.copy(lubricant)
    changed.method = method
    return changed


def _bath_options(gi, go, lubricants, oil_level, friction_model: str, fidelity: str,
                  options: dict) -> tuple[dict, dict]:
    """Each layer's layer options with its own oil level (see :class:`DoubleLayerOptions`)."""
    if oil_level is None:
        return options, options
    oil_level = float(check_quantity(oil_level, "oil_level", "m", 0.0, None, where=WHERE))
    if fidelity != "torque":  # checked, but the kinematic levels have no friction (as lubrication)
        return options, options
    if friction_model != "skf":
        raise ParameterError(f"{WHERE}: oil_level is used by friction_model='skf' at the torque "
                             f"level (the drag of the immersed balls, the starvation factor); "
                             f"Palmgren's f0 has no published oil-level dependence here")
    if "oil_level" in options:
        raise ParameterError(f"{WHERE}: give the oil level once, as oil_level (each layer sees "
                             f"it from its own lowest ball), not in layer_options")
    levels = (oil_level - 0.5 * (go.pitch_diameter - gi.pitch_diameter), oil_level)
    per_layer = []
    for g, lub, level in zip((gi, go), lubricants, levels, strict=True):
        layer = dict(options)
        if lub.method == "oil_bath" and level >= 0.0:
            layer.update(oil_level=level, Dw=g.ball_diameter, Z=g.ball_count)
        per_layer.append(layer)
    return per_layer[0], per_layer[1]


def _middle_ring_gap(options: Any, lubricant: Lubricant) -> tuple[float, ...]:
    """(radius, gap, length, wetted, eta, nu) of the middle ring's oil gap, checked."""
    opts = check_mapping(options, "middle_ring_drag", WHERE, "keys")
    check_options(opts, ("radius", "gap", "length", "wetted"), WHERE, "middle_ring_drag keys")
    missing = [k for k in ("radius", "gap", "length") if k not in opts]
    if missing:
        raise ParameterError(f"{WHERE}: middle_ring_drag needs {', '.join(missing)} [m] (the "
                             f"turning cylinder's radius, the oil gap and the wetted length)")
    if not lubricant.is_viscous:
        raise ParameterError(f"{WHERE}: middle_ring_drag needs an oil or grease in the outer "
                             f"layer, got {lubricant.describe()}")
    eta, nu = float(lubricant.dynamic_viscosity()), float(lubricant.kinematic_viscosity())
    wetted = opts.get("wetted", 1.0)
    radius, gap, length = (float(check_quantity(opts[k], f"middle_ring_drag[{k!r}]", "m",
                                                where=WHERE)) for k in ("radius", "gap", "length"))
    couette_damping(radius, gap, length, eta, wetted)  # checks them
    return radius, gap, length, float(wetted), eta, nu

