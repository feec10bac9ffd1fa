"""The double-layer bearing's factory: :func:`double_layer_bearing` builds the class of the
fidelity level asked for."""

from __future__ import annotations

from bearingsim.assemblies.double_layer.dynamic import DynamicDoubleLayerBearing
from bearingsim.assemblies.double_layer.options import _pair
from bearingsim.assemblies.double_layer.quasi_static import NestedQuasiStatic
from bearingsim.assemblies.double_layer.torque import DoubleLayerBearing
from bearingsim.errors import ParameterError
from bearingsim.validation import (
    check_options,
    keyword_names,
)

_DEFAULT_LUBRICATION = ("ISO VG 32", "ISO VG 32")


def double_layer_bearing(inner="61905", outer="61907", structure=None, fidelity="torque",
                         lubrication=_DEFAULT_LUBRICATION, **kwargs):
    """Build a double-layer bearing assembly.

    ``fidelity="quasi-static"`` returns a
    :class:`.NestedQuasiStatic` (load through both layers in series; keywords ``axial``,
    ``name``; it has no friction, so a ``lubrication`` other than the default raises);
    ``fidelity="dynamic"`` a :class:`DynamicDoubleLayerBearing`
    (keywords ``drive``, ``speed``, ``loads``, ``massive_balls``, ``rolling_resistance``,
    ``ring_drag``, ``w_middle0``, ``layer_options``, ``name``); the other levels a
    :class:`DoubleLayerBearing` (keywords ``friction_model``, ``drive``, ``speed``,
    ``layer_options``, ``name``).

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
        Keywords of the class built for ``fidelity`` (above).

    Returns
    -------
    DoubleLayerBearing or NestedQuasiStatic or DynamicDoubleLayerBearing

    Raises
    ------
    ParameterError
        For a keyword the chosen level does not take (listing the ones it takes), and the
        checks of the class built.
    """
    if fidelity == "quasi-static":
        where = "double_layer_bearing"
        check_options(kwargs, keyword_names(NestedQuasiStatic, ("inner", "outer", "structure")),
                      where, "keyword(s)", "at fidelity 'quasi-static'")
        if _pair(lubrication) != _pair(_DEFAULT_LUBRICATION):
            raise ParameterError(f"{where}: lubrication = {lubrication!r} is not used: the "
                                 f"quasi-static level has no friction (Hertz load sharing "
                                 f"only); leave lubrication out")
        return NestedQuasiStatic(inner, outer, structure, **kwargs)
    if fidelity == "dynamic":
        check_options(kwargs, keyword_names(DynamicDoubleLayerBearing,
                                            ("inner", "outer", "structure", "lubrication")),
                      "double_layer_bearing", "keyword(s)", "at fidelity 'dynamic'")
        return DynamicDoubleLayerBearing(inner, outer, structure, lubrication, **kwargs)
    check_options(kwargs, keyword_names(DoubleLayerBearing,
                                        ("inner", "outer", "structure", "fidelity",
                                         "lubrication")),
                  "double_layer_bearing", "keyword(s)", f"at fidelity {fidelity!r}")
    return DoubleLayerBearing(inner, outer, structure, fidelity, lubrication, **kwargs)
