"""A strong-coupling co-simulation master: each communication step iterated to a fixed point.

A Jacobi master exchanges the coupled values once per communication step and extrapolates
them through the step; where a coupled signal changes fast (a shaft leaving standstill inside
the friction's regularization band) the extrapolation lags. :func:`run_coupled` instead
iterates every step (waveform relaxation with rollback): it saves each FMU's state, steps all
FMUs on a guess of every coupled signal over the step, reads the outputs at the end of the
step, rolls back (``fmi2SetFMUstate`` / ``fmi3SetFMUState``) and steps again on the improved
guess until the end values agree with the guess; then it moves on.

Over the step each coupled input follows (``interpolation``)

* ``"cubic"``: the cubic Hermite polynomial through the output's value and total time
  derivative at both ends of the step; FMI 3.0 gets it through the ``intermediateUpdate``
  callback at every time it asks for, FMI 2.0 as input derivatives of order 1 to 3 at the
  step start (``fmi2SetRealInputDerivatives``; the standard allows any order, bearingsim's
  FMUs accept up to 3, many other FMUs only 1);
* ``"linear"``: the straight line from the value at the start to the value at the end (FMI
  2.0: a first-order input derivative, which any FMU with ``canInterpolateInputs`` accepts).

The total time derivative of an output is ``fmi3GetOutputDerivatives`` (inputs held) plus the
directional derivative along the rates of the FMU's coupled inputs (FMI 3.0), or
``fmi2GetRealOutputDerivatives`` with those rates set as input derivatives (FMI 2.0). The FMUs
must offer state save/restore, input interpolation (FMI 2.0) or intermediate update (FMI 3.0),
and output derivatives; bearingsim's co-simulation FMUs do.
"""

from __future__ import annotations

import shutil
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from bearingsim.errors import ParameterError, SimulationError

__all__ = ["CoupledRun", "run_coupled"]


@dataclass(frozen=True)
class CoupledRun:
    """Result of :func:`run_coupled`.

    Attributes
    ----------
    t : numpy.ndarray
        Communication points, the end of each step [s].
    values : dict of str to numpy.ndarray
        The recorded ``"component.variable"`` outputs at ``t`` [their units].
    do_steps : int
        ``doStep`` calls in total, all FMUs and all iterations.
    iterations : numpy.ndarray
        Iterations of each communication step (each one ``doStep`` per FMU).
    """

    t: np.ndarray
    values: dict[str, np.ndarray]
    do_steps: int
    iterations: np.ndarray


def _hermite(y0: float, d0: float, y1: float, d1: float, h: float, s: float) -> float:
    """Cubic through (0, y0) and (h, y1) with slopes d0, d1, at the fraction s of the step."""
    s2, s3 = s * s, s * s * s
    return ((2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * d0
            + (3 * s2 - 2 * s3) * y1 + (s3 - s2) * h * d1)


class _Member:
    """One FMU of the coupling, instantiated with fmpy's low-level API."""

    def __init__(self, name: str, path: Path, inputs: list[str], fmu_tolerance: float,
                 cubic: bool):
        from fmpy import extract, read_model_description

        md = read_model_description(str(path))
        if md.coSimulation is None:
            raise ParameterError(f"run_coupled: {name} ({path}) is not a co-simulation FMU")
        self.name = name
        self.fmi3 = md.fmiVersion.startswith("3")
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.causality = {v.name: v.causality for v in md.modelVariables}
        self.cubic = cubic
        self.segment = {}  # input name -> (y0, d0, y1, d1, t0, h) of the current guess
        self.unzip = extract(str(path))
        ident = md.coSimulation.modelIdentifier
        if self.fmi3:
            from fmpy.fmi3 import FMU3Slave

            self.fmu = FMU3Slave(guid=md.instantiationToken, unzipDirectory=self.unzip,
                                 modelIdentifier=ident, instanceName=name)
            self._callback = self._intermediate_update  # kept alive beside fmpy's wrapper
            self.fmu.instantiate(intermediateUpdate=self._callback,
                                 requiredIntermediateVariables=[self.vr[u] for u in inputs]
                                 or None)
            self.fmu.enterInitializationMode(tolerance=fmu_tolerance)
        else:
            from fmpy.fmi2 import FMU2Slave

            self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.unzip,
                                 modelIdentifier=ident, instanceName=name)
            self.fmu.instantiate()
            self.fmu.setupExperiment(tolerance=fmu_tolerance, startTime=0.0)
            self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()

    def check(self, variable: str, causality: str) -> int:
        """Value reference of ``variable``, which must have ``causality``."""
        if self.causality.get(variable) != causality:
            found = self.causality.get(variable, "not a variable")
            raise ParameterError(f"run_coupled: {self.name}.{variable} must be an "
                                 f"{causality} ({found})")
        return self.vr[variable]

    def _intermediate_update(self, env, t, *_):
        for u, (y0, d0, y1, d1, t0, h) in self.segment.items():
            s = (t - t0) / h
            value = _hermite(y0, d0, y1, d1, h, s) if self.cubic else y0 + (y1 - y0) * s
            self.fmu.setFloat64([self.vr[u]], [value])

    def get(self, variable: str) -> float:
        get = self.fmu.getFloat64 if self.fmi3 else self.fmu.getReal
        return get([self.vr[variable]])[0]

    def set_input(self, u: str, y0: float, d0: float, y1: float, d1: float, t0: float,
                  h: float) -> None:
        """The input ``u`` over the step [t0, t0 + h]: y0 at t0, the guess y1 at t0 + h."""
        if self.fmi3:
            self.fmu.setFloat64([self.vr[u]], [y0])
            self.segment[u] = (y0, d0, y1, d1, t0, h)
        elif self.cubic:  # the Hermite cubic's derivatives at t0
            self.fmu.setReal([self.vr[u]], [y0])
            secant = (y1 - y0) / h
            self.fmu.setRealInputDerivatives(
                [self.vr[u]] * 3, [1, 2, 3],
                [d0, 2.0 * (3.0 * secant - 2.0 * d0 - d1) / h,
                 6.0 * (d0 + d1 - 2.0 * secant) / (h * h)])
        else:
            self.fmu.setReal([self.vr[u]], [y0])
            self.fmu.setRealInputDerivatives([self.vr[u]], [1], [(y1 - y0) / h])

    def rate(self, y: str, input_rates: dict[str, float]) -> float:
        """Total time derivative of the output ``y`` with the inputs changing at
        ``input_rates`` [unit of y / s]."""
        us = list(input_rates)
        if not self.fmi3:
            if us:
                self.fmu.setRealInputDerivatives([self.vr[u] for u in us], [1] * len(us),
                                                 [input_rates[u] for u in us])
            return self.fmu.getRealOutputDerivatives([self.vr[y]], [1])[0]
        dy = self.fmu.getOutputDerivatives([self.vr[y]], [1])[0]
        if us:
            dy += self.fmu.getDirectionalDerivative([self.vr[y]], [self.vr[u] for u in us],
                                                    [input_rates[u] for u in us])[0]
        return dy

    def save(self):
        return self.fmu.getFMUState() if self.fmi3 else self.fmu.getFMUstate()

    def restore(self, state) -> None:
        (self.fmu.setFMUState if self.fmi3 else self.fmu.setFMUstate)(state)

    def free(self, state) -> None:
        (self.fmu.freeFMUState if self.fmi3 else self.fmu.freeFMUstate)(state)

    def do_step(self, t0: float, h: float) -> None:
        self.fmu.doStep(t0, h, False)  # noSetFMUStatePriorToCurrentPoint: we roll back

    def close(self) -> None:
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.unzip, ignore_errors=True)


def _split(path: str) -> tuple[str, str]:
    component, _, variable = path.partition(".")
    if not variable:
        raise ParameterError(f"run_coupled: {path!r} is not 'component.variable'")
    return component, variable


def run_coupled(fmus: dict[str, str | Path], connections: Sequence[tuple[str, str]],
                t_end: float, step: float, record: Sequence[str] = (),
                interpolation: str = "cubic", tolerance: float = 1e-4,
                max_iterations: int = 20, fmu_tolerance: float = 1e-8) -> CoupledRun:
    """Co-simulate FMUs with every communication step iterated until the coupling converges.

    Parameters
    ----------
    fmus : dict of str to path
        Component name -> co-simulation FMU (FMI 2.0 or 3.0; they may be mixed).
    connections : sequence of (str, str)
        ``("component.output", "component.input")`` pairs of scalar real variables.
    t_end : float
        End time [s]; a whole number of steps.
    step : float
        Communication step [s].
    record : sequence of str
        ``"component.output"`` variables recorded at every communication point.
    interpolation : {"cubic", "linear"}
        Shape of each coupled input over the step (module docstring). ``"cubic"`` needs FMI
        3.0 intermediate update, or FMI 2.0 input derivatives up to order 3.
    tolerance : float
        Convergence of a step: each coupled output changes between two iterations by at most
        ``tolerance`` times the largest magnitude it has had in the run [relative].
    max_iterations : int
        Iterations of one step before :class:`~bearingsim.errors.SimulationError`.
    fmu_tolerance : float
        Relative tolerance of the FMUs' own steppers.

    Returns
    -------
    CoupledRun
        Communication points, recorded values, ``doStep`` count and iterations per step.

    Raises
    ------
    ParameterError
        A connection or recorded variable that is not an output/input of a listed FMU, or a
        step that does not divide ``t_end``.
    SimulationError
        A step that does not converge within ``max_iterations``.

    Examples
    --------
    >>> run = run_coupled({"motor": "dc_motor_fmi3.fmu", "bearing": "bearing_fmi3.fmu"},
    ...                   MOTOR_BEARING_CONNECTIONS, 0.3, 1e-3,
    ...                   record=["bearing.M_shaft"])  # doctest: +SKIP
    """
    if interpolation not in ("cubic", "linear"):
        raise ParameterError(f"run_coupled: interpolation must be 'cubic' or 'linear', got "
                             f"{interpolation!r}")
    n = int(round(t_end / step)) if step > 0.0 else 0
    if n < 1 or abs(n * step - t_end) > 1e-9 * t_end:
        raise ParameterError(f"run_coupled: step = {step} s must divide t_end = {t_end} s")
    links = [(*_split(out), *_split(inp)) for out, inp in connections]
    names = {c for link in links for c in (link[0], link[2])} | {_split(r)[0] for r in record}
    if names - set(fmus):
        raise ParameterError(f"run_coupled: no FMU given for {sorted(names - set(fmus))}")
    members: dict[str, _Member] = {}
    try:
        for name, path in fmus.items():
            members[name] = _Member(name, Path(path),
                                    [iv for _, _, ic, iv in links if ic == name], fmu_tolerance,
                                    interpolation == "cubic")
        for oc, ov, ic, iv in links:
            members[oc].check(ov, "output")
            members[ic].check(iv, "input")
        for r in record:
            members[_split(r)[0]].check(_split(r)[1], "output")
        return _iterate(members, links, n, step, record, tolerance, max_iterations)
    finally:
        for member in members.values():
            member.close()


def _iterate(members, links, n, h, record, tolerance, max_iterations) -> CoupledRun:
    """The stepping loop of :func:`run_coupled` over opened, checked members."""
    def outputs():
        return np.array([members[oc].get(ov) for oc, ov, _, _ in links])

    def rates(d):
        """Total derivatives of the coupled outputs, the inputs changing at d (per link)."""
        return np.array([members[oc].rate(ov, {iv: d[j] for j, (_, _, ic, iv) in
                                               enumerate(links) if ic == oc})
                         for oc, ov, _, _ in links])

    def set_inputs(y0, d0, y1, d1, t0):
        for j, (_, _, ic, iv) in enumerate(links):
            members[ic].set_input(iv, y0[j], d0[j], y1[j], d1[j], t0, h)

    y0, d0 = outputs(), np.zeros(len(links))
    for _ in range(len(links) + 1):  # consistent start: inputs = outputs, rates likewise
        set_inputs(y0, d0, y0, d0, 0.0)
        y0 = outputs()
        d0 = rates(d0)
    scale = np.abs(y0)
    recorded = [_split(r) for r in record]
    values = np.empty((n, len(record)))
    iterations = np.zeros(n, dtype=int)
    do_steps = 0
    for k in range(n):
        t0 = k * h
        states = {name: m.save() for name, m in members.items()}
        y1, d1 = y0 + d0 * h, d0.copy()
        for it in range(1, max_iterations + 1):
            if it > 1:
                for name, m in members.items():
                    m.restore(states[name])
            set_inputs(y0, d0, y1, d1, t0)
            for m in members.values():
                m.do_step(t0, h)
            do_steps += len(members)
            y_new = outputs()
            d1 = rates(d1)
            scale = np.maximum(scale, np.abs(y_new))
            change = np.abs(y_new - y1)
            y1 = y_new
            if np.all(change <= tolerance * scale):
                break
        else:
            worst = int(np.argmax(change / np.maximum(scale, 1e-300)))
            oc, ov = links[worst][:2]
            raise SimulationError(
                f"run_coupled: the step from t = {t0:g} s did not converge in {max_iterations} "
                f"iterations ({oc}.{ov} still changed by {change[worst]:.3g}); raise "
                f"max_iterations or tolerance, or shorten the step")
        for name, m in members.items():
            m.free(states[name])
        iterations[k] = it
        y0, d0 = y1, d1
        values[k] = [members[c].get(v) for c, v in recorded]
    return CoupledRun(h * np.arange(1, n + 1), {r: values[:, j] for j, r in enumerate(record)},
                      do_steps, iterations)
