"""Sweep points: the keys a point can set, the Cartesian product of grids, and quasi-random
samples of ranges.

Samples come from :mod:`scipy.stats.qmc`: a Latin hypercube (``"lhs"``, optionally
``"lhs-optimal"`` with CD-optimal random permutations) or a Sobol sequence (``"sobol"``: only
a power of two keeps its balance properties; another count is run as asked, with a
:class:`SampleBalanceWarning` naming the powers of two around it). Both are scrambled by
default and reproducible with ``seed``.
"""

from __future__ import annotations

import itertools
import math
import numbers
import warnings
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from bearingsim.checks import check_output_size
from bearingsim.errors import ParameterError
from bearingsim.sweep_samplers import SAMPLERS
from bearingsim.units import parse_quantity

__all__ = ["SAMPLERS", "SIM_KEYS", "SampleBalanceWarning", "SweepError", "check_key",
           "crossed_points", "grid_points", "parse_sample", "sample_points"]

SIM_KEYS = ("t_end", "t_start", "rtol", "atol", "method", "max_step", "n_points", "initial")
"""The ``simulation.<setting>`` keys a sweep can set."""


class SweepError(ParameterError):
    """A sweep specification is invalid (key, value or point), naming it."""


class SampleBalanceWarning(UserWarning):
    """A Sobol sample of a count that is not a power of two: its points do not fill the
    ranges evenly (the sample runs as asked)."""


def check_key(key: str) -> None:
    """Raise :class:`SweepError` for a key a sweep point cannot set (naming the allowed ones).

    Parameters
    ----------
    key : str
        A sweep key (``inputs.X``, ``parameters.X`` or an assembly argument).
    """
    if not isinstance(key, str):
        raise SweepError(f"sweep key {key!r}: must be text (e.g. inputs.shaft_speed)")
    head = key.split(".", 1)[0]
    if head not in ("inputs", "parameters", "initial", "simulation", "assembly") or "." not in key:
        raise SweepError(
            f"sweep key {key!r}: must start with inputs., parameters., initial., simulation. "
            "or assembly. (e.g. inputs.shaft_speed, parameters.inner_layer.nu, "
            "assembly.lubrication, simulation.rtol)")
    if head == "simulation" and key.split(".", 1)[1] not in SIM_KEYS:
        raise SweepError(f"sweep key {key!r}: allowed simulation settings: "
                         + ", ".join(SIM_KEYS))


def parse_sample(items: list[str]) -> dict[str, tuple]:
    """``["parameters.shaft.J=1e-4:1e-3"]`` -> ``{"parameters.shaft.J": (1e-4, 1e-3)}``.

    Parameters
    ----------
    items : list of str
        ``key=low:high`` each, low and high in the key's SI unit or with a unit
        (``inputs.shaft_speed=500rpm:1000rpm``; SI values returned).

    Returns
    -------
    dict of str to tuple
        The range by key: ``(low, high)`` in SI, or ``(low, high, unit)`` for a range given
        with a unit (``unit`` the SI unit of its quantity, ``"rad/s"`` for rpm): its sampled
        values then carry that unit, and the sweep checks it against the key's, as it does a
        grid's ``"1 kN"``.

    Raises
    ------
    SweepError
        For a key a sweep cannot set, a key given twice, a malformed item or a range that
        is not finite with low < high.
    """
    ranges = {}
    for item in items:
        if "=" not in item or ":" not in item.split("=", 1)[1]:
            raise SweepError(f"--sample {item!r}: expected key=low:high")
        key, rng = item.split("=", 1)
        key = key.strip()
        check_key(key)
        if key in ranges:  # a second --sample of a key replaced the first one's range, unsaid
            raise SweepError(f"--sample {key} is given twice; give one range: "
                             f"--sample {key}=low:high")
        try:
            (lo, lo_unit), (hi, hi_unit) = (_bound(x) for x in rng.split(":", 1))
        except (ValueError, ParameterError):
            raise SweepError(f"--sample {key}: low and high must be numbers (SI) or numbers "
                             f"with a unit ('1000 rpm:2000 rpm'), got {rng!r}") from None
        if lo_unit and hi_unit and lo_unit != hi_unit:  # "1 kN:2 m": was "need low < high"
            raise SweepError(f"--sample {key}: low and high are different quantities (in SI "
                             f"{lo_unit} and {hi_unit}), got {rng!r}")
        if not _is_range((lo, hi)):
            raise SweepError(f"--sample {key}: need finite low < high, got {rng!r}")
        unit = lo_unit or hi_unit  # "1 mm:2 mm" for a force: refused by the sweep (was run
        ranges[key] = (lo, hi, unit) if unit else (lo, hi)  # with forces of 1-2 mN)
    return ranges


def grid_points(grid: dict[str, list[Any]]) -> list[dict[str, Any]]:
    """The Cartesian product of a grid, as a list of ``{key: value}`` (last key fastest).

    Parameters
    ----------
    grid : dict of str to list
        Values by key.

    Returns
    -------
    list of dict
        The points.

    Raises
    ------
    SweepError
        For a grid that is not a mapping, a key a sweep cannot set
        (:func:`check_key`) or a key without values.
    """
    if not isinstance(grid, Mapping):
        raise SweepError(f"grid_points: the grid must be a dict (sweep key -> list of values), "
                         f"got {type(grid).__name__}")
    grid = {key: _values(key, values) for key, values in grid.items()}
    keys = list(grid)
    check_output_size(math.prod(len(v) for v in grid.values()), 300 + 100 * len(keys),
                      "the number of grid points", "grid_points")
    return [dict(zip(keys, combo, strict=True)) for combo in itertools.product(*grid.values())]


def _values(key: Any, values: Any) -> list[Any]:
    """The values of a grid key as a list; :class:`SweepError` for a key a sweep cannot set,
    a single value (text, a number, a mapping) or none."""
    check_key(key)
    if isinstance(values, (str, bytes, Mapping)) or not isinstance(values, Iterable):
        raise SweepError(f"grid key {key}: expected a list of values, got "
                         f"{type(values).__name__} (a single value is a list of one: [v])")
    values = list(values)
    if not values:
        raise SweepError(f"grid key {key}: no values")
    return values


def _is_range(bounds: Any) -> bool:
    """Whether ``bounds`` is ``(low, high)`` or ``(low, high, unit)``: two finite real numbers
    (not booleans), low < high, and the unit's text."""
    if not isinstance(bounds, Sequence) or isinstance(bounds, str) or len(bounds) not in (2, 3):
        return False
    low, high, *unit = bounds
    return (all(isinstance(b, numbers.Real) and not isinstance(b, bool) and math.isfinite(b)
                for b in (low, high)) and low < high
            and all(isinstance(u, str) and u.strip() for u in unit))


def _whole(value: Any) -> bool:
    """Whether ``value`` is an integer (numpy's included), not a boolean."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def sample_points(ranges: dict[str, tuple[float, float]], n: int, seed: int | None = 0,
                  method: str = "lhs", scramble: bool = True) -> list[dict[str, Any]]:
    """``n`` quasi-random points in the box ``ranges`` (scipy.stats.qmc).

    Parameters
    ----------
    ranges : dict
        Key -> (low, high) in the key's SI unit, or (low, high, unit) with ``unit`` the SI
        unit of the bounds (:func:`parse_sample` of ``"1 kN:2 kN"``): the key's values are then
        text with that unit (``"1234.5 N"``), checked against the key's unit when the sweep
        runs and written to its table in SI.
    n : int
        Number of points (>= 1).
    seed : int or None
        Seed of the scrambling and permutations, >= 0 (None: fresh entropy, not
        reproducible).
    method : {"lhs", "lhs-optimal", "sobol"}
        Latin hypercube, Latin hypercube with centred-discrepancy optimal permutations, or
        the Sobol sequence.
    scramble : bool
        Random placement inside the Latin hypercube cells / Owen scrambling of Sobol; without
        it a Latin hypercube puts points at cell centres and Sobol starts at the origin.

    Returns
    -------
    list of dict
        ``n`` dicts key -> float (or text with the range's unit).

    Raises
    ------
    SweepError
        For ``n`` not a whole number >= 1, a seed not a whole number >= 0, an unknown
        method, no ranges, a key a sweep cannot set or a range not finite low < high.

    Warns
    -----
    SampleBalanceWarning
        For ``method="sobol"`` with ``n`` not a power of two.
    """
    if not _whole(n) or n < 1:
        raise SweepError(f"--samples must be >= 1 (a whole number), got {n!r}")
    if seed is not None and (not _whole(seed) or seed < 0):  # numpy's seeds
        raise SweepError(f"--seed must be a non-negative integer or None, got {seed!r}")
    if not isinstance(ranges, Mapping) or not ranges:
        raise SweepError("a sample needs at least one key=low:high range (a dict: sweep key "
                         f"-> (low, high)), got {ranges!r:.60}")
    for key, bounds in ranges.items():
        check_key(key)
        if not _is_range(bounds):
            raise SweepError(f"--sample {key}: need finite low < high (in SI units, and "
                             f"optionally the unit's text), got {bounds!r:.60}")
    check_output_size(n, 300 + 100 * len(ranges), "--samples", "sample_points")
    # imported here: scipy.stats takes about 0.5 s to import, which a grid sweep never needs
    from scipy.stats import qmc

    d = len(ranges)
    if method == "lhs":
        engine = qmc.LatinHypercube(d, scramble=scramble, rng=seed)
    elif method == "lhs-optimal":
        engine = qmc.LatinHypercube(d, scramble=scramble, optimization="random-cd", rng=seed)
    elif method == "sobol":
        engine = qmc.Sobol(d, scramble=scramble, rng=seed)
    else:
        raise SweepError(f"--sampler {method!r}: allowed: {', '.join(SAMPLERS)}")
    if method == "sobol" and n & (n - 1):
        below = 1 << (n.bit_length() - 1)
        warnings.warn(
            f"--sampler sobol with --samples {n}: a Sobol sample of n points is balanced (one "
            f"point in each of n equal intervals of every key's range) only when n is a power "
            f"of two; the first {n} points of the sequence leave some intervals empty and crowd "
            f"others. Use --samples {below} or {2 * below}, or --sampler lhs (balanced for any "
            "n)", SampleBalanceWarning, stacklevel=2)
    with warnings.catch_warnings():  # scipy's own warning says less; this one is above
        warnings.filterwarnings("ignore", message=".*balance properties.*")
        unit = engine.random(n)
    lows = [bounds[0] for bounds in ranges.values()]
    highs = [bounds[1] for bounds in ranges.values()]
    box = qmc.scale(unit, lows, highs)
    units = [bounds[2] if len(bounds) == 3 else None for bounds in ranges.values()]
    keys = list(ranges)
    return [{k: float(row[j]) if units[j] is None else f"{float(row[j])!r} {units[j]}"
             for j, k in enumerate(keys)} for row in box]


def crossed_points(grid_points: list[dict[str, Any]], samples: list[dict[str, Any]]
                   ) -> list[dict[str, Any]]:
    """Every grid point with every sample point (the sample fastest).

    Parameters
    ----------
    grid_points : list of dict
        The grid's points (``[{}]``: no grid).
    samples : list of dict
        The sample's points.

    Returns
    -------
    list of dict
        The points.

    Raises
    ------
    SweepError
        For a key both in the grid and in the sample (one would overwrite the other).
    """
    both = sorted(set(grid_points[0]) & set(samples[0])) if grid_points and samples else []
    if both:
        raise SweepError(f"{', '.join(both)}: both gridded (--grid) and sampled (--sample); "
                         "give each key one of them")
    return [{**p, **s} for p in grid_points for s in samples]


def _bound(text: str) -> tuple[float, str | None]:
    """A sample bound: a number (SI) or a number with a unit (``500rpm``), in SI, and its SI
    unit (None for a plain number)."""
    quantity = parse_quantity(text)
    return quantity if quantity is not None else (float(text), None)
