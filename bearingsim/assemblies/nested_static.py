"""Quasi-static fidelity of the double-layer bearing: the load through both layers in series.

The shaft carries the inner bearing's inner ring; the middle ring is a free body between the
inner bearing's outer ring and the outer bearing's inner ring; the outer bearing's outer ring sits
in a rigid housing. Each layer is a quasi-static :class:`~bearingsim.components.ball_row.BallRow`
(Hertz contacts, exact rigid-ring kinematics, contact angle from the clearance and the load).
The shaft and the middle ring are *aligned bodies*: they translate freely (x, y and, with
``axial=True``, z) while their tilts are held by the mounting (the spindle's other bearings),
so a single deep-groove row needs no tilt stiffness of its own. Both bodies carry a small mass so
the equilibrium is the steady state of a damped dynamic model: ``steady_state`` finds it and the
exact Jacobians give the stiffness (:mod:`bearingsim.simulation.statics`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bearingsim.assembler.system import System
from bearingsim.catalog import resolve_bearing
from bearingsim.components.ball_row import BallRow
from bearingsim.components.connectors import RingFrame
from bearingsim.components.rings import Housing
from bearingsim.errors import ParameterError, SimulationError, check_range
from bearingsim.language import Assembly, Component, Input, Parameter, Variable, connect, der
from bearingsim.simulation import steady_state
from bearingsim.simulation.statics import static_stiffness

__all__ = ["AlignedBody", "NestedQuasiStatic", "NestedEquilibrium", "nested_equilibrium"]

_AXES = ("x", "y", "z")
_LOADS = ("Fx", "Fy", "Fz")


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

    Variables
    ---------
    x, y, z [m] : displacement; vx, vy, vz [m/s]; inputs Fx, Fy, Fz [N] (external load).

    Connectors
    ----------
    frame[k] : RingFrame
    """

    def __init__(self, mass: float = 0.1, offsets=(0.0,), free=_AXES, damping: float = 1e3,
                 name=None):
        super().__init__(name)
        unknown = set(free) - set(_AXES)
        if unknown:
            raise ParameterError(f"{type(self).__name__}: free axes must be among {_AXES}, got "
                                 f"{sorted(unknown)}")
        self.mass = Parameter(mass, "kg", "body mass", low=0.0, low_inclusive=False)
        self.damping = Parameter(damping, "N.s/m", "numerical damping", low=0.0,
                                 low_inclusive=False)
        self._free = tuple(a for a in _AXES if a in free)
        self._offsets = [float(o) for o in offsets]
        self.frame = [RingFrame() for _ in self._offsets]
        for axis in _AXES:
            self.add(axis, Variable(0.0, "m", f"displacement {axis}"))
        for axis in self._free:
            self.add(f"v{axis}", Variable(0.0, "m/s", f"velocity {axis}"))
        for load in _LOADS:
            self.add(load, Input(0.0, "N", f"external load {load}"))

    def equations(self):
        eqs = []
        for frame in self.frame:
            eqs += [frame.x == self.x, frame.y == self.y, frame.z == self.z,
                    frame.tx == 0, frame.ty == 0]
        for axis, load in zip(_AXES, _LOADS, strict=True):
            pos = getattr(self, axis)
            if axis not in self._free:
                eqs.append(pos == 0)
                continue
            vel = getattr(self, f"v{axis}")
            total = getattr(self, load) + sum(getattr(f, load) for f in self.frame)
            eqs += [der(pos) == vel, self.mass * der(vel) == total - self.damping * vel]
        return eqs


class NestedQuasiStatic(Assembly):
    """Quasi-static double-layer bearing: two ball rows in series through a free middle ring.

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner (shaft side) and outer (housing side) bearing.
    structure : {"I", "Z"} or None
        As :class:`~bearingsim.assemblies.double_layer.DoubleLayerBearing` (checked the same
        way: anything else, or "I" when the inner bearing does not fit in the outer one's bore,
        raises :class:`~bearingsim.errors.ParameterError`); for "Z" the outer row sits
        ``(B1 + B2)/2`` axially behind the inner row on the middle ring.
    axial : bool
        Let the bodies move axially (needed for axial loads); with ``False`` the axial
        positions stay centred (a deep-groove bearing with clearance has axial play and no axial
        stiffness without an axial load).

    Inputs
    ------
    shaft.Fx, shaft.Fy, shaft.Fz [N] : load on the shaft
    """

    def __init__(self, inner="61905", outer="61907", structure: str | None = None,
                 axial: bool = True, name="nested"):
        super().__init__(name)
        from bearingsim.assemblies.double_layer import _structure

        gi, go = resolve_bearing(inner), resolve_bearing(outer)
        structure = _structure(gi, go, structure)
        self.structure = structure
        offset = 0.0 if structure == "I" else -(gi.width + go.width) / 2
        free = _AXES if axial else ("x", "y")
        self.geometries = (gi, go)
        self.shaft = AlignedBody(free=free)
        self.middle = AlignedBody(offsets=(0.0, offset), free=free)
        self.inner_row = BallRow(gi, reference="centred")
        self.outer_row = BallRow(go, reference="centred")
        self.housing = Housing(1)
        connect(self.shaft.frame[0], self.inner_row.inner)
        connect(self.inner_row.outer, self.middle.frame[0])
        connect(self.middle.frame[1], self.outer_row.inner)
        connect(self.outer_row.outer, self.housing.frame[0])


@dataclass(frozen=True)
class NestedEquilibrium:
    """Equilibrium of a nested pair under a shaft load."""

    shaft_displacement: np.ndarray
    """(x, y, z) of the shaft [m]."""
    middle_displacement: np.ndarray
    """(x, y, z) of the middle ring [m]."""
    inner_ball_loads: np.ndarray
    """Ball loads of the inner layer [N]."""
    outer_ball_loads: np.ndarray
    """Ball loads of the outer layer [N]."""
    inner_contact_angles: np.ndarray
    """Contact angles of the inner layer [rad]."""
    outer_contact_angles: np.ndarray
    """Contact angles of the outer layer [rad]."""
    stiffness: np.ndarray
    """Stiffness of the shaft against the housing in the free directions [N/m]."""
    state: np.ndarray


def nested_equilibrium(system: System, radial: float, axial: float = 0.0,
                       guess: np.ndarray | None = None) -> NestedEquilibrium:
    """Solve the nested pair for a radial (x) and axial (z) shaft load.

    Parameters
    ----------
    system : System
        Assembled :class:`NestedQuasiStatic`.
    radial : float
        Radial load on the shaft along x [N], >= 0; 0 only with an axial load (a load is
        needed to seat the balls).
    axial : float
        Axial load along z [N] (needs ``axial=True``).
    guess : array, optional
        Starting state (default: seated guess from the clearance).

    Returns
    -------
    NestedEquilibrium
    """
    check_range(radial, "radial", "N", 0.0, None, where="nested_equilibrium")
    check_range(axial, "axial", "N", where="nested_equilibrium")
    if radial == 0.0 and not axial:
        raise ParameterError("nested_equilibrium: radial = 0 N needs an axial load; the balls "
                             "of a bearing with clearance are seated by a load (radial > 0 N "
                             "or axial != 0 N)")
    axial_free = "shaft.z" in system.state_names
    if axial and not axial_free:
        raise ParameterError("nested_equilibrium: an axial load needs NestedQuasiStatic("
                             "axial=True)")
    inputs = {"shaft.Fx": float(radial)}
    if axial_free:
        inputs["shaft.Fz"] = float(axial)
    # Seat the balls radially (with at least the axial load, so that the axial path starts from
    # loaded contacts), add the axial load, then take the radial load down to its value.
    seat = max(float(radial), abs(float(axial)))
    x = _seated_guess(system, seat) if guess is None else np.array(guess, dtype=float)
    mass = min(v for n, v in zip(system.parameter_names, system.p0(), strict=True)
               if n.endswith(".mass"))
    tol = 1e-9 * (abs(radial) + abs(axial)) / mass  # force balance to 1e-9 of the load
    seated = {**inputs, "shaft.Fx": seat} | ({"shaft.Fz": 0.0} if axial_free else {})
    x = steady_state(system, inputs=seated, x_guess=x, residual_tol=tol)
    loaded = {**seated, **({"shaft.Fz": float(axial)} if axial_free else {})}
    if axial:
        x = _load_path(system, seated, loaded, x, tol)
    if seat != radial:
        x = _load_path(system, loaded, inputs, x, tol)
    u = system.u_default()
    for n, v in inputs.items():
        u[system.input_names.index(n)] = v
    obs = system.observe(0.0, x, u)
    free = [a for a in _AXES if f"shaft.{a}" in system.state_names]
    stiff = static_stiffness(system, x, [f"shaft.{a}" for a in free],
                             [f"shaft.F{a}" for a in free], inputs)

    def series(prefix, key, count):
        return np.array([obs[f"{prefix}.{key}[{j}]"] for j in range(count)])

    zi = _ball_count(obs, "inner_row")
    zo = _ball_count(obs, "outer_row")
    return NestedEquilibrium(
        np.array([obs[f"shaft.{a}"] for a in _AXES]),
        np.array([obs[f"middle.{a}"] for a in _AXES]),
        series("inner_row", "Q_i", zi), series("outer_row", "Q_i", zo),
        series("inner_row", "alpha_i", zi), series("outer_row", "alpha_i", zo),
        stiff, x,
    )


def _load_path(system: System, start: dict[str, float], end: dict[str, float], x: np.ndarray,
               tol: float, min_step: float = 1e-3) -> np.ndarray:
    """Move the shaft loads linearly from ``start`` to ``end`` in steps, each equilibrium
    solved from the previous one; a step that fails is halved, one that succeeds doubled (up to
    a quarter of the path).

    Raises
    ------
    SimulationError
        If a step below ``min_step`` of the path still fails.
    """
    done, step = 0.0, 0.1
    while done < 1.0:
        trial = min(1.0, done + step)
        loads = {k: start[k] + trial * (end[k] - start[k]) for k in end}
        try:
            x = steady_state(system, inputs=loads, x_guess=x, residual_tol=tol)
        except SimulationError as exc:
            step /= 2.0
            if step < min_step:
                raise SimulationError(f"nested_equilibrium: no equilibrium found from {start} "
                                      f"towards {end} beyond {done:.3g} of the way: {exc}"
                                      ) from None
            continue
        done, step = trial, min(2.0 * step, 0.25)
    return x


def _seated_guess(system: System, radial: float) -> np.ndarray:
    """Each layer's radial play taken up in the load direction plus the Hertz approach of its
    most loaded ball under Stribeck's estimate ``Qmax = 5 Fr / Z``."""
    p = dict(zip(system.parameter_names, system.p0(), strict=True))
    play = []
    for row in ("inner_row", "outer_row"):
        dw, fi, fo, a0, ki, ko = (p[f"{row}.{k}"] for k in ("Dw", "fi", "fo", "alpha0", "K_i",
                                                              "K_o"))
        z = _ball_count({n: 0 for n in system.observed_names}, row)
        k = (ki ** (-2.0 / 3.0) + ko ** (-2.0 / 3.0)) ** -1.5
        approach = (5.0 * abs(radial) / z / k) ** (2.0 / 3.0)
        play.append((fi + fo - 1.0) * dw * (1.0 - np.cos(a0)) + approach)
    x = system.x0()
    sign = np.sign(radial)
    x[system.state_names.index("middle.x")] = sign * play[1]
    x[system.state_names.index("shaft.x")] = sign * (play[0] + play[1])
    return x


def _ball_count(observed, row: str) -> int:
    """Number of balls of a row from the observed variable names."""
    return sum(1 for n in observed if n.startswith(f"{row}.Q_i["))
