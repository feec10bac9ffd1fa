"""Messages about a failed integration: which states diverged, what a failed CasADi evaluation
means."""

from __future__ import annotations

import re

import numpy as np

from bearingsim.assembler.system import System

__all__ = ["diverged", "evaluation_failure", "listed_names", "no_value_cause",
           "sundials_failure"]

_FAILED_IN = re.compile(r"for '(\S+)' \[(\w+)\]")

_SUNDIALS_FLAG = re.compile(r'returned "((?:CV|IDA)_[A-Z_]+)"')
"""The return flag of CVode or IDASolve in CasADi's error text."""

SUNDIALS_FLAGS: tuple[tuple[tuple[str, ...], str], ...] = (
    (("RHSFUNC", "RES_ERR", "RES_FAIL"),
     "the right-hand side was not finite or failed at the states the integrator tried, "
     "repeatedly (NaN or inf: a square root or logarithm of a negative value, or a division "
     "by zero, as a state crosses zero?)"),
    (("CONV_FAIL",), "the Newton iteration of the implicit steps failed repeatedly, down to "
                     "the smallest step (a discontinuity or a blow-up?)"),
    (("ERR_FAIL",), "the local error test failed repeatedly, down to the smallest step (a "
                    "discontinuity or a blow-up?)"),
    (("TOO_MUCH_ACC",), "the tolerances are tighter than the arithmetic allows (raise rtol "
                        "and atol)"),
    (("LINIT_FAIL", "LSETUP_FAIL", "LSOLVE_FAIL"),
     "the linear solver failed (a singular Newton matrix, or Jacobian entries not finite?)"),
)
"""What the failure flags of CVODES and IDAS mean (by a part of the flag's name), for
messages."""


def diverged(system: System, x: np.ndarray, x0: np.ndarray) -> str:
    """The non-finite states of ``x``, or the five that grew most from ``x0``, for messages.

    Parameters
    ----------
    system : System
        The system whose state vector ``x`` is.
    x, x0 : numpy.ndarray
        The state where the integration failed and the start state.

    Returns
    -------
    str
        ``"non-finite: a, b"`` or ``"largest growth: a=1e3, ..."``.
    """
    bad = [n for n, v in zip(system.state_names, x, strict=True) if not np.isfinite(v)]
    if bad:
        return "non-finite: " + ", ".join(bad[:10])
    growth = np.abs(x) / (np.abs(x0) + 1.0)
    order = np.argsort(growth)[::-1][:5]
    return "largest growth: " + ", ".join(
        f"{system.state_names[k]}={x[k]:.3g}" for k in order
    )


def evaluation_failure(exc: BaseException) -> str:
    """What a failed evaluation of the model's CasADi functions means, in one line: a Newton
    block that did not converge named as such, else the innermost CasADi message.

    Parameters
    ----------
    exc : BaseException
        The error CasADi raised (its text: one line per function in the call chain, then the
        reason).

    Returns
    -------
    str
        E.g. ``"the Newton iteration of the nonlinear block newton0 did not converge (no
        solution near its start: a speed or load beyond what the model carries?)"``.
    """
    text = str(exc)
    chain = _FAILED_IN.findall(text)
    reason = text.strip().splitlines()[-1] if text.strip() else type(exc).__name__
    if "rootfinder process failed" in text:
        block = next((name for name, kind in reversed(chain)
                      if kind in ("FastNewton", "Newton")), "of the model")
        return (f"the Newton iteration of the nonlinear block {block} did not converge (no "
                "solution near its start: a speed or load beyond what the model carries?)")
    where = f" in {chain[-1][0]}" if chain else ""
    return f"{type(exc).__name__}{where}: {reason[:300]}"


def sundials_failure(exc: BaseException) -> str:
    """What the failure flag of a CVODES or IDAS call means, in words, or ``""`` when the
    error names no flag.

    Parameters
    ----------
    exc : BaseException
        The error CasADi raised for the integrator call.

    Returns
    -------
    str
        E.g. ``"the right-hand side was not finite ... (CV_REPTD_RHSFUNC_ERR)"``.
    """
    found = _SUNDIALS_FLAG.search(str(exc))
    if found is None:
        return ""
    flag = found.group(1)
    meaning = next((text for parts, text in SUNDIALS_FLAGS if any(p in flag for p in parts)),
                   "a failure of the integrator")
    return f"{meaning} ({flag})"


def listed_names(names: list[str], most: int = 8) -> str:
    """The first ``most`` names, comma-separated, ``", ..."`` after them when there are more.

    Parameters
    ----------
    names : list of str
        The names.
    most : int
        How many are shown.

    Returns
    -------
    str
        E.g. ``"x, der(y)"``.
    """
    return ", ".join(names[:most]) + (", ..." if len(names) > most else "")


def no_value_cause(system: System) -> str:
    """Why a variable of ``system`` is not finite at a point, for messages: a nonlinear block
    without a solution there when the model has any, else the model's own NaN or inf.

    Parameters
    ----------
    system : System
        The system.

    Returns
    -------
    str
        The cause.
    """
    return ("the nonlinear blocks (algebraic loops) found no solution there"
            if system.rootfinder else "the model evaluates to NaN or inf there")
