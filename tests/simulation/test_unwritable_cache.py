"""A cache folder that cannot be used (a file in its place, as a misspelt BEARINGSIM_CACHE or a
read-only shipped cache can leave it) costs the run its caching, never the run: the system is
assembled instead of loaded, the kernel runs on CasADi's VM with the reason in its stats, and
only a run that asks for compiled C (``compiled=True``) is refused, by a CompileError that
names the folder and BEARINGSIM_CACHE."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble, assemble_cached
from bearingsim.assembler import cache as system_cache
from bearingsim.errors import CacheWarning
from bearingsim.simulation import kernels, simulate
from bearingsim.simulation.c_compiler import CompileError, c_compiler
from tests.models import TwoInertiaDrive

pytestmark = pytest.mark.skipif(c_compiler() is None, reason="no C compiler")


@pytest.fixture
def blocked_cache(tmp_path, monkeypatch):
    """BEARINGSIM_CACHE naming a file: no folder can be made there."""
    path = tmp_path / "cache"
    path.write_text("not a folder")
    monkeypatch.setenv("BEARINGSIM_CACHE", str(path))
    kernels.clear_kernel_cache()
    yield path
    kernels.clear_kernel_cache()


def test_the_system_is_assembled_instead_of_loaded(blocked_cache):
    """And says so, once per process and folder (before: silently, each run assembling)."""
    with pytest.warns(CacheWarning, match=rf"the cache {blocked_cache} cannot be written \(.*\): "
                                          r"assembled systems are not kept") as seen:
        system = assemble_cached(TwoInertiaDrive())
        assemble_cached(TwoInertiaDrive())
    assert len([w for w in seen if issubclass(w.category, CacheWarning)]) == 1
    assert not system_cache.LAST["hit"]
    fresh = assemble(TwoInertiaDrive())
    args = (0.1, fresh.x0() + 0.3, fresh.u_default() + 0.5, fresh.p0())
    np.testing.assert_array_equal(np.array(system.functions["ode"](*args)),
                                  np.array(fresh.functions["ode"](*args)))


def test_the_kernel_runs_on_the_vm_with_the_reason(blocked_cache, monkeypatch):
    monkeypatch.setattr(kernels, "AUTO_MIN_INSTRUCTIONS", 0)  # worth compiling, were it possible
    system = assemble_cached(TwoInertiaDrive())
    on_vm = simulate(system, 0.5, method="cvodes", compiled="auto")
    assert on_vm.stats["backend"] != kernels.COMPILED
    assert "cannot be written" in on_vm.stats["backend_reason"]
    assert "BEARINGSIM_CACHE" in on_vm.stats["backend_reason"]
    reference = simulate(assemble(TwoInertiaDrive()), 0.5, method="cvodes", compiled=False)
    for name in system.state_names:
        assert on_vm.final(name) == pytest.approx(reference.final(name), rel=1e-12, abs=1e-15)


def test_asking_for_compiled_c_names_the_folder(blocked_cache):
    system = assemble_cached(TwoInertiaDrive())
    with pytest.raises(CompileError, match=r"kernel cache folder .*cache cannot be written "
                                           r"\(.*\): point BEARINGSIM_CACHE"):
        simulate(system, 0.1, method="cvodes", compiled=True)
