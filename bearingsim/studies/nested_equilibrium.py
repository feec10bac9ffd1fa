"""Load sharing of a quasi-static double-layer bearing: equilibrium and stiffness of the shaft
and the middle ring under a shaft load (docs/studies.md, section A; the assembly is
:class:`~bearingsim.assemblies.double_layer.quasi_static.NestedQuasiStatic`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bearingsim.assembler.system import System, as_system
from bearingsim.components.aligned_body import AXES
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.simulation import steady_state
from bearingsim.simulation.statics import static_stiffness
from bearingsim.validation import check_quantity

__all__ = ["NestedEquilibrium", "nested_equilibrium"]


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


def nested_equilibrium(system: System, radial: float | str, axial: float | str = 0.0,
                       guess: np.ndarray | None = None) -> NestedEquilibrium:
    """Solve the nested pair for a radial (x) and axial (z) shaft load.

    Parameters
    ----------
    system : System
        Assembled :class:`NestedQuasiStatic`.
    radial : float or str
        Radial load on the shaft along x [N], >= 0, or a number with a unit (``"0.5 kN"``); 0
        only with an axial load (a load is needed to seat the balls).
    axial : float or str
        Axial load along z [N] or a number with a unit (needs ``axial=True``).
    guess : array, optional
        Starting state (default: seated guess from the clearance).

    Returns
    -------
    NestedEquilibrium

    Raises
    ------
    ParameterError
        For loads out of range, or a system that is not a nested quasi-static pair (another
        level of the double-layer bearing, another assembly), naming what it lacks.
    """
    system = as_system(system, "nested_equilibrium")
    _check_nested(system)
    radial = float(check_quantity(radial, "radial", "N", 0.0, None, where="nested_equilibrium"))
    axial = float(check_quantity(axial, "axial", "N", where="nested_equilibrium"))
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
    free = [a for a in AXES if f"shaft.{a}" in system.state_names]
    stiff = static_stiffness(system, x, [f"shaft.{a}" for a in free],
                             [f"shaft.F{a}" for a in free], inputs)

    def series(prefix, key, count):
        return np.array([obs[f"{prefix}.{key}[{j}]"] for j in range(count)])

    zi = _ball_count(obs, "inner_row")
    zo = _ball_count(obs, "outer_row")
    return NestedEquilibrium(
        np.array([obs[f"shaft.{a}"] for a in AXES]),
        np.array([obs[f"middle.{a}"] for a in AXES]),
        series("inner_row", "Q_i", zi), series("outer_row", "Q_i", zo),
        series("inner_row", "alpha_i", zi), series("outer_row", "alpha_i", zo),
        stiff, x,
    )


_NEEDS = {"input": ("shaft.Fx",), "state": ("shaft.x", "middle.x"),
          "parameter": ("inner_row.Dw", "outer_row.Dw")}
"""Names of each kind a :class:`NestedQuasiStatic` system has and :func:`nested_equilibrium`
reads."""


def _check_nested(system: System) -> None:
    """Raise a named error when ``system`` lacks a name of :data:`_NEEDS`."""
    have = {"input": system.input_names, "state": system.state_names,
            "parameter": system.parameter_names}
    missing = [f"{kind} {name}" for kind, names in _NEEDS.items() for name in names
               if name not in have[kind]]
    if missing:
        raise ParameterError(
            f"nested_equilibrium: expects an assembled quasi-static double-layer bearing "
            f"(assemble(double_layer_bearing(inner, outer, fidelity='quasi-static')), a "
            f"NestedQuasiStatic); the system {system.name} has no {', '.join(missing)} (its "
            f"inputs: {', '.join(system.input_names) or 'none'})")


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
