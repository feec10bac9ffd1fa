"""Assemblies a scene can name: their arguments, fidelity levels and what each level provides.

Every entry is an :class:`AssemblySpec`: a factory, the arguments a scene may give (with their
allowed values), the fidelity levels from lowest to highest, a table *output pattern -> lowest
fidelity that provides it* (used by ``fidelity = "auto"``), quantities computed after the
integration (post-processing) and a symmetry hook.

The table is conservative: a name that no pattern matches needs the assembly's highest automatic
fidelity. For the double-layer bearing, the kinematic level provides the speeds and the speed
ratio ``Rs`` (pure rolling), but its shaft torque is a numerical drag, not a friction torque, so
``M_shaft`` needs the torque level.
"""

from __future__ import annotations

import fnmatch
import importlib
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = [
    "ArgSpec",
    "AssemblySpec",
    "PostQuantity",
    "REGISTRY",
    "get_spec",
    "register",
    "min_fidelity",
]


@dataclass(frozen=True)
class ArgSpec:
    """One argument a scene may give to an assembly factory.

    ``kind`` is one of ``"bearing"`` (catalogue designation), ``"lubricant"`` (name, or a list of
    one name per layer), ``"choice"`` (one of ``choices``), ``"float"`` (a number, optionally
    with ``low``), ``"bool"``, ``"table"`` (a TOML table validated by ``table`` specs) or
    ``"floats"`` (a table of named numbers) or ``"signal"`` (a number or an expression of
    ``t``, see :mod:`bearingsim.scenes.expressions`).
    """

    kind: str
    default: Any = None
    doc: str = ""
    choices: tuple = ()
    low: float | None = None
    table: dict[str, ArgSpec] | None = None


@dataclass(frozen=True)
class PostQuantity:
    """A quantity computed from the saved series after the integration.

    ``needs`` are model variables the computation reads (added to the assembled outputs);
    ``compute(series, context)`` gets a dict name -> array and returns an array.
    """

    name: str
    unit: str
    doc: str
    needs: tuple[str, ...]
    compute: Callable[[dict[str, np.ndarray], dict[str, Any]], np.ndarray]
    fidelity: str


@dataclass
class AssemblySpec:
    """What the scene layer knows about an assembly factory."""

    name: str
    description: str
    build: Callable[[dict[str, Any], str], Any]
    """``build(args, fidelity) -> Component``."""
    args: dict[str, ArgSpec]
    fidelities: tuple[str, ...]
    """All levels, lowest first."""
    auto_fidelities: tuple[str, ...]
    """Levels ``auto`` may choose, lowest first."""
    output_fidelity: list[tuple[str, str]]
    """(fnmatch pattern of an output, input or parameter name, lowest fidelity providing it)."""
    default_outputs: list[str]
    post: Callable[[dict[str, Any]], dict[str, PostQuantity]] = lambda args: {}
    """Post-processed quantities for the given arguments."""
    parametric_args: dict[str, Callable[[dict[str, Any]], bool]] = field(default_factory=dict)
    """Arguments that only change parameter values (for sweeps without re-assembly), with a
    predicate on the other arguments that says when this holds."""
    symmetry: Callable[[dict[str, Any], dict[str, Any]], list[str]] = lambda args, inputs: []
    """``symmetry(args, inputs)`` -> notes on symmetric parts solved once."""
    symmetric_args: Callable[[dict[str, Any], dict[str, Any]], dict[str, Any]] = (
        lambda args, inputs: {})
    """``symmetric_args(args, inputs)`` -> assembly arguments that build the reduced model the
    loads allow (merged into the arguments before building)."""
    fidelity_arg: str | None = "fidelity"

    def with_defaults(self, args: dict[str, Any]) -> dict[str, Any]:
        """The arguments with the defaults of the ones not given (nested tables too)."""
        return _defaults(self.args, args)


def _defaults(specs: dict[str, ArgSpec], args: dict[str, Any]) -> dict[str, Any]:
    out = {}
    for key, spec in specs.items():
        if key in args:
            val = args[key]
            if spec.kind == "table" and isinstance(val, dict):
                val = _defaults(spec.table or {}, val)
            out[key] = val
        elif spec.kind == "table":
            out[key] = _defaults(spec.table or {}, {})
        else:
            out[key] = spec.default
    return out


def min_fidelity(spec: AssemblySpec, name: str) -> str:
    """Lowest fidelity that provides ``name`` (an output, input or parameter name)."""
    for pattern, fid in spec.output_fidelity:
        if fnmatch.fnmatchcase(name, pattern):
            return fid
    return spec.auto_fidelities[-1]


# --------------------------------------------------------------------------- double layer
_DL_KINEMATIC = ["Rs", "w_shaft", "w_middle", "shaft_speed", "middle.*", "shaft.phi",
                 "drive.*", "der(*phi)"]


def _lub_pair(value):
    return tuple(value) if isinstance(value, (list, tuple)) else (value, value)


def _build_double_layer(args: dict[str, Any], fidelity: str, drive: str = "speed"):
    from bearingsim.assemblies import double_layer_bearing

    opts = {k: v for k, v in (args.get("layer_options") or {}).items() if v is not None}
    return double_layer_bearing(
        args["inner"], args["outer"], structure=args.get("structure"), fidelity=fidelity,
        lubrication=_lub_pair(args["lubrication"]), friction_model=args["friction_model"],
        drive=drive, layer_options=opts or None,
    )


def _life_quantities(args: dict[str, Any], prefix: str) -> dict[str, PostQuantity]:
    """ISO 281 basic rating life [h] of each layer and the total friction power."""
    from bearingsim.catalog import get_bearing

    out: dict[str, PostQuantity] = {}
    load_prefix = prefix
    for layer, designation in (("inner_layer", args["inner"]), ("outer_layer", args["outer"])):
        try:
            g = get_bearing(designation)
        except Exception:  # noqa: BLE001 - validated elsewhere; no life without catalogue data
            continue
        if g.dynamic_load_rating is None or g.static_load_rating is None:
            continue
        out[f"{prefix}{layer}.L10h"] = PostQuantity(
            f"{prefix}{layer}.L10h", "h",
            f"ISO 281 basic rating life of the {layer.replace('_', ' ')} ({designation}) at the "
            "momentary load and relative speed (inf when unloaded or at rest)",
            (f"{load_prefix}Fr", f"{load_prefix}Fa", f"{prefix}{layer}.w_rel"),
            _life_fn(g, f"{load_prefix}Fr", f"{load_prefix}Fa", f"{prefix}{layer}.w_rel"),
            "torque",
        )
    out[f"{prefix}P_loss_total"] = PostQuantity(
        f"{prefix}P_loss_total", "W", "friction power of both layers",
        (f"{prefix}inner_layer.P_loss", f"{prefix}outer_layer.P_loss"),
        lambda s, c, a=f"{prefix}inner_layer.P_loss", b=f"{prefix}outer_layer.P_loss":
            s[a] + s[b],
        "torque",
    )
    return out


def _life_fn(g, fr_name: str, fa_name: str, w_name: str):
    from bearingsim.physics.life import equivalent_dynamic_load, static_factor

    f0 = static_factor(g.ball_diameter, g.pitch_diameter, g.contact_angle)

    def compute(series, context):
        fr = np.abs(np.asarray(series[fr_name], dtype=float))
        fa = np.abs(np.asarray(series[fa_name], dtype=float))
        w = np.abs(np.asarray(series[w_name], dtype=float))
        life_h = np.full(fr.shape, np.inf)
        loaded = (fr + fa > 0.0) & (w > 0.0)
        if np.any(loaded):
            p = np.asarray(
                equivalent_dynamic_load(fr[loaded], fa[loaded], g.static_load_rating, f0,
                                        g.contact_angle), dtype=float)
            ok = p > 0.0
            life = np.full(p.shape, np.inf)
            life[ok] = (g.dynamic_load_rating / p[ok]) ** 3
            life_h[loaded] = life * 1e6 * 2.0 * np.pi / (3600.0 * w[loaded])
        return life_h

    return compute


def _dl_args() -> dict[str, ArgSpec]:
    return {
        "inner": ArgSpec("bearing", "61905", "inner (shaft-side) deep-groove bearing"),
        "outer": ArgSpec("bearing", "61907", "outer (housing-side) deep-groove bearing"),
        "structure": ArgSpec("choice", None, "middle ring type (default: I if it fits, else Z)",
                             choices=("I", "Z")),
        "lubrication": ArgSpec("lubricant", "ISO VG 32",
                               "lubricant of both layers, or [inner, outer]"),
        "friction_model": ArgSpec("choice", "palmgren", "friction torque model (torque level)",
                                  choices=("palmgren", "skf")),
        "layer_options": ArgSpec("table", None, "options of the friction elements", table={
            "smooth": ArgSpec("bool", None, "smooth blend of the Palmgren M0 branches"),
            "load_dependent": ArgSpec("bool", None, "include the load-dependent torque M1"),
            "omega_reg": ArgSpec("float", None, "friction sign regularization speed [rad/s]",
                                 low=0.0),
        }),
    }


def _palmgren(args: dict[str, Any]) -> bool:
    return args.get("friction_model", "palmgren") == "palmgren"


def _no_symmetry(args, inputs) -> list[str]:
    return []


DOUBLE_LAYER = AssemblySpec(
    name="double_layer_bearing",
    description="I/Z-type double-layer (nested) ball bearing driven at an imposed shaft speed "
                "(input shaft_speed [rad/s]; torque level adds the loads Fr, Fa [N])",
    build=_build_double_layer,
    args=_dl_args(),
    fidelities=("kinematic_approx", "kinematic", "torque"),
    auto_fidelities=("kinematic", "torque"),
    output_fidelity=[(p, "kinematic") for p in _DL_KINEMATIC],
    default_outputs=["w_shaft", "w_middle", "Rs", "M_shaft"],
    post=lambda args: _life_quantities(args, ""),
    parametric_args={"lubrication": _palmgren},
    symmetry=_no_symmetry,
)


# --------------------------------------------------------------------------- motor drive
def _build_motor_drive(args: dict[str, Any], fidelity: str):
    from bearingsim.assemblies import motor_drive
    from bearingsim.scenes.expressions import compile_expression

    bearing = _build_double_layer(args["bearing"], fidelity, drive="flange")
    motor_options = {k: v for k, v in (args.get("motor_options") or {}).items()}
    load = args.get("load_torque", 0.0)
    # motor_drive(load_torque=None) does not yet give a usable input load.tau_in (see
    # tests/stress/test_stress_inputs.py), so the load is an argument: a number or expression
    load = (compile_expression(load, "assembly.load_torque") if isinstance(load, str)
            else float(load))
    return motor_drive(bearing, motor=args["motor"], speed_ref=None, load_torque=load,
                       shaft_inertia=args["shaft_inertia"], motor_options=motor_options or None)


MOTOR_DRIVE = AssemblySpec(
    name="motor_drive",
    description="speed-controlled DC or PMSM motor -> shaft inertia -> double-layer bearing; "
                "inputs motor.w_ref [rad/s], bearing.Fr, bearing.Fa [N] (torque level); the "
                "load torque is the argument load_torque",
    build=_build_motor_drive,
    args={
        "motor": ArgSpec("choice", "dc", "motor type with its PI speed control",
                         choices=("dc", "pmsm")),
        "load_torque": ArgSpec("signal", 0.0, "load torque on the shaft [N m] (positive drives "
                               "it): a number or an expression of t"),
        "shaft_inertia": ArgSpec("float", 1e-3, "shaft and spindle inertia [kg m^2]", low=0.0),
        "motor_options": ArgSpec("floats", None, "motor and controller constants (e.g. kp_w, "
                                 "ki_w for the PMSM, kp, ki, R, L, k, J for the DC motor)"),
        "bearing": ArgSpec("table", None, "the double-layer bearing", table=_dl_args()),
    },
    fidelities=("kinematic_approx", "kinematic", "torque"),
    auto_fidelities=("kinematic", "torque"),
    output_fidelity=[("bearing." + p, "kinematic") for p in _DL_KINEMATIC]
    + [("motor.w_ref", "kinematic")],
    default_outputs=["shaft.w", "bearing.w_middle", "bearing.Rs", "bearing.M_shaft"],
    post=lambda args: _life_quantities(args["bearing"], "bearing."),
    parametric_args={"bearing.lubrication": lambda a: _palmgren(a.get("bearing", {}))},
    symmetry=_no_symmetry,
)

REGISTRY: dict[str, AssemblySpec] = {}
"""Assembly name -> spec."""


def register(spec: AssemblySpec) -> AssemblySpec:
    """Add (or replace) an assembly spec; returns it."""
    REGISTRY[spec.name] = spec
    return spec


register(DOUBLE_LAYER)
register(MOTOR_DRIVE)

_OPTIONAL = (
    ("bearingsim.scenes.registry_extra", "register_extra"),
)


def _load_optional() -> None:
    """Register assemblies whose modules may not exist yet (duplex pair, deep-groove bearing)."""
    for module, fn in _OPTIONAL:
        try:
            mod = importlib.import_module(module)
        except ImportError:
            continue
        getattr(mod, fn)(register)


_load_optional()


def get_spec(name: str) -> AssemblySpec:
    """The spec of an assembly by name (raises ``KeyError`` with the known names)."""
    if name not in REGISTRY:
        raise KeyError(f"unknown assembly {name!r}; known: {', '.join(REGISTRY)}")
    return REGISTRY[name]
