"""The loop kernels of a pile's step (engine.exact.pile, engine.exact.pile_rows,
engine.exact.push_out) against their numpy twins.

Each kernel assembles, looks up or moves rows with its twin's products and sums in the same
order, so on the same inputs it must give the twin's arrays bit for bit (``same``: dtype,
shape and bytes; a -0.0 for a 0.0 would count), in the same order: the 1,000-ball pit stays
bit-identical on both paths. Without numba the kernels run as the plain Python they are
written in (``LoopKernel.py``).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from engine import kernels
from engine.exact import pile, pile_rows, push_out
from engine.exact.contacts import Contacts
from engine.exact.pile import Carried, carry_out, dissipative
from engine.exact.pile_rows import disc_rows, face_rows, held, warm_start
from engine.exact.push_out import push_out_rows
from engine.geometry.colliders import Box, Circle, Collider, Polygon, Segment
from engine.geometry.faces import compile_faces
from engine.kernels import LoopKernel

COMPILED = kernels.available()
seeds = st.integers(0, 2**32 - 1)


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not COMPILED:
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def same(x: object, y: object) -> bool:
    """The same array bit for bit (dtype, shape, bytes), or tuples of them."""
    if isinstance(x, tuple | list):
        assert isinstance(y, tuple | list)
        return len(x) == len(y) and all(same(p, q) for p, q in zip(x, y, strict=True))
    x, y = np.asarray(x), np.asarray(y)
    return x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()


def disc_pairs(seed: int, bodies: int, pairs: int) -> tuple[np.ndarray, ...]:
    """(pa, pb, la, lb, X, r, mu, e) of made-up pairs of discs: World rows pa < pb, their
    places in the pile, half the positions on a grid of nine points (so some centres
    coincide), radii, materials."""
    rng = np.random.default_rng(seed)
    U = np.sort(rng.choice(3 * bodies + 1, bodies, replace=False))
    la = rng.integers(0, bodies, pairs)
    lb = (la + rng.integers(1, max(bodies, 2), pairs)) % bodies if bodies > 1 else la
    la, lb = np.minimum(la, lb), np.maximum(la, lb)
    X = rng.integers(-1, 2, (bodies, 2)) * 0.25 + rng.normal(0, 1, (bodies, 2)) * (
        rng.random((bodies, 1)) < 0.5
    )
    r = rng.uniform(0.05, 1.0, bodies)
    return U[la], U[lb], la, lb, X, r, rng.uniform(0, 1, bodies), rng.uniform(0, 1, bodies)


@given(seed=seeds, bodies=st.integers(1, 30), pairs=st.integers(0, 80))
def test_disc_rows_kernel_is_its_numpy_twin(seed: int, bodies: int, pairs: int) -> None:
    """``disc_rows(fast=True)`` (``disc_loop``): the same normals (straight up where centres
    coincide), gaps, materials, slops and keys, bit for bit."""
    pa, pb, la, lb, X, r, mu, e = disc_pairs(seed, bodies, pairs)
    base = 3 * bodies + 7
    want = disc_rows(pa, pb, la, lb, X, r, mu, e, base)
    assert same(disc_rows(pa, pb, la, lb, X, r, mu, e, base, fast=True), want)


def carried_rows(seed: int, carried: int, rows: int, repeats: bool) -> tuple[Carried, np.ndarray]:
    """A made-up Carried (sorted keys, some repeated if ``repeats``; colour keys the same
    array or another) and this step's row keys: runs of sorted keys, some found, some new."""
    rng = np.random.default_rng(seed)
    keys = np.sort(rng.choice(4 * carried + 10, carried, replace=repeats)).astype(np.int64)
    lam = rng.normal(0, 1, (carried, 2))
    colors = rng.integers(-1, 12, carried).astype(np.int64)
    color_keys = keys if rng.random() < 0.5 else np.sort(rng.choice(4 * carried + 10, carried))
    c = Carried(keys, lam, float(rng.uniform(0.005, 0.05)), 50, color_keys, colors)
    key = rng.integers(0, 4 * carried + 12, rows).astype(np.int64)
    cut = np.sort(rng.integers(0, rows + 1, 3))
    for lo, hi in zip(cut[:-1], cut[1:], strict=True):  # sorted runs, as a pile's rows come
        key[lo:hi] = np.sort(key[lo:hi])
    return c, key


@given(
    seed=seeds,
    n_carried=st.integers(0, 60),
    rows=st.integers(0, 80),
    repeats=st.booleans(),
    base=st.sampled_from([50, 50, 51]),
)
def test_warm_start_kernel_is_its_numpy_twin(
    seed: int, n_carried: int, rows: int, repeats: bool, base: int
) -> None:
    """``warm_start(fast=True)`` (``carry_in``, a galloping search from the last place):
    each row finds the impulses and colour searchsorted finds (the first of repeated keys),
    nothing across a change of base."""
    c, key = carried_rows(seed, n_carried, rows, repeats)
    want = warm_start(c, key, base, 1 / 60, 4)
    assert same(warm_start(c, key, base, 1 / 60, 4, fast=True), want)


def test_warm_start_finds_every_key_of_a_sorted_run() -> None:
    """Keys carried from the last step are found again whatever their order."""
    keys = np.arange(0, 300, 3, dtype=np.int64)
    c = Carried(keys, np.ones((100, 2)), 0.01, 7, keys, np.arange(100, dtype=np.int64))
    for key in (keys, keys[::-1].copy(), np.random.default_rng(1).permutation(keys)):
        lam, prior = warm_start(c, key, 7, 0.01, 1, fast=True)
        assert same((lam, prior), warm_start(c, key, 7, 0.01, 1))
        assert (lam == 1.0).all() and same(prior, key // 3)


@given(seed=seeds, bodies=st.integers(1, 30), pairs=st.integers(0, 60), faces=st.integers(0, 20))
def test_held_kernel_is_its_numpy_twin(seed: int, bodies: int, pairs: int, faces: int) -> None:
    """``held(fast=True)`` (``held_loop``): the same pairs holding and near, the same gaps
    now (the static slot unmoved), the same rows held."""
    pa, pb, la, lb, X0, r, _, _ = disc_pairs(seed, bodies, pairs)
    rng = np.random.default_rng(seed + 1)
    X = X0 + rng.normal(0, 0.01, X0.shape) * (rng.random((bodies, 1)) < 0.8)
    fa = rng.integers(0, bodies, faces)
    ra = np.concatenate([la, np.full(faces, bodies)])
    rb = np.concatenate([lb, fa])
    angle = rng.uniform(0, 2 * np.pi, len(ra))
    nv = np.stack([np.cos(angle), np.sin(angle)], axis=1)
    sep = rng.normal(0, 0.01, len(ra))
    slop = rng.uniform(0, 0.002, len(ra))
    total = np.where(rng.random(len(ra)) < 0.5, rng.uniform(0, 1, len(ra)), 0.0)
    want = held(X, X0, la, lb, r, ra, rb, nv, sep, slop, total)
    assert same(held(X, X0, la, lb, r, ra, rb, nv, sep, slop, total, fast=True), want)


@given(seed=seeds, bodies=st.integers(1, 40), groups=st.integers(1, 5), gain=st.booleans())
def test_dissipative_kernel_is_its_numpy_twin(
    seed: int, bodies: int, groups: int, gain: bool
) -> None:
    """``dissipative(fast=True)`` (``dissipate_rows``): each group's sums in row order, the
    same scaled velocities (or V itself where no group gained), with and without groups."""
    rng = np.random.default_rng(seed)
    V0 = rng.normal(0, 1, (bodies, 2))
    dV = rng.normal(0, 0.1, (bodies, 2))
    V = V0 + (dV if gain else -0.05 * V0)
    m = rng.uniform(0.1, 3.0, bodies)
    group = rng.integers(0, groups, bodies).astype(np.int64)
    group = np.minimum(group, bodies - 1)
    assert same(dissipative(V, V0, m, group, fast=True), dissipative(V, V0, m, group))
    assert same(dissipative(V, V0, m, fast=True), dissipative(V, V0, m))


@given(seed=seeds, bodies=st.integers(1, 40), groups=st.integers(1, 5), gain=st.booleans())
def test_dissipative_kernel_with_spins_is_its_numpy_twin(
    seed: int, bodies: int, groups: int, gain: bool
) -> None:
    """With bodies that turn (spins W, W0, moments I; I = 0 for some), the kernel scales the
    same groups' V and W as the twin, bit for bit; with every I and spin 0 it gives the V of
    no spins at all."""
    rng = np.random.default_rng(seed)
    V0 = rng.normal(0, 1, (bodies, 2))
    V = V0 + (rng.normal(0, 0.1, (bodies, 2)) if gain else -0.05 * V0)
    W0 = rng.normal(0, 3, bodies)
    W = W0 + (rng.normal(0, 0.5, bodies) if gain else -0.05 * W0)
    inertia = np.where(rng.random(bodies) < 0.7, rng.uniform(0.01, 1.0, bodies), 0.0)
    m = rng.uniform(0.1, 3.0, bodies)
    group = np.minimum(rng.integers(0, groups, bodies), bodies - 1).astype(np.int64)
    spins = (W, W0, inertia)
    assert same(
        dissipative(V, V0, m, group, True, spins), dissipative(V, V0, m, group, False, spins)
    )
    z = np.zeros(bodies)
    for fast in (False, True):
        got, w = dissipative(V, V0, m, group, fast, (z, z, z))
        assert same(got, dissipative(V, V0, m, group, fast)) and not w.any()


def test_dissipative_counts_the_spins_energy() -> None:
    """Friction that passes a spin's energy to a body's speed is no gain: the spin's
    I omega^2 / 2 counts (without it, the speed's gain would be scaled away)."""
    V0, V = np.zeros((1, 2)), np.array([[1.0, 0.0]])  # 0.5 J of speed gained ...
    W0, W = np.array([4.0]), np.array([2.0])  # ... from 0.125 (16 - 4) / 2 = 0.75 J of spin
    inertia, m = np.array([0.125]), np.ones(1)
    for fast in (False, True):
        out, w = dissipative(V, V0, m, None, fast, (W, W0, inertia))
        assert same(out, V) and same(w, W)
        assert not same(dissipative(V, V0, m, None, fast), V)  # the speed alone: a gain


def test_dissipative_kernel_scales_a_gain_back() -> None:
    """A pile that gained energy is scaled back to its least, as the twin does."""
    V0, V = np.array([[1.0, 0.0], [-1.0, 0.0]]), np.array([[2.0, 0.0], [-2.0, 0.0]])
    m, group = np.ones(2), np.zeros(2, dtype=np.int64)
    out = dissipative(V, V0, m, group, fast=True)
    assert same(out, dissipative(V, V0, m, group))
    assert np.allclose(out, V0)  # s = 0: the change only added energy


@given(
    seed=seeds,
    n_carried=st.integers(0, 40),
    rows=st.integers(0, 60),
    colored=st.booleans(),
    base=st.sampled_from([12, 12, 13]),
)
def test_carry_out_kernel_is_its_numpy_twin(
    seed: int, n_carried: int, rows: int, colored: bool, base: int
) -> None:
    """``carry_out(fast=True)`` (``carry_keys``, the twin's sort, ``carry_gather``): the
    sleepers' rows kept (pairs of sleepers, sleepers on faces, none of the shapes' rows),
    the impulses over the step, the colours (-1 where the cache lost them), sorted by key
    alike, repeated keys too."""
    rng = np.random.default_rng(seed)
    n = 8
    keys = np.sort(rng.choice(n * 12 + 30, n_carried, replace=False)).astype(np.int64)
    colors = rng.integers(-1, 12, n_carried if colored else max(n_carried - 1, 0))
    c = Carried(keys, rng.normal(0, 1, (n_carried, 2)), 0.01, 12, keys, colors.astype(np.int64))
    asleep = rng.random(n) < 0.5
    key = rng.choice(n * 12 + 30, rows, replace=rng.random() < 0.2).astype(np.int64)
    lam_n, lam_t = rng.uniform(0, 1, rows), rng.normal(0, 1, rows)
    color = rng.integers(0, 12, rows).astype(np.int64)
    for sleeping in (asleep, asleep[:-1]):  # a World that changed: nothing kept
        want = carry_out(c, sleeping, n, base, key, lam_n, lam_t, 4, color, 0.02)
        got = carry_out(c, sleeping, n, base, key, lam_n, lam_t, 4, color, 0.02, fast=True)
        assert same(tuple(got), tuple(want))
        assert got.lam_dt == want.lam_dt and got.base == want.base


def contacts_of(colliders: list[Collider]) -> Contacts:
    contacts = Contacts()
    for c in colliders:
        contacts.add(c)
    return contacts


SCENES: dict[str, list[Collider]] = {
    "box": [Box((0, 0), (10, 8))],
    "pegs": [Box((0, 0), (10, 8)), Circle((3, 2), 0.7), Circle((6, 3), 0.4)],
    "walls": [Segment((1, 1), (9, 2)), Segment((5, 0), (5, 6), radius=0.3), Circle((2, 5), 1)],
}


def balls(seed: int, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Balls across the scenes' room: positions, velocities, radii (some far inside walls)."""
    rng = np.random.default_rng(seed)
    X = rng.uniform(-0.5, 10.5, (count, 2)) * (1.0, 0.8)
    V = rng.normal(0, 2, (count, 2))
    r = rng.uniform(0.1, 0.8, count)
    return X, V, r


@given(seed=seeds, count=st.integers(0, 40), scene=st.sampled_from(sorted(SCENES)))
def test_face_rows_kernel_is_its_numpy_twin(seed: int, count: int, scene: str) -> None:
    """``face_rows(fast=True)`` (``face_loop`` after the grid): the same (body, normal, gap,
    friction, face) rows in the same order, flat and round faces, two-sided and one."""
    contacts = contacts_of(SCENES[scene])
    X, V, r = balls(seed, count)
    margin = 0.05 * r + np.abs(V[:, 0]) * 0.02
    want = face_rows(contacts, X, r, margin)
    assert same(face_rows(contacts, X, r, margin, fast=True), want)


@given(
    seed=seeds,
    count=st.integers(0, 40),
    scene=st.sampled_from(sorted(SCENES)),
    filtered=st.booleans(),
)
def test_push_out_kernel_is_its_numpy_twin(
    seed: int, count: int, scene: str, filtered: bool
) -> None:
    """``push_out_rows(fast=True)`` (``push_rows``, each row through its rounds in turn):
    the same positions, velocities and pushed rows, bit for bit, with or without ``meets``
    (rows that meet only some faces), out of corners after four rounds alike."""
    colliders = SCENES[scene]
    faces = compile_faces(colliders, list(range(len(colliders))))
    X, V, r = balls(seed, count)
    r[np.random.default_rng(seed + 3).random(count) < 0.1] = -np.inf  # rows left alone
    meets = None
    if filtered:
        meets = np.random.default_rng(seed + 4).random((count, len(faces.owner))) < 0.7
    outs = []
    for fast in (False, True):
        x, v = X.copy(), V.copy()
        pushed = push_out_rows(faces, colliders, x, v, r, meets, fast)
        outs.append((x, v, pushed))
    assert same(outs[1], outs[0])


def test_push_out_kernel_frees_a_ball_in_a_corner() -> None:
    """A ball pressed between a peg and a wall needs more than four rounds: both paths put
    it at the same corner (out_of_corner after the kernel's rounds)."""
    colliders: list[Collider] = [Box((0, 0), (10, 8)), Circle((1.2, 4), 0.5)]
    faces = compile_faces(colliders, [0, 1])
    outs = []
    for fast in (False, True):
        x, v = np.array([[0.6, 4.05], [5.0, 0.3]]), np.array([[-1.0, 0.5], [0.0, -1.0]])
        pushed = push_out_rows(faces, colliders, x, v, np.array([0.5, 0.5]), None, fast)
        outs.append((x, v, pushed))
    assert same(outs[1], outs[0])
    assert outs[1][2].all()


def test_push_out_with_a_polygon_keeps_the_numpy_rounds() -> None:
    """A polygon's inside needs ``polygon_distance``: the fast path takes the twin's rounds."""
    colliders: list[Collider] = [Box((0, 0), (10, 8)), Polygon.box(2, 2, center=(5, 4))]
    faces = compile_faces(colliders, [0, 1])
    assert faces.polygons
    outs = []
    for fast in (False, True):
        x, v = np.array([[5.2, 4.1], [0.1, 3.0]]), np.zeros((2, 2))
        pushed = push_out_rows(faces, colliders, x, v, np.array([0.5, 0.5]), None, fast)
        outs.append((x, v, pushed))
    assert same(outs[1], outs[0]) and outs[0][2].all()


def test_the_comparison_can_fail() -> None:
    """``same`` sees one last bit: a disc_rows whose gap subtracts the radii summed first,
    dist - (r_a + r_b), not (dist - r_a) - r_b, differs from the twin on some rows."""
    pa, pb, la, lb, X, r, mu, e = disc_pairs(7, 30, 200)
    nrm, sep, *_ = disc_rows(pa, pb, la, lb, X, r, mu, e, 100, fast=True)
    d = X[lb] - X[la]
    other = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]) - (r[la] + r[lb])
    assert np.allclose(other, sep, rtol=0, atol=1e-14)  # the same to rounding...
    assert not same(other, sep)  # ...but not bit for bit, and the comparison says so
    flipped = np.where(nrm == 0.0, -0.0, nrm)  # a -0.0 for a 0.0 counts too
    assert (nrm == 0.0).any() and not same(flipped, nrm)


def test_the_kernels_are_the_engines_and_have_samples() -> None:
    """These modules are in engine.kernels.MODULES, and every kernel has a sample call for
    ``prepare`` that runs."""
    assert {"engine.exact.pile", "engine.exact.pile_rows", "engine.exact.push_out"} <= set(
        kernels.MODULES
    )
    mine = (
        pile.dissipate_rows,
        pile.carry_keys,
        pile.carry_gather,
        pile_rows.disc_loop,
        pile_rows.face_loop,
        pile_rows.carry_in,
        pile_rows.held_loop,
        push_out.push_rows,
    )
    for k in mine:
        assert k in kernels.kernels() and k.name in kernels._SAMPLES
        k.fast(*kernels._SAMPLES[k.name]())


@pytest.mark.skipif(not COMPILED, reason="numba is not installed: the fast path is not there")
def test_the_pit_is_bit_identical_on_both_paths() -> None:
    """The 1,000-ball pit over 300 steps: the same final positions on both paths, bit for
    bit."""
    from demos.bench.pit import DT, make_world

    ends = []
    for path in ("numpy", "fast"):
        world = make_world(1000, kernels=path)
        for _ in range(300):
            world.step(DT)
        ends.append(world.positions())
    assert np.abs(ends[1] - ends[0]).max() == 0.0


@given(
    x=st.floats(-6.0, 6.0),
    y=st.floats(-6.0, 6.0),
    r=st.sampled_from([0.0, 0.05, 0.3, 1.0]),
)
def test_one_body_clear_of_every_face_is_found_clear_at_once(x: float, y: float, r: float) -> None:
    """``push_out`` of one body looks at every face at once first, and stops where none is
    within reach (a game spawning a ball): the same answer, and the same place, as asking
    the colliders one by one (the body taken with a second, which always asks them), for
    a ball anywhere in a room with a peg, a capsule, a rounded and a sharp polygon."""
    colliders: list[Collider] = [
        Box((-5.0, -5.0), (5.0, 5.0)),
        Circle((2.0, 2.0), 0.7),
        Segment((-3.0, 1.0), (0.0, 2.5), radius=0.2),
        Polygon([(-2.0, -3.0), (0.0, -3.5), (-0.5, -1.0)], radius=0.1),
        Polygon.box(1.0, 1.5, center=(2.5, -2.0)),
    ]
    faces = compile_faces(colliders, list(range(len(colliders))))
    alone = (np.array([[x, y]]), np.array([[1.0, -1.0]]))
    paired = (np.array([[x, y], [0.0, 4.0]]), np.array([[1.0, -1.0], [0.0, 0.0]]))
    radius = np.array([r, 0.1])
    moved = push_out.push_out(colliders, faces, None, *alone, radius[:1], np.array([0]))
    asked = push_out.push_out(colliders, faces, None, *paired, radius, np.array([0, 1]))
    assert moved == [m for m in asked if m[0] == 0]
    assert np.array_equal(alone[0][0], paired[0][0]) and np.array_equal(alone[1][0], paired[1][0])
