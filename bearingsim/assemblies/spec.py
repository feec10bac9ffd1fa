"""What a scene needs to know about an assembly: its arguments, fidelity levels and outputs.

Each assembly module declares a ``SCENE_SPEC`` (an :class:`AssemblySpec`) beside its factory,
built from the module's own constants and the defaults of the factory's signature;
:data:`bearingsim.assemblies.SCENE_SPECS` lists them and :mod:`bearingsim.scenes` reads that list
(users add their own with :func:`bearingsim.scenes.register`, other distributions through the
``bearingsim.assemblies`` entry-point group, :mod:`bearingsim.assemblies.plugins`). A spec holds
a build function,
the arguments a scene may give (with their allowed values), the fidelity levels from lowest to
highest, a table *name pattern -> lowest fidelity that provides it* (used by
``fidelity = "auto"``), quantities computed after the integration (post-processing) and a
symmetry hook, and the plots that answer the assembly's question (:class:`AssemblyPlot`: ball
load against azimuth, modes by name, speed ratio against shaft speed), drawn beside the time
traces.

The table is conservative: a name that no pattern matches needs the assembly's highest automatic
fidelity.
"""

from __future__ import annotations

import fnmatch
import inspect
import json
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from bearingsim.errors import ParameterError
from bearingsim.validation import check_choice

__all__ = [
    "ARG_KINDS",
    "ArgSpec",
    "AssemblyPlot",
    "AssemblySpec",
    "PostQuantity",
    "FIDELITY_ERRORS_FILE",
    "declared_errors",
    "factory_default",
    "given_args",
    "nested_post",
    "single_level",
]

FIDELITY_ERRORS_FILE = Path(__file__).resolve().parent / "fidelity_errors.json"
"""Measured errors of the lower fidelity levels per quantity, written by
:mod:`bearingsim.studies.fidelity_errors` (never by hand)."""


def declared_errors(assembly: str) -> tuple[str | None, dict[str, dict[str, float]]]:
    """The reference level and the measured errors (level -> quantity pattern -> relative
    error [-]) of an assembly from :data:`FIDELITY_ERRORS_FILE`; ``(None, {})`` when it has
    none.

    Parameters
    ----------
    assembly : str
        The assembly's name.

    Returns
    -------
    tuple of (str or None, dict)
        Reference level and level -> quantity pattern -> relative error [-].
    """
    entry = json.loads(FIDELITY_ERRORS_FILE.read_text(encoding="utf-8")).get(assembly)
    if entry is None:
        return None, {}
    return entry["reference"], entry["errors"]

ARG_KINDS = ("bearing", "lubricant", "choice", "float", "bool", "table", "floats", "signal")
"""Kinds of scene arguments (see :class:`ArgSpec`)."""


@dataclass(frozen=True)
class ArgSpec:  # numpydoc ignore=PR02
    """One argument a scene may give to an assembly.

    Parameters
    ----------
    kind : str
        One of :data:`ARG_KINDS`: ``"bearing"`` (catalogue designation, written as the
        catalogue's look-up ``find`` reads it), ``"lubricant"`` (name,
        or a list of one name per layer), ``"choice"`` (one of ``choices``), ``"float"`` (a
        number, optionally > ``low``), ``"bool"``, ``"table"`` (a TOML table validated by the
        specs in ``table``), ``"floats"`` (a table of named numbers) or ``"signal"`` (a number
        or an expression of ``t``, see :mod:`bearingsim.scenes.expressions`; the build function
        gets a number or a function ``f(t)``).
    default : object
        Value when the scene does not give the argument (None: the factory's own default).
    doc : str
        One line for ``bearingsim list`` and error messages, with the unit.
    choices : tuple
        Allowed values of a ``"choice"``.
    low, high : float, optional
        Bounds of a ``"float"`` [its unit]: ``low`` exclusive unless ``low_inclusive``, ``high``
        inclusive.
    table : dict of str to ArgSpec, optional
        Entries of a ``"table"``.
    low_inclusive : bool
        Whether ``low`` itself is allowed (an oil level of 0, a clearance of 0).
    find : callable, optional
        Of a ``"bearing"``: the catalogue's look-up, a designation as written -> the
        designation as the catalogue spells it, or None when it knows none (default: the ball
        bearing catalogue with the registered bearings,
        :meth:`bearingsim.catalog.BEARINGS.find <bearingsim.registry.Registry.find>`).
    known : callable, optional
        Of a ``"bearing"`` from another catalogue than the ball bearings': its designations
        when a message lists them, the registered ones included (default: the ball
        bearings', :func:`bearingsim.catalog.list_bearings`).

    Raises
    ------
    ParameterError
        For an unknown kind, a choice without choices or a table without entries.
    """

    kind: str
    default: Any = None
    doc: str = ""
    choices: tuple = ()
    low: float | None = None
    table: dict[str, ArgSpec] | None = None
    high: float | None = None
    low_inclusive: bool = False
    find: Callable[[Any], str | None] | None = None
    known: Callable[[], list[str]] | None = None

    @property
    def unit(self) -> str:
        """The SI unit of a ``"float"`` argument [model notation]: the first one in brackets in
        :attr:`doc` (``"axial preload [N]"``), ``"1"`` for a dimensionless number (none or
        ``[-]``).

        Returns
        -------
        str
            The unit.
        """
        stated = re.search(r"\[([^\]]+)\]", self.doc)
        return stated.group(1) if stated and stated.group(1) != "-" else "1"

    @property
    def allowed(self) -> str:
        """What the argument takes, for ``bearingsim list`` (``"one of DF, DB, DT"``,
        ``"a number in m, or with a unit, >= 0"``).

        Returns
        -------
        str
            The text.
        """
        if self.kind == "bearing":
            return "a designation (any letter case; bearingsim list bearings)"
        if self.kind == "lubricant":
            return "a lubricant name (bearingsim list lubricants)"
        if self.kind == "choice":
            return "one of " + ", ".join(map(str, self.choices))
        if self.kind == "bool":
            return "true or false"
        if self.kind in ("table", "floats"):
            return ("a table of " + ", ".join(self.table) if self.table
                    else "a table of named numbers")
        unit = "" if self.unit == "1" else f" in {self.unit} (or with a unit)"
        text = f"a number{unit}" + (" or an expression of t" if self.kind == "signal" else "")
        if self.low is not None and self.high is not None:
            return f"{text}, {self.low:g} to {self.high:g}"
        if self.low is not None:
            return f"{text}, {'>=' if self.low_inclusive else '>'} {self.low:g}"
        return text

    def designation(self, name: Any) -> str | None:
        """A ``"bearing"`` argument's value as its catalogue spells it (``"7020c"`` ->
        ``"7020C"``, ``"NU 206"`` -> ``"NU206"``), or None when the catalogue knows none.

        Parameters
        ----------
        name : object
            The value as written: text, or a whole number as TOML reads ``inner = 61905``
            (anything else stands for none).

        Returns
        -------
        str or None
            The designation, or None.
        """
        from bearingsim.catalog import BEARINGS  # on use: a spec is read without the catalogue

        if isinstance(name, int) and not isinstance(name, bool):  # 61905 written unquoted
            name = str(name)
        return (self.find or BEARINGS.find)(name) if isinstance(name, str) else None

    def __post_init__(self) -> None:
        check_choice(self.kind, "kind", ARG_KINDS, "ArgSpec")
        if self.kind == "choice" and not self.choices:
            raise ParameterError("ArgSpec: a 'choice' argument needs its choices")
        if self.kind == "table" and not self.table:
            raise ParameterError("ArgSpec: a 'table' argument needs its entries (table=...)")


@dataclass(frozen=True)
class PostQuantity:
    """A quantity computed from the saved series after the integration.

    ``needs`` are model variables the computation reads (added to the assembled outputs);
    ``compute(series)`` gets a dict name -> array (at least ``needs``) and returns an array in
    ``unit``. ``fidelity`` is the lowest level whose model has every name in ``needs``.
    """

    name: str
    unit: str
    doc: str
    needs: tuple[str, ...]
    compute: Callable[[dict[str, np.ndarray]], np.ndarray]
    fidelity: str


@dataclass(frozen=True)
class AssemblyPlot:
    """A figure an assembly draws for its scenes beside the time traces.

    ``needs`` are model variables the figure reads (kept by the pruning, not written to the
    CSV); ``make(prep, result, series)`` gets the prepared scene
    (:class:`bearingsim.scenes.preparation.Prepared`), the :class:`~bearingsim.simulation.Result`
    and a dict name -> array of the requested outputs and ``needs``, and returns a
    :class:`bearingsim.plotting.FigureSpec` (values in SI; the figure shows them in engineering
    units) or None when the run does not allow it (e.g. no load).
    """

    name: str
    needs: tuple[str, ...]
    make: Callable[[Any, Any, dict[str, np.ndarray]], Any]


def _no_post(args: dict[str, Any]) -> dict[str, PostQuantity]:
    return {}


def _no_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    return []


def _no_symmetry(args: dict[str, Any], inputs: dict[str, Any]) -> list[str]:
    return []


def _no_symmetric_args(args: dict[str, Any], inputs: dict[str, Any]) -> dict[str, Any]:
    return {}


@dataclass
class AssemblySpec:
    """What the scene layer knows about an assembly.

    Raises
    ------
    ParameterError
        When ``auto_fidelities`` or the levels of ``output_fidelity`` are not in
        ``fidelities``.
    """

    name: str
    description: str
    build: Callable[[dict[str, Any], str], Any]
    """``build(args, fidelity) -> Component``; ``args`` has every key of ``args`` (defaults
    filled in), signal arguments as a number or ``f(t)``."""
    args: dict[str, ArgSpec]
    fidelities: tuple[str, ...]
    """All levels, lowest first."""
    auto_fidelities: tuple[str, ...]
    """Levels ``auto`` may choose, lowest first."""
    output_fidelity: list[tuple[str, str]]
    """(fnmatch pattern of an output, input or parameter name, lowest fidelity providing it)."""
    default_outputs: list[str]
    post: Callable[[dict[str, Any]], dict[str, PostQuantity]] = _no_post
    """Post-processed quantities for the given arguments."""
    parametric_args: dict[str, Callable[[dict[str, Any]], bool]] = field(default_factory=dict)
    """Arguments that only change parameter values (for sweeps without re-assembly), with a
    predicate on the other arguments that says when this holds."""
    symmetry: Callable[[dict[str, Any], dict[str, Any]], list[str]] = _no_symmetry
    """``symmetry(args, inputs)`` -> notes on symmetric parts solved once."""
    symmetric_args: Callable[[dict[str, Any], dict[str, Any]], dict[str, Any]] = (
        _no_symmetric_args)
    """``symmetric_args(args, inputs)`` -> assembly arguments that build the reduced model the
    loads allow (merged into the arguments before building)."""
    fidelity_arg: str | None = "fidelity"
    """None for an assembly with a single level (scenes then give no fidelity)."""
    level_errors: dict[str, dict[str, float]] = field(default_factory=dict)
    """Level -> output name pattern -> measured relative error [-] of that level's value
    against the same quantity at ``reference_fidelity`` (:func:`declared_errors`). A level
    below the reference that provides a quantity the reference also answers declares it here;
    ``auto`` never picks a level whose error exceeds the scene's tolerance."""
    reference_fidelity: str | None = None
    """The level the errors are measured against."""
    optional_inputs: tuple[str, ...] = ()
    """fnmatch patterns of the inputs a scene may leave out (they keep their start value, e.g.
    a load of 0); every other input of the assembled model must be given, so that a forgotten
    shaft speed is an error, not a run at 0."""
    plots: Callable[[dict[str, Any], str], list[AssemblyPlot]] = _no_plots
    """``plots(args, fidelity)`` -> the figures that answer the assembly's question at that
    level (:class:`AssemblyPlot`; their ``needs`` must be variables of that level's model)."""
    undefined_at_rest: dict[str, str] = field(default_factory=dict)
    """Output name pattern -> why that output has no value while the input ``shaft_speed`` is
    held at 0 (``Rs = w_middle / w_shaft`` is 0/0 at rest): a scene that asks for it with the
    speed constant 0 is refused, rather than reporting the model's regularized value as an
    answer (:func:`~bearingsim.scenes.scene_input_checks.rest_problems`)."""
    mode_names: dict[str, str] = field(default_factory=dict)
    """State name -> mode name ("radial x", ...) of the modes named after their dominant degree
    of freedom in a ``modes`` scene; other modes are named after the description of that
    state."""

    def is_optional_input(self, name: str) -> bool:
        """Whether a scene may leave the input ``name`` out.

        Parameters
        ----------
        name : str
            Input name.

        Returns
        -------
        bool
            True when the input is optional.
        """
        return any(fnmatch.fnmatchcase(name, p) for p in self.optional_inputs)

    def __post_init__(self) -> None:
        where = f"AssemblySpec({self.name!r})"
        levels = (*self.auto_fidelities, *(fid for _, fid in self.output_fidelity))
        for level in levels:
            check_choice(level, "fidelity level", self.fidelities, where)

    def with_defaults(self, args: dict[str, Any]) -> dict[str, Any]:
        """The arguments with the defaults of the ones not given (nested tables too).

        Parameters
        ----------
        args : dict
            The arguments a scene gives, by name.

        Returns
        -------
        dict
            Every argument of the spec, by name.
        """
        return _defaults(self.args, args)

    def level_error(self, level: str, name: str) -> float | None:
        """Declared relative error [-] of ``name`` at ``level`` against the reference level
        (None: not declared, i.e. the level is the only one or the reference for it).

        Parameters
        ----------
        level : str
            Fidelity level.
        name : str
            Output name.

        Returns
        -------
        float or None
            Relative error [-], >= 0, or None.
        """
        for pattern, error in self.level_errors.get(level, {}).items():
            if fnmatch.fnmatchcase(name, pattern):
                return float(error)
        return None

    def min_fidelity(self, name: str) -> str:
        """Lowest fidelity that provides ``name`` (an output, input or parameter name).

        Parameters
        ----------
        name : str
            Output, input or parameter name.

        Returns
        -------
        str
            The fidelity level.
        """
        for pattern, fid in self.output_fidelity:
            if fnmatch.fnmatchcase(name, pattern):
                return fid
        return self.auto_fidelities[-1]


def _defaults(specs: dict[str, ArgSpec], args: dict[str, Any]) -> dict[str, Any]:
    out = {}
    for key, spec in specs.items():
        if key in args:
            val = args[key]
            if spec.kind == "table" and isinstance(val, dict):
                val = _defaults(spec.table or {}, val)
            out[key] = val
        elif spec.kind == "table":
            out[key] = _defaults(spec.table or {}, {})
        else:
            out[key] = spec.default
    return out


def factory_default(factory: Callable, name: str) -> Any:
    """The default value of the parameter ``name`` in the signature of ``factory``.

    Lets a spec take its defaults from the factory instead of repeating them.

    Parameters
    ----------
    factory : callable
        The factory function or class.
    name : str
        Name of one of its parameters.

    Returns
    -------
    object
        The parameter's default value.

    Raises
    ------
    ParameterError
        When ``factory`` has no parameter ``name`` with a default.
    """
    parameter = inspect.signature(factory).parameters.get(name)
    if parameter is None or parameter.default is inspect.Parameter.empty:
        raise ParameterError(f"factory_default: {factory.__qualname__} has no parameter "
                             f"{name!r} with a default")
    return parameter.default


def given_args(args: dict[str, Any] | None, leave_out: tuple[str, ...] = ()) -> dict[str, Any]:
    """The arguments a build passes on as keywords: those with a value (an argument left at
    None takes the factory's own default), less ``leave_out``.

    Parameters
    ----------
    args : dict or None
        Arguments by name (None: none).
    leave_out : tuple of str
        Names the build handles itself.

    Returns
    -------
    dict
        The arguments whose value is not None.
    """
    return {k: v for k, v in (args or {}).items() if v is not None and k not in leave_out}


def single_level(level: str) -> dict[str, Any]:
    """The :class:`AssemblySpec` keywords of an assembly with one fidelity level: ``auto``
    picks it, every name is provided by it and scenes give no fidelity.

    Parameters
    ----------
    level : str
        The level's name, e.g. ``"quasi-static"``.

    Returns
    -------
    dict
        ``fidelities``, ``auto_fidelities``, ``output_fidelity`` and ``fidelity_arg``.
    """
    return {"fidelities": (level,), "auto_fidelities": (level,), "output_fidelity": [],
            "fidelity_arg": None}


def nested_post(quantities: dict[str, PostQuantity], prefix: str) -> dict[str, PostQuantity]:
    """Post-processed quantities of a sub-assembly, named as seen from its parent.

    Parameters
    ----------
    quantities : dict of str to PostQuantity
        The sub-assembly's quantities (its spec's ``post(args)``).
    prefix : str
        The sub-assembly's path in the parent with a trailing dot, e.g. ``"bearing."``.

    Returns
    -------
    dict of str to PostQuantity
        The same quantities with ``prefix`` on their names and on the names they need.
    """
    out = {}
    for q in quantities.values():
        def compute(series, q=q):
            return q.compute({n: series[prefix + n] for n in q.needs})

        out[prefix + q.name] = PostQuantity(prefix + q.name, q.unit, q.doc,
                                            tuple(prefix + n for n in q.needs), compute,
                                            q.fidelity)
    return out
