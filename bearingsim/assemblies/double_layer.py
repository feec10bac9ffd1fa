"""Double-layer (nested) ball bearings, I-type and Z-type (docs/studies.md, section A).

Two deep-groove ball bearings are nested: the inner bearing's outer ring, an intermediate sleeve
and the outer bearing's inner ring form the *middle ring*, three bodies joined rigidly by
connections (the assembler's alias elimination and index reduction merge them). The shaft drives
the inner bearing's inner ring; the outer bearing's outer ring sits in the housing. Friction
drags the middle ring to a speed ``n_z``; the speed distribution ratio is ``Rs = n_z / n_i``.

Fidelity levels: pure rolling (``kinematic``), friction torque (``torque``, Palmgren or SKF),
load sharing (``quasi-static``, :mod:`bearingsim.assemblies.nested_static`) and ball and cage
dynamics of both layers (``dynamic``, :class:`DynamicDoubleLayerBearing`).
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any

from bearingsim.assemblies.deep_groove import DeepGrooveBallBearing
from bearingsim.assemblies.spec import (
    ArgSpec,
    AssemblySpec,
    PostQuantity,
    declared_errors,
    factory_default,
)
from bearingsim.catalog import resolve_bearing
from bearingsim.catalog.geometry import check_speed_limit, speed_input_bounds
from bearingsim.checks import check_arguments
from bearingsim.components.bearing_torque import (
    PalmgrenBearing,
    PureRollingLayer,
    SkfBearing,
)
from bearingsim.components.connectors import Flange
from bearingsim.components.dynamic import RingBody
from bearingsim.components.middle_ring import (
    STRUCTURES,
    MiddleRing,
    middle_ring_bodies,
    middle_ring_structure,
    mounted_geometries,
)
from bearingsim.components.rotational import Damper, Fixed, SpeedSource
from bearingsim.errors import ParameterError
from bearingsim.language import Assembly, Input, Variable, connect, der
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.physics.drag import TAYLOR_ONSET, couette_damping, taylor_number
from bearingsim.physics.friction import skf_friction_components
from bearingsim.physics.life import basic_rating_life_hours
from bearingsim.physics.lubricant import as_lubricant
from bearingsim.physics.lubrication import LUBRICATION_METHODS
from bearingsim.validation import (
    check_choice,
    check_flag,
    check_mapping,
    check_options,
    check_range,
    keyword_names,
)

__all__ = [
    "DoubleLayerBearing",
    "DynamicDoubleLayerBearing",
    "double_layer_bearing",
    "double_layer_from_scene",
    "FIDELITIES",
    "RS_REGULARIZATION",
    "SCENE_SPEC",
    "speed_ratio",
    "shaft_speed_limit",
]

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

RS_REGULARIZATION = 1e-6
"""Shaft speed [rad/s] below which the speed ratio Rs is regularized (:func:`speed_ratio`)."""


LIMIT_TEXT = ("the sum of the limiting speeds of {} and {} (the highest shaft speed at which "
               "both layers can run within their limits)")


def shaft_speed_limit(gi, go) -> float | None:
    """The limiting shaft speed of a double-layer bearing [rad/s]: the inner layer runs at
    ``w_shaft (1 - Rs)`` and the outer at ``w_shaft Rs``, so both are within their catalogue
    limiting speeds ``n_i``, ``n_o`` at best (``Rs = n_o / (n_i + n_o)``) up to
    ``w_shaft = n_i + n_o``; None when a layer has no limiting speed.

    Parameters
    ----------
    gi, go : BearingGeometry
        Inner and outer layer.

    Returns
    -------
    float or None
    """
    if gi.limiting_speed is None or go.limiting_speed is None:
        return None
    return gi.limiting_speed + go.limiting_speed


def _check_shaft_speed(speed, gi, go) -> None:
    """A constant shaft speed [rad/s] against :func:`shaft_speed_limit` (a function of time is
    not checked here)."""
    if isinstance(speed, (int, float)):
        check_speed_limit(speed, shaft_speed_limit(gi, go), "double_layer_bearing",
                          LIMIT_TEXT.format(gi.designation, go.designation))


def _shaft_speed_input(gi, go) -> Input:
    """The required input ``shaft_speed`` [rad/s], bounded by :func:`shaft_speed_limit`."""
    return Input(0.0, "rad/s", "imposed shaft speed", required=True,
                 **speed_input_bounds(shaft_speed_limit(gi, go)))


def speed_ratio(w_middle, w_shaft):
    """Speed distribution ratio ``Rs = w_middle / w_shaft`` [1], defined at rest.

    ``Rs = w_middle w_shaft / (w_shaft^2 + w_reg^2)`` with ``w_reg`` =
    :data:`RS_REGULARIZATION`: exact to a relative 1e-4 from a shaft speed of
    ``100 w_reg`` (1e-4 rad/s, 0.001 r/min) and 0 at rest. A middle ring at rest with the shaft
    gives 0, the limit of a spin-up from rest (the middle ring lags the shaft); a middle ring
    still turning when the shaft stops gives a large ratio there (``w_middle / w_shaft`` grows
    without bound) that falls back to 0 at rest.
    """
    return w_middle * w_shaft / (w_shaft**2 + RS_REGULARIZATION**2)
"""Numeric layer options (> 0), checked here so that the message names them."""


def _layer(geometry, lubricant, fidelity: str, friction_model: str, options: dict):
    for key, unit in _POSITIVE_OPTIONS.items():
        if key in options:
            check_range(options[key], f"layer_options[{key!r}]", unit, 0.0, None,
                        low_inclusive=False, where="double_layer_bearing")
    if fidelity in ("kinematic", "kinematic_approx"):
        unused = sorted(set(options) - set(KINEMATIC_OPTIONS))
        if unused:
            raise ParameterError(
                f"double_layer_bearing: layer_options {', '.join(map(repr, unused))} not used at "
                f"fidelity {fidelity!r}; its only option is 'k' (pure-rolling drag coefficient "
                f"[N s/m], > 0)"
            )
        return PureRollingLayer(geometry, exact=fidelity == "kinematic", **options)
    check_options(options, layer_option_names(friction_model), "double_layer_bearing",
                  "layer_options", f"of the {friction_model!r} friction model (torque level)")
    layer = PalmgrenBearing if friction_model == "palmgren" else SkfBearing
    check_arguments(layer, (), {k: v for k, v in options.items()
                                if k in keyword_names(layer)},
                    "double_layer_bearing", "layer_options[{name!r}]")
    return layer(geometry, lubricant, **options)


def _with_method(lubricant, method: str):
    """A copy of ``lubricant`` lubricating by ``method``."""
    check_choice(method, "lubrication_method", LUBRICATION_METHODS, "double_layer_bearing")
    if not lubricant.is_viscous:
        raise ParameterError(f"double_layer_bearing: lubrication_method {method!r} needs an oil "
                             f"or grease, got {lubricant.describe()}")
    changed = copy.copy(lubricant)
    changed.method = method
    return changed


def _bath_options(gi, go, lubricants, oil_level, friction_model: str, fidelity: str,
                  options: dict) -> tuple[dict, dict]:
    """Each layer's layer options with its own oil level (see :class:`DoubleLayerBearing`)."""
    if oil_level is None:
        return options, options
    where = "double_layer_bearing"
    check_range(oil_level, "oil_level", "m", 0.0, None, where=where)
    if fidelity != "torque":  # checked, but the kinematic levels have no friction (as lubrication)
        return options, options
    if friction_model != "skf":
        raise ParameterError(f"{where}: oil_level is used by friction_model='skf' at the torque "
                             f"level (the drag of the immersed balls, the starvation factor); "
                             f"Palmgren's f0 has no published oil-level dependence here")
    if "oil_level" in options:
        raise ParameterError(f"{where}: give the oil level once, as oil_level (each layer sees "
                             f"it from its own lowest ball), not in layer_options")
    levels = (oil_level - 0.5 * (go.pitch_diameter - gi.pitch_diameter), oil_level)
    per_layer = []
    for g, lub, level in zip((gi, go), lubricants, levels, strict=True):
        layer = dict(options)
        if lub.method == "oil_bath" and level >= 0.0:
            layer.update(oil_level=level, Dw=g.ball_diameter, Z=g.ball_count)
        per_layer.append(layer)
    return per_layer[0], per_layer[1]


def _middle_ring_gap(options: Any, lubricant) -> tuple[float, ...]:
    """(radius, gap, length, wetted, eta, nu) of the middle ring's oil gap, checked."""
    where = "double_layer_bearing"
    opts = check_mapping(options, "middle_ring_drag", where, "keys")
    check_options(opts, ("radius", "gap", "length", "wetted"), where, "middle_ring_drag keys")
    missing = [k for k in ("radius", "gap", "length") if k not in opts]
    if missing:
        raise ParameterError(f"{where}: middle_ring_drag needs {', '.join(missing)} [m] (the "
                             f"turning cylinder's radius, the oil gap and the wetted length)")
    if not lubricant.is_viscous:
        raise ParameterError(f"{where}: middle_ring_drag needs an oil or grease in the outer "
                             f"layer, got {lubricant.describe()}")
    eta, nu = float(lubricant.dynamic_viscosity()), float(lubricant.kinematic_viscosity())
    wetted = opts.get("wetted", 1.0)
    couette_damping(opts["radius"], opts["gap"], opts["length"], eta, wetted)  # checks them
    return (float(opts["radius"]), float(opts["gap"]), float(opts["length"]), float(wetted),
            eta, nu)


def _check_drive(drive: str) -> None:
    check_choice(drive, "drive", ("speed", "flange"), "double_layer_bearing")


def _pair(lubrication) -> tuple[Any, Any]:
    if isinstance(lubrication, (tuple, list)):
        if len(lubrication) != 2:
            raise ParameterError(f"double_layer_bearing: lubrication must be one lubricant or "
                                 f"an (inner, outer) pair, got {len(lubrication)} items")
        return lubrication[0], lubrication[1]
    return lubrication, lubrication


class DoubleLayerBearing(Assembly):
    """A double-layer bearing at the kinematic or torque fidelity level.

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner (shaft side) and outer (housing side) deep-groove bearing.
    structure : {"I", "Z"} or None
        Middle ring type; None chooses "I" when the inner bearing fits in the outer bearing's
        bore (``D1 <= d2``), else "Z".
    fidelity : {"kinematic", "kinematic_approx", "torque"}
        Pure rolling (exact with contact angles, or the ``Dp1/(Dp1+Dp2)`` approximation) or
        friction torque models.
    lubrication : lubricant or (lubricant, lubricant)
        Lubricant of both layers, or of the (inner, outer) layer; names or objects. Used at
        the torque level only: the kinematic levels have no friction and ignore it (it is
        still checked, so an unknown name raises :class:`~bearingsim.errors.CatalogError`).
        It is not an error there because a scene with ``fidelity = "auto"`` passes its
        lubricant to whichever level it picks.
    friction_model : {"palmgren", "skf"}
        Friction torque model of the torque level; checked but ignored at the kinematic levels
        (as ``lubrication``).
    drive : {"speed", "flange"}
        ``"speed"``: an internal speed source drives the shaft at ``speed`` (an input
        ``shaft_speed`` [rad/s] when ``speed`` is None); ``"flange"``: the shaft flange is left
        for a motor.
    speed : callable or float or None
        Shaft speed [rad/s] for ``drive="speed"``.
    lubrication_method : str or (str, str), optional
        Lubrication method of both layers or of the (inner, outer) layer, one of
        :data:`~bearingsim.physics.lubrication.LUBRICATION_METHODS` (default: each lubricant's
        own, ``oil_bath`` for the named oils, ``grease`` for the greases). It sets Palmgren's
        f0 and the SKF starvation constant of each layer.
    oil_level : float, optional
        Oil bath level [m] above the lowest point of the outer layer's pitch circle (the centre
        of its lowest ball), used by ``friction_model="skf"`` at the torque level (an error with
        Palmgren's model; checked but ignored at the kinematic levels). Each layer sees it from
        its own lowest ball: the inner layer's level is ``oil_level - (dm2 - dm1) / 2``. A
        layer whose level is >= 0 gets the drag of its immersed balls and no starvation factor;
        a layer
        above the oil (negative level) is a low-level bath (starvation factor, no drag; SKF
        "Rolling bearings" 10000/3, 2017, p. 102). Only layers lubricated by ``oil_bath``
        take it.
    middle_ring_drag : dict, optional
        The middle ring's own viscous drag in the oil of the outer layer, at the torque level:
        a cylinder of ``radius`` [m] turning in a fixed bore ``gap`` [m] wider, over ``length``
        [m], on the ``wetted`` fraction of its circumference (default 1). The exact laminar
        Couette torque (:func:`~bearingsim.physics.drag.couette_damping`, a linear damper
        between the middle ring and the housing); the variable ``middle_Ta`` is the gap's
        Taylor number, which must stay below
        :data:`~bearingsim.physics.drag.TAYLOR_ONSET` (41.3) for the laminar torque to hold.
    layer_options : dict
        Extra keyword arguments of the layer elements: at the torque level those of
        :class:`~bearingsim.components.bearing_torque.PalmgrenBearing` or
        :class:`~bearingsim.components.bearing_torque.SkfBearing` (e.g. ``smooth``,
        ``load_dependent``; SKF: ``series``, ``omega_reg`` and the options of
        :func:`~bearingsim.physics.friction.skf_friction_components` such as ``seal``,
        ``oil_level``; see :func:`layer_option_names`); at the kinematic levels only ``k``, the
        drag coefficient of :class:`~bearingsim.components.bearing_torque.PureRollingLayer`
        [N s/m]. Others raise :class:`~bearingsim.errors.ParameterError` naming the accepted
        ones.

    Raises
    ------
    ParameterError
        For a fidelity, structure, drive, friction model or layer option outside the ones
        above.

    Connectors
    ----------
    shaft : Flange (inner ring of the inner bearing)

    Variables
    ---------
    w_shaft, w_middle [rad/s]; Rs [1] = w_middle / w_shaft (0 at rest, :func:`speed_ratio`);
    M_shaft [N m] friction torque the bearing exerts on the shaft (opposes its rotation:
    negative while it turns forward; the one sign convention of scenes, CSVs, plots and FMUs);
    inputs Fr, Fa [N] (radial and axial load carried by both layers in series)
    """

    def __init__(self, inner="61905", outer="61907", structure: str | None = None,
                 fidelity: str = "torque", lubrication=("ISO VG 32", "ISO VG 32"),
                 friction_model: str = "palmgren", drive: str = "speed",
                 speed: Callable | float | None = None, lubrication_method=None,
                 oil_level: float | None = None, middle_ring_drag: dict | None = None,
                 layer_options: dict | None = None, name="bearing"):
        super().__init__(name)
        gi, go = resolve_bearing(inner), resolve_bearing(outer)
        if fidelity not in FIDELITIES[:3]:
            raise ParameterError(
                f"double_layer_bearing: fidelity must be one of {', '.join(FIDELITIES)}, got "
                f"{fidelity!r} (the quasi-static and dynamic levels are built by "
                f"double_layer_bearing)"
            )
        structure = middle_ring_structure(gi, go, structure)
        _check_drive(drive)
        check_choice(friction_model, "friction_model", FRICTION_MODELS, "double_layer_bearing")
        lub_i, lub_o = (as_lubricant(x, "double_layer_bearing") for x in _pair(lubrication))
        if lubrication_method is not None:
            lub_i, lub_o = (_with_method(lub, m) for lub, m in
                            zip((lub_i, lub_o), _pair(lubrication_method), strict=True))
        opts = check_mapping(layer_options, "layer_options", "double_layer_bearing",
                             "option names")
        opts_i, opts_o = _bath_options(gi, go, (lub_i, lub_o), oil_level, friction_model,
                                       fidelity, opts)
        self.structure = structure
        self.geometries = (gi, go)
        self.shaft = Flange()
        self.housing = Fixed()
        self.middle = MiddleRing(middle_ring_bodies(gi, go, structure))
        self.inner_layer = _layer(gi, lub_i, fidelity, friction_model, opts_i)
        self.outer_layer = _layer(go, lub_o, fidelity, friction_model, opts_o)
        self.w_shaft = Variable(unit="rad/s", description="shaft (inner ring) speed")
        self.w_middle = Variable(unit="rad/s", description="middle ring speed")
        self.Rs = Variable(unit="1", description="speed distribution ratio n_z / n_i")
        self.M_shaft = Variable(unit="N.m", description="friction torque on the shaft")
        self._lubricated = fidelity == "torque"
        if self._lubricated:
            self.Fr = Input(0.0, "N", "radial load through both layers", low=0.0)
            self.Fa = Input(0.0, "N", "axial load through both layers (magnitude)", low=0.0)
        connect(self.shaft, self.inner_layer.inner)
        connect(self.inner_layer.outer, self.middle.inner_side)
        connect(self.middle.outer_side, self.outer_layer.inner)
        connect(self.outer_layer.outer, self.housing.flange)
        if drive == "speed":
            self.drive = SpeedSource(speed)
            connect(self.drive.flange, self.shaft)
            if speed is None:
                self.shaft_speed = _shaft_speed_input(gi, go)
            else:
                _check_shaft_speed(speed, gi, go)
        self._gap = None
        if middle_ring_drag is not None and fidelity == "torque":
            self._gap = _middle_ring_gap(middle_ring_drag, lub_o)
            radius, gap, length, wetted, eta, _ = self._gap
            self.middle_drag = Damper(couette_damping(radius, gap, length, eta, wetted))
            connect(self.middle.outer_side, self.middle_drag.flange_a)
            connect(self.middle_drag.flange_b, self.housing.flange)
            self.middle_Ta = Variable(unit="1", description="Taylor number of the middle ring's "
                                      f"oil gap (laminar below {TAYLOR_ONSET})")

    def equations(self):
        eqs = [
            self.w_shaft == der(self.shaft.phi),
            self.w_middle == self.middle.w,
            self.Rs == speed_ratio(self.w_middle, self.w_shaft),
            self.M_shaft == self.inner_layer.M,
        ]
        if self._lubricated:
            for layer in (self.inner_layer, self.outer_layer):
                eqs += [layer.Fr == self.Fr, layer.Fa == self.Fa]
        if hasattr(self, "shaft_speed"):
            eqs.append(self.drive.w_in == self.shaft_speed)
        if self._gap is not None:
            radius, gap, _, _, _, nu = self._gap
            eqs.append(self.middle_Ta == taylor_number(self.w_middle, radius, gap, nu))
        return eqs


_DYNAMIC_SETS = ("drive", "outer_ring", "ring_inertia", "speed", "loads", "drag",
                 "massive_balls", "inner_ring", "outer_support", "outer_start",
                 "rolling_resistance", "ring_drag")
"""Arguments of the layers' :class:`DeepGrooveBallBearing` that the dynamic level sets."""


class DynamicDoubleLayerBearing(Assembly):
    """A double-layer bearing with ball and cage dynamics in both layers.

    Each layer is a :class:`~bearingsim.assemblies.deep_groove.DeepGrooveBallBearing`: the inner
    layer's inner ring is the shaft, its outer ring rotates with the middle ring
    (``outer_ring="flange"``); the outer layer's inner ring is the middle ring (its rotation and
    polar inertia belong to the :class:`MiddleRing`, ``ring_inertia=False``) and its outer ring
    is fixed. The middle ring's rotation is the three-body :class:`MiddleRing` (the rigid joins
    are left to the assembler's index reduction); its translations are one
    :class:`~bearingsim.components.dynamic.RingBody` ``middle_body`` with the middle ring's total
    mass, whose frame carries the inner layer's outer race contacts (``outer_support="frame"``)
    and the outer layer's inner race contacts (``inner_ring="frame"``). The shaft load thus goes
    shaft, inner-layer balls, middle ring, outer-layer balls, housing: the two layers in series.
    The middle ring is held straight as the shaft is (its tilts are reactions; its tilt inertia,
    unused, is the thin-ring estimate of half the polar inertia); it starts at the outer
    layer's quasi-static displacement under ``loads``, the shaft at that plus the inner
    layer's own.

    Losses per layer (see docs/double_layer.md): race traction (slices), pocket and land
    contacts and films of the cage, the EHL rolling resistance at every race contact
    (``rolling_resistance``) and the :class:`~bearingsim.components.dynamic.RingDrag` between
    the layer's rings (``ring_drag``): Palmgren's ``M0`` of the layer's lubricant less the
    rolling-resistance loss, so that each layer's viscous loss equals the torque level's. The
    balls' drag in the oil-air mixture (:class:`~bearingsim.components.dynamic.BallDrag`) is
    off: it refers the oil to a housing at rest, which is wrong for the inner layer whose
    lubricant turns between the shaft and the middle ring; the churning it stands for is part
    of ``M0``.

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner and outer deep-groove bearing (contact angle 0).
    structure : {"I", "Z"} or None
        Middle ring type (None: "I" when the inner bearing fits in the outer one's bore).
    lubrication : lubricant or (lubricant, lubricant)
        Viscous lubricant (``Oil``, ``Grease`` or a name) of both layers or of (inner, outer).
    drive : {"speed", "flange"}
        ``"speed"``: a speed source turns the shaft at ``speed`` (an input ``shaft_speed``
        [rad/s] when ``speed`` is None); ``"flange"``: ``shaft`` (with the inner ring's polar
        inertia) is left for a motor.
    speed : callable or float or None
        Shaft speed [rad/s] for ``drive="speed"``.
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
        The two viscous loss terms above (with both, each layer's viscous loss is the torque
        level's M0 and the ratio follows its lubricant dependence).
    w_middle0 : float
        Initial middle ring speed [rad/s].
    fits : bool
        Mount both layers with the study's fits (k6 shaft seats, H7 bores): each layer's
        clearance becomes its operating clearance
        (:func:`~bearingsim.components.middle_ring.mounted_geometries`); default False, the
        clearance before mounting (catalogue rows: the CN mean).
    layer_options : dict, optional
        Further keyword arguments of both layers (``n_slices``, ``damping``, ...), those of
        :class:`~bearingsim.assemblies.deep_groove.DeepGrooveBallBearing` that this assembly
        does not set; others raise :class:`~bearingsim.errors.ParameterError`.

    Connectors
    ----------
    shaft : Flange (inner ring of the inner bearing)

    Variables
    ---------
    w_shaft, w_middle [rad/s]; Rs [1] = w_middle / w_shaft (0 at rest, :func:`speed_ratio`);
    M_middle [N m] net torque on the
    middle ring (its total polar inertia times its acceleration); the displacements
    ``inner_layer.ring.x, y, z`` (shaft) and ``middle_body.x, y, z`` (middle ring) [m]
    """

    def __init__(self, inner="61905", outer="61907", structure: str | None = None,
                 lubrication=("ISO VG 32", "ISO VG 32"), drive: str = "speed",
                 speed: Callable | float | None = None, loads: dict[str, Any] | None = None,
                 massive_balls: bool = True, rolling_resistance: bool = True,
                 ring_drag: bool = True, w_middle0: float = 0.0, fits: bool = False,
                 layer_options: dict | None = None, name="bearing"):
        super().__init__(name)
        gi, go = resolve_bearing(inner), resolve_bearing(outer)
        self.structure = middle_ring_structure(gi, go, structure)
        check_flag(fits, "fits", "double_layer_bearing")
        if fits:
            gi, go = mounted_geometries(gi, go, self.structure)
        _check_drive(drive)
        lub_i, lub_o = (as_lubricant(x, "double_layer_bearing") for x in _pair(lubrication))
        for lub in (lub_i, lub_o):
            if not lub.is_viscous:
                raise ParameterError(f"double_layer_bearing: the dynamic level needs viscous "
                                     f"lubricants (oil or grease), got {lub.describe()}")
        opts = check_mapping(layer_options, "layer_options", "double_layer_bearing",
                             "option names")
        for key in _DYNAMIC_SETS:
            if key in opts:
                raise ParameterError(f"double_layer_bearing: layer_options may not set "
                                     f"{key!r} (the nested assembly sets it)")
        if "oil_fraction" in opts:
            raise ParameterError("double_layer_bearing: layer_options 'oil_fraction' is not "
                                 "used: the dynamic level has no ball drag (drag=False)")
        check_options(opts, keyword_names(DeepGrooveBallBearing, _DYNAMIC_SETS + _LAYER_SETS
                                           + ("design", "oil_fraction")),
                      "double_layer_bearing", "layer_options", "at the dynamic level")
        if not opts.get("free_tilt", False):
            for key in ("Mx", "My"):
                if key in (loads or {}) and loads[key] != 0.0:
                    raise ParameterError(
                        f"double_layer_bearing: loads[{key!r}] = {loads[key]!r} [N.m] is not "
                        f"applied: the shaft and the middle ring are held straight (free_tilt="
                        f"False) and the moments are reactions; give {key} = 0 or leave it out")
        self.geometries = (gi, go)
        self.designs = (bearing_design(gi), bearing_design(go))
        loads = dict(loads or {})
        constant = {k: v for k, v in loads.items() if isinstance(v, (int, float))}
        common = dict(massive_balls=massive_balls, drag=False,
                      rolling_resistance=rolling_resistance, ring_drag=ring_drag,
                      drive="flange", **opts)
        self.shaft = Flange()
        self.middle = MiddleRing(middle_ring_bodies(gi, go, self.structure), w0=w_middle0)
        self.outer_layer = DeepGrooveBallBearing(self.designs[1], lub_o, ring_inertia=False,
                                                 loads=constant, inner_ring="frame", **common)
        start = self.outer_layer.start
        middle0 = tuple(float(v) for v in start.ring[:3]) if start else (0.0, 0.0, 0.0)
        self.middle_body = RingBody(self.middle.mass, 0.5 * self.middle.J,
                                      start=(*middle0, 0.0, 0.0))
        # an imposed shaft speed needs no shaft inertia (which would need the input's derivative)
        self.inner_layer = DeepGrooveBallBearing(self.designs[0], lub_i, outer_ring="flange",
                                                 ring_inertia=drive == "flange", loads=loads,
                                                 outer_support="frame", outer_start=middle0,
                                                 **common)
        self.w_shaft = Variable(unit="rad/s", description="shaft (inner ring) speed")
        self.w_middle = Variable(unit="rad/s", description="middle ring speed")
        self.Rs = Variable(unit="1", description="speed distribution ratio n_z / n_i")
        self.M_middle = Variable(unit="N.m", description="net torque on the middle ring")
        connect(self.shaft, self.inner_layer.shaft)
        connect(self.inner_layer.outer_flange, self.middle.inner_side)
        connect(self.middle.outer_side, self.outer_layer.shaft)
        connect(self.middle_body.frame, self.inner_layer.outer_frame,
                self.outer_layer.inner_frame)
        if drive == "speed":
            self.drive = SpeedSource(speed)
            connect(self.drive.flange, self.shaft)
            if speed is None:
                self.shaft_speed = _shaft_speed_input(gi, go)
            else:
                _check_shaft_speed(speed, gi, go)

    def rolling_start(self, w_shaft: float, w_middle: float,
                      states: list[str]) -> dict[str, float]:
        """Initial values for a start in pure rolling at the given ring speeds.

        The orbital speeds of the balls and cages are the epicyclic ones of each layer,
        ``w_c = (1 - g)/2 w_i + (1 + g)/2 w_o``, the balls spin about the axis at
        ``(w_c dm - w_i (dm - Dw)) / Dw`` (no slip at the inner race, hence none at the outer),
        and the middle ring turns at ``w_middle``.

        Parameters
        ----------
        w_shaft, w_middle : float
            Shaft and middle ring speed [rad/s].
        states : list of str
            State names of the assembled system (``system.state_names``); only those are
            returned (the middle ring's state is whichever of its bodies the assembler kept).

        Returns
        -------
        dict
            ``{state name: value}`` for :func:`~bearingsim.simulation.simulate` (``x0``).
        """
        prefix = self.path_prefix(states)
        start: dict[str, float] = {}
        for name, layer, (wi, wo) in (("inner_layer", self.inner_layer, (w_shaft, w_middle)),
                                      ("outer_layer", self.outer_layer, (w_middle, 0.0))):
            design = layer.design
            dm, dw = design.geometry.pitch_diameter, design.geometry.ball_diameter
            wc = design.epicyclic_ratio * wi + (1.0 - design.epicyclic_ratio) * wo
            start[f"{name}.cage.w"] = wc
            for j in range(design.geometry.ball_count):
                start[f"{name}.ball[{j}].w_orbit"] = wc
                start[f"{name}.ball[{j}].wz"] = (wc * dm - wi * (dm - dw)) / dw
        for body in ("inner_ring_of_inner_bearing", "sleeve", "outer_ring_of_outer_bearing"):
            start[f"middle.{body}.w"] = w_middle
        start["inner_layer.rotor.w"] = w_shaft
        return {prefix + k: v for k, v in start.items() if prefix + k in states}

    def path_prefix(self, states: list[str]) -> str:
        """Prefix of this assembly's state names in a system (empty when it is the root)."""
        key = "inner_layer.cage.w"
        for s in states:
            if s.endswith(key):
                return s[: -len(key)]
        raise ParameterError(f"{self.name}: the system holds no state {key!r}")

    def equations(self):
        eqs = [
            self.w_shaft == der(self.shaft.phi),
            self.w_middle == self.middle.w,
            self.Rs == speed_ratio(self.w_middle, self.w_shaft),
            self.M_middle == self.middle.J * der(self.middle.sleeve.w),
        ]
        if hasattr(self, "shaft_speed"):
            eqs.append(self.drive.w_in == self.shaft_speed)
        return eqs


_DEFAULT_LUBRICATION = ("ISO VG 32", "ISO VG 32")


def double_layer_bearing(inner="61905", outer="61907", structure=None, fidelity="torque",
                         lubrication=_DEFAULT_LUBRICATION, **kwargs):
    """Build a double-layer bearing assembly.

    ``fidelity="quasi-static"`` returns a
    :class:`~bearingsim.assemblies.nested_static.NestedQuasiStatic` (load through both layers
    in series; keywords ``axial``, ``name``; it has no friction, so a ``lubrication`` other
    than the default raises); ``fidelity="dynamic"`` a :class:`DynamicDoubleLayerBearing`
    (keywords ``drive``, ``speed``, ``loads``, ``massive_balls``, ``rolling_resistance``,
    ``ring_drag``, ``w_middle0``, ``layer_options``, ``name``); the other levels a
    :class:`DoubleLayerBearing` (keywords ``friction_model``, ``drive``, ``speed``,
    ``layer_options``, ``name``).

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner (shaft side) and outer (housing side) deep-groove bearing.
    structure : {"I", "Z"} or None
        Middle ring type (None: "I" when the inner bearing fits in the outer one's bore).
    fidelity : {"kinematic", "kinematic_approx", "torque", "quasi-static", "dynamic"}
        Fidelity level.
    lubrication : lubricant or (lubricant, lubricant)
        Lubricant of both layers or of (inner, outer).
    **kwargs
        Keywords of the class built for ``fidelity`` (above).

    Returns
    -------
    DoubleLayerBearing or NestedQuasiStatic or DynamicDoubleLayerBearing

    Raises
    ------
    ParameterError
        For a keyword the chosen level does not take (listing the ones it takes), and the
        checks of the class built.
    """
    if fidelity == "quasi-static":
        from bearingsim.assemblies.nested_static import NestedQuasiStatic

        where = "double_layer_bearing"
        check_options(kwargs, keyword_names(NestedQuasiStatic, ("inner", "outer", "structure")),
                      where, "keyword(s)", "at fidelity 'quasi-static'")
        if _pair(lubrication) != _pair(_DEFAULT_LUBRICATION):
            raise ParameterError(f"{where}: lubrication = {lubrication!r} is not used: the "
                                 f"quasi-static level has no friction (Hertz load sharing "
                                 f"only); leave lubrication out")
        return NestedQuasiStatic(inner, outer, structure, **kwargs)
    if fidelity == "dynamic":
        check_options(kwargs, keyword_names(DynamicDoubleLayerBearing,
                                            ("inner", "outer", "structure", "lubrication")),
                      "double_layer_bearing", "keyword(s)", "at fidelity 'dynamic'")
        return DynamicDoubleLayerBearing(inner, outer, structure, lubrication, **kwargs)
    check_options(kwargs, keyword_names(DoubleLayerBearing,
                                        ("inner", "outer", "structure", "fidelity",
                                         "lubrication")),
                  "double_layer_bearing", "keyword(s)", f"at fidelity {fidelity!r}")
    return DoubleLayerBearing(inner, outer, structure, fidelity, lubrication, **kwargs)


# --------------------------------------------------------------------------- scene spec
_KINEMATIC_NAMES = ("Rs", "w_shaft", "w_middle", "shaft_speed", "middle.*", "shaft.phi",
                    "drive.*", "der(*phi)")
"""Names the kinematic (pure rolling) level provides. Its shaft torque is a numerical drag, not
a friction torque, so ``M_shaft``, the losses, the loads and every other name need ``torque``."""


def double_layer_from_scene(args: dict[str, Any], fidelity: str,
                            drive: str = "speed") -> Assembly:
    """Build the bearing from the scene arguments of :data:`SCENE_SPEC`.

    Parameters
    ----------
    args : dict
        Every argument of ``SCENE_SPEC.args`` (defaults filled in).
    fidelity : {"kinematic_approx", "kinematic", "torque", "quasi-static", "dynamic"}
        Fidelity level: ``quasi-static`` is the load sharing of
        :class:`~bearingsim.assemblies.nested_static.NestedQuasiStatic` (inputs ``shaft.Fx``,
        ``shaft.Fy``, ``shaft.Fz`` [N]), ``dynamic`` the ball and cage dynamics of both layers
        (:class:`DynamicDoubleLayerBearing`, inputs ``shaft_speed`` and
        ``inner_layer.load.Fx`` ... [N]); the friction-model arguments belong to the lower
        levels.
    drive : {"speed", "flange"}
        Imposed shaft speed (input ``shaft_speed`` [rad/s]) or a free shaft flange.
    """
    if fidelity in ("quasi-static", "dynamic"):
        extra = {"drive": drive} if fidelity == "dynamic" else {}
        return double_layer_bearing(args["inner"], args["outer"], structure=args["structure"],
                                    fidelity=fidelity, lubrication=args["lubrication"], **extra)
    options = {k: v for k, v in (args["layer_options"] or {}).items() if v is not None}
    return double_layer_bearing(
        args["inner"], args["outer"], structure=args["structure"], fidelity=fidelity,
        lubrication=args["lubrication"], friction_model=args["friction_model"], drive=drive,
        lubrication_method=args["lubrication_method"], oil_level=args["oil_level"],
        middle_ring_drag={k: v for k, v in (args["middle_ring_drag"] or {}).items()
                          if v is not None} or None,
        layer_options=options or None,
    )


def _layer_life(geometry, layer: str) -> PostQuantity:
    name = f"{layer}.L10h"
    needs = ("Fr", "Fa", f"{layer}.w_rel")

    def compute(series):
        return basic_rating_life_hours(geometry, *(series[n] for n in needs))

    return PostQuantity(name, "h", f"ISO 281 basic rating life of the {layer.replace('_', ' ')} "
                        f"({geometry.designation}) at the momentary load and relative speed "
                        f"(inf when unloaded or at rest)", needs, compute, "torque")


def _total_loss(series):
    return series["inner_layer.P_loss"] + series["outer_layer.P_loss"]


def _scene_post(args: dict[str, Any]) -> dict[str, PostQuantity]:
    """ISO 281 basic rating life [h] of each layer with catalogue ratings, and the total friction
    power [W]."""
    out = {}
    for layer in ("inner", "outer"):
        geometry = resolve_bearing(args[layer])
        if geometry.dynamic_load_rating is not None and geometry.static_load_rating is not None:
            quantity = _layer_life(geometry, f"{layer}_layer")
            out[quantity.name] = quantity
    out["P_loss_total"] = PostQuantity("P_loss_total", "W", "friction power of both layers",
                                       ("inner_layer.P_loss", "outer_layer.P_loss"), _total_loss,
                                       "torque")
    return out


def _palmgren(args: dict[str, Any]) -> bool:
    """The lubricant only changes parameter values (the viscosity) under Palmgren friction."""
    return args["friction_model"] == "palmgren"


SCENE_SPEC = AssemblySpec(
    name="double_layer_bearing",
    description="I/Z-type double-layer (nested) ball bearing driven at an imposed shaft speed "
                "(input shaft_speed [rad/s]; torque level adds the loads Fr, Fa [N])",
    build=double_layer_from_scene,
    args={
        "inner": ArgSpec("bearing", factory_default(double_layer_bearing, "inner"),
                         "inner (shaft-side) deep-groove bearing"),
        "outer": ArgSpec("bearing", factory_default(double_layer_bearing, "outer"),
                         "outer (housing-side) deep-groove bearing"),
        "structure": ArgSpec("choice", factory_default(double_layer_bearing, "structure"),
                             "middle ring type (default: I if it fits, else Z)",
                             choices=STRUCTURES),
        "lubrication": ArgSpec("lubricant", factory_default(double_layer_bearing, "lubrication"),
                               "lubricant of both layers, or [inner, outer]"),
        "friction_model": ArgSpec("choice", factory_default(DoubleLayerBearing, "friction_model"),
                                  "friction torque model (torque level)",
                                  choices=FRICTION_MODELS),
        "lubrication_method": ArgSpec("choice", None, "lubrication method of both layers "
                                      "(default: the lubricant's own)",
                                      choices=LUBRICATION_METHODS),
        "oil_level": ArgSpec("float", None, "oil bath level above the outer layer's lowest ball "
                             "centre [m] (SKF friction model)", low=0.0),
        "middle_ring_drag": ArgSpec("table", None, "the middle ring's laminar drag in the oil "
                                    "(torque level)", table={
            "radius": ArgSpec("float", None, "radius of the turning cylinder [m]", low=0.0),
            "gap": ArgSpec("float", None, "oil gap to the fixed bore [m]", low=0.0),
            "length": ArgSpec("float", None, "wetted length [m]", low=0.0),
            "wetted": ArgSpec("float", None, "wetted fraction of the circumference", low=0.0),
        }),
        "layer_options": ArgSpec("table", None, "options of the friction elements", table={
            "smooth": ArgSpec("bool", None, "smooth blend of the Palmgren M0 branches"),
            "load_dependent": ArgSpec("bool", None, "include the load-dependent torque M1"),
            "omega_reg": ArgSpec("float", None, "friction sign regularization speed [rad/s]",
                                 low=0.0),
        }),
    },
    fidelities=FIDELITIES,
    auto_fidelities=("kinematic", "torque"),
    output_fidelity=[(pattern, "kinematic") for pattern in _KINEMATIC_NAMES],
    default_outputs=["w_shaft", "w_middle", "Rs", "M_shaft"],
    post=_scene_post,
    parametric_args={"lubrication": _palmgren},
    optional_inputs=("Fr", "Fa", "shaft.F*", "middle.F*", "inner_layer.load.*"),  # no load
    reference_fidelity=declared_errors("double_layer_bearing")[0],
    level_errors=declared_errors("double_layer_bearing")[1],
)
"""The double-layer bearing as a scene assembly (:mod:`bearingsim.scenes`)."""
