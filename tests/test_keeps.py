"""kept: an entry made once per key, at most ``limit`` kept, the oldest dropped first."""

from __future__ import annotations

from bearingsim.keeps import kept


def test_an_entry_is_made_once_and_the_oldest_dropped_at_the_limit():
    store: dict = {}
    made: list[str] = []

    def make(key: str):
        return lambda: made.append(key) or f"entry {key}"

    assert kept(store, "a", make("a"), 2) == "entry a"
    assert kept(store, "a", make("a"), 2) == "entry a"
    assert made == ["a"]  # kept: not made again
    kept(store, "b", make("b"), 2)
    kept(store, "c", make("c"), 2)
    assert list(store) == ["b", "c"]  # "a", the oldest, dropped
    kept(store, "a", make("a"), 2)
    assert made == ["a", "b", "c", "a"] and list(store) == ["c", "a"]
