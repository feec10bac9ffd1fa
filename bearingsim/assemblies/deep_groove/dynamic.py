"""The deep-groove ball bearing with ball and cage dynamics (:class:`DeepGrooveBallBearing`:
quasi-static or massive balls, traction, cage pockets and land, film damping)."""

from __future__ import annotations

import dataclasses
import math

from bearingsim.assemblies.deep_groove.options import _W_REG, WHERE, DeepGrooveOptions
from bearingsim.catalog.geometry import speed_input_bounds
from bearingsim.components.connectors import Flange, RingFrame
from bearingsim.components.dynamic import (
    Ball,
    BallDrag,
    Cage,
    FixedFrame,
    LandGuidance,
    PocketContact,
    RaceContact,
    RingBody,
    RingDrag,
    RingLoad,
)
from bearingsim.components.rolling_element import check_static_rating, load_input_bounds
from bearingsim.components.rotational import Fixed, Inertia, SpeedSource
from bearingsim.language import Assembly, Input, Variable, connect, der
from bearingsim.physics.ball_equilibrium import StaticState, static_state
from bearingsim.physics.bearing_design import BRASS, BearingDesign
from bearingsim.physics.hertz import load_deflection_constant
from bearingsim.physics.lubricant import Lubricant
from bearingsim.physics.materials import STEEL, effective_modulus
from bearingsim.validation import options_object


def _pocket_constant(design: BearingDesign) -> float:
    """Hertz constant of a ball on the concave pocket wall (Rx = Rb, Ry = Rb Rp / (Rp - Rb))."""
    rb = design.ball_radius
    rp = rb + design.cage.pocket_clearance
    return float(load_deflection_constant(rb, rb * rp / (rp - rb), effective_modulus(STEEL,
                                                                                      BRASS)))


class DeepGrooveBallBearing(Assembly):
    """Dynamic model of a single deep-groove ball bearing (see the package docstring).

    Parameters
    ----------
    design : BearingDesign
        From :func:`~bearingsim.physics.bearing_design.bearing_design`.
    lubricant : Lubricant
        Oil, Grease or Dry (traction law, viscosity for film, drag and cage forces).
    options : DeepGrooveOptions, optional
        Every other option, checked when it was built (:class:`~bearingsim.assemblies.
        deep_groove.options.DeepGrooveOptions`: ``massive_balls``, ``speed``, ``loads`` and
        the groups ``rings``, ``film``, ``cage``); default: quasi-static balls driven by the
        input ``shaft_speed``, every load an input.
    name : str
        Instance name.

    Connectors
    ----------
    shaft : Flange (the inner ring's rotation)
    inner_frame : RingFrame (with ``rings.inner_ring="frame"``)
    outer_frame : RingFrame (with ``rings.outer_support="frame"``)
    outer_flange : Flange (with ``rings.outer_ring="flange"``)

    Raises
    ------
    ParameterError
        For options the lubricant cannot honour (:meth:`FilmOptions.for_lubricant`) or a
        constant speed above the bearing's limit, naming ``deep_groove_ball_bearing``.

    Attributes
    ----------
    options : DeepGrooveOptions
        As given, with the lubricant's defaults filled in (``film``, ``cage``).
    start : StaticState or None
        Quasi-static solution of this bearing alone under the constant ``loads`` (relative to
        the outer race), the start values; None without constant loads.

    Variables
    ---------
    w_inner, w_cage, w_epicyclic [rad/s]; slip [1] = 1 - w_cage / w_epicyclic; with
    ``film.ring_drag`` P_resolved [W], the loss resolved at ball level (see
    ``_resolved_loss``)

    Examples
    --------
    >>> from bearingsim.assemblies.deep_groove import (DeepGrooveBallBearing,
    ...                                                 DeepGrooveOptions, RingOptions)
    >>> from bearingsim.physics.bearing_design import bearing_design
    >>> from bearingsim.physics.lubricant import get_lubricant
    >>> bearing = DeepGrooveBallBearing(
    ...     bearing_design("6304"), get_lubricant("ISO VG 32"),
    ...     DeepGrooveOptions(loads={"Fx": 500.0}, rings=RingOptions(drive="flange")))
    >>> len(bearing.ball), bearing.options.cage.pocket_mu
    (7, 0.1)
    """

    def __init__(self, design: BearingDesign, lubricant: Lubricant,
                 options: DeepGrooveOptions | None = None, name="bearing"):
        super().__init__(name)
        options = options_object(options, DeepGrooveOptions, WHERE)
        self.design, self.lubricant = design, lubricant
        self.options = dataclasses.replace(options, film=options.film.for_lubricant(lubricant),
                                           cage=options.cage.for_lubricant(lubricant))
        constant = DeepGrooveOptions.constant_loads(options.loads)
        check_static_rating(self.design.geometry,
                            [constant.get(k, 0.0) for k in ("Fx", "Fy", "Fz")], WHERE)
        self.start: StaticState | None = static_state(
            design, constant, free_tilt=options.rings.free_tilt) if constant else None
        self._build_rings()
        self._build_cage()
        self._build_balls()
        self._connect_balls()
        if options.film.ring_drag:
            self._build_ring_drag()
        self._build_drive()
        self._declare_variables()

    def _build_rings(self) -> None:
        """The shaft flange, the outer ring's support and rotation, and the inner ring's body
        and load (or its frame for an enclosing body)."""
        rings, design = self.options.rings, self.design
        self.shaft = Flange()
        if rings.outer_support == "frame":
            self.outer_frame = RingFrame()
        else:
            self.housing = FixedFrame()
        if rings.outer_ring == "flange":
            self.outer_flange = Flange()
        else:
            self.housing_flange = Fixed()
        if rings.inner_ring == "frame":
            self.inner_frame = RingFrame()
            return
        ring0 = [*self.start.ring] if self.start else [0.0] * 5
        self.ring = RingBody(design.ring_mass, design.ring_tilt_inertia,
                             start=[a + b for a, b in zip(ring0, (*rings.outer_start, 0.0, 0.0),
                                                          strict=True)],
                             free_tilt=rings.free_tilt)
        # a ring held straight takes no moment: no Mx, My inputs that would be ignored
        loads = self.options.loads if rings.free_tilt else {"Mx": 0.0, "My": 0.0,
                                                            **self.options.loads}
        self.load = RingLoad(loads, bounds=load_input_bounds(self.design.geometry))

    def _build_cage(self) -> None:
        """The cage body and its guidance by the outer ring land."""
        cage, opts = self.design.cage, self.options.cage
        self.cage = Cage(cage.mass, cage.inertia)
        self.guidance = LandGuidance(cage.guide_radius, cage.guide_width, cage.guide_clearance,
                                     float(self.lubricant.dynamic_viscosity()),
                                     k_land=_pocket_constant(self.design), mu=opts.land_mu,
                                     damping=opts.cage_damping)

    def _build_balls(self) -> None:
        """For every ball: the ball, its inner and outer race contacts, its cage pocket and
        (with ``film.drag``) its drag, at the start values shifted by ``rings.outer_start``."""
        design, lubricant, film = self.design, self.lubricant, self.options.film
        rings, start = self.options.rings, self.start
        g, cage = design.geometry, design.cage
        nz, dw, dm = g.ball_count, g.ball_diameter, g.pitch_diameter
        offset = rings.outer_start
        eta = float(lubricant.dynamic_viscosity())
        k_pocket = _pocket_constant(design)
        common = dict(ball_diameter=dw, lubricant=lubricant, damping=film.damping,
                      film_damping=film.film_damping, n_slices=film.n_slices,
                      traction_scale=film.traction_scale,
                      rolling_resistance=film.rolling_resistance, e_eff=design.e_eff)
        outer_moving = rings.outer_ring == "flange" or rings.outer_support == "frame"
        balls, inner, outer, pockets, drags = [], [], [], [], []
        for j in range(nz):
            theta = 2.0 * math.pi * j / nz
            r0 = (float(start.r[j]) if start else 0.5 * dm) + offset[0] * math.cos(theta) \
                + offset[1] * math.sin(theta)  # a small shift of the outer race, to first order
            z0 = (float(start.z[j]) if start else 0.0) + offset[2]
            balls.append(Ball(design.ball_mass, design.ball_inertia, r0, 0.5 * dm, theta, z0,
                              massive=self.options.massive_balls))
            inner.append(RaceContact("inner", design.rho_inner, g.fi, k_hertz=design.k_inner,
                                     a1=design.a1_inner, moving=True, rx=design.rx_inner,
                                     ry=design.ry_inner, **common))
            outer.append(RaceContact("outer", design.rho_outer, g.fo, k_hertz=design.k_outer,
                                     a1=design.a1_outer, moving=outer_moving,
                                     rx=design.rx_outer, ry=design.ry_outer, **common))
            pockets.append(PocketContact(j, nz, 0.5 * dm, 0.5 * dw,
                                         0.5 * dw + cage.pocket_clearance, cage.pocket_straight,
                                         cage.web, k_pocket, self.options.cage.pocket_mu, eta,
                                         self.options.cage.cage_damping))
            if film.drag:
                drags.append(BallDrag(dm, dw, film.oil_fraction * float(lubricant.density()),
                                      film.oil_fraction * eta))
        self.ball, self.inner, self.outer, self.pocket = balls, inner, outer, pockets
        if drags:
            self.drag = drags

    def _connect_balls(self) -> None:
        """Race contacts to their rings, pockets to the cage, each ball to its contacts."""
        if self.options.rings.inner_ring == "frame":
            connect(self.inner_frame, *[c.ring for c in self.inner])
        else:
            connect(self.ring.frame, self.load.frame, *[c.ring for c in self.inner])
        connect(self.outer_frame if self.options.rings.outer_support == "frame"
                else self.housing.frame, *[c.ring for c in self.outer])
        connect(self._outer_rotation(), self.guidance.ring, *[c.flange for c in self.outer])
        connect(self.cage.frame, self.guidance.cage, *[p.cage for p in self.pocket])
        drags = getattr(self, "drag", [])
        for j, ball in enumerate(self.ball):
            ports = [ball.frame, self.inner[j].ball, self.outer[j].ball, self.pocket[j].ball]
            connect(*(ports + ([drags[j].ball] if drags else [])))

    def _outer_rotation(self) -> Flange:
        """The outer ring's rotation: its flange, or the housing's."""
        if self.options.rings.outer_ring == "flange":
            return self.outer_flange
        return self.housing_flange.flange

    def _build_ring_drag(self) -> None:
        """The ring drag between the inner and outer ring rotations, and its resolved loss."""
        g = self.design.geometry
        self.ring_drag = RingDrag(g.pitch_diameter, self.lubricant, series=g.series)
        self.P_resolved = Variable(unit="W", description="viscous loss resolved at ball "
                                                         "level (rolling resistance, drag)")
        connect(self.ring_drag.inner, self.shaft)
        connect(self.ring_drag.outer, self._outer_rotation())

    def _build_drive(self) -> None:
        """The inner ring's rotation: a speed source (a constant speed checked against the
        limiting speed, or the input ``shaft_speed``), the ring's polar inertia, or neither."""
        g, speed, rings = self.design.geometry, self.options.speed, self.options.rings
        races = [c.flange for c in self.inner]
        if rings.drive == "speed":
            if isinstance(speed, (int, float)):
                g.check_speed(speed, f"deep_groove_ball_bearing({g.designation})")
            self.drive = SpeedSource(speed)
            connect(self.drive.flange, self.shaft, *races)
            if speed is None:
                self.shaft_speed = Input(0.0, "rad/s", "imposed inner-ring speed", required=True,
                                         **speed_input_bounds(g.limiting_speed))
        elif rings.ring_inertia:
            self.rotor = Inertia(self.design.ring_polar_inertia)
            connect(self.rotor.flange_a, self.shaft, *races)
        else:
            connect(self.shaft, *races)

    def _declare_variables(self) -> None:
        self.w_inner = Variable(unit="rad/s", description="inner-ring speed")
        self.w_outer = Variable(unit="rad/s", description="outer-ring speed")
        self.w_cage = Variable(unit="rad/s", description="cage speed")
        self.w_epicyclic = Variable(unit="rad/s", description="cage speed of pure rolling")
        self.slip = Variable(unit="1", description="cage slip ratio 1 - (w_cage - w_outer) / "
                                                   "(w_epicyclic - w_outer)")

    def equations(self):
        wk = self.w_epicyclic
        ratio = self.design.epicyclic_ratio
        w_o = self.w_outer
        rel_cage, rel_kin = self.w_cage - w_o, wk - w_o
        eqs = [
            self.w_inner == der(self.shaft.phi),
            w_o == (der(self.outer_flange.phi) if hasattr(self, "outer_flange") else 0.0),
            self.w_cage == self.cage.w,
            wk == ratio * self.w_inner + (1.0 - ratio) * w_o,
            self.slip == 1.0 - rel_cage * rel_kin / (rel_kin * rel_kin + _W_REG**2),
        ]
        if hasattr(self, "shaft_speed"):
            eqs.append(self.drive.w_in == self.shaft_speed)
        if hasattr(self, "ring_drag"):
            eqs += [self.P_resolved == self._resolved_loss(),
                    self.ring_drag.P_resolved == self.P_resolved]
        return eqs

    def _resolved_loss(self):
        """Power of the viscous losses resolved at ball level [W].

        The race contacts' rolling resistance ``P_roll``, and the power taken in by the
        elements that stand for the lubricant's drag on balls and cage: the ball drag, the
        pockets (film, and contact damping and friction) and the land guidance (film, and land
        contact). An element's power is the sum over its ports of flow (force or moment *on*
        the element) times the port's velocity; a ball port moves at ``(vr, r w_orbit, vz)``
        and turns at ``(wr, wt, wz)`` in the orbiting frame.
        """
        def ball_port(port, ball):
            return (port.Fr * ball.vr + port.Ft * ball.r * ball.w_orbit + port.Fz * ball.vz
                    + port.Mr * ball.wr + port.Mt * ball.wt + port.Mz * ball.wz)

        cage = self.cage

        def cage_port(port):
            return port.Fx * cage.vx + port.Fy * cage.vy + port.Mz * cage.w

        power = (cage_port(self.guidance.cage) + self.guidance.ring.tau * self.w_outer)
        for contact in (*self.inner, *self.outer):
            if contact.rolling:
                power = power + contact.P_roll
        for ball, pocket in zip(self.ball, self.pocket, strict=True):
            power = power + ball_port(pocket.ball, ball) + cage_port(pocket.cage)
        for ball, drag in zip(self.ball, getattr(self, "drag", []), strict=False):
            power = power + ball_port(drag.ball, ball)
        return power
