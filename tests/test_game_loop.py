"""The soft step's stages in one compiled call (engine.pipeline.game_loop.step_loop) against the
numpy path's stages one by one: the same bodies to the bit, the same sleep, the same joints'
impulses, the same sensing and the same events, step by step, through a scene that uses every
stage the kernel fuses (waking, sleep, contacts, joints of every row, a mouse joint, a
kinematic body, sensors)."""

from __future__ import annotations

from typing import Any

import numpy as np

from engine import (
    Body,
    Circle,
    Filter,
    GearJoint,
    GrooveJoint,
    Hinge,
    MouseJoint,
    Polygon,
    Segment,
    SlideJoint,
    Vector,
    World,
)
from engine.forces import Gravity
from tests.paths import FAST

DT = 1.0 / 60.0


def scene(kernels: str) -> tuple[World, dict[str, Any], list[tuple[str, str]]]:
    """A floor; a pyramid of six crates that falls asleep; a ball thrown at it at 1.5 s that
    wakes it; a plank on a hinge; a slide joint, a groove and a gear between bodies; a bead
    a pivot corrects slowly; a box dragged by a mouse joint; a kinematic platform; a sensor
    collider and a sensor body."""
    world = World(kernels=kernels, solver="soft")
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Segment((-20.0, 0.0), (20.0, 0.0), radius=0.05))
    world.add_collider(Circle((6.0, 0.6), 0.5, sensor=True))
    crates = []
    for row in range(3):
        for k in range(3 - row):
            at = (float(k - (2 - row) / 2.0), 0.55 + 1.0 * row)
            crates.append(world.add(Body(at, shape=Polygon.box(1.0, 1.0), mass=1.0)))
    ball = world.add(Body((-8.0, 0.3), radius=0.25, mass=2.0))
    plank = world.add(Body((-4.0, 3.0), shape=Polygon.box(2.0, 0.2), mass=1.0))
    world.add_link(Hinge(plank, world.static_body, (-4.0, 3.0)))
    a = world.add(Body((4.0, 4.0), shape=Polygon.box(0.4, 0.4), mass=1.0))
    b = world.add(Body((5.0, 4.0), radius=0.2, mass=0.5))
    slide = world.add_link(SlideJoint(a, b, (0.0, 0.0), (0.0, 0.0), 0.5, 1.2))
    rail = world.add(Body((8.0, 5.0), radius=0.2, mass=1.0))
    groove = world.add_link(
        GrooveJoint(world.static_body, rail, (7.0, 5.0), (10.0, 4.0), (0.0, 0.0))
    )
    wheel = world.add(Body((-8.0, 6.0), radius=0.5, mass=1.0, angular_velocity=3.0))
    gear_b = world.add(Body((-6.5, 6.0), radius=0.5, mass=1.0))
    world.add_link(Hinge(wheel, world.static_body, (-8.0, 6.0)))
    world.add_link(Hinge(gear_b, world.static_body, (-6.5, 6.0)))
    gear = world.add_link(GearJoint(wheel, gear_b, 0.0, -2.0))
    # A bead 0.3 m off its pivot (a groove of no length) that error_bias corrects slowly:
    # moved with no speed left, it stays awake until the move is slow (engine.pipeline.game_sleep's
    # drifting), then sleeps (at step 154).
    bead = world.add(Body((-12.3, 8.0), radius=0.1, mass=1.0))
    pivot = GrooveJoint(world.static_body, bead, (-12.0, 8.0), (-12.0, 8.0), (0.0, 0.0))
    world.add_link(pivot).error_bias = 0.5
    dragged = world.add(Body((12.0, 1.0), shape=Polygon.box(0.5, 0.5), mass=1.0))
    drag = world.add_link(MouseJoint(dragged, (12.0, 3.0), max_force=40.0))
    platform = world.add(Body((15.0, 1.5), (0.5, 0.0), shape=Polygon.box(2.0, 0.2), kinematic=True))
    ghost = world.add(Body((6.0, 3.0), radius=0.3, mass=1.0, sensor=True))
    seen: list[tuple[str, str]] = []
    world.on_collision(
        begin=lambda e: seen.append(("begin", repr(e))),
        separate=lambda e: seen.append(("end", repr(e))),
    )
    things = {"crates": crates, "ball": ball, "slide": slide, "groove": groove, "gear": gear,
              "drag": drag, "platform": platform, "ghost": ghost, "bead": bead}  # fmt: skip
    return world, things, seen


def state(world: World, things: dict[str, Any]) -> tuple[Any, ...]:
    """Everything the step leaves that a game reads: the bodies, who sleeps, the joints'
    impulses, what touches (with its impulse) and what the sensors hold."""
    bodies = np.array([[*b.pos, b.angle, *b.vel, b.angular_velocity] for b in world.bodies])
    asleep = tuple(world.is_sleeping(b) for b in world.bodies)
    joints = tuple(
        (j.impulse, *getattr(j, "linear_impulse", (0.0, 0.0)), getattr(j, "angular_impulse", 0.0))
        for j in (things["slide"], things["groove"], things["gear"])
    ) + (tuple(things["drag"].impulse),)
    touching = sorted(repr(e) for e in world.touching)
    return bodies, asleep, joints, touching


@FAST
def test_the_fused_step_is_the_numpy_stages_step_by_step() -> None:
    runs = [scene(k) for k in ("numpy", "fast")]
    slept = woke = False
    for step in range(200):
        if step == 90:  # the pile has slept: a ball thrown at it wakes it
            for world, things, _seen in runs:
                assert all(world.is_sleeping(c) for c in things["crates"])
                things["ball"].vel = (12.0, 2.0)
                slept = True
        for world, _things, _seen in runs:
            world.step(DT)
        (wa, ta, _), (wb, tb, _) = runs
        sa, sb = state(wa, ta), state(wb, tb)
        assert np.array_equal(sa[0], sb[0]), (step, np.abs(sa[0] - sb[0]).max())
        assert sa[1:] == sb[1:], step
        if slept and not any(wa.is_sleeping(c) for c in ta["crates"]):
            woke = True
    assert slept and woke  # the scene reached the stages it is for
    assert all(world.is_sleeping(things["bead"]) for world, things, _ in runs)
    (_, _, ea), (_, _, eb) = runs
    assert len(ea) > 10 and ea == eb


@FAST
def test_the_compiled_broadphase_is_reach_and_candidates_to_the_bit() -> None:
    """engine.pipeline.game_contacts.candidates_loop (the fast path's reach and pairs past a
    few bodies) against the numpy path's ``_reach`` and ``_candidates``: a tumbler (its walls
    big bodies) and a pit of discs, through their steps; one group; a body flung far."""
    from demos import stack
    from engine.pipeline import game_contacts, game_step

    def same(world: World) -> None:
        store = world._s.store
        n = len(store)
        accel = np.zeros((n, 2))
        accel[:, 1] = -9.81
        numpy_step = game_step.GameStep(False)
        margin = game_step._reach(store, accel, DT)
        a, b = numpy_step._candidates(store, margin)
        fa, fb, fm = game_contacts.candidates_loop(
            store.x, store.v, accel, store.omega, store.radius,
            np.ascontiguousarray(store.group, np.int64), DT, float(np.median(store.radius)), 1.0,
        )  # fmt: skip
        assert np.array_equal(fm, margin)
        assert np.array_equal(fa, a) and np.array_equal(fb, b)

    tumbler = stack.tumbler(60, kernels="fast", solver="soft")[0]
    pit = World(kernels="fast", solver="soft")
    pit.add_force(Gravity((0.0, -9.81)))
    pit.add_collider(Segment((-5.0, 0.0), (5.0, 0.0)))
    rng = np.random.default_rng(3)
    for p in rng.uniform((-4.0, 0.5), (4.0, 8.0), (80, 2)).tolist():
        pit.add(Body(tuple(p), radius=float(rng.uniform(0.1, 0.3)), mass=1.0))
    for world in (tumbler, pit):
        for step in range(40):
            if step % 10 == 0:
                same(world)
            world.step(DT)
    pit.bodies[0].vel = (1e6, 0.0)  # reaches past four times the median: a big body
    same(pit)
    for body in pit.bodies:
        body.filter = Filter(group=2)
    same(pit)


def _all_fast(kernels: str) -> np.ndarray:
    """40 balls of 0.1 m, every one thrown at 300 m/s, some across the others' paths: each
    reaches past four times the median radius, so every body is "big" to the broadphase.
    The bodies' positions and velocities after 5 steps."""
    w = World(kernels=kernels, solver="soft")
    for i in range(40):
        vx = 0.0 if i % 2 else 30.0
        w.add(Body(Vector(i * 0.15, 0.0), Vector(vx, 300.0 * (-1) ** i), radius=0.1))
    for _ in range(5):
        w.step(1 / 60)
    return np.array([(*b.pos, *b.vel) for b in w.bodies])


def test_a_scene_of_bodies_all_fast_steps_on_numpy() -> None:
    # (The numpy path's broadphase took the largest reach among the bodies that are not big,
    # none here: numpy's max of nothing raised.) The balls that meet are pushed apart: they
    # do not pass through each other.
    end = _all_fast("numpy")
    assert np.isfinite(end).all()
    gaps = np.hypot(*(end[:, None, :2] - end[None, :, :2]).transpose(2, 0, 1))
    assert gaps[np.triu_indices(40, 1)].min() > 0.2 - 0.01


@FAST
def test_a_scene_of_bodies_all_fast_gives_the_same_bits_on_both_paths() -> None:
    assert np.array_equal(_all_fast("numpy"), _all_fast("fast"))
