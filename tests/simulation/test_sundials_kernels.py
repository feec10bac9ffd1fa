"""CVODES and IDAS on compiled kernels: same numbers as the VM, set-up paid once, fallback."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest
import scipy.sparse as sparse
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.sparse.linalg import splu

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
from bearingsim.errors import ParameterError
from bearingsim.simulation import simulate
from bearingsim.simulation.c_compiler import CompileError, compilations
from bearingsim.simulation.inputs import input_signal
from bearingsim.simulation.kernels import VM, clear_kernel_cache, kernel
from bearingsim.simulation.ordering import fill_reducing_order
from bearingsim.simulation.sundials_integrators import (
    DENSE_LIMIT,
    choose_linear_solver,
    clear_integrator_cache,
)
from tests.models import Pendulum, SpringMassChain


@pytest.fixture(scope="module")
def torque_level():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque"))


def _same_run(a, b):
    assert a.stats["nsteps"] == b.stats["nsteps"]
    assert a.stats["nfevals"] == b.stats["nfevals"]
    np.testing.assert_allclose(b.values, a.values, rtol=1e-10, atol=1e-300)


@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_compiled_and_vm_kernels_take_the_same_steps_to_the_same_numbers(kernel_cache, method):
    system = assemble(Pendulum())  # fast_newton block: MX ODE form, SX DAE form for IDAS
    vm = simulate(system, 2.0, method=method, rtol=1e-8, atol=1e-10, compiled=False)
    c = simulate(system, 2.0, method=method, rtol=1e-8, atol=1e-10, compiled=True)
    assert (vm.stats["backend"], c.stats["backend"]) == ("CasADi VM", "compiled C")
    assert c.stats["form"] == ("dae" if method == "idas" else "ode")
    _same_run(vm, c)
    # the kernel path agrees with CasADi differentiating the model itself (main's old path)
    np.testing.assert_allclose(c["x"] ** 2 + c["y"] ** 2, 1.0, atol=1e-7)


def test_compiled_kernel_with_inputs_matches_vm(kernel_cache, torque_level):
    inputs = {"shaft_speed": ([0.0, 0.5, 1.0], [0.0, 300.0, 500.0]), "Fa": 50.0}
    vm = simulate(torque_level, 1.5, inputs=inputs, method="cvodes", compiled=False)
    c = simulate(torque_level, 1.5, inputs=inputs, method="cvodes", compiled=True)
    _same_run(vm, c)
    assert c.inputs["shaft_speed"] == 500.0  # table held after its last row


def test_parameter_and_input_changes_reuse_library_and_integrator(kernel_cache, torque_level):
    first = simulate(torque_level, 1.0, inputs={"shaft_speed": 300.0}, method="cvodes",
                     compiled=True)
    assert not first.stats["integrator_cached"]
    n = compilations()
    name = torque_level.parameter_names[-1]
    value = torque_level.p0()[-1] * 1.1 + 1e-3
    again = simulate(torque_level, 2.0, t_start=0.5, inputs={"shaft_speed": 450.0},
                     parameters={name: value}, method="cvodes", compiled=True)
    assert compilations() == n  # no compiler run for new parameters, inputs or time span
    assert again.stats["integrator_cached"] and again.stats["setup_time"] == 0.0
    clear_kernel_cache()
    clear_integrator_cache()
    fresh = simulate(torque_level, 2.0, t_start=0.5, inputs={"shaft_speed": 450.0},
                     parameters={name: value}, method="cvodes", compiled=True)
    assert compilations() == n  # the library came from the disk cache
    assert not fresh.stats["integrator_cached"]
    _same_run(fresh, again)


def test_without_a_compiler_auto_falls_back_to_the_vm_and_true_raises(kernel_cache, monkeypatch,
                                                                      tmp_path):
    empty = tmp_path / "empty_bin"
    empty.mkdir()
    monkeypatch.setenv("PATH", str(empty))
    monkeypatch.setenv("CC", "no-such-compiler")
    system = assemble(SpringMassChain())
    res = simulate(system, 1.0, method="cvodes", compiled="auto")
    assert res.stats["backend"] == VM
    assert res.stats["backend_reason"] == "no C compiler on PATH"
    with pytest.raises(CompileError, match="no C compiler"):
        simulate(system, 1.0, method="cvodes", compiled=True)


def test_auto_keeps_tiny_models_on_the_vm_and_says_why(kernel_cache):
    system = assemble(SpringMassChain())
    k = kernel(system, "ode", "auto")
    assert k.backend == VM and k.reason.startswith("tiny model")
    assert k.library is None


def test_newton_blocks_cannot_be_compiled_in_the_ode_form(kernel_cache):
    system = assemble(Pendulum(), rootfinder="newton")
    assert kernel(system, "ode", "auto").backend == VM
    with pytest.raises(CompileError, match="IDAS on the DAE form compiles"):
        kernel(system, "ode", True)
    assert kernel(system, "dae", True).backend == "compiled C"


def test_input_signal_lifts_numbers_and_keeps_the_structure(torque_level):
    a = input_signal(torque_level, {"shaft_speed": ([0.0, 1.0], [0.0, 10.0]), "Fa": 5.0})
    b = input_signal(torque_level, {"shaft_speed": ([0.0, 2.0], [1.0, 30.0]), "Fa": 7.0})
    assert a.key == b.key and not np.array_equal(a.q, b.q)
    k = torque_level.input_names.index("shaft_speed")
    assert float(a.u(0.5, a.q)[k]) == pytest.approx(5.0)
    assert float(b.u(5.0, b.q)[k]) == pytest.approx(30.0)  # held after the table
    c = input_signal(torque_level, {"shaft_speed": lambda t: 3.0 * t})
    assert c.key != a.key


def test_linear_solver_by_size_and_checked_choices(torque_level):
    assert choose_linear_solver(76, 1400) == "lapacklu"
    assert choose_linear_solver(DENSE_LIMIT + 1, 5000) == "csparse"  # in a fill-reducing order
    assert choose_linear_solver(DENSE_LIMIT + 1, 5000, "dae") in ("mumps", "lapacklu")
    assert choose_linear_solver(500, 100_000) == "lapacklu"  # dense enough for LAPACK
    with pytest.raises(ParameterError, match="linear_solver"):
        simulate(torque_level, 0.1, method="cvodes", linear_solver="ma27")
    with pytest.raises(ParameterError, match="compiled"):
        simulate(torque_level, 0.1, method="cvodes", compiled="yes")


def test_auto_runs_on_the_vm_while_c_compiles_in_the_background(kernel_cache, monkeypatch):
    from bearingsim.simulation import kernels

    monkeypatch.setattr(kernels, "AUTO_MIN_INSTRUCTIONS", 0)  # compile even a tiny model
    system = assemble(SpringMassChain())
    first = simulate(system, 1.0, method="cvodes", compiled="auto")
    kernels.wait_for_compilations()
    later = simulate(system, 1.0, method="cvodes", compiled="auto")
    assert later.stats["backend"] == "compiled C"
    if first.stats["backend"] == VM:  # the compiler had not finished at the first run
        assert "background" in first.stats["backend_reason"]
    _same_run(first, later)


def test_a_failing_compiler_leaves_auto_on_the_vm_and_raises_for_true(kernel_cache, monkeypatch):
    from bearingsim.simulation import kernels

    monkeypatch.setattr(kernels, "AUTO_MIN_INSTRUCTIONS", 0)
    monkeypatch.setenv("CC", "false")  # found on PATH, exits 1
    system = assemble(SpringMassChain())
    kernels.wait_for_compilations()
    for _ in range(50):  # until the failed build is noticed
        res = simulate(system, 0.5, method="cvodes", compiled="auto")
        if res.stats["backend_reason"].startswith("compiling failed"):
            break
        kernels.wait_for_compilations()
    assert res.stats["backend"] == VM
    assert res.stats["backend_reason"].startswith("compiling failed")
    with pytest.raises(CompileError, match="failed"):
        simulate(system, 0.5, method="cvodes", compiled=True)
    assert not list(kernel_cache.glob(".build_*"))  # no half-built leftovers


def _pattern(a: sparse.csc_matrix) -> ca.Sparsity:
    coo = a.tocoo()
    return ca.Sparsity.triplet(a.shape[0], a.shape[1], coo.row.tolist(), coo.col.tolist())


def _lu_fill(a: sparse.csc_matrix) -> int:
    """Non-zeros of L + U beyond those of ``a``, factorized in the given order."""
    lu = splu(a, permc_spec="NATURAL", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    return lu.L.nnz + lu.U.nnz - a.shape[0] - a.nnz


def _arrowhead(n_members: int, per_member: int, shared: int) -> sparse.csc_matrix:
    """Shared unknowns first (like ring states before the balls'), each member's block coupled
    to every shared unknown: the pattern of a bearing's Jacobian."""
    n = shared + n_members * per_member
    a = sparse.lil_matrix((n, n))
    a[:shared, :shared] = 1.0
    for k in range(n_members):
        lo = shared + k * per_member
        block = slice(lo, lo + per_member)
        a[block, block] = 1.0
        a[block, :shared] = 1.0
        a[:shared, block] = 1.0
    return (a + n * sparse.identity(n)).tocsc()


def test_fill_reducing_order_factorizes_a_bearing_pattern_without_fill_in():
    a = _arrowhead(n_members=12, per_member=9, shared=10)
    order = fill_reducing_order(_pattern(a))
    assert sorted(order) == list(range(a.shape[0]))
    assert _lu_fill(a) > 50 * a.shape[0]  # as given: the shared rows fill everything in
    assert _lu_fill(a[order][:, order].tocsc()) == 0


@settings(max_examples=30, deadline=None)
@given(st.integers(2, 15), st.integers(1, 9), st.integers(1, 12), st.integers(0, 2**32 - 1))
def test_fill_reducing_order_finds_the_bearing_pattern_in_any_given_order(members, size,
                                                                          shared, seed):
    a = _arrowhead(members, size, shared)
    shuffle = np.random.default_rng(seed).permutation(a.shape[0])
    given_order = a[shuffle][:, shuffle].tocsc()
    order = fill_reducing_order(_pattern(given_order))
    assert sorted(order) == list(range(a.shape[0]))
    assert _lu_fill(given_order[order][:, order].tocsc()) == 0


def test_the_order_is_kept_beside_the_library_and_read_back(tmp_path, monkeypatch):
    """A later process reads the order from the library's companion file instead of
    importing scipy.sparse for SuperLU (0.35-0.5 s a process)."""
    from bearingsim.simulation import ordering

    a = _arrowhead(n_members=12, per_member=9, shared=10)
    library = tmp_path / "bsm_ode_0123456789abcdef.so"
    order = ordering.kept_order(_pattern(a), library)
    np.testing.assert_array_equal(order, fill_reducing_order(_pattern(a)))
    kept = tmp_path / ("bsm_ode_0123456789abcdef.so" + ordering.ORDER_SUFFIX)
    assert kept.stat().st_size == 16 + 4 * a.shape[0]

    def no_superlu(pattern):
        raise AssertionError("computed again")

    monkeypatch.setattr(ordering, "fill_reducing_order", no_superlu)
    np.testing.assert_array_equal(ordering.kept_order(_pattern(a), library), order)


@pytest.mark.parametrize("damage", ["another pattern", "truncated", "not a permutation",
                                    "empty"])
def test_a_kept_order_that_does_not_fit_is_replaced_never_used(tmp_path, damage):
    from bearingsim.simulation import ordering

    a = _arrowhead(n_members=5, per_member=4, shared=3)
    library = tmp_path / "bsm_ode_0123456789abcdef.so"
    kept = tmp_path / ("bsm_ode_0123456789abcdef.so" + ordering.ORDER_SUFFIX)
    right = ordering.kept_order(_pattern(a), library)
    data = kept.read_bytes()
    if damage == "another pattern":
        other = _arrowhead(n_members=5, per_member=4, shared=3)
        other[0, a.shape[0] - 1] = 1.0  # one more nonzero, the same size
        ordering.kept_order(_pattern(other.tocsc()), library)
    elif damage == "truncated":
        kept.write_bytes(data[:-4])
    elif damage == "not a permutation":
        kept.write_bytes(data[:16] + np.zeros(a.shape[0], dtype=np.int32).tobytes())
    else:
        kept.write_bytes(b"")
    np.testing.assert_array_equal(ordering.kept_order(_pattern(a), library), right)
    assert kept.read_bytes() == data  # rewritten for this pattern


def test_an_order_that_cannot_be_kept_is_still_given(tmp_path):
    from bearingsim.simulation import ordering

    a = _arrowhead(n_members=5, per_member=4, shared=3)
    blocked = tmp_path / "a file"
    blocked.write_text("not a folder")
    np.testing.assert_array_equal(ordering.kept_order(_pattern(a), blocked / "lib.so"),
                                  fill_reducing_order(_pattern(a)))


def test_sparse_lu_integrates_in_a_fill_reducing_order_and_returns_the_systems_order(
        kernel_cache):
    system = assemble(deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0,
                                               loads={"Fx": 500.0}))
    runs = {solver: simulate(system, 2e-3, method="cvodes", linear_solver=solver,
                             compiled=False, rtol=1e-9, atol=1e-12, n_points=5)
            for solver in ("lapacklu", "csparse")}
    assert runs["lapacklu"].stats["state_order"] == "system"
    assert runs["csparse"].stats["state_order"] == "minimum degree"
    dense, ordered = (np.asarray(runs[s].values) for s in ("lapacklu", "csparse"))
    np.testing.assert_array_equal(ordered[:, 0], dense[:, 0])  # the start, in system order
    scale = np.maximum(np.abs(dense).max(axis=1, keepdims=True), 1e-9)
    assert np.max(np.abs(ordered - dense) / scale) < 1e-5
