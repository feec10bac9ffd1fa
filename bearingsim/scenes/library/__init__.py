"""The built-in scenes: TOML files shipped with the package (also reachable as ``scenes/`` in a
source checkout). A built-in scene is named by its file stem, e.g. ``double_layer_rs``."""

from __future__ import annotations

from pathlib import Path

__all__ = ["FOLDER", "DEMO_SCENES", "builtin_scenes", "builtin_scene_path"]

FOLDER = Path(__file__).resolve().parent
"""Folder of the built-in scene files."""

DEMO_SCENES = ("double_layer_rs", "duplex_modes", "deep_groove_statics", "motor_drive_spinup")
"""The scenes ``bearingsim demo`` (and ``make demo``) runs: one per study question, each with
its table and the figure that answers it (docs/studies.md): the steady speed ratio of a
double-layer bearing against speed, one curve per radial load; the natural frequencies of a
duplex pair against preload, by mode; the ISO/TS 16281 life, ball load and contact pressure of
a deep-groove ball bearing per duty condition; and a PMSM spin-up of the double-layer bearing
(a transient on purpose, with the load step drawn above the torque it drives)."""


def builtin_scenes() -> list[str]:
    """Names of the built-in scenes (file stems), sorted.

    Returns
    -------
    list of str
        The names.
    """
    return sorted(p.stem for p in FOLDER.glob("*.toml"))


def builtin_scene_path(name: str) -> Path | None:
    """The file of the built-in scene ``name`` (a stem, with or without ``.toml``), or None.

    Parameters
    ----------
    name : str
        Scene name.

    Returns
    -------
    Path or None
        The TOML file, or None for an unknown name.
    """
    stem = name[:-5] if name.endswith(".toml") else name
    path = FOLDER / f"{stem}.toml"
    return path if "/" not in stem and path.is_file() else None
