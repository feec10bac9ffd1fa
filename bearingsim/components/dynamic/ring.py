"""Rigid ring bodies of the dynamic bearing: a 5-DOF moving ring, a fixed ring, a load."""

from __future__ import annotations

import difflib
import numbers
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from bearingsim.components.connectors import FRAME_FLOWS, FRAME_POTENTIALS, RingFrame
from bearingsim.components.dynamic.ball import MICRON
from bearingsim.components.dynamic.rigid_body import PartialRigidBody
from bearingsim.components.rotational import _signal
from bearingsim.errors import ParameterError
from bearingsim.language import Component, Input, Variable, der
from bearingsim.symbolic import is_symbolic
from bearingsim.units import is_quantity
from bearingsim.validation import check_quantity

__all__ = ["RingBody", "FixedFrame", "RingLoad", "TiltGuide", "check_loads", "load_unit",
           "load_value"]


_LOAD_HINTS = {
    "fr": "; did you mean 'Fx' or 'Fy'? (radial forces; z is the bearing axis)",
    "fa": "; did you mean 'Fz'? (axial force; z is the bearing axis)",
    "mz": "; the torque about the axis is not a ring load: it goes through the shaft flange",
}
"""Hints for common load names that are not frame flows (keys in lower case)."""


def load_unit(key: str) -> str:
    """Unit of the ring-load component ``key``: ``"N"`` for forces, ``"N.m"`` for moments.

    Parameters
    ----------
    key : str
        "Fx", "Fy", "Fz", "Mx" or "My".

    Returns
    -------
    str
        Its unit.
    """
    return "N" if key.startswith("F") else "N.m"


def load_value(value: Any, key: str, where: str) -> float:
    """One constant ring load in SI units: a number in :func:`load_unit` or a number with a
    unit (``"2 kN"``, a :class:`pint.Quantity`), finite.

    Parameters
    ----------
    value : float or str or pint.Quantity
        The load.
    key : str
        Its name ("Fx", ..., "My").
    where : str
        Component or function name for the messages.

    Returns
    -------
    float
        The load [N or N m].

    Raises
    ------
    ParameterError
        For anything else (a bool, a sequence, text that is no number with a unit of that
        quantity), naming the load and its unit.
    """
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, str)) and not (
            is_quantity(value)):
        raise ParameterError(f"{where}: loads[{key!r}] must be a number in {load_unit(key)} or "
                             f"a number with a unit ('2 kN'), got {value!r:.60}")
    return float(check_quantity(value, f"loads[{key!r}]", load_unit(key), where=where))


def check_loads(loads: Mapping[str, Any] | None, where: str = "RingLoad") -> dict[str, Any]:
    """Validate a dict of ring loads before it is applied or used for start values.

    Parameters
    ----------
    loads : dict or None
        ``{"Fx": ..., "Fy": ..., "Fz": ..., "Mx": ..., "My": ...}`` [N, N m]: constants
        (numbers, or numbers with a unit: ``"2 kN"``), symbolic functions of time or ``None``
        (inputs).
    where : str
        Component or function name for the messages.

    Returns
    -------
    dict
        A copy of ``loads`` with the numeric constants as floats.

    Raises
    ------
    ParameterError
        For a key other than the frame flows ``Fx, Fy, Fz, Mx, My`` (the message suggests the
        nearest one), or a constant that is not a finite number.
    """
    if loads is None:
        return {}
    if not isinstance(loads, Mapping):
        raise ParameterError(f"{where}: loads must be a dict with keys {', '.join(FRAME_FLOWS)}, "
                             f"got {type(loads).__name__}")
    checked: dict[str, Any] = {}
    for key, value in loads.items():
        if key not in FRAME_FLOWS:
            lower = {k.lower(): k for k in FRAME_FLOWS}
            close = difflib.get_close_matches(str(key).lower(), list(lower), n=1, cutoff=0.5)
            hint = _LOAD_HINTS.get(str(key).lower())
            if hint is None:
                hint = f"; did you mean {lower[close[0]]!r}?" if close else ""
            raise ParameterError(f"{where}: unknown load {key!r}; the loads are "
                                 f"{', '.join(FRAME_FLOWS)} (forces [N], moments [N.m]){hint}")
        if value is None or callable(value) or is_symbolic(value):
            checked[key] = value
        else:
            checked[key] = load_value(value, key, where)
    return checked


class RingBody(PartialRigidBody):
    """A rigid ring (with its shaft) moving in 5 DOF: translations x, y, z and tilts tx, ty.

    ``m der(v) = F``, ``J_t der(w_t) = M`` with the forces and moments of everything connected
    to ``frame`` (ball contacts, external load). Its rotation about the axis is the business of
    the rotational components connected to the contacts' flanges.

    Parameters
    ----------
    mass : float
        [kg], > 0.
    tilt_inertia : float
        Moment of inertia about a diameter [kg m^2], > 0.
    start : sequence of 5 float
        Initial (x, y, z, tx, ty) [m, m, m, rad, rad].
    free_tilt : bool
        Whether the ring tilts; if False the shaft holds ``tx = ty = 0`` and the moments of the
        connected elements are reactions.
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    frame : RingFrame

    Variables
    ---------
    x, y, z [m], tx, ty [rad] and their rates vx, vy, vz [m/s], wx, wy [rad/s]; the states of
    the translations are x_um, y_um, z_um [um]
    """

    def __init__(self, mass: float, tilt_inertia: float, start: Sequence[float] = (0.0,) * 5,
                 free_tilt: bool = False, name=None):
        super().__init__(mass, tilt_inertia, "ring", "tilt inertia", name)
        self.free_tilt = bool(free_tilt)
        self.frame = RingFrame()
        units = ("m", "m", "m", "rad", "rad")
        for key, unit, x0 in zip(FRAME_POTENTIALS, units, start, strict=True):
            if unit == "rad" and not self.free_tilt:
                continue
            if unit == "m":
                self.add(key + "_um", Variable(float(x0) / MICRON, "um",
                                               f"ring displacement {key} (state)"))
            self.add(key, Variable(float(x0) if unit == "rad" else None, unit,
                                   f"ring displacement {key}"))
            rate = "v" + key if unit == "m" else "w" + key[1]
            self.add(rate, Variable(0.0, f"{unit}/s", f"rate of {key}"))

    def equations(self):
        f = self.frame
        eqs = []
        for key, flow in zip(FRAME_POTENTIALS, FRAME_FLOWS, strict=True):
            if key in ("tx", "ty") and not self.free_tilt:
                eqs.append(getattr(f, key) == 0.0)
                continue
            pos = getattr(self, key)
            rate = getattr(self, "v" + key if key in "xyz" else "w" + key[1])
            inertia = self.m if key in "xyz" else self.J
            if key in "xyz":
                micro = getattr(self, key + "_um")
                eqs += [pos == MICRON * micro, MICRON * der(micro) == rate]
            else:
                eqs.append(der(pos) == rate)
            eqs += [getattr(f, key) == pos, inertia * der(rate) == getattr(f, flow)]
        return eqs


class FixedFrame(Component):
    """A ring frame fixed at zero displacement (the housing side); the reactions are free.

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, name=None):
        super().__init__(name)
        self.frame = RingFrame()

    def equations(self):
        return [p == 0.0 for p in self.frame.displacement()]


class RingLoad(Component):
    """External load on a ring: forces Fx, Fy, Fz [N] and moments Mx, My [N m].

    Each component is a constant, a symbolic function of time, or ``None`` for an input of the
    same name.

    Parameters
    ----------
    loads : dict
        ``{"Fx": ..., "Fy": ..., "Fz": ..., "Mx": ..., "My": ...}``; missing keys are inputs
        with default 0. Other keys and constants that are not finite numbers raise
        :class:`~bearingsim.errors.ParameterError` (see :func:`check_loads`).
    name : str
        Instance name (the prefix of its variables' dotted names).
    bounds : dict, optional
        Load name -> keywords of its input (``low``, ``high``, ``warn_above``, ``limit``:
        :func:`~bearingsim.components.rolling_element.load_input_bounds`); a constant load is
        checked where it is given.

    Connectors
    ----------
    frame : RingFrame
    """

    def __init__(self, loads: dict[str, float | Callable | None] | None = None, name=None,
                 bounds: Mapping[str, Mapping[str, Any]] | None = None):
        super().__init__(name)
        self.frame = RingFrame()
        self._loads = check_loads(loads, type(self).__name__)
        for key in FRAME_FLOWS:
            if self._loads.get(key) is None:
                self.add(key, Input(0.0, load_unit(key), f"external load {key} on the ring",
                                    **(bounds or {}).get(key, {})))

    def equations(self):
        return [getattr(self.frame, key) == -_signal(self._loads.get(key), self, key,
                                                     load_unit(key))
                for key in FRAME_FLOWS]


class TiltGuide(Component):
    """Holds a ring frame straight (``tx = ty = 0``): the shaft's other supports take the
    moments, no force.

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, name=None):
        super().__init__(name)
        self.frame = RingFrame()

    def equations(self):
        f = self.frame
        return [f.tx == 0.0, f.ty == 0.0, f.Fx == 0.0, f.Fy == 0.0, f.Fz == 0.0]
