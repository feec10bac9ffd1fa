"""Assemblies from other distributions: the ``bearingsim.assemblies`` entry-point group.

A distribution declares its assemblies as entry points of the group :data:`ENTRY_POINT_GROUP`,
e.g. in its ``pyproject.toml``::

    [project.entry-points."bearingsim.assemblies"]
    flywheel = "my_package.flywheel:flywheel"

Each entry point loads either an :class:`~bearingsim.assemblies.spec.AssemblySpec` or an object
(a factory or a module) with the spec as its ``SCENE_SPEC`` attribute, the convention of the
built-in assemblies. Scenes, ``bearingsim list`` and ``bearingsim export-fmu`` then name the
assembly by the spec's ``name``, like a built-in one.

:func:`discover` loads the entry points; :mod:`bearingsim.scenes.registry` calls it once, on the
first use of the registry. An entry point that cannot be loaded or that loads something else
is skipped with a :class:`PluginWarning` naming the entry point and its distribution; an
assembly name that a built-in assembly or another plug-in already has is a
:class:`PluginError` naming both.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib.metadata import EntryPoint, entry_points
from typing import Any

from bearingsim.assemblies.spec import AssemblySpec
from bearingsim.errors import BearingsimError

__all__ = ["ENTRY_POINT_GROUP", "PluginError", "PluginFailure", "PluginWarning", "describe",
           "discover", "spec_of"]

ENTRY_POINT_GROUP = "bearingsim.assemblies"
"""The entry-point group of assembly plug-ins."""


class PluginError(BearingsimError):
    """Two assemblies (a plug-in and a built-in one, or two plug-ins) have the same name."""


class PluginWarning(UserWarning):
    """An assembly plug-in could not be loaded and is skipped."""


@dataclass(frozen=True)
class PluginFailure:
    """An entry point that gave no assembly: ``where`` names it and its distribution."""

    name: str
    where: str
    reason: str

    def __str__(self) -> str:
        return f"assembly plug-in {self.where} skipped: {self.reason}"


def describe(entry: EntryPoint) -> str:
    """``entry point NAME = VALUE of distribution DIST VERSION`` for messages."""
    dist = getattr(entry, "dist", None)
    owner = "an unknown distribution" if dist is None else (
        f"distribution {dist.metadata['Name']} {dist.version}")
    return f"entry point {entry.name} = {entry.value} ({owner})"


def spec_of(obj: Any) -> AssemblySpec | None:
    """The spec an entry point's object stands for: the object itself when it is an
    :class:`AssemblySpec`, else its ``SCENE_SPEC`` attribute when that is one (None otherwise)."""
    if isinstance(obj, AssemblySpec):
        return obj
    spec = getattr(obj, "SCENE_SPEC", None)
    return spec if isinstance(spec, AssemblySpec) else None


def _origin(spec: AssemblySpec) -> str:
    return getattr(spec.build, "__module__", None) or "unknown module"


def discover(builtin: dict[str, AssemblySpec]) -> tuple[dict[str, AssemblySpec],
                                                         list[PluginFailure]]:
    """Load the assembly plug-ins of the installed distributions.

    Parameters
    ----------
    builtin : dict of str to AssemblySpec
        The built-in assemblies by name (their names are taken).

    Returns
    -------
    specs : dict of str to AssemblySpec
        The plug-ins' assemblies by name.
    failures : list of PluginFailure
        Entry points that could not be loaded or loaded no spec.

    Raises
    ------
    PluginError
        When a plug-in's assembly has the name of a built-in assembly or of another plug-in's.
    """
    specs: dict[str, AssemblySpec] = {}
    origins: dict[str, str] = {}
    failures: list[PluginFailure] = []
    for entry in sorted(entry_points(group=ENTRY_POINT_GROUP), key=lambda e: (e.name, e.value)):
        where = describe(entry)
        try:
            obj = entry.load()
        except Exception as exc:  # noqa: BLE001 - any failure of a plug-in's import is reported
            failures.append(PluginFailure(entry.name, where, f"loading it raised "
                                          f"{type(exc).__name__}: {exc}"))
            continue
        spec = spec_of(obj)
        if spec is None:
            failures.append(PluginFailure(
                entry.name, where, f"it loads {type(obj).__name__} {obj!r:.80}, which is neither "
                "an AssemblySpec nor an object with an AssemblySpec as its SCENE_SPEC"))
            continue
        if spec.name in builtin:
            raise PluginError(
                f"assembly plug-in {where} names its assembly {spec.name!r}, the name of the "
                f"built-in assembly {spec.name!r} ({_origin(builtin[spec.name])}); rename the "
                "plug-in's assembly (its AssemblySpec name) or uninstall the distribution")
        if spec.name in specs:
            raise PluginError(
                f"assembly plug-ins {origins[spec.name]} and {where} both name their assembly "
                f"{spec.name!r}; rename one or uninstall one of the distributions")
        specs[spec.name] = spec
        origins[spec.name] = where
    return specs, failures
