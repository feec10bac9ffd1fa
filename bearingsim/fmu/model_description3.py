"""``modelDescription.xml`` for FMI 3.0: float64 variables with units, the independent variable
``time``, capabilities and the model structure (dependencies by value reference).

The variables and value references are those of the FMI 2.0 export
(:mod:`bearingsim.fmu.interface`); ``time`` is added after the parameters (value reference
``VR_END`` of the C template).
"""

from __future__ import annotations

import datetime as _dt
import xml.etree.ElementTree as ET

from bearingsim.fmu.interface import FmuInterface, FmuVariable
from bearingsim.fmu.model_description import (
    LOG_CATEGORIES,
    _fmt,
    _unit_definitions,
    dependency_list,
    value_attributes,
    variable_attributes,
)

__all__ = ["model_description3_xml", "time_value_reference"]


def time_value_reference(iface: FmuInterface) -> int:
    """Value reference of the independent variable ``time`` (after the parameters)."""
    return iface.vr_p + iface.np


def _float64(parent: ET.Element, v: FmuVariable, derivative_of: int | None) -> None:
    attrs = {**variable_attributes(v), **value_attributes(v, derivative_of)}
    ET.SubElement(parent, "Float64", attrs)


def model_description3_xml(iface: FmuInterface, model_name: str, model_identifier: str,
                           token: str, kinds: tuple[str, ...], description: str = "",
                           tolerance: float = 1e-6) -> str:
    """Build the FMI 3.0 model description.

    Parameters
    ----------
    iface : FmuInterface
        Variables, sizes and dependency patterns.
    model_name, model_identifier : str
        ``modelName`` and the shared-library name.
    token : str
        ``instantiationToken``, identical to the one compiled into the binary.
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
        "fmiVersion": "3.0",
        "modelName": model_name,
        "instantiationToken": token,
        "description": description,
        "generationTool": f"bearingsim {__version__}",
        "generationDateAndTime": _dt.datetime.now(_dt.timezone.utc).strftime(
            "%Y-%m-%dT%H:%M:%SZ"
        ),
        "variableNamingConvention": "structured",
    })
    common = {
        "modelIdentifier": model_identifier,
        "canGetAndSetFMUState": "true",
        "canSerializeFMUState": "true",
        "providesDirectionalDerivatives": "true",
        "providesAdjointDerivatives": "false",
    }
    if "ME" in kinds:
        ET.SubElement(root, "ModelExchange", {**common, "needsCompletedIntegratorStep": "false"})
    if "CS" in kinds:
        ET.SubElement(root, "CoSimulation", {
            **common,
            "canHandleVariableCommunicationStepSize": "true",
            "maxOutputDerivativeOrder": "0",
            "hasEventMode": "false",
            "providesIntermediateUpdate": "false",
            "canReturnEarlyAfterIntermediateUpdate": "false",
        })
    _unit_definitions(root, iface.variables, extra=("s",))
    cats = ET.SubElement(root, "LogCategories")
    for name in LOG_CATEGORIES:
        ET.SubElement(cats, "Category", name=name)
    ET.SubElement(root, "DefaultExperiment", startTime="0.0", tolerance=_fmt(tolerance))

    mv = ET.SubElement(root, "ModelVariables")
    ET.SubElement(mv, "Float64", {
        "name": "time", "valueReference": str(time_value_reference(iface)),
        "causality": "independent", "variability": "continuous", "unit": "s",
        "description": "simulation time",
    })
    for v in iface.variables:
        _float64(mv, v, iface.vr_x + v.index if v.kind == "derivative" else None)

    x_vrs = [iface.vr_x + k for k in range(iface.nx)]
    u_vrs = [iface.vr_u + k for k in range(iface.nu)]
    p_vrs = [iface.vr_p + k for k in range(iface.np)]
    sp = iface.sparsity

    def deps(vr: int, with_params: bool) -> str:
        if vr < iface.vr_dx:  # a state reported as an output depends on itself
            return str(vr)
        pre, k = ("ode", vr - iface.vr_dx) if vr < iface.vr_u else ("out", vr - iface.vr_y)
        rows, refs = [sp[f"{pre}_x"][k], sp[f"{pre}_u"][k]], [x_vrs, u_vrs]
        if with_params:
            rows.append(sp[f"{pre}_p"][k])
            refs.append(p_vrs)
        return dependency_list(rows, refs)

    structure = ET.SubElement(root, "ModelStructure")
    for vr in sorted(set(iface.output_vrs)):
        ET.SubElement(structure, "Output", valueReference=str(vr), dependencies=deps(vr, False))
    for k in range(iface.nx):
        vr = iface.vr_dx + k
        ET.SubElement(structure, "ContinuousStateDerivative", valueReference=str(vr),
                      dependencies=deps(vr, False))
    initial = sorted({vr for vr in iface.output_vrs if vr >= iface.vr_dx}
                     | {iface.vr_dx + k for k in range(iface.nx)})
    for vr in initial:
        ET.SubElement(structure, "InitialUnknown", valueReference=str(vr),
                      dependencies=deps(vr, True))
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode")
