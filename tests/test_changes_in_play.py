"""Changes a game makes in the middle of play while bodies sleep (World.sleep_time, 0.5 s by
default): each scene lets a crate or a stack come to rest (asleep on the soft step), makes the
change, steps, and checks what must then happen against a closed form or an obvious bound, on
both solvers and both paths. pymunk wakes a body whose shape's filter or sensor is set
(cpShapeSetFilter, cpShapeSetSensor) and whose constraint or spring is edited
(cpConstraintActivateBodies), and a kinematic body wakes what it touches."""

from __future__ import annotations

import pytest
from paths import PATHS

from engine import Body, DampedSpring, Filter, Polygon, Segment, Vector, World
from engine.forces import Gravity

G = 9.81
DT = 1 / 60
SOLVERS = ["soft", "exact"]


def floor_world(kernels: str, solver: str) -> World:
    """A World under gravity with a floor segment along y = 0."""
    w = World(kernels=kernels, solver=solver)
    w.add_force(Gravity((0, -G)))
    w.add_collider(Segment((-10, 0), (10, 0), restitution=0.0))
    return w


def crate(x: float, y: float, **kw: object) -> Body:
    """A 1 m, 2 kg crate at (x, y)."""
    return Body(Vector(x, y), shape=Polygon.box(1.0, 1.0), mass=2, restitution=0.0, **kw)


def steps(w: World, n: int) -> None:
    for _ in range(n):
        w.step(DT)


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("kernels", PATHS)
def test_a_kinematic_sensor_made_solid_pushes_out_the_crate_asleep_in_it(
    kernels: str, solver: str
) -> None:
    """A kinematic door, a sensor, overlaps a crate asleep on the floor by 0.2 m; made solid,
    it wakes the crate (the bodies it overlaps wake: both solvers left the crate asleep in
    it), which is pushed out to the door's face: its centre at 0.3 - 0.5 = -0.2 m."""
    w = floor_world(kernels, solver)
    box = w.add(crate(0.0, 0.5))
    door = w.add(Body(Vector(0.8, 0.5), shape=Polygon.box(1.0, 1.0), kinematic=True, sensor=True))
    steps(w, 120)
    assert w.is_sleeping(box)
    assert abs(box.pos.x) < 1e-6
    door.sensor = False
    steps(w, 30)
    assert abs(box.pos.x - -0.2) < 2e-3  # against the door's face (it slid off it no further)
    assert w.overlap() < 1e-3
    assert door.pos == Vector(0.8, 0.5)  # (the game moves the door; the crate does not)


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("kernels", PATHS)
def test_crates_asleep_one_in_another_made_to_collide_push_apart(kernels: str, solver: str) -> None:
    """Two crates in one group (which do not collide) rest 0.8 m apart, 0.2 m into each other,
    asleep; one given its own filter wakes, and so does the other it overlaps (the exact step
    left it asleep, and the pair stayed 0.2 m deep): they push apart to 1 m, equally (equal
    masses), as pymunk's do when a shape's filter is set."""
    w = floor_world(kernels, solver)
    a = w.add(crate(0.0, 0.5, filter=Filter(group=5)))
    b = w.add(crate(0.8, 0.5, filter=Filter(group=5)))
    steps(w, 120)
    assert w.is_sleeping(a) and w.is_sleeping(b)
    b.filter = Filter()
    steps(w, 60)
    gap = b.pos.x - a.pos.x
    assert 1.0 - 5e-3 < gap < 1.0 + 5e-3
    assert abs(a.pos.x + b.pos.x - 0.8) < 5e-3  # about the middle, 0.4 m


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("kernels", PATHS)
def test_a_spring_lengthened_lowers_the_crate_asleep_on_it(kernels: str, solver: str) -> None:
    """A crate hangs from a damped spring to the world at rest (asleep on the soft step);
    its rest length set from 0 to 1 m lowers the crate by 1 m (its equilibrium is at
    5 - L - m g / k, the spring's top at 5 m): the spring's edit wakes its bodies (the soft
    step left the crate asleep, hanging where it was)."""
    w = World(kernels=kernels, solver=solver)
    w.add_force(Gravity((0, -G)))
    box = w.add(crate(0.0, 3.0))
    spring = w.add_link(DampedSpring(box, w.static_body, (0, 0), (0, 5), 0.0, 100.0, 20.0))
    steps(w, 300)
    if solver == "soft":
        assert w.is_sleeping(box)
    y0 = box.pos.y
    spring.rest_length = 1.0
    steps(w, 300)
    assert abs(box.pos.y - (y0 - 1.0)) < 2e-3


@pytest.mark.parametrize("kernels", PATHS)
def test_a_spring_made_softer_lowers_the_crate_asleep_on_it(kernels: str) -> None:
    """As above, the spring's stiffness halved (100 to 50 N/m): the crate, asleep, wakes and
    sinks to the new equilibrium 5 - m g / k = 4.608 m (from 4.804), on the soft step."""
    w = World(kernels=kernels, solver="soft")
    w.add_force(Gravity((0, -G)))
    box = w.add(crate(0.0, 3.0))
    spring = w.add_link(DampedSpring(box, w.static_body, (0, 0), (0, 5), 0.0, 100.0, 20.0))
    steps(w, 300)
    assert w.is_sleeping(box)
    assert abs(box.pos.y - (5 - 2 * G / 100)) < 2e-3
    spring.stiffness = 50.0
    steps(w, 300)
    assert abs(box.pos.y - (5 - 2 * G / 50)) < 2e-3


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("kernels", PATHS)
def test_the_last_body_taken_out_ends_its_contact_and_a_new_one_begins(
    kernels: str, solver: str
) -> None:
    """Breakout's last ball lost: the only body, asleep on the floor, is taken out (the soft
    step's next step raised an IndexError, the events reading the gone body's contact as
    touching still); its contact with the floor ends once, steps of an empty World report
    nothing, and a new crate served onto the floor begins its own contact and rests there."""
    w = floor_world(kernels, solver)
    floor = w.colliders[0]
    log: list[tuple[str, Body]] = []
    w.on_contact(
        floor,
        begin=lambda e: log.append(("begin", e.body)),
        end=lambda e: log.append(("end", e.body)),
    )
    old = w.add(crate(0.0, 0.5))
    steps(w, 120)
    assert w.is_sleeping(old)
    w.remove(old)
    steps(w, 10)
    assert log == [("begin", old), ("end", old)]
    new = w.add(crate(0.0, 0.6))
    steps(w, 60)
    assert log == [("begin", old), ("end", old), ("begin", new)]
    assert abs(new.pos.y - 0.5) < 1e-3
