"""Checks of physical quantities in SI units and their plausible limits: diameters in metres
(a millimetre value is caught), the reduced radii of an elliptical contact, Young's moduli (a
value in GPa is caught) and regularization widths. Each raises
:class:`~bearingsim.errors.ParameterError` naming the argument, its unit and valid range; the
generic checks they build on are in :mod:`bearingsim.validation`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim import symbolic as op
from bearingsim.errors import ParameterError, PlasticDeformationWarning
from bearingsim.validation import check_range

__all__ = [
    "MIN_LENGTH",
    "MODULUS_RANGE",
    "MIN_REGULARIZATION",
    "MAX_BALL_DIAMETER",
    "MAX_BEARING_DIAMETER",
    "check_diameter",
    "check_modulus",
    "check_radii",
    "check_regularization",
    "check_static_pressure",
]

MIN_LENGTH = 1e-9
"""Smallest contact radius or film length [m] (1 nm, a few atoms): below it a length is a
unit or sign slip, and its square underflows in the dimensionless groups."""
MODULUS_RANGE = (1e8, 1e13)
"""Valid Young's or effective modulus [Pa]: polymers about 3e9, steel 2.08e11, ceramics 3.1e11
(a value in GPa falls below)."""
MAX_BEARING_DIAMETER = 6.0
"""Largest plausible pitch, bore or outside diameter [m] (large slewing bearings: a few metres);
a larger value is taken for a millimetre value passed as metres."""
MAX_BALL_DIAMETER = 0.5
"""Largest plausible ball diameter [m] (slewing-bearing balls stay below about 0.15 m)."""


def check_diameter(value, name: str, where: str, high: float = MAX_BEARING_DIAMETER):
    """Check a diameter in metres: finite, > 0 and at most ``high`` (a catalogue-unit slip).

    Bearing catalogues give diameters in millimetres; the SI functions of bearingsim take
    metres. A value above ``high`` is reported as a likely millimetre value. Symbolic (CasADi)
    values are passed through unchecked.

    Parameters
    ----------
    value : float, array or casadi.SX
        The diameter [m].
    name : str
        Argument name, used in the message.
    where : str
        Function name, used in the message.
    high : float
        Largest plausible value [m]: :data:`MAX_BEARING_DIAMETER` (pitch, bore and outside
        diameters) or :data:`MAX_BALL_DIAMETER` (balls).

    Returns
    -------
    The value unchanged.

    Raises
    ------
    ParameterError
        ``"<where>: <name> = 40 [m] is outside the valid range (0, 6] [m] (did you pass
        mm?)"`` above ``high``; the usual range message for a value <= 0 or not finite.
    """
    check_range(value, name, "m", 0.0, low_inclusive=False, where=where)
    try:
        check_range(value, name, "m", 0.0, high, low_inclusive=False, where=where)
    except ParameterError as exc:
        raise ParameterError(f"{exc} (did you pass mm?)") from None
    return value


def check_radii(rx, ry, where: str):
    """Check reduced radii of an elliptical contact: ``Rx > 0``, ``Ry > 0`` and ``Ry >= Rx``.

    The Hertz, Hamrock-Dowson and rolling-resistance formulas of bearingsim take ``Rx`` along
    and ``Ry`` across the rolling direction and assume ``Ry >= Rx`` (ellipticity ``k = a/b
    >= 1``). Symbolic (CasADi) radii are checked for sign only when numbers are bound.

    Parameters
    ----------
    rx, ry : float, array or casadi.SX
        Reduced radii along and across the rolling direction [m], > 0, ``ry >= rx``.
    where : str
        Function name, used in the message.

    Raises
    ------
    ParameterError
        For non-positive or non-finite radii, or ``Ry < Rx`` (swapped radii).
    """
    check_range(rx, "Rx", "m", MIN_LENGTH, where=where)
    check_range(ry, "Ry", "m", MIN_LENGTH, where=where)
    if not op.is_symbolic(rx, ry) and np.any(np.asarray(ry) < np.asarray(rx)):
        raise ParameterError(
            f"{where}: need Ry >= Rx (Ry across, Rx along the rolling direction) [m], "
            f"got Rx = {rx}, Ry = {ry}; swap the radii for a contact elongated along x"
        )


MIN_REGULARIZATION = 1e-100
"""Smallest regularization width: its square must stay a normal float (a width of 1e-300
squares to 0, and ``x / sqrt(x^2 + w^2)`` becomes 0/0 at x = 0)."""


def check_regularization(value: Any, name: str, unit: str, where: str) -> Any:
    """A regularization width (of ``|x|``, a sign, an eccentricity): finite and at least
    :data:`MIN_REGULARIZATION`.

    Parameters
    ----------
    value : object
        The value to check.
    name : str
        Argument name, for the message.
    unit : str
        Unit of the value, for the message.
    where : str
        The component or function, for the message.

    Returns
    -------
    float or array or SX
        ``value``, checked.

    Raises
    ------
    ParameterError
        Naming the argument, its unit and the valid range.
    """
    return check_range(value, name, unit, MIN_REGULARIZATION, None, where=where)


def check_modulus(value: Any, name: str, where: str) -> Any:
    """A Young's or effective modulus [Pa] within :data:`MODULUS_RANGE`.

    Parameters
    ----------
    value : object
        The value to check.
    name : str
        Argument name, for the message.
    where : str
        The component or function, for the message.

    Returns
    -------
    float or array or SX
        ``value`` [Pa], checked.

    Raises
    ------
    ParameterError
        Outside it, with a hint for a value in GPa.
    """
    try:
        return check_range(value, name, "Pa", *MODULUS_RANGE, where=where)
    except ParameterError as exc:
        raise ParameterError(f"{exc} (bearing materials: polymers about 3e9 Pa, steel "
                             f"2.08e11 Pa, ceramics 3.1e11 Pa; did you pass GPa?)") from None


def check_static_pressure(p_max: float, limit: float, exponent: str, where: str,
                          loads: str) -> None:
    """A quasi-static solution's largest contact pressure against ISO 76: refused above that of
    :data:`~bearingsim.checks.MAX_STATIC_LOAD_FACTOR` times the static load rating C0 (beyond
    the strength of bearing steel: a unit slip), warned about above ``limit`` (the pressure
    of C0: the raceways deform permanently).

    Parameters
    ----------
    p_max : float
        Largest contact pressure [Pa].
    limit : float
        ISO 76's pressure at C0 [Pa] (4.2e9 ball bearings, 4.0e9 roller bearings).
    exponent : str
        The power of the load the pressure grows as ("1/3" point contact, "1/2" line
        contact), which gives the pressure of 10 C0.
    where : str
        The function and bearing, for the messages.
    loads : str
        The loads, as the messages name them.

    Raises
    ------
    ParameterError
        Above the pressure of 10 C0.

    Warns
    -----
    PlasticDeformationWarning
        Above ``limit``.
    """
    import warnings

    from bearingsim.checks import MAX_STATIC_LOAD_FACTOR

    numerator, denominator = (float(v) for v in exponent.split("/"))
    highest = limit * MAX_STATIC_LOAD_FACTOR ** (numerator / denominator)
    if p_max > highest:
        raise ParameterError(
            f"{where}: the loads {loads} give a largest contact pressure of {p_max / 1e6:.0f} "
            f"MPa, above the {highest / 1e6:.0f} MPa of {MAX_STATIC_LOAD_FACTOR:g} x the static "
            f"load rating C0 (ISO 76's {limit / 1e6:.0f} MPa at C0; the pressure grows as the "
            f"load to the power {exponent}): beyond the strength of bearing steel (N given for "
            f"kN?)")
    if p_max > limit:
        warnings.warn(f"{where}: the largest contact pressure is {p_max / 1e6:.0f} MPa, above "
                      f"the {limit / 1e6:.0f} MPa of ISO 76's static load rating: the raceways "
                      f"deform permanently (loads {loads})", PlasticDeformationWarning,
                      stacklevel=3)
