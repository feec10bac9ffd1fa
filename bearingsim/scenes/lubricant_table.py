"""A scene's ``[lubricants]`` table: lubricants the scene defines or overrides, by name.

Each sub-table ``[lubricants."NAME"]`` either defines a new mineral oil (``grade``, or ``nu40``
and ``nu100``; with ``fill_fraction`` or ``thickener_factor`` a grease of that base oil) or,
without them, derives from a known lubricant (``base``, default ``NAME`` itself: the override of
a known lubricant, e.g. its temperature). The other keys set the operating ``temperature`` and
the properties of :class:`~bearingsim.physics.lubricant.Oil` or ``Grease``. Numbers are SI
(K, m^2/s); text with a unit is converted (``"60 degC"``, ``"32 mm^2/s"``).

The lubricants are registered (:func:`~bearingsim.physics.lubricant.register_lubricant`,
replacing one of the same name) when the scene is read, before the assembly's lubricant names
are checked, and the lubricant contract is checked then. They belong to the scene: reading or
preparing another scene first forgets them (an overridden built-in lubricant comes back), and
preparing a scene registers its own again, so that scenes read one after the other in a
process each run with their own lubricants.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from bearingsim.errors import BearingsimError, ParameterError
from bearingsim.physics.lubricant import (
    LUBRICANTS,
    Grease,
    Lubricant,
    Oil,
    get_lubricant,
    register_lubricant,
)
from bearingsim.scenes.tables import SceneFileError
from bearingsim.units import UnitError, to_si

__all__ = ["LUBRICANT_KEYS", "load_lubricants_table"]

LUBRICANT_KEYS: dict[str, str] = {
    "base": "a known lubricant this one derives from (default: the table's own name)",
    "grade": "ISO VG grade of a new mineral oil (10 ... 460)",
    "nu40": "kinematic viscosity at 40 degC of a new oil [m^2/s, or text with a unit]",
    "nu100": "kinematic viscosity at 100 degC of a new oil [m^2/s, or text with a unit]",
    "temperature": "operating temperature [K, or text with a unit: \"60 degC\"]",
    "method": "lubrication method (oil_bath, oil_jet, oil_mist, grease, vertical_shaft)",
    "mu_bl": "boundary sliding friction coefficient [-]",
    "mu_ehl": "full-film sliding friction coefficient [-]",
    "rho15": "density at 15 degC [kg/m^3]",
    "alpha": "pressure-viscosity coefficient [1/Pa]",
    "fill_fraction": "grease fill of the free volume [-] (makes a grease)",
    "thickener_factor": "grease thickener factor [-] (makes a grease)",
}
"""The keys of a ``[lubricants."NAME"]`` table and what they mean."""

_UNITS = {"nu40": "m^2/s", "nu100": "m^2/s", "temperature": "K"}
_GREASE_KEYS = ("fill_fraction", "thickener_factor")

_FROM_SCENE: dict[str, Callable[..., Lubricant]] = {}
"""The lubricants the last scene read or prepared registered, by name (their factories)."""


def _values(name: str, entry: dict[str, Any]) -> dict[str, Any]:
    """The entry's values in SI (ParameterError naming the key for a unit slip)."""
    out = {}
    for key, value in entry.items():
        if key in _UNITS:
            try:
                value = to_si(value, _UNITS[key], f"lubricants.{name}.{key}")
            except UnitError as exc:
                raise ParameterError(str(exc)) from None
        out[key] = value
    return out


def _new_oil_factory(name: str, v: dict[str, Any]) -> Callable[..., Lubricant]:
    """A new oil (or grease of that oil) from ``grade`` or ``nu40`` and ``nu100``."""
    if "grade" in v and ("nu40" in v or "nu100" in v):
        raise ParameterError(f"lubricants.{name}: give grade or nu40 and nu100, not both")
    if "grade" not in v and not ("nu40" in v and "nu100" in v):
        raise ParameterError(f"lubricants.{name}: a new oil needs grade, or nu40 and nu100 "
                             f"[m^2/s]")
    grease = {k: v[k] for k in _GREASE_KEYS if k in v}
    oil_keys = {k: v[k] for k in ("temperature", "method", "mu_bl", "mu_ehl", "rho15", "alpha")
                if k in v}
    if grease:
        oil_keys["method"] = oil_keys.get("method", "grease")

    def oil(**kw: Any) -> Oil:
        keys = {"name": name, **oil_keys, **kw}
        if "grade" in v:
            return Oil.from_iso_vg(v["grade"], **keys)
        try:
            return Oil(v["nu40"] * 1e6, 40.0, v["nu100"] * 1e6, 100.0, **keys)
        except ParameterError as exc:  # named as the table names them
            raise ParameterError(str(exc).replace("nu1_cst", "nu40").replace(
                "nu2_cst", "nu100")) from None

    if not grease:
        return oil

    def grease_factory(**kw: Any) -> Grease:
        base_kw = {k: kw.pop(k) for k in list(kw) if k not in ("temperature", *_GREASE_KEYS)}
        return Grease(oil(**base_kw), **{"name": name, **grease, **kw})

    return grease_factory


def _derived_factory(name: str, v: dict[str, Any]) -> Callable[..., Lubricant]:
    """A known lubricant (``base``, default ``name``) with the entry's values as defaults."""
    base = v.pop("base", name)
    factory = LUBRICANTS[base]  # CatalogError: unknown, with the close matches
    overrides = dict(v)

    def derived(**kw: Any) -> Lubricant:
        try:
            return factory(**{**overrides, **kw})
        except TypeError as exc:
            raise ParameterError(f"lubricants.{name}: {sorted(overrides)} do not all apply to "
                                 f"{base!r} ({exc})") from None

    return derived


def _factory(name: str, entry: dict[str, Any]) -> Callable[..., Lubricant]:
    unknown = sorted(set(entry) - set(LUBRICANT_KEYS))
    if unknown:
        raise ParameterError(f"lubricants.{name}: unknown key {unknown[0]!r}; give "
                             f"{', '.join(LUBRICANT_KEYS)}")
    v = _values(name, entry)
    if any(k in v for k in ("grade", "nu40", "nu100")):
        if "base" in v:
            raise ParameterError(f"lubricants.{name}: base derives from a known lubricant; a "
                                 f"new oil (grade, nu40, nu100) has none")
        return _new_oil_factory(name, v)
    return _derived_factory(name, v)


def load_lubricants_table(table: Any) -> list[SceneFileError]:
    """Register the lubricants of a scene's ``[lubricants]`` table; the problems found.

    Parameters
    ----------
    table : dict or None
        ``{name: {key: value}}`` with the keys of :data:`LUBRICANT_KEYS`.

    Returns
    -------
    list of SceneFileError
        One per lubricant that could not be defined, its ``key`` the scene key
        (``lubricants.NAME``), its ``reason`` naming the property, unit and range.
    """
    for name, factory in _FROM_SCENE.items():  # the last scene's, forgotten
        LUBRICANTS.forget(name, factory)
    _FROM_SCENE.clear()
    if table is None:
        return []
    if not isinstance(table, dict):
        return [SceneFileError("lubricants", f"must be a table of lubricants, got {table!r:.60}",
                               '[lubricants."NAME"] tables')]
    problems = []
    for name, entry in table.items():
        key = f"lubricants.{name}"
        if not isinstance(entry, dict):
            problems.append(SceneFileError(key, f"must be a table, got {entry!r:.60}",
                                           ", ".join(LUBRICANT_KEYS)))
            continue
        try:
            factory = _factory(name, dict(entry))
            register_lubricant(name, factory, replace=True)
            _FROM_SCENE[name] = LUBRICANTS.registered()[name]
            get_lubricant(name)  # the table's own values once more, through the registry
        except BearingsimError as exc:  # (the key is said once, by the problem)
            problems.append(SceneFileError(key, str(exc).removeprefix(f"{key}: "),
                                           ", ".join(LUBRICANT_KEYS)))
    return problems
