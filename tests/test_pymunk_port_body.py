"""pymunk's own tests of its Body, ported to this engine.

As ``test_pymunk_port.py`` ports pymunk's Space, shape, arbiter and shape filter tests, this
file ports ``pymunk/tests/test_body.py`` (class ``UnitTestBody``) test by test, keeping
pymunk's scenes and numbers where the concepts map:

* pymunk's ``Body(mass, moment)`` is ``Body(Vector(x, y), mass=mass, moment=moment)`` (here
  ``Body(m, i)`` is a body on a line at position m moving at i); a ``Circle(body, r)`` on it
  is ``Body(..., radius=r)``;
* a ``Space`` is a World (``body.space`` is ``body.world``); ``Body.KINEMATIC`` is
  ``Body(..., kinematic=True)``; the static body is ``world.static_body`` (static geometry
  is colliders);
* ``apply_force_at_world_point(f, p)`` is ``apply_force(f, at=p)``, for the World's next step
  only, as pymunk's (it needs the body in a World); until that step the push shows in
  ``own_acc`` (pymunk's ``force / mass``) and ``torque``; ``apply_impulse_at_world_point`` is
  ``apply_impulse(j, at=p)``; the ``_at_local_point`` forms take ``at=body.local_to_world(p)``;
* ``body.each_arbiter`` is ``world.touching`` (the contacts going on after the step), and
  ``body.constraints`` the World's links whose ``bodies`` hold it;
* a custom attribute on a Body (``b.custom = "test"``) is ``body.data``.

Each ported test is named ``test_body_<pymunk's name>`` (``test_body_test_sleep`` ports
``test_sleep``), and a variant of one ``test_body_<pymunk's name>__<what>``. A difference kept
on purpose is a strict xfail that asserts pymunk's number and gives the reason; a pymunk
feature this engine does not have is listed in ``MISSING`` with the reason, and
``test_every_pymunk_body_test_is_ported_or_listed`` checks (where pymunk is installed: the
``bench`` extra) that no test of pymunk's test_body.py is left out unsaid.
"""

from __future__ import annotations

import math
import pickle

import pytest

from engine import Body, Circle, ContactEvent, Hinge, Rod, Segment, Vector, World
from engine.forces import Gravity
from tests.pymunk_tests import check_ported, their_tests

pytestmark = pytest.mark.filterwarnings("ignore::engine.OverlapWarning")


def disc(world: World, x: float, y: float, r: float = 1.0, mass: float = 1.0) -> Body:
    """A pymunk ``Body(mass, moment)`` with a ``Circle(body, r)`` at (x, y): a disc."""
    return world.add(Body(Vector(x, y), mass=mass, radius=r))


def test_body_test_properties() -> None:
    b = Body(Vector(0, 0), mass=10, moment=100)
    assert b.mass == 10
    b.mass = 11
    assert b.mass == 11
    assert b.moment == 100  # given: it does not follow the mass
    b.moment = 101
    assert b.moment == 101
    assert b.position == (0, 0)
    b.position = 1, 2
    assert b.position == (1, 2) and b.pos == (1, 2)
    # pymunk sets center_of_gravity; here it follows from the shape (a body's centre of mass
    # is its position), and a write is refused.
    assert b.center_of_gravity == (0, 0)
    with pytest.raises(AttributeError, match="follows from its shape"):
        b.center_of_gravity = (1, 2)
    assert b.velocity == (0, 0)
    b.velocity = 3, 4
    assert b.velocity == (3, 4) and b.vel == (3, 4)
    # (pymunk's force is the push until the next step: test_body_test_force.)
    assert b.angle == 0
    b.angle = 1.2
    assert b.angle == 1.2
    assert b.angular_velocity == 0
    b.angular_velocity = 1.3
    assert b.angular_velocity == 1.3
    assert b.torque == 0
    b.torque = 1.4
    assert b.torque == 1.4
    # (No rotation_vector: Vector(1, 0).rotate_rad(body.angle).)
    assert b.world is None
    w = World()
    w.add(b)
    assert b.world is w
    # In a World the same values are read from its arrays.
    assert (b.mass, b.moment, b.position, b.velocity) == (11, 101, (1, 2), (3, 4))
    assert (b.angle, b.angular_velocity, b.torque) == (1.2, 1.3, 1.4)


def test_body_test_repr() -> None:
    b = Body(Vector(0, 0), mass=1, moment=2)
    assert repr(b) == (
        "Body(position=Vector(0.0, 0.0), velocity=Vector(0.0, 0.0), "
        "acceleration=Vector(0.0, 0.0), mass=1.0)"
    )
    k = Body(Vector(0, 0), kinematic=True)
    assert repr(k).endswith(", mass=1.0, kinematic=True)")
    # pymunk's STATIC body: world.static_body.
    assert repr(World().static_body) == "world.static_body"


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="str(body) is the lesson's three lines (Position, Velocity, Acceleration) and "
    "repr(body) gives its position, velocity, acceleration and mass; pymunk's str gives its "
    "mass, moment and type",
)
def test_body_test_repr__pymunk_text() -> None:
    assert str(Body(Vector(0, 0), mass=1, moment=2)) == "Body(1.0, 2.0, Body.DYNAMIC)"


def test_body_test_coordinate_conversion() -> None:
    b = Body(Vector(0, 0), kinematic=True)
    v = 1, 2
    assert b.local_to_world(v) == v and b.world_to_local(v) == v
    b.position = 3, 4
    assert b.local_to_world(v) == (4, 6)
    assert b.world_to_local(v) == (-2, -2)


def test_body_test_velocity_conversion() -> None:
    b = Body(Vector(0, 0), mass=1, moment=2)
    assert b.velocity_at_world_point((1, 1)) == (0, 0)
    assert b.velocity_at_local_point((1, 1)) == (0, 0)
    b.position = 1, 2
    b.angular_velocity = 1.2
    assert b.velocity_at_world_point((1, 1)) == (1.2, 0)
    assert b.velocity_at_local_point((1, 1)) == (-1.2, 1.2)


@pytest.mark.parametrize(("local", "torque"), [(False, -60), (True, -100)])
def test_body_test_force(local: bool, torque: float) -> None:
    # pymunk's force and torque until the step are own_acc * mass and torque here; the step
    # of dt takes them (v = F dt / m, omega = tau dt / I) and lets them go, as pymunk's.
    w = World()
    b = w.add(Body(Vector(3, 4), mass=1, moment=2))
    at = b.local_to_world((0, 10)) if local else Vector(0, 10)
    b.apply_force((10, 0), at=at)
    assert b.own_acc * b.mass == (10, 0)
    assert b.torque == torque
    w.step(0.5)
    assert b.velocity == (5, 0)
    assert b.angular_velocity == torque / 2 * 0.5
    assert b.own_acc == (0, 0) and b.torque == 0  # for that step only
    w.step(0.5)
    assert b.velocity == (5, 0) and b.angular_velocity == torque / 2 * 0.5


def test_body_test_impulse() -> None:
    b = Body(Vector(3, 4), mass=1, moment=2)
    b.apply_impulse((10, 0), at=(0, 10))
    assert b.velocity == (10, 0)
    assert b.angular_velocity == -30
    b = Body(Vector(3, 4), mass=1, moment=2)
    b.apply_impulse((10, 0), at=b.local_to_world((0, 10)))
    assert b.velocity == (10, 0)
    assert b.angular_velocity == -50


def test_body_test_sleep() -> None:
    # A body sleeps where it rests on another (test_body_test_sleep__alone): a second disc,
    # far off, that it could meet.
    w = World()
    w.sleep_time = 0.01
    disc(w, 50, 0)
    b = Body(Vector(0, 0), mass=1, moment=1, radius=1)
    assert not b.is_sleeping
    with pytest.raises(ValueError, match="this body is in none"):
        b.sleep()
    w.add(b)
    b.sleep()
    assert b.is_sleeping and w.sleeping == 1
    b.activate()
    assert not b.is_sleeping
    b.sleep()
    w.remove(b)
    assert not b.is_sleeping
    b.activate()
    assert not b.is_sleeping


@pytest.mark.xfail(
    strict=True,
    raises=ValueError,
    reason="bodies sleep where they rest on one another: in a World where no two bodies can "
    "meet, body.sleep() is refused, saying so; pymunk puts a lone body to sleep",
)
def test_body_test_sleep__alone() -> None:
    w = World()
    w.sleep_time = 0.01
    b = w.add(Body(Vector(0, 0), mass=1, moment=1, radius=1))
    b.sleep()
    assert b.is_sleeping


def test_body_test_sleep_with_group() -> None:
    # pymunk's sleep_with_group(b2) puts b1 in b2's sleeping group; here a body sleeps with
    # the bodies touching it, one group: two discs put into each other, parted by a step.
    w = World()
    w.sleep_time = 0.01
    b1 = Body(Vector(1.5, 0), mass=1, radius=1)
    with pytest.raises(ValueError, match="this body is in none"):
        b1.sleep()
    b2 = w.add(Body(Vector(0, 0), mass=2, radius=1))
    w.add(b1)
    w.step(0.01)
    assert [(e.body, e.collider) for e in w.touching] == [(b2, b1)]
    b1.sleep()
    assert b1.is_sleeping and b2.is_sleeping
    b2.activate()
    assert not b1.is_sleeping and not b2.is_sleeping


def test_body_test_kinetic_energy() -> None:
    # No body.kinetic_energy: world.energy() is the World's total, m v^2 / 2 + I w^2 / 2.
    w = World()
    b = w.add(Body(Vector(0, 0), mass=1, moment=10))
    assert w.energy() == 0
    b.apply_impulse((10, 0))
    assert w.energy() == 50
    b.angular_velocity = 2
    assert w.energy() == 50 + 20


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="the energy is m v^2 / 2; pymunk's kinetic_energy is Chipmunk's "
    "cpBodyKineticEnergy, m v^2 + I w^2, without the halves",
)
def test_body_test_kinetic_energy__without_the_half() -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), mass=1, moment=10))
    b.apply_impulse((10, 0))
    assert w.energy() == 100


def test_body_test_dynamic() -> None:
    b1 = Body(Vector(0, 0), mass=1, moment=1)
    b2 = Body(Vector(0, 0), mass=1, moment=1, kinematic=False)
    assert not b1.kinematic and not b2.kinematic
    b1.apply_impulse((1, 0))  # forces and impulses move it
    assert b1.velocity == (1, 0)


def test_body_test_kinematic() -> None:
    b = Body(Vector(0, 0), kinematic=True)
    assert b.kinematic
    with pytest.raises(ValueError, match="moved by the game and takes no impulse"):
        b.apply_impulse((1, 0))
    with pytest.raises(AttributeError, match="kinematic is fixed when it is made"):
        b.kinematic = False


def test_body_test_static() -> None:
    # No static Body: static geometry is colliders (world.add_collider), and a joint or link
    # holds a body to the World itself through world.static_body.
    w = World()
    s = w.static_body
    assert s is w.static_body and not isinstance(s, Body)
    w.add_force(Gravity((10, 0)))
    b = w.add(Body(Vector(0, -1), mass=1, moment=1))
    w.add_link(Rod(b, s, anchor_b=(0, 0)))  # a pendulum 1 long, hung at the origin
    xs = []
    for _ in range(60):
        w.step(1 / 60)
        assert b.pos.length() == pytest.approx(1, abs=1e-9)
        xs.append(b.pos.x)
    assert max(xs) > 0.99  # it swings through (1, 0), below the origin for that pull


def test_body_test_mass() -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), mass=2))
    for bad in (0, math.inf):
        with pytest.raises(ValueError, match="mass must be positive and finite"):
            b.mass = bad
    assert b.mass == 2
    w.remove(b)
    # pymunk takes a mass of 0 out of a Space and refuses the step; here it is refused at
    # once, in a World or not.
    with pytest.raises(ValueError, match="mass must be positive and finite"):
        b.mass = 0
    w.add(b)
    w.step(1)
    assert b.mass == 2
    # pymunk's fix, a shape's density set: here the Body's (its one shape), a mass of 10 pi.
    c = w.add(Body(Vector(5, 0), mass=2, shape=Circle((0, 0), 1)))
    c.density = 10
    w.step(1)
    assert c.mass == 10 * math.pi and c.moment == 5 * math.pi and c.density == 10


def test_body_test_moment() -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), mass=2, moment=3))
    with pytest.raises(ValueError, match="moment must be > 0"):
        b.moment = 0
    b.moment = math.inf  # fine: a body that never turns
    assert b.moment == math.inf and not b.turns
    w.remove(b)
    with pytest.raises(ValueError, match="moment must be > 0"):
        b.moment = 0  # refused at once, as the mass is
    w.add(b)
    w.step(1)
    assert b.moment == math.inf


def test_body_test_mass_moment_from_shape() -> None:
    # pymunk's Circle(b, 10) given mass 3, then 4: the body's mass is its shape's, and its
    # moment follows, m r^2 / 2 (pymunk's 200 at 4 kg). Here the body's mass is the Body's.
    w = World()
    b = w.add(Body(Vector(0, 0), mass=3, shape=Circle((0, 0), 10)))
    assert b.mass == 3 and b.moment == 150
    b.mass = 4
    assert b.mass == 4
    assert b.moment == 200


def test_body_test_mass_moment_from_shape__offset_circle() -> None:
    # pymunk's body takes an offset Circle(b, 10, (2, 3)) and moves its centre of gravity
    # there; here the body's position is its centre of gravity, so the body is there.
    b = Body(Vector(0, 0), mass=4, shape=Circle((2, 3), 10))
    assert b.moment == 200 and b.center_of_gravity == (2, 3)
    assert b.pos == (2, 3) and b.shape.center == (0, 0)


def test_body_test_shapes() -> None:
    # pymunk adds a Circle and a Segment to a body of mass 1 and moment 1, whose centre of
    # gravity stays at its origin: here the body is made of them (shapes=[...]), its centre of
    # gravity given where pymunk's is, so it holds the very shapes.
    s = World()
    s1, s2 = Circle((0, 0), 3), Segment((0, 0), (1, 2), 1)
    b1 = s.add(Body(Vector(0, 0), mass=1, moment=1, shapes=[s1, s2], center_of_gravity=(0, 0)))
    s3 = Circle((0, 0), 3)
    b2 = s.add(Body(Vector(0, 0), mass=1, moment=1, shape=s3))
    assert s1 in b1.shapes and s2 in b1.shapes
    assert s1 not in b2.shapes and s3 in b2.shapes


def test_body_test_each_arbiters() -> None:
    w = World()
    b1 = w.add(Body(Vector(0, 0), mass=1, moment=1, radius=10))
    b2 = w.add(Body(Vector(0, 0), mass=1, moment=1, radius=10))
    w.step(1)
    seen: list[ContactEvent] = [e for e in w.touching if b1 in (e.body, e.collider)]
    assert [(e.body, e.collider) for e in seen] == [(b1, b2)]


def test_body_test_constraints() -> None:
    w = World()
    b1 = w.add(Body(Vector(0, 0), mass=1, moment=1))
    b2 = Body(Vector(0, 0), mass=1, moment=1)
    j1 = Hinge(b1, w.static_body, (0, 0))
    j2 = Hinge(b2, w.static_body, (0, 0))
    assert b1 in j1.bodies and b2 not in j1.bodies and b2 in j2.bodies
    w.add_link(j1)
    assert [k for k in w.links if b1 in k.bodies] == [j1]
    assert [k for k in w.links if b2 in k.bodies] == []
    with pytest.raises(ValueError, match="bodies must be in this World first"):
        w.add_link(j2)  # pymunk lets b2 hold j2 outside the Space; here it is refused


def test_body_test_pickle() -> None:
    b = Body(
        Vector(3, 4),
        Vector(7, 8),
        mass=1,
        moment=2,
        angle=11,
        angular_velocity=12,
        torque=13,
        data="test",
    )
    b.own_acc = Vector(9, 10)  # pymunk's b.force = 9, 10 (on 1 kg), kept here until changed
    b2 = pickle.loads(pickle.dumps(b))
    assert (b2.mass, b2.moment, b2.kinematic, b2.data) == (1, 2, False, "test")
    assert (b2.position, b2.velocity, b2.own_acc) == ((3, 4), (7, 8), (9, 10))
    assert (b2.angle, b2.angular_velocity, b2.torque) == (11, 12, 13)
    w = World()
    w.add(b2)
    w.step(0.1)
    # Semi-implicit Euler for the position; the angle's constant torque in closed form.
    assert b2.velocity == pytest.approx((7.9, 9.0), abs=1e-12)
    assert b2.position == pytest.approx((3 + 0.79, 4 + 0.9), abs=1e-12)
    assert b2.angular_velocity == pytest.approx(12 + 6.5 * 0.1, abs=1e-12)
    assert b2.angle == pytest.approx(11 + 12 * 0.1 + 6.5 * 0.01 / 2, abs=1e-12)
    assert b.position == (3, 4)  # the original, in no World, unmoved


# ---- what is not ported, and why --------------------------------------------------------------

_CALLBACKS = (
    "no position_func or velocity_func: forces act through the World (world.add_force, "
    "engine.forces; apply_force for one step), and a body the game moves is "
    "Body(..., kinematic=True), whose pos or vel it writes"
)

#: pymunk tests whose concept this engine does not have, with the reason a user would accept.
MISSING: dict[str, str] = {
    "test_body.test_position_func": _CALLBACKS,
    "test_body.test_velocity_func": _CALLBACKS,
    "test_body.test_reset_callback_getters": _CALLBACKS,
    "test_body.test_reset_callbacks_stay_reset_after_copy": _CALLBACKS + "; what is left, "
    "that a copied World steps as the original, is test_pymunk_port.py's "
    "test_space_testCopyMethods",
    "test_body.test_custom_callbacks_can_be_reinstalled": _CALLBACKS,
    "test_body.test_pickle_circular_ref": "it copies a body whose position_func is bound to "
    "an object holding the Space: " + _CALLBACKS,
    "test_body.test_body_type_update": "skipped in pymunk itself; here a body's kinematic flag "
    "is fixed when it is made (body.kinematic = ... raises, saying to make a new Body), and "
    "there is no static Body to turn dynamic",
}


def _ported() -> set[str]:
    """The pymunk tests this file ports: 'test_body.name' from each test function's name."""
    out = set()
    for name in globals():
        if name.startswith("test_body_"):
            out.add("test_body." + name[len("test_body_") :].split("__")[0])
    return out


def test_every_pymunk_body_test_is_ported_or_listed() -> None:
    theirs = their_tests("test_body.py", lambda cls: "test_body" if cls == "UnitTestBody" else None)
    check_ported(theirs, _ported(), set(MISSING), least=20)
