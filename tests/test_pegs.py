"""A ball going over a round peg: it slides on the arc with the energy the closed form gives,
and leaves where the closed form says (within a step), under every method, with one begin
and one end (pymunk's test suite found it clinging under semi-implicit Euler: 32 impacts a
step, velocity set to zero, 225 ends)."""

from __future__ import annotations

import math

import pytest

from engine import Body, Circle, Segment, Vector, World
from engine.forces import Gravity

G, R_PEG, R_BALL, V0, DT = 9.81, 0.5, 0.1, 0.1, 1 / 60


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "velocity_verlet", "rk4", "auto"])
def test_a_frictionless_ball_leaves_a_peg_where_the_closed_form_says(integrator: str) -> None:
    w = World(integrator=integrator)
    w.add_force(Gravity((0, -G)))
    peg = w.add_collider(Circle((0, 0), R_PEG))
    ball = w.add(
        Body(Vector(0, R_PEG + R_BALL), Vector(V0, 0), Vector(0, 0), radius=R_BALL, friction=0.0)
    )
    began, ended = [], []
    w.on_contact(ball, begin=began.append, end=ended.append)
    rc = R_PEG + R_BALL
    while w.resting(ball) is not None or w.t == 0.0:
        w.step(DT)
        if w.resting(ball) is not None:
            # On the arc, its speed is the energy's: v^2 = v0^2 + 2 g (rc - y).
            speed = math.sqrt(V0 * V0 + 2 * G * (rc - ball.pos.y))
            assert abs(ball.vel.magnitude() - speed) <= 1e-9 * speed
            assert abs(ball.pos.magnitude() - rc) <= 1e-12
        assert w.t < 2.0
    for _ in range(60):
        w.step(DT)
    assert w.capped == 0
    assert [e.collider for e in began] == [peg] and [e.collider for e in ended] == [peg]
    # It leaves when the arc asks more than gravity's part along the normal can give:
    # v^2 / rc = g cos(theta), with v^2 = v0^2 + 2 g rc (1 - cos(theta)).
    theta = math.acos((V0 * V0 / rc + 2 * G) / (3 * G))
    left = math.atan2(ended[0].point.x, ended[0].point.y)
    step = math.sqrt(G * rc * math.cos(theta)) / rc * DT  # the angle it turns in one step
    assert theta <= left <= theta + step
    assert ball.pos.y < -5.0  # and fell away


@pytest.mark.parametrize(
    ("collider", "start", "velocity", "r", "mu"),
    [
        # Found by a search of one-ball scenes: an inelastic ball striking a peg's upper side,
        # and one striking a slanted capsule's underside, as gravity pulls it away again.
        (Circle((0.298, 0.199), 0.834), (-1.321, 1.256), (6.586, -6.361), 0.5, 0.0),
        (
            Segment((-2.744, -0.055), (2.971, -2.202), 0.2),
            (1.469, 0.025),
            (2.996, -1.157),
            0.2,
            0.5,
        ),
    ],
)
def test_an_inelastic_hit_that_gravity_pulls_away_is_one_begin_and_one_end(
    collider, start, velocity, r: float, mu: float
) -> None:
    w = World(integrator="semi_implicit_euler")
    w.add_force(Gravity((0, -G)))
    c = w.add_collider(collider)
    ball = w.add(
        Body(
            Vector(*start), Vector(*velocity), Vector(0, 0), radius=r, restitution=0.0, friction=mu
        )
    )
    began, ended = [], []
    w.on_contact(ball, begin=began.append, end=ended.append)
    for _ in range(120):
        w.step(DT)
    assert w.capped == 0
    assert [e.collider for e in began] == [c] and [e.collider for e in ended] == [c]
    assert ball.pos.y < -10.0 and ball.vel.y < -10.0  # it went on falling, never stuck
