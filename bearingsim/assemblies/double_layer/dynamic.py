"""The double-layer bearing with ball and cage dynamics in both layers
(:class:`DynamicDoubleLayerBearing`)."""

from __future__ import annotations

from bearingsim.assemblies.deep_groove import DeepGrooveBallBearing, DeepGrooveOptions
from bearingsim.assemblies.double_layer.base import PartialDoubleLayer
from bearingsim.assemblies.double_layer.options import DynamicDoubleLayerOptions
from bearingsim.components.dynamic import RingBody
from bearingsim.components.middle_ring import MiddleRing, middle_ring_bodies
from bearingsim.errors import ParameterError
from bearingsim.language import Variable, connect, der
from bearingsim.physics.bearing_design import bearing_design


class DynamicDoubleLayerBearing(PartialDoubleLayer):
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
    options : DynamicDoubleLayerOptions, optional
        The layers, lubricants, drive, loads and loss terms, checked when it was built
        (:class:`~bearingsim.assemblies.double_layer.options.DynamicDoubleLayerOptions`);
        default: 61905 in 61907, ISO VG 32, massive balls, rolling resistance and ring drag,
        driven by the input ``shaft_speed``, every load an input.
    name : str
        Instance name.

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

    def __init__(self, options: DynamicDoubleLayerOptions | None = None, name="bearing"):
        super().__init__(options, DynamicDoubleLayerOptions, name)
        options = self.options
        gi, go = self.geometries
        self.designs = (bearing_design(gi), bearing_design(go))
        lub_i, lub_o = options.lubricants
        loads = options.loads
        constant = DeepGrooveOptions.constant_loads(loads)
        self.middle = MiddleRing(middle_ring_bodies(gi, go, self.structure), w0=options.w_middle0)
        self.outer_layer = DeepGrooveBallBearing(self.designs[1], lub_o, options.for_layer(
            constant, ring_inertia=False, inner_ring="frame"))
        start = self.outer_layer.start
        middle0 = tuple(float(v) for v in start.ring[:3]) if start else (0.0, 0.0, 0.0)
        self.middle_body = RingBody(self.middle.mass, 0.5 * self.middle.J,
                                      start=(*middle0, 0.0, 0.0))
        # an imposed shaft speed needs no shaft inertia (which would need the input's derivative)
        self.inner_layer = DeepGrooveBallBearing(self.designs[0], lub_i, options.for_layer(
            loads, outer_ring="flange", ring_inertia=options.drive == "flange",
            outer_support="frame", outer_start=middle0))
        self._declare_speeds()
        self.M_middle = Variable(unit="N.m", description="net torque on the middle ring")
        connect(self.shaft, self.inner_layer.shaft)
        connect(self.inner_layer.outer_flange, self.middle.inner_side)
        connect(self.middle.outer_side, self.outer_layer.shaft)
        connect(self.middle_body.frame, self.inner_layer.outer_frame,
                self.outer_layer.inner_frame)
        self._build_drive()

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
        """Prefix of this assembly's state names in a system (empty when it is the root).

        Parameters
        ----------
        states : list of str
            The system's state names.

        Returns
        -------
        str
            The dotted prefix (``""`` at the root, else ending in ``"."``).

        Raises
        ------
        ParameterError
            When the system holds no state of this assembly.
        """
        key = "inner_layer.cage.w"
        for s in states:
            if s.endswith(key):
                return s[: -len(key)]
        raise ParameterError(f"{self.name}: the system holds no state {key!r}")

    def equations(self):
        return [*self._speed_equations(),
                self.M_middle == self.middle.J * der(self.middle.sleeve.w),
                *self._drive_equations()]
