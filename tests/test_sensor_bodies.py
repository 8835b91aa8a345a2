"""Sensor bodies (engine.pipeline.body_sensors): a Body made with ``sensor=True`` pushes nothing and
is pushed by nothing, and the World reports what it overlaps at the end of each step, by its
shape, as a sensor collider's overlaps are reported: a player's feet sensor, on both paths."""

from __future__ import annotations

import pytest
from paths import PATHS

from engine import Body, ContactEvent, Filter, Plane, Polygon, Segment, Vector, World
from engine.forces import Gravity

G = 9.81
DT = 1 / 60


def platform_world(
    kernels: str, feet: bool, solver: str = "auto"
) -> tuple[World, Body, Body | None, list[str]]:
    """A player box (0.8 x 1.6) dropped from 2 m onto a ground segment, with a kinematic
    feet sensor (0.6 x 0.2, in the player's group: it does not sense the player) or not;
    the log of what the feet began and ended touching, on ``solver``."""
    w = World(kernels=kernels, solver=solver)
    w.add_force(Gravity((0, -G)))
    w.add_collider(Segment((-10, 0), (10, 0), restitution=0.0))
    mine = Filter(group=1)
    player = w.add(
        Body(
            Vector(0, 2),
            shape=Polygon.box(0.8, 1.6),
            mass=70,
            restitution=0.0,
            fixed_rotation=True,
            filter=mine,
        )
    )
    log: list[str] = []
    sensor = None
    if feet:
        sensor = w.add(
            Body(
                Vector(0, 1.2),
                shape=Polygon.box(0.6, 0.2),
                kinematic=True,
                sensor=True,
                filter=mine,
            )
        )
        w.on_contact(
            sensor,
            begin=lambda e: log.append(f"begin {type(e.collider).__name__}"),
            end=lambda e: log.append(f"end {type(e.collider).__name__}"),
        )
    return w, player, sensor, log


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("solver", ["exact", "soft"])
def test_a_feet_sensor_says_when_the_player_stands_and_changes_nothing(
    kernels: str, solver: str
) -> None:
    # (On the soft step the game's writes to the kinematic sensor's position woke the sleeping
    # player beside it each step, so it rested a few 1e-19 m/s from still, and the two runs
    # parted at the 19th digit: a sensor, whose filter meets nothing, now wakes nothing.)
    paths = []
    for feet in (True, False):
        w, player, sensor, log = platform_world(kernels, feet, solver)
        standing = []
        for k in range(150):
            if k == 100:
                player.vel = Vector(0, 5)  # a jump
            if sensor is not None:
                sensor.pos = player.pos - Vector(0, 0.8)  # where its feet are
            w.step(DT)
            standing.append(len(log) % 2 == 1)
            paths.append((feet, player.pos, player.vel))
        if feet:
            # It lands (its feet within 0.1 m of the ground: the sensor's half height), then
            # leaves the ground the step after the jump (the kinematic sensor follows a step
            # behind); the player itself is in its group, never sensed.
            assert log == ["begin Segment", "end Segment"]
            landed = standing.index(True)
            assert 0 < landed < 100 and all(standing[landed:101]) and not any(standing[102:])
    with_feet = [(p, v) for f, p, v in paths if f]
    without = [(p, v) for f, p, v in paths if not f]
    assert with_feet == without  # the sensor pushed nothing, bit for bit


@pytest.mark.parametrize("kernels", PATHS)
def test_a_sensor_ball_falls_through_a_floor_and_a_ball_reporting_each_overlap(
    kernels: str,
) -> None:
    # A sensor ball (r 0.25) falls from y = 1 through a floor, past a solid ball (r 0.25)
    # resting below it: it moves as in free fall (a twin World with nothing else), and the
    # events open exactly for the steps it ends overlapping each: the floor while
    # |y| < 0.25, the ball at (0, -1) while |y + 1| < 0.5.
    w = World(kernels=kernels)
    w.add_force(Gravity((0, -G)))
    w.add_collider(Plane((0, -1.25), (0, 1), restitution=0.0))  # holds the solid ball
    floor = w.add_collider(Segment((-1, 0), (1, 0)))
    other = w.add(Body(Vector(0, -1), radius=0.25, restitution=0.0, collision_type=3))
    ghost = w.add(Body(Vector(0, 1), radius=0.25, sensor=True, collision_type=4))
    free = World(kernels=kernels)
    free.add_force(Gravity((0, -G)))
    twin = free.add(Body(Vector(0, 1), radius=0.25))
    seen: dict[object, list[bool]] = {floor: [], other: []}
    open_now: set[int] = set()
    began: list[ContactEvent] = []
    w.on_collision(4, 3, begin=began.append)  # a sensor body takes collision types too
    w.on_contact(ghost, begin=lambda e: open_now.add(id(e.collider)))
    w.on_contact(ghost, end=lambda e: open_now.discard(id(e.collider)))
    ys = []
    for _ in range(40):
        w.step(DT)
        free.step(DT)
        assert ghost.pos == twin.pos and ghost.vel == twin.vel
        ys.append(ghost.pos.y)
        for thing in seen:
            seen[thing].append(id(thing) in open_now)
    assert seen[floor] == [abs(y) < 0.25 for y in ys]
    assert seen[other] == [abs(y + 1) < 0.5 for y in ys]
    assert any(seen[other]) and other.pos.y == pytest.approx(-1.0, abs=1e-9)
    assert len(began) == 1 and began[0].body is ghost and began[0].collider is other


def test_a_sensor_made_solid_lands_and_its_flag_is_checked() -> None:
    w = World()
    w.add_force(Gravity((0, -G)))
    w.add_collider(Plane((0, 0), (0, 1), restitution=0.0))
    ball = w.add(Body(Vector(0, 1), radius=0.25, restitution=0.0, sensor=True))
    for _ in range(60):
        w.step(DT)
    assert ball.pos.y < -1  # it fell through
    ball.pos, ball.vel = Vector(0, 1), Vector(0, 0)
    ball.sensor = False
    for _ in range(60):
        w.step(DT)
    assert ball.pos.y == pytest.approx(0.25, abs=1e-9)  # it rests on the floor
    with pytest.raises(TypeError, match="sensor must be True"):
        ball.sensor = 1  # type: ignore[assignment]


@pytest.mark.parametrize("solver", ["soft", "exact"])
@pytest.mark.parametrize("kernels", PATHS)
def test_a_trapdoor_made_a_sensor_in_play_drops_the_crate_asleep_on_it(
    kernels: str, solver: str
) -> None:
    """A kinematic trapdoor made a sensor after a crate came to rest on it (asleep, on the soft
    step) wakes the crate (its filter changed what it meets: the bodies touching it wake),
    which falls through, onto the floor below; the door reports the solid contact's end and
    the overlap's begin the step it is made one, and the overlap's end once the crate has
    left it."""
    w = World(kernels=kernels, solver=solver)
    w.add_force(Gravity((0, -G)))
    w.add_collider(Segment((-10, -3), (10, -3), restitution=0.0))
    door = w.add(Body(Vector(0, 0), shape=Polygon.box(2.0, 0.2), kinematic=True))
    crate = w.add(Body(Vector(0, 0.6), shape=Polygon.box(1.0, 1.0), mass=2, restitution=0.0))
    log: list[str] = []
    w.on_contact(door, begin=lambda e: log.append("begin"), end=lambda e: log.append("end"))
    for _ in range(60):
        w.step(DT)
    # (On the exact solver a body resting on a kinematic one stays awake: the door may move.)
    assert w.is_sleeping(crate) == (solver == "soft")
    assert abs(crate.pos.y - 0.6) < 0.01 and log == ["begin"]  # on the door (top at 0.1 m)
    door.sensor = True
    w.step(DT)
    assert sorted(log) == ["begin", "begin", "end"]  # the contact ends, the overlap begins
    for _ in range(60):
        w.step(DT)
    assert crate.pos.y < -2.0  # fell through, onto the floor (its centre 0.5 m above it)
    assert log.count("end") == 2  # and left the door
