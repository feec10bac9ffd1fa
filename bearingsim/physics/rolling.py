"""Hydrodynamic (EHL) rolling resistance of a lubricated elliptical contact.

In an elastohydrodynamic contact the pressure build-up in the inlet shears the lubricant even
in pure rolling; the resulting loss appears as a *hydrodynamic rolling force* ``F_R`` that
resists the rolling of each body. Its dependence on speed and viscosity, ``(eta u)^0.66``, is
the ``(nu n)^(2/3)`` of Palmgren's load-independent torque ``M0``
(:func:`~bearingsim.physics.friction.palmgren_m0`): the rolling force is the part of ``M0``
that a ball-level model resolves contact by contact.

Every function works on floats, numpy arrays and CasADi symbols; SI units.
"""

from __future__ import annotations

from typing import Any

from bearingsim.checks import guard_public_functions
from bearingsim.physical_checks import check_radii
from bearingsim.physics.film import (
    dimensionless_load,
    dimensionless_material,
    dimensionless_speed,
    ellipticity,
)
from bearingsim.symbolic import power
from bearingsim.validation import check_range

__all__ = ["ROLLING_FORCE_COEFFICIENT", "ROLLING_FORCE_EXPONENTS",
           "hydrodynamic_rolling_force", "rolling_resistance"]

ROLLING_FORCE_COEFFICIENT = 2.86
"""Leading constant of :func:`hydrodynamic_rolling_force` [-]."""
ROLLING_FORCE_EXPONENTS: dict[str, float] = {"k": 0.348, "G": 0.022, "U": 0.66, "W": 0.47}
"""Exponents of ellipticity, materials, speed and load parameter in
:func:`hydrodynamic_rolling_force` [-]."""


def hydrodynamic_rolling_force(U: Any, G: Any, W: Any, k: Any, E_eff: Any,  # noqa: N803
                               Rx: Any) -> Any:  # noqa: N803
    """Isothermal hydrodynamic rolling force of an elliptical EHL contact [N].

    ``F_R = 2.86 E' Rx^2 k^0.348 G^0.022 U^0.66 W^0.47``

    the curve fit of numerical EHL solutions of Houpert (L. Houpert, "Ball bearing and tapered
    roller bearing torque: analytical, numerical and experimental results", Tribology
    Transactions 45 (2002) 345-353), as given by Harris & Kotzalas (*Rolling Bearing Analysis*,
    5th ed., *Advanced Concepts of Bearing Technology*, ch. "Friction in rolling
    element-raceway contacts", hydrodynamic rolling force). Verification status: unverified;
    the coefficients have not been checked against the printed page. The tests check the
    formula's own scaling laws (``F ~ (eta u)^0.66``, ``F ~ Q^0.47``, dimensionless collapse)
    and its agreement with the ``(nu n)^(2/3)`` scaling of Palmgren's ``M0``. Isothermal:
    the inlet shear heating reduction (significant above ``u eta`` of order 1 Pa m) is not
    applied.

    Parameters
    ----------
    U, G, W : float, array or casadi.SX
        Hamrock-Dowson speed (``eta0 u / (E' Rx)``, >= 0), materials (``alpha E'``, >= 0) and
        load (``Q / (E' Rx^2)``, > 0) parameters [-]
        (:mod:`bearingsim.physics.film`).
    k : float, array or casadi.SX
        Ellipticity ``a/b`` [-], > 0.
    E_eff : float, array or casadi.SX
        Effective modulus ``E'`` [Pa], > 0 (2.275e11 steel on steel).
    Rx : float, array or casadi.SX
        Reduced radius in the rolling direction [m], > 0.

    Returns
    -------
    float, array or casadi.SX
        ``F_R`` [N], >= 0, on each body against its rolling.
    """
    where = "hydrodynamic_rolling_force"
    check_range(U, "U", "-", 0.0, None, where=where)
    check_range(G, "G", "-", 0.0, None, where=where)
    check_range(W, "W", "-", 0.0, None, low_inclusive=False, where=where)
    check_range(k, "k", "-", 0.0, None, low_inclusive=False, where=where)
    check_range(E_eff, "E_eff", "Pa", 0.0, None, low_inclusive=False, where=where)
    check_range(Rx, "Rx", "m", 0.0, None, low_inclusive=False, where=where)
    e = ROLLING_FORCE_EXPONENTS
    return (ROLLING_FORCE_COEFFICIENT * E_eff * Rx * Rx * power(k, e["k"]) * power(G, e["G"])
            * power(U, e["U"]) * power(W, e["W"]))


def rolling_resistance(Q: Any, u: Any, Rx: Any, Ry: Any, E_eff: Any, eta0: Any,  # noqa: N803
                       alpha: Any) -> Any:
    """Hydrodynamic rolling force of a contact from physical inputs [N].

    Forms ``U, G, W`` and the ellipticity ``k = 1.0339 (Ry/Rx)^0.636`` as for the Hamrock-Dowson
    film (:func:`~bearingsim.physics.film.hamrock_dowson`) and evaluates
    :func:`hydrodynamic_rolling_force`.

    Parameters
    ----------
    Q : float, array or casadi.SX
        Normal contact load [N], > 0.
    u : float, array or casadi.SX
        Entrainment speed [m/s], >= 0.
    Rx, Ry : float, array or casadi.SX
        Reduced radii along and across the rolling direction [m], > 0, ``Ry >= Rx``
        (swapped radii raise ParameterError, as in :mod:`bearingsim.physics.hertz`).
    E_eff : float, array or casadi.SX
        Effective modulus ``E'`` [Pa], > 0.
    eta0 : float, array or casadi.SX
        Dynamic viscosity at the inlet [Pa s], >= 0.
    alpha : float, array or casadi.SX
        Pressure-viscosity coefficient [1/Pa], >= 0.

    Returns
    -------
    float, array or casadi.SX
        ``F_R`` [N].
    """
    check_radii(Rx, Ry, "rolling_resistance")
    return hydrodynamic_rolling_force(
        dimensionless_speed(eta0, u, E_eff, Rx), dimensionless_material(alpha, E_eff),
        dimensionless_load(Q, E_eff, Rx), ellipticity(Rx, Ry), E_eff, Rx)


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
