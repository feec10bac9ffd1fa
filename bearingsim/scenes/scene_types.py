"""The parts of a scene: its keys and kinds, the error that names a key and its line, input tables,
solver settings, settling criterion and output folder."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from bearingsim.errors import ParameterError
from bearingsim.scenes.expressions import compile_expression
from bearingsim.simulation.budget import DEFAULT_MAX_STEPS

TOP_KEYS = ("title", "description", "analysis", "outputs", "tolerance", "bearings", "lubricants",
            "assembly",
            "inputs", "parameters", "initial", "grid", "cases", "settling",
            "transient_on_purpose", "statics", "simulation", "output")
ANALYSES = ("transient", "steady", "modes", "statics")
"""What a scene asks (key ``analysis``): a run in time (``transient``, the default), the
settled operating point (``steady``), natural frequencies and mode names at the equilibrium
(``modes``) or quasi-static ball loads, stiffness, contact pressure and life (``statics``); the
last three for each point of ``grid`` or ``cases`` (:mod:`bearingsim.scenes.analyses`)."""
POINT_HEADS = ("inputs", "parameters", "assembly")
"""Key heads of an operating grid or load case (``inputs.shaft_speed``, ``parameters.<name>``,
``assembly.<argument>``)."""
STATICS_METHODS = ("exact", "iso_ts_16281")
DEFAULT_TOLERANCE = 0.05
"""Largest relative error of the requested outputs a scene accepts from ``fidelity = "auto"``
when it gives no ``tolerance`` [-]."""
TABLE_KEYS = ("file", "column", "time_column", "times", "values")
MAX_SCENE_BYTES = 50_000_000
"""Largest scene file read [bytes] (a scene with inline tables of 10^6 rows is about 30 MB;
larger tables belong in CSV files)."""


class SceneError(ParameterError):
    """A scene file or scene object is invalid.

    Parameters
    ----------
    message : str
        What is wrong.
    key : str
        Dotted key (``simulation.rtol``).
    line : int or None
        1-based line in the scene file, when known.
    allowed : str
        The allowed values.
    path : str or None
        The scene file.
    problems : list of SceneError, optional
        All problems found.

    Attributes
    ----------
    key : str
        Dotted key (``simulation.rtol``).
    line : int or None
        1-based line in the scene file, when known.
    allowed : str
        The allowed values.
    problems : list of SceneError
        All problems found (the first one is this error itself when several are reported).
    """

    def __init__(self, message: str, key: str = "", line: int | None = None, allowed: str = "",
                 path: str | None = None, problems: list | None = None):
        self.key, self.line, self.allowed, self.path = key, line, allowed, path
        self.reason = message
        self.problems = problems or [self]
        super().__init__(self._format())

    def _format(self) -> str:
        if len(self.problems) > 1:
            return f"{len(self.problems)} problems in the scene:\n  " + "\n  ".join(
                p._format() for p in self.problems)
        where = self.path or "scene"
        if self.line is not None:
            where += f":{self.line}"
        text = f"{where}: {self.key}: {self.reason}" if self.key else f"{where}: {self.reason}"
        if self.allowed:
            text += f"; allowed: {self.allowed}"
        return text


@dataclass
class TableInput:
    """An input given as a table: linear interpolation between ``times`` [s] and ``values``."""

    times: list[float]
    values: list[float]
    source: str = ""

    def as_tuple(self) -> tuple[np.ndarray, np.ndarray]:
        """``(times, values)`` as accepted by ``simulate(inputs=...)``.

        Returns
        -------
        tuple of numpy.ndarray
            Times [s] and values (the input's SI unit).
        """
        return np.asarray(self.times, dtype=float), np.asarray(self.values, dtype=float)


@dataclass
class Simulation:
    """Time span and solver of a scene."""

    t_end: float = 1.0
    t_start: float = 0.0
    method: str | None = None
    """The integration method; None: ``simulate``'s fastest accurate choice
    (:func:`~bearingsim.simulation.choice.choose_method`)."""
    rtol: float = 1e-6
    atol: float = 1e-8
    n_points: int = 501
    max_step: float = math.inf
    initial: str = "start"
    max_steps: int = DEFAULT_MAX_STEPS
    timeout: float | None = None


@dataclass
class Settling:
    """When a transient scene's outputs count as settled (key ``settling``).

    An output has settled when its range (largest minus smallest value) over the last
    ``window`` of the run is at most ``tolerance`` times its final magnitude (or, for an
    output that ends near zero, ``tolerance`` times its largest magnitude in the run).
    """

    window: float = 0.2
    """Fraction of the run checked, at its end [-], in (0, 1)."""
    tolerance: float = 1e-3
    """Largest relative change over the window [-]."""


@dataclass
class Output:
    """Where and what a scene run writes."""

    folder: str = "results"
    csv: bool = True
    plots: bool = True
    plot_groups: list[list[str]] = field(default_factory=list)


# --------------------------------------------------------------------------- line numbers
_KEY_PART = r'(?:"[^"]*"|\'[^\']*\'|[A-Za-z0-9_\-]+)'
_KEY_LINE = re.compile(rf"^\s*({_KEY_PART}(?:\s*\.\s*{_KEY_PART})*)\s*=")
_HEADER = re.compile(rf"^\s*\[\[?\s*({_KEY_PART}(?:\s*\.\s*{_KEY_PART})*)\s*\]\]?")


def _split_key(text: str) -> tuple[str, ...]:
    parts = re.findall(_KEY_PART, text)
    return tuple(p[1:-1] if p[:1] in "\"'" else p for p in parts)


def line_of(text: str | None, key: tuple[str, ...] | str) -> int | None:
    """1-based line of a (dotted) key in TOML text: the longest prefix of the key found.

    Keys may be written as table headers (``[simulation]``), plain or dotted keys
    (``rtol = ...``, ``"inner_layer.nu" = ...``) or inside inline tables (the line of the
    enclosing key is returned).

    Parameters
    ----------
    text : str or None
        The TOML text (None: no line).
    key : tuple of str or str
        The key, dotted or as parts.

    Returns
    -------
    int or None
        The line, or None when the key is not found.
    """
    if not text:
        return None
    if isinstance(key, str):
        key = tuple(key.split("."))
    best, best_len = None, 0
    table: tuple[str, ...] = ()
    for n, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0] if '"' not in raw and "'" not in raw else raw
        m = _HEADER.match(line)
        if m and not _KEY_LINE.match(line):
            table = _split_key(m.group(1))
            full = table
        else:
            m = _KEY_LINE.match(line)
            if not m:
                continue
            full = table + _split_key(m.group(1))
        # match both nested keys and quoted dotted names ("inner_layer.nu")
        flat = ".".join(full)
        target = ".".join(key)
        length = 0
        if target == flat or target.startswith(flat + "."):
            length = len(flat)
        if length > best_len:
            best, best_len = n, length
    return best


def simulate_inputs(inputs: dict[str, Any]) -> dict[str, Any]:
    """Scene inputs as accepted by ``simulate``: expressions compiled, tables as arrays.

    Parameters
    ----------
    inputs : dict
        Scene inputs by name (numbers, expressions or tables).

    Returns
    -------
    dict
        The inputs for ``simulate``.
    """
    out = {}
    for k, v in inputs.items():
        if isinstance(v, str):
            out[k] = compile_expression(v, f"inputs.{k}")
        elif isinstance(v, TableInput):
            out[k] = v.as_tuple()
        else:
            out[k] = v
    return out
