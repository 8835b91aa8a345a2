"""A disc on a face that turns, on the soft step (engine.dynamics.turning_faces).

The closed form: a bead on a rod turning at a constant omega, frictionless and without gravity,
slides along it as u'' = omega^2 u (the centrifugal pull along the rod; the rod's push takes the
Coriolis and centrifugal parts across it), so u(t) = u0 cosh(omega t) + u0' sinh(omega t) /
omega. A disc riding the leading face of a kinematic bar is that bead while the face pushes it
(2 omega u' > omega^2 d, d its centre's distance off the bar's line), which these starts keep.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import demos.pinball as pb
from engine import Body, Polygon, Segment, StabilityWarning, Vector, World
from engine.dynamics.turning_faces import FACE_A, FACE_B, FACE_NUMBERS, ROUND, SEGMENT, face_rows
from engine.forces import Gravity
from tests.paths import PATHS

OMEGA = 3.0  # rad/s, the bar's
HALF = 0.1  # m, the bar's radius (a capsule 30 m long)
R = 0.2  # m, the disc's
U0, U0_DOT = 1.0, 1.0  # m and m/s along the bar at the start
DT = 1.0 / 60.0
SECONDS = 1.0


def ride(substeps: int) -> tuple[float, float, float]:
    """The disc flung along the turning bar for SECONDS: (its distance along the bar, the
    closed form's, its deepest overlap with the bar after any step (m))."""
    world = World(solver="soft")
    world.contact_iterations = substeps
    bar = world.add(
        Body(Vector(0.0, 0.0), shape=Segment((-15.0, 0.0), (15.0, 0.0), radius=HALF),
             kinematic=True, friction=0.0, restitution=0.0)
    )  # fmt: skip
    bar.angular_velocity = OMEGA
    d = HALF + R
    # On the bar's leading face (+y, as it turns counter-clockwise), moving with it, and
    # outward along it at U0_DOT.
    disc = world.add(
        Body(Vector(U0, d), Vector(U0_DOT - OMEGA * d, OMEGA * U0), radius=R, mass=1.0,
             friction=0.0, restitution=0.0)
    )  # fmt: skip
    deepest = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        for _ in range(round(SECONDS / DT)):
            world.step(DT)
            deepest = max(deepest, world.overlap())
    c, s = math.cos(bar.angle), math.sin(bar.angle)
    u = disc.pos.x * c + disc.pos.y * s
    t = world.t
    exact = U0 * math.cosh(OMEGA * t) + U0_DOT / OMEGA * math.sinh(OMEGA * t)
    return u, exact, deepest


@pytest.fixture(scope="module")
def rides() -> dict[int, tuple[float, float, float]]:
    return {k: ride(k) for k in (4, 16)}


def test_a_disc_flung_along_a_turning_bar_follows_the_closed_form(
    rides: dict[int, tuple[float, float, float]],
) -> None:
    # At the default 4 substeps: 0.08% short after 1 s (13.4 m out), where rows fixed at the
    # step's start left it 5.9% short at any number of substeps.
    u, exact, _ = rides[4]
    assert exact == pytest.approx(13.407, abs=1e-3)
    assert u == pytest.approx(exact, rel=5e-3)


def test_more_substeps_bring_the_disc_closer_to_the_closed_form_and_out_of_the_bar(
    rides: dict[int, tuple[float, float, float]],
) -> None:
    # What the soft step's warning advises (raise world.contact_iterations) does here: 43 mm
    # deep at 4 substeps, 11 mm at 16 (113 and 109 mm with the rows fixed at the start); the
    # distance along the bar 0.08% and 0.02% short.
    u4, exact, deep4 = rides[4]
    u16, _, deep16 = rides[16]
    assert abs(u16 - exact) < 0.5 * abs(u4 - exact)
    assert u16 == pytest.approx(exact, rel=1e-3)
    assert deep4 < 0.3 * R
    assert deep16 < 0.35 * deep4
    assert deep16 < 0.08 * R


def _rows(
    nx: float,
    ny: float,
    shapes: tuple[str, str],
    angle: float = 0.0,
    parts: int = 1,
    angle_b: float = 0.0,
) -> tuple[int, float]:
    """``face_rows`` of one row between body 0 and body 1 (normal from 0 to 1), their shapes
    "box" (a unit box at ``angle``, body 1's at ``angle_b``, of rounding radius 0.05 where it
    is body 1's, 0.02 where body 0's) or "disc" (radius 0.25)."""
    box = np.array([[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]] * 2)
    circle = np.array([s == "disc" for s in shapes])
    index = np.array([0, 1], dtype=np.int64)
    body_parts = np.array([[0, 1], [1, parts]], dtype=np.int64)
    face, radius = face_rows.py(
        np.array([0]), np.array([1]), np.array([nx]), np.array([ny]), 2, parts != 1,
        np.array([angle, angle_b]), circle, index, body_parts, box, np.array([4, 4]),
        np.array([0.02, 0.05]), np.array([0.25, 0.25]), np.array([-1]), np.zeros(0, bool),
        np.zeros(0, np.int64), box * 0.5,
    )  # fmt: skip
    return int(face[0]), float(radius[0])


def _static_rows(nx: float, ny: float, shape: str) -> tuple[int, list[float]]:
    """``face_rows`` of one row between a disc (body 0, radius 0.25) and a static shape
    (normal from the disc to it): "box" (a unit box, rounding 0.02), "segment" (a capsule's
    core from (-1, 0) to (1, 0), rounding 0.05), "circle" (radius 0.5) or "plane" (a half
    plane). Its kind and its FACE_NUMBERS numbers."""
    corners = np.array([[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]],
                        [[-1.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 0.0]]])  # fmt: skip
    normals = np.array([[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]],
                        [[0.0, -1.0], [0.0, 1.0], [0.0, 1.0], [0.0, 1.0]]])  # fmt: skip
    circle, index = {"box": (False, 0), "segment": (False, 1), "circle": (True, 1),
                     "plane": (False, -1)}[shape]  # fmt: skip
    face, numbers = face_rows.py(
        np.array([0]), np.array([1]), np.array([nx]), np.array([ny]), 1, False,
        np.array([0.0]), np.array([True]), np.array([0], dtype=np.int64),
        np.array([[0, 1]], dtype=np.int64), normals, np.array([4, 2]), np.array([0.02, 0.05]),
        np.array([0.25, 0.5]), np.array([0]), np.array([circle]),
        np.array([index], dtype=np.int64), corners,
    )  # fmt: skip
    return int(face[0]), numbers.tolist()


def test_a_row_turns_with_a_face_and_not_with_a_corner_or_a_disc() -> None:
    # A disc on a box's top face: the face is A's (the box), or B's with the bodies the
    # other way round (the normal from the disc down to the box).
    assert _rows(0.0, 1.0, ("box", "disc")) == (FACE_A, 0.25)
    assert _rows(0.0, -1.0, ("disc", "box")) == (FACE_B, 0.25)
    # The box turned a quarter of a radian: its top face's normal turned with it.
    turned = (-math.sin(0.25), math.cos(0.25))
    assert _rows(*turned, ("box", "disc"), angle=0.25) == (FACE_A, 0.25)
    # On a corner (the normal between two faces'), two discs: as before.
    corner = (math.sqrt(0.5), math.sqrt(0.5))
    assert _rows(*corner, ("box", "disc")) == (0, 0.0)
    assert _rows(0.0, 1.0, ("disc", "disc")) == (0, 0.0)
    # Two boxes: the face is the one whose edge normal the row's is, A's first where both
    # are (flat on each other), and the radius the other's rounding.
    assert _rows(0.0, 1.0, ("box", "box")) == (FACE_A, 0.05)
    assert _rows(*turned, ("box", "box"), angle=0.25) == (FACE_A, 0.05)
    assert _rows(*turned, ("box", "box"), angle_b=0.25) == (FACE_B, 0.02)
    # A corner of each (the normal along neither's face): as before.
    assert _rows(*corner, ("box", "box"), angle=0.3, angle_b=-0.2) == (0, 0.0)
    # A body of several shapes in the World: no row is taken again.
    assert _rows(0.0, 1.0, ("box", "disc"), parts=2) == (0, 0.0)


def test_a_disc_by_a_static_shape_meets_its_core_where_it_is_round() -> None:
    # A disc above a static box's top face: the face's rows are exact as they are (a static
    # face never turns). By its corner: the line from the corner, a round feature (ROUND,
    # the disc's radius and the box's rounding). Beside a capsule, on its side or its end:
    # its core segment (SEGMENT, with the segment's ends). A circle collider: ROUND. A half
    # plane: its own normal, as before.
    corner = (-math.sqrt(0.5), -math.sqrt(0.5))  # (from the disc, up and right of it, down)
    assert _static_rows(0.0, -1.0, "box") == (0, [0.0] * FACE_NUMBERS)
    assert _static_rows(*corner, "box") == (ROUND, [0.25, 0.02, 0.0, 0.0, 0.0, 0.0])
    segment = [0.25, 0.05, -1.0, 0.0, 1.0, 0.0]
    assert _static_rows(0.0, -1.0, "segment") == (SEGMENT, segment)
    assert _static_rows(*corner, "segment") == (SEGMENT, segment)
    assert _static_rows(*corner, "circle") == (ROUND, [0.25, 0.5, 0.0, 0.0, 0.0, 0.0])
    assert _static_rows(0.0, -1.0, "plane") == (0, [0.0] * FACE_NUMBERS)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_ball_shot_up_the_pinball_lane_passes_the_ends_beside_it(kernels: str) -> None:
    # The pinball's shooter lane (demos.pinball), in the table's units (cm: World's
    # length_units_per_meter=100, so the speculative rows reach 2 cm): the ball, shot up the
    # lane between two walls 1 mm from it, passes the inlane guide's round end where it meets
    # the lane's wall (its surface 1 mm off the ball's path) and, through the lane's wall,
    # the right slingshot's top end (5 mm off). The rows of each were taken along the line
    # from the ball to that end at the step's start (a slingshot's side's line, extended
    # past its end): closing on it faster than its gap allows, the ball was stopped there
    # (104 cm/s sideways at the guide), every shot, and the game never left the lane. Taken
    # again as the ball moves, to the nearest point of the end's core, they never push: the
    # ball flies up the lane as it would alone (to 1e-9 cm and cm/s: it is stepped in
    # substeps there, in one closed form alone).
    world = World(integrator="auto", solver="soft", length_units_per_meter=100, kernels=kernels)
    pb.build_table(world)
    ball = pb.add_ball(world, pb.PLUNGER_REST)
    ball.vel = Vector(0.0, 280.0)
    free = World(integrator="auto", solver="soft", length_units_per_meter=100, kernels=kernels)
    free.add_force(Gravity((0.0, -pb.GRAVITY)))
    alone = free.add(Body(Vector(*pb.PLUNGER_REST), Vector(0.0, 280.0), radius=pb.BALL_RADIUS,
                          mass=pb.BALL_MASS))  # fmt: skip
    while ball.pos.y < 80.0:
        world.step(pb.DT)
        free.step(pb.DT)
        assert (ball.pos - alone.pos).length() < 1e-9, world.t
        assert (ball.vel - alone.vel).length() < 1e-9, world.t


def test_a_disc_on_a_box_that_tips_gives_the_same_bits_on_both_paths() -> None:
    # A disc rests on a box that tips off a ledge: the disc's row turns with the box's face.
    pytest.importorskip("numba")
    got = []
    for kernels in ("numpy", "fast"):
        world = World(solver="soft", kernels=kernels)
        world.add_force(Gravity((0.0, -9.81)))
        world.add_collider(Segment((-3.0, 0.0), (0.3, 0.0), radius=0.05))
        box = world.add(Body(Vector(0.6, 0.55), shape=Polygon.box(1.0, 1.0), mass=2.0))
        disc = world.add(Body(Vector(0.4, 1.3), radius=0.25, mass=0.5))
        for _ in range(90):
            world.step(DT)
        got.append((box.pos.x, box.pos.y, box.angle, disc.pos.x, disc.pos.y, disc.angle))
    assert got[0] == got[1]
