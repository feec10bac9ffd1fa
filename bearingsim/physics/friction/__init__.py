"""Bearing friction torque: Palmgren's M0 + M1 model and the SKF four-component model.

Public functions take SI values (torque N m, speed rad/s, dm m, viscosity m^2/s); the published
formulas, which are defined in catalogue units (N mm, r/min, mm, mm^2/s), are evaluated inside after
converting once.

Sign convention: a friction torque returned here is the torque the bearing exerts on the ring that
turns at ``omega_rel`` relative to the other ring. It is opposite in sign to ``omega_rel`` (so the
power ``M * omega_rel <= 0``) and passes smoothly through zero speed,
``M = -|M|(|omega|) * omega_rel / sqrt(omega_rel^2 + omega_reg^2)``, with a regularization speed
``omega_reg`` (default 0.1 rad/s, about 1 r/min: at 0.7 rad/s the torque is 99 % of its magnitude).

* :mod:`.palmgren`: Palmgren's M0 + M1;
* :mod:`.skf`: the SKF four-component model and its tables.
"""

from bearingsim.physics.friction import palmgren, skf
from bearingsim.physics.friction.palmgren import (  # noqa: F401 (in __all__)
    PALMGREN_F1,
    palmgren_f1,
    palmgren_m0,
    palmgren_p1,
    palmgren_torque,
)
from bearingsim.physics.friction.skf import (  # noqa: F401 (in __all__)
    SKF_ANGULAR_CONTACT,
    SKF_CYLINDRICAL_ROLLER,
    SKF_DEEP_GROOVE,
    SKF_KRS,
    SKF_KZ,
    SKF_ROLLER_TYPES,
    SkfFriction,
    SkfSeal,
    skf_friction_components,
    skf_friction_torque,
)

# the public names of the submodules, each imported above by name
__all__ = [*palmgren.__all__, *skf.__all__]
