"""Kinematic bodies that the game turns: a windmill, a turntable, a tumbler's walls.

A kinematic body takes an ``angular_velocity`` (rad/s) as it takes a ``vel``, and writing its
``angle`` turns it there over the next step, as writing its ``pos`` moves it; contacts see its
points move at v + omega x r and take its moment as infinite.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pygame
import pytest

from demos.stack import TUMBLE, TUMBLE_STRESS, TUMBLED_SIDE, into_walls, outside, tumbler
from engine import Body, Polygon, Vector, World
from engine.forces import Gravity
from engine.render.camera import Camera
from engine.render.world_view import BACKGROUND, KINEMATIC, draw_world
from engine.stability import StabilityWarning

DT = 1.0 / 60.0


def test_a_kinematic_body_turns_at_the_angular_velocity_the_game_gives() -> None:
    w = World()
    mill = w.add(Body(Vector(1, 2), shape=Polygon.box(4, 0.2), kinematic=True))
    assert not mill.turns  # nothing turns it but the game
    mill.angular_velocity = 3.0
    for _ in range(100):
        w.step(DT)
    assert mill.angle == pytest.approx(3.0 * 100 * DT, rel=1e-12)
    assert mill.angular_velocity == 3.0
    assert tuple(mill.pos) == (1.0, 2.0)  # turning about its position


def test_writing_a_kinematic_bodys_angle_turns_it_there_over_the_next_step() -> None:
    w = World()
    paddle = w.add(Body(Vector(0, 0), shape=Polygon.box(2, 0.2), kinematic=True))
    paddle.angular_velocity = 1.0
    paddle.angle = 0.5
    assert paddle.angle == 0.0  # not there yet: the next step takes it there
    w.step(DT)
    assert paddle.angle == pytest.approx(0.5, abs=1e-15)
    assert paddle.angular_velocity == 1.0  # then it goes on as it was told
    w.step(DT)
    assert paddle.angle == pytest.approx(0.5 + DT, abs=1e-15)
    # A ball in the way is struck at the speed the turn takes (omega = 0.5 / dt at 1 m).
    w2 = World()
    bat = w2.add(Body(Vector(0, 0), shape=Polygon.box(2.0, 0.2), kinematic=True,
                      restitution=1.0))  # fmt: skip
    ball = w2.add(Body(Vector(0.8, 0.25), radius=0.1, restitution=1.0, friction=0.0))
    bat.angle = 0.2
    w2.step(DT)
    assert ball.vel.y > 0.2 / DT * 0.5  # knocked up, at least by the bat's own speed there


def test_a_kinematic_body_refuses_a_torque_and_a_1d_one_any_turn() -> None:
    with pytest.raises(ValueError, match="set its angular_velocity"):
        Body(Vector(0, 0), radius=1.0, kinematic=True, torque=1.0)
    b = Body(Vector(0, 0), radius=1.0, kinematic=True)
    with pytest.raises(ValueError, match="turned by the game, not by a torque"):
        b.torque = 2.0
    with pytest.raises(ValueError, match="1D body does not turn"):
        Body(0.0, 0.0, 0.0, kinematic=True, angular_velocity=1.0)


@pytest.mark.parametrize("e", [1.0, 0.5])
def test_a_turning_bat_knocks_a_ball_off_at_one_plus_e_times_its_speed_there(e: float) -> None:
    # A kinematic bat turning at omega meets a ball at rest d from its pivot: along the normal
    # the ball leaves at (1 + e) omega d (the bat's infinite moment keeps its spin).
    omega, d = 5.0, 0.8
    w = World()
    bat = w.add(Body(Vector(0, 0), shape=Polygon.box(2.0, 0.2), kinematic=True,
                     angular_velocity=omega, restitution=1.0))  # fmt: skip
    ball = w.add(Body(Vector(d, 0.25), radius=0.1, restitution=e, friction=0.0))
    for _ in range(30):
        w.step(DT)
    assert bat.angular_velocity == omega
    assert ball.vel.x == pytest.approx(0.0, abs=1e-9)
    assert ball.vel.y == pytest.approx((1 + e) * omega * d, rel=1e-9)


def test_a_crate_rides_a_turntable_turning_with_it() -> None:
    # A crate on a platform that tilts at 0.3 rad/s about the crate's own centre line stays
    # put on it (tan(0.3) < mu), turning with it: its angle and its place in the platform's
    # frame hold while the platform turns 0.3 rad.
    w = World(integrator="auto")
    w.add_force(Gravity((0, -9.81)))
    table = w.add(Body(Vector(0, 0), shape=Polygon.box(4, 0.2), kinematic=True))
    crate = w.add(Body(Vector(0, 0.35), shape=Polygon.box(0.5, 0.5), friction=0.8,
                       restitution=0.0))  # fmt: skip
    for _ in range(30):
        w.step(DT)  # settle
    table.angular_velocity = 0.3
    start = table.world_to_local(crate.pos)
    for _ in range(60):
        w.step(DT)
    assert table.angle == pytest.approx(0.3, rel=1e-12)
    assert crate.angle == pytest.approx(table.angle, abs=2e-3)
    place = table.world_to_local(crate.pos)
    assert abs(place - start) < 2e-3
    assert not w.is_sleeping(crate)  # what a kinematic body touches does not sleep


def test_snapshot_keeps_a_kinematic_turn_in_progress() -> None:
    w = World()
    paddle = w.add(Body(Vector(0, 0), shape=Polygon.box(2, 0.2), kinematic=True))
    paddle.angular_velocity = 2.0
    w.step(DT)
    paddle.angle = 1.0  # to be reached over the next step
    snap = w.snapshot()
    w.step(DT)
    w.step(DT)
    after = (paddle.angle, paddle.angular_velocity)
    w.restore(snap)
    assert paddle.angle == pytest.approx(2.0 * DT)
    w.step(DT)
    w.step(DT)
    assert (paddle.angle, paddle.angular_velocity) == after
    assert after[0] == pytest.approx(1.0 + 2.0 * DT)
    bad = dataclasses.replace(w.snapshot(), turns=((0, math.nan),))
    with pytest.raises(ValueError, match="snapshot.turns holds"):
        w.restore(bad)
    assert (paddle.angle, paddle.angular_velocity) == after  # the bad one changed nothing


#: Seconds the tumbler turns (s): at 90 degrees a second two whole turns, eight times the pile
#: slides from one wall to the next (the scene repeats a quarter turn apart; 20 s took over four
#: minutes on numpy); at 25 degrees a second the pile lands, is carried up and tumbles down
#: (its deepest overlap came at 6.4 s of 20). Half as long on numpy, where it costs six times
#: more (CI runs the suite on both paths and its time is near its budget; both paths give the
#: same numbers to rounding).
TUMBLED_FOR = 8.0 if World().kernels == "fast" else 4.0


@pytest.fixture(
    scope="module",
    params=[
        pytest.param(TUMBLE, id="25-degrees-a-second"),
        pytest.param(
            TUMBLE_STRESS,
            id="90-degrees-a-second",
            marks=pytest.mark.skipif(
                World().kernels != "fast", reason="the stress scene on the fast path alone"
            ),
        ),
    ],
)
def tumbled(
    request: pytest.FixtureRequest,
) -> tuple[World, list[Body], list[Body], float, int, float]:
    """Box2D's tumbler (shared/anchors/box2d): 500 boxes of 0.25 m in a 19 m room whose
    walls turn at 25 degrees a second (Box2D's benchmark) or 90 (the stress scene), for
    TUMBLED_FOR s: (world, boxes, walls, the deepest any box's corner went past a wall's inner
    face (m), boxes whose centre ever went past one, the deepest overlap of two bodies (m))."""
    w, boxes, walls = tumbler(spin=request.param, solver="exact")
    deepest, out = -math.inf, np.zeros(len(boxes), dtype=bool)
    overlap = 0.0
    with warnings.catch_warnings():
        # The landing and the avalanches overlap boxes by more than the pile's warning
        # level (5% of the smallest radius), as the stack demo's read-out shows; what this
        # scene checks is that none is lost through a wall.
        warnings.simplefilter("ignore", StabilityWarning)
        for _ in range(round(TUMBLED_FOR / DT)):
            w.step(DT)
            deepest = max(deepest, into_walls(boxes, walls))
            out |= outside(boxes, walls)
            overlap = max(overlap, w.overlap())
    return w, boxes, walls, deepest, int(out.sum()), overlap


def test_the_tumbler_loses_no_box_into_its_turning_walls(
    tumbled: tuple[World, list[Body], list[Body], float, int, float],
) -> None:
    # The issue "Bodies that turn": no box ever ends a step inside a wall. pymunk 7.3.1 on
    # this scene at 90 degrees a second (demos.bench.tumbler's twin): 104 boxes' centres past
    # a wall in 8 s, 94 out at 8 s (136 and 97 in 20 s). Box2D v3 (617d32ab, 4 substeps;
    # shared/anchors/box2d, 20 s): none at the end, but centres past a wall's inner face during
    # the run (up to 10 at once at 90 degrees a second, 3 at 25), a corner 293 mm (254 mm)
    # into a wall. Here no centre ever passes a wall's inner face and no corner goes 0.1 m
    # past it (at 90: 59 mm in 8 s, 69 mm in 20 s).
    w, boxes, walls, deepest, lost, _ = tumbled
    assert lost == 0
    assert deepest < 0.1
    assert walls[0].angle == pytest.approx(walls[0].angular_velocity * w.t, rel=1e-12)
    assert walls[0].angular_velocity in (TUMBLE, TUMBLE_STRESS)
    assert all(math.isfinite(b.pos.x) and math.isfinite(b.angle) for b in boxes)


@pytest.mark.xfail(
    strict=True,
    reason="92 mm at 25 degrees a second (the issue's target is 25 mm, 10% of a side; Box2D "
    "v3 itself went 274 mm): at 6.37 s a box spinning at 11 rad/s (25 after) swings a corner "
    "24 degrees in the step into its neighbour, a corner that was no point of the pair's "
    "contact at the step's start (it had one, 16 mm deep) and so has no row in the step",
)
def test_no_two_bodies_of_the_tumbler_overlap_by_a_tenth_of_a_side(
    tumbled: tuple[World, list[Body], list[Body], float, int, float],
) -> None:
    # The issue "Rigid bodies as Box2D's own tests expect": at either speed no two boxes
    # overlap by more than 10% of a side. Measured (``World.overlap``, two boxes or a box and
    # a wall, the deepest after any step): at 25 degrees a second 92 mm in 20 s (at 6.4 s), at
    # 90 234 mm (at 1.4 s). Box2D v3 (617d32ab, 4 substeps, its contacts' separations after
    # each step, 20 s): two boxes 274 mm into each other at 25 and 266 mm at 90, a box 254
    # and 293 mm into a wall, where boxes carried up fall 19 m onto the pile; 3 to 7 cm in the
    # pile at rest on a wall.
    *_, overlap = tumbled
    assert overlap <= 0.1 * TUMBLED_SIDE


def test_a_turned_kinematic_body_is_drawn_at_its_angle() -> None:
    # A 4 x 0.4 m plank turned a quarter turn stands upright: 1.5 m above its centre is
    # plank, 1.5 m to its right is paper (and the other way round before it turned).
    w = World()
    plank = w.add(Body(Vector(0, 0), shape=Polygon.box(4, 0.4), kinematic=True))
    cam = Camera(scale=20.0, origin=(60.0, 60.0))
    surface = pygame.Surface((120, 120))

    def colour_at(x: float, y: float) -> tuple[int, ...]:
        surface.fill(BACKGROUND)
        draw_world(surface, w, cam)
        px, py = cam.to_px(x, y)
        return tuple(surface.get_at((round(px), round(py))))[:3]

    assert colour_at(1.5, 0.0) == tuple(KINEMATIC)[:3]
    assert colour_at(0.0, 1.5) == tuple(BACKGROUND)[:3]
    plank.angle = math.pi / 2
    w.step(DT)
    assert colour_at(0.0, 1.5) == tuple(KINEMATIC)[:3]
    assert colour_at(1.5, 0.0) == tuple(BACKGROUND)[:3]
