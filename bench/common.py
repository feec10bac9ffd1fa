"""Shared helpers of the benchmarks: timing, fits, Markdown tables, machine description."""

from __future__ import annotations

import compileall
import contextlib
import datetime as _dt
import io
import os
import platform
import statistics
import subprocess
import tarfile
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

__all__ = [
    "Section",
    "machine_info",
    "sweep_command",
    "median_call_time",
    "loglog_slope",
    "interp_loglog",
    "markdown_table",
    "peak_rss_reset",
    "peak_rss_kib",
    "fmt",
    "CasePart",
    "case_report",
    "case_text",
    "case_command_line",
    "scene_command",
    "byte_compiled",
]


@dataclass
class Section:
    """One benchmark's report: a title, Markdown body and raw numbers.

    Attributes
    ----------
    title : str
        Heading of the section.
    body : str
        Markdown text (tables, remarks, image links).
    data : dict
        Raw numbers, for callers that want more than the text.
    """

    title: str
    body: str
    data: dict = field(default_factory=dict)


ROOT = Path(__file__).resolve().parents[1]
"""The checkout the benchmarks run in."""


def byte_compiled(folder: Path) -> None:
    """Write the bytecode of the package ``bearingsim`` in ``folder``, as pip writes it for an
    install: a process that imports it then reads the bytecode instead of compiling every
    module (0.5-0.6 s of each command where the environment sets PYTHONDONTWRITEBYTECODE,
    as this machine's does), for this checkout and a baseline's export alike. Only what
    changed is compiled.

    Parameters
    ----------
    folder : Path
        The folder holding ``bearingsim``.
    """
    compileall.compile_dir(folder / "bearingsim", quiet=1)


@contextlib.contextmanager
def exported_package(commit: str) -> Iterator[dict[str, str]]:
    """The package ``bearingsim`` at ``commit``, exported from git into a temporary folder
    for the ``with`` block; yields the environment a Python process needs to import it
    instead of this checkout's (with this checkout's ``bench`` and ``tests`` on the path),
    both byte-compiled (:func:`byte_compiled`), so that neither compiles its modules in
    every process.

    Parameters
    ----------
    commit : str
        A commit of this repository.

    Yields
    ------
    dict of str to str
        ``os.environ`` with ``PYTHONPATH`` (the export first) and ``PYTHONSAFEPATH``
        (``-m`` would otherwise put the working folder, this checkout, first).
    """
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", commit, "bearingsim"],
                                 check=True, capture_output=True).stdout
        with tarfile.open(fileobj=io.BytesIO(archive)) as tar:
            tar.extractall(tmp, filter="data")
        byte_compiled(Path(tmp))
        byte_compiled(ROOT)
        yield {**os.environ, "PYTHONPATH": os.pathsep.join([tmp, str(ROOT)]),
               "PYTHONSAFEPATH": "1"}


CLI = "import sys; from bearingsim.cli import main; sys.exit(main(sys.argv[1:]))"
"""``python -c CLI <arguments>`` runs ``bearingsim <arguments>`` with the package that the
process's ``PYTHONPATH`` finds (a baseline's export, :func:`exported_package`)."""


def scene_command(env: dict[str, str], scene: str) -> tuple[float, float, dict]:
    """``bearingsim run scene --out <temporary folder> --no-progress`` in a new Python process.

    Parameters
    ----------
    env : dict of str to str
        The process's environment (:func:`exported_package` for a baseline's package).
    scene : str
        A shipped scene's name.

    Returns
    -------
    tuple of (float, float, dict)
        Wall time [s] from launch to exit, CPU time [s] of the process and its children, and
        the run's summary (``<scene>.summary.json``).
    """
    import json
    import resource
    import sys

    def children_cpu() -> float:
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        return usage.ru_utime + usage.ru_stime

    with tempfile.TemporaryDirectory() as out:
        cpu0, t0 = children_cpu(), time.perf_counter()
        subprocess.run([sys.executable, "-c", CLI, "run", scene, "--out", out,
                        "--no-progress"], check=True, capture_output=True, env=env, cwd=ROOT)
        wall, cpu = time.perf_counter() - t0, children_cpu() - cpu0
        summary = json.loads((Path(out) / f"{scene}.summary.json").read_text())
    return wall, cpu, summary


def sweep_command(env: dict[str, str], scene: str, arguments: list[str]
                  ) -> tuple[float, dict, list[float]]:
    """``bearingsim sweep scene <arguments> --out <temporary folder> --no-progress`` in a new
    Python process.

    Parameters
    ----------
    env : dict of str to str
        The process's environment (:func:`exported_package` for a baseline's package).
    scene : str
        A shipped scene's name.
    arguments : list of str
        The sweep's arguments (``--grid``, ``--workers``, ...).

    Returns
    -------
    tuple of (float, dict, list of float)
        Wall time [s] from launch to exit, the sweep's summary (``<scene>.sweep.json``) and
        each point's wall time [s] from its table.
    """
    import csv
    import json
    import sys

    with tempfile.TemporaryDirectory() as out:
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", CLI, "sweep", scene, *arguments, "--out", out,
                        "--no-progress"], check=True, capture_output=True, env=env, cwd=ROOT)
        wall = time.perf_counter() - t0
        summary = json.loads((Path(out) / f"{scene}.sweep.json").read_text())
        with (Path(out) / f"{scene}.sweep.csv").open(encoding="utf-8") as table:
            points = [float(v) for row in csv.DictReader(table)
                      for k, v in row.items() if k.startswith("wall_s") and v]
    return wall, summary, points


def machine_info() -> dict[str, str]:
    """Describe the machine and the numerical stack.

    Returns
    -------
    dict
        Cores, CPU model (from ``/proc/cpuinfo``), OS, and Python/numpy/scipy/casadi versions.
    """
    import casadi
    import scipy

    cpu = platform.processor() or "unknown"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:
        usable = os.cpu_count() or 0
    return {
        "cores": f"{usable} usable ({os.cpu_count()} logical)",
        "cpu": cpu,
        "os": platform.platform(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "casadi": casadi.__version__,
        "matplotlib": matplotlib.__version__,
        "date": _dt.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"),
    }


def median_call_time(fn: Callable[[], object], n_calls: int = 200, repeats: int = 7) -> float:
    """Median over ``repeats`` batches of the mean time of one call of ``fn`` [s].

    Parameters
    ----------
    fn : callable
        Function of no arguments.
    n_calls : int
        Calls per batch.
    repeats : int
        Number of batches.

    Returns
    -------
    float
        Median seconds per call.
    """
    fn()  # warm up
    per_call = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(n_calls):
            fn()
        per_call.append((time.perf_counter() - t0) / n_calls)
    return statistics.median(per_call)


def loglog_slope(x: Sequence[float], y: Sequence[float]) -> float:
    """Least-squares slope of ``log y`` against ``log x`` (the exponent ``k`` of ``y ~ x^k``)."""
    lx, ly = np.log(np.asarray(x, float)), np.log(np.asarray(y, float))
    return float(np.polyfit(lx, ly, 1)[0])


def interp_loglog(x_new: float, x: Sequence[float], y: Sequence[float]) -> float:
    """Interpolate ``y(x_new)`` linearly in log-log coordinates; NaN outside the data range.

    The points are sorted by ``x``; for non-monotone data this is a piecewise-linear path through
    the sorted points.
    """
    xs, ys = np.asarray(x, float), np.asarray(y, float)
    ok = (xs > 0) & (ys > 0) & np.isfinite(xs) & np.isfinite(ys)
    xs, ys = xs[ok], ys[ok]
    if xs.size < 2:
        return float("nan")
    order = np.argsort(xs)
    lx, ly = np.log(xs[order]), np.log(ys[order])
    lq = np.log(x_new)
    if lq < lx[0] or lq > lx[-1]:
        return float("nan")
    return float(np.exp(np.interp(lq, lx, ly)))


def fmt(value: float, digits: int = 3) -> str:
    """Format a number compactly (``g`` format); NaN becomes an em dash."""
    if value is None or (isinstance(value, float) and not np.isfinite(value)):
        return "—"
    return f"{value:.{digits}g}"


def markdown_table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A GitHub-flavoured Markdown table."""
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


@dataclass(frozen=True)
class CasePart:
    """One table a case-by-case benchmark can report: its heading, columns and rows.

    Attributes
    ----------
    heading : str
        The line above the table.
    header : sequence of str
        The column names.
    rows : callable
        A case -> the table's rows.
    """

    heading: str
    header: Sequence[str]
    rows: Callable[[object], list]


def case_report(parts: dict[str, CasePart], chosen: Sequence[str],
                cases: Sequence[object]) -> str:
    """The Markdown of the ``chosen`` parts for every case (an object with ``label`` and
    ``system()`` returning the assembled system first): per case a heading with its number
    of states, then each part's heading and table."""
    out = []
    for case in cases:
        system = case.system()[0]
        out.append(f"### {case.label}: {system.n_states} states\n")
        for name in chosen:
            part = parts[name]
            out.append(part.heading + "\n")
            out.append(markdown_table(part.header, part.rows(case)) + "\n")
    return "\n".join(out)


def case_text(doc: str, note: str, module: str, parts: dict[str, CasePart],
              cases: dict[str, object], quick: bool) -> str:
    """The run_all section body of a case-by-case benchmark: the module docstring ``doc``
    without its first paragraph and its last (the command line), ``note``, the command that
    reruns it and every part's tables for the massive-ball case (``quick``) or the massive
    and nested ones."""
    names = ("massive",) if quick else ("massive", "nested")
    body = doc.split("\n\n", 1)[1].rsplit("\n\n", 1)[0]
    return (f"{body}\n\n{note}\n\nCommand: `python -m {module} {' '.join(parts)} --cases "
            f"{','.join(names)}`\n\n"
            + case_report(parts, tuple(parts), [cases[name] for name in names]))


def case_command_line(description: str, parts: dict[str, CasePart], cases: dict[str, object],
                      default_cases: str) -> None:
    """The command line of a case-by-case benchmark: the chosen parts (default all) for the
    cases named by ``--cases`` (default ``default_cases``), Markdown on standard output."""
    import argparse

    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("parts", nargs="*", default=list(parts), choices=list(parts))
    parser.add_argument("--cases", default=default_cases)
    args = parser.parse_args()
    print(case_report(parts, args.parts, [cases[name] for name in args.cases.split(",")]))


def peak_rss_reset() -> bool:
    """Reset the kernel's peak-RSS counter of this process (Linux); True on success."""
    try:
        with open("/proc/self/clear_refs", "w", encoding="ascii") as fh:
            fh.write("5")
        return True
    except OSError:
        return False


def peak_rss_kib() -> tuple[int, int]:
    """Current and peak resident set size of this process [KiB] (Linux; zeros elsewhere)."""
    rss = hwm = 0
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("VmRSS:"):
                    rss = int(line.split()[1])
                elif line.startswith("VmHWM:"):
                    hwm = int(line.split()[1])
    except OSError:
        pass
    return rss, hwm


def image_link(path: Path, out_md: Path, alt: str) -> str:
    """Markdown image reference to ``path`` relative to the report's folder."""
    rel = os.path.relpath(path, out_md.parent)
    return f"![{alt}]({rel})"
