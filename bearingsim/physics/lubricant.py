"""Lubricants as swappable objects with one interface: :class:`Oil`, :class:`Grease`, :class:`Dry`.

Lubricants are plug-ins: a name in the registry :data:`LUBRICANTS` (built in, the
``bearingsim.lubricants`` entry-point group, :func:`register_lubricant`, a scene's
``[lubricants]`` table) or any object of a :class:`Lubricant` subclass is accepted wherever a
lubricant is asked for (assemblies, scenes, ``bearingsim list``), through the one converter
:func:`as_lubricant`. Every lubricant is checked against the contract
(:func:`check_lubricant_contract`) where it is defined.

Every property method takes an optional temperature ``T`` [K] (float, array or CasADi symbol);
``None`` means the lubricant's operating temperature. Values are SI (Pa s, m^2/s, kg/m^3, 1/Pa).
Catalogue data (mm^2/s at degC, ISO VG grades) are converted in the constructors.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from bearingsim.errors import ParameterError
from bearingsim.physics.dry import Dry
from bearingsim.physics.grease import Grease
from bearingsim.physics.lubricant_models import (
    KINEMATIC_VISCOSITY_RANGE,
    Lubricant,
    check_kinematic_viscosity,
)
from bearingsim.physics.lubrication import LUBRICATION_METHODS
from bearingsim.physics.oil import ISO_VG_NU100, MIN_OIL_VISCOSITY_CST, Oil
from bearingsim.registry import Registry
from bearingsim.validation import check_range

__all__ = [
    "ENTRY_POINT_GROUP",
    "LUBRICANTS",
    "LUBRICANT_CONTRACT",
    "check_lubricant_contract",
    "Lubricant",
    "Oil",
    "Grease",
    "Dry",
    "ISO_VG_NU100",
    "KINEMATIC_VISCOSITY_RANGE",
    "MIN_OIL_VISCOSITY_CST",
    "check_kinematic_viscosity",
    "as_lubricant",
    "get_lubricant",
    "known_lubricants",
    "register_lubricant",
    "unregister_lubricant",
]


ENTRY_POINT_GROUP = "bearingsim.lubricants"
"""Entry-point group of lubricant plug-ins: each entry point loads a factory (keyword
arguments -> :class:`Lubricant`), registered under the entry point's name."""


LUBRICANT_CONTRACT: tuple[tuple[str, str, float, float, str], ...] = (
    ("temperature", "K", 200.0, 600.0, "operating temperature, the default of every property"),
    ("mu_bl", "-", 0.0, 2.0, "boundary sliding friction coefficient of the SKF friction model"),
    ("mu_ehl", "-", 0.0, 2.0, "full-film sliding friction coefficient of the SKF friction model"),
    ("contact_friction", "-", 0.0, 2.0, "sliding friction of the cage pockets and lands"),
)
"""The numeric properties every lubricant must have: (attribute, unit, low, high, what it is
for). :func:`check_lubricant_contract` checks them (and ``name`` and ``method``) when a lubricant
is defined, so that a missing one is named there and not deep inside a friction model."""


def check_lubricant_contract(lubricant: Any, where: str = "lubricant") -> Lubricant:
    """Check that ``lubricant`` keeps the :class:`Lubricant` contract; returns it.

    Parameters
    ----------
    lubricant : Lubricant
        The object to check.
    where : str
        Who defines it, named in the error (``register_lubricant``, a scene key, ...).

    Returns
    -------
    Lubricant

    Raises
    ------
    ParameterError
        For an object that is no :class:`Lubricant`, a missing or non-text ``name``, a
        ``method`` that is not a lubrication method, or a property of
        :data:`LUBRICANT_CONTRACT` that is missing or outside its range; the message names the
        lubricant, the property, its unit and its range.
    """
    if not isinstance(lubricant, Lubricant):
        raise ParameterError(f"{where}: a lubricant must be a Lubricant (Oil, Grease, Dry, ...), "
                             f"got {type(lubricant).__name__}")
    name = getattr(lubricant, "name", None)
    if not isinstance(name, str) or not name.strip():
        raise ParameterError(f"{where}: a {type(lubricant).__name__} lubricant needs a name "
                             f"(non-empty text), got {name!r}")
    label = f"{where}: lubricant {name!r}"
    method = getattr(lubricant, "method", None)
    if method not in (*LUBRICATION_METHODS, "dry"):
        raise ParameterError(f"{label}: method = {method!r} is not a lubrication method; give "
                             f"one of {', '.join((*LUBRICATION_METHODS, 'dry'))}")
    for attribute, unit, low, high, purpose in LUBRICANT_CONTRACT:
        if not hasattr(lubricant, attribute):
            raise ParameterError(f"{label} has no {attribute} [{unit}] ({purpose}); give it a "
                                 f"value in [{low:g}, {high:g}] {unit}")
        check_range(getattr(lubricant, attribute), attribute, unit, low, high, where=label)
    return lubricant


def _normalize(name: str) -> str:
    """Names match ignoring case, spaces, hyphens, underscores and a leading "ISO"."""
    return "".join(ch for ch in str(name).lower() if ch.isalnum()).removeprefix("iso")


def _lithium_grease(**kwargs: Any) -> Grease:
    return Grease(Oil.from_iso_vg(100, method="grease", name="ISO VG 100"),
                  **{"name": "lithium grease", **kwargs})


def _builtin_lubricants() -> dict[str, Callable[..., Lubricant]]:
    return {**{f"ISO VG {g}": (lambda g=g, **kw: Oil.from_iso_vg(g, **kw)) for g in ISO_VG_NU100},
            "lithium grease": _lithium_grease}


def _checked_factory(factory: Any, name: str, where: str) -> Callable[..., Lubricant]:
    """``factory`` once it is callable and its lubricant (default arguments) keeps the
    contract."""
    if not callable(factory):
        raise ParameterError(f"{where}: factory for {name!r} must be callable "
                             f"(keyword arguments -> Lubricant), got {type(factory).__name__}")
    check_lubricant_contract(factory(), f"{where} ({name!r})")
    return factory


def _plugin_factory(obj: Any, entry_name: str) -> tuple[str, Callable[..., Lubricant]]:
    """An entry point's factory under the entry point's name (TypeError: skipped, with why)."""
    try:
        return entry_name, _checked_factory(obj, entry_name, "lubricant plug-in")
    except ParameterError as exc:
        raise TypeError(str(exc)) from None


LUBRICANTS = Registry("lubricant", _builtin_lubricants, group=ENTRY_POINT_GROUP,
                      convert=_plugin_factory, normalize=_normalize)
"""Lubricant name -> factory (keyword arguments override its defaults): the built-in oils and
grease, the plug-ins of :data:`ENTRY_POINT_GROUP` and the registered ones."""


def register_lubricant(name: str, factory: Callable[..., Lubricant], *,
                       replace: bool = False) -> None:
    """Make a lubricant known by name to assemblies, scenes and ``bearingsim list``.

    The factory is called once without arguments and its lubricant checked against the contract
    (:func:`check_lubricant_contract`), so that a lubricant missing, e.g., ``mu_bl`` is refused
    here.

    Parameters
    ----------
    name : str
        The name users give (matched ignoring case, spaces, hyphens and underscores).
    factory : callable
        Called with the user's keyword arguments (e.g. ``temperature=343.15``); returns a new
        :class:`Lubricant`.
    replace : bool
        Allow replacing a registered lubricant of the same name.

    Raises
    ------
    ParameterError
        For an empty name, a factory that is not callable or whose lubricant breaks the
        contract, or a name already registered (without ``replace``; a
        :class:`~bearingsim.registry.NameTakenError`).

    Examples
    --------
    >>> from bearingsim.physics.lubricant import Oil, register_lubricant, unregister_lubricant
    >>> register_lubricant("spindle oil 10", lambda **kw: Oil(10.0, 40.0, 2.7, 100.0,
    ...                    **{"name": "spindle oil 10", **kw}))
    >>> as_lubricant("Spindle-Oil 10").name
    'spindle oil 10'
    >>> unregister_lubricant("spindle oil 10")
    """
    if not isinstance(name, str) or not _normalize(name):
        raise ParameterError(f"register_lubricant: name must be a non-empty string, got {name!r}")
    LUBRICANTS.register(name, _checked_factory(factory, name, "register_lubricant"),
                        replace=replace)


def unregister_lubricant(name: str) -> None:
    """Remove a registered lubricant; a built-in (or plug-in) lubricant it replaced comes
    back.

    Parameters
    ----------
    name : str
        Name of a registered lubricant.

    Raises
    ------
    CatalogError
        For a name that is not registered (a built-in lubricant stays).
    """
    LUBRICANTS.unregister(name)


def known_lubricants() -> list[str]:
    """Names accepted by :func:`get_lubricant` (built in, plug-ins, registered).

    Returns
    -------
    list of str
        The names.
    """
    return list(LUBRICANTS)


def get_lubricant(name: str, **kwargs: Any) -> Lubricant:
    """A named lubricant from the registry: built in are ``"ISO VG 10"`` ... ``"ISO VG 460"``
    (mineral oils, oil bath) and ``"lithium grease"`` (ISO VG 100 base oil, one-third fill,
    thickener factor 2); more with :func:`register_lubricant`, the ``bearingsim.lubricants``
    entry-point group or a scene's ``[lubricants]`` table.

    Case, spaces, hyphens and underscores are ignored (``"iso_vg_68"``, ``"VG68"`` work).

    Parameters
    ----------
    name : str
        Lubricant name.
    **kwargs
        Constructor arguments that override the defaults (:class:`Oil` for the oils, e.g.
        ``temperature=343.15``; :class:`Grease` for the grease, e.g. ``fill_fraction=0.25`` or
        ``temperature=343.15``, the operating temperature of its base oil).

    Returns
    -------
    Lubricant
        A new object.

    Raises
    ------
    CatalogError
        For an unknown name; the message lists the known ones and the close matches.
    ParameterError
        When the registered factory returns something that breaks the contract.
    """
    lubricant = LUBRICANTS[name](**kwargs)
    if not isinstance(lubricant, Lubricant):
        raise ParameterError(f"lubricant {LUBRICANTS.find(name)!r}: its registered factory "
                             f"returned {type(lubricant).__name__}, not a Lubricant")
    return check_lubricant_contract(lubricant, f"lubricant {LUBRICANTS.find(name)!r}")


def as_lubricant(value: Lubricant | str, where: str = "lubricant") -> Lubricant:
    """The lubricant ``value`` stands for: a :class:`Lubricant` object (checked against the
    contract), a name through :func:`get_lubricant`.

    Parameters
    ----------
    value : Lubricant or str
        An object of any :class:`Lubricant` subclass, or a registered name.
    where : str
        The component or argument asking, named in the error.

    Returns
    -------
    Lubricant

    Raises
    ------
    CatalogError
        For an unknown name (listing the known ones).
    ParameterError
        For anything else, or an object that breaks the contract.
    """
    if isinstance(value, Lubricant):
        return check_lubricant_contract(value, where)
    if isinstance(value, str):
        return get_lubricant(value)
    raise ParameterError(f"{where}: a lubricant must be a Lubricant object (Oil, Grease, Dry, "
                         f"...) or one of the names {', '.join(known_lubricants())}; got "
                         f"{type(value).__name__} {value!r:.60}")
