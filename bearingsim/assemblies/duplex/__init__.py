"""Duplex pairs of angular contact ball bearings, DF, DB and DT, as a product (docs/studies.md,
section B).

A rigid shaft runs in two quasi-static ball rows (:class:`~bearingsim.components.ball_row.
BallRow`). Each row's inner ring sits on the shaft, its outer ring in the housing. The rows lie
at ``z = L1`` (row 0) and ``z = -L2`` (row 1) from the shaft's centre of mass. Arrangements
(the axial direction ``s`` in which each row's inner ring must move to load it):

* **DB** (back-to-back, "O"): ``s = (-1, +1)``; the contact lines meet the axis outside the
  rows, at the pressure centres ``z = L1 + (dm/2) tan a`` and ``-L2 - (dm/2) tan a``.
* **DF** (face-to-face, "X"): ``s = (+1, -1)``; pressure centres ``L1 - (dm/2) tan a`` and
  ``-L2 + (dm/2) tan a``, so the tilt stiffness is lower than DB's.
* **DT** (tandem): ``s = (+1, +1)``; both rows carry thrust in +z and share it.

The inner and outer spacers between the rows differ in width; after clamping, row 1's inner
ring sits ``width_difference`` further along the axis than in the reference configuration in
which its balls just touch. The model represents the clamped stack exactly by a
:class:`~bearingsim.components.rings.Spacer` of zero lever between the shaft's row-1 frame and
row 1's inner ring, carrying the mounting offset (and the preload as its force). A DT pair is
preloaded by a constant axial (spring) force on the shaft instead.

* :mod:`.shaft`: :class:`ShaftSpec`;
* :mod:`.preload`: arrangements, preload classes, offsets and preload stiffness;
* :mod:`.limits`: the pair's static load rating (ISO 76 rules for pairs) as the bounds of the
  shaft's load inputs and the check of constant loads, and its limiting speed;
* :mod:`.options`: :class:`DuplexOptions`, everything a pair is built from, checked once;
* :mod:`.pair`: :class:`DuplexPair` (built from a :class:`DuplexOptions`), :func:`duplex_pair`
  (from keywords);
* :mod:`.figures`: natural frequencies by mode name over a run; mode names of a
  ``modes`` scene;
* :mod:`.scene`: :data:`SCENE_SPEC`.
"""

from bearingsim.assemblies.duplex.options import DuplexOptions
from bearingsim.assemblies.duplex.pair import DuplexPair, duplex_pair
from bearingsim.assemblies.duplex.preload import (
    ARRANGEMENTS,
    PRELOAD_CLASSES,
    PRELOAD_FRACTIONS,
    offset_preload,
    preload_force,
    preload_offset,
    preload_stiffness,
)
from bearingsim.assemblies.duplex.scene import SCENE_SPEC
from bearingsim.assemblies.duplex.shaft import ShaftSpec

__all__ = ["ShaftSpec", "DuplexOptions", "DuplexPair", "duplex_pair", "ARRANGEMENTS",
           "PRELOAD_CLASSES", "PRELOAD_FRACTIONS", "SCENE_SPEC", "preload_offset", "preload_force",
           "offset_preload", "preload_stiffness"]
