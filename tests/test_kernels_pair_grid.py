"""The broadphase's loop kernel (engine.geometry.pair_grid.grid_pairs_loop) against its numpy twin.

The twins must give the same pairs in the same order, not just the same set: the pairs'
order is the order of the contacts downstream, and a Gauss-Seidel solve depends on it. So
every comparison here is of the arrays themselves, element by element. Without numba the
kernel runs as its plain Python (the fixture below, as in tests/test_kernels.py).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from engine import kernels
from engine.geometry.pair_grid import find_pairs, grid_pairs, grid_pairs_loop
from engine.kernels import LoopKernel

COMPILED = kernels.available()


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not COMPILED:
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def same(x: tuple[np.ndarray, ...], y: tuple[np.ndarray, ...]) -> bool:
    """The same arrays: as many, each of the same length and the same values in order."""
    return len(x) == len(y) and all(
        len(p) == len(q) and bool(np.array_equal(p, q)) for p, q in zip(x, y, strict=True)
    )


def points(seed: int, n: int, h: float, kind: str) -> np.ndarray:
    """n points (n, 2), made to stress a grid of side h: spread over a few cells, on cell
    borders (multiples of h), repeated, far from the origin, or negative."""
    rng = np.random.default_rng(seed)
    if kind == "spread":
        return rng.uniform(-5.0, 5.0, (n, 2)) * h
    if kind == "borders":
        return rng.integers(-4, 5, (n, 2)) * h
    if kind == "repeats":
        base = rng.uniform(-3.0, 3.0, (max(1, n // 4), 2)) * h
        return base[rng.integers(0, len(base), n)]
    if kind == "far":
        return rng.uniform(-3.0, 3.0, (n, 2)) * h + rng.uniform(-1e6, 1e6, 2) * h
    if kind == "one column":
        return np.column_stack([np.zeros(n), rng.uniform(-20.0, 20.0, n) * h])
    if kind == "sparse":  # keys far apart: the kernel sorts by merging, not counting
        return rng.uniform(-1e4, 1e4, (n, 2)) * h
    return -rng.uniform(0.0, 6.0, (n, 2)) * h  # negative


KINDS = ["spread", "borders", "repeats", "far", "one column", "sparse", "negative"]


@settings(max_examples=300, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 120),
    h=st.sampled_from([1e-6, 0.013, 0.5, 1.0, 2.2, 7.0, 1e5]),
    kind=st.sampled_from(KINDS),
)
@example(seed=0, n=1, h=1.0, kind="spread")  # one point: no pairs
@example(seed=1, n=30, h=1.0, kind="repeats")
def test_grid_kernel_gives_the_twins_pairs_in_its_order(
    seed: int, n: int, h: float, kind: str
) -> None:
    """grid_pairs on the fast path (grid_pairs_loop) gives the numpy twin's pairs, in its
    order, on random point sets."""
    P = points(seed, n, h, kind)
    want = grid_pairs(P, h)
    got = grid_pairs(P, h, fast=True)
    assert same(got, want)
    # and no pair twice, none with itself (what the twin promises)
    keys = np.minimum(*want) * n + np.maximum(*want)
    assert len(np.unique(keys)) == len(keys)
    assert not (want[0] == want[1]).any()


@settings(max_examples=200, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 120),
    kind=st.sampled_from(KINDS),
)
def test_grid_kernel_filters_by_reach_as_find_pairs_does(seed: int, n: int, kind: str) -> None:
    """With ``near``, the kernel's pairs are find_pairs' lines after the grid: (lower,
    higher), those with |D|^2 <= (r_a + r_b + reach_a + reach_b)^2 kept, in the grid's order;
    some pairs exactly at the limit."""
    rng = np.random.default_rng(seed)
    r = rng.uniform(0.1, 0.5, n)
    reach = np.where(rng.random(n) < 0.3, 0.0, rng.uniform(0.0, 0.3, n))
    h = 2.0 * float((r + reach).max())
    P = points(seed, n, h / 3.0, kind)
    if n >= 2:
        P[1] = P[0] + (r[0] + r[1] + reach[0] + reach[1], 0.0)  # touching at the limit
    ia, ib = grid_pairs(P, h)
    ia, ib = np.minimum(ia, ib), np.maximum(ia, ib)
    D = P[ia] - P[ib]
    far = r[ia] + r[ib] + reach[ia] + reach[ib]
    keep = D[:, 0] * D[:, 0] + D[:, 1] * D[:, 1] <= far * far
    assert same(grid_pairs_loop(P, h, r, reach, True), (ia[keep], ib[keep]))


@settings(max_examples=100, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(2, 80),
    racing=st.integers(0, 3),
    dt=st.sampled_from([1 / 240, 1 / 60, 1 / 7]),
)
def test_find_pairs_fast_path_is_its_numpy_twin(seed: int, n: int, racing: int, dt: float) -> None:
    """find_pairs with ``fast`` gives the numpy path's World rows in its order, and the same
    search arrays: a crowd at rest or falling, with a few bodies racing past it (tested
    against everyone), and some bodies not live."""
    rng = np.random.default_rng(seed)
    N = n + 3
    x1 = rng.uniform(-4.0, 4.0, (N, 2))
    v1 = rng.normal(0.0, 1.0, (N, 2)) * rng.choice([0.0, 1.0], (N, 1))
    v1[rng.integers(0, N, racing)] *= 60.0
    v0 = v1 + rng.normal(0.0, 0.1, (N, 2))
    A = np.tile([0.0, -9.81], (N, 1))
    x0 = x1 - v1 * dt
    store = SimpleNamespace(radius=rng.uniform(0.2, 0.5, N))
    live = np.sort(rng.choice(N, n, replace=False))
    want = find_pairs(x0, v0, x1, v1, A, dt, live, store, False, True)
    got = find_pairs(x0, v0, x1, v1, A, dt, live, store, False, True, fast=True)
    assert same(got[:2], want[:2])
    assert same(tuple(got[2]), tuple(want[2]))
    assert (want[0] < want[1]).all()


def test_the_comparison_catches_a_kernel_that_differs() -> None:
    """The check can fail: pairs in another order, one pair left out, or one cell
    neighbour not looked up (a grid that misses the cells ny + 1 apart) all differ."""
    P = points(5, 200, 1.0, "spread")
    want = grid_pairs(P, 1.0)
    got = grid_pairs(P, 1.0, fast=True)
    assert same(got, want)
    order = np.lexsort((got[1], got[0]))  # the same pairs, sorted: not the twin's order
    assert not np.array_equal(order, np.arange(len(order)))
    assert not same((got[0][order], got[1][order]), want)
    assert not same((got[0][1:], got[1][1:]), want)
    # A point shifted by a cell's width has other neighbours: other pairs.
    Q = P.copy()
    Q[0] += 3.0
    assert not same(grid_pairs(Q, 1.0, fast=True), want)


def test_the_kernel_is_one_of_the_engines_and_compiles_from_its_sample() -> None:
    """prepare() finds the kernel (engine.geometry.pair_grid is in kernels.MODULES), and its sample
    call gives the one touching pair."""
    assert "engine.geometry.pair_grid" in kernels.MODULES
    assert grid_pairs_loop in kernels.kernels()
    a, b = grid_pairs_loop(np.array([[0.0, 0.0], [1.0, 0.0]]), 2.0, np.full(2, 0.5),
                           np.zeros(2), True)  # fmt: skip
    assert a.tolist() == [0] and b.tolist() == [1]


@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 60),
    few=st.integers(0, 5),
)
def test_reach_pairs_is_pairs_of(seed: int, n: int, few: int) -> None:
    """The fast few against everyone: the same pairs, in the same order, on both paths."""
    from engine.geometry.pair_grid import pairs_of

    rng = np.random.default_rng(seed)
    P = rng.uniform(-5, 5, (n, 2))
    P[rng.random(n) < 0.1] = 0.0  # some centres at one place
    r = rng.uniform(0.0, 0.8, n)
    reach = rng.uniform(0.0, 3.0, n) * (rng.random(n) < 0.5)
    bodies = rng.choice(n, size=min(few, n), replace=False)
    fa, fb = pairs_of(bodies, P, r, reach)
    ga, gb = pairs_of(bodies, P, r, reach, fast=True)
    want_a = np.concatenate([np.zeros(0, dtype=np.int64), *fa])
    want_b = np.concatenate([np.zeros(0, dtype=np.int64), *fb])
    assert np.array_equal(np.concatenate(ga), want_a)
    assert np.array_equal(np.concatenate(gb), want_b)
