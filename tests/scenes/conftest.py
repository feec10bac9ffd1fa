"""Fixtures the sweep tests share."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="module")
def client():
    """One in-process dask worker (threads): the sweep machinery without process start-up."""
    distributed = pytest.importorskip("distributed")
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=":0") as c:
        yield c
