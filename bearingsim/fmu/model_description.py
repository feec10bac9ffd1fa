"""``modelDescription.xml`` for FMI 2.0 and 3.0: variables with units, capabilities and the model
structure.

One writer for both versions (in the manner of FMPy's single ``model_description.py``). The
variables and value references come from :mod:`bearingsim.fmu.interface` and are the same in
both; FMI 3.0 adds the independent variable ``time`` after the parameters (value reference
``VR_END`` of the C template). What differs is spelled out in :data:`_VERSIONS`: the root's
identity attribute (``guid`` / ``instantiationToken``), capability flags, the variable element
(``ScalarVariable`` with a ``Real`` child / ``Float64``), how the model structure refers to
variables (1-based indices into ``ModelVariables`` / value references) and how co-simulation
inputs are given between communication points (FMI 2.0: ``canInterpolateInputs``, input
derivatives; FMI 3.0: intermediate update, inputs marked ``intermediateUpdate="true"``).
"""

from __future__ import annotations

import datetime as _dt
import xml.etree.ElementTree as ET
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from bearingsim.fmu.interface import FmuInterface, FmuVariable
from bearingsim.fmu.units import BASE_UNITS, parse_unit

__all__ = ["LOG_CATEGORIES", "model_description_xml", "time_value_reference"]

LOG_CATEGORIES = ("logStatusWarning", "logStatusDiscard", "logStatusError", "logAll")
"""Log categories the C template uses."""


@dataclass(frozen=True)
class _Version:
    """What the FMI versions spell differently."""

    identity: str
    """Root attribute holding the GUID / instantiation token."""
    root: dict[str, str]
    """Further root attributes."""
    capabilities: dict[str, str]
    """Attributes of both interface elements."""
    model_exchange: dict[str, str]
    """Further attributes of ``ModelExchange``."""
    co_simulation: dict[str, str]
    """Further attributes of ``CoSimulation``."""


_VERSIONS = {
    "2.0": _Version(
        identity="guid",
        root={"numberOfEventIndicators": "0"},
        capabilities={"canGetAndSetFMUstate": "true", "canSerializeFMUstate": "true",
                      "providesDirectionalDerivative": "true"},
        model_exchange={},
        co_simulation={"canHandleVariableCommunicationStepSize": "true",
                       "canInterpolateInputs": "true", "maxOutputDerivativeOrder": "1"},
    ),
    "3.0": _Version(
        identity="instantiationToken",
        root={},
        capabilities={"canGetAndSetFMUState": "true", "canSerializeFMUState": "true",
                      "providesDirectionalDerivatives": "true",
                      "providesAdjointDerivatives": "false"},
        model_exchange={"needsCompletedIntegratorStep": "false"},
        co_simulation={"canHandleVariableCommunicationStepSize": "true",
                       "maxOutputDerivativeOrder": "1", "hasEventMode": "false",
                       "providesIntermediateUpdate": "true",
                       "canReturnEarlyAfterIntermediateUpdate": "false"},
    ),
}


def _fmt(v: float) -> str:
    return repr(float(v))


def time_value_reference(iface: FmuInterface) -> int:
    """Value reference of the FMI 3.0 independent variable ``time`` (after the parameters)."""
    return iface.vr_p + iface.np


def _unit_definitions(parent: ET.Element, variables: list[FmuVariable],
                      extra: tuple[str, ...] = ()) -> None:
    names = sorted({v.unit for v in variables if v.unit} | set(extra))
    if not names:
        return
    defs = ET.SubElement(parent, "UnitDefinitions")
    for name in names:
        unit = ET.SubElement(defs, "Unit", name=name)
        d = parse_unit(name)
        if d.exponents is None:
            continue
        attrs = {b: str(d.exponents[b]) for b in BASE_UNITS if b in d.exponents}
        if d.factor != 1.0:
            attrs["factor"] = _fmt(d.factor)
        if d.offset != 0.0:
            attrs["offset"] = _fmt(d.offset)
        ET.SubElement(unit, "BaseUnit", attrs)


def _variable_attributes(v: FmuVariable) -> dict[str, str]:
    """Name, value reference, causality, variability, initial and description of a variable."""
    attrs = {
        "name": v.name,
        "valueReference": str(v.vr),
        "causality": v.causality,
        "variability": v.variability,
    }
    if v.initial is not None:
        attrs["initial"] = v.initial
    if v.description:
        attrs["description"] = v.description
    return attrs


def _value_attributes(v: FmuVariable, derivative_of: int | None) -> dict[str, str]:
    """Unit, range, nominal, start and the ``derivative`` reference of a real variable."""
    attrs: dict[str, str] = {}
    if v.unit:
        attrs["unit"] = v.unit
    if v.low is not None:
        attrs["min"] = _fmt(v.low)
    if v.high is not None:
        attrs["max"] = _fmt(v.high)
    if v.nominal is not None:
        attrs["nominal"] = _fmt(v.nominal)
    if v.start is not None:
        attrs["start"] = _fmt(v.start)
    if derivative_of is not None:
        attrs["derivative"] = str(derivative_of)
    return attrs


def _dependency_list(rows: list[np.ndarray], refs: list[list[int]]) -> str:
    """Sorted, space-separated references of the structural non-zeros of ``rows``."""
    out: list[int] = []
    for row, idx in zip(rows, refs, strict=True):
        out.extend(idx[j] for j in np.flatnonzero(row))
    return " ".join(str(i) for i in sorted(out))


def _dependencies(iface: FmuInterface, ref: Callable[[int], int]) -> Callable[[int, bool], str]:
    """``deps(vr, with_params)``: what an output, derivative or state reported as an output
    depends on, each dependency written as ``ref(vr)``."""
    x_refs = [ref(iface.vr_x + k) for k in range(iface.nx)]
    u_refs = [ref(iface.vr_u + k) for k in range(iface.nu)]
    p_refs = [ref(iface.vr_p + k) for k in range(iface.np)]
    sp = iface.sparsity

    def deps(vr: int, with_params: bool) -> str:
        if vr < iface.vr_dx:  # a state reported as an output depends on itself
            return str(ref(vr))
        pre, k = ("ode", vr - iface.vr_dx) if vr < iface.vr_u else ("out", vr - iface.vr_y)
        rows, refs = [sp[f"{pre}_x"][k], sp[f"{pre}_u"][k]], [x_refs, u_refs]
        if with_params:
            rows.append(sp[f"{pre}_p"][k])
            refs.append(p_refs)
        return _dependency_list(rows, refs)

    return deps


def _model_structure_2(root: ET.Element, iface: FmuInterface, index: dict[int, int]) -> None:
    """FMI 2.0 ``ModelStructure``: Outputs, Derivatives, InitialUnknowns by 1-based index."""
    deps = _dependencies(iface, index.__getitem__)
    structure = ET.SubElement(root, "ModelStructure")
    groups = (
        ("Outputs", sorted(set(iface.output_vrs), key=index.__getitem__), False),
        ("Derivatives", [iface.vr_dx + k for k in range(iface.nx)], False),
        ("InitialUnknowns", sorted(_initial_unknowns(iface), key=index.__getitem__), True),
    )
    for tag, vrs, with_params in groups:
        if vrs:
            group = ET.SubElement(structure, tag)
            for vr in vrs:
                ET.SubElement(group, "Unknown", index=str(index[vr]),
                              dependencies=deps(vr, with_params))


def _model_structure_3(root: ET.Element, iface: FmuInterface) -> None:
    """FMI 3.0 ``ModelStructure``: Output, ContinuousStateDerivative, InitialUnknown by value
    reference."""
    deps = _dependencies(iface, lambda vr: vr)
    structure = ET.SubElement(root, "ModelStructure")
    groups = (
        ("Output", sorted(set(iface.output_vrs)), False),
        ("ContinuousStateDerivative", [iface.vr_dx + k for k in range(iface.nx)], False),
        ("InitialUnknown", sorted(_initial_unknowns(iface)), True),
    )
    for tag, vrs, with_params in groups:
        for vr in vrs:
            ET.SubElement(structure, tag, valueReference=str(vr),
                          dependencies=deps(vr, with_params))


def _initial_unknowns(iface: FmuInterface) -> set[int]:
    """Derivatives and computed outputs (states reported as outputs are not unknowns)."""
    return ({vr for vr in iface.output_vrs if vr >= iface.vr_dx}
            | {iface.vr_dx + k for k in range(iface.nx)})


def model_description_xml(iface: FmuInterface, fmi_version: str, model_name: str,
                          model_identifier: str, token: str, kinds: tuple[str, ...],
                          description: str = "", tolerance: float = 1e-6,
                          source_files: list[str] | None = None) -> str:
    """Build the model description of an FMI 2.0 or 3.0 FMU.

    Parameters
    ----------
    iface : FmuInterface
        Variables, sizes and dependency patterns.
    fmi_version : {"2.0", "3.0"}
        FMI version.
    model_name, model_identifier : str
        ``modelName`` and the shared-library name.
    token : str
        GUID (FMI 2.0) or ``instantiationToken`` (FMI 3.0), identical to the one compiled into
        the binary.
    kinds : tuple of str
        ``"ME"`` and/or ``"CS"``.
    description : str
        One line about the model.
    tolerance : float
        Default relative tolerance.
    source_files : list of str, optional
        The ``.c`` files under ``sources/``; FMI 2.0 lists them as ``SourceFiles`` of both
        interfaces (FMI 3.0 describes them in ``sources/buildDescription.xml`` instead).

    Returns
    -------
    str
        The XML document.
    """
    from bearingsim import __version__

    spec = _VERSIONS[fmi_version]
    root = ET.Element("fmiModelDescription", {
        "fmiVersion": fmi_version,
        "modelName": model_name,
        spec.identity: token,
        "description": description,
        "generationTool": f"bearingsim {__version__}",
        "generationDateAndTime": _dt.datetime.now(_dt.timezone.utc).strftime(
            "%Y-%m-%dT%H:%M:%SZ"
        ),
        "variableNamingConvention": "structured",
        **spec.root,
    })
    common = {"modelIdentifier": model_identifier, **spec.capabilities}
    interfaces = []
    if "ME" in kinds:
        interfaces.append(ET.SubElement(root, "ModelExchange", {**common, **spec.model_exchange}))
    if "CS" in kinds:
        interfaces.append(ET.SubElement(root, "CoSimulation", {**common, **spec.co_simulation}))
    if fmi_version == "2.0" and source_files:
        for element in interfaces:
            files = ET.SubElement(element, "SourceFiles")
            for file_name in source_files:
                ET.SubElement(files, "File", name=file_name)
    _unit_definitions(root, iface.variables, extra=("s",) if fmi_version == "3.0" else ())
    cats = ET.SubElement(root, "LogCategories")
    for name in LOG_CATEGORIES:
        ET.SubElement(cats, "Category", name=name)
    ET.SubElement(root, "DefaultExperiment", startTime="0.0", tolerance=_fmt(tolerance))

    mv = ET.SubElement(root, "ModelVariables")
    if fmi_version == "2.0":
        index = {v.vr: k + 1 for k, v in enumerate(iface.variables)}
        for v in iface.variables:
            der_of = index[iface.vr_x + v.index] if v.kind == "derivative" else None
            sv = ET.SubElement(mv, "ScalarVariable", _variable_attributes(v))
            ET.SubElement(sv, "Real", _value_attributes(v, der_of))
        _model_structure_2(root, iface, index)
    else:
        ET.SubElement(mv, "Float64", {
            "name": "time", "valueReference": str(time_value_reference(iface)),
            "causality": "independent", "variability": "continuous", "unit": "s",
            "description": "simulation time",
        })
        between = {"intermediateUpdate": "true"} if "CS" in kinds else {}
        for v in iface.variables:
            der_of = iface.vr_x + v.index if v.kind == "derivative" else None
            ET.SubElement(mv, "Float64", {**_variable_attributes(v),
                                          **(between if v.causality == "input" else {}),
                                          **_value_attributes(v, der_of)})
        _model_structure_3(root, iface)
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode")
