"""More model classes through the FMU: a nonlinear algebraic loop (CasADi MX with a Newton
rootfinder in the generated C) and the motor drives with the torque-level double-layer bearing."""

from __future__ import annotations

import pytest
from fmpy.validation import validate_fmu

from bearingsim.assembler import assemble
from bearingsim.assemblies.motor_drive import motor_drive
from bearingsim.fmu import export_fmu
from tests.fmu.fmu_models import ImplicitDecay
from tests.fmu.helpers import reference, rel_err, run_fmu

DRIVE_OUTPUTS = ["shaft.w", "bearing.middle.sleeve.w", "bearing.middle.sleeve.flange_a.tau"]


@pytest.fixture(scope="module")
def implicit(fmu_dir):
    system = assemble(ImplicitDecay(), outputs=["x", "z"])
    assert not system.functions["ode"].is_a("SXFunction")
    return system, export_fmu(system, fmu_dir / "implicit.fmu")


@pytest.mark.parametrize("kind", ["ModelExchange", "CoSimulation"])
def test_nonlinear_loop_model(kind, implicit):
    system, path = implicit
    assert validate_fmu(str(path)) == []
    ref = reference(system, 2.0, 0.02, parameters={"k": 3.0})
    res = run_fmu(path, kind, 2.0, 0.02, ["x", "z"], start_values={"k": 3.0})
    for name in ("x", "z"):
        assert rel_err(res[name], ref[name]) < 1e-6, name
    z = res["z"]
    assert abs(z + z**3 - res["x"]).max() < 1e-10


@pytest.mark.parametrize("motor", ["dc", "pmsm"])
def test_motor_drive_with_double_layer_bearing(motor, fmu_dir):
    system = assemble(motor_drive(motor=motor, speed_ref=None), outputs=DRIVE_OUTPUTS)
    path = export_fmu(system, fmu_dir / f"{motor}_drive.fmu")
    assert validate_fmu(str(path)) == []
    inputs = {"motor.w_ref": 100.0, "bearing.Fr": 500.0}
    ref = reference(system, 1.0, 0.01, inputs=inputs)
    for kind in ("ModelExchange", "CoSimulation"):
        res = run_fmu(path, kind, 1.0, 0.01, DRIVE_OUTPUTS, start_values=inputs)
        for name in DRIVE_OUTPUTS:
            assert rel_err(res[name], ref[name]) < 1e-6, (kind, name)
    assert ref["shaft.w"][-1] == pytest.approx(100.0, rel=0.05)
