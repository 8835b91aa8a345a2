"""The static contacts' loop kernels against their twins: the first looks
(engine.geometry.face_looks.looks_loop, called by ``first_looks``) against ``near``, ``asleep`` and
``narrow`` as engine.exact.contacts takes them (the same rows, sleepers and (body, face) pairs, in
the same order), the free bodies' paths (engine.exact.sweep_paths.paths_loop) against
``solve_few``'s Python floats (the same states, events and resting faces), on random bodies among
random faces; and a World whose static contacts take either path ends bit-identical."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine import Body, Box, Circle, Filter, Polygon, Segment, Vector, World, kernels
from engine.dynamics.rotation import Spin
from engine.exact.contacts import Contacts
from engine.exact.resting import asleep as asleep_arrays
from engine.exact.sweep import Paths
from engine.exact.sweep_one import MET, MISSED, PYTHON, _paths_fast, asleep_few, solve_few
from engine.forces import Gravity
from engine.geometry.face_grid import FaceGrid
from engine.geometry.face_looks import first_looks, grid_args, looks_loop, looks_ready, narrow, near
from engine.geometry.faces import Faces
from engine.kernels import LoopKernel

Allowed = Callable[[np.ndarray, np.ndarray], np.ndarray] | None


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not kernels.available():
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def numpy_looks(
    grid: FaceGrid,
    faces: Faces,
    x0: np.ndarray,
    v0: np.ndarray,
    B: np.ndarray,
    W: np.ndarray,
    dt: float,
    radius: np.ndarray,
    friction: np.ndarray,
    rest: np.ndarray,
    frozen: np.ndarray | None,
    allowed: Allowed,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The looks as Contacts.resolve takes them on the numpy path (``_near`` with the resting
    rows that stay put, then the frozen rows dropped, then ``narrow``)."""
    need, cell, reach, a_bound = near(grid, x0, v0, B, W, dt, radius)
    resting = np.flatnonzero(rest >= 0)
    asleep = asleep_arrays(faces, rest, resting, x0, v0, W, friction)
    assert np.array_equal(asleep, asleep_few(faces, rest, resting, x0, v0, W, friction))
    if len(resting):
        need[resting] = True
        need[asleep] = False
    rows = np.flatnonzero(need)
    assert cell is not None
    cell, reach = cell.take(rows), reach.take(rows)
    if frozen is not None and frozen[rows].any():
        awake = ~frozen[rows]
        rows, reach, cell = rows[awake], reach[awake], cell[awake]
    if not len(rows):
        return rows, rows, rows, asleep
    busy = rest.take(rows) >= 0
    rows, pb, pf = narrow(grid, rows, busy, cell, reach, a_bound, x0, v0, dt, radius, allowed)
    return rows, pb, pf, asleep


def make_grid(rng: np.random.Generator, kind: str) -> tuple[FaceGrid, Faces, np.ndarray]:
    """A grid over random faces: segments and pegs, inside a Box unless ``kind`` is "open";
    "edited": one segment taken out after the grid was laid (its slots renumbered). Returns
    the grid, the faces and points on them (where bodies are put near)."""
    contacts = Contacts()
    if kind != "open":
        contacts.add(Box((0.0, 0.0), (20.0, 15.0)))
    points = []
    segments = []
    for _ in range(int(rng.integers(2 if kind == "edited" else 1, 8))):
        a = rng.uniform((2.0, 2.0), (18.0, 13.0))
        b = a + rng.uniform(-3.0, 3.0, 2)
        seg = Segment(tuple(a), tuple(b), float(rng.choice([0.0, 0.05, 0.3])))
        segments.append(seg)
        contacts.add(seg)
        points += [a, b, 0.5 * (a + b)]
    for _ in range(int(rng.integers(0, 4))):
        c = rng.uniform((2.0, 2.0), (18.0, 13.0))
        contacts.add(Circle(tuple(c), float(rng.uniform(0.1, 1.0))))
        points.append(c)
    if kind == "edited":
        contacts.grid  # noqa: B018  (laid now, so the removal edits it in place)
        contacts.remove(segments[0])
    return contacts.grid, contacts.faces, np.array(points)


def bodies(
    rng: np.random.Generator,
    n: int,
    points: np.ndarray,
    speed: float,
    faces: int,
    small: bool = False,
    inside: bool = False,
):
    """n random bodies, many of them near the faces' points; some resting (half of those
    still), some frozen: (x0, v0, B, W, radius, rest, friction, frozen). ``small``: radii
    that let the quick way hold (each body's faces from its cell's list); ``inside``: all
    within the box, clear of its walls."""
    x0 = rng.uniform((-1.0, -1.0), (21.0, 16.0), (n, 2))
    near_face = rng.random(n) < 0.6
    x0[near_face] = points[rng.integers(0, len(points), int(near_face.sum()))]
    x0[near_face] += rng.normal(0.0, 0.3, (int(near_face.sum()), 2))
    if inside:
        x0 = np.clip(x0, (0.5, 0.5), (19.5, 14.5))
    v0 = rng.normal(0.0, speed, (n, 2)) * rng.choice([0.0, 1.0], (n, 1), p=[0.1, 0.9])
    B = np.tile([0.0, -9.81], (n, 1)) + rng.normal(0.0, 1.0, (n, 2)) * (rng.random((n, 1)) < 0.3)
    W = B if rng.random() < 0.5 else B + rng.normal(0.0, 0.5, (n, 2))
    radius = rng.choice([0.02, 0.05] if small else [0.02, 0.05, 0.1, 0.3], n)
    rest = np.where(rng.random(n) < 0.2, rng.integers(0, faces, n), -1).astype(np.intp)
    v0[(rest >= 0) & (rng.random(n) < 0.5)] = 0.0
    friction = rng.uniform(0.0, 1.5, n)
    frozen = rng.random(n) < 0.1 if rng.random() < 0.5 else None
    return x0, v0, B, W, radius, rest, friction, frozen


def filters(rows: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """A stand-in for colliders' filters: some (body, face) pairs do not meet."""
    return (rows + 2 * faces) % 3 != 0


@settings(deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 60),
    kind=st.sampled_from(["box", "open", "edited"]),
    speed=st.sampled_from([0.5, 3.0, 30.0]),
    dt=st.sampled_from([1 / 120, 1 / 60, 1 / 20]),
    filtered=st.booleans(),
    small=st.booleans(),
    inside=st.booleans(),
)
def test_first_looks_give_the_numpy_twins_rows_and_pairs(
    seed: int,
    n: int,
    kind: str,
    speed: float,
    dt: float,
    filtered: bool,
    small: bool,
    inside: bool,
) -> None:
    rng = np.random.default_rng(seed)
    grid, faces, points = make_grid(rng, kind)
    assert looks_ready(grid)
    x0, v0, B, W, radius, rest, friction, frozen = bodies(
        rng, n, points, speed, len(grid.cap), small, inside
    )
    allowed = filters if filtered else None
    args = (grid, faces, x0, v0, B, W, dt, radius, friction, rest, frozen, allowed)
    want = numpy_looks(*args)
    got = first_looks(*args)
    for g, w in zip(got, want, strict=True):
        assert g.dtype == w.dtype
        assert np.array_equal(g, w)


def kernels_call(grid, faces, x0, v0, B, W, radius, friction, rest):
    """``looks_loop`` called as ``first_looks`` calls it, at dt = 1/120 s."""
    return looks_loop(
        *grid_args(grid), faces.p, faces.n, faces.two, faces.c, faces.mu, x0, v0, B, W,
        1 / 120, radius, friction, rest, np.zeros(0, bool),
    )  # fmt: skip


def test_the_quick_way_is_taken_and_finds_pairs_and_sleepers() -> None:
    """Slow small balls by the faces, five still on the floor: the kernel's own narrow look
    answers (pairs found) and the five stay put."""
    rng = np.random.default_rng(5)
    grid, faces, points = make_grid(rng, "box")
    x0, v0, B, W, radius, rest, friction, _ = bodies(
        rng, 200, points, 0.5, len(grid.cap), small=True, inside=True
    )
    floor = int(np.flatnonzero((faces.n[:, 0] == 0.0) & (faces.n[:, 1] == 1.0))[0])
    rest[:5], v0[:5], x0[:5, 1] = floor, 0.0, 0.05 + 1e-9
    radius[:5] = 0.05
    B = W = np.tile([0.0, -9.81], (len(x0), 1))
    out = kernels_call(grid, faces, x0, v0, B, W, radius, friction, rest)
    assert out[3]  # the quick way held
    assert len(out[1]) > 0
    assert set(range(5)) <= set(out[7].tolist())
    want = numpy_looks(grid, faces, x0, v0, B, W, 1 / 120, radius, friction, rest, None, None)
    got = (*out[:3], out[7])
    assert all(np.array_equal(g, w) for g, w in zip(got, want, strict=True))


def test_the_comparison_can_fail() -> None:
    """Looks that forget which bodies rest keep fewer rows than the numpy twins do."""
    rng = np.random.default_rng(11)
    grid, faces, points = make_grid(rng, "box")
    x0, v0, B, W, radius, rest, friction, _ = bodies(rng, 60, points, 0.5, len(grid.cap))
    rest[:30] = 0
    v0[:30] += 1.0
    want = numpy_looks(grid, faces, x0, v0, B, W, 1 / 120, radius, friction, rest, None, None)
    free = np.full(len(rest), -1, dtype=np.intp)
    got = first_looks(grid, faces, x0, v0, B, W, 1 / 120, radius, friction, free, None, None)
    assert not np.array_equal(got[0], want[0])


def box_world(n: int, fast: bool) -> World:
    """Balls (not colliding with each other) in a box with segments and a peg."""
    rng = np.random.default_rng(2)
    world = World(integrator="auto", kernels="numpy")
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Box((0.0, 0.0), (20.0, 15.0)))
    for _ in range(10):
        a = rng.uniform((2.0, 2.0), (18.0, 13.0))
        b = a + rng.uniform(-2.0, 2.0, 2)
        world.add_collider(Segment(tuple(a), tuple(b)))
    world.add_collider(Circle((10.0, 5.0), 0.5))
    one = Filter(group=1)
    for p, v in zip(
        rng.uniform((1.0, 1.0), (19.0, 14.0), (n, 2)).tolist(),
        rng.uniform(-8.0, 8.0, (n, 2)).tolist(),
        strict=True,
    ):
        world.add(
            Body(Vector(*p), Vector(*v), Vector(0, 0), radius=0.1, restitution=0.9, filter=one)
        )
    # The path of the static contacts alone (the World's own kernels stay numpy's).
    world._s.contacts.fast = fast  # type: ignore[union-attr]
    return world


@pytest.mark.filterwarnings("ignore")
def test_a_box_of_balls_ends_bit_identical_on_both_paths() -> None:
    fast, slow = box_world(150, True), box_world(150, False)
    events = 0
    for _ in range(240):
        fast.step(1 / 120)
        slow.step(1 / 120)
        a, b = fast._s.contacts.began, slow._s.contacts.began  # type: ignore[union-attr]
        events += len(b)
        assert len(a) == len(b)
        assert all(np.array_equal(np.hstack(e), np.hstack(f)) for e, f in zip(a, b, strict=True))
    assert events > 100
    assert np.array_equal(fast.positions(), slow.positions())
    assert np.array_equal(fast.velocities(), slow.velocities())


def test_a_world_on_the_fast_path_says_so() -> None:
    """Contacts takes the World's path when the World makes them."""
    world = World(kernels="numpy")
    world.add_collider(Box((0.0, 0.0), (1.0, 1.0)))
    assert world._s.contacts.fast is False  # type: ignore[union-attr]
    if kernels.available():
        world = World(kernels="fast")
        world.add_collider(Box((0.0, 0.0), (1.0, 1.0)))
        assert world._s.contacts.fast is True  # type: ignore[union-attr]


def solve_both(
    seed: int,
    n: int,
    kind: str,
    speed: float,
    dt: float,
    resting_share: float,
    spinning: bool = False,
):
    """``solve_few`` on random bodies among random faces, each body against every face,
    without and with the loop kernel ``paths_loop``: (numpy's floats, the kernel's), each
    (changed, x, v, capped, began, ended, resting faces after; and with ``spinning``, some
    bodies turn: their angles and angular velocities after)."""
    rng = np.random.default_rng(seed)
    contacts = Contacts()
    if kind != "open":
        contacts.add(Box((0.0, 0.0), (20.0, 15.0), friction=0.5))
    points = []
    for _ in range(int(rng.integers(1, 6))):
        a = rng.uniform((2.0, 2.0), (18.0, 13.0))
        b = a + rng.uniform(-3.0, 3.0, 2)
        contacts.add(Segment(tuple(a), tuple(b), float(rng.choice([0.0, 0.2])), friction=0.4))
        points += [a, b]
    for _ in range(int(rng.integers(0, 3))):
        c = rng.uniform((2.0, 2.0), (18.0, 13.0))
        contacts.add(Circle(tuple(c), float(rng.uniform(0.2, 1.0)), restitution=0.8))
        points.append(c)
    if kind == "polygons":
        # Solid slabs, thin and thick, some turned (their far faces are behind a ball beside
        # them: engine.geometry.faces.behind_solid), some rounded.
        for _ in range(int(rng.integers(1, 4))):
            c = rng.uniform((2.0, 2.0), (18.0, 13.0))
            size = (float(rng.uniform(1.0, 6.0)), float(rng.choice([0.1, 0.5, 1.5])))
            q = float(rng.uniform(0.0, np.pi))
            u, w = (
                np.array([np.cos(q), np.sin(q)]) * size[0] / 2,
                np.array([-np.sin(q), np.cos(q)]) * size[1] / 2,
            )
            corners = [tuple(c + s * u + t * w) for s, t in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
            contacts.add(Polygon(corners, radius=float(rng.choice([0.0, 0.05])), friction=0.3))
            points.append(c)
    faces = contacts.faces
    F = len(faces.owner)
    x0, v0, B, W, radius, rest, _, _ = bodies(rng, n, np.array(points), speed, F, inside=True)
    rest = np.where(rng.random(n) < resting_share, rest, -1).astype(np.intp)
    contacts.bodies_added(n)
    restitution = rng.choice([0.0, 0.5, 0.9, 1.0], n)
    friction, mass = rng.uniform(0.0, 1.0, n), rng.uniform(0.5, 2.0, n)
    paths = Paths(x0, v0, B, W, dt, 1.5, radius, restitution, friction, mass)
    rows = np.flatnonzero(rng.random(n) < 0.8)
    pb = np.repeat(np.arange(len(rows)), F)
    pf = np.tile(np.arange(F), len(rows))
    keep = rng.random(len(pb)) < 0.9  # some pairs left out
    pb, pf = pb[keep], pf[keep]
    out = []
    for fast in (False, True):
        began: list = []
        ended: list = []
        resting = rest.copy()
        spin = None
        if spinning:
            turns = rng_spin(seed, n)
            spin = Spin.free(*turns, dt)
        changed, X, V, capped = solve_few(
            faces, paths, rows, pb, pf, resting, contacts.push_out_rows, began, ended, fast,
            spin,
        )  # fmt: skip
        spun = () if spin is None else (spin.angle, spin.omega)
        out.append((changed, X, V, capped, began, ended, resting, *spun))
    return out


def rng_spin(seed: int, n: int) -> tuple[np.ndarray, ...]:
    """Random rotation for n bodies (``Spin.free``'s arguments but dt): some do not turn
    (1 / I = 0), some spin, some have a torque."""
    rng = np.random.default_rng(seed + 1)
    inv = np.where(rng.random(n) < 0.7, rng.uniform(0.5, 3.0, n), 0.0)
    omega = np.where(inv > 0.0, rng.normal(0.0, 20.0, n) * rng.integers(0, 2, n), 0.0)
    torque = np.where(inv > 0.0, rng.normal(0.0, 1.0, n) * rng.integers(0, 2, n), 0.0)
    mass = rng.uniform(0.5, 2.0, n)
    radius = rng.uniform(0.1, 0.5, n)
    return rng.uniform(-3.0, 3.0, n), omega, inv, torque, mass, radius


@settings(deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 30),
    kind=st.sampled_from(["box", "open", "polygons"]),
    speed=st.sampled_from([0.5, 5.0, 50.0]),
    dt=st.sampled_from([1 / 120, 1 / 30]),
    resting_share=st.sampled_from([0.0, 0.3]),
    spinning=st.booleans(),
)
@pytest.mark.filterwarnings("ignore")
def test_paths_loop_gives_the_python_floats_results(
    seed: int, n: int, kind: str, speed: float, dt: float, resting_share: float, spinning: bool
) -> None:
    slow, fast = solve_both(seed, n, kind, speed, dt, resting_share, spinning)
    for a, b in zip(slow, fast, strict=True):
        if isinstance(a, np.ndarray):
            assert a.dtype == b.dtype and np.array_equal(a, b)
        else:
            assert a == b


def test_paths_loop_lets_a_ball_leaving_a_faces_end_fly_on_as_the_floats_do() -> None:
    """Balls that touch a slanted segment at its ends (and one a hair inside it), pulled into
    it and moving along it, each at the start of a step: one leaving the face at an end flies
    on (engine.geometry.impact's ``leaves_end_one``: the end's round face holds it, and it goes
    over), in the kernel as in Python's floats; the others meet the face at once. The same
    states, events and resting faces both ways."""
    contacts = Contacts()
    contacts.add(Segment((0.0, 0.0), (8.0, 4.0)))
    faces = contacts.faces
    t = np.array([8.0, 4.0]) / np.hypot(8.0, 4.0)
    n = np.array([-t[1], t[0]])
    r, speed = 0.25, 5.0
    length = float(np.hypot(8.0, 4.0))
    # (place along the segment, direction along it): off the high end, off the low end, back
    # from the high end, a hair inside the high end moving off it.
    cases = [(length, 1.0), (0.0, -1.0), (length, -1.0), (length - 1e-6, 1.0)]
    x0 = np.array([t * s + n * r for s, _ in cases])
    v0 = np.array([t * (speed * d) for _, d in cases])
    m = len(cases)
    B = np.tile([0.0, -9.81], (m, 1))
    one = np.ones(m)
    contacts.bodies_added(m)
    paths = Paths(x0, v0, B, B, 1 / 60, 0.0, r * one, 0.0 * one, 0.0 * one, one)
    F = len(faces.owner)
    pb, pf = np.repeat(np.arange(m), F), np.tile(np.arange(F), m)
    out = []
    for fast in (False, True):
        began: list = []
        ended: list = []
        resting = np.full(m, -1, dtype=np.intp)
        changed, X, V, capped = solve_few(
            faces, paths, np.arange(m), pb, pf, resting, contacts.push_out_rows, began, ended,
            fast,
        )  # fmt: skip
        out.append((changed, X, V, capped, began, ended, resting))
    for a, b in zip(*out, strict=True):
        assert np.array_equal(a, b) if isinstance(a, np.ndarray) else a == b
    changed, X, V, capped, _, _, resting = out[1]
    # The two leaving fly the parabola (they met nothing); the other two met the face: the
    # one moving back along it rests on it, the one a hair inside the end slides off the end
    # and flies on over it (engine.exact.sweep, "A slide's end").
    assert changed.tolist() == [2, 3] and resting.tolist() == [-1, -1, 0, -1], resting
    # The kernel's own branch: the ends' round faces (whose quartic it leaves to Python) left
    # out of the pairs, the two leaving miss the face in the kernel; the others meet it.
    line = pf == 0
    status, *_ = _paths_fast(faces, paths, np.arange(m), pb[line], pf[line], np.full(m, -1))
    assert status.tolist() == [MISSED, MISSED, PYTHON, PYTHON], status


def test_paths_loop_takes_most_bodies_and_the_comparison_can_fail() -> None:
    """Most bouncing bodies are the kernel's own (not left to Python), and its results
    differ from those of a step one ulp longer."""
    rng = np.random.default_rng(4)
    contacts = Contacts()
    contacts.add(Box((0.0, 0.0), (20.0, 15.0)))
    contacts.add(Segment((5.0, 5.0), (15.0, 6.0)))
    faces = contacts.faces
    n = 50
    x0 = rng.uniform((1.0, 1.0), (19.0, 14.0), (n, 2))
    v0 = rng.normal(0.0, 200.0, (n, 2))
    B = np.tile([0.0, -9.81], (n, 1))
    one = np.ones(n)
    F = len(faces.owner)
    pb, pf = np.repeat(np.arange(n), F), np.tile(np.arange(F), n)
    results = []
    for dt in (1 / 60, np.nextafter(1 / 60, 1.0)):
        paths = Paths(x0, v0, B, B, dt, 0.0, 0.1 * one, 0.9 * one, 0.5 * one, one)
        status, X, V, ev, *_ = _paths_fast(faces, paths, np.arange(n), pb, pf, np.full(n, -1))
        results.append((X, V))
    assert (status == MET).sum() > 10 and (status == PYTHON).sum() < 5
    assert len(ev) > 10
    assert not np.array_equal(results[0][0][status == MET], results[1][0][status == MET])
