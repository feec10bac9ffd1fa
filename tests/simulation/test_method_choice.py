"""``simulate(method=None)`` picks the documented method (issue 31 items 3 and 6), says why,
and a first run on a cold cache waits for the compiler only when the run outlasts it; no
compiler process outlives the program."""

from __future__ import annotations

import os
import stat
import time

import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.simulation import choice, kernels, simulate
from bearingsim.simulation.c_compiler import Build, c_compiler, stop_builds
from bearingsim.simulation.kernels import clear_kernel_cache, wait_for_compilations
from tests.models import Pendulum

needs_cc = pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")
SPEED = {"shaft_speed": 300.0}


@pytest.fixture()
def cold_cache(tmp_path, monkeypatch):
    """An empty kernel library cache, and kernels small enough to compile in a test (the
    torque level has 122 instructions: below AUTO_MIN_INSTRUCTIONS it would stay on the VM)."""
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    monkeypatch.setattr(kernels, "AUTO_MIN_INSTRUCTIONS", 0)
    clear_kernel_cache()
    yield tmp_path
    wait_for_compilations()
    clear_kernel_cache()


@pytest.fixture()
def torque_level():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque"))


@needs_cc
def test_warm_cache_picks_compiled_bdf_and_says_why(torque_level, cold_cache):
    first = simulate(torque_level, 0.01, inputs=SPEED, compiled=True)  # compiles now
    assert first.stats["method"] == "compiled_bdf"
    assert first.stats["method_reason"].startswith("stiff ODE form, compiled=True")
    again = simulate(torque_level, 0.01, inputs=SPEED)
    assert again.stats["method"] == "compiled_bdf" and again.stats["backend"] == "compiled C"
    assert again.stats["method_reason"] == ("stiff ODE form, compiled kernels cached: the BDF "
                                            "step loop in C")


@needs_cc
def test_a_short_first_run_starts_on_the_vm_while_c_compiles(torque_level, cold_cache,
                                                              monkeypatch):
    monkeypatch.setattr(choice, "_vm_seconds", lambda *args: 0.0)
    short = simulate(torque_level, 0.01, inputs=SPEED)
    assert short.stats["method"] == "cvodes" and short.stats["backend"] == "CasADi VM"
    assert short.stats["method_reason"].startswith("cold cache: a short run (about 0 s on the "
                                                   "VM) starts on CasADi's VM with CVODES")
    wait_for_compilations()
    later = simulate(torque_level, 0.01, inputs=SPEED)
    assert later.stats["method"] == "compiled_bdf"  # the background build is picked up


@needs_cc
def test_a_long_first_run_waits_for_the_compiler(torque_level, cold_cache, monkeypatch):
    monkeypatch.setattr(choice, "_vm_seconds", lambda *args: 1e6)
    long = simulate(torque_level, 0.01, inputs=SPEED)
    assert long.stats["method"] == "compiled_bdf" and long.stats["backend"] == "compiled C"
    assert "outlasts compiling" in long.stats["method_reason"]
    assert "waited for the compiler" in long.stats["method_reason"]


def test_without_a_compiler_or_with_compiled_false_cvodes_on_the_vm(torque_level,
                                                                   monkeypatch):
    res = simulate(torque_level, 0.01, inputs=SPEED, compiled=False)
    assert res.stats["method"] == "cvodes" and res.stats["backend"] == "CasADi VM"
    assert res.stats["method_reason"] == "compiled=False: CVODES on CasADi's VM"
    monkeypatch.setattr(choice, "c_compiler", lambda: None)
    res = simulate(torque_level, 0.01, inputs=SPEED)
    assert res.stats["method"] == "cvodes"
    assert res.stats["method_reason"] == "no C compiler: CVODES on CasADi's VM"


def test_newton_blocks_run_idas_on_the_dae_form():
    system = assemble(Pendulum(), rootfinder="newton")
    res = simulate(system, 0.1, compiled=False)
    assert res.stats["method"] == "idas (dae)" and res.stats["form"] == "dae"
    assert "IDAS on the semi-explicit DAE form" in res.stats["method_reason"]


def test_a_given_method_is_kept(torque_level):
    res = simulate(torque_level, 0.01, inputs=SPEED, method="BDF")
    assert res.stats["method"] == "BDF" and res.stats["method_reason"] == "method='BDF' given"
    assert simulate(torque_level, 0.01, inputs=SPEED, backend="scipy").stats["method"] == "BDF"


@pytest.mark.skipif(not os.path.isdir("/proc"), reason="reads /proc")
def test_no_compiler_outlives_the_program(tmp_path, monkeypatch):
    """A build still running when the program ends is stopped with its whole process group
    and its build folder removed (stop_builds runs at interpreter exit)."""
    slow = tmp_path / "slowcc"
    slow.write_text("#!/bin/sh\nsleep 60\n")
    slow.chmod(slow.stat().st_mode | stat.S_IEXEC)
    monkeypatch.setenv("CC", str(slow))
    build = Build("int f(void) { return 0; }", tmp_path / "lib" / "never.so", ("-O0",))
    assert not build.done()
    stop_builds(grace=0.2)
    assert build.done() and not (tmp_path / "lib" / "never.so").exists()
    assert [p.name for p in (tmp_path / "lib").iterdir()] == []  # build folder removed
    # the group was sent SIGKILL; its processes end asynchronously (a loaded machine may show
    # the sleep for a moment): none may still run a few seconds later
    deadline = time.monotonic() + 5.0
    while _running_in_group(build._proc.pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _running_in_group(build._proc.pid) == []  # the sleep included


def _running_in_group(group: int) -> list[int]:
    """Processes of a process group that are still running (zombies are finished)."""
    running = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                fields = open(f"/proc/{entry}/stat").read().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[2]) == group and fields[0] != "Z":
                running.append(int(entry))
    return running


SCENE = """
title = "torque level, no method given"
outputs = ["Rs"]

[assembly]
name = "double_layer_bearing"
fidelity = "torque"
inner = "61905"
outer = "61907"

[inputs]
shaft_speed = "rpm(3000) * ramp(0, 0.005)"

[simulation]
t_end = 0.01
n_points = 11
{method}
"""


def _scene_run(method_line: str = ""):
    from bearingsim.scenes import parse_scene
    from bearingsim.scenes.preparation import prepare
    from bearingsim.scenes.scene_simulation import run_simulation

    prep = prepare(parse_scene(SCENE.format(method=method_line)))
    return prep, run_simulation(prep)


@needs_cc
def test_a_scene_without_a_method_runs_the_default_method(cold_cache):
    prep, _ = _scene_run()
    assert prep.scene.simulation.method is None
    kernels.kernel(prep.system, "ode", True)  # the kernels compiled: the warm-cache rule
    _, res = _scene_run()
    assert res.stats["method"] == "compiled_bdf" and res.stats["backend"] == "compiled C"
    assert res.stats["method_reason"] == ("stiff ODE form, compiled kernels cached: the BDF "
                                          "step loop in C")
    # the same numbers as the method given by name, and as CVODES to its tolerance
    _, named = _scene_run('method = "compiled_bdf"')
    assert named.stats["method_reason"] == "method='compiled_bdf' given"
    assert (res["Rs"] == named["Rs"]).all()
    _, cvodes = _scene_run('method = "cvodes"')
    assert abs(res["Rs"][-1] - cvodes["Rs"][-1]) <= 1e-4 * abs(cvodes["Rs"][-1])


def test_a_scene_without_a_method_and_no_compiler_runs_cvodes(monkeypatch):
    monkeypatch.setattr(choice, "c_compiler", lambda: None)
    _, res = _scene_run()
    assert res.stats["method"] == "cvodes" and res.stats["backend"] == "CasADi VM"
    assert res.stats["method_reason"] == "no C compiler: CVODES on CasADi's VM"


def test_a_scene_keeps_the_method_it_states():
    _, res = _scene_run('method = "BDF"')
    assert res.stats["method"] == "BDF" and res.stats["method_reason"] == "method='BDF' given"
