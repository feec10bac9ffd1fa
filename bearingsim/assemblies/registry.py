"""The registry of assemblies by name: the built-in specs, then the plug-ins' (loaded once, on
first use, from the ``bearingsim.assemblies`` entry-point group, :mod:`bearingsim.assemblies.
plugins`), then the ones users register (:func:`bearingsim.scenes.register`).

Scenes (:mod:`bearingsim.scenes.registry`), ``bearingsim list`` and ``bearingsim export-fmu``
all read :data:`REGISTRY`, a :class:`bearingsim.registry.Registry` like the bearings' and the
lubricants' (one error style for an unknown name).
"""

from __future__ import annotations

from bearingsim.assemblies import SCENE_SPECS
from bearingsim.assemblies.plugins import ENTRY_POINT_GROUP, entry_spec, spec_origin
from bearingsim.assemblies.spec import AssemblySpec
from bearingsim.registry import Registry

__all__ = ["REGISTRY", "AssemblyRegistry"]


class AssemblyRegistry(Registry):
    """Assembly name -> spec: the built-in specs, then the plug-ins' (loaded on first use),
    then the registered ones (:class:`bearingsim.registry.Registry`).

    Parameters
    ----------
    builtin : tuple of AssemblySpec
        The built-in specs.
    """

    def __init__(self, builtin: tuple[AssemblySpec, ...]):
        super().__init__("assembly", lambda: {spec.name: spec for spec in builtin},
                         group=ENTRY_POINT_GROUP, convert=entry_spec, origin=spec_origin)


REGISTRY = AssemblyRegistry(SCENE_SPECS)
"""Assembly name -> spec (built-in, plug-ins, registered)."""
