"""Hertz theory of elastic point (elliptical) contact between a ball and a raceway.

Every function works on floats, numpy arrays and CasADi SX alike (math through
:mod:`bearingsim.symbolic`), so components can put them into symbolic equations. The inputs
come from :mod:`bearingsim.physics.materials` (the effective modulus of two materials) and
:mod:`bearingsim.physics.contact_curvature` (the effective radii of a ball-raceway contact).

Notation (Hamrock, *Fundamentals of Fluid Film Lubrication*, chapter "Elastohydrodynamic
lubrication of elliptical conjunctions" / "Simplified solutions for stresses and deformations"):
``Rx`` is the effective radius in the rolling direction and ``Ry`` the one across it
(``1/Rx = 1/r_ax + 1/r_bx``), ``R = 1/(1/Rx + 1/Ry)`` the curvature sum radius,
``alpha_r = Ry/Rx >= 1``, ``k = a/b >= 1`` the ellipticity with ``a`` the semi-axis across the
rolling direction, ``K(m)``, ``E(m)`` the complete elliptic integrals with ``m = 1 - 1/k^2`` and
``E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` the effective modulus. The same relations are given
with Harris's notation in Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., *Essential
Concepts of Bearing Technology*, chapter "Contact stress and deformation".
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.physical_checks import check_radii
from bearingsim.physics.contact_curvature import raceway_radii
from bearingsim.physics.materials import STEEL, Material, effective_modulus
from bearingsim.validation import check_range

if TYPE_CHECKING:
    from bearingsim.catalog import BearingGeometry

__all__ = [
    "EllipticParameters",
    "HertzContact",
    "elliptic_parameters",
    "ellipticity",
    "semi_axes",
    "approach",
    "max_pressure",
    "load_deflection_constant",
    "combined_load_deflection_constant",
    "bearing_load_deflection_constants",
    "orthogonal_shear_stress",
    "hertz_contact",
]

METHODS = ("exact", "hamrock_brewe")
_NEWTON_STEPS = 5
_M_MIN = 1e-12  # smallest elliptic parameter used: k - 1 < 1e-12 (circular contact)
_M_MAX = 1.0 - 1e-15


class EllipticParameters(NamedTuple):
    """Ellipticity and complete elliptic integrals of a contact.

    Attributes
    ----------
    k : ellipticity a/b [-]
    first_kind : K(m), m = 1 - 1/k^2 [-]
    second_kind : E(m) [-]
    """

    k: Any
    first_kind: Any
    second_kind: Any


@dataclass(frozen=True)
class HertzContact:
    """Result of :func:`hertz_contact` (floats, arrays or SX).

    Attributes
    ----------
    k : ellipticity a/b [-]
    a : semi-axis across the rolling direction (major) [m]
    b : semi-axis in the rolling direction (minor) [m]
    approach : elastic approach of the two bodies delta [m]
    max_pressure : maximum Hertz pressure [Pa]
    load_deflection_constant : K in Q = K delta^1.5 [N/m^1.5]
    tau0 : maximum subsurface orthogonal shear stress [Pa]
    z0 : its depth below the surface [m]
    """

    k: Any
    a: Any
    b: Any
    approach: Any
    max_pressure: Any
    load_deflection_constant: Any
    tau0: Any
    z0: Any


def _check_method(method: str) -> None:
    if method not in METHODS:
        raise ParameterError(f"method must be one of {METHODS}, got {method!r}")


def _hamrock_brewe(alpha_r):
    """Brewe & Hamrock (1977) curve fits for k, K, E as functions of alpha_r = Ry/Rx."""
    k = 1.0339 * op.power(alpha_r, 0.6360)
    first = 1.5277 + 0.6023 * op.log(alpha_r)
    second = 1.0003 + 0.5968 / alpha_r
    return k, first, second


def _exact_parameter(alpha_r):
    """Elliptic parameter m solving Hertz's ellipticity equation, by a fixed number of Newton steps.

    The equation ``F(rho) = ((k^2 + 1) E - 2 K) / ((k^2 - 1) E)`` is written in m = 1 - 1/k^2 as
    ``2 B(m) / E(m) - 1 = (alpha_r - 1) / (alpha_r + 1)`` with ``B = (E - (1 - m) K) / m``,
    which has no spurious root at k = 1. ``dK/dm = B / (2 (1 - m))``, ``dE/dm = -(K - B) / 2``,
    ``dB/dm = (K/2 - B) / m``. Started from Brewe & Hamrock's k, five steps converge to better
    than 1e-8 in k for 1 <= alpha_r <= 1e4; m is kept in [1e-12, 1 - 1e-15] so that no step
    produces NaN (a circular contact gives k - 1 < 1e-8).
    """
    target = (alpha_r - 1.0) / (alpha_r + 1.0)
    k0 = _hamrock_brewe(alpha_r)[0]
    m = op.fmin(1.0 - 1.0 / (k0 * k0), _M_MAX)  # the fit's k of a huge alpha_r rounds m to 1
    for _ in range(_NEWTON_STEPS):
        first, second = op.ellipk(m), op.ellipe(m)
        b_int = (second - (1.0 - m) * first) / m
        residual = 2.0 * b_int / second - 1.0 - target
        d_b = (0.5 * first - b_int) / m
        d_e = -0.5 * (first - b_int)
        slope = 2.0 * (d_b * second - b_int * d_e) / (second * second)
        m = op.fmin(op.fmax(m - residual / slope, _M_MIN), _M_MAX)
    return m


def elliptic_parameters(rx, ry, method: str = "exact") -> EllipticParameters:
    """Ellipticity k and complete elliptic integrals K, E of a Hertz point contact.

    ``method="exact"`` solves Hertz's transcendental equation (Harris & Kotzalas, chapter
    "Contact stress and deformation"; Hamrock) with exact complete elliptic integrals, by a fixed
    count of Newton steps so that SX inputs stay symbolic. ``method="hamrock_brewe"`` uses the
    curve fits of Brewe & Hamrock (1977), ``k = 1.0339 alpha_r^0.636``,
    ``E = 1.0003 + 0.5968 / alpha_r``, ``K = 1.5277 + 0.6023 ln(alpha_r)`` (the fits given by
    Harris & Kotzalas and by Hamrock & Dowson, *Ball Bearing Lubrication*, 1981; the method name
    is kept for compatibility). Hamrock & Brewe (1983) later replaced them by
    ``k = alpha_r^(2/pi)``, ``E = 1 + (pi/2 - 1)/alpha_r``, ``K = pi/2 + (pi/2 - 1) ln(alpha_r)``,
    the forms of Hamrock's *Fundamentals of Fluid Film Lubrication*, which are not implemented
    here. Against the exact solution the 1977 fits are within 3.4 % (k), 1.7 % (E) and 2.8 % (K)
    for 1 <= alpha_r <= 10 (measured; the fit range stated in the paper was not retrievable);
    the error in k grows to 6 % at alpha_r = 100.

    Parameters
    ----------
    rx, ry : float or array or SX
        Effective radii along and across the rolling direction [m], ``Ry >= Rx``.
    method : {"exact", "hamrock_brewe"}

    Returns
    -------
    EllipticParameters
        (k [-], K [-], E [-]).

    References
    ----------
    Brewe, D. E., Hamrock, B. J. (1977), Simplified solution for elliptical-contact deformation
    between two elastic solids, J. Lubr. Technol. 99(4), 485-487 (the fits used here).
    Hamrock, B. J., Brewe, D. E. (1983), Simplified solution for stresses and deformations,
    J. Lubr. Technol. 105(2), 171-177 (the later ``alpha_r^(2/pi)`` forms).
    """
    _check_method(method)
    check_radii(rx, ry, "elliptic_parameters")
    alpha_r = op.fmax(ry / rx, 1.0)
    if method == "hamrock_brewe":
        return EllipticParameters(*_hamrock_brewe(alpha_r))
    m = _exact_parameter(alpha_r)
    return EllipticParameters(1.0 / op.sqrt(1.0 - m), op.ellipk(m), op.ellipe(m))


def ellipticity(rx, ry, method: str = "exact"):
    """Ellipticity ``k = a/b`` [-] of a Hertz point contact; see :func:`elliptic_parameters`.

    Parameters
    ----------
    rx, ry : float or array
        Effective radii of curvature in the rolling and transverse directions [m], > 0.
    method : {"exact", "hamrock_brewe"}
        Elliptic parameters exact or by Hamrock and Brewe's fit.

    Returns
    -------
    float or array
        k = a/b [-].
    """
    return elliptic_parameters(rx, ry, method).k


def _unit_load_semi_axes(rx, ry, e_eff, params: EllipticParameters):
    """Semi-axes a, b at unit load: ``a = (6 k^2 E R / (pi E'))^(1/3)``, ``b = a / k`` (Hamrock)."""
    k, _, second = params
    r = rx * ry / (rx + ry)
    a1 = op.power(6.0 * k * k * second * r / (np.pi * e_eff), 1.0 / 3.0)
    return a1, a1 / k


def _load_deflection(rx, ry, e_eff, params: EllipticParameters):
    """``K = pi k E' sqrt(2 E R / 9) / K(m)^1.5`` (Hamrock), so that ``Q = K delta^1.5``.

    From ``delta = K(m) (9 / (2 E R) (Q / (pi k E'))^2)^(1/3)``.
    """
    k, first, second = params
    r = rx * ry / (rx + ry)
    return np.pi * k * e_eff * op.sqrt(2.0 * second * r / 9.0) / op.power(first, 1.5)


def _check_contact(load, rx, ry, e_eff, method, where):
    _check_method(method)
    check_range(load, "load", "N", 0.0, where=where)
    check_range(e_eff, "e_eff", "Pa", 0.0, low_inclusive=False, where=where)
    return elliptic_parameters(rx, ry, method)


def semi_axes(load, rx, ry, e_eff, method: str = "exact"):
    """Semi-axes of the contact ellipse (Hamrock; Harris & Kotzalas).

    Parameters
    ----------
    load : float or array or SX
        Normal contact load Q [N], >= 0.
    rx, ry : float or array or SX
        Effective radii [m], ``Ry >= Rx``.
    e_eff : float or array or SX
        Effective modulus E' [Pa], see :func:`~bearingsim.physics.materials.effective_modulus`.
    method : {"exact", "hamrock_brewe"}

    Returns
    -------
    (a, b) : tuple
        Semi-axes across (major) and along (minor) the rolling direction [m].
    """
    params = _check_contact(load, rx, ry, e_eff, method, "semi_axes")
    a1, b1 = _unit_load_semi_axes(rx, ry, e_eff, params)
    scale = op.power(load, 1.0 / 3.0)
    return a1 * scale, b1 * scale


def load_deflection_constant(rx, ry, e_eff, method: str = "exact"):
    """Load-deflection constant K of one contact, ``Q = K delta^1.5`` [N/m^1.5] (Hamrock).

    Parameters
    ----------
    rx, ry : float or array or SX
        Effective radii [m], ``Ry >= Rx``; see
        :func:`~bearingsim.physics.contact_curvature.raceway_radii`.
    e_eff : float or array or SX
        Effective modulus E' [Pa].
    method : {"exact", "hamrock_brewe"}

    Returns
    -------
    K [N/m^1.5]
    """
    params = _check_contact(0.0, rx, ry, e_eff, method, "load_deflection_constant")
    return _load_deflection(rx, ry, e_eff, params)


def approach(load, rx, ry, e_eff, method: str = "exact"):
    """Elastic approach ``delta = (Q / K)^(2/3)`` of the two bodies [m] (Hamrock).

    Parameters are those of :func:`semi_axes`. Returns delta [m].

    Parameters
    ----------
    load : float or array
        Contact load [N], >= 0.
    rx, ry : float or array
        Effective radii of curvature in the rolling and transverse directions [m], > 0.
    e_eff : float
        Effective modulus [Pa], > 0 (:func:`~bearingsim.physics.materials.effective_modulus`).
    method : {"exact", "hamrock_brewe"}
        Elliptic parameters exact or by Hamrock and Brewe's fit.

    Returns
    -------
    float or array
        Approach delta [m].
    """
    params = _check_contact(load, rx, ry, e_eff, method, "approach")
    return op.power(load / _load_deflection(rx, ry, e_eff, params), 2.0 / 3.0)


def max_pressure(load, rx, ry, e_eff, method: str = "exact"):
    """Maximum Hertz pressure ``p_max = 3 Q / (2 pi a b)`` [Pa] (zero at zero load).

    Parameters are those of :func:`semi_axes`. Returns p_max [Pa].

    Parameters
    ----------
    load : float or array
        Contact load [N], >= 0.
    rx, ry : float or array
        Effective radii of curvature in the rolling and transverse directions [m], > 0.
    e_eff : float
        Effective modulus [Pa], > 0 (:func:`~bearingsim.physics.materials.effective_modulus`).
    method : {"exact", "hamrock_brewe"}
        Elliptic parameters exact or by Hamrock and Brewe's fit.

    Returns
    -------
    float or array
        p_max [Pa].
    """
    params = _check_contact(load, rx, ry, e_eff, method, "max_pressure")
    a1, b1 = _unit_load_semi_axes(rx, ry, e_eff, params)
    return 1.5 * op.power(load, 1.0 / 3.0) / (np.pi * a1 * b1)


def combined_load_deflection_constant(k_inner, k_outer):
    """Load-deflection constant of the inner and outer contacts of a ball in series.

    ``K = (K_i^(-2/3) + K_o^(-2/3))^(-3/2)`` [N/m^1.5] (Harris & Kotzalas, chapter "Distribution of
    internal loading in statically loaded bearings").

    Parameters
    ----------
    k_inner, k_outer : float or array or SX
        Constants of the inner and outer contacts [N/m^1.5], > 0.

    Returns
    -------
    float or array
        K [N/m^1.5].
    """
    where = "combined_load_deflection_constant"
    check_range(k_inner, "k_inner", "N/m^1.5", 0.0, low_inclusive=False, where=where)
    check_range(k_outer, "k_outer", "N/m^1.5", 0.0, low_inclusive=False, where=where)
    return op.power(op.power(k_inner, -2.0 / 3.0) + op.power(k_outer, -2.0 / 3.0), -1.5)


def bearing_load_deflection_constants(
    geometry: BearingGeometry,
    ball: Material = STEEL,
    ring: Material = STEEL,
    contact_angle=None,
    method: str = "exact",
):
    """Load-deflection constants of the inner, outer and combined contacts of a bearing.

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry (Dw, dm, fi, fo).
    ball, ring : Material
        Ball and ring materials.
    contact_angle : float or array or SX, optional
        Operating contact angle [rad]; the free contact angle of ``geometry`` by default.
    method : {"exact", "hamrock_brewe"}

    Returns
    -------
    (K_i, K_o, K) : tuple
        Inner, outer and combined constants [N/m^1.5].
    """
    angle = geometry.free_contact_angle if contact_angle is None else contact_angle
    e_eff = effective_modulus(ball, ring)
    dw, dm = geometry.ball_diameter, geometry.pitch_diameter
    k_i = load_deflection_constant(*raceway_radii(dw, dm, geometry.fi, angle, "inner"), e_eff,
                                   method)
    k_o = load_deflection_constant(*raceway_radii(dw, dm, geometry.fo, angle, "outer"), e_eff,
                                   method)
    return k_i, k_o, combined_load_deflection_constant(k_i, k_o)


def orthogonal_shear_stress(p_max, b, k):
    """Maximum subsurface orthogonal shear stress tau0 and its depth z0 (Lundberg-Palmgren).

    With t from ``(t^2 - 1)(2t - 1) = (b/a)^2 = 1/k^2``:
    ``tau0 = p_max sqrt(2t - 1) / (2 t (t + 1))``, ``z0 = b / ((t + 1) sqrt(2t - 1))``
    (Harris & Kotzalas, chapter "Contact stress and deformation"). t is found by eight Newton
    steps started to the right of the root (the cubic is convex and increasing for t >= 1).

    Parameters
    ----------
    p_max : float or array or SX
        Maximum Hertz pressure [Pa], >= 0.
    b : float or array or SX
        Semi-minor axis [m], >= 0.
    k : float or array or SX
        Ellipticity a/b [-], >= 1.

    Returns
    -------
    (tau0, z0) : tuple
        Amplitude [Pa] and depth [m].
    """
    where = "orthogonal_shear_stress"
    check_range(p_max, "p_max", "Pa", 0.0, where=where)
    check_range(b, "b", "m", 0.0, where=where)
    check_range(k, "k", "-", 1.0, where=where)
    ratio2 = 1.0 / (k * k)
    t = 1.0 + 0.5 * ratio2
    for _ in range(8):
        t = t - ((t * t - 1.0) * (2.0 * t - 1.0) - ratio2) / (6.0 * t * t - 2.0 * t - 2.0)
    root = op.sqrt(2.0 * t - 1.0)
    return p_max * root / (2.0 * t * (t + 1.0)), b / ((t + 1.0) * root)


def hertz_contact(load, rx, ry, e_eff, method: str = "exact") -> HertzContact:
    """All Hertz quantities of one contact at once; see :func:`semi_axes` for the parameters.

    Parameters
    ----------
    load : float or array
        Contact load [N], >= 0.
    rx, ry : float or array
        Effective radii of curvature in the rolling and transverse directions [m], > 0.
    e_eff : float
        Effective modulus [Pa], > 0 (:func:`~bearingsim.physics.materials.effective_modulus`).
    method : {"exact", "hamrock_brewe"}
        Elliptic parameters exact or by Hamrock and Brewe's fit.

    Returns
    -------
    HertzContact
        All quantities of the contact.
    """
    params = _check_contact(load, rx, ry, e_eff, method, "hertz_contact")
    a1, b1 = _unit_load_semi_axes(rx, ry, e_eff, params)
    scale = op.power(load, 1.0 / 3.0)
    stiffness = _load_deflection(rx, ry, e_eff, params)
    p_max = 1.5 * scale / (np.pi * a1 * b1)
    b = b1 * scale
    tau0, z0 = orthogonal_shear_stress(p_max, b, params.k)
    return HertzContact(
        k=params.k,
        a=a1 * scale,
        b=b,
        approach=op.power(load / stiffness, 2.0 / 3.0),
        max_pressure=p_max,
        load_deflection_constant=stiffness,
        tau0=tau0,
        z0=z0,
    )


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
