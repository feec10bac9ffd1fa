"""Double-layer (nested) ball bearings, I-type and Z-type (models.md section A).

Two deep-groove ball bearings are nested: the inner bearing's outer ring, an intermediate sleeve
and the outer bearing's inner ring form the *middle ring*, three bodies joined rigidly by
connections (the assembler's alias elimination and index reduction merge them). The shaft drives
the inner bearing's inner ring; the outer bearing's outer ring sits in the housing. Friction
drags the middle ring to a speed ``n_z``; the speed distribution ratio is ``Rs = n_z / n_i``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.bearing_torque import PalmgrenBearing, PureRollingLayer, SkfBearing
from bearingsim.components.rotational import Fixed, Flange, Inertia, SpeedSource
from bearingsim.errors import ParameterError, check_range
from bearingsim.language import Assembly, Input, Variable, connect, der

__all__ = [
    "MiddleRing",
    "RingBody",
    "DoubleLayerBearing",
    "double_layer_bearing",
    "middle_ring_bodies",
    "FIDELITIES",
]

FIDELITIES = ("kinematic", "kinematic_approx", "torque", "quasi-static")
STEEL_DENSITY = 7850.0
"""Bearing steel density [kg/m^3]."""


@dataclass(frozen=True)
class RingBody:
    """Mass properties of one part of the middle ring."""

    name: str
    mass: float
    """[kg]"""
    inertia: float
    """Polar moment of inertia [kg m^2]."""


def _tube(name: str, r_in: float, r_out: float, width: float, rho: float) -> RingBody:
    m = rho * math.pi * (r_out**2 - r_in**2) * width
    return RingBody(name, m, 0.5 * m * (r_out**2 + r_in**2))


def middle_ring_bodies(
    inner: BearingGeometry, outer: BearingGeometry, structure: str, wall: float = 2.5e-3,
    density: float = STEEL_DENSITY,
) -> list[RingBody]:
    """Mass and polar inertia of the three parts of the middle ring.

    The rings are hollow cylinders: the inner bearing's outer ring from the outer land radius
    ``dm/2 + 0.3 Dw`` to ``D/2``; the outer bearing's inner ring from ``d/2`` to the inner land
    radius ``dm/2 - 0.3 Dw`` (an estimate of the land heights of deep-groove rings). The sleeve
    is a plain tube between ``D1/2`` and ``d2/2`` (I-type), or a Z section (Z-type): a hub of
    thickness ``wall`` around the inner bearing, a hub of thickness ``wall`` inside the outer
    bearing's bore, joined by a radial web of thickness ``wall``.

    Parameters
    ----------
    inner, outer : BearingGeometry
        Inner (1) and outer (2) bearing.
    structure : {"I", "Z"}
        Middle ring type.
    wall : float
        Wall thickness of the Z-section sleeve [m].
    density : float
        Material density [kg/m^3].

    Returns
    -------
    list of RingBody
        Inner bearing's outer ring, sleeve, outer bearing's inner ring.
    """
    check_range(wall, "wall", "m", 0.0, None, low_inclusive=False, where="middle_ring_bodies")
    ring1 = _tube("inner bearing outer ring", inner.pitch_diameter / 2 + 0.3 * inner.ball_diameter,
                  inner.outside_diameter / 2, inner.width, density)
    ring2 = _tube("outer bearing inner ring", outer.bore / 2,
                  outer.pitch_diameter / 2 - 0.3 * outer.ball_diameter, outer.width, density)
    r1, r2 = inner.outside_diameter / 2, outer.bore / 2
    if structure == "I":
        sleeve = _tube("sleeve", r1, r2, max(inner.width, outer.width), density)
    else:
        hub1 = _tube("", r1, r1 + wall, inner.width, density)
        hub2 = _tube("", r2 - wall, r2, outer.width, density)
        web = _tube("", min(r2 - wall, r1), max(r1 + wall, r2), wall, density)
        sleeve = RingBody("sleeve", hub1.mass + hub2.mass + web.mass,
                          hub1.inertia + hub2.inertia + web.inertia)
    return [ring1, sleeve, ring2]


class MiddleRing(Assembly):
    """The middle ring: three rigid bodies joined by connections (not a hand-merged inertia).

    Connectors
    ----------
    inner_side : Flange (the inner bearing's outer ring)
    outer_side : Flange (the outer bearing's inner ring)

    Variables
    ---------
    w [rad/s] : speed of the middle ring
    """

    def __init__(self, bodies: list[RingBody], w0: float = 0.0, name=None):
        super().__init__(name)
        ring1, sleeve, ring2 = bodies
        self.inner_ring_of_inner_bearing = Inertia(ring1.inertia, w0=w0)
        self.sleeve = Inertia(sleeve.inertia)
        self.outer_ring_of_outer_bearing = Inertia(ring2.inertia)
        self.inner_side = Flange()
        self.outer_side = Flange()
        self.w = Variable(unit="rad/s", description="middle ring speed")
        self.mass = sum(b.mass for b in bodies)
        connect(self.inner_side, self.inner_ring_of_inner_bearing.flange_a)
        connect(self.inner_ring_of_inner_bearing.flange_b, self.sleeve.flange_a)
        connect(self.sleeve.flange_b, self.outer_ring_of_outer_bearing.flange_a)
        connect(self.outer_ring_of_outer_bearing.flange_b, self.outer_side)

    def equations(self):
        return [self.w == self.sleeve.w]


def _layer(geometry, lubricant, fidelity: str, friction_model: str, options: dict):
    if fidelity == "kinematic":
        return PureRollingLayer(geometry, exact=True)
    if fidelity == "kinematic_approx":
        return PureRollingLayer(geometry, exact=False)
    if friction_model == "palmgren":
        return PalmgrenBearing(geometry, lubricant, **options)
    if friction_model == "skf":
        return SkfBearing(geometry, lubricant, **options)
    raise ParameterError(
        f"friction_model must be 'palmgren' or 'skf', got {friction_model!r}"
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
        Lubricant of both layers, or of the (inner, outer) layer; names or objects.
    friction_model : {"palmgren", "skf"}
        Friction torque model of the torque level.
    drive : {"speed", "flange"}
        ``"speed"``: an internal speed source drives the shaft at ``speed`` (an input
        ``shaft_speed`` [rad/s] when ``speed`` is None); ``"flange"``: the shaft flange is left
        for a motor.
    speed : callable or float or None
        Shaft speed [rad/s] for ``drive="speed"``.
    layer_options : dict
        Extra keyword arguments of the layer elements (e.g. ``smooth``, ``load_dependent``).

    Connectors
    ----------
    shaft : Flange (inner ring of the inner bearing)

    Variables
    ---------
    w_shaft, w_middle [rad/s]; Rs [1] = w_middle / w_shaft; M_shaft [N m] friction torque on
    the shaft; inputs Fr, Fa [N] (radial and axial load carried by both layers in series)
    """

    def __init__(self, inner="61905", outer="61907", structure: str | None = None,
                 fidelity: str = "torque", lubrication=("ISO VG 32", "ISO VG 32"),
                 friction_model: str = "palmgren", drive: str = "speed",
                 speed: Callable | float | None = None, layer_options: dict | None = None,
                 name="bearing"):
        super().__init__(name)
        gi, go = resolve_bearing(inner), resolve_bearing(outer)
        if fidelity not in FIDELITIES[:3]:
            raise ParameterError(
                f"double_layer_bearing: fidelity must be one of {', '.join(FIDELITIES)}, got "
                f"{fidelity!r} (the quasi-static level is built by double_layer_bearing)"
            )
        fits = gi.outside_diameter <= go.bore
        structure = structure or ("I" if fits else "Z")
        if structure not in ("I", "Z"):
            raise ParameterError(f"double_layer_bearing: structure must be 'I' or 'Z', got "
                                 f"{structure!r}")
        if structure == "I" and not fits:
            raise ParameterError(
                f"double_layer_bearing: an I-type middle ring needs the inner bearing's outside "
                f"diameter ({gi.outside_diameter * 1e3:g} mm) <= the outer bearing's bore "
                f"({go.bore * 1e3:g} mm); use structure='Z'"
            )
        if drive not in ("speed", "flange"):
            raise ParameterError(f"double_layer_bearing: drive must be 'speed' or 'flange', got "
                                 f"{drive!r}")
        lub_i, lub_o = (lubrication if isinstance(lubrication, (tuple, list))
                        else (lubrication, lubrication))
        opts = dict(layer_options or {})
        self.structure = structure
        self.geometries = (gi, go)
        self.shaft = Flange()
        self.housing = Fixed()
        self.middle = MiddleRing(middle_ring_bodies(gi, go, structure))
        self.inner_layer = _layer(gi, lub_i, fidelity, friction_model, opts)
        self.outer_layer = _layer(go, lub_o, fidelity, friction_model, opts)
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
                self.shaft_speed = Input(0.0, "rad/s", "imposed shaft speed")

    def equations(self):
        eqs = [
            self.w_shaft == der(self.shaft.phi),
            self.w_middle == self.middle.w,
            self.Rs == self.w_middle * self.w_shaft / (self.w_shaft**2 + 1e-6),
            self.M_shaft == self.inner_layer.M,
        ]
        if self._lubricated:
            for layer in (self.inner_layer, self.outer_layer):
                eqs += [layer.Fr == self.Fr, layer.Fa == self.Fa]
        if hasattr(self, "shaft_speed"):
            eqs.append(self.drive.w_in == self.shaft_speed)
        return eqs


def double_layer_bearing(inner="61905", outer="61907", structure=None, fidelity="torque",
                         lubrication=("ISO VG 32", "ISO VG 32"), **kwargs):
    """Build a double-layer bearing assembly.

    ``fidelity="quasi-static"`` returns a
    :class:`~bearingsim.assemblies.nested_static.NestedQuasiStatic` (load through both layers
    in series; keyword ``axial``); the other levels return a :class:`DoubleLayerBearing`.
    """
    if fidelity == "quasi-static":
        from bearingsim.assemblies.nested_static import NestedQuasiStatic

        return NestedQuasiStatic(inner, outer, structure, **kwargs)
    return DoubleLayerBearing(inner, outer, structure, fidelity, lubrication, **kwargs)
