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
    from bearingsim.simulation.sundials_integrators import clear_integrator_cache

    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    clear_kernel_cache()
    clear_integrator_cache()
    yield tmp_path
    clear_kernel_cache()
    clear_integrator_cache()


STRESS_TOTAL: dict[str, float] = {}
"""Stress cases of all workers by kind and their times [s] (controller side;
``tests/stress/conftest.py`` names the kinds)."""


def _local_stress() -> dict:
    """This process's count: the ``STRESS`` dict of the generated stress suite, if it ran."""
    import sys

    for name, module in list(sys.modules.items()):
        if name.endswith("test_stress_generated") and hasattr(module, "STRESS"):
            return dict(module.STRESS)
    return {}


def _add(counts: dict) -> None:
    for key, value in counts.items():
        STRESS_TOTAL[key] = STRESS_TOTAL.get(key, 0) + value


def pytest_sessionfinish(session):
    """Hand this worker's stress count to the controller (pytest-xdist), or keep it."""
    counts = _local_stress()
    if hasattr(session.config, "workeroutput"):
        session.config.workeroutput["stress"] = counts
    else:
        _add(counts)


def pytest_testnodedown(node, error):
    """Collect a worker's stress count (pytest-xdist controller)."""
    _add(getattr(node, "workeroutput", {}).get("stress", {}))


def pytest_terminal_summary(terminalreporter):
    """Print the stress suite's two counts when it ran."""
    total = STRESS_TOTAL
    if total.get("cases"):
        terminalreporter.write_line(
            f"stress suite: {total.get('valid', 0)} valid operating points run and checked "
            f"against their invariants in {total.get('valid_seconds', 0.0):.1f} s; "
            f"{total.get('invalid', 0)} invalid inputs refused with a named error in "
            f"{total.get('invalid_seconds', 0.0):.1f} s ({total.get('invalid_accepted', 0)} "
            f"generated bad-input draws were valid and gave finite numbers); "
            f"{total['seconds']:.1f} s in all (a case over its time limit fails its test)")
