"""engine.Body: the lesson's rbpbodies.Body, refusing what the lesson silently skipped."""

from __future__ import annotations

import copy
import math

import pytest

from engine import Body, Vector, World
from engine.forces import ConstantForce, Gravity, Spring


def test_str_is_the_lessons_text_for_a_2d_body() -> None:
    b = Body(Vector(0, 0), Vector(1, 0), Vector(0, -9.8))
    # rbpbodies: "Position: " + str(pos) + "\n" "Velocity: " ... "Acceleration: " ... "\n"
    assert (
        str(b) == "Position: X: 0.0 Y: 0.0\nVelocity: X: 1.0 Y: 0.0\nAcceleration: X: 0.0 Y: -9.8\n"
    )


def test_str_of_a_1d_body_shows_the_numbers() -> None:
    assert str(Body(2, 1, 0)) == "Position: 2.0\nVelocity: 1.0\nAcceleration: 0.0\n"


def test_a_1d_body_holds_floats() -> None:
    b = Body(2, 1, 0)
    assert b.dim == 1
    assert (b.pos, b.vel, b.acc, b.mass) == (2.0, 1.0, 0.0, 1.0)
    assert all(type(value) is float for value in (b.pos, b.vel, b.acc, b.mass))


def test_a_2d_body_holds_vectors_even_when_given_tuples() -> None:
    b = Body((1, 2), Vector(3, 4), (0, -10), mass=2)
    assert b.dim == 2
    assert all(type(value) is Vector for value in (b.pos, b.vel, b.acc))
    assert (b.pos, b.vel, b.acc) == (Vector(1, 2), Vector(3, 4), Vector(0, -10))
    assert b.mass == 2.0


def test_out_of_a_world_attributes_are_plain_stored_values() -> None:
    b = Body(Vector(0, 0), Vector(0, 0), Vector(0, 0))
    b.pos = (1, 2)
    b.vel = Vector(3, 4)
    b.acc = Vector(0, -1)
    assert (b.pos, b.vel, b.acc, b.own_acc) == ((1, 2), (3, 4), (0, -1), (0, -1))
    b.mass = 3
    assert b.mass == 3.0


def test_a_shared_vector_is_not_changed_by_the_body() -> None:
    start = Vector(1, 1)
    b = Body(start, Vector(1, 0), Vector(0, 0))
    p = b.pos
    p += Vector(5, 5)
    assert b.pos == Vector(1, 1) and start == Vector(1, 1)


# -- refusals ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("args", "named"),
    [
        (((0, 0), 1.0, (0, 0)), "velocity is 1D"),
        ((0.0, (1, 1), 0.0), "velocity is 2D"),
        ((0.0, 0.0, Vector(0, 0)), "acceleration is 2D"),
        ((Vector(0, 0), Vector(0, 0), 0.0), "acceleration is 1D"),
    ],
)
def test_mixing_dimensions_is_a_type_error_naming_the_argument(
    args: tuple[object, object, object], named: str
) -> None:
    with pytest.raises(TypeError, match=f"mix dimensions.*{named}"):
        Body(*args)


@pytest.mark.parametrize(
    ("args", "named"),
    [
        (("0", 0.0, 0.0), "position"),
        ((None, 0.0, 0.0), "position"),
        ((0.0, "fast", 0.0), "velocity"),
        ((0.0, [1, 2, 3], 0.0), "velocity"),
        ((0.0, 0.0, "slow"), "acceleration"),  # (None is the default: zero)
        ((True, 0.0, 0.0), "position"),
        (((0, "y"), (0, 0), (0, 0)), "position"),
    ],
)
def test_a_non_number_argument_is_a_type_error_naming_it(
    args: tuple[object, object, object], named: str
) -> None:
    # The lesson's Body skipped a non-Vector argument silently and left the attribute missing.
    with pytest.raises(TypeError, match=f"Body {named} must be"):
        Body(*args)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
@pytest.mark.parametrize("which", ["position", "velocity", "acceleration"])
def test_a_non_finite_value_is_a_value_error_naming_the_argument(which: str, bad: float) -> None:
    args = {"position": 0.0, "velocity": 0.0, "acceleration": 0.0}
    args[which] = bad
    with pytest.raises(ValueError, match=f"{which} must be finite"):
        Body(**args)
    args2 = {"position": (0, 0), "velocity": (0, 0), "acceleration": (0, 0)}
    args2[which] = (0.0, bad)
    with pytest.raises(ValueError, match=f"{which} must be finite"):
        Body(**args2)


@pytest.mark.parametrize("bad", [0, 0.0, -1.0, math.nan, math.inf])
def test_mass_must_be_positive_and_finite(bad: float) -> None:
    with pytest.raises(ValueError, match="mass must be positive and finite"):
        Body(0.0, 0.0, 0.0, mass=bad)
    b = Body(0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="mass must be positive and finite"):
        b.mass = bad
    assert b.mass == 1.0


@pytest.mark.parametrize("bad", ["1", None, True, (1, 1)])
def test_mass_must_be_a_number(bad: object) -> None:
    with pytest.raises(TypeError, match="mass must be a positive real number"):
        Body(0.0, 0.0, 0.0, mass=bad)  # type: ignore[arg-type]


def test_setters_refuse_wrong_kind_and_non_finite_values_and_keep_the_old_one() -> None:
    b = Body(Vector(1, 2), Vector(0, 0), Vector(0, 0))
    with pytest.raises(TypeError, match="pos must be a Vector"):
        b.pos = 3.0
    with pytest.raises(ValueError, match="vel must be finite"):
        b.vel = (math.nan, 0)
    with pytest.raises(TypeError, match="acc must be a Vector"):
        b.acc = "down"
    assert (b.pos, b.vel, b.acc) == (Vector(1, 2), Vector(0, 0), Vector(0, 0))


# -- in a World --------------------------------------------------------------------------------


def test_in_a_world_pos_and_vel_are_live() -> None:
    world = World("exact")
    b = world.add(Body(Vector(0, 0), Vector(1, 2), Vector(0, 0)))
    world.step(0.5)
    assert b.pos == Vector(0.5, 1.0)
    b.pos = Vector(10, 10)
    b.vel = (0, 0)
    assert world.positions()[0].tolist() == [10.0, 10.0]
    world.step(0.5)
    assert b.pos == Vector(10, 10) and b.vel == Vector(0, 0)


def test_in_a_world_acc_is_own_acceleration_plus_forces_over_mass() -> None:
    world = World()
    b = world.add(Body(Vector(3, 0), Vector(0, 0), Vector(1, 0), mass=2.0))
    world.add_force(Gravity((0, -10)))
    world.add_force(ConstantForce((4, 6)))  # 4/2, 6/2 on a 2 kg body
    world.add_force(Spring((0, 0), k=8))  # -8 * (3, 0) / 2 = (-12, 0)
    assert b.own_acc == Vector(1, 0)
    assert b.acc == Vector(1 + 2 - 12, -10 + 3)
    b.pos = (1, 0)
    assert b.acc == Vector(1 + 2 - 4, -10 + 3)


def test_setting_acc_in_a_world_is_an_attribute_error_pointing_to_own_acc() -> None:
    world = World()
    b = world.add(Body(0.0, 0.0, 1.0))
    with pytest.raises(AttributeError, match="own_acc"):
        b.acc = 2.0
    assert b.own_acc == 1.0
    b.own_acc = 2.0
    world.step(1.0)  # semi-implicit Euler: v = 2, x = 2
    assert (b.pos, b.vel, b.acc) == (2.0, 2.0, 2.0)


def test_a_removed_body_keeps_its_last_state() -> None:
    world = World("exact")
    b = world.add(Body(0.0, 1.0, 0.0))
    world.step(2.0)
    world.remove(b)
    assert b.world is None
    assert (b.pos, b.vel) == (2.0, 1.0)
    b.acc = 3.0  # out of a world again, acc is a plain value
    assert b.acc == 3.0


def test_data_holds_the_games_own_things_and_no_other_attribute_is_taken() -> None:
    brick = {"points": 50}
    b = Body(Vector(0, 5), radius=0.2, data=brick)
    assert b.data is brick and Body(Vector(0, 0)).data is None
    world = World()
    world.add(b)
    assert b.data is brick  # a handle in a World keeps it
    saved = world.snapshot()
    b.data = "hit"
    world.step(0.1)
    world.restore(saved)  # the physics come back; the game's own data is not part of them
    assert b.data == "hit" and b.pos == Vector(0, 5)
    world.remove(b)
    assert b.data == "hit"
    with pytest.raises(AttributeError, match="hp"):
        b.hp = 3  # type: ignore[attr-defined]  # no other new attribute: data is the place


def test_copy_of_a_body_in_a_world_is_a_body_in_no_world_with_its_state() -> None:
    # It once shared the body's row: the copy moved with the World's steps, and once the body
    # was removed it read another body's row. As pymunk's body copy, it leaves the World.
    world = World()
    other = world.add(Body(Vector(9, 9)))
    b = world.add(
        Body(Vector(1, 2), Vector(3, 0), Vector(0, -1), mass=2.0, moment=0.5, data=["hit"])
    )
    b.angular_velocity = 4.0
    world.step(0.5)
    b.apply_force((8, 0), at=b.pos + Vector(0, 1))  # for the World's next step only
    twin = copy.copy(b)
    assert twin.world is None and twin.slot == -1 and twin is not b
    assert (twin.pos, twin.vel, twin.own_acc) == (b.pos, b.vel, Vector(0, -1))
    assert (twin.mass, twin.moment, twin.angle, twin.angular_velocity) == (2.0, 0.5, 2.0, 4.0)
    assert twin.torque == 0.0 and twin.data is b.data  # the push stays with b; data is shared
    pos = twin.pos
    world.step(0.5)
    world.remove(other)
    assert twin.pos == pos != b.pos
    # A body of its own: it steps alone, or in a World, the same one or another.
    world.add(twin)
    assert world.bodies == (b, twin)
    lone = copy.copy(Body(0.0, 1.0, 2.0))
    lone.step(1.0)
    assert (lone.pos, lone.vel, lone.world) == (3.0, 3.0, None)
