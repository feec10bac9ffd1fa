"""Benchmark: CVODES and IDAS on compiled kernels against the CasADi VM.

Models (``CASES``):

* ``torque``: ``double_layer_bearing("61905", "61907", fidelity="torque")``, 3 states, spin-up
  at ``shaft_speed = 1000 rad/s`` for 3 s;
* ``massive``: ``deep_groove_ball_bearing("6304", "dynamic_massive_balls", n_slices=0)``,
  duty condition 1 (938 N on ``Fx``; input ``shaft_speed`` ramped to 1730 r/min over 5 ms);
* ``qs``: the same bearing at the ``dynamic`` level (quasi-static balls): IDAS on the
  semi-explicit DAE form;
* ``qs_cvodes``: the ``dynamic`` level with its ``newton`` blocks inside CVODES' right-hand side
  (VM only: no C for ``newton``);
* ``qs_fast_newton``: the same with ``fast_newton`` blocks (C: every ball's Newton iteration
  and its implicit derivative inlined);
* ``nested``: ``double_layer_bearing("61905", "61907", fidelity="dynamic")`` as the speed-ratio
  study runs it (oil mist, 100 N axial, ``n_slices=0``, outputs ``Rs``, ``M_middle``), started
  in pure rolling at ``Rs = 0.4``, ``shaft_speed = 300 rad/s``.

Sections (``python -m bench.sundials_compiled SECTION [--cases a,b]``):

* ``calls``: cost of one call [us] of the kernel (right-hand side or DAE residual) and of its
  exact Jacobian, VM and C, measured inside CasADi (``Function.map(n, "serial")``, no Python
  per call), and of a dense LU factorization and solve of the Newton matrix; on ODE-form
  cases also of the compiled integrators' sparse LU (``c/bsm_lu.c``) and of its dense-storage
  predecessor (commit ``SPARSE_LU_BEFORE``, compiled from git);
* ``compile``: generate-and-compile time of the kernel library at -O0, -O1, -O2 (empty cache)
  and the run time of the ``runs`` start-up with each;
* ``runs``: start-up and steady running, VM and C (and on ODE-form cases the BDF loop in C,
  ``method="compiled_bdf"``, on the C kernels): CPU seconds of the integration per simulated
  second, steps,
  right-hand-side and Jacobian evaluations per simulated second, the physical limit (compiled
  per-call costs times the calls the run took) and the distance to it; VM = C check;
* ``linsol``: every SUNDIALS linear solver on the start-up run (compiled kernels);
* ``setup``: first run (kernel from the disk cache, integrator built) and repeated runs (all
  cached) of a short run, as the secant speed ratio makes them;
* ``progress``: the cost of the progress bar's clock in the oracle: 20 ms and 300 ms start-up
  runs with 501 output points without and with a bar, CPU time and whether the values are
  identical bit for bit (they must be: the bar observes the run).
"""

from __future__ import annotations

import argparse
import contextlib
import ctypes
import io
import statistics
import subprocess
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assembler.system import System
from bearingsim.simulation import simulate
from bearingsim.simulation.compile import compile_source
from bearingsim.simulation.inputs import input_signal
from bearingsim.simulation.kernels import clear_kernel_cache, kernel
from bearingsim.simulation.ordering import fill_reducing_order, newton_pattern
from bearingsim.simulation.sparse_lu import SparseLu
from bearingsim.simulation.sundials_integrators import (
    LINEAR_SOLVERS,
    choose_linear_solver,
    clear_integrator_cache,
)
from bench.common import Section, fmt, markdown_table
from bench.kernel_timing import kernel_call_us

__all__ = ["CASES", "Case", "main", "report", "section"]


@dataclass
class Case:
    """One model and its runs: ``start`` (start-up) and ``steady`` (continued from its end)."""

    label: str
    build: Callable[[], tuple[System, dict[str, Any]]]
    """-> (system, keyword arguments of ``simulate`` shared by the runs)."""
    method: str
    t_start_up: float
    t_steady: float
    rtol: float = 1e-5
    atol: float = 1e-6
    cache: dict = field(default_factory=dict)

    def system(self) -> tuple[System, dict[str, Any]]:
        """The assembled system (built once)."""
        if "system" not in self.cache:
            t0 = time.perf_counter()
            self.cache["system"] = self.build()
            self.cache["assemble_s"] = time.perf_counter() - t0
        return self.cache["system"]

    def run(self, t0: float, t1: float, x0: dict | None = None, method: str | None = None,
            **kw) -> Any:
        """One ``simulate`` call of this case from ``t0`` to ``t1`` (its own method unless
        ``method`` is given)."""
        system, common = self.system()
        args = {**common, **kw}
        if x0 is not None:
            args["x0"] = x0
        return simulate(system, t1, t_start=t0, method=method or self.method, rtol=self.rtol,
                        atol=self.atol, n_points=3, progress=False, **args)


def _ramp_speed(rpm: float, ramp: float = 0.005):
    w = rpm * np.pi / 30.0
    return lambda t: w * ca.fmin(t / ramp, 1.0)


def _deep_groove(fidelity: str, rootfinder: str | None = None):
    from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
    from bearingsim.studies.deep_groove import DUTY_CYCLE

    def build():
        n_rpm, load = DUTY_CYCLE[0]
        bearing = deep_groove_ball_bearing("6304", fidelity, speed=None, loads={"Fx": load},
                                           n_slices=0)
        return (assemble(bearing, rootfinder=rootfinder),
                {"inputs": {"shaft_speed": _ramp_speed(n_rpm)}})
    return build


def _torque():
    from bearingsim.assemblies import double_layer_bearing

    return (assemble(double_layer_bearing("61905", "61907", fidelity="torque")),
            {"inputs": {"shaft_speed": 1000.0}})


def _nested():
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.physics.lubricant import Oil

    oil = Oil.from_iso_vg(32, method="oil_mist")
    loads = {"Fx": 0.0, "Fy": 0.0, "Fz": 100.0, "Mx": 0.0, "My": 0.0}
    bearing = double_layer_bearing("61905", "61907", fidelity="dynamic", lubrication=(oil, oil),
                                   loads=loads, layer_options={"n_slices": 0})
    system = assemble(bearing, outputs=["Rs", "M_middle"])
    w = 300.0
    x0 = bearing.rolling_start(w, 0.4 * w, system.state_names)
    return system, {"inputs": {"shaft_speed": w}, "x0": x0}


CASES: dict[str, Case] = {
    "torque": Case("61905/61907 torque level (3 states)", _torque, "cvodes", 3.0, 3.0),
    "massive": Case("6304 massive balls, condition 1", _deep_groove("dynamic_massive_balls"),
                    "cvodes", 0.05, 0.1),
    "qs": Case("6304 quasi-static balls (IDAS, DAE form), condition 1",
               _deep_groove("dynamic"), "idas", 0.05, 0.1),
    "qs_cvodes": Case("6304 quasi-static balls (CVODES, newton in the rhs), condition 1",
                      _deep_groove("dynamic"), "cvodes", 0.05, 0.1),
    "qs_fast_newton": Case("6304 quasi-static balls (CVODES, fast_newton in the rhs), "
                           "condition 1", _deep_groove("dynamic", "fast_newton"), "cvodes",
                           0.05, 0.1),
    "nested": Case("61905/61907 nested dynamic (speed-ratio run)", _nested, "cvodes", 0.02,
                   0.05, atol=1e-8),
}


# ------------------------------------------------------------------------------ per call
def per_call_us(fn: ca.Function, args: list, n: int = 5000, repeats: int = 7) -> float:
    """CPU time of one call of ``fn`` [us] (:func:`_call_us`): zero-copy ``Function.buffer``
    calls in a Python loop, less the loop's own cost (a trivial function called the same way).
    (``Function.map(n, "serial")`` is no substitute: it adds ~10 us per call of an external.)
    """
    return max(_loop_us(fn, args, n, repeats) - _loop_us(_trivial(fn), args, n, repeats), 0.0)


def _trivial(fn: ca.Function) -> ca.Function:
    sym = [ca.SX.sym(fn.name_in(i), fn.sparsity_in(i)) for i in range(fn.n_in())]
    return ca.Function("trivial", sym, [sym[0]] * fn.n_out())


def _loop_us(fn: ca.Function, args: list, n: int, repeats: int) -> float:
    buf, evaluate = fn.buffer()
    keep = []
    for i, value in enumerate(args):
        arr = np.ascontiguousarray(np.atleast_1d(np.asarray(value, dtype=float)).ravel(
            order="F"))
        keep.append(arr)
        buf.set_arg(i, memoryview(arr))
    for i in range(fn.n_out()):
        arr = np.zeros(fn.nnz_out(i))
        keep.append(arr)
        buf.set_res(i, memoryview(arr))
    evaluate()
    return _call_us(evaluate, n, repeats)


def _operating_point(case: Case, form: str) -> list:
    """Kernel arguments at the end of the start-up run."""
    system, common = case.system()
    res = case.run(0.0, case.t_start_up, x0=common.get("x0"), compiled=False)
    x = np.array([res.final(n) for n in system.state_names])
    signal = input_signal(system, common.get("inputs"))
    u = np.asarray(signal.u(res.t[-1], signal.q), dtype=float).ravel()
    p = system.p0()
    if form == "dae":
        funcs = system.symbolic_functions or system.functions
        z = np.asarray(funcs["dae_z"](res.t[-1], x, u, p), dtype=float).ravel()
        return [res.t[-1], x, z, u, p]
    return [res.t[-1], x, u, p]


def _form(case: Case) -> str:
    return "dae" if case.method == "idas" else "ode"


RHS_IN_C = "rhs C (loop in C)"
JAC_IN_C = "jac C d/dx (loop in C)"
"""Per-call costs of the compiled kernel timed in loops inside C
(:func:`bench.kernel_timing.kernel_call_us`): the limits' costs where measured."""


def calls(case: Case) -> dict[str, float]:
    """Per-call costs [us] of the kernel and its Jacobian, VM and C, and of the default linear
    solver's factorization and solve (dense LU, or the ordered sparse LU above DENSE_LIMIT)."""
    system, _ = case.system()
    form = _form(case)
    args = _operating_point(case, form)
    out = {}
    for label, comp in (("VM", False), ("C", True)):
        try:
            kern = kernel(system, form, comp)
        except Exception as exc:  # noqa: BLE001 - report why C is missing
            out[f"rhs {label}"] = out[f"jac {label}"] = float("nan")
            out[f"note {label}"] = str(exc)
            continue
        fn = kern.function
        jac = fn.jacobian()
        if label == "VM":  # the SX functions themselves, not the MX wrapper around them
            fn = ca.Function(fn.name(), fn.mx_in(), fn.call(fn.mx_in()))
        value = fn(*args)
        value = value if isinstance(value, (list, tuple)) else [value]
        out[f"rhs {label}"] = per_call_us(fn, args)
        out[f"jac {label}"] = per_call_us(jac, [*args, *value], n=1000)
        if comp and form == "ode":  # the limit's costs: loops inside C, as bdf.c calls them
            out[RHS_IN_C] = kernel_call_us(kern, "rhs", args)
            out[JAC_IN_C] = kernel_call_us(kern, "jac", args)
    n = system.n_states + (args[2].size if form == "dae" else 0)
    nnz = jac.sparsity_out(1).nnz() + n  # jac_ode_x and the identity (ode form)
    if form == "ode" and choose_linear_solver(n, nnz, form) == "csparse":
        # the default above DENSE_LIMIT: the ordered sparse LU of the run's own Newton matrix
        jac_x = np.asarray(ca.densify(jac(*args, *value)[1]))
        newton = np.eye(n) - 1e-3 * jac_x
        out["lu fact+solve"] = sparse_lu_us(newton, kern.function)
        out["lu solve"] = lu_solve_us(newton, kern.function)
    else:
        out["lu fact+solve"] = dense_lu_us(n)
        out["lu solve"] = lu_solve_us(np.eye(n) + 0.01 * np.random.default_rng(0)
                                      .standard_normal((n, n)))
    if form == "ode":
        jac_nz = np.asarray(jac(*args, *value)[1].nonzeros(), dtype=float)
        own = bsm_lu_us(jac.sparsity_out(1), jac_nz)
        before = dense_storage_lu_us(jac.sparsity_out(1), jac_nz)
        out.update(own)
        out.update(before)
        out["bsm_lu factor / rhs"] = own["bsm_lu factor"] / out["rhs C"]
        if before:
            out["dense-storage factor / rhs"] = before["dense-storage factor"] / out["rhs C"]
    out["n"] = n
    return out


SPARSE_LU_BEFORE = "29a6fd4"
"""The last commit whose ``c/bsm_lu.c`` factorised ``I - c J`` in dense storage (partial
pivoting that skips structural zeros): the "before" of the sparse LU."""


def _call_us(call: Callable[[], Any], n: int, repeats: int = 7) -> float:
    """CPU time of one ``call()`` [us], the least of ``repeats`` loops of ``n`` (thread CPU
    time: on the shared machine the wall clock also counts the time others hold the core)."""
    times = []
    for _ in range(repeats):
        t0 = time.thread_time()
        for _ in range(n):
            call()
        times.append((time.thread_time() - t0) / n * 1e6)
    return min(times)


def _net_us(call: Callable[[], Any], empty_call: Callable[[], Any], n: int) -> float:
    """Cost of ``call`` [us] less that of the same call on an empty matrix (Python, ctypes)."""
    return max(_call_us(call, n) - _call_us(empty_call, n), 0.0)


def bsm_lu_us(pattern: ca.Sparsity, jac_nonzeros: np.ndarray, c: float = 1e-3,
              n: int = 2000) -> dict[str, float]:
    """Costs [us] of the compiled integrators' sparse LU (``c/bsm_lu.c`` as the BDF
    integrator runs it) on the Newton matrix ``I - c J`` in the fill-reducing order: a
    factorisation in the kept pivot order and pattern and a solve, each repeated inside C
    (:meth:`~bearingsim.simulation.sparse_lu.SparseLu.time_calls`), a fresh factorisation (from
    Python, less an empty matrix's call); and the nonzeros of ``L`` and ``U``."""
    newton = newton_pattern(pattern)
    values, none = newton.values(jac_nonzeros, c), np.zeros(0)
    lu = SparseLu(newton.start, newton.index, keep_order=True)
    empty = SparseLu([0], [], keep_order=True)
    factor_s, solve_s = lu.time_calls(values, np.ones(newton.order.size), repeats=n)
    return {"bsm_lu factor": factor_s * 1e6,
            "bsm_lu fresh": _net_us(lambda: lu.factor(values, fresh=True),
                                    lambda: empty.factor(none, fresh=True), max(n // 5, 1)),
            "bsm_lu solve": solve_s * 1e6,
            "L+U nonzeros": sum(lu.nnz)}


def dense_storage_lu_us(pattern: ca.Sparsity, jac_nonzeros: np.ndarray, c: float = 1e-3,
                        n: int = 1000) -> dict[str, float]:
    """The same for the LU of commit ``SPARSE_LU_BEFORE`` (compiled from git; empty without
    the history): a factorisation (with the copy of the dense matrix into its storage, as the
    integrator filled it) and a solve [us], and the nonzeros of its factors."""
    here = Path(__file__).parent
    try:
        source = {name: subprocess.run(
            ["git", "show", f"{SPARSE_LU_BEFORE}:bearingsim/simulation/c/{name}"], cwd=here,
            capture_output=True, text=True, check=True).stdout
            for name in ("bsm_lu.c", "bsm_lu.h")}
    except (OSError, subprocess.CalledProcessError):
        return {}
    newton = newton_pattern(pattern)
    size = newton.order.size
    import scipy.sparse

    dense = scipy.sparse.csc_matrix((newton.values(jac_nonzeros, c), newton.index,
                                     newton.start), shape=(size, size)).toarray()
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in source.items():
            (Path(tmp) / name).write_text(text)
        dll = ctypes.CDLL(str(compile_source(source["bsm_lu.c"], Path(tmp) / "dense_lu.so",
                                             flags=("-O2", f"-I{tmp}"))))
        v = ctypes.c_void_p
        dll.bsm_lu_factor.argtypes = [v, ctypes.c_int, v, v]
        dll.bsm_lu_solve.argtypes = [v, ctypes.c_int, v, v, v]

        def storage(m: int):
            half = max(m * m // 2, 1)
            arrays = [np.zeros(m, np.int32), np.zeros(m + 1, np.int32),
                      np.zeros(half, np.int32), np.zeros(half), np.zeros(m + 1, np.int32),
                      np.zeros(half, np.int32), np.zeros(half), np.zeros(m)]
            factors = (v * 8)(*[a.ctypes.data for a in arrays])
            work, order = np.zeros(2 * m, np.int32), np.arange(m, dtype=np.int32)
            matrix = dense if m else np.zeros((0, 0))
            a, x, xw = np.empty((m, m)), np.ones(m), np.zeros(m)

            def factor():
                np.copyto(a, matrix)
                return dll.bsm_lu_factor(a.ctypes.data, m, factors, work.ctypes.data)

            def solve():
                dll.bsm_lu_solve(factors, m, order.ctypes.data, xw.ctypes.data, x.ctypes.data)
            return factor, solve, arrays

        factor, solve, arrays = storage(size)
        empty_factor, empty_solve, _ = storage(0)
        factor()
        return {"dense-storage factor": _net_us(factor, empty_factor, n),
                "dense-storage solve": _net_us(solve, empty_solve, 4 * n),
                "dense-storage L+U nonzeros": int(arrays[1][-1] + arrays[4][-1])}


def lu_solve_us(newton: np.ndarray, fn: ca.Function | None = None, n: int = 2000) -> float:
    """Cost of one solve [us] with the LU factors of a Newton matrix (scipy): dense LAPACK
    factors, or (with ``fn``) SuperLU's of the matrix in the minimum-degree order the
    integrator uses, without further ordering."""
    import scipy.linalg
    import scipy.sparse
    import scipy.sparse.linalg

    rhs = np.ones(newton.shape[0])
    if fn is None:
        factors = scipy.linalg.lu_factor(newton)
        solve = lambda: scipy.linalg.lu_solve(factors, rhs)  # noqa: E731
    else:
        jac = fn.jacobian()
        pattern = jac.sparsity_out(jac.name_out().index("jac_ode_x")) + ca.Sparsity.diag(
            newton.shape[0])
        order = [int(i) for i in fill_reducing_order(pattern)]
        matrix = scipy.sparse.csc_matrix(newton[np.ix_(order, order)])
        solve = scipy.sparse.linalg.splu(matrix, permc_spec="NATURAL").solve
        solve = (lambda f: lambda: f(rhs))(solve)
    start = time.perf_counter()
    for _ in range(n):
        solve()
    return (time.perf_counter() - start) / n * 1e6


def newton_solves(stats: dict) -> int:
    """Linear solves of a run: CVODES/IDAS one per Newton iteration (``nniters``);
    compiled_bdf one per right-hand side in its Newton iterations (``nfevals``, less the two
    of its start)."""
    return int(stats["nniters"]) if "nniters" in stats else max(int(stats["nfevals"]) - 2, 0)


def sparse_lu_us(newton: np.ndarray, fn: ca.Function) -> float:
    """Cost of one CSparse LU factorization and solve [us] of a Newton matrix with the pattern
    of ``I + d fn / d x``, in the minimum-degree order the integrator uses."""
    jac = fn.jacobian()
    pattern = jac.sparsity_out(jac.name_out().index("jac_ode_x")) + ca.Sparsity.diag(
        newton.shape[0])
    order = [int(i) for i in fill_reducing_order(pattern)]
    ordered = pattern.sub(order, order, False)[0]
    a = ca.MX.sym("A", ordered)
    b = ca.MX.sym("b", newton.shape[0])
    lu = ca.Function("lu", [a, b], [ca.solve(a, b, "csparse")])
    values = ca.project(ca.DM(newton[np.ix_(order, order)]), ordered).nonzeros()
    return per_call_us(lu, [np.asarray(values), np.ones(newton.shape[0])], n=500)


def physical_limit_s(stats: dict, rhs_us: float, jac_us: float, lu_us: float = 0.0) -> float:
    """The physical limit of a run [s]: compiled per-call costs [us] of the kernel, its
    Jacobian and (optionally) the LU of the Newton matrix (factorization and solve) times the
    calls the run made."""
    return (stats["nfevals"] * rhs_us + stats["njevals"] * jac_us
            + stats["nlinsetups"] * lu_us) * 1e-6


def dense_lu_us(n: int) -> float:
    """Cost of one dense LAPACK LU factorization and solve of an ``n x n`` Newton matrix [us]."""
    a = ca.MX.sym("A", n * n)
    b = ca.MX.sym("b", n)
    lu = ca.Function("lu", [a, b], [ca.solve(ca.reshape(a, n, n), b, "lapacklu")])
    mat = np.eye(n) + 0.01 * np.random.default_rng(0).standard_normal((n, n))
    return per_call_us(lu, [mat.ravel(order="F"), np.ones(n)], n=500)


# ------------------------------------------------------------------------------ compile
def compile_levels(case: Case, levels=("-O0", "-O1", "-O1/-Og", "-O2")) -> list[list]:
    """Compile time of the kernel library per optimisation level (empty cache), and the
    start-up run's wall time with it. A level ``"A/B"`` compiles the main translation unit
    with ``A`` and the split units (per-ball Jacobians) with ``B``; ``"A"`` all with ``A``."""
    system, common = case.system()
    rows = []
    for flags in levels:
        main, _, split = flags.partition("/")
        with tempfile.TemporaryDirectory() as tmp:
            clear_kernel_cache()
            clear_integrator_cache()
            t0 = time.perf_counter()
            kern = kernel(system, _form(case), True, flags=(main,), cache_dir=tmp,
                          split_flags=(split or main,))
            t_build = time.perf_counter() - t0
            walls = []
            for _ in range(3):
                res = _run_with_kernel(case, kern, common)
                walls.append(res.stats["wall_time"])
            size = kern.library.stat().st_size
            rows.append([flags, fmt(t_build), f"{size / 1e6:.2f}", fmt(min(walls)),
                         fmt(res.stats["rhs_time"] / res.stats["nfevals"] * 1e6),
                         fmt(res.stats["jac_time"] / max(res.stats["njevals"], 1) * 1e6)])
    clear_kernel_cache()
    clear_integrator_cache()
    return rows


def _run_with_kernel(case: Case, kern, common: dict):
    """A start-up run on a given kernel (bypassing the kernel cache's flags)."""
    from bearingsim.simulation import kernels as kernels_module

    system, _ = case.system()
    cache = kernels_module._system_cache(system)
    for key in [k for k in cache if k[0] == kern.form and k[1] is True]:
        del cache[key]
    cache[kernels_module.cache_key(kern.form, True)] = kern
    return case.run(0.0, case.t_start_up, x0=common.get("x0"), compiled=True)


# ------------------------------------------------------------------------------ runs
COMPILED_BDF = "C, compiled_bdf"
"""Row label of the BDF loop in C (``method="compiled_bdf"``) on the C kernels."""


RUN_REPEATS = 7
"""Runs per backend and phase, the least CPU time kept: as many as the per-call costs' loops
(least of 7), so that the run and its limit are estimated alike on the shared machine."""


def runs(case: Case, per_call: dict[str, float], repeats: int = RUN_REPEATS) -> dict[str, Any]:
    """Start-up and steady running on VM and C (and, for ODE-form cases, the compiled BDF
    on C): integration CPU times (``integrate_cpu_time``), counts, limit."""
    system, common = case.system()
    out: dict[str, Any] = {}
    finals = {}
    backends = [("VM", False, case.method), ("C", True, case.method)]
    if _form(case) == "ode":
        backends.append((COMPILED_BDF, True, "compiled_bdf"))
    for label, comp, method in backends:
        try:
            kernel(system, _form(case), comp)
        except Exception:  # noqa: BLE001 - no C for this case
            continue
        best = {}
        for _ in range(repeats):
            res0 = case.run(0.0, case.t_start_up, x0=common.get("x0"), method=method,
                            compiled=comp)
            x_mid = {n: res0.final(n) for n in system.state_names}
            res1 = case.run(case.t_start_up, case.t_start_up + case.t_steady, x0=x_mid,
                            method=method, compiled=comp)
            for phase, res, span in (("start-up", res0, case.t_start_up),
                                     ("steady", res1, case.t_steady)):
                cpu = res.stats["integrate_cpu_time"]
                if phase not in best or cpu < best[phase][0].stats["integrate_cpu_time"]:
                    best[phase] = (res, span, [])
                best[phase][2].append(cpu)
        for phase, (res, span, walls) in best.items():
            out[(label, phase)] = (res, span, walls)
        finals[label] = best["steady"][0]
    if {"VM", "C"} <= set(finals):
        a, b = finals["VM"].values, finals["C"].values
        scale = np.maximum(np.abs(a), 1e-300)
        out["max rel diff"] = float(np.nanmax(np.abs(a - b) / scale))
        out["same steps"] = finals["VM"].stats["nsteps"] == finals["C"].stats["nsteps"]
    out["per_call"] = per_call
    return out


def run_rows(case: Case, data: dict) -> list[list]:
    """Table rows of :func:`runs`."""
    pc = data["per_call"]
    rows = []
    for (label, phase), (res, span, cpus) in ((k, v) for k, v in data.items()
                                                if isinstance(k, tuple)):
        st = res.stats
        cpu = min(cpus)
        rhs_us, jac_us = pc.get(RHS_IN_C, pc["rhs C"]), pc.get(JAC_IN_C, pc["jac C"])
        limit = physical_limit_s(st, rhs_us, jac_us)
        set_up_us, solve_us = lu_costs(pc)
        limit_la = physical_limit_s(st, rhs_us, jac_us, set_up_us)
        solves = newton_solves(st)
        limit_all = limit_la + max(solves - st["nlinsetups"], 0) * solve_us * 1e-6
        rows.append([label, phase, fmt(span), fmt(cpu / span), fmt(max(cpus) / cpu),
                     fmt(st["nsteps"] / span), fmt(st["nfevals"] / span),
                     fmt(st["njevals"] / span), fmt(solves / st["nsteps"]),
                     fmt(limit / span), fmt(cpu / limit),
                     fmt(limit_la / span), fmt(cpu / limit_la),
                     fmt(limit_all / span), fmt(cpu / limit_all),
                     *[fmt(st[key] / st["wall_time"], 2) if key in st else "-"
                       for key in ("rhs_time", "jac_time")],
                     f"{st['npivotings']} / {st['nlinsetups']}" if "npivotings" in st else "-"])
    return rows


def lu_costs(per_call: dict[str, float]) -> tuple[float, float]:
    """The LU costs of the limit [us]: a factorisation and solve, and a solve, each the cheaper
    of the library LU (CSparse or LAPACK; SuperLU's or LAPACK's solve) and ``bsm_lu``."""
    inf = float("inf")
    own_set_up = per_call.get("bsm_lu factor", inf) + per_call.get("bsm_lu solve", inf)
    return (min(per_call["lu fact+solve"], own_set_up),
            min(per_call["lu solve"], per_call.get("bsm_lu solve", inf)))


RUN_HEADER = ["backend", "phase", "sim [s]", "CPU / sim s", "spread (max/min)",
              "steps / sim s", "rhs / sim s", "jac / sim s", "solves / step",
              "limit / sim s (kernels)", "CPU / limit", "limit / sim s (+LU per set-up)",
              "CPU / limit (+LU per set-up)", "limit / sim s (+every solve)",
              "CPU / limit (+every solve)", "rhs share of wall", "jac share of wall",
              "fresh LU / set-ups"]


# ------------------------------------------------------------------------------ linsol
def linear_solvers(case: Case, solvers=LINEAR_SOLVERS, repeats: int = 3) -> list[list]:
    """Every linear solver on the start-up run (C kernels where possible)."""
    system, common = case.system()
    rows = []
    for solver in solvers:
        walls, res = [], None
        try:
            for _ in range(repeats):
                res = case.run(0.0, case.t_start_up, x0=common.get("x0"), compiled="auto",
                               linear_solver=solver)
                walls.append(res.stats["wall_time"])
        except Exception as exc:  # noqa: BLE001 - a solver may fail on a model
            rows.append([solver, "failed", str(exc).splitlines()[0][:60], "", "", ""])
            continue
        st = res.stats
        kern = st["rhs_time"] + st["jac_time"]
        label = solver if st["state_order"] == "system" else f"{solver} ({st['state_order']})"
        rows.append([label, fmt(min(walls)), fmt(max(walls) / min(walls)), st["nsteps"],
                     st["nlinsetups"], fmt((min(walls) - kern) / min(walls), 2)])
    return rows


# ------------------------------------------------------------------------------ set-up
def setup_costs(case: Case, n: int = 5) -> list[list]:
    """A short run (1 ms, or the case's start-up for the torque level) repeated: cold
    (kernel from the disk cache and integrator built) and warm (both cached), and the same
    with a changed parameter and constant input (still cached)."""
    system, common = case.system()
    t_run = min(case.t_start_up, 0.001)
    rows = []
    for comp in (False, True):
        clear_kernel_cache()
        clear_integrator_cache()
        walls = []
        for _ in range(n):
            t0 = time.perf_counter()
            res = case.run(0.0, t_run, x0=common.get("x0"), compiled=comp)
            walls.append((time.perf_counter() - t0, res.stats))
        first, rest = walls[0], walls[1:]
        st = first[1]
        rows.append([st["backend"], fmt(t_run), fmt(first[0] * 1e3),
                     fmt(st["kernel_time"] * 1e3), fmt(st["setup_time"] * 1e3),
                     fmt(statistics.median(w for w, _ in rest) * 1e3),
                     fmt(statistics.median(s["prepare_time"] for _, s in rest) * 1e3)])
    return rows


# ------------------------------------------------------------------------------ progress
class _Terminal(io.StringIO):
    """Standard error as a terminal (the bar's output discarded)."""

    def isatty(self) -> bool:
        return True


def progress_costs(case: Case, t_runs=(0.02, 0.3), n_points: int = 501,
                   repeats: int = 3) -> list[list]:
    """Start-up runs over ``t_runs`` [s] without and with a progress bar (``progress=True``,
    the bar's output discarded): least process CPU time of ``repeats`` (compiled kernels,
    integrators cached), the cost of the bar's clock, and whether the two runs' values are
    identical bit for bit."""
    system, common = case.system()

    def run(progress):
        with contextlib.redirect_stderr(_Terminal()):
            cpu = time.process_time()
            res = simulate(system, t_run, method=case.method, rtol=case.rtol, atol=case.atol,
                           n_points=n_points, compiled=True, progress=progress, **common)
        return res, time.process_time() - cpu

    rows = []
    for t_run in t_runs:
        runs_ = {flag: [run(flag) for _ in range(repeats)] for flag in (False, True)}
        plain, shown = runs_[False][0][0], runs_[True][0][0]
        cpu = {flag: min(c for _, c in r) for flag, r in runs_.items()}
        rows.append([fmt(t_run * 1e3), plain.stats["nsteps"], plain.stats["nfevals"],
                     fmt(cpu[False] * 1e3), fmt(cpu[True] * 1e3),
                     f"{100 * (cpu[True] / cpu[False] - 1):+.1f} %",
                     fmt((cpu[True] - cpu[False]) / plain.stats["nfevals"] * 1e6),
                     "yes" if np.array_equal(plain.values, shown.values) else "NO"])
    return rows


PROGRESS_HEADER = ["run [ms]", "steps", "rhs evaluations", "CPU no bar [ms]",
                   "CPU with bar [ms]", "bar's cost", "per evaluation [us]",
                   "values identical"]


# ------------------------------------------------------------------------------ main
def report(sections: tuple[str, ...], cases: tuple[str, ...],
           levels: tuple[str, ...] = ("-O0", "-O1", "-O2")) -> str:
    """The Markdown of the chosen sections for the chosen cases."""
    out: list[str] = []
    for name in cases:
        case = CASES[name]
        system, _ = case.system()
        out.append(f"### {case.label}: {system.n_states} states, method {case.method} "
                   f"(assembled in {case.cache['assemble_s']:.1f} s)\n")
        per_call = None
        if "calls" in sections or "runs" in sections:
            per_call = calls(case)
            out.append("Cost of one call [us] (CPU time, least of 7 loops):\n")
            out.append(markdown_table(list(per_call), [[fmt(v) if isinstance(v, float) else v
                                                        for v in per_call.values()]]) + "\n")
        if "compile" in sections:
            out.append(markdown_table(["flags", "generate + compile [s]", "library [MB]",
                                       "start-up run [s]", "rhs [us] in run",
                                       "jac [us] in run"],
                                      compile_levels(case, levels)) + "\n")
        if "runs" in sections:
            data = runs(case, per_call)
            out.append(markdown_table(RUN_HEADER, run_rows(case, data)) + "\n")
            out.append(f"VM vs C: max relative difference {data.get('max rel diff', 'n/a')}, "
                       f"same steps: {data.get('same steps', 'n/a')}\n")
        if "linsol" in sections:
            out.append(markdown_table(["linear solver", "start-up wall [s]", "spread", "steps",
                                       "factorizations", "share outside kernels"],
                                      linear_solvers(case)) + "\n")
        if "setup" in sections:
            out.append(markdown_table(["backend", "run [s]", "first call [ms]", "kernel [ms]",
                                       "integrator build [ms]", "later calls [ms]",
                                       "prepare (inputs, x0) [ms]"], setup_costs(case)) + "\n")
        if "progress" in sections:
            out.append(markdown_table(PROGRESS_HEADER, progress_costs(case)) + "\n")
    return "\n".join(out)


def section(quick: bool = False) -> Section:
    """The run_all section: calls, runs and set-up of the torque level, the 6304 massive-ball
    level and the nested dynamic bearing (the torque level only with ``quick``)."""
    cases = ("torque",) if quick else ("torque", "massive", "qs", "nested")
    intro = (
        "`simulate(..., method=\"cvodes\")` on CasADi's VM (`compiled=False`) and on generated "
        "C (`compiled=True`: right-hand side and exact Jacobian as a library loaded with "
        "`casadi.external`), same integrator, same steps; *C, compiled_bdf*: "
        "`method=\"compiled_bdf\"`, a BDF whose step loop is C calling the same C kernels "
        "(`bearingsim.simulation.compiled_bdf`; its own steps, no time split by kernel). "
        "Times are CPU times (the integration's thread, `Result.stats[\"integrate_cpu_time\"]`; "
        "per call the least of 7 loops, per run the least of 7 runs; *spread*: the slowest run "
        "over the fastest), so that the other jobs on this shared 2-core machine count less; "
        "ratios come from one run, side by side. "
        "*CPU / sim s*: CPU seconds per "
        "simulated second; *limit*: the compiled per-call costs times the calls the run took "
        "(kernels only, and with the LU of the Newton matrix: one factorisation and solve per "
        "linear set-up, i.e. per Jacobian update or step-size change), the physical limit of "
        f"this machine; the kernels' costs on ODE forms *{RHS_IN_C}* and *{JAC_IN_C}*, the "
        "calls repeated in loops inside C as the compiled integrators make them (of the "
        "Jacobian only the block d ode / d x; `bench/kernel_timing.py`), on the DAE form "
        "*rhs C* and *jac C*, a Python loop of calls of the whole functions less an empty "
        "function's loop; *CPU / limit*: the distance to it; *+every solve*: the limit counted "
        "with one LU solve per Newton iteration besides the set-ups' (CVODES' `nniters`, "
        "compiled_bdf's right-hand sides). The LU costs of the limits are the cheaper of a "
        "library LU (dense LAPACK, or above 200 states CSparse's ordered sparse LU, the "
        "default's; the solve LAPACK's or SuperLU's in the integrator's order) and the "
        "compiled integrators' own sparse LU (`bsm_lu`, `c/bsm_lu.c`; its factorisation and "
        "solve repeated in loops inside C), all measured on the "
        "run's Newton matrix I - 1e-3 J in the fill-reducing order. *bsm_lu factor*: a "
        "factorisation in the kept pivot order and fill pattern (what the integrator does at "
        "almost every set-up); *bsm_lu fresh*: one that finds a new pivot order and pattern "
        "(the first, and when a pivot falls below 1e-3 of its column); *dense-storage*: the "
        f"LU it replaced (commit `{SPARSE_LU_BEFORE}`'s, compiled from git: partial pivoting "
        "in dense storage, skipping zeros, the dense matrix's copy counted as its fill); "
        "*/ rhs*: in "
        "right-hand-side calls; *fresh LU / set-ups*: compiled_bdf's fresh factorisations "
        "(`npivotings`) of its linear set-ups. *solves / step*: "
        "Newton iterations per step. Where compiled_bdf's steps spend their time inside the "
        "run (the kernels, the LU and its stepping core apart), and its distance to the limit "
        "with the operations timed inside the same run (steadier than this table's ratios, "
        "whose run and per-call costs are measured apart under the machine's changing load): "
        "section \"The compiled BDF's stepping core\". Goals: at most 1 s per "
        "simulated second for the 6304 massive-ball level, 10 s for the nested dynamic bearing. "
        "Set-up: a 1 ms run repeated, first call (kernel from the disk cache, integrator built) "
        "and later calls (both cached).\n\n"
        "Command: `python -m bench.sundials_compiled calls runs setup --cases "
        + ",".join(cases) + "`\n")
    text = intro + "\n" + report(("calls", "runs", "setup"), cases)
    if not quick:
        levels = ("-O1", "-O1/-Og", "-Og", "-O2")
        text += ("\n#### Optimisation level of the kernel libraries\n\n"
                 "The default is -O1 for the main translation unit "
                 "(`bearingsim.simulation.compile.DEFAULT_FLAGS`) and -Og for the units split off "
                 "it, the per-ball Jacobians (`DEFAULT_SPLIT_FLAGS`; *A/B*: main unit at A, "
                 "split units at B): generate + compile time (empty cache) and the start-up run "
                 "on that library. Command: `python -m bench.sundials_compiled compile --cases "
                 "massive,nested --levels=" + ",".join(levels) + "`\n\n"
                 + report(("compile",), ("massive", "nested"), levels))
        text += ("\n#### Linear solvers\n\n"
                 "Every SUNDIALS linear solver on the start-up run, side by side (best of 3). "
                 "The sparse LU (`csparse`) of CVODES runs the states in a minimum-degree "
                 "order of the Jacobian (`bearingsim.simulation.ordering.fill_reducing_order`); "
                 "IDAS keeps the system's order. The default (`choose_linear_solver`) is dense "
                 "LU up to 200 unknowns, above it the ordered sparse LU (CVODES) or MUMPS "
                 "(IDAS). Command: `python -m bench.sundials_compiled linsol --cases "
                 "massive,qs,nested`\n\n" + report(("linsol",), ("massive", "qs", "nested")))
    return Section("SUNDIALS on compiled kernels", text)


def main() -> None:
    """Command line: one or more sections for the chosen cases, Markdown on stdout."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sections", nargs="+",
                        choices=["calls", "compile", "runs", "linsol", "setup", "progress"])
    parser.add_argument("--cases", default="torque,massive,qs,nested")
    parser.add_argument("--levels", default="-O0,-O1,-O2")
    args = parser.parse_args()
    print(report(tuple(args.sections), tuple(args.cases.split(",")),
                 tuple(args.levels.split(","))))


if __name__ == "__main__":
    main()
