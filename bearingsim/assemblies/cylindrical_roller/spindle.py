"""A spindle: a duplex pair of angular contact ball bearings as the locating bearing at the nose
and a cylindrical roller bearing (NU) as the non-locating bearing at the rear.

The :class:`~bearingsim.assemblies.duplex.DuplexPair` (its shaft, rows, rings, spacers and
preload as built by :func:`~bearingsim.assemblies.duplex.duplex_pair`) is used whole; the roller
row's inner ring sits on the same shaft, joined rigidly to the shaft frame of the rear duplex row
by an :class:`~bearingsim.components.rings.InnerRing` whose raceway lies ``roller_distance``
further back, and its outer ring in a rigid housing. The NU bearing carries radial load and
the tilt of the shaft at its position (a misalignment that follows from the deflection of the
pair), no axial load: the duplex pair locates the shaft.

The axial load input ``pair.shaft.Fz`` is held to the pair's static load rating (it all passes
through the pair); the radial forces and moments are shared by the pair and the NU bearing as
their stiffnesses decide, so no one load bounds them and they are left unbounded.
"""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies.duplex import ARRANGEMENTS, PRELOAD_CLASSES, ShaftSpec, duplex_pair
from bearingsim.assemblies.duplex.figures import MODE_NAMES_BY_STATE
from bearingsim.assemblies.spec import ArgSpec, AssemblySpec, given_args, single_level
from bearingsim.catalog.rollers import find_roller_bearing, list_roller_bearings
from bearingsim.components.dynamic import FixedFrame
from bearingsim.components.rings import InnerRing
from bearingsim.components.roller_row import RollerRow
from bearingsim.language import Assembly, connect
from bearingsim.validation import check_quantity

__all__ = ["SPINDLE_SCENE_SPEC", "Spindle", "spindle"]

DEFAULT_SHAFT = ShaftSpec(diameter=0.070, length=0.500, row_spacing=0.040, centre_offset=0.150)
"""A 70 mm steel spindle shaft 500 mm long, the duplex rows 40 mm apart with their midpoint
150 mm ahead of the centre of mass (the nose)."""


class Spindle(Assembly):
    """Spindle on a duplex pair (locating) and a cylindrical roller bearing (non-locating).

    Parameters
    ----------
    bearing : str or BearingGeometry
        Angular contact bearing of both duplex rows.
    roller_bearing : str or RollerBearingGeometry
        The NU bearing.
    arrangement : {"DF", "DB", "DT"}
    preload : str or float, optional
        Preload class or axial preload [N] of the pair (:class:`DuplexPair`).
    roller_distance : float
        Axial distance from the rear duplex row to the NU bearing [m], > 0.
    n_slices : int
        Slices per roller.
    shaft : ShaftSpec or dict, optional
        Default :data:`DEFAULT_SHAFT`.
    name : str
        Instance name (the prefix of its variables' dotted names).
    **pair_options
        Further keywords of :func:`~bearingsim.assemblies.duplex.duplex_pair`
        (``damping_ratio``, ``speed``, ...).
    """

    def __init__(self, bearing: str = "7014C", roller_bearing: str = "NU210",
                 arrangement: str = "DB", preload: str | float | None = None,
                 roller_distance: float = 0.330, n_slices: int = 5,
                 shaft: ShaftSpec | dict | None = None, name="spindle", **pair_options: Any):
        super().__init__(name)
        roller_distance = check_quantity(roller_distance, "roller_distance", "m", 0.0,
                                         low_inclusive=False, where="spindle")
        self.pair = duplex_pair(bearing, arrangement, preload,
                                shaft=DEFAULT_SHAFT if shaft is None else shaft, name="pair",
                                shared_radial=True, **pair_options)
        self.roller_distance = float(roller_distance)
        self.nu_ring = InnerRing(groove_offset=-self.roller_distance)
        self.nu = RollerRow(roller_bearing, n_slices)
        self.nu_housing = FixedFrame()
        connect(self.pair.shaft.frame[1], self.nu_ring.frame_a)
        connect(self.nu_ring.frame_b, self.nu.inner)
        connect(self.nu.outer, self.nu_housing.frame)


def spindle(bearing: str = "7014C", roller_bearing: str = "NU210", arrangement: str = "DB",
            preload: str | float | None = None, **options: Any) -> Spindle:
    """Build a spindle; see :class:`Spindle` for the parameters.

    Parameters
    ----------
    bearing : str
        Catalogue designation of the angular contact bearing of both duplex rows.
    roller_bearing : str
        Catalogue designation of the NU bearing.
    arrangement : {"DF", "DB", "DT"}
        Arrangement of the duplex pair.
    preload : str or float, optional
        Preload class ("light", "medium", "heavy") or axial preload [N], > 0, of the pair.
    **options
        Further keywords of :class:`Spindle`.

    Returns
    -------
    Spindle
        The spindle assembly.

    Examples
    --------
    >>> from bearingsim.assemblies.cylindrical_roller.spindle import spindle
    >>> s = spindle("7014C", "NU210", "DB", preload="light")
    >>> round(s.pair.preload_force)
    412
    """
    return Spindle(bearing, roller_bearing, arrangement, preload, **options)


def _spindle_from_scene(args: dict[str, Any], fidelity: str) -> Spindle:
    """Build the spindle from the scene arguments (defaults filled in; one level)."""
    return spindle(**given_args(args))


SPINDLE_SCENE_SPEC = AssemblySpec(
    name="spindle",
    description="spindle: a duplex pair of angular contact ball bearings (locating, nose) and a "
                "cylindrical roller bearing NU (non-locating, rear) on a rigid shaft; inputs "
                "pair.shaft.Fx, Fy, Fz [N], Mx, My [N m]",
    build=_spindle_from_scene,
    args={
        "bearing": ArgSpec("bearing", "7014C", "angular contact bearing of the pair"),
        "roller_bearing": ArgSpec("bearing", "NU210", "the NU bearing",
                                  known=list_roller_bearings,
                                  find=find_roller_bearing),
        "arrangement": ArgSpec("choice", "DB", "arrangement of the pair",
                               choices=tuple(ARRANGEMENTS)),
        "preload": ArgSpec("choice", "light", "preload class of the pair",
                           choices=PRELOAD_CLASSES),
        "roller_distance": ArgSpec("float", 0.330, "rear duplex row to NU bearing [m]",
                                   low=0.0),
        "damping_ratio": ArgSpec("float", None, "damping ratio of the shaft against the "
                                 "housing [-] (default: none)", low=0.0, high=1.0,
                                 low_inclusive=True),
    },
    **single_level("quasi-static"),
    default_outputs=["pair.shaft.x", "pair.shaft.ty", "nu.Q[0]"],
    optional_inputs=("pair.shaft.*",),
    mode_names={f"pair.{state}": name for state, name in MODE_NAMES_BY_STATE.items()},
)
"""The spindle as a scene assembly (:mod:`bearingsim.scenes`)."""
