"""The model functions of an FMU as CasADi Functions, and their C code.

Every function takes ``(t, x, u, p)`` and returns one (possibly sparse) matrix:

========== ===================================================
``ode``     state derivatives ``der(x)``
``jac_x``   d der(x) / dx (exact, sparse)
``jac_u``   d der(x) / du
``jac_t``   partial d der(x) / dt (for non-autonomous models)
``output``  the FMU outputs ``y``
``out_jac_x``, ``out_jac_u``  dy/dx, dy/du
``out_jac_t``  partial dy/dt (output derivatives of co-simulation)
========== ===================================================

The order of :data:`FUNCTION_NAMES` is the order of the function table of the C template.
Models with ball sets get ``ode`` and its Jacobians with one function per ball mapped over
each row (:mod:`bearingsim.assembler.mapped`): C that grows with one ball, not with Z.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import casadi as ca

from bearingsim.simulation.c_units import generate_units

__all__ = ["FUNCTION_NAMES", "OPTIMISATION", "PREFIX", "CSource", "fmu_functions",
           "generate_c"]

FUNCTION_NAMES = ("ode", "jac_x", "jac_u", "jac_t", "output", "out_jac_x", "out_jac_u",
                  "out_jac_t")
"""Model functions in the order of the C enum ``FN_ODE ... FN_OUT_JAC_T``."""

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
        "out_jac_t": ca.jacobian(y, t),
    }
    return {
        key: ca.Function(PREFIX + key, list(args), [exprs[key]], ["t", "x", "u", "p"], [key])
        for key in FUNCTION_NAMES
    }


OPTIMISATION = {"ode": "-O2", "jac_t": "-O2", "jac_x": "-O1", "jac_u": "-O1",
                "output": "-O0", "out_jac_x": "-O0", "out_jac_u": "-O0", "out_jac_t": "-O0"}
"""gcc optimisation of each function's file, by how often it runs: the right-hand side and its
time derivative at every stage of every internal step; the state and input Jacobians when the
W-method renews its Jacobian (every 100 steps or fewer); the outputs and their Jacobians once
per communication point or output sample. gcc's time grows faster than linearly with a file's
size and optimisation level (duplex pair, 248 outputs: the output Jacobian 2.0 s at -O0 and
22.9 s at -O2, the state Jacobian 6.4 s at -O1 and 16.2 s at -O2)."""


@dataclass(frozen=True)
class CSource:
    """One generated C file of the FMU and the optimisation flag it is compiled with."""

    name: str
    optimisation: str


def generate_c(functions: dict[str, ca.Function], directory: Path,
               header: str = "bsm_casadi.h") -> tuple[dict[str, int], list[CSource]]:
    """Write C code for the functions to ``directory``: one file per function, plus one per large
    SX function a ball-level model's mapped kernel calls
    (:func:`~bearingsim.simulation.c_units.generate_units`), and a header declaring them.

    Separate files compile in parallel, each with its own optimisation level
    (:data:`OPTIMISATION`).

    Parameters
    ----------
    functions : dict of str to casadi.Function
        From :func:`fmu_functions`.
    directory : pathlib.Path
        Target folder (exists).
    header : str
        Name of the header declaring the table functions.

    Returns
    -------
    work : dict of str to int
        Largest work sizes over all functions: ``"arg"``, ``"res"``, ``"iw"``, ``"w"``.
    sources : list of CSource
        The written ``.c`` files.
    """
    sources: dict[str, CSource] = {}
    shared: dict[str, str] = {}  # exported name of a split-off function -> its file
    rank = {"-O0": 0, "-O1": 1, "-O2": 2}
    for key in FUNCTION_NAMES:
        main, *units = generate_units([functions[key]], f"{PREFIX}c_{key}")
        texts = {f"{PREFIX}c_{key}.c": main}
        for k, unit in enumerate(units, start=1):
            # a per-ball function several model functions call is compiled once, at the
            # highest optimisation of its callers
            exported = _EXPORTED.search(unit).group(1)
            name = shared.setdefault(exported, f"{PREFIX}c_{key}_u{k}.c")
            texts.setdefault(name, unit)
        for name, text in texts.items():
            if name in sources:
                if rank[OPTIMISATION[key]] > rank[sources[name].optimisation]:
                    sources[name] = CSource(name, OPTIMISATION[key])
                continue
            (directory / name).write_text(text)
            sources[name] = CSource(name, OPTIMISATION[key])
    (directory / header).write_text(_header(header))
    work = {
        "arg": max(f.sz_arg() for f in functions.values()),
        "res": max(f.sz_res() for f in functions.values()),
        "iw": max(f.sz_iw() for f in functions.values()),
        "w": max(f.sz_w() for f in functions.values()),
    }
    return work, list(sources.values())


_EXPORTED = re.compile(r"^CASADI_SYMBOL_EXPORT int (\w+)\(const casadi_real\*\* arg", re.M)
"""The function a split-off unit exports (its first exported evaluation function)."""


def _header(name: str) -> str:
    """Declarations of the generated functions the function table of ``model_data.c`` holds."""
    guard = re.sub(r"\W", "_", name).upper()
    lines = ["/* Generated by bearingsim.fmu: the CasADi-generated model functions. */",
             f"#ifndef {guard}", f"#define {guard}", "",
             "#ifndef casadi_real", "#define casadi_real double", "#endif",
             "#ifndef casadi_int", "#define casadi_int long long int", "#endif", ""]
    for key in FUNCTION_NAMES:
        fn = PREFIX + key
        lines += [
            f"int {fn}(const casadi_real** arg, casadi_real** res, casadi_int* iw, "
            "casadi_real* w, int mem);",
            f"const casadi_int* {fn}_sparsity_out(casadi_int i);",
            f"int {fn}_checkout(void);",
            f"void {fn}_release(int mem);",
        ]
    return "\n".join([*lines, "", "#endif", ""])
