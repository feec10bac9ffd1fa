"""The runtime: what is done with an assembled :class:`~bearingsim.assembler.System`.

``simulate`` integrates it (scipy's ``solve_ivp`` or SUNDIALS through CasADi), ``steady_state``
solves ``dx/dt = 0``, ``linearize`` gives the state-space matrices, natural frequencies and
modes; :mod:`~bearingsim.simulation.statics` gives static stiffness and compliance.
"""

from bearingsim.simulation.linearize import LinearModel, linearize
from bearingsim.simulation.result import Result
from bearingsim.simulation.simulate import simulate
from bearingsim.simulation.steady import steady_state

__all__ = ["LinearModel", "Result", "linearize", "simulate", "steady_state"]
