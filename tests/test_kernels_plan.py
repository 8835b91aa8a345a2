"""The plan's loop kernel (engine.exact.pair_plan.plan_pairs) against its numpy twins: the same
bodies marked as a pile's, on random pairs of discs (identical masks)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from engine import kernels
from engine.exact.pair_plan import grow, join_masks, plan_pairs, rest_seeds
from engine.kernels import LoopKernel


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not kernels.available():
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def numpy_plan(a, b, x0, v0, A, Ah, r, dt, loaded, island, kin, asleep):
    """The plan as engine.exact.collisions takes it on the numpy path."""
    island = island.copy()
    seed = rest_seeds(a, b, x0, v0, A, Ah, r, dt, loaded)
    island[a[seed]] = island[b[seed]] = True
    near_a, near_b = join_masks(a, b, x0, v0, A, r, dt)
    k = kin[a] | kin[b]
    near_a, near_b = near_a | k, near_b | k
    awake = ~(asleep[a] | asleep[b])
    return grow(island, a, b, near_a & awake, near_b & awake)


def scene(seed: int, n: int, pairs: int, spread: float):
    """Random discs close together, some resting (near and slow), some fast, some coinciding,
    some held, kinematic or asleep."""
    rng = np.random.default_rng(seed)
    x0 = rng.uniform(0, spread, (n, 2))
    if n > 1:
        x0[1] = x0[0]  # two centres at one place: the normal is straight up
    v0 = rng.normal(0, 1, (n, 2)) * rng.choice([0.0, 0.01, 1.0, 100.0], (n, 1))
    A = np.tile([0.0, -9.81], (n, 1)) + rng.normal(0, 0.1, (n, 2)) * (rng.random((n, 1)) < 0.3)
    held = rng.random(n) < 0.2
    Ah = np.where(held[:, None], 0.0, A)
    r = rng.uniform(0.1, 0.6, n)
    a = rng.integers(0, n, pairs)
    b = rng.integers(0, n, pairs)
    keep = a != b
    a, b = np.minimum(a, b)[keep], np.maximum(a, b)[keep]
    loaded = rng.random(len(a)) < 0.1
    island = rng.random(n) < 0.1
    kin = rng.random(n) < 0.05
    asleep = rng.random(n) < 0.1
    return a, b, x0, v0, A, Ah, r, 1 / 60, loaded, island, kin, asleep


@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(2, 40),
    pairs=st.integers(0, 120),
    spread=st.sampled_from([0.5, 2.0, 10.0]),
)
def test_plan_kernel_marks_the_numpy_twins_bodies(seed, n, pairs, spread) -> None:
    args = scene(seed, n, pairs, spread)
    want = numpy_plan(*args)
    island = args[9].copy()
    plan_pairs(*args[:9], island, *args[10:], True)
    assert np.array_equal(island, want)


@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(2, 40),
    pairs=st.integers(0, 120),
    spread=st.sampled_from([0.5, 2.0, 10.0]),
)
def test_plan_kernel_without_seeds_grows_as_the_numpy_twin(seed, n, pairs, spread) -> None:
    """Collisions._grow on the fast path: the piles given, grown, no new seeds."""
    a, b, x0, v0, A, _, r, dt, loaded, island, kin, asleep = scene(seed, n, pairs, spread)
    near_a, near_b = join_masks(a, b, x0, v0, A, r, dt)
    k = kin[a] | kin[b]
    awake = ~(asleep[a] | asleep[b])
    want = grow(island.copy(), a, b, (near_a | k) & awake, (near_b | k) & awake)
    got = island.copy()
    plan_pairs(a, b, x0, v0, A, A, r, dt, loaded, got, kin, asleep, False)
    assert np.array_equal(got, want)


def test_the_comparison_can_fail() -> None:
    """A plan that forgets what carried load in the last step marks fewer bodies."""
    args = list(scene(3, 30, 100, 10.0))
    args[8] = np.ones(len(args[0]), dtype=bool)  # every pair loaded
    want = numpy_plan(*args)
    island = args[9].copy()
    args[8] = np.zeros(len(args[0]), dtype=bool)
    plan_pairs(*args[:9], island, *args[10:], True)
    assert not np.array_equal(island, want)


def test_the_plan_kernel_is_one_of_the_engines() -> None:
    assert plan_pairs in kernels.kernels()
