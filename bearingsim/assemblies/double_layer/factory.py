"""The double-layer bearing's factory: :func:`double_layer_bearing` builds the class of the
fidelity level asked for."""

from __future__ import annotations

import dataclasses

from bearingsim.assemblies.double_layer.dynamic import DynamicDoubleLayerBearing
from bearingsim.assemblies.double_layer.options import (
    _DEFAULT_LUBRICATION,
    DoubleLayerOptions,
    DynamicDoubleLayerOptions,
    _pair,
)
from bearingsim.assemblies.double_layer.quasi_static import NestedQuasiStatic
from bearingsim.assemblies.double_layer.torque import DoubleLayerBearing
from bearingsim.errors import ParameterError
from bearingsim.validation import check_options, keyword_names


def double_layer_bearing(inner="61905", outer="61907", structure=None, fidelity="torque",
                         lubrication=_DEFAULT_LUBRICATION, **kwargs):
    """Build a double-layer bearing assembly.

    ``fidelity="quasi-static"`` returns a
    :class:`.NestedQuasiStatic` (load through both layers in series; keywords ``axial``,
    ``fits``, ``name``; it has no friction, so a ``lubrication`` other than the default
    raises); ``fidelity="dynamic"`` a :class:`DynamicDoubleLayerBearing` built from a
    :class:`~bearingsim.assemblies.double_layer.options.DynamicDoubleLayerOptions` (keywords
    ``drive``, ``speed``, ``loads``, ``massive_balls``, ``rolling_resistance``, ``ring_drag``,
    ``w_middle0``, ``fits``, ``layer_options``, and ``name``); the other levels a
    :class:`DoubleLayerBearing` built from a
    :class:`~bearingsim.assemblies.double_layer.options.DoubleLayerOptions` (keywords
    ``friction_model``, ``drive``, ``speed``, ``lubrication_method``, ``oil_level``,
    ``middle_ring_drag``, ``layer_options``, and ``name``).

    Parameters
    ----------
    inner, outer : str or BearingGeometry
        Inner (shaft side) and outer (housing side) deep-groove bearing.
    structure : {"I", "Z"} or None
        Middle ring type (None: "I" when the inner bearing fits in the outer one's bore).
    fidelity : {"kinematic", "kinematic_approx", "torque", "quasi-static", "dynamic"}
        Fidelity level.
    lubrication : lubricant or (lubricant, lubricant)
        Lubricant of both layers or of (inner, outer).
    **kwargs
        Keywords of the options of the level built for ``fidelity`` (above).

    Returns
    -------
    DoubleLayerBearing or NestedQuasiStatic or DynamicDoubleLayerBearing

    Raises
    ------
    ParameterError
        For a keyword the chosen level does not take (listing the ones it takes), and the
        checks of the level's options.
    """
    if fidelity == "quasi-static":
        where = "double_layer_bearing"
        check_options(kwargs, keyword_names(NestedQuasiStatic, ("inner", "outer", "structure")),
                      where, "keyword(s)", "at fidelity 'quasi-static'",
                      owner=double_layer_bearing)
        if _pair(lubrication) != _pair(_DEFAULT_LUBRICATION):
            raise ParameterError(f"{where}: lubrication = {lubrication!r} is not used: the "
                                 f"quasi-static level has no friction (Hertz load sharing "
                                 f"only); leave lubrication out")
        return NestedQuasiStatic(inner, outer, structure, **kwargs)
    level = DynamicDoubleLayerOptions if fidelity == "dynamic" else DoubleLayerOptions
    context = "at fidelity 'dynamic'" if fidelity == "dynamic" else f"at fidelity {fidelity!r}"
    check_options(kwargs, _option_names(level) + ("name",), "double_layer_bearing",
                  "keyword(s)", context, owner=double_layer_bearing)
    name = kwargs.pop("name", "bearing")
    pair = dict(inner=inner, outer=outer, structure=structure, lubrication=lubrication)
    if fidelity == "dynamic":
        return DynamicDoubleLayerBearing(DynamicDoubleLayerOptions(**pair, **kwargs), name)
    return DoubleLayerBearing(DoubleLayerOptions(**pair, fidelity=fidelity, **kwargs), name)


def _option_names(level: type) -> tuple[str, ...]:
    """The keywords of a level's options that the factory does not take as its own."""
    own = ("inner", "outer", "structure", "fidelity", "lubrication")
    return tuple(f.name for f in dataclasses.fields(level) if f.init and f.name not in own)
