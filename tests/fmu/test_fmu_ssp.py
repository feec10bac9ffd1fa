"""Two rotational FMUs coupled speed -> torque through an SSP file reproduce the monolithic
model (first-order convergence of the explicit coupling)."""

from __future__ import annotations

import numpy as np
import pytest
from fmpy.ssp.simulation import simulate_ssp
from fmpy.ssp.ssd import read_ssd

from bearingsim.assembler import assemble
from bearingsim.errors import ParameterError
from bearingsim.fmu import export_fmu, write_ssp
from bearingsim.simulation import simulate
from tests.fmu.fmu_models import CoupledDrive, DrivenInertia

CONNECTIONS = [("driven.rotor.w", "load.w_in"), ("load.sensor.tau", "driven.tau_load")]


@pytest.fixture(scope="module")
def ssp(fmu_dir, load_fmu):
    driven = export_fmu(DrivenInertia(), fmu_dir / "driven_2nm.fmu", outputs=["rotor.w"],
                        inputs={"tau_drive": 2.0}, kinds=("CS",))
    return write_ssp(fmu_dir / "drive.ssp", {"driven": driven, "load": load_fmu}, CONNECTIONS,
                     name="drive_train", stop_time=2.0)


def test_ssd_is_valid(ssp):
    ssd = read_ssd(str(ssp), validate=True)
    names = {e.name: {c.name: c.kind for c in e.connectors} for e in ssd.system.elements}
    assert names == {"driven": {"rotor.w": "output", "tau_load": "input"},
                     "load": {"w_in": "input", "sensor.tau": "output"}}
    assert len(ssd.system.connections) == 2


def test_coupled_fmus_match_the_monolithic_model(ssp):
    system = assemble(CoupledDrive(torque=2.0), outputs=["rotor.w"])
    ref = simulate(system, 2.0, n_points=201, rtol=1e-10, atol=1e-12, progress=False)
    errors = []
    for h in (2e-3, 1e-3):
        res = simulate_ssp(str(ssp), stop_time=2.0, step_size=h)
        # recorded values are the outputs at the end of each step
        t = res["time"] + h
        w = np.interp(ref.t[1:], t, res["driven.rotor.w"])
        errors.append(np.max(np.abs(w - ref["rotor.w"][1:])) / np.max(np.abs(ref["rotor.w"])))
    assert errors[1] < 5e-3
    assert 1.6 < errors[0] / errors[1] < 2.4  # first order in the communication step


def test_bad_connections(fmu_dir, load_fmu, drive_fmu):
    with pytest.raises(ParameterError, match="not an input"):
        write_ssp(fmu_dir / "x.ssp", {"a": drive_fmu, "b": load_fmu}, [("a.j2.w", "b.sensor.tau")])
    with pytest.raises(ParameterError, match="COMPONENT.VARIABLE"):
        write_ssp(fmu_dir / "x.ssp", {"a": drive_fmu}, [("c.x", "a.y")])
    with pytest.raises(ParameterError, match="not an output"):
        write_ssp(fmu_dir / "x.ssp", {"a": drive_fmu}, [], observe=["a.sd.c"])
