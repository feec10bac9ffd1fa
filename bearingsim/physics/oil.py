"""A lubricating oil, :class:`Oil`: viscosity-temperature by ASTM D341 (Walther) from two
viscosities or an ISO VG grade (:data:`ISO_VG_NU100`), density, pressure-viscosity coefficient
and EHL traction.

Catalogue data (mm^2/s at degC, ISO VG grades) are converted to SI in the constructors; the
properties take an optional temperature ``T`` [K] like every
:class:`~bearingsim.physics.lubricant_models.Lubricant`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim.errors import CatalogError, ParameterError
from bearingsim.physics.lubricant_models import Lubricant
from bearingsim.physics.lubrication import LUBRICATION_METHODS
from bearingsim.physics.traction import EHL_TRACTION_DEFAULT, ehl_traction
from bearingsim.symbolic import log, power
from bearingsim.units import celsius_to_kelvin, cst_to_m2_s
from bearingsim.validation import check_range

__all__ = [
    "Oil",
    "ISO_VG_NU100",
    "MIN_OIL_VISCOSITY_CST",
]

ISO_VG_NU100: dict[int, float] = {
    10: 2.6, 15: 3.4, 22: 4.3, 32: 5.4, 46: 6.8, 68: 8.7,
    100: 11.1, 150: 14.7, 220: 19.0, 320: 24.0, 460: 30.5,
}
"""Kinematic viscosity at 100 degC [mm^2/s] of paraffinic mineral oils of viscosity index about
95-100, by ISO VG grade (ISO 3448 fixes the 40 degC midpoint = the grade).

Verification: checked against the viscosity-index definition of ASTM D2270 (Table 1, L and H
against nu100, as reproduced in CalebBell/thermo, ``thermo/viscosity.py``): with nu40 = grade,
every entry is within half a unit of its last digit (0.05 mm^2/s) of a nu100 giving VI 95-100;
nominal VI 86 (VG 10, the one-decimal rounding of 2.64-2.66), 95-103 for the others (VG 15:
3.4, VI 98). See ``tests/physics/test_published_contact_film.py``.
No manufacturer's data sheet was compared."""

MIN_OIL_VISCOSITY_CST = 0.5
"""Smallest kinematic viscosity [mm^2/s] an :class:`Oil` accepts: Walther's
``log10(log10(nu + 0.7))`` needs ``nu > 0.3``, and ASTM D341's form holds above about 2 (the
thinnest lubricating oils, ISO VG 2, have about 2 mm^2/s at 40 degC)."""

_LOG10 = float(np.log(10.0))


def _log10(x: Any) -> Any:
    return log(x) / _LOG10


class Oil(Lubricant):
    """A lubricating oil defined by two kinematic viscosities at two temperatures.

    Viscosity-temperature: Walther's equation as standardized in ASTM D341,
    ``log10(log10(nu + 0.7)) = A - B log10(T)`` (``nu`` in mm^2/s, ``T`` in K), with ``A`` and ``B``
    fixed by the two given points (ASTM D341 uses 0.7 for ``nu >= 2 mm^2/s``; below that it adds
    correction terms, which are omitted, so results below 2 mm^2/s are approximate).

    Density: ``rho = rho15 (1 - beta (T - 288.15 K))``, linear thermal expansion with the volumetric
    coefficient ``beta`` of mineral oils (about 6.4e-4 1/K; Hamrock, Schmid & Jacobson,
    *Fundamentals of Fluid Film Lubrication*, 2nd ed., ch. 4, density).

    Pressure-viscosity coefficient: given, or the correlation for mineral oils of Gold et al.
    (J. Synthetic Lubrication 18 (2001) 51-79), ``alpha = 9.904 nu^0.139`` [1/GPa] with ``nu`` the
    kinematic viscosity at the same temperature in mm^2/s (the one used by ISO/TS 16281 practice).

    Parameters
    ----------
    nu1_cst, nu2_cst : float
        Kinematic viscosities [mm^2/s] at ``t1_degc`` and ``t2_degc``; ``nu1 > nu2 > 0``.
    t1_degc, t2_degc : float
        The two temperatures [degC], ``t1 < t2``.
    name : str
        Name shown in messages.
    temperature : float
        Operating temperature [K].
    rho15 : float
        Density at 15 degC [kg/m^3].
    beta : float
        Volumetric thermal expansion coefficient [1/K].
    alpha : float, optional
        Fixed pressure-viscosity coefficient [1/Pa]; None: Gold et al. correlation.
    method : str
        Lubrication method (:data:`~bearingsim.physics.lubrication.LUBRICATION_METHODS`).
    traction : dict, optional
        Coefficients ``A, B, C, D`` of :func:`~bearingsim.physics.traction.ehl_traction`.
    mu_bl, mu_ehl : float
        Boundary and full-film sliding coefficients [-] (SKF 2005: 0.15; 0.05 for mineral oils).
    """

    def __init__(
        self,
        nu1_cst: float,
        t1_degc: float,
        nu2_cst: float,
        t2_degc: float,
        *,
        name: str = "oil",
        temperature: float = 313.15,
        rho15: float = 870.0,
        beta: float = 6.4e-4,
        alpha: float | None = None,
        method: str = "oil_bath",
        traction: dict[str, float] | None = None,
        mu_bl: float = 0.15,
        mu_ehl: float = 0.05,
    ) -> None:
        where = f"Oil {name!r}"
        for value, label in ((nu1_cst, "nu1_cst"), (nu2_cst, "nu2_cst")):
            try:
                check_range(value, label, "mm^2/s", MIN_OIL_VISCOSITY_CST, 1e6, where=where)
            except ParameterError as exc:
                raise ParameterError(
                    f"{exc}; lubricating oils have 1 to 1e5 mm^2/s (cSt) and the Walther "
                    f"equation needs more than {MIN_OIL_VISCOSITY_CST} mm^2/s (did you pass "
                    f"m^2/s? 32 mm^2/s = 3.2e-5 m^2/s)") from None
        check_range(nu2_cst, "nu2_cst", "mm^2/s", 0.0, nu1_cst, low_inclusive=False,
                    high_inclusive=False, where=where)
        check_range(t1_degc, "t1_degc", "degC", -50.0, 300.0, where=where)
        check_range(t2_degc, "t2_degc", "degC", t1_degc, 300.0, low_inclusive=False, where=where)
        check_range(temperature, "temperature", "K", 200.0, 600.0, where=where)
        check_range(rho15, "rho15", "kg/m^3", 500.0, 2000.0, where=where)
        check_range(beta, "beta", "1/K", 0.0, 2e-3, where=where)
        if alpha is not None:
            check_range(alpha, "alpha", "1/Pa", 0.0, 1e-7, where=where)
        check_range(mu_bl, "mu_bl", "-", 0.0, 1.0, where=where)
        check_range(mu_ehl, "mu_ehl", "-", 0.0, 1.0, where=where)
        if method not in LUBRICATION_METHODS:
            raise ParameterError(
                f"{where}: method {method!r} is not one of {', '.join(LUBRICATION_METHODS)}")
        self.traction = dict(EHL_TRACTION_DEFAULT if traction is None else traction)
        if set(self.traction) != set(EHL_TRACTION_DEFAULT):
            raise ParameterError(f"{where}: traction needs exactly the keys A, B, C, D")
        ehl_traction(0.0, **self.traction)  # validates the coefficients
        self.name, self.method, self.temperature = name, method, float(temperature)
        self.rho15, self.beta, self.alpha = float(rho15), float(beta), alpha
        self.mu_bl, self.mu_ehl = float(mu_bl), float(mu_ehl)
        self.nu_points = ((float(nu1_cst), float(t1_degc)), (float(nu2_cst), float(t2_degc)))
        z1 = np.log10(np.log10(nu1_cst + 0.7))
        z2 = np.log10(np.log10(nu2_cst + 0.7))
        x1 = np.log10(celsius_to_kelvin(t1_degc))
        x2 = np.log10(celsius_to_kelvin(t2_degc))
        self.walther_b = float((z1 - z2) / (x2 - x1))
        self.walther_a = float(z1 + self.walther_b * x1)

    @classmethod
    def from_iso_vg(cls, grade: int, **kwargs: Any) -> Oil:
        """Mineral oil of an ISO VG grade (nu at 40 degC = grade, at 100 degC from
        :data:`ISO_VG_NU100`). Keyword arguments go to the constructor.

        Parameters
        ----------
        grade : int
            ISO VG grade, a key of :data:`ISO_VG_NU100` (nu at 40 degC [mm^2/s]).
        **kwargs
            Further keywords of :class:`Oil`.

        Returns
        -------
        Oil
            The oil.
        """
        if grade not in ISO_VG_NU100:
            raise CatalogError(
                f"unknown ISO VG grade {grade!r}; known: {', '.join(map(str, ISO_VG_NU100))}")
        kwargs.setdefault("name", f"ISO VG {grade}")
        return cls(float(grade), 40.0, ISO_VG_NU100[grade], 100.0, **kwargs)

    def kinematic_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """Kinematic viscosity [m^2/s] by ASTM D341 (Walther) at ``T`` [K].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            Kinematic viscosity [m^2/s], > 0.
        """
        z = self.walther_a - self.walther_b * _log10(self._t(T))
        return cst_to_m2_s(power(10.0, power(10.0, z)) - 0.7)

    def density(self, T: Any = None) -> Any:  # noqa: N803
        """Density [kg/m^3] at ``T`` [K] (linear thermal expansion from 15 degC).

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            Density [kg/m^3], > 0.
        """
        return self.rho15 * (1.0 - self.beta * (self._t(T) - 288.15))

    def pressure_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """Pressure-viscosity coefficient [1/Pa]: given, or Gold et al. (2001) at ``T`` [K].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            alpha [1/Pa], > 0.
        """
        if self.alpha is not None:
            return self.alpha + 0.0 * self._t(T)
        nu_cst = self.kinematic_viscosity(T) * 1e6
        return 9.904e-9 * power(nu_cst, 0.139)

    def traction_coefficient(self, slip_speed: Any) -> Any:
        """EHL traction curve (:func:`~bearingsim.physics.traction.ehl_traction`) [-].

        Parameters
        ----------
        slip_speed : float or array or SX
            Sliding speed [m/s], either sign.

        Returns
        -------
        float or array or SX
            Traction coefficient [-].
        """
        return ehl_traction(slip_speed, **self.traction)

    def churning_factor(self) -> float:
        """1: the f0 table already refers to the oil lubrication method.

        Returns
        -------
        float
            1 [-].
        """
        return 1.0

    def describe(self) -> str:
        (nu1, t1), (nu2, t2) = self.nu_points
        return (f"Oil {self.name}: {nu1:g} mm^2/s at {t1:g} degC, {nu2:g} mm^2/s at {t2:g} degC, "
                f"{self.method}, operating at {self.temperature - 273.15:g} degC")
