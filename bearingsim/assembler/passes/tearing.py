"""Solving the BLT blocks: explicit assignments, torn linear loops and torn nonlinear loops.

Each block's unknowns are expressed through the *base* symbols (time, states, inputs,
parameters) and the tearing variables of earlier nonlinear blocks. Within a block a greedy
tearing (the variable in most remaining equations is torn first) leaves a small set of tearing
variables; the other unknowns follow explicitly from equations linear in them. A linear residual
system is solved symbolically; a nonlinear one becomes a :class:`NonlinearBlock` that code
generation turns into a CasADi ``fast_newton`` rootfinder.

**Ball sets** (:mod:`~bearingsim.assembler.passes.ball_sets`) are solved once per set: when
member ``k``'s equations are member 0's with member ``k``'s variables and parameters in place
of member 0's (compared as functions with fresh symbols, :class:`_Mirrors`), member ``k``'s
solutions are member 0's solutions with those symbols substituted, in one substitution per
member, instead of solving its blocks again. These are the expressions solving member ``k``'s
own blocks would give (the same operations on the same structure); a member that differs is
solved block by block.
"""

from __future__ import annotations

from collections import defaultdict
from typing import TYPE_CHECKING

import casadi as ca

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.ir import BallSet, Block, Causal, NonlinearBlock
from bearingsim.assembler.passes.ball_sets import find_ball_sets, function_identity

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "causalize"]

NAME = "tearing and block solving"
"""The pass name in timings, logs and ``extra_passes``."""


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


class _Mirrors:
    """The members of ball sets whose blocks are member 0's with their own symbols.

    ``counterpart[id(block)]`` is member 0's block for each block of such a member (``k >= 1``),
    ``blocks_of[(s, k)]`` the member's blocks in BLT order, ``sigma[(s, k)]`` the symbols of
    member 0 and of member ``k`` (variables and parameters, pattern by pattern) that turn member
    0's solutions into member ``k``'s."""

    def __init__(self, dae: DAE, blocks: list[Block], sets: list[BallSet]):
        self.sets = sets
        self.position = {id(e): i for i, e in enumerate(dae.eqs)}
        self.where: dict[int, tuple[int, int, str]] = {}
        """``id(var)`` -> (set, member, pattern)."""
        for s, bs in enumerate(sets):
            for k in range(bs.count):
                for j, v in enumerate(bs.variables[k]):
                    self.where[id(v)] = (s, k, bs.patterns[j])
        per_member: dict[tuple[int, int], dict[frozenset, Block]] = defaultdict(dict)
        for block in blocks:
            found = {self.where.get(id(v), (None, None, None)) for _, v in block}
            members = {(s, k) for s, k, _ in found}
            if len(members) == 1 and None not in next(iter(members)):
                per_member[next(iter(members))][frozenset(p for *_, p in found)] = block
        self.counterpart: dict[int, Block] = {}
        self.blocks_of: dict[tuple[int, int], list[Block]] = {}
        self.sigma: dict[tuple[int, int], tuple[ca.SX, ca.SX]] = {}
        for s, bs in enumerate(sets):
            base = per_member.get((s, 0), {})
            keys = sorted(base, key=sorted)
            reference = self._identity(bs, 0, [base[q] for q in keys]) if base else None
            for k in range(1, bs.count if reference is not None else 0):
                mine = per_member.get((s, k), {})
                if set(mine) != set(base) or \
                        self._identity(bs, k, [mine[q] for q in keys], reference) != reference:
                    continue
                for q in keys:
                    self.counterpart[id(mine[q])] = base[q]
                ids = {id(m) for m in mine.values()}
                self.blocks_of[(s, k)] = [b for b in blocks if id(b) in ids]
                self.sigma[(s, k)] = (self._symbols(bs, 0), self._symbols(bs, k))

    @staticmethod
    def _symbols(bs: BallSet, k: int) -> ca.SX:
        return ca.vertcat(*[v.sym for v in bs.variables[k]],
                          *[q.sym for q in bs.parameters[k]])

    def _identity(self, bs: BallSet, k: int, blocks: list[Block],
                  reference: tuple | None = None) -> tuple | None:
        """Member ``k``'s equations (each block's in the order of the model's equations, which
        does not depend on the matching) as a function of its symbols (pattern order) and the
        shared symbols they read (by name), with fresh symbols; None if it cannot be built, or
        if the names of the shared symbols already differ from those of ``reference`` (read
        from the equations' cached symbol names, before any function is built)."""
        own_names = {v.sym.name() for v in bs.variables[k]} | {
            q.sym.name() for q in bs.parameters[k]}
        names = tuple(sorted({n for block in blocks for e, _ in block
                              for n in e.symbol_names()} - own_names))
        if reference is not None and names != reference[0]:
            return None
        rows = [e.residual for block in blocks
                for e in sorted((e for e, _ in block), key=lambda e: self.position[id(e)])]
        residuals = ca.vertcat(*rows)
        shared = sorted((sym for sym in ca.symvar(residuals) if sym.name() not in own_names),
                        key=lambda sym: sym.name())
        try:
            fn = ca.Function("member", [self._symbols(bs, k), ca.vertcat(*shared)], [residuals])
        except RuntimeError:
            return None
        return names, function_identity(fn)


def causalize(dae: DAE, blocks: list[Block], sets: list[BallSet] | None = None) -> Causal:
    """Express every unknown through base symbols, block by block; the members of ``sets``
    (ball sets) that repeat member 0 by copying member 0's solutions.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    blocks : list of Block
        The BLT blocks, in order.
    sets : list of BallSet, optional
        Ball sets whose members copy member 0.

    Returns
    -------
    Causal
        The solutions and nonlinear residuals.
    """
    out = Causal(n_blocks=len(blocks))
    solved_by_name: dict[str, Var] = {}
    mirrors = _Mirrors(dae, blocks, sets) if sets else None
    out.copied_members = len(mirrors.sigma) if mirrors is not None else 0
    pending: dict[str, tuple[int, int]] = {}
    """Unknowns of repeating members reached in BLT order, copied by :func:`flush` when read."""
    done: set[int] = set()
    """``id(block)`` of the copied blocks."""
    flushed: set[tuple[int, int]] = set()
    """Members copied already: once only, so that the copies share subexpressions the way
    solving gives (a second copy would duplicate what the first one copied); their later
    blocks are solved."""
    linear_loops: set[int] = set()
    """``id(block)`` of the blocks solved as linear loops."""
    nonlinear_of: dict[int, NonlinearBlock] = {}
    """``id(var)`` of a tearing variable -> its nonlinear block."""

    def ready(block: Block) -> bool:
        """Whether a repeating member's block can be copied: member 0's is solved.

        Parameters
        ----------
        block : Block
            A repeating member's block.

        Returns
        -------
        bool
            Whether it can be copied.
        """
        return all(v in out.expr for _, v in mirrors.counterpart[id(block)])

    def flush(member: tuple[int, int]) -> None:
        """Copy every block of ``member`` whose member 0 block is solved (reached in BLT order
        or not: the copies are expressions of base symbols): member 0's solutions and
        nonlinear residuals with the member's symbols, in one substitution.

        Parameters
        ----------
        member : tuple of (int, int)
            Set and member index.
        """
        if member in flushed:
            return
        flushed.add(member)
        todo = [b for b in mirrors.blocks_of[member]  # not those solved before (not ready then)
                if ready(b) and not any(v in out.expr for _, v in b)]
        if len(todo) == len(mirrors.blocks_of[member]):
            bs = mirrors.sets[member[0]]
            out.copied.add((bs.name, bs.count, member[1]))
        where = mirrors.where
        pattern_var = {where[id(v)][2]: v for block in todo for _, v in block}
        pairs, residual_blocks = [], []
        for block in todo:
            base = mirrors.counterpart[id(block)]
            pairs += [(pattern_var[where[id(v0)][2]], v0) for _, v0 in base]
            nl = next((nonlinear_of[id(v0)] for _, v0 in base if id(v0) in nonlinear_of), None)
            if nl is not None:
                residual_blocks.append((block, nl))
            out.n_linear_loops += id(base) in linear_loops
            done.add(id(block))
        values = [out.expr[v0] for _, v0 in pairs] + [nl.residuals for _, nl in residual_blocks]
        old, new = mirrors.sigma[member]
        copied = ca.substitute([ca.vertcat(*values)], [old], [new])[0]
        for i, (v, _) in enumerate(pairs):
            out.expr[v] = copied[i]
            solved_by_name[v.sym.name()] = v
            pending.pop(v.sym.name(), None)
        offset = len(pairs)
        for block, nl in residual_blocks:
            n = nl.residuals.numel()
            tears = [pattern_var[where[id(t)][2]] for t in nl.tears]
            out.nonlinear.append(NonlinearBlock(tears, copied[offset:offset + n],
                                                [_guess(t) for t in tears],
                                                [e for e, _ in block]))
            offset += n

    def resolved(expr: ca.SX, names: tuple[str, ...] | None = None) -> ca.SX:
        """``expr`` with the unknowns of earlier blocks replaced by their solutions; ``names``:
        the names of its symbols or more (those of the equation it came from), if known.

        Parameters
        ----------
        expr : casadi.SX
            An expression.
        names : tuple of str, optional
            Names of its symbols, if known.

        Returns
        -------
        casadi.SX
            The resolved expression.
        """
        if names is None:
            names = [s.name() for s in ca.symvar(expr)]
        for member in {pending[n] for n in names if n in pending}:
            flush(member)
        prev = [solved_by_name[n] for n in names if n in solved_by_name]
        if not prev:
            return expr
        return ca.substitute(expr, ca.vertcat(*[v.sym for v in prev]),
                             ca.vertcat(*[out.expr[v] for v in prev]))

    for block in blocks:
        out.largest_block = max(out.largest_block, len(block))
        if id(block) in done:
            continue
        copy = mirrors is not None and id(block) in mirrors.counterpart
        member = mirrors.where[id(block[0][1])][:2] if copy else None
        if copy and member not in flushed and ready(block):
            for _, v in block:
                pending[v.sym.name()] = member
                solved_by_name[v.sym.name()] = v
            continue
        if len(block) == 1:
            # One equation in one unknown: solved on the equation as written (small), then
            # earlier solutions substituted into the solution; the unknown is not in them, so
            # linearity and the coefficient are those of the resolved equation.
            e, v = block[0]
            coef = _linear_coefficient(e.residual, v)
            names = e.symbol_names()
            if coef is not None and (coef.is_constant() or not _vanishes(resolved(coef, names))):
                out.expr[v] = resolved(_solve_linear_scalar(e.residual, v, coef), names)
            else:
                out.expr[v] = v.sym
                out.nonlinear.append(NonlinearBlock([v], resolved(e.residual, names), [_guess(v)],
                                                    [e]))
                nonlinear_of[id(v)] = out.nonlinear[-1]  # member 0's, for its copies
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
            linear_loops.add(id(block))
            g0 = ca.substitute(g, z, ca.DM.zeros(len(tears)))
            zsol = ca.solve(jac, -g0)
            tear_expr = {t: zsol[k] for k, t in enumerate(tears)}
        else:
            out.nonlinear.append(
                NonlinearBlock(tears, g, [_guess(t) for t in tears], [e for e, _ in block])
            )
            nonlinear_of.update((id(t), out.nonlinear[-1]) for t in tears)
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
    for member in mirrors.blocks_of if mirrors is not None else ():
        flush(member)
    return out


def _guess(v: Var) -> float:
    return float(v.start) if v.start is not None else 0.0


def run(state: AssemblyState) -> None:
    """Set ``state.causal`` by solving ``state.blocks`` in order; report the loops.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae", "blocks")
    c = state.causal = causalize(state.dae, state.blocks, find_ball_sets(state.dae))
    state.report["blocks"] = (
        f"{c.n_blocks} (largest {c.largest_block}; {c.n_linear_loops} linear loop(s) solved "
        f"symbolically; {len(c.nonlinear)} nonlinear loop(s) by Newton"
        + (f"; {c.copied_members} member(s) of ball sets copied from member 0"
           if c.copied_members else "") + ")"
    )
