"""Exceptions of bearingsim.

Every error names what the user wrote: the component path, parameter or variable in dotted names,
its unit and the valid range. Structural errors list the equations and unknowns involved.
"""

from __future__ import annotations

__all__ = [
    "BearingsimError",
    "ParameterError",
    "ModelError",
    "ConnectionError_",
    "StructuralError",
    "UnderdeterminedError",
    "OverdeterminedError",
    "SingularBlockError",
    "UnconnectedInputError",
    "SimulationError",
    "BudgetExceededError",
    "PassOrderError",
    "CatalogError",
    "PlasticDeformationWarning",
    "LongRunWarning",
    "SpeedLimitWarning",
    "MultipleSteadyStatesWarning",
    "CacheWarning",
]


class BearingsimError(Exception):
    """Base class of all bearingsim errors."""


class ParameterError(BearingsimError, ValueError):
    """A parameter or input value is of the wrong type or outside its valid range."""


class CatalogError(BearingsimError, KeyError):
    """An unknown bearing designation or lubricant name."""

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


class ModelError(BearingsimError):
    """A model is built wrongly (bad declaration, bad equation, bad nesting)."""


class ConnectionError_(ModelError):
    """Two connectors of different types, or a connection that Modelica semantics forbid."""


class StructuralError(ModelError):
    """The flattened equations cannot be solved for the unknowns.

    Parameters
    ----------
    message : str
        What is wrong, in words.
    equations : list of str
        Descriptions of the equations involved.
    unknowns : list of str
        Names of the unknowns involved.

    Attributes
    ----------
    equations : list of str
        Descriptions of the equations involved (origin component and text).
    unknowns : list of str
        Dotted names of the unknowns involved.
    """

    def __init__(self, message: str, equations=(), unknowns=()):
        self.equations = list(equations)
        self.unknowns = list(unknowns)
        parts = [message]
        if self.equations:
            parts.append("equations:\n  " + "\n  ".join(self.equations))
        if self.unknowns:
            parts.append("unknowns:\n  " + "\n  ".join(self.unknowns))
        super().__init__("\n".join(parts))


class UnderdeterminedError(StructuralError):
    """Fewer equations than unknowns (or unknowns that no equation determines)."""


class OverdeterminedError(StructuralError):
    """More equations than unknowns (or equations that no unknown is left for)."""


class SingularBlockError(StructuralError):
    """A block of equations is structurally singular."""


class UnconnectedInputError(ModelError):
    """A required input of a sub-component is neither connected nor bound by an equation."""


class SimulationError(BearingsimError, RuntimeError):
    """The integrator failed; the message names the time reached and the diverging variables."""


class BudgetExceededError(SimulationError):
    """A run used up its step or wall-time budget (``max_steps``, ``timeout``).

    Parameters
    ----------
    message : str
        What was exceeded, in words.
    t_reached : float
        Time the run reached [s].
    steps : int
        Integrator steps taken.
    wall_time : float
        Wall time spent [s].

    Attributes
    ----------
    t_reached : float
        Simulated time reached [s].
    steps : int
        Steps taken [-].
    wall_time : float
        Wall time used [s].
    """

    def __init__(self, message: str, t_reached: float, steps: int, wall_time: float):
        super().__init__(message)
        self.t_reached = t_reached
        self.steps = steps
        self.wall_time = wall_time


class PassOrderError(BearingsimError, RuntimeError):
    """An assembler pass ran before the pass that produces what it needs (an extra pass
    inserted too early, or an internal error)."""


class PlasticDeformationWarning(UserWarning):
    """A load beyond the static load rating: the contacts deform permanently (ISO 76's limit of
    4 200 MPa Hertz pressure for ball bearings is exceeded)."""


class LongRunWarning(UserWarning):
    """A run whose size (steps forced by ``max_step``, output bytes) makes it long or large."""


class MultipleSteadyStatesWarning(UserWarning):
    """A model with more than one stable steady state at the operating point (the SKF friction
    model's bistable speed ratio): the message lists them and says which one was returned and
    why."""


class SpeedLimitWarning(UserWarning):
    """A speed above the catalogue limiting speed of a bearing."""


class CacheWarning(UserWarning):
    """The cache folder (``$BEARINGSIM_CACHE``) cannot be written: assembled systems are not
    kept, and every run assembles anew."""
