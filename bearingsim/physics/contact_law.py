"""The load-deflection law of a Hertz point contact in the models' equations:
``Q = K max(delta, 0)^1.5`` and its tangent stiffness, optionally with ``max(delta, 0)``
smoothed so that an unloaded contact keeps the equations differentiable. ``K`` comes from
:func:`bearingsim.physics.hertz.load_deflection_constant`; the line contact of rollers has its
own law (:mod:`bearingsim.physics.line_contact`).
"""

from __future__ import annotations

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.validation import check_range

__all__ = ["contact_load", "contact_stiffness"]


def _compression(delta, smooth):
    if smooth is None:
        return op.fmax(delta, 0.0)
    check_range(smooth, "smooth", "m", 0.0, low_inclusive=False, where="contact_load")
    return op.smooth_max0(delta, smooth)


def contact_load(k_const, delta, smooth=None):
    """Hertz contact load ``Q = K max(delta, 0)^1.5`` [N].

    Parameters
    ----------
    k_const : float or array or SX
        Load-deflection constant K [N/m^1.5], >= 0.
    delta : float or array or SX
        Approach (overlap, positive in compression) [m], finite (any sign: a negative value
        is a gap and gives no load).
    smooth : float, optional
        If given, ``max(delta, 0)`` is replaced by the smooth
        ``(delta + sqrt(delta^2 + smooth^2)) / 2`` [m], differentiable everywhere for use in
        equations (error at most smooth/2 in delta).

    Returns
    -------
    Q [N], non-negative and non-decreasing in delta.

    Raises
    ------
    ParameterError
        For a negative or non-finite ``k_const``, a NaN or infinite ``delta`` or a
        non-positive ``smooth`` (symbolic values are passed through unchecked).
    """
    check_range(k_const, "k_const", "N/m^1.5", 0.0, where="contact_load")
    check_range(delta, "delta", "m", where="contact_load")
    return k_const * op.sqrt_power(_compression(delta, smooth), 1)


def contact_stiffness(k_const, delta, smooth=None):
    """Tangent contact stiffness ``dQ/d delta`` of :func:`contact_load` [N/m].

    ``1.5 K max(delta, 0)^0.5``, or with ``smooth`` the exact derivative of the smooth form,
    ``1.5 K s^0.5 (1 + delta / sqrt(delta^2 + smooth^2)) / 2``. Parameters are those of
    :func:`contact_load`.

    Parameters
    ----------
    k_const : float or array or SX
        Load-deflection constant K [N/m^1.5], >= 0.
    delta : float or array or SX
        Approach [m] (negative: a gap).
    smooth : float, optional
        Smoothing length [m], > 0 (None: exact).

    Returns
    -------
    float or array or SX
        dQ/d delta [N/m].
    """
    check_range(k_const, "k_const", "N/m^1.5", 0.0, where="contact_stiffness")
    check_range(delta, "delta", "m", where="contact_stiffness")
    stiffness = 1.5 * k_const * op.sqrt(_compression(delta, smooth))
    if smooth is None:
        return stiffness
    return stiffness * 0.5 * (1.0 + delta / op.smooth_abs(delta, smooth))


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
