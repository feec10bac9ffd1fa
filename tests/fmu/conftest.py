"""FMUs built once per test session."""

from __future__ import annotations

import casadi as ca
import pytest

from bearingsim.assembler import assemble
from bearingsim.fmu import export_fmu
from tests.fmu.fmu_models import DrivenInertia, SpeedDrivenLoad, StiffChain
from tests.models import TwoInertiaDrive

DRIVE_OUTPUTS = ["j2.w", "sd.tau", "j1.phi"]
DRIVEN_OUTPUTS = ["rotor.w", "friction.tau"]
STIFF_OUTPUTS = ["load.phi", "load.w", "link[0].tau", "coupling.tau"]


@pytest.fixture(scope="session")
def fmu_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("fmus")


@pytest.fixture(scope="session")
def drive_system():
    return assemble(TwoInertiaDrive(), outputs=DRIVE_OUTPUTS)


@pytest.fixture(scope="session")
def drive_fmu(fmu_dir, drive_system):
    return export_fmu(drive_system, fmu_dir / "drive.fmu")


@pytest.fixture(scope="session")
def driven_system():
    return assemble(DrivenInertia(), outputs=DRIVEN_OUTPUTS)


@pytest.fixture(scope="session")
def driven_fmu(fmu_dir, driven_system):
    return export_fmu(driven_system, fmu_dir / "driven.fmu")


@pytest.fixture(scope="session")
def load_fmu(fmu_dir):
    return export_fmu(SpeedDrivenLoad(), fmu_dir / "load.fmu", outputs=["sensor.tau"])


@pytest.fixture(scope="session")
def stiff_system():
    return assemble(StiffChain(), outputs=STIFF_OUTPUTS)


@pytest.fixture(scope="session")
def stiff_fmu(fmu_dir, stiff_system):
    return export_fmu(stiff_system, fmu_dir / "stiff.fmu", kinds=("CS",))


def cosim_ramp(t):
    """Speed reference of the motor/bearing co-simulation tests: 0 -> 100 rad/s in 0.1 s."""
    return 100.0 * ca.fmin(t / 0.1, 1.0)


COSIM_FR = 500.0
"""Radial load of the bearing in the co-simulation tests [N]."""


@pytest.fixture(scope="session")
def cosim_pair(fmu_dir):
    """``cosim_pair(motor, fmi_version="2.0")``: motor FMU, bearing FMU (and SSP for FMI 2.0)
    with the ramp reference, exported once per session."""
    from bearingsim.studies.motor_bearing_cosim import export_motor_bearing

    cache = {}

    def get(motor: str, fmi_version: str = "2.0"):
        key = (motor, fmi_version)
        if key not in cache:
            cache[key] = export_motor_bearing(
                fmu_dir / f"cosim_{motor}_{fmi_version}", motor=motor, speed_ref=cosim_ramp,
                Fr=COSIM_FR, fmi_version=fmi_version, ssp=fmi_version == "2.0")
        return cache[key]

    return get
