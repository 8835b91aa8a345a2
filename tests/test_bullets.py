"""Bullets (``Body.bullet``, Box2D's ``isBullet``): on the soft step a fast bullet is swept to its
time of impact against the dynamic bodies too (engine.dynamics.game_continuous), a fast body that is
none against the colliders and the static and kinematic bodies only; on the exact solver the
flag is kept and changes nothing. The flag is set any time, and snapshots and copies keep it."""

from __future__ import annotations

import copy
from dataclasses import replace

import numpy as np
import pytest

from demos.bench import pinball as bench
from engine import Body, Polygon, Vector, World
from tests.paths import FAST

DT = 1.0 / 60.0


def test_a_body_is_no_bullet_unless_made_or_set_one() -> None:
    assert Body(Vector(0, 0)).bullet is False
    b = Body(Vector(0, 0), radius=0.1, bullet=True)
    assert b.bullet is True
    b.bullet = False
    assert b.bullet is False
    w = World(solver="soft")
    w.add(b)
    b.bullet = True
    assert b.bullet is True
    assert w.bodies[0].bullet is True
    w.remove(b)
    assert b.bullet is True  # a body taken out keeps it


@pytest.mark.parametrize("value", [1, 0, "yes", None, np.True_])
def test_a_bullet_flag_that_is_not_a_bool_is_refused_naming_bullet(value: object) -> None:
    with pytest.raises(TypeError, match=r"bullet must be True .* or False, got"):
        Body(Vector(0, 0), radius=0.1, bullet=value)  # type: ignore[arg-type]
    b = Body(Vector(0, 0), radius=0.1, bullet=True)
    with pytest.raises(TypeError, match=r"bullet must be True .* or False, got"):
        b.bullet = value
    assert b.bullet is True  # refused: the old value stays


def _box_at_plate(
    kernels: str = "numpy", bullet: bool = False, solver: str = "soft", late: bool = False
) -> tuple[bool, World]:
    """A thin box (0.1 by 1 m, 0.05 kg) turning 150 rad/s thrown at 200 m/s at a free plate
    (0.05 by 10 m, 0.25 kg) 5 m off (a throw that passes it unless swept against it):
    whether its centre crossed the plate's plane within its span in the plate's frame, and
    the World. ``late``: made a bullet after its first step, not when made."""
    w = World(kernels=kernels, integrator="auto", solver=solver)
    plate = w.add(Body(Vector(0, 0), shape=Polygon.box(0.05, 10.0), mass=0.25,
                       restitution=0.0, friction=0.6))  # fmt: skip
    box = w.add(Body(Vector(-5.0 - 0.4 * 200.0 * DT, 0.0), Vector(200.0, 0.0),
                     shape=Polygon.box(0.1, 1.0), mass=0.05, restitution=0.0, friction=0.6,
                     angular_velocity=150.0, bullet=bullet and not late))  # fmt: skip
    before = plate.world_to_local(box.pos)
    for k in range(12):
        w.step(DT)
        if late and k == 0:
            box.bullet = bullet
        now = plate.world_to_local(box.pos)
        if before.x < 0.0 <= now.x and abs(now.y) < 5.0:
            return True, w
        before = now
    return False, w


def test_a_thin_box_turning_fast_passes_a_free_plate_unless_it_is_a_bullet() -> None:
    # (Turning 2.5 rad a step, its far end swings through the plate between two steps: the
    # points its contact held at the step's start do not see it. At 100 rad/s, the bullet
    # test's of tests/test_rotation_shapes.py, the soft step's contact now holds it bullet or
    # not: its points' separations follow the turn across the normal.)
    assert _box_at_plate(bullet=False)[0]
    assert not _box_at_plate(bullet=True)[0]


def test_a_bullet_set_mid_game_is_swept_from_the_next_step() -> None:
    assert not _box_at_plate(bullet=True, late=True)[0]


def test_the_exact_solver_keeps_the_flag_and_steps_as_without_it() -> None:
    ends = []
    for bullet in (False, True):
        _, w = _box_at_plate(bullet=bullet, solver="exact")
        assert w.bodies[1].bullet is bullet
        ends.append([(tuple(b.pos), tuple(b.vel), b.angle) for b in w.bodies])
    assert ends[0] == ends[1]


def test_a_bullet_ball_never_passes_a_flipper_on_the_soft_step() -> None:
    # demos.bench.pinball's trials (a ball at up to 40 m/s at the pinball's left flipper as it
    # flips, a dynamic body on a hinge) on the soft step: the ball that is no bullet is swept
    # against nothing there and passes the bat in some (10 of these 40), the bullet in none.
    plain = bench.tunnelling(40, solver="soft", bullet=False)
    assert len(plain.passes) >= 3
    swept = bench.tunnelling(40, solver="soft", bullet=True)
    assert swept.passes == []
    assert swept.hits >= 35


def test_a_snapshot_and_a_copy_keep_the_flag() -> None:
    w = World(solver="soft")
    a = w.add(Body(Vector(0, 0), radius=0.1, bullet=True))
    b = w.add(Body(Vector(1, 0), radius=0.1))
    snap = w.snapshot()
    assert snap.bullets == (True, False)
    twin = w.copy()
    a.bullet, b.bullet = False, True
    assert [c.bullet for c in twin.bodies] == [True, False]
    assert twin._s.store is not None and twin._s.store.bullet.tolist() == [True, False]
    assert [copy.copy(c).bullet for c in (a, b)] == [False, True]
    w.restore(snap)
    assert (a.bullet, b.bullet) == (True, False)
    assert w._s.store is not None and w._s.store.bullet.tolist() == [True, False]
    w.restore(replace(snap, bullets=None))  # None: left as they are
    assert (a.bullet, b.bullet) == (True, False)
    for bad in ((True,), (1, 0), [True, False]):
        with pytest.raises(ValueError, match=r"snapshot.bullets must be a tuple of 2 bools"):
            w.restore(replace(snap, bullets=bad))


def test_a_restored_bullet_is_swept_again() -> None:
    hit, w = _box_at_plate(bullet=True)
    assert not hit
    w2 = World(integrator="auto", solver="soft", kernels="numpy")
    plate = w2.add(Body(Vector(0, 0), shape=Polygon.box(0.05, 10.0), mass=0.25,
                        restitution=0.0, friction=0.6))  # fmt: skip
    box = w2.add(Body(Vector(-5.0 - 0.4 * 200.0 * DT, 0.0), Vector(200.0, 0.0),
                      shape=Polygon.box(0.1, 1.0), mass=0.05, restitution=0.0, friction=0.6,
                      angular_velocity=150.0, bullet=True))  # fmt: skip
    snap = w2.snapshot()
    box.bullet = False
    w2.restore(snap)
    for _ in range(12):
        w2.step(DT)
    assert [(tuple(b.pos), b.angle) for b in w2.bodies] == [
        (tuple(b.pos), b.angle) for b in w.bodies
    ]
    assert plate.world_to_local(box.pos).x < 0.0


@FAST
def test_both_paths_give_the_same_bits_for_a_bullet() -> None:
    ends = []
    for kernels in ("numpy", "fast"):
        hit, w = _box_at_plate(kernels, bullet=True)
        assert not hit
        assert w._s.game is not None
        ends.append(np.array([v for b in w.bodies for v in (*b.pos, *b.vel, b.angle,
                                                            b.angular_velocity)]))  # fmt: skip
    np.testing.assert_array_equal(ends[0], ends[1])
