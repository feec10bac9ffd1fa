"""The factory of the cylindrical roller bearing: options in, the model of the chosen level
out."""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies.cylindrical_roller.options import CylindricalRollerOptions
from bearingsim.assemblies.cylindrical_roller.quasi_static import QuasiStaticCylindricalRoller
from bearingsim.assemblies.cylindrical_roller.torque import CylindricalRollerTorque
from bearingsim.catalog.rollers import RollerBearingGeometry
from bearingsim.validation import check_options, keyword_names

__all__ = ["cylindrical_roller_bearing"]


def cylindrical_roller_bearing(designation: str | RollerBearingGeometry = "NU206",
                               fidelity: str = "quasi-static", **options: Any
                               ) -> QuasiStaticCylindricalRoller | CylindricalRollerTorque:
    """Build a cylindrical roller bearing (NU type) at a chosen fidelity.

    Parameters
    ----------
    designation : str or RollerBearingGeometry
        Catalogue designation (:func:`~bearingsim.catalog.rollers.list_roller_bearings`: NU 204
        to NU 212, NU 304 to NU 312) or geometry.
    fidelity : {"quasi-static", "torque"}
        ``"quasi-static"``: the rollers' load distribution (sliced line contacts, clearance,
        misalignment); ``"torque"``: the friction torque between shaft and housing (Palmgren or
        SKF).
    **options
        The fields of :class:`~bearingsim.assemblies.cylindrical_roller.options.
        CylindricalRollerOptions` (``clearance``, ``misalignment``, ``n_slices``, ``loads``,
        ``lubricant``, ``friction_model``); another name raises
        :class:`~bearingsim.errors.ParameterError` naming the accepted ones.

    Returns
    -------
    QuasiStaticCylindricalRoller or CylindricalRollerTorque

    Examples
    --------
    >>> from bearingsim.assemblies.cylindrical_roller import cylindrical_roller_bearing
    >>> bearing = cylindrical_roller_bearing("NU206", loads={"Fx": 5000.0})
    >>> bearing.geometry.roller_count
    12
    """
    check_options(options, keyword_names(CylindricalRollerOptions, ("bearing", "fidelity")),
                  "cylindrical_roller_bearing", "option(s)", f"at fidelity {fidelity!r}",
                  owner=cylindrical_roller_bearing)
    opts = CylindricalRollerOptions(designation, fidelity, **options)
    if opts.fidelity == "torque":
        return CylindricalRollerTorque(opts)
    return QuasiStaticCylindricalRoller(opts)
