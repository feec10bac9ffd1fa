"""Double-layer (nested) ball bearings, I-type and Z-type (docs/studies.md, section A), as a
product: options, fidelity levels, factory and scene face.

Two deep-groove ball bearings are nested: the inner bearing's outer ring, an intermediate sleeve
and the outer bearing's inner ring form the *middle ring*, three bodies joined rigidly by
connections (the assembler's alias elimination and index reduction merge them). The shaft drives
the inner bearing's inner ring; the outer bearing's outer ring sits in the housing. Friction
drags the middle ring to a speed ``n_z``; the speed distribution ratio is ``Rs = n_z / n_i``.

* :mod:`.options`: fidelity levels, friction models, the layer options each level takes, and
  the levels' options checked once: :class:`DoubleLayerOptions` (with each layer's lubrication
  method and oil-bath level, the middle ring's oil gap), :class:`DynamicDoubleLayerOptions`;
* :mod:`.speed`: the limiting shaft speed and the speed ratio ``Rs``;
* :mod:`.base`: what the torque and dynamic levels share (the shaft, its speed variables and
  drive), :class:`~.base.PartialDoubleLayer`;
* :mod:`.torque`: pure rolling (``kinematic``) and friction torque (``torque``, Palmgren or SKF),
  :class:`DoubleLayerBearing` with each layer's element;
* :mod:`.quasi_static`: load sharing (``quasi-static``), :class:`NestedQuasiStatic`;
* :mod:`.dynamic`: ball and cage dynamics of both layers (``dynamic``),
  :class:`DynamicDoubleLayerBearing`;
* :mod:`.factory`: :func:`double_layer_bearing`;
* :mod:`.figures`: the steady speed ratio against shaft speed;
* :mod:`.scene`: :data:`SCENE_SPEC` (arguments, the build from a scene, each layer's life and
  the total friction power).
"""

from bearingsim.assemblies.double_layer.dynamic import DynamicDoubleLayerBearing
from bearingsim.assemblies.double_layer.factory import double_layer_bearing
from bearingsim.assemblies.double_layer.options import (
    FIDELITIES,
    FRICTION_MODELS,
    DoubleLayerOptions,
    DynamicDoubleLayerOptions,
    LayerPairOptions,
    layer_option_names,
)
from bearingsim.assemblies.double_layer.quasi_static import NestedQuasiStatic
from bearingsim.assemblies.double_layer.scene import SCENE_SPEC, double_layer_from_scene
from bearingsim.assemblies.double_layer.speed import (
    RS_REGULARIZATION,
    shaft_speed_limit,
    speed_ratio,
)
from bearingsim.assemblies.double_layer.torque import DoubleLayerBearing

__all__ = [
    "DoubleLayerBearing",
    "DoubleLayerOptions",
    "DynamicDoubleLayerBearing",
    "DynamicDoubleLayerOptions",
    "FIDELITIES",
    "FRICTION_MODELS",
    "LayerPairOptions",
    "NestedQuasiStatic",
    "RS_REGULARIZATION",
    "SCENE_SPEC",
    "double_layer_bearing",
    "double_layer_from_scene",
    "layer_option_names",
    "shaft_speed_limit",
    "speed_ratio",
]
