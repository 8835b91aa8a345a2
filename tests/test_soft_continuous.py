"""The soft step's continuous stage (engine.dynamics.game_continuous): after the solve, each fast
body is swept from its pose at the step's start to its end against what the solve does not move, and
set back to its first time of impact, on both paths and with the same bits; a body that rests,
slides or rolls is never fast, and the stage leaves it as it was."""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import pytest

import demos.pinball as pb
from demos.stack import ROOM, in_room, tumbler
from engine import Body, Polygon, Segment, StabilityWarning, Vector, World
from engine.forces import Gravity
from tests.paths import FAST, PATHS

DT = 1.0 / 60.0

#: Directions (rad from straight at the segment) and phases (a share of a step's travel) of the
#: ball's throws: without the stage a third of them pass (tested below).
ANGLES = (0.3, 0.6, 1.0, 1.3)
PHASES = (0.0, 0.1, 0.6, 0.75, 0.9)


def _ball_at(
    kernels: str, angle: float, phase: float, stage: bool = True, kinematic: bool = False
) -> tuple[bool, World]:
    """A ball of radius 0.05 m thrown at 300 m/s, ``angle`` off straight, under gravity at a
    static segment of no thickness 10 m long, or a kinematic plate 0.05 m thick rising at
    1 m/s (``phase`` of a step's travel set back): whether its centre ever crossed the
    segment's (the plate's) line within its span in 10 steps, and the World."""
    w = World(kernels=kernels, solver="soft", integrator="auto")
    w._s.game.continuous.enabled = stage
    w.add_force(Gravity((0.0, -9.81)))
    if kinematic:
        wall = w.add(Body((0.0, 0.0), (0.0, 1.0), shape=Polygon.box(0.05, 10.0), kinematic=True))
    else:
        wall = None
        w.add_collider(Segment((0.0, -5.0), (0.0, 5.0)))
    d = Vector(math.cos(angle), math.sin(angle))
    ball = w.add(Body(d * -(3.0 + phase * 300.0 * DT), d * 300.0, radius=0.05, mass=0.1,
                      restitution=0.0, friction=0.3))  # fmt: skip

    def where() -> Vector:
        return ball.pos if wall is None else wall.world_to_local(ball.pos)

    before = where()
    for _ in range(10):
        w.step(DT)
        now = where()
        if before.x < 0.0 <= now.x and abs(now.y) < 5.0:
            return True, w
        before = now
    return False, w


def _passed(kernels: str, stage: bool = True, kinematic: bool = False) -> list[tuple[float, ...]]:
    return [(a, p) for a in ANGLES for p in PHASES if _ball_at(kernels, a, p, stage, kinematic)[0]]


@pytest.mark.parametrize("kinematic", [False, True], ids=["static segment", "kinematic plate"])
@pytest.mark.parametrize("kernels", PATHS)
def test_a_fast_small_ball_never_passes_a_thin_wall(kernels: str, kinematic: bool) -> None:
    # The ball's speculative contact is taken at its nearest point at the step's start; its
    # separation follows the ball's turn across the normal, so met at a slant with friction
    # it holds; and were it to let the ball through a static wall, the stage would set it
    # back where it first touches (a moving kinematic body is swept against bullets alone,
    # Box2D's rule: below).
    assert _passed(kernels, kinematic=kinematic) == []


def _tumbled(kernels: str, degrees: float, steps: int) -> tuple[float, int, np.ndarray]:
    """Box2D's tumbler with 50 boxes turning at ``degrees`` a second on the soft step, for
    ``steps``: the deepest overlap of two bodies after any step (m), the steps after which
    one went past 50 mm, and the boxes' centres in the room's frame at the end."""
    w, boxes, walls = tumbler(50, spin=math.radians(degrees), kernels=kernels, solver="soft")
    deepest, deep = 0.0, 0
    for _ in range(steps):
        w.step(DT)
        got = w.overlap()
        deepest = max(deepest, got)
        deep += got > 0.05
    return deepest, deep, in_room(boxes, walls)[0]


@pytest.mark.parametrize("kernels", PATHS)
def test_boxes_a_turning_wall_carries_are_not_set_back_into_one_another(kernels: str) -> None:
    # Box2D's tumbler with 50 boxes, its walls (kinematic bodies) turning at 25 degrees a
    # second: the pile lands, rides up a wall at up to 6 m/s, fast for a box of 0.25 m, and
    # tumbles down. Swept against the turning walls (whose corners move 10 cm a step), the
    # carried boxes were set back from the poses the solve gave them and into those it did
    # not set back: two boxes 186 mm into each other, 100 mm and more for two seconds. Box2D
    # sweeps a body that is no bullet against static shapes alone, and so does the stage now.
    # Over 8 s (the landing, two loads carried up and their fall), 4 substeps: 85 mm, 10 steps
    # past 50 mm, with the rows of two boxes fixed at the step's start; 59 mm (the landing,
    # boxes spinning at 20 rad/s that meet faster than the rows take again), 3 to 6 steps
    # (the pile is chaotic: a change of the last bit moves it), with a corner's row on a face
    # taken again as the face turns (engine.dynamics.turning_faces).
    # (The issue asks 25 mm, 10% of a side; Box2D v3 went 274 mm on its tumbler of 500.)
    deepest, deep, centre = _tumbled(kernels, 25.0, 480)
    assert deepest < 0.07
    assert deep <= 8
    assert np.abs(centre).max() < ROOM  # every centre inside the room


#: Balls thrown at the pinball's left bat as it flips (demos.bench.pinball's trials 356, 678
#: and 788 of 1,000 at up to 6 m/s): where each starts (cm), its velocity (cm/s), and the
#: steps of 1/120 s it is watched.
THROWN_AT_THE_BAT = [
    ((28.504215557813946, 16.40317317508324), (-248.92711593178643, -136.3956596115206), 22),
    ((31.877167067715444, 19.500651886524572), (-366.02572095880566, -216.3384353130843), 22),
    ((32.47134059200084, 30.17342620988574), (-273.3348481784661, -370.4731229096494), 24),
]


@pytest.mark.parametrize("throw", THROWN_AT_THE_BAT, ids=["356", "678", "788"])
@pytest.mark.parametrize("kernels", PATHS)
def test_a_bullet_the_flipping_bat_carries_is_not_set_back_into_it(
    kernels: str, throw: tuple[tuple[float, float], tuple[float, float], int]
) -> None:
    # The pinball's ball (a bullet) lands on the bat as it swings up at 40 rad/s and rides
    # it, a few millimetres into it under the load that turns it (the soft contact's give).
    # The bat turns a third of a radian a step, so the ball, swept against the bat on the
    # bat's own sweep, came within the time of impact's target of it early in the step
    # and was set back there, while the bat went on to its end pose: 1.05 to 1.25 of the
    # ball's radius into it (its centre inside the bat). Against a body the solve moves, a
    # bullet is swept to that body's end pose, Box2D's rule (b2MakeSweep of a finalized
    # body): 0.29 to 0.39.
    start, vel, steps = throw
    w = World(integrator="auto", solver="soft", length_units_per_meter=100, kernels=kernels)
    w.add_force(Gravity((0.0, -pb.GRAVITY)))
    _, hinge = pb.add_flipper(w, -1)
    ball = pb.add_ball(w, start)
    ball.vel = Vector(*vel)
    ball.bullet = True
    deepest = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)  # (the give: a quarter of r and more)
        for _ in range(steps):
            pb.drive(hinge, -1, w.t >= 0.03 - 1e-12)  # (the key pressed at 0.03 s)
            w.step(pb.DT)
            deepest = max(deepest, w.overlap())
    assert deepest < 0.5 * pb.BALL_RADIUS


@FAST
def test_boxes_tumbled_at_90_degrees_a_second_do_not_stay_deep_in_one_another() -> None:
    # The stress scene: at 90 degrees a second the drum's faces turn 1.5 degrees a step under
    # the pile and the boxes on them. With the rows of two boxes fixed at the step's start,
    # 216 of 480 steps (8 s) ended with two boxes more than 50 mm into each other (390 past
    # 25 mm; the deepest 130 mm); with a corner's row on a face taken again as the face turns,
    # 6 (16 past 25 mm; the landing's 110 mm). The numpy path gives the same bits
    # (tests/test_turning_faces.py), at six times the cost.
    deepest, deep, centre = _tumbled("fast", 90.0, 480)
    assert deep <= 12
    assert deepest < 0.12
    assert np.abs(centre).max() < ROOM


#: The spinning box's throws (``_box_at``): directions (rad from straight at the segment)
#: and phases (a share of a step's travel).
BOX_ANGLES = (0.0, 0.3, 0.6)
BOX_PHASES = (0.0, 0.25, 0.5, 0.75)


def _box_at(kernels: str, angle: float, phase: float, stage: bool = True) -> bool:
    """A thin box (0.1 by 1 m, 0.05 kg) turning 200 rad/s thrown at 300 m/s, ``angle`` off
    straight, at a static segment of no thickness 10 m long, with no gravity: whether its
    centre ever crossed the segment's line within its span in 14 steps."""
    w = World(kernels=kernels, solver="soft", integrator="auto")
    w._s.game.continuous.enabled = stage
    w.add_collider(Segment((0.0, -5.0), (0.0, 5.0)))
    d = Vector(math.cos(angle), math.sin(angle))
    box = w.add(Body(d * -(5.0 + phase * 300.0 * DT), d * 300.0, shape=Polygon.box(0.1, 1.0),
                     mass=0.05, restitution=0.0, friction=0.6, angular_velocity=200.0))  # fmt: skip
    before = box.pos
    for _ in range(14):
        w.step(DT)
        now = box.pos
        if before.x < 0.0 <= now.x and abs(now.y) < 5.0:
            return True
        before = now
    return False


@pytest.mark.parametrize("kernels", PATHS)
def test_a_thin_box_turning_fast_never_passes_a_thin_wall(kernels: str) -> None:
    # Turning 3.3 rad a step, its far end swings through the wall between two steps, where
    # the points its contact held at the step's start do not see it: the stage sweeps it.
    assert not any(_box_at(kernels, a, p) for a in BOX_ANGLES for p in BOX_PHASES)


@FAST
def test_without_the_stage_the_spinning_box_passes_the_wall() -> None:
    # (What the test above would meet without the stage: 4 of these 12 pass, measured.)
    passed = [(a, p) for a in BOX_ANGLES for p in BOX_PHASES if _box_at("fast", a, p, False)]
    assert len(passed) >= 3


def _state(w: World) -> list[Any]:
    return [(tuple(b.pos), tuple(b.vel), b.angle, b.angular_velocity) for b in w.bodies]


def _floor_scene(kernels: str, stage: bool) -> tuple[World, list[int]]:
    """A crate resting on a floor, a crate sliding along it at 5 m/s, a ball rolling at 6 m/s
    and one dropped from 1 m, stepped 1 s: the stage's fast bodies found each step."""
    w = World(kernels=kernels, solver="soft", integrator="auto")
    w._s.game.continuous.enabled = stage
    w.add_force(Gravity((0.0, -9.81)))
    w.add_collider(Segment((-30.0, 0.0), (30.0, 0.0), radius=0.05))
    w.add(Body((0.0, 0.55), shape=Polygon.box(1.0, 1.0), mass=1.0))
    w.add(Body((-10.0, 0.55), (5.0, 0.0), shape=Polygon.box(1.0, 1.0), mass=1.0, friction=0.2))
    w.add(Body((5.0, 0.3), (6.0, 0.0), radius=0.25, mass=1.0, angular_velocity=-24.0))
    w.add(Body((-4.0, 1.3), radius=0.25, mass=1.0))
    found = []
    for _ in range(60):
        w.step(DT)
        found.append(w._s.game.continuous.found)
    return w, found


@pytest.mark.parametrize("kernels", PATHS)
def test_a_body_resting_sliding_or_rolling_is_untouched_by_the_stage(kernels: str) -> None:
    on, found = _floor_scene(kernels, True)
    off, _ = _floor_scene(kernels, False)
    assert found == [0] * 60  # no body is fast: the stage's kernel is never called
    assert _state(on) == _state(off)


@FAST
def test_both_paths_set_the_same_bodies_back_to_the_same_bits() -> None:
    ends = []
    for kernels in ("numpy", "fast"):
        hit, w = _ball_at(kernels, 0.6, 0.1)
        assert not hit
        ends.append(np.array([v for s in _state(w) for v in (*s[0], *s[1], s[2], s[3])]))
    np.testing.assert_allclose(ends[0], ends[1], rtol=1e-12, atol=1e-12)
