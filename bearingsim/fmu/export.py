"""``export_fmu``: from an assembly or an assembled system to an ``.fmu`` archive."""

from __future__ import annotations

import logging
import platform
import re
import tempfile
import uuid
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from bearingsim.assembler import System, assemble_cached
from bearingsim.checks import check_output_file
from bearingsim.errors import ParameterError
from bearingsim.fmu.build import (
    BINARY_PLATFORMS,
    CROSS_PLATFORMS,
    TEMPLATE_OPTIMISATION,
    build_description_xml,
    compile_shared_library,
    copy_templates,
    cross_compile_shared_library,
    write_archive,
)
from bearingsim.fmu.codegen import fmu_functions, generate_c
from bearingsim.fmu.interface import build_interface
from bearingsim.fmu.model_c import STEPPERS, resolve_stepper, write_model_c
from bearingsim.fmu.model_description import model_description_xml
from bearingsim.fmu.nominal import state_nominals
from bearingsim.fmu.units import derivative_unit
from bearingsim.language import Component
from bearingsim.simulation.input_ranges import check_input_value
from bearingsim.simulation.ordering import newton_pattern

__all__ = ["FMI_VERSIONS", "export_fmu"]

log = logging.getLogger("bearingsim.fmu")

FMI_VERSIONS = ("2.0", "3.0")
"""FMI versions ``export_fmu`` can write."""

KINDS = ("ME", "CS")


def _identifier(name: str) -> str:
    ident = re.sub(r"\W", "_", name)
    return ident if re.match(r"[A-Za-z_]", ident) else f"m_{ident}"


def _system(model, outputs):
    if isinstance(model, System):
        if model.rootfinder not in (None, "fast_newton"):
            raise ParameterError(
                f"export_fmu: the nonlinear blocks of {model.name!r} use CasADi's "
                f"{model.rootfinder!r} rootfinder, which generates no C code; assemble with "
                "rootfinder='fast_newton'"
            )
        return model
    if isinstance(model, Component):
        return assemble_cached(model, list(outputs) if outputs else None,
                               rootfinder="fast_newton")
    raise ParameterError(
        f"export_fmu: expected an assembly (Component) or a System, got {type(model).__name__}"
    )


def _outputs(system, outputs) -> tuple[list[str], list[str], list[str]]:
    """FMU output names, units and descriptions; inputs of the system are dropped."""
    known = {s.name: s for s in system.states + system.outputs}
    known.update({f"der({s.name})": None for s in system.states})
    state_names = {s.name for s in system.states}
    if outputs:
        names = list(outputs)
    else:  # every variable, but the rate of a variable that is no state is not a derivative
        names = [n for n in system.output_names
                 if not (n.startswith("der(") and n[4:-1] not in state_names)]
    inputs = set(system.input_names)
    dropped = [n for n in names if n in inputs]
    if dropped:
        log.warning("export_fmu: %s are inputs of the FMU, not outputs", ", ".join(dropped))
    names = [n for n in names if n not in inputs]
    unknown = [n for n in names if n not in known]
    if unknown:
        raise ParameterError(
            f"export_fmu: unknown output(s) {', '.join(unknown)}; outputs of {system.name}: "
            + ", ".join(system.output_names)
            + " (export the assembly, not the system, to choose other outputs)"
        )
    if len(set(names)) != len(names):
        raise ParameterError("export_fmu: outputs must not repeat")
    units, descriptions = [], []
    for n in names:
        sig = known[n]
        if sig is None:
            state = known[n[4:-1]]
            units.append(derivative_unit(state.unit))
            descriptions.append(f"time derivative of {state.name}")
        else:
            units.append(sig.unit)
            descriptions.append(sig.description)
    return names, units, descriptions


def _input_starts(system, inputs):
    u = system.u_default()
    for name, value in (inputs or {}).items():
        if name not in system.input_names:
            raise ParameterError(
                f"export_fmu: unknown input {name!r}; inputs: "
                + (", ".join(system.input_names) or "none")
            )
        try:
            u[system.input_names.index(name)] = check_input_value(system, name, value)
        except ParameterError as exc:
            raise ParameterError(f"export_fmu: start value of {exc}") from None
    return u


def _description(model, system: System) -> str:
    """One line about the model: the first docstring line of the assembly's class, or, for an
    already assembled system (whose class docstring describes ``System`` itself), its name."""
    if isinstance(model, System):
        return f"{system.name} (an assembled bearingsim system)"
    return (type(model).__doc__ or "").strip().split("\n")[0]


def export_fmu(
    model,
    path: str | Path,
    inputs: dict[str, float | str] | None = None,
    outputs: Sequence[str] | None = None,
    parameters: dict[str, float] | None = None,
    fmi_version: str = "2.0",
    kinds: Sequence[str] = ("ME", "CS"),
    model_name: str | None = None,
    stepper: str = STEPPERS[0],
    platforms: Sequence[str] = (),
) -> Path:
    """Export an assembly or an assembled system as a Functional Mock-up Unit.

    The model's functions are generated as C by CasADi (one file per function), joined to the
    generic FMI template of ``bearingsim/fmu/templates`` and compiled in parallel with the
    system C compiler (``$CC``, default ``gcc``) into ``binaries/linux64/<model>.so``, a
    binary that loads on glibc 2.17 and later. The sources travel in ``sources/`` with their
    build description (FMI 2.0 ``SourceFiles``, FMI 3.0 ``buildDescription.xml``). States
    carry nominal values from the model's scales (:mod:`bearingsim.fmu.nominal`). No Python
    runs inside the FMU.

    Parameters
    ----------
    model : Component or System
        An assembly (assembled here, pruned to ``outputs``) or the result of
        :func:`bearingsim.assembler.assemble`.
    path : str or pathlib.Path
        The ``.fmu`` file to write.
    inputs : dict, optional
        Input name -> start value [input unit] or number with a unit (``"3000 rpm"``),
        checked against the input's range (the
        FMU refuses values outside it in ``fmi2SetReal``/``fmi3SetFloat64`` too, and warns
        once above its limit, e.g. a limiting speed).
    outputs : sequence of str, optional
        Dotted names of the FMU outputs. Default: the system's outputs (for an assembly: every
        variable). Inputs named here are dropped (they are FMU inputs already).
    parameters : dict, optional
        Parameter name -> start value, validated against the declared range. All parameters
        stay tunable in the FMU.
    fmi_version : {"2.0", "3.0"}
        FMI version. Both share the C runtime (model functions, checks, co-simulation
        stepper); only the API layer (``fmi2_api.c`` or ``fmi3_api.c``) and the model
        description differ.
    kinds : sequence of {"ME", "CS"}
        Model Exchange and/or Co-Simulation interfaces.
    model_name : str, optional
        ``modelName``; its C-identifier form names the library. Default: the system's name.
    stepper : {"auto", "bdf", "ros34pw2", "rodas3"}
        Co-simulation stepper (``bsm_solver.c``): the variable-order BDF of
        ``method="compiled_bdf"`` (its stepping core, history kept across doSteps); the
        Rosenbrock-W method ROS34PW2, which reuses the Jacobian and its LU factorisation over
        many steps; or Rodas3, which evaluates the Jacobian and factorises at every internal
        step (both order 3 with an embedded order-2 error estimate). ``"auto"``: BDF from
        :data:`~bearingsim.fmu.model_c.BDF_MIN_STATES` states on, ROS34PW2 below.
    platforms : sequence of str
        Cross-built binaries besides the Linux x86-64 one, from
        :data:`~bearingsim.fmu.build.CROSS_PLATFORMS` (``"linux-aarch64"``, ``"darwin-x86_64"``,
        ``"darwin-aarch64"``, ``"windows-x86_64"``; the aarch64 ones FMI 3.0 only), built with
        zig's C compiler (``pip install ziglang``). Untested: none is loaded here.

    Returns
    -------
    pathlib.Path
        The written ``.fmu``.

    Raises
    ------
    ParameterError
        For an unknown FMI version, kind, stepper, output, input or parameter, or a value out
        of range.
    CompileError
        If the C compiler is missing or fails, or the binary would need a glibc newer than
        2.17.
    """
    check_output_file(path, ".fmu", "path", "export_fmu")
    if fmi_version not in FMI_VERSIONS:
        raise ParameterError(
            f"export_fmu: fmi_version must be one of {', '.join(FMI_VERSIONS)}, got "
            f"{fmi_version!r}"
        )
    kinds = tuple(kinds)
    if not kinds or any(k not in KINDS for k in kinds):
        raise ParameterError(f"export_fmu: kinds must be a non-empty subset of {KINDS}, got "
                             f"{kinds!r}")
    if stepper not in STEPPERS:
        raise ParameterError(f"export_fmu: stepper must be one of {', '.join(STEPPERS)}, got "
                             f"{stepper!r}")
    platforms = tuple(platforms)
    bad = [p for p in platforms
           if p not in CROSS_PLATFORMS or fmi_version not in CROSS_PLATFORMS[p][1]]
    if bad:
        offered = [p for p, (_, folders, _) in CROSS_PLATFORMS.items() if fmi_version in folders]
        raise ParameterError(f"export_fmu: platform(s) {', '.join(bad)} not offered for FMI "
                             f"{fmi_version}; cross platforms: {', '.join(offered)}")
    if platform.system() != "Linux" or platform.machine() not in ("x86_64", "AMD64"):
        raise ParameterError("export_fmu: only Linux x86_64 binaries can be built")
    system = _system(model, outputs)
    names, units, descriptions = _outputs(system, outputs)
    u0 = _input_starts(system, inputs)
    p0 = system.p0(parameters)
    name = model_name or system.name
    ident = _identifier(name)
    functions = fmu_functions(system, names)
    x0 = np.array([s.start for s in system.states], dtype=float)
    jacobian = functions["jac_x"](0.0, x0, u0, p0).full()
    iface = build_interface(system, functions, names, units, descriptions, u0, p0,
                            state_nominals(jacobian, x0))
    guid = "{" + str(uuid.uuid4()) + "}"
    with tempfile.TemporaryDirectory(prefix="bearingsim_fmu_") as tmp:
        src = Path(tmp) / "sources"
        src.mkdir()
        work, generated = generate_c(functions, src)
        written = write_model_c(src, iface, system, guid, work, kinds,
                                stepper=resolve_stepper(stepper, system.n_states),
                                lu_pattern=newton_pattern(functions["jac_x"].sparsity_out(0)))
        template = copy_templates(src, fmi_version)
        flags = {g.name: g.optimisation for g in generated}
        c_files = sorted(n for n in [*flags, *written, *template] if n.endswith(".c"))
        xml = model_description_xml(iface, fmi_version, name, ident, guid, kinds,
                                    description=_description(model, system),
                                    source_files=c_files)
        if fmi_version == "3.0":
            (src / "buildDescription.xml").write_text(build_description_xml(ident, c_files))
        units = [(src / n, flags.get(n, TEMPLATE_OPTIMISATION)) for n in c_files]
        binary = Path(tmp) / f"{ident}.so"
        compile_shared_library(units, binary, src)
        binaries = {f"binaries/{BINARY_PLATFORMS[fmi_version]}/{ident}.so": binary}
        for name in platforms:
            _, folders, extension = CROSS_PLATFORMS[name]
            cross = Path(tmp) / name / f"{ident}{extension}"
            cross.parent.mkdir()
            cross_compile_shared_library(units, cross, src, name)
            binaries[f"binaries/{folders[fmi_version]}/{ident}{extension}"] = cross
        return write_archive(Path(path), xml, binaries, sorted(src.iterdir()))
