"""Adding or taking out a collider changes only what it must, and gives the same bits as
building every collider's faces and the grid afresh.

``World.add_collider`` and ``World.remove_collider`` put the collider's faces among the others
(``engine.geometry.faces.faces_added``, ``faces_removed``) and into the grid (``FaceGrid.added``,
``removed``) in place, in a few array operations, where they were once all compiled and the
grid laid again (235 plain steps for a peg on a board of 48). Here: the arrays and the grid
agree with a fresh build after every change, a World changed between steps moves exactly as one
whose faces and grid are rebuilt after each change, and a World changed before its bodies come
moves exactly as one built with the final colliders from the start.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from test_contacts_paths import scene

from engine import Body, Box, Circle, Filter, Plane, Polygon, Segment, Vector, World
from engine.exact.contacts import Contacts
from engine.forces import Gravity
from engine.geometry.colliders import Collider
from engine.geometry.face_grid import FaceGrid
from engine.geometry.faces import Faces, compile_faces

FIELDS = ("p", "n", "rho", "two", "lo", "hi", "c", "r", "owner", "e", "mu", "infinite")
LISTS = ("line_list", "disc_list", "e_list", "mu_list", "owner_list")


def events(world: World, evs: list[Any]) -> list[tuple[Any, ...]]:
    """Each event as (body's place, what it met, point, normal, impulse, time, removal); what
    it met by its repr (a collider taken out is named too)."""
    bodies = world.bodies

    def name(thing: Any) -> Any:
        place = [k for k, b in enumerate(bodies) if b is thing]
        return ("body", place[0]) if place else repr(thing)

    return [
        (name(e.body), name(e.collider), *e.point, *e.normal, *e.impulse, e.time, e.removal)
        for e in evs
    ]


def fresh_faces(contacts: Contacts) -> Faces:
    cols = contacts.colliders
    return compile_faces(cols, [k for k, c in enumerate(cols) if not c.sensor])


def assert_same_faces(got: Faces, want: Faces) -> None:
    for name in FIELDS:
        a, b = getattr(got, name), getattr(want, name)
        assert a.dtype == b.dtype and a.shape == b.shape, name
        assert np.array_equal(a, b), name
    for name in LISTS:
        assert getattr(got, name) == getattr(want, name), name
    assert got.boxed == want.boxed
    assert (got.filters is None) == (want.filters is None)
    if got.filters is not None and want.filters is not None:
        for a, b in zip(got.filters, want.filters, strict=True):
            assert np.array_equal(a, b)
    assert len(got.polygons) == len(want.polygons)
    for a, b in zip(got.polygons, want.polygons, strict=True):
        assert np.array_equal(a, b)


def lists(grid: FaceGrid, table: np.ndarray | None) -> np.ndarray | None:
    """Each cell's list as face indices, -1 past its end, as wide as the longest."""
    if table is None:
        return None
    faces = np.where(table >= 0, grid._slot_face[np.maximum(table, 0)], -1)
    width = max(int((faces >= 0).sum(axis=1).max()), 1)
    assert not (faces[:, width:] >= 0).any()
    return faces[:, :width]


def assert_same_grid(got: FaceGrid, want: FaceGrid) -> None:
    assert got.n_finite == want.n_finite and np.array_equal(got.finite, want.finite)
    assert np.array_equal(got.inf_ids, want.inf_ids)
    if not want.n_finite:
        return
    assert got.shape == want.shape and got.h == want.h and np.array_equal(got.lo, want.lo)
    assert got.pad == want.pad and got.far == want.far and got.margin == want.margin
    assert np.array_equal(got.bound, want.bound)
    assert np.array_equal(got._ring, want._ring)
    assert np.array_equal(got._gap_ring, want._gap_ring)
    assert np.array_equal(got.safe, want.safe)
    assert np.array_equal(got.cap, want.cap, equal_nan=True)
    for name in ("table", "fin_table"):
        a, b = lists(got, getattr(got, name)), lists(want, getattr(want, name))
        assert (a is None) == (b is None), name
        if a is not None and b is not None:
            assert np.array_equal(a, b), name
    # Pairs from the lists the other way too (``listed`` reads ``fin_table``).
    rng = np.random.default_rng(0)
    X = rng.uniform(want.lo, want.lo + np.array(want.shape) * want.h, (500, 2))
    reach = rng.uniform(0.0, 2.0 * want.pad, 500)
    for a, b in zip(got.pairs(X, reach), want.pairs(X, reach), strict=True):
        assert np.array_equal(a, b)


def check(world: World) -> None:
    """The World's faces and grid are what a fresh build of its colliders gives."""
    contacts = world._contacts
    assert contacts is not None
    want = fresh_faces(contacts)
    assert_same_faces(contacts.faces, want)
    if contacts._grid is not None:
        assert_same_grid(contacts._grid, FaceGrid(want))


def rebuilt(world: World) -> None:
    """Throw away the World's faces and grid and build them afresh (the old way)."""
    contacts = world._contacts
    assert contacts is not None
    contacts._faces = fresh_faces(contacts)
    contacts._grid = None


#: The changes made between steps, in turn: each takes the World and what it added so far.
def _changes() -> list[Callable[[World, list[Collider]], None]]:
    def add(make: Callable[[], Collider]) -> Callable[[World, list[Collider]], None]:
        def go(w: World, added: list[Collider]) -> None:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # a ball it lands on is pushed off
                added.append(w.add_collider(make()))

        return go

    def remove_added(k: int) -> Callable[[World, list[Collider]], None]:
        def go(w: World, added: list[Collider]) -> None:
            w.remove_collider(added.pop(k))

        return go

    def remove_own(k: int) -> Callable[[World, list[Collider]], None]:
        def go(w: World, added: list[Collider]) -> None:
            own = [c for c in w.colliders if not any(c is a for a in added)]
            w.remove_collider(own[k])

        return go

    return [
        add(lambda: Circle((1.0, -6.0), 0.3)),  # a peg: its round face goes last
        add(lambda: Segment((-3.0, 3.0), (0.0, 4.0))),  # flat faces before every round one
        add(lambda: Segment((3.0, -7.0), (6.0, -6.0), 0.1, restitution=0.5)),
        add(lambda: Polygon([(-1.0, -8.0), (1.0, -8.0), (0.0, -7.0)], friction=0.2)),
        add(lambda: Circle((5.0, 5.0), 0.5, sensor=True)),
        remove_own(3),  # a segment of the scene's: the faces after it move down
        add(lambda: Circle((-6.0, 6.0), 0.4, filter=Filter(group=1))),  # the balls' own group
        remove_added(1),
        remove_own(9),  # a peg of the scene's
        add(lambda: Segment((-9.0, -9.5), (9.0, -9.5))),  # along the room's floor
        remove_added(3),  # the sensor
        remove_added(0),
        add(lambda: Polygon([(6.0, 6.0), (8.0, 6.0), (8.0, 8.0), (6.0, 8.0)], 0.05)),
        remove_added(2),  # the filtered peg: no filter left
        add(lambda: Circle((30.0, 0.0), 0.5)),  # outside the grid: laid afresh
        remove_added(-1),  # and back
        add(lambda: Plane((0.0, -9.0), (0.0, 1.0))),  # an endless face: laid afresh
        remove_own(1),  # the scene's slanted plane
        remove_added(-1),
        remove_added(0),  # the first segment: the faces after it move down
    ]


@pytest.mark.parametrize("method", ["auto", "semi_implicit_euler"])
@pytest.mark.parametrize("seed", range(2))
def test_a_world_changed_between_steps_moves_as_one_rebuilt(seed: int, method: str) -> None:
    changed, _ = scene(seed, method)
    again, _ = scene(seed, method)
    changes = _changes()
    added: dict[int, list[Collider]] = {id(changed): [], id(again): []}
    struck = 0
    for step in range(40 * len(changes) + 60):
        if step >= 20 and step % 40 == 20 and (step - 20) // 40 < len(changes):
            change = changes[(step - 20) // 40]
            for w in (changed, again):
                change(w, added[id(w)])
            rebuilt(again)
            check(changed)
            assert changed._contacts is not None and again._contacts is not None
            assert np.array_equal(changed._contacts.rest, again._contacts.rest), step
        changed.step(1.0 / 60.0)
        again.step(1.0 / 60.0)
        assert np.array_equal(changed.positions(), again.positions()), step
        assert np.array_equal(changed.velocities(), again.velocities()), step
        assert events(changed, changed.began) == events(again, again.began), step
        assert events(changed, changed.ended) == events(again, again.ended), step
        assert changed._contacts is not None and again._contacts is not None
        assert np.array_equal(changed._contacts.rest, again._contacts.rest), step
        struck += len(changed.began)
    assert struck > 100


def _board(colliders: list[Collider]) -> World:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -9.81)))
    for c in colliders:
        w.add_collider(c)
    return w


def _pegs(n: int) -> list[Collider]:
    return [
        Circle((1.2 * (i % 9) + 0.6 * ((i // 9) % 2), 2.0 + 1.2 * (i // 9)), 0.15) for i in range(n)
    ]


def _walls() -> list[Collider]:
    return [
        Segment((-1.0, 0.0), (12.0, 0.0)),
        Segment((-1.0, 0.0), (-1.0, 14.0)),
        Segment((12.0, 0.0), (12.0, 14.0)),
    ]


def _drop(w: World, n: int, seed: int) -> list[Body]:
    rng = np.random.default_rng(seed)
    return [
        w.add(
            Body(
                Vector(float(rng.uniform(0.0, 11.0)), float(rng.uniform(9.0, 13.0))),
                Vector(float(rng.uniform(-2.0, 2.0)), 0.0),
                radius=0.25,
                restitution=0.7,
            )
        )
        for _ in range(n)
    ]


def _run(w: World, steps: int) -> list[Any]:
    out = []
    for _ in range(steps):
        w.step(1.0 / 60.0)
        out.append((w.positions().copy(), w.velocities().copy(), events(w, w.began)))
    return out


def test_a_board_changed_before_its_balls_moves_as_one_built_with_its_final_pegs() -> None:
    pegs, walls = _pegs(40), _walls()
    extra = [Circle((3.3, 6.1), 0.1), Segment((2.0, 1.0), (4.0, 1.5)), Circle((7.1, 3.0), 0.12)]
    changed = _board(pegs + walls)
    probe = _drop(changed, 1, 99)[0]
    for _ in range(30):
        changed.step(1.0 / 60.0)  # the grid is built
    changed.add_collider(extra[0])
    changed.step(1.0 / 60.0)
    changed.remove_collider(pegs[7])
    changed.add_collider(extra[1])
    changed.step(1.0 / 60.0)
    changed.remove_collider(pegs[20])
    changed.add_collider(extra[2])
    changed.remove_collider(extra[0])
    changed.remove(probe)
    check(changed)
    assert changed._contacts is not None and changed._contacts._grid is not None
    final = [c for c in pegs + walls if c is not pegs[7] and c is not pegs[20]]
    final += [extra[1], extra[2]]
    assert list(changed.colliders) == final
    fresh = _board(final)
    probe = _drop(fresh, 1, 99)[0]
    for _ in range(32):
        fresh.step(1.0 / 60.0)
    fresh.remove(probe)
    assert changed.t == fresh.t
    _drop(changed, 30, 1)
    _drop(fresh, 30, 1)
    a, b = _run(changed, 240), _run(fresh, 240)
    for k, (x, y) in enumerate(zip(a, b, strict=True)):
        assert np.array_equal(x[0], y[0]) and np.array_equal(x[1], y[1]), k
        assert x[2] == y[2], k
    assert sum(len(x[2]) for x in a) > 50


def test_a_ball_resting_on_a_peg_stays_on_it_when_faces_move() -> None:
    w = _board([Circle((0.0, 0.0), 0.5), Segment((-5.0, -2.0), (5.0, -2.0))])
    ball = w.add(Body(Vector(0.0, 0.75), radius=0.25, restitution=0.0))
    for _ in range(30):
        w.step(1.0 / 60.0)
    assert w.resting(ball) is w.colliders[0]
    w.add_collider(Segment((3.0, 1.0), (4.0, 1.0)))  # flat faces go before the peg's
    w.add_collider(Circle((-3.0, 1.0), 0.2))
    check(w)
    assert w.resting(ball) is w.colliders[0]
    w.remove_collider(w.colliders[1])  # the floor: the peg's face moves down
    check(w)
    assert w.resting(ball) is w.colliders[0]
    w.step(1.0 / 60.0)
    assert w.resting(ball) is w.colliders[0] and ball.pos == Vector(0.0, 0.75)
    w.remove_collider(w.colliders[0])  # the peg it rests on: it falls
    assert w.resting(ball) is None
    check(w)


def test_a_new_peg_pushes_out_the_ball_it_lands_on_as_before() -> None:
    w = _board(_pegs(20) + _walls())
    ball = w.add(Body(Vector(5.0, 0.25), radius=0.25))
    far = w.add(Body(Vector(9.0, 8.0), radius=0.25))
    w.step(1.0 / 60.0)
    with pytest.warns(Warning, match="pushed out"):
        w.add_collider(Circle((5.1, 0.3), 0.1))
    assert abs(ball.pos - Vector(5.1, 0.3)) >= 0.35 - 1e-9
    assert far.pos.y < 8.0
    # A body added inside a peg is pushed out too, and one added near nothing is not.
    with pytest.warns(Warning, match="pushed out"):
        inside = w.add(Body(Vector(0.6, 3.2), radius=0.25))
    assert abs(inside.pos - Vector(0.6 + 0.6, 3.2)) >= 0.4 - 1e-9 or inside.pos != Vector(0.6, 3.2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        w.add(Body(Vector(6.0, 11.0), radius=0.25))
    check(w)


def test_many_changes_keep_the_grid_as_built_afresh() -> None:
    w = _board(_pegs(60) + _walls())
    _drop(w, 3, 5)
    w.step(1.0 / 60.0)
    assert w._contacts is not None and w._contacts._grid is not None
    grid = w._contacts._grid
    rng = np.random.default_rng(3)
    for k in range(150):
        cols = [c for c in w.colliders if isinstance(c, Circle)]
        if k % 3 == 2 and cols:
            w.remove_collider(cols[int(rng.integers(len(cols)))])
        else:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                w.add_collider(
                    Circle(tuple(rng.uniform(1.0, 9.0, 2)), float(rng.uniform(0.05, 0.15)))
                )
        if k % 10 == 0:
            check(w)
        w.step(1.0 / 60.0)
    check(w)
    assert w._contacts._grid is grid  # kept, not laid afresh


def test_a_box_room_takes_pegs_in_place() -> None:
    w = _board([Box((-1.0, -1.0), (11.5, 14.0)), *_pegs(20)])
    _drop(w, 2, 7)
    w.step(1.0 / 60.0)
    assert w._contacts is not None
    grid = w._contacts._grid
    w.add_collider(Segment((2.0, 2.5), (5.0, 2.7), 0.05))
    w.add_collider(Circle((8.0, 3.0), 0.1))
    check(w)
    w.remove_collider(w.colliders[3])
    check(w)
    assert w._contacts._grid is grid


def test_a_board_emptied_peg_by_peg_keeps_its_grid_and_its_steps() -> None:
    pegs = _pegs(150)
    changed, again = _board(pegs + _walls()), _board([*_pegs(150), *_walls()])
    for w in (changed, again):
        _drop(w, 20, 4)
        w.step(1.0 / 60.0)
    assert changed._contacts is not None and again._contacts is not None
    grid = changed._contacts._grid
    order = np.random.default_rng(8).permutation(150)[:130].tolist()
    for k, j in enumerate(order):
        for w in (changed, again):
            w.remove_collider(
                w.colliders[[c.center for c in w.colliders[:-3]].index(pegs[j].center)]
            )  # type: ignore[attr-defined]
        rebuilt(again)
        if k % 20 == 0:
            check(changed)
        changed.step(1.0 / 60.0)
        again.step(1.0 / 60.0)
        assert np.array_equal(changed.positions(), again.positions()), k
        assert np.array_equal(changed.velocities(), again.velocities()), k
        assert events(changed, changed.began) == events(again, again.began), k
    check(changed)
    # Kept, with its slots renumbered once more were let go than kept.
    assert changed._contacts._grid is grid and len(grid._slot_face) < 150 + 9
