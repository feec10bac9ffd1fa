"""Flattening: the instance tree becomes one list of scalar variables and equations.

The members of a component array get their equations from member 0's by substitution when
they are the same but for their symbols (:mod:`~bearingsim.assembler.passes.member_equations`).
Connection sets are expanded with Modelica semantics: potentials equal, flows of inside
connectors plus the negated flows of outside connectors sum to zero, and the flow of a connector
that is connected nowhere as an inside connector is zero. Parameters bound to expressions of
other parameters are substituted.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import casadi as ca

from bearingsim.assembler.dae import DAE, Eq, Param, Var
from bearingsim.assembler.passes.member_equations import MemberEquations
from bearingsim.errors import ModelError, UnconnectedInputError
from bearingsim.language.component import Component, flow_sign
from bearingsim.language.connector import Connector
from bearingsim.language.declarations import Declaration, Input, Parameter, Variable
from bearingsim.language.symbols import readable, time

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "flatten", "to_residuals"]

NAME = "flatten"
"""The pass name in timings, logs and ``extra_passes``."""


def to_residuals(item: Any, origin: str) -> list[ca.SX]:
    """Turn an equation item (``lhs == rhs``, residual expression or list) into scalar residuals.

    Parameters
    ----------
    item : object
        An equation item.
    origin : str
        Where it comes from, for messages.

    Returns
    -------
    list of casadi.SX
        Scalar residuals.
    """
    if isinstance(item, (list, tuple)):
        return [r for sub in item for r in to_residuals(sub, origin)]
    if isinstance(item, (bool, int, float)) or item is None:
        raise ModelError(
            f"{origin or '<root>'}: an equation evaluated to the constant {item!r}; "
            "write equations with symbolic variables (lhs == rhs)"
        )
    expr = ca.SX(item)
    out = []
    for i in range(expr.numel()):
        e = expr[i]
        r = e.dep(0) - e.dep(1) if e.is_op(ca.OP_EQ) else e
        if r.is_constant():
            raise ModelError(
                f"{origin or '<root>'}: equation {readable(e)} reduces to the constant "
                f"{float(r):g}; it has no unknowns"
            )
        out.append(r)
    return out


def _connection_sets(root: Component) -> list[list[tuple[Connector, float]]]:
    parent: dict[tuple[int, bool], tuple[int, bool]] = {}
    members: dict[tuple[int, bool], tuple[Connector, float]] = {}

    def find(k):
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for comp in root.walk():
        for group in comp._connections:
            keys = []
            for c in group:
                sign = flow_sign(c, comp)
                key = (id(c), sign < 0)
                parent.setdefault(key, key)
                members[key] = (c, sign)
                keys.append(key)
            for k in keys[1:]:
                ra, rb = find(keys[0]), find(k)
                if ra != rb:
                    parent[rb] = ra
    sets: dict[tuple[int, bool], list[tuple[Connector, float]]] = {}
    for key in members:
        sets.setdefault(find(key), []).append(members[key])
    return list(sets.values())


def flatten(root: Component, members: MemberEquations | None = None) -> DAE:
    """Flatten an instance tree.

    Parameters
    ----------
    root : Component
        The assembly (or component) to flatten; its own inputs become system inputs.
    members : MemberEquations, optional
        Derives array members' equations from member 0's (a fresh one by default; pass one
        to read how many components it instantiated, or ``MemberEquations(enabled=False)``
        to build every component by its own code).

    Returns
    -------
    DAE
        Scalar variables, equations and parameters with dotted names.
    """
    eqs: list[Eq] = []
    init_eqs: list[Eq] = []
    eq_owner: list[Component] = []
    members = members if members is not None else MemberEquations()
    for comp in root.walk():
        where = comp.path
        residuals = members.instantiate(comp)
        if residuals is None:
            members.begin(comp)
            residuals = [r for item in comp.all_equations() for r in to_residuals(item, where)]
            members.record(comp, residuals)
        for r in residuals:
            eqs.append(Eq(r, where))
            eq_owner.append(comp)
        for item in comp.initial_equations():
            for r in to_residuals(item, where):
                init_eqs.append(Eq(r, where, initial=True))

    # connection equations
    connected_inside: set[int] = set()
    for members in _connection_sets(root):
        ref, _ = members[0]
        scope_path = ref.owner.path
        for c, sign in members:
            if sign > 0:
                connected_inside.add(id(c))
        for p_ref in ref.potentials:
            for c, _ in members[1:]:
                p = c.fields[p_ref.attr]
                eqs.append(Eq(p_ref.sym - p.sym, scope_path, text=f"{p_ref.path} = {p.path}"))
                eq_owner.append(None)
        for f_ref in ref.flows:
            terms = [(c.fields[f_ref.attr], sign) for c, sign in members]
            total = terms[0][0].sym if terms[0][1] > 0 else -terms[0][0].sym
            for f, sign in terms[1:]:
                total = total + f.sym if sign > 0 else total - f.sym
            text = " ".join(("+" if sign > 0 else "-") + f.path for f, sign in terms)
            eqs.append(Eq(total, scope_path, text=text + " = 0"))
            eq_owner.append(None)

    # declarations (after equations: der() creates derivative declarations)
    decls: list[Declaration] = []
    for comp in root.walk():
        decls.extend(comp._declarations.values())
        for conn in comp._connectors.values():
            decls.extend(conn.fields.values())
            if id(conn) not in connected_inside:
                for f in conn.flows:
                    eqs.append(Eq(f.sym, conn.path, text=f"{f.path} = 0 (unconnected flow)"))
                    eq_owner.append(None)

    params: list[Param] = []
    bound_syms, bound_exprs = [], []
    variables: list[Var] = []
    var_of_decl: dict[int, Var] = {}
    inputs: list[tuple[Input, Var]] = []
    for d in decls:
        if isinstance(d, Parameter):
            if d.binding is not None:
                bound_syms.append(d.sym)
                bound_exprs.append(d.binding)
            else:
                params.append(Param(d.path, d.sym, d.value, d.unit, d.description, d))
            continue
        var = _make_var(d)
        variables.append(var)
        var_of_decl[id(d)] = var
        if isinstance(d, Input):
            inputs.append((d, var))
        if isinstance(d, Variable) and d.derivative is not None:
            dv = _make_var(d.derivative)
            dv.is_derivative = True
            variables.append(dv)
            var_of_decl[id(d.derivative)] = dv
            var.derivative = dv

    _mark_inputs(root, inputs, eqs, eq_owner)

    if bound_syms:
        _substitute_bindings(eqs, init_eqs, bound_syms, bound_exprs, params)

    return DAE(vars=variables, eqs=eqs, params=params, time=time, initial_eqs=init_eqs)


def _make_var(d: Declaration) -> Var:
    return Var(
        name=d.path,
        sym=d.sym,
        unit=d.unit,
        description=d.description,
        start=getattr(d, "start", None),
        fixed=getattr(d, "fixed", False),
        nominal=getattr(d, "nominal", None),
        default=getattr(d, "default", None),
        low=getattr(d, "low", None),
        high=getattr(d, "high", None),
        required=getattr(d, "required", False),
        warn_above=getattr(d, "warn_above", None),
        limit=getattr(d, "limit", None),
    )


def _mark_inputs(root, inputs, eqs, eq_owner) -> None:
    if not inputs:
        return
    by_name = {v.sym.name(): (d, v) for d, v in inputs}
    bound: set[str] = set()
    # which equations each input occurs in: one structural Jacobian instead of a symvar per
    # equation
    incidence = ca.jacobian_sparsity(ca.vertcat(*[eq.residual for eq in eqs]),
                                     ca.vertcat(*[v.sym for _, v in inputs]))
    rows, cols = incidence.get_triplet()
    for row, col in zip(rows, cols, strict=True):
        d, v = inputs[col]
        owner = eq_owner[row]
        if owner is None or owner is not d.owner:
            bound.add(v.sym.name())
    for name, (d, v) in by_name.items():
        if name in bound:
            continue
        if d.owner is root or d.default is not None:
            v.is_input = True
            if v.default is None:
                v.default = 0.0
        else:
            raise UnconnectedInputError(
                f"input {d.path} [{d.unit}] ({d.description or 'no description'}) is neither "
                "connected nor bound by an equation of an enclosing component, and has no default"
            )


def _substitute_bindings(eqs, init_eqs, bound_syms, bound_exprs, params) -> None:
    free = {p.sym.name() for p in params}
    bound = ca.vertcat(*bound_syms)
    exprs = ca.vertcat(*bound_exprs)
    for _ in range(len(bound_syms) + 1):
        if not ca.depends_on(exprs, bound):
            break
        exprs = ca.substitute(exprs, bound, exprs)
    for s in ca.symvar(exprs):
        if s.name() not in free and s.name() != time.name():
            raise ModelError(
                f"a parameter binding uses {readable(s)}, which is not a parameter; bind "
                "parameters to expressions of parameters only"
            )
    all_eqs = eqs + init_eqs
    res = ca.substitute(ca.vertcat(*[e.residual for e in all_eqs]), bound, exprs)
    for e, r in zip(all_eqs, ca.vertsplit(res), strict=True):
        e.residual = r


def run(state: AssemblyState) -> None:
    """Flatten ``state.root`` into ``state.dae``.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    members = MemberEquations()
    state.dae = flatten(state.root, members)
    state.report["flat"] = f"{len(state.dae.vars)} variables, {len(state.dae.eqs)} equations"
    if members.instantiated:
        state.report["flat"] += (f" ({members.instantiated} components' equations by "
                                 "substitution from their array's member 0)")
