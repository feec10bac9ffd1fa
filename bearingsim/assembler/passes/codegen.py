"""Code generation: CasADi Functions for the ODE right-hand side, its exact sparse Jacobian,
the outputs and every observed variable.

Models whose BLT contains nonlinear blocks get MX functions in which each block is a CasADi
rootfinder: ``fast_newton`` (plain Newton steps, code-generatable C, for FMUs and compiled
systems) or ``newton`` (Newton with a line search, for models whose blocks need globalization;
not code-generatable); all other models are pure SX.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache, partial
from typing import TYPE_CHECKING

import casadi as ca

from bearingsim.assembler.dae import DAE
from bearingsim.assembler.function_options import CSE, rootfinder_options
from bearingsim.assembler.ir import Causal
from bearingsim.assembler.mapped_forms import MappedForms
from bearingsim.assembler.system import FunctionTable, Signal, System
from bearingsim.errors import StructuralError

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["GRAPH_KEYS", "JACOBIANS", "NAME", "run", "build_functions",
           "initial_problem", "mapped_ode_functions"]

NAME = "code generation"
"""The pass name in timings, logs and ``extra_passes``."""

def build_functions(dae: DAE, causal: Causal, outputs: list[str] | None, newton_tol: float,
                    rootfinder: str = "fast_newton"):
    """Return (function table, observed names, output names); the right-hand side, observed and
    output functions and their Jacobians are built on first access.

    ``rootfinder`` is one of :data:`~bearingsim.assembler.function_options.ROOTFINDERS` (the
    plugin of the nonlinear blocks).

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    causal : Causal
        The causalized system.
    outputs : list of str or None
        Requested outputs (None: every variable).
    newton_tol : float
        Absolute residual tolerance of the nonlinear blocks, > 0.
    rootfinder : str
        CasADi rootfinder plugin.

    Returns
    -------
    tuple
        (function table, observed names, output names).
    """
    states = dae.states
    inputs = dae.inputs
    t = dae.time
    x = ca.vertcat(*[v.sym for v in states]) if states else ca.SX(0, 1)
    u = ca.vertcat(*[v.sym for v in inputs]) if inputs else ca.SX(0, 1)
    p = ca.vertcat(*[q.sym for q in dae.params]) if dae.params else ca.SX(0, 1)

    derivs = [causal.value(v.derivative) for v in states]
    xdot = ca.vertcat(*derivs) if states else ca.SX(0, 1)

    observed_names: list[str] = []
    observed: list[ca.SX] = []
    for v in dae.vars:
        observed_names.append(v.name)
        observed.append(causal.value(v))
    index = {v.name: v for v in dae.vars}
    if dae.aliases:
        scales, reps, offsets = [], [], []
        for a in dae.aliases.values():
            observed_names.append(a.name)
            rep = a.representative
            scales.append(a.scale if rep is not None else 0.0)
            reps.append(causal.value(rep) if rep is not None else ca.SX(0))
            offsets.append(a.offset)
        observed.append(ca.DM(offsets) + ca.DM(scales) * ca.vertcat(*reps))
    obs = ca.vertcat(*observed) if observed else ca.SX(0, 1)
    obs_pos = {n: k for k, n in enumerate(observed_names)}
    output_names = list(outputs) if outputs else [n for n in observed_names if n in index]
    out_pos = [obs_pos[n] for n in output_names]

    args = [t, x, u, p]
    names = ["t", "x", "u", "p"]
    if not causal.nonlinear:
        # The right-hand side, observed and output functions share one common subexpression
        # elimination over the whole model; built on first access, like the Jacobians:
        # the SUNDIALS kernels of models with ball sets never read them (they map one
        # function per ball), and the elimination is a quarter of the 6304 ball level's
        # assembly.
        @cache
        def exprs() -> dict:
            return _shared_graph([t, x, u, p], xdot, obs, out_pos)

        pending = {k: partial(_graph_function, exprs, k, args, names) for k in GRAPH_KEYS}
        # Differentiating the shared graph gives Jacobians that share its subexpressions from
        # the start: ~10x cheaper than eliminating common subexpressions of a Jacobian
        # afterwards (6304 ball level: 1.6 s vs 12 s for jac_x, instruction count within 2 %).
        # Built on first access (8 of the 10 s of code generation of the nested bearing).
        pending.update(_jacobians(exprs, x, u, args, names))
        return FunctionTable({}, pending), observed_names, output_names

    # MX composition with rootfinders
    base_sx = ca.vertcat(t, x, u, p)
    mt, mx = ca.MX.sym("t"), ca.MX.sym("x", x.numel())
    mu, mp = ca.MX.sym("u", u.numel()), ca.MX.sym("p", p.numel())
    base_mx = ca.vertcat(mt, mx, mu, mp)
    z_sx: list[ca.SX] = []
    z_mx: list[ca.MX] = []
    for k, blk in enumerate(causal.nonlinear):
        zb = ca.vertcat(*[v.sym for v in blk.tears])
        prev_sx = ca.vertcat(base_sx, *z_sx)
        g = ca.Function(f"g{k}", [zb, prev_sx], [blk.residuals])
        solver = ca.rootfinder(f"newton{k}", rootfinder, g,
                               rootfinder_options(rootfinder, newton_tol))
        zk = solver(ca.DM(blk.guess), ca.vertcat(base_mx, *z_mx))
        z_sx.append(zb)
        z_mx.append(zk)
    full_sx = ca.vertcat(base_sx, *z_sx)
    full_mx = ca.vertcat(base_mx, *z_mx)
    margs = [mt, mx, mu, mp]

    @cache
    def mexprs() -> dict:
        return {k: ca.Function(f"{k}_sx", [full_sx], [e])(full_mx)
                for k, e in _shared_graph([full_sx], xdot, obs, out_pos).items()}

    pending = {k: partial(_graph_function, mexprs, k, margs, names) for k in GRAPH_KEYS}
    pending.update(_jacobians(mexprs, mx, mu, margs, names))
    funcs = _semi_explicit_dae(t, x, u, p, z_sx, z_mx, margs, causal, xdot, obs)
    return FunctionTable(funcs, pending), observed_names, output_names


GRAPH_KEYS = ("ode", "observe", "output")
"""The functions of the shared graph (:func:`_shared_graph`)."""


def _graph_function(exprs: Callable[[], dict], key: str, args: list,
                    names: list[str]) -> ca.Function:
    """The function ``key`` of the shared graph ``exprs()`` (SX or MX)."""
    return ca.Function(key, args, [exprs()[key]], names, [key])


JACOBIANS = {"jac_x": ("ode", "x", "jac_x"), "jac_u": ("ode", "u", "jac_u"),
             "out_jac_x": ("output", "x", "J"), "out_jac_u": ("output", "u", "J")}
"""The Jacobian functions of every system: key -> (function differentiated, by which input,
output name)."""


def _jacobians(exprs: Callable[[], dict], x, u, args: list, names: list[str]) -> dict:
    """Builders of ``jac_x``, ``jac_u``, ``out_jac_x`` and ``out_jac_u`` (the Jacobians of
    ``exprs()["ode"]`` and ``exprs()["output"]``, SX or MX), for a :class:`FunctionTable`."""
    wrts = {"x": x, "u": u}
    return {key: partial(_jacobian_function, key, exprs, of, wrts[wrt], args, names, out)
            for key, (of, wrt, out) in JACOBIANS.items()}


def mapped_ode_functions(system: System) -> dict[str, ca.Function] | None:
    """The functions of ``system`` that a run evaluates (:data:`GRAPH_KEYS`, ``jac_x`` and
    ``jac_u``; same names and signatures) with one function per ball mapped over each row, or
    None when the system's ODE form does not map (no ball sets).

    The right-hand side, its Jacobians and the observed variables are the mapped kernel's
    (:attr:`System.mapped`), the outputs a selection of the observed variables. Not included:
    the outputs' Jacobians (``out_jac_x``, ``out_jac_u``; evaluated once per linearization):
    differentiated through the mapped observe function, with every variable an output (the
    default), they generate several times the C of all the others together.

    Parameters
    ----------
    system : System
        An assembled system.

    Returns
    -------
    dict of str to casadi.Function or None
        The mapped functions, or None.
    """
    per_ball = system.mapped.find("ode") if system.mapped is not None else None
    if per_ball is None:
        return None
    names = ["t", "x", "u", "p"]
    args = [ca.MX.sym("t"), ca.MX.sym("x", system.n_states),
            ca.MX.sym("u", len(system.inputs)), ca.MX.sym("p", len(system.params))]
    xdot, _, jac_x, jac_u = per_ball.ode_with_jacobians(*args)
    observed = per_ball.observe(*args)
    position = {n: k for k, n in enumerate(system.observed_names)}
    output = (observed[[position[n] for n in system.output_names]] if system.output_names
              else ca.MX(0, 1))
    exprs = {"ode": xdot, "observe": observed, "output": output, "jac_x": jac_x,
             "jac_u": jac_u}
    out_names = {**{k: k for k in GRAPH_KEYS}, **{k: v[2] for k, v in JACOBIANS.items()}}
    return {k: ca.Function(k, args, [e], names, [out_names[k]]) for k, e in exprs.items()}


def _jacobian_function(name: str, exprs: Callable[[], dict], of: str, wrt, args: list,
                       names: list[str], out_name: str) -> ca.Function:
    """``d exprs()[of] / d wrt`` as a function of ``args`` (SX or MX)."""
    return ca.Function(name, args, [ca.jacobian(exprs()[of], wrt)], names, [out_name])


def _shared_graph(args: list[ca.SX], xdot: ca.SX, obs: ca.SX, out_pos: list[int]) -> dict:
    """The right-hand side, observed and output expressions after one common subexpression
    elimination over the whole model (CasADi ``cse``), so that the functions built from them,
    and their Jacobians, share subexpressions without eliminating them again (for the 270-state
    nested bearing, one elimination instead of three saves about 10 s)."""
    xdot_shared, obs_shared = ca.Function("shared", args, [xdot, obs], CSE)(*args)
    y_shared = obs_shared[out_pos] if out_pos else ca.SX(0, 1)
    return {"ode": xdot_shared, "observe": obs_shared, "output": y_shared}


def _semi_explicit_dae(t, x, u, p, z_sx, z_mx, margs, causal, xdot, obs) -> dict:
    """The model as ``x' = f(t, x, z, u, p), 0 = g(t, x, z, u, p)`` with ``z`` the tearing
    variables of the nonlinear blocks: for DAE solvers (IDAS) that iterate on ``z`` themselves
    instead of calling a Newton solve inside every right-hand side."""
    z = ca.vertcat(*z_sx)
    g = ca.vertcat(*[blk.residuals for blk in causal.nonlinear])
    args, names = [t, x, z, u, p], ["t", "x", "z", "u", "p"]
    return {
        "dae_ode": ca.Function("dae_ode", args, [xdot], names, ["ode"]),
        "dae_alg": ca.Function("dae_alg", args, [g], names, ["alg"]),
        "dae_observe": ca.Function("dae_observe", args, [obs], names, ["observe"]),
        "dae_z": ca.Function("dae_z", margs, [ca.vertcat(*z_mx)], ["t", "x", "u", "p"], ["z"]),
    }


def initial_problem(dae: DAE, funcs: dict) -> tuple[ca.Function | None, list[int]]:
    """Residual of the initial equations as a function of (t, x, u, p), and the free states.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    funcs : dict
        The function table of :func:`build_functions`.

    Returns
    -------
    tuple of (casadi.Function or None, list of int)
        The residual (None without initial equations) and the indices of the free states.
    """
    if not dae.initial_eqs:
        return None, []
    states = dae.states
    free = [k for k, v in enumerate(states) if not v.fixed]
    if len(free) != len(dae.initial_eqs):
        raise StructuralError(
            f"{len(dae.initial_eqs)} initial equation(s) for {len(free)} state(s) without a "
            "fixed start value; give fixed=False exactly to the states the initial equations "
            "determine",
            equations=[e.describe() for e in dae.initial_eqs],
            unknowns=[states[k].name for k in free],
        )
    values = ca.vertcat(*[v.sym for v in dae.vars])
    p = ca.vertcat(*[q.sym for q in dae.params]) if dae.params else ca.SX(0, 1)
    res = ca.vertcat(*[e.residual for e in dae.initial_eqs])
    r_fn = ca.Function("init_r", [values, dae.time, p], [res])
    obs = funcs["observe"]
    mt, mx = ca.MX.sym("t"), ca.MX.sym("x", obs.size1_in(1))
    mu, mp = ca.MX.sym("u", obs.size1_in(2)), ca.MX.sym("p", obs.size1_in(3))
    all_vals = obs(mt, mx, mu, mp)[: len(dae.vars)]
    res_mx = r_fn(all_vals, mt, mp)
    return ca.Function("init", [mt, mx, mu, mp], [res_mx], ["t", "x", "u", "p"], ["r"]), free


def run(state: AssemblyState) -> None:
    """Set ``state.system``: the functions of ``state.dae`` solved as ``state.causal`` says,
    with the names, units, descriptions and start values of states, inputs and outputs.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae", "causal")
    dae, causal = state.dae, state.causal
    funcs, observed, out_names = build_functions(dae, causal, state.outputs, state.newton_tol,
                                                 state.rootfinder)
    units = {v.name: v.unit for v in dae.vars}
    descs = {v.name: v.description for v in dae.vars}
    for a in dae.aliases.values():
        units[a.name] = a.unit
        descs[a.name] = a.description
    states = [
        Signal(v.name, v.unit, v.description, v.start if v.start is not None else 0.0, v.fixed,
               v.nominal)
        for v in dae.states
    ]
    inputs = [Signal(v.name, v.unit, v.description, v.default or 0.0, low=v.low, high=v.high,
                     required=v.required, warn_above=v.warn_above,
                     limit=v.limit)
              for v in dae.inputs]
    outputs = [Signal(n, units.get(n, "1"), descs.get(n, "")) for n in out_names]
    init_fn, free = initial_problem(dae, funcs)
    repeats = state.repeats
    state.system = System(
        name=state.root.display_name,
        states=states,
        inputs=inputs,
        outputs=outputs,
        params=dae.params,
        functions=funcs,
        observed_names=observed,
        observed_units={n: units.get(n, "1") for n in observed},
        observed_descriptions={n: descs.get(n, "") for n in observed},
        init_residual=init_fn,
        free_initial_states=free,
        skipped=list(dae.skipped),
        rootfinder=state.rootfinder if causal.nonlinear else None,
        mapped=MappedForms(dae, causal, repeats, state.rootfinder, state.newton_tol)
        if repeats is not None and repeats.sets else None,
    )
