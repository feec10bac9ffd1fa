"""``assemble``: the passes from an instance tree to a :class:`System`, as staged lists.

As in OpenModelica's new backend, the pipeline is three stages of named pass modules, each a
module (or object) with a ``NAME`` and a ``run(state)`` on the shared
:class:`~bearingsim.assembler.state.AssemblyState`:

* ``pre``: build and simplify the flat DAE. It need not balance yet: the structural check that
  opens the main stage names what is missing or extra.
* ``main``: the structural passes. Equations and unknowns must balance after each one (an
  internal :class:`~bearingsim.errors.StructuralError` otherwise).
* ``post``: from the sorted equations to compiled functions.

Every pass is timed (debug log of ``bearingsim.assembler`` and :attr:`System.timings`).
``assemble(..., extra_passes=...)`` runs user passes right after named ones, in the stage of the
pass they follow.
"""

from __future__ import annotations

import logging
import time as _time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Protocol

from bearingsim.assembler.function_options import ROOTFINDERS
from bearingsim.assembler.passes import (
    alias_elimination,
    blt,
    codegen,
    flatten,
    index_reduction,
    matching,
    pruning,
    repeated,
    structural_check,
    tearing,
)
from bearingsim.assembler.state import AssemblyState
from bearingsim.assembler.system import System
from bearingsim.checks import check_tolerance
from bearingsim.entry_points import entry_point
from bearingsim.errors import ParameterError
from bearingsim.language.component import Component
from bearingsim.validation import check_choice, check_mapping

__all__ = ["Pass", "Stage", "STAGES", "PASS_NAMES", "assemble"]

log = logging.getLogger("bearingsim.assembler")


class Pass(Protocol):
    """One step of the pipeline: a module or an object with a name and a ``run``."""

    NAME: str
    """Its name in timings, logs and the keys of ``extra_passes``."""

    def run(self, state: AssemblyState) -> None:
        """Read and update ``state`` (in place).

        Parameters
        ----------
        state : AssemblyState
            The assembly state the pass reads and updates.
        """


@dataclass(frozen=True)
class Stage:
    """A named list of passes run in order."""

    name: str
    passes: tuple[Pass, ...]
    check_balance: bool
    """Whether equations and unknowns must balance after each of its passes."""


STAGES: tuple[Stage, ...] = (
    Stage("pre", (flatten, alias_elimination), check_balance=False),
    Stage("main", (structural_check, index_reduction, matching, pruning, blt),
          check_balance=True),
    Stage("post", (tearing, repeated, codegen), check_balance=False),
)
"""The built-in pipeline, in execution order."""

PASS_NAMES: tuple[str, ...] = tuple(p.NAME for stage in STAGES for p in stage.passes)
"""Names of the built-in passes, in execution order: the valid keys of ``extra_passes``."""


def _with_extra_passes(extra_passes: Mapping[str, Pass | Sequence[Pass]] | None,
                       ) -> tuple[Stage, ...]:
    """:data:`STAGES` with each extra pass right after the pass its key names."""
    after: dict[str, list[Pass]] = {}
    names = set(PASS_NAMES)
    for point, value in check_mapping(extra_passes, "extra_passes", "assemble",
                                      "pass names").items():
        check_choice(point, "extra_passes key", PASS_NAMES, "assemble")
        passes = list(value) if isinstance(value, (list, tuple)) else [value]
        for p in passes:
            name = getattr(p, "NAME", None)
            if not isinstance(name, str) or not name or not callable(getattr(p, "run", None)):
                raise ParameterError(f"assemble: extra_passes[{point!r}] must be a pass or a "
                                     f"list of passes, each with a NAME (text) and a run(state) "
                                     f"method; got {p!r:.80}")
            if name in names:
                raise ParameterError(f"assemble: extra_passes[{point!r}]: a pass named {name!r} "
                                     f"is already in the pipeline; give each pass its own NAME")
            names.add(name)
        after[point] = passes
    return tuple(
        Stage(stage.name, tuple(q for p in stage.passes for q in (p, *after.get(p.NAME, ()))),
              stage.check_balance)
        for stage in STAGES
    )


@entry_point
def assemble(
    assembly: Component, outputs: list[str] | None = None, *, newton_tol: float = 1e-12,
    rootfinder: str | None = None,
    extra_passes: Mapping[str, Pass | Sequence[Pass]] | None = None,
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
    extra_passes : dict, optional
        Built-in pass name (one of :data:`PASS_NAMES`) -> a pass or a list of passes to run
        right after it, in that order. A pass is a module or object with a ``NAME`` (text, not
        used by another pass) and a ``run(state)`` method on the
        :class:`~bearingsim.assembler.state.AssemblyState`; it is timed like the built-in
        passes, and in the main stage followed by the balance check.

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
    check_tolerance(newton_tol, "newton_tol", "newton", "assemble")
    if rootfinder is None:
        rootfinder = ("newton" if any(c.needs_line_search for c in assembly.walk())
                      else "fast_newton")
    check_choice(rootfinder, "rootfinder", ROOTFINDERS, "assemble")
    stages = _with_extra_passes(extra_passes)
    state = AssemblyState(assembly, list(outputs) if outputs else None, newton_tol, rootfinder)
    timings = []
    for stage in stages:
        for p in stage.passes:
            t0 = _time.perf_counter()
            p.run(state)
            dt = _time.perf_counter() - t0
            timings.append((p.NAME, dt))
            log.debug("pass %-26s %8.2f ms", p.NAME, dt * 1e3)
            if stage.check_balance:
                state.dae.check_balance(p.NAME)
    state.require("assemble", "system")
    state.system.timings = timings
    state.system.report = state.report
    state.system.requested_outputs = list(outputs) if outputs else None
    return state.system
