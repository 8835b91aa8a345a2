"""Fuzzing links (engine.dynamics.links) and kinematic bodies: anything a caller passes is a link or
a clear error naming the argument, and any world of linked bodies steps without nan, holds
every rod to 1e-9 of its length (unless it warned that a step stretched it too far), keeps
every pinned body on its pin, and reruns bit for bit from a snapshot.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from engine import Body, Cable, Pin, Rod, StabilityWarning, Vector, World
from engine.forces import Gravity
from tests.fuzzing import anything, attempt, fuzz, moderate, numbers, pairs


def body(x: float = 0.0, y: float = 0.0) -> Body:
    return Body(Vector(x, y), Vector(0, 0), Vector(0, 0))


ends = st.one_of(st.just("body"), st.just("other"), st.just("self"), pairs, anything)


def pick(which: object, a: Body, b: Body) -> object:
    return {"body": a, "other": b, "self": a}.get(which, which) if isinstance(which, str) else which


@fuzz(300)
@given(
    kind=st.sampled_from(["rod", "cable", "pin"]),
    first=ends,
    second=ends,
    length=st.one_of(st.none(), numbers, anything),
    e=st.one_of(numbers, anything),
)
def test_any_link_arguments_make_a_link_or_a_clear_error(kind, first, second, length, e) -> None:  # type: ignore[no-untyped-def]
    a, b = body(0.0, 0.0), body(1.0, 0.0)
    x, y = pick(first, a, b), pick(second, a, b)
    make = {
        "rod": lambda: Rod(x, y, length),
        "cable": lambda: Cable(x, y, length, e),
        "pin": lambda: Pin(x, y),
    }[kind]
    ok, link = attempt(make, "body", "other", "point", "length", "restitution")
    if ok:
        assert link is not None
        assert link.body is x
        assert math.isfinite(link.length) and link.length >= 0.0
        assert 0.0 <= link.restitution <= 1.0
        if kind != "pin":
            assert link.length > 0.0 and link.other is not link.body


@st.composite
def linked_worlds(draw: st.DrawFn) -> tuple[World, list[Body], list[object], float]:
    n = draw(st.integers(1, 8))
    world = World(
        integrator=draw(st.sampled_from(["auto", "semi_implicit_euler", "velocity_verlet", "rk4"]))
    )
    if draw(st.booleans()):
        world.add_force(Gravity((0.0, -9.81)))
    bodies = []
    for k in range(n):
        pos = Vector(draw(st.floats(-5, 5)), draw(st.floats(-5, 5)))
        vel = Vector(draw(st.floats(-5, 5)), draw(st.floats(-5, 5)))
        mass = draw(st.floats(1e-3, 1e3))
        radius = draw(st.sampled_from([0.0, 0.0, 0.1, 0.3]))
        kinematic = draw(st.booleans()) and k > 0 and draw(st.booleans())
        bodies.append(
            world.add(Body(pos, vel, Vector(0, 0), mass=mass, radius=radius, kinematic=kinematic))
        )
    links: list[object] = []
    for _ in range(draw(st.integers(0, 10))):
        i = draw(st.integers(0, n - 1))
        kind = draw(st.sampled_from(["rod", "cable", "pin", "rod-point"]))
        j = draw(st.integers(0, n - 1))
        point = (draw(st.floats(-5, 5)), draw(st.floats(-5, 5)))
        length = draw(st.floats(0.1, 5.0))
        e = draw(st.floats(0.0, 1.0))
        a, b = bodies[i], bodies[j]

        def make(
            kind: str = kind,
            a: Body = a,
            b: Body = b,
            p: tuple = point,
            length: float = length,
            e: float = e,
        ) -> object:
            if kind == "rod":
                return Rod(a, b)
            if kind == "cable":
                return Cable(a, b, length, e)
            return Pin(a, p) if kind == "pin" else Rod(a, p)

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # bodies that start overlapping
            ok, link = attempt(
                lambda: world.add_link(make()),  # noqa: B023 - called at once
                "other",
                "length",
                "body",
                "pinned",
                "kinematic",
            )
        if ok:
            links.append(link)
    return world, bodies, links, draw(st.sampled_from([1 / 60, 1 / 240]))


@fuzz(60)
@given(scene=linked_worlds())
def test_linked_worlds_step_finite_hold_their_links_and_rerun_bit_for_bit(scene) -> None:  # type: ignore[no-untyped-def]
    world, bodies, links, dt = scene
    snap = world.snapshot()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for _ in range(60):
            world.step(dt)
    x = world.positions().copy()
    assert np.isfinite(x).all() and np.isfinite(world.velocities()).all()
    stretched = any(
        issubclass(w.category, StabilityWarning) and "stretched" in str(w.message) for w in caught
    )
    pinned = {p.body for p in links if isinstance(p, Pin)}
    for link in links:
        if isinstance(link, Pin):
            assert link.body.pos == link.point
            continue
        other = link.other
        end = other.pos if isinstance(other, Body) else other
        d = (link.body.pos - end).length()
        # A link between two ends nothing can move (kinematic, pinned or a point) holds
        # nothing; every other one holds.
        fixed = [
            b is None or b.kinematic or b in pinned
            for b in (link.body, other if isinstance(other, Body) else None)
        ]
        if stretched or all(fixed):
            continue
        if isinstance(link, Rod):
            assert abs(d - link.length) <= 1e-9 * max(link.length, 1.0)
        else:
            assert d <= link.length * (1.0 + 1e-9)
    world.restore(snap)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(60):
            world.step(dt)
    assert np.array_equal(world.positions(), x)


@fuzz(100)
@given(value=anything)
def test_kinematic_takes_only_a_bool(value) -> None:  # type: ignore[no-untyped-def]
    ok, made = attempt(
        lambda: Body(Vector(0, 0), Vector(0, 0), Vector(0, 0), kinematic=value), "kinematic"
    )
    assert ok == isinstance(value, bool)
    if ok:
        assert made is not None and made.kinematic is value


@fuzz(100)
@given(target=pairs)
def test_a_kinematic_body_moved_anywhere_is_a_target_or_a_clear_error(target) -> None:  # type: ignore[no-untyped-def]
    world = World()
    paddle = world.add(Body(Vector(0, 0), Vector(0, 0), Vector(0, 0), radius=0.5, kinematic=True))
    ball = world.add(Body(Vector(3, 0), Vector(0, 0), Vector(0, 0), radius=0.5))
    ok, _ = attempt(lambda: setattr(paddle, "pos", target), "pos")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        # A finite position too far for one step's speed is refused at the step.
        stepped, _ = attempt(lambda: world.step(1 / 60), "pos")
        if not stepped:
            ok = False
            world.step(1 / 60)  # the move was dropped: the World steps on
    assert np.isfinite(world.positions()).all()
    if not ok:
        assert paddle.pos == Vector(0, 0)  # refused whole: nothing moved
    assert ball.pos.x >= 3.0 - 1e-12  # struck or not, never pulled
    _ = moderate
