"""Pruning: keep only the equations and states that the requested outputs depend on."""

from __future__ import annotations

import difflib
from typing import TYPE_CHECKING

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.errors import ModelError

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "resolve_names", "prune"]

NAME = "pruning"
"""The pass name in timings, logs and ``extra_passes``."""


def resolve_names(dae: DAE, names: list[str]) -> list[Var]:
    """Map dotted names (variables or eliminated aliases) to the variables that carry them.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    names : list of str
        Dotted names.

    Returns
    -------
    list of Var
        The variables, in the order of ``names``.
    """
    by_path = {v.name: v for v in dae.vars}
    out: list[Var] = []
    unknown = []
    for name in names:
        if name in by_path:
            out.append(by_path[name])
        elif name in dae.aliases:
            rep = dae.aliases[name].representative
            if rep is not None:
                out.append(rep)
        else:
            known = list(by_path) + list(dae.aliases)
            close = difflib.get_close_matches(name, known, n=5)
            unknown.append(f"unknown output variable {name!r}"
                           + (f" (did you mean {', '.join(close)}?)" if close else ""))
    if unknown:  # every one at once
        raise ModelError("; ".join(unknown))
    return out


def prune(dae: DAE, matching: dict[Eq, Var], outputs: list[str]) -> list[str]:
    """Drop equations, unknowns and states that no requested output depends on.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    matching : dict of Eq to Var
        Each equation -> the unknown it determines; pruned in place.
    outputs : list of str
        Requested outputs.

    Returns
    -------
    list of str
        What was skipped, for the scene summary.
    """
    var_eq = {v: e for e, v in matching.items()}
    lookup = dae.by_name()
    needed: set[Var] = set()
    stack = resolve_names(dae, outputs)
    while stack:
        v = stack.pop()
        if v in needed:
            continue
        needed.add(v)
        if v.is_state:
            stack.append(v.derivative)
        elif v in var_eq:
            stack.extend(dae.incidence(var_eq[v], lookup))
    dropped_states = [v.name for v in dae.states if v not in needed]
    dropped_eqs = [e for e in dae.eqs if matching[e] not in needed]
    keep = {id(e) for e in dae.eqs if matching[e] in needed}
    dae.eqs = [e for e in dae.eqs if id(e) in keep]
    for e in dropped_eqs:
        del matching[e]
    dae.vars = [v for v in dae.vars if v in needed or v.is_input]
    kept = set(dae.vars)
    dae.aliases = {
        k: a for k, a in dae.aliases.items() if a.representative is None or a.representative in kept
    }
    skipped = []
    if dropped_states:
        skipped.append(f"{len(dropped_states)} state(s) not needed: {', '.join(dropped_states)}")
    if dropped_eqs:
        skipped.append(f"{len(dropped_eqs)} equation(s) not needed by the requested outputs")
    return skipped


def run(state: AssemblyState) -> None:
    """With ``state.outputs``, prune ``state.dae`` and ``state.matching`` to what they need.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae", "matching")
    if state.outputs:
        state.dae.skipped.extend(prune(state.dae, state.matching, state.outputs))
