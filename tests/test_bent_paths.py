"""A body that bounces off a collider and meets another body within the same step.

The static contacts bend a body's path within a step (engine.exact.bent_paths); the bodies must meet
one another on the bent path, at the exact moments, as on a straight one. Each test derives the
exact answer in closed form (the bounce off the wall at the time its line is reached, the
velocity mirrored in the wall's normal; then the meeting of two paths, the closed-form 2D
collision of two discs) and checks the engine's step against it, on both paths (engine.kernels).
Before the fix the pair was never searched (its broadphase looked around where the free path
ends, through the wall) or only along the last straight piece, and the ball passed through.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from engine import Body, Segment, Vector, World, kernels
from engine.forces import Gravity

PATHS = ["numpy", "fast"] if kernels.available() else ["numpy"]
TOL = 1e-12


def ball(pos: Any, vel: Any, radius: float, mass: float = 1.0) -> Body:
    """A frictionless, perfectly elastic disc that does not turn."""
    return Body(
        Vector(*pos), Vector(*vel), Vector(0.0, 0.0), mass, radius=radius, restitution=1.0,
        friction=0.0, fixed_rotation=True,
    )  # fmt: skip


def vec(v: Vector) -> np.ndarray:
    """A Vector as a numpy array."""
    return np.array([v.x, v.y])


def wall_time(x: np.ndarray, v: np.ndarray, p: np.ndarray, n: np.ndarray, r: float) -> float:
    """When a centre moving from x at v reaches distance r from the line through p with unit
    normal n, approaching it: (x + v t - p).n = r."""
    return float((r - (x - p) @ n) / (v @ n))


def meet_time(d: np.ndarray, w: np.ndarray, R: float) -> float:
    """The first t >= 0 with |d + w t| = R (closing): the smaller root of |w|^2 t^2 +
    2 d.w t + |d|^2 - R^2 = 0."""
    A, B, C = w @ w, 2.0 * (d @ w), d @ d - R * R
    return float((-B - math.sqrt(B * B - 4.0 * A * C)) / (2.0 * A))


def collide(
    xa: np.ndarray, va: np.ndarray, ma: float, xb: np.ndarray, vb: np.ndarray, mb: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Velocities of two frictionless discs after an elastic impact at centres xa, xb, and
    the impulse on a: J = 2 u / (1/m_a + 1/m_b) along n = (xa - xb) / |xa - xb|, u the
    closing speed."""
    n = (xa - xb) / np.linalg.norm(xa - xb)
    u = -((va - vb) @ n)
    J = 2.0 * u / (1.0 / ma + 1.0 / mb) * n
    return va + J / ma, vb - J / mb, J


def close(got: Vector, want: np.ndarray) -> bool:
    """Whether a Vector equals an array to TOL in each component."""
    return bool(np.all(np.abs(vec(got) - want) <= TOL * (1.0 + np.abs(want))))


def kinetic(bodies: list[Body]) -> float:
    """Kinetic energy (J) of bodies that do not turn."""
    return sum(0.5 * b.mass * (b.vel.x**2 + b.vel.y**2) for b in bodies)


def momentum(bodies: list[Body]) -> np.ndarray:
    """Total momentum (N s)."""
    return sum((b.mass * vec(b.vel) for b in bodies), np.zeros(2))


def walls_gave(world: World) -> np.ndarray:
    """The momentum (N s) the colliders gave in the last step, as its events report it (the
    impulses between bodies cancel in pairs)."""
    hits = [e for e in world.began if not isinstance(e.collider, Body)]
    return sum((vec(e.impulse) for e in hits), np.zeros(2))


@pytest.mark.parametrize("path", PATHS)
def test_a_ball_bounced_off_a_wall_meets_the_ball_behind_it(path: str) -> None:
    """The reported case: a, at x = 1.5 moving at 4 m/s toward a wall at x = 2, meets it when
    its centre is at 1.75, at t = 0.25 / 4 = 0.0625 s; it comes back at -4 m/s and meets b (at
    rest at 0.9) when the centres are 0.5 apart, at x_a = 1.4: t = 0.0625 + 0.35 / 4 = 0.15 s.
    Equal masses, e = 1: a stops, b leaves at -4 m/s, so at t = 0.4 s a is at 1.4 at rest
    and b at 0.9 - 4 * 0.25 = -0.1."""
    w = World(kernels=path)
    wall = Segment((2.0, -5.0), (2.0, 5.0), restitution=1.0)
    w.add_collider(wall)
    a = Body(Vector(1.5, 0.0), Vector(4.0, 0.0), Vector(0, 0), radius=0.25, restitution=1.0)
    b = Body(Vector(0.9, 0.0), Vector(0.0, 0.0), Vector(0, 0), radius=0.25, restitution=1.0)
    w.add_all([a, b])
    p0 = a.mass * vec(a.vel) + b.mass * vec(b.vel)
    k0 = kinetic([a, b])
    w.step(0.4)
    assert close(a.pos, np.array([1.4, 0.0])) and close(a.vel, np.array([0.0, 0.0]))
    assert close(b.pos, np.array([-0.1, 0.0])) and close(b.vel, np.array([-4.0, 0.0]))
    assert abs(kinetic([a, b]) - k0) <= TOL * k0
    # The events: the wall's bounce at 0.0625 s, then the impact of a on b at 0.15 s, at
    # b's surface (1.15, 0), normal toward a, impulse +4 on a (momentum: the wall's -8 and
    # this one's +4 and -4 add to what changed).
    began = sorted(w.began, key=lambda e: e.time)
    assert [(e.body, e.collider) for e in began] == [(a, wall), (a, b)]
    hit_wall, hit_b = began
    assert abs(hit_wall.time - 0.0625) <= TOL and close(hit_wall.impulse, np.array([-8.0, 0.0]))
    assert abs(hit_b.time - 0.15) <= TOL
    assert close(hit_b.point, np.array([1.15, 0.0])) and close(hit_b.normal, np.array([1.0, 0.0]))
    assert close(hit_b.impulse, np.array([4.0, 0.0]))
    p1 = a.mass * vec(a.vel) + b.mass * vec(b.vel)
    assert np.allclose(p1 - p0, vec(hit_wall.impulse), rtol=0.0, atol=TOL)
    assert [(e.body, e.collider) for e in sorted(w.ended, key=lambda e: e.time)] == [
        (a, wall),
        (a, b),
    ]


@pytest.mark.parametrize("path", PATHS)
def test_a_ball_bounced_off_a_slanted_wall_strikes_a_ball_off_centre(path: str) -> None:
    """A wall through p = (2, 0) slanted at 30 degrees from the vertical (unit normal n into
    the room, toward -x): a ball thrown at it is mirrored, v' = v - 2 (v.n) n, and its new
    path comes back up past where it started and strikes a ball that stands off its line,
    obliquely (about 30 degrees). Exact: the wall's time, then the meeting of the mirrored
    path with b, then the 2D elastic collision (unequal masses)."""
    r, ma, mb, dt = 0.2, 1.0, 2.0, 0.8
    p = np.array([2.0, 0.0])
    tilt = math.radians(30.0)
    n = np.array([-math.cos(tilt), math.sin(tilt)])  # into the room
    along = np.array([n[1], -n[0]])
    xa0, va0 = np.array([1.0, 0.0]), np.array([5.0, 0.0])
    xb0 = np.array([0.7, 2.25])
    t1 = wall_time(xa0, va0, p, n, r)
    c1 = xa0 + va0 * t1
    va1 = va0 - 2.0 * (va0 @ n) * n
    t2 = t1 + meet_time(c1 - xb0, va1, 2.0 * r)
    assert 0.0 < t1 < t2 < dt
    xa2 = c1 + va1 * (t2 - t1)
    va2, vb2, J = collide(xa2, va1, ma, xb0, np.zeros(2), mb)
    assert abs(((xa2 - xb0) / (2 * r)) @ (va1 / np.linalg.norm(va1))) < 0.95  # off centre
    want_a, want_b = xa2 + va2 * (dt - t2), xb0 + vb2 * (dt - t2)
    # Neither meets the wall again, nor each other, before dt.
    assert ((want_a - p) @ n) > r and ((want_b - p) @ n) > r
    assert np.linalg.norm(want_a - want_b) > 2 * r

    w = World(kernels=path)
    w.add_collider(Segment(p - 6.0 * along, p + 6.0 * along, restitution=1.0))
    a, b = ball(xa0, va0, r, ma), ball(xb0, (0.0, 0.0), r, mb)
    w.add_all([a, b])
    k0, p0 = kinetic([a, b]), momentum([a, b])
    w.step(dt)
    assert np.allclose(momentum([a, b]) - p0, walls_gave(w), rtol=0.0, atol=TOL * 10)
    assert close(a.pos, want_a) and close(a.vel, va2)
    assert close(b.pos, want_b) and close(b.vel, vb2)
    assert abs(kinetic([a, b]) - k0) <= TOL * k0
    hit = [e for e in w.began if e.collider is b]
    assert len(hit) == 1 and abs(hit[0].time - t2) <= TOL
    assert close(hit[0].impulse, J)


@pytest.mark.parametrize("path", PATHS)
def test_a_ball_dropped_on_a_floor_bounces_up_into_a_ball_above_within_a_step(path: str) -> None:
    """Under gravity g (the closed form, "auto"): a is thrown down at 20 m/s from 0.3 m over
    a floor, b falls from rest at 0.9 m, radius 0.1. a reaches the floor when its parabola
    0.3 - 20 t - g t^2 / 2 is 0.1 (the root of a quadratic) and leaves at minus its speed
    then; from there the gap y_b - y_a is linear in t (g cancels: both fall alike), so the
    meeting is where it is 2r. Equal masses, e = 1: they swap velocities, and fly on as
    parabolas to the step's end, 0.06 s."""
    g, r, dt = 9.81, 0.1, 0.06
    ya0, va0, yb0 = 0.3, -20.0, 0.9
    # 0.1 = ya0 + va0 t - g t^2 / 2: g/2 t^2 - va0 t + (0.1 - ya0) = 0, the smaller root.
    qa, qb, qc = 0.5 * g, -va0, r - ya0
    t1 = (-qb + math.sqrt(qb * qb - 4 * qa * qc)) / (2 * qa)
    up = -(va0 - g * t1)  # the rebound speed
    # gap(t) = y_b(t) - y_a(t), linear after t1: y_b = yb0 - g t^2 / 2, y_a = r + up (t - t1)
    # - g (t - t1)^2 / 2, so gap = yb0 - r + up t1 + g t1^2 / 2 - (up + g t1) t.
    t2 = (yb0 - r + up * t1 + 0.5 * g * t1 * t1 - 2 * r) / (up + g * t1)
    assert 0.0 < t1 < t2 < dt
    ya2, va2 = r + up * (t2 - t1) - 0.5 * g * (t2 - t1) ** 2, up - g * (t2 - t1)
    yb2, vb2 = yb0 - 0.5 * g * t2 * t2, -g * t2
    assert abs((yb2 - ya2) - 2 * r) < 1e-12
    s = dt - t2
    want_a = (ya2 + vb2 * s - 0.5 * g * s * s, vb2 - g * s)  # they swap velocities
    want_b = (yb2 + va2 * s - 0.5 * g * s * s, va2 - g * s)
    assert want_a[0] > r  # a does not reach the floor again

    w = World(integrator="auto", kernels=path)
    w.add_force(Gravity((0.0, -g)))
    w.add_collider(Segment((-5.0, 0.0), (5.0, 0.0), restitution=1.0))
    a, b = ball((0.0, ya0), (0.0, va0), r), ball((0.0, yb0), (0.0, 0.0), r)
    w.add_all([a, b])

    def energy() -> float:
        """Kinetic plus potential energy (J): e = 1 everywhere keeps it."""
        return kinetic([a, b]) + g * (a.mass * a.pos.y + b.mass * b.pos.y)

    e0 = energy()
    w.step(dt)
    assert close(a.pos, np.array([0.0, want_a[0]])) and close(a.vel, np.array([0.0, want_a[1]]))
    assert close(b.pos, np.array([0.0, want_b[0]])) and close(b.vel, np.array([0.0, want_b[1]]))
    assert abs(energy() - e0) <= TOL * e0
    hit = [e for e in w.began if e.collider is b]
    assert len(hit) == 1 and abs(hit[0].time - t2) <= TOL


@pytest.mark.parametrize("path", PATHS)
def test_two_balls_each_bounced_off_its_wall_meet_in_between(path: str) -> None:
    """Walls at x = -2 and x = 2; a (1 kg) flies left at 4 m/s from -1.5, b (3 kg) right at
    3 m/s from 1.4, radius 0.25: a meets its wall at x = -1.75 at 0.0625 s, b its own at 1.75
    at 0.35 / 3 s; they come back and meet when 0.5 apart, and part as the 1D elastic
    collision says: v_a' = ((m_a - m_b) v_a + 2 m_b v_b) / (m_a + m_b), and b's likewise."""
    r, ma, mb, dt = 0.25, 1.0, 3.0, 0.6
    ta, tb = 0.25 / 4.0, 0.35 / 3.0
    # After both bounces: x_a = -1.75 + 4 (t - ta), x_b = 1.75 - 3 (t - tb); gap 2r when
    # 3.5 - 4 (t - ta) - 3 (t - tb) = 0.5.
    t2 = (3.0 + 4.0 * ta + 3.0 * tb) / 7.0
    assert max(ta, tb) < t2 < dt
    xa2, xb2 = -1.75 + 4.0 * (t2 - ta), 1.75 - 3.0 * (t2 - tb)
    ua = ((ma - mb) * 4.0 + 2 * mb * -3.0) / (ma + mb)
    ub = ((mb - ma) * -3.0 + 2 * ma * 4.0) / (ma + mb)
    want_a, want_b = xa2 + ua * (dt - t2), xb2 + ub * (dt - t2)
    assert -2.0 + r < want_a and want_b < 2.0 - r  # no wall again

    w = World(kernels=path)
    for x in (-2.0, 2.0):
        w.add_collider(Segment((x, -5.0), (x, 5.0), restitution=1.0))
    a, b = ball((-1.5, 0.0), (-4.0, 0.0), r, ma), ball((1.4, 0.0), (3.0, 0.0), r, mb)
    w.add_all([a, b])
    k0, p0 = kinetic([a, b]), momentum([a, b])
    w.step(dt)
    # The walls gave m_a 8 and -m_b 6 (N s); the impact's impulses cancel.
    assert np.allclose(walls_gave(w), [8.0 - 18.0, 0.0], rtol=0.0, atol=TOL * 20)
    assert np.allclose(momentum([a, b]) - p0, walls_gave(w), rtol=0.0, atol=TOL * 20)
    assert close(a.pos, np.array([want_a, 0.0])) and close(a.vel, np.array([ua, 0.0]))
    assert close(b.pos, np.array([want_b, 0.0])) and close(b.vel, np.array([ub, 0.0]))
    assert abs(kinetic([a, b]) - k0) <= TOL * k0
    hit = [e for e in w.began if e.collider is b]
    assert len(hit) == 1 and abs(hit[0].time - t2) <= TOL


# -- the property: balls in a box, one step, against an exact event-driven reference -------------

HALF = 2.0  # the box is [-HALF, HALF]^2


def reference(
    x: np.ndarray, v: np.ndarray, r: np.ndarray, m: np.ndarray, dt: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Frictionless elastic discs in the box over dt, event by event: the earliest of every
    ball's wall and every pair's meeting (``meet_time``), applied, then the next, in exact
    time order. (x, v, the walls' total impulse), or None where two events come within 1e-6
    s of each other or a pair grazes (closing slower than 1e-3 m/s): the order of
    near-simultaneous events is rounding's, no test of the engine."""
    x, v = x.copy(), v.copy()
    wall_impulse = np.zeros(2)
    t = 0.0
    for _ in range(200):
        times: list[tuple[float, str, int, int]] = []
        for i in range(len(x)):
            for k in range(2):
                if v[i, k] > 1e-9:
                    times.append(((HALF - r[i] - x[i, k]) / v[i, k], "wall", i, k))
                elif v[i, k] < -1e-9:
                    times.append(((-HALF + r[i] - x[i, k]) / v[i, k], "wall", i, k))
            for j in range(i + 1, len(x)):
                d, w = x[i] - x[j], v[i] - v[j]
                R = r[i] + r[j]
                if d @ w < 0.0 and (d @ w) ** 2 - (w @ w) * (d @ d - R * R) > 0.0:
                    times.append((meet_time(d, w, R), "pair", i, j))
        times.sort()
        left = [e for e in times if e[0] <= dt - t + 1e-6]
        if len(left) >= 2 and left[1][0] - left[0][0] < 1e-6:
            return None
        if not left or left[0][0] > dt - t:
            if left:
                return None  # an event within 1e-6 s of the step's end
            return x + v * (dt - t), v, wall_impulse
        tau, kind, i, j = left[0]
        x += v * tau
        t += tau
        if kind == "wall":
            wall_impulse[j] += -2.0 * m[i] * v[i, j]
            v[i, j] = -v[i, j]
        else:
            n = (x[i] - x[j]) / np.linalg.norm(x[i] - x[j])
            if -((v[i] - v[j]) @ n) < 1e-3:
                return None
            v[i], v[j], _ = collide(x[i], v[i], m[i], x[j], v[j], m[j])
    return None


@st.composite
def boxes(draw: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Two or three balls in the box, apart from each other and the walls."""
    k = draw(st.integers(2, 3))
    r = np.array([draw(st.floats(0.1, 0.4)) for _ in range(k)])
    m = np.array([draw(st.floats(0.5, 3.0)) for _ in range(k)])
    x = np.array([[draw(st.floats(-HALF + ri + 0.01, HALF - ri - 0.01)) for _ in range(2)]
                  for ri in r])  # fmt: skip
    v = np.array([[draw(st.floats(-6.0, 6.0)) for _ in range(2)] for _ in range(k)])
    return x, v, r, m


def scene_of(*rows: tuple[float, float, float, float, float, float]) -> tuple[np.ndarray, ...]:
    """A scene for ``boxes``' test from rows (x, y, vx, vy, radius, mass)."""
    a = np.array(rows, dtype=float)
    return a[:, 0:2], a[:, 2:4], a[:, 4], a[:, 5]


@pytest.mark.parametrize("path", PATHS)
@settings(max_examples=150, deadline=None)
@given(scene=boxes())
# c's floor bounce (0.4375 s, found by the static contacts) never happens: b, back from
# its wall at 0.25 s, strikes c at 0.34 s; c then meets the floor at 0.475 s instead.
@example(scene=scene_of((0, 0, 0, 0, 0.25, 1), (1, -1.5, 3, 0, 0.25, 1), (1, 0, 0, -4, 0.25, 1)))
# After the impact at 0.098 s, b meets its wall at 0.27 s and comes back into a at 0.36 s,
# before a reaches the ceiling (0.47 s on the path the impact gave it).
@example(scene=scene_of((-0.125, -0.25, 3, 5, 0.25, 2), (0.5, 0.5, 1, 0, 0.25, 0.5)))
# The light ball struck into the ceiling: the event's impulse is its change of momentum.
@example(scene=scene_of((0, 1, 0, 0, 0.25, 0.5), (0, 0, 0, 3, 0.25, 1)))
def test_balls_in_a_box_meet_as_the_exact_events_say(path: str, scene: Any) -> None:
    """Balls in a box of four walls, one step of 0.5 s (long enough for several bounces
    each): the step ends where the exact events, replayed one by one, say; kinetic energy is
    kept to 1e-12 (e = 1, no friction), and momentum changes by exactly the walls' impulses
    the events report (the pairs' cancel)."""
    x, v, r, m = scene
    dt = 0.5
    for i in range(len(x)):
        for j in range(i):
            assume(np.linalg.norm(x[i] - x[j]) > r[i] + r[j] + 0.01)
    want = reference(x, v, r, m, dt)
    assume(want is not None)
    assert want is not None
    wx, wv, wall_impulse = want

    w = World(kernels=path)
    long = HALF + 1.0  # past the corners: no ball meets a wall's round end
    for s in (-HALF, HALF):
        w.add_collider(Segment((-long, s), (long, s), restitution=1.0))
        w.add_collider(Segment((s, -long), (s, long), restitution=1.0))
    bodies = [ball(x[i], v[i], r[i], m[i]) for i in range(len(x))]
    w.add_all(bodies)
    k0, p0 = kinetic(bodies), momentum(bodies)
    w.step(dt)
    for i, body in enumerate(bodies):
        assert np.allclose(vec(body.pos), wx[i], rtol=0.0, atol=1e-9), (i, body.pos, wx[i])
        assert np.allclose(vec(body.vel), wv[i], rtol=0.0, atol=1e-9), (i, body.vel, wv[i])
    assert abs(kinetic(bodies) - k0) <= TOL * k0
    reported = walls_gave(w)
    scale = 1.0 + float(np.abs(wall_impulse).sum())
    assert np.allclose(momentum(bodies) - p0, reported, rtol=0.0, atol=TOL * scale)
    assert np.allclose(reported, wall_impulse, rtol=0.0, atol=1e-9 * scale)
