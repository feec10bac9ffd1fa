"""Quasi-static fidelity of the double-layer bearing: the load through both layers in series.

The shaft carries the inner bearing's inner ring; the middle ring is a free body between the
inner bearing's outer ring and the outer bearing's inner ring; the outer bearing's outer ring sits
in a rigid housing. Each layer is a quasi-static :class:`~bearingsim.components.ball_row.BallRow`
(Hertz contacts, exact rigid-ring kinematics, contact angle from the clearance and the load).
The shaft and the middle ring are *aligned bodies*: they translate freely (x, y and, with
``axial=True``, z) while their tilts are held by the mounting (the spindle's other bearings),
so a single deep-groove row needs no tilt stiffness of its own. Both bodies carry a small mass so
the equilibrium is the steady state of a damped dynamic model, which
:func:`~bearingsim.studies.nested_equilibrium.nested_equilibrium` solves; the exact Jacobians
give the stiffness.
"""

from __future__ import annotations

from bearingsim.catalog import resolve_bearing
from bearingsim.components.aligned_body import AXES, AlignedBody
from bearingsim.components.ball_row import BallRow
from bearingsim.components.middle_ring import middle_ring_structure, mounted_geometries
from bearingsim.components.rings import Housing
from bearingsim.components.rolling_element import load_input_bounds
from bearingsim.language import Assembly, connect
from bearingsim.validation import check_flag

__all__ = ["NestedQuasiStatic"]

class NestedQuasiStatic(Assembly):
    """Quasi-static double-layer bearing: two ball rows in series through a free middle ring.

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner (shaft side) and outer (housing side) bearing.
    structure : {"I", "Z"} or None
        As :class:`~bearingsim.assemblies.double_layer.DoubleLayerBearing` (checked the same
        way: anything else, or "I" when the inner bearing does not fit in the outer one's bore,
        raises :class:`~bearingsim.errors.ParameterError`); for "Z" the outer row sits
        ``(B1 + B2)/2`` axially behind the inner row on the middle ring.
    axial : bool
        Let the bodies move axially (needed for axial loads); with ``False`` the axial
        positions stay centred (a deep-groove bearing with clearance has axial play and no axial
        stiffness without an axial load).
    fits : bool
        Mount both layers with the study's fits (k6 shaft seats, H7 bores): each layer's
        clearance becomes its operating clearance
        (:func:`~bearingsim.components.middle_ring.mounted_geometries`); default False, the
        clearance before mounting (catalogue rows: the CN mean).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Inputs
    ------
    shaft.Fx, shaft.Fy, shaft.Fz [N] : load on the shaft
    """

    def __init__(self, inner="61905", outer="61907", structure: str | None = None,
                 axial: bool = True, fits: bool = False, name="nested"):
        super().__init__(name)
        gi, go = resolve_bearing(inner), resolve_bearing(outer)
        structure = middle_ring_structure(gi, go, structure)
        check_flag(fits, "fits", "double_layer_bearing")
        if fits:
            gi, go = mounted_geometries(gi, go, structure)
        self.structure = structure
        offset = 0.0 if structure == "I" else -(gi.width + go.width) / 2
        free = AXES if axial else ("x", "y")
        self.geometries = (gi, go)
        # the shaft's load passes through both layers, the middle ring's through the outer one
        self.shaft = AlignedBody(free=free, bounds=load_input_bounds(gi, go))
        self.middle = AlignedBody(offsets=(0.0, offset), free=free,
                                  bounds=load_input_bounds(go))
        self.inner_row = BallRow(gi, reference="centred")
        self.outer_row = BallRow(go, reference="centred")
        self.housing = Housing(1)
        connect(self.shaft.frame[0], self.inner_row.inner)
        connect(self.inner_row.outer, self.middle.frame[0])
        connect(self.middle.frame[1], self.outer_row.inner)
        connect(self.outer_row.outer, self.housing.frame[0])


