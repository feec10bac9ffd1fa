"""The integration method of ``simulate(method=None)``, and whether a first run on a cold cache
waits for the C compiler.

The rule (the work-precision data behind it: ``docs/benchmarks.md``, sections "SUNDIALS on
compiled kernels" and "Deep-groove work-precision, 50 ms"; ``docs/simulation.md``):

1. a model whose nonlinear blocks use a rootfinder without C code generation (``newton``):
   ``"idas"`` on the semi-explicit DAE form, which compiles;
2. no C compiler, or ``compiled=False``: ``"cvodes"`` on CasADi's VM;
3. otherwise the ODE form (every shipped model is stiff: ball contacts and friction) with
   ``"compiled_bdf"``, the BDF step loop in C on the compiled kernels, about twice as fast
   as CVODES on the same kernels at matched error, except
4. on a cold cache (the kernel library not compiled yet), a run expected to end before the
   compiler does starts on the VM with ``"cvodes"`` while C compiles in the background (both
   give the same numbers as on C); a longer one waits for the compiler and runs
   ``"compiled_bdf"``. The run's VM cost is estimated from a few evaluations of the VM
   right-hand side and the run's length (:data:`RHS_PER_SIMULATED_S`,
   :data:`VM_STEP_FACTOR`); the compile time from the C source's size at this machine's
   recorded compile speed (:func:`~bearingsim.simulation.c_compiler.compile_estimate`);
5. tiny models (the kernel below
   :data:`~bearingsim.simulation.kernels.AUTO_MIN_INSTRUCTIONS`): ``"cvodes"`` on the VM,
   which costs less than compiling.

``Result.stats["method"]`` names the method and ``stats["method_reason"]`` says why;
``stats["backend"]`` and ``stats["backend_reason"]`` the evaluator.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from bearingsim.assembler.numeric import buffered
from bearingsim.assembler.system import System
from bearingsim.simulation.c_compiler import c_compiler, compile_estimate
from bearingsim.simulation.kernels import COMPILED, kernel, pending_build

__all__ = ["RHS_PER_SIMULATED_S", "VM_STEP_FACTOR", "MethodChoice", "choose_method"]

RHS_PER_SIMULATED_S = 1.0e5
"""Right-hand-side evaluations per simulated second [1/s] a first run is assumed to take
(CVODES at rtol 1e-5 on the 6304 massive-ball start-up: 1.2e5/s over 10 ms, 5e4/s over
300 ms)."""

VM_STEP_FACTOR = 2.0
"""VM cost of a CVODES run per right-hand-side evaluation, in right-hand sides (Jacobians,
linear algebra, the integrator's own work: 2.7 on the 6304 massive-ball start-up)."""


@dataclass(frozen=True)
class MethodChoice:
    """The method of a run and the ``compiled`` argument it runs with, and why."""

    method: str
    compiled: bool | str
    reason: str


def _vm_seconds(system: System, function, t_span: float) -> float:
    """Expected VM time [s] of a run over ``t_span`` [s]: the right-hand side's cost (least of
    three evaluations at the start values) times the assumed evaluations."""
    call = buffered(function)
    args = (0.0, system.x0(), system.u_default(), system.p0())
    costs = []
    for _ in range(3):
        start = time.perf_counter()
        call(*args)
        costs.append(time.perf_counter() - start)
    return t_span * RHS_PER_SIMULATED_S * VM_STEP_FACTOR * min(costs)


def choose_method(system: System, t_span: float, compiled: bool | str) -> MethodChoice:
    """The method of ``simulate(system, ..., method=None)`` (rules in the module docstring).

    Parameters
    ----------
    system : System
        The system to integrate.
    t_span : float
        Length of the run [s].
    compiled : bool or "auto"
        ``simulate``'s ``compiled`` argument.

    Returns
    -------
    MethodChoice
    """
    if system.rootfinder not in (None, "fast_newton") and "dae_ode" in system.functions:
        return MethodChoice("idas", compiled, f"nonlinear blocks with the "
                            f"{system.rootfinder!r} rootfinder (no C for the ODE form): IDAS "
                            "on the semi-explicit DAE form")
    if compiled is False:
        return MethodChoice("cvodes", False, "compiled=False: CVODES on CasADi's VM")
    if c_compiler() is None:
        return MethodChoice("cvodes", compiled, "no C compiler: CVODES on CasADi's VM")
    if compiled is True:
        return MethodChoice("compiled_bdf", True, "stiff ODE form, compiled=True: the BDF "
                            "step loop in C on the compiled kernels")
    kern = kernel(system, "ode", "auto")
    if kern.backend == COMPILED:
        return MethodChoice("compiled_bdf", True, "stiff ODE form, compiled kernels cached: "
                            "the BDF step loop in C")
    build = pending_build(system, "ode")
    if build is None:  # a tiny model, or a failed build: the VM
        return MethodChoice("cvodes", "auto", f"CVODES on CasADi's VM ({kern.reason})")
    run_s = _vm_seconds(system, kern.function, t_span)
    compile_s = max(compile_estimate(build.source_bytes, build.lib.parent)
                    - (time.perf_counter() - build.started), 0.0)
    if run_s > compile_s:
        kernel(system, "ode", True)  # waits for the build
        return MethodChoice("compiled_bdf", True, f"cold cache: the run (about "
                            f"{_seconds(run_s)} on the VM) outlasts compiling (about "
                            f"{_seconds(compile_s)}): waited for the compiler, then the BDF "
                            "step loop in C")
    return MethodChoice("cvodes", "auto", f"cold cache: a short run (about {_seconds(run_s)} "
                        f"on the VM) starts on CasADi's VM with CVODES while C compiles in "
                        f"the background (about {_seconds(compile_s)}; same numbers)")


def _seconds(value: float) -> str:
    """A duration for a message: ``0.42 s``, ``12 s``."""
    return f"{value:.2g} s" if value < 10 else f"{np.round(value):.0f} s"
