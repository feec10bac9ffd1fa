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
construction); :class:`~bearingsim.assembler.mapped_parts.NotMappable` (with the reason)
otherwise.

The member and shared functions are built by :mod:`~bearingsim.assembler.mapped_parts`; the
kernels of one model are kept by :mod:`~bearingsim.assembler.mapped_forms`.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca

from bearingsim.assembler.dae import DAE
from bearingsim.assembler.function_options import CSE
from bearingsim.assembler.ir import Causal, Repeats
from bearingsim.assembler.mapped_parts import Builder, Entry, NotMappable, cut_value

__all__ = ["MappedKernel", "mapped_kernel"]


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


def _scatter(order: list[int], member_out: list[ca.MX], shared_out: ca.MX) -> ca.MX:
    """The output vector from the member outputs (one matrix per set) and the shared rows,
    stacked in ``order`` (of :meth:`Builder.parts`)."""
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


def _compose(b: Builder, entries: list[Entry], tag: str, mx_in: list[ca.MX],
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


def _column_order(b: Builder) -> list[tuple[int, int]]:
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
    b = Builder(causal, rep, inputs)
    mx_in = [ca.MX.sym(name, len(syms)) for name, syms, _ in inputs]
    # The observe function's members return every member variable, so comparing them covers
    # the ODE rows and exports of the kernel too; the DAE form's residual rows are checked
    # with the kernel.
    observe = _observe(b, dae, causal, rep, inputs, mx_in, form)
    entries: list[Entry] = []
    for v in states:
        o = owner.get(id(v))
        entries.append(Entry(o, ("ode", b.pattern.get(id(v), "")),
                              causal.value(v.derivative),
                              None if o else cut_value(v.derivative, rep)))
    n_ode = len(entries)
    if form == "dae":
        shared_blocks = {id(blk.tears[0]): blk for blk in rep.shared_nonlinear}
        for blk in causal.nonlinear:
            o = owner.get(id(blk.tears[0]))
            cut = None if o else shared_blocks[id(blk.tears[0])].residuals
            for i in range(blk.residuals.numel()):
                entries.append(Entry(o, ("alg", b.pattern.get(id(blk.tears[0]), ""), i),
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


def _observe(b: Builder, dae: DAE, causal: Causal, rep: Repeats, inputs, mx_in, form: str):
    """Every observed variable (the order of ``System.observed_names``) with mapped balls."""
    owner = rep.owner
    entries = [Entry(owner.get(id(v)), ("var", b.pattern.get(id(v), "")), causal.value(v),
                      None if owner.get(id(v)) else cut_value(v, rep)) for v in dae.vars]
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
