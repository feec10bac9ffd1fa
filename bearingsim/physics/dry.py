"""No lubricant, :class:`Dry`: regularized Coulomb traction, no film and no viscous friction,
behind the :class:`~bearingsim.physics.lubricant_models.Lubricant` interface.
"""

from __future__ import annotations

from typing import Any

from bearingsim.physics.lubricant_models import Lubricant
from bearingsim.physics.traction import regularized_coulomb
from bearingsim.validation import check_range

__all__ = ["Dry"]


class Dry(Lubricant):
    """No lubricant: Coulomb friction, no film, no viscous friction.

    Viscosity, density and pressure-viscosity coefficient are zero, so film thickness, drag and
    the Palmgren ``M0`` vanish; traction is the regularized Coulomb law
    (:func:`~bearingsim.physics.traction.regularized_coulomb`).

    Parameters
    ----------
    mu : float
        Coulomb coefficient [-], in [0, 2].
    v_reg : float
        Regularization speed of the Coulomb law [m/s].
    temperature : float
        Temperature [K] (kept for the common interface).
    name : str
        Name shown in messages.
    """

    def __init__(self, mu: float = 0.1, v_reg: float = 1e-3, temperature: float = 293.15,
                 *, name: str = "dry") -> None:
        regularized_coulomb(0.0, mu, v_reg)  # validates mu and v_reg
        check_range(temperature, "temperature", "K", 200.0, 600.0, where=f"Dry {name!r}")
        self.mu, self.v_reg, self.temperature = float(mu), float(v_reg), float(temperature)
        self.name, self.method = name, "dry"
        self.mu_bl = self.mu_ehl = self.contact_friction = self.mu

    def kinematic_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """0 [m^2/s].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float
            0 [m^2/s].
        """
        return 0.0 * self._t(T)

    def density(self, T: Any = None) -> Any:  # noqa: N803
        """0 [kg/m^3].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float
            0 [kg/m^3].
        """
        return 0.0 * self._t(T)

    def pressure_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """0 [1/Pa].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float
            0 [1/Pa].
        """
        return 0.0 * self._t(T)

    def traction_coefficient(self, slip_speed: Any) -> Any:
        """Regularized Coulomb coefficient [-].

        Parameters
        ----------
        slip_speed : float or array or SX
            Sliding speed [m/s], either sign.

        Returns
        -------
        float or array or SX
            Traction coefficient [-], of the sign of ``slip_speed``.
        """
        return regularized_coulomb(slip_speed, self.mu, self.v_reg)

    def churning_factor(self) -> float:
        """0: no viscous friction.

        Returns
        -------
        float
            0 [-].
        """
        return 0.0

    def describe(self) -> str:
        return f"Dry {self.name}: Coulomb mu = {self.mu:g}"
