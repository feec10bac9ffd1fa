"""The deep-groove ball bearing with ball and cage dynamics (:class:`DeepGrooveBallBearing`:
quasi-static or massive balls, traction, cage pockets and land, film damping)."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from bearingsim.assemblies.deep_groove.options import _W_REG, FILM_DAMPING
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
from bearingsim.components.dynamic.ring import check_loads
from bearingsim.components.rotational import Fixed, Inertia, SpeedSource
from bearingsim.errors import ParameterError
from bearingsim.language import Assembly, Input, Variable, connect, der
from bearingsim.physics.ball_equilibrium import StaticState, static_state
from bearingsim.physics.bearing_design import BRASS, BearingDesign
from bearingsim.physics.hertz import STEEL, effective_modulus, load_deflection_constant
from bearingsim.physics.lubricant import Lubricant
from bearingsim.validation import (
    check_choice,
    check_number,
    check_range,
)


def _pocket_constant(design: BearingDesign) -> float:
    """Hertz constant of a ball on the concave pocket wall (Rx = Rb, Ry = Rb Rp / (Rp - Rb))."""
    rb = design.ball_radius
    rp = rb + design.cage.pocket_clearance
    return float(load_deflection_constant(rb, rb * rp / (rp - rb), effective_modulus(STEEL,
                                                                                      BRASS)))


class DeepGrooveBallBearing(Assembly):
    """Dynamic model of a single deep-groove ball bearing (see the module docstring).

    Parameters
    ----------
    design : BearingDesign
        From :func:`~bearingsim.physics.bearing_design.bearing_design`.
    lubricant : Lubricant
        Oil, Grease or Dry (traction law, viscosity for film, drag and cage forces).
    massive_balls : bool
        Ball radial/axial motion with inertia (True) or quasi-static (False).
    speed : callable or float or None
        Inner-ring speed [rad/s] imposed through a speed source (``None``: an input
        ``shaft_speed``); ignored with ``drive="flange"``.
    drive : {"speed", "flange"}
        ``"flange"`` leaves ``shaft`` (with the ring's polar inertia) for the user to drive.
    ring_inertia : bool
        With ``drive="flange"``: whether the inner ring's polar inertia belongs to this bearing
        (False when an enclosing assembly models the ring's rotation, e.g. a nested bearing's
        middle ring).
    outer_ring : {"fixed", "flange"}
        ``"flange"``: the outer ring may rotate (its translations stay fixed); its rotation is
        the connector ``outer_flange`` (a nested bearing's middle ring). The epicyclic cage
        speed and the slip then use both ring speeds.
    loads : dict
        ``Fx, Fy, Fz`` [N], ``Mx, My`` [N m] on the inner ring: finite constants, functions of
        time or ``None`` for inputs (missing keys are inputs with default 0); any other key
        raises :class:`~bearingsim.errors.ParameterError`.
    free_tilt : bool
        Whether the inner ring tilts under the moments ``Mx, My``. With False the shaft holds
        it straight and takes the moments as a reaction: ``loads`` may then give ``Mx, My``
        only as 0 (a constant moment, a function of time or ``None`` raises
        :class:`~bearingsim.errors.ParameterError`; missing keys stay inputs, without effect).
    inner_ring : {"body", "frame"}
        ``"body"``: the inner ring is a 5-DOF ``RingBody`` (``ring``) loaded by ``loads``
        (``load``); ``"frame"``: no ring body and no load, the inner race contacts' ring frame
        is the connector ``inner_frame`` for an enclosing body (a nested bearing's middle ring);
        ``loads`` must then be constants and only set the start values (the load the enclosing
        body passes on).
    outer_support : {"housing", "frame"}
        ``"housing"``: the outer race is fixed (``housing``); ``"frame"``: the outer race
        contacts' ring frame is the connector ``outer_frame`` for an enclosing body that may
        translate (the outer race contacts then use its velocity).
    outer_start : sequence of 3 float
        With ``outer_support="frame"``: start displacement (x, y, z) of the outer race [m]; the
        inner ring and the balls start shifted by it.
    damping : float
        Hunt-Crossley coefficient of the race contacts [s/m], >= 0.
    film_damping : float, optional
        Film damping time constant of the race contacts [s], >= 0 (damping = ``film_damping``
        times the tangent contact stiffness, see
        :class:`~bearingsim.components.dynamic.RaceContact`); default :data:`FILM_DAMPING`
        with a viscous lubricant, 0 dry. A value given with a ``Dry`` lubricant is applied
        (as stiffness-proportional contact damping).
    n_slices : int
        ``2 n + 1`` traction slices per contact, an integer >= 0.
    drag : bool, optional
        Ball drag in the oil-air mixture; default: on with a viscous lubricant, off with
        ``Dry``. ``drag=True`` with a ``Dry`` lubricant raises
        :class:`~bearingsim.errors.ParameterError`.
    oil_fraction : float
        Oil volume fraction of the cavity mixture [-] (drag), in (0, 1].
    traction_scale : float
        Multiplier of the race traction [-], >= 0 (0: frictionless races).
    pocket_mu, land_mu : float, optional
        Coulomb coefficients of pocket and land contacts [-], in [0, 2]; default the ``mu``
        of a ``Dry`` lubricant, else 0.1.
    cage_damping : float
        Hunt-Crossley coefficient of the pocket and land contacts [s/m], >= 0.
    rolling_resistance : bool
        EHL hydrodynamic rolling resistance at every race contact (viscous lubricants only;
        see :class:`~bearingsim.components.dynamic.RaceContact`). Default False.
    ring_drag : bool
        A :class:`~bearingsim.components.dynamic.RingDrag` between the inner and outer ring
        rotations: the load-independent Palmgren ``M0`` less the viscous losses resolved at
        ball level (rolling resistance, ball drag, cage pockets and land), so that the
        bearing's viscous loss equals the torque level's. Default False.

    Connectors
    ----------
    shaft : Flange (the inner ring's rotation)
    inner_frame : RingFrame (with ``inner_ring="frame"``)
    outer_frame : RingFrame (with ``outer_support="frame"``)

    Raises
    ------
    ParameterError
        For a choice, load, option or range outside the ones above, naming
        ``deep_groove_ball_bearing``, the argument, its unit and valid range.

    Attributes
    ----------
    start : StaticState or None
        Quasi-static solution of this bearing alone under the constant ``loads`` (relative to
        the outer race), the start values; None without constant loads.

    Variables
    ---------
    w_inner, w_cage, w_epicyclic [rad/s]; slip [1] = 1 - w_cage / w_epicyclic; with
    ``ring_drag`` P_resolved [W], the loss resolved at ball level (see ``_resolved_loss``)
    """

    def __init__(self, design: BearingDesign, lubricant: Lubricant, massive_balls: bool = False,
                 speed: Callable | float | None = None, drive: str = "speed",
                 loads: dict[str, Any] | None = None, free_tilt: bool = False,
                 damping: float = 1.0, film_damping: float | None = None,
                 n_slices: int = 2, drag: bool | None = None,
                 oil_fraction: float = 0.05, traction_scale: float = 1.0,
                 pocket_mu: float | None = None, land_mu: float | None = None,
                 cage_damping: float = 10.0, outer_ring: str = "fixed",
                 rolling_resistance: bool = False, ring_drag: bool = False,
                 ring_inertia: bool = True, inner_ring: str = "body",
                 outer_support: str = "housing",
                 outer_start: tuple[float, float, float] = (0.0, 0.0, 0.0), name="bearing"):
        super().__init__(name)
        where = "deep_groove_ball_bearing"
        check_choice(drive, "drive", ("speed", "flange"), where)
        check_choice(outer_ring, "outer_ring", ("fixed", "flange"), where)
        check_choice(inner_ring, "inner_ring", ("body", "frame"), where)
        check_choice(outer_support, "outer_support", ("housing", "frame"), where)
        offset = tuple(float(v) for v in outer_start)
        if len(offset) != 3 or (outer_support == "housing" and any(offset)):
            raise ParameterError(f"deep_groove_ball_bearing: outer_start must be (x, y, z) [m], "
                                 f"nonzero only with outer_support='frame', got {outer_start!r}")
        check_range(oil_fraction, "oil_fraction", "-", 0.0, 1.0, low_inclusive=False,
                    where=where)
        # the components check these too, but before they are named; name them here
        for key, value, unit, high in (("damping", damping, "s/m", None),
                                       ("film_damping", film_damping, "s", None),
                                       ("traction_scale", traction_scale, "1", None),
                                       ("pocket_mu", pocket_mu, "1", 2.0),
                                       ("land_mu", land_mu, "1", 2.0),
                                       ("cage_damping", cage_damping, "s/m", None)):
            if value is not None:
                check_number(value, key, unit, high, where)
        g, cage = design.geometry, design.cage
        self.design, self.lubricant = design, lubricant
        loads = check_loads(loads, where)
        if not free_tilt:
            for key in ("Mx", "My"):
                if key in loads and loads[key] != 0.0:
                    raise ParameterError(
                        f"{where}: loads[{key!r}] = {loads[key]!r} [N.m] is not applied with "
                        f"free_tilt=False: the shaft holds the inner ring straight and takes "
                        f"the moments as a reaction; give free_tilt=True to tilt the ring, or "
                        f"{key} = 0 (or leave it out)")
        constant = {k: v for k, v in loads.items() if isinstance(v, (int, float))}
        if inner_ring == "frame" and len(constant) != len(loads):
            raise ParameterError("deep_groove_ball_bearing: with inner_ring='frame' the loads "
                                 "only set the start values and must be constants")
        start = static_state(design, constant, free_tilt=free_tilt) if constant else None
        self.start: StaticState | None = start
        eta = float(lubricant.dynamic_viscosity())
        if (rolling_resistance or ring_drag) and not lubricant.is_viscous:
            raise ParameterError(f"deep_groove_ball_bearing: rolling_resistance and ring_drag "
                                 f"need a viscous lubricant, got {lubricant.describe()}")
        if film_damping is None:
            film_damping = FILM_DAMPING if lubricant.is_viscous else 0.0
        if drag and not lubricant.is_viscous:
            raise ParameterError(f"{where}: drag=True needs a viscous lubricant (the ball drag "
                                 f"is that of an oil-air mixture), got {lubricant.describe()}; "
                                 f"leave drag out or give drag=False")
        drag = lubricant.is_viscous if drag is None else bool(drag)
        mu_dry = lubricant.contact_friction
        pocket_mu = mu_dry if pocket_mu is None else pocket_mu
        land_mu = mu_dry if land_mu is None else land_mu
        nz, dw, dm = g.ball_count, g.ball_diameter, g.pitch_diameter

        self.shaft = Flange()
        if outer_support == "frame":
            self.outer_frame = RingFrame()
        else:
            self.housing = FixedFrame()
        rotating_outer = outer_ring == "flange"
        if rotating_outer:
            self.outer_flange = Flange()
        else:
            self.housing_flange = Fixed()
        if inner_ring == "frame":
            self.inner_frame = RingFrame()
        else:
            ring0 = [*start.ring] if start else [0.0] * 5
            self.ring = RingBody(design.ring_mass, design.ring_tilt_inertia,
                                 start=[a + b for a, b in zip(ring0, (*offset, 0.0, 0.0),
                                                              strict=True)],
                                 free_tilt=free_tilt)
            self.load = RingLoad(loads)
        self.cage = Cage(cage.mass, cage.inertia)
        self.guidance = LandGuidance(cage.guide_radius, cage.guide_width, cage.guide_clearance,
                                     eta, k_land=_pocket_constant(design), mu=land_mu,
                                     damping=cage_damping)
        balls, inner, outer, pockets, drags = [], [], [], [], []
        k_pocket = _pocket_constant(design)
        for j in range(nz):
            theta = 2.0 * math.pi * j / nz
            r0 = (float(start.r[j]) if start else 0.5 * dm) + offset[0] * math.cos(theta) \
                + offset[1] * math.sin(theta)  # a small shift of the outer race, to first order
            z0 = (float(start.z[j]) if start else 0.0) + offset[2]
            balls.append(Ball(design.ball_mass, design.ball_inertia, r0, 0.5 * dm, theta, z0,
                              massive=massive_balls))
            common = dict(ball_diameter=dw, lubricant=lubricant, damping=damping,
                          film_damping=film_damping, n_slices=n_slices,
                          traction_scale=traction_scale, rolling_resistance=rolling_resistance,
                          e_eff=design.e_eff)
            inner.append(RaceContact("inner", design.rho_inner, g.fi, k_hertz=design.k_inner,
                                     a1=design.a1_inner, moving=True, rx=design.rx_inner,
                                     ry=design.ry_inner, **common))
            outer.append(RaceContact("outer", design.rho_outer, g.fo, k_hertz=design.k_outer,
                                     a1=design.a1_outer,
                                     moving=rotating_outer or outer_support == "frame",
                                     rx=design.rx_outer, ry=design.ry_outer, **common))
            pockets.append(PocketContact(j, nz, 0.5 * dm, 0.5 * dw,
                                         0.5 * dw + cage.pocket_clearance, cage.pocket_straight,
                                         cage.web, k_pocket, pocket_mu, eta, cage_damping))
            if drag:
                drags.append(BallDrag(dm, dw, oil_fraction * float(lubricant.density()),
                                      oil_fraction * eta))
        self.ball = balls
        self.inner = inner
        self.outer = outer
        self.pocket = pockets
        if drags:
            self.drag = drags
        if inner_ring == "frame":
            connect(self.inner_frame, *[c.ring for c in inner])
        else:
            connect(self.ring.frame, self.load.frame, *[c.ring for c in inner])
        connect(self.outer_frame if outer_support == "frame" else self.housing.frame,
                *[c.ring for c in outer])
        outer_rotation = self.outer_flange if rotating_outer else self.housing_flange.flange
        connect(outer_rotation, self.guidance.ring, *[c.flange for c in outer])
        connect(self.cage.frame, self.guidance.cage, *[p.cage for p in pockets])
        for j in range(nz):
            ports = [balls[j].frame, inner[j].ball, outer[j].ball, pockets[j].ball]
            connect(*(ports + ([drags[j].ball] if drags else [])))
        if ring_drag:
            self.ring_drag = RingDrag(dm, lubricant, series=g.series)
            self.P_resolved = Variable(unit="W", description="viscous loss resolved at ball "
                                                             "level (rolling resistance, drag)")
            connect(self.ring_drag.inner, self.shaft)
            connect(self.ring_drag.outer, outer_rotation)
        if drive == "speed":
            if isinstance(speed, (int, float)):
                g.check_speed(speed, f"deep_groove_ball_bearing({g.designation})")
            self.drive = SpeedSource(speed)
            connect(self.drive.flange, self.shaft, *[c.flange for c in inner])
            if speed is None:
                self.shaft_speed = Input(0.0, "rad/s", "imposed inner-ring speed", required=True,
                                         **speed_input_bounds(g.limiting_speed))
        elif ring_inertia:
            self.rotor = Inertia(design.ring_polar_inertia)
            connect(self.rotor.flange_a, self.shaft, *[c.flange for c in inner])
        else:
            connect(self.shaft, *[c.flange for c in inner])
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
