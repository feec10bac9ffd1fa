"""The on-disk cache of assembled systems (bearingsim.assembler.cache): a hit is the system a
fresh assembly gives (names, start values, every function at a random point), parameter values
stay free, and stale or corrupt entries are rebuilt, never loaded."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble, assemble_cached
from bearingsim.assembler import cache as system_cache
from bearingsim.assembler.fingerprint import structure_key
from bearingsim.cache_paths import cache_root
from bearingsim.errors import ParameterError
from bearingsim.units.registry import PINT_CACHE
from tests.models import Pendulum, SpringMassChain, TwoInertiaDrive


def _entries(root):
    return sorted((root / "systems").glob("*.bsys"))


def _same_system(a, b, rng):
    """Equal names, units, start values and function values at a random point."""
    assert a.state_names == b.state_names
    assert a.input_names == b.input_names and a.output_names == b.output_names
    assert a.parameter_names == b.parameter_names
    assert a.observed_names == b.observed_names and a.variable_units == b.variable_units
    np.testing.assert_array_equal(a.x0(), b.x0())
    np.testing.assert_array_equal(a.p0(), b.p0())
    args = (0.3, a.x0() + rng.normal(size=a.n_states) * 0.1,
            a.u_default() + 0.5, a.p0() * (1 + 0.1 * rng.random(len(a.params))))
    for key in ("ode", "observe", "output", "jac_x", "jac_u", "out_jac_x", "out_jac_u"):
        np.testing.assert_allclose(np.array(b.functions[key](*args)),
                                   np.array(a.functions[key](*args)), rtol=1e-12, atol=1e-12,
                                   err_msg=key)


def test_a_hit_equals_a_fresh_assembly(tmp_path):
    rng = np.random.default_rng(1)
    fresh = assemble(TwoInertiaDrive())
    cold = assemble_cached(TwoInertiaDrive(), cache_dir=tmp_path)
    assert not system_cache.LAST["hit"] and len(_entries(tmp_path)) == 1
    warm = assemble_cached(TwoInertiaDrive(), cache_dir=tmp_path)
    assert system_cache.LAST["hit"] and "cache" in warm.report
    _same_system(fresh, cold, rng)
    _same_system(fresh, warm, rng)


def test_ball_model_with_mapped_kernels_loads_equal(tmp_path):
    """The 6304 massive-ball level: per-ball kernels mapped over the row survive the cache."""
    from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing

    def build():
        return deep_groove_ball_bearing("6304", "dynamic_massive_balls", n_slices=0)

    fresh = assemble(build())
    assemble_cached(build(), cache_dir=tmp_path)
    warm = assemble_cached(build(), cache_dir=tmp_path)
    assert system_cache.LAST["hit"]
    assert warm.mapped.summary == fresh.mapped.summary
    k_fresh, k_warm = fresh.mapped.get("ode"), warm.mapped.get("ode")
    x, u, p = fresh.x0(), fresh.u_default() + 100.0, fresh.p0()
    np.testing.assert_array_equal(np.array(k_warm.function(0.0, x, u, p)),
                                  np.array(k_fresh.function(0.0, x, u, p)))
    np.testing.assert_allclose(np.array(warm.functions["ode"](0.0, x, u, p)),
                               np.array(k_fresh.function(0.0, x, u, p)), rtol=1e-10,
                               atol=1e-9)


def test_parameter_values_stay_free(tmp_path):
    """Another value of a parameter hits the same entry; the loaded system has the new value and
    the declaration's range check (spring constant > 0)."""
    assemble_cached(SpringMassChain(), cache_dir=tmp_path)
    other = SpringMassChain()
    other.k2.c = 40.0
    system = assemble_cached(other, cache_dir=tmp_path)
    assert system_cache.LAST["hit"]
    _same_system(assemble(other), system, np.random.default_rng(3))
    assert system.p0()[system.parameter_names.index("k2.c")] == 40.0
    assert len(_entries(tmp_path)) == 1
    with pytest.raises(ParameterError, match=r"k2\.c.*N\.m/rad"):
        system.p0({"k2.c": -1.0})


def test_structure_outputs_and_options_change_the_key():
    base = structure_key(TwoInertiaDrive())
    assert structure_key(TwoInertiaDrive()) == base
    assert structure_key(TwoInertiaDrive(), ["w1"]) != base
    assert structure_key(TwoInertiaDrive(), rootfinder="newton") != base
    assert structure_key(Pendulum()) != base
    # a start value is structure (not a parameter): another start, another entry
    assert structure_key(Pendulum(angle0=0.4)) != structure_key(
        Pendulum(angle0=0.5))


def test_structure_chosen_at_parameter_values_is_not_reused(tmp_path):
    """Index reduction picks dummy derivatives at the start point's parameter values: such an
    entry is reused only at the same values."""
    assemble_cached(Pendulum(L=1.0), cache_dir=tmp_path)
    assemble_cached(Pendulum(L=1.0), cache_dir=tmp_path)
    assert system_cache.LAST["hit"]
    longer = Pendulum(L=1.0)
    longer.L = 2.0
    system = assemble_cached(longer, cache_dir=tmp_path)
    assert not system_cache.LAST["hit"]
    np.testing.assert_array_equal(system.p0(), assemble(longer).p0())


@pytest.mark.parametrize("damage", ["flip a byte", "truncate", "magic", "empty"])
def test_corrupt_entries_are_rebuilt_not_loaded(tmp_path, damage):
    rng = np.random.default_rng(2)
    assemble_cached(TwoInertiaDrive(), cache_dir=tmp_path)
    (entry,) = _entries(tmp_path)
    raw = bytearray(entry.read_bytes())
    if damage == "flip a byte":
        raw[len(raw) // 2] ^= 0xFF
    elif damage == "truncate":
        raw = raw[: len(raw) // 3]
    elif damage == "magic":
        raw[:4] = b"XXXX"
    else:
        raw = bytearray()
    entry.write_bytes(bytes(raw))
    system = assemble_cached(TwoInertiaDrive(), cache_dir=tmp_path)
    assert not system_cache.LAST["hit"]
    _same_system(assemble(TwoInertiaDrive()), system, rng)
    assemble_cached(TwoInertiaDrive(), cache_dir=tmp_path)
    assert system_cache.LAST["hit"]  # rewritten whole


def test_entries_of_other_code_are_stale(tmp_path, monkeypatch):
    assemble_cached(TwoInertiaDrive(), cache_dir=tmp_path)
    (entry,) = _entries(tmp_path)
    key = entry.stem
    # the same key under other code (e.g. an edited package): the entry says which code wrote it
    monkeypatch.setattr(system_cache, "code_version", lambda: "other code")
    assert system_cache._read_entry(entry, key, {}) is None
    assert not entry.exists()


def test_cache_info_and_clear(tmp_path, monkeypatch):
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    from bearingsim.simulation.c_compiler import default_cache_dir

    assert default_cache_dir() == tmp_path == cache_root()
    assemble_cached(TwoInertiaDrive())
    (tmp_path / "bsm_ode_0123456789abcdef.so").write_bytes(b"x" * 10)
    (tmp_path / "notes.txt").write_text("not ours")
    units = tmp_path / PINT_CACHE  # where the units library keeps its parsed definitions
    units.mkdir(exist_ok=True)
    (units / "definitions.pickle").write_bytes(b"y" * 20)
    info = system_cache.cache_info()
    assert info.systems == 1 and info.systems_bytes > 1000
    assert info.libraries == 1 and info.libraries_bytes == 10
    assert info.units_bytes >= 20
    system_cache.clear_cache()
    after = system_cache.cache_info()
    assert (after.systems, after.libraries, after.units_bytes) == (0, 0, 0)
    assert not units.exists()  # "cache clear" empties every cache (it left the units' before)
    assert (tmp_path / "notes.txt").exists()


def test_cache_command_shows_and_clears(tmp_path, monkeypatch, capsys):
    from bearingsim.cli import main

    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    assemble_cached(TwoInertiaDrive())
    assert main(["cache"]) == 0
    assert f"{tmp_path} holds: 1 assembled system(s)" in capsys.readouterr().out
    assert main(["cache", "clear"]) == 0
    assert f"{tmp_path} removed: 1 assembled system(s)" in capsys.readouterr().out
    assert not _entries(tmp_path)
