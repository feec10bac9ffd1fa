"""A rigid body that translates but does not tilt, with ring frames at axial offsets."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from bearingsim.components.connectors import RingFrame
from bearingsim.errors import ParameterError
from bearingsim.language import Component, Input, Parameter, Variable, der

__all__ = ["AXES", "AlignedBody", "LOADS"]

AXES = ("x", "y", "z")
"""Translation axes (z is the bearing axis)."""
LOADS = ("Fx", "Fy", "Fz")
"""External load inputs along :data:`AXES`."""


class AlignedBody(Component):
    """A rigid body that translates but does not tilt; frames at axial offsets.

    ``m x'' = sum of frame forces + external load - c x'`` per free axis (``c`` is a numerical
    damping that makes the steady state an attracting one; it does not change the equilibrium).
    Axes that are not free stay at zero; tilts are zero (their moments are reactions).

    Parameters
    ----------
    mass : float
        Mass [kg], > 0.
    offsets : sequence of float
        Axial positions of the frames relative to the body's reference point [m].
    free : sequence of str
        Free translations among "x", "y", "z".
    damping : float
        Numerical damping [N s/m], > 0.
    name : str
        Instance name (the prefix of its variables' dotted names).
    bounds : dict, optional
        Load name -> keywords of its input (``low``, ``high``, ``warn_above``, ``limit``:
        :func:`~bearingsim.components.rolling_element.load_input_bounds` of the bearings the
        body's load passes through).

    Variables
    ---------
    x, y, z [m] : displacement; vx, vy, vz [m/s]; inputs Fx, Fy, Fz [N] (external load).

    Connectors
    ----------
    frame[k] : RingFrame
    """

    def __init__(self, mass: float = 0.1, offsets=(0.0,), free=AXES, damping: float = 1e3,
                 name=None, bounds: Mapping[str, Mapping[str, Any]] | None = None):
        super().__init__(name)
        unknown = set(free) - set(AXES)
        if unknown:
            raise ParameterError(f"{type(self).__name__}: free axes must be among {AXES}, got "
                                 f"{sorted(unknown)}")
        self.mass = Parameter(mass, "kg", "body mass", low=0.0, low_inclusive=False)
        self.damping = Parameter(damping, "N.s/m", "numerical damping", low=0.0,
                                 low_inclusive=False)
        self._free = tuple(a for a in AXES if a in free)
        self._offsets = [float(o) for o in offsets]
        self.frame = [RingFrame() for _ in self._offsets]
        for axis in AXES:
            self.add(axis, Variable(0.0, "m", f"displacement {axis}"))
        for axis in self._free:
            self.add(f"v{axis}", Variable(0.0, "m/s", f"velocity {axis}"))
        for load in LOADS:
            self.add(load, Input(0.0, "N", f"external load {load}",
                                 **(bounds or {}).get(load, {})))

    def equations(self):
        eqs = []
        for frame in self.frame:
            eqs += [frame.x == self.x, frame.y == self.y, frame.z == self.z,
                    frame.tx == 0, frame.ty == 0]
        for axis, load in zip(AXES, LOADS, strict=True):
            pos = getattr(self, axis)
            if axis not in self._free:
                eqs.append(pos == 0)
                continue
            vel = getattr(self, f"v{axis}")
            total = getattr(self, load) + sum(getattr(f, load) for f in self.frame)
            eqs += [der(pos) == vel, self.mass * der(vel) == total - self.damping * vel]
        return eqs
