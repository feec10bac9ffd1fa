"""A failed run says why in its error, and only there: CVODES and IDAS no longer print a CasADi
warning per failed evaluation (a square root of a state crossing zero printed 1 369 lines on
standard error before the error), their failure flag is put in words, and the compiled BDF
names the variables that are not finite where it stopped."""

from __future__ import annotations

import casadi as ca
import pytest

from bearingsim import Component, Variable, der
from bearingsim.assembler import assemble
from bearingsim.errors import SimulationError
from bearingsim.simulation import simulate
from bearingsim.simulation.c_compiler import c_compiler
from bearingsim.simulation.diagnostics import sundials_failure


class Draining(Component):
    """Torricelli's tank, y' = -10 sqrt(y), y(0) = 1: empty at t = 0.2 s, after which the
    integrator's trial states below zero make the square root NaN."""

    def __init__(self):
        super().__init__("tank")
        self.y = Variable(1.0, "1", "level")

    def equations(self):
        return [der(self.y) == -10.0 * ca.sqrt(self.y)]


class NoRealRoot(Component):
    """x^2 + 1 = 0 (no real solution) feeding y' = x."""

    def __init__(self):
        super().__init__("loop")
        self.x = Variable(1.0, "1", "unknown of the loop", fixed=False)
        self.y = Variable(0.0, "1", "integral")

    def equations(self):
        return [self.x**2 + 1.0 == 0.0, der(self.y) == self.x]


@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_a_right_hand_side_that_turns_nan_fails_quietly_with_the_reason(method, capfd):
    system = assemble(Draining())
    with pytest.raises(SimulationError) as err:
        simulate(system, 1.0, method=method, compiled=False)
    text = str(err.value)
    assert f"{method.upper()} failed between t = 0.2" in text
    assert "right-hand side was not finite" in text
    assert ("RHSFUNC" if method == "cvodes" else "RES_ERR") in text
    printed = capfd.readouterr()
    assert "NaN detected" not in printed.err and "recoverable" not in printed.err
    assert printed.err.count("\n") <= 2, printed.err[:500]


def test_the_flags_in_words():
    assert sundials_failure(RuntimeError("... CVode returned \"CV_CONV_FAILURE\". Consult")) \
        .startswith("the Newton iteration of the implicit steps failed repeatedly")
    assert sundials_failure(RuntimeError('IDASolve returned "IDA_TOO_MUCH_ACC"')) == (
        "the tolerances are tighter than the arithmetic allows (raise rtol and atol) "
        "(IDA_TOO_MUCH_ACC)")
    assert sundials_failure(RuntimeError('CVode returned "CV_SOMETHING_NEW"')) == \
        "a failure of the integrator (CV_SOMETHING_NEW)"
    assert sundials_failure(RuntimeError("no flag here")) == ""


@pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")
def test_the_compiled_bdf_names_what_is_not_finite_and_the_loop_without_a_root(kernel_cache):
    system = assemble(NoRealRoot())
    with pytest.raises(SimulationError) as err:
        simulate(system, 1.0, method="compiled_bdf")
    assert "the model returned non-finite values: x, der(y) not finite at the state " \
           "reached; the nonlinear blocks (algebraic loops) found no solution there" \
        in str(err.value)


def test_linearize_refuses_an_operating_point_without_a_solution():
    """Linearizing where the loop x^2 + 1 = 0 has no solution returned a linear model with no
    modes (A finite: der(y) = x - y does not see x's NaN in its derivative by y), a silent
    non-answer; it now names the variables that are not finite there."""
    from bearingsim.simulation import linearize

    class Loop(NoRealRoot):
        def equations(self):
            return [self.x**2 + 1.0 == 0.0, der(self.y) == self.x - self.y]

    with pytest.raises(SimulationError, match=r"linearize: loop: its variables are not finite "
                       r"at the operating point \(t = 0 s\): x, der\(y\); the nonlinear "
                       r"blocks \(algebraic loops\) found no solution there"):
        linearize(assemble(Loop()))


@pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")
def test_steady_state_says_a_compiled_block_found_no_root(kernel_cache):
    """A block of compiled C without a root gives NaN rather than an error: the message named
    only "y nan 1/s", not the block (the VM's error was counted, the compiled NaN was not)."""
    from bearingsim.simulation import steady_state

    class Loop(NoRealRoot):
        def equations(self):
            return [self.x**2 + 1.0 == 0.0, der(self.y) == self.x - self.y]

    with pytest.raises(SimulationError, match=r"steady state not found: .* of the points tried "
                       r"a nonlinear block of the model found no root"):
        steady_state(assemble(Loop()), compiled=True)
