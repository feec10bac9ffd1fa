"""Test configuration.

Hypothesis draws new random examples on every local run (and has found real boundary bugs that
way); in CI (``CI`` set) it runs a fixed, derandomized set so a green submission stays green.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import settings

settings.register_profile("ci", derandomize=True, deadline=None)
if os.environ.get("CI"):
    settings.load_profile("ci")



@pytest.fixture()
def kernel_cache(tmp_path, monkeypatch):
    """A fresh kernel library cache (``BEARINGSIM_CACHE``), and no kernels or integrators left
    in memory from other tests."""
    from bearingsim.simulation.kernels import clear_kernel_cache
    from bearingsim.simulation.sundials import clear_integrator_cache

    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    clear_kernel_cache()
    clear_integrator_cache()
    yield tmp_path
    clear_kernel_cache()
    clear_integrator_cache()


STRESS_TOTAL = {"cases": 0, "seconds": 0.0}
"""Generated stress cases of all workers and their time [s] (controller side)."""


def _local_stress() -> dict:
    """This process's count: the ``STRESS`` dict of the generated stress suite, if it ran."""
    import sys

    for name, module in list(sys.modules.items()):
        if name.endswith("test_stress_generated") and hasattr(module, "STRESS"):
            return dict(module.STRESS)
    return {"cases": 0, "seconds": 0.0}


def pytest_sessionfinish(session):
    """Hand this worker's stress count to the controller (pytest-xdist), or keep it."""
    counts = _local_stress()
    if hasattr(session.config, "workeroutput"):
        session.config.workeroutput["stress"] = counts
    else:
        STRESS_TOTAL["cases"] += counts["cases"]
        STRESS_TOTAL["seconds"] += counts["seconds"]


def pytest_testnodedown(node, error):
    """Collect a worker's stress count (pytest-xdist controller)."""
    counts = getattr(node, "workeroutput", {}).get("stress", {})
    STRESS_TOTAL["cases"] += counts.get("cases", 0)
    STRESS_TOTAL["seconds"] += counts.get("seconds", 0.0)


def pytest_terminal_summary(terminalreporter):
    """Print the size of the generated stress suite when it ran."""
    if STRESS_TOTAL["cases"]:
        terminalreporter.write_line(
            f"stress suite: {STRESS_TOTAL['cases']} generated cases in "
            f"{STRESS_TOTAL['seconds']:.1f} s, each finite or a named error, none over its "
            "time bound")
