"""A system with its inputs bound: the functions of ``(t, x, p)`` that integrators and solvers
call.

Inputs given as constants, symbolic functions of time or tables (:mod:`.inputs`) are composed
into the system's functions, so no Python runs inside an integration.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import casadi as ca

from bearingsim.assembler.system import System
from bearingsim.simulation.inputs import input_expression

__all__ = ["ClosedModel", "close_inputs"]


@dataclass
class ClosedModel:
    """The system with its inputs bound."""

    f: ca.Function
    """``f(t, x, p)``: state derivatives."""
    jac: ca.Function
    """``J(t, x, p)``: their exact sparse Jacobian with respect to ``x``."""
    observe: ca.Function
    """``observe(t, x, p)``: every variable of the model (``System.observed_names``)."""
    u: ca.Function
    """``u(t)``: the input vector."""
    symbolic: bool
    """Whether ``f``, ``jac`` and ``observe`` are SX functions (else MX)."""


def close_inputs(system: System, inputs: dict[str, Any] | None,
                 symbolic: bool = False) -> ClosedModel:
    """Compose the system's functions with symbolic input signals of time.

    Parameters
    ----------
    system : System
        An assembled system.
    inputs : dict, optional
        Input name -> constant, symbolic function of time or ``(times, values)`` table
        (:func:`~bearingsim.simulation.inputs.input_expression`).
    symbolic : bool
        Use the symbolic originals of a compiled system (needed where CasADi differentiates the
        functions, as in its integrators).

    Returns
    -------
    ClosedModel
    """
    funcs = (system.symbolic_functions or system.functions) if symbolic else system.functions
    ode, obs, jac = (funcs[k] for k in ("ode", "observe", "jac_x"))
    t_sx = ca.SX.sym("t")
    u_expr = input_expression(system, inputs, t_sx)
    u_fn = ca.Function("u", [t_sx], [u_expr])
    sx = ode.is_a("SXFunction")
    sym = ca.SX if sx else ca.MX
    t = sym.sym("t")
    x = sym.sym("x", system.n_states)
    p = sym.sym("p", len(system.params))
    u = u_fn(t)
    args, names = [t, x, p], ["t", "x", "p"]
    return ClosedModel(
        f=ca.Function("f", args, [ode(t, x, u, p)], names, ["xdot"]),
        jac=ca.Function("J", args, [jac(t, x, u, p)], names, ["J"]),
        observe=ca.Function("obs", args, [obs(t, x, u, p)], names, ["y"]),
        u=u_fn,
        symbolic=sx,
    )
