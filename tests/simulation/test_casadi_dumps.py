"""CasADi prints the inputs of every function in the chain of a failed evaluation on
``sys.stderr`` before it raises (``Function::operator()``, whatever the options: ``print_in``
only adds a print of every call). :func:`casadi_dumps_dropped` drops exactly those lines and
lets everything else through at once."""

import contextlib
import io
import sys

import casadi as ca
import pytest

from bearingsim.simulation.native_streams import casadi_dumps_dropped


def _failing_newton() -> ca.Function:
    """A fast_newton rootfinder that cycles (x^3 - 2x + 2 from 0) inside an MX function."""
    x, p = ca.SX.sym("x"), ca.SX.sym("p")
    g = ca.Function("g", [x, p], [x**3 - 2 * x + p])
    newton = ca.rootfinder("newton0", "fast_newton", g, {"abstol": 1e-12, "max_iter": 5})
    big_x, big_p = ca.MX.sym("X"), ca.MX.sym("P")
    return ca.Function("f", [big_x, big_p], [newton(big_x, big_p)])


def test_the_dump_is_dropped_and_other_text_passes():
    held = io.StringIO()
    with contextlib.redirect_stderr(held):
        with casadi_dumps_dropped():
            sys.stderr.write("progress 10 %\r")
            with pytest.raises(RuntimeError, match="rootfinder process failed"):
                _failing_newton()(0.0, 2.0)
            sys.stderr.write("Input from a person\n")
            sys.stderr.write("warning: a line\n")
        assert sys.stderr is held
    assert held.getvalue() == "progress 10 %\rInput from a person\nwarning: a line\n"


def test_without_it_casadi_prints_the_inputs():
    held = io.StringIO()
    with contextlib.redirect_stderr(held), pytest.raises(RuntimeError):
        _failing_newton()(0.0, 2.0)
    assert "Function newton0 (0x" in held.getvalue() and "Input 1 (i1): 2" in held.getvalue()
