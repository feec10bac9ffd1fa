"""Kernel libraries of loaded systems found by name (bearingsim.simulation.kernel_names): a
second process finds the library without generating its C source, and an entry that does not
fit (other bytes, other code, a library gone, a malformed name) is never used."""

from __future__ import annotations

import hashlib

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assembler import cache as system_cache
from bearingsim.cache_paths import KERNEL_NAMES
from bearingsim.simulation import kernel_names, kernels
from bearingsim.simulation.c_compiler import c_compiler
from tests.models import SpringMassChain, TwoInertiaDrive

pytestmark = pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")


@pytest.fixture
def named_by_source(monkeypatch, tmp_path):
    """Kernels named by their generated C source (as the mapped ball-level kernels are) in a
    fresh cache folder; the payload of TwoInertiaDrive."""
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    monkeypatch.setattr(kernels, "_identity", lambda form, sources: None)
    return system_cache.dumps_system(assemble(TwoInertiaDrive()))


def _no_source(*args, **kwargs):
    raise AssertionError("the C source was generated")


def test_a_loaded_system_carries_the_hash_of_its_bytes():
    payload = system_cache.dumps_system(assemble(TwoInertiaDrive()))
    loaded = system_cache.loads_system(payload)
    assert loaded.content_key == hashlib.sha256(payload).hexdigest()
    assert assemble(TwoInertiaDrive()).content_key is None
    again = system_cache.loads_system(system_cache.dumps_system(loaded))
    assert again.content_key is not None  # the key is not stored in the bytes themselves


def test_a_second_process_finds_the_library_without_its_source(named_by_source, monkeypatch,
                                                               tmp_path):
    first = kernels.kernel(system_cache.loads_system(named_by_source), "ode", True)
    assert [p.parent.name for p in tmp_path.glob(f"{KERNEL_NAMES}/*")] == [KERNEL_NAMES]
    monkeypatch.setattr(kernels, "generate_units", _no_source)
    # a new System object: its kernel cache is empty, as in a new process
    second = kernels.kernel(system_cache.loads_system(named_by_source), "ode", True)
    assert second.library == first.library
    x = np.linspace(0.1, 0.4, first.function.size1_in(1))
    args = (0.2, x, np.ones(first.function.size1_in(2)), np.ones(first.function.size1_in(3)))
    np.testing.assert_array_equal(np.array(second.function(*args)),
                                  np.array(first.function(*args)))


def test_an_assembled_system_is_not_remembered(named_by_source, tmp_path):
    kernels.kernel(assemble(TwoInertiaDrive()), "ode", True)
    assert not (tmp_path / KERNEL_NAMES).exists()


@pytest.mark.parametrize("damage", ["library gone", "malformed", "other code", "other bytes"])
def test_an_entry_that_does_not_fit_is_not_used(named_by_source, monkeypatch, tmp_path, damage):
    first = kernels.kernel(system_cache.loads_system(named_by_source), "ode", True)
    (entry,) = (tmp_path / KERNEL_NAMES).iterdir()
    system = system_cache.loads_system(named_by_source)
    recipe = ("ode", "mapped=False", "bsm_ode", *kernels.DEFAULT_FLAGS, "split:",
              *kernels.DEFAULT_SPLIT_FLAGS)
    assert kernel_names.remembered_library(system, recipe, None) == first.library
    if damage == "library gone":
        first.library.unlink()
    elif damage == "malformed":
        entry.write_text("../../etc/passwd")
    elif damage == "other code":
        monkeypatch.setattr(kernel_names, "code_version", lambda: "other code")
    else:
        system = system_cache.loads_system(
            system_cache.dumps_system(assemble(SpringMassChain())))
    assert kernel_names.remembered_library(system, recipe, None) is None


def test_cache_clear_removes_the_names(named_by_source, tmp_path):
    kernels.kernel(system_cache.loads_system(named_by_source), "ode", True)
    assert (tmp_path / KERNEL_NAMES).is_dir()
    system_cache.clear_cache()
    assert not (tmp_path / KERNEL_NAMES).exists()
