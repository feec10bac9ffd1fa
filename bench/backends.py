"""Benchmark: evaluation backends — plain CasADi calls, buffered calls, compiled C.

The same assembled system is evaluated (one right-hand side, one sparse Jacobian) and simulated
with scipy's BDF and LSODA and with CVODES, on the interpreted CasADi virtual machine and on the
compiled C backend (:func:`bearingsim.simulation.compile.compile_system`), side by side in one run.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assemblies import deep_groove_ball_bearing, double_layer_bearing, motor_drive
from bearingsim.simulation import simulate
from bearingsim.simulation.closed import close_inputs
from bearingsim.simulation.compile import compile_system
from bearingsim.simulation.fastcall import BufferedFunction
from bench.common import Section, fmt, markdown_table, median_call_time
from bench.models import TorsionChain

__all__ = ["run"]


def _models(quick: bool):
    n = 30 if quick else 100
    yield f"torsion chain N={n}", TorsionChain(n), 1.0
    yield "PMSM + double-layer bearing", motor_drive(double_layer_bearing(drive="flange"),
                                                      motor="pmsm", speed_ref=300.0), 1.0
    yield "6304 massive balls", deep_groove_ball_bearing(
        "6304", "dynamic_massive_balls", speed=100.0, loads={"Fx": 500.0}, n_slices=0), 2e-4


def _call_costs(name: str, system) -> dict[str, float]:
    """Median call times [s] of the closed RHS (plain and buffered) and of the Jacobian."""
    x, p = system.x0() + 1e-3, system.p0()
    closed = close_inputs(system, None)
    f, j = BufferedFunction(closed.f), BufferedFunction(closed.jac)
    return {
        f"plain {name}": median_call_time(lambda: closed.f(0.1, x, p)),
        f"buffered {name}": median_call_time(lambda: f.vector(0.1, x, p)),
        f"jac {name}": median_call_time(lambda: j.sparse(0.1, x, p)),
    }


def _best_wall(system, t_end, method, repeats=3) -> tuple[float, float]:
    best, final = np.inf, np.nan
    for _ in range(repeats):
        res = simulate(system, t_end, method=method, rtol=1e-8, atol=1e-10, n_points=201)
        best = min(best, res.stats["wall_time"])
        final = res.values[:, -1]
    return best, final


def run(quick: bool, img_dir: Path, out_md: Path, log=print) -> Section:
    """Measure call costs and simulation wall times per backend.

    Parameters
    ----------
    quick : bool
        Smaller chain.
    img_dir, out_md : Path
        Unused (no plots); kept for the common benchmark signature.
    log : callable
        Progress printer.
    """
    call_rows, sim_rows = [], []
    with tempfile.TemporaryDirectory() as cache:
        for label, model, t_end in _models(quick):
            log(f"  {label}")
            system = assemble(model)
            t0 = time.perf_counter()
            compiled = compile_system(system, cache_dir=cache)
            t_compile = time.perf_counter() - t0
            t_inlined = "-"
            if compiled.report["compiled_balls"] == "mapped":
                t0 = time.perf_counter()
                compile_system(system, cache_dir=cache, mapped=False)
                t_inlined = fmt(time.perf_counter() - t0)
            costs = {}
            for name, sysx in (("VM", system), ("C", compiled)):
                costs.update(_call_costs(name, sysx))
            call_rows.append([label, system.n_states, fmt(t_compile), t_inlined] + [
                fmt(costs[k] * 1e6) for k in ("plain VM", "buffered VM", "buffered C",
                                               "jac VM", "jac C")])
            for method in ("BDF", "LSODA", "cvodes"):
                wall_vm, end_vm = _best_wall(system, t_end, method)
                wall_c, end_c = _best_wall(compiled, t_end, method)
                diff = float(np.max(np.abs(end_vm - end_c) / (np.abs(end_vm) + 1e-12)))
                sim_rows.append([label, method, fmt(wall_vm), fmt(wall_c),
                                 fmt(wall_vm / wall_c), fmt(diff)])
    body = "\n".join([
        "Call costs from Python with numpy arguments (median, µs). *plain*: "
        "`Function(t, x, p)` as CasADi's Python interface converts arguments; *buffered*: "
        "`bearingsim.simulation.fastcall.BufferedFunction` (zero-copy `Function.buffer`), which "
        "`simulate` uses for scipy's integrators; *VM*: CasADi's SX virtual machine; *C*: the "
        "compiled backend (`compile_system`, gcc -O2). *compile*: `compile_system` on an empty "
        "cache (a model with ball sets maps them: one function per ball); *compile inlined*: "
        "`compile_system(..., mapped=False)`, every ball inlined (including building the "
        "inlined functions).",
        "",
        markdown_table(["model", "states", "compile [s]", "compile inlined [s]", "plain VM",
                        "buffered VM",
                        "buffered C", "Jacobian VM", "Jacobian C"], call_rows),
        "",
        "Simulation wall time (best of 3, rtol 1e-8) on the VM and on compiled C, and the largest "
        "relative difference of all variables at the end time between the two:",
        "",
        markdown_table(["model", "method", "VM [s]", "C [s]", "VM / C", "max rel. diff"],
                       sim_rows),
    ])
    return Section("4. Evaluation backends: buffered calls and compiled C", body,
                   {"calls": call_rows, "simulate": sim_rows})
