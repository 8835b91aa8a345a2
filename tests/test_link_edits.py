"""A link or joint changed after it is made (issue "What a pymunk user reaches for", item 4):
a rod's or cable's length and anchors (a winch, a crane's hook moved along its beam) and a
joint's ``collide``, taken by the next step on both solvers and both paths, woken where they
slept, and put back by a snapshot on the same link objects."""

import math

import pytest

from engine import Body, Cable, Hinge, Pin, Polygon, Rod, Vector, World
from engine.forces import Gravity
from tests.paths import PATHS

DT = 1.0 / 60.0
G = 9.81
SOLVERS = ["exact", "soft"]


def crane(kernels: str, solver: str) -> tuple[World, Body, Cable]:
    """A 2 kg crate (0.5 m box) hanging 3 m below a fixed hook on a cable to its top."""
    world = World(kernels=kernels, solver=solver, integrator="auto")
    world.add_force(Gravity((0.0, -G)))
    crate = world.add(Body(Vector(0.0, -3.25), mass=2.0, shape=Polygon.box(0.5, 0.5)))
    cable = world.add_link(Cable(crate, (0.0, 0.0), 3.0, anchor_a=(0.0, 0.25)))
    return world, crate, cable


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("solver", SOLVERS)
def test_a_winch_shortens_a_cable_and_the_crate_comes_up_with_it(kernels: str, solver: str) -> None:
    world, crate, cable = crane(kernels, solver)
    for _ in range(60):
        world.step(DT)
    worst = 0.0
    for _ in range(120):  # 2 s at 0.5 m/s
        cable.length -= 0.5 * DT
        world.step(DT)
        worst = max(worst, abs(abs(cable.end_a() - cable.end_b()) - cable.length))
    assert cable.length == pytest.approx(2.0, abs=1e-12)
    # The exact solver holds each new length at the step's end; the soft one follows it by
    # its joints' 60 Hz spring, a few millimetres behind a winch at 0.5 m/s (3.8 measured).
    assert worst <= (1e-12 if solver == "exact" else 5e-3)
    assert crate.pos.y == pytest.approx(-2.25, abs=1e-9 if solver == "exact" else 5e-3)
    assert crate.pos.x == 0.0 and crate.angle == 0.0  # straight up, not swinging
    # Stopped, it hangs by the cable: the cable carries its weight (m g dt a step).
    for _ in range(60):
        world.step(DT)
    assert cable.tension(DT) == pytest.approx(2.0 * G, rel=1e-6)


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("solver", SOLVERS)
def test_a_rods_anchor_set_is_where_it_holds_from_the_next_step(kernels: str, solver: str) -> None:
    world = World(kernels=kernels, solver=solver)
    a = world.add(Body(Vector(0.0, 0.0), mass=1.0, shape=Polygon.box(1.0, 1.0)))
    b = world.add(Body(Vector(3.0, 0.0), mass=1.0, radius=0.2))
    rod = world.add_link(Rod(a, b, anchor_a=(0.5, 0.0)))  # 2.5 m, from a's right face
    assert rod.length == pytest.approx(2.5)
    rod.anchor_a = (0.5, 0.5)  # its corner: 2.55 m from b's centre, the rod 2.5
    rod.anchor_b = (0.0, 0.1)
    assert rod.anchor_a == Vector(0.5, 0.5) and rod.anchor_b == Vector(0.0, 0.1)
    for _ in range(120):
        world.step(DT)
    corner = a.local_to_world(Vector(0.5, 0.5))
    assert abs(rod.end_a() - corner) < 1e-12
    # The rod holds its length between the new anchors (exactly, or within the soft give),
    # and momentum stays zero: the correction is internal.
    assert abs(rod.end_a() - rod.end_b()) == pytest.approx(
        2.5, abs=1e-9 if solver == "exact" else 1e-3
    )
    p = a.vel * a.mass + b.vel * b.mass
    assert abs(p) < 1e-9


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("solver", SOLVERS)
def test_a_joints_collide_set_after_it_is_added_takes_effect(kernels: str, solver: str) -> None:
    world = World(kernels=kernels, solver=solver)
    a = world.add(Body(Vector(0.0, 0.0), mass=1.0, radius=0.5))
    b = world.add(Body(Vector(0.6, 0.0), mass=1.0, radius=0.5))  # 0.4 m into each other
    hinge = world.add_link(Hinge(a, b, (0.3, 0.0)))
    for _ in range(10):
        world.step(DT)
    # Kept apart by the hinge (collide False): they rest as they are, overlapping.
    assert abs(a.pos - b.pos) == pytest.approx(0.6, abs=1e-6)
    assert not world.touching
    hinge.collide = True
    world.step(DT)
    assert any(e.collider is b or e.body is b for e in world.touching)  # they touch now


@pytest.mark.parametrize("kernels", PATHS)
def test_a_winch_wakes_the_crate_asleep_on_its_cable(kernels: str) -> None:
    # On the soft solver a still island sleeps, links and all (on the exact one a body held
    # by a link never sleeps: what moves it would pull it).
    world, crate, cable = crane(kernels, "soft")
    world.add_link(Cable(crate, (1.0, 0.0), 3.5, anchor_a=(0.25, 0.25)))  # a slack guy rope
    for _ in range(240):
        world.step(DT)
    assert world.is_sleeping(crate)
    y = crate.pos.y
    cable.length = 2.5
    for _ in range(60):
        world.step(DT)
    assert crate.pos.y > y + 0.4  # hauled up, not left asleep where it hung


def test_a_snapshot_puts_a_set_length_back_on_the_same_cable() -> None:
    world, crate, cable = crane("numpy", "exact")
    for _ in range(30):
        world.step(DT)
    saved = world.snapshot()
    path = []
    for _ in range(60):
        cable.length -= 0.5 * DT
        world.step(DT)
        path.append(crate.pos)
    world.restore(saved)
    # The game's own cable is still the World's, at the length it had: a winch keeps working.
    assert list(world.links) == [cable] and cable.length == 3.0
    again = []
    for _ in range(60):
        cable.length -= 0.5 * DT
        world.step(DT)
        again.append(crate.pos)
    assert again == path


def test_what_is_fixed_once_made_says_so_and_bad_values_are_refused() -> None:
    world = World()
    a = world.add(Body(Vector(0.0, 0.0), mass=1.0, radius=0.2))
    b = world.add(Body(Vector(2.0, 0.0), mass=1.0, radius=0.2))
    rod = world.add_link(Rod(a, b))
    pin = world.add_link(Pin(world.add(Body(Vector(5.0, 0.0), radius=0.2)), (5.0, 0.0)))
    with pytest.raises(AttributeError, match="Pin's length is fixed once it is made"):
        pin.length = 2.0
    hinge = Hinge(a, b, (1.0, 0.0))
    with pytest.raises(AttributeError, match="Hinge's anchor_a is fixed once it is made"):
        hinge.anchor_a = (0.1, 0.0)
    with pytest.raises(ValueError, match="length"):
        rod.length = -1.0
    with pytest.raises(ValueError, match="length"):
        rod.length = math.nan
    assert rod.length == 2.0  # nothing lost
    hook = Cable(a, (0.0, 3.0), 3.0)
    with pytest.raises(ValueError, match="anchor_b is the anchor on a second body"):
        hook.anchor_b = (0.1, 0.0)
    with pytest.raises(TypeError, match="collide must be True or False"):
        hinge.collide = 1  # type: ignore[assignment]
    assert hinge.collide is False


@pytest.mark.parametrize("kernels", PATHS)
def test_a_hinges_motor_set_between_steps_drives_the_next_step(kernels: str) -> None:
    # The soft step keeps its joints' rows whole while no setting of any joint is set
    # (engine.dynamics.links.edits): a motor's speed and torque, set between two steps of a
    # game, are each the next step's. A wheel on a hinge at its centre, no gravity: the motor
    # (no bound on its torque) turns it at its speed, and with no torque it turns on as it was.
    world = World(kernels=kernels, solver="soft")
    wheel = world.add(Body(Vector(0.0, 0.0), mass=1.0, radius=0.5))
    hinge = world.add_link(Hinge(wheel, world.static_body, (0.0, 0.0), motor_speed=2.0))
    for _ in range(10):
        world.step(DT)
    assert wheel.angular_velocity == pytest.approx(2.0, abs=1e-9)
    hinge.motor_speed = -3.0
    world.step(DT)
    assert wheel.angular_velocity == pytest.approx(-3.0, abs=1e-9)
    hinge.max_torque = 0.0
    hinge.motor_speed = 5.0
    world.step(DT)
    assert wheel.angular_velocity == pytest.approx(-3.0, abs=1e-9)  # no torque: it turns on
