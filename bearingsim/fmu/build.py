"""Compiling the FMU's C sources (a Linux binary that loads on glibc 2.17 and later, and opt-in
cross-built binaries), describing how to rebuild them, and zipping the archive.

The compiler runs through bearingsim's one driver,
:func:`bearingsim.simulation.c_compiler.compile_units`; what is particular to an FMU is passed to
it as flags (the forced include that pins glibc symbols, hidden visibility, C99) or as the
compiler (zig's for a cross target). Failures raise
:class:`~bearingsim.simulation.c_compiler.CompileError`.
"""

from __future__ import annotations

import shutil
import struct
import xml.etree.ElementTree as ET
import zipfile
from importlib import resources
from pathlib import Path

from bearingsim.files import atomic_path
from bearingsim.simulation.c_compiler import CompileError, compile_units

__all__ = ["BINARY_PLATFORMS", "CROSS_PLATFORMS", "GLIBC_BASELINE",
           "TEMPLATE_OPTIMISATION",
           "LU_FILES", "RUNTIME_FILES", "TEMPLATE_FILES", "build_description_xml",
           "compile_shared_library", "copy_templates", "cross_compile_shared_library",
           "fmi_header_dir", "glibc_versions",
           "write_archive"]

RUNTIME_FILES = ("bsm_model.h", "bsm_eval.c", "bsm_solver.c")
"""The FMI-independent runtime of the C template, shared by every exported FMU."""

LU_FILES = ("bsm_lu.h", "bsm_lu.c", "bsm_bdf.h", "bsm_bdf.c")
"""The runtime's sparse LU and BDF stepping core, shared with the compiled BDF integrator
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


def fmi_header_dir() -> Path:
    """Folder of the FMI headers shipped with fmpy (``fmpy/c-code``).

    Returns
    -------
    Path
        The folder.
    """
    import fmpy

    return Path(fmpy.__file__).parent / "c-code"


def copy_templates(directory: Path, fmi_version: str = "2.0") -> list[str]:
    """Copy the generic C template (runtime, its LU and the API layer of ``fmi_version``) and
    the FMI headers into ``directory``.

    Parameters
    ----------
    directory : Path
        The FMU's ``sources`` folder.
    fmi_version : {"2.0", "3.0"}
        FMI version of the API layer.

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


GLIBC_BASELINE = (2, 17)
"""Oldest glibc the Linux x86-64 binaries load on (the manylinux2014 / RHEL 7 baseline)."""

GLIBC_PIN_HEADER = "glibc_2_17.h"
"""Template header force-included (``-include``) into every file of the shipped Linux binary:
pins the libm symbols that glibc 2.29 versioned anew to their original version."""

TEMPLATE_OPTIMISATION = "-O3"
"""Optimisation of the template runtime (of the generated model functions:
:data:`bearingsim.fmu.codegen.OPTIMISATION`). -O3, as for the compiled BDF of ``simulate``
(:data:`bearingsim.simulation.compiled_bdf.FLAGS`): the steppers' loops over the states
vectorise, which -O2 leaves scalar (6304 ball-level CS FMU, bdf stepper: 0.85-0.90x of -O2's
CPU per step in ``bench/fmu_stepper.py`` runs side by side); the files are small, so the export
time hardly changes; no -march, so the binary runs on any x86-64."""


CROSS_PLATFORMS = {
    "linux-aarch64": ("aarch64-linux-gnu.2.17", {"3.0": "aarch64-linux"}, ".so"),
    "darwin-x86_64": ("x86_64-macos", {"2.0": "darwin64", "3.0": "x86_64-darwin"}, ".dylib"),
    "darwin-aarch64": ("aarch64-macos", {"3.0": "aarch64-darwin"}, ".dylib"),
    "windows-x86_64": ("x86_64-windows-gnu", {"2.0": "win64", "3.0": "x86_64-windows"}, ".dll"),
}
"""Opt-in cross-built binaries (``export_fmu(platforms=...)``): zig's C compiler target, the
``binaries/`` folder per FMI version (FMI 2.0 names no aarch64 platform) and the library
extension. Built with ``python -m ziglang cc`` (the ``ziglang`` wheel, extra ``fmu-cross``);
none of them is loaded or run on the build machine: they are untested."""


def cross_compile_shared_library(sources: list[tuple[Path, str]], output: Path, include: Path,
                                 platform_name: str) -> None:
    """Cross-compile the sources for one of :data:`CROSS_PLATFORMS` with zig's C compiler.

    Parameters
    ----------
    sources : list of (pathlib.Path, str)
        The ``.c`` files and the optimisation flag of each.
    output : pathlib.Path
        The library to write.
    include : pathlib.Path
        Folder with the headers.
    platform_name : str
        A key of :data:`CROSS_PLATFORMS`.

    Raises
    ------
    CompileError
        If the ``ziglang`` package is missing or the compiler fails.
    """
    import importlib.util
    import sys

    if importlib.util.find_spec("ziglang") is None:
        raise CompileError(f"cross-building for {platform_name} needs zig's C compiler: "
                           "pip install ziglang (or bearingsim[fmu-cross])")
    target = CROSS_PLATFORMS[platform_name][0]
    compile_units([(source, [optimisation]) for source, optimisation in sources], output,
                  compiler=[sys.executable, "-m", "ziglang", "cc", "-target", target],
                  flags=_fmu_flags(include), pic=not target.startswith("x86_64-windows"),
                  what=f"the FMU for {platform_name}")


def compile_shared_library(sources: list[tuple[Path, str]], output: Path, include: Path) -> None:
    """Compile C sources, each with its own flags and in parallel, into a shared library that
    loads on glibc 2.17 and later.

    Parameters
    ----------
    sources : list of (pathlib.Path, str)
        The ``.c`` files and the optimisation flag of each.
    output : pathlib.Path
        The ``.so`` to write.
    include : pathlib.Path
        Folder with the headers.

    Raises
    ------
    CompileError
        If no C compiler is found, with the compiler's messages, or if the library needs a
        glibc symbol version newer than :data:`GLIBC_BASELINE`.
    """
    pin = resources.files("bearingsim.fmu") / "templates" / GLIBC_PIN_HEADER
    compile_units([(source, [optimisation]) for source, optimisation in sources], output,
                  flags=[*_fmu_flags(include), "-include", str(pin)],
                  link_flags=["-Wl,-Bsymbolic"], what="the FMU")
    too_new = {sym: v for sym, v in glibc_versions(output).items() if v > GLIBC_BASELINE}
    if too_new:
        found = ", ".join(f"{sym}@GLIBC_{'.'.join(map(str, v))}"
                          for sym, v in sorted(too_new.items()))
        raise CompileError(
            f"the FMU binary needs glibc symbols newer than "
            f"{'.'.join(map(str, GLIBC_BASELINE))}: {found}; pin them in "
            f"bearingsim/fmu/templates/{GLIBC_PIN_HEADER}")


def _fmu_flags(include: Path) -> list[str]:
    """Flags of every file of an FMU binary: C99, only the FMI functions exported (the model
    functions stay inside the library), the headers in ``include``."""
    return ["-std=c99", "-fvisibility=hidden", "-DCASADI_SYMBOL_EXPORT=", f"-I{include}"]


def glibc_versions(library: Path) -> dict[str, tuple[int, ...]]:
    """The glibc version each imported symbol of an ELF64 little-endian shared library is bound
    to, read from its ``.dynsym``, ``.gnu.version`` and ``.gnu.version_r`` sections (what
    ``objdump -T`` prints as ``(GLIBC_2.29) pow``).

    Parameters
    ----------
    library : pathlib.Path
        The shared library.

    Returns
    -------
    dict of str to tuple of int
        Symbol name -> version, e.g. ``{"pow": (2, 2, 5)}``; symbols of other libraries or
        without a ``GLIBC_`` version are left out.
    """
    data = Path(library).read_bytes()
    if data[:4] != b"\x7fELF" or data[4] != 2 or data[5] != 1:
        raise CompileError(f"{library} is not an ELF64 little-endian file")
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum = struct.unpack_from("<HH", data, 0x3A)
    sections = [struct.unpack_from("<IIQQQQIIQQ", data, shoff + k * shentsize)
                for k in range(shnum)]
    by_type = {sh[1]: sh for sh in sections}

    def string(table: int, offset: int) -> str:
        start = sections[table][4] + offset
        return data[start:data.index(b"\0", start)].decode()

    names: dict[int, str] = {}  # version index -> version name
    verneed = by_type.get(_SHT_GNU_VERNEED)
    if verneed is not None:
        pos = verneed[4]
        for _ in range(verneed[7]):
            _, count, _, aux, nxt = struct.unpack_from("<HHIII", data, pos)
            apos = pos + aux
            for _ in range(count):
                _, _, other, name, anext = struct.unpack_from("<IHHII", data, apos)
                names[other] = string(verneed[6], name)
                apos += anext
            pos += nxt
    dynsym, versym = by_type.get(_SHT_DYNSYM), by_type.get(_SHT_GNU_VERSYM)
    if dynsym is None or versym is None:
        return {}
    out = {}
    for k in range(dynsym[5] // 24):
        name, _, _, shndx, _, _ = struct.unpack_from("<IBBHQQ", data, dynsym[4] + 24 * k)
        version = names.get(struct.unpack_from("<H", data, versym[4] + 2 * k)[0] & 0x7FFF, "")
        if shndx == 0 and version.startswith("GLIBC_"):
            out[string(dynsym[6], name)] = tuple(int(v) for v in version[6:].split("."))
    return out


_SHT_DYNSYM, _SHT_GNU_VERNEED, _SHT_GNU_VERSYM = 11, 0x6FFFFFFE, 0x6FFFFFFF


def build_description_xml(model_identifier: str, c_files: list[str]) -> str:
    """``sources/buildDescription.xml`` of an FMI 3.0 source FMU: one C99 file set and libm.

    Parameters
    ----------
    model_identifier : str
        The library name.
    c_files : list of str
        The ``.c`` files under ``sources/``.

    Returns
    -------
    str
        The XML document.
    """
    root = ET.Element("fmiBuildDescription", fmiVersion="3.0")
    config = ET.SubElement(root, "BuildConfiguration", modelIdentifier=model_identifier)
    files = ET.SubElement(config, "SourceFileSet", language="C99")
    for name in c_files:
        ET.SubElement(files, "SourceFile", name=name)
    ET.SubElement(files, "PreprocessorDefinition", name="CASADI_SYMBOL_EXPORT", value="",
                  description="the model functions stay inside the library")
    ET.SubElement(config, "Library", name="m", description="the C math library (POSIX)")
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode")


def write_archive(path: Path, model_description: str, binaries: dict[str, Path],
                  sources: list[Path]) -> Path:
    """Zip the model description, binary and sources into an ``.fmu``.

    Parameters
    ----------
    path : pathlib.Path
        The ``.fmu`` file to write (replaced if it exists).
    model_description : str
        The XML text.
    binaries : dict of str to pathlib.Path
        Path inside the archive (e.g. ``"binaries/linux64/model.so"``) -> compiled library.
    sources : list of pathlib.Path
        Files stored under ``sources/``.

    Returns
    -------
    pathlib.Path
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp, zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("modelDescription.xml", model_description)
        for name, binary in binaries.items():
            z.write(binary, name)
        for src in sources:
            z.write(src, f"sources/{src.name}")
    return path
