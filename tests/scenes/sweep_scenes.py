"""The small scene the sweep tests run: the double-layer bearing's torque level at a constant
shaft speed (a point integrates in milliseconds, so the tests time the sweep machinery)."""

from __future__ import annotations


def torque_level_scene(outputs: tuple[str, ...] = ("Rs",), t_end: float = 0.02) -> str:
    """Scene text (TOML) of the double-layer bearing's torque level at 300 rad/s.

    Parameters
    ----------
    outputs : tuple of str
        The scene's outputs.
    t_end : float
        End time [s].

    Returns
    -------
    str
        The scene file's text.
    """
    names = ", ".join(f'"{name}"' for name in outputs)
    return f"""outputs = [{names}]
[assembly]
name = "double_layer_bearing"
fidelity = "torque"
[inputs]
shaft_speed = 300.0
[simulation]
t_end = {t_end!r}
n_points = 3
"""
