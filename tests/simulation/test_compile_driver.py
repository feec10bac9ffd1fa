"""The one C compiler driver (:mod:`bearingsim.simulation.c_compiler`): files with their own
flags compiled in parallel and linked; failures and a missing compiler as ``CompileError``,
from the cached kernels and from the FMU export alike."""

from __future__ import annotations

import ctypes
import os
import stat

import pytest

from bearingsim.fmu import export_fmu
from bearingsim.simulation.c_compiler import CompileError, compile_units
from bearingsim.simulation.compile import compile_source
from tests.fmu.fmu_models import DrivenInertia


def test_units_with_their_own_flags_are_linked_into_one_library(tmp_path):
    (tmp_path / "scale.c").write_text("double scale(double x) { return FACTOR * x; }\n")
    (tmp_path / "twice.c").write_text(
        "double scale(double x);\ndouble twice_scaled(double x) { return 2.0 * scale(x); }\n")
    lib = compile_units([(tmp_path / "scale.c", ["-O0", "-DFACTOR=3.0"]),
                         (tmp_path / "twice.c", ["-O2"])], tmp_path / "libt.so",
                        flags=["-std=c99"])
    f = ctypes.CDLL(str(lib)).twice_scaled
    f.restype, f.argtypes = ctypes.c_double, [ctypes.c_double]
    assert f(1.5) == 9.0


def test_compiler_messages_are_reported(tmp_path):
    (tmp_path / "bad.c").write_text("int f(void) { return undefined_name; }\n")
    with pytest.raises(CompileError,
                       match=r"(?s)compiling the test unit failed \(.*bad\.c.*undefined_name"):
        compile_units([(tmp_path / "bad.c", [])], tmp_path / "libbad.so", what="the test unit")
    with pytest.raises(CompileError, match="undefined_name"):
        compile_source("int f(void) { return undefined_name; }\n", tmp_path / "libc.so")


@pytest.fixture
def no_compiler(tmp_path, monkeypatch):
    """A PATH without gcc or cc."""
    empty = tmp_path / "empty_bin"
    empty.mkdir()
    monkeypatch.setenv("PATH", str(empty))
    monkeypatch.delenv("CC", raising=False)


def test_a_missing_compiler_is_one_error_for_kernels_and_fmus(tmp_path, no_compiler):
    with pytest.raises(CompileError, match="no C compiler"):
        compile_source("int f(void) { return 0; }\n", tmp_path / "lib.so")
    with pytest.raises(CompileError, match="no C compiler"):
        export_fmu(DrivenInertia(), tmp_path / "d.fmu", outputs=["rotor.w"])


def test_the_fmu_export_reports_a_failing_compiler(tmp_path, monkeypatch):
    """``$CC`` names the compiler of the FMU binary as of the cached kernels; its messages
    reach the error."""
    fake = tmp_path / "failing-cc"
    fake.write_text("#!/bin/sh\necho 'fake compiler: no thanks' >&2\nexit 1\n")
    fake.chmod(fake.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setenv("CC", str(fake))
    assert os.access(fake, os.X_OK)
    with pytest.raises(CompileError, match=r"(?s)compiling the FMU failed \(.*failing-cc.*"
                                           r"-include .*glibc_2_17\.h.*no thanks"):
        export_fmu(DrivenInertia(), tmp_path / "d.fmu", outputs=["rotor.w"])
