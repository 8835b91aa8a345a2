"""Bodies with a shape (Body(..., shape=...)): boxes, polygons and capsules.

They turn (tests/test_rotation_shapes.py has what turning does); where a test is about a box
that keeps its angle it says ``fixed_rotation=True``.

Each is checked against the closed form or a theorem: a column of boxes lands and rests
with overlaps at most 1% of a box's height and sleeps; a box on a slope stays when
tan(theta) <= mu and otherwise slides at g (sin - mu cos); shapes meet with momentum kept to
1e-12 and the restitution rule; a kinematic box pushes and lifts; the errors name what to
write instead.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pygame
import pytest

from engine import Body, Box, Plane, Vector, World
from engine.forces import Gravity
from engine.geometry.colliders import Circle, Polygon, Segment
from engine.render.camera import Camera
from engine.render.world_view import ASLEEP, BACKGROUND, INK, draw_world

G = 9.81
DT = 1.0 / 60.0


def _world(floor_friction: float = 1.0) -> World:
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0), friction=floor_friction))
    return w


@pytest.fixture(scope="module")
def column() -> tuple[World, list[Body], list[float]]:
    """Ten unit boxes that do not turn (``fixed_rotation``; the column of boxes that turn is
    in tests/test_rotation_shapes.py) dropped in a column (each 0.1 m above the one below,
    2 cm to the side), stepped 4 s: the world, the boxes, and the deepest overlap of any
    step after 1 s."""
    w = _world()
    boxes = [
        w.add(
            Body(
                Vector(0.02 * k, 0.6 + 1.1 * k),
                shape=Polygon.box(1.0, 1.0),
                restitution=0.0,
                friction=0.5,
                fixed_rotation=True,
            )
        )
        for k in range(10)
    ]
    deepest: list[float] = []
    for _i in range(240):
        w.step(DT)
        y = np.array([b.pos.y for b in boxes])
        over = max(float(-(np.diff(y) - 1.0).min()), 0.5 - float(y[0]))
        if w.t > 1.0:
            deepest.append(over)
    return w, boxes, deepest


def test_a_column_of_ten_boxes_lands_rests_within_1_percent_and_sleeps(
    column: tuple[World, list[Body], list[float]],
) -> None:
    w, boxes, deepest = column
    assert max(deepest) <= 0.01  # of a box's height (1 m)
    assert w.sleeping == 10
    assert all(b.vel == Vector(0.0, 0.0) for b in boxes)
    # Stacked in order, each on the one below (no turning: the 2 cm offsets stay).
    y = np.array([b.pos.y for b in boxes])
    assert np.all(np.abs(np.diff(y) - 1.0) <= 0.01)
    assert [b.pos.x for b in boxes] == pytest.approx([0.02 * k for k in range(10)], abs=1e-9)
    # Asleep, they stay exactly put.
    before = [b.pos for b in boxes]
    for _ in range(30):
        w.step(DT)
    assert [b.pos for b in boxes] == before


def test_the_column_is_drawn_as_boxes(column: tuple[World, list[Body], list[float]]) -> None:
    w, boxes, _ = column
    pygame.init()
    surface = pygame.Surface((200, 400))
    surface.fill(BACKGROUND)
    camera = Camera.fit((-2.0, -0.5, 2.0, 11.0), (0, 0, 200, 400))
    draw_world(surface, w, camera)
    # The middle of each box is filled with the asleep colour, its corners' outside is not:
    # a square, not the circle of its bounding radius (which would cover the gap beside it).
    for b in boxes:
        cx, cy = camera.point((b.pos.x, b.pos.y))
        assert tuple(surface.get_at((cx, cy)))[:3] == ASLEEP
        right = camera.point((b.pos.x + 0.6, b.pos.y))  # outside the box, inside the circle
        assert tuple(surface.get_at(right))[:3] == BACKGROUND
        edge = camera.point((b.pos.x + 0.5, b.pos.y))
        near = [tuple(surface.get_at((edge[0] + d, edge[1])))[:3] for d in (-1, 0, 1)]
        assert INK in near


@pytest.mark.parametrize(("degrees", "mu"), [(20.0, 0.5), (26.0, 0.5), (30.0, 0.5), (45.0, 0.2)])
def test_a_box_on_a_slope_stays_or_slides_at_g_sin_minus_mu_cos(degrees: float, mu: float) -> None:
    theta = math.radians(degrees)
    n = (-math.sin(theta), math.cos(theta))
    down = Vector(-math.cos(theta), -math.sin(theta))  # along the slope, downhill
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), n, friction=1.0))
    # A unit box that does not turn (fixed_rotation: a box that turns, set on one corner,
    # topples onto a face, its weight acting beside its one point of support; the box that
    # turns lies flat on its slope in tests/test_rotation_shapes.py) touches the slope with
    # one corner: placed with its lowest corner (along the normal) on the plane.
    lowest = min(
        (Vector(sx * 0.5, sy * 0.5) for sx in (-1, 1) for sy in (-1, 1)),
        key=lambda c: c.x * n[0] + c.y * n[1],
    )
    box = w.add(Body(-lowest, shape=Polygon.box(1.0, 1.0), friction=mu, restitution=0.0,
                     fixed_rotation=True))  # fmt: skip
    for _ in range(30):  # settle onto the corner
        w.step(DT)
    t0, v0 = w.t, box.vel.dot(down)
    for _ in range(120):
        w.step(DT)
    a = (box.vel.dot(down) - v0) / (w.t - t0)
    want = G * (math.sin(theta) - mu * math.cos(theta))
    if want <= 0.0:
        assert box.vel == Vector(0.0, 0.0) or abs(box.vel) <= 1e-9
    else:
        assert a == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("other", ["disc", "capsule", "box", "pentagon"])
def test_shapes_meet_with_momentum_kept_and_restitution_along_the_normal(other: str) -> None:
    # No gravity, no walls: a box (2 kg) at 3 m/s head-on into a body (0.7 kg) at -1 m/s;
    # the normal is x. Momentum is kept to 1e-12; the relative normal speed after is e times
    # what it was (e = e_a e_b = 0.8 x 0.9), the tangential one untouched without friction.
    # That is the law of the centres' speeds for bodies that do not turn (fixed_rotation: the
    # pentagon meets the box at a corner 0.1 m off its centre, and a body that turns takes
    # some of the impulse as spin; tests/test_rotation_shapes.py has an off-centre impact of
    # a box that turns against its closed form).
    w = World(integrator="auto")
    a = w.add(
        Body(Vector(0.0, 0.0), Vector(3.0, 0.5), shape=Polygon.box(1.0, 0.6), mass=2.0,
             restitution=0.8, friction=0.0, fixed_rotation=True)
    )  # fmt: skip
    shape = {
        "disc": None,
        "capsule": Segment((0.0, -0.3), (0.0, 0.3), 0.2),
        "box": Polygon.box(0.5, 0.5),
        "pentagon": Polygon([(-0.3, -0.3), (0.3, -0.3), (0.4, 0.1), (0.0, 0.4), (-0.4, 0.1)]),
    }[other]
    kw = {"radius": 0.3} if shape is None else {"shape": shape}
    b = w.add(Body(Vector(2.0, 0.0), Vector(-1.0, 0.5), mass=0.7, restitution=0.9,
                   friction=0.0, fixed_rotation=True, **kw))  # fmt: skip
    p0 = a.mass * a.vel + b.mass * b.vel
    scale = a.mass * abs(a.vel) + b.mass * abs(b.vel)
    began = []
    for _ in range(60):
        w.step(DT)
        began += w.began
        assert abs(a.mass * a.vel + b.mass * b.vel - p0) <= 1e-12 * scale
    assert [(e.body, e.collider) for e in began] == [(a, b)]
    assert b.vel.x - a.vel.x == pytest.approx(0.72 * 4.0, rel=1e-9)
    assert a.vel.y == b.vel.y == 0.5


def test_a_kinematic_box_pushes_a_ball_and_a_platform_lifts_one() -> None:
    w = _world(floor_friction=0.0)
    pusher = w.add(
        Body(Vector(0.0, 0.5), Vector(1.0, 0.0), shape=Polygon.box(1.0, 1.0), kinematic=True)
    )
    ball = w.add(Body(Vector(1.2, 0.3), radius=0.3, friction=0.0, restitution=0.0))
    lift = w.add(
        Body(Vector(-5.0, 0.1), Vector(0.0, 0.5), shape=Polygon.box(2.0, 0.2), kinematic=True)
    )
    rider = w.add(Body(Vector(-5.0, 0.45), radius=0.25, restitution=0.0))
    for _ in range(120):
        w.step(DT)
    assert pusher.pos.x == pytest.approx(2.0, rel=1e-12)  # the game's path, whatever it hit
    assert ball.pos.x - pusher.pos.x == pytest.approx(0.8, abs=0.005)  # pushed ahead, touching
    assert ball.vel.x == pytest.approx(1.0, abs=0.01)
    assert lift.pos.y == pytest.approx(1.1, rel=1e-12)
    assert rider.pos.y - lift.pos.y == pytest.approx(0.35, abs=0.005)  # carried up on it
    assert rider.vel.y == pytest.approx(0.5, abs=0.01)


def test_a_box_lands_on_the_floor_with_one_began_event() -> None:
    w = _world()
    floor = w.colliders[0]
    box = w.add(Body(Vector(0.0, 2.0), shape=Polygon.box(1.0, 0.5), restitution=0.0))
    events = []
    for _ in range(120):
        w.step(DT)
        events += [(e.body, e.collider) for e in w.began]
    assert events == [(box, floor)]
    assert box.pos.y == pytest.approx(0.25, abs=0.005) and w.is_sleeping(box)


def test_a_body_shape_is_checked_and_the_errors_say_what_to_write() -> None:
    with pytest.raises(TypeError, match=r"is a room .* shape=Polygon.box\(width, height\)"):
        Body(Vector(0.0, 0.0), shape=Box((0.0, 0.0), (1.0, 1.0)))
    with pytest.raises(TypeError, match="radius=... or shape=..., not both"):
        Body(Vector(0.0, 0.0), radius=0.5, shape=Polygon.box(1.0, 1.0))
    with pytest.raises(ValueError, match="are the Body's"):
        Body(Vector(0.0, 0.0), shape=Polygon.box(1.0, 1.0, friction=0.2))
    with pytest.raises(ValueError, match=r"centred on its position, .*: Circle\(\(0, 0\), 1.0\)"):
        Body(Vector(0.0, 0.0), shape=Circle((1.0, 0.0), 1.0), kinematic=True)
    with pytest.raises(TypeError, match="cannot be a body's shape"):
        Body(Vector(0.0, 0.0), shape=Plane((0.0, 0.0), (0.0, 1.0)))
    with pytest.raises(TypeError, match="only a 2D body"):
        Body(0.0, shape=Polygon.box(1.0, 1.0))
    with pytest.raises(TypeError, match="shape must be"):
        Body(Vector(0.0, 0.0), shape="box")
    b = Body(Vector(0.0, 0.0), shape=Polygon.box(2.0, 1.0))
    assert b.radius == pytest.approx(math.hypot(1.0, 0.5))  # the circle that holds it
    with pytest.raises(AttributeError, match="fixed when it is made"):
        b.shape = Polygon.box(1.0, 1.0)  # type: ignore[misc]
    # A round shape is a disc: the same as radius=.
    assert Body(Vector(0.0, 0.0), shape=Circle((0.0, 0.0), 0.5)).radius == 0.5


@pytest.mark.parametrize("speed", [10.0, 100.0, 1000.0])
@pytest.mark.parametrize("other", ["thin box", "capsule", "disc", "thin wall"])
def test_fast_shapes_never_pass_through_each_other_or_a_thin_wall(speed: float, other: str) -> None:
    # A box thrown head-on at a body coming the other way (or at a thin static wall), from
    # gaps that the two close within one step and from farther: elastic, frictionless, so
    # they come apart at their speeds of approach, and the box is never past the other.
    # Bodies that do not turn (fixed_rotation): the target is 0.1 m off the box's centre
    # line, and a box that turns takes part of the impulse as spin (see
    # tests/test_rotation_shapes.py for that impact's closed form).
    for gap in (0.35, 0.9 * 2.0 * speed * DT, 1.3 * 2.0 * speed * DT, 2.5 * 2.0 * speed * DT):
        w = World(integrator="auto")
        box = w.add(Body(Vector(0.0, 0.0), Vector(speed, 0.0), shape=Polygon.box(0.5, 0.5),
                         restitution=1.0, friction=0.0, fixed_rotation=True))  # fmt: skip
        x_far = 0.25 + gap + 0.05
        if other == "thin wall":
            w.add_collider(Segment((x_far, -5.0), (x_far, 5.0)))
            target = None
        else:
            shape = {
                "thin box": Polygon.box(0.1, 0.5),
                "capsule": Segment((0.0, -0.2), (0.0, 0.2), 0.05),
                "disc": None,
            }[other]
            kw = {"radius": 0.05} if shape is None else {"shape": shape}
            target = w.add(Body(Vector(x_far, 0.1), Vector(-speed, 0.0), restitution=1.0,
                                friction=0.0, fixed_rotation=True, **kw))  # fmt: skip
        for _ in range(int(gap / speed / DT) + 4):
            w.step(DT)
            assert box.pos.x < (x_far if target is None else target.pos.x)
        assert box.vel.x == pytest.approx(-speed, rel=1e-9)
        if target is not None:
            assert target.vel.x == pytest.approx(speed, rel=1e-9)


def _apex_and_stop(dt: float) -> tuple[float, float]:
    """A 1 m box dropped from 1 m (e 0.5): the first apex after the bounce (m, its bottom);
    and one sliding from 5 m/s with mu 0.5: where it stops (m)."""
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -9.81)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    drop = w.add(Body(Vector(0.0, 1.5), shape=Polygon.box(1.0, 1.0), restitution=0.5,
                      friction=0.0))  # fmt: skip
    slide = w.add(Body(Vector(5.0, 0.5), Vector(5.0, 0.0), shape=Polygon.box(1.0, 1.0),
                       restitution=0.0, friction=0.5))  # fmt: skip
    apex, rose = math.nan, False
    for _ in range(round(2.0 / dt)):
        w.step(dt)
        rose = rose or drop.vel.y > 0.0
        if rose and math.isnan(apex) and drop.vel.y <= 0.0:
            apex = drop.pos.y - 0.5
    return apex, slide.pos.x - 5.0


def test_a_box_bounces_at_a_step_and_slides_to_its_stop_as_the_readme_says() -> None:
    # A shape's bounce is the soft step's, at a step (not the discs' exact moment): below the
    # closed form's apex h e^2 = 0.25 m, nearer to it at a smaller dt; sliding, it stops
    # within 1% of v0^2 / (2 mu g).
    coarse, stop = _apex_and_stop(1 / 60)
    fine, _ = _apex_and_stop(1 / 240)
    assert 0.2 < coarse < fine <= 0.25
    closed = 5.0**2 / (2 * 0.5 * 9.81)
    assert abs(stop / closed - 1) < 0.01
    readme = " ".join((Path(__file__).parent.parent / "README.md").read_text().split())
    said = (
        f"rises to {coarse:.4f} m at dt = 1/60 (the closed form 0.25; {fine:.4f} at dt = "
        f"1/240), and a box sliding at 5 m/s with mu = 0.5 stops {100 * (1 - stop / closed):.3f}%"
    )
    assert said in readme, said


def test_world_overlap_measures_shapes_not_their_bounding_circles() -> None:
    # Two 1 m boxes side by side 0.9 m apart overlap by 0.1 m (their bounding circles, of
    # radius sqrt(0.5), by 0.51 m); turned by 45 degrees, the corner of one reaches
    # 0.5 + sqrt(0.5) from its centre, into the other's face at 0.9 - 0.5.
    w = World()
    w.add(Body(Vector(0, 0), shape=Polygon.box(1, 1)))
    b = w.add(Body(Vector(0.9, 0), shape=Polygon.box(1, 1)))
    w.add(Body(Vector(5, 0), radius=0.5))
    disc = w.add(Body(Vector(5.8, 0), radius=0.5))
    assert w.overlap() == pytest.approx(0.2, abs=1e-12)  # the discs, deeper
    disc.pos = Vector(6.5, 0)
    assert w.overlap() == pytest.approx(0.1, abs=1e-12)
    b.angle = math.pi / 4
    assert w.overlap() == pytest.approx(0.5 + math.sqrt(0.5) - 0.9, abs=1e-12)
    b.pos = Vector(3, 3)
    assert w.overlap() == 0.0
    # A long platform (a body far larger than the rest) is measured against every body.
    w.add(Body(Vector(0, -0.9), shape=Polygon.box(20, 1), kinematic=True))
    assert w.overlap() == pytest.approx(0.1, abs=1e-12)  # the first box sits 0.1 into it
