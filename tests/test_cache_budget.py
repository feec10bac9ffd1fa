"""The cache's size budget (bearingsim.cache_budget): the budget read from
$BEARINGSIM_CACHE_SIZE with its unit, the least recently used systems and libraries removed
when a store exceeds it, a hit marking its entry used, the entry just stored kept."""

from __future__ import annotations

import os
import time

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.assembler import assemble_cached
from bearingsim.cache_budget import (
    BUDGET_VARIABLE,
    DEFAULT_BUDGET,
    REFILL,
    budget_bytes,
    keep_to_budget,
)
from bearingsim.errors import ParameterError
from bearingsim.simulation.c_compiler import c_compiler
from tests.models import Pendulum, RigidPair, SpringMassChain, TwoInertiaDrive


def _file(path, size, age_s):
    """A file of ``size`` bytes last used ``age_s`` seconds ago."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"x" * size)
    t = time.time() - age_s
    os.utime(path, (t, t))
    return path


def _systems(root):
    return sorted(p.name for p in (root / "systems").glob("*.bsys"))


@pytest.mark.parametrize(("text", "expected"), [
    ("", DEFAULT_BUDGET[1]), ("500 MB", 5e8), ("1.5 GiB", 1.5 * 2**30), ("64 kB", 64e3),
    ("2 GiB", DEFAULT_BUDGET[1])])
def test_budget_is_a_size_with_its_unit(monkeypatch, text, expected):
    monkeypatch.setenv(BUDGET_VARIABLE, text)
    assert budget_bytes() == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("text", ["lots", "3 m", "500", "0 B", "-1 GB", "nan GB", "inf B",
                                  "1e999 GB"])
def test_a_budget_that_is_no_size_is_refused_by_name(monkeypatch, text):
    monkeypatch.setenv(BUDGET_VARIABLE, text)
    with pytest.raises(ParameterError, match=r"BEARINGSIM_CACHE_SIZE=.*greater than 0 B.*GiB"):
        budget_bytes()


def test_least_recently_used_go_first_libraries_with_their_companions(tmp_path):
    old_system = _file(tmp_path / "systems" / "a.bsys", 400, age_s=500)
    old_lib = _file(tmp_path / "bsm_ode_0123456789abcdef.so", 300, age_s=400)
    # the companion was written with the library; using the library marks the library only
    companion = _file(tmp_path / "bsm_ode_0123456789abcdef.so.balls", 10, age_s=400)
    recent = _file(tmp_path / "systems" / "b.bsys", 300, age_s=10)
    building = _file(tmp_path / ".build_x" / "bsm_ode_1123456789abcdef.so", 5000, age_s=900)
    stored = _file(tmp_path / "systems" / "c.bsys", 200, age_s=0)
    notes = _file(tmp_path / "notes.txt", 5000, age_s=900)  # not the cache's
    # 1210 bytes counted; down to 0.9 x 700: the two oldest entries go
    removed = keep_to_budget(tmp_path, stored, 700)
    assert set(removed) == {old_system, old_lib, companion}
    assert recent.exists() and stored.exists() and building.exists() and notes.exists()
    assert keep_to_budget(tmp_path, stored, 700) == []  # under the budget: nothing to do


def test_the_entry_just_stored_stays_even_alone_over_budget(tmp_path):
    older = _file(tmp_path / "systems" / "a.bsys", 100, age_s=50)
    stored = _file(tmp_path / "systems" / "big.bsys", 5000, age_s=100)  # oldest time stamp
    assert keep_to_budget(tmp_path, stored, 1000) == [older]
    assert stored.exists()


@settings(max_examples=60, deadline=None)
@given(entries=st.lists(st.tuples(st.integers(1, 2000), st.integers(0, 10**6)), min_size=1,
                        max_size=12),
       budget=st.integers(1, 10000), stored_at=st.integers(0, 11))
def test_budget_property(tmp_path_factory, entries, budget, stored_at):
    """Whatever the sizes and ages: afterwards the cache holds at most REFILL of the budget
    (or only the stored entry over it), nothing was removed when it was within the budget,
    the stored entry is kept, and every removed entry was used before every kept one."""
    root = tmp_path_factory.mktemp("cache")
    files = [_file(root / "systems" / f"e{k}.bsys", size, age) for k, (size, age)
             in enumerate(entries)]
    stored = files[stored_at % len(files)]
    total = sum(size for size, _ in entries)
    removed = set(keep_to_budget(root, stored, budget))
    kept = [f for f in files if f not in removed]
    assert stored in kept and all(not f.exists() for f in removed)
    if total <= budget:
        assert not removed
    else:
        rest = sum(f.stat().st_size for f in kept)
        assert rest <= REFILL * budget or kept == [stored] or \
            rest - stored.stat().st_size <= REFILL * budget
    kept_times = [f.stat().st_mtime for f in kept if f != stored]
    removed_ages = [entries[files.index(f)][1] for f in removed]
    if kept_times and removed_ages:
        newest_removed = time.time() - min(removed_ages)
        assert newest_removed <= min(kept_times) + 1.0


def _stored(model):
    """Assemble ``model`` through the cache; its entry."""
    from bearingsim.assembler import cache as system_cache

    assemble_cached(model)
    return system_cache.LAST["path"]


def test_assembled_systems_keep_to_the_budget_and_a_hit_counts_as_use(tmp_path, monkeypatch):
    from bearingsim.assembler import cache as system_cache

    # the fourth model's entry size, learnt in a cache of its own (within a few bytes: the
    # entries of one structure differ a little from one assembly to the next)
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path / "probe"))
    size_d = _stored(SpringMassChain()).stat().st_size
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path / "cache"))
    a, b, c = _stored(TwoInertiaDrive()), _stored(Pendulum()), _stored(RigidPair())
    for age, entry in zip((3000, 2000, 1000), (a, b, c), strict=True):
        os.utime(entry, (time.time() - age, time.time() - age))
    # a hit marks its entry used: the drive, the oldest by far, becomes the newest
    assert _stored(TwoInertiaDrive()) == a and system_cache.LAST["hit"]
    assert a.stat().st_mtime > time.time() - 60
    sizes = {e: e.stat().st_size for e in (a, b, c)}
    room = 1.02 * (sizes[a] + sizes[c] + size_d)  # a, c and d, 2 % to spare
    assert sizes[b] > 0.2 * room  # over the budget with b: removing b alone is enough
    monkeypatch.setenv(BUDGET_VARIABLE, f"{room / REFILL:.0f} B")
    d = _stored(SpringMassChain())
    assert not b.exists()  # the least recently used
    assert a.exists() and c.exists() and d.exists()


def test_a_budget_that_is_no_size_stops_before_assembling(tmp_path, monkeypatch):
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    monkeypatch.setenv(BUDGET_VARIABLE, "plenty")
    with pytest.raises(ParameterError, match="BEARINGSIM_CACHE_SIZE"):
        assemble_cached(TwoInertiaDrive())
    assert _systems(tmp_path) == []


@pytest.mark.skipif(c_compiler() is None, reason="no C compiler")
def test_compiled_libraries_keep_to_the_budget_and_a_hit_counts_as_use(tmp_path, monkeypatch):
    from bearingsim.simulation.compile import source_library

    def library(k):
        return source_library([f"int budget_probe_{k}(void) {{ return {k}; }}\n"],
                              cache_dir=tmp_path, prefix="bsm_probe")

    first, second = library(1), library(2)
    for age, lib in ((2000, first), (1000, second)):
        os.utime(lib, (time.time() - age, time.time() - age))
    assert library(1) == first and first.stat().st_mtime > time.time() - 60  # a hit: used
    size = max(first.stat().st_size, second.stat().st_size)
    monkeypatch.setenv(BUDGET_VARIABLE, f"{2.5 * size / REFILL:.0f} B")  # room for two
    third = library(3)
    assert not second.exists()
    assert first.exists() and third.exists()


def test_cache_command_states_the_budget(tmp_path, monkeypatch, capsys):
    from bearingsim.cli import main

    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    monkeypatch.setenv(BUDGET_VARIABLE, "500 MB")
    assert main(["cache"]) == 0
    assert "budget for the systems and libraries: 500.0 MB ($BEARINGSIM_CACHE_SIZE" in \
        capsys.readouterr().out


def test_cache_command_on_a_file_says_it_is_not_a_folder(tmp_path, monkeypatch, capsys):
    """Before: ``cache`` said the file "holds: 0 assembled system(s)", and ``cache clear``
    failed on "<file>/kernel_names: a part of the path is a file"."""
    from bearingsim.cli import main

    blocked = tmp_path / "cache"
    blocked.write_text("not a folder")
    monkeypatch.setenv("BEARINGSIM_CACHE", str(blocked))
    said = f"bearingsim cache: {blocked} is not a folder: nothing is kept there"
    assert main(["cache"]) == 0
    assert capsys.readouterr().out.startswith(said)
    assert main(["cache", "clear"]) == 2
    assert capsys.readouterr().err.startswith(said)
    assert blocked.read_text() == "not a folder"
