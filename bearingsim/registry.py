"""One registry pattern for everything users name: assemblies, bearings and lubricants.

A :class:`Registry` maps names to entries in three layers, looked up in this order: the built-in
entries (given lazily, e.g. read from a catalogue file on first use), the plug-ins of installed
distributions (the entry points of the registry's group, loaded once, on first use) and the
entries users register (:meth:`Registry.register`). Names are matched through the registry's
``normalize`` function (case, spaces, ...).

Every registry speaks with the same errors:

* an unknown name is a :class:`~bearingsim.errors.CatalogError` naming the kind, the name, the
  known names, the close matches (:func:`difflib.get_close_matches`) and why a plug-in of that
  name could not be loaded;
* a name already taken is a :class:`NameTakenError` (a ``CatalogError`` and a
  ``ParameterError``);
* a plug-in that cannot be loaded is skipped with a :class:`PluginWarning` naming its entry
  point and distribution; a plug-in with a built-in entry's or another plug-in's name is a
  :class:`PluginError` naming both, raised on every use until :meth:`Registry.reload_plugins`.
"""

from __future__ import annotations

import difflib
import warnings
from collections.abc import Callable, Iterator, Mapping, MutableMapping
from dataclasses import dataclass
from importlib.metadata import EntryPoint, entry_points
from typing import Any

from bearingsim.errors import BearingsimError, CatalogError, ParameterError

__all__ = ["NameTakenError", "PluginError", "PluginFailure", "PluginWarning", "Registry",
           "describe_entry_point"]


class NameTakenError(CatalogError, ParameterError):
    """A name given to :meth:`Registry.register` is taken (and ``replace`` was not given)."""


class PluginError(BearingsimError):
    """Two entries of a registry (a plug-in and a built-in one, or two plug-ins) have one
    name."""


class PluginWarning(UserWarning):
    """A plug-in could not be loaded and is skipped."""


@dataclass(frozen=True)
class PluginFailure:
    """An entry point that gave no entry: ``where`` names it and its distribution."""

    name: str
    where: str
    reason: str
    kind: str = "assembly"

    def __str__(self) -> str:
        return f"{self.kind} plug-in {self.where} skipped: {self.reason}"


def describe_entry_point(entry: EntryPoint) -> str:
    """``entry point NAME = VALUE (distribution DIST VERSION)`` for messages.

    Parameters
    ----------
    entry : EntryPoint
        The entry point.

    Returns
    -------
    str
        The description.
    """
    dist = getattr(entry, "dist", None)
    owner = "an unknown distribution" if dist is None else (
        f"distribution {dist.metadata['Name']} {dist.version}")
    return f"entry point {entry.name} = {entry.value} ({owner})"


def _identity(name: str) -> str:
    return name


class Registry(MutableMapping):
    """Name -> entry: built-in entries, then plug-ins, then registered ones.

    Parameters
    ----------
    kind : str
        What the entries are, for messages (``"assembly"``, ``"bearing"``, ``"lubricant"``).
    builtin : callable
        Returns the built-in entries by name (called once, on first use).
    group : str, optional
        Entry-point group of the plug-ins (None: no plug-ins).
    convert : callable, optional
        ``convert(obj, entry_name) -> (name, entry)`` for an entry point's loaded object; raises
        ``TypeError`` with the reason for an object that is no entry. Default: the object
        itself under the entry point's name.
    normalize : callable
        Maps a name to the key names are matched by (default: the name itself).
    origin : callable, optional
        ``origin(entry) -> str`` for the clash message (where a built-in entry comes from).
    builtin_label : str, optional
        How a built-in entry is called in messages (default ``"built-in <kind>"``).
    replace_builtin : bool
        Whether :meth:`register` may replace a built-in entry (with ``replace=True``).
    """

    def __init__(self, kind: str, builtin: Callable[[], Mapping[str, Any]], *,
                 group: str | None = None,
                 convert: Callable[[Any, str], tuple[str, Any]] | None = None,
                 normalize: Callable[[str], str] = _identity,
                 origin: Callable[[Any], str] | None = None,
                 builtin_label: str | None = None, replace_builtin: bool = True) -> None:
        self.kind, self.group = kind, group
        self._builtin_source, self._convert = builtin, convert
        self._normalize, self._origin = normalize, origin
        self._builtin_label = builtin_label or f"built-in {kind}"
        self._replace_builtin = replace_builtin
        self._builtin: dict[str, Any] | None = None
        self._entries: dict[str, Any] = {}
        self._registered: dict[str, Any] = {}
        self._loaded = False
        self._error: PluginError | None = None
        self.plugins: dict[str, Any] = {}
        """The plug-ins' entries by name."""
        self.plugin_failures: list[PluginFailure] = []
        """Entry points skipped at the last discovery."""
        self.sibling: tuple[Registry, str] | None = None
        """A registry of another kind that a name asked of this one may belong to, and what its
        entries are (the ball and the roller bearings): :meth:`unknown` says so."""

    # ---- loading -----------------------------------------------------------------------------
    def _builtins(self) -> dict[str, Any]:
        if self._builtin is None:
            self._builtin = dict(self._builtin_source())
            self._entries = {**self._builtin, **self._entries}
        return self._builtin

    def _load(self) -> None:
        builtin = self._builtins()
        if not self._loaded:
            self._loaded = True
            try:
                self.plugins, self.plugin_failures = self._discover(builtin)
            except PluginError as exc:
                self._error = exc
            for failure in self.plugin_failures:
                warnings.warn(str(failure), PluginWarning, stacklevel=4)
            for name, entry in self.plugins.items():
                self._entries.setdefault(name, entry)
        if self._error is not None:
            raise self._error

    def _discover(self, builtin: dict[str, Any]) -> tuple[dict[str, Any], list[PluginFailure]]:
        if self.group is None:
            return {}, []
        found: dict[str, Any] = {}
        origins: dict[str, str] = {}
        failures: list[PluginFailure] = []
        taken = {self._normalize(n): n for n in builtin}
        for entry in sorted(entry_points(group=self.group), key=lambda e: (e.name, e.value)):
            where = describe_entry_point(entry)
            try:
                obj = entry.load()
            except Exception as exc:  # noqa: BLE001 - any failure of a plug-in's import
                failures.append(PluginFailure(entry.name, where, f"loading it raised "
                                              f"{type(exc).__name__}: {exc}", self.kind))
                continue
            try:
                name, value = (self._convert(obj, entry.name) if self._convert
                               else (entry.name, obj))
            except TypeError as exc:  # the object is no entry of this registry
                failures.append(PluginFailure(entry.name, where, str(exc), self.kind))
                continue
            key = self._normalize(name)
            if key in taken:
                known = taken[key]
                source = f" ({self._origin(builtin[known])})" if self._origin else ""
                raise PluginError(
                    f"{self.kind} plug-in {where} names its {self.kind} {name!r}, the name of "
                    f"the {self._builtin_label} {known!r}{source}; rename the plug-in's "
                    f"{self.kind} or uninstall the distribution")
            if key in origins:
                raise PluginError(
                    f"{self.kind} plug-ins {origins[key]} and {where} both name their "
                    f"{self.kind} {name!r}; rename one or uninstall one of the distributions")
            found[name] = value
            origins[key] = where
        return found, failures

    def reload_plugins(self) -> None:
        """Forget the plug-ins (and their errors) and discover them again on the next use;
        registered entries stay."""
        for name, entry in self.plugins.items():
            if self._entries.get(name) is entry:
                del self._entries[name]
        self.plugins, self.plugin_failures = {}, []
        self._loaded, self._error = False, None

    # ---- names -------------------------------------------------------------------------------
    def find(self, name: Any) -> str | None:
        """The registered name that ``name`` stands for (through ``normalize``), or None.

        Parameters
        ----------
        name : object
            A name (one the registry's ``normalize`` cannot read stands for none).

        Returns
        -------
        str or None
            The registered name, or None.
        """
        self._load()
        try:
            key = self._normalize(name)
        except (TypeError, ValueError, AttributeError):  # a name of no kind this registry reads
            return None
        return next((known for known in self._entries if self._normalize(known) == key), None)

    def unknown(self, name: Any) -> CatalogError:
        """The error for an unknown name: kind, name, known names, close matches and the
        reason a plug-in of that name was skipped.

        Parameters
        ----------
        name : object
            The name asked for.

        Returns
        -------
        CatalogError
            The error (returned, not raised).
        """
        self._load()
        known = list(self._entries)
        by_key = {self._normalize(k): k for k in known}
        close = difflib.get_close_matches(self._normalize(str(name)), list(by_key), n=3,
                                          cutoff=0.6)
        text = f"unknown {self.kind} {name!r}; known: {', '.join(known)}"
        if close:
            text += f"; did you mean {', '.join(repr(by_key[c]) for c in close)}?"
        text += "".join(f"; {failure}" for failure in self.plugin_failures
                        if failure.name == name)
        other = self.in_sibling(name)
        if other:
            text += f"; {name!r} is {other}"
        return CatalogError(text)

    def in_sibling(self, name: Any) -> str | None:
        """What ``name`` is when the :attr:`sibling` registry has it (``"a cylindrical
        roller bearing"``), else None.

        Parameters
        ----------
        name : object
            A name (one the sibling's ``normalize`` cannot read stands for none).

        Returns
        -------
        str or None
            The sibling's description of its entries, or None.
        """
        if self.sibling is not None and self.sibling[0].find(name) is not None:
            return self.sibling[1]
        return None

    def register(self, name: str, entry: Any, *, replace: bool = False) -> None:
        """Add an entry under ``name`` (replacing the one it stands for with ``replace``).

        Parameters
        ----------
        name : str
            Name of the entry, not empty.
        entry : object
            The entry (converted by the registry's ``convert``).
        replace : bool
            Replace the entry the name stands for.

        Raises
        ------
        ParameterError
            For an empty name.
        NameTakenError
            For a name already taken (without ``replace``; built-in names of a registry that
            keeps them always).
        """
        if not isinstance(name, str) or not self._normalize(name).strip():
            raise ParameterError(f"register {self.kind}: name must be a non-empty string, got "
                                 f"{name!r}")
        taken = self.find(name)
        if taken is not None and taken in self._builtins() and not self._replace_builtin:
            raise NameTakenError(f"register {self.kind}: {name!r} is a {self._builtin_label}; "
                                 f"give yours another name")
        if taken is not None and not replace:
            raise NameTakenError(f"register {self.kind}: {name!r} is already registered (as "
                                 f"{taken!r}); give replace=True to replace it")
        if taken is not None:
            del self._entries[taken]
            self._registered.pop(taken, None)
        self._entries[name] = entry
        self._registered[name] = entry

    def unregister(self, name: str) -> None:
        """Forget an entry :meth:`register` added (a built-in entry or a plug-in's stays, and
        one that the registration replaced comes back).

        Parameters
        ----------
        name : str
            Its name (through ``normalize``).

        Raises
        ------
        CatalogError
            For a name that no registered entry has (an unknown name, a built-in entry).
        """
        known = self.find(name)
        if known is None:
            raise self.unknown(name)
        if known not in self._registered:
            raise CatalogError(f"unregister {self.kind}: {name!r} is not a registered "
                               f"{self.kind}")
        del self[known]
        key = self._normalize(known)  # an entry it replaced comes back
        for source in (self._builtin or {}, self.plugins):
            base = next((n for n in source if self._normalize(n) == key), None)
            if base is not None:
                self._entries[base] = source[base]
                break

    def forget(self, name: str, entry: Any) -> None:
        """Unregister ``name`` if it still stands for ``entry`` (what a scene or a sweep's chunk
        registered for itself; a registration of another entry made since stays).

        Parameters
        ----------
        name : str
            The name it was registered under.
        entry : object
            The entry registered then.
        """
        if self._registered.get(name) is entry:
            self.unregister(name)

    def registered(self) -> dict[str, Any]:
        """The entries :meth:`register` added in this process (a scene's bearings and
        lubricants among them), by name, in the order they were registered: what another
        process (a sweep's worker) registers to know the same names.

        Returns
        -------
        dict of str to object
            Name -> entry.
        """
        return dict(self._registered)

    # ---- mapping -----------------------------------------------------------------------------
    def __getitem__(self, name: str) -> Any:
        known = self.find(name)
        if known is None:
            raise self.unknown(name)
        return self._entries[known]

    def __setitem__(self, name: str, entry: Any) -> None:
        self.register(name, entry, replace=True)

    def __delitem__(self, name: str) -> None:
        known = self.find(name)
        if known is None:
            raise self.unknown(name)
        del self._entries[known]
        self._registered.pop(known, None)

    def __iter__(self) -> Iterator[str]:
        self._load()
        return iter(list(self._entries))

    def __len__(self) -> int:
        self._load()
        return len(self._entries)

    def __contains__(self, name: object) -> bool:
        return self.find(name) is not None

    def __repr__(self) -> str:
        return f"Registry({self.kind}: {', '.join(self._entries)})"
