"""The FMU runs in a plain C program (dlopen, no Python, empty environment)."""

from __future__ import annotations

import shutil
import subprocess
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description

from bearingsim.fmu.build import fmi_header_dir
from tests.fmu.helpers import reference, rel_err

HOST_SOURCE = Path(__file__).with_name("host.c")


@pytest.fixture(scope="module")
def host(tmp_path_factory):
    if shutil.which("gcc") is None:
        pytest.skip("gcc not available")
    exe = tmp_path_factory.mktemp("host") / "host"
    subprocess.run(["gcc", "-std=c99", "-D_DEFAULT_SOURCE", f"-I{fmi_header_dir()}",
                    str(HOST_SOURCE), "-o", str(exe), "-ldl"], check=True)
    return exe


def _run(host, fmu, tmp_path, t_end, h, outputs, sets=()):
    with zipfile.ZipFile(fmu) as z:
        z.extractall(tmp_path)
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    lib = tmp_path / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so"
    args = [str(host), str(lib), md.guid, str(t_end), str(h),
            ",".join(str(vr[n]) for n in outputs), *[f"{vr[n]}={v!r}" for n, v in sets]]
    return subprocess.run(args, capture_output=True, text=True, env={}, check=False)


def test_c_host_reproduces_python(host, driven_fmu, driven_system, tmp_path):
    sets = [("rotor.J", 0.2), ("tau_drive", 1.5), ("tau_load", 0.3)]
    proc = _run(host, driven_fmu, tmp_path, 2.0, 0.01, ["rotor.w", "friction.tau"], sets)
    assert proc.returncode == 0, proc.stderr
    data = np.loadtxt(proc.stdout.splitlines())
    ref = reference(driven_system, 2.0, 0.01, parameters={"rotor.J": 0.2},
                    inputs={"tau_drive": 1.5, "tau_load": 0.3})
    np.testing.assert_allclose(data[:, 0], ref.t[1:], atol=1e-9)
    assert rel_err(data[:, 1], ref["rotor.w"][1:]) < 1e-6
    assert rel_err(data[:, 2], ref["friction.tau"][1:]) < 1e-6


def test_c_host_sees_logged_errors(host, drive_fmu, tmp_path):
    proc = _run(host, drive_fmu, tmp_path, 1.0, 0.1, ["j2.w"], [("sd.c", 0.0)])
    assert proc.returncode == 3
    assert "[logStatusError] host (status 3): parameter sd.c = 0 [N.m/rad] is outside its " \
           "valid range (0, inf); value not set" in proc.stderr
