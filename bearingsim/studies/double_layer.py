"""Speed-ratio studies of double-layer bearings (models.md section A)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bearingsim.assemblies.double_layer import double_layer_bearing
from bearingsim.solver import assemble, steady_state
from bearingsim.solver.system import System

__all__ = ["SpeedRatioSweep", "speed_ratio_sweep", "steady_ratio"]


@dataclass
class SpeedRatioSweep:
    """Steady speed ratio against shaft speed."""

    speeds: np.ndarray
    """Shaft speeds [rad/s]."""
    rs: np.ndarray
    """Speed distribution ratio at each speed [1]."""
    friction_torque: np.ndarray
    """Friction torque on the shaft at each speed [N m]."""


def steady_ratio(system: System, speed: float, loads=(0.0, 0.0), parameters=None,
                 x_guess=None) -> tuple[float, float, np.ndarray]:
    """Steady ``Rs`` and shaft friction torque of an assembled double-layer bearing.

    Returns
    -------
    (Rs [1], M_shaft [N m], steady state vector)
    """
    inputs = {"shaft_speed": float(speed)}
    if "Fr" in system.input_names:
        inputs.update({"Fr": float(loads[0]), "Fa": float(loads[1])})
    x = steady_state(system, inputs=inputs, parameters=parameters, x_guess=x_guess)
    u = np.array([inputs.get(n, 0.0) for n in system.input_names])
    obs = system.observe(0.0, x, u, system.p0(parameters))
    return obs["Rs"], obs["M_shaft"], x


def speed_ratio_sweep(speeds, inner="61905", outer="61907", loads=(0.0, 0.0), parameters=None,
                      system: System | None = None, **bearing) -> SpeedRatioSweep:
    """Steady speed ratio over shaft speeds with ONE assembled system (no re-assembly).

    Parameters
    ----------
    speeds : array_like
        Shaft speeds [rad/s], > 0.
    inner, outer : str or BearingGeometry
        Bearings.
    loads : (float, float)
        Radial and axial load [N] (torque fidelity).
    parameters : dict, optional
        Parameter overrides (e.g. another viscosity).
    system : System, optional
        A system assembled from :func:`double_layer_bearing` (built if not given).
    **bearing
        Passed to :func:`double_layer_bearing` (structure, fidelity, lubrication, ...).
    """
    speeds = np.asarray(speeds, dtype=float)
    if system is None:
        system = assemble(double_layer_bearing(inner, outer, **bearing),
                          outputs=["Rs", "M_shaft"])
    rs, torque = np.empty_like(speeds), np.empty_like(speeds)
    x = None
    for k, w in enumerate(speeds):
        rs[k], torque[k], x = steady_ratio(system, w, loads, parameters, x_guess=x)
    return SpeedRatioSweep(speeds, rs, torque)
