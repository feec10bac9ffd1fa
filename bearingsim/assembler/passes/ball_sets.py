"""Ball sets: the arrays of identical components of a model (the Z balls of a row with their
contacts, pockets and drag), found by their flat names.

A *ball set* is every array of components with the same parent and length in the flat names
(``ball[k]``, ``inner[k]``, ``outer[k]``, ``drag[k]``, ``pocket[k]`` of one row): member ``k``
is everything with index ``k``. Any array qualifies: the two bearings of a duplex pair form a
set of two members too. A variable belongs to member ``k`` when its name, with the index
replaced by ``*`` (its *pattern*), occurs for every member of its set; everything else (rings,
cage, drive, and the port variables that alias elimination kept under one ball's name) is
shared.

Tearing solves the members' blocks once per set and copies the solution to the other members
(:mod:`~bearingsim.assembler.passes.tearing`); the repeated-structure pass maps one function
per ball over the set (:mod:`~bearingsim.assembler.passes.repeated`).
"""

from __future__ import annotations

import re
from collections import defaultdict
from collections.abc import Callable

import casadi as ca

from bearingsim.assembler.dae import DAE
from bearingsim.assembler.ir import BallSet

__all__ = ["MIN_MEMBERS", "find_ball_sets", "function_identity", "owners"]

_INDEXED = re.compile(r"^(?P<head>(?:der\()?)(?P<path>[^\[]*)\[(?P<k>\d+)\](?P<rest>.*)$")
"""A flat name with an array index: ``ball[3].w`` or ``der(inner[3].delta)``."""

MIN_MEMBERS = 2
"""Ball sets of fewer members are inlined."""


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


def find_ball_sets(dae: DAE) -> list[BallSet]:
    """The ball sets of ``dae`` (of at least :data:`MIN_MEMBERS` members), by parent.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.

    Returns
    -------
    list of BallSet
        The ball sets.
    """
    var_sets = _group(dae.vars, lambda v: v.name)
    par_sets = _group(dae.params, lambda q: q.name)
    out = []
    for (parent, count), patterns in sorted(var_sets.items()):
        if count < MIN_MEMBERS:
            continue
        order = sorted(patterns)
        p_members = par_sets.get((parent, count), {})
        p_order = sorted(p_members)
        out.append(BallSet(
            parent, count, order, [[patterns[p][k] for p in order] for k in range(count)],
            p_order, [[p_members[p][k] for p in p_order] for k in range(count)]))
    return out


def owners(sets: list[BallSet]) -> dict[int, tuple[int, int]]:
    """``id(var or param)`` -> (set, member) for the members' variables and parameters.

    Parameters
    ----------
    sets : list of BallSet
        The ball sets.

    Returns
    -------
    dict of int to tuple of (int, int)
        Set and member index by object id.
    """
    out = {}
    for s, bs in enumerate(sets):
        for k in range(bs.count):
            for item in (*bs.variables[k], *bs.parameters[k]):
                out[id(item)] = (s, k)
    return out


def function_identity(f: ca.Function) -> str:
    """``f`` serialized with fresh input symbols: equal for two members' functions exactly when
    they compute the same (same operations in the same order, same constants), whatever their
    symbols are called.

    Parameters
    ----------
    f : casadi.Function
        A member's function.

    Returns
    -------
    str
        The identity string.
    """
    fresh = [ca.SX.sym(f"i{i}", f.sparsity_in(i)) for i in range(f.n_in())]
    return ca.Function("f", fresh, f.call(fresh)).serialize()
