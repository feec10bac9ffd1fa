"""Viscous drag of the oil-air mixture on an orbiting, spinning ball."""

from __future__ import annotations

from bearingsim import symbolic as op
from bearingsim.components.connectors import BallFrame
from bearingsim.language import Component, Parameter
from bearingsim.physics.drag import orbital_drag_force, spin_drag_moment

__all__ = ["BallDrag"]


class BallDrag(Component):
    """Orbital drag force and spin drag moment on a ball (docs/studies.md, section C; Schlichting).

    The bearing cavity holds an oil-air mixture of oil volume fraction ``X`` at rest; its
    density and viscosity are ``X rho_oil`` and ``X eta_oil`` (the effective-mixture assumption of
    Harris & Kotzalas, *Advanced Concepts*, ch. 5). Orbital drag
    :func:`~bearingsim.physics.drag.orbital_drag_force` acts along ``-e_t``; the spin drag moment
    :func:`~bearingsim.physics.drag.spin_drag_moment` opposes the ball's angular velocity vector.

    Parameters
    ----------
    pitch_diameter, ball_diameter : float
        dm, Dw [m].
    rho, eta : float
        Mixture density [kg/m^3] and viscosity [Pa s], > 0.
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    ball : BallFrame
    """

    def __init__(self, pitch_diameter: float, ball_diameter: float, rho: float, eta: float,
                 name=None):
        super().__init__(name)
        self.dm, self.Dw = pitch_diameter, ball_diameter
        self.rho = Parameter(rho, "kg/m3", "oil-air mixture density", low=0.0,
                             low_inclusive=False)
        self.eta = Parameter(eta, "Pa.s", "oil-air mixture viscosity", low=0.0,
                             low_inclusive=False)
        self.ball = BallFrame()

    def equations(self):
        b = self.ball
        f_t = orbital_drag_force(b.w_orbit, self.dm, self.Dw, self.rho, self.eta)
        spin = op.sqrt(b.wr * b.wr + b.wt * b.wt + b.wz * b.wz + 1e-12)
        per_unit = spin_drag_moment(spin, self.Dw, self.rho, self.eta) / spin
        return [
            b.Fr == 0.0, b.Ft == -f_t, b.Fz == 0.0,
            b.Mr == -per_unit * b.wr, b.Mt == -per_unit * b.wt, b.Mz == -per_unit * b.wz,
        ]
