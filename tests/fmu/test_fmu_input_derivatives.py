"""FMI 2.0 input derivatives of order 1 to 3 (``fmi2SetRealInputDerivatives``): over a
co-simulation step each input follows the polynomial u0 + u' t + u'' t^2 / 2 + u''' t^3 / 6 of
the derivatives set at the step start, for every stepper; a cubic input is then exact at a
coarse communication step, where its first derivative alone is not."""

from __future__ import annotations

import pytest
from fmpy.fmi1 import FMICallException

from bearingsim.fmu import export_fmu
from bearingsim.simulation import simulate
from tests.fmu.conftest import DRIVEN_OUTPUTS
from tests.fmu.helpers import LogCapture, open_fmu, rel_err

H = 0.25
T_END = 2.0
COEFFICIENTS = (1.0, 2.0, -1.5, 0.4)
"""tau_drive(t) = 1 + 2 t - 1.5 t^2 + 0.4 t^3 [N m]."""


def tau(t: float, order: int = 0) -> float:
    """The input's derivative of ``order`` at t."""
    c = COEFFICIENTS
    return [c[0] + t * (c[1] + t * (c[2] + t * c[3])),
            c[1] + t * (2 * c[2] + t * 3 * c[3]),
            2 * c[2] + 6 * c[3] * t,
            6 * c[3]][order]


@pytest.fixture(scope="module", params=["ros34pw2", "rodas3", "bdf"])
def driven_cs(request, fmu_dir):
    from tests.fmu.fmu_models import DrivenInertia

    return export_fmu(DrivenInertia(), fmu_dir / f"driven_{request.param}.fmu",
                      outputs=DRIVEN_OUTPUTS, kinds=("CS",), stepper=request.param)


def drive(path, tmp_path, orders):
    """rotor.w at the communication points, tau_drive given by its value and the derivatives
    of ``orders`` at each step start."""
    fmu, _, vr = open_fmu(path, tmp_path)
    fmu.setupExperiment(tolerance=1e-10)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    out = []
    for k in range(round(T_END / H)):
        t = k * H
        fmu.setReal([vr["tau_drive"]], [tau(t)])
        fmu.setRealInputDerivatives([vr["tau_drive"]] * len(orders), list(orders),
                                    [tau(t, n) for n in orders])
        fmu.doStep(t, H)
        out.append(fmu.getReal([vr["rotor.w"]])[0])
    fmu.terminate()
    fmu.freeInstance()
    return out


def test_a_cubic_input_is_exact_with_three_derivatives(driven_cs, driven_system, tmp_path):
    ref = simulate(driven_system, T_END, inputs={"tau_drive": tau}, n_points=9, rtol=1e-11,
                   atol=1e-13, progress=False)["rotor.w"][1:]
    assert rel_err(drive(driven_cs, tmp_path, (1, 2, 3)), ref) < 1e-7
    assert rel_err(drive(driven_cs, tmp_path, (1,)), ref) > 1e-3


@pytest.mark.parametrize("order", [0, 4])
def test_other_orders_are_refused(driven_fmu, tmp_path, order):
    log = LogCapture()
    fmu, _, vr = open_fmu(driven_fmu, tmp_path, log=log)
    fmu.setupExperiment()
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    with pytest.raises(FMICallException):
        fmu.setRealInputDerivatives([vr["tau_drive"]], [order], [1.0])
    assert (f"derivatives of order 1 to 3 of inputs only (got vr {vr['tau_drive']}, "
            f"order {order})") in log.text()
    fmu.freeInstance()
