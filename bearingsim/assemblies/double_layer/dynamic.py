"""The double-layer bearing with ball and cage dynamics in both layers
(:class:`DynamicDoubleLayerBearing`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from bearingsim.assemblies.deep_groove import DeepGrooveBallBearing
from bearingsim.assemblies.double_layer.options import _LAYER_SETS, _check_drive, _pair
from bearingsim.assemblies.double_layer.speed import (
    _check_shaft_speed,
    _shaft_speed_input,
    speed_ratio,
)
from bearingsim.catalog import resolve_bearing
from bearingsim.components.connectors import Flange
from bearingsim.components.dynamic import RingBody
from bearingsim.components.middle_ring import (
    MiddleRing,
    middle_ring_bodies,
    middle_ring_structure,
    mounted_geometries,
)
from bearingsim.components.rotational import SpeedSource
from bearingsim.errors import ParameterError
from bearingsim.language import Assembly, Variable, connect, der
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.physics.lubricant import as_lubricant
from bearingsim.validation import (
    check_flag,
    check_mapping,
    check_options,
    keyword_names,
)

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
