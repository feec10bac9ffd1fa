"""Portable FMUs: a Linux binary that loads on glibc 2.17, and sources an importer rebuilds."""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from bearingsim.fmu import export_fmu
from bearingsim.fmu.build import GLIBC_BASELINE, glibc_versions
from tests.fmu.conftest import DRIVE_OUTPUTS
from tests.fmu.helpers import run_fmu


def _binary(fmu, tmp_path):
    with zipfile.ZipFile(fmu) as z:
        name = next(n for n in z.namelist() if n.startswith("binaries/") and n.endswith(".so"))
        z.extract(name, tmp_path)
    return tmp_path / name


def test_binary_needs_no_glibc_above_2_17(drive_fmu, tmp_path):
    lib = _binary(drive_fmu, tmp_path)
    versions = glibc_versions(lib)
    # the runtime's step-size control calls pow, which glibc 2.29 versioned anew
    assert versions["pow"] == (2, 2, 5)
    assert max(versions.values()) <= GLIBC_BASELINE
    if shutil.which("objdump"):  # the same reading as binutils'
        out = subprocess.run(["objdump", "-T", str(lib)], capture_output=True, text=True,
                             check=True).stdout
        listed = {line.split()[-1]: line.split()[-2].strip("()") for line in out.splitlines()
                  if "(GLIBC_" in line and "*UND*" in line}
        assert listed == {s: "GLIBC_" + ".".join(map(str, v)) for s, v in versions.items()}


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
def test_glibc_reader_sees_an_unpinned_pow(tmp_path):
    """Without the pin, this glibc's pow is the 2.29 one; the reader must report it (on a glibc
    older than 2.29 there is no newer pow to pin and the case does not arise)."""
    import os

    glibc = os.confstr("CS_GNU_LIBC_VERSION").split()[-1]
    if tuple(int(v) for v in glibc.split(".")) < (2, 29):
        pytest.skip(f"glibc {glibc} has no pow@GLIBC_2.29")
    src = tmp_path / "p.c"
    src.write_text("#include <math.h>\ndouble f(double x, double y) { return pow(x, y); }\n")
    lib = tmp_path / "p.so"
    subprocess.run(["gcc", "-shared", "-fPIC", "-O2", str(src), "-o", str(lib), "-lm"],
                   check=True)
    assert glibc_versions(lib)["pow"] == (2, 29)


@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_source_fmu_describes_its_build(fmi_version, drive_system, fmu_dir):
    path = export_fmu(drive_system, fmu_dir / f"drive_src_{fmi_version}.fmu",
                      fmi_version=fmi_version)
    assert validate_fmu(str(path)) == []
    md = read_model_description(str(path))
    (config,) = md.buildConfigurations
    (files,) = config.sourceFileSets
    with zipfile.ZipFile(path) as z:
        shipped = {n[len("sources/"):] for n in z.namelist()
                   if n.startswith("sources/") and n.endswith(".c")}
    assert sorted(files.sourceFiles) == sorted(shipped)
    assert config.modelIdentifier == md.coSimulation.modelIdentifier


@pytest.mark.skipif(shutil.which("cmake") is None, reason="fmpy builds with cmake")
@pytest.mark.parametrize("fmi_version", ["2.0", "3.0"])
def test_fmpy_rebuilds_the_fmu_from_its_sources(fmi_version, drive_system, fmu_dir, tmp_path):
    """fmpy's ``build_platform_binary`` compiles the sources alone (its own CMake project, no
    flags of ours) into a binary whose results equal the shipped one's."""
    from fmpy.build import build_platform_binary

    path = export_fmu(drive_system, fmu_dir / f"drive_rebuild_{fmi_version}.fmu",
                      fmi_version=fmi_version)
    unzipped = tmp_path / "fmu"
    with zipfile.ZipFile(path) as z:
        z.extractall(unzipped)
    shutil.rmtree(unzipped / "binaries")
    (tmp_path / "build").mkdir()
    build_platform_binary(unzipped, build_dir=tmp_path / "build")
    assert list((unzipped / "binaries").rglob("*.so"))
    for kind in ("CoSimulation", "ModelExchange"):
        shipped = run_fmu(path, kind, 1.0, 0.01, DRIVE_OUTPUTS)
        rebuilt = run_fmu(unzipped, kind, 1.0, 0.01, DRIVE_OUTPUTS)
        for name in DRIVE_OUTPUTS:
            scale = np.max(np.abs(shipped[name]))
            assert np.max(np.abs(rebuilt[name] - shipped[name])) <= 1e-12 * scale, (kind, name)


@pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")
def test_build_description_alone_is_enough_to_rebuild(drive_system, fmu_dir, tmp_path):
    """Without CMake: compile exactly the files and definitions the FMI 3.0 build description
    names (nothing else of ours) with a plain gcc call; the rebuilt FMU runs like the shipped
    one."""
    path = export_fmu(drive_system, fmu_dir / "drive_plain_rebuild.fmu", fmi_version="3.0")
    unzipped = tmp_path / "fmu"
    with zipfile.ZipFile(path) as z:
        z.extractall(unzipped)
    md = read_model_description(str(path))
    (config,) = md.buildConfigurations
    (files,) = config.sourceFileSets
    binary = next((unzipped / "binaries").rglob("*.so"))
    binary.unlink()
    sources = unzipped / "sources"
    subprocess.run(["gcc", "-shared", "-fPIC", "-std=c99", "-O2", f"-I{sources}",
                    *[f"-D{d.name}={d.value or ''}" for d in files.preprocessorDefinitions],
                    *[str(sources / f) for f in files.sourceFiles], "-o", str(binary), "-lm"],
                   check=True)
    shipped = run_fmu(path, "CoSimulation", 1.0, 0.01, DRIVE_OUTPUTS)
    rebuilt = run_fmu(unzipped, "CoSimulation", 1.0, 0.01, DRIVE_OUTPUTS)
    for name in DRIVE_OUTPUTS:
        scale = np.max(np.abs(shipped[name]))
        assert np.max(np.abs(rebuilt[name] - shipped[name])) <= 1e-12 * scale, name


def test_cross_platform_not_offered_for_fmi2(drive_system, tmp_path):
    from bearingsim.errors import ParameterError

    with pytest.raises(ParameterError, match="linux-aarch64 not offered for FMI 2.0"):
        export_fmu(drive_system, tmp_path / "x.fmu", platforms=["linux-aarch64"])


@pytest.mark.skipif(importlib.util.find_spec("ziglang") is None, reason="needs pip ziglang")
def test_cross_built_binaries_are_libraries_of_their_platform(drive_system, fmu_dir):
    """Opt-in cross builds (untested: nothing here can load them): each is a shared library
    of its platform's format and machine that defines the FMI 3 functions."""
    path = export_fmu(drive_system, fmu_dir / "drive_cross.fmu", fmi_version="3.0",
                      platforms=["linux-aarch64", "darwin-aarch64"])
    assert validate_fmu(str(path)) == []
    with zipfile.ZipFile(path) as z:
        elf = z.read("binaries/aarch64-linux/drive.so")
        macho = z.read("binaries/aarch64-darwin/drive.dylib")
        assert "binaries/x86_64-linux/drive.so" in z.namelist()
    assert elf[:4] == b"\x7fELF" and int.from_bytes(elf[18:20], "little") == 183  # EM_AARCH64
    assert int.from_bytes(macho[:4], "little") == 0xFEEDFACF  # 64-bit Mach-O
    assert int.from_bytes(macho[4:8], "little") == 0x0100000C  # CPU_TYPE_ARM64
    assert int.from_bytes(macho[12:16], "little") == 6  # MH_DYLIB
    for binary in (elf, macho):
        assert b"fmi3DoStep" in binary and b"fmi3InstantiateCoSimulation" in binary
