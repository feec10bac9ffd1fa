"""1-D rotational mechanics (in the manner of Modelica.Mechanics.Rotational).

Sign convention: a flange's torque ``tau`` is the cut torque acting *on* the component that owns
the flange; connected flanges share ``phi`` and their torques sum to zero.
"""

from __future__ import annotations

from collections.abc import Callable

import casadi as ca

from bearingsim.components.connectors import Flange
from bearingsim.language import (
    Component,
    Input,
    Parameter,
    Variable,
    der,
)
from bearingsim.language.symbols import of_time
from bearingsim.validation import check_quantity, check_range

__all__ = [
    "Flange",
    "Inertia",
    "PartialTwoFlanges",
    "PartialCompliant",
    "Spring",
    "Damper",
    "SpringDamper",
    "Fixed",
    "TorqueSource",
    "SpeedSource",
    "IdealGear",
    "SpeedSensor",
    "TorqueSensor",
]

TimeFunction = Callable[[ca.SX], ca.SX]


class PartialTwoFlanges(Component):
    """Base of elements between two flanges, ``flange_a`` and ``flange_b``.

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    flange_a, flange_b : Flange
    """

    def __init__(self, name=None):
        super().__init__(name)
        self.flange_a = Flange()
        self.flange_b = Flange()


class Inertia(PartialTwoFlanges):
    """Rigid body rotating about a fixed axis.

    Parameters
    ----------
    J : float
        Moment of inertia [kg m^2], > 0.
    phi0, w0 : float
        Initial angle [rad] and angular speed [rad/s].
    name : str
        Instance name (the prefix of its variables' dotted names).

    Variables
    ---------
    phi [rad], w [rad/s], a [rad/s^2]

    Connectors
    ----------
    flange_a, flange_b : Flange
    """

    def __init__(self, J: float = 1.0, phi0: float = 0.0, w0: float = 0.0, name=None):
        super().__init__(name)
        self.J = Parameter(J, "kg.m2", "moment of inertia", low=0.0, low_inclusive=False)
        self.phi = Variable(phi0, "rad", "absolute rotation angle")
        self.w = Variable(w0, "rad/s", "absolute angular speed")

    def equations(self):
        return [
            self.phi == self.flange_a.phi,
            self.phi == self.flange_b.phi,
            der(self.phi) == self.w,
            self.J * der(self.w) == self.flange_a.tau + self.flange_b.tau,
        ]


class PartialCompliant(PartialTwoFlanges):
    """Base of elements that transmit a torque ``tau`` from flange_a to flange_b.

    Variables
    ---------
    phi_rel [rad] : flange_b.phi - flange_a.phi
    tau [N m] : torque acting on the element at flange_b (at flange_a: -tau)

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, name=None):
        super().__init__(name)
        self.phi_rel = Variable(unit="rad", description="relative rotation angle")
        self.tau = Variable(unit="N.m", description="transmitted torque")

    def compliant_equations(self):
        """The two-flange relations every subclass includes.

        Returns
        -------
        list
            The relations of the relative angle and the flange torques.
        """
        return [
            self.phi_rel == self.flange_b.phi - self.flange_a.phi,
            self.flange_b.tau == self.tau,
            self.flange_a.tau == -self.tau,
        ]


class Spring(PartialCompliant):
    """Linear torsional spring.

    Parameters
    ----------
    c : float
        Stiffness [N m/rad], > 0.
    phi_rel0 : float
        Unstretched relative angle [rad].
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, c: float = 1.0, phi_rel0: float = 0.0, name=None):
        super().__init__(name)
        self.c = Parameter(c, "N.m/rad", "spring constant", low=0.0, low_inclusive=False)
        self.phi_rel0 = Parameter(phi_rel0, "rad", "unstretched spring angle")

    def equations(self):
        return self.compliant_equations() + [
            self.tau == self.c * (self.phi_rel - self.phi_rel0)
        ]


class Damper(PartialCompliant):
    """Linear torsional damper.

    Parameters
    ----------
    d : float
        Damping constant [N m s/rad], >= 0.
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, d: float = 1.0, name=None):
        super().__init__(name)
        self.d = Parameter(d, "N.m.s/rad", "damping constant", low=0.0)
        self.w_rel = Variable(unit="rad/s", description="relative angular speed")

    def equations(self):
        return self.compliant_equations() + [
            self.w_rel == der(self.phi_rel),
            self.tau == self.d * self.w_rel,
        ]


class SpringDamper(PartialCompliant):
    """Linear spring and damper in parallel.

    Parameters
    ----------
    c : float
        Stiffness [N m/rad], > 0.
    d : float
        Damping [N m s/rad], >= 0.
    phi_rel0 : float
        Unstretched relative angle [rad].
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, c: float = 1.0, d: float = 0.0, phi_rel0: float = 0.0, name=None):
        super().__init__(name)
        self.c = Parameter(c, "N.m/rad", "spring constant", low=0.0, low_inclusive=False)
        self.d = Parameter(d, "N.m.s/rad", "damping constant", low=0.0)
        self.phi_rel0 = Parameter(phi_rel0, "rad", "unstretched spring angle")
        self.w_rel = Variable(unit="rad/s", description="relative angular speed")

    def equations(self):
        return self.compliant_equations() + [
            self.w_rel == der(self.phi_rel),
            self.tau == self.c * (self.phi_rel - self.phi_rel0) + self.d * self.w_rel,
        ]


class Fixed(Component):
    """Flange fixed at an angle.

    Parameters
    ----------
    phi0 : float
        Fixed angle [rad].
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, phi0: float = 0.0, name=None):
        super().__init__(name)
        self.phi0 = Parameter(phi0, "rad", "fixed angle")
        self.flange = Flange()

    def equations(self):
        return [self.flange.phi == self.phi0]


class TorqueSource(Component):
    """Drives its flange with a torque given by an input or a function of time.

    Parameters
    ----------
    torque : callable or float or None
        ``torque(t)`` built from CasADi/`bearingsim.symbolic` math (kept symbolic), a constant, or
        ``None`` for an input ``tau_in`` [N m].
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, torque: TimeFunction | float | None = None, name=None):
        super().__init__(name)
        self.flange = Flange()
        self._torque = _check_signal(torque, "torque", "N.m", self)
        if torque is None:
            self.tau_in = Input(0.0, unit="N.m", description="driving torque")

    def equations(self):
        tau = _signal(self._torque, self, "tau_in")
        return [self.flange.tau == -tau]


class SpeedSource(Component):
    """Forces its flange to turn at a speed given by an input or a function of time.

    Parameters
    ----------
    speed : callable or float or None
        ``speed(t)`` [rad/s] (symbolic), a constant, or ``None`` for an input ``w_in``.
    phi0 : float
        Initial angle [rad].
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, speed: TimeFunction | float | None = None, phi0: float = 0.0, name=None):
        super().__init__(name)
        self.flange = Flange()
        self._speed = _check_signal(speed, "speed", "rad/s", self)
        self.phi = Variable(phi0, "rad", "angle of the driven flange")
        self.w = Variable(unit="rad/s", description="imposed angular speed")
        if speed is None:
            self.w_in = Input(0.0, unit="rad/s", description="imposed angular speed")

    def equations(self):
        return [
            self.w == _signal(self._speed, self, "w_in"),
            der(self.phi) == self.w,
            self.flange.phi == self.phi,
        ]


class IdealGear(PartialTwoFlanges):
    """Ideal gear without inertia: ``phi_a = ratio * phi_b``, power conserving.

    Parameters
    ----------
    ratio : float
        Transmission ratio flange_a/flange_b [1], non-zero.
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, ratio: float = 1.0, name=None):
        super().__init__(name)
        self.ratio = Parameter(ratio, "1", "transmission ratio phi_a/phi_b")
        if ratio == 0:
            from bearingsim.errors import ParameterError

            raise ParameterError(f"{type(self).__name__}: ratio [1] must be non-zero")

    def equations(self):
        return [
            self.flange_a.phi == self.ratio * self.flange_b.phi,
            0 == self.ratio * self.flange_a.tau + self.flange_b.tau,
        ]


class SpeedSensor(Component):
    """Measures the absolute angular speed ``w`` [rad/s] of its flange.

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, name=None):
        super().__init__(name)
        self.flange = Flange()
        self.w = Variable(unit="rad/s", description="measured angular speed")

    def equations(self):
        return [self.w == der(self.flange.phi), self.flange.tau == 0]


class TorqueSensor(PartialTwoFlanges):
    """Measures the torque ``tau`` [N m] passed from flange_a to flange_b.

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, name=None):
        super().__init__(name)
        self.tau = Variable(unit="N.m", description="measured torque")

    def equations(self):
        return [
            self.flange_a.phi == self.flange_b.phi,
            self.flange_a.tau == self.tau,
            self.flange_b.tau == -self.tau,
        ]


def _check_signal(source, name: str, unit: str, component: Component):
    """Validate a constant signal argument, a number in ``unit`` or with a unit ("0.05 N m"),
    as a float in ``unit`` (callables are checked when simulated)."""
    if source is None or callable(source):
        return source
    return float(check_quantity(source, name, unit, where=f"{type(component).__name__}"))


def _signal(source, component: Component, input_name: str, unit: str = "-"):
    """The symbolic value of a signal: its input ``input_name``, ``source(time)`` or a constant.

    A constant must be a finite number (:class:`~bearingsim.errors.ParameterError` naming the
    component, the signal and its ``unit`` otherwise).
    """
    if source is None:
        return getattr(component, input_name)
    if callable(source):
        return of_time(source, component.time, f"{component.display_name}: {input_name}")
    where = component.display_name
    check_range(source, input_name, unit, where=where)  # not a number: a clear message
    return ca.SX(float(check_range(float(source), input_name, unit, where=where)))
