"""The typed state that the assembler's passes share.

``assemble`` fills the request fields (what to assemble and how); every other field is set by
one pass, named in its ``set_by`` metadata and its docstring, and read by the passes after it.
A pass states what it reads with :meth:`AssemblyState.require`, so a pass that runs before its
inputs exist (an extra pass inserted too early) stops with a :class:`PassOrderError` naming the
pass that should have run first.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.ir import Block, Causal, Repeats
from bearingsim.assembler.system import System
from bearingsim.errors import PassOrderError
from bearingsim.language.component import Component

__all__ = ["AssemblyState"]


def _set_by(name: str, **kwargs: Any) -> Any:
    """A dataclass field whose metadata names the pass that sets it."""
    return field(metadata={"set_by": name}, **kwargs)


@dataclass
class AssemblyState:
    """Everything the assembler's passes share, field by field with the pass that sets it."""

    root: Component = _set_by("assemble")
    """The instance tree to assemble."""
    outputs: list[str] | None = _set_by("assemble")
    """Dotted names of the requested outputs; ``None``: keep and output everything."""
    newton_tol: float = _set_by("assemble", default=1e-12)
    """Absolute residual tolerance of the Newton iterations of nonlinear loops."""
    rootfinder: str = _set_by("assemble", default="fast_newton")
    """CasADi rootfinder plugin of the nonlinear loops (see ``function_options.ROOTFINDERS``)."""
    dae: DAE | None = _set_by("flatten", default=None)
    """The flat DAE; alias elimination, index reduction and pruning transform it in place."""
    matching: dict[Eq, Var] | None = _set_by("matching", default=None)
    """Each equation -> the unknown it determines; pruning drops the dropped equations."""
    blocks: list[Block] | None = _set_by("BLT sorting", default=None)
    """The matched (equation, unknown) pairs as blocks in block lower triangular order."""
    causal: Causal | None = _set_by("tearing and block solving", default=None)
    """Every unknown as an expression of the base symbols, and the nonlinear blocks."""
    repeats: Repeats | None = _set_by("repeated structure", default=None)
    """The ball sets (identical members) and the shared unknowns solved around them."""
    system: System | None = _set_by("code generation", default=None)
    """The compiled result that ``assemble`` returns."""
    report: dict[str, str | int] = _set_by("any pass", default_factory=dict)
    """Summary lines by topic, for :attr:`System.report`."""

    def require(self, by: str, *names: str) -> None:
        """Check that the fields ``names`` that pass ``by`` reads are set.

        Parameters
        ----------
        by : str
            Name of the pass.
        *names
            Names of the fields the pass reads.

        Raises
        ------
        PassOrderError
            Naming the pass, each missing field and the pass that sets it.
        """
        set_by = {f.name: f.metadata["set_by"] for f in fields(self)}
        missing = [n for n in names if getattr(self, n) is None]
        if missing:
            needs = ", ".join(f"{n} (set by pass {set_by[n]!r})" for n in missing)
            raise PassOrderError(f"assembler pass {by!r} runs before what it needs: {needs}")
