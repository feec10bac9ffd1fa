"""Nominal values of the FMU's states: the magnitudes importers scale absolute tolerances with.

An importer integrating a Model Exchange FMU sets the absolute tolerance of state ``i`` to
``rtol * nominal_i``. With every nominal 1 the duplex pair's displacements (1e-6 to 3.5e-5 m)
drown in an absolute tolerance of ``rtol`` metres. The nominals come from the model's own
scales:

* the start values are the operating point the model was built for: the preload deflection
  of a duplex pair, the ball and cage speeds of a ball-level bearing at its shaft speed;
* the states with no scale of their own (zero start: a lateral displacement, a tilt, a
  velocity) take it from the dynamics that couple them to those, by balancing the Jacobian
  ``d der(x)/dx`` at the start point (``scipy.linalg.matrix_balance``: the diagonal
  similarity ``D^-1 J D`` with rows and columns of equal norm, in powers of 2). For a
  spring-mass pair ``der(q) = v``, ``der(v) = -k/m q`` it gives ``v ~ sqrt(k/m) q``: the
  velocity scale of an oscillation with the displacement's scale; for a tilt coupled to a
  displacement, the tilt whose moment matches that displacement's force.

The balanced scales are relative; the states with a non-zero start anchor them (the largest
ratio ``|x0| / d`` over those states), and no nominal is below the state's own ``|x0|``. A model
whose states all start at zero has no scale to anchor: its nominals stay 1.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

__all__ = ["state_nominals"]


def state_nominals(jacobian: np.ndarray, x0: np.ndarray) -> np.ndarray:
    """Nominal magnitudes of the states.

    Parameters
    ----------
    jacobian : numpy.ndarray
        ``d der(x)/dx`` at the start point, shape (nx, nx) [unit of x_i / (s unit of x_j)].
    x0 : numpy.ndarray
        Start values of the states [state units].

    Returns
    -------
    numpy.ndarray
        Positive nominal values [state units]; all 1 when no state has a non-zero start value
        or the Jacobian is not finite.
    """
    x0 = np.abs(np.asarray(x0, dtype=float))
    jacobian = np.asarray(jacobian, dtype=float)
    anchored = x0 > 0
    if x0.size == 0 or not anchored.any() or not np.all(np.isfinite(jacobian)):
        return np.ones_like(x0)
    _, (scale, _) = scipy.linalg.matrix_balance(jacobian, permute=False, separate=True)
    anchor = np.max(x0[anchored] / scale[anchored])
    return np.maximum(anchor * scale, x0)
