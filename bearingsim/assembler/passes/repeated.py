"""Repeated structure: the Z identical balls of a row, found so that code generation can
write one function per ball and map it over the row instead of inlining Z copies.

A *ball set* is every array of components with the same parent and length in the flat names
(``ball[k]``, ``inner[k]``, ``outer[k]``, ``drag[k]``, ``pocket[k]`` of one row): member ``k``
is everything with index ``k``. Any array qualifies: the two bearings of a duplex pair form a
set of two members too (mirrored, so not the same function: they stay inlined). A variable
belongs to member ``k`` when its name, with the index replaced by ``*``, occurs for every
member of its set; everything else (rings, cage, drive, and the port variables that alias
elimination kept under one ball's name) is shared.

The mapping is valid when every BLT block is either shared or belongs to one member. The
shared unknowns are then solved once more with the members' variables kept as symbols
(:attr:`Repeats.shared_expr`): a ring's acceleration becomes a function of the contact forces
of each ball, not of the contact equations inlined Z times. Code generation checks that the
members' equations are the same function (:mod:`bearingsim.assembler.mapped`) and falls back
to the inlined functions otherwise.
"""

from __future__ import annotations

import re
from collections import defaultdict
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import casadi as ca

from bearingsim.assembler.dae import DAE, Param, Var
from bearingsim.assembler.passes.blt import Block
from bearingsim.assembler.passes.tearing import causalize

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "BallSet", "Repeats", "find_repeats", "run"]

NAME = "repeated structure"
"""The pass name in timings, logs and ``extra_passes``."""

_INDEXED = re.compile(r"^(?P<head>(?:der\()?)(?P<path>[^\[]*)\[(?P<k>\d+)\](?P<rest>.*)$")
"""A flat name with an array index: ``ball[3].w`` or ``der(inner[3].delta)``."""

MIN_MEMBERS = 2
"""Ball sets of fewer members are inlined."""


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
class Repeats:
    """The ball sets of a model and its shared unknowns solved around them."""

    sets: list[BallSet] = field(default_factory=list)
    owner: dict[int, tuple[int, int]] = field(default_factory=dict)
    """``id(var or param)`` -> (set, member) for the members' variables and parameters."""
    shared_expr: dict[Var, ca.SX] = field(default_factory=dict)
    """Each shared unknown through the base symbols and the members' variables' own
    symbols."""
    shared_nonlinear: list = field(default_factory=list)
    """Nonlinear blocks among the shared unknowns, as :func:`causalize` returns them."""
    reason: str = ""
    """Why the model has no ball sets to map (empty when it has)."""


def _split(name: str) -> tuple[str, str, int] | None:
    """(array path, pattern with ``*`` for the index, index) of an indexed name."""
    m = _INDEXED.match(name)
    if m is None:
        return None
    pattern = f"{m['head']}{m['path']}[*]{m['rest']}"
    return m["path"], pattern, int(m["k"])


def _group(items: list, name_of: Callable[[object], str]) -> dict[tuple[str, int], dict]:
    """Members of each (parent, length) set: ``{(parent, length): {pattern: {k: item}}}`` for
    the patterns that occur for every index."""
    by_path: dict[str, dict[str, dict[int, object]]] = defaultdict(lambda: defaultdict(dict))
    for item in items:
        split = _split(name_of(item))
        if split is not None:
            path, pattern, k = split
            by_path[path][pattern][k] = item
    sets: dict[tuple[str, int], dict[str, dict[int, object]]] = defaultdict(dict)
    for path, patterns in by_path.items():
        count = 1 + max(k for members in patterns.values() for k in members)
        parent = path.rsplit(".", 1)[0] if "." in path else ""
        for pattern, members in patterns.items():
            if len(members) == count:
                sets[(parent, count)][pattern] = members
    return sets


def find_repeats(dae: DAE, blocks: list[Block]) -> Repeats:
    """The ball sets of ``dae`` and its shared unknowns solved around them (``reason`` says
    why there are none)."""
    var_sets = _group(dae.vars, lambda v: v.name)
    par_sets = _group(dae.params, lambda q: q.name)
    out = Repeats()
    for (parent, count), patterns in sorted(var_sets.items()):
        if count < MIN_MEMBERS:
            continue
        s = len(out.sets)
        order = sorted(patterns)
        p_order = sorted(par_sets.get((parent, count), {}))
        p_members = par_sets.get((parent, count), {})
        out.sets.append(BallSet(
            parent, count, order, [[patterns[p][k] for p in order] for k in range(count)],
            p_order, [[p_members[p][k] for p in p_order] for k in range(count)]))
        for pattern in order:
            for k, v in patterns[pattern].items():
                out.owner[id(v)] = (s, k)
        for pattern in p_order:
            for k, q in p_members[pattern].items():
                out.owner[id(q)] = (s, k)
    if not out.sets:
        return Repeats(reason="no arrays of identical components")
    shared_blocks = []
    for block in blocks:
        owners = {out.owner.get(id(v)) for _, v in block}
        if len(owners) > 1:
            names = ", ".join(sorted(v.name for _, v in block)[:4])
            return Repeats(reason=f"a block couples members with other unknowns ({names}, ...)")
        if owners == {None}:
            shared_blocks.append(block)
    shared = causalize(dae, shared_blocks)
    out.shared_expr = shared.expr
    out.shared_nonlinear = shared.nonlinear
    return out


def run(state: AssemblyState) -> None:
    """Set ``state.repeats`` from ``state.dae`` and ``state.blocks``; report the ball sets."""
    state.require(NAME, "dae", "blocks")
    rep = state.repeats = find_repeats(state.dae, state.blocks)
    state.report["repeated structure"] = (
        ", ".join(f"{s.name or 'root'}: {s.count} x {len(s.patterns)} variables"
                  for s in rep.sets) or rep.reason)
