"""The colouring's and the piles' loop kernels (engine.kernels) against their numpy twins.

``coloring.colors`` and ``coloring.batches`` (the solving order of a pile's rows) and
``pile.components`` (a pile's, and sleep's, groups) are integer algorithms: each loop kernel
must give its twin's arrays exactly, element for element and dtype for dtype, on every graph
of rows: bodies that do not move, rows at the static slot, rows sharing bodies, a body with
more rows than there are colours, and none at all. Without numba the kernels run as the plain
Python they are written in (``LoopKernel.py``).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from engine import kernels
from engine.dynamics import coloring
from engine.dynamics.coloring import MAX_COLORS, batches, colors
from engine.exact.pile import components
from engine.kernels import LoopKernel

COMPILED = kernels.available()


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not COMPILED:
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def same(x: np.ndarray, y: np.ndarray) -> bool:
    """The same array: dtype, shape and every element."""
    return x.dtype == y.dtype and x.shape == y.shape and bool(np.array_equal(x, y))


def same_batches(x: list[np.ndarray], y: list[np.ndarray]) -> bool:
    return len(x) == len(y) and all(same(p, q) for p, q in zip(x, y, strict=True))


def row_graph(
    seed: int, bodies: int, rows: int, hub: int = 0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rows (a, b) of a made-up pile over ``bodies`` bodies and the static slot (the last,
    which does not move), a != b; some bodies held (do not move); ``hub`` more rows at
    body 0, which forces it past MAX_COLORS colours when hub > MAX_COLORS."""
    rng = np.random.default_rng(seed)
    n = bodies + hub
    a = rng.integers(0, n + 1, rows)
    b = rng.integers(0, n + 1, rows)
    b = np.where(a == b, (a + 1) % (n + 1), b)
    if hub:
        a = np.concatenate([a, np.zeros(hub, dtype=np.int64)])
        b = np.concatenate([b, rng.permutation(np.arange(1, n + 1))[:hub]])
        mix = rng.permutation(len(a))  # the hub's rows among the others
        a, b = a[mix], b[mix]
    swap = rng.random(len(a)) < 0.5
    a, b = np.where(swap, b, a), np.where(swap, a, b)
    moves = np.append(rng.random(n) < 0.85, False)
    if hub:
        moves[0] = True
    return a, b, moves


def choices(seed: int, rows: int, priorities: str, priors: str) -> tuple[object, object]:
    """(priority, prior) for ``colors``: none, distinct or tied priorities, or distinct ones
    of both signs (the kernel sorts a float's bits as an integer's); none, a few or many
    colours kept (clashing at bodies, some the last colour)."""
    rng = np.random.default_rng(seed + 1)
    priority = {
        "none": None,
        "distinct": rng.permutation(rows).astype(np.float64) + rng.random(rows) * 0.5,
        "tied": rng.integers(0, 4, rows).astype(np.float64),
        "signed": (rng.permutation(rows) - rows // 2) * rng.choice([1e-300, 1.0, 1e300]),
    }[priorities]
    prior = None
    if priors != "none":
        top = 8 if priors == "few" else MAX_COLORS
        prior = np.where(rng.random(rows) < 0.6, rng.integers(0, top, rows), -1)
    return priority, prior


graphs = dict(
    seed=st.integers(0, 2**32 - 1),
    bodies=st.integers(0, 30),
    rows=st.integers(0, 120),
    hub=st.sampled_from([0, 0, 3, MAX_COLORS + 1, 2 * MAX_COLORS + 5]),
)


@given(
    **graphs,
    priorities=st.sampled_from(["none", "distinct", "tied", "signed"]),
    priors=st.sampled_from(["none", "few", "many"]),
)
def test_colors_kernel_is_its_numpy_twin(
    seed: int, bodies: int, rows: int, hub: int, priorities: str, priors: str
) -> None:
    """``colors(fast=True)`` (``color_rows``: the greedy in priority order, or the rounds for
    tied priorities) gives the numpy rounds' colours exactly."""
    if bodies + hub == 0:
        bodies = 1
    a, b, moves = row_graph(seed, bodies, rows, hub)
    priority, prior = choices(seed, len(a), priorities, priors)
    want = colors(a, b, moves, priority, prior)  # type: ignore[arg-type]
    got = colors(a, b, moves, priority, prior, fast=True)  # type: ignore[arg-type]
    assert same(got, want)
    if hub > MAX_COLORS and priorities != "tied":
        assert (want == MAX_COLORS - 1).any()  # the hub's rows past the colours


@given(**graphs, priors=st.sampled_from(["none", "many"]))
def test_batches_kernel_is_its_numpy_twin(
    seed: int, bodies: int, rows: int, hub: int, priors: str
) -> None:
    """``batches(fast=True)`` (``batch_rows``) gives the numpy twin's batches exactly, for
    the colours of ``colors`` (the last colour's rows split into rounds)."""
    if bodies + hub == 0:
        bodies = 1
    a, b, moves = row_graph(seed, bodies, rows, hub)
    _, prior = choices(seed, len(a), "none", priors)
    color = colors(a, b, moves, prior=prior)  # type: ignore[arg-type]
    assert same_batches(batches(color, a, b, moves, fast=True), batches(color, a, b, moves))


@given(seed=st.integers(0, 2**32 - 1), bodies=st.integers(1, 12), rows=st.integers(0, 80))
def test_batches_kernel_takes_any_colours(seed: int, bodies: int, rows: int) -> None:
    """Colours not from ``colors`` (below 0, or past the last: the kernel's merge sort, not
    its counting sort; every colour from MAX_COLORS - 1 up split into rounds) batch alike."""
    a, b, moves = row_graph(seed, bodies, rows)
    rng = np.random.default_rng(seed + 2)
    color = rng.integers(-2, MAX_COLORS + 3, len(a))
    assert same_batches(batches(color, a, b, moves, fast=True), batches(color, a, b, moves))


@given(seed=st.integers(0, 2**32 - 1), bodies=st.integers(0, 40), rows=st.integers(0, 100))
def test_components_kernel_is_its_numpy_twin(seed: int, bodies: int, rows: int) -> None:
    """``components(fast=True)`` (``label_rows``, a union-find) labels every body by its
    component's least body, as the numpy label propagation does; rows at the static slot
    (``bodies``) join nothing."""
    a, b, _ = row_graph(seed, bodies, rows)
    assert same(components(bodies, a, b, fast=True), components(bodies, a, b))


def _sleep_groups(n: int, pa: np.ndarray, pb: np.ndarray) -> np.ndarray:
    """engine.exact.sleep's groups as it labelled them before it took ``components``: each body
    the least label of its neighbours, then labels follow labels, to a fixed point."""
    label = np.arange(n)
    while len(pa):
        low = np.minimum(label[pa], label[pb])
        new = label.copy()
        np.minimum.at(new, pa, low)
        np.minimum.at(new, pb, low)
        new = new[new]
        if np.array_equal(new, label):
            break
        label = new
    return label


@given(seed=st.integers(0, 2**32 - 1), bodies=st.integers(1, 40), rows=st.integers(0, 100))
def test_sleep_groups_are_the_components(seed: int, bodies: int, rows: int) -> None:
    """The groups engine.exact.sleep labelled with its own loop are ``components``' labels, on
    both paths (sleep takes them now, and on the fast path the kernel's)."""
    rng = np.random.default_rng(seed)
    pa, pb = rng.integers(0, bodies, rows), rng.integers(0, bodies, rows)
    want = _sleep_groups(bodies, pa, pb)
    for fast in (False, True):
        assert np.array_equal(components(bodies, pa, pb, fast), want)


def test_empty_rows() -> None:
    """No rows: no colours, no batches, every body its own component, on both paths."""
    z = np.zeros(0, dtype=np.int64)
    moves = np.array([True, True, False])
    for fast in (False, True):
        assert same(colors(z, z, moves, fast=fast), np.zeros(0, dtype=np.int64))
        assert same(colors(z, z, moves, np.zeros(0), z, fast=fast), np.zeros(0, dtype=np.int64))
        assert batches(z, z, z, moves, fast=fast) == []
        assert same(components(2, z, z, fast), np.arange(2))
        assert same(components(0, z, z, fast), np.arange(0))


def test_a_hub_takes_every_colour_and_its_rows_are_split() -> None:
    """A body with twice MAX_COLORS rows: its rows take every colour, the last one many
    times, and the last colour's batches share no moving body, on both paths alike."""
    hub = 2 * MAX_COLORS
    a = np.zeros(hub, dtype=np.int64)
    b = np.arange(1, hub + 1)
    moves = np.append(np.ones(hub + 1, dtype=bool), False)
    color = colors(a, b, moves)
    assert same(colors(a, b, moves, fast=True), color)
    assert sorted(set(color.tolist())) == list(range(MAX_COLORS))
    out = batches(color, a, b, moves, fast=True)
    assert same_batches(out, batches(color, a, b, moves))
    assert len(out) == MAX_COLORS - 1 + (hub - (MAX_COLORS - 1))  # a round a row at the hub
    for rows in out:
        bodies = np.concatenate([a[rows], b[rows]])
        assert len(np.unique(bodies)) == len(bodies)


def test_the_comparison_can_fail() -> None:
    """The twin comparison catches a kernel that colours in another order: the greedy with
    the priority reversed gives another colouring of a chain of rows."""
    a, b = np.array([0, 1, 2, 3]), np.array([1, 2, 3, 4])
    moves = np.append(np.ones(5, dtype=bool), False)
    want = colors(a, b, moves)
    other = colors(a, b, moves, priority=-np.arange(4.0)[::-1], fast=True)
    assert not same(other, want)
    # The kernel with the twin's own default priority agrees.
    assert same(colors(a, b, moves, priority=-(a * 5.0 + b) - np.arange(4) / 5.0, fast=True), want)
    assert want.tolist() == [0, 1, 0, 1] and other.tolist() == [1, 0, 1, 0]


def test_prepare_compiles_the_kernels() -> None:
    """The modules of these kernels are in engine.kernels.MODULES, so ``prepare`` reaches
    them (each with a sample call)."""
    assert {"engine.dynamics.coloring", "engine.exact.pile"} <= set(kernels.MODULES)
    names = {k.name for k in kernels.kernels()}
    assert {
        "engine.dynamics.coloring.color_rows",
        "engine.dynamics.coloring.batch_rows",
        "engine.exact.pile.label_rows",
    } <= names
    for k in (coloring.color_rows, coloring.batch_rows):
        assert k.name in kernels._SAMPLES
