"""Assemblies from other distributions: the ``bearingsim.assemblies`` entry-point group.

A distribution declares its assemblies as entry points of the group :data:`ENTRY_POINT_GROUP`,
e.g. in its ``pyproject.toml``::

    [project.entry-points."bearingsim.assemblies"]
    flywheel = "my_package.flywheel:flywheel"

Each entry point loads either an :class:`~bearingsim.assemblies.spec.AssemblySpec` or an object
(a factory or a module) with the spec as its ``SCENE_SPEC`` attribute, the convention of the
built-in assemblies. Scenes, ``bearingsim list`` and ``bearingsim export-fmu`` then name the
assembly by the spec's ``name``, like a built-in one.

The assembly registry (:mod:`bearingsim.assemblies.registry`, a
:class:`bearingsim.registry.Registry`) loads the entry points once, on its first use, with
:func:`entry_spec`. An entry point that cannot be loaded or that loads something else is skipped
with a :class:`PluginWarning` naming the entry point and its distribution; an assembly name that
a built-in assembly or another plug-in already has is a :class:`PluginError` naming both.
"""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies.spec import AssemblySpec
from bearingsim.registry import PluginError, PluginFailure, PluginWarning

__all__ = ["ENTRY_POINT_GROUP", "PluginError", "PluginFailure", "PluginWarning", "entry_spec",
           "spec_origin", "spec_of"]

ENTRY_POINT_GROUP = "bearingsim.assemblies"
"""The entry-point group of assembly plug-ins."""


def spec_of(obj: Any) -> AssemblySpec | None:
    """The spec an entry point's object stands for: the object itself when it is an
    :class:`AssemblySpec`, else its ``SCENE_SPEC`` attribute when that is one (None otherwise).

    Parameters
    ----------
    obj : object
        The object an entry point loaded (a spec or a module).

    Returns
    -------
    AssemblySpec or None
        The spec, or None when the object stands for none.
    """
    if isinstance(obj, AssemblySpec):
        return obj
    spec = getattr(obj, "SCENE_SPEC", None)
    return spec if isinstance(spec, AssemblySpec) else None


def entry_spec(obj: Any, entry_name: str) -> tuple[str, AssemblySpec]:
    """``(spec.name, spec)`` of an entry point's loaded object (:func:`spec_of`).

    Parameters
    ----------
    obj : object
        The object the entry point loaded.
    entry_name : str
        The entry point's name (for the error message).

    Returns
    -------
    tuple of (str, AssemblySpec)
        The spec's name and the spec.

    Raises
    ------
    TypeError
        When the object stands for no spec (the registry skips the entry point with a warning).
    """
    spec = spec_of(obj)
    if spec is None:
        raise TypeError(f"it loads {type(obj).__name__} {obj!r:.80}, which is neither an "
                        "AssemblySpec nor an object with an AssemblySpec as its SCENE_SPEC")
    return spec.name, spec


def spec_origin(spec: AssemblySpec) -> str:
    """The module that builds an assembly (named when a plug-in takes its name).

    Parameters
    ----------
    spec : AssemblySpec
        The assembly's spec.

    Returns
    -------
    str
        The module name of the spec's build function.
    """
    return getattr(spec.build, "__module__", None) or "unknown module"
