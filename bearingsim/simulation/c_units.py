"""A library's generated C in several translation units, so that the C compiler builds them in
parallel.

gcc's time on CasADi's straight-line code grows with the size of each function (register
allocation is two thirds of it), and one translation unit is compiled on one core. The kernels
of the ball-level models hold very large SX functions, the per-ball Jacobian of the mapped
kernel in two parts (columns of the ball's own states and of the shared states: about 11 000
and 5 000 instructions for a 6304 ball against 1 400 for the ball itself), called by the small
MX functions around them. :func:`generate_units` generates the functions as usual
(``casadi.CodeGenerator``) and moves each large SX function they call into a unit of its own:

* the unit is CasADi's own C for that function under its name, visible inside the library
  only (``visibility("hidden")``); its helpers (e.g. ``casadi_sq``) get a prefix of their own,
  so the units link without clashes;
* in the main unit the function's static body is replaced by a call of that export, with the
  same arguments (same work vectors: it is the same function).

The parts compute exactly what the single file computes (the same expressions in the same
order; the tests compare the kernels bit for bit with CasADi's VM). When the generated source
does not have the expected layout (another CasADi version) the library is generated as one
unit.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

import casadi as ca

__all__ = ["SPLIT_MIN_INSTRUCTIONS", "generate_source", "generate_units"]

SPLIT_MIN_INSTRUCTIONS = 4000
"""SX functions of at least this many instructions get a translation unit of their own (gcc
-O1 needs about 0.2 ms per instruction; below this a unit saves less than it costs to
start)."""

_HIDDEN = '#define CASADI_SYMBOL_EXPORT __attribute__((visibility("hidden")))\n'
"""Prepended to a unit: its function is called by the main unit, not exported by the library."""

_SIGNATURE = ("(const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w, "
              "int mem)")


_NEWTON_LOOP = re.compile(
    r"(  for \(iter=0; iter<(\d+); \+\+iter\) \{\n(?:(?!  \}\n).*\n)*?"
    r"    if \(casadi_newton\(&m\)\) break;\n  \}\n)")
"""The iteration loop of a ``fast_newton`` rootfinder in CasADi's C (3.8): ``max_iter`` Newton
steps, left early when the residual or the step is below its tolerance."""


def _newton_failures_reported(source: str) -> str:
    """``source`` with every ``fast_newton`` loop that ends without converging reporting a
    failure (``return 1``, as a failed evaluation): CasADi's generated C returns the last
    iterate as if it were the root, where its virtual machine raises "failed to converge"
    (a Newton block without a root gave a number and a run went on with it)."""
    return _NEWTON_LOOP.sub(lambda m: m.group(1) + f"  if (iter>={m.group(2)}) return 1;"
                            " /* bearingsim: no root found, as CasADi's VM reports */\n",
                            source)


def generate_source(functions: Sequence[ca.Function], name: str = "bsm") -> str:
    """C source of ``functions`` in one file (``casadi.CodeGenerator``, no header); a Newton
    block (``fast_newton``) that does not converge within its iterations fails the
    evaluation, as on CasADi's virtual machine.

    Parameters
    ----------
    functions : sequence of casadi.Function
        The functions to generate.
    name : str, default "bsm"
        Base name of the generated file (``<name>.c``).

    Returns
    -------
    str
        The C source.
    """
    gen = ca.CodeGenerator(f"{name}.c", {"with_header": False})
    for fn in functions:
        gen.add(fn)
    return _newton_failures_reported(gen.dump())


def _large_dependencies(functions: Sequence[ca.Function], min_instructions: int
                        ) -> list[ca.Function]:
    """The SX functions called by ``functions`` that are large enough for a unit of their
    own, each once; none whose name is not unique (the units are linked by name)."""
    found: dict[str, dict[int, ca.Function]] = {}
    for fn in functions:
        for dep in fn.find_functions(-1):  # hash: the underlying function, as codegen sees it
            found.setdefault(dep.name(), {})[hash(dep)] = dep
    top = {fn.name() for fn in functions}
    return [dep for name, same_name in found.items() if len(same_name) == 1
            for dep in same_name.values()
            if name not in top and dep.is_a("SXFunction")
            and dep.n_instructions() >= min_instructions]


def _forwarded(source: str, fn: ca.Function, export: str) -> str | None:
    """``source`` with the static definition of ``fn`` replaced by a call of ``export``, or
    None if the definition is not found exactly once."""
    pattern = re.compile(
        r"^/\* " + re.escape(str(fn).split(" ")[0]) + r" \*/\n"
        r"static int (casadi_f\d+)" + re.escape(_SIGNATURE) + r" \{\n.*?^\}\n",
        re.M | re.S)
    hits = pattern.findall(source)
    if len(hits) != 1:
        return None
    static = hits[0]
    stub = (f"int {export}{_SIGNATURE};\n"
            f"static int {static}{_SIGNATURE} {{\n"
            f"  return {export}(arg, res, iw, w, mem);\n}}\n")
    return pattern.sub(lambda _: stub, source, count=1)


def generate_units(functions: Sequence[ca.Function], name: str = "bsm",
                   min_instructions: int = SPLIT_MIN_INSTRUCTIONS) -> list[str]:
    """C sources of ``functions``: the main unit (every function, exported under its name)
    and one unit per large SX function they call.

    Parameters
    ----------
    functions : sequence of casadi.Function
        The functions the library exports.
    name : str
        Prefix of the internal symbols (``casadi.CodeGenerator`` file name); unit ``k`` uses
        ``<name>_u<k>``.
    min_instructions : int
        Size from which a called SX function gets a unit of its own.

    Returns
    -------
    list of str
        The units; the first is the main unit. One unit when nothing is large enough or the
        generated source does not have the expected layout.
    """
    main = generate_source(functions, name)
    units = []
    for k, dep in enumerate(_large_dependencies(functions, min_instructions), start=1):
        forwarded = _forwarded(main, dep, dep.name())
        if forwarded is None:
            continue
        main = forwarded
        units.append(_HIDDEN + generate_source([dep], f"{name}_u{k}"))
    return [main, *units]

