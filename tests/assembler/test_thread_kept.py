"""thread_kept: one evaluator per thread, function and key, bounded per kind."""

from __future__ import annotations

import threading

import casadi as ca

from bearingsim.assembler.numeric import thread_kept


def _function(name: str) -> ca.Function:
    x = ca.SX.sym("x")
    return ca.Function(name, [x], [2 * x])


def test_the_same_function_and_key_give_the_same_evaluator():
    fn = _function("f")
    first = thread_kept("test_same", id(fn), fn, object, 4)
    assert thread_kept("test_same", id(fn), fn, object, 4) is first
    assert thread_kept("test_other_kind", id(fn), fn, object, 4) is not first


def test_a_key_taken_by_another_function_is_made_anew():
    fn, other = _function("f"), _function("g")
    first = thread_kept("test_reuse", 7, fn, object, 4)
    # the same key (as id(fn) would be once fn is gone) for another function: not fn's evaluator
    assert thread_kept("test_reuse", 7, other, object, 4) is not first


def test_the_oldest_are_dropped_at_the_limit():
    fns = [_function(f"f{i}") for i in range(4)]
    made = [thread_kept("test_limit", i, fn, object, 3) for i, fn in enumerate(fns)]
    assert thread_kept("test_limit", 0, fns[0], object, 3) is not made[0]  # dropped
    assert thread_kept("test_limit", 3, fns[3], object, 3) is made[3]


def test_threads_get_their_own():
    fn = _function("f")
    here = thread_kept("test_threads", id(fn), fn, object, 4)
    there = []
    worker = threading.Thread(
        target=lambda: there.append(thread_kept("test_threads", id(fn), fn, object, 4)))
    worker.start()
    worker.join()
    assert there[0] is not here
