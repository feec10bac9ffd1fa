"""The model functions of an FMU as CasADi Functions, and their C code.

Every function takes ``(t, x, u, p)`` and returns one (possibly sparse) matrix:

========== ===================================================
``ode``     state derivatives ``der(x)``
``jac_x``   d der(x) / dx (exact, sparse)
``jac_u``   d der(x) / du
``jac_t``   partial d der(x) / dt (for non-autonomous models)
``output``  the FMU outputs ``y``
``out_jac_x``, ``out_jac_u``  dy/dx, dy/du
========== ===================================================

The order of :data:`FUNCTION_NAMES` is the order of the function table of the C template.
Models with ball sets get ``ode`` and its Jacobians with one function per ball mapped over
each row (:mod:`bearingsim.assembler.mapped`): C that grows with one ball, not with Z.
"""

from __future__ import annotations

from pathlib import Path

import casadi as ca

__all__ = ["FUNCTION_NAMES", "PREFIX", "fmu_functions", "generate_c"]

FUNCTION_NAMES = ("ode", "jac_x", "jac_u", "jac_t", "output", "out_jac_x", "out_jac_u")
"""Model functions in the order of the C enum ``FN_ODE ... FN_OUT_JAC_U``."""

PREFIX = "bsm_"
"""Prefix of the generated C function names."""


def fmu_functions(system, output_names: list[str]) -> dict[str, ca.Function]:
    """Build the FMU's model functions from a system's compiled functions.

    Parameters
    ----------
    system : System
        The assembled system.
    output_names : list of str
        Names from ``system.observed_names``; the system's own ``output`` function is reused
        when they equal ``system.output_names``.

    Returns
    -------
    dict of str to casadi.Function
        Keyed by :data:`FUNCTION_NAMES`, each named ``PREFIX + key``.
    """
    fns = system.functions
    # one function per ball (None: no ball sets, or Newton blocks inside the right-hand side)
    mapped = system.mapped.find("ode") if system.mapped is not None else None
    sym = ca.SX if fns["ode"].is_a("SXFunction") and mapped is None else ca.MX
    t = sym.sym("t")
    x = sym.sym("x", system.n_states)
    u = sym.sym("u", len(system.inputs))
    p = sym.sym("p", len(system.params))
    args = (t, x, u, p)
    if mapped is not None:  # one function per ball, its Jacobian by the chain rule
        xdot, jac_t, jac_x, jac_u = mapped.ode_with_jacobians(*args)
    else:
        xdot = fns["ode"](*args)
        jac_t, jac_x, jac_u = ca.jacobian(xdot, t), fns["jac_x"](*args), fns["jac_u"](*args)
    if list(output_names) == system.output_names:
        y = fns["output"](*args)
        y_x, y_u = fns["out_jac_x"](*args), fns["out_jac_u"](*args)
    else:
        obs = fns["observe"](*args)
        pos = {n: k for k, n in enumerate(system.observed_names)}
        y = ca.vertcat(*[obs[pos[n]] for n in output_names]) if output_names else sym(0, 1)
        y_x, y_u = ca.jacobian(y, x), ca.jacobian(y, u)
    exprs = {
        "ode": xdot,
        "jac_x": jac_x,
        "jac_u": jac_u,
        "jac_t": jac_t,
        "output": y,
        "out_jac_x": y_x,
        "out_jac_u": y_u,
    }
    return {
        key: ca.Function(PREFIX + key, list(args), [exprs[key]], ["t", "x", "u", "p"], [key])
        for key in FUNCTION_NAMES
    }


def generate_c(functions: dict[str, ca.Function], directory: Path,
               stem: str = "bsm_casadi") -> dict[str, int]:
    """Write C code for the functions to ``directory/stem.c`` and ``stem.h``.

    Parameters
    ----------
    functions : dict of str to casadi.Function
        From :func:`fmu_functions`.
    directory : pathlib.Path
        Target folder (exists).
    stem : str
        File name stem.

    Returns
    -------
    dict of str to int
        Largest work sizes over all functions: ``"arg"``, ``"res"``, ``"iw"``, ``"w"``.
    """
    gen = ca.CodeGenerator(f"{stem}.c", {"with_header": True})
    for key in FUNCTION_NAMES:
        gen.add(functions[key])
    gen.generate(str(directory) + "/")
    return {
        "arg": max(f.sz_arg() for f in functions.values()),
        "res": max(f.sz_res() for f in functions.values()),
        "iw": max(f.sz_iw() for f in functions.values()),
        "w": max(f.sz_w() for f in functions.values()),
    }
