"""The progress bar of a run (tqdm, on standard error), shared by the scipy and SUNDIALS paths.

``progress`` as :func:`~bearingsim.simulation.simulate` takes it: ``True`` shows the bar at
once, ``False`` never, ``None`` (the default) only when standard error is a terminal and the
run lasts longer than :data:`DELAY` seconds (nothing is written to a pipe or a log file).
"""

from __future__ import annotations

import sys
from typing import Any

__all__ = ["DELAY", "progress_bar", "shows_progress"]

DELAY = 2.0
"""Wall seconds [s] before a bar with ``progress=None`` appears (tqdm's ``delay``)."""


def shows_progress(progress: bool | None) -> bool:
    """Whether a run with this ``progress`` setting gets a bar: ``progress`` itself, or for
    ``None`` whether standard error is a terminal (tqdm's ``disable=None`` rule).

    Parameters
    ----------
    progress : bool or None
        The run's ``progress`` option.

    Returns
    -------
    bool
        Whether to show a bar.
    """
    if progress is not None:
        return bool(progress)
    isatty = getattr(sys.stderr, "isatty", None)
    try:
        return bool(isatty and isatty())
    except ValueError:  # a closed stream
        return False


def progress_bar(t0: float, t1: float, progress: bool | None) -> Any:
    """A tqdm bar over simulated time, or None when :func:`shows_progress` says no.

    Parameters
    ----------
    t0, t1 : float
        Start and end time [s]; the bar counts simulated seconds (``bar.update(dt)``).
    progress : bool or None
        See the module docstring.

    Returns
    -------
    tqdm.tqdm or None
        Close it when the run ends (it leaves no line behind).
    """
    if not shows_progress(progress):
        return None
    from tqdm import tqdm

    return tqdm(total=t1 - t0, unit="s(sim)", delay=0.0 if progress else DELAY, leave=False,
                file=sys.stderr,
                bar_format="{l_bar}{bar}| {n:.3g}/{total:.3g} s [{elapsed}<{remaining}]")
