"""A system with its inputs bound: the functions of ``(t, x, p)`` that integrators and solvers
call.

Inputs given as constants, symbolic functions of time or tables (:mod:`.inputs`) are composed
into the system's functions, so no Python runs inside an integration. The composition with
``u(t, q)`` (the run's numbers ``q`` free) is built once per system and input structure and
kept with the system; a run binds its numbers with a thin wrapper (building the composition of
a ball-level model's observed variables costs milliseconds, the wrapper microseconds).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import casadi as ca

from bearingsim.assembler.system import System
from bearingsim.keeps import kept
from bearingsim.simulation.inputs import InputSignal, input_signal

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


def close_inputs(system: System, inputs: dict[str, Any] | None,
                 symbolic: bool = False, signal: InputSignal | None = None) -> ClosedModel:
    """Compose the system's functions with symbolic input signals of time.

    Parameters
    ----------
    system : System
        An assembled system.
    inputs : dict, optional
        Input name -> constant, symbolic function of time or ``(times, values)`` table
        (:func:`~bearingsim.simulation.inputs.input_signal`).
    symbolic : bool
        Use the symbolic originals of a compiled system (needed where CasADi differentiates the
        functions, as in its integrators).
    signal : InputSignal, optional
        ``input_signal(system, inputs)`` when the caller has it already.

    Returns
    -------
    ClosedModel
        The same object for runs with the same inputs (the last :data:`CLOSED_PER_SYSTEM`
        input sets are kept with the system).
    """
    signal = input_signal(system, inputs) if signal is None else signal
    key = (signal.key, signal.q.tobytes(), symbolic)
    return kept(system.__dict__.setdefault("_closed_models", {}), key,
                lambda: _closed(system, signal, symbolic), CLOSED_PER_SYSTEM)


def _closed(system: System, signal: InputSignal, symbolic: bool) -> ClosedModel:
    """The closed model of ``signal``'s inputs (:func:`closed_model`, made anew)."""
    generic = _composed(system, signal, symbolic)
    t, x, p = ca.MX.sym("t"), ca.MX.sym("x", system.n_states), ca.MX.sym("p", len(system.params))
    q = ca.DM(signal.q)
    args, names = [t, x, p], ["t", "x", "p"]
    bound = [ca.Function(name, args, [fn(t, x, p, q)], names, [out])
             for fn, name, out in zip(generic, ("f", "J", "obs"), ("xdot", "J", "y"),
                                      strict=True)]
    t_u = ca.SX.sym("t")
    u_fn = ca.Function("u", [t_u], [signal.u(t_u, q)])
    return ClosedModel(f=bound[0], jac=bound[1], observe=bound[2], u=u_fn)


CLOSED_PER_SYSTEM = 16
"""Input sets whose closed model a system keeps (the oldest are dropped first)."""


def _composed(system: System, signal: InputSignal,
              symbolic: bool) -> tuple[ca.Function, ca.Function, ca.Function]:
    """``(f, J, observe)`` of ``(t, x, p, q)`` with ``u(t, q)`` composed in; built once per
    system, input structure and ``symbolic`` (kept with the system)."""
    cache = system.__dict__.setdefault("_closed_cache", {})
    key = (signal.key, symbolic)
    if key in cache:
        return cache[key]
    funcs = (system.symbolic_functions or system.functions) if symbolic else system.functions
    ode, obs, jac = (funcs[k] for k in ("ode", "observe", "jac_x"))
    sym = ca.SX if ode.is_a("SXFunction") else ca.MX
    t = sym.sym("t")
    x = sym.sym("x", system.n_states)
    p = sym.sym("p", len(system.params))
    q = sym.sym("q", signal.q.size)
    u = signal.u(t, q)
    args = [t, x, p, q]
    composed = (ca.Function("f", args, [ode(t, x, u, p)]),
                ca.Function("J", args, [jac(t, x, u, p)]),
                ca.Function("obs", args, [obs(t, x, u, p)]))
    cache[key] = composed
    return composed
