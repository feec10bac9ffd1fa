"""Mapped-ball functions: the right-hand side (or DAE residual), its exact Jacobian and the
observe function of a model with ball sets, written with one CasADi function per ball that
``Function.map`` evaluates for every ball of the row.

Per ball set ``s`` with members ``k = 0..Z-1`` the inputs split into the member's own
differentiable entries ``l_k`` (its states and tearing variables), its parameters ``q_k``, and
the shared entries ``S = (S_d, S_n)`` (time, ring and cage states, inputs; shared parameters).
Then

* ``(o_k, e_k) = f_s(l_k, q_k, S_d, S_n)``: the member's rows of the outputs and the member
  variables that the shared equations read (contact forces, pocket forces), mapped over k;
* ``o_shared = h(S_d, S_n, L_s, Q_s, E_s)``: the shared rows, with ``L_s, Q_s, E_s`` all
  members' entries (the ring's force is a sum over the ``e_k``).

The Jacobian follows by the chain rule from the per-ball Jacobians of ``f_s`` (mapped) and
the Jacobian of ``h``:

* ``d o_k / d l_k = F_l``, ``d o_k / d S_d = F_S`` (rows of ``o_k``);
* ``d o_shared / d l_k = H_L,k + H_E,k E_l,k``;
* ``d o_shared / d S_d = H_S + sum_k H_E,k E_S,k``;

so code size and Jacobian work grow with one ball, not with Z. The members must be the same
function: each member's function is serialized with fresh symbols and compared with the first
one's (except the members whose every solution tearing copied from member 0's: they are by
construction); :class:`NotMappable` (with the reason) otherwise.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import casadi as ca
import numpy as np

from bearingsim.assembler.dae import DAE, Var
from bearingsim.assembler.function_options import CSE, rootfinder_options
from bearingsim.assembler.ir import Causal, Repeats
from bearingsim.assembler.passes.ball_sets import function_identity

__all__ = ["NotMappable", "MappedKernel", "MappedForms", "mapped_kernel"]


class NotMappable(Exception):
    """The model's ball sets cannot be mapped (the message says why)."""


@dataclass(frozen=True)
class MappedKernel:
    """A kernel function, its Jacobian (``jac_<name>``, the signature of
    ``function.jacobian()``) and the observe function, all with mapped balls."""

    function: ca.Function
    jacobian: ca.Function
    observe: ca.Function
    ball_function: ca.Function
    """The per-ball function of the first ball set (its size is what grows with one ball)."""

    def ode_with_jacobians(self, t: ca.MX, x: ca.MX, u: ca.MX, p: ca.MX
                           ) -> tuple[ca.MX, ca.MX, ca.MX, ca.MX]:
        """The ``ode`` form's right-hand side and its Jacobians by ``t``, ``x`` and ``u`` at
        symbolic arguments: ``(xdot, d xdot/dt, d xdot/dx, d xdot/du)``.

        Parameters
        ----------
        t : casadi.MX
            Time [s].
        x : casadi.MX
            States.
        u : casadi.MX
            Inputs.
        p : casadi.MX
            Parameters.

        Returns
        -------
        tuple of casadi.MX
            ``(xdot, d xdot/dt, d xdot/dx, d xdot/du)``.
        """
        xdot = self.function(t, x, u, p)
        jac_t, jac_x, jac_u, _ = self.jacobian(t, x, u, p, ca.MX(ca.Sparsity(xdot.size1(), 1)))
        return xdot, jac_t, jac_x, jac_u


@dataclass
class _Entry:
    """One scalar of an output: its owner ((set, member) or None), the key that orders it
    within its member, the full expression and the shared expression (members' variables as
    symbols)."""

    owner: tuple[int, int] | None
    key: tuple
    full: ca.SX
    cut: ca.SX | None


def _cut_value(v: Var, rep: Repeats) -> ca.SX:
    return v.sym if v.is_state or v.is_input else rep.shared_expr[v]


def _vcat(items: list) -> ca.SX:
    return ca.vertcat(*items) if items else ca.SX(0, 1)


class _Layout:
    """Where each scalar of the kernel's inputs lives: member entries and shared entries."""

    def __init__(self, inputs: list[tuple[str, list[ca.SX], bool]],
                 owner_key: Callable[[str], tuple[tuple[int, int], tuple] | None],
                 sizes: list[int]):
        n_sets = len(sizes)
        self.ld = [[[] for _ in range(z)] for z in sizes]  # (input, pos, sym, key)
        self.ln = [[[] for _ in range(z)] for z in sizes]
        self.sd: list[tuple[int, int, ca.SX]] = []
        self.sn: list[tuple[int, int, ca.SX]] = []
        for a, (_, syms, diff) in enumerate(inputs):
            for i, sym in enumerate(syms):
                found = owner_key(sym.name())
                if found is None:
                    (self.sd if diff else self.sn).append((a, i, sym))
                else:
                    (s, k), key = found
                    (self.ld if diff else self.ln)[s][k].append((a, i, sym, key))
        for table in (self.ld, self.ln):
            for s in range(n_sets):
                for members in table[s]:
                    members.sort(key=lambda e: e[3])
                keys = [[e[3] for e in m] for m in table[s]]
                if any(k != keys[0] for k in keys):
                    raise NotMappable("the members' states or parameters differ")


def _member_function(name: str, lay: _Layout, s: int, k: int, outs: list[ca.SX]) -> ca.Function:
    args = [_vcat([e[2] for e in lay.ld[s][k]]), _vcat([e[2] for e in lay.ln[s][k]]),
            _vcat([e[2] for e in lay.sd]), _vcat([e[2] for e in lay.sn])]
    try:
        return ca.Function(name, args, outs, ["l", "q", "S_d", "S_n"],
                           [f"o{i}" for i in range(len(outs))])
    except RuntimeError as exc:
        raise NotMappable(f"a member's equations read another member's variables "
                          f"({str(exc).splitlines()[-1][:200]})") from None


def _same_members(fns: list[ca.Function], copied: set[int]) -> None:
    """Raise unless every member's function is member 0's; members in ``copied`` (whose every
    solution tearing copied from member 0's, with their own symbols) are so by construction."""
    first = None
    for k, f in enumerate(fns[1:], start=1):
        if k in copied:
            continue
        first = first or function_identity(fns[0])
        if function_identity(f) != first:
            raise NotMappable(f"member {k} of a repeated set is not the same function as member "
                              f"0")


class _Builder:
    """The mapped form of one kernel: entries of its outputs, the members' functions, the
    shared function and their MX composition."""

    def __init__(self, causal: Causal, rep: Repeats,
                 inputs: list[tuple[str, list[ca.SX], bool]]):
        self.sets = rep.sets
        self.causal = causal
        self.by_name: dict[str, tuple[tuple[int, int], tuple[str, str]]] = {}
        """Symbol name of a member's variable or parameter -> ((set, member), ("v" or "p",
        pattern))."""
        self.pattern: dict[int, str] = {}
        """``id(var)`` -> its pattern, for the members' variables."""
        for s, bs in enumerate(rep.sets):
            for k in range(bs.count):
                for j, v in enumerate(bs.variables[k]):
                    self.by_name[v.sym.name()] = ((s, k), ("v", bs.patterns[j]))
                    self.pattern[id(v)] = bs.patterns[j]
                for j, q in enumerate(bs.parameters[k]):
                    self.by_name[q.sym.name()] = ((s, k), ("p", bs.param_patterns[j]))
        self.input_syms = {sym.name() for _, syms, _ in inputs for sym in syms}
        self.lay = _Layout(inputs, self.by_name.get, [bs.count for bs in rep.sets])

    # ------------------------------------------------------------ pieces
    def _exports(self, entries: list[_Entry]) -> list[list[str]]:
        """Per set, the patterns of member variables (not inputs) the shared rows read."""
        used: list[set[str]] = [set() for _ in self.sets]
        cuts = [e.cut for e in entries if e.owner is None]
        for sym in ca.symvar(_vcat(cuts)) if cuts else []:
            name = sym.name()
            if name in self.by_name and name not in self.input_syms:
                (s, _), (_, pattern) = self.by_name[name]  # parameters are inputs
                used[s].add(pattern)
        return [sorted(u) for u in used]

    def _export_vars(self, s: int, k: int, patterns: list[str]) -> list[Var]:
        bs = self.sets[s]
        index = {p: j for j, p in enumerate(bs.patterns)}
        return [bs.variables[k][index[p]] for p in patterns]

    def parts(self, entries: list[_Entry], tag: str, check: bool = True):
        """Member functions (one per set; with ``check``, compared over the members), the
        shared function, and the row order: per set each member's rows, then the shared
        rows."""
        lay = self.lay
        exports = self._exports(entries)
        rows = [[[] for _ in range(bs.count)] for bs in self.sets]
        shared_rows = []
        for r, e in enumerate(entries):
            if e.owner is None:
                shared_rows.append(r)
            else:
                rows[e.owner[0]][e.owner[1]].append(r)
        members = []
        for s, bs in enumerate(self.sets):
            for k in range(bs.count):
                rows[s][k].sort(key=lambda r: entries[r].key)
            keys = [[entries[r].key for r in m] for m in rows[s]]
            if any(kk != keys[0] for kk in keys):
                raise NotMappable("the members' rows differ")
            fns = []
            for k in range(bs.count):
                outs = [_vcat([entries[r].full for r in rows[s][k]]),
                        _vcat([self.causal.value(v)
                               for v in self._export_vars(s, k, exports[s])])]
                fns.append(_member_function(f"{tag}_ball{s}", lay, s, k, outs))
            if check:
                _same_members(fns, {k for name, count, k in self.causal.copied
                                    if (name, count) == (bs.name, bs.count)})
            f0 = fns[0]
            members.append(ca.Function(f0.name(), f0.sx_in(), f0.call(f0.sx_in()),
                                       f0.name_in(), f0.name_out(), CSE))
        h_in = [_vcat([e[2] for e in lay.sd]), _vcat([e[2] for e in lay.sn])]
        h_names = ["S_d", "S_n"]
        for s, bs in enumerate(self.sets):
            h_in += [_vcat([e[2] for k in range(bs.count) for e in lay.ld[s][k]]),
                     _vcat([e[2] for k in range(bs.count) for e in lay.ln[s][k]]),
                     _vcat([v.sym for k in range(bs.count)
                            for v in self._export_vars(s, k, exports[s])])]
            h_names += [f"L{s}", f"Q{s}", f"E{s}"]
        try:
            shared = ca.Function(f"{tag}_shared", h_in,
                                 [_vcat([entries[r].cut for r in shared_rows])], h_names,
                                 ["o"], CSE)
        except RuntimeError as exc:
            raise NotMappable(f"the shared equations read member variables that are not "
                              f"exported ({str(exc).splitlines()[-1][:200]})") from None
        order = [r for per_set in rows for member in per_set for r in member] + shared_rows
        return members, shared, order

    # ------------------------------------------------------------ MX composition
    def gather(self, mx_in: list[ca.MX]):
        """MX of the member matrices (per set: L, Q) and the shared vectors from the kernel's
        MX inputs: each one gather of non-zeros, from the one input its entries come from, or
        else from the inputs it uses stacked (the generated C copies no more than that)."""
        lay = self.lay

        def pick(items, shape=None):
            if not items:
                return ca.MX(*(shape or (0, 1)))
            used = sorted({a for a, *_ in items})
            start = {a: sum(mx_in[b].numel() for b in used[:j]) for j, a in enumerate(used)}
            source = mx_in[used[0]] if len(used) == 1 else ca.vertcat(*[mx_in[a] for a in used])
            index = ca.DM([start[a] + i for a, i, *_ in items])
            return source[ca.reshape(index, *shape) if shape else index]

        sd, sn = pick(lay.sd), pick(lay.sn)
        L, Q = [], []
        for s, bs in enumerate(self.sets):
            L.append(pick([e for k in range(bs.count) for e in lay.ld[s][k]],
                          (len(lay.ld[s][0]), bs.count)))
            Q.append(pick([e for k in range(bs.count) for e in lay.ln[s][k]],
                          (len(lay.ln[s][0]), bs.count)))
        return sd, sn, L, Q


def _scatter(order: list[int], member_out: list[ca.MX], shared_out: ca.MX) -> ca.MX:
    """The output vector from the member outputs (one matrix per set) and the shared rows,
    stacked in ``order`` (of :meth:`_Builder.parts`)."""
    stacked = ca.vertcat(*[ca.vec(m) for m in member_out], shared_out)
    return stacked[_positions(order)]


def _positions(order: list[int]) -> list[int]:
    """The inverse permutation: where each row stands in ``order``."""
    position = [0] * len(order)
    for p, r in enumerate(order):
        position[r] = p
    return position


def _shared_args(sd: ca.MX, sn: ca.MX, L: list[ca.MX], Q: list[ca.MX],
                 E: list[ca.MX]) -> list[ca.MX]:
    """The arguments of the shared function: ``S_d, S_n`` and per set ``L, Q, E``."""
    return [sd, sn, *[ca.vec(m) for s in range(len(L)) for m in (L[s], Q[s], E[s])]]


def _union(sp: ca.Sparsity, z: int) -> ca.Sparsity:
    """The union of the sparsity patterns of the ``z`` column blocks of ``sp``."""
    ones = ca.DM.ones(sp)
    n = sp.size2() // z
    return sum((ones[:, k * n:(k + 1) * n] for k in range(z)), ca.DM(sp.size1(), n)).sparsity()


def _compose(b: _Builder, entries: list[_Entry], tag: str, mx_in: list[ca.MX],
             with_jacobian: bool, check: bool = True):
    members, shared, order = b.parts(entries, tag, check)
    sd, sn, L, Q = b.gather(mx_in)
    outs_member, E = [], []
    for s, f in enumerate(members):
        o, e = f.map(b.sets[s].count)(L[s], Q[s], sd, sn)
        outs_member.append(o)
        E.append(e)
    value = _scatter(order, outs_member, shared(*_shared_args(sd, sn, L, Q, E)))
    if not with_jacobian:
        return value, members[0], None, order
    # Jacobian by the chain rule (module docstring): the members' Jacobians (with their
    # exports, so that the members are evaluated once), the shared function's Jacobian, the
    # products H_E,k E_l,k and the sum over k of H_E,k E_S,k as mapped functions; rows in the
    # order of _scatter, columns (each set's members' l entries, then S_d), permuted later.
    # The member's Jacobian is two functions, its l columns (with e) and its S_d columns:
    # the larger SX functions of a kernel, each gets a translation unit of its own
    # (simulation.c_units), compiled side by side (6304 ball: 11 000 + 5 000 instructions).
    jac_members, jac_fns = [], []
    for s, f in enumerate(members):
        sym = f.sx_in()
        o, e = f.call(sym)
        jf_l = ca.Function(f"{tag}_ball{s}_jac_l", sym,
                           [ca.jacobian(o, sym[0]), ca.jacobian(e, sym[0]), e], CSE)
        jf_s = ca.Function(f"{tag}_ball{s}_jac_s", sym,
                           [ca.jacobian(o, sym[2]), ca.jacobian(e, sym[2])], CSE)
        jac_fns.append((jf_l, jf_s))
        z = b.sets[s].count
        Fl, El, e_mapped = jf_l.map(z)(L[s], Q[s], sd, sn)
        FS, ES = jf_s.map(z)(L[s], Q[s], sd, sn)
        jac_members.append((Fl, FS, El, ES, e_mapped))
    h_args = _shared_args(sd, sn, L, Q, [jm[4] for jm in jac_members])
    sym_h = shared.sx_in()
    out_h = shared.call(sym_h)[0]
    jh_outs = [ca.jacobian(out_h, sym_h[0])]
    for s in range(len(b.sets)):
        jh_outs += [ca.jacobian(out_h, sym_h[2 + 3 * s]), ca.jacobian(out_h, sym_h[4 + 3 * s])]
    jh = ca.Function(f"{tag}_shared_jac", sym_h, jh_outs, CSE)
    H = jh(*h_args)
    pieces, sizes = [], []
    shared_S = H[0]
    for s, (Fl, FS, El, ES, _) in enumerate(jac_members):
        z = b.sets[s].count
        n_e = members[s].nnz_out(1)
        H_L, H_E = H[1 + 2 * s], H[2 + 2 * s]
        if n_e:
            jf_l, jf_s = jac_fns[s]
            he, el, es = (ca.SX.sym("he", _union(jh.sparsity_out(2 + 2 * s), z)),
                          ca.SX.sym("el", jf_l.sparsity_out(1)),
                          ca.SX.sym("es", jf_s.sparsity_out(1)))
            chain = ca.Function(f"{tag}_ball{s}_chain", [he, el, es],
                                [ca.mtimes(he, el), ca.mtimes(he, es)])
            hel, hes = chain.map(f"{tag}_ball{s}_chain_map", "serial", z, [], [1])(H_E, El, ES)
            H_L = H_L + hel
            shared_S = shared_S + hes
        pieces += [Fl, FS, H_L]
        sizes.append((z, members[s].nnz_in(0), members[s].nnz_in(2)))
    pieces.append(shared_S)
    return value, members[0], _BlockJacobian(pieces, sizes), order


class _BlockJacobian:
    """The Jacobian in block order (rows: each member's rows, then the shared rows; columns:
    each member's ``l`` entries, then ``S_d``) from its pieces: per set the mapped ``F_l`` and
    ``F_S`` (members side by side) and the shared rows' member columns, then the shared rows'
    ``S_d`` columns. The pieces are never concatenated as matrices (sparse concatenation
    transposes): :meth:`select` gathers a block's nonzeros straight from them, at positions
    found by assembling the same layout from index matrices."""

    def __init__(self, pieces: list[ca.MX], sizes: list[tuple[int, int, int]]):
        self.nonzeros = ca.vertcat(*[p.nz[:] for p in pieces])
        offset, index = 0, []
        for p in pieces:
            nnz = p.sparsity().nnz()
            index.append(ca.DM(p.sparsity(), ca.DM(range(offset + 1, offset + nnz + 1))))
            offset += nnz
        top_l, top_s, bottom = [], [], []
        for s, (z, n_l, n_s) in enumerate(sizes):
            Fl, FS, HL = index[3 * s:3 * s + 3]
            top_l += [Fl[:, k * n_l:(k + 1) * n_l] for k in range(z)]
            top_s += [FS[:, k * n_s:(k + 1) * n_s] for k in range(z)]
            bottom.append(HL)
        bottom.append(index[-1])
        self.index = ca.vertcat(ca.horzcat(ca.diagcat(*top_l), ca.vertcat(*top_s)),
                                ca.horzcat(*bottom))

    def select(self, rows: list[int], cols: list[int]) -> ca.MX:
        """The sub-matrix of the given block rows and columns, as one gather of nonzeros."""
        block = self.index[rows, cols]
        where = [int(v) - 1 for v in block.nonzeros()]
        return ca.MX(block.sparsity(), self.nonzeros[where])


def _column_order(b: _Builder) -> list[tuple[int, int]]:
    """(input, position) of each column of the block Jacobian."""
    cols = [(a, i) for s, bs in enumerate(b.sets) for k in range(bs.count)
            for a, i, *_ in b.lay.ld[s][k]]
    cols += [(a, i) for a, i, _ in b.lay.sd]
    return cols


def mapped_kernel(dae: DAE, causal: Causal, rep: Repeats, form: str) -> MappedKernel:
    """The kernel of ``form`` (``"ode"``: ``ode(t, x, u, p)``; ``"dae"``:
    ``dae(t, x, z, u, p) -> (ode, alg)``) with mapped balls, its Jacobian and observe function.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    causal : Causal
        The causalized system.
    rep : Repeats
        The ball sets and shared unknowns.
    form : {"ode", "dae"}
        Kernel form.

    Returns
    -------
    MappedKernel
        The kernel.

    Raises
    ------
    NotMappable
        When the ball sets cannot be mapped (the message says why).
    """
    if not rep.sets:
        raise NotMappable(rep.reason)
    owner = rep.owner
    t = dae.time
    states = dae.states
    x = [v.sym for v in states]
    u = [v.sym for v in dae.inputs]
    p = [q.sym for q in dae.params]
    tears = [v for blk in causal.nonlinear for v in blk.tears]
    if form == "ode":
        if causal.nonlinear:
            raise NotMappable("the ODE form of a model with nonlinear blocks solves them by "
                              "Newton: built from the DAE form (through_newton)")
        inputs = [("t", [t], True), ("x", x, True), ("u", u, True), ("p", p, False)]
        out_names = ["ode"]
    else:
        if not causal.nonlinear:
            raise NotMappable("the model has no nonlinear blocks, so no DAE form")
        inputs = [("t", [t], True), ("x", x, True), ("z", [v.sym for v in tears], True),
                  ("u", u, True), ("p", p, False)]
        out_names = ["ode", "alg"]
    b = _Builder(causal, rep, inputs)
    mx_in = [ca.MX.sym(name, len(syms)) for name, syms, _ in inputs]
    # The observe function's members return every member variable, so comparing them covers
    # the ODE rows and exports of the kernel too; the DAE form's residual rows are checked
    # with the kernel.
    observe = _observe(b, dae, causal, rep, inputs, mx_in, form)
    entries: list[_Entry] = []
    for v in states:
        o = owner.get(id(v))
        entries.append(_Entry(o, ("ode", b.pattern.get(id(v), "")),
                              causal.value(v.derivative),
                              None if o else _cut_value(v.derivative, rep)))
    n_ode = len(entries)
    if form == "dae":
        shared_blocks = {id(blk.tears[0]): blk for blk in rep.shared_nonlinear}
        for blk in causal.nonlinear:
            o = owner.get(id(blk.tears[0]))
            cut = None if o else shared_blocks[id(blk.tears[0])].residuals
            for i in range(blk.residuals.numel()):
                entries.append(_Entry(o, ("alg", b.pattern.get(id(blk.tears[0]), ""), i),
                                      blk.residuals[i], None if o else cut[i]))
    value, ball_fn, J_block, order = _compose(b, entries, form, mx_in, True,
                                              check=form == "dae")
    row_pos = _positions(order)
    col_order = _column_order(b)
    col_pos = {c: q for q, c in enumerate(col_order)}
    names_in = [name for name, _, _ in inputs]
    outs = [value[:n_ode]] if form == "ode" else [value[:n_ode], value[n_ode:]]
    fn = ca.Function(form, mx_in, outs, names_in, out_names,
                     {"is_diff_in": [d for _, _, d in inputs]})
    # Jacobian with the signature of fn.jacobian(): inputs (*inputs, out_*), outputs
    # jac_<out>_<in> for every pair (non-differentiable inputs: structurally zero).
    out_syms = [ca.MX.sym(f"out_{n}", ca.Sparsity(o.numel(), 1))
                for n, o in zip(out_names, outs, strict=True)]
    jac_outs, jac_names = [], []
    spans = [(0, n_ode)] + ([(n_ode, len(entries))] if form == "dae" else [])
    for name_o, (r0, r1) in zip(out_names, spans, strict=True):
        rsel = [row_pos[r] for r in range(r0, r1)]
        for a, (name_a, syms, diff) in enumerate(inputs):
            jac_names.append(f"jac_{name_o}_{name_a}")
            if not diff or not syms:
                jac_outs.append(ca.MX(ca.Sparsity(r1 - r0, len(syms))))
                continue
            csel = [col_pos[(a, i)] for i in range(len(syms))]
            jac_outs.append(J_block.select(rsel, csel))
    jac = ca.Function(f"jac_{form}", mx_in + out_syms, jac_outs,
                      names_in + [f"out_{n}" for n in out_names], jac_names)
    return MappedKernel(fn, jac, observe, ball_fn)


def _observe(b: _Builder, dae: DAE, causal: Causal, rep: Repeats, inputs, mx_in, form: str):
    """Every observed variable (the order of ``System.observed_names``) with mapped balls."""
    owner = rep.owner
    entries = [_Entry(owner.get(id(v)), ("var", b.pattern.get(id(v), "")), causal.value(v),
                      None if owner.get(id(v)) else _cut_value(v, rep)) for v in dae.vars]
    value = _compose(b, entries, f"{form}_observe", mx_in, False)[0]
    parts = [value]
    if dae.aliases:
        index = {id(v): k for k, v in enumerate(dae.vars)}
        # a constant alias has no representative and scale 0: any index will do
        reps = [index[id(a.representative)] if a.representative is not None else 0
                for a in dae.aliases.values()]
        scales = [a.scale for a in dae.aliases.values()]
        offsets = [a.offset for a in dae.aliases.values()]
        parts.append(ca.DM(offsets) + ca.DM(scales) * value[reps])
    name = "observe" if form == "ode" else "dae_observe"
    return ca.Function(name, mx_in, [ca.vertcat(*parts)], [n for n, _, _ in inputs],
                       ["observe"])


def through_newton(dae_kernel: MappedKernel, guess: list[float], rootfinder: str,
                   newton_tol: float) -> MappedKernel:
    """The ODE form ``ode(t, x, u, p)`` of a model with nonlinear blocks from its mapped DAE
    form ``dae(t, x, z, u, p) -> (ode, alg)``: ``z`` from one CasADi rootfinder on ``alg = 0``
    (every ball's Newton block at once; its Jacobian ``d alg / d z`` is the DAE form's
    chain-rule Jacobian, block diagonal over the balls), the right-hand side and the observed
    variables at that ``z``, and the exact Jacobian by the implicit function theorem,
    ``d ode / d a = F_a - F_z G_z^-1 G_a`` for ``a`` in ``t, x, u``, from the same blocks.
    Code size grows with one ball, as the DAE form's does.

    Parameters
    ----------
    dae_kernel : MappedKernel
        The mapped DAE form.
    guess : list of float
        Start of the Newton iteration (the tearing variables' start values, in ``z`` order).
    rootfinder : str
        CasADi rootfinder plugin (``fast_newton`` generates C).
    newton_tol : float
        Absolute tolerance of the residual.

    Returns
    -------
    MappedKernel
        The ODE form.
    """
    F, JF, obs = dae_kernel.function, dae_kernel.jacobian, dae_kernel.observe
    sizes = [F.size1_in(i) for i in range(F.n_in())]  # t, x, z, u, p
    t, x, u, p = (ca.MX.sym(n, sizes[i]) for n, i in (("t", 0), ("x", 1), ("u", 3), ("p", 4)))
    n_ode, n_z = F.size1_out(0), sizes[2]
    # alg(z, w) with w = (t, x, u, p), differentiated by calling the chain-rule Jacobian
    # (parameters are not differentiable, as in every kernel)
    z_s, w = ca.MX.sym("z", n_z), ca.MX.sym("w", sizes[0] + sizes[1] + sizes[3] + sizes[4])
    tw, xw, uw, pw = ca.vertsplit(w, list(np.cumsum([0, *sizes[:2], *sizes[3:]])))
    blocks_w = JF(tw, xw, z_s, uw, pw, ca.MX(ca.Sparsity(n_ode, 1)), ca.MX(ca.Sparsity(n_z, 1)))
    jac_g = ca.Function("jac_alg_balls", [z_s, w, ca.MX.sym("out", ca.Sparsity(n_z, 1))],
                        [blocks_w[7], ca.horzcat(blocks_w[5], blocks_w[6], blocks_w[8],
                                                 blocks_w[9])])
    g = ca.Function("alg_balls", [z_s, w], [F(tw, xw, z_s, uw, pw)[1]],
                    {"custom_jacobian": jac_g, "never_inline": True})
    solve = ca.rootfinder("newton_balls", rootfinder, g,
                          rootfinder_options(rootfinder, newton_tol))
    z = solve(ca.DM(guess), ca.vertcat(t, x, u, p))
    args, names = [t, x, u, p], ["t", "x", "u", "p"]
    fn = ca.Function("ode", args, [F(t, x, z, u, p)[0]], names, ["ode"],
                     {"is_diff_in": [True, True, True, False]})
    blocks = JF(t, x, z, u, p, ca.MX(ca.Sparsity(n_ode, 1)), ca.MX(ca.Sparsity(n_z, 1)))
    f_z, g_z = blocks[2], blocks[7]
    jac_outs = []
    for a, (f_a, g_a) in enumerate(zip(blocks[:5], blocks[5:], strict=True)):
        if a == 2:  # z: not an input of the ODE form
            continue
        if a == 4:  # p: not differentiable
            jac_outs.append(ca.MX(ca.Sparsity(n_ode, sizes[4])))
            continue
        jac_outs.append(f_a - ca.mtimes(f_z, ca.solve(g_z, g_a, "qr")))
    out = ca.MX.sym("out_ode", ca.Sparsity(n_ode, 1))
    jac = ca.Function("jac_ode", [*args, out], jac_outs, [*names, "out_ode"],
                      [f"jac_ode_{n}" for n in names])
    observe = ca.Function("observe", args, [obs(t, x, z, u, p)], names, ["observe"])
    return MappedKernel(fn, jac, observe, dae_kernel.ball_function)


class MappedForms:
    """The mapped kernels of one assembled model, built on first request per form.

    Parameters
    ----------
    dae, causal, repeats
        What the assembler's passes produced (kept for the lazy build); ``None`` for forms
        restored by :meth:`from_data`.
    rootfinder, newton_tol
        Rootfinder plugin and tolerance of the nonlinear blocks: the ODE form of a model with
        nonlinear blocks solves them (:func:`through_newton`).
    """

    FORMS = ("ode", "dae")

    def __init__(self, dae: DAE | None, causal: Causal | None, repeats: Repeats | None,
                 rootfinder: str = "fast_newton", newton_tol: float = 1e-12):
        self._dae, self._causal, self._repeats = dae, causal, repeats
        self._rootfinder, self._newton_tol = rootfinder, newton_tol
        self._built: dict[str, MappedKernel | NotMappable] = {}
        self.summary = ", ".join(f"{s.name or 'root'}: {s.count} members"
                                 for s in repeats.sets) if repeats is not None else ""
        """The sets, e.g. ``"inner_layer: 13 members, outer_layer: 14 members"`` (a member of a
        row of balls is one ball with its contacts, pocket and drag)."""

    def get(self, form: str) -> MappedKernel:
        """The mapped kernel of ``form`` (``"ode"`` or ``"dae"``).

        Parameters
        ----------
        form : {"ode", "dae"}
            Kernel form.

        Returns
        -------
        MappedKernel
            The kernel (built on first use).

        Raises
        ------
        NotMappable
            When this form cannot be mapped (the message says why).
        """
        found = self._built.get(form)
        if found is None:
            try:
                if self._repeats is None:
                    raise NotMappable(f"the {form} form was not built before packing")
                if form == "ode" and self._causal.nonlinear:
                    guess = [g for blk in self._causal.nonlinear for g in blk.guess]
                    found = through_newton(self.get("dae"), guess, self._rootfinder,
                                           self._newton_tol)
                else:
                    found = mapped_kernel(self._dae, self._causal, self._repeats, form)
            except NotMappable as exc:
                found = exc
            self._built[form] = found
        if isinstance(found, NotMappable):
            raise found
        return found

    def find(self, form: str) -> MappedKernel | None:
        """The mapped kernel of ``form``, or None when it cannot be mapped.

        Parameters
        ----------
        form : {"ode", "dae"}
            Kernel form.

        Returns
        -------
        MappedKernel or None
            The kernel, or None.
        """
        try:
            return self.get(form)
        except NotMappable:
            return None

    def to_data(self) -> dict:
        """Plain data (every form built, functions serialized) for another process.

        Returns
        -------
        dict
            Picklable plain data.
        """
        forms = {}
        for form in self.FORMS:
            try:
                k = self.get(form)
            except NotMappable as exc:
                forms[form] = str(exc)
            else:
                forms[form] = [f.serialize() for f in (k.function, k.jacobian, k.observe,
                                                       k.ball_function)]
        return {"summary": self.summary, "forms": forms}

    @classmethod
    def from_data(cls, data: dict) -> MappedForms:
        """The forms of :meth:`to_data`.

        Parameters
        ----------
        data : dict
            From :meth:`to_data`.

        Returns
        -------
        MappedForms
            The forms.
        """
        out = cls(None, None, None)
        out.summary = data["summary"]
        for form, value in data["forms"].items():
            out._built[form] = (NotMappable(value) if isinstance(value, str) else MappedKernel(
                *[ca.Function.deserialize(v) for v in value]))
        return out
