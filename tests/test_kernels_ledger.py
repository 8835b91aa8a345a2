"""The contact ledger's loop kernel (engine.dynamics.events' ``merge_loop``) against its numpy twin.

A step's ledger looks at every key that was open, was reported, is held at rest or is inside a
sensor: the kernel walks the sorted lists at once where the twin concatenates, sorts and
searches; on any lists the two give the same keys in the same order with the same flags,
exactly (keys and flags are integers and booleans: nothing to round). Without numba the
kernel runs as the plain Python it is written in (``LoopKernel.py``).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine import kernels
from engine.dynamics.events import _merge, _unique, merge_loop
from engine.kernels import LoopKernel

COMPILED = kernels.available()


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not COMPILED:
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def lists(seed: int) -> tuple[np.ndarray, ...]:
    """The ledger's inputs as ``settle`` hands them on: keys drawn from a small pool (so the
    lists share many), ``prev``, ``resting``, ``sensing`` and ``exact`` sorted and unique,
    ``touched`` unique in report order with whether each is open after the reports; any of
    them may be empty. Keys of two bodies and of colliders, with high slots."""
    rng = np.random.default_rng(seed)
    pool = np.unique(
        (rng.integers(0, 3000, 60).astype(np.int64) << 32) | rng.integers(0, 2**31 + 50, 60)
    )

    def some(p: float) -> np.ndarray:
        return _unique(pool[rng.random(len(pool)) < p]) if rng.random() > 0.1 else pool[:0]

    prev, resting, sensing = some(0.5), some(0.5), some(0.15)
    exact = _unique(np.concatenate([some(0.1), sensing]))
    touched = rng.permutation(some(0.3))
    return prev, touched, rng.random(len(touched)) < 0.5, resting, sensing, exact


@settings(max_examples=200, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_merge_loop_is_its_twin(seed: int) -> None:
    args = lists(seed)
    want = _merge(*args)
    got = merge_loop.fast(*args)
    assert len(got) == len(want) == 5
    for g, w, name in zip(got, want, ("keys", "after", "exact", "final", "sensed"), strict=True):
        assert g.dtype == w.dtype, name
        assert np.array_equal(g, w), name


def test_a_key_reported_closed_is_not_open_after_though_it_was_before() -> None:
    """The reports decide: a contact open before and reported ended is not open after; one
    reported begun is; a resting key nobody reported is held, not open after."""
    prev = np.array([1, 5], dtype=np.int64)
    touched = np.array([5, 3], dtype=np.int64)
    opened = np.array([False, True])
    resting = np.array([1, 9], dtype=np.int64)
    none = np.zeros(0, dtype=np.int64)
    for merge in (_merge, merge_loop.fast):
        keys, after, exact, final, sensed = merge(prev, touched, opened, resting, none, none)
        assert keys.tolist() == [1, 3, 5, 9]
        assert after.tolist() == [True, True, False, False]
        assert final.tolist() == [True, False, False, True]
        assert not exact.any() and not sensed.any()
