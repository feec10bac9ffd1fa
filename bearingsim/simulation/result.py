"""Simulation results: named series, CSV/NPZ export and plots."""

from __future__ import annotations

import html
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from bearingsim.checks import checked
from bearingsim.errors import ParameterError
from bearingsim.files import atomic_path, column_name, write_series_csv
from bearingsim.plotting import set_value_scale
from bearingsim.units import engineering, unit_label

__all__ = ["Result"]


@dataclass
class Result:
    """Time series of every observed variable of a run.

    ``res["j1.w"]`` is the series of one variable; ``res.t`` the time points [s].

    Attributes
    ----------
    t : ndarray
        Output times [s].
    names : list of str
        Dotted names of the observed variables.
    values : ndarray
        Shape (len(names), len(t)).
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
    """

    t: np.ndarray
    names: list[str]
    values: np.ndarray
    units: dict[str, str] = field(default_factory=dict)
    stats: dict[str, object] = field(default_factory=dict)
    inputs: dict[str, float] = field(default_factory=dict)
    parameters: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self._index = {n: k for k, n in enumerate(self.names)}

    def __getitem__(self, name: str) -> np.ndarray:
        if name in ("t", "time"):
            return self.t
        try:
            return self.values[self._index[name]]
        except KeyError:
            import difflib

            close = difflib.get_close_matches(name, self.names, n=5)
            hint = f"; did you mean {', '.join(close)}?" if close else ""
            raise KeyError(f"no variable {name!r} in the result{hint}") from None

    def __contains__(self, name: str) -> bool:
        return name in self._index

    @checked
    def final(self, name: str) -> float:
        """Value at the last time point."""
        return float(self[name][-1])

    def to_csv(self, path: str | Path, names: list[str] | None = None) -> Path:
        """Write ``time`` and the chosen variables (default all) as CSV, one header row
        ``time [s], name [unit], ...`` (:func:`~bearingsim.files.write_series_csv`)."""
        names = names or self.names
        return write_series_csv(path, self.t, {n: self[n] for n in names}, self.units)

    def to_npz(self, path: str | Path) -> Path:
        """Write all series to a compressed NumPy archive."""
        path = Path(path)
        if path.suffix != ".npz":  # numpy appends it; return the file actually written
            path = path.with_name(path.name + ".npz")
        with atomic_path(path) as tmp:
            np.savez_compressed(tmp, t=self.t, names=np.array(self.names), values=self.values)
        return path

    def plot(self, names: list[str] | None = None, path: str | Path | None = None, title=None,
             ax=None):
        """Plot variables against time; save to ``path`` if given. Returns the figure.

        The figure is a :class:`matplotlib.figure.Figure` made without pyplot: the session's
        backend is never changed (a notebook keeps its inline plots) and the figure is shown
        once, by being returned (or through ``ax``'s figure).

        Parameters
        ----------
        names : list of str, optional
            Variables to plot (default: the first six), one axes each.
        path : str or Path, optional
            File to save the figure to (written atomically).
        title : str, optional
            Figure title.
        ax : matplotlib.axes.Axes, optional
            Draw every variable into this axes of the caller's figure instead.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure

        names = names or self.names[: min(6, len(self.names))]
        if ax is not None:
            fig, axes = ax.figure, [ax] * len(names)
        else:
            fig = Figure(figsize=(7, 1.8 * len(names) + 1))
            axes = np.atleast_1d(fig.subplots(len(names), 1, sharex=True))
        for axis, n in zip(axes, names, strict=True):
            unit = unit_label(self.units.get(n, ""))
            axis.plot(self.t, self[n], label=f"{n} [{unit}]")
            if ax is None:
                set_value_scale(axis, [self[n]])
                axis.set_ylabel(f"{n}\n[{unit}]", fontsize=8)
            axis.grid(True, alpha=0.3)
        axes[-1].set_xlabel("time [s]")
        if ax is not None:
            ax.legend(fontsize=8)
        if title:
            fig.suptitle(title)
        if ax is None:
            fig.tight_layout()
        if path is not None:
            with atomic_path(path) as tmp:
                fig.savefig(tmp, dpi=120)
        return fig

    def to_pandas(self):
        """The series as a :class:`pandas.DataFrame`: one column ``name [unit]`` per variable,
        indexed by ``time [s]`` (pandas: ``pip install bearingsim[notebook]``)."""
        try:
            import pandas as pd
        except ImportError:
            raise ParameterError("Result.to_pandas needs pandas: pip install "
                                 "'bearingsim[notebook]'") from None
        columns = {column_name(n, self.units.get(n, "")): self[n] for n in self.names}
        return pd.DataFrame(columns, index=pd.Index(self.t, name=column_name("time", "s")))

    def to_xarray(self):
        """The series as an :class:`xarray.Dataset` over ``time`` with each variable's unit in
        its ``attrs`` (xarray is not a dependency: install it to use this)."""
        try:
            import xarray as xr
        except ImportError:
            raise ParameterError("Result.to_xarray needs xarray: pip install xarray") from None
        return xr.Dataset({n: ("time", self[n], {"units": self.units.get(n, "1")})
                           for n in self.names}, coords={"time": ("time", self.t,
                                                                  {"units": "s"})})

    def _repr_html_(self) -> str:
        """A short table for notebooks: the run and the final value of the first variables,
        in engineering units (:func:`bearingsim.units.engineering`: r/min, um, deg, kN, N m)."""
        rows = "".join(f"<tr><td>{html.escape(n)}</td>"
                       f"<td>{html.escape(engineering(float(self[n][-1]), self.units.get(n, '')))}"
                       f"</td><td>{html.escape(unit_label(self.units.get(n, '')))}</td></tr>"
                       for n in self.names[:12])
        more = (f"<tr><td colspan=3>... {len(self.names) - 12} more</td></tr>"
                if len(self.names) > 12 else "")
        return (f"<p>{html.escape(repr(self))}</p><table><tr><th>variable</th>"
                f"<th>final</th><th>unit (SI)</th></tr>{rows}{more}</table>")

    def __repr__(self) -> str:
        shown = ", ".join(f"{n} [{unit_label(self.units.get(n, ''))}]" for n in self.names[:4])
        shown += ", ..." if len(self.names) > 4 else ""
        span = f"{self.t[0]:g} .. {self.t[-1]:g} s" if self.t.size else "no points"
        method = self.stats.get("method", "")
        return (f"<Result {span}, {self.t.size} points, {len(self.names)} variables ({shown})"
                + (f", {method}>" if method else ">"))
