"""The built-in scenes: TOML files shipped with the package (also reachable as ``scenes/`` in a
source checkout). A built-in scene is named by its file stem, e.g. ``double_layer_rs``."""

from __future__ import annotations

from pathlib import Path

__all__ = ["FOLDER", "DEMO_SCENES", "builtin_scenes", "builtin_scene_path"]

FOLDER = Path(__file__).resolve().parent
"""Folder of the built-in scene files."""

DEMO_SCENES = ("motor_drive_spinup", "double_layer_friction", "deep_groove_radial",
               "duplex_pair_axial")
"""The scenes ``bearingsim demo`` (and ``make demo``) runs: a PMSM spin-up of a double-layer
bearing and the steady speed ratio of a double-layer bearing against its friction torque (each
with Rs against shaft speed), the load distribution of a deep-groove ball bearing (ball load
against azimuth) and a duplex pair under load steps (its modes by name)."""


def builtin_scenes() -> list[str]:
    """Names of the built-in scenes (file stems), sorted."""
    return sorted(p.stem for p in FOLDER.glob("*.toml"))


def builtin_scene_path(name: str) -> Path | None:
    """The file of the built-in scene ``name`` (a stem, with or without ``.toml``), or None."""
    stem = name[:-5] if name.endswith(".toml") else name
    path = FOLDER / f"{stem}.toml"
    return path if "/" not in stem and path.is_file() else None
