"""The SKF four-component friction torque model (rolling, sliding, seals, drag) with its
catalogue tables of geometry constants."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.physical_checks import MAX_BALL_DIAMETER, check_diameter
from bearingsim.physics.drag import orbital_drag_force
from bearingsim.physics.friction.palmgren import _signed
from bearingsim.physics.lubricant import Lubricant
from bearingsim.symbolic import (
    arccos,
    exp,
    fmax,
    fmin,
    if_else,
    is_symbolic,
    power,
    sin,
    smooth_abs,
)
from bearingsim.units import m2_s_to_cst, rad_s_to_rpm
from bearingsim.validation import check_count, check_range, table_entry

__all__ = [
    "SKF_DEEP_GROOVE",
    "SKF_ANGULAR_CONTACT",
    "SKF_CYLINDRICAL_ROLLER",
    "SKF_ROLLER_TYPES",
    "SKF_KRS",
    "SKF_KZ",
    "SkfSeal",
    "SkfFriction",
    "skf_friction_components",
    "skf_friction_torque",
]

# SKF model, geometry constants. Source: SKF General Catalogue 6000 EN (2005), section "Friction",
# Table 3a "Geometry constants for rolling and sliding frictional moments" (the same model and
# tables in the SKF "Rolling bearings" catalogue, PUB BU/P1 10000 EN, "Friction").
# Units: those of the catalogue formulas (dm mm, n r/min, nu mm^2/s, loads N, torque N mm).
# Verification: every row below equals Table 3a of the SKF General Catalogue 6000, Russian
# edition (data as of 2006), p. 93 ("2, 3", "42, 43", "60, 630", "62, 622", "63, 623", "64",
# "160, 161", "617, 618, 628, 637, 638", "619, 639"); the Grr/Gsl forms equal its Table 2a, p. 91
# (tests/physics/test_published_examples.py).
SKF_DEEP_GROOVE: dict[str, dict[str, float]] = {
    "2": {"R1": 4.4e-7, "R2": 1.7, "S1": 2.00e-3, "S2": 100.0},
    # The catalogue has one row "2, 3"; S1 = 2.00e-3 is the value of that row in the public
    # transcription.
    "3": {"R1": 4.4e-7, "R2": 1.7, "S1": 2.00e-3, "S2": 100.0},
    "42": {"R1": 5.4e-7, "R2": 0.96, "S1": 3.00e-3, "S2": 40.0},
    "60": {"R1": 4.1e-7, "R2": 1.7, "S1": 3.73e-3, "S2": 14.6},
    "62": {"R1": 3.9e-7, "R2": 1.7, "S1": 3.23e-3, "S2": 36.5},
    "63": {"R1": 3.7e-7, "R2": 1.7, "S1": 2.84e-3, "S2": 92.8},
    "64": {"R1": 3.6e-7, "R2": 1.7, "S1": 2.43e-3, "S2": 198.0},
    "160": {"R1": 4.3e-7, "R2": 1.7, "S1": 4.63e-3, "S2": 4.25},
    "618": {"R1": 4.7e-7, "R2": 1.7, "S1": 6.50e-3, "S2": 0.78},
    "619": {"R1": 4.3e-7, "R2": 1.7, "S1": 4.75e-3, "S2": 3.6},
}
# Angular contact rows: "72B" equals the single-row angular contact row of Table 3 of the SKF
# General Catalogue 6000 (Russian ed., 2006 data), p. 92, which gives one row for all single-row
# series (also used by an independent public implementation, GitHub code index). "73B" is
# UNVERIFIED (no source for it was retrieved: that catalogue has no separate 73 B row, and
# neither the 2018 catalogue 17000 nor an SKF friction web page giving a 73 B row was
# retrievable). Caution: its R1 (4.78e-7) equals R1 of the four-point contact row of the same
# Table 3 (4.78e-7, 2.42, 1.40e-12, 1.20e-2, 0.9, 1.40e-12), while its other five constants
# differ from that row; whether "73B" is SKF's later 73 B(E) row or a mix-up could not be
# settled.
SKF_ANGULAR_CONTACT: dict[str, dict[str, float]] = {
    "72B": {"R1": 5.03e-7, "R2": 1.97, "R3": 1.90e-12, "S1": 1.30e-2, "S2": 0.68, "S3": 1.91e-12},
    "73B": {"R1": 4.78e-7, "R2": 1.65, "R3": 2.71e-12, "S1": 1.31e-2, "S2": 0.68, "S3": 1.96e-12},
}
SKF_KRS: dict[str, float] = {
    # Replenishment/starvation constant Krs: 3e-8 for low-level oil bath and oil jet, 6e-8 for
    # grease and oil-air (oil mist). SKF General Catalogue 6000 (Russian ed., 2006 data), p. 98;
    # SKF "Rolling bearings" PUB BU/P1 10000/3 (2017), p. 102, which applies phi_rs only to oil-air,
    # oil jet, grease and an oil bath whose level is below the centre of the lowest rolling
    # element. An oil bath with a given level (at or above that centre) and a vertical shaft get
    # no starvation factor (phi_rs = 1). Oil mist is not named by SKF; the oil-air value is used.
    "oil_bath": 3e-8,
    "oil_jet": 3e-8,
    "grease": 6e-8,
    "oil_mist": 6e-8,
}
SKF_CYLINDRICAL_ROLLER: dict[str, dict[str, float]] = {
    # Cylindrical roller bearings with a cage (N, NU, NJ, NUP) by dimension series:
    # Grr = R1 dm^2.41 Fr^0.31, Gsl = S1 dm^0.9 Fa + S2 dm Fr. SKF General Catalogue 6000
    # (Russian ed., 2006 data), p. 93, Table 3c (forms: Table 2b, p. 92); the full-complement
    # row (2.13e-6, 0.16, 0.0015) is not taken.
    "2": {"R1": 1.09e-6, "S1": 0.16, "S2": 0.0015},
    "3": {"R1": 1.09e-6, "S1": 0.16, "S2": 0.0015},
    "4": {"R1": 1.00e-6, "S1": 0.16, "S2": 0.0015},
    "10": {"R1": 1.12e-6, "S1": 0.17, "S2": 0.0015},
    "12": {"R1": 1.23e-6, "S1": 0.16, "S2": 0.0015},
    "20": {"R1": 1.23e-6, "S1": 0.16, "S2": 0.0015},
    "22": {"R1": 1.40e-6, "S1": 0.16, "S2": 0.0015},
    "23": {"R1": 1.48e-6, "S1": 0.16, "S2": 0.0015},
}
SKF_KZ: dict[str, float] = {"deep_groove_ball": 3.1, "angular_contact_ball": 4.4}
"""Bearing type geometry constant Kz of the replenishment factor (SKF 2005, Table 5; verified
against the SKF General Catalogue 6000, Russian ed., 2006 data, p. 98, Table 5)."""
SKF_ROLLER_TYPES: dict[str, dict[str, float]] = {"cylindrical_roller": {"Kz": 5.1, "mu_EHL": 0.02}}
"""Roller bearing types of the SKF model: their Kz (SKF General Catalogue 6000, Russian ed.,
2006 data, p. 98, Table 5: 5.1 for cylindrical roller bearings with a cage) and the full-film
sliding friction coefficient SKF prescribes for them instead of the lubricant's (same
catalogue, p. 101: 0.02 for cylindrical roller bearings)."""


@dataclass(frozen=True)
class SkfSeal:
    """Seal constants of the SKF model, ``Mseal = KS1 ds^beta + KS2`` [N mm].

    Take the values for the bearing and seal type from the SKF catalogue seal table (SKF General
    Catalogue 2005, "Frictional moment of seals", Table 4); units as there.

    Attributes
    ----------
    ks1 : float
        Constant KS1 [N mm^(1-beta)], >= 0.
    ks2 : float
        Constant KS2 [N mm], >= 0.
    beta : float
        Exponent [-], >= 0.
    ds_mm : float
        Seal counterface diameter [mm], > 0.

    Raises
    ------
    ParameterError
        For a value outside these ranges (a negative ``ds_mm`` would give a complex moment).
    """

    ks1: float
    ks2: float
    beta: float
    ds_mm: float

    def __post_init__(self) -> None:
        where = "SkfSeal"
        check_range(self.ks1, "ks1", "N mm^(1-beta)", 0.0, None, where=where)
        check_range(self.ks2, "ks2", "N mm", 0.0, None, where=where)
        check_range(self.beta, "beta", "-", 0.0, None, where=where)
        check_range(self.ds_mm, "ds_mm", "mm", 0.0, None, low_inclusive=False, where=where)


@dataclass(frozen=True)
class SkfFriction:
    """The parts of the SKF frictional moment (magnitudes, SI).

    Attributes
    ----------
    rolling, sliding, seal, drag : float or casadi.SX
        ``phi_ish phi_rs Mrr``, ``Msl``, ``Mseal``, ``Mdrag`` [N m].
    phi_ish, phi_rs, phi_bl, mu_sl : float or casadi.SX
        Inlet shear heating factor, replenishment/starvation factor, boundary weighting factor
        and sliding friction coefficient [-].
    total : float or casadi.SX
        Sum of the four moments [N m].
    """

    rolling: Any
    sliding: Any
    seal: Any
    drag: Any
    phi_ish: Any
    phi_rs: Any
    phi_bl: Any
    mu_sl: Any

    @property
    def total(self) -> Any:
        return self.rolling + self.sliding + self.seal + self.drag


def _skf_g_factors(series, dm_mm, n_rpm, Fr, Fa, C0, bearing_type=None):  # noqa: N803
    """Grr and Gsl (catalogue units) for a deep-groove or angular contact ball bearing, or a
    cylindrical roller bearing (``bearing_type="cylindrical_roller"``)."""
    if bearing_type == "cylindrical_roller":
        c = table_entry(SKF_CYLINDRICAL_ROLLER, series, "SKF cylindrical roller series")
        g_rr = c["R1"] * dm_mm**2.41 * power(Fr, 0.31)
        g_sl = c["S1"] * dm_mm**0.9 * Fa + c["S2"] * dm_mm * Fr
        return g_rr, g_sl, bearing_type
    if series in SKF_ANGULAR_CONTACT:
        c = SKF_ANGULAR_CONTACT[series]
        fg_rr = c["R3"] * dm_mm**4 * n_rpm**2
        fg_sl = c["S3"] * dm_mm**4 * n_rpm**2
        g_rr = c["R1"] * dm_mm**1.97 * power(Fr + fg_rr + c["R2"] * Fa, 0.54)
        g_sl = c["S1"] * dm_mm**0.26 * (
            power(Fr + fg_sl, 4.0 / 3.0) + c["S2"] * power(Fa, 4.0 / 3.0))
        return g_rr, g_sl, "angular_contact_ball"
    c = table_entry(SKF_DEEP_GROOVE, series, "SKF bearing series")
    # Catalogue: Fa > 0 uses the alpha_F forms; Fa = 0 the radial forms. Fa is floored so that
    # both branches stay finite (if_else evaluates both).
    fa = fmax(Fa, 1e-9 * C0)
    alpha_f = np.deg2rad(24.6) * power(fa / C0, 0.24)
    g_rr_axial = c["R1"] * dm_mm**1.96 * power(Fr + c["R2"] / sin(alpha_f) * fa, 0.54)
    g_sl_axial = c["S1"] * dm_mm**-0.145 * power(
        power(Fr, 5.0) + c["S2"] * dm_mm**1.5 / sin(alpha_f) * power(fa, 4.0), 1.0 / 3.0)
    g_rr = if_else(Fa > 0.0, g_rr_axial, c["R1"] * dm_mm**1.96 * power(Fr, 0.54))
    g_sl = if_else(Fa > 0.0, g_sl_axial, c["S1"] * dm_mm**-0.26 * power(Fr, 5.0 / 3.0))
    return g_rr, g_sl, "deep_groove_ball"


def skf_friction_components(
    omega_rel: Any,
    dm: float,
    lubricant: Lubricant,
    series: str,
    Fr: Any,  # noqa: N803
    Fa: Any = 0.0,  # noqa: N803
    *,
    C0: float,  # noqa: N803
    d: float,
    D: float,  # noqa: N803
    T: Any = None,  # noqa: N803
    seal: SkfSeal | None = None,
    oil_level: float | None = None,
    Dw: float | None = None,  # noqa: N803
    Z: int | None = None,  # noqa: N803
    omega_reg: float = 0.1,
    bearing_type: str | None = None,
) -> SkfFriction:
    """SKF four-component frictional moment ``M = phi_ish phi_rs Mrr + Msl + Mseal + Mdrag``.

    SKF General Catalogue 6000 EN (2005), section "Friction" (same model in the SKF Rolling
    bearings catalogue 2018), in catalogue units inside:

    * ``Mrr = Grr (nu n)^0.6``, ``Grr`` from :data:`SKF_DEEP_GROOVE` / :data:`SKF_ANGULAR_CONTACT`
      (deep groove: ``R1 dm^1.96 (Fr + R2/sin(alpha_F) Fa)^0.54``, ``alpha_F = 24.6 (Fa/C0)^0.24``
      deg; ``R1 dm^1.96 Fr^0.54`` when ``Fa = 0``; angular contact: ``R1 dm^1.97 (Fr + Fg +
      R2 Fa)^0.54``, ``Fg = R3 dm^4 n^2``).
    * ``Msl = Gsl mu_sl``, ``mu_sl = phi_bl mu_bl + (1 - phi_bl) mu_EHL``,
      ``phi_bl = exp(-2.6e-8 (n nu)^1.4 dm)``; ``mu_bl``, ``mu_EHL`` from the lubricant. Verified
      against the SKF "Rolling bearings" catalogue (10000 EN), "Sliding frictional moment",
      p. 105 (``phi_bl`` constant 2.6e-8, exponent 1.4; ``mu_bl`` about 0.15; ``mu_EHL`` 0.05
      mineral oil, 0.04 synthetic oil, 0.1 transmission fluid); the same in the SKF General
      Catalogue 6000 (Russian ed., 2006 data), pp. 100-101.
    * ``phi_ish = 1 / (1 + 1.84e-9 (n dm)^1.28 nu^0.64)`` (inlet shear heating; SKF General
      Catalogue 6000, Russian ed., 2006 data, p. 97; its worked example on p. 104, 0.85, is
      reproduced in tests/physics/test_published_examples.py).
    * ``phi_rs = exp(-Krs nu n (d + D) sqrt(Kz / (2 (D - d))))`` (kinematic replenishment /
      starvation), ``Krs`` from :data:`SKF_KRS` by lubrication method (same catalogue, p. 98;
      its example on p. 105, 0.8 with Kz = 5.5, is reproduced). As SKF applies it (2017
      edition, p. 102): oil-air/oil mist, oil jet, grease and an oil bath below the lowest ball
      centre (an oil bath without ``oil_level``); an oil bath with ``oil_level`` (>= 0: at or
      above that centre) and a vertical shaft have ``phi_rs = 1``.
    * ``Mseal = KS1 ds^beta + KS2`` (:class:`SkfSeal`), 0 without seals.
    * ``Mdrag``: SKF's drag term needs the ``VM`` diagram, which is not reproduced here; instead
      the drag of the immersed balls is computed from
      :func:`~bearingsim.physics.drag.orbital_drag_force` (Schlichting drag at the pitch
      circle, cage speed for a rotating inner ring), for the
      fraction ``arccos(1 - 2 H/dm)/pi`` of balls whose centres lie below the oil level ``H``.
      Only for oil-bath lubrication and when ``oil_level``, ``Dw`` and ``Z`` are given.

    The deep-groove ``Fa = 0`` / ``Fa > 0`` forms are the catalogue's own two branches and do not
    join continuously; keep ``Fa`` either zero or positive throughout a simulation.

    Parameters
    ----------
    omega_rel : float or casadi.SX
        Relative ring speed [rad/s].
    dm : float
        Pitch diameter [m], in (0, 6] (a larger value is taken for millimetres, see
        :func:`~bearingsim.physical_checks.check_diameter`).
    lubricant : Lubricant
        Oil or Grease (the base oil viscosity is used); Dry gives zero rolling moment.
    series : str
        Bearing series, a key of :data:`SKF_DEEP_GROOVE` (e.g. ``"62"``) or
        :data:`SKF_ANGULAR_CONTACT` (e.g. ``"72B"``).
    Fr, Fa : float or casadi.SX
        Radial and axial load [N], >= 0.
    C0 : float
        Basic static load rating [N].
    d, D : float
        Bore and outside diameter [m], ``0 < d < D <= 6``.
    T : float or casadi.SX, optional
        Lubricant temperature [K].
    seal : SkfSeal, optional
        Seal constants.
    oil_level : float, optional
        Oil level above the lowest point of the ball pitch circle [m], for the drag term.
    Dw : float, optional
        Ball diameter [m], for the drag term, in (0, dm) and at most 0.5.
    Z : int, optional
        Number of balls [-], for the drag term, a whole number >= 1.
    omega_reg : float
        Regularization speed of ``|omega_rel|`` [rad/s].
    bearing_type : {None, "cylindrical_roller"}
        None: a ball bearing (the table follows from ``series``); "cylindrical_roller": the
        rows :data:`SKF_CYLINDRICAL_ROLLER` (``Grr = R1 dm^2.41 Fr^0.31``, ``Gsl = S1 dm^0.9 Fa
        + S2 dm Fr``), ``Kz = 5.1`` and ``mu_EHL = 0.02`` (:data:`SKF_ROLLER_TYPES`); the
        drag term then treats the rollers as balls of their diameter (an estimate).

    Returns
    -------
    SkfFriction
        Moment parts and factors (magnitudes).
    """
    where = "skf_friction_components"
    check_range(omega_rel, "omega_rel", "rad/s", where=where)
    check_diameter(dm, "dm", where)
    check_range(Fr, "Fr", "N", 0.0, None, where=where)
    check_range(Fa, "Fa", "N", 0.0, None, where=where)
    check_range(C0, "C0", "N", 0.0, None, low_inclusive=False, where=where)
    check_diameter(d, "d", where)
    check_diameter(D, "D", where)
    check_range(D, "D", "m", d, None, low_inclusive=False, where=where)
    speed = smooth_abs(omega_rel, omega_reg)
    n = rad_s_to_rpm(speed)
    nu = m2_s_to_cst(lubricant.kinematic_viscosity(T))
    dm_mm, d_mm, big_d_mm = dm * 1e3, d * 1e3, D * 1e3
    g_rr, g_sl, kind = _skf_g_factors(series, dm_mm, n, Fr, Fa, C0, bearing_type)
    roller = SKF_ROLLER_TYPES.get(kind)
    phi_ish = 1.0 / (1.0 + 1.84e-9 * power(n * dm_mm, 1.28) * power(nu, 0.64))
    # a Dry lubricant has no replenishment (nu = 0); a full oil bath (its level given, at or
    # above the lowest ball centre) and a vertical shaft are not starved (SKF 2017, p. 102)
    full_bath = lubricant.method == "oil_bath" and oil_level is not None
    krs = 0.0 if full_bath else SKF_KRS.get(lubricant.method, 0.0)
    kz = SKF_KZ[kind] if roller is None else roller["Kz"]
    kz_term = np.sqrt(kz / (2.0 * (big_d_mm - d_mm)))
    phi_rs = exp(-krs * nu * n * (d_mm + big_d_mm) * kz_term)
    phi_bl = exp(-2.6e-8 * power(n * nu, 1.4) * dm_mm)
    mu_ehl = lubricant.mu_ehl if roller is None else roller["mu_EHL"]
    mu_sl = phi_bl * lubricant.mu_bl + (1.0 - phi_bl) * mu_ehl
    m_rr = g_rr * power(nu * n, 0.6)
    m_seal = 0.0
    if seal is not None:
        m_seal = seal.ks1 * seal.ds_mm**seal.beta + seal.ks2
    drag = 0.0 * speed
    if oil_level is not None and lubricant.method in ("oil_bath", "vertical_shaft"):
        if Dw is None or Z is None:
            raise ParameterError(f"{where}: Dw [m] and Z [-] are required with oil_level")
        check_range(oil_level, "oil_level", "m", 0.0, None, where=where)
        check_diameter(Dw, "Dw", where, MAX_BALL_DIAMETER)
        # dm is a model parameter (a symbol) inside components: compare with it when numeric
        check_range(Dw, "Dw", "m", 0.0, None if is_symbolic(dm) else dm, low_inclusive=False,
                    high_inclusive=False, where=where)
        check_count(Z, "Z", 1, where=where)
        fraction = arccos(1.0 - 2.0 * fmin(oil_level / dm, 1.0)) / np.pi
        gamma = Dw / dm
        omega_cage = 0.5 * (1.0 - gamma) * speed
        force = orbital_drag_force(omega_cage, dm, Dw, lubricant.density(T),
                                   lubricant.dynamic_viscosity(T))
        drag = -Z * fraction * force * 0.5 * dm
    return SkfFriction(
        rolling=phi_ish * phi_rs * m_rr * 1e-3,
        sliding=g_sl * mu_sl * 1e-3,
        seal=m_seal * 1e-3 + 0.0 * speed,
        drag=drag,
        phi_ish=phi_ish,
        phi_rs=phi_rs,
        phi_bl=phi_bl,
        mu_sl=mu_sl,
    )


def skf_friction_torque(omega_rel: Any, dm: float, lubricant: Lubricant, series: str, Fr: Any,
                        Fa: Any = 0.0, **kwargs: Any) -> Any:
    """SKF frictional moment [N m] signed against the rotation (see module docstring).

    Parameters
    ----------
    omega_rel, dm, lubricant, series, Fr, Fa, **kwargs
        As :func:`skf_friction_components` (``C0``, ``d``, ``D`` required).

    Returns
    -------
    float or casadi.SX
        Friction torque on the ring [N m], opposite in sign to ``omega_rel``.
    """
    parts = skf_friction_components(omega_rel, dm, lubricant, series, Fr, Fa, **kwargs)
    return _signed(parts.total, omega_rel, kwargs.get("omega_reg", 0.1), "skf_friction_torque")


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
