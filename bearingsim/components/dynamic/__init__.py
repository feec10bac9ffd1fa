"""Dynamic ball-bearing components: balls, race contacts with slice traction, cage, pockets,
land guidance, drag, ring bodies and the viscous drag between the rings (docs/studies.md, section C;
z is the bearing axis)."""

from bearingsim.components.dynamic.ball import Ball
from bearingsim.components.dynamic.cage import Cage, LandGuidance, PocketContact
from bearingsim.components.dynamic.drag import BallDrag
from bearingsim.components.dynamic.race_contact import RaceContact
from bearingsim.components.dynamic.ring import FixedFrame, RingBody, RingLoad, TiltGuide
from bearingsim.components.dynamic.ring_drag import RingDrag

__all__ = [
    "Ball",
    "BallDrag",
    "Cage",
    "FixedFrame",
    "LandGuidance",
    "PocketContact",
    "RaceContact",
    "RingBody",
    "RingDrag",
    "RingLoad",
    "TiltGuide",
]
