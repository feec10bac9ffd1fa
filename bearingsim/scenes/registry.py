"""The assemblies a scene can name: the built-in specs, the plug-ins' and the ones users
register.

The built-in specs are declared by the assembly modules beside their factories
(:data:`bearingsim.assemblies.SCENE_SPECS`; the spec types are in
:mod:`bearingsim.assemblies.spec`). Installed distributions add theirs through the
``bearingsim.assemblies`` entry-point group (:mod:`bearingsim.assemblies.plugins`), loaded once,
on the first use of :data:`REGISTRY` (:mod:`bearingsim.assemblies.registry`). :func:`register`
adds a user's own.
"""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies.registry import REGISTRY, AssemblyRegistry
from bearingsim.assemblies.spec import ArgSpec, AssemblySpec
from bearingsim.errors import ParameterError
from bearingsim.scenes.expressions import compile_expression

__all__ = [
    "REGISTRY",
    "AssemblyRegistry",
    "build_component",
    "get_spec",
    "register",
    "unregister",
]




def register(spec: AssemblySpec) -> AssemblySpec:
    """Add (or replace) an assembly spec, so that scenes can name it; returns it.

    Parameters
    ----------
    spec : AssemblySpec
        The spec.

    Returns
    -------
    AssemblySpec
        ``spec``.

    Raises
    ------
    ParameterError
        When ``spec`` is not an :class:`~bearingsim.assemblies.spec.AssemblySpec`.
    """
    if not isinstance(spec, AssemblySpec):
        raise ParameterError(f"register: spec must be an AssemblySpec "
                             f"(bearingsim.assemblies.spec), got {type(spec).__name__}")
    REGISTRY[spec.name] = spec
    return spec


def unregister(name: str) -> AssemblySpec:
    """Remove a registered assembly spec by name; returns it (``CatalogError``, a ``KeyError``,
    with the known names for an unknown one).

    Parameters
    ----------
    name : str
        Assembly name.

    Returns
    -------
    AssemblySpec
        The removed spec.
    """
    spec = get_spec(name)
    del REGISTRY[name]
    return spec


def get_spec(name: str) -> AssemblySpec:
    """The spec of an assembly by name (raises :class:`~bearingsim.errors.CatalogError`, a
    ``KeyError``, with the known names, close matches and the reason when a plug-in of that
    name could not be loaded).

    Parameters
    ----------
    name : str
        Assembly name.

    Returns
    -------
    AssemblySpec
        The spec.
    """
    return REGISTRY[name]


def _compiled_signals(specs: dict[str, ArgSpec], args: dict[str, Any],
                      prefix: str) -> dict[str, Any]:
    out = dict(args)
    for key, spec in specs.items():
        value = args.get(key)
        if spec.kind == "signal" and isinstance(value, str):
            out[key] = compile_expression(value, prefix + key)
        elif spec.kind == "table" and isinstance(value, dict):
            out[key] = _compiled_signals(spec.table or {}, value, f"{prefix}{key}.")
    return out


def build_component(spec: AssemblySpec, args: dict[str, Any], fidelity: str) -> Any:
    """``spec.build(args, fidelity)`` with the signal arguments given as expression text
    compiled to functions of time (nested tables too).

    Parameters
    ----------
    spec : AssemblySpec
        The assembly.
    args : dict
        Its arguments, defaults filled in (``spec.with_defaults``).
    fidelity : str
        One of ``spec.fidelities``.

    Returns
    -------
    Component
        What ``spec.build`` returns.
    """
    return spec.build(_compiled_signals(spec.args, args, "assembly."), fidelity)
