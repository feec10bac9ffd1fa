"""The assembled system: compiled functions plus the names, units and defaults around them."""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler.dae import Param
from bearingsim.assembler.mapped_forms import MappedForms
from bearingsim.assembler.numeric import buffered
from bearingsim.entry_points import value_key
from bearingsim.errors import ParameterError
from bearingsim.language.component import Component
from bearingsim.units import to_si, unit_label
from bearingsim.validation import check_mapping, check_quantity

__all__ = ["Signal", "FunctionTable", "System", "as_system"]


class FunctionTable(Mapping):
    """A system's CasADi functions by name; the expensive ones (the inlined right-hand side,
    observed and output functions and their Jacobians) are built on first access, so that runs
    which never read them (the SUNDIALS kernels map one function per ball and differentiate
    that) do not pay for them.

    Parameters
    ----------
    ready : dict
        Functions built already, by name.
    pending : dict
        Name -> a callable without arguments that builds the function.
    """

    def __init__(self, ready: dict[str, ca.Function],
                 pending: dict[str, Callable[[], ca.Function]] | None = None):
        self._ready = dict(ready)
        self._pending = dict(pending or {})

    def __getitem__(self, key: str) -> ca.Function:
        if key not in self._ready:
            build = self._pending.pop(key, None)
            if build is None:
                raise KeyError(key)
            self._ready[key] = build()
        return self._ready[key]

    def __iter__(self) -> Iterator[str]:
        return iter([*self._ready, *self._pending])

    def __len__(self) -> int:
        return len(self._ready) + len(self._pending)

    def __contains__(self, key: object) -> bool:
        return key in self._ready or key in self._pending  # without building it

    def built(self, key: str) -> bool:
        """Whether ``key`` has been built (every key is available either way).

        Parameters
        ----------
        key : str
            Function name.

        Returns
        -------
        bool
            Whether it is built.
        """
        return key in self._ready


@dataclass(frozen=True)
class Signal:
    """Name, unit, description and start value of a state, input or output."""

    name: str
    unit: str
    description: str = ""
    start: float = 0.0
    fixed: bool = True
    nominal: float | None = None
    """Typical magnitude, for tolerance scaling (None: unknown)."""
    low: float | None = None
    """Smallest valid value (inputs), None: unbounded."""
    high: float | None = None
    """Largest valid value (inputs), None: unbounded."""
    required: bool = False
    """An input every run must give (a shaft speed: never held at its start value)."""
    warn_above: float | None = None
    """Input magnitude above which a run warns (a bearing's limiting speed)."""
    limit: str | None = None
    """What ``warn_above`` is: a key of :data:`~bearingsim.input_limits.INPUT_LIMITS`."""


@dataclass
class System:
    """An assembled model, ready for ``simulate``, ``linearize`` and FMU export.

    The ODE is ``dx/dt = ode(t, x, u, p)``; every CasADi function takes ``(t, x, u, p)``:

    * ``ode`` -> state derivatives; ``jac_x``, ``jac_u`` -> their exact sparse Jacobians;
    * ``output`` -> the requested outputs; ``out_jac_x``, ``out_jac_u`` -> their Jacobians;
    * ``observe`` -> every variable of the model (``observed_names``), aliases included.

    Parameters are function arguments, so new parameter values need no recompilation.
    """

    name: str
    states: list[Signal]
    inputs: list[Signal]
    outputs: list[Signal]
    params: list[Param]
    functions: Mapping[str, ca.Function]
    observed_names: list[str]
    observed_units: dict[str, str] = field(default_factory=dict)
    observed_descriptions: dict[str, str] = field(default_factory=dict)
    symbolic_functions: Mapping[str, ca.Function] | None = None
    """The symbolic originals when ``functions`` are compiled (CasADi's integrators need them)."""
    init_residual: ca.Function | None = None
    free_initial_states: list[int] = field(default_factory=list)
    timings: list[tuple[str, float]] = field(default_factory=list)
    report: dict[str, Any] = field(default_factory=dict)
    skipped: list[str] = field(default_factory=list)
    rootfinder: str | None = None
    """CasADi plugin of the nonlinear blocks (``None``: the model has none)."""
    mapped: MappedForms | None = None
    """The kernels with one function per ball mapped over each row (``None``: the model has
    no ball sets); the SUNDIALS kernels use them."""
    requested_outputs: list[str] | None = None
    """The outputs ``assemble`` was asked for (None: all variables kept)."""
    content_key: str | None = None
    """SHA-256 (hex) of the bytes the system was loaded from
    (:func:`~bearingsim.assembler.cache.loads_system`), which determine its functions; None for
    a system assembled in this process. Kernel libraries are remembered by it
    (:mod:`bearingsim.simulation.kernel_names`)."""

    # ---------------------------------------------------------------- names
    @functools.cached_property
    def _layout(self) -> _Layout:
        """Names, indices and default vectors, gathered on first use (a system is not changed
        after assembly; every public accessor hands out copies)."""
        return _Layout(self)

    @property
    def state_names(self) -> list[str]:
        """Dotted names of the states, in vector order.

        Returns
        -------
        list of str
            The names (a new list).
        """
        return list(self._layout.state_names)

    @property
    def input_names(self) -> list[str]:
        """Dotted names of the inputs, in vector order.

        Returns
        -------
        list of str
            The names (a new list).
        """
        return list(self._layout.input_names)

    @property
    def output_names(self) -> list[str]:
        """Dotted names of the requested outputs, in vector order.

        Returns
        -------
        list of str
            The names (a new list).
        """
        return [s.name for s in self.outputs]

    @property
    def parameter_names(self) -> list[str]:
        """Dotted names of the free parameters, in vector order.

        Returns
        -------
        list of str
            The names (a new list).
        """
        return list(self._layout.parameter_names)

    @property
    def input_ranges(self) -> tuple[tuple[float | None, float | None], ...]:
        """The valid range ``(low, high)`` of every input, in vector order (None: unbounded).

        Returns
        -------
        tuple of (float or None, float or None)
            The ranges.
        """
        return self._layout.input_ranges

    @property
    def n_states(self) -> int:
        """Number of states.

        Returns
        -------
        int
            The number of states.
        """
        return len(self.states)

    # ---------------------------------------------------------------- vectors
    def x0(self, overrides: dict[str, float] | None = None) -> np.ndarray:
        """Start values of the states, with optional overrides by name.

        Parameters
        ----------
        overrides : dict of str to float, optional
            Start values by state name: numbers in SI units, or with a unit (``"100 rpm"``,
            a :class:`pint.Quantity`).

        Returns
        -------
        ndarray
            The start values (a new array).
        """
        layout = self._layout
        x = layout.x_start.copy()
        overrides = check_mapping(overrides, "x0", self.name, "state names")
        if not overrides:
            return x
        index = layout.state_index
        values = np.array([_plain_float(v) for v in overrides.values()])
        if np.all(np.isfinite(values)) and all(name in index for name in overrides):
            x[[index[name] for name in overrides]] = values  # every override a finite number
            return x
        for name, val in overrides.items():
            k = index.get(name)
            if k is None:
                raise ParameterError(
                    f"initial value given for {name!r}, which is not a state; states: "
                    + ", ".join(index)
                )
            x[k] = float(check_quantity(val, name, self.states[k].unit,
                                        where=f"{self.name}: initial value"))
        return x

    def p0(self, overrides: dict[str, float] | None = None) -> np.ndarray:
        """Parameter vector: defaults, then validated overrides by dotted name (a number in
        the parameter's SI unit, or with a unit: ``"25 µm"``, a :class:`pint.Quantity`).

        Parameters
        ----------
        overrides : dict, optional
            Parameter values by dotted name.

        Returns
        -------
        ndarray
            The parameter vector (SI units; a new array).
        """
        layout = self._layout
        p = layout.p_default.copy()
        for name, val in check_mapping(overrides, "parameters", self.name,
                                       "parameter names").items():
            key = value_key(val)
            found = None if key is None else layout.validated.get((name, key))
            if found is None:
                found = self._validated(name, val)
                if key is not None:
                    if len(layout.validated) >= VALIDATED_PER_SYSTEM:
                        del layout.validated[next(iter(layout.validated))]
                    layout.validated[(name, key)] = found
            p[found[0]] = found[1]
        return p

    def _validated(self, name: str, value: Any) -> tuple[int, float]:
        """The position of parameter ``name`` and ``value`` in its SI unit, checked against
        its declaration (:meth:`p0` without the memory)."""
        k = self._layout.parameter_index.get(name)
        if k is None:
            import difflib

            close = difflib.get_close_matches(name, self._layout.parameter_names, n=5)
            hint = f"; did you mean {', '.join(close)}?" if close else ""
            raise ParameterError(f"{self.name}: unknown parameter {name!r}{hint}")
        decl = self.params[k].declaration
        value = to_si(value, self.params[k].unit, f"{self.name}: parameter {name}")
        return k, decl.validate(value) if decl is not None else float(value)

    def u_default(self) -> np.ndarray:
        """Default input values.

        Returns
        -------
        ndarray
            The input vector (SI units; a new array).
        """
        return self._layout.u_start.copy()

    # ---------------------------------------------------------------- evaluation
    def rhs(self, t: float, x, u=None, p=None) -> np.ndarray:
        """State derivatives at one point (numbers).

        Parameters
        ----------
        t : float
            Time [s].
        x : array_like
            State vector, in :attr:`state_names` order (SI units).
        u : array_like, optional
            Input vector, in :attr:`input_names` order (None: :meth:`u_default`).
        p : array_like, optional
            Parameter vector, in :attr:`parameter_names` order (None: :meth:`p0`).

        Returns
        -------
        ndarray
            d x/dt (SI units per second).
        """
        u = self.u_default() if u is None else u
        p = self.p0() if p is None else p
        return np.asarray(self.functions["ode"](t, x, u, p), dtype=float).ravel()

    def observe(self, t: float, x, u=None, p=None) -> dict[str, float]:
        """Every variable of the model at one point, by dotted name.

        Parameters
        ----------
        t : float
            Time [s].
        x : array_like
            State vector, in :attr:`state_names` order (SI units).
        u : array_like, optional
            Input vector, in :attr:`input_names` order (None: :meth:`u_default`).
        p : array_like, optional
            Parameter vector, in :attr:`parameter_names` order (None: :meth:`p0`).

        Returns
        -------
        dict of str to float
            Values (SI units) by dotted name.
        """
        u = self.u_default() if u is None else u
        p = self.p0() if p is None else p
        vals = buffered(self.functions["observe"])(t, x, u, p)[0].ravel()
        return dict(zip(self.observed_names, vals, strict=True))

    @property
    def variable_units(self) -> dict[str, str]:
        """Unit of every observed variable, state, input and output, by dotted name (a new
        dict, copied from one built on first use).

        Returns
        -------
        dict of str to str
            Unit by dotted name.
        """
        units = self.__dict__.get("_variable_units")
        if units is None:
            units = dict(self.observed_units)
            units.update({s.name: s.unit for s in self.states + self.inputs + self.outputs})
            self.__dict__["_variable_units"] = units
        return dict(units)

    def __repr__(self) -> str:
        shown = ", ".join(f"{sig.name} [{unit_label(sig.unit)}]" for sig in self.inputs[:4])
        shown += ", ..." if len(self.inputs) > 4 else ""
        return (f"<System {self.name}: {self.n_states} states, {len(self.inputs)} inputs"
                + (f" ({shown})" if shown else "")
                + f", {len(self.outputs)} outputs, {len(self.params)} parameters; "
                f".describe() for the details>")

    def describe(self) -> str:
        """A short text summary: sizes, pass timings and skipped parts.

        Returns
        -------
        str
            The summary.
        """
        lines = [
            f"system {self.name}: {self.n_states} states, {len(self.inputs)} inputs, "
            f"{len(self.outputs)} outputs, {len(self.params)} parameters"
        ]
        for key, val in self.report.items():
            lines.append(f"  {key}: {val}")
        for name, dt in self.timings:
            lines.append(f"  pass {name:<26s} {dt * 1e3:9.2f} ms")
        for s in self.skipped:
            lines.append(f"  skipped: {s}")
        return "\n".join(lines)


class _Layout:
    """What a system's names and default vectors give once (:attr:`System._layout`): name
    tuples, the index of each state and parameter name, and the start, default parameter and
    default input vectors (read-only arrays; callers get copies)."""

    def __init__(self, system: System):
        self.state_names = tuple(s.name for s in system.states)
        self.input_names = tuple(s.name for s in system.inputs)
        self.parameter_names = tuple(q.name for q in system.params)
        self.input_ranges = tuple((s.low, s.high) for s in system.inputs)
        self.state_index = {name: k for k, name in enumerate(self.state_names)}
        self.parameter_index: dict[str, int] = {}
        for k, name in enumerate(self.parameter_names):
            self.parameter_index.setdefault(name, k)
        self.x_start = _frozen([s.start for s in system.states])
        self.p_default = _frozen([q.value for q in system.params])
        self.u_start = _frozen([s.start for s in system.inputs])
        self.validated: dict[tuple[str, tuple], tuple[int, float]] = {}
        """Parameter values checked by :meth:`System.p0`: (name, value key) -> (position,
        SI value)."""


VALIDATED_PER_SYSTEM = 1024
"""Parameter values whose check a system remembers (the oldest are forgotten first)."""


def _frozen(values: list[float]) -> np.ndarray:
    """``values`` as a read-only float array."""
    array = np.array(values, dtype=float)
    array.flags.writeable = False
    return array


def _plain_float(value: Any) -> float:
    """``value`` as a float when it is a real number (not a bool), else NaN (which sends it
    through the full check with its error message)."""
    if isinstance(value, (float, int, np.floating, np.integer)) and not isinstance(
            value, (bool, np.bool_)):
        return float(value)
    return float("nan")


def as_system(value: Any, where: str) -> System:
    """An assembled :class:`System`, else a named error (a component that still needs
    assembling says so).

    Parameters
    ----------
    value : object
        The value to check.
    where : str
        The function, for the message.

    Returns
    -------
    System
        ``value``.

    Raises
    ------
    ParameterError
        For anything that is not a System.
    """
    if isinstance(value, System):
        return value
    if isinstance(value, Component):
        raise ParameterError(f"{where}: got the component {value.display_name!r}, which is not "
                             f"assembled yet; pass assemble({type(value).__name__}(...)) "
                             f"(bearingsim.assembler.assemble)")
    raise ParameterError(f"{where}: expected an assembled System (from "
                         f"bearingsim.assembler.assemble), got {type(value).__name__}")
