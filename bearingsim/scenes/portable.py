"""Ship an assembled :class:`~bearingsim.assembler.System` to other processes.

CasADi functions do not pickle without a context, and parameter declarations point into the
instance tree. :func:`pack` turns a system into plain data: every CasADi function through
``Function.serialize()`` (the Jacobians built on first access are built here, and the mapped-ball
kernels of both forms), parameters as (name, value, unit, description), everything else as is.
:func:`unpack` rebuilds a system that ``simulate`` accepts; parameter values given to it must
have been validated on the sending side (the declarations with their ranges stay there).
"""

from __future__ import annotations

import dataclasses
import hashlib
from collections.abc import Mapping
from typing import Any

import casadi as ca

from bearingsim.assembler.dae import Param
from bearingsim.assembler.mapped import MappedForms
from bearingsim.assembler.system import System

__all__ = ["pack", "unpack", "load_cached"]

_CACHE: dict[str, System] = {}
LOADS: dict[str, int] = {}
"""How often each packed model was deserialized in this process (for tests and reports)."""


def _ser(value: Any) -> Any:
    if isinstance(value, ca.Function):
        return {"__casadi__": value.serialize()}
    if isinstance(value, Mapping) and value and all(isinstance(v, ca.Function)
                                                    for v in value.values()):
        return {"__casadi_dict__": {k: v.serialize() for k, v in value.items()}}
    if isinstance(value, MappedForms):
        return {"__mapped__": value.to_data()}
    return value


def _de(value: Any) -> Any:
    if isinstance(value, dict) and "__casadi__" in value:
        return ca.Function.deserialize(value["__casadi__"])
    if isinstance(value, dict) and "__casadi_dict__" in value:
        return {k: ca.Function.deserialize(v) for k, v in value["__casadi_dict__"].items()}
    if isinstance(value, dict) and "__mapped__" in value:
        return MappedForms.from_data(value["__mapped__"])
    return value


def pack(system: System) -> dict[str, Any]:
    """Plain-data form of a system (picklable, no CasADi objects); includes a ``token``."""
    data = {}
    for f in dataclasses.fields(System):
        value = getattr(system, f.name)
        if f.name == "params":
            value = [(q.name, float(q.value), q.unit, q.description) for q in value]
        data[f.name] = _ser(value)
    digest = hashlib.sha1()
    for k in sorted(data):
        digest.update(k.encode())
        digest.update(repr(data[k]).encode())
    return {"token": digest.hexdigest(), "fields": data}


def unpack(packed: dict[str, Any]) -> System:
    """Rebuild a :class:`System` from :func:`pack` output (parameters without declarations)."""
    fields = {k: _de(v) for k, v in packed["fields"].items()}
    fields["params"] = [Param(n, ca.SX.sym(n), v, u, d) for n, v, u, d in fields["params"]]
    return System(**fields)


def load_cached(packed: dict[str, Any]) -> System:
    """:func:`unpack` once per process and model (keyed by the token)."""
    token = packed["token"]
    if token not in _CACHE:
        _CACHE[token] = unpack(packed)
        LOADS[token] = LOADS.get(token, 0) + 1
    return _CACHE[token]
