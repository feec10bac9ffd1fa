"""Linear-elastic materials of balls and rings (:class:`Material`, :data:`STEEL`,
:data:`SILICON_NITRIDE`) and the effective modulus of two of them (:func:`effective_modulus`),
the material input of the Hertz, line-contact and film formulas.
"""

from __future__ import annotations

from dataclasses import dataclass

from bearingsim.checks import guard_public_functions
from bearingsim.physical_checks import check_modulus
from bearingsim.validation import check_range

__all__ = [
    "Material",
    "STEEL",
    "SILICON_NITRIDE",
    "effective_modulus",
]


@dataclass(frozen=True)
class Material:
    """Linear-elastic material of a ball or ring.

    Attributes
    ----------
    name : str
        Material name.
    youngs_modulus : float
        Young's modulus [Pa], in [1e8, 1e13] (a value in GPa is caught).
    poisson_ratio : float
        Poisson's ratio [-], in [0, 0.5).
    """

    name: str
    youngs_modulus: float
    poisson_ratio: float

    def __post_init__(self) -> None:
        where = f"Material({self.name})"
        check_range(self.youngs_modulus, "youngs_modulus", "Pa", 0.0, low_inclusive=False,
                    where=where)
        check_modulus(self.youngs_modulus, "youngs_modulus", where)
        check_range(self.poisson_ratio, "poisson_ratio", "-", 0.0, 0.5, high_inclusive=False,
                    where=where)


STEEL = Material("AISI 52100 bearing steel", 208e9, 0.3)
"""Through-hardened bearing steel (Harris & Kotzalas, Essential Concepts, chapter "Contact stress
and deformation": E = 208 GPa, nu = 0.3)."""

SILICON_NITRIDE = Material("silicon nitride (Si3N4)", 310e9, 0.26)
"""Hot isostatically pressed silicon nitride for hybrid bearings (Harris & Kotzalas, Essential
Concepts, chapter "Rolling bearing materials": E = 310 GPa, nu = 0.26)."""


def effective_modulus(body1: Material = STEEL, body2: Material = STEEL) -> float:
    """Effective modulus ``E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` [Pa] (Hamrock).

    Parameters
    ----------
    body1, body2 : Material
        Materials of the two bodies (ball and ring).

    Returns
    -------
    float
        E' [Pa].
    """
    compliance = (1.0 - body1.poisson_ratio**2) / body1.youngs_modulus + (
        1.0 - body2.poisson_ratio**2
    ) / body2.youngs_modulus
    return 2.0 / compliance


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
