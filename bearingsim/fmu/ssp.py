"""``write_ssp``: an SSP 1.0 archive (``SystemStructure.ssd`` + ``resources/*.fmu``) that connects
co-simulation FMUs output -> input, for fmpy's ``simulate_ssp`` or any SSP importer."""

from __future__ import annotations

import xml.etree.ElementTree as ET
import zipfile
from collections.abc import Mapping, Sequence
from pathlib import Path

from bearingsim.errors import ParameterError
from bearingsim.files import atomic_path
from bearingsim.fmu.units import BASE_UNITS, parse_unit

__all__ = ["write_ssp"]

SSD = "http://ssp-standard.org/SSP1/SystemStructureDescription"
SSC = "http://ssp-standard.org/SSP1/SystemStructureCommon"


def _split(endpoint: str, fmus: Mapping[str, Path]) -> tuple[str, str]:
    element, sep, variable = endpoint.partition(".")
    if not sep or element not in fmus:
        raise ParameterError(
            f"write_ssp: connection end {endpoint!r} must be COMPONENT.VARIABLE with COMPONENT "
            f"one of {', '.join(fmus)}"
        )
    return element, variable


def _variables(fmu: Path) -> dict:
    from fmpy import read_model_description

    md = read_model_description(str(fmu))
    if md.coSimulation is None:
        raise ParameterError(f"write_ssp: {fmu} has no co-simulation interface")
    return {v.name: v for v in md.modelVariables}


def write_ssp(
    path: str | Path,
    fmus: Mapping[str, str | Path],
    connections: Sequence[tuple[str, str]],
    name: str = "system",
    stop_time: float | None = None,
    observe: Sequence[str] = (),
) -> Path:
    """Write an SSP file that couples FMUs.

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.ssp`` file to write.
    fmus : mapping of str to path
        Component name -> co-simulation FMU; stored as ``resources/<name>.fmu``.
    connections : sequence of (str, str)
        ``("source.output", "target.input")`` pairs; the first dot separates the component name
        from the variable name (variable names may contain dots).
    name : str
        Name of the system.
    stop_time : float, optional
        ``DefaultExperiment`` stop time [s].
    observe : sequence of str
        More ``"component.output"`` connectors that are not connected; an importer records them
        (fmpy's ``simulate_ssp`` returns the values of every connector).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ParameterError
        For an unknown component or variable, a start that is not an output, an end that is not
        an input, an input connected twice or an FMU without co-simulation.
    """
    fmus = {k: Path(v) for k, v in fmus.items()}
    variables = {k: _variables(f) for k, f in fmus.items()}
    connectors: dict[str, dict[str, str]] = {k: {} for k in fmus}
    links = []
    for start, end in connections:
        (se, sv), (ee, ev) = _split(start, fmus), _split(end, fmus)
        for element, var, kind in ((se, sv, "output"), (ee, ev, "input")):
            v = variables[element].get(var)
            if v is None or v.causality != kind:
                raise ParameterError(
                    f"write_ssp: {element}.{var} is not an {kind} of {fmus[element].name}"
                )
            if kind == "input" and var in connectors[element]:
                raise ParameterError(f"write_ssp: input {element}.{var} is connected twice")
            connectors[element][var] = kind
        links.append((se, sv, ee, ev))
    for endpoint in observe:
        element, var = _split(endpoint, fmus)
        v = variables[element].get(var)
        if v is None or v.causality != "output":
            raise ParameterError(
                f"write_ssp: {element}.{var} is not an output of {fmus[element].name}"
            )
        connectors[element].setdefault(var, "output")

    ET.register_namespace("ssd", SSD)
    ET.register_namespace("ssc", SSC)
    root = ET.Element(f"{{{SSD}}}SystemStructureDescription", version="1.0", name=name)
    system = ET.SubElement(root, f"{{{SSD}}}System", name=name)
    elements = ET.SubElement(system, f"{{{SSD}}}Elements")
    units: set[str] = set()
    for element in fmus:
        comp = ET.SubElement(elements, f"{{{SSD}}}Component", name=element,
                             source=f"resources/{element}.fmu",
                             type="application/x-fmu-sharedlibrary")
        conns = ET.SubElement(comp, f"{{{SSD}}}Connectors")
        for var, kind in connectors[element].items():
            c = ET.SubElement(conns, f"{{{SSD}}}Connector", name=var, kind=kind)
            unit = variables[element][var].unit
            real = ET.SubElement(c, f"{{{SSC}}}Real")
            if unit:
                real.set("unit", unit)
                units.add(unit)
    wires = ET.SubElement(system, f"{{{SSD}}}Connections")
    for se, sv, ee, ev in links:
        ET.SubElement(wires, f"{{{SSD}}}Connection", startElement=se, startConnector=sv,
                      endElement=ee, endConnector=ev)
    if units:
        defs = ET.SubElement(root, f"{{{SSD}}}Units")
        for unit in sorted(units):
            u = ET.SubElement(defs, f"{{{SSC}}}Unit", name=unit)
            d = parse_unit(unit)
            base = {b: str(d.exponents[b]) for b in BASE_UNITS if b in (d.exponents or {})}
            if d.factor != 1.0:
                base["factor"] = repr(d.factor)
            if d.offset != 0.0:
                base["offset"] = repr(d.offset)
            ET.SubElement(u, f"{{{SSC}}}BaseUnit", base)
    experiment = ET.SubElement(root, f"{{{SSD}}}DefaultExperiment", startTime="0.0")
    if stop_time is not None:
        experiment.set("stopTime", repr(float(stop_time)))
    ET.indent(root)
    xml = '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode")

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp, zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("SystemStructure.ssd", xml)
        for element, fmu in fmus.items():
            z.write(fmu, f"resources/{element}.fmu")
    return path
