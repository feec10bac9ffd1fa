"""A grease, :class:`Grease`: a base :class:`~bearingsim.physics.oil.Oil` in a thickener
filling part of the bearing's free volume; the base oil forms the film, the fill adds churning.
"""

from __future__ import annotations

import copy
from typing import Any

from bearingsim.errors import ParameterError
from bearingsim.physics.lubricant_models import Lubricant
from bearingsim.physics.oil import Oil
from bearingsim.validation import check_range

__all__ = ["Grease"]


class Grease(Lubricant):
    """A grease: a base :class:`Oil` in a thickener, filling part of the bearing's free volume.

    Film thickness, traction and the SKF rolling moment use the base oil (the base oil forms the
    EHL film; SKF 2005 and Harris & Kotzalas use the base-oil viscosity). The churning of the
    thickener adds viscous friction that grows with the fill fraction ``phi``; the Palmgren f0 for
    grease (tabulated for a normal fill, about one third of the free volume) is multiplied by

        ``churning_factor = (1 + k_t phi) / (1 + k_t / 3)``

    with the thickener factor ``k_t`` (0: no fill effect). This linear growth is a modelling
    assumption of bearingsim (the measured trend it represents, higher friction with more grease
    until it is channelled, is described by Harris & Kotzalas, 5th ed., Essential Concepts, ch.
    on lubrication, and by the double-layer study, docs/studies.md, section A); it is 1 at
    ``phi = 1/3``.

    Parameters
    ----------
    base_oil : Oil
        The base oil.
    fill_fraction : float
        Fraction of the free volume filled with grease [-], in (0, 1].
    thickener_factor : float
        ``k_t`` [-], >= 0 (2 for a generic lithium soap grease).
    name : str
        Name shown in messages.
    temperature : float, optional
        Operating temperature [K], in [200, 600] (the range of :class:`Oil`). Given, the grease
        uses a copy of ``base_oil`` at this temperature (``base_oil`` itself is not changed);
        default the base oil's operating temperature. This lets
        ``get_lubricant("lithium grease", temperature=343.15)`` work like it does for the oils.
    """

    def __init__(self, base_oil: Oil, fill_fraction: float = 1.0 / 3.0,
                 thickener_factor: float = 2.0, *, name: str = "grease",
                 temperature: float | None = None) -> None:
        where = f"Grease {name!r}"
        if not isinstance(base_oil, Oil):
            raise ParameterError(f"{where}: base_oil must be an Oil, got {type(base_oil).__name__}")
        check_range(fill_fraction, "fill_fraction", "-", 0.0, 1.0, low_inclusive=False,
                    where=where)
        check_range(thickener_factor, "thickener_factor", "-", 0.0, 100.0, where=where)
        if temperature is not None:
            check_range(temperature, "temperature", "K", 200.0, 600.0, where=where)
            base_oil = copy.copy(base_oil)
            base_oil.temperature = float(temperature)
        self.base_oil, self.name, self.method = base_oil, name, "grease"
        self.fill_fraction, self.thickener_factor = float(fill_fraction), float(thickener_factor)
        self.temperature = base_oil.temperature
        self.mu_bl, self.mu_ehl = base_oil.mu_bl, base_oil.mu_ehl

    def kinematic_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """Base-oil kinematic viscosity [m^2/s].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            Kinematic viscosity [m^2/s], > 0.
        """
        return self.base_oil.kinematic_viscosity(T)

    def density(self, T: Any = None) -> Any:  # noqa: N803
        """Base-oil density [kg/m^3].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            Density [kg/m^3], > 0.
        """
        return self.base_oil.density(T)

    def pressure_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """Base-oil pressure-viscosity coefficient [1/Pa].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            alpha [1/Pa], > 0.
        """
        return self.base_oil.pressure_viscosity(T)

    def traction_coefficient(self, slip_speed: Any) -> Any:
        """Base-oil traction curve [-].

        Parameters
        ----------
        slip_speed : float or array or SX
            Sliding speed [m/s], either sign.

        Returns
        -------
        float or array or SX
            Traction coefficient [-].
        """
        return self.base_oil.traction_coefficient(slip_speed)

    def churning_factor(self) -> float:
        """``(1 + k_t phi) / (1 + k_t/3)`` [-], increasing with the fill fraction ``phi``.

        Returns
        -------
        float
            Churning factor [-], > 0.
        """
        k = self.thickener_factor
        return (1.0 + k * self.fill_fraction) / (1.0 + k / 3.0)

    def describe(self) -> str:
        return (f"Grease {self.name}: base oil {self.base_oil.name}, fill "
                f"{self.fill_fraction:.0%} of free volume, "
                f"thickener factor {self.thickener_factor:g}")
