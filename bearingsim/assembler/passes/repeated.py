"""Repeated structure: the Z identical balls of a row, found so that code generation can
write one function per ball and map it over the row instead of inlining Z copies.

The ball sets are those of :func:`~bearingsim.assembler.passes.ball_sets.find_ball_sets` (every
array of components with one parent and one length; member ``k`` is everything with index
``k``; the two bearings of a duplex pair form a set too, mirrored, so not the same function:
they stay inlined).

The mapping is valid when every BLT block is either shared or belongs to one member. The
shared unknowns are then solved once more with the members' variables kept as symbols
(:attr:`Repeats.shared_expr`): a ring's acceleration becomes a function of the contact forces
of each ball, not of the contact equations inlined Z times. Code generation checks that the
members' equations are the same function (:mod:`bearingsim.assembler.mapped`) and falls back
to the inlined functions otherwise.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from bearingsim.assembler.dae import DAE
from bearingsim.assembler.ir import Block, Repeats
from bearingsim.assembler.passes.ball_sets import find_ball_sets, owners
from bearingsim.assembler.passes.tearing import causalize

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "find_repeats", "run"]

NAME = "repeated structure"
"""The pass name in timings, logs and ``extra_passes``."""


def find_repeats(dae: DAE, blocks: list[Block]) -> Repeats:
    """The ball sets of ``dae`` and its shared unknowns solved around them (``reason`` says
    why there are none).

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    blocks : list of Block
        The BLT blocks.

    Returns
    -------
    Repeats
        The ball sets and shared unknowns.
    """
    sets = find_ball_sets(dae)
    if not sets:
        return Repeats(reason="no arrays of identical components")
    out = Repeats(sets=sets, owner=owners(sets))
    shared_blocks = []
    for block in blocks:
        block_owners = {out.owner.get(id(v)) for _, v in block}
        if len(block_owners) > 1:
            names = ", ".join(sorted(v.name for _, v in block)[:4])
            return Repeats(reason=f"a block couples members with other unknowns ({names}, ...)")
        if block_owners == {None}:
            shared_blocks.append(block)
    shared = causalize(dae, shared_blocks)
    out.shared_expr = shared.expr
    out.shared_nonlinear = shared.nonlinear
    return out


def run(state: AssemblyState) -> None:
    """Set ``state.repeats`` from ``state.dae`` and ``state.blocks``; report the ball sets.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae", "blocks")
    rep = state.repeats = find_repeats(state.dae, state.blocks)
    state.report["repeated structure"] = (
        ", ".join(f"{s.name or 'root'}: {s.count} x {len(s.patterns)} variables"
                  for s in rep.sets) or rep.reason)
