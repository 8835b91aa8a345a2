"""World.remove_force: a force taken out acts on nothing from the next step, and every body
wakes (pymunk's ``space.gravity = ...`` wakes the sleeping bodies too): gravity turned round in
play lifts a crate asleep on the floor, on both solvers and both paths."""

from __future__ import annotations

import pytest
from paths import PATHS

from engine import Body, Polygon, Segment, Vector, World
from engine.forces import Drag, Gravity

G = 9.81
DT = 1 / 60


@pytest.mark.parametrize("solver", ["soft", "exact"])
@pytest.mark.parametrize("kernels", PATHS)
def test_gravity_turned_round_in_play_lifts_the_crate_asleep_on_the_floor(
    kernels: str, solver: str
) -> None:
    w = World(kernels=kernels, solver=solver)
    down = w.add_force(Gravity((0, -G)))
    w.add_collider(Segment((-10, 0), (10, 0), restitution=0.0))
    crate = w.add(Body(Vector(0, 0.5), shape=Polygon.box(1.0, 1.0), mass=2, restitution=0.0))
    for _ in range(120):
        w.step(DT)
    assert abs(crate.pos.y - 0.5) < 0.01
    assert w.is_sleeping(crate)
    w.remove_force(down)
    assert w.forces == ()
    up = w.add_force(Gravity((0, G)))
    y0 = crate.pos.y
    for _ in range(60):
        w.step(DT)
    # Free flight up from rest for 1 s: g t^2 / 2 = 4.905 m, to the semi-implicit Euler
    # step's bias of g t dt / 2 (the soft step's substeps take a quarter of it).
    risen = crate.pos.y - y0
    assert risen == pytest.approx(0.5 * G, abs=0.5 * G * DT)
    assert w.forces == (up,)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_force_removed_acts_on_nothing_and_the_others_stay(kernels: str) -> None:
    """Drag removed, gravity kept: the ball then falls as in a World that never had drag."""
    worlds = []
    for with_drag in (True, False):
        w = World(kernels=kernels)
        w.add_force(Gravity((0, -G)))
        drag = w.add_force(Drag(0.5)) if with_drag else None
        ball = w.add(Body(Vector(0, 100), mass=1, radius=0.1))
        worlds.append((w, ball, drag))
    (wd, bd, drag), (w0, b0, _) = worlds
    assert drag is not None
    wd.remove_force(drag)
    for _ in range(60):
        wd.step(DT)
        w0.step(DT)
    assert (bd.pos, bd.vel) == (b0.pos, b0.vel)


def test_a_force_not_in_the_world_is_refused_naming_what_is() -> None:
    w = World()
    g = w.add_force(Gravity((0, -G)))
    other = Gravity((0, -1.0))
    with pytest.raises(
        ValueError,
        match=r"Gravity\(.*\) is not a force of this World \(it "
        r"holds Gravity\(.*\)\): give the object world.add_force returned",
    ):
        w.remove_force(other)
    assert w.forces == (g,)  # nothing lost
    w.remove_force(g)
    with pytest.raises(ValueError, match=r"it holds none"):
        w.remove_force(g)
