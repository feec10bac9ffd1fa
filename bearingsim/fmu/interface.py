"""The FMU's view of a system: scalar variables with value references, and dependencies.

Value references are laid out in contiguous blocks that the C template relies on::

    [0, nx)                  states x
    [nx, 2 nx)               derivatives der(x)
    [2 nx, 2 nx + nu)        inputs u
    [.., .. + ny)            outputs y
    [.., .. + np)            parameters p

An output that is also a state (or a state derivative) is declared once, as that state with
causality ``output``; its slot in the output block is then not declared.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import casadi as ca
import numpy as np

from bearingsim.errors import ParameterError
from bearingsim.fmu.units import derivative_unit, normalize_unit

__all__ = ["FmuInterface", "FmuVariable", "build_interface"]



@dataclass(frozen=True)
class FmuVariable:
    """One ``ScalarVariable`` of the model description.

    Attributes
    ----------
    name, description, unit : str
        As declared in the model (unit normalized).
    vr : int
        Value reference.
    kind : {"state", "derivative", "input", "output", "parameter"}
        The block of value references the variable lives in.
    index : int
        Position within its block (state index for derivatives).
    causality, variability : str
        FMI attributes.
    initial : str or None
        FMI ``initial`` attribute (``None``: not written).
    start : float or None
        Start value (written when not ``None``).
    low, high : float or None
        ``min``/``max`` (parameter and input ranges, inclusive as FMI reads them).
    nominal : float or None
        ``nominal`` (states: :mod:`bearingsim.fmu.nominal`; None: not written).
    """

    name: str
    vr: int
    kind: str
    index: int
    causality: str
    variability: str
    initial: str | None
    start: float | None
    unit: str
    description: str = ""
    low: float | None = None
    high: float | None = None
    nominal: float | None = None


@dataclass
class FmuInterface:
    """Variables, sizes and dependency patterns of one FMU.

    Attributes
    ----------
    variables : list of FmuVariable
        Declared variables in value-reference order.
    nx, nu, ny, np : int
        Numbers of states, inputs, outputs and parameters.
    output_vrs : list of int
        Value reference that declares each output (its own slot, or the merged state's).
    sparsity : dict of str to numpy.ndarray
        Boolean dependency patterns ``"ode_x"``, ``"ode_u"``, ``"ode_p"``, ``"out_x"``,
        ``"out_u"``, ``"out_p"`` (rows: derivatives or outputs, columns: states, inputs or
        parameters).
    """

    variables: list[FmuVariable]
    nx: int
    nu: int
    ny: int
    np: int
    output_vrs: list[int]
    sparsity: dict[str, np.ndarray]

    @property
    def vr_x(self) -> int:
        """First value reference of the states.

        Returns
        -------
        int
            Always 0: the states come first.
        """
        return 0

    @property
    def vr_dx(self) -> int:
        """First value reference of the derivatives.

        Returns
        -------
        int
            ``nx``, after the states.
        """
        return self.nx

    @property
    def vr_u(self) -> int:
        """First value reference of the inputs.

        Returns
        -------
        int
            ``2 nx``, after the derivatives.
        """
        return 2 * self.nx

    @property
    def vr_y(self) -> int:
        """First value reference of the outputs.

        Returns
        -------
        int
            ``2 nx + nu``, after the inputs.
        """
        return 2 * self.nx + self.nu

    @property
    def vr_p(self) -> int:
        """First value reference of the parameters.

        Returns
        -------
        int
            ``2 nx + nu + ny``, after the outputs.
        """
        return 2 * self.nx + self.nu + self.ny

    def by_kind(self, kind: str) -> list[FmuVariable]:
        """Declared variables of one kind, in value-reference order.

        Parameters
        ----------
        kind : {"state", "derivative", "input", "output", "parameter"}
            The kind wanted.

        Returns
        -------
        list of FmuVariable
            Those of ``variables`` with that kind.
        """
        return [v for v in self.variables if v.kind == kind]


def _pattern(fn: ca.Function, iind: int) -> np.ndarray:
    """Structural dependency of output 0 of ``fn`` on input ``iind`` as a dense boolean array."""
    n_out, n_in = fn.size1_out(0), fn.size1_in(iind)
    if n_out == 0 or n_in == 0:
        return np.zeros((n_out, n_in), dtype=bool)
    sp = fn.jac_sparsity(0, iind)
    return np.array(ca.DM(sp, 1.0), dtype=float) != 0


def _inclusive_bounds(decl) -> tuple[float | None, float | None]:
    """A declaration's range as FMI's inclusive ``min``/``max``: an excluded bound becomes the
    next double inside it (``min`` of a positive length is 5e-324, not 0)."""
    low, high = getattr(decl, "low", None), getattr(decl, "high", None)
    if low is not None and not getattr(decl, "low_inclusive", True):
        low = math.nextafter(low, math.inf)
    if high is not None and not getattr(decl, "high_inclusive", True):
        high = math.nextafter(high, -math.inf)
    return low, high


def build_interface(system, functions: dict[str, ca.Function], output_names: list[str],
                    output_units: list[str], output_descriptions: list[str],
                    input_starts: np.ndarray, parameter_values: np.ndarray,
                    state_nominals: np.ndarray | None = None) -> FmuInterface:
    """Lay out the FMU variables of a system.

    Parameters
    ----------
    system : System
        The assembled system.
    functions : dict of str to casadi.Function
        The model functions of the FMU (``ode`` and ``output`` are used for dependencies).
    output_names, output_units, output_descriptions : list of str
        The FMU outputs (inputs of the system are not allowed here).
    input_starts : numpy.ndarray
        Start values of the inputs.
    parameter_values : numpy.ndarray
        Start values (defaults) of the parameters, validated.
    state_nominals : numpy.ndarray, optional
        Nominal values of the states (default 1).

    Returns
    -------
    FmuInterface
    """
    nx, nu, ny, n_p = system.n_states, len(system.inputs), len(output_names), len(system.params)
    vr_y = 2 * nx + nu
    state_pos = {s.name: k for k, s in enumerate(system.states)}
    der_pos = {f"der({s.name})": k for k, s in enumerate(system.states)}
    output_vrs = []
    for k, name in enumerate(output_names):
        if name in state_pos:
            output_vrs.append(state_pos[name])
        elif name in der_pos:
            output_vrs.append(nx + der_pos[name])
        else:
            output_vrs.append(vr_y + k)
    merged = set(output_vrs) - set(range(vr_y, vr_y + ny))

    variables: list[FmuVariable] = []
    for k, s in enumerate(system.states):
        if not s.fixed and system.init_residual is not None:
            raise ParameterError(
                f"state {s.name} has no fixed start value (initial equations); FMU export "
                "needs fixed start values for all states"
            )
        causality = "output" if k in merged else "local"
        variables.append(FmuVariable(
            s.name, k, "state", k, causality, "continuous", "exact", float(s.start),
            normalize_unit(s.unit), s.description,
            nominal=1.0 if state_nominals is None else float(state_nominals[k]),
        ))
    for k, s in enumerate(system.states):
        causality = "output" if nx + k in merged else "local"
        variables.append(FmuVariable(
            f"der({s.name})", nx + k, "derivative", k, causality, "continuous", None, None,
            derivative_unit(normalize_unit(s.unit)), f"time derivative of {s.name}",
        ))
    for k, s in enumerate(system.inputs):
        variables.append(FmuVariable(
            s.name, 2 * nx + k, "input", k, "input", "continuous", None, float(input_starts[k]),
            normalize_unit(s.unit), s.description, s.low, s.high,
        ))
    for k, name in enumerate(output_names):
        if output_vrs[k] == vr_y + k:
            variables.append(FmuVariable(
                name, vr_y + k, "output", k, "output", "continuous", None, None,
                normalize_unit(output_units[k]), output_descriptions[k],
            ))
    for k, q in enumerate(system.params):
        decl = q.declaration
        variables.append(FmuVariable(
            q.name, vr_y + ny + k, "parameter", k, "parameter", "tunable", "exact",
            float(parameter_values[k]), normalize_unit(q.unit), q.description,
            *_inclusive_bounds(decl),
        ))
    sparsity = {
        "ode_x": _pattern(functions["ode"], 1),
        "ode_u": _pattern(functions["ode"], 2),
        "ode_p": _pattern(functions["ode"], 3),
        "out_x": _pattern(functions["output"], 1),
        "out_u": _pattern(functions["output"], 2),
        "out_p": _pattern(functions["output"], 3),
    }
    return FmuInterface(variables, nx, nu, ny, n_p, output_vrs, sparsity)
