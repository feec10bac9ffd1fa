"""Simulation results: named series, CSV/NPZ export, pandas and xarray views, plots."""

from __future__ import annotations

import functools
import html
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from bearingsim.checks import checked
from bearingsim.errors import ParameterError
from bearingsim.files import atomic_path, file_path
from bearingsim.plotting import keep_tight_layout, wrapped_label
from bearingsim.series_csv import write_series_csv
from bearingsim.units import describe, display_label, engineering, to_display
from bearingsim.units.registry import UnitError, si_factor, si_label

__all__ = ["Result", "ResultLayout"]


@dataclass(frozen=True)
class ResultLayout:
    """What every result of one system shares: the observed variables' names, the units and
    descriptions by name, the variables shown first, and the row of each name. Never changed
    (a :class:`Result` hands out copies).

    Attributes
    ----------
    names : tuple of str
        Dotted names of the observed variables, in row order.
    units : dict
        Unit of each variable by name.
    descriptions : dict
        What each variable is, by name.
    outputs : tuple of str
        The variables asked for (see :attr:`Result.outputs`).
    input_names, parameter_names : tuple of str
        The system's inputs and parameters, in vector order.
    index : dict
        Row of each name.
    """

    names: tuple[str, ...]
    units: dict[str, str]
    descriptions: dict[str, str]
    outputs: tuple[str, ...]
    input_names: tuple[str, ...]
    parameter_names: tuple[str, ...]
    index: dict[str, int] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "index", {name: k for k, name in enumerate(self.names)})


_MADE_ON_FIRST_READ = {"names": list, "units": dict, "descriptions": dict, "outputs": list,
                       "inputs": dict, "parameters": dict}
"""The fields a result of :meth:`Result.of_run` makes on first read (the first four copied
from its layout)."""


@dataclass
class Result:
    """Time series of every observed variable of a run.

    ``res["Rs"]`` is the series of one variable (SI), ``res[["Rs", "w_middle"]]`` a
    :class:`Result` with those variables only, ``res.t`` the time points [s];
    :meth:`to_pandas` and :meth:`to_xarray` give the same as a table with plain variable names
    and the units beside them.

    Attributes
    ----------
    t : ndarray
        Output times [s].
    names : list of str
        Dotted names of the observed variables.
    values : ndarray
        Shape (len(names), len(t)), in SI units.
    units : dict
        Unit of each variable by name.
    stats : dict
        Integrator statistics (method, counts, wall time).
    inputs : dict
        Value of every system input at the last output time ``t[-1]``, by name, in the
        input's unit (what the run's constants, time functions or tables gave there). Empty
        for a result not made by :func:`~bearingsim.simulation.simulate`.
    parameters : dict
        The parameter values of the run (defaults and the run's overrides), by dotted name.
        Empty for a result not made by :func:`~bearingsim.simulation.simulate`.
    descriptions : dict
        What each variable is (``"middle ring speed"``), by name: the labels of plots.
    outputs : list of str
        The variables asked for (the outputs the system was assembled for, else the
        assembly's own variables), shown first and alone by :meth:`to_pandas`,
        :meth:`to_xarray` and :meth:`plot` unless ``internal=True``; empty: all.

    A result of :func:`~bearingsim.simulation.simulate` (:meth:`of_run`) makes its
    ``names``, ``units``, ``descriptions``, ``outputs``, ``inputs`` and ``parameters`` when
    they are first read, from what every run of its system shares (:class:`ResultLayout`) and
    the run's own numbers: a run whose result is not read, as a sweep point, does not copy a
    thousand names; each is the result's own, so a result changed by its user changes no
    other result.
    """

    t: np.ndarray
    names: list[str]
    values: np.ndarray
    units: dict[str, str] = field(default_factory=dict)
    stats: dict[str, object] = field(default_factory=dict)
    inputs: dict[str, float] = field(default_factory=dict)
    parameters: dict[str, float] = field(default_factory=dict)
    descriptions: dict[str, str] = field(default_factory=dict)
    outputs: list[str] = field(default_factory=list)

    @classmethod
    def of_run(cls, t: np.ndarray, values: np.ndarray, layout: ResultLayout,
               stats: dict[str, object], u_end: np.ndarray, p: np.ndarray) -> Result:
        """The result of a run, its names, units, descriptions, outputs, inputs and
        parameters made when first read (from ``layout``, ``u_end`` and ``p``).

        Parameters
        ----------
        t : numpy.ndarray
            Output times [s].
        values : numpy.ndarray
            Shape (len(layout.names), len(t)), in SI units.
        layout : ResultLayout
            The system's names, units, descriptions and outputs (never changed).
        stats : dict
            Integrator statistics.
        u_end : numpy.ndarray
            Every input at ``t[-1]``, in the order of ``layout.input_names`` (not changed
            later).
        p : numpy.ndarray
            The run's parameter vector, in the order of ``layout.parameter_names`` (not
            changed later).

        Returns
        -------
        Result
            The result.
        """
        result = cls.__new__(cls)
        result.__dict__.update(t=t, values=values, stats=stats, _layout=layout,
                               _run_vectors={"inputs": u_end, "parameters": p})
        return result

    def __getattr__(self, name: str):
        """A field of a result of :meth:`of_run` not read before, made now (called only for
        attributes the result does not hold)."""
        layout = self.__dict__.get("_layout")
        if layout is None or name not in _MADE_ON_FIRST_READ:
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        if name in ("inputs", "parameters"):
            names = layout.input_names if name == "inputs" else layout.parameter_names
            value = dict(zip(names, self.__dict__["_run_vectors"][name].tolist(), strict=True))
        else:
            value = _MADE_ON_FIRST_READ[name](getattr(layout, name))
        self.__dict__[name] = value
        return value

    @functools.cached_property
    def _index(self) -> dict[str, int]:
        """Row of each variable by name (built on first use: a run that is only looked at
        once, or not at all, as a sweep point, does not pay for it; a result of
        :meth:`of_run` whose names were never read uses its layout's)."""
        layout = self.__dict__.get("_layout")
        if layout is not None and "names" not in self.__dict__:
            return layout.index
        return {name: k for k, name in enumerate(self.names)}

    def _series(self, name: str) -> np.ndarray:
        if name in ("t", "time"):
            return self.t
        if not isinstance(name, str):
            raise ParameterError(f"Result: a variable is named by text, got {name!r:.60}")
        try:
            return self.values[self._index[name]]
        except KeyError:
            import difflib

            close = difflib.get_close_matches(name, self.names, n=5)
            shown = ", ".join(self.names[:8]) + (", ..." if len(self.names) > 8 else "")
            hint = (f"; did you mean {', '.join(close)}?" if close else
                    f"; its variables are {shown} ({len(self.names)} in all, Result.names)")
            raise KeyError(f"no variable {name!r} in the result{hint}") from None

    def __getitem__(self, key: str | Sequence[str]):
        """``res["Rs"]``: the series (SI); ``res[["Rs", "w_middle"]]``: a :class:`Result` with
        those variables, in that order."""
        if isinstance(key, str):
            return self._series(key)
        names = self._names(key, "Result[...]")
        return Result(self.t, names, np.array([self._series(n) for n in names]).reshape(
            len(names), self.t.size), {n: self.units.get(n, "1") for n in names}, self.stats,
            self.inputs, self.parameters, {n: self.descriptions.get(n, "") for n in names},
            [n for n in names if n in self.outputs])

    def __contains__(self, name: str) -> bool:
        return name in self._index

    def _names(self, names, where: str) -> list[str]:
        """Checked variable names: one name (text) or a list of them, each in the result."""
        if isinstance(names, str):
            names = [names]
        try:
            names = list(names)
        except TypeError:
            raise ParameterError(f"{where}: expected a variable name or a list of them, got "
                                 f"{names!r:.60}") from None
        for n in names:
            self._series(n)  # KeyError with close matches, ParameterError for non-text
        return names

    def columns(self, internal: bool = False) -> list[str]:
        """The variables of the tables: the requested outputs first, then (``internal=True``)
        every other observed variable.

        Parameters
        ----------
        internal : bool
            Also the variables inside the components (connector torques, derivatives...).

        Returns
        -------
        list of str
        """
        first = [n for n in self.outputs if n in self._index] or list(self.names)
        if not internal:
            return first
        return first + [n for n in self.names if n not in set(first)]

    @checked
    def final(self, name: str, unit: str | None = None) -> float:
        """Value at the last time point, in SI or in ``unit``.

        Parameters
        ----------
        name : str
            A variable's dotted name.
        unit : str, optional
            A unit of the variable's quantity to give the value in (``"rpm"`` for a speed,
            ``"N mm"`` for a torque); None: its SI unit (:attr:`units`).

        Returns
        -------
        float
            Its last value, in SI or in ``unit``.

        Raises
        ------
        UnitError
            For a unit of another quantity, naming the variable and its SI unit.

        Examples
        --------
        >>> res.final("w_shaft", "rpm")  # doctest: +SKIP
        5000.0
        """
        if not isinstance(name, str):
            raise ParameterError(f"Result.final: expected a variable name, got {name!r:.60}")
        value = float(self[name][-1])
        if unit is None:
            return value
        si_unit = self.units.get(name, "1")
        try:
            factor, offset = si_factor(unit, si_unit)
        except UnitError as exc:
            raise UnitError(f"Result.final: {name} [{si_label(si_unit)}]: {exc}") from None
        return (value - offset) / factor

    @checked(skip=("names",))  # names: one or a list, checked by _names
    def to_csv(self, path: str | Path, names: list[str] | None = None) -> Path:
        """Write ``time`` and the chosen variables (default all) as CSV in SI, one header row
        ``time [s], name [unit], ...`` (:func:`~bearingsim.series_csv.write_series_csv`).

        Parameters
        ----------
        path : str or Path
            File to write.
        names : list of str, optional
            These variables, in this order (default all).

        Returns
        -------
        Path
            The file written.
        """
        names = self._names(names, "Result.to_csv") if names is not None else self.names
        return write_series_csv(path, self.t, {n: self[n] for n in names}, self.units)

    @checked
    def to_npz(self, path: str | Path) -> Path:
        """Write all series to a compressed NumPy archive.

        Parameters
        ----------
        path : str or Path
            File to write (``.npz`` appended if missing).

        Returns
        -------
        Path
            The file written.
        """
        path = file_path(path)
        if path.suffix != ".npz":  # numpy appends it; return the file actually written
            path = path.with_name(path.name + ".npz")
        with atomic_path(path) as tmp:
            np.savez_compressed(tmp, t=self.t, names=np.array(self.names), values=self.values)
        return path

    def input_echo(self) -> dict[str, dict[str, object]]:
        """Every input at the last output time in SI and as a person reads it, so that a bare
        number given in SI is never silent (docs/units.md): name -> ``{"value": 1047.2,
        "unit": "rad/s", "shown": "10000 r/min (1047.2 rad/s)"}``.

        Returns
        -------
        dict
        """
        return {n: {"value": v, "unit": self.units.get(n, "1"),
                    "shown": engineering(v, self.units.get(n, "1"), both=True)}
                for n, v in self.inputs.items()}

    def label(self, name: str) -> str:
        """The axis label of a variable: its description (else its name) and its display
        unit, ``"middle ring speed [r/min]"``.

        Parameters
        ----------
        name : str
            A variable's dotted name, or ``"t"`` (``"time"``) for the time.

        Returns
        -------
        str
            The label.

        Raises
        ------
        KeyError
            For a name that is not a variable of the result, with close matches (or some of its
            variables), as ``result[name]``.
        """
        if name in ("t", "time"):
            return describe("t", "time", "s")
        self._series(name)  # KeyError with close matches, ParameterError for non-text
        return describe(name, self.descriptions.get(name, ""), self.units.get(name, "1"))

    @checked(skip=("names",))
    def plot(self, names: str | Sequence[str] | None = None, path: str | Path | None = None,
             title=None, ax=None):
        """Plot variables against time in engineering units (r/min, µm, N mm, kN: one per
        quantity kind, :mod:`bearingsim.units.display`), one axis per kind, labelled with the
        variables' descriptions; save to ``path`` if given. Returns the figure.

        The figure is a :class:`matplotlib.figure.Figure` made without pyplot: the session's
        backend is never changed (a notebook keeps its inline plots) and the figure is shown
        once, by being returned (or through ``ax``'s figure).

        Parameters
        ----------
        names : str or list of str, optional
            A variable or the variables to plot (default: the first six outputs).
        path : str or Path, optional
            File to save the figure to (written atomically).
        title : str, optional
            Figure title.
        ax : matplotlib.axes.Axes, optional
            Draw into this axes of the caller's figure: the first unit kind on it, each further
            kind on a twin axis sharing its time axis.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure

        names = (self._names(names, "Result.plot") if names is not None
                 else self.columns()[:6])
        if not names:
            raise ParameterError("Result.plot: no variables to plot")
        groups: dict[str, list[str]] = {}
        for n in names:
            groups.setdefault(display_label(self.units.get(n, "1")), []).append(n)
        if ax is not None:
            fig, axes = ax.figure, [ax]
            for k in range(1, len(groups)):
                twin = ax.twinx()
                twin.spines["right"].set_position(("outward", 55 * (k - 1)))
                axes.append(twin)
        else:
            fig = Figure(figsize=(7, 2.0 * len(groups) + 1))
            axes = list(np.atleast_1d(fig.subplots(len(groups), 1, sharex=True)))
        cycle = iter(f"C{k}" for k in range(len(names)))
        for axis, (unit, group) in zip(axes, groups.items(), strict=True):
            for n in group:
                y, _ = to_display(self[n], self.units.get(n, "1"))
                axis.plot(self.t, y, color=next(cycle), label=self.descriptions.get(n) or n)
            # several variables: the legend names them, the axis its unit
            axis.set_ylabel(wrapped_label(self.descriptions.get(group[0]) or group[0], unit)
                            if len(group) == 1 else f"[{unit}]", fontsize=8)
            if len(group) > 1 or ax is not None:
                axis.legend(fontsize=7, loc="best")
            if ax is None or axis is ax:
                axis.grid(True, alpha=0.3)
        axes[0 if ax is not None else -1].set_xlabel("time [s]")
        if title:
            fig.suptitle(title)
        if ax is None:
            keep_tight_layout(fig)
        if path is not None:
            with atomic_path(path) as tmp:
                fig.savefig(tmp, dpi=120)
        return fig

    def to_pandas(self, internal: bool = False, names: Sequence[str] | None = None):
        """The series as a :class:`pandas.DataFrame` in SI: one column per variable, named
        plainly (``df["Rs"]``), indexed by ``time``; the units in ``df.attrs["units"]`` (the
        index's as ``"time"``), the descriptions in ``df.attrs["descriptions"]`` (pandas:
        ``pip install bearingsim[notebook]``).

        Parameters
        ----------
        internal : bool
            Also the variables inside the components (default: the requested outputs only,
            :meth:`columns`).
        names : list of str, optional
            These variables, in this order, instead.

        Returns
        -------
        pandas.DataFrame
        """
        try:
            import pandas as pd
        except ImportError:
            raise ParameterError("Result.to_pandas needs pandas: pip install "
                                 "'bearingsim[notebook]'") from None
        cols = self._names(names, "Result.to_pandas") if names is not None \
            else self.columns(internal)
        frame = pd.DataFrame({n: self[n] for n in cols}, index=pd.Index(self.t, name="time"))
        frame.attrs["units"] = {"time": "s", **{n: self.units.get(n, "1") for n in cols}}
        frame.attrs["descriptions"] = {n: self.descriptions.get(n, "") for n in cols}
        return frame

    def to_xarray(self, internal: bool = False, names: Sequence[str] | None = None):
        """The series as an :class:`xarray.Dataset` over ``time`` in SI, each variable with
        its ``units`` and ``long_name`` (description) in ``attrs`` (xarray: ``pip install
        bearingsim[notebook]``); ``internal`` and ``names`` as for :meth:`to_pandas`.

        Returns
        -------
        xarray.Dataset

        Parameters
        ----------
        internal : bool
            Also the variables inside the components (default: the requested outputs only,
            :meth:`columns`).
        names : list of str, optional
            These variables, in this order, instead.
        """
        try:
            import xarray as xr
        except ImportError:
            raise ParameterError("Result.to_xarray needs xarray: pip install "
                                 "'bearingsim[notebook]'") from None
        cols = self._names(names, "Result.to_xarray") if names is not None \
            else self.columns(internal)
        return xr.Dataset(
            {n: ("time", self[n], {"units": self.units.get(n, "1"),
                                   "long_name": self.descriptions.get(n) or n}) for n in cols},
            coords={"time": ("time", self.t, {"units": "s", "long_name": "time"})})

    def _repr_html_(self) -> str:
        """A short table for notebooks: the run and the final value of the requested outputs
        in engineering units (:func:`bearingsim.units.to_display`), the value in the unit its
        unit column names."""
        shown = self.columns()
        rows = []
        for n in shown[:12]:
            unit = self.units.get(n, "1")
            value, label = to_display(float(self[n][-1]), unit)
            rows.append(f"<tr><td>{html.escape(n)}</td>"
                        f"<td>{html.escape(self.descriptions.get(n, ''))}</td>"
                        f"<td>{value:.6g}</td><td>{html.escape(label)}</td></tr>")
        more = (f"<tr><td colspan=4>... {len(shown) - 12} more</td></tr>"
                if len(shown) > 12 else "")
        return (f"<p>{html.escape(repr(self))}</p><table><tr><th>variable</th>"
                f"<th>description</th><th>final</th><th>unit</th></tr>{''.join(rows)}{more}"
                f"</table>")

    def __repr__(self) -> str:
        names = self.columns()
        shown = ", ".join(f"{n} [{display_label(self.units.get(n, '1'))}]" for n in names[:4])
        shown += ", ..." if len(names) > 4 else ""
        span = f"{self.t[0]:g} .. {self.t[-1]:g} s" if self.t.size else "no points"
        method = self.stats.get("method", "")
        return (f"<Result {span}, {self.t.size} points, {len(self.names)} variables ({shown})"
                + (f", {method}>" if method else ">"))
