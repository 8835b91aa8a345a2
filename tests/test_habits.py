"""What a pygame or pymunk user writes first: it works, or it is refused with what to use.

A name the engine does not have is an AttributeError that says what to write instead, never an
attribute kept and ignored; what cannot change once made is refused, so the World is never
left holding a shape it no longer agrees with.
"""

from __future__ import annotations

import copy
import math

import pytest

from engine import Body, Box, Circle, Plane, Rod, Segment, Vector, World
from engine.forces import Gravity

G = (0.0, -9.81)


# -- Body: what may be left out, and pymunk's names --------------------------------------------


def test_a_body_made_from_its_position_alone_is_at_rest() -> None:
    b = Body(Vector(0, 5))
    assert (b.pos, b.vel, b.acc) == (Vector(0, 5), Vector(0, 0), Vector(0, 0))
    assert all(type(v) is Vector for v in (b.pos, b.vel, b.acc))
    line = Body(0.0)
    assert (line.pos, line.vel, line.acc, line.dim) == (0.0, 0.0, 0.0, 1)
    assert all(type(v) is float for v in (line.pos, line.vel, line.acc))
    moving = Body((1, 2), (3, 4))
    assert (moving.vel, moving.acc) == (Vector(3, 4), Vector(0, 0))
    pushed = Body(2.0, acceleration=1.0)
    assert (pushed.vel, pushed.acc) == (0.0, 1.0)
    # The lesson's text is unchanged.
    assert str(Body(Vector(0, 5))) == "Position: X: 0.0 Y: 5.0\nVelocity: X: 0.0 Y: 0.0\n" + (
        "Acceleration: X: 0.0 Y: 0.0\n"
    )


def test_a_body_left_at_rest_falls_in_a_world_as_one_given_zeros() -> None:
    short, full = World(integrator="auto"), World(integrator="auto")
    a = short.add(Body(Vector(0, 5), radius=0.1))
    b = full.add(Body(Vector(0, 5), Vector(0, 0), Vector(0, 0), radius=0.1))
    for world in (short, full):
        world.add_force(Gravity(G))
        for _ in range(30):
            world.step(1 / 60)
    assert a.pos == b.pos and a.vel == b.vel
    assert a.pos.y == pytest.approx(5 - 9.81 * 0.5**2 / 2, rel=1e-14)


def test_a_bad_position_is_still_named_when_the_rest_is_left_out() -> None:
    with pytest.raises(TypeError, match="Body position must be"):
        Body("here")
    with pytest.raises(TypeError, match="mix dimensions"):
        Body(Vector(0, 5), 1.0)


def test_pymunks_names_read_and_write_the_lessons() -> None:
    lone = Body(Vector(1, 2), Vector(3, 4), Vector(0, -1))
    assert (lone.position, lone.velocity, lone.acceleration) == (lone.pos, lone.vel, lone.acc)
    lone.position, lone.velocity = (5, 6), Vector(7, 8)
    assert (lone.pos, lone.vel) == (Vector(5, 6), Vector(7, 8))
    world = World(integrator="auto")
    body = world.add(Body(Vector(0, 0), Vector(1, 0)))
    world.add_force(Gravity(G))
    body.velocity = Vector(2, 0)
    world.step(0.5)
    assert body.position == body.pos == Vector(1.0, -9.81 * 0.25 / 2)
    assert body.velocity == body.vel and body.acceleration == body.acc == Vector(*G)
    with pytest.raises(AttributeError, match="own_acc"):
        body.acceleration = Vector(0, 0)  # in a World, acc is the total: the lesson's rule


@pytest.mark.parametrize(
    ("name", "says"),
    [
        ("force", "own_acc"),
        ("apply_impulse_at_world_point", "body.apply_impulse"),
        ("space", "body.world"),
        ("body_type", "kinematic=True"),
        ("sleep_with_group", r"body\.sleep\(\)"),
        ("elasticity", "restitution"),
    ],
)
def test_a_pymunk_body_name_says_what_to_use(name: str, says: str) -> None:
    body = Body(Vector(0, 0))
    with pytest.raises(AttributeError, match=says):
        getattr(body, name)
    with pytest.raises(AttributeError, match=says):
        setattr(body, name, 1.0)


def test_pymunks_body_mass_moment_order_says_what_to_write() -> None:
    # pymunk's Body(mass, moment) fills Body's position and velocity: a body on a line.
    with pytest.raises(ValueError, match="velocity must be finite") as refused:
        Body(70, math.inf)  # pymunk's body that never turns
    said = str(refused.value)
    assert "Body's arguments are (position, velocity=None, acceleration=None, mass=1.0" in said
    assert "Body(70, math.inf) is a body on a line (1D) at position 70" in said
    assert "Body(Vector(x, y), mass=70, moment=math.inf)" in said
    written = Body(Vector(0, 0), mass=70, moment=math.inf)  # what it says works
    assert (written.mass, written.moment, written.turns) == (70.0, math.inf, False)
    # Finite numbers make a 1D body; a 2D position written to it says why it is 1D.
    on_a_line = Body(1, 100)
    for name in ("position", "pos", "velocity", "vel"):
        with pytest.raises(TypeError, match=r"this body is 1D, made of numbers.*"
                           r"Body\(Vector\(x, y\), mass=m, moment=I\)"):  # fmt: skip
            setattr(on_a_line, name, (50, 100))
    assert (on_a_line.pos, on_a_line.vel) == (1.0, 100.0)
    plane = World()
    plane.add(Body(Vector(0, 0)))
    with pytest.raises(TypeError, match=r"1D but this World is 2D.*pymunk's Body\(mass, moment\)"):
        plane.add(Body(1, 100))
    line = World()
    line.add(Body(1, 100))
    with pytest.raises(TypeError, match=r"2D but this World is 1D.*pymunk's Body\(mass, moment\)"):
        line.add_collider(Segment((0, 0), (10, 0)))


@pytest.mark.parametrize("name", ["radius", "kinematic"])
def test_what_a_body_is_made_with_is_refused_with_the_way_to_change_it(name: str) -> None:
    world = World()
    body = world.add(Body(Vector(0, 0), radius=0.5))
    before = getattr(body, name)
    with pytest.raises(AttributeError, match=rf"Body\(\.\.\., {name}="):
        setattr(body, name, 0.25)
    assert getattr(body, name) == before


# -- World: pymunk's Space habits ----------------------------------------------------------------


def test_gravity_written_as_in_pymunk_is_refused_with_the_force_to_add() -> None:
    world = World()
    world.add(Body(Vector(0, 10)))
    with pytest.raises(AttributeError, match=r"add_force\(Gravity\(\(0, -9\.81\)\)\)"):
        world.gravity = (0, -9.8)  # type: ignore[attr-defined]
    with pytest.raises(AttributeError, match="add_force"):
        _ = world.gravity  # type: ignore[attr-defined]
    assert "gravity" not in vars(world)
    world.add_force(Gravity(G))  # what the message says works
    world.step(1.0)
    assert world.bodies[0].vel == Vector(*G)


@pytest.mark.parametrize(
    ("name", "says"),
    [
        ("damping", "Drag"),
        ("iterations", "contact_iterations"),
        ("sleep_time_threshold", "sleep_time"),
        ("add_collision_handler", "on_contact"),
        ("constraints", "world.links"),
    ],
)
def test_a_pymunk_space_name_says_what_to_use(name: str, says: str) -> None:
    world = World()
    with pytest.raises(AttributeError, match=says):
        setattr(world, name, 1)
    with pytest.raises(AttributeError, match=says):
        getattr(world, name)


def test_space_add_of_a_body_and_its_shape_says_a_body_carries_its_shape() -> None:
    world = World()
    ball = Body(Vector(0, 5), radius=0.5)
    with pytest.raises(TypeError, match="World.add takes one Body, got 2 things") as refused:
        world.add(ball, Circle((0, 0), 0.5))  # type: ignore[arg-type]  # pymunk's space.add
    said = str(refused.value)
    assert "Circle((0.0, 0.0), 0.5)" in said and "space.add(body, shape)" in said
    assert "a Body carries its shape (Body(..., radius=r)" in said and "world.add_all" in said
    assert world.bodies == ()  # nothing added
    world.add(ball)  # what it says works
    with pytest.raises(TypeError, match=r"World.remove takes one Body.*goes out with it"):
        world.remove(ball, Circle((0, 0), 0.5))  # type: ignore[arg-type]
    assert world.bodies == (ball,)


def test_a_collider_or_a_link_handed_to_add_or_remove_names_its_method() -> None:
    world = World()
    floor = world.add_collider(Segment((0, 0), (10, 0)))
    lamp = world.add(Body(Vector(0, 5), radius=0.5))
    rod = world.add_link(Rod(lamp, (0, 8)))
    with pytest.raises(TypeError, match=r"World\.remove takes a Body, got Segment Segment\(.*"
                       r"world\.remove_collider\(collider\)"):  # fmt: skip
        world.remove(floor)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"got Rod .*world\.remove_link\(link\)"):
        world.remove(rod)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"World\.add takes a Body, got Circle .*add_collider"):
        world.add(Circle((3, 3), 1))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"got Rod .*world\.add_link\(link\)"):
        world.add(Rod(lamp, (0, 9)))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"got int 3: a collider goes by world\.remove_collider"):
        world.remove(3)  # type: ignore[arg-type]
    assert (world.colliders, world.links, world.bodies) == ((floor,), (rod,), (lamp,))
    world.remove_collider(floor)  # what they say works
    world.remove_link(rod)
    assert world.colliders == () and world.links == ()


def test_an_unknown_name_is_refused_and_the_settable_ones_are_listed() -> None:
    world = World()
    with pytest.raises(AttributeError, match="contact_iterations, sleep_time"):
        world.contact_iteration = 4  # type: ignore[attr-defined]  # a typo, not a new attribute
    assert not hasattr(world, "contact_iteration")
    world.contact_iterations, world.sleep_time = 4, math.inf  # what can be set still can
    assert (world.contact_iterations, world.sleep_time) == (4, math.inf)
    with pytest.raises(AttributeError):
        world.t = 3.0  # type: ignore[misc]  # time moves by step alone


def test_a_subclass_keeps_names_of_its_own_but_not_pymunks() -> None:
    class Game(World):
        def __init__(self) -> None:
            super().__init__()
            self.score = 0

    game = Game()
    game.score += 10
    assert game.score == 10
    with pytest.raises(AttributeError, match="add_force"):
        game.gravity = (0, -9.8)  # type: ignore[attr-defined]


def test_a_worlds_method_can_still_be_replaced_for_a_test(monkeypatch) -> None:
    world = World()
    calls: list[float] = []
    monkeypatch.setattr(world, "step", calls.append)
    world.step(0.5)
    assert calls == [0.5]


# -- colliders: their geometry fixed once made (their material is not: test_material_changes) --

SHAPES = [
    (Plane((0, 0), (0, 1)), ["point", "normal"]),
    (Segment((0, 0), (1, 0), 0.1), ["a", "b", "radius"]),
    (Circle((1, 2), 0.5), ["center", "radius"]),
    (Box((0, 0), (4, 3)), ["lower_left", "upper_right"]),
]


@pytest.mark.parametrize(("shape", "names"), SHAPES, ids=lambda v: type(v).__name__)
def test_every_attribute_of_a_collider_is_refused_with_what_to_do(
    shape: object, names: list[str]
) -> None:
    kind = type(shape).__name__
    for name in names:
        before = getattr(shape, name)
        with pytest.raises(AttributeError, match=rf"world\.add_collider\({kind}\("):
            setattr(shape, name, getattr(shape, name))
        with pytest.raises(AttributeError, match="remove_collider"):
            delattr(shape, name)
        assert getattr(shape, name) == before
    for name in ("restitution", "friction", "sensor", "filter"):
        with pytest.raises(AttributeError, match="remove_collider"):
            delattr(shape, name)
    twin = copy.deepcopy(shape)
    assert repr(twin) == repr(shape) and twin is not shape


def test_moving_a_peg_by_hand_is_refused_and_the_world_stays_whole() -> None:
    # The story: peg.center = (x, y) corrupted the World (the error came later from
    # step or remove_collider); peg.center = Vector(...) was kept and ignored.
    world = World(integrator="auto")
    world.add_force(Gravity(G))
    ball = world.add(Body(Vector(3, 5), radius=0.25, restitution=0.5))
    peg = world.add_collider(Circle((0, 2), 0.5))
    for value in ((3, 2), Vector(3, 2)):
        with pytest.raises(AttributeError, match="kinematic=True"):
            peg.center = value  # type: ignore[misc]
    assert peg.center == Vector(0, 2)
    for _ in range(30):
        world.step(1 / 60)
    assert ball.pos.y == pytest.approx(5 - 9.81 * 0.5**2 / 2, rel=1e-12)  # falling freely
    # What the message says: take the peg out and add one where it is wanted.
    world.remove_collider(peg)
    moved = world.add_collider(Circle((3, 2), 0.5))
    hits, lowest = [], math.inf
    for _ in range(120):
        world.step(1 / 60)
        hits += [e for e in world.began if e.collider is moved]
        lowest = min(lowest, ball.pos.y)
    assert hits, "the ball never met the peg where it was added"
    assert lowest >= 2 + 0.5 + 0.25 - 1e-9  # it landed on the peg's top, never inside it
