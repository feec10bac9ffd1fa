"""What the bodies of the dynamic level share (:class:`PartialRigidBody`): a mass and an
inertia, both positive."""

from __future__ import annotations

from bearingsim.language import Component, Parameter

__all__ = ["PartialRigidBody"]


class PartialRigidBody(Component):
    """Base of the balls, cage and ring bodies: the parameters ``m`` [kg] and ``J`` [kg m^2].

    Parameters
    ----------
    mass : float
        Mass [kg], > 0.
    inertia : float
        Moment of inertia [kg m^2], > 0, about the axis ``inertia_kind`` names.
    body : str
        What the body is, for the descriptions ("ball", "cage", "ring").
    inertia_kind : str
        Which inertia ``J`` is ("moment of inertia", "polar inertia", "tilt inertia").
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, mass: float, inertia: float, body: str, inertia_kind: str, name=None):
        super().__init__(name)
        self.m = Parameter(mass, "kg", f"{body} mass", low=0.0, low_inclusive=False)
        self.J = Parameter(inertia, "kg.m2", f"{body} {inertia_kind}", low=0.0,
                           low_inclusive=False)
