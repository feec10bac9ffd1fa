"""A very stiff chain (eigenvalues near -1e5 1/s) through CS doStep with communication steps
thousands of times longer than an explicit method's stability limit."""

from __future__ import annotations

import time

import numpy as np

from tests.fmu.conftest import STIFF_OUTPUTS
from tests.fmu.helpers import LogCapture, open_fmu, reference, rel_err


def test_stiff_chain_large_communication_steps(stiff_fmu, stiff_system, tmp_path):
    eig = np.linalg.eigvals(np.array(stiff_system.functions["jac_x"](
        0.0, stiff_system.x0(), stiff_system.u_default(), stiff_system.p0())))
    assert np.max(np.abs(eig)) > 1e5  # explicit methods need steps below ~1e-5 s
    h, t_end = 0.05, 1.0
    log = LogCapture()
    fmu, _, vr = open_fmu(stiff_fmu, tmp_path, log=log, logging_on=True)
    fmu.setupExperiment(tolerance=1e-8)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    refs = [vr[n] for n in STIFF_OUTPUTS]
    out, t = [], 0.0
    wall = time.perf_counter()
    for _ in range(int(round(t_end / h))):
        fmu.doStep(t, h)
        t += h
        out.append(fmu.getReal(refs))
    wall = time.perf_counter() - wall
    fmu.terminate()
    fmu.freeInstance()
    out = np.array(out)
    assert np.all(np.isfinite(out))
    ref = reference(stiff_system, t_end, h)
    for k, name in enumerate(STIFF_OUTPUTS):
        assert rel_err(out[:, k], ref[name][1:]) < 1e-4, name
    steps = int(log.text().split("after ")[-1].split(" internal")[0])
    assert steps < 5000  # versus ~1e5 for an explicit method
    assert wall < 1.0
