"""Options of the CasADi functions the assembler builds: common subexpression elimination and
the rootfinders of nonlinear blocks (shared by code generation and the mapped-ball kernels)."""

from __future__ import annotations

__all__ = ["CSE", "ROOTFINDERS", "rootfinder_options"]

ROOTFINDERS = ("fast_newton", "newton")
"""CasADi rootfinder plugins the assembler can put in nonlinear blocks."""

CSE = {"cse": True}
"""Function options: common subexpression elimination (CasADi), e.g. 3x fewer instructions
for the duplex pair's right-hand side."""


def rootfinder_options(rootfinder: str, newton_tol: float) -> dict:
    """CasADi options of a nonlinear block's rootfinder.

    Parameters
    ----------
    rootfinder : {"fast_newton", "newton"}
        ``fast_newton``: plain Newton steps, generates C; ``newton``: with a line search.
    newton_tol : float
        Absolute tolerance on the residual (in the residual's units).

    Returns
    -------
    dict
        Options for ``casadi.rootfinder``.
    """
    if rootfinder == "fast_newton":
        return {"abstol": newton_tol, "max_iter": 50}
    return {"abstol": newton_tol, "max_iter": 100, "line_search": True,
            "show_eval_warnings": False}
