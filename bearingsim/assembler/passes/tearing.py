"""Solving the BLT blocks: explicit assignments, torn linear loops and torn nonlinear loops.

Each block's unknowns are expressed through the *base* symbols (time, states, inputs,
parameters) and the tearing variables of earlier nonlinear blocks. Within a block a greedy
tearing (the variable in most remaining equations is torn first) leaves a small set of tearing
variables; the other unknowns follow explicitly from equations linear in them. A linear residual
system is solved symbolically; a nonlinear one becomes a :class:`NonlinearBlock` that code
generation turns into a CasADi ``fast_newton`` rootfinder.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import casadi as ca

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.passes.blt import Block

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "NonlinearBlock", "Causal", "causalize"]

NAME = "tearing and block solving"
"""The pass name in timings, logs and ``extra_passes``."""


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

    def value(self, v: Var) -> ca.SX:
        """``v`` through the base symbols: its own symbol for a state or input, else its
        solution."""
        return v.sym if v.is_state or v.is_input else self.expr[v]


def _vanishes(coef: ca.SX) -> bool:
    """Whether a coefficient is identically zero."""
    return coef.is_constant() and float(coef) == 0.0


def _linear_coefficient(r: ca.SX, v: Var) -> ca.SX | None:
    """``dr/dv`` if the residual ``r`` is linear in ``v`` with a coefficient that is not
    identically zero, else None."""
    coef = ca.jacobian(r, v.sym)
    if ca.depends_on(coef, v.sym) or _vanishes(coef):
        return None
    return coef


def _solve_linear_scalar(r: ca.SX, v: Var, coef: ca.SX | None = None) -> ca.SX:
    """``v`` from ``r = 0``, linear in ``v`` (``coef``: ``dr/dv`` if already known)."""
    if coef is None:
        coef = ca.jacobian(r, v.sym)
    rest = ca.substitute(r, v.sym, ca.SX(0))
    return -rest / coef


def _tear(block: Block, residuals: dict[Eq, ca.SX]):
    """Greedy tearing. Returns (ordered explicit (eq, var) pairs, tear vars, residual eqs)."""
    eqs = [e for e, _ in block]
    unknown = {v for _, v in block}
    occurs = {e: [v for v in unknown if ca.depends_on(residuals[e], v.sym)] for e in eqs}
    remaining_eqs = list(eqs)
    solved: list[tuple[Eq, Var]] = []
    tears: list[Var] = []
    while unknown:
        progress = True
        while progress:
            progress = False
            for e in list(remaining_eqs):
                left = [v for v in occurs[e] if v in unknown]
                if len(left) == 1 and _linear_coefficient(residuals[e], left[0]) is not None:
                    solved.append((e, left[0]))
                    unknown.discard(left[0])
                    remaining_eqs.remove(e)
                    progress = True
        if not unknown:
            break
        counts = {v: sum(v in occurs[e] for e in remaining_eqs) for v in unknown}
        pick = max(sorted(unknown, key=lambda v: v.name), key=lambda v: counts[v])
        tears.append(pick)
        unknown.discard(pick)
    return solved, tears, remaining_eqs


def causalize(dae: DAE, blocks: list[Block]) -> Causal:
    """Express every unknown through base symbols, block by block."""
    out = Causal(n_blocks=len(blocks))
    solved_by_name: dict[str, Var] = {}

    def resolved(expr: ca.SX) -> ca.SX:
        """``expr`` with the unknowns of earlier blocks replaced by their solutions."""
        prev = [solved_by_name[s.name()] for s in ca.symvar(expr) if s.name() in solved_by_name]
        if not prev:
            return expr
        return ca.substitute(expr, ca.vertcat(*[v.sym for v in prev]),
                             ca.vertcat(*[out.expr[v] for v in prev]))

    for block in blocks:
        out.largest_block = max(out.largest_block, len(block))
        if len(block) == 1:
            # One equation in one unknown: solved on the equation as written (small), then
            # earlier solutions substituted into the solution; the unknown is not in them, so
            # linearity and the coefficient are those of the resolved equation.
            e, v = block[0]
            coef = _linear_coefficient(e.residual, v)
            if coef is not None and not _vanishes(resolved(coef)):
                out.expr[v] = resolved(_solve_linear_scalar(e.residual, v, coef))
            else:
                out.expr[v] = v.sym
                out.nonlinear.append(NonlinearBlock([v], resolved(e.residual), [_guess(v)], [e]))
            solved_by_name[v.sym.name()] = v
            continue
        raw = resolved(ca.vertcat(*[e.residual for e, _ in block]))
        residuals = {e: raw[k] for k, (e, _) in enumerate(block)}
        solved, tears, res_eqs = _tear(block, residuals)
        local: dict[Var, ca.SX] = {}
        for e, v in solved:
            r = residuals[e]
            if local:
                keys = [k for k in local if ca.depends_on(r, k.sym)]
                if keys:
                    r = ca.substitute(
                        r, ca.vertcat(*[k.sym for k in keys]), ca.vertcat(*[local[k] for k in keys])
                    )
            local[v] = _solve_linear_scalar(r, v)
        g = ca.vertcat(*[residuals[e] for e in res_eqs])
        if local:
            g = ca.substitute(
                g, ca.vertcat(*[k.sym for k in local]), ca.vertcat(*[local[k] for k in local])
            )
        z = ca.vertcat(*[t.sym for t in tears])
        jac = ca.jacobian(g, z)
        if not ca.depends_on(jac, z):
            out.n_linear_loops += 1
            g0 = ca.substitute(g, z, ca.DM.zeros(len(tears)))
            zsol = ca.solve(jac, -g0)
            tear_expr = {t: zsol[k] for k, t in enumerate(tears)}
        else:
            out.nonlinear.append(
                NonlinearBlock(tears, g, [_guess(t) for t in tears], [e for e, _ in block])
            )
            tear_expr = {t: t.sym for t in tears}
        for t, ex in tear_expr.items():
            out.expr[t] = ex
            solved_by_name[t.sym.name()] = t
        if local:
            vals = ca.substitute(
                ca.vertcat(*[local[v] for v in local]),
                z,
                ca.vertcat(*[tear_expr[t] for t in tears]),
            )
            for k, v in enumerate(local):
                out.expr[v] = vals[k]
                solved_by_name[v.sym.name()] = v
    return out


def _guess(v: Var) -> float:
    return float(v.start) if v.start is not None else 0.0


def run(state: AssemblyState) -> None:
    """Set ``state.causal`` by solving ``state.blocks`` in order; report the loops."""
    state.require(NAME, "dae", "blocks")
    c = state.causal = causalize(state.dae, state.blocks)
    state.report["blocks"] = (
        f"{c.n_blocks} (largest {c.largest_block}; {c.n_linear_loops} linear loop(s) solved "
        f"symbolically; {len(c.nonlinear)} nonlinear loop(s) by Newton)"
    )
