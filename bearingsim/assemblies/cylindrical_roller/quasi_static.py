"""Quasi-static level: the rollers' load distribution (sliced line contacts).

A :class:`~bearingsim.components.roller_row.RollerRow` between the fixed outer ring and an inner
ring held at the imposed misalignment (:class:`~bearingsim.components.misalignment.
MisalignmentGuide`) and loaded radially (:class:`~bearingsim.components.dynamic.RingLoad`); the
inner ring's radial displacement is algebraic, solved by the assembler's Newton blocks from the
numeric equilibrium at the constant loads (:func:`~bearingsim.components.roller_row.
roller_row_equilibrium`; load inputs count as 0 there).
"""

from __future__ import annotations

from bearingsim.assemblies.cylindrical_roller.options import CylindricalRollerOptions
from bearingsim.components.dynamic import FixedFrame, RingLoad
from bearingsim.components.misalignment import MisalignmentGuide
from bearingsim.components.roller_row import (
    RollerRow,
    roller_row_equilibrium,
    roller_row_parameters,
)
from bearingsim.components.rolling_element import check_static_rating, load_input_bounds
from bearingsim.language import Assembly, connect

__all__ = ["QuasiStaticCylindricalRoller"]


class QuasiStaticCylindricalRoller(Assembly):
    """Quasi-static cylindrical roller bearing: roller row, misaligned inner ring, radial load.

    Parameters
    ----------
    options : CylindricalRollerOptions
        The bearing, its clearance, misalignment and loads (checked there).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Attributes
    ----------
    options : CylindricalRollerOptions
    geometry : RollerBearingGeometry
    start : RollerEquilibrium
        The numeric equilibrium at the constant loads (the Newton start).
    """

    def __init__(self, options: CylindricalRollerOptions, name="bearing"):
        super().__init__(name)
        self.options = options
        self.geometry = g = options.geometry
        loads = options.loads
        constant = [float(v) if isinstance(v, (int, float)) else 0.0
                    for v in (loads.get("Fx"), loads.get("Fy"))]
        check_static_rating(g, [*constant, 0.0], "cylindrical_roller_bearing(quasi-static)")
        rp = roller_row_parameters(g, options.clearance)
        self.start = roller_row_equilibrium(rp, g.roller_count, options.n_slices, constant,
                                            options.misalignment)
        self.row = RollerRow(g, options.n_slices, clearance=options.clearance)
        self.housing = FixedFrame()
        self.guide = MisalignmentGuide(*options.misalignment)
        self.load = RingLoad({**loads, "Fz": 0.0, "Mx": 0.0, "My": 0.0},
                             bounds=load_input_bounds(g))
        self.row.inner.guess(x=float(self.start.inner[0]), y=float(self.start.inner[1]))
        connect(self.row.outer, self.housing.frame)
        connect(self.row.inner, self.load.frame, self.guide.frame)
