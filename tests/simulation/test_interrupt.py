"""SUNDIALS and compiled BDF runs in a user's process: Ctrl-C (SIGINT) during a run raises
KeyboardInterrupt promptly (CasADi reports it as a failed evaluation, which used to start the
interval-by-interval failure diagnosis of a 200 s run, i.e. a hang; the C loop of compiled_bdf
returns to Python every few thousand steps) and leaves no partial output file; a run on MUMPS
leaves standard output clean."""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import pytest

SCRIPT = """
import sys
from bearingsim.assembler import assemble
from bearingsim.assemblies import deep_groove_ball_bearing
from bearingsim.simulation import simulate

system = assemble(deep_groove_ball_bearing("6304", "dynamic_massive_balls", n_slices=0))
print("running", flush=True)
res = simulate(system, 200.0, inputs={"shaft_speed": 1500.0, "load.Fx": 2000.0},
               method="cvodes", compiled=False, n_points=2001, progress=sys.argv[2] == "bar")
res.to_csv(sys.argv[1] + "/result.csv")
print("finished", flush=True)
"""


def _interrupted(script: str, *args: str) -> tuple[str, float]:
    """Run ``script`` in a child process, send Ctrl-C 1.5 s after it prints "running" (inside
    the integration: the whole run takes minutes); its standard error and the seconds it took
    to stop. It must stop within 60 s and fail."""
    proc = subprocess.Popen([sys.executable, "-c", script, *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "running"
    time.sleep(1.5)
    sent = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("the run did not stop within 60 s of Ctrl-C")
    assert proc.returncode != 0
    return err, time.perf_counter() - sent


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process")
@pytest.mark.parametrize("bar", ["bar", "no bar"])  # with a bar: in one of the chunks
def test_ctrl_c_stops_a_cvodes_run_and_writes_nothing(tmp_path, bar):
    err, seconds = _interrupted(SCRIPT, str(tmp_path), bar)
    assert seconds < 30.0
    assert "KeyboardInterrupt: CVODES run interrupted" in err
    assert list(tmp_path.iterdir()) == []


BDF_SCRIPT = """
import sys
from bearingsim.assembler import assemble
from bearingsim.assemblies import deep_groove_ball_bearing
from bearingsim.simulation import simulate
from bearingsim.simulation.kernels import kernel

system = assemble(deep_groove_ball_bearing("6304", "dynamic_massive_balls", n_slices=0))
kernel(system, "ode", True)  # compiled before the signal
print("running", flush=True)
res = simulate(system, 200.0, inputs={"shaft_speed": 1500.0, "load.Fx": 2000.0},
               method="compiled_bdf", n_points=3, progress=False,
               max_steps=10**9)  # the step budget would end it before the Ctrl-C
res.to_csv(sys.argv[1] + "/result.csv")
print("finished", flush=True)
"""


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process")
def test_ctrl_c_stops_a_compiled_bdf_run_with_few_outputs(tmp_path):
    """The C loop returns to Python every STEPS_PER_CALL steps, however far apart the output
    times are (here three over 200 s): Ctrl-C is seen within one call."""
    from bearingsim.simulation.c_compiler import c_compiler

    if c_compiler() is None:
        pytest.skip("needs a C compiler")
    err, seconds = _interrupted(BDF_SCRIPT, str(tmp_path))
    assert seconds < 10.0
    assert "KeyboardInterrupt" in err
    assert list(tmp_path.iterdir()) == []


MUMPS_SCRIPT = """
from bearingsim.assembler import assemble
from bearingsim.assemblies import deep_groove_ball_bearing
from bearingsim.simulation import simulate

system = assemble(deep_groove_ball_bearing("6304", "dynamic_massive_balls", n_slices=0))
res = simulate(system, 2e-4, inputs={"shaft_speed": 300.0}, method="cvodes", n_points=3,
               compiled=False, linear_solver="mumps")
print(res.stats["linear_solver"])
"""


def test_a_run_on_mumps_leaves_standard_output_to_the_user():
    """MUMPS prints a banner when CasADi destroys its solver (flushed by the Fortran runtime at
    exit); a script's standard output must hold only what the script printed."""
    proc = subprocess.run([sys.executable, "-c", MUMPS_SCRIPT], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == "mumps\n"
