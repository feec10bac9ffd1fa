"""Benchmark: assembly time of the ball-level bearing models, pass by pass.

The ball-level models are the largest the project assembles: every ball, contact and cage
pocket has its own equations. Each model is built once and assembled once; the table gives the
wall time of building the component tree, of the whole assembly and of its three most
expensive passes (``system.timings``), the number of states and the size of the right-hand side
and its Jacobian (CasADi instructions of the SX functions; MX functions with Newton blocks are
given as "MX"), and the time to generate and compile the kernel the SUNDIALS integrators run
(right-hand side and exact Jacobian; the quasi-static level's semi-explicit DAE residual for
IDAS: its ``newton`` blocks have no C) with an empty library cache at the default flags, beside
the targets for assembly plus compilation (6304 massive balls 5 s, quasi-static balls 15 s, the
nested bearing 20 s). The kernel is compiled twice, side by side: with one function per ball
mapped over each row (what simulations use; ``bearingsim.assembler.mapped``) and with the Z
balls inlined (``kernel(..., mapped=False)``, what every run used before).

Registered in ``bench/run_all.py``; ``python -m bench.ball_level_assembly`` prints the section.
"""

from __future__ import annotations

import tempfile
import time
from collections.abc import Callable

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
from bearingsim.physics.lubricant import Oil
from bearingsim.simulation.compile import DEFAULT_FLAGS, DEFAULT_SPLIT_FLAGS
from bearingsim.simulation.kernels import kernel
from bench.common import Section, fmt, markdown_table

__all__ = ["run", "section"]

PASS_COLUMNS = ("flatten", "tearing and block solving", "code generation")


def _models() -> list[tuple[str, Callable[[], object], str, float, dict]]:
    """(label, build, kernel form, target for assembly + compilation [s], assemble options)."""
    oil = Oil.from_iso_vg(32, method="oil_mist")
    axial = {"Fx": 0.0, "Fy": 0.0, "Fz": 100.0, "Mx": 0.0, "My": 0.0}
    return [
        ("6304, massive balls (`dynamic_massive_balls`)",
         lambda: deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0,
                                          loads={"Fx": 500.0}), "ode", 5.0, {}),
        ("6304, quasi-static balls (`dynamic`), DAE form (IDAS)",
         lambda: deep_groove_ball_bearing("6304", "dynamic", speed=100.0, loads={"Fx": 500.0}),
         "dae", 15.0, {}),
        ("6304, quasi-static balls (`dynamic`), ODE form with `fast_newton` (CVODES, FMU)",
         lambda: deep_groove_ball_bearing("6304", "dynamic", speed=100.0, loads={"Fx": 500.0}),
         "ode", 15.0, {"rootfinder": "fast_newton"}),
        ("61905/61907 double layer, `dynamic`",
         lambda: double_layer_bearing("61905", "61907", fidelity="dynamic", lubrication=oil,
                                      loads=axial), "ode", 20.0, {}),
    ]


def _size(system, key: str) -> str:
    fn = system.functions[key]
    return str(fn.n_instructions()) if fn.is_a("SXFunction") else "MX"


def _compile(system, form: str, mapped: bool) -> tuple[float, float, str]:
    """(seconds to build and compile the kernel into an empty cache, library size [MB],
    what it maps)."""
    with tempfile.TemporaryDirectory() as empty_cache:
        t0 = time.perf_counter()
        kern = kernel(system, form, True, cache_dir=empty_cache, mapped=mapped)
        return time.perf_counter() - t0, kern.library.stat().st_size / 1e6, kern.mapped


def run() -> dict:
    """Build and assemble each model once; compile its kernel mapped and inlined.

    Returns
    -------
    dict
        Per model label: ``states``, ``build_s``, ``assemble_s``, the pass times [s], the
        instruction counts of ``ode``, ``jac_x`` and the per-ball function, and per kernel
        (``mapped``, ``inlined``) the compile time [s] and library size [MB].
    """
    results = {}
    for label, build, form, target, options in _models():
        t0 = time.perf_counter()
        model = build()
        t1 = time.perf_counter()
        system = assemble(model, **options)
        t2 = time.perf_counter()
        mapped_s, mapped_mb, balls = _compile(system, form, True)
        ball_fn = system.mapped.get(form).ball_function
        inlined_s, inlined_mb, _ = _compile(system, form, False)
        passes = dict(system.timings)
        results[label] = {
            "states": system.n_states,
            "build_s": t1 - t0,
            "assemble_s": t2 - t1,
            "passes": {name: passes.get(name, 0.0) for name in PASS_COLUMNS},
            "ode_size": _size(system, "ode"),
            "jac_size": _size(system, "jac_x"),
            "ball_size": ball_fn.n_instructions(),
            "balls": balls,
            "form": form,
            "compile_s": mapped_s,
            "library_mb": mapped_mb,
            "inlined_compile_s": inlined_s,
            "inlined_library_mb": inlined_mb,
            "target_s": target,
        }
    return results


def section() -> Section:
    """The benchmark as a report section."""
    data = run()
    rows = [
        [label, r["states"], fmt(r["build_s"]), fmt(r["assemble_s"]),
         *[fmt(r["passes"][name]) for name in PASS_COLUMNS], r["ode_size"], r["jac_size"],
         r["ball_size"], f"{r['form']}: {fmt(r['compile_s'])}", fmt(r["library_mb"]),
         fmt(r["inlined_compile_s"]), fmt(r["inlined_library_mb"]),
         fmt(r["inlined_compile_s"] / r["compile_s"]),
         fmt(r["build_s"] + r["assemble_s"] + r["compile_s"]), fmt(r["target_s"])]
        for label, r in data.items()
    ]
    headers = ["model", "states", "build [s]", "assemble [s]",
               *[f"{name} [s]" for name in PASS_COLUMNS], "ode instr.", "jac_x instr.",
               "per-ball function instr.", "kernel, mapped balls [s]", "library [MB]",
               "kernel, balls inlined [s]", "library [MB]", "inlined / mapped",
               "total (mapped) [s]", "target [s]"]
    body = "\n".join([
        "Each model is built and assembled once (wall time, `time.perf_counter`); the pass times "
        f"are `system.timings`; kernels compiled with `{' '.join(DEFAULT_FLAGS)}` (the units "
        f"split off the main one, the per-ball Jacobians: `{' '.join(DEFAULT_SPLIT_FLAGS)}`) "
        "into an empty cache. The ODE form of the quasi-static level solves every ball's Newton "
        "block in one `fast_newton` rootfinder on the mapped DAE form "
        "(`bearingsim.assembler.mapped_forms.through_newton`). Code generation builds the inlined "
        "functions on first access (the mapped kernels never read them). The kernel is built "
        "and compiled twice in the same run: with one function per ball mapped over each row "
        "(what simulations use; building the mapped functions is part of its time) and with "
        "the balls inlined; *total* is build + assemble + the mapped kernel. "
        + "; ".join(f"{label}: {r['balls']}" for label, r in data.items())
        + ".",
        "",
        markdown_table(headers, rows),
    ])
    return Section("Assembly time of the ball-level models", body, data)


if __name__ == "__main__":
    print(section().body)
