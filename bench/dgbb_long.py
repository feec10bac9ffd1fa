"""Benchmark: deep-groove work-precision over 50 ms of each of the four duty conditions.

The question the study asks of its model is the cage speed under each duty condition, from rest
through the speed ramp into steady running; 50 ms covers the ramp (5 ms) and the settling of
the cage. For each condition:

* the study's method: Newton-Raphson for the quasi-static ball positions inside every stage of
  fixed-step classical RK4 (the ``dynamic`` model) at 0.9 of its stable step
  ``2.785 / |lambda|_max``, its fastest setting (:data:`FRACTIONS`), twice: on CasADi's VM
  (the right-hand side with its ``fast_newton`` blocks evaluated by the VM, as the study's
  Python loop would call it) and on the compiled kernel (the same right-hand side, every
  ball's Newton iteration compiled C): the same steps and errors, the second several times
  faster; both ratios are reported;
* this project's SUNDIALS integrators on compiled kernels: IDAS on the same quasi-static model
  (its semi-explicit DAE form: the ball equations are algebraic, no Newton iteration inside the
  right-hand side; the ``newton`` blocks of the ODE form have no C) and CVODES on the
  ``dynamic_massive_balls`` model (ball inertia instead of quasi-static balls: a pure ODE),
  and on that model the BDF loop in C (``method="compiled_bdf"``) on the same kernels;
* the error: relative error of the final cage speed against each model's own run at rtol
  1e-9: CVODES on the massive-ball model; on the quasi-static model CVODES on its ODE form, or
  IDAS on its DAE form where CVODES stops (a ball's Newton iteration failing at a trial state);
* the ratio: the study's wall time (each variant) over ours at the study's errors (log-log
  interpolation of our curve); the physical limit of each CVODES run: compiled per-call costs
  of the right-hand side, its Jacobian and a dense LU of the Newton matrix, times the calls
  the run made;
* the models differ: the massive-ball and quasi-static final cage speeds differ by 1e-4 to
  5e-3 over 50 ms (relative; measured per condition and printed), far above the errors
  compared, so each method's error is taken against a reference of its own model.

Kernels are compiled before timing (a library is built once per machine and model; its time is
reported beside the table); the integrator is built by a first, untimed run.

``python -m bench.dgbb_long`` prints the section (``--quick``: condition 1 over 10 ms).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from bearingsim.assembler.numeric import buffered
from bearingsim.errors import SimulationError
from bearingsim.simulation import simulate
from bearingsim.simulation.closed import close_inputs
from bearingsim.simulation.fastcall import BufferedFunction
from bearingsim.simulation.inputs import input_signal
from bearingsim.simulation.kernels import kernel
from bearingsim.studies.deep_groove import DUTY_CYCLE
from bench import dgbb
from bench.common import Section, fmt, interp_loglog, markdown_table
from bench.sundials_compiled import dense_lu_us, per_call_us, physical_limit_s

__all__ = ["run", "section"]

T_END = 0.05
RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7)
FRACTIONS = (0.9,)
"""RK4 step as a fraction of its stable step. At 0.9 the study's method already reaches a
cage-speed error of ~4e-8 over 10 ms (condition 1): a smaller step only costs it more time, so
one point per condition is the study at its fastest."""


def _cage_error(value: float, ref: dict) -> float:
    return abs(value - ref["w_cage"]) / abs(ref["w_cage"])


def _per_call(system, res, form: str) -> dict[str, float]:
    """Compiled per-call costs [us] at the end of ``res``: right-hand side (or DAE residual),
    its Jacobian and a dense LU factorisation and solve of the Newton matrix."""
    kern = kernel(system, form, True)
    x = np.array([res.final(n) for n in system.state_names])
    signal = input_signal(system, None)
    t, p = res.t[-1], system.p0()
    u = np.asarray(signal.u(t, signal.q), dtype=float).ravel()
    args = [t, x, u, p]
    if form == "dae":
        funcs = system.symbolic_functions or system.functions
        z = np.asarray(funcs["dae_z"](t, x, u, p), dtype=float).ravel()
        args = [t, x, z, u, p]
    value = kern.function(*args)
    value = list(value) if isinstance(value, (list, tuple)) else [value]
    n = system.n_states + (args[2].size if form == "dae" else 0)
    return {"rhs": per_call_us(kern.function, args, n=2000),
            "jac": per_call_us(kern.function.jacobian(), [*args, *value], n=500),
            "lu": dense_lu_us(n)}


def _sundials(system, method: str, ref, t_end: float, label: str, pc: dict[str, float]):
    """Rows and the (error, wall) curve of CVODES or IDAS on compiled kernels over ``RTOLS``."""
    rows, curve = [], []
    for rtol in RTOLS:
        kw = dict(method=method, rtol=rtol, atol=rtol * 0.1, n_points=3, progress=False,
                  compiled=True)
        try:
            simulate(system, t_end, **kw)  # builds the integrator (once per system and setting)
        except SimulationError as exc:  # a loose tolerance can lose the run: say so
            rows.append([label, f"rtol {rtol:g}", "failed", str(exc).split(";")[0], "", "", ""])
            continue
        t0 = time.perf_counter()
        res = simulate(system, t_end, **kw)
        wall = time.perf_counter() - t0
        err = _cage_error(res.final("w_cage"), ref)
        limit = physical_limit_s(res.stats, pc["rhs"], pc["jac"], pc["lu"])
        curve.append((err, wall))
        rows.append([label, f"rtol {rtol:g}", fmt(wall), fmt(err, 2), fmt(res.stats["nsteps"]),
                     fmt(limit), fmt(wall / limit)])
    return rows, curve


STUDY_VM = "study: RK4 + Newton (qs), VM"
STUDY_C = "study: RK4 + Newton (qs), compiled fast_newton"


def _rk4(rhs, x: np.ndarray, t_end: float, dt: float) -> tuple[np.ndarray, float]:
    """Classical RK4 from ``t = 0`` with a fixed step of at most ``dt`` [s], ending exactly at
    ``t_end``; ``rhs(t, x)`` the state derivatives. Returns the end state and the step."""
    n = int(np.ceil(t_end / dt))
    dt = t_end / n
    t = 0.0
    for _ in range(n):
        k1 = rhs(t, x)
        k2 = rhs(t + dt / 2, x + dt / 2 * k1)
        k3 = rhs(t + dt / 2, x + dt / 2 * k2)
        k4 = rhs(t + dt, x + dt * k3)
        x = x + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t += dt
    return x, dt


def _study_rhs(system, compiled: bool):
    """The study's right-hand side ``rhs(t, x)``: the closed model on CasADi's VM, or the
    compiled ODE kernel (its ``fast_newton`` blocks in C), both through buffers."""
    p = system.p0()
    if not compiled:
        f = BufferedFunction(close_inputs(system, None).f).vector
        return lambda t, x: f(t, x, p)
    call = buffered(kernel(system, "ode", True).function)
    u = input_signal(system, None).at(0.0)[:, 0]  # constant loads; the speed is in the model
    return lambda t, x: call(t, x, u, p)[0].ravel()


def _study(system, compilable, ref, t_end: float, dt_stable: float, fractions):
    """Rows and (error, wall) curves of the study's method on the VM (``system``) and on
    compiled C (``compilable``: the same model assembled with ``fast_newton`` blocks)."""
    rows, curves = [], {}
    for label, model, compiled in ((STUDY_VM, system, False), (STUDY_C, compilable, True)):
        rhs = _study_rhs(model, compiled)
        for frac in fractions:
            t0 = time.perf_counter()
            x, dt = _rk4(rhs, model.x0(), t_end, frac * dt_stable)
            wall = time.perf_counter() - t0
            err = _cage_error(model.observe(t_end, x)["w_cage"], ref)
            curves.setdefault(label, []).append((err, wall))
            rows.append([label, f"dt {dt:.3g} s", fmt(wall), fmt(err, 2),
                         fmt(round(t_end / dt)), "", ""])
    return rows, curves


def _ratios(study: dict[str, list], ours: dict[str, list]) -> list[list[str]]:
    """The study's wall time over ours at the study's error, per study variant and method."""
    out = []
    for variant, points in study.items():
        for label, curve in ours.items():
            for err, wall in points:
                a = interp_loglog(err, [e for e, _ in curve], [w for _, w in curve])
                out.append([variant, label, fmt(err, 2), fmt(wall / a) if np.isfinite(a) else
                            "outside our error range"])
    return out


def _qs_reference(qs, t_end: float) -> tuple[dict, str]:
    """The quasi-static model's reference run and how it was made: CVODES on its ODE form at
    rtol 1e-9, or IDAS on its DAE form where CVODES stops (a ball's Newton iteration failing
    at a trial state)."""
    try:
        return dgbb._reference(qs, t_end), "CVODES, ODE form"
    except SimulationError:
        return dgbb._reference(qs, t_end, "idas"), "IDAS, DAE form (CVODES stopped)"


def run(quick: bool = False) -> tuple[str, dict]:
    """Run the benchmark; return the Markdown body and the ratios by condition."""
    t_end = 0.01 if quick else T_END
    conditions = (1,) if quick else (1, 2, 3, 4)
    lines = [f"Model: 6304, one slice per contact, speed ramp over {dgbb.RAMP * 1e3:g} ms, "
             f"t = 0 .. {t_end:g} s. Error: relative error of the final cage speed against "
             "a run at rtol 1e-9 on the same model (massive balls: CVODES; quasi-static balls: "
             "CVODES on the ODE form, or IDAS on the DAE form where CVODES stops, a ball's "
             "Newton iteration failing at a trial state: named per condition). *limit*: "
             "compiled per-call costs "
             "(right-hand side, Jacobian, dense LU) times the calls of the run; *wall / limit* "
             "the distance to it. Ratio: the study's wall time / ours at the study's error, "
             "with the study's loop (RK4 + Newton) on CasADi's VM and on compiled kernels "
             "(`fast_newton` blocks in C): both are honest baselines, the second the faster. "
             "The massive-ball and quasi-static models are different models: their final "
             "cage speeds differ by 1e-4..5e-3 over 50 ms (this run's difference per "
             "condition below), far more than the errors compared, so each method's error "
             "is taken against its own model's reference (like with like).",
             "", f"Command: `python -m bench.dgbb_long{' --quick' if quick else ''}`", ""]
    numbers: dict = {}
    for k in conditions:
        qs = dgbb._system(k, "dynamic")
        massive = dgbb._system(k, "dynamic_massive_balls")
        qs_fast = dgbb._system(k, "dynamic", rootfinder="fast_newton")
        t0 = time.perf_counter()
        kernel(qs, "dae", True)
        kernel(massive, "ode", True)
        kernel(qs_fast, "ode", True)
        compile_s = time.perf_counter() - t0
        ref_qs, ref_method = _qs_reference(qs, t_end)
        ref_m = dgbb._reference(massive, t_end)
        _, dt_qs = dgbb.stable_step(qs, ref_qs["res"])
        study_rows, study = _study(qs, qs_fast, ref_qs, t_end, dt_qs, FRACTIONS)
        rows_qs, curve_qs = _sundials(qs, "idas", ref_qs, t_end, "IDAS, C (qs)",
                                      _per_call(qs, ref_qs["res"], "dae"))
        pc_m = _per_call(massive, ref_m["res"], "ode")
        rows_m, curve_m = _sundials(massive, "cvodes", ref_m, t_end, "CVODES, C (massive balls)",
                                    pc_m)
        rows_b, curve_b = _sundials(massive, "compiled_bdf", ref_m, t_end,
                                    "compiled_bdf (massive balls)", pc_m)
        ratios = _ratios(study, {"IDAS, C (qs)": curve_qs,
                                 "CVODES, C (massive balls)": curve_m,
                                 "compiled_bdf (massive balls)": curve_b})
        numbers[k] = ratios
        models = abs(ref_m["w_cage"] - ref_qs["w_cage"]) / abs(ref_qs["w_cage"])
        numbers.setdefault("model_difference", {})[k] = models
        n_rpm, load = DUTY_CYCLE[k - 1]
        lines += [f"### Condition {k}: {n_rpm:g} r/min, {load:g} N", "",
                  f"Kernels generated and compiled (or loaded from the cache) in "
                  f"{compile_s:.1f} s; RK4 stable step of the qs model {dt_qs:.3g} s; "
                  f"reference of the qs model: {ref_method}. The two models' reference cage "
                  f"speeds differ by {models:.2g} (relative): each method's error is taken "
                  "against its own model's reference.", "",
                  markdown_table(["method", "setting", "wall [s]", "cage-speed error",
                                  "steps", "limit [s]", "wall / limit"],
                                 study_rows + rows_qs + rows_m + rows_b), "",
                  "The study's wall time / ours at matched cage-speed error (goal >= 50), for "
                  "the study's loop on the VM and on compiled kernels:", "",
                  markdown_table(["study", "ours", "error", "ratio"], ratios), ""]
    return "\n".join(lines), numbers


def section(quick: bool = False) -> Section:
    """The run_all section."""
    body, numbers = run(quick)
    return Section("Deep-groove work-precision over 50 ms, four duty conditions", body,
                   {"ratios": numbers})


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    print(run(parser.parse_args().quick)[0])


if __name__ == "__main__":
    main()
