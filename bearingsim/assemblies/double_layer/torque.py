"""The double-layer bearing at the kinematic and friction-torque levels
(:class:`DoubleLayerBearing`)."""

from __future__ import annotations

from bearingsim.assemblies.double_layer.options import DoubleLayerOptions
from bearingsim.assemblies.double_layer.speed import _shaft_speed_input, speed_ratio
from bearingsim.components.bearing_torque import PalmgrenBearing, PureRollingLayer, SkfBearing
from bearingsim.components.connectors import Flange
from bearingsim.components.middle_ring import MiddleRing, middle_ring_bodies
from bearingsim.components.rotational import Damper, Fixed, SpeedSource
from bearingsim.language import Assembly, Input, Variable, connect, der
from bearingsim.physics.drag import TAYLOR_ONSET, couette_damping, taylor_number
from bearingsim.validation import options_object


class DoubleLayerBearing(Assembly):
    """A double-layer bearing at the kinematic or torque fidelity level.

    Parameters
    ----------
    options : DoubleLayerOptions, optional
        The layers, lubricants, drive, fidelity and friction options, checked when it was
        built (:class:`~bearingsim.assemblies.double_layer.options.DoubleLayerOptions`);
        default: 61905 in 61907 at the Palmgren torque level, ISO VG 32, driven by the input
        ``shaft_speed``.
    name : str
        Instance name.

    Connectors
    ----------
    shaft : Flange (inner ring of the inner bearing)

    Attributes
    ----------
    options : DoubleLayerOptions
    structure : {"I", "Z"}
    geometries : (BearingGeometry, BearingGeometry)
        Inner and outer layer.

    Variables
    ---------
    w_shaft, w_middle [rad/s]; Rs [1] = w_middle / w_shaft (0 at rest, :func:`speed_ratio`);
    M_shaft [N m] friction torque the bearing exerts on the shaft (opposes its rotation:
    negative while it turns forward; the one sign convention of scenes, CSVs, plots and FMUs);
    inputs Fr, Fa [N] (radial and axial load carried by both layers in series)

    Examples
    --------
    >>> from bearingsim.assemblies.double_layer import DoubleLayerBearing, DoubleLayerOptions
    >>> bearing = DoubleLayerBearing(DoubleLayerOptions(fidelity="kinematic", speed=100.0))
    >>> bearing.structure
    'Z'
    """

    def __init__(self, options: DoubleLayerOptions | None = None, name="bearing"):
        super().__init__(name)
        options = options_object(options, DoubleLayerOptions, "double_layer_bearing")
        self.options = options
        self.structure = options.structure
        self.geometries = gi, go = options.geometries
        fidelity, friction_model = options.fidelity, options.friction_model
        self.shaft = Flange()
        self.housing = Fixed()
        self.middle = MiddleRing(middle_ring_bodies(gi, go, self.structure))
        self.inner_layer, self.outer_layer = (
            _layer(g, lub, fidelity, friction_model, opts) for g, lub, opts in
            zip(options.geometries, options.lubricants, options.layer_options_each, strict=True))
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
        if options.drive == "speed":
            self.drive = SpeedSource(options.speed)
            connect(self.drive.flange, self.shaft)
            if options.speed is None:
                self.shaft_speed = _shaft_speed_input(gi, go)
        self._gap = options.gap
        if self._gap is not None:
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


def _layer(geometry, lubricant, fidelity: str, friction_model: str, options: dict):
    """A layer's element (options checked by :class:`DoubleLayerOptions`): pure rolling at the
    kinematic levels, Palmgren's or SKF's friction torque at the torque level."""
    if fidelity in ("kinematic", "kinematic_approx"):
        return PureRollingLayer(geometry, exact=fidelity == "kinematic", **options)
    layer = PalmgrenBearing if friction_model == "palmgren" else SkfBearing
    return layer(geometry, lubricant, **options)
