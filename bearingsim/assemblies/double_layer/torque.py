"""The double-layer bearing at the kinematic and friction-torque levels
(:class:`DoubleLayerBearing`)."""

from __future__ import annotations

from collections.abc import Callable

from bearingsim.assemblies.double_layer.layers import (
    _bath_options,
    _layer,
    _middle_ring_gap,
    _with_method,
)
from bearingsim.assemblies.double_layer.options import (
    FIDELITIES,
    FRICTION_MODELS,
    _check_drive,
    _pair,
)
from bearingsim.assemblies.double_layer.speed import (
    _check_shaft_speed,
    _shaft_speed_input,
    speed_ratio,
)
from bearingsim.catalog import resolve_bearing
from bearingsim.components.connectors import Flange
from bearingsim.components.middle_ring import (
    MiddleRing,
    middle_ring_bodies,
    middle_ring_structure,
)
from bearingsim.components.rotational import Damper, Fixed, SpeedSource
from bearingsim.errors import ParameterError
from bearingsim.language import Assembly, Input, Variable, connect, der
from bearingsim.physics.drag import TAYLOR_ONSET, couette_damping, taylor_number
from bearingsim.physics.lubricant import as_lubricant
from bearingsim.validation import (
    check_choice,
    check_mapping,
)


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
