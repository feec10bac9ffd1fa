"""Traction (friction) coefficients and their integration over a Hertzian contact ellipse.

Every coefficient here is an odd, smooth function of the sliding speed: it has the sign of the
slip and passes through zero without a jump, so it can go straight into equations integrated by an
implicit solver (no events).

Sign convention: a coefficient ``mu(s)`` has the sign of the sliding speed ``s`` of the body
relative to its counter-surface; the traction force on the body is ``-mu(s) Q`` along the slip.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.physical_checks import check_regularization
from bearingsim.symbolic import exp, smooth_abs, sqrt
from bearingsim.validation import check_range

__all__ = [
    "EHL_TRACTION_DEFAULT",
    "regularized_coulomb",
    "ehl_traction",
    "ehl_traction_peak",
    "hertz_slice_weights",
    "SliceTraction",
    "slice_traction",
]

EHL_TRACTION_DEFAULT: dict[str, float] = {"A": -0.04, "B": 0.3, "C": 2.0, "D": 0.04}
"""Default coefficients of :func:`ehl_traction` (A, D [-]; B, C [s/m]).

Representative of a mineral oil in a steel EHL contact: zero at zero slip (``A = -D``), a peak of
about 0.08 near 0.5 m/s and a thermal fall-off to 0.04 at large slip, the shape of the measured
curves shown by Gupta (*Advanced Dynamics of Rolling Elements*, ch. 2). They are not a fit to a
particular fluid: fit ``A..D`` to traction data for quantitative work.

Verification status: representative values, no published source. No published table of
``A..D`` for a named oil was found; these numbers were chosen to give the shape described above
and must not be cited as measured data.
"""


def regularized_coulomb(slip_speed: Any, mu: float, v_reg: float = 1e-3) -> Any:
    """Coulomb friction coefficient regularized through zero slip.

    ``mu_eff = mu * s / sqrt(s^2 + v_reg^2)``: odd, smooth, bounded by ``mu``; it reaches 99 % of
    ``mu`` at ``|s| = 7.1 v_reg``. This is the standard viscous regularization of the Coulomb law
    (e.g. Gupta, *Advanced Dynamics of Rolling Elements*, sect. 2.6, and the smoothed friction laws
    used with implicit integrators).

    Parameters
    ----------
    slip_speed : float, array or casadi.SX
        Sliding speed of the body relative to its counter-surface [m/s].
    mu : float
        Coulomb friction coefficient [-], ``0 <= mu <= 2``.
    v_reg : float
        Regularization speed [m/s], > 0.

    Returns
    -------
    float, array or casadi.SX
        Friction coefficient with the sign of ``slip_speed`` [-].
    """
    check_range(mu, "mu", "-", 0.0, 2.0, where="regularized_coulomb")
    check_regularization(v_reg, "v_reg", "m/s", "regularized_coulomb")
    check_range(slip_speed, "slip_speed", "m/s", where="regularized_coulomb")
    return mu * slip_speed / smooth_abs(slip_speed, v_reg)


def _check_ehl(a: float, b: float, c: float, d: float, where: str) -> None:
    for name, value in (("A", a), ("B", b), ("C", c), ("D", d)):
        check_range(value, name, "-" if name in "AD" else "s/m", -1.0 if name == "A" else 0.0,
                    None, where=where)
    if c <= 0.0 and b > 0.0:
        raise ParameterError(f"{where}: C = {c} [s/m] must be > 0 when B > 0, or mu is unbounded")


def ehl_traction(
    slip_speed: Any,
    A: float = EHL_TRACTION_DEFAULT["A"],  # noqa: N803 - published symbol names
    B: float = EHL_TRACTION_DEFAULT["B"],  # noqa: N803
    C: float = EHL_TRACTION_DEFAULT["C"],  # noqa: N803
    D: float = EHL_TRACTION_DEFAULT["D"],  # noqa: N803
    v_reg: float = 1e-4,
) -> Any:
    """EHL traction coefficient ``mu = (A + B |s|) exp(-C |s|) + D``, made odd in the slip.

    The four-coefficient curve is the empirical traction form used in the ball- and roller-bearing
    dynamics models of Gupta (*Advanced Dynamics of Rolling Elements*, 1984, ch. 2) and in the
    skidding analyses following Harris & Kotzalas (*Rolling Bearing Analysis*, 5th ed., Advanced
    Concepts, ch. on lubricant traction). Here ``|s|`` is ``sqrt(s^2 + v_reg^2)`` and the result is
    multiplied by ``s/|s|``, so the curve is odd and smooth through zero (exactly zero at zero slip
    when ``A = -D``).

    Parameters
    ----------
    slip_speed : float, array or casadi.SX
        Sliding speed [m/s].
    A, D : float
        Curve coefficients [-]; ``A + D`` is the coefficient at vanishing slip.
    B, C : float
        Curve coefficients [s/m], ``B, C >= 0`` (``C > 0`` if ``B > 0``).
    v_reg : float
        Regularization speed [m/s], > 0.

    Returns
    -------
    float, array or casadi.SX
        Traction coefficient with the sign of ``slip_speed`` [-]; bounded in magnitude by
        :func:`ehl_traction_peak`.
    """
    _check_ehl(A, B, C, D, "ehl_traction")
    check_range(v_reg, "v_reg", "m/s", 0.0, None, low_inclusive=False, where="ehl_traction")
    check_range(slip_speed, "slip_speed", "m/s", where="ehl_traction")
    s_abs = smooth_abs(slip_speed, v_reg)
    return ((A + B * s_abs) * exp(-C * s_abs) + D) * slip_speed / s_abs


def ehl_traction_peak(
    A: float = EHL_TRACTION_DEFAULT["A"],  # noqa: N803
    B: float = EHL_TRACTION_DEFAULT["B"],  # noqa: N803
    C: float = EHL_TRACTION_DEFAULT["C"],  # noqa: N803
    D: float = EHL_TRACTION_DEFAULT["D"],  # noqa: N803
) -> float:
    """Least upper bound of ``|mu|`` of :func:`ehl_traction` over all slip speeds.

    The stationary point of ``(A + B s) exp(-C s) + D`` is ``s* = 1/C - A/B`` with value
    ``(B/C) exp(-C s*) + D``; the bound is the largest of that, ``|A + D|`` (zero slip) and
    ``|D|`` (infinite slip).

    Parameters
    ----------
    A, B, C, D : float
        Coefficients of :func:`ehl_traction` ([-], [s/m], [s/m], [-]).

    Returns
    -------
    float
        Peak traction coefficient [-].
    """
    _check_ehl(A, B, C, D, "ehl_traction_peak")
    candidates = [abs(A + D), abs(D)]
    if B > 0.0:
        s_star = 1.0 / C - A / B
        if s_star > 0.0:
            candidates.append(abs(B / C * float(np.exp(-C * s_star)) + D))
    return max(candidates)


def hertz_slice_weights(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Centres and Hertzian load shares of ``2n+1`` equal slices of a contact ellipse.

    The ellipse is cut perpendicular to its major axis ``a``. Integrating the Hertz pressure
    ``p = p0 sqrt(1 - (x/a)^2 - (y/b)^2)`` across the minor axis gives a load per unit length
    ``(3 Q / 4a) (1 - (x/a)^2)`` (Harris & Kotzalas, 5th ed., Essential Concepts, ch. 6; Johnson,
    *Contact Mechanics*, sect. 4.2). A slice ``[xi_1, xi_2]`` (in units of ``a``) carries exactly
    ``3/4 [xi - xi^3/3]`` of ``Q``; the shares add up to 1 (normalized to round-off).

    Parameters
    ----------
    n : int
        Half the number of slices minus one (``n >= 0``), ``2n + 1`` slices in all.

    Returns
    -------
    centres : numpy.ndarray
        Slice centres in units of the semi-major axis ``a`` [-], from ``-1`` to ``1``.
    weights : numpy.ndarray
        Load share of each slice [-], summing to 1.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0 or n > 1000:
        raise ParameterError(f"hertz_slice_weights: n = {n!r} [-] must be an integer in [0, 1000]")
    edges = np.linspace(-1.0, 1.0, 2 * n + 2)
    primitive = 0.75 * (edges - edges**3 / 3.0)
    weights = np.diff(primitive)
    return 0.5 * (edges[:-1] + edges[1:]), weights / weights.sum()


@dataclass(frozen=True)
class SliceTraction:
    """Traction on a body from a sliced contact ellipse (contact frame ``e_r, e_t, n``).

    ``e_r`` is the rolling direction (minor axis), ``e_t`` the major axis, ``n = e_r x e_t`` the
    contact normal pointing into the body.

    Attributes
    ----------
    force_r, force_t : float or casadi.SX
        Total traction force on the body along ``e_r`` and ``e_t`` [N].
    moment_n : float or casadi.SX
        Moment of the slice forces about the contact centre, along ``n`` [N m] (spin moment).
    positions : list
        Slice centres along ``e_t`` [m].
    loads : list
        Normal load of each slice [N]; they sum to ``Q``.
    forces_r, forces_t : list
        Traction force of each slice on the body [N], for moments about other points.
    """

    force_r: Any
    force_t: Any
    moment_n: Any
    positions: list
    loads: list
    forces_r: list
    forces_t: list


def slice_traction(
    Q: Any,  # noqa: N803 - published symbol
    a: Any,
    sliding_velocity: Callable[[Any], tuple[Any, Any]],
    traction: Callable[[Any], Any],
    n: int = 5,
    v_reg: float = 1e-6,
) -> SliceTraction:
    """Traction force and spin moment of an elliptical contact, integrated slice by slice.

    The ellipse is cut into ``2n+1`` slices along its major axis (docs/studies.md, section C; the
    slicing method of Harris & Kotzalas, 5th ed., Advanced Concepts, ch. on ball-raceway
    friction, and Gupta, ch. 3). Each slice carries its Hertzian share of ``Q``
    (:func:`hertz_slice_weights`) and a traction coefficient at its own sliding speed ``|du|``;
    the force on the body is ``-mu(|du|) Q_i du/|du|``, with
    ``|du| = sqrt(du_r^2 + du_t^2 + v_reg^2)``.

    Parameters
    ----------
    Q : float or casadi.SX
        Normal contact load [N], >= 0.
    a : float or casadi.SX
        Semi-major axis of the contact ellipse [m], >= 0.
    sliding_velocity : callable
        ``sliding_velocity(x) -> (du_r, du_t)``: sliding velocity of the body surface relative to
        the counter-surface at position ``x`` [m] along the major axis, components along ``e_r``
        and ``e_t`` [m/s]. For rigid bodies ``du = v_b + w_b x r_c - v_ring - w_ring x R_c``.
    traction : callable
        ``traction(s) -> mu``: odd traction coefficient of the sliding speed [m/s], e.g.
        ``lubricant.traction_coefficient``.
    n : int
        ``2n+1`` slices.
    v_reg : float
        Regularization speed of the slip magnitude [m/s], > 0.

    Returns
    -------
    SliceTraction
        Total force, spin moment and the per-slice loads and forces.
    """
    check_range(Q, "Q", "N", 0.0, None, where="slice_traction")
    check_range(a, "a", "m", 0.0, None, where="slice_traction")
    check_range(v_reg, "v_reg", "m/s", 0.0, None, low_inclusive=False, where="slice_traction")
    centres, weights = hertz_slice_weights(n)
    positions, loads, forces_r, forces_t = [], [], [], []
    for xi, w in zip(centres, weights, strict=True):
        x = float(xi) * a
        du_r, du_t = sliding_velocity(x)
        speed = sqrt(du_r * du_r + du_t * du_t + v_reg * v_reg)
        q_i = float(w) * Q
        scale = -q_i * traction(speed) / speed
        positions.append(x)
        loads.append(q_i)
        forces_r.append(scale * du_r)
        forces_t.append(scale * du_t)
    moment_n = sum(-x * f for x, f in zip(positions, forces_r, strict=True))
    return SliceTraction(
        force_r=sum(forces_r),
        force_t=sum(forces_t),
        moment_n=moment_n,
        positions=positions,
        loads=loads,
        forces_r=forces_r,
        forces_t=forces_t,
    )


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
