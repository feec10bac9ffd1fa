"""The deep-groove ball bearing's factory: :func:`deep_groove_ball_bearing` builds the class of the
fidelity level asked for."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

from bearingsim.assemblies.deep_groove.dynamic import DeepGrooveBallBearing
from bearingsim.assemblies.deep_groove.options import FIDELITIES, DeepGrooveOptions
from bearingsim.assemblies.deep_groove.quasi_static import QuasiStaticDeepGroove
from bearingsim.errors import ParameterError
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.physics.lubricant import Lubricant, Oil, as_lubricant
from bearingsim.units import is_quantity
from bearingsim.validation import check_options, check_quantity


def deep_groove_ball_bearing(designation: str = "6304", fidelity: str = "dynamic",
                             lubricant: Lubricant | str = "ISO VG 32",
                             clearance: float | str | None = None, housing: str = "fixed",
                             speed: Callable | float | None = None,
                             loads: dict[str, Any] | None = None, **options: Any):
    """Build a single deep-groove ball bearing at a chosen fidelity.

    Parameters
    ----------
    designation : str or BearingGeometry
        Catalogue designation (``"6304"`` has the validation geometry of
        docs/studies.md, section C).
    fidelity : {"quasi-static", "dynamic", "dynamic_massive_balls"}
        ``"dynamic"``: ball orbit and spin dynamics, cage dynamics, quasi-static ball positions
        (algebraic, solved by the assembler's Newton blocks) as in the study (docs/studies.md,
        section C);
        ``"dynamic_massive_balls"``: the balls' radial and axial motion with inertia too;
        ``"quasi-static"``: the ``BallRow`` of the duplex pairs (Hertz load sharing only).
    lubricant : Lubricant or str
        ``Oil``, ``Grease``, ``Dry`` or a name for
        :func:`~bearingsim.physics.lubricant.get_lubricant`.
    clearance : float or str, optional
        Diametral clearance Pd [m], or a number with a unit (``"20 um"``); default: catalogue
        (at every fidelity).
    housing : {"fixed"}
        The outer ring is fixed to a rigid housing (the only option of the dynamic levels).
    speed : callable or float or str or None
        Inner-ring speed [rad/s] (or a number with a unit, ``"3000 rpm"``). Dynamic levels:
        a function of time, a constant or ``None`` (input ``shaft_speed``). Quasi-static
        level: a constant >= 0 (centrifugal and gyroscopic ball loads when > 0) or ``None``
        for a bearing at rest (no input); a function of time raises
        :class:`~bearingsim.errors.ParameterError`.
    loads : dict, optional
        External loads on the inner ring, ``Fx, Fy, Fz`` [N], ``Mx, My`` [N m]; finite
        constants, functions of time or None (inputs); other keys raise
        :class:`~bearingsim.errors.ParameterError`. At the quasi-static level the shaft holds
        the ring straight and takes the moments: ``Mx, My`` must then be absent or 0.
    **options
        Dynamic levels only: the fields of the option groups of
        :class:`~bearingsim.assemblies.deep_groove.options.DeepGrooveOptions` by name
        (:class:`~bearingsim.assemblies.deep_groove.options.RingOptions`: ``drive``,
        ``free_tilt``, ...; :class:`~bearingsim.assemblies.deep_groove.options.FilmOptions`:
        ``damping``, ``n_slices``, ``drag``, ``traction_scale``, ...;
        :class:`~bearingsim.assemblies.deep_groove.options.CageOptions`: ``pocket_mu``,
        ``land_mu``, ``cage_damping``), ``name``, and ``pocket_clearance``,
        ``guide_clearance`` of :func:`~bearingsim.physics.bearing_design.bearing_design`;
        another name raises :class:`~bearingsim.errors.ParameterError` listing the accepted
        ones. The quasi-static level takes none and raises
        :class:`~bearingsim.errors.ParameterError` if any is given.

    Returns
    -------
    DeepGrooveBallBearing or QuasiStaticDeepGroove
    """
    if fidelity not in FIDELITIES:
        raise ParameterError(f"deep_groove_ball_bearing: fidelity must be one of "
                             f"{', '.join(FIDELITIES)}, got {fidelity!r}")
    if housing != "fixed":
        raise ParameterError(f"deep_groove_ball_bearing: housing must be 'fixed', got "
                             f"{housing!r}")
    lub = as_lubricant(lubricant, "deep_groove_ball_bearing")
    if not isinstance(lub, (Lubricant, Oil)):
        raise ParameterError(f"deep_groove_ball_bearing: lubricant must be a Lubricant or a "
                             f"name, got {type(lubricant).__name__}")
    if fidelity == "quasi-static" and options:
        raise ParameterError(f"deep_groove_ball_bearing: the quasi-static level takes no "
                             f"options (they belong to the dynamic levels), got "
                             f"{', '.join(sorted(options))}")
    if clearance is not None:  # its range is bearing_design's to check
        clearance = check_quantity(clearance, "clearance", "m", where="deep_groove_ball_bearing")
    if isinstance(speed, str) or is_quantity(speed):  # a number with a unit: "3000 rpm"
        speed = check_quantity(speed, "speed", "rad/s", where="deep_groove_ball_bearing")
    cage_keys = ("pocket_clearance", "guide_clearance")
    if options:
        check_options(options, DeepGrooveOptions.keyword_names() + ("name",) + cage_keys,
                      "deep_groove_ball_bearing", "option(s)", f"at fidelity {fidelity!r}",
                      owner=deep_groove_ball_bearing)
    design = bearing_design(designation, clearance,
                            **{k: options.pop(k) for k in cage_keys if k in options})
    if fidelity == "quasi-static":
        geometry = dataclasses.replace(design.geometry, diametral_clearance=design.clearance)
        return QuasiStaticDeepGroove(geometry, loads, 0.0 if speed is None else speed)
    name = options.pop("name", "bearing")
    return DeepGrooveBallBearing(design, lub, DeepGrooveOptions.from_keywords(
        massive_balls=fidelity == "dynamic_massive_balls", speed=speed, loads=loads, **options),
        name=name)
