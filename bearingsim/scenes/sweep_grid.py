"""The points of a sweep applied to its scene.

``--grid`` items parsed into values by key (:func:`parse_grid`), a swept value converted to the
type its key expects (:func:`coerce`), the scene of one point, validated with errors that name
the sweep key (:func:`point_scene`), the checks that every point sets the same keys
(:func:`check_point_keys`) and that an analysis scene's own grid inputs still have values
(:func:`check_operating_points`), and the swept values as the sweep's table stores
them (:func:`si_values`). Running the points is :func:`bearingsim.scenes.sweep.run_sweep`.
"""

from __future__ import annotations

import sys
from collections.abc import Mapping, Sequence
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from bearingsim.scenes.sampling import SweepError, check_key
from bearingsim.scenes.scene import Scene, SceneError

__all__ = ["check_operating_points", "check_point_keys", "coerce", "parse_grid", "point_scene",
           "si_values"]


def _split_values(text: str) -> list[str]:
    """Split on ';' if present, else on commas outside parentheses, brackets and quotes (a
    TOML list such as ``["lithium grease", "ISO VG 32"]`` is one value); an empty value between
    two separators is kept (:func:`parse_grid` refuses it), a trailing separator ignored."""
    if ";" in text:
        parts = [v.strip() for v in text.split(";")]
        return parts[:-1] if parts[-1] == "" else parts
    out, depth, cur, quote = [], 0, "", ""
    for ch in text:
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        if ch == "," and depth == 0 and not quote:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        out.append(cur.strip())
    return out


def _value(text: str) -> Any:
    """A grid value: a TOML list or quoted string as TOML reads it, true/false, a number, or
    the text itself."""
    if text.strip()[:1] in ("[", "\"", "'"):
        try:
            return tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            raise SweepError(f"grid value {text!r} is not a TOML value (a list needs quoted "
                             f"text: [\"lithium grease\", \"ISO VG 32\"])") from None
    low = text.strip().lower()
    if low in ("true", "false"):
        return low == "true"
    try:
        v = float(text)
    except ValueError:
        return text.strip()
    return int(v) if v.is_integer() and "." not in text and "e" not in low else v


def parse_grid(items: list[str]) -> dict[str, list[Any]]:
    """``["inputs.shaft_speed=100,200", ...]`` -> ``{"inputs.shaft_speed": ["100", "200"]}``.

    Values stay text here; they are converted by the type the key expects when a point is
    applied to a scene (numbers for parameters, designations stay text).

    Parameters
    ----------
    items : list of str
        ``key=v1,v2,...`` each.

    Returns
    -------
    dict of str to list of str
        The values by key.

    Raises
    ------
    SweepError
        For a malformed item, a key a sweep cannot set, a key without values or a key given
        twice.
    """
    grid: dict[str, list[Any]] = {}
    for item in items:
        if "=" not in item:
            raise SweepError(f"--grid {item!r}: expected key=v1,v2,...")
        key, values = item.split("=", 1)
        key = key.strip()
        check_key(key)
        if key in grid:  # a second --grid of a key replaced the first one's values, unsaid
            raise SweepError(f"--grid {key} is given twice; give all its values in one: "
                             f"--grid {key}=v1,v2,...")
        vals = _split_values(values)
        if not any(vals):
            raise SweepError(f"--grid {key}: no values")
        if "" in vals:  # "1,,2": was refused as the expression '' of a point
            raise SweepError(f"--grid {key}: value {vals.index('') + 1} of {len(vals)} is "
                             "empty (two separators in a row)")
        grid[key] = vals
    return grid


def _set_nested(d: dict, path: list[str], value: Any) -> None:
    for p in path[:-1]:
        d = d.setdefault(p, {})
    d[path[-1]] = value


def coerce(scene: Scene, key: str, value: Any) -> Any:
    """A grid value converted to the type its key expects.

    Parameters
    ----------
    scene : Scene
        The swept scene (its assembly's arguments give the kinds).
    key : str
        The sweep key (``inputs.<name>``, ``assembly.<argument>``, ...).
    value : object
        The value as given (text from ``--grid``, or already converted).

    Returns
    -------
    object
        The value: a number, bool, text or list of text.
    """
    head, rest = key.split(".", 1)
    text_kinds = ("bearing", "lubricant", "choice")
    if head == "assembly":
        spec = scene.spec.args
        parts = rest.split(".")
        arg = None
        for part in parts:
            arg = spec.get(part) if spec else None
            spec = arg.table if arg is not None and arg.table else None
        if isinstance(value, str) and value.strip()[:1] in ("[", "\"", "'"):
            value = _value(value)
        if isinstance(value, list):
            return [str(v) for v in value]
        if arg is not None and arg.kind == "bearing" and (
                found := arg.designation(value)) is not None:
            return found  # the table says "NU206" for "nu 206"
        if rest == "fidelity" or (arg is not None and arg.kind in text_kinds):
            return str(value) if not isinstance(value, str) else value
        if arg is not None and arg.kind == "signal" and isinstance(value, str):
            v = _value(value)
            return v if not isinstance(v, bool) else value
    if head == "simulation" and rest in ("method", "initial"):
        return str(value)
    if isinstance(value, str):
        v = _value(value)
        return value if isinstance(v, bool) and head != "assembly" else v
    return value


def point_scene(scene: Scene, point: dict[str, Any]) -> Scene:
    """The scene with the point's values applied, validated (errors name the sweep key); an
    analysis scene's own grid or cases are left out (the sweep's point is its one operating
    point).

    Parameters
    ----------
    scene : Scene
        The swept scene.
    point : dict
        The point's values by sweep key.

    Returns
    -------
    Scene
        The scene of the point.

    Raises
    ------
    SweepError
        When the point's values make an invalid scene.
    """
    d = scene.to_dict()
    if scene.analysis != "transient":
        d.pop("grid", None)
        d.pop("cases", None)
    for key, value in point.items():
        value = coerce(scene, key, value)
        head, rest = key.split(".", 1)
        if head == "assembly":
            _set_nested(d["assembly"], rest.split("."), value)
        else:
            d.setdefault(head, {})[rest] = value
    from bearingsim.scenes.scene import scene_from_dict

    carried = {k: u for k, u in scene.given_units.items() if k not in point}
    try:
        return scene_from_dict(d, path=scene.path, carried_units=carried)
    except SceneError as exc:
        shown = ", ".join(f"{k}={v!r}" for k, v in point.items())
        why = "; ".join(p.key + ": " + p.reason + (f"; allowed: {p.allowed}" if p.allowed else "")
                        for p in exc.problems)
        raise SweepError(f"sweep point ({shown}): {why}") from None


def check_point_keys(points: list[dict[str, Any]]) -> None:
    """Raise :class:`SweepError` unless the points are a list of dicts that all set the same
    keys, each one a sweep key (:func:`~bearingsim.scenes.sampling.check_key`): they are the
    table's columns, which name what each row ran (a point with other keys had its row say
    nothing of them).

    Parameters
    ----------
    points : list of dict
        The sweep's points (values by sweep key).
    """
    if isinstance(points, (str, bytes, Mapping)) or not isinstance(points, Sequence):
        raise SweepError("the sweep's points must be a list of dicts (sweep key -> value, "
                         f"e.g. from grid_points or sample_points), got {type(points).__name__}")
    for k, point in enumerate(points):
        if not isinstance(point, Mapping):
            raise SweepError(f"sweep point {k} must be a dict (sweep key -> value), got "
                             f"{type(point).__name__}")
    keys = set(points[0])
    for key in sorted(keys, key=str):
        check_key(key)
    for k, point in enumerate(points):
        if set(point) != keys:
            raise SweepError(
                f"sweep point {k} sets {', '.join(sorted(map(str, point))) or 'no key'}, "
                f"point 0 {', '.join(sorted(keys)) or 'no key'}: every point of a sweep sets "
                "the same keys (the columns of its table)")


def check_operating_points(scene: Scene, points: list[dict[str, Any]]) -> None:
    """Raise :class:`SweepError` when an input the analysis scene takes from its own grid or
    from every one of its load cases (which a sweep replaces) has no value at the sweep's
    points. An input only some cases set (an axial load in the last case) is one the scene
    leaves at the model's default in the others, as the sweep's points then do.

    Parameters
    ----------
    scene : Scene
        The swept analysis scene.
    points : list of dict
        The sweep's points (values by sweep key).
    """
    every_case = [k for k in (scene.cases[0] if scene.cases else {})
                  if all(k in case for case in scene.cases)]
    varied = list(dict.fromkeys([*scene.grid, *every_case]))
    missing = sorted(k for k in varied if k.startswith("inputs.") and k not in points[0]
                     and k.split(".", 1)[1] not in scene.inputs)
    if missing:
        one = len(missing) == 1
        own = "grid" if scene.grid else "load cases"
        known = {*scene.grid, *(k for case in scene.cases for k in case)}
        strange = [k for k in points[0] if k.startswith("inputs.") and k not in known
                   and k.split(".", 1)[1] not in scene.inputs]
        raise SweepError(
            f"the sweep replaces the {own} of this {scene.analysis} scene, and "
            f"{', '.join(missing)} then {'has' if one else 'have'} no value: "
            f"sweep {'it' if one else 'them'} (--grid {missing[0]}=...) or "
            f"give {'it' if one else 'them'} under [inputs]"
            + (f" ({', '.join(strange)}: not in the scene's {own} or [inputs]; check the "
               f"spelling if {'it is' if len(strange) == 1 else 'they are'} meant for "
               f"{'it' if one else 'one of them'})" if strange else ""))


def si_values(point: dict[str, Any], memo: dict | None = None,
              scene: Scene | None = None) -> dict[str, Any]:
    """The swept values as the table stores them: SI numbers for inputs that are constant
    (``"500 rpm"``, ``"rpm(500)"`` -> 52.36 under ``[rad/s]``) and, given the point's validated
    ``scene``, for every other number with a unit (``"1.5 kN"`` as a preload -> 1500.0 under
    ``[N]``, ``"50 ms"`` as ``simulation.t_end`` -> 0.05 under ``[s]``); others as given
    (names, expressions of ``t``). ``memo`` keeps the converted inputs across the points of a
    sweep (a grid repeats each value).

    Parameters
    ----------
    point : dict
        A point's values by sweep key.
    memo : dict, optional
        Converted input values by (key, value), shared by the points of a sweep.
    scene : Scene, optional
        The point's scene (:func:`point_scene`), holding its values in SI units.

    Returns
    -------
    dict
        The values by sweep key, numbers in SI units.
    """
    from bearingsim.scenes.expressions import constant_value
    from bearingsim.units import split_quantity

    memo = {} if memo is None else memo
    out = {}
    for key, value in point.items():
        if key.startswith("inputs."):
            seen = (key, repr(value))
            if seen not in memo:
                si = constant_value(value, key)
                memo[seen] = value if si is None else si
            out[key] = memo[seen]
        elif scene is not None and isinstance(value, str) and split_quantity(value) is not None:
            out[key] = _scene_value(scene, key, value)
        else:
            out[key] = value
    return out


def _scene_value(scene: Scene, key: str, given: Any) -> Any:
    """The value of a parameter, initial value, assembly argument or simulation setting
    ``key`` in ``scene`` (validated: in SI units); ``given`` where the scene has none."""
    head, _, name = key.partition(".")
    held = {"parameters": scene.parameters, "initial": scene.initial,
            "assembly": scene.args}.get(head)
    if held is not None:
        return held.get(name, given)
    if head == "simulation":
        return getattr(scene.simulation, name, given)
    return given
