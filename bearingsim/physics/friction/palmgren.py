"""Palmgren's friction torque model: the load-independent M0 and the load-dependent M1 with the
factors f1 and P1, and the signed, regularized torque (:func:`palmgren_torque`)."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from bearingsim.checks import MAX_STATIC_LOAD_FACTOR, guard_public_functions
from bearingsim.errors import ParameterError, PlasticDeformationWarning
from bearingsim.physical_checks import check_diameter
from bearingsim.physics.lubricant import Lubricant, check_kinematic_viscosity
from bearingsim.symbolic import (
    if_else,
    is_symbolic,
    power,
    smooth_abs,
    smooth_max0,
)
from bearingsim.units import m2_s_to_cst, rad_s_to_rpm
from bearingsim.validation import check_range, table_entry

__all__ = ["PALMGREN_F1", "palmgren_f1", "palmgren_p1", "palmgren_m0", "palmgren_torque"]

PALMGREN_F1: dict[str, tuple[float, float]] = {
    # bearing type: (z, y) in f1 = z (P0/C0)^y. Ball bearings: Palmgren (1959) as given in
    # the double-layer study (docs/studies.md, section A; deep groove) and Harris & Kotzalas, 5th
    # ed., Essential Concepts, table of f1; roller bearings have a constant f1 (y = 0, middle of
    # the range given there).
    "deep_groove_ball": (0.0009, 0.55),
    "angular_contact_ball": (0.001, 0.33),
    "angular_contact_ball_pair": (0.001, 0.33),
    "self_aligning_ball": (0.0003, 0.40),
    "thrust_ball": (0.0008, 0.33),
    "cylindrical_roller": (0.0003, 0.0),
    "spherical_roller": (0.00045, 0.0),
    "tapered_roller": (0.0004, 0.0),
}

_PALMGREN_BLEND = 3.2  # smoothing width of the M0 branch blend, 2 % of the 160 plateau
_NU_N_BRANCH_CUBE_ROOT = 160.0  # 160 = the low-speed plateau of (nu n)^(2/3)


def palmgren_f1(bearing_type: str, P0: Any, C0: float) -> Any:  # noqa: N803
    """Palmgren load-dependent friction factor ``f1 = z (P0/C0)^y`` [-].

    Deep-groove ball: ``0.0009 (P0/C0)^0.55``; angular contact: ``0.001 (P0/C0)^0.33``
    (Palmgren 1959; Harris & Kotzalas, 5th ed., Essential Concepts, f1 table). Roller bearings
    use a constant (table :data:`PALMGREN_F1`).

    Parameters
    ----------
    bearing_type : str
        Key of :data:`PALMGREN_F1`.
    P0 : float or casadi.SX
        Equivalent static load [N], >= 0.
    C0 : float
        Basic static load rating [N], > 0.

    Returns
    -------
    float or casadi.SX
        f1 [-].

    Warns
    -----
    PlasticDeformationWarning
        For a numeric ``P0 > C0`` (the formula's catalogue range ends at C0).

    Raises
    ------
    ParameterError
        For ``P0`` beyond :data:`~bearingsim.checks.MAX_STATIC_LOAD_FACTOR` x ``C0``.
    """
    z, y = table_entry(PALMGREN_F1, bearing_type, "bearing type")
    check_range(P0, "P0", "N", 0.0, None, where="palmgren_f1")
    check_range(C0, "C0", "N", 0.0, None, low_inclusive=False, where="palmgren_f1")
    if not is_symbolic(P0) and np.any(np.asarray(P0) > MAX_STATIC_LOAD_FACTOR * C0):
        raise ParameterError(
            f"palmgren_f1: P0 = {np.max(P0):g} N is more than {MAX_STATIC_LOAD_FACTOR:g} x the "
            f"static load rating C0 = {C0:g} N: beyond the strength of bearing steel (a load "
            f"in N given for kN?); valid P0 in [0, {MAX_STATIC_LOAD_FACTOR * C0:g}] N")
    if not is_symbolic(P0) and np.any(np.asarray(P0) > C0):
        warnings.warn(f"palmgren_f1: P0 = {np.max(P0):g} N exceeds the static load rating "
                      f"C0 = {C0:g} N: the contacts deform permanently, and f1 = z (P0/C0)^y is "
                      f"extrapolated beyond the catalogue range", PlasticDeformationWarning,
                      stacklevel=2)
    return z * power(P0 / C0, y) if y else z + 0.0 * P0


def palmgren_p1(
    Fr: Any,  # noqa: N803
    Fa: Any,  # noqa: N803
    bearing_type: str,
    contact_angle: float = float(np.arctan(0.3)),
    load_eps: float = 1.0,
) -> Any:
    """Load ``P1`` that determines the load-dependent friction torque [N].

    Harris & Kotzalas (5th ed., Essential Concepts, table of ``P1``, after Palmgren):
    deep-groove ball ``max(Fr, 0.9 Fa cot(alpha) - 0.1 Fr)`` (the default ``alpha = atan(0.3)``
    gives the familiar ``3 Fa - 0.1 Fr``); angular contact, single row ``max(Fr, Fa - 0.1 Fr)``;
    angular contact pair / double row ``Fr + 1.4 Fa``; thrust ball ``Fa``; other types ``Fr``.
    The maximum is smoothed, ``Fr + smooth_max0(x - Fr, load_eps)`` (error at most ``load_eps/2``).

    Parameters
    ----------
    Fr, Fa : float or casadi.SX
        Radial and axial load [N], >= 0.
    bearing_type : str
        Key of :data:`PALMGREN_F1`.
    contact_angle : float
        Contact angle of a deep-groove ball bearing under the axial load [rad], in (0, pi/2].
    load_eps : float
        Smoothing width of the maximum [N], > 0.

    Returns
    -------
    float or casadi.SX
        P1 [N].
    """
    table_entry(PALMGREN_F1, bearing_type, "bearing type")
    check_range(Fr, "Fr", "N", 0.0, None, where="palmgren_p1")
    check_range(Fa, "Fa", "N", 0.0, None, where="palmgren_p1")
    check_range(contact_angle, "contact_angle", "rad", 0.0, np.pi / 2, low_inclusive=False,
                where="palmgren_p1")
    if bearing_type == "deep_groove_ball":
        other = 0.9 * Fa / np.tan(contact_angle) - 0.1 * Fr
    elif bearing_type == "angular_contact_ball":
        other = Fa - 0.1 * Fr
    elif bearing_type == "angular_contact_ball_pair":
        return Fr + 1.4 * Fa
    elif bearing_type == "thrust_ball":
        return Fa + 0.0 * Fr
    else:
        return Fr + 0.0 * Fa
    return Fr + smooth_max0(other - Fr, load_eps)


def palmgren_m0(nu: Any, n_abs: Any, dm: float, f0: float, smooth: bool = True) -> Any:
    """Palmgren load-independent torque magnitude ``M0`` [N m] (Palmgren 1959; Harris & Kotzalas).

    In catalogue units ``M0 = 1e-7 f0 (nu n)^(2/3) dm^3`` [N mm] for ``nu n >= 2000`` and
    ``160e-7 f0 dm^3`` below (``nu`` mm^2/s, ``n`` r/min, ``dm`` mm).

    With ``smooth=False`` this piecewise form is evaluated exactly (``if_else``; it jumps by 0.8 %
    at the branch point since ``2000^(2/3) = 158.74``). With ``smooth=True`` (for equations) the
    factor ``(nu n)^(2/3)`` is replaced by ``160 + smooth_max0((nu n)^(2/3) - 160, 3.2)``, a smooth
    maximum of the two branches with width 3.2 (2 % of 160): it deviates from ``max`` by at most
    1 % (at ``nu n = 2024``) and from the exact piecewise form by at most 1.8 % (near
    ``nu n = 2000``, which includes the 0.8 % jump of the original); the deviation falls below
    0.1 % for ``nu n`` outside [1400, 2700].

    Parameters
    ----------
    nu : float, array or casadi.SX
        Kinematic viscosity of the (base) oil at operating temperature [m^2/s], >= 0.
    n_abs : float, array or casadi.SX
        Magnitude of the relative speed [rad/s], >= 0.
    dm : float
        Pitch diameter [m], in (0, 6] (a larger value is taken for millimetres, see
        :func:`~bearingsim.physical_checks.check_diameter`).
    f0 : float
        Palmgren factor [-], >= 0.
    smooth : bool
        Smooth branch blend (True) or the exact piecewise form (False).

    Returns
    -------
    float, array or casadi.SX
        ``M0`` [N m], >= 0.
    """
    check_kinematic_viscosity(nu, "nu", "palmgren_m0")
    check_range(n_abs, "n_abs", "rad/s", 0.0, None, where="palmgren_m0")
    check_diameter(dm, "dm", "palmgren_m0")
    check_range(f0, "f0", "-", 0.0, None, where="palmgren_m0")
    nu_n = m2_s_to_cst(nu) * rad_s_to_rpm(n_abs)
    speed_term = power(nu_n, 2.0 / 3.0)
    plateau = _NU_N_BRANCH_CUBE_ROOT
    if smooth:
        factor = plateau + smooth_max0(speed_term - plateau, _PALMGREN_BLEND)
    else:
        factor = if_else(nu_n >= 2000.0, speed_term, plateau)
    dm_mm = dm * 1e3
    return 1e-7 * f0 * factor * dm_mm**3 * 1e-3


def _signed(magnitude: Any, omega_rel: Any, omega_reg: float, where: str) -> Any:
    check_range(omega_reg, "omega_reg", "rad/s", 0.0, None, low_inclusive=False, where=where)
    return -magnitude * omega_rel / smooth_abs(omega_rel, omega_reg)


def palmgren_torque(
    omega_rel: Any,
    dm: float,
    lubricant: Lubricant,
    bearing_type: str,
    load_P1: Any = 0.0,  # noqa: N803
    P0: Any = None,  # noqa: N803
    C0: float | None = None,  # noqa: N803
    smooth: bool = True,
    T: Any = None,  # noqa: N803
    omega_reg: float = 0.1,
    series: str | None = None,
) -> Any:
    """Palmgren friction torque ``M = M0 + M1`` of a bearing [N m], signed against the rotation.

    ``M0`` from :func:`palmgren_m0` with ``f0 = lubricant.palmgren_f0(bearing_type)`` (which
    carries the lubrication method and, for grease, the fill fraction) and the lubricant's
    kinematic viscosity at ``T``; ``M1 = f1 P1 dm`` with ``f1`` from :func:`palmgren_f1`
    (Palmgren 1959; Harris & Kotzalas, 5th ed., Essential Concepts, ch. on friction). See the
    module docstring for the sign convention and ``omega_reg``.

    Parameters
    ----------
    omega_rel : float, array or casadi.SX
        Speed of the ring relative to the other ring [rad/s].
    dm : float
        Pitch diameter [m], in (0, 6] (a larger value is taken for millimetres, see
        :func:`~bearingsim.physical_checks.check_diameter`).
    lubricant : Lubricant
        Oil, Grease or Dry object (:mod:`bearingsim.physics.lubricant`).
    bearing_type : str
        Key of :data:`~bearingsim.physics.lubrication.PALMGREN_F0`.
    load_P1 : float, array or casadi.SX
        Friction-determining load ``P1`` [N] (see :func:`palmgren_p1`), >= 0. Zero (a Python or
        numpy zero, or an array of zeros) means no load: ``M1`` is then not evaluated and
        ``P0``, ``C0`` are not needed.
    P0 : float, array or casadi.SX, optional
        Static equivalent load [N] of ``f1 = z (P0/C0)^y`` (ISO 76, e.g.
        :func:`bearingsim.physics.life.static_equivalent_load`). Required, and
        > 0 wherever ``load_P1 > 0``, for the ball bearing types (``y > 0``): no default value
        is documented (Palmgren 1959; Harris & Kotzalas), and ``P0 = 0`` would make
        ``f1 = 0`` and drop ``M1`` silently. Optional (and ignored) for the roller types, whose
        ``f1`` is constant (``y = 0``).
    C0 : float, optional
        Basic static load rating [N], > 0; required when ``load_P1 > 0``.
    smooth : bool
        Smooth ``M0`` branch blend (for equations) or exact piecewise form.
    T : float or casadi.SX, optional
        Lubricant temperature [K]; default the lubricant's operating temperature.
    omega_reg : float
        Regularization speed of the sign [rad/s], > 0.
    series : str, optional
        Catalogue series of the bearing (e.g. ``"619"``) for the f0 of
        :data:`~bearingsim.physics.lubrication.PALMGREN_F0_BY_SERIES`.

    Returns
    -------
    float, array or casadi.SX
        Friction torque on the ring [N m], opposite in sign to ``omega_rel``: the torque the
        other ring exerts through the bearing on the ring that turns at ``+omega_rel``
        relative to it (negative for a positive speed; bearingsim's one sign convention of
        friction torques).
    """
    where = "palmgren_torque"
    check_range(omega_rel, "omega_rel", "rad/s", where=where)
    check_range(load_P1, "load_P1", "N", 0.0, None, where=where)
    check_diameter(dm, "dm", where)
    speed = smooth_abs(omega_rel, omega_reg)
    f0 = lubricant.palmgren_f0(bearing_type, series)
    magnitude = palmgren_m0(lubricant.kinematic_viscosity(T), speed, dm, f0, smooth)
    if P0 is not None:
        check_range(P0, "P0", "N", 0.0, None, where=where)
    if _has_load(load_P1):
        if C0 is None:
            raise ParameterError(f"{where}: C0 [N] is required when load_P1 is given")
        _z, y = table_entry(PALMGREN_F1, bearing_type, "bearing type")
        if y > 0.0:
            _check_static_load(load_P1, P0, where)
        p0 = 0.0 if P0 is None else P0
        magnitude = magnitude + palmgren_f1(bearing_type, p0, C0) * load_P1 * dm
    return _signed(magnitude, omega_rel, omega_reg, where)


def _has_load(load: Any) -> bool:
    """Whether a load may be nonzero: symbolic, or a number/array with a nonzero entry."""
    if is_symbolic(load):
        return True
    return bool(np.any(np.asarray(load, dtype=float) != 0.0))


def _check_static_load(load_P1: Any, P0: Any, where: str) -> None:  # noqa: N803
    """``P0`` must be given, and > 0 wherever ``load_P1 > 0`` (numbers; symbols pass)."""
    if P0 is None:
        raise ParameterError(
            f"{where}: P0 [N] (static equivalent load, > 0) is required when load_P1 > 0: "
            f"f1 = z (P0/C0)^y, and P0 = 0 would drop the load-dependent torque M1"
        )
    if is_symbolic(load_P1, P0):
        return
    loaded = np.asarray(load_P1, dtype=float) > 0.0
    p0 = np.broadcast_to(np.asarray(P0, dtype=float), loaded.shape)
    if np.any(p0[loaded] <= 0.0):
        raise ParameterError(
            f"{where}: P0 = {P0} [N] is outside the valid range (0, inf) [N] where load_P1 > 0 "
            f"(f1 = z (P0/C0)^y would be 0 and drop M1)"
        )


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
