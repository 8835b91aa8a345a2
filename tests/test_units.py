"""A World in other length units (``World(length_units_per_meter=...)``, Box2D's
b2SetLengthUnitsPerMeter): the same scene built in centimetres moves as the one in metres,
scaled, on the soft step, whose slop, speculative distance, push and bounce speeds, fresh
contacts' reach and sleep are set in metres (engine.pipeline.game_step)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine import Body, Hinge, Polygon, Segment, Vector, World
from engine.forces import Gravity
from tests.paths import PATHS

DT = 1.0 / 60.0
STEPS = 150  # 2.5 s: landings, a bounce, a push out of the floor, a swing, sleep


def scene(kernels: str, scale: float, unit: float) -> World:
    """A soft World whose lengths are ``scale`` of its units a metre, told it is ``unit``:
    a floor; two boxes stacked on it; a box dropped turned; a box set 4 cm into the floor (the
    push apart, at most 3 m/s); a ball dropped from 0.5 m with restitution 0.8 (it meets the
    floor at 3.1 m/s: past the 1 m/s threshold, it bounces) and one from 2 cm (0.6 m/s: it
    does not); a ball rolling at 2 m/s, and one at 3 mm/s (under the 5 cm/s of sleep's
    stillness: it falls asleep); a plank swinging on a hinge."""
    s = scale
    world = World(kernels=kernels, solver="soft", length_units_per_meter=unit)
    world.add_force(Gravity((0.0, -9.81 * s)))
    world.add_collider(Segment((-6 * s, 0.0), (6 * s, 0.0), radius=0.05 * s, friction=0.6))
    box = Polygon.box(0.5 * s, 0.5 * s)
    for y in (0.3, 0.8):
        world.add(Body(Vector(-4 * s, y * s), mass=1.0, shape=box, friction=0.6))
    world.add(Body(Vector(-2.5 * s, 1.0 * s), mass=2.0, shape=box, angle=0.3, friction=0.6))
    world.add(Body(Vector(-1.0 * s, 0.26 * s), mass=1.0, shape=box, friction=0.6))
    for x, y in ((0.5, 0.6), (1.5, 0.17)):
        world.add(Body(Vector(x * s, y * s), mass=0.5, radius=0.1 * s, restitution=0.8))
    for x, speed in ((2.5, 2.0), (-5.5, 0.003)):
        world.add(Body(Vector(x * s, 0.16 * s), Vector(speed * s, 0.0), mass=0.5, radius=0.1 * s))
    plank = world.add(
        Body(Vector(5.0 * s, 1.5 * s), mass=1.0, shape=Polygon.box(0.8 * s, 0.1 * s), angle=0.5)
    )
    world.add_link(Hinge(plank, world.static_body, (4.6 * s, 1.5 * s)))
    return world


def run(world: World) -> np.ndarray:
    """Each body's x, y, angle, vx, vy, omega after each of STEPS steps, and the number of
    contacts touching then (STEPS, N, 7)."""
    path = []
    for _ in range(STEPS):
        world.step(DT)
        touching = len(world.touching)
        path.append([[*b.pos, b.angle, *b.vel, b.angular_velocity, touching] for b in world.bodies])
    return np.array(path)


def in_metres(path: np.ndarray, scale: float) -> np.ndarray:
    """``run``'s path of a World ``scale`` units a metre, in metres (angles as they are)."""
    out = path.copy()
    out[..., [0, 1, 3, 4]] /= scale
    return out


@pytest.fixture(scope="module", params=PATHS)
def metres(request: pytest.FixtureRequest) -> tuple[str, np.ndarray]:
    return request.param, run(scene(request.param, 1.0, 1.0))


def test_the_scene_in_centimetres_moves_as_in_metres(metres: tuple[str, np.ndarray]) -> None:
    kernels, m = metres
    cm = in_metres(run(scene(kernels, 100.0, 100.0)), 100.0)
    # The same motion at every step, to rounding: every length and speed of the step is
    # scaled, so only the rounding of numbers 100 times larger differs.
    assert np.abs(cm - m).max() < 1e-9, np.abs(cm - m).max()


def test_told_nothing_a_scene_in_centimetres_is_a_different_scene(
    metres: tuple[str, np.ndarray],
) -> None:
    # The soft step's lengths in metres against a scene in centimetres: 2 cm of speculative
    # distance is 0.2 mm there, an overlap is pushed apart at 3 cm/s, a ball bounces from
    # 1 cm/s: not the scene in metres.
    kernels, m = metres
    cm = in_metres(run(scene(kernels, 100.0, 1.0)), 100.0)
    assert np.abs(cm - m)[..., :2].max() > 1e-3


def test_a_world_says_its_units_and_a_copy_keeps_them() -> None:
    world = scene("numpy", 100.0, 100.0)
    assert World().length_units_per_meter == 1.0
    assert world.length_units_per_meter == 100.0
    world.step(DT)  # (its soft step made: the copy's is a copy of it)
    copy = world.copy()
    assert copy.length_units_per_meter == 100.0
    for _ in range(30):
        world.step(DT)
        copy.step(DT)
    assert [b.pos for b in copy.bodies] == [b.pos for b in world.bodies]


@pytest.mark.parametrize("bad", [0.0, -1.0, math.inf, math.nan, "100", True])
def test_length_units_must_be_a_positive_number(bad: object) -> None:
    with pytest.raises(ValueError, match="length_units_per_meter must be a number > 0"):
        World(length_units_per_meter=bad)  # type: ignore[arg-type]
