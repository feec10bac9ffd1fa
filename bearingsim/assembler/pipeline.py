"""``assemble``: the ordered list of named passes from an instance tree to a :class:`System`.

Each pass is a small function of the shared :class:`AssemblyState`; the pipeline times every
pass (debug log) and checks after each one that equations and unknowns still balance.
"""

from __future__ import annotations

import logging
import time as _time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import casadi as ca

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.passes import (
    alias_elimination,
    blt,
    codegen,
    flatten,
    index_reduction,
    matching,
    pruning,
    structural_check,
    tearing,
)
from bearingsim.assembler.system import Signal, System
from bearingsim.errors import ParameterError, StructuralError
from bearingsim.language.component import Component
from bearingsim.validation import check_choice, check_range, entry_point

__all__ = ["AssemblyState", "PASSES", "assemble"]

log = logging.getLogger("bearingsim.assembler")


@dataclass
class AssemblyState:
    """Everything the passes share."""

    root: Component
    outputs: list[str] | None
    newton_tol: float = 1e-12
    rootfinder: str = "fast_newton"
    dae: DAE | None = None
    matching: dict[Eq, Var] = field(default_factory=dict)
    blocks: list = field(default_factory=list)
    causal: tearing.Causal | None = None
    system: System | None = None
    report: dict[str, Any] = field(default_factory=dict)


def _flatten(s: AssemblyState) -> None:
    s.dae = flatten.flatten(s.root)
    s.report["flat"] = f"{len(s.dae.vars)} variables, {len(s.dae.eqs)} equations"


def _alias(s: AssemblyState) -> None:
    n = len(s.dae.vars)
    alias_elimination.eliminate_aliases(s.dae)
    s.report["aliases eliminated"] = n - len(s.dae.vars)


def _structural_check(s: AssemblyState) -> None:
    structural_check.check_structure(s.dae)


def _index_reduction(s: AssemblyState) -> None:
    info = index_reduction.reduce_index(s.dae)
    if info["differentiated_equations"]:
        s.report["index reduction"] = (
            f"{info['differentiated_equations']} equation(s) differentiated; dummy derivatives: "
            + (", ".join(info["dummy_derivatives"]) or "none")
        )


def _matching(s: AssemblyState) -> None:
    s.matching = matching.match(s.dae)


def _pruning(s: AssemblyState) -> None:
    if s.outputs:
        s.dae.skipped.extend(pruning.prune(s.dae, s.matching, s.outputs))


def _blt(s: AssemblyState) -> None:
    s.blocks = blt.blt_blocks(s.dae, s.matching)


def _tearing(s: AssemblyState) -> None:
    s.causal = tearing.causalize(s.dae, s.blocks)
    c = s.causal
    s.report["blocks"] = (
        f"{c.n_blocks} (largest {c.largest_block}; {c.n_linear_loops} linear loop(s) solved "
        f"symbolically; {len(c.nonlinear)} nonlinear loop(s) by Newton)"
    )


def _codegen(s: AssemblyState) -> None:
    dae = s.dae
    funcs, observed, out_names = codegen.build_functions(dae, s.causal, s.outputs, s.newton_tol,
                                                       s.rootfinder)
    units = {v.name: v.unit for v in dae.vars}
    descs = {v.name: v.description for v in dae.vars}
    for name, (_, rep, _) in dae.aliases.items():
        decl = dae.alias_declarations.get(name)
        units[name] = decl[0] if decl else (rep.unit if rep is not None else "1")
        descs[name] = decl[1] if decl else ""
    states = [
        Signal(v.name, v.unit, v.description, v.start if v.start is not None else 0.0, v.fixed,
               v.nominal)
        for v in dae.states
    ]
    inputs = [Signal(v.name, v.unit, v.description, v.default or 0.0, low=v.low, high=v.high)
              for v in dae.inputs]
    outputs = [Signal(n, units.get(n, "1"), descs.get(n, "")) for n in out_names]
    init_fn, free = _initial_problem(dae, funcs)
    s.system = System(
        name=s.root.display_name,
        states=states,
        inputs=inputs,
        outputs=outputs,
        params=dae.params,
        functions=funcs,
        observed_names=observed,
        observed_units={n: units.get(n, "1") for n in observed},
        observed_descriptions={n: descs.get(n, "") for n in observed},
        init_residual=init_fn,
        free_initial_states=free,
        skipped=list(dae.skipped),
        rootfinder=s.rootfinder if s.causal.nonlinear else None,
    )


def _initial_problem(dae: DAE, funcs: dict) -> tuple[ca.Function | None, list[int]]:
    """Residual of the initial equations as a function of (t, x, u, p), and the free states."""
    if not dae.initial_eqs:
        return None, []
    states = dae.states
    free = [k for k, v in enumerate(states) if not v.fixed]
    if len(free) != len(dae.initial_eqs):
        raise StructuralError(
            f"{len(dae.initial_eqs)} initial equation(s) for {len(free)} state(s) without a "
            "fixed start value; give fixed=False exactly to the states the initial equations "
            "determine",
            equations=[e.describe() for e in dae.initial_eqs],
            unknowns=[states[k].name for k in free],
        )
    values = ca.vertcat(*[v.sym for v in dae.vars])
    p = ca.vertcat(*[q.sym for q in dae.params]) if dae.params else ca.SX(0, 1)
    res = ca.vertcat(*[e.residual for e in dae.initial_eqs])
    r_fn = ca.Function("init_r", [values, dae.time, p], [res])
    obs = funcs["observe"]
    mt, mx = ca.MX.sym("t"), ca.MX.sym("x", obs.size1_in(1))
    mu, mp = ca.MX.sym("u", obs.size1_in(2)), ca.MX.sym("p", obs.size1_in(3))
    all_vals = obs(mt, mx, mu, mp)[: len(dae.vars)]
    res_mx = r_fn(all_vals, mt, mp)
    return ca.Function("init", [mt, mx, mu, mp], [res_mx], ["t", "x", "u", "p"], ["r"]), free


Pass = tuple[str, Callable[[AssemblyState], None], bool]

PASSES: list[Pass] = [
    ("flatten", _flatten, False),
    ("alias elimination", _alias, False),
    ("structural check", _structural_check, True),
    ("index reduction", _index_reduction, True),
    ("matching", _matching, True),
    ("pruning", _pruning, True),
    ("BLT sorting", _blt, True),
    ("tearing and block solving", _tearing, False),
    ("code generation", _codegen, False),
]
"""(name, function, check balance afterwards) in execution order."""


@entry_point
def assemble(
    assembly: Component, outputs: list[str] | None = None, *, newton_tol: float = 1e-12,
    rootfinder: str | None = None,
) -> System:
    """Flatten, reduce and compile an assembly.

    Parameters
    ----------
    assembly : Component
        The root of the instance tree.
    outputs : list of str, optional
        Dotted names of the variables the caller needs. Only equations and states they depend on
        are kept (pruning). ``None`` keeps everything and outputs every variable.
    newton_tol : float
        Absolute residual tolerance of the Newton iterations of nonlinear loops.
    rootfinder : {"fast_newton", "newton"}, optional
        CasADi plugin of the nonlinear loops: ``"fast_newton"`` (plain Newton, generates C:
        needed by :func:`~bearingsim.fmu.export_fmu` and
        :func:`~bearingsim.simulation.compile.compile_system`) or ``"newton"`` (with a line
        search). Default: ``"newton"`` if a component of the assembly declares
        ``needs_line_search`` (e.g. the quasi-static ball), else ``"fast_newton"``.

    Returns
    -------
    System
        Compiled functions with names, units, start values and the pass report.
    """
    if not isinstance(assembly, Component):
        raise ParameterError(f"assemble: expected a component or assembly (a model to "
                             f"assemble), got {type(assembly).__name__}")
    if outputs is not None and (isinstance(outputs, str) or not all(
            isinstance(o, str) for o in outputs)):
        raise ParameterError(f"assemble: outputs must be a list of variable names, got "
                             f"{outputs!r:.80}")
    check_range(newton_tol, "newton_tol", "1", 0.0, None, low_inclusive=False,
                where="assemble")
    if rootfinder is None:
        rootfinder = ("newton" if any(c.needs_line_search for c in assembly.walk())
                      else "fast_newton")
    check_choice(rootfinder, "rootfinder", codegen.ROOTFINDERS, "assemble")
    state = AssemblyState(assembly, list(outputs) if outputs else None, newton_tol, rootfinder)
    timings = []
    for name, fn, check in PASSES:
        t0 = _time.perf_counter()
        fn(state)
        dt = _time.perf_counter() - t0
        timings.append((name, dt))
        log.debug("pass %-26s %8.2f ms", name, dt * 1e3)
        if check:
            state.dae.check_balance(name)
    state.system.timings = timings
    state.system.report = state.report
    return state.system
