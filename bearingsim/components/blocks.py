"""Signal blocks: controllers built from symbolic equations."""

from __future__ import annotations

from bearingsim.language import Component, Input, Parameter, Variable, der

__all__ = ["PIController"]


def _times_second(unit: str) -> str:
    """``unit`` times a second, written so that it reads one way only: ``rad/s`` -> ``rad``,
    ``A`` -> ``A.s``, ``m/s2`` -> ``(m/s2).s`` (``rad/s.s`` reads as rad/s^2 as well)."""
    if unit in ("", "1"):
        return "s"
    if unit.endswith("/s") and unit.count("/") == 1 and "(" not in unit:
        return unit[:-2]
    return f"({unit}).s" if "/" in unit else f"{unit}.s"


class PIController(Component):
    """Proportional-integral controller ``y = kp e + ki int(e) dt`` with ``e = r - m``.

    Parameters
    ----------
    kp : float
        Proportional gain [unit of y / unit of e], >= 0.
    ki : float
        Integral gain [unit of y / (unit of e s)], >= 0.
    unit_e, unit_y : str
        Units of the error (reference and measurement) and of the output, e.g. ``"rad/s"`` and
        ``"V"`` (default ``"1"``, dimensionless).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Variables
    ---------
    r, m : inputs (reference, measurement); e : error; xi : integral state; y : output.
    """

    def __init__(self, kp: float, ki: float, unit_e: str = "1", unit_y: str = "1", name=None):
        super().__init__(name)
        self.kp = Parameter(kp, f"({unit_y})/({unit_e})", "proportional gain", low=0.0)
        self.ki = Parameter(ki, f"({unit_y})/({_times_second(unit_e)})", "integral gain",
                            low=0.0)
        self.r = Input(unit=unit_e, description="reference")
        self.m = Input(unit=unit_e, description="measurement")
        self.e = Variable(unit=unit_e, description="control error r - m")
        self.xi = Variable(0.0, _times_second(unit_e), "integral of the control error")
        self.y = Variable(unit=unit_y, description="controller output")

    def equations(self):
        return [
            self.e == self.r - self.m,
            der(self.xi) == self.e,
            self.y == self.kp * self.e + self.ki * self.xi,
        ]
