"""The parts of a mapped-ball kernel (:mod:`~bearingsim.assembler.mapped`): which scalars of
the kernel's outputs and inputs belong to which member of a ball set and which are shared
(:class:`Entry`, the input layout), the member functions ``f_s`` (each member's serialized with
fresh symbols and compared with the first one's) and the shared function ``h``, and the MX
gathers of their arguments from the kernel's inputs (:class:`Builder`). A model whose members
are not the same function, or whose shared equations read member variables that are not
exported, raises :class:`NotMappable` with the reason.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import casadi as ca

from bearingsim.assembler.dae import Var
from bearingsim.assembler.function_options import CSE
from bearingsim.assembler.ir import Causal, Repeats
from bearingsim.assembler.passes.ball_sets import function_identity

__all__ = ["Builder", "Entry", "NotMappable", "cut_value"]


class NotMappable(Exception):
    """The model's ball sets cannot be mapped (the message says why)."""


@dataclass
class Entry:
    """One scalar of an output: its owner ((set, member) or None), the key that orders it
    within its member, the full expression and the shared expression (members' variables as
    symbols)."""

    owner: tuple[int, int] | None
    key: tuple
    full: ca.SX
    cut: ca.SX | None


def cut_value(v: Var, rep: Repeats) -> ca.SX:
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


class Builder:
    """The mapped form of one kernel: entries of its outputs, the members' functions, the
    shared function and their MX composition.

    Parameters
    ----------
    causal : Causal
        The causalized system.
    rep : Repeats
        The ball sets and shared unknowns.
    inputs : list of (str, list of casadi.SX, bool)
        The kernel's inputs: name, scalar symbols and whether it is differentiable.
    """

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
    def _exports(self, entries: list[Entry]) -> list[list[str]]:
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

    def parts(self, entries: list[Entry], tag: str, check: bool = True):
        """Member functions (one per set; with ``check``, compared over the members), the
        shared function, and the row order: per set each member's rows, then the shared
        rows.

        Parameters
        ----------
        entries : list of Entry
            The scalars of the kernel's outputs.
        tag : str
            Start of the functions' names.
        check : bool, default True
            Compare every member's function with the first one's.

        Returns
        -------
        members : list of casadi.Function
            One member function ``f_s(l, q, S_d, S_n) -> (o, e)`` per set.
        shared : casadi.Function
            The shared function ``h(S_d, S_n, L0, Q0, E0, ...) -> o``.
        order : list of int
            The entries' rows in the order of the stacked outputs.

        Raises
        ------
        NotMappable
            When the members differ or the shared rows read unexported member variables.
        """
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
        else from the inputs it uses stacked (the generated C copies no more than that).

        Parameters
        ----------
        mx_in : list of casadi.MX
            The kernel's MX inputs (in the order of ``inputs``).

        Returns
        -------
        sd, sn : casadi.MX
            The shared differentiable and non-differentiable entries.
        L, Q : list of casadi.MX
            Per set, the members' differentiable and non-differentiable entries (one column
            per member).
        """
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
