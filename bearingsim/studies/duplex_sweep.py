"""Duplex pair parameter sweeps (docs/studies.md, section B): natural frequencies and stiffness
of a :class:`~bearingsim.studies.duplex.DuplexModel` over one configuration parameter (preload,
contact angle, speed or ball position angle), and their plot.

Each point re-solves the equilibrium of the one assembled model with new parameter values (no
re-assembly) and takes its modes from the exact stiffness (:func:`sweep`, :class:`Sweep`,
:func:`plot_sweep`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.errors import ParameterError
from bearingsim.physics.shaft_modes import MODE_NAMES, modal_analysis
from bearingsim.studies.duplex import DuplexModel
from bearingsim.units import to_deg
from bearingsim.validation import check_quantity

__all__ = ["SWEEP_PARAMETERS", "Sweep", "sweep", "plot_sweep"]

SWEEP_PARAMETERS = {
    "preload": ("N", 1.0),
    "contact_angle": ("deg", to_deg(1.0)),
    "speed": ("rad/s", 1.0),
    "ball_position_angle": ("deg", to_deg(1.0)),
}
"""Sweepable configuration parameters: (display unit, factor from SI to it)."""

SI_UNITS = {"contact_angle": "rad", "speed": "rad/s", "ball_position_angle": "rad"}
"""The SI unit of each swept value but the preload (a class name or a force, which
:meth:`~bearingsim.studies.duplex.DuplexModel.preload_force` reads)."""


@dataclass
class Sweep:
    """Natural frequencies over one configuration parameter.

    Attributes
    ----------
    parameter : str
        Swept parameter (a key of :data:`SWEEP_PARAMETERS`).
    values : ndarray
        Its values (SI units).
    frequencies : ndarray (n, 5)
        Natural frequencies [Hz], columns in :data:`MODE_NAMES` order.
    stiffness : ndarray (n, 5, 5)
        Stiffness matrices.
    label : str
        Legend label of the swept model.
    """

    parameter: str
    values: np.ndarray
    frequencies: np.ndarray
    stiffness: np.ndarray
    label: str = ""

    def relative_change(self) -> np.ndarray:
        """Per mode: (max - min) / min of the frequency over the sweep [-].

        Returns
        -------
        ndarray
            Relative change [-] of each mode's frequency.
        """
        f = self.frequencies
        return (f.max(axis=0) - f.min(axis=0)) / f.min(axis=0)


def sweep(model: DuplexModel, parameter: str, values, label: str = "",
          **config: Any) -> Sweep:
    """Natural frequencies of ``model`` over ``values`` of one configuration parameter.

    Parameters
    ----------
    model : DuplexModel
    parameter : {"preload", "contact_angle", "speed", "ball_position_angle"}
    values : array_like
        Values in SI units (N, rad, rad/s, rad) or numbers with a unit (``"15 deg"``,
        ``"6000 rpm"``, ``"0.5 kN"``); preload may also list class names.
    label : str
        Legend label.
    **config
        The other configuration parameters (see :meth:`DuplexModel.parameters`); those not
        given keep the pair's own values (``pair_options``).

    Returns
    -------
    Sweep
        The frequencies [Hz] of each mode at each value.
    """
    if parameter not in SWEEP_PARAMETERS:
        raise ParameterError(f"sweep: parameter must be one of {', '.join(SWEEP_PARAMETERS)}, "
                             f"got {parameter!r}")
    freqs, stiff, xs = [], [], []
    for v in values:
        if parameter in SI_UNITS:
            v = float(check_quantity(v, parameter, SI_UNITS[parameter], where="sweep"))
        config[parameter] = v
        eq = model.equilibrium(**config)
        k = model.stiffness(eq)
        modes = modal_analysis(k, model.mass)
        freqs.append([modes.frequency(n) for n in MODE_NAMES])
        stiff.append(k)
        xs.append(model.preload_force(v, config.get("bearing")) if parameter == "preload"
                  else float(v))
    return Sweep(parameter, np.array(xs), np.array(freqs), np.array(stiff), label)


def plot_sweep(result: Sweep, ax=None, modes=MODE_NAMES, **line_kw):
    """Plot natural frequencies against the swept parameter.

    Parameters
    ----------
    result : Sweep
    ax : matplotlib Axes, optional
    modes : sequence of str
        Modes to draw.
    **line_kw
        Passed to ``ax.plot``.

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt

    ax = ax if ax is not None else plt.subplots(figsize=(6, 4))[1]
    unit, factor = SWEEP_PARAMETERS[result.parameter]
    for name in modes:
        k = MODE_NAMES.index(name)
        label = f"{result.label} {name}".strip()
        ax.plot(result.values * factor, result.frequencies[:, k], marker="o", label=label,
                **line_kw)
    ax.set_xlabel(f"{result.parameter.replace('_', ' ')} [{unit}]")
    ax.set_ylabel("natural frequency [Hz]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return ax
