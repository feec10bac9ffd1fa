"""Torque-level bearing elements: a bearing as a friction torque between two ring flanges.

These are the *kinematic* and *torque* fidelity levels: no balls are resolved, the bearing is a
massless element that transmits a friction torque between its inner-ring and outer-ring flanges.
The lubricant enters through parameters (viscosity, Palmgren f0), so swapping the lubricant of
an assembled system is a parameter change, not a recompilation.
"""

from __future__ import annotations

from typing import Any

from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.connectors import Flange
from bearingsim.components.rolling_element import (
    element_of,
    friction_key,
    magnitude_input_bounds,
    resolve_geometry,
    static_equivalent_load,
)
from bearingsim.errors import ParameterError
from bearingsim.language import Component, Input, Parameter, Variable, der
from bearingsim.physics.friction import (
    palmgren_f1,
    palmgren_m0,
    palmgren_p1,
    skf_friction_components,
)
from bearingsim.physics.lubricant import KINEMATIC_VISCOSITY_RANGE, as_lubricant
from bearingsim.symbolic import smooth_abs

__all__ = [
    "BearingTorqueElement",
    "PalmgrenBearing",
    "SkfBearing",
    "PureRollingLayer",
]


def friction_bearing_type(geometry: BearingGeometry) -> str:
    """Key of the friction tables for a geometry ("deep_groove_ball", "cylindrical_roller",
    ...; :func:`~bearingsim.components.rolling_element.friction_key`).

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.

    Returns
    -------
    str
        The friction tables' key.
    """
    return friction_key(geometry)


class BearingTorqueElement(Component):
    """Base: a massless element between an inner-ring and an outer-ring flange.

    Subclasses define ``friction_torque()``: the torque acting on the inner ring [N m] (on the
    outer ring it acts with the opposite sign).

    Variables
    ---------
    w_rel [rad/s] : inner-ring speed relative to the outer ring
    M [N m] : friction torque on the inner ring
    P_loss [W] : dissipated power, ``-M * w_rel`` (>= 0)

    Connectors
    ----------
    inner, outer : Flange

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, name=None):
        super().__init__(name)
        self.inner = Flange()
        self.outer = Flange()
        self.w_rel = Variable(unit="rad/s", description="inner-ring speed relative to outer ring")
        self.M = Variable(unit="N.m", description="friction torque acting on the inner ring")
        self.P_loss = Variable(unit="W", description="dissipated friction power")

    def friction_torque(self) -> Any:
        """Friction torque on the inner ring as an expression of ``w_rel`` [N m]."""
        raise NotImplementedError  # pragma: no cover - abstract

    def equations(self):
        return [
            self.w_rel == der(self.inner.phi) - der(self.outer.phi),
            self.M == self.friction_torque(),
            self.inner.tau == -self.M,
            self.outer.tau == self.M,
            self.P_loss == -self.M * self.w_rel,
        ]


class _LubricatedBearing(BearingTorqueElement):
    """Shared parameters of the lubricated friction models.

    Parameters
    ----------
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, bearing, lubricant, omega_reg: float, name=None):
        super().__init__(name)
        self.geometry = resolve_geometry(bearing)
        self.lubricant = as_lubricant(lubricant, type(self).__name__)
        g = self.geometry
        self.dm = Parameter(g.pitch_diameter, "m", "pitch diameter", low=0.0, low_inclusive=False)
        self.omega_reg = Parameter(
            omega_reg, "rad/s", "speed below which friction is regularized (smooth sign)",
            low=0.0, low_inclusive=False,
        )
        bounds = magnitude_input_bounds(g)
        self.Fr = Input(0.0, "N", "radial load", **bounds["Fr"])
        self.Fa = Input(0.0, "N", "axial load (magnitude)", **bounds["Fa"])

    @property
    def bearing_type(self) -> str:
        """Friction table key of this bearing."""
        return friction_bearing_type(self.geometry)

    def _signed(self, magnitude):
        return -magnitude * self.w_rel / smooth_abs(self.w_rel, self.omega_reg)


class PalmgrenBearing(_LubricatedBearing):
    """Palmgren friction torque ``M = M0 + M1`` between two ring flanges.

    ``M0 = 1e-7 f0 (nu n)^(2/3) dm^3`` [N mm] for ``nu n >= 2000``, else ``160e-7 f0 dm^3``;
    ``M1 = f1 P1 dm`` (Palmgren 1959; Harris & Kotzalas, *Rolling Bearing Analysis*). See
    :func:`bearingsim.physics.friction.palmgren_m0` for the smooth branch blend.

    Parameters
    ----------
    bearing : str or BearingGeometry or RollerBearingGeometry
        Catalogue designation or geometry.
    lubricant : str or Lubricant
        Lubricant object or name; sets ``nu`` and ``f0`` (both parameters afterwards).
    load_dependent : bool
        Include ``M1`` (needs the catalogue's static rating C0).
    smooth : bool
        Smooth blend of the two M0 branches (default) or the exact piecewise form.
    omega_reg : float
        Regularization speed of the friction sign [rad/s].
    name : str
        Instance name (the prefix of its variables' dotted names).

    Parameters (model)
    ------------------
    dm [m], nu [m^2/s], f0 [-], C0 [N], omega_reg [rad/s]; inputs Fr, Fa [N].
    """

    def __init__(self, bearing, lubricant="ISO VG 32", *, load_dependent: bool = True,
                 smooth: bool = True, omega_reg: float = 0.1, name=None):
        super().__init__(bearing, lubricant, omega_reg, name)
        self.nu = Parameter(
            float(self.lubricant.kinematic_viscosity()), "m2/s",
            "kinematic viscosity of the (base) oil at operating temperature", low=0.0,
            high=KINEMATIC_VISCOSITY_RANGE[1],
        )
        self.f0 = Parameter(
            float(self.lubricant.palmgren_f0(self.bearing_type, self.geometry.series)), "1",
            "Palmgren load-independent friction factor f0", low=0.0,
        )
        self._smooth = smooth
        self._load_dependent = load_dependent
        if load_dependent:
            c0 = self.geometry.static_load_rating
            if c0 is None:
                raise ParameterError(
                    f"{self.display_name}: bearing {self.geometry.designation} has no static load "
                    "rating C0 [N]; give load_dependent=False or a geometry with C0"
                )
            self.C0 = Parameter(c0, "N", "basic static load rating", low=0.0, low_inclusive=False)

    def friction_torque(self):
        n_abs = smooth_abs(self.w_rel, self.omega_reg)
        magnitude = palmgren_m0(self.nu, n_abs, self.dm, self.f0, self._smooth)
        if self._load_dependent:
            p1 = palmgren_p1(self.Fr, self.Fa, self.bearing_type)
            p0 = static_equivalent_load(self.Fr, self.Fa, self.geometry)
            magnitude = magnitude + palmgren_f1(self.bearing_type, p0, self.C0) * p1 * self.dm
        return self._signed(magnitude)


class SkfBearing(_LubricatedBearing):
    """SKF four-component friction torque between two ring flanges.

    ``M = phi_ish phi_rs M_rr + M_sl + M_seal + M_drag`` (SKF rolling bearings catalogue; see
    :func:`bearingsim.physics.friction.skf_friction_components`). The lubricant data (viscosity
    at its operating temperature, friction coefficients) are fixed at assembly.

    Parameters
    ----------
    bearing : str or BearingGeometry or RollerBearingGeometry
        Catalogue designation or geometry (needs C0).
    lubricant : str or Lubricant
        Lubricant object or name.
    series : str, optional
        SKF series key of the geometry constants (default: from the designation, e.g. "619").
    omega_reg : float
        Regularization speed of the friction sign [rad/s].
    **options
        Passed to ``skf_friction_components`` (seals, oil level, ...).
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, bearing, lubricant="ISO VG 32", *, series: str | None = None,
                 omega_reg: float = 0.1, name=None, **options):
        super().__init__(bearing, lubricant, omega_reg, name)
        g = self.geometry
        self._series = series or (_skf_series(g.designation) if element_of(g) == "ball"
                                  else g.series)
        self._roller_type = None if element_of(g) == "ball" else g.bearing_type
        self._options = options

    def friction_torque(self):
        g = self.geometry
        parts = skf_friction_components(
            self.w_rel, self.dm, self.lubricant, self._series, self.Fr, self.Fa,
            C0=g.static_load_rating, d=g.bore, D=g.outside_diameter,
            omega_reg=self.omega_reg, bearing_type=self._roller_type, **self._options,
        )
        return self._signed(parts.total)


def _skf_series(designation: str) -> str:
    digits = "".join(ch for ch in designation if ch.isdigit())
    if designation.startswith("7"):
        return designation[:2] + "B"
    return digits[:3] if digits.startswith("6") and len(digits) == 5 else digits[:2]


class PureRollingLayer(BearingTorqueElement):
    """Kinematic (pure-rolling) layer: drag proportional to the cage's relative speed.

    The balls roll without slip, so the cage turns at ``w_c = (1 - g) / 2 w_i + (1 + g) / 2 w_o``
    with ``g = Dw cos(a) / dm``. Each race feels a friction force proportional to the cage speed
    relative to it, acting at its contact radius (``dm (1 -/+ g) / 2``), with one coefficient
    ``k`` for every layer (docs/studies.md, section A). The torque between the rings is then a
    linear damper ``M = -k dm (1 - g^2) / 4 w_rel``; in a double-layer bearing it gives the
    pure-rolling speed ratio ``Rs = (1 - g1^2) Dp1 / ((1 - g1^2) Dp1 + (1 - g2^2) Dp2)`` exactly,
    with ``g_k = Dw_k cos(a_k) / Dp_k`` of layer k (the same ratio as
    :func:`bearingsim.physics.double_layer_theory.speed_ratio_pure_rolling`, which writes it
    with its own ``g_k`` standing for ``gamma_k^2``). With ``exact=False`` the ``g^2`` term is
    dropped
    (``Rs = Dp1 / (Dp1 + Dp2)``).

    Parameters
    ----------
    bearing : str or BearingGeometry
        Catalogue designation or geometry.
    k : float
        Drag coefficient per unit race speed [N s/m] (equal for both layers).
    exact : bool
        Keep the contact-angle term ``g^2``.
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, bearing, k: float = 1.0, *, exact: bool = True, name=None):
        super().__init__(name)
        self.geometry = resolve_bearing(bearing)
        g = self.geometry
        self.k = Parameter(k, "N.s/m", "pure-rolling drag coefficient", low=0.0,
                           low_inclusive=False)
        self.dm = Parameter(g.pitch_diameter, "m", "pitch diameter", low=0.0, low_inclusive=False)
        self.gamma = Parameter(g.gamma if exact else 0.0, "1", "Dw cos(alpha) / dm",
                               low=0.0, high=1.0, high_inclusive=False)

    def friction_torque(self):
        return -self.k * self.dm * (1.0 - self.gamma**2) / 4.0 * self.w_rel
