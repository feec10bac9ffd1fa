"""Parameter sweeps of a scene on dask.distributed.

A sweep runs one scene over a grid (``--grid key=v1,v2,...``, the Cartesian product of all
grids) or a random sample (``--sample key=low:high --samples N``) of keys:

* ``inputs.<name>``: a number or an expression of ``t``;
* ``parameters.<name>``, ``initial.<state>``: numbers;
* ``simulation.<setting>``: ``t_end``, ``rtol``, ``atol``, ``method``, ``max_step``,
  ``n_points``, ``initial``;
* ``assembly.<argument>`` (also ``assembly.bearing.lubrication`` and ``assembly.fidelity``).

Every point is validated before anything runs. The model is assembled on the client once per
distinct structure (arguments that only change parameter values, such as the lubricant of a
Palmgren friction model, become parameter overrides), serialized with
``casadi.Function.serialize`` and scattered to the workers, which deserialize it once per process.
Results gather into one table (CSV; also Parquet when pyarrow is installed) with a progress bar;
a failing point is recorded with its parameters and error and does not affect the others.
"""

from __future__ import annotations

import copy
import itertools
import json
import math
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from bearingsim.checks import check_output_size
from bearingsim.errors import BearingsimError, ParameterError
from bearingsim.files import atomic_path, column_name
from bearingsim.scenes.portable import LOADS, load_cached, pack
from bearingsim.scenes.registry import build_component
from bearingsim.scenes.runner import Prepared, choose_fidelity, prepare, simulate_inputs
from bearingsim.scenes.scene import Scene, SceneError, TableInput, load_scene
from bearingsim.units import display_unit
from bearingsim.validation import check_count

__all__ = ["SweepError", "SweepResult", "parse_grid", "parse_sample", "grid_points",
           "sample_points", "run_sweep"]

SIM_KEYS = ("t_end", "t_start", "rtol", "atol", "method", "max_step", "n_points", "initial")


class SweepError(ParameterError):
    """A sweep specification is invalid (key, value or point), naming it."""


@dataclass
class SweepResult:
    """Rows of the result table (one per point), failures and written files."""

    keys: list[str]
    rows: list[dict[str, Any]]
    failures: list[dict[str, Any]]
    models_built: int
    files: list[Path] = field(default_factory=list)
    wall_s: float = 0.0

    @property
    def ok(self) -> list[dict[str, Any]]:
        """The rows of the points that succeeded."""
        return [r for r in self.rows if r["status"] == "ok"]


# --------------------------------------------------------------------------- specification
def _split_values(text: str) -> list[str]:
    """Split on ';' if present, else on commas outside parentheses, brackets and quotes (a
    TOML list such as ``["lithium grease", "ISO VG 32"]`` is one value)."""
    if ";" in text:
        return [v.strip() for v in text.split(";") if v.strip()]
    out, depth, cur, quote = [], 0, "", ""
    for ch in text:
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        if ch == "," and depth == 0 and not quote:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        out.append(cur.strip())
    return out


def _value(text: str) -> Any:
    """A grid value: a TOML list or quoted string as TOML reads it, true/false, a number, or
    the text itself."""
    if text.strip()[:1] in ("[", "\"", "'"):
        try:
            return tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            raise SweepError(f"grid value {text!r} is not a TOML value (a list needs quoted "
                             f"text: [\"lithium grease\", \"ISO VG 32\"])") from None
    low = text.strip().lower()
    if low in ("true", "false"):
        return low == "true"
    try:
        v = float(text)
    except ValueError:
        return text.strip()
    return int(v) if v.is_integer() and "." not in text and "e" not in low else v


def _check_key(key: str) -> None:
    head = key.split(".", 1)[0]
    if head not in ("inputs", "parameters", "initial", "simulation", "assembly") or "." not in key:
        raise SweepError(
            f"sweep key {key!r}: must start with inputs., parameters., initial., simulation. "
            "or assembly. (e.g. inputs.shaft_speed, parameters.inner_layer.nu, "
            "assembly.lubrication, simulation.rtol)")
    if head == "simulation" and key.split(".", 1)[1] not in SIM_KEYS:
        raise SweepError(f"sweep key {key!r}: allowed simulation settings: "
                         + ", ".join(SIM_KEYS))


def parse_grid(items: list[str]) -> dict[str, list[Any]]:
    """``["inputs.shaft_speed=100,200", ...]`` -> ``{"inputs.shaft_speed": ["100", "200"]}``.

    Values stay text here; they are converted by the type the key expects when a point is
    applied to a scene (numbers for parameters, designations stay text).
    """
    grid: dict[str, list[Any]] = {}
    for item in items:
        if "=" not in item:
            raise SweepError(f"--grid {item!r}: expected key=v1,v2,...")
        key, values = item.split("=", 1)
        key = key.strip()
        _check_key(key)
        vals = _split_values(values)
        if not vals:
            raise SweepError(f"--grid {key}: no values")
        grid[key] = vals
    return grid


def parse_sample(items: list[str]) -> dict[str, tuple[float, float]]:
    """``["parameters.shaft.J=1e-4:1e-3"]`` -> ``{"parameters.shaft.J": (1e-4, 1e-3)}``."""
    ranges = {}
    for item in items:
        if "=" not in item or ":" not in item.split("=", 1)[1]:
            raise SweepError(f"--sample {item!r}: expected key=low:high")
        key, rng = item.split("=", 1)
        key = key.strip()
        _check_key(key)
        try:
            lo, hi = (float(x) for x in rng.split(":", 1))
        except ValueError:
            raise SweepError(f"--sample {key}: low and high must be numbers, got {rng!r}"
                             ) from None
        if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
            raise SweepError(f"--sample {key}: need finite low < high, got {rng!r}")
        ranges[key] = (lo, hi)
    return ranges


def grid_points(grid: dict[str, list[Any]]) -> list[dict[str, Any]]:
    """The Cartesian product of a grid, as a list of {key: value}."""
    keys = list(grid)
    check_output_size(math.prod(len(v) for v in grid.values()), 300 + 100 * len(keys),
                      "the number of grid points", "grid_points")
    return [dict(zip(keys, combo, strict=True)) for combo in itertools.product(*grid.values())]


def sample_points(ranges: dict[str, tuple[float, float]], n: int, seed: int = 0
                  ) -> list[dict[str, Any]]:
    """``n`` Latin-hypercube points in the given ranges (reproducible with ``seed``)."""
    if n < 1:
        raise SweepError(f"--samples must be >= 1, got {n}")
    check_output_size(n, 300 + 100 * len(ranges), "--samples", "sample_points")
    rng = np.random.default_rng(seed)
    cols = {}
    for key, (lo, hi) in ranges.items():
        u = (rng.permutation(n) + rng.random(n)) / n
        cols[key] = lo + u * (hi - lo)
    return [{k: float(cols[k][i]) for k in ranges} for i in range(n)]


# --------------------------------------------------------------------------- planning
def _set_nested(d: dict, path: list[str], value: Any) -> None:
    for p in path[:-1]:
        d = d.setdefault(p, {})
    d[path[-1]] = value


def _coerce(scene: Scene, key: str, value: Any) -> Any:
    """A grid value converted to the type its key expects."""
    head, rest = key.split(".", 1)
    text_kinds = ("bearing", "lubricant", "choice")
    if head == "assembly":
        spec = scene.spec.args
        parts = rest.split(".")
        arg = None
        for part in parts:
            arg = spec.get(part) if spec else None
            spec = arg.table if arg is not None and arg.table else None
        if isinstance(value, str) and value.strip()[:1] in ("[", "\"", "'"):
            value = _value(value)
        if isinstance(value, list):
            return [str(v) for v in value]
        if rest == "fidelity" or (arg is not None and arg.kind in text_kinds):
            return str(value) if not isinstance(value, str) else value
        if arg is not None and arg.kind == "signal" and isinstance(value, str):
            v = _value(value)
            return v if not isinstance(v, bool) else value
    if head == "simulation" and rest in ("method", "initial"):
        return str(value)
    if isinstance(value, str):
        v = _value(value)
        return value if isinstance(v, bool) and head != "assembly" else v
    return value


def _point_scene(scene: Scene, point: dict[str, Any]) -> Scene:
    """The scene with the point's values applied, validated (errors name the sweep key)."""
    d = scene.to_dict()
    for key, value in point.items():
        value = _coerce(scene, key, value)
        head, rest = key.split(".", 1)
        if head == "assembly":
            _set_nested(d["assembly"], rest.split("."), value)
        else:
            d.setdefault(head, {})[rest] = value
    from bearingsim.scenes.scene import scene_from_dict

    try:
        return scene_from_dict(d, path=scene.path)
    except SceneError as exc:
        shown = ", ".join(f"{k}={v!r}" for k, v in point.items())
        why = "; ".join(p.key + ": " + p.reason + (f"; allowed: {p.allowed}" if p.allowed else "")
                        for p in exc.problems)
        raise SweepError(f"sweep point ({shown}): {why}") from None


def _parameter_values(component) -> dict[str, float]:
    from bearingsim.language.declarations import Parameter

    out = {}
    for comp in component.walk():
        for decl in comp.declarations.values():
            if isinstance(decl, Parameter) and decl.value is not None:
                out[decl.path] = float(decl.value)
    return out


def _structure(sc: Scene) -> tuple[str, str]:
    """Key of the model structure of a point: fidelity and the non-parametric arguments."""
    spec = sc.spec
    args = spec.with_defaults(sc.args)
    post_all = spec.post(args)
    post = {n: post_all[n] for n in (sc.outputs or spec.default_outputs) if n in post_all}
    fidelity, _, _ = choose_fidelity(sc, spec, post)
    stripped = copy.deepcopy(args)
    for key, holds in spec.parametric_args.items():
        if holds(args):
            path, d = key.split("."), stripped
            for p in path[:-1]:
                d = d.get(p, {})
            d.pop(path[-1], None)
    return fidelity, json.dumps(stripped, sort_keys=True, default=str)


@dataclass
class _Plan:
    prepared: dict[tuple, Prepared]
    packed: dict[tuple, dict]
    jobs: list[dict[str, Any]]


def _plan(scene: Scene, points: list[dict[str, Any]]) -> _Plan:
    spec = scene.spec
    scenes = [_point_scene(scene, p) for p in points]
    prepared: dict[tuple, Prepared] = {}
    packed: dict[tuple, dict] = {}
    base_values: dict[tuple, dict[str, float]] = {}
    jobs = []
    for k, (raw, sc) in enumerate(zip(points, scenes, strict=True)):
        pt = {key: _coerce(scene, key, v) for key, v in raw.items()}
        key = _structure(sc)
        if key not in prepared:
            try:
                prep = prepare(sc)
            except SceneError as exc:
                raise SweepError(f"sweep point {pt}: {exc}") from None
            prepared[key] = prep
            packed[key] = pack(prep.system)
            base_values[key] = _parameter_values(build_component(spec, prep.args, prep.fidelity))
        prep = prepared[key]
        params: dict[str, float] = {}
        args = spec.with_defaults(sc.args)
        if json.dumps(args, sort_keys=True, default=str) != json.dumps(
                prep.args, sort_keys=True, default=str):
            # parametric arguments differ from the assembled ones: parameter overrides
            new = _parameter_values(build_component(spec, args, prep.fidelity))
            if set(new) != set(base_values[key]):
                raise SweepError(f"sweep point {pt}: the arguments change the model structure "
                                 "although declared parametric; please report")
            params.update({n: v for n, v in new.items()
                           if n in prep.system.parameter_names and v != base_values[key][n]})
        params.update(sc.parameters)
        try:
            prep.system.p0(params)
        except ParameterError as exc:
            raise SweepError(f"sweep point {pt}: {exc}") from None
        for name in sc.inputs:
            if name not in prep.system.input_names:
                raise SweepError(f"sweep point {pt}: the model has no input {name!r}; inputs: "
                                 + ", ".join(prep.system.input_names))
        inputs = {n: ((list(v.times), list(v.values)) if isinstance(v, TableInput) else v)
                  for n, v in sc.inputs.items()}
        s = sc.simulation
        jobs.append({
            "index": k, "point": pt, "structure": key, "parameters": params, "inputs": inputs,
            "x0": dict(sc.initial),
            "sim": {"t_end": s.t_end, "t_start": s.t_start, "method": s.method, "rtol": s.rtol,
                    "atol": s.atol, "n_points": s.n_points, "max_step": s.max_step,
                    "initial": s.initial},
            "outputs": list(prep.model_outputs),
        })
    return _Plan(prepared, packed, jobs)


# --------------------------------------------------------------------------- execution
def run_point(packed: dict[str, Any], job: dict[str, Any]) -> dict[str, Any]:
    """Run one sweep point (on a worker): returns final values or the error; never raises."""
    from bearingsim.simulation import simulate

    t0 = time.perf_counter()
    out = {"index": job["index"], "pid": os.getpid(), "token": packed["token"]}
    try:
        system = load_cached(packed)
        inputs = {n: (tuple(np.asarray(x, dtype=float) for x in v) if isinstance(v, (list, tuple))
                      else v) for n, v in job["inputs"].items()}
        sim = dict(job["sim"])
        t_end = sim.pop("t_end")
        res = simulate(system, t_end, inputs=simulate_inputs(inputs),
                       parameters=job["parameters"] or None, x0=job["x0"] or None,
                       progress=False, **sim)
        final = {}
        for n in job["outputs"]:
            y = np.asarray(res[n], dtype=float)
            if not np.all(np.isfinite(y)):
                raise BearingsimError(f"output {n} is not finite")
            final[n] = float(y[-1])
        out.update(status="ok", final=final, error="",
                   nsteps=int(res.stats.get("nfev", res.stats.get("nsteps", 0)) or 0))
    except Exception as exc:  # noqa: BLE001 - a failed point is reported, never fatal
        out.update(status="failed", final={}, error=f"{type(exc).__name__}: {exc}")
    out["wall_s"] = time.perf_counter() - t0
    out["model_loads"] = LOADS.get(packed["token"], 0)
    return out


def _distributed():
    """The ``distributed`` package, or a named error saying how to install it."""
    try:
        import distributed
    except ImportError:
        raise SweepError("sweeps run on dask.distributed, which is not installed: "
                         "pip install 'bearingsim[dask]'") from None
    return distributed


def _client(scheduler: str | None, n_workers: int):
    distributed = _distributed()
    Client, LocalCluster = distributed.Client, distributed.LocalCluster  # noqa: N806

    if scheduler:
        return Client(scheduler), None
    cluster = LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=40)
    return Client(cluster), cluster


def _column_units(plan_prepared: dict, keys: list[str]) -> dict[str, str]:
    """Unit of every numeric sweep column: the swept inputs, parameters and initial values and
    the outputs (from the first model; every model of a sweep has the same outputs)."""
    prep = next(iter(plan_prepared.values()))
    system = prep.system
    units = system.variable_units
    units.update({n: q.unit for n, q in prep.post.items()})
    units.update({p.name: p.unit for p in system.params})
    out = {n: units[n] for n in prep.outputs if n in units}
    for key in keys:
        head, _, name = key.partition(".")
        if head in ("inputs", "parameters", "initial") and name in units:
            out[key] = units[name]
    out["wall_s"] = "s"
    return out


def _write_table(rows: list[dict[str, Any]], folder: Path, stem: str,
                 units: dict[str, str]) -> list[Path]:
    """The sweep table: one row per point, headers ``name [unit]`` for the numeric columns
    (readable by ``pandas.read_csv`` without options), and a Parquet copy with pyarrow."""
    import csv

    cols: list[str] = []
    for r in rows:
        for k in r:
            if k not in cols:
                cols.append(k)
    path = folder / f"{stem}.csv"
    with atomic_path(path) as tmp, tmp.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow([column_name(k, units[k]) if k in units else k for k in cols])
        for r in rows:
            w.writerow([r.get(k, "") for k in cols])
    files = [path]
    try:
        import pyarrow  # noqa: F401
        import pyarrow.csv as pacsv
        import pyarrow.parquet as pq

        pq.write_table(pacsv.read_csv(path), folder / f"{stem}.parquet")
        files.append(folder / f"{stem}.parquet")
    except ImportError:
        pass
    return files


def _sweep_plot(rows: list[dict[str, Any]], keys: list[str], units: dict[str, str],
                folder: Path, stem: str) -> list[Path]:
    """``<stem>.png``: each output against the first numeric swept key (engineering units),
    one panel per output; none when no swept key is numeric."""
    from matplotlib.figure import Figure

    ok = [r for r in rows if r["status"] == "ok"]
    numeric = [k for k in keys if ok and all(isinstance(r.get(k), (int, float)) for r in ok)]
    outputs = [k for k in units if k not in keys and k != "wall_s"]
    if not numeric or not outputs:
        return []
    x_key = numeric[0]
    x = np.array([r[x_key] for r in ok], dtype=float)
    order = np.argsort(x)
    x_factor, x_unit = display_unit(units.get(x_key, ""), x)
    fig = Figure(figsize=(7, 1.9 * len(outputs) + 1))
    axes = np.atleast_1d(fig.subplots(len(outputs), 1, sharex=True))
    for ax, name in zip(axes, outputs, strict=True):
        y = np.array([r[name] for r in ok], dtype=float)
        factor, unit = display_unit(units[name], y)
        ax.plot(x[order] * x_factor, y[order] * factor, "o-")
        ax.set_ylabel(f"{name}\n[{unit}]", fontsize=8)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(f"{x_key} [{x_unit}]")
    fig.tight_layout()
    path = folder / f"{stem}.png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110)
    return [path]


def run_sweep(scene: Scene | str | Path, points: list[dict[str, Any]], *,
              scheduler: str | None = None, n_workers: int = 2, out: str | Path | None = None,
              progress: bool = True, client=None) -> SweepResult:
    """Run a scene at every point on dask.distributed and gather one table.

    Parameters
    ----------
    scene : Scene or path
    points : list of dict
        From :func:`grid_points` or :func:`sample_points`.
    scheduler : str, optional
        Address of a running dask scheduler (``tcp://host:8786``); default: a LocalCluster.
    n_workers : int
        Workers of the LocalCluster.
    out : path, optional
        Folder for ``<scene>.sweep.csv`` (and ``.parquet``) and ``.sweep.json``; None: no files.
    progress : bool
        Show a progress bar.
    client : distributed.Client, optional
        Use this client (and leave it open).

    Raises
    ------
    SweepError
        For an invalid key or point (before anything runs).
    """
    check_count(n_workers, "n_workers", 1, "run_sweep")
    as_completed = _distributed().as_completed
    from tqdm import tqdm

    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    if not points:
        raise SweepError("a sweep needs at least one point")
    wall = time.perf_counter()
    plan = _plan(scene, points)
    own = client is None
    cluster = None
    if own:
        client, cluster = _client(scheduler, n_workers)
    try:
        # a dict given to scatter is stored key by key ("token", "fields": the same keys for
        # every model), so each packed model goes in a list of its own
        shipped = {k: client.scatter([v], broadcast=True)[0] for k, v in plan.packed.items()}
        futures = {}
        for job in plan.jobs:
            fut = client.submit(run_point, shipped[job["structure"]], job, pure=False,
                                key=f"sweep-point-{job['index']}-{time.time_ns()}")
            futures[fut] = job
        results: dict[int, dict[str, Any]] = {}
        bar = tqdm(total=len(futures), unit="point", disable=not progress, leave=False)
        for fut in as_completed(futures):
            job = futures[fut]
            try:
                r = fut.result()
            except Exception as exc:  # noqa: BLE001 - a lost worker fails only its point
                r = {"index": job["index"], "status": "failed", "final": {},
                     "error": f"{type(exc).__name__}: {exc}", "wall_s": float("nan")}
            results[job["index"]] = r
            bar.update(1)
        bar.close()
    finally:
        if own:
            client.close()
            if cluster is not None:
                cluster.close()
    keys = list(points[0])
    rows, failures = [], []
    for job in plan.jobs:
        r = results[job["index"]]
        prep = plan.prepared[job["structure"]]
        row: dict[str, Any] = {"point": job["index"], **job["point"], "status": r["status"]}
        finals = {k: np.array([v]) for k, v in r["final"].items()}
        for name in prep.outputs:
            if r["status"] != "ok":
                row[name] = float("nan")
            elif name in prep.post:
                row[name] = float(prep.post[name].compute(finals, {"args": prep.args})[0])
            else:
                row[name] = r["final"][name]
        row["wall_s"] = round(float(r.get("wall_s", float("nan"))), 4)
        row["error"] = r["error"]
        rows.append(row)
        if r["status"] != "ok":
            failures.append({"point": job["index"], "values": job["point"], "error": r["error"]})
    res = SweepResult(keys, rows, failures, len(plan.prepared))
    res.wall_s = time.perf_counter() - wall
    if out is not None:
        folder = Path(out)
        folder.mkdir(parents=True, exist_ok=True)
        stem = (Path(scene.path).stem if scene.path else scene.assembly) + ".sweep"
        units = _column_units(plan.prepared, keys)
        res.files = _write_table(rows, folder, stem, units)
        res.files += _sweep_plot(rows, keys, units, folder, stem)
        summary = {
            "scene": scene.path, "points": len(rows), "ok": len(res.ok),
            "failed": len(failures), "failures": failures, "models_built": res.models_built,
            "structures": [{"fidelity": k[0], "arguments": json.loads(k[1])}
                           for k in plan.prepared],
            "model_loads_per_worker": sorted({(r.get("pid"), r.get("model_loads"))
                                              for r in results.values() if "pid" in r}),
            "scheduler": scheduler or f"LocalCluster({n_workers} workers)",
            "wall_s": round(res.wall_s, 3),
        }
        path = folder / f"{stem}.json"
        with atomic_path(path) as tmp:
            tmp.write_text(json.dumps(summary, indent=2, default=str))
        res.files.append(path)
    return res


def describe_failures(res: SweepResult) -> str:
    """One line per failed point: its values and the error."""
    lines = []
    for f in res.failures:
        values = ", ".join(f"{k}={v!r}" for k, v in f["values"].items())
        lines.append(f"point {f['point']} ({values}): {f['error']}")
    return "\n".join(lines)
