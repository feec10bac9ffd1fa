"""``modelDescription.xml`` for FMI 2.0: variables, units, capabilities and model structure."""

from __future__ import annotations

import datetime as _dt
import xml.etree.ElementTree as ET

import numpy as np

from bearingsim.fmu.interface import FmuInterface, FmuVariable
from bearingsim.fmu.units import BASE_UNITS, parse_unit

__all__ = ["LOG_CATEGORIES", "model_description_xml"]

LOG_CATEGORIES = ("logStatusWarning", "logStatusDiscard", "logStatusError", "logAll")
"""Log categories the C template uses."""


def _fmt(v: float) -> str:
    return repr(float(v))


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


def variable_attributes(v: FmuVariable) -> dict[str, str]:
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


def value_attributes(v: FmuVariable, derivative_of: int | None) -> dict[str, str]:
    """Unit, range, start and the ``derivative`` reference of a real variable."""
    attrs: dict[str, str] = {}
    if v.unit:
        attrs["unit"] = v.unit
    if v.low is not None:
        attrs["min"] = _fmt(v.low)
    if v.high is not None:
        attrs["max"] = _fmt(v.high)
    if v.start is not None:
        attrs["start"] = _fmt(v.start)
    if derivative_of is not None:
        attrs["derivative"] = str(derivative_of)
    return attrs


def _scalar_variable(parent: ET.Element, v: FmuVariable, derivative_index: int | None) -> None:
    sv = ET.SubElement(parent, "ScalarVariable", variable_attributes(v))
    ET.SubElement(sv, "Real", value_attributes(v, derivative_index))


def dependency_list(rows: list[np.ndarray], refs: list[list[int]]) -> str:
    """Sorted, space-separated references of the structural non-zeros of ``rows``."""
    out: list[int] = []
    for row, idx in zip(rows, refs, strict=True):
        out.extend(idx[j] for j in np.flatnonzero(row))
    return " ".join(str(i) for i in sorted(out))


def model_description_xml(iface: FmuInterface, model_name: str, model_identifier: str,
                          guid: str, kinds: tuple[str, ...], description: str = "",
                          tolerance: float = 1e-6) -> str:
    """Build the FMI 2.0 model description.

    Parameters
    ----------
    iface : FmuInterface
        Variables, sizes and dependency patterns.
    model_name, model_identifier : str
        ``modelName`` and the shared-library name.
    guid : str
        GUID, identical to the one compiled into the binary.
    kinds : tuple of str
        ``"ME"`` and/or ``"CS"``.
    description : str
        One line about the model.
    tolerance : float
        Default relative tolerance.

    Returns
    -------
    str
        The XML document.
    """
    from bearingsim import __version__

    root = ET.Element("fmiModelDescription", {
        "fmiVersion": "2.0",
        "modelName": model_name,
        "guid": guid,
        "description": description,
        "generationTool": f"bearingsim {__version__}",
        "generationDateAndTime": _dt.datetime.now(_dt.timezone.utc).strftime(
            "%Y-%m-%dT%H:%M:%SZ"
        ),
        "variableNamingConvention": "structured",
        "numberOfEventIndicators": "0",
    })
    common = {
        "modelIdentifier": model_identifier,
        "canGetAndSetFMUstate": "true",
        "canSerializeFMUstate": "true",
        "providesDirectionalDerivative": "true",
    }
    if "ME" in kinds:
        ET.SubElement(root, "ModelExchange", common)
    if "CS" in kinds:
        ET.SubElement(root, "CoSimulation", {
            **common,
            "canHandleVariableCommunicationStepSize": "true",
            "canInterpolateInputs": "true",
        })
    _unit_definitions(root, iface.variables)
    cats = ET.SubElement(root, "LogCategories")
    for name in LOG_CATEGORIES:
        ET.SubElement(cats, "Category", name=name)
    ET.SubElement(root, "DefaultExperiment", startTime="0.0", tolerance=_fmt(tolerance))

    index = {v.vr: k + 1 for k, v in enumerate(iface.variables)}
    mv = ET.SubElement(root, "ModelVariables")
    for v in iface.variables:
        der_of = index[iface.vr_x + v.index] if v.kind == "derivative" else None
        _scalar_variable(mv, v, der_of)

    x_idx = [index[iface.vr_x + k] for k in range(iface.nx)]
    u_idx = [index[iface.vr_u + k] for k in range(iface.nu)]
    p_idx = [index[iface.vr_p + k] for k in range(iface.np)]
    sp = iface.sparsity

    def deps(kind: str, k: int, with_params: bool) -> str:
        """Dependencies of derivative k or (unmerged) output k."""
        pre = "ode" if kind == "derivative" else "out"
        cols = [sp[f"{pre}_x"][k], sp[f"{pre}_u"][k]]
        idx = [x_idx, u_idx]
        if with_params:
            cols.append(sp[f"{pre}_p"][k])
            idx.append(p_idx)
        return dependency_list(cols, idx)

    def unknown(vr: int, with_params: bool) -> tuple[int, str]:
        if vr < iface.vr_dx:
            return index[vr], str(index[vr])
        if vr < iface.vr_u:
            return index[vr], deps("derivative", vr - iface.vr_dx, with_params)
        return index[vr], deps("output", vr - iface.vr_y, with_params)

    structure = ET.SubElement(root, "ModelStructure")
    if iface.output_vrs:
        outs = ET.SubElement(structure, "Outputs")
        for vr in sorted(set(iface.output_vrs), key=lambda r: index[r]):
            i, d = unknown(vr, False)
            ET.SubElement(outs, "Unknown", index=str(i), dependencies=d)
    if iface.nx:
        ders = ET.SubElement(structure, "Derivatives")
        for k in range(iface.nx):
            i, d = unknown(iface.vr_dx + k, False)
            ET.SubElement(ders, "Unknown", index=str(i), dependencies=d)
    initial = sorted(
        {vr for vr in iface.output_vrs if vr >= iface.vr_dx}
        | {iface.vr_dx + k for k in range(iface.nx)},
        key=lambda r: index[r],
    )
    if initial:
        inits = ET.SubElement(structure, "InitialUnknowns")
        for vr in initial:
            i, d = unknown(vr, True)
            ET.SubElement(inits, "Unknown", index=str(i), dependencies=d)
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode")
