"""Collision types and per-pair callbacks (engine.pipeline.collision_handlers): pymunk's
``collision_type`` and ``on_collision(type_a, type_b, begin, pre_solve, post_solve, separate)``,
and a pre_solve that ignores a contact for a step (a one-way platform), on both paths."""

from __future__ import annotations

import math
from typing import Any

import pytest
from paths import PATHS

from engine import Body, Plane, Polygon, Segment, Vector, World
from engine.dynamics.events import ContactEvent
from engine.forces import Gravity
from engine.kernels import available as kernels_available

G = 9.81
DT = 1 / 60


def test_begin_comes_at_the_exact_moment_of_impact_and_separate_when_thrown_off() -> None:
    # A ball of radius 0.25 dropped from y = 2 meets the floor at sqrt(2 (2 - 0.25) / g).
    w = World(integrator="exact")  # the closed form: the path is the exact parabola
    w.add_force(Gravity((0, -G)))
    floor = w.add_collider(Plane((0, 0), (0, 1), restitution=0.0))
    floor.collision_type = 7
    ball = w.add(Body(Vector(0, 2), mass=2, radius=0.25, restitution=0.0, collision_type=1))
    began: list[ContactEvent] = []
    ended: list[ContactEvent] = []
    solved: list[ContactEvent] = []
    w.on_collision(1, 7, begin=began.append, separate=ended.append, post_solve=solved.append)
    other: list[ContactEvent] = []
    w.on_collision(1, 8, begin=other.append)  # a type nothing has: never called
    for _ in range(60):
        w.step(DT)
    assert len(began) == 1 and not ended and not other
    assert began[0].body is ball and began[0].collider is floor
    assert began[0].time == pytest.approx(math.sqrt(2 * 1.75 / G), abs=1e-12)
    # At rest, post_solve carries the floor's push over a step: m g dt (2 kg).
    assert solved[-1].impulse.y == pytest.approx(2 * G * DT, rel=1e-9)
    ball.vel = Vector(0, 5)
    w.step(DT)
    assert len(ended) == 1 and ended[0].body is ball and ended[0].collider is floor


def test_a_pair_of_bodies_comes_from_the_first_types_side_and_wildcards_match_any() -> None:
    # Two balls meet; the handler (2, 1) sees the type-2 ball as event.body, (None, 2) the
    # type-2 ball as event.collider.
    w = World()
    a = w.add(Body(Vector(0, 0), Vector(1, 0), mass=1, radius=0.5, collision_type=1,
                   restitution=0.5))  # fmt: skip
    b = w.add(Body(Vector(2, 0), Vector(-1, 0), mass=1, radius=0.5, collision_type=2,
                   restitution=0.5))  # fmt: skip
    seen: list[ContactEvent] = []
    anything: list[ContactEvent] = []
    w.on_collision(2, 1, begin=seen.append)
    w.on_collision(None, 2, begin=anything.append)
    w.step(1.0)
    assert len(seen) == 1 and seen[0].body is b and seen[0].collider is a
    # The normal points toward event.body (b, at larger x) and the impulse on it is
    # m (1 + e) v_rel / 2 with e = 0.5 * 0.5 (the bodies' restitutions' product), along +x.
    assert seen[0].normal.x == pytest.approx(1.0)
    assert seen[0].impulse.x == pytest.approx(1.25 * 2 / 2, rel=1e-12)
    assert len(anything) == 1 and anything[0].body is a and anything[0].collider is b


def test_collision_types_and_callbacks_are_checked() -> None:
    with pytest.raises(ValueError, match="collision_type must be an int >= 0"):
        Body(Vector(0, 0), radius=1, collision_type=-1)
    with pytest.raises(TypeError, match="collision_type must be an int"):
        Plane((0, 0), (0, 1)).collision_type = "floor"  # type: ignore[assignment]
    with pytest.raises(TypeError, match="pre_solve must be a function"):
        World().on_collision(1, 2, pre_solve=3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="collision_type"):
        seg = Segment((0, 0), (1, 0))
        seg.collision_type = 1
        Body(Vector(0, 0), shape=seg)


def one_way(contact: ContactEvent) -> bool:
    """Solid only for a body above the ledge and not going up (the guide's one-way ledge)."""
    return contact.normal.y > 0 and contact.body.vel.y <= 0


def thrown_through(
    kernels: str, handled: bool, ledge: Any, steps: int, solver: str = "auto", **shape: Any
) -> tuple[float, float, float]:
    """A body of ``shape`` (mass 1, type 1) thrown up at 8 m/s from a floor at y = 0, under a
    ledge of type 2 (``ledge(world)`` adds it), for ``steps`` steps, with the one-way handler
    or not, on ``solver``: the highest its centre got, and its height and vertical speed at
    the end."""
    w = World(kernels=kernels, solver=solver)
    w.add_force(Gravity((0, -G)))
    w.add_collider(Plane((0, 0), (0, 1), restitution=0.0))
    ledge(w).collision_type = 2
    body = w.add(
        Body(Vector(0, 0.25), Vector(0, 8), mass=1, restitution=0.0, collision_type=1, **shape)
    )
    if handled:
        w.on_collision(1, 2, pre_solve=one_way)
    top = 0.0
    for _ in range(steps):
        w.step(DT)
        top = max(top, body.pos.y)
    return top, body.pos.y, body.vel.y


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("shaped", [False, "exact", "soft"], ids=["disc", "box-exact", "box-soft"])
def test_a_one_way_ledge_lets_a_body_up_through_and_holds_it_from_above(
    kernels: str, shaped: bool | str
) -> None:
    # Thrown up at 8 m/s from the floor, through a ledge at y = 2; it rises to
    # 0.25 + 64 / 2g = 3.51 (less what the floor's first step takes) and lands on the ledge:
    # at rest, its centre at the ledge's top + 0.25 (a disc by exact impacts; a box by the
    # pile's rows on the exact solver, and within the soft step's rest depth on it: Box2D's
    # soft contact holds a box a few hundredths of a millimetre into its support).
    shape: dict[str, Any] = {"radius": 0.25}
    solver, rest = "auto", 1e-6
    if shaped:
        shape = {"shape": Polygon.box(0.5, 0.5), "fixed_rotation": True}
        solver, rest = str(shaped), (1e-6 if shaped == "exact" else 1e-4)

    def ledge(w: World) -> Any:
        return w.add_collider(Segment((-2, 2), (2, 2), restitution=0.0))

    top, y, vy = thrown_through(kernels, True, ledge, 150, solver, **shape)
    top_blocked, _, _ = thrown_through(kernels, False, ledge, 150, solver, **shape)
    assert top > 3.4 and y == pytest.approx(2.25, abs=rest) and vy == pytest.approx(0, abs=1e-9)
    assert top_blocked < 2.0 - 0.25 + 1e-6  # without the handler the ledge stops it below


@pytest.mark.parametrize("kernels", PATHS)
def test_a_pre_solve_that_always_refuses_is_a_filter(kernels: str) -> None:
    # Every contact of the ball and the floor ignored: it falls freely through, as it does in
    # a World without the floor, and nothing begins.
    w = World(kernels=kernels)
    w.add_force(Gravity((0, -G)))
    floor = w.add_collider(Plane((0, 0), (0, 1)))
    floor.collision_type = 3
    ball = w.add(Body(Vector(0, 1), mass=1, radius=0.25, collision_type=4))
    asked: list[float] = []

    def refuse(contact: ContactEvent) -> bool:
        asked.append(contact.time)
        return False

    began: list[ContactEvent] = []
    w.on_collision(3, 4, pre_solve=refuse, begin=began.append)
    for _ in range(40):
        w.step(DT)
    free = World(kernels=kernels)
    free.add_force(Gravity((0, -G)))
    twin = free.add(Body(Vector(0, 1), mass=1, radius=0.25))
    for _ in range(40):
        free.step(DT)
    assert w.method == free.method and ball.pos.y == twin.pos.y < -1.0
    assert not began and asked  # asked before the steps it might touch in


def test_a_one_way_platform_body_lets_a_ball_up_through_and_holds_it_alike_on_both_paths() -> None:
    # The ledge is a kinematic 4 x 0.2 box (a moving platform's kind) at y = 2: the pair of
    # bodies is filtered for the steps its pre_solve refuses (as a joint's pair is), in the
    # exact impacts and in the pile's rows; the ball rests on its top, 2.1 + 0.25, within the
    # pile's slop (SLOP r = 5e-4), the same on both paths.

    def platform(w: World) -> Any:
        return w.add(Body(Vector(0, 2), shape=Polygon.box(4, 0.2), kinematic=True))

    ends = [
        thrown_through(kernels, handled, platform, 180, radius=0.25)
        for kernels, handled in (("numpy", True), ("numpy", False))
    ]
    (top, y, vy), blocked = ends
    assert top > 3.4 and abs(y - 2.35) < 0.002 * 0.25 and vy == pytest.approx(0, abs=1e-9)
    assert blocked[0] < 1.9 - 0.25 + 1e-6  # without the handler it stops below
    if kernels_available():  # (the README's test command has no fast path: CI's second run)
        fast = thrown_through("fast", True, platform, 180, radius=0.25)
        assert fast == pytest.approx(ends[0], abs=1e-12)
