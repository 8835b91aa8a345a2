"""The contacts' first looks skip only bodies that cannot meet anything.

``engine.geometry.face_looks.near`` compares each body's reach with a lower bound on its distance to
every face (``FaceGrid.gap``: the grid's bounds, which hold the endless faces too), and
``engine.geometry.face_looks.narrow`` takes each body's faces from its cell's list, by the quick way
(``FaceGrid.listed_fast``: endless faces listed as capsules, for bodies in cells clear of
their backs) or the other (endless faces against every body). Here: the bound never exceeds
the true distance, the quick lists hold every face a body can reach, the two ways give the
same steps bit for bit, and fast balls, thin walls and velocities set by hand are caught.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from test_contacts_paths import events, scene

from engine import Body, Box, Circle, Filter, Segment, Vector, World
from engine.forces import Gravity

APART = Filter(group=1)


def true_gaps(world: World, X: np.ndarray) -> np.ndarray:
    """(N, faces) distance of each point from each face, signed for an endless one-sided face
    (negative behind it), less the face's offset."""
    contacts = world._contacts
    assert contacts is not None
    faces = contacts.faces
    L = len(faces.p)
    out = np.empty((len(X), L + len(faces.c)))
    for f in range(L):
        d = X - faces.p[f]
        along = d @ np.array([-faces.n[f, 1], faces.n[f, 0]])
        across = d @ faces.n[f]
        if faces.infinite[f] and not faces.two[f]:
            out[:, f] = across - faces.rho[f]
        else:
            off = np.maximum(np.maximum(faces.lo[f] - along, along - faces.hi[f]), 0.0)
            out[:, f] = np.hypot(across, off) - faces.rho[f]
    for j in range(len(faces.c)):
        out[:, L + j] = np.hypot(*(X - faces.c[j]).T) - faces.r[j]
    return out


@pytest.mark.parametrize("seed", range(3))
def test_the_bound_never_exceeds_the_distance(seed: int) -> None:
    rng = np.random.default_rng(seed)
    world, _ = scene(seed, "auto")
    contacts = world._contacts
    assert contacts is not None
    grid = contacts.grid
    # Inside the room, on its walls, outside it and far away.
    X = np.concatenate(
        [
            rng.uniform(-10.5, 10.5, (3000, 2)),
            rng.uniform(-100.0, 100.0, (500, 2)),
            np.stack([rng.uniform(-10, 10, 200), np.full(200, -10.0)], axis=1),
        ]
    )
    cell = grid.cells(X)
    bound = grid.gap(X, cell)
    truth = true_gaps(world, X).min(axis=1)
    # Inside the grid, the cells' bounds are below the distance outright; outside, the
    # distances from the endless faces are measured as n.x - (n.p + rho), rounding apart from
    # (x - p).n - rho by an ulp or so (the reach they are compared with is widened by TOUCH
    # and 1e-9 of itself).
    inside = ~grid.outside[cell]
    assert inside.sum() > 3000 and (~inside).sum() > 300
    assert np.all(bound[inside] <= truth[inside]), np.max(bound - truth)
    assert np.all(bound <= truth + 1e-13 * (1.0 + np.abs(X).max(axis=1)))


@pytest.mark.parametrize("seed", range(3))
def test_the_quick_lists_hold_every_face_within_reach(seed: int) -> None:
    rng = np.random.default_rng(seed)
    world, _ = scene(seed, "auto")
    contacts = world._contacts
    assert contacts is not None
    grid = contacts.grid
    assert grid.table is not None
    X = rng.uniform(-10.5, 10.5, (4000, 2))
    cell = grid.cells(X)
    X, cell = X[grid.safe[cell]], cell[grid.safe[cell]]
    assert len(X) > 2000  # most of the room is clear of the walls' backs
    # A safe cell is wholly on the free side of every endless face (its capsule stands for
    # it there), even where a point is found in it by rounding.
    faces = contacts.faces
    for f in np.flatnonzero(faces.infinite):
        assert np.all((X - faces.p[f]) @ faces.n[f] >= 0.0)
    edge = np.stack([rng.uniform(-10.0, 10.0, 500), np.full(500, -10.0)], axis=1)
    edge[:, 1] += rng.choice([-1e-15, 0.0, 1e-15], 500)
    assert not grid.safe[grid.cells(edge)].any()  # on the Box's floor: not safe
    reach = rng.uniform(0.0, grid.pad, len(X))
    fb, ff = grid.listed_fast(cell)
    listed = set(zip(fb.tolist(), ff.tolist(), strict=True))
    gaps = true_gaps(world, X)
    for b, f in zip(*np.nonzero(gaps <= reach[:, None]), strict=True):
        assert (int(b), int(f)) in listed, (b, f, gaps[b, f], reach[b])
    # Each body's faces in the other way's order: the endless ones first.
    for b in range(0, len(X), 97):
        mine = ff[fb == b].tolist()
        endless = [f for f in mine if f < len(faces.p) and faces.infinite[f]]
        assert mine[: len(endless)] == endless == sorted(endless)


@pytest.mark.parametrize("method", ["auto", "semi_implicit_euler"])
@pytest.mark.parametrize("seed", range(3))
def test_the_quick_way_and_the_other_give_the_same_steps(seed: int, method: str) -> None:
    quick, other = box_world(100, seed, method=method), box_world(100, seed, method=method)
    assert quick._contacts is not None and other._contacts is not None
    other._contacts.grid.table = None  # the endless faces against every body
    # numpy's two ways (the fast path's kernel, engine.geometry.face_looks.looks_loop, takes the
    # quick one in its own loop: tests/test_kernels_faces.py compares it with these).
    quick._contacts.fast = False
    grid = quick._contacts.grid
    used = [0]
    listed_fast = grid.listed_fast

    def counted(cell: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        used[0] += 1
        return listed_fast(cell)

    grid.listed_fast = counted  # type: ignore[method-assign]
    struck = 0
    for step in range(480):
        quick.step(1.0 / 120.0)
        other.step(1.0 / 120.0)
        assert np.array_equal(quick.positions(), other.positions()), step
        assert np.array_equal(quick.velocities(), other.velocities()), step
        assert events(quick, quick.began) == events(other, other.began), step
        assert events(quick, quick.ended) == events(other, other.ended), step
        struck += len(quick.began)
    assert used[0] > 200 and struck > 200, (used, struck)  # the quick way was taken


def box_world(n: int = 200, seed: int = 0, gravity: bool = True, method: str = "auto") -> World:
    """The benchmark's kind of scene, small: balls of a few sizes and materials in a 40 x 30
    box with thin and thick segments and a few round pegs; they bounce, and some come to rest
    on the floor and on the segments."""
    rng = np.random.default_rng(seed)
    world = World(integrator=method)
    if gravity:
        world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Box((0.0, 0.0), (40.0, 30.0), friction=0.5))
    for k in range(20):
        a = rng.uniform(2.0, 38.0, 2) * [1.0, 0.7]
        b = a + 2.0 * np.array([math.cos(rng.uniform(0.0, np.pi)), 0.5])
        world.add_collider(Segment(tuple(a), tuple(b), 0.0 if k % 2 else 0.2, friction=0.4))
    for _ in range(4):
        world.add_collider(Circle(tuple(rng.uniform(3.0, 27.0, 2)), float(rng.uniform(0.2, 1.0))))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        world.add_all(
            Body(
                Vector(*p),
                Vector(*v),
                Vector(0, 0),
                radius=float(rng.choice([0.05, 0.1, 0.3])),
                restitution=float(rng.choice([0.0, 0.5, 0.9])),
                friction=0.5,
                filter=APART,
            )
            for p, v in zip(
                rng.uniform(1.0, 29.0, (n, 2)).tolist(),
                rng.uniform(-10.0, 10.0, (n, 2)).tolist(),
                strict=True,
            )
        )
    return world


def test_a_fast_ball_from_far_away_bounces_off_a_thin_segment() -> None:
    world = box_world()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # balls it is dropped onto are pushed off it
        seg = world.add_collider(Segment((20.0, 5.0), (20.0, 25.0)))  # thin, upright
    for _ in range(10):
        world.step(1.0 / 120.0)
    # 19 m from the segment, at 3,000 m/s: it gets there within the step.
    ball = world.add(
        Body(Vector(1.0, 15.0), Vector(3000.0, 0.0), Vector(0, 0), radius=0.1, filter=APART)
    )
    hits: list[object] = []
    world.on_contact(ball, begin=lambda e: hits.append(e.collider))
    world.step(1.0 / 120.0)
    assert hits[0] is seg
    for _ in range(3):
        assert ball.pos.x < 20.0 - 0.1 + 1e-9  # never through it
        world.step(1.0 / 120.0)


def test_a_velocity_set_by_hand_is_caught_the_next_step() -> None:
    world = box_world(gravity=False)  # the ball floats, far from everything
    ball = world.add(
        Body(
            Vector(20.0, 15.0),
            Vector(0.0, 0.0),
            Vector(0, 0),
            radius=0.1,
            filter=APART,
            restitution=0.5,
        )  # fmt: skip
    )  # (it bounces, so that each impact shows in its velocity)
    for _ in range(30):
        world.step(1.0 / 120.0)
    assert ball.pos == Vector(20.0, 15.0)
    ball.vel = Vector(0.0, -5000.0)  # 15 m down to the floor within the next step
    world.step(1.0 / 120.0)
    assert ball.vel.y > 0.0 and 0.1 - 1e-9 <= ball.pos.y < 30.0
    # And a position set by hand, right against the wall, heading into it.
    ball.pos = Vector(39.85, 15.0)
    ball.vel = Vector(100.0, 0.0)
    world.step(1.0 / 120.0)
    assert ball.vel.x < 0.0 and ball.pos.x <= 40.0 - 0.1 + 1e-9


def test_a_box_much_larger_than_its_segments() -> None:
    """The grid covers only the segments then (not the box's corners): bodies outside it are
    measured against the walls directly, and both ways still step alike."""

    def world() -> World:
        rng = np.random.default_rng(3)
        w = World(integrator="auto")
        w.add_force(Gravity((0.0, -9.81)))
        w.add_collider(Box((0.0, 0.0), (200.0, 150.0)))
        for _ in range(10):
            a = rng.uniform(5.0, 25.0, 2)
            w.add_collider(Segment(tuple(a), tuple(a + rng.uniform(-2.0, 2.0, 2))))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            w.add_all(
                Body(
                    Vector(*p), Vector(*v), Vector(0, 0), radius=0.2, restitution=0.8, filter=APART
                )
                for p, v in zip(
                    np.concatenate(
                        [rng.uniform(1, 29, (40, 2)), rng.uniform(1, 149, (40, 2))]
                    ).tolist(),
                    rng.uniform(-20.0, 20.0, (80, 2)).tolist(),
                    strict=True,
                )
            )
        return w

    quick, other = world(), world()
    assert quick._contacts is not None and other._contacts is not None
    grid = quick._contacts.grid
    assert not grid.boxed  # the box is far larger than the segments: not covered
    X = np.random.default_rng(4).uniform(-5.0, 205.0, (3000, 2))
    bound = grid.gap(X, grid.cells(X))
    truth = true_gaps(quick, X).min(axis=1)
    assert np.all(bound <= truth + 1e-13 * (1.0 + np.abs(X).max(axis=1)))
    other._contacts.grid.table = None
    for step in range(240):
        quick.step(1.0 / 120.0)
        other.step(1.0 / 120.0)
        assert np.array_equal(quick.positions(), other.positions()), step
        assert np.array_equal(quick.velocities(), other.velocities()), step
    assert np.all((quick.positions() > 0.0) & (quick.positions() < [200.0, 150.0]))
