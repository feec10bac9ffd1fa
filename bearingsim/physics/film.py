"""Elastohydrodynamic film thickness of elliptical contacts (Hamrock & Dowson) and the lambda ratio.

Inputs are the reduced radii ``Rx`` (rolling direction) and ``Ry`` (transverse) and the *effective*
modulus ``E' = 2 / ((1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b)`` of Hamrock & Dowson (note: twice the
``E*`` used in many Hertz texts). All values SI; every function works on floats, arrays and CasADi
symbols.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from bearingsim.checks import guard_public_functions
from bearingsim.physical_checks import (
    MAX_BALL_DIAMETER,
    MIN_LENGTH,
    check_diameter,
    check_modulus,
    check_radii,
    check_regularization,
)
from bearingsim.symbolic import cos, exp, power, smooth_abs, sqrt
from bearingsim.validation import check_range

__all__ = [
    "dimensionless_speed",
    "dimensionless_material",
    "dimensionless_load",
    "ellipticity",
    "minimum_film_thickness",
    "central_film_thickness",
    "FilmThickness",
    "hamrock_dowson",
    "entrainment_speed",
    "rolling_entrainment_speed",
    "lambda_ratio",
]


def _pos(value: Any, name: str, unit: str, where: str, strict: bool = True) -> Any:
    return check_range(value, name, unit, 0.0, None, low_inclusive=not strict, where=where)


def dimensionless_speed(eta0: Any, u: Any, E_eff: Any, Rx: Any) -> Any:  # noqa: N803
    """Speed parameter ``U = eta0 u / (E' Rx)`` [-] (Hamrock & Dowson 1977).

    Parameters
    ----------
    eta0 : float, array or casadi.SX
        Dynamic viscosity at atmospheric pressure [Pa s], >= 0.
    u : float, array or casadi.SX
        Entrainment (mean surface) speed [m/s], >= 0.
    E_eff : float
        Effective modulus ``E'`` [Pa], > 0.
    Rx : float, array or casadi.SX
        Reduced radius in the rolling direction [m], > 0.

    Returns
    -------
    float, array or casadi.SX
        ``U`` [-].
    """
    where = "dimensionless_speed"
    _pos(eta0, "eta0", "Pa s", where, strict=False)
    _pos(u, "u", "m/s", where, strict=False)
    check_modulus(E_eff, "E_eff", where)
    check_range(Rx, "Rx", "m", MIN_LENGTH, where=where)
    return eta0 * u / (E_eff * Rx)


def dimensionless_material(alpha: Any, E_eff: Any) -> Any:  # noqa: N803
    """Materials parameter ``G = alpha E'`` [-] (Hamrock & Dowson 1977).

    Parameters
    ----------
    alpha : float or casadi.SX
        Pressure-viscosity coefficient [1/Pa], >= 0.
    E_eff : float
        Effective modulus ``E'`` [Pa], > 0.

    Returns
    -------
    float or casadi.SX
        ``G`` [-].
    """
    _pos(alpha, "alpha", "1/Pa", "dimensionless_material", strict=False)
    check_modulus(E_eff, "E_eff", "dimensionless_material")
    return alpha * E_eff


def dimensionless_load(Q: Any, E_eff: Any, Rx: Any) -> Any:  # noqa: N803
    """Load parameter ``W = Q / (E' Rx^2)`` [-] (Hamrock & Dowson 1977).

    Parameters
    ----------
    Q : float, array or casadi.SX
        Normal contact load [N], > 0.
    E_eff : float
        Effective modulus ``E'`` [Pa], > 0.
    Rx : float, array or casadi.SX
        Reduced radius in the rolling direction [m], > 0.

    Returns
    -------
    float, array or casadi.SX
        ``W`` [-].
    """
    _pos(Q, "Q", "N", "dimensionless_load")
    check_modulus(E_eff, "E_eff", "dimensionless_load")
    check_range(Rx, "Rx", "m", MIN_LENGTH, where="dimensionless_load")
    return Q / (E_eff * Rx * Rx)


def ellipticity(Rx: Any, Ry: Any) -> Any:  # noqa: N803
    """Ellipticity ``k = a/b = 1.0339 (Ry/Rx)^0.636`` [-] (Brewe & Hamrock 1977 approximation,
    used with the Hamrock-Dowson formulas; Hamrock & Dowson, *Ball Bearing Lubrication*, 1981).
    Against the exact Hertz value it is within 3.4 % for ``1 <= Ry/Rx <= 50`` and 6.3 % high at
    ``Ry/Rx = 100`` (measured with :func:`bearingsim.physics.hertz.elliptic_parameters`).
    Hamrock's later texts use ``(Ry/Rx)^(2/pi)`` instead (Hamrock & Brewe 1983), which is 3.1 % to
    3.4 % lower than this on ``1 <= Ry/Rx <= 100``.

    Parameters
    ----------
    Rx, Ry : float, array or casadi.SX
        Reduced radii in the rolling and transverse direction [m], > 0, ``Ry >= Rx``
        (:func:`bearingsim.physical_checks.check_radii`; swapped radii are rejected).

    Returns
    -------
    float, array or casadi.SX
        ``k`` [-], >= 1.0339.
    """
    check_radii(Rx, Ry, "ellipticity")
    return 1.0339 * power(Ry / Rx, 0.636)


def minimum_film_thickness(U: Any, G: Any, W: Any, k: Any, Rx: Any) -> Any:  # noqa: N803
    """Hamrock-Dowson minimum film thickness ``h_min = Rx 3.63 U^0.68 G^0.49 W^-0.073
    (1 - exp(-0.68 k))`` [m].

    Hamrock & Dowson, "Isothermal elastohydrodynamic lubrication of point contacts, Part III",
    J. Lubr. Technol. 99 (1977) 264-276; docs/studies.md, section C.

    Parameters
    ----------
    U, G, W : float, array or casadi.SX
        Dimensionless speed (>= 0), materials (>= 0) and load (> 0) parameters [-].
    k : float, array or casadi.SX
        Ellipticity ``a/b`` [-], > 0.
    Rx : float, array or casadi.SX
        Reduced radius in the rolling direction [m], > 0.

    Returns
    -------
    float, array or casadi.SX
        ``h_min`` [m].
    """
    _check_dimensionless(U, G, W, k, Rx, "minimum_film_thickness")
    return (Rx * 3.63 * power(U, 0.68) * power(G, 0.49) * power(W, -0.073)
            * (1.0 - exp(-0.68 * k)))


def central_film_thickness(U: Any, G: Any, W: Any, k: Any, Rx: Any) -> Any:  # noqa: N803
    """Hamrock-Dowson central film thickness ``h_c = Rx 2.69 U^0.67 G^0.53 W^-0.067
    (1 - 0.61 exp(-0.73 k))`` [m].

    Hamrock & Dowson, "Isothermal elastohydrodynamic lubrication of point contacts, Part III"
    (1977); Hamrock, *Fundamentals of Fluid Film Lubrication*.

    Parameters
    ----------
    U, G, W : float, array or casadi.SX
        Dimensionless speed, materials and load parameters [-].
    k : float, array or casadi.SX
        Ellipticity ``a/b`` [-].
    Rx : float, array or casadi.SX
        Reduced radius in the rolling direction [m].

    Returns
    -------
    float, array or casadi.SX
        ``h_c`` [m].
    """
    _check_dimensionless(U, G, W, k, Rx, "central_film_thickness")
    return (Rx * 2.69 * power(U, 0.67) * power(G, 0.53) * power(W, -0.067)
            * (1.0 - 0.61 * exp(-0.73 * k)))


def _check_dimensionless(U, G, W, k, Rx, where):  # noqa: N803
    _pos(U, "U", "-", where, strict=False)
    _pos(G, "G", "-", where, strict=False)
    _pos(W, "W", "-", where)
    _pos(k, "k", "-", where)
    check_range(Rx, "Rx", "m", MIN_LENGTH, where=where)


@dataclass(frozen=True)
class FilmThickness:
    """Result of :func:`hamrock_dowson` (SI).

    Attributes
    ----------
    h_min, h_c : float, array or casadi.SX
        Minimum and central film thickness [m].
    U, G, W, k : float, array or casadi.SX
        Dimensionless parameters and ellipticity [-].
    """

    h_min: Any
    h_c: Any
    U: Any  # noqa: N815
    G: Any  # noqa: N815
    W: Any  # noqa: N815
    k: Any


def hamrock_dowson(
    Q: Any,  # noqa: N803
    u: Any,
    Rx: Any,  # noqa: N803
    Ry: Any,  # noqa: N803
    E_eff: float,  # noqa: N803
    eta0: Any,
    alpha: Any,
) -> FilmThickness:
    """Minimum and central film thickness of an elliptical contact from physical inputs.

    Checked against a published answer: Stachowiak & Batchelor's *Engineering Tribology*
    chapter 7 problem of a ball rolling down an oiled plate (h_min 0.059 and 0.281 um,
    reproduced to the printed digits; ``tests/physics/test_published_contact_film.py``). That
    book writes the formula with the reduced radius ``R'`` where Hamrock & Dowson use ``Rx``;
    this function follows Hamrock & Dowson. No printed result of a ball *bearing* example
    (e.g. Hamrock's 209 bearing) was retrievable.

    Computes ``U, G, W, k`` and evaluates :func:`minimum_film_thickness` and
    :func:`central_film_thickness` (Hamrock & Dowson 1977). Take ``eta0``, ``alpha`` from a
    lubricant at the inlet temperature, e.g. ``oil.dynamic_viscosity(T)``.

    Parameters
    ----------
    Q : float, array or casadi.SX
        Contact load [N], > 0.
    u : float, array or casadi.SX
        Entrainment speed [m/s], >= 0 (:func:`entrainment_speed`).
    Rx, Ry : float, array or casadi.SX
        Reduced radii along and across the rolling direction [m], > 0, ``Ry >= Rx``
        (swapped radii raise ParameterError).
    E_eff : float
        Effective modulus ``E'`` [Pa] (2.275e11 for steel on steel).
    eta0 : float, array or casadi.SX
        Dynamic viscosity [Pa s].
    alpha : float, array or casadi.SX
        Pressure-viscosity coefficient [1/Pa].

    Returns
    -------
    FilmThickness
        ``h_min``, ``h_c`` [m] and ``U, G, W, k`` [-].
    """
    check_radii(Rx, Ry, "hamrock_dowson")
    U = dimensionless_speed(eta0, u, E_eff, Rx)  # noqa: N806
    G = dimensionless_material(alpha, E_eff)  # noqa: N806
    W = dimensionless_load(Q, E_eff, Rx)  # noqa: N806
    k = ellipticity(Rx, Ry)
    return FilmThickness(
        h_min=minimum_film_thickness(U, G, W, k, Rx),
        h_c=central_film_thickness(U, G, W, k, Rx),
        U=U, G=G, W=W, k=k,
    )


def entrainment_speed(u_a: Any, u_b: Any, v_reg: float = 1e-9) -> Any:
    """Entrainment (mean rolling) speed ``u = |u_a + u_b| / 2`` [m/s] (Hamrock & Dowson).

    Parameters
    ----------
    u_a, u_b : float, array or casadi.SX
        Surface speeds of the two bodies relative to the contact, along the rolling
        direction [m/s].
    v_reg : float
        Regularization of the magnitude [m/s] (smooth through zero).

    Returns
    -------
    float, array or casadi.SX
        ``u`` [m/s], >= 0.
    """
    check_range(u_a, "u_a", "m/s", where="entrainment_speed")
    check_range(u_b, "u_b", "m/s", where="entrainment_speed")
    check_regularization(v_reg, "v_reg", "m/s", "entrainment_speed")
    return smooth_abs(0.5 * (u_a + u_b), v_reg)


def rolling_entrainment_speed(
    omega_rel: Any,
    Dw: float,  # noqa: N803
    dm: float,
    contact_angle: float = 0.0,
    v_reg: float = 1e-9,
) -> Any:
    """Entrainment speed of both ball-race contacts in pure rolling [m/s].

    ``u = dm/4 (1 - gamma^2) |omega_i - omega_o|``, ``gamma = Dw cos(alpha) / dm``: the surface
    speed of either race relative to the cage (Harris & Kotzalas, 5th ed., Essential Concepts,
    kinematics of rolling bearings). Equal at the inner and outer contact.

    Parameters
    ----------
    omega_rel : float, array or casadi.SX
        Inner minus outer ring speed [rad/s].
    Dw : float
        Ball diameter [m], in (0, 0.5] (a larger value is taken for millimetres, see
        :func:`~bearingsim.physical_checks.check_diameter`).
    dm : float
        Pitch diameter [m], > Dw and at most 6.
    contact_angle : float
        Contact angle [rad], in [0, pi/2].
    v_reg : float
        Regularization of the magnitude [m/s].

    Returns
    -------
    float, array or casadi.SX
        ``u`` [m/s], >= 0.
    """
    where = "rolling_entrainment_speed"
    check_diameter(Dw, "Dw", where, MAX_BALL_DIAMETER)
    check_diameter(dm, "dm", where)
    check_range(dm, "dm", "m", Dw, None, low_inclusive=False, where=where)
    check_range(contact_angle, "contact_angle", "rad", 0.0, 1.5707963267948966, where=where)
    check_range(omega_rel, "omega_rel", "rad/s", where=where)
    gamma = Dw * cos(contact_angle) / dm
    return smooth_abs(0.25 * dm * (1.0 - gamma * gamma) * omega_rel, v_reg)


def lambda_ratio(h_min: Any, sigma_a: float, sigma_b: float) -> Any:
    """Film parameter ``Lambda = h_min / sqrt(sigma_a^2 + sigma_b^2)`` [-] (Hamrock, *Fundamentals
    of Fluid Film Lubrication*; Harris & Kotzalas, 5th ed., Advanced Concepts).

    Parameters
    ----------
    h_min : float, array or casadi.SX
        Minimum film thickness [m], >= 0.
    sigma_a, sigma_b : float
        RMS surface roughness of the two surfaces [m], >= 0, not both zero.

    Returns
    -------
    float, array or casadi.SX
        ``Lambda`` [-].
    """
    where = "lambda_ratio"
    _pos(h_min, "h_min", "m", where, strict=False)
    _pos(sigma_a, "sigma_a", "m", where, strict=False)
    _pos(sigma_b, "sigma_b", "m", where, strict=False)
    composite = sqrt(sigma_a * sigma_a + sigma_b * sigma_b)
    check_range(composite, "composite roughness", "m", 0.0, None, low_inclusive=False, where=where)
    return h_min / composite


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
