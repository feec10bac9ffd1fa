"""A sweep's phases account for its whole wall time: the import of dask.distributed (about
0.5 s in a fresh process) ran before the sweep's clock started, so neither
``SweepResult.phases`` (the summary's ``phases_s``) nor ``wall_s`` held it."""

from __future__ import annotations

import json
import time

import pytest

from bearingsim.scenes import sweep

pytest.importorskip("distributed")

SLOW_IMPORT_S = 0.3
"""How long the import of dask.distributed is made to take [s]."""


def test_the_import_of_dask_is_a_phase_of_the_sweep(client, tmp_path, monkeypatch):
    real = sweep.distributed_module

    def slow_import():
        time.sleep(SLOW_IMPORT_S)
        return real()

    monkeypatch.setattr(sweep, "distributed_module", slow_import)
    res = sweep.run_sweep("deep_groove_radial", [{}], client=client, out=tmp_path,
                          progress=False)
    assert res.phases["imports"] >= SLOW_IMPORT_S
    assert res.wall_s >= SLOW_IMPORT_S
    assert sum(res.phases.values()) == pytest.approx(res.wall_s, abs=1e-3)
    summary = json.loads((tmp_path / "deep_groove_radial.sweep.json").read_text())
    assert summary["phases_s"]["imports"] >= SLOW_IMPORT_S
