"""The units library keeps the SI conversions pint computed (bearingsim.units.conversion_memo):
a later process reads them without importing pint and gets the same numbers and the same
refusals; a memo of another pint version or translation, or a damaged one, is not trusted."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from bearingsim.units.conversion_memo import FILE, MAX_UNITS, ConversionMemo, memo
from bearingsim.units.display import DISPLAY_UNITS
from bearingsim.units.registry import PINT_CACHE, UnitError, _base_exponents, base_exponents

UNITS = [*DISPLAY_UNITS, *DISPLAY_UNITS.values(), "rpm", "degC", "kg.m2", "N/um", "cSt",
         "W", "h", "mm", "(rad/s)/s", "1"]

CONVERT = f"""
import json, sys
from bearingsim.units.display import to_display
from bearingsim.units.registry import UnitError, base_exponents
from bearingsim.units import to_si
out = {{u: base_exponents(u) for u in {UNITS!r}}}
out["shown"] = [to_display(1.0, u) for u in ("rad/s", "K", "N.m")]
out["rpm"] = to_si("10000 rpm", "rad/s", "speed")
try:
    base_exponents("blorps")
except UnitError as exc:
    out["refused"] = str(exc)
print(json.dumps({{"values": repr(out), "pint": "pint" in sys.modules}}))
"""


def _fresh_process(cache):
    env = {**os.environ, "BEARINGSIM_CACHE": str(cache)}
    out = subprocess.run([sys.executable, "-c", CONVERT], env=env, check=True,
                         capture_output=True, text=True, timeout=300).stdout
    return json.loads(out.strip().splitlines()[-1])


def test_a_later_process_converts_without_pint_to_the_same_numbers(tmp_path):
    first = _fresh_process(tmp_path)
    second = _fresh_process(tmp_path)
    assert first["pint"] and not second["pint"]
    assert second["values"] == first["values"]  # every number and refusal, as repr
    assert "blorps" in first["values"]


@pytest.fixture
def own_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("BEARINGSIM_CACHE", str(tmp_path))
    memo.cache_clear()
    base_exponents.cache_clear()
    yield tmp_path / PINT_CACHE / FILE
    memo.cache_clear()
    base_exponents.cache_clear()


def test_kept_values_are_pints_exactly(own_cache):
    for unit in UNITS:
        assert base_exponents(unit) == _base_exponents(unit)
    memo.cache_clear()
    base_exponents.cache_clear()
    reread = ConversionMemo(own_cache, memo().key)
    for unit in UNITS:
        assert reread.get(unit) is not None
        assert base_exponents(unit) == _base_exponents(unit)  # read back from the file


@pytest.mark.parametrize("damage", ["foreign key", "garbage", "wrong shape"])
def test_a_memo_of_another_key_or_damaged_is_not_trusted(own_cache, damage):
    own_cache.parent.mkdir(parents=True, exist_ok=True)
    wrong = {"rad/s": [[["meter", 1.0]], 2.0, 0.0]}  # what a stale memo might claim
    if damage == "foreign key":
        own_cache.write_text(json.dumps({"key": "pint 0.1; 0123", "units": wrong}))
    elif damage == "garbage":
        own_cache.write_bytes(b"\x00garbage{")
    else:
        own_cache.write_text(json.dumps({"key": memo().key, "units": ["rad/s"]}))
        memo.cache_clear()
    assert base_exponents("rad/s") == ((("radian", 1.0), ("second", -1.0)), 1.0, 0.0)
    data = json.loads(own_cache.read_text())
    assert data["key"] == memo().key and data["units"]["rad/s"][1] == 1.0


def test_a_refusal_is_kept_with_its_message(own_cache):
    with pytest.raises(UnitError) as first:
        base_exponents("blorps")
    memo.cache_clear()
    base_exponents.cache_clear()
    with pytest.raises(UnitError) as kept:
        base_exponents("blorps")
    assert str(kept.value) == str(first.value)
    assert "blorps" in str(kept.value)


def test_the_memo_stops_growing_at_its_bound(tmp_path):
    path = tmp_path / FILE
    kept = ConversionMemo(path, "k")
    for k in range(MAX_UNITS + 5):
        kept.put(f"unit{k}", {"error": "refused"})
    reread = ConversionMemo(path, "k")
    assert reread.get(f"unit{MAX_UNITS - 1}") == {"error": "refused"}
    assert reread.get(f"unit{MAX_UNITS}") is None
    assert len(json.loads(path.read_text())["units"]) == MAX_UNITS
