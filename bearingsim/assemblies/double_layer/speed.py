"""The double-layer bearing's speeds: the limiting shaft speed of two nested layers and the speed
distribution ratio ``Rs``."""

from __future__ import annotations

from bearingsim.catalog.geometry import check_speed_limit, speed_input_bounds
from bearingsim.language import Input

RS_REGULARIZATION = 1e-6
"""Shaft speed [rad/s] below which the speed ratio Rs is regularized (:func:`speed_ratio`)."""


LIMIT_TEXT = ("the sum of the limiting speeds of {} and {} (the highest shaft speed at which "
               "both layers can run within their limits)")


def shaft_speed_limit(gi, go) -> float | None:
    """The limiting shaft speed of a double-layer bearing [rad/s]: the inner layer runs at
    ``w_shaft (1 - Rs)`` and the outer at ``w_shaft Rs``, so both are within their catalogue
    limiting speeds ``n_i``, ``n_o`` at best (``Rs = n_o / (n_i + n_o)``) up to
    ``w_shaft = n_i + n_o``; None when a layer has no limiting speed.

    Parameters
    ----------
    gi, go : BearingGeometry
        Inner and outer layer.

    Returns
    -------
    float or None
    """
    if gi.limiting_speed is None or go.limiting_speed is None:
        return None
    return gi.limiting_speed + go.limiting_speed


def _check_shaft_speed(speed, gi, go) -> None:
    """A constant shaft speed [rad/s] against :func:`shaft_speed_limit` (a function of time is
    not checked here)."""
    if isinstance(speed, (int, float)):
        check_speed_limit(speed, shaft_speed_limit(gi, go), "double_layer_bearing",
                          LIMIT_TEXT.format(gi.designation, go.designation))


def _shaft_speed_input(gi, go) -> Input:
    """The required input ``shaft_speed`` [rad/s], bounded by :func:`shaft_speed_limit`."""
    return Input(0.0, "rad/s", "imposed shaft speed", required=True,
                 **speed_input_bounds(shaft_speed_limit(gi, go)))


def speed_ratio(w_middle, w_shaft):
    """Speed distribution ratio ``Rs = w_middle / w_shaft`` [1], defined at rest.

    ``Rs = w_middle w_shaft / (w_shaft^2 + w_reg^2)`` with ``w_reg`` =
    :data:`RS_REGULARIZATION`: exact to a relative 1e-4 from a shaft speed of
    ``100 w_reg`` (1e-4 rad/s, 0.001 r/min) and 0 at rest. A middle ring at rest with the shaft
    gives 0, the limit of a spin-up from rest (the middle ring lags the shaft); a middle ring
    still turning when the shaft stops gives a large ratio there (``w_middle / w_shaft`` grows
    without bound) that falls back to 0 at rest.

    Parameters
    ----------
    w_middle : float or array_like or casadi.SX
        Middle ring speed [rad/s].
    w_shaft : float or array_like or casadi.SX
        Shaft speed [rad/s].

    Returns
    -------
    float or array_like or casadi.SX
        The speed ratio Rs [1], of the arguments' type.
    """
    return w_middle * w_shaft / (w_shaft**2 + RS_REGULARIZATION**2)
