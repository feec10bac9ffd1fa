"""Benchmark: the compiled BDF integrator's stepping core, where a step's time goes, and the
core before and after its bookkeeping was cut.

Runs: the start-up and steady runs of the 6304 massive-ball level and the nested dynamic
bearing as ``bench/sundials_compiled.py`` runs them (``CASES``: its tolerances, inputs, spans).

* ``split``: the runs on an instrumented build of the integrator (``-DBSM_BDF_PROFILE``,
  ``c/bdf.c``), which times each call of the right-hand side (with the input signal), the
  Jacobian, the LU factorisation (with the fill of ``I - c J``) and the LU solve on the
  monotonic clock (a call the machine's other work interrupted, longer than 1 ms, counts as
  the mean of the others), and the whole run in CPU time. Per step [us]: the time in each,
  and the rest, the stepping core's own work (prediction, Newton updates, norms, difference
  updates, step size and order), with the clock's own cost taken out (one reading per timed
  call from the operations, one from the rest); the uninstrumented run's CPU per step beside
  it. The run of least CPU time of ``REPEATS``. *CPU / limit (in-run)*: the run over its
  operations' time, the distance to the limit counted with every LU solve, both measured in
  the same run (the limit of section "SUNDIALS on compiled kernels" times the operations
  apart from the runs, and moves with the machine's load between the two).
* ``before``: the stepping core of commit ``BEFORE`` (its ``bsm_bdf.c`` and ``bsm_lu.c`` from git
  under the tree's driver ``bdf.c``, compiled at its -O2) and the tree's, on the start-up runs at
  four tolerances: CPU per step (thread time, least of ``REPEATS``, the two builds alternating),
  steps, right-hand sides, Newton iterations per step and the error against a tight CVODES
  reference (the largest over 201 output times of the weighted RMS norm of the difference, weights
  ``atol + rtol |x|`` with the case's rtol and atol: a global error in units of the case's
  tolerance); and the tree's again with rtol larger by 1e-9 of itself, whose errors show how much
  a rounding-level change of the step sequence alone moves the error at one tolerance.

``python -m bench.compiled_bdf_core [split] [before] [--cases massive,nested]``
"""

from __future__ import annotations

import contextlib
import ctypes
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from bearingsim.simulation import compiled_bdf
from bench.common import CasePart, Section, case_command_line, case_text, fmt
from bench.sundials_compiled import CASES, Case

__all__ = ["PARTS", "main", "section", "text"]

BEFORE = "da2b26e"
"""The last commit before the stepping core's bookkeeping was cut (its library at -O2)."""

BEFORE_FLAGS = ("-O2",)

REPEATS = 5

TOLERANCES = (1e-4, 1e-5, 1e-6, 1e-7)
"""rtol of the ``before`` runs (atol in the case's proportion)."""

NUDGE = 1e-9
"""The tree's runs again with rtol larger by this fraction: the scatter of the error at one
tolerance that a rounding-level change of the step sequence gives (the cuts of the core change
the rounding of the norms)."""

SOURCES = ("bdf.c", "bsm_bdf.c", "bsm_bdf.h", "bsm_lu.c", "bsm_lu.h")


@contextlib.contextmanager
def integrator_build(c_dir: Path | None = None, flags: tuple[str, ...] | None = None):
    """``method="compiled_bdf"`` runs on the integrator library built from the C sources in
    ``c_dir`` (default: the tree's) with ``flags`` (default: the tree's) while in the block."""
    saved = (compiled_bdf.C_DIR, compiled_bdf.DRIVER_SOURCE, compiled_bdf.FLAGS)
    folder = c_dir or saved[0]
    own = tuple(f for f in saved[2] if not f.startswith("-I"))
    compiled_bdf.C_DIR, compiled_bdf.DRIVER_SOURCE = folder, folder / "bdf.c"
    compiled_bdf.FLAGS = (*(own if flags is None else flags), f"-I{folder}")
    compiled_bdf._PREPARED.clear()
    compiled_bdf._driver.cache_clear()
    try:
        yield
    finally:
        compiled_bdf.C_DIR, compiled_bdf.DRIVER_SOURCE, compiled_bdf.FLAGS = saved
        compiled_bdf._PREPARED.clear()
        compiled_bdf._driver.cache_clear()


def _phases(case: Case, **kw) -> dict[str, tuple]:
    """The start-up run and the steady run continued from its end: (result, span)."""
    system, common = case.system()
    res0 = case.run(0.0, case.t_start_up, x0=common.get("x0"), method="compiled_bdf", **kw)
    x_mid = {n: res0.final(n) for n in system.state_names}
    res1 = case.run(case.t_start_up, case.t_start_up + case.t_steady, x0=x_mid,
                    method="compiled_bdf", **kw)
    return {"start-up": (res0, case.t_start_up), "steady": (res1, case.t_steady)}


# ------------------------------------------------------------------------------ split
SPLIT_HEADER = ["build", "phase", "steps", "CPU / step (uninstrumented)",
                "CPU / step (instrumented)", "rhs", "jac", "LU factor", "LU solve",
                "stepping core", "core share", "CPU / limit (in-run)",
                "timed calls / step", "interrupted share", "clock reading [ns]"]


def split(case: Case) -> list[list]:
    """Per-step time [us] of each operation and of the stepping core (``split``): the tree's
    integrator, and the same with commit ``BEFORE``'s stepping core (``bsm_bdf.c``, at its
    -O2), the two alternating."""
    with tempfile.TemporaryDirectory() as tmp:
        older = sources_at(BEFORE, Path(tmp))
        builds = {"tree": (None, _tree_flags()),
                  f"{BEFORE}'s core (-O2)": (older, BEFORE_FLAGS)}
        plain: dict[tuple[str, str], list[float]] = {}
        profiled: dict[tuple[str, str], list[tuple]] = {}
        for _ in range(REPEATS):
            for label, (folder, flags) in builds.items():
                with integrator_build(folder, flags):
                    for phase, (res, _) in _phases(case).items():
                        plain.setdefault((label, phase), []).append(
                            res.stats["integrate_cpu_time"] / res.stats["nsteps"])
                with integrator_build(folder, (*flags, "-DBSM_BDF_PROFILE")), \
                        _profiles() as runs:
                    phases = _phases(case)
                for (phase, (res, _)), profile in zip(phases.items(), runs, strict=True):
                    profiled.setdefault((label, phase), []).append(
                        (profile, res.stats["nsteps"]))
    rows = []
    for (label, phase), found in profiled.items():
        profile, steps = min(found, key=lambda pr: pr[0][4])
        run, clock = profile[4], profile[13]
        calls = [profile[5 + k] + profile[9 + k] for k in range(4)]
        # interrupted calls at the mean of the others; less one clock reading per call
        ops = [(profile[k] / profile[5 + k] - clock) * calls[k] if profile[5 + k] else 0.0
               for k in range(4)]
        core = run - sum(ops) - 2 * clock * sum(calls)
        per = [v / steps * 1e6 for v in (run, *ops, core)]
        rows.append([label, phase, steps, fmt(min(plain[label, phase]) * 1e6),
                     *[fmt(v) for v in per], fmt(core / run, 2), fmt(run / sum(ops), 3),
                     fmt(sum(calls) / steps),
                     fmt(sum(profile[9:13]) / sum(calls), 2), fmt(clock * 1e9)])
    return rows


def _tree_flags() -> tuple[str, ...]:
    """The tree's flags of the integrator library, without its include folder."""
    return tuple(f for f in compiled_bdf.FLAGS if not f.startswith("-I"))


@contextlib.contextmanager
def _profiles():
    """Collect ``bsm_bdf_profile`` of every run in the block (a list, in order): read when the
    run takes its counters (``bsm_bdf_stats``, right after its last step; a kept solver's
    profile starts anew with each run)."""
    found: list[list[float]] = []
    originals = {}

    def prepare(kern, signal, cache_dir):
        prep = original_prepare(kern, signal, cache_dir)
        dll = prep.dll
        if id(dll) not in originals:
            originals[id(dll)] = (dll, dll.bsm_bdf_stats)
            dll.bsm_bdf_profile.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
            stats = dll.bsm_bdf_stats

            def profiled_stats(solver, out_at):
                out = (ctypes.c_double * 14)()
                dll.bsm_bdf_profile(solver, out)
                found.append(list(out))
                stats(solver, out_at)
            dll.bsm_bdf_stats = profiled_stats
        return prep

    original_prepare = compiled_bdf._prepare
    compiled_bdf._prepare = prepare
    try:
        yield found
    finally:
        compiled_bdf._prepare = original_prepare
        for dll, stats in originals.values():
            dll.bsm_bdf_stats = stats


BEFORE_HEADER = ["build", "rtol", "CPU / step [us]", "steps", "rhs", "iterations / step",
                 "error / tol"]


def sources_at(commit: str, folder: Path) -> Path:
    """The integrator's C sources (``SOURCES``) written into ``folder``: the stepping core and
    the LU (``bsm_bdf.c``, ``bsm_lu.c`` and their headers) of ``commit``, the driver
    ``bdf.c`` of the tree (its functions are the ones the tree's Python calls; the cores of
    ``BEFORE`` and of :data:`bench.compiled_bdf_newton.BEFORE` share the tree's header)."""
    for name in SOURCES:
        text = (compiled_bdf.DRIVER_SOURCE.read_text() if name == "bdf.c" else subprocess.run(
            ["git", "show", f"{commit}:bearingsim/simulation/c/{name}"],
            cwd=Path(__file__).parent, capture_output=True, text=True, check=True).stdout)
        (folder / name).write_text(text)
    return folder


def before_after(case: Case) -> list[list]:
    """The start-up run at each of ``TOLERANCES`` on commit ``BEFORE``'s core and the tree's
    (``before``)."""
    from bearingsim.simulation import simulate

    system, common = case.system()
    names = system.state_names

    def states(res) -> np.ndarray:
        return np.array([res[n] for n in names])

    reference = states(simulate(system, case.t_start_up, method="cvodes", rtol=1e-11,
                                atol=case.atol * 1e-6, n_points=201, progress=False, **common))
    weights = case.atol + case.rtol * np.abs(reference)
    with tempfile.TemporaryDirectory() as tmp:
        builds = {f"{BEFORE} (-O2)": (sources_at(BEFORE, Path(tmp)), BEFORE_FLAGS, 1.0),
                  "tree": (None, None, 1.0),
                  f"tree, rtol x {1 + NUDGE:.10g}": (None, None, 1.0 + NUDGE)}
        best: dict[tuple[str, float], tuple] = {}
        for _ in range(REPEATS):
            for label, (folder, flags, nudge) in builds.items():
                with integrator_build(folder, flags):
                    for rtol in TOLERANCES:
                        res = simulate(system, case.t_start_up, method="compiled_bdf",
                                       rtol=rtol * nudge, atol=rtol * case.atol / case.rtol,
                                       n_points=201, progress=False, **common)
                        key = (label, rtol)
                        cpu = res.stats["integrate_cpu_time"]
                        if key not in best or cpu < best[key][0]:
                            best[key] = (cpu, res)
    rows = []
    for (label, rtol), (cpu, res) in best.items():
        st = res.stats
        error = np.max(np.sqrt(np.mean(((states(res) - reference) / weights) ** 2, axis=0)))
        rows.append([label, f"{rtol:g}", fmt(cpu / st["nsteps"] * 1e6), st["nsteps"],
                     st["nfevals"], fmt((st["nfevals"] - 2) / st["nsteps"]), fmt(error)])
    return rows


# ------------------------------------------------------------------------------ report
PARTS = {
    "split": CasePart("Where a step's time goes [us per step] (instrumented build):",
                      SPLIT_HEADER, split),
    "before": CasePart(f"Commit `{BEFORE}`'s stepping core and the tree's, start-up run:",
                       BEFORE_HEADER, before_after),
}
"""The tables this benchmark reports, by the name the command line chooses them with."""


NOTE = ("CPU per step on this shared 2-core machine varies by 10-30 % from run to "
        "run; the two builds of `before` alternate, so that both see the same load.")
"""The section's note on the machine."""


def text(quick: bool = False) -> str:
    """The section body."""
    return case_text(__doc__, NOTE, "bench.compiled_bdf_core", PARTS, CASES, quick)


def section(quick: bool = False) -> Section:
    """The run_all section."""
    return Section("The compiled BDF's stepping core", text(quick))


def main() -> None:
    """Command line: the chosen parts for the chosen cases, Markdown on stdout."""
    case_command_line(__doc__.splitlines()[0], PARTS, CASES, "massive,nested")


if __name__ == "__main__":
    main()
