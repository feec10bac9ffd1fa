"""Simulation results: named series, CSV/NPZ export and plots."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from bearingsim.files import atomic_path, write_series_csv
from bearingsim.plotting import set_value_scale

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

    def plot(self, names: list[str] | None = None, path: str | Path | None = None, title=None):
        """Plot variables against time; save to ``path`` if given. Returns the figure."""
        import matplotlib

        if path is not None:
            matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        names = names or self.names[: min(6, len(self.names))]
        fig, axes = plt.subplots(len(names), 1, sharex=True, figsize=(7, 1.8 * len(names) + 1))
        axes = np.atleast_1d(axes)
        for ax, n in zip(axes, names, strict=True):
            ax.plot(self.t, self[n])
            set_value_scale(ax, [self[n]])
            unit = self.units.get(n, "")
            ax.set_ylabel(f"{n}\n[{unit}]" if unit else n, fontsize=8)
            ax.grid(True, alpha=0.3)
        axes[-1].set_xlabel("time [s]")
        if title:
            fig.suptitle(title)
        fig.tight_layout()
        if path is not None:
            with atomic_path(path) as tmp:
                fig.savefig(tmp, dpi=120)
            plt.close(fig)
        return fig
