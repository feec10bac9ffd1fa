"""The registry of assemblies by name: the built-in specs, then the plug-ins' (loaded once, on
first use, from the ``bearingsim.assemblies`` entry-point group, :mod:`bearingsim.assemblies.
plugins`), then the ones users register (:func:`bearingsim.scenes.register`).

Scenes (:mod:`bearingsim.scenes.registry`), ``bearingsim list`` and ``bearingsim export-fmu``
all read :data:`REGISTRY`.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator, MutableMapping

from bearingsim.assemblies import SCENE_SPECS
from bearingsim.assemblies.plugins import PluginError, PluginFailure, PluginWarning, discover
from bearingsim.assemblies.spec import AssemblySpec

__all__ = ["REGISTRY", "AssemblyRegistry"]


class AssemblyRegistry(MutableMapping):
    """Assembly name -> spec: the built-in specs, then the plug-ins' (loaded on first use).

    A plug-in that cannot be loaded is skipped with a
    :class:`~bearingsim.assemblies.plugins.PluginWarning` (and listed in
    :attr:`plugin_failures`); a plug-in whose assembly name is taken raises
    :class:`~bearingsim.assemblies.plugins.PluginError` on every use until
    :meth:`reload_plugins` finds the clash gone.
    """

    def __init__(self, builtin: tuple[AssemblySpec, ...]):
        self._builtin = {spec.name: spec for spec in builtin}
        self._specs = dict(self._builtin)
        self._loaded = False
        self._error: PluginError | None = None
        self.plugin_failures: list[PluginFailure] = []
        """Entry points skipped at the last discovery."""
        self.plugins: dict[str, AssemblySpec] = {}
        """The plug-ins' assemblies by name."""

    def _load(self) -> None:
        if not self._loaded:
            self._loaded = True
            try:
                self.plugins, self.plugin_failures = discover(self._builtin)
            except PluginError as exc:
                self._error = exc
            for failure in self.plugin_failures:
                warnings.warn(str(failure), PluginWarning, stacklevel=4)
            for name, spec in self.plugins.items():
                self._specs.setdefault(name, spec)
        if self._error is not None:
            raise self._error

    def reload_plugins(self) -> None:
        """Forget the plug-ins (and their errors) and discover them again on the next use;
        specs added with :func:`register` stay."""
        for name, spec in self.plugins.items():
            if self._specs.get(name) is spec:
                del self._specs[name]
        self.plugins, self.plugin_failures = {}, []
        self._loaded, self._error = False, None

    def __getitem__(self, name: str) -> AssemblySpec:
        self._load()
        return self._specs[name]

    def __setitem__(self, name: str, spec: AssemblySpec) -> None:
        self._load()
        self._specs[name] = spec

    def __delitem__(self, name: str) -> None:
        self._load()
        del self._specs[name]

    def __iter__(self) -> Iterator[str]:
        self._load()
        return iter(list(self._specs))

    def __len__(self) -> int:
        self._load()
        return len(self._specs)

    def __contains__(self, name: object) -> bool:
        self._load()
        return name in self._specs

    def __repr__(self) -> str:
        return f"AssemblyRegistry({', '.join(self._specs)})"


REGISTRY = AssemblyRegistry(SCENE_SPECS)
"""Assembly name -> spec (built-in, plug-ins, registered)."""
