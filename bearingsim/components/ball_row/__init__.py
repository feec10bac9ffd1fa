"""Quasi-static ball row: Z balls with Hertz contacts between an inner and an outer ring frame.

Geometry (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., *Essential Concepts*, chapter
"Rolling bearing macrogeometry"; *Advanced Concepts*, chapters "Distribution of internal
loading" and "High-speed operation"). Ball ``j`` sits at the azimuth
``psi_j = psi0 + 2 pi j / Z`` (measured from x towards y). In the reference configuration the
inner and outer groove curvature centres of ball ``j`` are, in (radial, axial) coordinates of
its azimuth plane,

    C_i = (dm/2 + (fi - 1/2) Dw cos a0,  s (fi - 1/2) Dw sin a0)
    C_o = (dm/2 - (fo - 1/2) Dw cos a0, -s (fo - 1/2) Dw sin a0)

(``reference="touching"``: the balls just touch at the free contact angle ``a0``, so the groove
centres are ``A = (fi + fo - 1) Dw`` apart) or both at axial position 0 (``reference="centred"``:
a deep-groove bearing with its rings centred and the radial clearance ``Pd = 2 A (1 - cos a0)``).
``s = direction = +-1`` is the axial direction in which the inner ring must move relative to
the outer ring to load the row. The groove centres move with their rings by exact rigid-body
kinematics (:mod:`bearingsim.vectors`; the small-angle form is an option).

**Classic form** (``speed_effects=False``). Without body forces each ball is a two-force member:
its contact loads act along the line through both groove centres, the inner and outer contact
angles are equal, and the single unknown of the ball, its total elastic approach, follows
explicitly from ``d = C_i - C_o`` projected on the azimuth plane (the ball moves tangentially
with the cage, so the tangential part does not load it):

    delta_j = |d| - A,   Q_j = K delta_j^1.5,   alpha_j = atan2(s d_z, d_r)

with ``K = (K_i^(-2/3) + K_o^(-2/3))^(-3/2)`` (Jones 1960; Harris & Kotzalas). This is the
formulation behind ``Fa = Z K A^1.5 sin a (cos a0 / cos a - 1)^1.5`` for a pure axial load.

**Jones-Harris form** (``speed_effects=True``). The ball centre ``(b_r, b_z)`` in its azimuth
plane is an unknown of each ball (two algebraic unknowns, solved by the assembler's Newton
blocks). The inner and outer contacts have their own deflections and angles, and the ball's
equilibrium includes the centrifugal force ``Fc = m dm wm^2 / 2`` and the gyroscopic moment
``Mg = J wR wm sin(beta)`` carried by friction at the outer contact (outer raceway control,
``lambda_o = 2``, ``tan beta = sin a_o / (cos a_o + Dw / dm)``; Jones 1960, Harris & Kotzalas,
*Advanced Concepts*, chapter "Ball bearing kinematics" / "High-speed operation"). The orbital
and spin speeds ``wm``, ``wR`` follow from pure rolling at both contacts with the operating
contact angles.

**Regularization.** ``max(delta, 0)`` is replaced by ``(delta + sqrt(delta^2 + eps^2)) / 2``
(:func:`bearingsim.physics.contact_law.contact_load` with ``smooth = eps``) so that unloaded
balls keep
the equations differentiable. For a loaded contact the load is then too high by the relative
amount ``(3/8) (eps / delta)^2`` (3.75e-7 at ``delta = 1 um`` with the default ``eps = 1 nm``);
a contact that just touches carries ``K (eps/2)^1.5`` (about 1e-4 N for a 7020 ball), and one
with a gap ``g`` carries ``K (eps^2 / (4 g))^1.5``. In the Jones-Harris form a ball that is
unloaded at both contacts floats on these tiny forces: use it at speed (the centrifugal force
seats the ball) or with every ball preloaded.

Loads on the rings are summed per ball with the exact lever from the ring frame's point to the
groove centre (and to the outer contact point for the friction force).

* :mod:`.parameters`: :class:`RowParameters`, :func:`row_parameters`;
* :mod:`.loads`: :func:`row_loads`, :func:`axial_approach`;
* :mod:`.component`: :class:`BallRow`;
* :mod:`.statics`: :func:`row_stiffness`, :func:`row_equilibrium`.
"""

from bearingsim.components.ball_row.component import BallRow
from bearingsim.components.ball_row.loads import axial_approach, row_loads
from bearingsim.components.ball_row.parameters import REFERENCES, RowParameters, row_parameters
from bearingsim.components.ball_row.statics import RowEquilibrium, row_equilibrium, row_stiffness

__all__ = [
    "BallRow",
    "RowParameters",
    "row_parameters",
    "row_loads",
    "axial_approach",
    "row_stiffness",
    "row_equilibrium",
    "RowEquilibrium",
    "REFERENCES",
]
