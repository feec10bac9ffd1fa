"""Generated C in several translation units compiled in parallel
(bearingsim.simulation.c_units, bearingsim.simulation.c_compiler.Build): the linked library
computes what CasADi computes, bit for bit; the moved function is not exported; a source
without the expected layout stays one unit; a failing unit names the compiler's message."""

from __future__ import annotations

import ctypes

import casadi as ca
import numpy as np
import pytest

from bearingsim.simulation.c_compiler import CompileError, c_compiler
from bearingsim.simulation.c_units import generate_units
from bearingsim.simulation.compile import compile_source, library_path

pytestmark = pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")


def _functions():
    """An MX function that maps a larger SX function (and its Jacobian) over 5 members."""
    x = ca.SX.sym("x", 3)
    q = ca.SX.sym("q", 2)
    y = x
    for k in range(30):
        y = ca.vertcat(ca.sin(y[0] * q[0] + y[1]), ca.exp(-y[1] ** 2) * y[2], y[0] * q[1] - y[2])
        y = y + 0.1 * k
    member = ca.Function("member", [x, q], [y])
    member_jac = ca.Function("member_jac", [x, q], [ca.jacobian(y, x)], {"cse": True})
    X, Q = ca.MX.sym("X", 3, 5), ca.MX.sym("Q", 2, 5)
    top = ca.Function("top", [X, Q], [member.map(5)(X, Q), member_jac.map(5)(X, Q)])
    return [top], member, member_jac


def test_units_compile_to_the_same_numbers(tmp_path):
    functions, member, member_jac = _functions()
    units = generate_units(functions, "unit_test", min_instructions=member.n_instructions() + 1)
    assert len(units) == 2  # the Jacobian (larger than the member) has a unit of its own
    assert "member_jac" in units[1] and "visibility(\"hidden\")" in units[1]
    lib = compile_source(units, tmp_path / "split.so")
    compiled = ca.external("top", str(lib))
    rng = np.random.default_rng(3)
    args = [rng.standard_normal((3, 5)), rng.uniform(0.5, 1.5, (2, 5))]
    for got, want in zip(compiled(*args), functions[0](*args), strict=True):
        np.testing.assert_array_equal(np.asarray(got), np.asarray(want))
    handle = ctypes.CDLL(str(lib))
    assert hasattr(handle, "top")
    assert not hasattr(handle, "member_jac")  # visible inside the library only


def test_nothing_large_enough_gives_one_unit():
    functions, member_jac = _functions()[0], _functions()[2]
    assert len(generate_units(functions, "unit_test",
                              min_instructions=member_jac.n_instructions() + 1)) == 1


def test_a_called_function_whose_name_is_not_unique_stays_in_the_main_unit():
    x = ca.SX.sym("x")
    a = ca.Function("same", [x], [ca.sin(x) * ca.cos(x) + x ** 3])
    b = ca.Function("same", [x], [ca.exp(x) - x])
    X = ca.MX.sym("X")
    top = ca.Function("top", [X], [a(X) + b(X)])
    assert len(generate_units([top], "unit_test", min_instructions=1)) == 1


def test_a_failing_unit_raises_with_the_compiler_message(tmp_path):
    functions = _functions()[0]
    units = generate_units(functions, "unit_test", min_instructions=10)
    units[-1] += "\nthis is not C;\n"
    with pytest.raises(CompileError, match="unit") as err:
        compile_source(units, tmp_path / "broken.so")
    assert "error" in str(err.value)
    assert not (tmp_path / "broken.so").exists()


def test_split_units_get_their_own_flags(tmp_path):
    functions, member, _ = _functions()
    units = generate_units(functions, "unit_test", min_instructions=member.n_instructions() + 1)
    units[0] += "\n#ifdef SPLIT_ONLY\n#error the main unit got the split units' flags\n#endif\n"
    units[1] += "\n#ifndef SPLIT_ONLY\n#error a split unit lacks its flags\n#endif\n"
    with pytest.raises(CompileError, match="lacks its flags"):
        compile_source(units, tmp_path / "same_flags.so", flags=("-O1", "-DMAIN"))
    lib = compile_source(units, tmp_path / "split_flags.so", flags=("-O1",),
                         split_flags=("-Og", "-DSPLIT_ONLY"))
    assert lib.exists()


def test_split_flags_are_part_of_the_library_key(tmp_path):
    same = library_path("source", flags=("-O1",), cache_dir=tmp_path)
    assert library_path("source", flags=("-O1",), split_flags=("-O1",), cache_dir=tmp_path) == same
    assert library_path("source", flags=("-O1",), split_flags=("-Og",), cache_dir=tmp_path) != same


def _newton_block():
    """f(p) = the root z of z^2 = p, by CasADi's fast_newton from z = 0.5 (20 iterations): no
    real root for p < 0."""
    z, p = ca.SX.sym("z"), ca.SX.sym("p")
    root = ca.rootfinder("root", "fast_newton", ca.Function("g", [z, p], [z ** 2 - p]),
                         {"max_iter": 20})
    x = ca.SX.sym("x")
    return ca.Function("f", [x], [root(0.5, x)])


def test_a_newton_block_without_a_root_fails_in_c_as_on_the_vm(tmp_path):
    """CasADi's generated C returned the last Newton iterate as if it were the root (f(-1)
    gave 0.4685, a number a run went on with) where its virtual machine raises; the generated
    source now fails the evaluation after the last iteration, and a converged block is
    unchanged."""
    f = _newton_block()
    [source] = generate_units([f], "newton_test")
    assert source.count("if (iter>=20) return 1;") == 1
    compiled = ca.external("f", str(compile_source([source], tmp_path / "newton.so")))
    assert float(compiled(4.0)) == float(f(4.0)) == pytest.approx(2.0, rel=1e-12)
    with pytest.raises(RuntimeError, match="failed"):
        f(-1.0)  # the VM
    with pytest.raises(RuntimeError, match="Evaluation failed"):
        compiled(-1.0)
