"""The helpers scene specs share: the arguments a build passes on, the keywords of one level."""

from __future__ import annotations

from bearingsim.assemblies.cylindrical_roller.spindle import SPINDLE_SCENE_SPEC
from bearingsim.assemblies.duplex import SCENE_SPEC as DUPLEX_SPEC
from bearingsim.assemblies.spec import AssemblySpec, given_args, single_level


def test_given_args_passes_on_what_has_a_value():
    args = {"a": 1.0, "b": None, "c": 0.0, "d": False, "e": "x"}
    assert given_args(args) == {"a": 1.0, "c": 0.0, "d": False, "e": "x"}
    assert given_args(args, leave_out=("a", "e")) == {"c": 0.0, "d": False}
    assert given_args(None) == {}


def test_a_single_level_spec_has_that_level_for_every_name_and_takes_no_fidelity():
    spec = AssemblySpec(name="one", description="", build=lambda args, fidelity: None, args={},
                        default_outputs=[], **single_level("static"))
    assert spec.fidelities == spec.auto_fidelities == ("static",)
    assert spec.min_fidelity("anything.at_all") == "static"
    assert spec.fidelity_arg is None
    for shipped in (SPINDLE_SCENE_SPEC, DUPLEX_SPEC):
        assert (shipped.fidelities, shipped.fidelity_arg) == (("quasi-static",), None)
