"""Colliders taken out of a game's World (the soft step, engine.pipeline.game_step): the rest
of the scene goes on as if the collider had never been there, and the last step's events still
read as that step left them; on both paths.

A game takes colliders out in play (a coin collected, a door opened). The soft step keeps its
static shapes' tables then and gives the gone collider's shapes an empty box
(``game_step._without``), so every other contact keeps its warm start by key and nothing is
made again but the colliders' arrays; past half the shapes gone, the tables are made afresh.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from engine import Body, Circle, Polygon, Segment, World
from engine.forces import Gravity
from tests.paths import PATHS

DT = 1.0 / 60.0


def ledges(kernels: str, count: int) -> tuple[World, list[Segment], list[Body], Circle]:
    """A game's scene: a coin (a sensor circle, the World's first collider, high up where
    nothing reaches it), then ``count`` ledges 2 m apart, a unit box resting on each."""
    w = World(integrator="auto", kernels=kernels, solver="soft")
    w.add_force(Gravity((0.0, -9.81)))
    coin = w.add_collider(Circle((0.0, 20.0), 0.3, sensor=True))
    made, boxes = [], []
    for k in range(count):
        x = 2.0 * k
        made.append(w.add_collider(Segment((x - 0.8, 0.0), (x + 0.8, 0.0))))
        boxes.append(w.add(Body((x, 0.5), shape=Polygon.box(1.0, 1.0), mass=1.0, friction=0.6)))
    return w, made, boxes, coin


def state(w: World) -> np.ndarray:
    """Every body's position, velocity, angle and angular velocity, side by side."""
    b = w.bodies
    return np.array([(*x.pos, *x.vel, x.angle, x.angular_velocity) for x in b])


@pytest.mark.parametrize("kernels", PATHS)
def test_taking_a_coin_out_changes_nothing_else_to_the_bit(kernels: str) -> None:
    # The coin is the first collider: made again, the tables would put every ledge one place
    # down, and each box's contact would start its next step cold (a new key): the boxes
    # settle by another path. Kept, nothing but the coin changes.
    taken, _, _, coin = ledges(kernels, 3)
    kept = ledges(kernels, 3)[0]
    for _ in range(20):  # (the boxes still settling: their impulses are still changing)
        taken.step(DT)
        kept.step(DT)
    assert np.array_equal(state(taken), state(kept))
    taken.remove_collider(coin)
    for _ in range(40):
        taken.step(DT)
        kept.step(DT)
    assert np.array_equal(state(taken), state(kept))


@pytest.mark.parametrize("kernels", PATHS)
def test_a_box_falls_where_its_ledge_is_taken_and_only_there(kernels: str) -> None:
    # Six ledges taken one by one, the last from the front: the first three keep the tables
    # (their shapes' boxes emptied), the fourth makes them afresh (half gone), and so on.
    w, made, boxes, _ = ledges(kernels, 6)
    for _ in range(30):
        w.step(DT)
    for k in (2, 5, 0, 3, 1, 4):
        w.remove_collider(made[k])
        for _ in range(30):
            w.step(DT)
        for j, box in enumerate(boxes):
            gone = made[j] not in w.colliders
            if gone:
                assert box.pos.y < -0.5, (k, j, box.pos)  # fell (0.5 s of free fall: 1.23 m)
            else:
                assert abs(box.pos.y - 0.5) < 1e-3, (k, j, box.pos)  # still on its ledge
    # A ledge put back after the last is taken (the tables made afresh): a box lands on it.
    w.add_collider(Segment((-2.0, -30.0), (2.0, -30.0)))
    for _ in range(180):
        w.step(DT)
    assert abs(boxes[0].pos.y - (-29.5)) < 1e-2


def seen(world: World, made: list[Segment]) -> list[tuple[int, int, tuple[float, ...]]]:
    """The open contacts: each box's and ledge's number, the point and the impulse (N s)."""
    return sorted(
        (world.bodies.index(e.body), made.index(e.collider), (*e.point, *e.impulse))
        for e in world.touching
    )


@pytest.mark.parametrize("kernels", PATHS)
def test_the_last_steps_events_read_as_it_left_them_after_a_collider_goes(kernels: str) -> None:
    # The events of a step are made when read. Taking a collider out before they are read
    # leaves them as the step left them: the contact on it open, and named.
    w, made, boxes, _ = ledges(kernels, 2)
    twin, twin_made, _, _ = ledges(kernels, 2)
    for _ in range(10):
        w.step(DT)
        twin.step(DT)
    w.remove_collider(made[0])
    assert seen(w, made) == seen(twin, twin_made)
    assert len(seen(w, made)) == 2  # one a box (a contact is reported once, at its first point)
    w.step(DT)
    assert [(e.collider, e.body, e.removal) for e in w.ended] == [(made[0], boxes[0], True)]
    assert {e.collider for e in w.touching} == {made[1]}


def asleep(kernels: str) -> tuple[World, list[Segment], list[Body], Circle]:
    """``ledges``' scene of three, stepped until every box sleeps."""
    w, made, boxes, coin = ledges(kernels, 3)
    for _ in range(90):
        w.step(DT)
    assert w.sleeping == 3
    return w, made, boxes, coin


def changed(w: World, change: Callable[[Any], object], collider: object) -> None:
    """``change`` (the World's add or remove) made with ``collider``, then a step."""
    change(collider)
    w.step(DT)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_collider_taken_wakes_what_touched_it_and_nothing_else(kernels: str) -> None:
    # Box2D and pymunk wake the bodies a removed shape touched, alone: a coin taken wakes no
    # pile, a ledge taken wakes the box on it (which falls).
    w, made, boxes, coin = asleep(kernels)
    changed(w, w.remove_collider, coin)
    assert w.sleeping == 3
    changed(w, w.remove_collider, made[1])
    assert [w.is_sleeping(b) for b in boxes] == [True, False, True]
    assert boxes[1].vel.y < 0.0


@pytest.mark.parametrize("kernels", PATHS)
def test_a_collider_added_in_play_wakes_what_it_may_touch_and_nothing_else(kernels: str) -> None:
    w, _, boxes, _ = asleep(kernels)
    changed(w, w.add_collider, Segment((20.0, 5.0), (22.0, 5.0)))  # far off: no box wakes
    assert w.sleeping == 3
    changed(w, w.add_collider, Segment((1.5, 1.0), (2.5, 1.0)))  # on the middle box's top
    assert [w.is_sleeping(b) for b in boxes] == [True, False, True]


def bodies_scene(kernels: str) -> tuple[World, list[Body], Segment]:
    """Two balls side by side on a floor, touching, and a box dropped beside them, landing
    in step 15."""
    w = World(integrator="auto", kernels=kernels, solver="soft")
    w.add_force(Gravity((0.0, -9.81)))
    floor = w.add_collider(Segment((-10.0, 0.0), (10.0, 0.0)))
    made = [
        w.add(Body((0.0, 0.5), mass=1.0, radius=0.5)),
        w.add(Body((1.0, 0.5), mass=1.0, radius=0.5)),
        w.add(Body((3.0, 0.8), shape=Polygon.box(1.0, 1.0), mass=1.0)),
    ]
    return w, made, floor


def described(w: World, made: list[Body], floor: Segment, events: list[Any]) -> list[Any]:
    def name(x: Any) -> str:
        return "floor" if x is floor else f"body {made.index(x)}"

    return sorted(
        (name(e.body), name(e.collider), *e.point, *e.normal, *e.impulse, e.time, e.removal)
        for e in events
    )


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("gone", [0, 2])
def test_the_last_steps_events_read_as_it_left_them_after_a_body_goes(
    kernels: str, gone: int
) -> None:
    # Taken out before the step's events are read, a body is still named in them, where it
    # was: the same begins, ends and open contacts as read before it went.
    w, made, floor = bodies_scene(kernels)
    twin, twin_made, twin_floor = bodies_scene(kernels)
    for _ in range(15):
        w.step(DT)
        twin.step(DT)
    read = [described(twin, twin_made, twin_floor, e) for e in (twin.began, twin.touching)]
    twin.remove(twin_made[gone])
    w.remove(made[gone])
    assert [described(w, made, floor, e) for e in (w.began, w.touching)] == read
    assert any(made[gone] in (e.body, e.collider) for e in w.touching)
    assert any(e.body is made[2] for e in w.began)  # the box's landing, in this step
    w.step(DT)
    twin.step(DT)
    assert described(w, made, floor, w.ended) == described(twin, twin_made, twin_floor, twin.ended)
    assert all(e.removal for e in w.ended if made[gone] in (e.body, e.collider))
