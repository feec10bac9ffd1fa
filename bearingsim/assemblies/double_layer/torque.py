"""The double-layer bearing at the kinematic and friction-torque levels
(:class:`DoubleLayerBearing`)."""

from __future__ import annotations

from bearingsim.assemblies.double_layer.base import PartialDoubleLayer
from bearingsim.assemblies.double_layer.options import DoubleLayerOptions
from bearingsim.components.bearing_torque import PalmgrenBearing, PureRollingLayer, SkfBearing
from bearingsim.components.middle_ring import MiddleRing, middle_ring_bodies
from bearingsim.components.rolling_element import magnitude_input_bounds
from bearingsim.components.rotational import Damper, Fixed
from bearingsim.language import Input, Variable, connect
from bearingsim.physics.drag import TAYLOR_ONSET, couette_damping, taylor_number


class DoubleLayerBearing(PartialDoubleLayer):
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
        super().__init__(options, DoubleLayerOptions, name)
        options = self.options
        fidelity, friction_model = options.fidelity, options.friction_model
        self.housing = Fixed()
        self.middle = MiddleRing(middle_ring_bodies(*self.geometries, self.structure))
        self.inner_layer, self.outer_layer = (
            _layer(g, lub, fidelity, friction_model, opts) for g, lub, opts in
            zip(options.geometries, options.lubricants, options.layer_options_each, strict=True))
        self._declare_speeds()
        self.M_shaft = Variable(unit="N.m", description="friction torque on the shaft")
        self._lubricated = fidelity == "torque"
        if self._lubricated:
            bounds = magnitude_input_bounds(*options.geometries)
            self.Fr = Input(0.0, "N", "radial load through both layers", **bounds["Fr"])
            self.Fa = Input(0.0, "N", "axial load through both layers (magnitude)",
                            **bounds["Fa"])
        connect(self.shaft, self.inner_layer.inner)
        connect(self.inner_layer.outer, self.middle.inner_side)
        connect(self.middle.outer_side, self.outer_layer.inner)
        connect(self.outer_layer.outer, self.housing.flange)
        self._build_drive()
        self._gap = options.gap
        if self._gap is not None:
            radius, gap, length, wetted, eta, _ = self._gap
            self.middle_drag = Damper(couette_damping(radius, gap, length, eta, wetted))
            connect(self.middle.outer_side, self.middle_drag.flange_a)
            connect(self.middle_drag.flange_b, self.housing.flange)
            self.middle_Ta = Variable(unit="1", description="Taylor number of the middle ring's "
                                      f"oil gap (laminar below {TAYLOR_ONSET})")

    def equations(self):
        eqs = [*self._speed_equations(), self.M_shaft == self.inner_layer.M]
        if self._lubricated:
            for layer in (self.inner_layer, self.outer_layer):
                eqs += [layer.Fr == self.Fr, layer.Fa == self.Fa]
        eqs += self._drive_equations()
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
