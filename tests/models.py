"""Small models shared by the foundation tests."""

from __future__ import annotations

from bearingsim import (
    Assembly,
    Component,
    Connector,
    Flow,
    Parameter,
    Potential,
    Variable,
    connect,
    der,
)
from bearingsim.components.rotational import (
    Damper,
    Fixed,
    IdealGear,
    Inertia,
    Spring,
    SpringDamper,
    TorqueSource,
)


class TwoInertiaDrive(Assembly):
    """Torque T on J1, spring-damper to J2."""

    def __init__(self, J1=1.0, J2=2.0, c=100.0, d=2.0, T=1.0):
        super().__init__("drive")
        self.src = TorqueSource(T)
        self.j1 = Inertia(J1)
        self.sd = SpringDamper(c=c, d=d)
        self.j2 = Inertia(J2)
        connect(self.src.flange, self.j1.flange_a)
        connect(self.j1.flange_b, self.sd.flange_a)
        connect(self.sd.flange_b, self.j2.flange_a)


class RigidPair(Assembly):
    """Two inertias joined rigidly (optionally through an ideal gear), driven by a torque."""

    def __init__(self, J1=1.0, J2=3.0, T=2.0, ratio=None):
        super().__init__("pair")
        self.src = TorqueSource(T)
        self.j1 = Inertia(J1)
        self.j2 = Inertia(J2)
        connect(self.src.flange, self.j1.flange_a)
        if ratio is None:
            connect(self.j1.flange_b, self.j2.flange_a)
        else:
            self.gear = IdealGear(ratio)
            connect(self.j1.flange_b, self.gear.flange_a)
            connect(self.gear.flange_b, self.j2.flange_a)


class DampersInSeries(Assembly):
    """J1 -- D1 -- (massless joint) -- D2 -- J2: an algebraic loop at the joint."""

    def __init__(self, d1=3.0, d2=6.0, w1=10.0):
        super().__init__("series")
        self.j1 = Inertia(1.0, w0=w1)
        self.d1 = Damper(d1)
        self.d2 = Damper(d2)
        self.j2 = Inertia(2.0)
        connect(self.j1.flange_b, self.d1.flange_a)
        connect(self.d1.flange_b, self.d2.flange_a)
        connect(self.d2.flange_b, self.j2.flange_a)


class SpringMassChain(Assembly):
    """Wall -- k1 -- J1 -- k2 -- J2 (2-DOF torsional chain)."""

    def __init__(self, k1=1000.0, k2=500.0, J1=2.0, J2=1.0, phi0=0.0):
        super().__init__("chain")
        self.wall = Fixed()
        self.k1 = Spring(k1)
        self.j1 = Inertia(J1, phi0=phi0)
        self.k2 = Spring(k2)
        self.j2 = Inertia(J2)
        connect(self.wall.flange, self.k1.flange_a)
        connect(self.k1.flange_b, self.j1.flange_a)
        connect(self.j1.flange_b, self.k2.flange_a)
        connect(self.k2.flange_b, self.j2.flange_a)


class Pendulum(Component):
    """Cartesian pendulum: index-3 DAE with the rod force as algebraic unknown."""

    def __init__(self, L=1.0, m=1.0, g=9.81, angle0=0.5):
        import math

        super().__init__("pendulum")
        self.L = Parameter(L, "m", "rod length", low=0.0, low_inclusive=False)
        self.m = Parameter(m, "kg", "mass", low=0.0, low_inclusive=False)
        self.g = Parameter(g, "m/s2", "gravity")
        self.x = Variable(L * math.sin(angle0), "m", "horizontal position")
        self.y = Variable(-L * math.cos(angle0), "m", "vertical position", fixed=False)
        self.vx = Variable(0.0, "m/s", "horizontal speed")
        self.vy = Variable(0.0, "m/s", "vertical speed", fixed=False)
        self.F = Variable(m * g, "N", "rod force", fixed=False)

    def equations(self):
        return [
            der(self.x) == self.vx,
            der(self.y) == self.vy,
            self.m * der(self.vx) == -self.F * self.x / self.L,
            self.m * der(self.vy) == -self.F * self.y / self.L - self.m * self.g,
            self.x**2 + self.y**2 == self.L**2,
        ]


class Pin(Connector):
    v = Potential(unit="V", description="potential")
    i = Flow(unit="A", description="current into the component")


class Resistor(Component):
    def __init__(self, R=1.0, name=None):
        super().__init__(name)
        self.R = Parameter(R, "Ohm", "resistance", low=0.0, low_inclusive=False)
        self.p = Pin()
        self.n = Pin()

    def equations(self):
        return [self.p.v - self.n.v == self.R * self.p.i, self.p.i + self.n.i == 0]
