"""The results of a sweep: its result columns with their SI units, a point's table row, the
sweep's figure and its outcome (:class:`SweepResult`, told in words by :func:`describe_points`
and :func:`describe_failures`).

A sweep's row holds what ``bearingsim run`` gives for one operating point of the scene
(:func:`~bearingsim.scenes.analyses.run_operating_point`); :func:`result_columns` names those
columns from the prepared model (a modes sweep's from its first point), :func:`column_units`
adds the swept keys' units and :func:`sweep_figures` draws each result against the first
numeric swept key.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from bearingsim.scenes.operating_points import key_unit
from bearingsim.scenes.preparation import Prepared

__all__ = ["TRANSIENT_COLUMNS", "SweepResult", "column_units", "describe_failures",
           "describe_points", "point_warnings", "result_columns", "sweep_figures", "table_row"]


TRANSIENT_COLUMNS = ("settled", "time_constant", "unsettled")
"""The columns a transient point adds to its outputs' final values
(:func:`~bearingsim.scenes.analyses.run_operating_point`)."""


def result_columns(prep: Prepared, probe: dict[str, Any] | None
                   ) -> tuple[list[str], dict[str, str]]:
    """The result columns of a sweep's rows and their SI units: those of the scene's own table
    row for its analysis (a transient's outputs with ``settled``, ``time_constant`` and
    ``unsettled``, without them for a transient on purpose; a steady point's outputs; a
    statics point's columns; a modes point's mode names, read from the ``probe`` row of the
    first point).

    Parameters
    ----------
    prep : Prepared
        The prepared model of the sweep's first point.
    probe : dict, optional
        The row of the first point (a modes sweep's mode names), or None.

    Returns
    -------
    tuple of (list of str, dict of str to str)
        The result column names and their SI units by name.
    """
    from bearingsim.scenes.analysis_table import analysis_units

    kind = prep.scene.analysis
    if kind == "transient":
        system = prep.system
        units = {**system.variable_units, **{n: q.unit for n, q in prep.post.items()},
                 **{p.name: p.unit for p in system.params}}
        output_units = {n: units[n] for n in prep.outputs if n in units}
        if prep.scene.transient_on_purpose:  # not checked for settling: no such columns
            return list(prep.outputs), output_units
        return [*prep.outputs, *TRANSIENT_COLUMNS], {**output_units, "time_constant": "s"}
    if kind == "statics":
        names = list(prep.outputs)
    elif kind == "modes":
        names = [n for n in (probe or {}) if not n.startswith("_")]
    else:
        names = list(prep.outputs)
    units = analysis_units(prep, [probe] if probe else [])
    return names, {n: units[n] for n in names if units.get(n)}


def column_units(prep: Prepared, keys: list[str], results: dict[str, str]
                 ) -> dict[str, str]:
    """Unit of every numeric sweep column: the swept keys' (inputs, parameters and initial
    values from the first model, whose names every model of a sweep shares; assembly
    arguments and simulation settings, :func:`~bearingsim.scenes.operating_points.key_unit`),
    the results' and ``wall_s``.

    Parameters
    ----------
    prep : Prepared
        The prepared model of the sweep's first point.
    keys : list of str
        The swept keys.
    results : dict of str to str
        SI units of the result columns (:func:`result_columns`).

    Returns
    -------
    dict of str to str
        SI unit by column name (a key of text values, or of no one unit, has none).
    """
    out = dict(results)
    for key in keys:
        unit = key_unit(prep, prep.scene, key)
        if unit:
            out[key] = unit
    out["wall_s"] = "s"
    return out


def table_row(index: int, values: dict[str, Any], results: list[str],
              r: dict[str, Any]) -> dict[str, Any]:
    """The table row of a finished point: its number, swept values, status, results (NaN
    when it failed), wall time [s] and error.

    Parameters
    ----------
    index : int
        The point number.
    values : dict
        The point's swept values by key (:func:`~bearingsim.scenes.sweep_grid.si_values`).
    results : list of str
        The result columns (:func:`result_columns`).
    r : dict
        What the worker returned for the point (``status``, ``final``, ``wall_s``,
        ``error``).

    Returns
    -------
    dict
        The row by column name.
    """
    row: dict[str, Any] = {"point": index, **values, "status": r["status"]}
    for name in results:
        row[name] = r["final"].get(name, float("nan")) if r["status"] == "ok" else float("nan")
    row["wall_s"] = round(float(r.get("wall_s", float("nan"))), 4)
    row["error"] = r["error"]
    return row


def sweep_figures(prep: Prepared, rows: list[dict[str, Any]], keys: list[str],
                  results: list[str], units: dict[str, str], stem: str) -> list:
    """``<stem>.png``: each result against the first numeric swept key (engineering units),
    one panel per output (natural frequencies in one panel) and one curve per value of the
    other keys, as an analysis scene draws them
    (:func:`~bearingsim.scenes.plots.characteristic_figures`: points in order along the axis,
    lives on a logarithmic axis, a sampled sweep as markers); when no swept key is a number
    that varies (a sweep over lubricants), one bar per point
    (:func:`~bearingsim.scenes.bar_figures.category_figures`).

    Parameters
    ----------
    prep : Prepared
        The prepared model of the sweep's first point.
    rows : list of dict
        The sweep's rows (:func:`table_row`).
    keys : list of str
        The swept keys.
    results : list of str
        The result columns.
    units : dict of str to str
        SI unit by column name (:func:`column_units`).
    stem : str
        File name stem of the sweep's files.

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        File name and figure (none or one).
    """

    from bearingsim.scenes.analysis_figures import curves_or_bars
    from bearingsim.scenes.bar_figures import statics_columns
    from bearingsim.scenes.plots import varies

    ok = [r for r in rows if r["status"] == "ok"]
    if ok and prep.scene.analysis == "transient":
        ok, keys, units = _with_end_values(prep, ok, keys, units)
    outputs = [n for n in results if n in units and n not in TRANSIENT_COLUMNS
               and all(isinstance(r[n], float) for r in ok)]  # not a statics life at rest
    if not ok or not outputs:  # (every point failed: the table says why)
        return []
    if prep.scene.analysis == "statics":  # the columns a statics scene draws
        outputs = [n for n in statics_columns(prep, ok) if n in outputs] or outputs
    if not any(varies(ok, k) for k in keys):  # (the same point again and again)
        return []
    what = prep.scene.analysis if prep.scene.analysis in ("modes", "statics") else "steady"
    figs = curves_or_bars(prep, ok, keys, units, outputs, what, len(rows) - len(ok))
    return [(f"{stem}.png", fig) for _, fig in figs[:1]]


def _with_end_values(prep: Prepared, rows: list[dict[str, Any]], keys: list[str],
                     units: dict[str, str]
                     ) -> tuple[list[dict[str, Any]], list[str], dict[str, str]]:
    """``rows``, ``keys`` and ``units`` with each input swept as expressions of ``t`` replaced
    by its value at the end of each point's run (the time of the final values; key
    ``<key> at t_end``, the input's unit), where distinct expressions end at distinct values
    (otherwise the curves would merge): a sweep over ``rpm(N) * ramp(0, 0.02)`` is drawn
    against the speed the run ended at."""
    import casadi as ca

    from bearingsim.scenes.expressions import compile_expression

    def end(row: dict[str, Any], key: str) -> tuple[str, float]:
        return row[key], float(row.get("simulation.t_end", prep.scene.simulation.t_end))

    for key in [k for k in keys if k.startswith("inputs.")]:
        if not all(isinstance(r[key], str) for r in rows):
            continue
        try:
            ends = {(text, t): float(ca.DM(compile_expression(text, key)(t)))
                    for text, t in {end(r, key) for r in rows}}
        except Exception:  # noqa: BLE001 - a text that is no expression: drawn as it is
            continue
        if len(set(ends.values())) < len(ends):
            continue
        derived = f"{key} at t_end"
        rows = [{**r, derived: ends[end(r, key)]} for r in rows]
        keys = [derived if k == key else k for k in keys]
        units = {**units, derived: units.get(key, "")}
    return rows, keys, units


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")

SHOWN_POINTS = 8
"""Most point numbers a warning of a sweep lists."""


def point_warnings(results: dict[int, dict[str, Any]], n_points: int) -> list[dict[str, Any]]:
    """The warnings the points of a sweep gave (their rows' ``warnings``,
    :func:`~bearingsim.scenes.sweep_worker.run_job`), one per kind: a category and a message
    alike but for its numbers (``shaft_speed reaches 58847 r/min`` and ``... 46027 r/min``
    are one kind), with the points that gave it.

    Parameters
    ----------
    results : dict of int to dict
        The rows the points returned, by point number.
    n_points : int
        The points of the sweep.

    Returns
    -------
    list of dict
        Per kind, in the order first given: ``category`` (the Warning class), ``points``
        (their numbers, increasing), ``message`` (the first point's) and ``text`` (one line
        for the user: how many points, which, and the first point's message).
    """
    kinds: dict[tuple, dict[str, Any]] = {}
    for index in sorted(results):
        for category, message in results[index].get("warnings", ()):
            kind = kinds.setdefault((category, _NUMBER.sub("#", message)),
                                    {"category": category, "points": [], "message": message})
            if not kind["points"] or kind["points"][-1] != index:
                kind["points"].append(index)
    for kind in kinds.values():
        points = kind["points"]
        listed = ", ".join(map(str, points[:SHOWN_POINTS])) + (
            ", ..." if len(points) > SHOWN_POINTS else "")
        kind["text"] = (f"{len(points)} of {n_points} point(s) ({listed}): {kind['message']}"
                        + (f" (point {points[0]}; the others alike)" if len(points) > 1
                           else f" (point {points[0]})"))
    return list(kinds.values())


@dataclass
class SweepResult:
    """Rows of the result table (one per point, in point order), failures and written files."""

    keys: list[str]
    rows: list[dict[str, Any]]
    failures: list[dict[str, Any]]
    models_built: int
    files: list[Path] = field(default_factory=list)
    wall_s: float = 0.0
    resumed: int = 0
    """Points taken from the table of an earlier run (``resume``)."""
    chunk_size: int = 1
    """Most points in one task."""
    point_s: float = math.nan
    """Median wall time of a point [s] (which sized the chunks with ``longest_first=False``)."""
    spans: dict[int, tuple[int, float, float]] = field(default_factory=dict)
    """Point -> (process id of the worker that ran it, epoch time it started [s], its wall
    time [s]) of the points this sweep ran: a timeline of the workers."""
    point_cpu: dict[int, float] = field(default_factory=dict)
    """Point -> CPU time of the thread that ran it on its worker [s], of the points this
    sweep ran; below the wall time in :attr:`spans` by the time the point waited for a core
    (other processes on the worker's machine)."""
    phases: dict[str, float] = field(default_factory=dict)
    """Wall time [s] of the client's phases: ``imports`` (dask.distributed, the first sweep of
    a process: about 0.5 s), ``plan`` (validate, prepare or load the models),
    ``cluster`` (waiting for the cluster after planning), ``ship`` (scatter the models),
    ``points`` (first chunk out to last row in; the client imports what writing takes
    meanwhile), ``close`` (close the cluster), ``write`` (sorted table, Parquet copy, plot,
    summary)."""
    warnings: list[dict[str, Any]] = field(default_factory=list)
    """The warnings the points gave, one per kind, with the points that gave it
    (:func:`~bearingsim.scenes.sweep_results.point_warnings`); each is also warned once on
    the client (a worker's own standard error shows none)."""
    settling: str = ""
    """Whether the rows say if each point settled: ``"checked"`` (a transient scene: columns
    ``settled`` and ``unsettled``), ``"on purpose"`` (a transient scene that reports a
    transient on purpose: not checked, as ``bearingsim run`` does not) or ``""`` (a steady,
    modes or statics point is solved, not run in time)."""
    plot_failures: list[dict[str, str]] = field(default_factory=list)
    """The figures that failed (``plot``, ``error``); the table and summary are written."""

    @property
    def ok(self) -> list[dict[str, Any]]:
        """The rows of the points that succeeded (settled or not).

        Returns
        -------
        list of dict
            The rows.
        """
        return [r for r in self.rows if r["status"] == "ok"]

    @property
    def unsettled(self) -> list[dict[str, Any]]:
        """The rows of the points that ran but had not settled by ``t_end``: their values are
        flagged (``settled`` False, the outputs that had not in ``unsettled``). Empty unless the
        sweep checks settling (:attr:`settling`).

        Returns
        -------
        list of dict
            The rows.
        """
        return [r for r in self.ok if self.settling == "checked" and not r["settled"]]


def describe_points(res: SweepResult) -> str:
    """The points of a sweep by outcome, as ``bearingsim sweep`` reports them: ``4 point(s): 3
    settled, 1 not settled (values flagged: settled False), 0 failed`` when the sweep checks
    settling (:attr:`SweepResult.settling`), otherwise ``4 point(s): 4 ok, 0 failed`` (a
    transient reported on purpose says its values were not checked for settling).

    Parameters
    ----------
    res : SweepResult
        A sweep's result.

    Returns
    -------
    str
        The counts.
    """
    ok = len(res.ok)
    if res.settling == "checked":
        unsettled = len(res.unsettled)
        outcome = (f"{ok - unsettled} settled, {unsettled} not settled"
                   + (" (values flagged: settled False)" if unsettled else ""))
    else:
        outcome = f"{ok} ok" + (" (transient on purpose: not checked for settling)"
                                if res.settling == "on purpose" else "")
    return f"{len(res.rows)} point(s): {outcome}, {len(res.failures)} failed"


def describe_failures(res: SweepResult) -> str:
    """One line per failed point: its values and the error.

    Parameters
    ----------
    res : SweepResult
        A sweep's result.

    Returns
    -------
    str
        The lines (empty without failures).
    """
    lines = []
    for f in res.failures:
        values = ", ".join(f"{k}={v!r}" for k, v in f["values"].items())
        lines.append(f"point {f['point']} ({values}): {f['error']}")
    return "\n".join(lines)
