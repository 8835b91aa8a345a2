"""A body's shapes about its centre of mass (engine.body_shapes): a dynamic body given a shape
drawn off the origin of its frame is held about the shape's centroid and is there, so it turns
about its centre of mass; a kinematic body turns about its position; a body weighted off its
centroid is given its ``center_of_gravity``. Checked against the closed forms of free rotation,
a triangle's moment and a physical pendulum's period, on both solvers and both paths."""

from __future__ import annotations

import math

import pytest
import swings
from paths import PATHS

from engine import Body, Hinge, Polygon, Segment, Vector, World
from engine.forces import Gravity

SOLVERS = ["exact", "soft"]


def _turned(angle: float, x: float, y: float) -> tuple[float, float]:
    c, s = math.cos(angle), math.sin(angle)
    return c * x - s * y, s * x + c * y


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("solver", SOLVERS)
def test_a_free_box_drawn_off_its_origin_spins_about_its_centre(solver: str, kernels: str) -> None:
    # A 2 x 2 box drawn about (2, 0), spinning at 1 rad/s with no force on it: its centre stays
    # at (2, 0) and the frame it was drawn in turns about it. (It turned about the frame's
    # origin, and its centre went round a circle of 2 m with nothing pushing it.)
    w = World(kernels=kernels, solver=solver)
    b = w.add(Body(Vector(0, 0), shape=Polygon.box(2, 2, center=(2, 0)), mass=3.0,
                   angular_velocity=1.0))  # fmt: skip
    assert b.pos == (2, 0) and b.center_of_gravity == (2, 0)
    assert b.moment == pytest.approx(3.0 * 8.0 / 12.0, rel=1e-12)  # about the centre
    steps = 189  # a little over half a turn at dt 1/60
    for _ in range(steps):
        w.step(1 / 60)
    assert b.pos == (2, 0) and b.vel == (0, 0)
    assert b.angle == pytest.approx(steps / 60, rel=1e-12)
    origin = b.local_to_world(-b.center_of_gravity)
    ox, oy = _turned(b.angle, -2.0, 0.0)
    assert origin.x == pytest.approx(2.0 + ox, abs=1e-12)
    assert origin.y == pytest.approx(oy, abs=1e-12)


def test_the_frame_given_is_put_at_the_position_turned_by_the_angle() -> None:
    # A capsule drawn from its end: the body's position is its middle, the end where it was put.
    at, angle = Vector(1.0, 1.0), 0.7
    b = Body(at, shape=Segment((0, 0), (2, 0), 0.1), angle=angle)
    cx, cy = _turned(angle, 1.0, 0.0)
    assert b.pos.x == pytest.approx(1.0 + cx, abs=1e-15)
    assert b.pos.y == pytest.approx(1.0 + cy, abs=1e-15)
    assert tuple(b.shape.a) == (-1.0, 0.0) and tuple(b.shape.b) == (1.0, 0.0)
    end = b.local_to_world(-b.center_of_gravity)
    assert end.x == pytest.approx(1.0, abs=1e-15) and end.y == pytest.approx(1.0, abs=1e-15)
    # A shape centred on its origin is held as it was given, the very object.
    box = Polygon.box(1, 1)
    assert Body(at, shape=box).shape is box and Body(at, shape=box).pos == at


@pytest.mark.parametrize("kernels", PATHS)
def test_origin_is_the_frame_s_origin_read_and_written_as_pymunk_s_position(
    kernels: str,
) -> None:
    # pymunk's body.position is the origin of the frame its shapes are drawn in; here
    # body.origin, where pos is the centre of mass. Written, the body moves so that the
    # origin is there, at its angle.
    w = World(kernels=kernels, solver="soft")
    b = w.add(Body(Vector(1, 2), shape=Segment((0, 0), (2, 0), 0.1), angle=0.5))
    assert b.origin.x == pytest.approx(1.0, abs=1e-15)
    assert b.origin.y == pytest.approx(2.0, abs=1e-15)
    b.origin = (5, 5)
    cx, cy = _turned(0.5, 1.0, 0.0)
    assert b.pos.x == pytest.approx(5 + cx, abs=1e-15) and b.pos.y == pytest.approx(
        5 + cy, abs=1e-15
    )
    assert (b.origin - Vector(5, 5)).length() < 1e-14
    with pytest.raises(TypeError, match="origin must be"):
        b.origin = "here"


def test_a_triangle_drawn_from_its_corner_has_its_mass_centre_and_moment() -> None:
    # The right triangle (0, 0), (4, 0), (0, 3) at density 2: mass 12 kg, centroid (4/3, 1), and
    # about it I = m (a^2 + b^2 + c^2) / 36 with sides 3, 4 and 5 (pymunk's moment with its
    # centre of gravity there).
    b = Body(Vector(0, 0), shape=Polygon([(0, 0), (4, 0), (0, 3)]), density=2.0)
    assert b.mass == pytest.approx(12.0, rel=1e-15)
    assert b.center_of_gravity.x == pytest.approx(4 / 3, rel=1e-15)
    assert b.center_of_gravity.y == pytest.approx(1.0, rel=1e-15)
    assert b.moment == pytest.approx(12.0 * 50.0 / 36.0, rel=1e-12)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_kinematic_arm_turns_about_its_position(kernels: str) -> None:
    # A windmill's arm drawn from the hub: the game turns it about the hub, where it put it.
    w = World(kernels=kernels, solver="soft")
    arm = w.add(Body(Vector(3, 1), shape=Segment((0, 0), (2, 0), 0.1), kinematic=True,
                     angular_velocity=2.0))  # fmt: skip
    assert arm.center_of_gravity == (0, 0) and tuple(arm.shape.b) == (2.0, 0.0)
    for _ in range(30):
        w.step(1 / 60)
    assert arm.pos == (3, 1)
    tip = arm.local_to_world(arm.shape.b)
    tx, ty = _turned(1.0, 2.0, 0.0)  # 2 rad/s for 0.5 s
    assert tip.x == pytest.approx(3.0 + tx, abs=1e-12)
    assert tip.y == pytest.approx(1.0 + ty, abs=1e-12)


def test_a_body_weighted_off_its_centroid_is_given_its_centre_of_gravity() -> None:
    bat = Polygon([(0, -1.2), (8, -0.6), (8, 0.6), (0, 1.2)])
    weighted = Body(Vector(5, 5), shape=bat, mass=150.0, center_of_gravity=(0, 0))
    assert weighted.pos == (5, 5) and weighted.shape is bat
    assert weighted.moment == bat.moment(150.0)  # the shape's about its given centre
    uniform = Body(Vector(5, 5), shape=bat, mass=150.0)
    c = bat.centroid
    assert uniform.moment == pytest.approx(bat.moment(150.0) - 150.0 * (c.x**2 + c.y**2), rel=1e-12)
    with pytest.raises(ValueError, match="kinematic body turns about its position"):
        Body(Vector(0, 0), shape=bat, kinematic=True, center_of_gravity=(1, 0))
    with pytest.raises(ValueError, match="round body turns about its centre"):
        Body(Vector(0, 0), radius=1.0, center_of_gravity=(0.5, 0))
    with pytest.raises(TypeError, match="center_of_gravity must be"):
        Body(Vector(0, 0), shape=bat, center_of_gravity="pivot")
    with pytest.raises(AttributeError, match="follows from its shape"):
        weighted.center_of_gravity = (1, 0)


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("solver", SOLVERS)
def test_a_rod_hung_from_its_end_swings_as_a_physical_pendulum(solver: str, kernels: str) -> None:
    # A uniform rod of length 2 (1 kg) drawn from its end, hung there on a Hinge, let go 0.05
    # rad from hanging straight down: its weight acts at its middle, so it swings with the
    # period T = 2 pi sqrt(I_p / (m g d)) (1 + theta0^2 / 16), I_p = m L^2 / 3, d = 1. (Weighted
    # at the end it hung from, it did not swing at all.)
    g, theta0, dt = 9.81, 0.05, 1 / 240
    w = World(kernels=kernels, solver=solver)
    w.add_force(Gravity((0.0, -g)))
    angle = -math.pi / 2 + theta0
    rod = w.add(Body(Vector(0, 0), shape=Segment((0, 0), (2, 0)), mass=1.0, angle=angle))
    w.add_link(Hinge(rod, w.static_body, (0, 0)))
    period = 2 * math.pi * math.sqrt((4 / 3) / g) * (1 + theta0**2 / 16)
    # A period is between two crossings of zero of the angular velocity, going down.
    crossings = swings.crossings(w, rod, dt, 3.5 * period)
    assert len(crossings) >= 3, crossings
    # Measured: exact -5.3e-6, soft -2.1e-7 (the amplitude's term alone is 1.6e-4).
    assert crossings[1] - crossings[0] == pytest.approx(period, rel=2e-5)
    # The hinge holds the end where it was hung: the exact models to rounding, the soft step's
    # joint (a stiff spring) within 0.07 mm, measured.
    pivot = rod.local_to_world(-rod.center_of_gravity)
    assert pivot.length() < (1e-9 if solver == "exact" else 1e-4)
