"""Surface velocity (pymunk's ``shape.surface_velocity``): a conveyor belt's surface moves along
itself, and friction carries what rests on it (engine.exact.soft, ``Rows.slip``), on both paths."""

from __future__ import annotations

import pytest
from paths import FAST, PATHS

from engine import Body, Polygon, Segment, Vector, World
from engine.forces import Gravity

G = 9.81
DT = 1 / 60
MU = 0.5  # the box's; the belt's friction is 1, so the pair's is 0.5
U = 2.0  # the belt's surface speed (m/s)


def belt_world(
    kernels: str, speed: tuple[float, float] = (U, 0.0), turns: bool = False
) -> tuple[World, Body]:
    # The exact models, asked for: a box resting on the belt to 1e-6 (World() would take the
    # soft step, whose contact holds it 0.03 mm into the belt).
    w = World(kernels=kernels, solver="exact")
    w.add_force(Gravity((0, -G)))
    belt = w.add_collider(Segment((-50, 0), (50, 0), restitution=0.0, friction=1.0))
    belt.surface_velocity = speed
    box = w.add(
        Body(
            Vector(0, 0.5),
            mass=1,
            shape=Polygon.box(1, 1),
            restitution=0.0,
            friction=MU,
            fixed_rotation=not turns,
        )
    )
    return w, box


@pytest.mark.parametrize("kernels", PATHS)
def test_a_box_on_a_conveyor_is_carried_up_to_its_speed_in_u_over_mu_g(kernels: str) -> None:
    # Kinetic friction accelerates it at mu g until it moves with the belt, at
    # T = u / (mu g) = 0.408 s; then static friction holds it at u, exactly.
    w, box = belt_world(kernels)
    speeds = []
    for _ in range(60):
        w.step(DT)
        speeds.append(box.vel.x)
    for k, vx in enumerate(speeds, start=1):
        assert vx == pytest.approx(min(U, MU * G * k * DT), abs=1e-12), k
    reached = next(k for k, vx in enumerate(speeds, start=1) if vx == pytest.approx(U, abs=1e-12))
    T = U / (MU * G)
    assert (reached - 1) * DT < T <= reached * DT  # the first step that ends past T
    assert box.pos.y == pytest.approx(0.5, abs=1e-6)  # it slides on it, not into it


def test_the_conveyor_moves_a_box_as_pymunks_does() -> None:
    pymunk = pytest.importorskip("pymunk")
    space = pymunk.Space()
    space.gravity = (0, -G)
    seg = pymunk.Segment(space.static_body, (-50, 0), (50, 0), 0)
    seg.friction, seg.surface_velocity = 1.0, (U, 0)
    body = pymunk.Body(1, float("inf"))
    body.position = (0, 0.5)
    shape = pymunk.Poly.create_box(body, (1, 1))
    shape.friction = MU
    space.add(body, shape, seg)
    w, box = belt_world("numpy")
    for _ in range(40):
        space.step(DT)
        w.step(DT)
        assert box.vel.x == pytest.approx(body.velocity.x, abs=1e-9)


def test_only_the_part_along_the_surface_counts_and_it_can_be_set_while_running() -> None:
    # A belt's velocity across its own surface moves nothing; set back to 0 it holds the box.
    w, box = belt_world("numpy", (0.0, 5.0))
    for _ in range(10):
        w.step(DT)
    assert box.vel.x == 0.0 and box.pos.y == pytest.approx(0.5, abs=1e-6)
    belt = w.colliders[0]
    belt.surface_velocity = Vector(-U, 0)
    w.step(DT)
    assert box.vel.x == pytest.approx(-MU * G * DT, abs=1e-12)
    with pytest.raises(TypeError, match="surface_velocity"):
        belt.surface_velocity = 3.0


@FAST
def test_a_box_that_tips_on_a_conveyor_moves_alike_on_both_paths() -> None:
    # A box free to turn, thrown onto a fast belt: friction at its corners turns it (the
    # soft step's lever arms); the compiled rows are their numpy twin's, bit for bit.
    ends = []
    for kernels in ("numpy", "fast"):
        w, box = belt_world(kernels, (8.0, 0.0), turns=True)
        box.pos, box.vel = Vector(0, 1.5), Vector(-3, 0)
        for _ in range(90):
            w.step(DT)
        ends.append((box.pos, box.vel, box.angle, box.angular_velocity))
    assert ends[0] == ends[1]
    assert ends[0][2] != 0.0 and ends[0][1].x > 0  # it turned, and the belt carries it


@pytest.mark.parametrize("kernels", PATHS)
def test_a_ball_on_a_conveyor_rolls_at_a_third_of_its_speed(kernels: str) -> None:
    # A disc (I = m r^2 / 2) set on the belt: friction mu m g pushes it along, v = mu g t,
    # and spins it up, omega r = 2 mu g t, so the slip at its foot v + omega r - u closes at
    # 3 mu g and ends at t = u / (3 mu g) = 0.136 s; then it rolls with the belt's surface:
    # v = u / 3, omega = 2 u / (3 r) (a disc near a moving surface is the soft step's).
    w = World(kernels=kernels)
    w.add_force(Gravity((0, -G)))
    belt = w.add_collider(Segment((-50, 0), (50, 0), restitution=0.0, friction=1.0))
    belt.surface_velocity = (U, 0)
    ball = w.add(Body(Vector(0, 0.5), radius=0.5, restitution=0.0, friction=MU))
    speeds = []
    for _ in range(30):
        w.step(DT)
        speeds.append(ball.vel.x)
    for k, vx in enumerate(speeds, start=1):
        assert vx == pytest.approx(min(U / 3, MU * G * k * DT), abs=1e-9), k
    assert ball.angular_velocity == pytest.approx(2 * U / (3 * 0.5), abs=1e-9)
    assert ball.pos.y == pytest.approx(0.5, abs=1e-6)
