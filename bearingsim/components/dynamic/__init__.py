"""Dynamic ball-bearing components: balls, race contacts with slice traction, cage, pockets,
land guidance, drag, ring bodies and the viscous drag between the rings (models.md section C;
z is the bearing axis)."""

from bearingsim.components.dynamic.ball import Ball
from bearingsim.components.dynamic.cage import Cage, LandGuidance, PocketContact
from bearingsim.components.dynamic.drag import BallDrag
from bearingsim.components.dynamic.frames import BallFrame, CageFrame
from bearingsim.components.dynamic.race_contact import RaceContact
from bearingsim.components.dynamic.ring import FixedFrame, RingBody, RingLoad, TiltGuide
from bearingsim.components.dynamic.ring_drag import RingDrag
from bearingsim.components.dynamic.static import StaticState, static_state
from bearingsim.physics.bearing_design import BearingDesign, CageDesign, bearing_design

__all__ = [
    "Ball",
    "BallDrag",
    "BallFrame",
    "BearingDesign",
    "Cage",
    "CageDesign",
    "CageFrame",
    "FixedFrame",
    "LandGuidance",
    "PocketContact",
    "RaceContact",
    "RingBody",
    "RingDrag",
    "RingLoad",
    "StaticState",
    "TiltGuide",
    "bearing_design",
    "static_state",
]
