"""Load-independent viscous friction between the two rings of a ball-level bearing."""

from __future__ import annotations

from bearingsim import symbolic as op
from bearingsim.components.connectors import Flange
from bearingsim.language import Component, Input, Parameter, Variable, der
from bearingsim.physics.friction import palmgren_m0
from bearingsim.physics.lubricant import KINEMATIC_VISCOSITY_RANGE, Lubricant

__all__ = ["RingDrag"]

_M_SMOOTH = 1e-6
"""Width [N m] of the smooth non-negative limit of the remaining drag torque."""


class RingDrag(Component):
    """Viscous (churning) torque of the lubricant between an inner and an outer ring flange.

    The torque level represents all load-independent, viscous losses of a bearing by
    Palmgren's ``M0 = 1e-7 f0 (nu n)^(2/3) dm^3`` [N mm]
    (:func:`~bearingsim.physics.friction.palmgren_m0`; ``f0`` from the lubricant, which carries
    the lubrication method and, for grease, the fill fraction through
    :meth:`~bearingsim.physics.lubricant.Lubricant.palmgren_f0`). A ball-level model resolves
    part of that loss itself: the EHL rolling resistance at the race contacts, the films of the
    cage pockets and of the guiding land and, if present, the drag of the balls in the oil-air
    mixture. This element supplies the rest, so that the total viscous loss of the layer
    equals the torque level's::

        M = -sign(w_rel) < M0(|w_rel|) - P_resolved / |w_rel| >

    ``P_resolved`` [W] is the power of the losses resolved at ball level (an input, bound by
    the bearing assembly to the power of those elements);
    ``< >`` is a smooth non-negative limit (width 1e-6 N m). The reaction acts on the outer
    flange: a turning inner ring drags the outer ring forwards, as the lubricant sheared
    between them does. What each term represents: ``P_resolved`` the losses whose forces act
    on the balls and the cage (and through them on the races and the guiding ring), this
    element the churning of the lubricant between the rings that the ball model does not
    resolve. If the resolved losses exceed ``M0`` this element vanishes and the layer's viscous
    loss is the resolved one.

    Parameters
    ----------
    pitch_diameter : float
        dm [m], > 0.
    lubricant : Lubricant
        Sets ``nu`` (base oil, operating temperature) and ``f0`` (parameters afterwards).
    bearing_type : str
        Key of the Palmgren f0 table (default deep-groove ball bearing).
    omega_reg : float
        Regularization speed of the sign and of ``|w_rel|`` [rad/s], > 0.
    series : str, optional
        Catalogue series (e.g. ``"63"``) for f0 by series
        (:data:`~bearingsim.physics.lubrication.PALMGREN_F0_BY_SERIES`).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    inner, outer : Flange

    Variables
    ---------
    w_rel [rad/s] inner relative to outer ring; M [N m] torque on the inner ring; M0 [N m]
    Palmgren's load-independent torque magnitude; P_loss [W] this element's loss; input
    P_resolved [W]
    """

    def __init__(self, pitch_diameter: float, lubricant: Lubricant,
                 bearing_type: str = "deep_groove_ball", omega_reg: float = 0.1,
                 series: str | None = None, name=None):
        super().__init__(name)
        self.dm = Parameter(pitch_diameter, "m", "pitch diameter", low=0.0, low_inclusive=False)
        self.nu = Parameter(float(lubricant.kinematic_viscosity()), "m2/s",
                            "kinematic viscosity of the (base) oil", low=0.0,
                            high=KINEMATIC_VISCOSITY_RANGE[1])
        self.f0 = Parameter(float(lubricant.palmgren_f0(bearing_type, series)), "1",
                            "Palmgren load-independent friction factor f0", low=0.0)
        self.omega_reg = Parameter(omega_reg, "rad/s", "regularization speed", low=0.0,
                                   low_inclusive=False)
        self.inner = Flange()
        self.outer = Flange()
        self.P_resolved = Input(0.0, "W", "viscous loss resolved at ball level")
        self.w_rel = Variable(unit="rad/s", description="inner-ring speed relative to outer ring")
        self.M = Variable(unit="N.m", description="drag torque on the inner ring")
        self.M0 = Variable(unit="N.m", description="Palmgren load-independent torque")
        self.P_loss = Variable(unit="W", description="loss of this element")

    def equations(self):
        speed = op.smooth_abs(self.w_rel, self.omega_reg)
        remaining = op.smooth_max0(self.M0 - self.P_resolved / speed, _M_SMOOTH)
        return [
            self.w_rel == der(self.inner.phi) - der(self.outer.phi),
            self.M0 == palmgren_m0(self.nu, speed, self.dm, self.f0),
            self.M == -remaining * self.w_rel / speed,
            self.inner.tau == -self.M,
            self.outer.tau == self.M,
            self.P_loss == -self.M * self.w_rel,
        ]
