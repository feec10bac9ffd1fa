"""The typed assembly state: each field names the pass that sets it, and a pass run before what
it reads exists stops with a PassOrderError naming the pass that sets it."""

from __future__ import annotations

from dataclasses import fields

import pytest

from bearingsim.assembler import PASS_NAMES, STAGES, AssemblyState
from bearingsim.assembler.passes import (
    alias_elimination,
    blt,
    codegen,
    pruning,
    repeated,
    tearing,
)
from bearingsim.errors import PassOrderError
from tests.assembler.hand_dae import dae, state_of, state_var


def test_every_field_names_a_pass_that_exists():
    set_by = {f.name: f.metadata["set_by"] for f in fields(AssemblyState)}
    assert set(set_by.values()) <= {"assemble", "any pass", *PASS_NAMES}
    assert {set_by[n] for n in ("dae", "matching", "blocks", "causal", "repeats", "system")} == {
        "flatten", "matching", "BLT sorting", "tearing and block solving", "repeated structure",
        "code generation"}


def test_every_pass_module_has_a_name_and_a_run():
    passes = [p for stage in STAGES for p in stage.passes]
    assert all(isinstance(p.NAME, str) and callable(p.run) for p in passes)
    assert len(set(PASS_NAMES)) == len(PASS_NAMES) == 10


@pytest.mark.parametrize(("module", "message"), [
    (alias_elimination, "'alias elimination' runs before what it needs: dae (set by pass "
                        "'flatten')"),
    (pruning, "'pruning' runs before what it needs: matching (set by pass 'matching')"),
    (repeated, "'repeated structure' runs before what it needs: blocks (set by pass "
               "'BLT sorting')"),
    (blt, "'BLT sorting' runs before what it needs: matching (set by pass 'matching')"),
    (tearing, "'tearing and block solving' runs before what it needs: blocks (set by pass "
              "'BLT sorting')"),
    (codegen, "'code generation' runs before what it needs: causal (set by pass 'tearing and "
              "block solving')"),
])
def test_a_pass_run_too_early_names_the_pass_it_waits_for(module, message):
    state = state_of(None) if module is alias_elimination else state_of(
        dae(list(state_var("x", 1.0)), []))
    with pytest.raises(PassOrderError) as err:
        module.run(state)
    assert str(err.value) == f"assembler pass {message}"
