"""A scene's ``[lubricants]`` belong to the scene. Before, a scene's override of a built-in
lubricant stayed for the process: a scene read after it that named the built-in ran with the
override (ISO VG 32 at 320 mm^2/s instead of 32), a worker of a persistent cluster kept an
earlier sweep's override, and unregistering the override left no ISO VG 32 at all."""

from __future__ import annotations

import pytest

from bearingsim.physics.lubricant import (
    LUBRICANTS,
    Oil,
    get_lubricant,
    register_lubricant,
    unregister_lubricant,
)
from bearingsim.scenes import parse_scene, sweep_worker
from bearingsim.scenes.lubricant_table import load_lubricants_table
from bearingsim.scenes.preparation import prepare

SCENE = """
title = "{title}"
outputs = ["Rs"]
[assembly]
name = "double_layer_bearing"
fidelity = "torque"
lubrication = "ISO VG 32"
[inputs]
shaft_speed = "6000 rpm"
[simulation]
t_end = 0.01
"""
OVERRIDE = """
[lubricants."ISO VG 32"]
nu40 = "320 mm^2/s"
nu100 = "25 mm^2/s"
"""


def _nu40() -> float:
    return get_lubricant("ISO VG 32").nu_points[0][0]


@pytest.fixture(autouse=True)
def no_scene_lubricants():
    yield
    load_lubricants_table(None)  # forgets the last scene's
    assert _nu40() == 32.0


def test_each_scene_runs_with_its_own_lubricants_whatever_was_read_since():
    overriding = parse_scene(SCENE.format(title="a") + OVERRIDE)
    assert _nu40() == 320.0
    plain = parse_scene(SCENE.format(title="b"))
    assert _nu40() == 32.0  # it stayed at 320 before
    nu = {}
    for scene in (overriding, plain, overriding):
        system = prepare(scene).system
        nu[scene.title] = system.p0()[system.parameter_names.index("inner_layer.nu")]
    assert nu["a"] == pytest.approx(10 * nu["b"], rel=1e-9)
    assert parse_scene(overriding.text).lubricants == overriding.to_dict()["lubricants"]


def test_unregistering_an_override_gives_the_built_in_back():
    register_lubricant("iso vg 32", lambda **kw: Oil(320.0, 40.0, 25.0, 100.0,
                                                     **{"name": "iso vg 32", **kw}), replace=True)
    assert _nu40() == 320.0
    unregister_lubricant("ISO VG 32")
    assert _nu40() == 32.0 and get_lubricant("ISO VG 32").name == "ISO VG 32"
    assert "ISO VG 32" not in LUBRICANTS.registered()


def test_a_worker_forgets_an_earlier_sweeps_override(monkeypatch):
    """A worker of a persistent cluster (another process) registers what each chunk's client
    registered; a later sweep whose client registered nothing under the name ships nothing,
    and the worker now gives the built-in back. In the client's own process (a worker thread
    there) nothing is restored or forgotten."""
    parse_scene(SCENE.format(title="a") + OVERRIDE)
    shipped = sweep_worker.registrations(["ISO VG 32"])
    load_lubricants_table(None)  # the client's process is done with that scene
    assert _nu40() == 32.0
    sweep_worker.restore_registrations(shipped)  # in the client's own process: nothing
    assert _nu40() == 32.0
    monkeypatch.setattr(sweep_worker, "process_token", lambda: "a worker's process")
    sweep_worker.restore_registrations(shipped)  # the first sweep's chunk on a worker
    assert _nu40() == 320.0
    sweep_worker.restore_registrations(b"")  # a later sweep's: nothing registered
    assert _nu40() == 32.0
