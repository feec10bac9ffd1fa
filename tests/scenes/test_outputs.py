"""Outputs that survive faults (issue 30, items 5 and 6).

One writer per output folder (a lock naming its holder), every file whole, the summary last
and naming its files, a killed run never leaving a summary that describes other data, a plot
failure reported as such, file errors as one-line errors with exit status 2. Each test fails on
the code before issue 30: two runs wrote into one folder at once, the old summary stayed beside
a new CSV, a failing plot was "simulation failed", ``Result.to_csv`` into a missing folder
raised ``FileNotFoundError`` naming a ``.part.csv``.
"""

from __future__ import annotations

import csv
import errno
import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from bearingsim.cli import main
from bearingsim.errors import BearingsimError, SimulationError
from bearingsim.files import FileAccessError, atomic_write_text
from bearingsim.scenes.outputs import LOCK_NAME, OutputFolder, OutputFolderBusy, file_record
from bearingsim.simulation import Result

ROOT = Path(__file__).resolve().parents[2]

FAST = """
title = "outputs test"
outputs = ["Rs"]
[assembly]
name = "double_layer_bearing"
[inputs]
shaft_speed = "rpm({rpm}) * ramp(0, 0.1)"
[simulation]
t_end = 0.2
n_points = 21
[output]
folder = "out"
"""


def _scene(folder: Path, rpm: float = 1000.0) -> Path:
    path = folder / "fast.toml"
    path.write_text(FAST.format(rpm=rpm))
    return path


def _python(code: str, **kwargs) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.Popen([sys.executable, "-c", textwrap.dedent(code)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)


def _consistent(folder: Path) -> bool:
    """The summary (if any) describes the files beside it: each listed file has the size and
    SHA-256 recorded, and the final value of Rs is the CSV's last row."""
    summary_path = folder / "fast.summary.json"
    if not summary_path.exists():
        return True
    summary = json.loads(summary_path.read_text())
    rows = list(csv.reader((folder / "fast.csv").open()))
    if float(rows[-1][1]) != pytest.approx(summary["outputs"]["Rs"]["final"], rel=1e-12):
        return False
    return all(isinstance(r, dict) and file_record(folder / r["name"]) == r
               for r in summary["files"])


# ----------------------------------------------------------------------------- lock
def test_a_second_run_into_a_busy_folder_says_who_holds_it(tmp_path, capsys):
    """Issue 30: two runs into one folder at once both wrote."""
    out = tmp_path / "out"
    holder = _python(f"""
        import sys, time
        from bearingsim.scenes.outputs import OutputFolder
        with OutputFolder({str(out)!r}, "bearingsim run other.toml"):
            print("locked", flush=True)
            sys.stdin.read()
        """, stdin=subprocess.PIPE)
    try:
        assert holder.stdout.readline().strip() == "locked"
        assert main(["run", str(_scene(tmp_path)), "--out", str(out), "--no-progress"]) == 2
        err = capsys.readouterr().err
        assert f"held by process {holder.pid} on host" in err
        assert "bearingsim run other.toml" in err and err.count("\n") == 1
        assert not (out / "fast.csv").exists()
    finally:
        holder.communicate("", timeout=30)
    # released when the holder ends (also by SIGKILL: the operating system drops the flock)
    assert main(["run", str(_scene(tmp_path)), "--out", str(out), "--no-progress"]) == 0


def test_the_lock_is_released_when_the_holder_is_killed(tmp_path):
    holder = _python(f"""
        import sys
        from bearingsim.scenes.outputs import OutputFolder
        held = OutputFolder({str(tmp_path)!r}, "x").__enter__()  # never released
        print("locked", flush=True)
        sys.stdin.read()
        """, stdin=subprocess.PIPE)
    assert holder.stdout.readline().strip() == "locked"
    with pytest.raises(OutputFolderBusy), OutputFolder(tmp_path, "y"):
        pass
    holder.send_signal(signal.SIGKILL)
    holder.communicate(timeout=30)
    assert (tmp_path / LOCK_NAME).exists()  # left by the killed holder, locking nothing
    with OutputFolder(tmp_path, "y") as out:
        assert json.loads((tmp_path / LOCK_NAME).read_text())["pid"] == os.getpid()
        assert out.files == []
    assert not (tmp_path / LOCK_NAME).exists()


# ----------------------------------------------------------------------------- killed runs
def test_a_run_killed_after_replacing_the_csv_leaves_no_stale_summary(tmp_path):
    """Issue 30: a run killed with SIGKILL left partial files beside a stale summary."""
    out = tmp_path / "out"
    assert main(["run", str(_scene(tmp_path, 1000.0)), "--out", str(out), "--no-progress"]) == 0
    assert _consistent(out)
    first = (out / "fast.csv").read_text()
    # the second run (another speed) kills itself with SIGKILL once its CSV has replaced the
    # first one's, before its plots and summary
    killed = _python(f"""
        import os, signal
        import bearingsim.scenes.runner as runner
        real = runner.write_series_csv
        def write_then_die(*args, **kwargs):
            real(*args, **kwargs)
            os.kill(os.getpid(), signal.SIGKILL)
        runner.write_series_csv = write_then_die
        from bearingsim.cli import main
        main(["run", {str(_scene(tmp_path, 3000.0))!r}, "--out", {str(out)!r}, "--overwrite",
              "--no-progress"])
        """)
    killed.communicate(timeout=300)
    assert killed.returncode == -signal.SIGKILL
    assert (out / "fast.csv").read_text() != first  # the new data is there ...
    assert _consistent(out)  # ... and no summary describes the old one


def test_a_run_killed_mid_write_leaves_a_part_file_that_the_next_run_removes(tmp_path):
    out = tmp_path / "out"
    killed = _python(f"""
        import os, signal
        import bearingsim.files as files
        def half_then_die(path, t, columns, units):
            with files.atomic_path(path) as tmp:
                tmp.write_text("time [s],Rs [-]\\n0,0\\n")
                os.kill(os.getpid(), signal.SIGKILL)
        import bearingsim.scenes.runner as runner
        runner.write_series_csv = half_then_die
        from bearingsim.cli import main
        main(["run", {str(_scene(tmp_path))!r}, "--out", {str(out)!r}, "--no-progress"])
        """)
    killed.communicate(timeout=300)
    assert killed.returncode == -signal.SIGKILL
    parts = [p.name for p in out.iterdir() if ".part" in p.name]
    assert parts == [f".fast.{killed.pid}.part.csv"]
    assert not (out / "fast.csv").exists() and not (out / "fast.summary.json").exists()
    assert main(["run", str(_scene(tmp_path)), "--out", str(out), "--no-progress"]) == 0
    assert not [p for p in out.iterdir() if ".part" in p.name]
    assert _consistent(out)


def test_the_summary_is_written_last_and_names_its_files(tmp_path):
    out = tmp_path / "out"
    assert main(["run", str(_scene(tmp_path)), "--out", str(out), "--no-progress"]) == 0
    summary = json.loads((out / "fast.summary.json").read_text())
    names = [r["name"] for r in summary["files"]]
    assert names == ["fast.csv", "fast.rs_speed.png", "fast.png"]
    assert summary["plot_failures"] == []
    mtimes = {p.name: p.stat().st_mtime_ns for p in out.iterdir()}
    assert max(mtimes, key=mtimes.get) == "fast.summary.json"
    assert _consistent(out)


# ----------------------------------------------------------------------------- plot failure
def test_a_failing_plot_is_a_plot_failure_not_a_simulation_failure(tmp_path, monkeypatch,
                                                                     capsys):
    """Issue 30: a duplex run whose modes plot failed reported "simulation failed" and left
    the new CSV beside the old summary and plots."""
    import bearingsim.scenes.runner as runner

    out = tmp_path / "out"
    assert main(["run", str(_scene(tmp_path, 1000.0)), "--out", str(out), "--no-progress"]) == 0
    capsys.readouterr()

    def failing_figures(*args, **kwargs):
        raise SimulationError("modes: the linearisation did not converge at t = 0.2 s")

    monkeypatch.setattr(runner, "scene_figures", failing_figures)
    assert main(["run", str(_scene(tmp_path, 3000.0)), "--out", str(out), "--overwrite",
                 "--no-progress"]) == 1
    err = capsys.readouterr().err
    assert "plot failed: all figures: SimulationError: modes" in err
    assert "simulation failed" not in err
    summary = json.loads((out / "fast.summary.json").read_text())
    assert [r["name"] for r in summary["files"]] == ["fast.csv"]
    assert summary["plot_failures"][0]["plot"] == "all figures"
    assert _consistent(out)
    assert sorted(p.name for p in out.iterdir()) == ["fast.csv", "fast.summary.json"]


# ----------------------------------------------------------------------------- file errors
def _result() -> Result:
    t = np.linspace(0.0, 1.0, 5)
    return Result(t, ["x"], np.vstack([t ** 2]), {"x": "m"})


def test_result_to_csv_into_a_missing_folder_is_a_named_error(tmp_path):
    """Issue 30: ``FileNotFoundError`` on a ``.part.csv``."""
    path = tmp_path / "missing" / "r.csv"
    with pytest.raises(FileAccessError) as info:
        _result().to_csv(path)
    assert isinstance(info.value, BearingsimError)
    assert str(info.value) == f"cannot write {path}: the folder or file does not exist"


@pytest.mark.parametrize("code, reason", [
    (errno.ENOSPC, "no space left on the device"),
    (errno.EROFS, "the file system is read-only"),
    (errno.EACCES, "permission denied"),
])
def test_a_failing_write_is_one_line_and_leaves_nothing(tmp_path, monkeypatch, code, reason):
    """A full disk or read-only folder (simulated: the write fails; the tests may run as
    root, which ignores permissions)."""
    import bearingsim.files as files

    def failing_replace(src, dst):
        raise OSError(code, os.strerror(code), str(src))

    monkeypatch.setattr(files.os, "replace", failing_replace)
    with pytest.raises(FileAccessError, match=f"cannot write .*r.csv: {reason}$"):
        _result().to_csv(tmp_path / "r.csv")
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(FileAccessError, match=reason):
        atomic_write_text(tmp_path / "a.txt", "x")


def _errors(err: str) -> str:
    """Standard error of a command without its warning lines."""
    return "".join(line for line in err.splitlines(keepends=True)
                   if not line.startswith("bearingsim run: warning: "))


def test_the_cli_reports_file_errors_in_one_line_with_exit_2(tmp_path, monkeypatch, capsys):
    import bearingsim.files as files

    blocker = tmp_path / "file"
    blocker.write_text("")
    assert main(["run", str(_scene(tmp_path)), "--out", str(blocker / "out"),
                 "--no-progress"]) == 2
    err = _errors(capsys.readouterr().err)  # the run's warnings are lines of their own
    assert err.count("\n") == 1 and "cannot use the output folder" in err

    def full_disk(src, dst):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(src))

    monkeypatch.setattr(files.os, "replace", full_disk)
    assert main(["run", str(_scene(tmp_path)), "--out", str(tmp_path / "o"),
                 "--no-progress"]) == 2
    err = _errors(capsys.readouterr().err)
    assert err.count("\n") == 1 and "fast.csv: no space left on the device" in err
    assert not (tmp_path / "o" / "fast.summary.json").exists()


def _zlib_level(png: bytes) -> int:
    """FLEVEL of a PNG's image data (the zlib header's two top bits of its second byte:
    0 fastest, 1 fast, 2 default, 3 best; RFC 1950, section 2.2)."""
    at = png.index(b"IDAT") + 4
    return png[at + 1] >> 6


def test_figures_are_written_with_fast_png_compression(tmp_path):
    """A sweep's four-panel figure took 0.5 s to write at Pillow's default zlib level 6, a
    large share of a sweep's fixed cost; level 1 writes it in 0.3 s for a 9 % larger file."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(4, 3))
    fig.subplots().plot(np.arange(100.0), np.sin(np.arange(100.0)))
    with OutputFolder(tmp_path, "test") as folder:
        folder.save_figures(lambda: [("f.png", fig)])
    png = (tmp_path / "f.png").read_bytes()
    assert png.startswith(b"\x89PNG") and _zlib_level(png) == 0
