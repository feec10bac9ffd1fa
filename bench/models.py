"""Benchmark models: a torsional chain of N inertia / spring-damper pairs."""

from __future__ import annotations

from collections.abc import Callable

import casadi as ca

from bearingsim import Assembly, connect
from bearingsim.components.rotational import Fixed, Inertia, Spring, SpringDamper, TorqueSource

__all__ = ["TorsionChain", "sine_torque"]


def sine_torque(amplitude: float = 10.0, omega: float = 5.0) -> Callable[[ca.SX], ca.SX]:
    """A symbolic torque ``amplitude * sin(omega t)`` [N m]."""

    def torque(t: ca.SX) -> ca.SX:
        return amplitude * ca.sin(omega * t)

    return torque


class TorsionChain(Assembly):
    """Torque source -- J -- k -- J -- k ... -- J -- k -- (Fixed): N inertia-spring pairs.

    Parameters
    ----------
    n : int
        Number of inertia / spring(-damper) pairs (2 n states).
    J : float
        Inertia of every body [kg m^2].
    c : float
        Stiffness of every spring [N m/rad].
    d : float or None
        Damping of every spring-damper [N m s/rad]; None uses plain springs.
    torque : callable or float
        Driving torque at the free end: a constant or a symbolic function of time [N m].
    fixed : bool
        Fix the far end of the last spring to the ground.
    """

    def __init__(self, n: int, J: float = 1.0, c: float = 1.0e4, d: float | None = 50.0,
                 torque: Callable[[ca.SX], ca.SX] | float = 1.0, fixed: bool = True,
                 name: str = "chain"):
        super().__init__(name)
        self.src = TorqueSource(torque)
        self.body = [Inertia(J) for _ in range(n)]
        self.spring = [Spring(c) if d is None else SpringDamper(c=c, d=d) for _ in range(n)]
        connect(self.src.flange, self.body[0].flange_a)
        for i in range(n):
            connect(self.body[i].flange_b, self.spring[i].flange_a)
            if i + 1 < n:
                connect(self.spring[i].flange_b, self.body[i + 1].flange_a)
        if fixed:
            self.ground = Fixed()
            connect(self.spring[n - 1].flange_b, self.ground.flange)
