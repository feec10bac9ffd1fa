"""Closed-form speed distribution ratios of double-layer bearings (docs/studies.md, section A) and
the optimal-ratio design helper."""

from __future__ import annotations

from dataclasses import dataclass

from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError

__all__ = [
    "speed_ratio_pure_rolling",
    "speed_ratio_palmgren",
    "optimal_speed_ratio",
    "PairingReport",
    "design_report",
]


def speed_ratio_pure_rolling(inner, outer, exact: bool = True) -> float:
    """Pure-rolling speed ratio ``Rs = (1-g1) Dp1 / ((1-g1) Dp1 + (1-g2) Dp2)`` [1].

    ``g_k = (Dw_k cos a_k / Dp_k)^2``; with ``exact=False`` the approximation
    ``Dp1 / (Dp1 + Dp2)``.

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner and outer layer's bearing.
    exact : bool
        With the contact angles' terms (default) or the pitch-diameter approximation.

    Returns
    -------
    float
        Rs [1].
    """
    g1, g2 = resolve_bearing(inner), resolve_bearing(outer)
    k1 = (1 - g1.gamma**2) if exact else 1.0
    k2 = (1 - g2.gamma**2) if exact else 1.0
    a, b = k1 * g1.pitch_diameter, k2 * g2.pitch_diameter
    return a / (a + b)


def speed_ratio_palmgren(inner, outer) -> float:
    """Palmgren M0 speed ratio ``Rs = Dp1^4.5 / (Dp1^4.5 + Dp2^4.5)`` [1] (equal f0 and nu).

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner and outer layer's bearing.

    Returns
    -------
    float
        Rs [1].
    """
    g1, g2 = resolve_bearing(inner), resolve_bearing(outer)
    a, b = g1.pitch_diameter**4.5, g2.pitch_diameter**4.5
    return a / (a + b)


def _limit(g: BearingGeometry) -> float:
    speed = g.limiting_speed or g.reference_speed
    if speed is None:
        raise ParameterError(f"bearing {g.designation} has no limiting speed in the catalogue")
    return speed


def optimal_speed_ratio(inner, outer) -> float:
    """``Rs_opt = n_o,max / (n_i,max + n_o,max)`` [1] from the catalogue limiting speeds.

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner and outer layer's bearing.

    Returns
    -------
    float
        Rs_opt [1].
    """
    ni, no = _limit(resolve_bearing(inner)), _limit(resolve_bearing(outer))
    return no / (ni + no)


@dataclass(frozen=True)
class PairingReport:
    """How close a pairing comes to its optimal speed ratio."""

    inner: str
    outer: str
    pitch_diameter_ratio: float
    rs_optimal: float
    rs_pure_rolling: float
    rs_palmgren: float
    max_shaft_speed: float
    """Highest shaft speed with both layers within their limits at ``rs_palmgren`` [rad/s]."""
    max_shaft_speed_optimal: float
    """The same at ``rs_optimal`` [rad/s]."""

    @property
    def speed_utilisation(self) -> float:
        """``max_shaft_speed / max_shaft_speed_optimal`` [1] (1 = optimal pairing).

        Returns
        -------
        float
            The utilisation [1].
        """
        return self.max_shaft_speed / self.max_shaft_speed_optimal


def design_report(inner, outer, rs: float | None = None) -> PairingReport:
    """Compare a pairing's speed ratio with the optimal one.

    Parameters
    ----------
    inner, outer : str or BearingGeometry
    rs : float, optional
        Speed ratio to assess (default: the Palmgren ratio).

    Returns
    -------
    PairingReport
        The pairing's speed ratios and limiting shaft speeds.
    """
    gi, go = resolve_bearing(inner), resolve_bearing(outer)
    ni, no = _limit(gi), _limit(go)
    rs_pal = speed_ratio_palmgren(gi, go)
    rs_use = rs_pal if rs is None else rs
    if not 0.0 < rs_use < 1.0:
        raise ParameterError(f"design_report: rs must lie in (0, 1), got {rs_use!r}")
    rs_opt = no / (ni + no)

    def n_max(r):
        return min(ni / (1.0 - r), no / r)

    return PairingReport(gi.designation, go.designation, gi.pitch_diameter / go.pitch_diameter,
                         rs_opt, speed_ratio_pure_rolling(gi, go), rs_pal, n_max(rs_use),
                         n_max(rs_opt))




guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
