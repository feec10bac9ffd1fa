"""The lubricant interface: :class:`Lubricant`, the contract every lubricant model keeps, and
the plausible range of a kinematic viscosity (:func:`check_kinematic_viscosity`).

The models are :class:`~bearingsim.physics.oil.Oil` (two viscosities or an ISO VG grade,
ASTM D341), :class:`~bearingsim.physics.grease.Grease` (a base oil and a fill) and
:class:`~bearingsim.physics.dry.Dry`. Every property method takes an optional temperature ``T``
[K] (float, array or CasADi symbol); ``None`` means the lubricant's operating temperature. Values
are SI (Pa s, m^2/s, kg/m^3, 1/Pa). The registry of lubricants by name is
:mod:`bearingsim.physics.lubricant`, which also exports these names.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Any

import numpy as np

from bearingsim.physics.lubrication import palmgren_f0
from bearingsim.symbolic import is_symbolic
from bearingsim.validation import check_range

__all__ = [
    "Lubricant",
    "KINEMATIC_VISCOSITY_RANGE",
    "check_kinematic_viscosity",
]

KINEMATIC_VISCOSITY_RANGE = (1e-7, 1e-2)
"""Plausible kinematic viscosity [m^2/s] of a bearing lubricant at its operating temperature:
0.1 mm^2/s (below water's 1 mm^2/s) to 10 000 mm^2/s (an ISO VG 680 gear oil near 0 degC). A
value above it is most likely given in mm^2/s (1 mm^2/s = 1e-6 m^2/s)."""


def check_kinematic_viscosity(nu: Any, name: str = "nu", where: str = "") -> Any:
    """A kinematic viscosity [m^2/s] within :data:`KINEMATIC_VISCOSITY_RANGE`, or 0 (a dry
    contact, :class:`~bearingsim.physics.dry.Dry`); CasADi symbols pass unchecked.

    Parameters
    ----------
    nu : float or array or SX
        Kinematic viscosity [m^2/s].
    name : str
        Parameter name, for the message.
    where : str
        The model, for the message.

    Returns
    -------
    float or array or SX
        ``nu``, checked.

    Raises
    ------
    ParameterError
        Outside the range; above it with the hint that mm^2/s were probably given
        (:func:`~bearingsim.validation.check_range` adds it for every m^2/s value).
    """
    if not is_symbolic(nu) and np.all(np.asarray(check_range(nu, name, "m^2/s", where=where),
                                                 dtype=float) == 0.0):
        return nu
    return check_range(nu, name, "m^2/s", *KINEMATIC_VISCOSITY_RANGE, where=where)


class Lubricant(ABC):
    """Interface of all lubricants.

    Contract for subclasses:

    1. set ``name`` (str), ``method`` (lubrication method, one of
       :data:`~bearingsim.physics.lubrication.LUBRICATION_METHODS`, or ``"dry"``), ``temperature``
       (operating temperature [K]), ``mu_bl`` and ``mu_ehl`` (boundary and full-film sliding
       friction coefficients [-], used by the SKF model);
    2. implement :meth:`kinematic_viscosity`, :meth:`density`, :meth:`pressure_viscosity`,
       :meth:`traction_coefficient`, :meth:`churning_factor` and :meth:`describe`.

    :meth:`dynamic_viscosity` and :meth:`palmgren_f0` are derived from those.
    """

    name: str
    method: str
    temperature: float
    mu_bl: float
    mu_ehl: float
    contact_friction: float = 0.1
    """Sliding friction coefficient [-] of the cage pockets and guiding lands, used where no
    film model applies (lubricated steel on polymer or brass: about 0.1)."""

    @property
    def is_viscous(self) -> bool:
        """True when the lubricant has a viscosity at its operating temperature (oil, grease):
        it forms an EHL film, drags the balls and churns; False for
        :class:`~bearingsim.physics.dry.Dry`.

        Returns
        -------
        bool
            Whether the lubricant is viscous.
        """
        return float(self.kinematic_viscosity()) > 0.0

    def _t(self, T: Any) -> Any:  # noqa: N803
        return self.temperature if T is None else check_range(
            T, "T", "K", 200.0, 600.0, where=f"{type(self).__name__} {self.name!r}")

    @abstractmethod
    def kinematic_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """Kinematic viscosity [m^2/s] at temperature ``T`` [K].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            Kinematic viscosity [m^2/s], >= 0.
        """

    @abstractmethod
    def density(self, T: Any = None) -> Any:  # noqa: N803
        """Density [kg/m^3] at temperature ``T`` [K].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            Density [kg/m^3], >= 0.
        """

    @abstractmethod
    def pressure_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """Barus pressure-viscosity coefficient alpha [1/Pa] at temperature ``T`` [K].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            alpha [1/Pa], >= 0.
        """

    @abstractmethod
    def traction_coefficient(self, slip_speed: Any) -> Any:
        """Odd, smooth traction coefficient [-] at a sliding speed [m/s].

        Parameters
        ----------
        slip_speed : float or array or SX
            Sliding speed [m/s], either sign.

        Returns
        -------
        float or array or SX
            Traction coefficient [-], of the sign of ``slip_speed``.
        """

    @abstractmethod
    def churning_factor(self) -> float:
        """Multiplier [-] of the load-independent (viscous) friction for this lubricant fill."""

    @abstractmethod
    def describe(self) -> str:
        """One-line human-readable description."""

    def dynamic_viscosity(self, T: Any = None) -> Any:  # noqa: N803
        """Dynamic viscosity ``eta = nu rho`` [Pa s] at temperature ``T`` [K].

        Parameters
        ----------
        T : float or SX, optional
            Temperature [K], in [200, 600]; None: the operating ``temperature``.

        Returns
        -------
        float or SX
            Dynamic viscosity [Pa s], >= 0.
        """
        return self.kinematic_viscosity(T) * self.density(T)

    def palmgren_f0(self, bearing_type: str, series: str | None = None) -> float:
        """Palmgren factor f0 [-] for this lubricant's method (and the bearing's catalogue
        ``series`` where the catalogue table has it), times :meth:`churning_factor`
        (:func:`~bearingsim.physics.lubrication.palmgren_f0`).

        Parameters
        ----------
        bearing_type : str
            Bearing type, e.g. ``"deep_groove"`` or ``"angular_contact"``.
        series : str, optional
            Catalogue series of the bearing (None: the type's default row).

        Returns
        -------
        float
            f0 [-], >= 0.
        """
        if self.churning_factor() == 0.0:
            return 0.0
        return palmgren_f0(bearing_type, self.method, series) * self.churning_factor()

    def __repr__(self) -> str:
        return f"<{self.describe()}>"
