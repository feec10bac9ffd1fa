"""The units library keeps pint's parsed definitions under the cache root and never trusts a
broken entry."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

CONVERT = ("from bearingsim.units.registry import registry; "
           "print(registry().Quantity(1.0, 'rpm').to('rad/s').magnitude)")


def _run(cache: Path) -> str:
    env = {**os.environ, "BEARINGSIM_CACHE": str(cache)}
    return subprocess.run([sys.executable, "-c", CONVERT], env=env, check=True,
                          capture_output=True, text=True).stdout.strip()


def test_parsed_definitions_are_kept_and_a_corrupt_entry_is_rebuilt(tmp_path):
    rpm = 2 * 3.141592653589793 / 60
    assert abs(float(_run(tmp_path)) - rpm) < 1e-15
    entries = sorted((tmp_path / "pint").glob("*.pickle"))
    assert entries, "the registry kept no parsed definitions under the cache root"
    for entry in entries:
        entry.write_bytes(b"garbage")  # what a half-written or foreign file looks like
    assert abs(float(_run(tmp_path)) - rpm) < 1e-15
    rebuilt = sorted((tmp_path / "pint").glob("*.pickle"))
    assert rebuilt and all(e.read_bytes() != b"garbage" for e in rebuilt)
