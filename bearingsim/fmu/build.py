"""Compiling the FMU's C sources with the system C compiler and zipping the archive."""

from __future__ import annotations

import os
import shutil
import subprocess
import zipfile
from importlib import resources
from pathlib import Path

from bearingsim.errors import BearingsimError
from bearingsim.files import atomic_path

__all__ = ["BINARY_PLATFORMS", "FmuBuildError", "LU_FILES", "RUNTIME_FILES", "TEMPLATE_FILES",
           "compile_shared_library", "copy_templates", "fmi_header_dir", "write_archive"]

RUNTIME_FILES = ("bsm_model.h", "bsm_eval.c", "bsm_solver.c")
"""The FMI-independent runtime of the C template, shared by every exported FMU."""

LU_FILES = ("bsm_lu.h", "bsm_lu.c")
"""The runtime's sparse LU, shared with the compiled BDF integrator
(``bearingsim/simulation/c``)."""

API_FILES = {"2.0": "fmi2_api.c", "3.0": "fmi3_api.c"}
"""The FMI API layer of the template, per FMI version."""

TEMPLATE_FILES = (*RUNTIME_FILES, API_FILES["2.0"])
"""The generic C template of an FMI 2.0 FMU."""

FMI_HEADERS = {
    "2.0": ("fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h"),
    "3.0": ("fmi3Functions.h", "fmi3FunctionTypes.h", "fmi3PlatformTypes.h"),
}
"""FMI headers (from fmpy) per FMI version."""

BINARY_PLATFORMS = {"2.0": "linux64", "3.0": "x86_64-linux"}
"""Folder of the shared library under ``binaries/`` per FMI version."""


class FmuBuildError(BearingsimError):
    """The C compiler is missing or failed."""


def fmi_header_dir() -> Path:
    """Folder of the FMI headers shipped with fmpy (``fmpy/c-code``)."""
    import fmpy

    return Path(fmpy.__file__).parent / "c-code"


def copy_templates(directory: Path, fmi_version: str = "2.0") -> list[str]:
    """Copy the generic C template (runtime, its LU and the API layer of ``fmi_version``) and
    the FMI headers into ``directory``.

    Returns
    -------
    list of str
        The copied file names.
    """
    templates = resources.files("bearingsim.fmu") / "templates"
    shared = resources.files("bearingsim.simulation") / "c"
    files = (*RUNTIME_FILES, API_FILES[fmi_version])
    for name in files:
        (directory / name).write_text((templates / name).read_text())
    for name in LU_FILES:
        (directory / name).write_text((shared / name).read_text())
    for name in FMI_HEADERS[fmi_version]:
        shutil.copyfile(fmi_header_dir() / name, directory / name)
    return [*files, *LU_FILES, *FMI_HEADERS[fmi_version]]


def compile_shared_library(sources: list[Path], output: Path, include: Path,
                           optimize: str = "-O2") -> None:
    """Compile C sources into a shared library.

    Parameters
    ----------
    sources : list of pathlib.Path
        The ``.c`` files.
    output : pathlib.Path
        The ``.so`` to write.
    include : pathlib.Path
        Folder with the headers.
    optimize : str
        Optimisation flag for the compiler.

    Raises
    ------
    FmuBuildError
        With the compiler's messages.
    """
    cc = os.environ.get("CC", "gcc")
    if shutil.which(cc) is None:
        raise FmuBuildError(f"C compiler {cc!r} not found; install gcc or set CC")
    cmd = [
        cc, "-shared", "-fPIC", optimize, "-std=c99", "-fvisibility=hidden",
        "-Wl,-Bsymbolic", "-DCASADI_SYMBOL_EXPORT=", f"-I{include}",
        *[str(s) for s in sources], "-o", str(output), "-lm",
    ]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise FmuBuildError(
            f"compiling the FMU failed ({' '.join(cmd)}):\n{proc.stderr[-4000:]}"
        )


def write_archive(path: Path, model_description: str, binary: Path, platform: str,
                  model_identifier: str, sources: list[Path]) -> Path:
    """Zip the model description, binary and sources into an ``.fmu``.

    Parameters
    ----------
    path : pathlib.Path
        The ``.fmu`` file to write (replaced if it exists).
    model_description : str
        The XML text.
    binary : pathlib.Path
        The compiled shared library.
    platform : str
        Binary folder name, e.g. ``"linux64"`` (FMI 2.0) or ``"x86_64-linux"`` (FMI 3.0).
    model_identifier : str
        Library name without extension.
    sources : list of pathlib.Path
        Files stored under ``sources/``.

    Returns
    -------
    pathlib.Path
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp, zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("modelDescription.xml", model_description)
        z.write(binary, f"binaries/{platform}/{model_identifier}.so")
        for src in sources:
            z.write(src, f"sources/{src.name}")
    return path
