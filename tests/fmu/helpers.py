"""Shared helpers of the FMU tests: fmpy runs, error measures, log capture."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
from fmpy import read_model_description, simulate_fmu
from fmpy.fmi2 import (
    FMU2Model,
    FMU2Slave,
    calloc,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    free,
)
from fmpy.fmi3 import FMU3Model, FMU3Slave

from bearingsim.simulation import simulate


def rel_err(a, ref) -> float:
    """Largest deviation relative to the largest magnitude of the reference signal."""
    a, ref = np.asarray(a, dtype=float), np.asarray(ref, dtype=float)
    return float(np.max(np.abs(a - ref)) / max(np.max(np.abs(ref)), 1e-300))


def run_fmu(path, kind, t_end, dt, outputs, start_values=None, tol=1e-9):
    """Simulate with fmpy: ME with CVode or CS with the FMU's own stepper."""
    return simulate_fmu(
        str(path), fmi_type=kind, stop_time=t_end, output_interval=dt, step_size=dt,
        output=outputs, start_values=start_values or {}, relative_tolerance=tol,
    )


def open_fmu3(path, tmp_path, kind="CS", messages=None, intermediate_update=None,
              required=()):
    """Extract and instantiate an FMI 3.0 FMU with fmpy's low-level classes; log messages go to
    ``messages`` (a list) if given. ``intermediate_update``: the importer's callback
    ``f(env, time, set_requested, get_allowed, step_finished, can_return_early,
    early_return_requested, early_return_time)`` for the value references ``required``
    (co-simulation only).

    Returns (instance, model description, value-reference lookup by name).
    """
    unzip = Path(tmp_path) / f"{Path(path).stem}_{kind}3"
    if not unzip.exists():
        with zipfile.ZipFile(path) as z:
            z.extractall(unzip)
    md = read_model_description(str(path))
    cls = FMU3Slave if kind == "CS" else FMU3Model
    ident = (md.coSimulation if kind == "CS" else md.modelExchange).modelIdentifier
    fmu = cls(guid=md.instantiationToken, unzipDirectory=str(unzip), modelIdentifier=ident,
              instanceName="t")

    def log(env, status, category, message):
        if messages is not None:
            messages.append(message.decode())

    if kind == "CS":
        fmu.instantiate(logMessage=log, intermediateUpdate=intermediate_update,
                        requiredIntermediateVariables=list(required) or None)
    else:
        fmu.instantiate(logMessage=log)
    return fmu, md, {v.name: v.valueReference for v in md.modelVariables}


def reference(system, t_end, dt, **kwargs):
    """In-Python simulation on the same time grid."""
    n = int(round(t_end / dt)) + 1
    return simulate(system, t_end, n_points=n, rtol=1e-10, atol=1e-12, progress=False, **kwargs)


class LogCapture:
    """fmpy callbacks that record every logged message as (status, category, text)."""

    def __init__(self):
        self.messages: list[tuple[int, str, str]] = []

        def log(env, name, status, category, message):
            self.messages.append((status, category.decode(), message.decode()))

        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = fmi2CallbackLoggerTYPE(log)
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)

    def text(self) -> str:
        """All messages, one per line."""
        return "\n".join(m[2] for m in self.messages)


def open_fmu(path, tmp_path, kind="CS", log: LogCapture | None = None, logging_on=False):
    """Extract and instantiate an FMU with fmpy's low-level classes.

    Returns (instance, model description, value-reference lookup by name).
    """
    unzip = Path(tmp_path) / f"{Path(path).stem}_{kind}"
    if not unzip.exists():
        with zipfile.ZipFile(path) as z:
            z.extractall(unzip)
    md = read_model_description(str(path))
    cls = FMU2Slave if kind == "CS" else FMU2Model
    ident = md.coSimulation.modelIdentifier if kind == "CS" else md.modelExchange.modelIdentifier
    fmu = cls(guid=md.guid, unzipDirectory=str(unzip), modelIdentifier=ident, instanceName="t")
    fmu.instantiate(callbacks=log.callbacks if log else None, loggingOn=logging_on)
    vrs = {v.name: v.valueReference for v in md.modelVariables}
    return fmu, md, vrs
