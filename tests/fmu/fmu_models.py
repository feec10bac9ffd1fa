"""Small assemblies for the FMU tests: inputs at the root, a stiff chain, a coupled pair."""

from __future__ import annotations

import casadi as ca

from bearingsim import Assembly, Component, Input, Parameter, Variable, connect, der
from bearingsim.components.rotational import (
    Damper,
    Fixed,
    Inertia,
    SpeedSource,
    SpringDamper,
    TorqueSensor,
    TorqueSource,
)


class DrivenInertia(Assembly):
    """A rotor driven by an input torque against an input load torque, with viscous bearing
    friction to ground. Output: rotor.w."""

    def __init__(self, J=0.5, d=0.05, w0=0.0):
        super().__init__("driven")
        self.tau_drive = Input(0.0, "N.m", "driving torque")
        self.tau_load = Input(0.0, "N.m", "load torque against the rotor")
        self.drive = TorqueSource(None)
        self.load = TorqueSource(None)
        self.rotor = Inertia(J, w0=w0)
        self.friction = Damper(d)
        self.ground = Fixed()
        connect(self.drive.flange, self.rotor.flange_a)
        connect(self.rotor.flange_b, self.friction.flange_a, self.load.flange)
        connect(self.friction.flange_b, self.ground.flange)

    def equations(self):
        return [self.drive.tau_in == self.tau_drive, self.load.tau_in == -self.tau_load]


class SpeedDrivenLoad(Assembly):
    """A load inertia behind a spring-damper coupling whose shaft turns at an input speed.
    Output: sensor.tau, the torque the shaft delivers into the coupling."""

    def __init__(self, J=2.0, c=50.0, d=1.0):
        super().__init__("load")
        self.w_in = Input(0.0, "rad/s", "shaft speed")
        self.shaft = SpeedSource(None)
        self.sensor = TorqueSensor()
        self.coupling = SpringDamper(c, d)
        self.inertia = Inertia(J)
        connect(self.shaft.flange, self.sensor.flange_a)
        connect(self.sensor.flange_b, self.coupling.flange_a)
        connect(self.coupling.flange_b, self.inertia.flange_a)

    def equations(self):
        return [self.shaft.w_in == self.w_in]


class CoupledDrive(Assembly):
    """The monolithic counterpart of DrivenInertia + SpeedDrivenLoad."""

    def __init__(self, J=0.5, d=0.05, J_load=2.0, c=50.0, d_c=1.0, torque=2.0):
        super().__init__("coupled")
        self.drive = TorqueSource(torque)
        self.rotor = Inertia(J)
        self.friction = Damper(d)
        self.ground = Fixed()
        self.coupling = SpringDamper(c, d_c)
        self.inertia = Inertia(J_load)
        connect(self.drive.flange, self.rotor.flange_a)
        connect(self.rotor.flange_b, self.friction.flange_a, self.coupling.flange_a)
        connect(self.friction.flange_b, self.ground.flange)
        connect(self.coupling.flange_b, self.inertia.flange_a)


class StiffChain(Assembly):
    """An input torque drives a chain of ``n`` small inertias joined by very stiff
    spring-dampers (eigenvalues near -1e5 1/s); the chain drives a large load inertia through a
    soft coupling (a slow oscillation of about 0.5 Hz on top of the spin-up)."""

    def __init__(self, n=5, J=1e-3, c=1e7, d=50.0, J_load=1.0, c_load=10.0, d_load=0.5,
                 torque=1.0):
        super().__init__("stiff")
        self.tau = Input(torque, "N.m", "driving torque")
        self.src = TorqueSource(None)
        self.mass = [Inertia(J) for _ in range(n)]
        self.link = [SpringDamper(c, d) for _ in range(n - 1)]
        self.coupling = SpringDamper(c_load, d_load)
        self.load = Inertia(J_load)
        connect(self.src.flange, self.mass[0].flange_a)
        for i in range(1, n):
            connect(self.mass[i - 1].flange_b, self.link[i - 1].flange_a)
            connect(self.link[i - 1].flange_b, self.mass[i].flange_a)
        connect(self.mass[n - 1].flange_b, self.coupling.flange_a)
        connect(self.coupling.flange_b, self.load.flange_a)

    def equations(self):
        return [self.src.tau_in == self.tau]


class Sqrt(Component):
    """der(x) = sqrt(1 - t): not finite (NaN) after t = 1 s."""

    def __init__(self):
        super().__init__("sqrt")
        self.x = Variable(0.0, "1", "integral of sqrt(1 - t)")

    def equations(self):
        return [der(self.x) == ca.sqrt(1.0 - self.time)]


class ImplicitDecay(Component):
    """der(x) = -k z with z + z^3 = x: a nonlinear algebraic loop solved by Newton in the
    generated code."""

    def __init__(self, k=2.0):
        super().__init__("implicit")
        self.k = Parameter(k, "1/s", "decay rate", low=0.0)
        self.x = Variable(2.0, "1", "decaying quantity")
        self.z = Variable(1.0, "1", "root of z + z^3 = x", fixed=False)

    def equations(self):
        return [der(self.x) == -self.k * self.z, self.z + self.z**3 == self.x]
