"""The staged pipeline and the ``extra_passes`` hook of ``assemble``."""

from __future__ import annotations

import types

import pytest

from bearingsim.assembler import PASS_NAMES, STAGES, assemble
from bearingsim.errors import ParameterError, PassOrderError, StructuralError
from tests.models import TwoInertiaDrive


def test_the_stages_run_the_passes_in_the_documented_order():
    assert [(s.name, [p.NAME for p in s.passes], s.check_balance) for s in STAGES] == [
        ("pre", ["flatten", "alias elimination"], False),
        ("main", ["structural check", "index reduction", "matching", "pruning", "BLT sorting"],
         True),
        ("post", ["tearing and block solving", "repeated structure", "code generation"], False),
    ]
    system = assemble(TwoInertiaDrive())
    assert [name for name, _ in system.timings] == list(PASS_NAMES)


class DaeSize:
    """Records the size of the DAE when it runs."""

    def __init__(self, name):
        self.NAME = name
        self.sizes = []

    def run(self, state):
        state.require(self.NAME, "dae")
        self.sizes.append((len(state.dae.vars), len(state.dae.eqs)))
        state.report[self.NAME] = f"{len(state.dae.eqs)} equations"


def test_extra_passes_run_right_after_the_named_passes_and_are_timed():
    before, after = DaeSize("size before aliases"), DaeSize("size after index reduction")
    two = [DaeSize("size after BLT"), DaeSize("size after BLT, again")]
    end = DaeSize("size at the end")
    system = assemble(TwoInertiaDrive(), extra_passes={
        "flatten": before, "index reduction": after, "BLT sorting": two, "code generation": end})
    assert before.sizes == [(26, 21)]  # the flat model (system.report["flat"])
    assert after.sizes == [(9, 5)]  # 17 aliases gone, one equation differentiated
    assert two[0].sizes == two[1].sizes == end.sizes == [(9, 5)]
    assert system.report["size before aliases"] == "21 equations"
    names = [name for name, _ in system.timings]
    assert names == ["flatten", "size before aliases", "alias elimination", "structural check",
                     "index reduction", "size after index reduction", "matching", "pruning",
                     "BLT sorting", "size after BLT", "size after BLT, again",
                     "tearing and block solving", "repeated structure", "code generation",
                     "size at the end"]


def test_a_module_is_a_pass_and_may_rewrite_the_model():
    """A pass module that starts the second inertia at 3 rad/s before the structure is fixed."""
    module = types.ModuleType("spin_up")
    module.NAME = "spin up j2"

    def run(state):
        state.require(module.NAME, "dae")
        (w2,) = [v for v in state.dae.vars if v.name == "j2.w"]
        w2.start = 3.0

    module.run = run
    system = assemble(TwoInertiaDrive(), extra_passes={"alias elimination": module})
    assert list(system.x0()) == [0.0, 0.0, 0.0, 3.0]
    assert list(assemble(TwoInertiaDrive()).x0()) == [0.0, 0.0, 0.0, 0.0]


class DropEquation:
    NAME = "drop an equation"

    def run(self, state):
        state.dae.eqs.pop()


def test_a_main_stage_pass_that_breaks_the_balance_is_caught():
    with pytest.raises(StructuralError, match="internal error after pass 'drop an equation': "
                                              "4 equations for 5 unknowns"):
        assemble(TwoInertiaDrive(), extra_passes={"index reduction": DropEquation()})


class NeedsMatching:
    NAME = "needs matching"

    def run(self, state):
        state.require(self.NAME, "dae", "matching")


def test_a_pass_inserted_before_its_inputs_exist_names_the_missing_pass():
    with pytest.raises(PassOrderError, match="'needs matching' runs before what it needs: "
                                             "matching \\(set by pass 'matching'\\)"):
        assemble(TwoInertiaDrive(), extra_passes={"flatten": NeedsMatching()})
    assemble(TwoInertiaDrive(), extra_passes={"matching": NeedsMatching()})


NOT_A_PASS = r"extra_passes\['matching'\] must be a pass or a list of passes, each with a NAME"


@pytest.mark.parametrize(("extra", "message"), [
    ([NeedsMatching()], "extra_passes must be a dict of pass names -> values, got list"),
    ({"BLT sort": NeedsMatching()}, "extra_passes key must be .*, got 'BLT sort'"),
    ({"matching": object()}, NOT_A_PASS),
    ({"matching": [types.SimpleNamespace(NAME="", run=print)]}, NOT_A_PASS),
    ({"matching": types.SimpleNamespace(NAME="pruning", run=print)},
     r"extra_passes\['matching'\]: a pass named 'pruning' is already in the pipeline"),
    ({"flatten": NeedsMatching(), "matching": NeedsMatching()},
     r"extra_passes\['matching'\]: a pass named 'needs matching' is already in the pipeline"),
])
def test_bad_extra_passes_are_refused_by_name(extra, message):
    with pytest.raises(ParameterError, match=f"^assemble: {message}"):
        assemble(TwoInertiaDrive(), extra_passes=extra)
