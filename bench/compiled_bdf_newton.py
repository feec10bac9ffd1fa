"""Benchmark: the compiled BDF's Newton iteration, iterations per step before and after the
Jacobian is renewed on slow convergence, against CVODES.

Runs: the start-up and steady phases of the 6304 massive-ball level and the nested dynamic
bearing as ``bench/sundials_compiled.py`` runs them (``CASES``: inputs, spans, atol in
proportion to rtol), at the case's tolerance and ten times tighter; the steady phase starts
from a tight CVODES reference's state at the end of the start-up, the same for every build.
Each run is made ``NUDGES`` times with rtol larger by k * 1e-9 of itself (k = 0, 1, ...): a
change at the level of rounding that moves the step sequence, so that the counts are means
over ``NUDGES`` step sequences rather than one (one steady run of the nested bearing has
50-100 steps, and its counts move by 20-30 % with such a nudge).

* ``counts``: the tree's stepping core and commit ``BEFORE``'s (its ``bsm_bdf.c`` and ``bsm_lu.c``
  from git under the tree's driver, at the tree's flags), alternating; CPU seconds per simulated
  second (thread time, per nudge the least of ``REPEATS``, summed over the nudges), steps, Newton
  iterations per step (right-hand sides less the two of the first step size, with the iterations
  of attempts that failed), Jacobians, LU factorisations, error-test failures and the error
  against a tight CVODES reference (the largest over 201 output times of the weighted RMS norm of
  the difference, weights ``atol + rtol |x|`` with the case's rtol and atol; geometric mean over
  the nudges). CVODES on the same compiled kernels at the same tolerance for comparison
  (``nniters`` per step; its CPU includes CasADi's integrator interface). And an experiment,
  ``KEPT_RATE``: the tree's core with the rate estimate kept at a new factorisation instead of
  reset to 1 (as CVODES resets it): the reset costs a second iteration at almost every new
  factorisation; kept, the iteration may stop after one. And a second, ``LOOSE_TEST``: the tree's
  core with the Newton iteration's stopping test ``LOOSE_COEF`` of the tolerance instead of
  ``NEWTON_COEF`` (0.1, CVODES' ``nlscoef``): fewer iterations a step, at the price of what the
  looser corrections leave in the error estimate.
* ``histogram``: the same runs one step per call of the C loop: the share of steps that took
  1, 2, 3 and 4 or more Newton iterations (with those of attempts that failed), the share of
  steps with a Jacobian evaluation in them (after a failed attempt on an old one, or asked
  for by a slow convergence, or 50 steps old) and the iterations per step of the steps with
  and without one.

``python -m bench.compiled_bdf_newton [counts] [histogram] [--cases massive,nested]``
"""

from __future__ import annotations

import ctypes
import tempfile
from pathlib import Path

import numpy as np

from bearingsim.simulation import compiled_bdf, simulate
from bench.common import CasePart, Section, case_command_line, case_text, fmt
from bench.compiled_bdf_core import SOURCES, integrator_build, sources_at
from bench.sundials_compiled import CASES, Case

__all__ = ["PARTS", "main", "section", "text"]

BEFORE = "506389c"
"""The last commit before the Newton iteration's Jacobian policy changed."""

NUDGES = 4
REPEATS = 3
TIGHTER = 10.0
"""The second tolerance: the case's rtol divided by this."""


def _references(case: Case) -> dict:
    """Tight CVODES runs of both phases (the steady one from the start-up's end): the output
    states and the steady phase's start."""
    if "newton_references" in case.cache:
        return case.cache["newton_references"]
    system, common = case.system()
    names = system.state_names
    rest = {k: v for k, v in common.items() if k != "x0"}
    tight = {"method": "cvodes", "rtol": 1e-11, "atol": case.atol * 1e-6, "n_points": 201,
             "progress": False}
    start = simulate(system, case.t_start_up, **tight, **common)
    x_mid = {n: start.final(n) for n in names}
    steady = simulate(system, case.t_start_up + case.t_steady, t_start=case.t_start_up,
                      x0=x_mid, **tight, **rest)
    found = case.cache["newton_references"] = {
        "x_mid": x_mid, "start-up": _states(start, names), "steady": _states(steady, names)}
    return found


def _states(res, names) -> np.ndarray:
    return np.array([res[n] for n in names])


def _phase_runs(case: Case, rtol: float, **kw) -> dict:
    """Both phases at rtol (atol in the case's proportion): {phase: (result, span)}."""
    system, common = case.system()
    rest = {k: v for k, v in common.items() if k != "x0"}
    x_mid = _references(case)["x_mid"]
    args = {"rtol": rtol, "atol": case.atol * rtol / case.rtol, "n_points": 201,
            "progress": False, **kw}
    start = simulate(system, case.t_start_up, **args, **common)
    steady = simulate(system, case.t_start_up + case.t_steady, t_start=case.t_start_up,
                      x0=x_mid, **args, **rest)
    return {"start-up": (start, case.t_start_up), "steady": (steady, case.t_steady)}


def _error(case: Case, res, phase: str) -> float:
    system, _ = case.system()
    reference = _references(case)[phase]
    weights = case.atol + case.rtol * np.abs(reference)
    diff = (_states(res, system.state_names) - reference) / weights
    return float(np.max(np.sqrt(np.mean(diff**2, axis=0))))


def _iterations(stats: dict) -> int:
    """Newton iterations of a run (CVODES counts them; the compiled BDF evaluates the
    right-hand side once per iteration besides the two of its first step size)."""
    return int(stats["nniters"]) if "nniters" in stats else int(stats["nfevals"]) - 2


# ------------------------------------------------------------------------------ counts
COUNT_HEADER = ["build", "rtol", "phase", "CPU / sim s", "steps", "iterations / step",
                "Jacobians", "LU factorisations", "error-test failures", "error / tol"]

_COUNTED = ("nsteps", "njevals", "nlinsetups", "netfails")


def _tolerances(case: Case) -> tuple[float, float]:
    return case.rtol, case.rtol / TIGHTER


RESET_LINE = "    h->c_lu = c;\n    h->crate = 1.0;\n"
"""The reset of the rate estimate at a new factorisation in ``c/bsm_bdf.c``."""

KEPT_RATE = "tree, rate kept at a new LU (experiment)"

TEST_LINE = "#define NEWTON_COEF 0.1\n"
"""The Newton iteration's stopping test in ``c/bsm_bdf.c`` (a share of the tolerance)."""
LOOSE_COEF = 0.33
"""The looser stopping test of the experiment ``LOOSE_TEST`` (IDA's ``epsNewt``)."""
LOOSE_TEST = f"tree, Newton test {LOOSE_COEF:g} of the tolerance (experiment)"


def _variant_sources(folder: Path, line: str, replacement: str) -> Path:
    """The tree's C sources in ``folder`` with ``line`` of ``bsm_bdf.c`` replaced (an
    experiment)."""
    for name in SOURCES:
        (folder / name).write_text((compiled_bdf.C_DIR / name).read_text())
    core = (folder / "bsm_bdf.c").read_text()
    if line not in core:
        raise RuntimeError(f"bsm_bdf.c no longer has {line.strip()!r}")
    (folder / "bsm_bdf.c").write_text(core.replace(line, replacement))
    return folder


def counts(case: Case) -> list[list]:
    """The tree's core and ``BEFORE``'s, alternating, the experiments ``KEPT_RATE`` and
    ``LOOSE_TEST``, and CVODES (``counts``)."""
    runs: dict[tuple, tuple] = {}
    with (tempfile.TemporaryDirectory() as tmp, tempfile.TemporaryDirectory() as kept,
          tempfile.TemporaryDirectory() as loose):
        builds = {f"{BEFORE} (before)": sources_at(BEFORE, Path(tmp)), "tree": None,
                  KEPT_RATE: _variant_sources(Path(kept), RESET_LINE, "    h->c_lu = c;\n"),
                  LOOSE_TEST: _variant_sources(Path(loose), TEST_LINE,
                                               f"#define NEWTON_COEF {LOOSE_COEF}\n")}
        for _ in range(REPEATS):
            for label, folder in builds.items():
                with integrator_build(folder, _tree_flags()):
                    _count_runs(case, label, {"method": "compiled_bdf"}, runs)
    _count_runs(case, "CVODES (C kernels)", {"method": "cvodes", "compiled": True}, runs)
    rows = []
    for key in dict.fromkeys(k[:3] for k in runs):
        label, rtol, phase = key
        found = [runs[(*key, k)] for k in range(NUDGES)]
        span = case.t_start_up if phase == "start-up" else case.t_steady
        total = {n: sum(int(st[n]) for _, st, _ in found) for n in _COUNTED}
        iterations = sum(_iterations(st) for _, st, _ in found)
        errors = [e for _, _, e in found]
        rows.append([label, f"{rtol:g}", phase, fmt(sum(c for c, _, _ in found) / NUDGES / span),
                     fmt(total["nsteps"] / NUDGES), fmt(iterations / total["nsteps"]),
                     fmt(total["njevals"] / NUDGES), fmt(total["nlinsetups"] / NUDGES),
                     fmt(total["netfails"] / NUDGES),
                     fmt(float(np.exp(np.mean(np.log(errors)))))])
    order = list(dict.fromkeys(r[0] for r in rows))
    return sorted(rows, key=lambda r: (-float(r[1]), r[2], order.index(r[0])))


def _count_runs(case: Case, label: str, method: dict, runs: dict) -> None:
    """Both phases at each tolerance and nudge into ``runs``: (least CPU time so far, the
    statistics, the error) by (label, rtol, phase, nudge)."""
    for rtol in _tolerances(case):
        for k in range(NUDGES):
            for phase, (res, _) in _phase_runs(case, rtol * (1 + 1e-9 * k), **method).items():
                key, cpu = (label, rtol, phase, k), res.stats["integrate_cpu_time"]
                if key not in runs:
                    runs[key] = (cpu, res.stats, _error(case, res, phase))
                elif cpu < runs[key][0]:
                    runs[key] = (cpu, *runs[key][1:])


def _tree_flags() -> tuple[str, ...]:
    return tuple(f for f in compiled_bdf.FLAGS if not f.startswith("-I"))


# ------------------------------------------------------------------------------ histogram
HISTOGRAM_HEADER = ["build", "rtol", "phase", "steps", "1 iteration", "2", "3", "4 or more",
                    "steps with a Jacobian", "iterations / step (with a Jacobian)",
                    "iterations / step (without)"]


class _StepRecorder:
    """The counters after every call of the C loop, when it takes one step per call."""

    def __init__(self):
        self.runs: list[list[np.ndarray]] = []

    def wrap(self, dll) -> None:
        if getattr(dll, "_recorder", None) is self:
            return
        advance, recorder = dll.bsm_bdf_advance, self
        stats = dll.bsm_bdf_stats

        def recorded(solver, *args):
            status = advance(solver, *args)
            out = np.zeros(len(compiled_bdf.STAT_NAMES), dtype=np.int64)
            stats(solver, out.ctypes.data_as(ctypes.POINTER(ctypes.c_longlong)))
            recorder.runs[-1].append(out)
            return status
        dll.bsm_bdf_advance = recorded
        dll._recorder = self


def histogram(case: Case) -> list[list]:
    """Per-step iterations of the tree's core and ``BEFORE``'s (``histogram``)."""
    names = compiled_bdf.STAT_NAMES
    col = {n: names.index(n) for n in ("nsteps", "nfevals", "njevals")}
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, folder in {f"{BEFORE} (before)": sources_at(BEFORE, Path(tmp)),
                              "tree": None}.items():
            for rtol in _tolerances(case):
                per_phase: dict[str, list] = {}
                for k in range(NUDGES):
                    for phase, records in _recorded_phases(case, folder,
                                                           rtol * (1 + 1e-9 * k)).items():
                        per_phase.setdefault(phase, []).extend(records)
                for phase, steps in per_phase.items():
                    rows.append([label, f"{rtol:g}", phase, *_histogram_row(steps, col)])
    return rows


def _recorded_phases(case: Case, folder: Path | None, rtol: float) -> dict[str, list]:
    """Per-step counter differences of both phases at rtol, one step per call."""
    recorder = _StepRecorder()
    original_prepare, original_steps = compiled_bdf._prepare, compiled_bdf.STEPS_PER_CALL

    def prepare(kern, signal, cache_dir):
        prep = original_prepare(kern, signal, cache_dir)
        recorder.runs.append([])
        recorder.wrap(prep.dll)
        return prep
    compiled_bdf._prepare, compiled_bdf.STEPS_PER_CALL = prepare, 1
    try:
        with integrator_build(folder, _tree_flags()):
            phases = _phase_runs(case, rtol, method="compiled_bdf")
    finally:
        compiled_bdf._prepare, compiled_bdf.STEPS_PER_CALL = original_prepare, original_steps
    out = {}
    for phase, run in zip(phases, recorder.runs, strict=True):
        counters = np.array(run)
        out[phase] = [b - a for a, b in zip(counters[:-1], counters[1:], strict=False)]
    return out


def _histogram_row(steps: list[np.ndarray], col: dict[str, int]) -> list:
    """Shares of steps by iterations (those of failed attempts counted), the share with a
    Jacobian evaluation, and the iterations per step of the steps with and without one."""
    taken = [d for d in steps if d[col["nsteps"]] == 1]
    iterations = np.array([d[col["nfevals"]] for d in taken])
    with_jac = np.array([d[col["njevals"]] > 0 for d in taken])
    n = max(len(taken), 1)
    shares = [np.sum(iterations == 1), np.sum(iterations == 2), np.sum(iterations == 3),
              np.sum(iterations >= 4)]
    return [len(taken), *[fmt(s / n, 2) for s in shares], fmt(float(np.mean(with_jac)), 2),
            fmt(float(np.mean(iterations[with_jac]))) if with_jac.any() else "-",
            fmt(float(np.mean(iterations[~with_jac]))) if (~with_jac).any() else "-"]


# ------------------------------------------------------------------------------ report
PARTS = {
    "counts": CasePart(f"Commit `{BEFORE}`'s core, the tree's and CVODES (means over "
                       f"{NUDGES} nudged step sequences):", COUNT_HEADER, counts),
    "histogram": CasePart("Newton iterations per step (shares of the steps):",
                          HISTOGRAM_HEADER, histogram),
}
"""The tables this benchmark reports, by the name the command line chooses them with."""


NOTE = ("CPU times on this shared 2-core machine vary by 10-30 % from run to run; "
        "the builds alternate, so that both see the same load.")
"""The section's note on the machine."""


def text(quick: bool = False) -> str:
    """The section body."""
    return case_text(__doc__, NOTE, "bench.compiled_bdf_newton", PARTS, CASES, quick)


def section(quick: bool = False) -> Section:
    """The run_all section."""
    return Section("The compiled BDF's Newton iteration", text(quick))


def main() -> None:
    """Command line: the chosen parts for the chosen cases, Markdown on stdout."""
    case_command_line(__doc__.splitlines()[0], PARTS, CASES, "massive,nested")


if __name__ == "__main__":
    main()
