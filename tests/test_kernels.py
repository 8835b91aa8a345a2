"""The loop kernels (engine.kernels) against their numpy twins, and the choice of path.

Each kernel is the same algorithm as its numpy twin, so a single call on the same inputs gives
the same numbers to rounding: 1e-12 relative (a call is a function of its inputs; chaos over
many steps, which amplifies rounding, is not in it). Without numba the kernels run as the plain
Python they are written in (``LoopKernel.py``), so the algorithm is checked on every machine;
with the ``fast`` extra installed they run compiled.
"""

from __future__ import annotations

import os
import subprocess
import sys
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from engine import Body, Vector, World, kernels
from engine.exact.soft import Arms, Rows, SoftStep
from engine.kernels import LoopKernel

COMPILED = kernels.available()


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not COMPILED:
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def close(x: np.ndarray, y: np.ndarray, rel: float = 1e-12) -> bool:
    """Equal to ``rel`` relative, against the largest magnitude of either."""
    scale = max(1.0, float(np.abs(x).max(initial=0.0)), float(np.abs(y).max(initial=0.0)))
    return bool(np.all(np.abs(np.asarray(x) - np.asarray(y)) <= rel * scale))


def random_pile(seed: int, bodies: int, rows: int) -> tuple[Rows, np.ndarray, np.ndarray, dict]:
    """Rows of a made-up pile: pairs of bodies and bodies against the static slot (the last),
    unit normals, gaps and overlaps, materials, warm-start impulses; some bodies held."""
    rng = np.random.default_rng(seed)
    a = rng.integers(0, bodies, rows)
    b = rng.integers(0, bodies + 1, rows)  # bodies: the static slot
    same = a == b
    b[same] = bodies
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    static = hi == bodies
    a = np.where(static, bodies, lo)  # A is the static slot for a wall, as in engine.exact.pile
    b = np.where(static, lo, hi)
    angle = rng.uniform(0, 2 * np.pi, rows)
    warm = rng.random(rows) < 0.6
    r = Rows(
        a,
        b,
        np.exp(1j * angle),
        rng.uniform(-0.05, 0.05, rows),
        rng.uniform(0.0, 1.0, rows),
        rng.uniform(0.0, 1.0, rows),
        np.where(warm, rng.uniform(0.0, 0.2, rows), 0.0),
        np.where(warm, rng.uniform(-0.05, 0.05, rows), 0.0),
        static,
    )
    moves = np.append(rng.random(bodies) < 0.9, False)
    w = np.append(1.0 / rng.uniform(0.2, 5.0, bodies), 0.0)
    w[~moves] = 0.0
    slop = rng.uniform(0.0, 0.02, rows)
    options = dict(
        push_speed=rng.uniform(0.1, 2.0, rows),
        threshold=float(rng.uniform(0.0, 0.5)),
        slop=slop if rng.random() < 0.7 else None,
    )
    return r, w, moves, options


def copy_rows(r: Rows) -> Rows:
    return Rows(*(np.array(getattr(r, f)) for f in Rows.__dataclass_fields__))


@given(
    seed=st.integers(0, 2**32 - 1),
    bodies=st.integers(1, 25),
    rows=st.integers(0, 60),
    substeps=st.integers(1, 6),
    dt=st.sampled_from([1 / 240, 1 / 60, 1 / 7]),
)
def test_soft_step_kernel_is_its_numpy_twin(
    seed: int, bodies: int, rows: int, substeps: int, dt: float
) -> None:
    """SoftStep.run on the fast path (``run_rows``) gives the numpy twin's state, impulses
    and totals to 1e-12 relative, on random piles."""
    r, w, moves, options = random_pile(seed, bodies, rows)
    rng = np.random.default_rng(seed + 1)
    x0 = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    v0 = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    acc = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    acc[:-1][~moves[:-1]] = 0.0
    out = {}
    for fast in (False, True):
        rows_copy = copy_rows(r)
        step = SoftStep(rows_copy, w, moves, dt, substeps, fast=fast, **options)
        x, v = step.run(x0.copy(), v0.copy(), acc)
        out[fast] = (x, v, rows_copy.lam_n, rows_copy.lam_t, step.total)
    for got, want in zip(out[True], out[False], strict=True):
        assert close(got, want)


def test_the_twins_differ_where_the_algorithm_does() -> None:
    """The comparison can fail: a kernel that skips friction is caught by it."""
    r, w, moves, options = random_pile(7, 10, 40)
    r.friction[:] = 0.9
    x0 = v0 = np.zeros(11, dtype=complex)
    acc = np.append(np.full(10, 1.0 - 9.81j), 0.0)
    ref = SoftStep(copy_rows(r), w, moves, 1 / 60, fast=False, **options).run(x0, v0, acc)
    r.friction[:] = 0.0
    other = SoftStep(copy_rows(r), w, moves, 1 / 60, fast=True, **options).run(x0, v0, acc)
    assert not close(ref[1], other[1])


def random_arms(seed: int, bodies: int, r: Rows, moves: np.ndarray) -> tuple[Arms, ...]:
    """Lever arms for a made-up pile: some moving bodies turn (a radius and a moment each),
    with a spin and an angular acceleration; (arms, omega0, alpha), the static slot last."""
    rng = np.random.default_rng(seed + 2)
    turns = np.append(rng.random(bodies) < 0.7, False) & moves
    radius = rng.uniform(0.1, 1.0, bodies + 1)
    inv = np.where(turns, 1.0 / rng.uniform(0.05, 3.0, bodies + 1), 0.0)
    # A row's lever arm: the radius, less half of an overlap (engine.exact.pile_rows.lever_arms).
    half = 0.5 * np.minimum(r.separation, 0.0)
    la = np.where(turns[r.a], radius[r.a] + half, 0.0)
    lb = np.where(turns[r.b], radius[r.b] + half, 0.0)
    omega0 = np.where(turns, rng.normal(0.0, 5.0, bodies + 1), 0.0)
    alpha = np.where(turns, rng.normal(0.0, 3.0, bodies + 1), 0.0)
    return Arms(la, lb, inv), omega0, alpha


@given(
    seed=st.integers(0, 2**32 - 1),
    bodies=st.integers(1, 25),
    rows=st.integers(0, 60),
    substeps=st.integers(1, 6),
    dt=st.sampled_from([1 / 240, 1 / 60, 1 / 7]),
)
def test_soft_step_kernel_with_lever_arms_is_its_numpy_twin(
    seed: int, bodies: int, rows: int, substeps: int, dt: float
) -> None:
    """With discs that turn (lever arms, spins, torques), the loop kernel gives the numpy
    twin's state, spins, angles, impulses and totals bit for bit, on random piles."""
    r, w, moves, options = random_pile(seed, bodies, rows)
    arms, omega0, alpha = random_arms(seed, bodies, r, moves)
    rng = np.random.default_rng(seed + 1)
    x0 = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    v0 = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    acc = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    acc[:-1][~moves[:-1]] = 0.0
    out = {}
    for fast in (False, True):
        rows_copy = copy_rows(r)
        step = SoftStep(rows_copy, w, moves, dt, substeps, fast=fast, arms=arms, **options)
        x, v = step.run(x0.copy(), v0.copy(), acc, omega0.copy(), alpha)
        out[fast] = (x, v, rows_copy.lam_n, rows_copy.lam_t, step.total, step.omega, step.turned)
    for got, want in zip(out[True], out[False], strict=True):
        assert np.array_equal(got, want)


@given(seed=st.integers(0, 2**32 - 1), bodies=st.integers(1, 25), rows=st.integers(0, 60))
def test_lever_arms_of_zero_leave_every_number_as_it_was(seed: int, bodies: int, rows: int) -> None:
    """Rows whose lever arms are all 0 (no disc turns) give, on both paths, the bits of rows
    without lever arms: x - 0.0 is x, k + 0.0 is k, and a spin of 0 stays 0."""
    r, w, moves, options = random_pile(seed, bodies, rows)
    zero = Arms(np.zeros(rows), np.zeros(rows), np.zeros(bodies + 1))
    rng = np.random.default_rng(seed + 1)
    v0 = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    acc = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    acc[:-1][~moves[:-1]] = 0.0
    for fast in (False, True):
        plain, armed = copy_rows(r), copy_rows(r)
        a = SoftStep(plain, w, moves, 1 / 60, fast=fast, **options)
        b = SoftStep(armed, w, moves, 1 / 60, fast=fast, arms=zero, **options)
        got_a = a.run(v0.copy(), v0.copy(), acc)
        got_b = b.run(v0.copy(), v0.copy(), acc, np.zeros(bodies + 1), np.zeros(bodies + 1))
        for x, y in zip(got_a, got_b, strict=True):
            assert np.array_equal(x, y)
        assert np.array_equal(plain.lam_n, armed.lam_n)
        assert np.array_equal(plain.lam_t, armed.lam_t)
        assert np.array_equal(a.total, b.total)
        assert not b.omega.any() and not b.turned.any()


def corner_arms(seed: int, bodies: int, r: Rows, moves: np.ndarray) -> tuple[Arms, ...]:
    """``random_arms`` with bodies with corners: each row's contact point anywhere within a
    metre of the centres that turn, so the normal rows get lever arms r x n too."""
    arms, omega0, alpha = random_arms(seed, bodies, r, moves)
    rng = np.random.default_rng(seed + 3)
    turns = arms.inv_moment > 0.0
    rows = len(r.a)
    na = np.where(turns[r.a], rng.uniform(-1.0, 1.0, rows), 0.0)
    nb = np.where(turns[r.b], rng.uniform(-1.0, 1.0, rows), 0.0)
    return Arms(arms.a, arms.b, arms.inv_moment, na, nb), omega0, alpha


@given(
    seed=st.integers(0, 2**32 - 1),
    bodies=st.integers(1, 25),
    rows=st.integers(0, 60),
    substeps=st.integers(1, 6),
    dt=st.sampled_from([1 / 240, 1 / 60, 1 / 7]),
)
def test_soft_step_kernel_with_normal_lever_arms_is_its_numpy_twin(
    seed: int, bodies: int, rows: int, substeps: int, dt: float
) -> None:
    """With bodies with corners (lever arms on the normal rows too: warm start, solve,
    relax, restitution, projection), the loop kernel gives the numpy twin's state, spins,
    angles, impulses and totals bit for bit, on random piles."""
    r, w, moves, options = random_pile(seed, bodies, rows)
    arms, omega0, alpha = corner_arms(seed, bodies, r, moves)
    rng = np.random.default_rng(seed + 1)
    x0 = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    v0 = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    acc = np.append(rng.normal(size=bodies) + 1j * rng.normal(size=bodies), 0.0)
    acc[:-1][~moves[:-1]] = 0.0
    out = {}
    for fast in (False, True):
        rows_copy = copy_rows(r)
        step = SoftStep(rows_copy, w, moves, dt, substeps, fast=fast, arms=arms, **options)
        x, v = step.run(x0.copy(), v0.copy(), acc, omega0.copy(), alpha)
        out[fast] = (x, v, rows_copy.lam_n, rows_copy.lam_t, step.total, step.omega, step.turned)
    for got, want in zip(out[True], out[False], strict=True):
        assert np.array_equal(got, want)


def test_the_twins_differ_where_the_normal_lever_arms_do() -> None:
    """The comparison can fail: a kernel given the normal lever arms' opposite sign is
    caught by it."""
    r, w, moves, options = random_pile(13, 10, 40)
    arms, omega0, alpha = corner_arms(13, 10, r, moves)
    x0 = np.zeros(11, dtype=complex)
    acc = np.append(np.full(10, 1.0 - 9.81j), 0.0)
    ref = SoftStep(copy_rows(r), w, moves, 1 / 60, fast=False, arms=arms, **options)
    ref.run(x0, x0, acc, omega0, alpha)
    assert arms.na is not None and arms.nb is not None
    flipped = Arms(arms.a, arms.b, arms.inv_moment, -arms.na, -arms.nb)
    other = SoftStep(copy_rows(r), w, moves, 1 / 60, fast=True, arms=flipped, **options)
    other.run(x0, x0, acc, omega0, alpha)
    assert not close(ref.omega, other.omega)


def test_the_twins_differ_where_the_lever_arms_do() -> None:
    """The comparison can fail: a kernel given the lever arms' opposite sign (the slip's
    omega terms added, not taken off) is caught by it."""
    r, w, moves, options = random_pile(11, 10, 40)
    r.friction[:] = 0.9
    arms, omega0, alpha = random_arms(11, 10, r, moves)
    x0 = np.zeros(11, dtype=complex)
    acc = np.append(np.full(10, 1.0 - 9.81j), 0.0)
    ref = SoftStep(copy_rows(r), w, moves, 1 / 60, fast=False, arms=arms, **options)
    ref.run(x0, x0, acc, omega0, alpha)
    flipped = Arms(-arms.a, -arms.b, arms.inv_moment)
    other = SoftStep(copy_rows(r), w, moves, 1 / 60, fast=True, arms=flipped, **options)
    other.run(x0, x0, acc, omega0, alpha)
    assert not close(ref.omega, other.omega)


# -- the path a World takes -------------------------------------------------------------------


def test_a_world_says_its_path_and_takes_the_one_asked(monkeypatch: pytest.MonkeyPatch) -> None:
    assert World(kernels="numpy").kernels == "numpy"
    monkeypatch.setenv("ENGINE_KERNELS", "numpy")
    assert World().kernels == "numpy"
    monkeypatch.delenv("ENGINE_KERNELS")
    assert World().kernels == ("fast" if COMPILED else "numpy")


@pytest.mark.parametrize("bad", ["gpu", "", "Fast", 3])
def test_a_path_that_is_not_one_is_refused_by_name(bad: object) -> None:
    with pytest.raises(ValueError, match="kernels must be 'numpy' or 'fast'"):
        World(kernels=bad)  # type: ignore[arg-type]


def test_a_bad_environment_value_is_named(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ENGINE_KERNELS", "cuda")
    with pytest.raises(ValueError, match="ENGINE_KERNELS must be 'numpy' or 'fast'.*'cuda'"):
        World()


@pytest.mark.skipif(COMPILED, reason="numba is installed: fast is available")
def test_fast_without_numba_says_how_to_install_it() -> None:
    with pytest.raises(ValueError, match=r"pip install -e '\.\[fast\]'"):
        World(kernels="fast")


def test_import_engine_does_not_import_numba() -> None:
    """Nor does a World on the numpy path: only the fast path needs it."""
    code = (
        "import sys, engine; from engine import World; World(kernels='numpy'); "
        "print('numba' in sys.modules)"
    )
    env = {**os.environ, "ENGINE_KERNELS": ""}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    )
    assert out.stdout.strip() == "False"


@pytest.mark.skipif(not COMPILED, reason="numba is not installed: nothing compiles")
def test_a_world_on_the_fast_path_is_made_with_every_kernel_ready() -> None:
    """Its first step waits on no compile: ``kernels.prepare`` ran when it was made."""
    World(kernels="fast")
    engine_kernels = [k for k in kernels.kernels() if k.name.startswith("engine.")]
    assert len(engine_kernels) >= 22
    assert [k.name for k in engine_kernels if not k.ready] == []
    assert all(len(k.fast.signatures) >= 1 for k in engine_kernels)
    assert kernels.prepare() == 0.0  # a second call has nothing to do


def test_a_pile_lands_the_same_on_both_paths() -> None:
    """Ten balls dropped into a bin, one step at a time on each path: the same to 1e-9 m
    over the first half second (before rounding's chaos, which a pile amplifies, grows)."""
    from engine import Box
    from engine.forces import Gravity

    def bin_world(path: str) -> World:
        world = World(integrator="auto", kernels=path)
        world.add_force(Gravity((0.0, -9.81)))
        world.add_collider(Box((0.0, 0.0), (4.0, 100.0)))
        for k in range(10):
            world.add(Body(Vector(0.6 + 0.9 * (k % 4), 0.5 + 1.05 * (k // 4)), Vector(0, 0),
                           Vector(0, 0), radius=0.45, restitution=0.3, friction=0.5))  # fmt: skip
        return world

    paths = ["numpy", "fast"] if COMPILED else ["numpy"]
    worlds = [bin_world(p) for p in paths]
    for _ in range(30):
        for world in worlds:
            world.step(1 / 60)
    y = worlds[0].positions()[:, 1]
    assert y.min() > 0.4  # the balls rest on the floor, not through it
    if len(worlds) == 2:
        assert np.abs(worlds[0].positions() - worlds[1].positions()).max() < 1e-9


_SORT: list[Any] = []


def _compiled_sort() -> Any:
    """The compiled twin of ``stable_order``, compiled once for the tests below (its plain
    Python without numba)."""
    if not _SORT:
        sort: Any = kernels._stable_order_compiled
        if COMPILED:
            import numba

            sort = numba.njit(sort)
        _SORT.append(sort)
    return _SORT[0]


@pytest.mark.parametrize("n", [0, 1, 2, 15, 16, 17, 33, 63, 64, 65, 200, 1000, 5000])
@pytest.mark.parametrize("spread", ["ties", "wide", "narrow", "extreme"])
def test_the_compiled_stable_order_is_numpys_stable_argsort(n: int, spread: str) -> None:
    """``engine.kernels.stable_order``'s compiled twin (buckets of the leading bits, each
    merge-sorted from runs of 16 by insertion) gives numpy's stable argsort, the one answer a
    stable sort has: ties keep their order (few distinct keys), keys spread wide or packed
    close, and keys at the ends of the int64 range (a span wider than an int64)."""
    rng = np.random.default_rng(n * 7 + len(spread))
    keys = {
        "ties": rng.integers(0, 5, n),
        "wide": rng.integers(-(2**40), 2**40, n),
        "narrow": rng.integers(10**12, 10**12 + 3 * n + 1, n),
        "extreme": rng.choice(np.array([-(2**63), 2**63 - 1, 0, -1, 1]), n),
    }[spread].astype(np.int64)
    want = np.argsort(keys, kind="stable")
    assert np.array_equal(_compiled_sort()(keys), want)
    assert np.array_equal(kernels.stable_order(keys), want)
