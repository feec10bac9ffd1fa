"""Scenes: a simulation described as data (TOML file or :class:`Scene` dataclass).

``load_scene`` reads and validates a file; ``run_scene`` assembles only what the requested
outputs need (pruning, automatic fidelity), simulates and writes CSV, a JSON summary and plots;
``run_sweep`` runs a scene over a parameter grid on dask.distributed. See ``docs/scenes.md``.
"""

from bearingsim.scenes.expressions import ExpressionError, compile_expression
from bearingsim.scenes.preparation import Prepared, choose_fidelity, prepare, validate_scene
from bearingsim.scenes.registry import REGISTRY, get_spec, register, unregister
from bearingsim.scenes.runner import SceneRun, run_scene
from bearingsim.scenes.scene import (
    Output,
    Scene,
    SceneError,
    Simulation,
    TableInput,
    load_scene,
    parse_scene,
)

__all__ = [
    "REGISTRY",
    "ExpressionError",
    "Output",
    "Prepared",
    "Scene",
    "SceneError",
    "SceneRun",
    "Simulation",
    "TableInput",
    "choose_fidelity",
    "compile_expression",
    "get_spec",
    "load_scene",
    "parse_scene",
    "prepare",
    "register",
    "run_scene",
    "unregister",
    "validate_scene",
]
