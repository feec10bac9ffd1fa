"""The modules a scene's sweep workers import at their first point, learned from one sweep and
imported by the next sweep's fork server before it forks the workers."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import bearingsim
from bearingsim.scenes import load_scene
from bearingsim.scenes.library import FOLDER, builtin_scenes
from bearingsim.scenes.sweep import run_sweep
from bearingsim.sweep_preloads import (
    BUILTIN_SCENES,
    MAX_PRELOADS,
    imported_since,
    learned_preloads,
    remember_preloads,
    scene_file,
)
from bearingsim.sweep_server import PRELOAD_VARIABLE, WORKER_MODULES, import_learned


def test_the_scene_file_is_the_one_load_scene_reads(tmp_path, monkeypatch):
    assert BUILTIN_SCENES == FOLDER
    for name in builtin_scenes():
        expected = Path(load_scene(name).path).resolve()
        assert scene_file(name) == expected
        assert scene_file(f"{name}.toml") == expected
    monkeypatch.chdir(tmp_path)
    (tmp_path / "double_layer_rs.toml").write_text((FOLDER / "double_layer_rs.toml").read_text())
    # a file of that name in the current folder comes first, as for load_scene
    assert scene_file("double_layer_rs.toml") == tmp_path / "double_layer_rs.toml"
    assert scene_file("no_such_scene") is None
    assert scene_file(None) is None  # a scene made without a file


def test_records_keep_the_union_of_valid_module_names(tmp_path, monkeypatch):
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path / "cache"))
    scene = tmp_path / "s.toml"
    assert learned_preloads(scene) == ()
    remember_preloads(scene, ["scipy.linalg", "scipy._lib", "os; rm -rf ~", "a.b.c", "numpy"])
    assert learned_preloads(scene) == ("numpy", "scipy.linalg")
    remember_preloads(scene, ["scipy.optimize", "numpy"])  # added, not replaced
    assert learned_preloads(scene) == ("numpy", "scipy.linalg", "scipy.optimize")
    assert learned_preloads(tmp_path / "other.toml") == ()
    remember_preloads(None, ["scipy.fft"])
    assert learned_preloads(None) == ()
    remember_preloads(scene, [f"m{k}" for k in range(2 * MAX_PRELOADS)])
    assert len(learned_preloads(scene)) == MAX_PRELOADS
    record = next((tmp_path / "cache" / "sweep_preloads").iterdir())
    record.write_bytes(b"\xff\xfe")
    assert learned_preloads(scene) == ()  # a record that cannot be read preloads nothing


def test_a_cache_that_cannot_be_written_is_no_error(tmp_path, monkeypatch):
    (tmp_path / "cache").write_text("a file where the cache folder should be")
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path / "cache"))
    remember_preloads(tmp_path / "s.toml", ["scipy.linalg"])
    assert learned_preloads(tmp_path / "s.toml") == ()


def test_imported_since_names_new_public_modules(tmp_path, monkeypatch):
    (tmp_path / "bsm_probe_pkg").mkdir()
    (tmp_path / "bsm_probe_pkg" / "__init__.py").write_text("from . import inner, _private\n")
    (tmp_path / "bsm_probe_pkg" / "inner.py").write_text("")
    (tmp_path / "bsm_probe_pkg" / "_private.py").write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    baseline = frozenset(sys.modules)
    import bsm_probe_pkg  # noqa: F401

    assert imported_since(baseline) == ["bsm_probe_pkg", "bsm_probe_pkg.inner"]
    for name in ("bsm_probe_pkg", "bsm_probe_pkg.inner", "bsm_probe_pkg._private"):
        monkeypatch.delitem(sys.modules, name)


def test_the_server_imports_each_learned_module_on_its_own(tmp_path, monkeypatch):
    """multiprocessing's fork server skips a preload that raises ImportError but dies of any
    other error: a learned module that raises as it is imported must not stop the sweeps."""
    (tmp_path / "bsm_probe_raises.py").write_text("raise RuntimeError('not today')\n")
    (tmp_path / "bsm_probe_fine.py").write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setenv(PRELOAD_VARIABLE, "bsm_probe_raises bsm_probe_gone bsm_probe_fine")
    import_learned()
    assert "bsm_probe_fine" in sys.modules and "bsm_probe_raises" not in sys.modules
    assert PRELOAD_VARIABLE not in os.environ  # the workers forked after it do not see it
    monkeypatch.delitem(sys.modules, "bsm_probe_fine")


def test_the_next_sweep_of_a_scene_preloads_what_its_workers_imported(tmp_path):
    """A steady point solves with LAPACK's gesv from scipy.linalg: the first sweep's worker
    imports it at its first point (~0.25 s, every worker), the summary says so and the record
    keeps it; the next sweep's fork server imports it before forking, and its worker imports
    nothing more. Before, every sweep's every worker imported it at its first point."""
    scene = tmp_path / "rs.toml"
    scene.write_text((FOLDER / "double_layer_rs.toml").read_text())
    env = {**os.environ, "BEARINGSIM_CACHE": str(tmp_path / "cache"),
           "PYTHONPATH": str(Path(bearingsim.__file__).parents[1])}
    summaries = []
    for k in range(2):
        proc = subprocess.run(
            [sys.executable, "-m", "bearingsim.cli", "sweep", str(scene), "--grid",
             "inputs.shaft_speed=100,200", "--grid", "inputs.Fr=0", "--workers", "1",
             "--no-progress", "--out", str(tmp_path / f"out{k}")],
            capture_output=True, text=True, timeout=240, env=env)
        assert proc.returncode == 0, proc.stderr
        summaries.append(json.loads((tmp_path / f"out{k}" / "rs.sweep.json").read_text()))
    first, second = summaries
    assert first["worker_preloads"] == list(WORKER_MODULES)
    assert "scipy.linalg" in first["worker_imports"]
    assert second["worker_preloads"][:2] == list(WORKER_MODULES)
    assert set(first["worker_imports"]) <= set(second["worker_preloads"])
    assert "scipy.linalg" not in second["worker_imports"]
    assert first["failed"] == second["failed"] == 0


def test_an_in_process_worker_reports_no_imports_of_its_own(client, tmp_path, monkeypatch):
    """A worker thread in the client's process shares its modules: what the client imported
    meanwhile (the figure's matplotlib, a first-use scipy module) is not the points' and is
    neither reported nor kept."""
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path / "cache"))
    scene = tmp_path / "rs.toml"
    scene.write_text((FOLDER / "double_layer_rs.toml").read_text())
    (tmp_path / "bsm_probe_late.py").write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    import bsm_probe_late  # noqa: F401 - a module the process imports after the worker module

    run_sweep(scene, [{"inputs.shaft_speed": 100.0, "inputs.Fr": 0.0}], client=client,
              out=tmp_path / "out", progress=False)
    summary = json.loads((tmp_path / "out" / "rs.sweep.json").read_text())
    assert summary["worker_imports"] == [] and summary["worker_preloads"] is None
    assert learned_preloads(scene.resolve()) == ()
    monkeypatch.delitem(sys.modules, "bsm_probe_late")
