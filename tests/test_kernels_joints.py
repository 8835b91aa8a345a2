"""The joint solver's loop kernels (engine.exact.joint_rows' ``rows_loop`` and ``turned_loop``)
against their numpy twins.

Each row's value c and its gradient's row of J come from the same products in the same order,
so the two agree to 1e-12 relative on random rows of every kind (a point two bodies share, a
distance, an angle, a motor, a soft weld's, a contact's normal and slip), to a body or to the
world, at random positions and angles; and a whole step of jointed scenes (a chain of hinges,
a car on its motor, the pinball's flipper knocked by a ball) reads the same on both paths.
Without numba the kernel runs as the plain Python it is written in (``LoopKernel.py``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import demos.pinball as pb
from engine import Body, Polygon, Vector, World, kernels
from engine.dynamics.joints import Hinge
from engine.exact.joint_rows import CN, CT, Plan, _rows, _turned, evaluate, rows_loop, turned_loop
from engine.forces import Gravity
from engine.geometry.manifold_kinds import Polygons
from engine.kernels import LoopKernel

COMPILED = kernels.available()
seeds = st.integers(0, 2**32 - 1)


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not COMPILED:
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def close(x: np.ndarray, y: np.ndarray, rel: float = 1e-12) -> bool:
    """Equal to ``rel`` relative, against the largest magnitude of either."""
    scale = max(1.0, float(np.abs(x).max(initial=0.0)), float(np.abs(y).max(initial=0.0)))
    return bool(np.all(np.abs(np.asarray(x) - np.asarray(y)) <= rel * scale))


def random_plan(seed: int) -> tuple[np.ndarray, np.ndarray, Plan]:
    """Positions (m, 2) and angles (m,) of m joined bodies, and R rows of every kind among
    them: each to another body or (a fifth of them) to the world, anchors and bounds, and a
    contact's normal, lever arms, reference places and gap."""
    rng = np.random.default_rng(seed)
    m = int(rng.integers(1, 6))
    R = int(rng.integers(1, 24))
    X = rng.uniform(-50.0, 50.0, (m, 2))
    TH = rng.uniform(-7.0, 7.0, m)
    kind = rng.integers(0, CT + 1, R).astype(np.intp)
    a = rng.integers(0, m, R).astype(np.intp)
    b = rng.integers(0, m, R).astype(np.intp)
    world = (rng.random(R) < 0.2) | (a == b)
    b[world] = -1
    angle = rng.uniform(0.0, 2.0 * math.pi, R)
    normal = np.stack([np.cos(angle), np.sin(angle)], 1)
    touch = (
        normal,
        rng.uniform(-2.0, 2.0, (R, 2)),  # the contact point less the body's centre
        rng.uniform(-2.0, 2.0, (R, 2)),  # ... less the other's
        X[a] + rng.uniform(-0.1, 0.1, (R, 2)),  # where the body was
        np.where(world[:, None], 0.0, X[np.maximum(b, 0)] + rng.uniform(-0.1, 0.1, (R, 2))),
        TH[a] + rng.uniform(-0.2, 0.2, R),
        np.where(world, 0.0, TH[np.maximum(b, 0)] + rng.uniform(-0.2, 0.2, R)),
        rng.uniform(-0.05, 0.05, R),  # the gap
        np.zeros(R, dtype=np.int8),
        np.full(R, -1, dtype=np.intp),
        np.zeros(R),
    )
    # A distance row whose two anchors meet (length 0) takes the twin's guard too.
    aa = rng.uniform(-3.0, 3.0, (R, 2))
    ab = rng.uniform(-3.0, 3.0, (R, 2))
    bound = rng.uniform(0.0, 4.0, R)
    return X, TH, Plan(kind, bound, a, b, aa, ab, touch, 3 * m)


@settings(max_examples=60, deadline=None)
@given(seeds)
def test_rows_loop_is_its_twin(seed: int) -> None:
    X, TH, P = random_plan(seed)
    want_c, want_J = _rows(X, TH, P)
    got_c, got_J = rows_loop.fast(X, TH, P.ints, P.floats, P.width)
    assert close(got_c, want_c)
    assert close(got_J, want_J)
    # Each row touches the columns of its own bodies only.
    assert np.array_equal(got_J != 0.0, want_J != 0.0)


#: A box, a triangle (padded to four vertices by repeating its last, as Polygons pads) and a
#: capsule's core (a two-vertex polygon, rounded 0.3), each of about a unit's size.
SHAPES = Polygons(
    np.array(
        [
            [[-1.0, -0.5], [1.0, -0.5], [1.0, 0.5], [-1.0, 0.5]],
            [[0.0, 0.0], [1.5, 0.0], [0.0, 1.0], [0.0, 1.0]],
            [[-1.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 0.0]],
        ]
    ),
    np.array(
        [
            [[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]],
            [[0.0, -1.0], [0.5547001962252291, 0.8320502943378437], [-1.0, 0.0], [-1.0, 0.0]],
            [[0.0, -1.0], [0.0, 1.0], [0.0, 1.0], [0.0, 1.0]],
        ]
    ),
    np.array([4, 3, 2]),
    np.array([0.0, 0.0, 0.3]),
)


def turned_plan(seed: int) -> tuple[np.ndarray, np.ndarray, Plan]:
    """Positions and angles of m bodies, and contacts of a disc against a polygon that turns
    (a normal row and a slip row each; the polygon the body or the other, the other a body
    or the world), at random places and angles about the shapes: inside, outside, past a
    corner, and with a path from where they began that crosses the shape."""
    rng = np.random.default_rng(seed)
    m = int(rng.integers(1, 5))
    k = int(rng.integers(1, 8))
    X = rng.uniform(-2.0, 2.0, (m, 2))
    TH = rng.uniform(-4.0, 4.0, m)
    a = rng.integers(0, m, k)
    b = rng.integers(0, m, k)
    b[(rng.random(k) < 0.25) | (a == b)] = -1
    turn = np.where(rng.random(k) < 0.5, 1, -1).astype(np.int8)
    turn[b < 0] = 1  # the world is no polygon here: the body is
    poly = rng.integers(0, len(SHAPES), k)
    bc = np.maximum(b, 0)
    refb = X[a] + rng.uniform(-2.5, 2.5, (k, 2))
    refo = np.where((b < 0)[:, None], 0.0, X[bc] + rng.uniform(-2.5, 2.5, (k, 2)))
    thb = TH[a] + rng.uniform(-1.0, 1.0, k)
    tho = np.where(b < 0, 0.0, TH[bc] + rng.uniform(-1.0, 1.0, k))
    angle = rng.uniform(0.0, 2.0 * math.pi, k)
    two = lambda v: np.repeat(v, 2, axis=0)  # noqa: E731 (each contact's two rows)
    touch = (
        two(np.stack([np.cos(angle), np.sin(angle)], 1)),
        two(rng.uniform(-1.0, 1.0, (k, 2))),
        two(rng.uniform(-1.0, 1.0, (k, 2))),
        two(refb), two(refo), two(thb), two(tho),
        two(rng.uniform(-0.05, 0.05, k)),
        two(turn), two(poly), two(rng.uniform(0.05, 0.5, k)),
    )  # fmt: skip
    kind = np.tile([CN, CT], k)
    z = np.zeros((2 * k, 2))
    return X, TH, Plan(kind, np.zeros(2 * k), two(a), two(b), z, z, touch, 3 * m, SHAPES)


@settings(max_examples=80, deadline=None)
@given(seeds)
def test_turned_loop_is_its_twin_to_the_bit(seed: int) -> None:
    # The rows of a disc against a polygon that turns (the pinball's ball on its bat), which
    # the joints' solve evaluates a few times a step where the two touch: the kernel gives
    # the numpy twin's bits, whatever the shape, the side and the path.
    X, TH, P = turned_plan(seed)
    want_c, want_J = rows_loop.fast(X, TH, P.ints, P.floats, P.width)
    got_c, got_J = want_c.copy(), want_J.copy()
    _turned(X, TH, P, want_c, want_J)
    turned_loop.fast(X, TH, P.ints, P.floats, P.turned, SHAPES.vertices, SHAPES.normals,
                     SHAPES.count, SHAPES.radius, got_c, got_J)  # fmt: skip
    assert np.array_equal(got_c, want_c)
    assert np.array_equal(got_J, want_J)


def test_a_distance_of_zero_takes_the_guard() -> None:
    """Two anchors at one point: the distance row's gradient is 0 (not nan) on both paths."""
    X, TH = np.array([[0.0, 0.0], [1.0, 0.0]]), np.zeros(2)
    z2, z1 = np.zeros((1, 2)), np.zeros(1)
    touch = (z2, z2, z2, z2, z2, z1, z1, z1, np.zeros(1, np.int8), np.full(1, -1), z1)
    P = Plan(np.array([2]), np.array([0.5]), np.array([0]), np.array([1]),
             np.array([[0.5, 0.0]]), np.array([[-0.5, 0.0]]), touch, 6)  # fmt: skip
    for fast in (False, True):
        c, J = evaluate(X, TH, P, fast)
        assert c[0] == -0.5
        assert np.isfinite(J).all() and not J[0, :2].any()


def chain(path: str) -> World:
    """Five planks of 1 m hinged end to end from the world at the origin, a motor with limits
    at the top, dropped from horizontal."""
    world = World(kernels=path)
    world.add_force(Gravity((0.0, -9.81)))
    last = world.static_body
    for k in range(5):
        plank = Body(Vector(0.5 + k, 0.0), Vector(0.0, 0.0), Vector(0.0, 0.0), mass=1.0,
                     shape=Polygon.box(1.0, 0.1))  # fmt: skip
        world.add(plank)
        if k == 0:
            world.add_link(Hinge(plank, last, (0.0, 0.0), limits=(-1.0, 0.2), motor_speed=2.0,
                                 max_torque=3.0))  # fmt: skip
        else:
            world.add_link(Hinge(plank, last, (float(k), 0.0)))
        last = plank
    return world


def flipper(path: str) -> World:
    """The pinball's left flipper and a ball thrown onto it as the key is pressed."""
    world = World(integrator="auto", kernels=path)
    world.add_force(Gravity((0.0, -pb.GRAVITY)))
    _, hinge = pb.add_flipper(world, -1)
    pb.drive(hinge, -1, True)
    pivot = Vector(*pb.LEFT_PIVOT)
    ball = pb.add_ball(world, (pivot.x + 0.6 * pb.FLIPPER_LENGTH, pivot.y + 20.0))
    ball.vel = Vector(0.0, -300.0)
    return world


@pytest.mark.skipif(not COMPILED, reason="a World on the fast path needs numba (the fast extra)")
@pytest.mark.parametrize("scene", [chain, flipper])
def test_jointed_scenes_read_the_same_on_both_paths(scene: Any) -> None:
    """Steps of a falling chain on a motor at its limit, and of a ball meeting a flipper as it
    swings: every body's place, speed, angle and spin agree on both paths (to 1e-9 of the
    scene: a few steps, each a function of its inputs), and the joints hold on both."""
    worlds = [scene("numpy"), scene("fast")]
    assert [w.kernels for w in worlds] == ["numpy", "fast"]
    for _ in range(12):
        for w in worlds:
            w.step(1 / 120)
        a, b = (w.bodies for w in worlds)
        for p, q in zip(a, b, strict=True):
            assert close(np.array([*p.pos, *p.vel, p.angle, p.angular_velocity]),
                         np.array([*q.pos, *q.vel, q.angle, q.angular_velocity]), 1e-9)  # fmt: skip
