"""The intermediate representation the assembler's passes hand on: the types of the fields of
:class:`~bearingsim.assembler.state.AssemblyState` that the passes set after the flat DAE
(:mod:`~bearingsim.assembler.dae`), and what code generation and the mapped-ball kernels read.

This module sits below the passes and imports none of them: a pass, the state and the kernel
builders (:mod:`~bearingsim.assembler.mapped`) all import their types from here.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca

from bearingsim.assembler.dae import Eq, Param, Var

__all__ = ["Block", "BallSet", "NonlinearBlock", "Causal", "Repeats"]

Block = list[tuple[Eq, Var]]
"""One block of the BLT form: (equation, the unknown it determines) pairs solved together."""


@dataclass
class BallSet:
    """One row of identical members (balls with their contacts, pockets and drag)."""

    name: str
    """The parent of the arrays (``""`` at the root, ``"inner_layer"`` in a nested bearing)."""
    count: int
    """Number of members (balls)."""
    patterns: list[str]
    """The members' variable names with the index as ``*``, in one order for all members."""
    variables: list[list[Var]]
    """``variables[k][j]``: member ``k``'s variable of ``patterns[j]``."""
    param_patterns: list[str]
    parameters: list[list[Param]]
    """``parameters[k][j]``: member ``k``'s parameter of ``param_patterns[j]``."""


@dataclass
class NonlinearBlock:
    """Residuals ``g(z) = 0`` in the tearing variables ``z`` (their own symbols)."""

    tears: list[Var]
    residuals: ca.SX
    guess: list[float]
    equations: list[Eq]


@dataclass
class Causal:
    """Every unknown as an expression of base symbols and nonlinear-block tearing variables."""

    expr: dict[Var, ca.SX] = field(default_factory=dict)
    nonlinear: list[NonlinearBlock] = field(default_factory=list)
    n_blocks: int = 0
    n_linear_loops: int = 0
    largest_block: int = 0
    copied_members: int = 0
    """Members of ball sets whose solutions were copied from member 0's."""
    copied: set[tuple[str, int, int]] = field(default_factory=set)
    """(set name, set size, member) of the members all of whose blocks were copied: their
    solutions are member 0's with their own symbols, by construction."""

    def value(self, v: Var) -> ca.SX:
        """``v`` through the base symbols: its own symbol for a state or input, else its
        solution.

        Parameters
        ----------
        v : Var
            A variable of the DAE.

        Returns
        -------
        casadi.SX
            Its expression in the base symbols.
        """
        return v.sym if v.is_state or v.is_input else self.expr[v]


@dataclass
class Repeats:
    """The ball sets of a model and its shared unknowns solved around them."""

    sets: list[BallSet] = field(default_factory=list)
    owner: dict[int, tuple[int, int]] = field(default_factory=dict)
    """``id(var or param)`` -> (set, member) for the members' variables and parameters."""
    shared_expr: dict[Var, ca.SX] = field(default_factory=dict)
    """Each shared unknown through the base symbols and the members' variables' own
    symbols."""
    shared_nonlinear: list = field(default_factory=list)
    """Nonlinear blocks among the shared unknowns, as
    :func:`~bearingsim.assembler.passes.tearing.causalize` returns them."""
    reason: str = ""
    """Why the model has no ball sets to map (empty when it has)."""
