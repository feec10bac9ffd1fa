"""Electric motors for bearing drives: a DC motor and a PMSM in the rotor (dq) frame, each with
its own rotor inertia and, as drives, a PI speed controller.

Units: V, A, ohm, H, Wb, N m, rad/s.
"""

from __future__ import annotations

import numbers
from collections.abc import Callable

from bearingsim.components.blocks import PIController
from bearingsim.components.connectors import Flange
from bearingsim.errors import ParameterError
from bearingsim.language import Assembly, Component, Input, Parameter, Variable, connect, der
from bearingsim.language.symbols import of_time
from bearingsim.units import is_quantity
from bearingsim.validation import check_choice, check_quantity

__all__ = ["DCMotor", "PMSM", "DCMotorDrive", "PMSMDrive", "MOTOR_DRIVES",
           "speed_controlled_motor", "speed_reference"]


def _positive(value, unit, description):
    return Parameter(value, unit, description, low=0.0, low_inclusive=False)


class _Machine(Component):
    """Rotor of an electric machine: inertia ``J`` (a parameter) on ``flange``, driven by the
    electromagnetic torque ``tau_em`` that the subclass defines together with ``P_el``."""

    def _declare_rotor(self, J: float, w0: float) -> None:  # noqa: N803 - the rotor inertia
        self.J = _positive(J, "kg.m2", "rotor inertia")
        self.flange = Flange()
        self.phi = Variable(0.0, "rad", "rotor angle")
        self.w = Variable(w0, "rad/s", "rotor speed")
        self.tau_em = Variable(unit="N.m", description="electromagnetic torque")
        self.P_el = Variable(unit="W", description="electrical input power")
        self.P_mech = Variable(unit="W", description="electromagnetic (air-gap) power")

    def _rotor_equations(self) -> list:
        return [
            der(self.phi) == self.w,
            self.J * der(self.w) == self.tau_em + self.flange.tau,
            self.flange.phi == self.phi,
            self.P_mech == self.tau_em * self.w,
        ]


class DCMotor(_Machine):
    """Permanent-magnet DC motor with rotor inertia.

    ``L di/dt = v - R i - k w``, ``J dw/dt = k i + flange.tau``.

    Parameters
    ----------
    R : float
        Armature resistance [ohm].
    L : float
        Armature inductance [H].
    k : float
        Torque and back-EMF constant [N m/A] = [V s/rad].
    J : float
        Rotor inertia [kg m^2].
    w0 : float
        Start speed of the rotor [rad/s].
    name : str
        Instance name (the prefix of its variables' dotted names).

    Variables
    ---------
    v (input) [V], i [A], phi [rad], w [rad/s], tau_em [N m], P_el [W], P_mech [W]

    Connectors
    ----------
    flange : Flange (the shaft end)
    """

    def __init__(self, R=0.5, L=1e-3, k=0.05, J=2e-4, w0=0.0, name=None):
        super().__init__(name)
        self.R = _positive(R, "Ohm", "armature resistance")
        self.L = _positive(L, "H", "armature inductance")
        self.k = _positive(k, "N.m/A", "torque constant")
        self._declare_rotor(J, w0)
        self.v = Input(unit="V", description="terminal voltage")
        self.i = Variable(0.0, "A", "armature current")

    def equations(self):
        return [
            self.L * der(self.i) == self.v - self.R * self.i - self.k * self.w,
            self.tau_em == self.k * self.i,
            self.P_el == self.v * self.i,
            *self._rotor_equations(),
        ]


class PMSM(_Machine):
    """Permanent-magnet synchronous motor in the rotor (dq) frame.

    ``Ld did/dt = vd - R id + p w Lq iq``,
    ``Lq diq/dt = vq - R iq - p w (Ld id + psi)``,
    ``tau_em = 3/2 p (psi iq + (Ld - Lq) id iq)`` (amplitude-invariant Park transform).

    Parameters
    ----------
    p : int
        Pole pairs [1].
    R : float
        Stator resistance per phase [ohm].
    Ld, Lq : float
        d- and q-axis inductances [H].
    psi : float
        Permanent-magnet flux linkage [Wb].
    J, w0 : float
        Rotor inertia [kg m^2] and its start speed [rad/s].
    name : str
        Instance name (the prefix of its variables' dotted names).

    Variables
    ---------
    vd, vq (inputs) [V], id, iq [A], phi [rad], w [rad/s], tau_em [N m], P_el, P_mech [W]
    """

    def __init__(self, p=2, R=0.2, Ld=5e-4, Lq=6e-4, psi=0.02, J=2e-4, w0=0.0, name=None):
        super().__init__(name)
        self.p = _positive(p, "1", "pole pairs")
        self.R = _positive(R, "Ohm", "stator resistance")
        self.Ld = _positive(Ld, "H", "d-axis inductance")
        self.Lq = _positive(Lq, "H", "q-axis inductance")
        self.psi = _positive(psi, "Wb", "permanent-magnet flux linkage")
        self._declare_rotor(J, w0)
        self.vd = Input(unit="V", description="d-axis voltage")
        self.vq = Input(unit="V", description="q-axis voltage")
        self.id = Variable(0.0, "A", "d-axis current")
        self.iq = Variable(0.0, "A", "q-axis current")

    def equations(self):
        we = self.p * self.w
        return [
            self.Ld * der(self.id) == self.vd - self.R * self.id + we * self.Lq * self.iq,
            self.Lq * der(self.iq)
            == self.vq - self.R * self.iq - we * (self.Ld * self.id + self.psi),
            self.tau_em
            == 1.5 * self.p * (self.psi * self.iq + (self.Ld - self.Lq) * self.id * self.iq),
            self.P_el == 1.5 * (self.vd * self.id + self.vq * self.iq),
            *self._rotor_equations(),
        ]


SpeedReference = Callable | float | str | None


def speed_reference(speed_ref: SpeedReference, where: str) -> Callable | float | None:
    """A drive's speed reference, checked: a function of time and None unchanged, a number
    [rad/s] or a number with a unit (``"3000 rpm"``, a :class:`pint.Quantity`) as a finite
    float in rad/s.

    Parameters
    ----------
    speed_ref : callable or float or str or None
        The speed reference as given.
    where : str
        The component or function, for the message.

    Returns
    -------
    callable or float or None
        ``f(t)``, the speed [rad/s] or None.

    Raises
    ------
    ParameterError
        For NaN or an infinity, text that is not a number with a unit of speed, or another
        type, naming ``speed_ref``, its unit and the accepted forms.
    """
    if speed_ref is None or callable(speed_ref):
        return speed_ref
    if isinstance(speed_ref, bool) or not (isinstance(speed_ref, (numbers.Real, str))
                                           or is_quantity(speed_ref)):
        raise ParameterError(
            f"{where}: speed_ref must be a number [rad/s], a number with a unit (e.g. "
            f"'3000 rpm'), a function of time f(t) or None (an input w_ref), got "
            f"{speed_ref!r:.60} ({type(speed_ref).__name__})")
    return float(check_quantity(speed_ref, "speed_ref", "rad/s", where=where))


class DCMotorDrive(Assembly):
    """DC motor with a PI speed controller acting on the terminal voltage.

    Parameters
    ----------
    speed_ref : callable or float or str or None
        Speed reference [rad/s]: ``f(t)`` (symbolic), a constant (a number with a unit such as
        ``"3000 rpm"`` is converted), or None for an input ``w_ref``.
    kp, ki : float
        Speed controller gains [V s/rad], [V/rad].
    **motor
        Passed to :class:`DCMotor`.
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    flange : Flange (motor shaft end)
    """

    def __init__(self, speed_ref: SpeedReference = None, kp=0.5, ki=5.0, name=None, **motor):
        super().__init__(name)
        self.motor = DCMotor(**motor)
        self.speed_pi = PIController(kp, ki, "rad/s", "V")
        _shaft_and_reference(self, speed_ref)

    def equations(self):
        return [
            self.speed_pi.r == _reference(self._ref, self),
            self.speed_pi.m == self.motor.w,
            self.motor.v == self.speed_pi.y,
        ]


class PMSMDrive(Assembly):
    """PMSM with field-oriented control: speed PI -> iq reference; current PIs -> vd, vq with
    decoupling feed-forward; id reference zero.

    Parameters
    ----------
    speed_ref : callable or float or str or None
        Speed reference [rad/s]: ``f(t)``, a constant (a number with a unit such as
        ``"3000 rpm"`` is converted), or None for an input ``w_ref``.
    kp_w, ki_w : float
        Speed controller gains [A s/rad], [A/rad].
    kp_i, ki_i : float
        Current controller gains [V/A], [V/(A s)].
    **motor
        Passed to :class:`PMSM`.
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, speed_ref: SpeedReference = None, kp_w=0.5, ki_w=10.0, kp_i=2.0,
                 ki_i=400.0, name=None, **motor):
        super().__init__(name)
        self.motor = PMSM(**motor)
        self.speed_pi = PIController(kp_w, ki_w, "rad/s", "A")
        self.id_pi = PIController(kp_i, ki_i, "A", "V")
        self.iq_pi = PIController(kp_i, ki_i, "A", "V")
        _shaft_and_reference(self, speed_ref)

    def equations(self):
        m = self.motor
        we = m.p * m.w
        return [
            self.speed_pi.r == _reference(self._ref, self),
            self.speed_pi.m == m.w,
            self.iq_pi.r == self.speed_pi.y,
            self.iq_pi.m == m.iq,
            self.id_pi.r == 0.0,
            self.id_pi.m == m.id,
            m.vd == self.id_pi.y - we * m.Lq * m.iq,
            m.vq == self.iq_pi.y + we * (m.Ld * m.id + m.psi),
        ]


MOTOR_DRIVES = {"dc": DCMotorDrive, "pmsm": PMSMDrive}
"""Speed-controlled motor drives by the name assemblies and scenes use."""


def speed_controlled_motor(motor: str, speed_ref: SpeedReference,
                           motor_options: dict | None, where: str) -> DCMotorDrive | PMSMDrive:
    """A speed-controlled motor drive of :data:`MOTOR_DRIVES` by name.

    Parameters
    ----------
    motor : {"dc", "pmsm"}
        Motor type.
    speed_ref : callable or float or str or None
        Speed reference [rad/s]: ``f(t)``, constant (or a number with a unit, ``"3000 rpm"``),
        or None for the drive's input ``w_ref``.
    motor_options : dict, optional
        Keyword arguments of the drive (gains, motor constants).
    where : str
        Caller's name, used in the message.

    Returns
    -------
    DCMotorDrive or PMSMDrive
        The drive.

    Raises
    ------
    ParameterError
        For an unknown motor type.
    """
    check_choice(motor, "motor", tuple(MOTOR_DRIVES), where)
    return MOTOR_DRIVES[motor](speed_ref, **(motor_options or {}))


def _shaft_and_reference(drive: Assembly, speed_ref: SpeedReference) -> None:
    """The drive's shaft flange (connected to its motor's) and its speed reference
    (:func:`speed_reference`): kept for :func:`_reference`, or an input ``w_ref`` [rad/s] when
    None."""
    drive.flange = Flange()
    drive._ref = speed_reference(speed_ref, type(drive).__name__)
    if speed_ref is None:
        drive.w_ref = Input(0.0, "rad/s", "speed reference")
    connect(drive.flange, drive.motor.flange)


def _reference(ref, component):
    if ref is None:
        return component.w_ref
    if callable(ref):
        return of_time(ref, component.time, f"{component.display_name}: speed reference")
    return float(ref) + 0.0 * component.time
