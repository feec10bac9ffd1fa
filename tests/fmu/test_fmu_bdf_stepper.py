"""The BDF co-simulation stepper (``export_fmu(stepper="bdf")``, the stepping core of
``method="compiled_bdf"``): its history (step size, order, differences) survives the
communication points and FMU states, within a process and across processes, bit for bit;
``stepper="auto"`` picks it for models of many states."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pytest

from bearingsim.fmu import export_fmu
from bearingsim.fmu.model_c import BDF_MIN_STATES, resolve_stepper
from tests.fmu.conftest import STIFF_OUTPUTS
from tests.fmu.helpers import open_fmu, reference, rel_err
from tests.fmu.test_fmu_stepper import run_cs

H = 0.05
"""Communication step of the state tests [s]."""


@pytest.fixture(scope="module")
def stiff_bdf_fmu(fmu_dir, stiff_system):
    return export_fmu(stiff_system, fmu_dir / "stiff_bdf.fmu", kinds=("CS",), stepper="bdf",
                      model_name="stiff_bdf")


def _steps(fmu, refs, t, n):
    out = []
    for _ in range(n):
        fmu.doStep(t, H)
        t += H
        out.append(fmu.getReal(refs))
    return np.array(out)


def test_history_survives_the_communication_points(stiff_bdf_fmu, stiff_system, tmp_path):
    """Stopping every 1 ms instead of every 50 ms costs at most one extra step per
    communication point (a restart at each point would start again at order 1 and a small
    step: several steps each), and both runs agree with simulate."""
    ref = reference(stiff_system, 1.0, 0.05)
    coarse, c_coarse = run_cs(stiff_bdf_fmu, tmp_path / "coarse", 0.05, 1.0, STIFF_OUTPUTS, 1e-8)
    fine, c_fine = run_cs(stiff_bdf_fmu, tmp_path / "fine", 0.001, 1.0, STIFF_OUTPUTS, 1e-8)
    for k, name in enumerate(STIFF_OUTPUTS):
        assert rel_err(coarse[:, k], ref[name][1:]) < 1e-4, name
        assert rel_err(fine[49::50, k], ref[name][1:]) < 1e-4, name
    assert c_fine["steps"] < c_coarse["steps"] + 1000, (c_fine, c_coarse)
    assert c_fine["lu"] < c_fine["steps"] / 5, c_fine


def test_steps_as_few_as_compiled_bdf(stiff_bdf_fmu, stiff_system, tmp_path):
    """The FMU's BDF takes about the steps of ``compiled_bdf`` (the same core) at the same
    error weights (rtol, atol = rtol / 100), although it stops at every communication
    point."""
    from bearingsim.simulation import simulate

    rtol = 1e-8
    _, c = run_cs(stiff_bdf_fmu, tmp_path, 0.01, 1.0, STIFF_OUTPUTS, rtol)
    res = simulate(stiff_system, 1.0, method="compiled_bdf", rtol=rtol, atol=rtol / 100,
                   n_points=101, progress=False)
    assert 0.5 < c["steps"] / res.stats["nsteps"] < 1.5, (c, res.stats)


def test_restored_state_continues_bit_for_bit(stiff_bdf_fmu, tmp_path):
    """The history and where its Jacobian and factorisation were made are in the FMU state:
    a run from a restored state repeats the first exactly, although the instance's cached
    Jacobian and LU moved on meanwhile."""
    fmu, _, vr = open_fmu(stiff_bdf_fmu, tmp_path)
    fmu.setupExperiment(tolerance=1e-8)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    refs = [vr[n] for n in STIFF_OUTPUTS]
    _steps(fmu, refs, 0.0, 3)
    state = fmu.getFMUstate()
    first = _steps(fmu, refs, 3 * H, 5)
    fmu.setFMUstate(state)
    np.testing.assert_array_equal(_steps(fmu, refs, 3 * H, 5), first)
    fmu.setFMUstate(fmu.deSerializeFMUstate(fmu.serializeFMUstate(state)))
    np.testing.assert_array_equal(_steps(fmu, refs, 3 * H, 5), first)
    fmu.freeFMUstate(state)
    fmu.terminate()
    fmu.freeInstance()


CHILD = """
import sys
import numpy as np
from tests.fmu.helpers import open_fmu
from tests.fmu.test_fmu_bdf_stepper import _steps, STIFF_OUTPUTS, H

fmu, _, vr = open_fmu(sys.argv[1], sys.argv[2])
fmu.setupExperiment(tolerance=1e-8)
fmu.enterInitializationMode()
fmu.exitInitializationMode()
refs = [vr[n] for n in STIFF_OUTPUTS]
_steps(fmu, refs, 0.0, 3)
state = fmu.getFMUstate()
open(sys.argv[3], "wb").write(bytes(fmu.serializeFMUstate(state)))
np.save(sys.argv[4], _steps(fmu, refs, 3 * H, 5))
"""


def test_serialized_state_continues_in_another_process(stiff_bdf_fmu, tmp_path):
    """A state serialized in one process and restored in another continues bit for bit."""
    blob, expected = tmp_path / "state.bin", tmp_path / "expected.npy"
    subprocess.run([sys.executable, "-c", textwrap.dedent(CHILD), str(stiff_bdf_fmu),
                    str(tmp_path / "child"), str(blob), str(expected)], check=True)
    fmu, _, vr = open_fmu(stiff_bdf_fmu, tmp_path / "parent")
    fmu.setupExperiment(tolerance=1e-8)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    refs = [vr[n] for n in STIFF_OUTPUTS]
    fmu.setFMUstate(fmu.deSerializeFMUstate(blob.read_bytes()))
    np.testing.assert_array_equal(_steps(fmu, refs, 3 * H, 5), np.load(expected))
    fmu.terminate()
    fmu.freeInstance()


def test_input_jump_restarts_the_history(stiff_bdf_fmu, stiff_system, tmp_path):
    """Doubling the torque at 0.5 s (a jump the history's differences know nothing of)
    restarts the stepper there: the run continues exactly as a fresh FMU started at 0.5 s
    from the state reached, and agrees with simulate."""
    names = [s.name for s in stiff_system.states]
    fmu, _, vr = open_fmu(stiff_bdf_fmu, tmp_path / "jumped")
    fmu.setupExperiment(tolerance=1e-8)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    refs = [vr[n] for n in STIFF_OUTPUTS]
    _steps(fmu, refs, 0.0, 10)
    x = fmu.getReal([vr[n] for n in names])
    fmu.setReal([vr["tau"]], [2.0])
    jumped = _steps(fmu, refs, 10 * H, 10)
    fmu.terminate()
    fmu.freeInstance()
    fresh_fmu, _, _ = open_fmu(stiff_bdf_fmu, tmp_path / "fresh")
    fresh_fmu.setupExperiment(tolerance=1e-8, startTime=10 * H)
    fresh_fmu.enterInitializationMode()
    fresh_fmu.setReal([vr[n] for n in names], x)
    fresh_fmu.setReal([vr["tau"]], [2.0])
    fresh_fmu.exitInitializationMode()
    np.testing.assert_array_equal(jumped, _steps(fresh_fmu, refs, 10 * H, 10))
    fresh_fmu.terminate()
    fresh_fmu.freeInstance()
    ref = reference(stiff_system, 0.5, H, inputs={"tau": 2.0},
                    x0=dict(zip(names, x, strict=True)))
    for k, name in enumerate(STIFF_OUTPUTS):
        assert rel_err(jumped[:, k], ref[name][1:]) < 1e-4, name


def test_auto_takes_bdf_for_many_states():
    assert resolve_stepper("auto", BDF_MIN_STATES) == "bdf"
    assert resolve_stepper("auto", BDF_MIN_STATES - 1) == "ros34pw2"
    assert resolve_stepper("rodas3", 500) == "rodas3"
