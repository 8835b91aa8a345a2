"""Discs that meet at an exact impact turn each other (engine.exact.pair_bounce): friction acts at
the point of contact, each body's angular momentum about that point is kept, the slip is
stopped or reduced by mu J, never reversed, and no energy is gained. Each test holds the
engine to a closed form or a theorem, to rounding where the answer is exact."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import engine.exact.pair_impacts as pair_impacts
from engine import Body, ContactEvent, Segment, Vector, World
from engine.exact.pair_bounce import Turns, bounce
from engine.forces import Gravity

G = 9.81


def cross(p: tuple[float, float], v: tuple[float, float]) -> float:
    return p[0] * v[1] - p[1] * v[0]


def spun_point(v: Vector, omega: float, x: Vector, c: tuple[float, float]) -> tuple[float, float]:
    """The velocity of a body's material point at c: v + omega x (c - x)."""
    px, py = c[0] - x.x, c[1] - x.y
    return (v.x - omega * py, v.y + omega * px)


def about(body: Body, c: tuple[float, float]) -> float:
    """A body's angular momentum about the fixed point c: I omega + m (x - c) x v."""
    lin = body.mass * cross((body.pos.x - c[0], body.pos.y - c[1]), (body.vel.x, body.vel.y))
    return body.moment * body.angular_velocity + lin


def energy(*bodies: Body) -> float:
    return sum(
        0.5 * b.mass * (b.vel.x**2 + b.vel.y**2) + 0.5 * b.moment * b.angular_velocity**2
        for b in bodies
    )


# -- the impulse itself (engine.exact.pair_bounce.bounce), on random impacts -----------------------


def one_impact(
    m: tuple[float, float],
    r: tuple[float, float],
    inv_moment: tuple[float, float],
    va: tuple[float, float],
    vb: tuple[float, float],
    omega: tuple[float, float],
    phi: float,
    e: float,
    mu: float,
    t: float = 0.025,
    dt: float = 0.1,
) -> tuple[np.ndarray, ...]:
    """Two discs touching at time t of a step of dt, a's centre at the origin and b's along
    the angle phi from it, with no acceleration: before and after (x at t, v, omega), the
    impulse on a and the point of contact."""
    n = np.array([math.cos(phi), math.sin(phi)])  # from a toward b
    x_t = np.array([[0.0, 0.0], (r[0] + r[1]) * n])
    V = np.array([va, vb], dtype=float)
    X = x_t + V * (dt - t)  # the paths' end states (A = 0)
    A = np.zeros((2, 2))
    w = np.array([1.0 / m[0], 1.0 / m[1]])
    rr = np.array(r, dtype=float)
    iI = np.array(inv_moment, dtype=float)
    turns = Turns(
        np.zeros(2), np.array(omega, dtype=float), np.zeros(2), iI.copy(),
        np.array([m[0] * r[0] ** 2 * iI[0], m[1] * r[1] ** 2 * iI[1]]), iI > 0.0, iI > 0.0,
    )  # fmt: skip
    before = (V.copy(), turns.omega.copy())
    got = bounce(
        np.array([0]), np.array([1]), np.array([t]), X, V, A, w, rr,
        np.array([e, 1.0]), np.array([mu, 1.0]), dt, turns,
    )  # fmt: skip
    c = x_t[0] + r[0] * n
    return before[0], before[1], V, turns.omega, got[4][0], c, x_t, n


finite = st.floats(-5.0, 5.0, allow_nan=False)
impacts = st.tuples(
    st.tuples(st.floats(0.1, 10.0), st.floats(0.1, 10.0)),  # masses
    st.tuples(st.floats(0.05, 2.0), st.floats(0.05, 2.0)),  # radii
    st.tuples(st.sampled_from([0.0, 0.5, 1.0, 2.0]), st.sampled_from([0.0, 0.5, 1.0, 2.0])),
    st.tuples(finite, finite),
    st.tuples(finite, finite),
    st.tuples(st.floats(-20.0, 20.0), st.floats(-20.0, 20.0)),
    st.floats(0.0, 2.0 * math.pi),
    st.floats(0.0, 1.0),  # e
    st.floats(0.0, 2.0),  # mu
)


@settings(max_examples=300, deadline=None)
@given(impacts)
def test_an_impact_keeps_momentum_and_each_bodys_angular_momentum_about_the_contact(
    case: tuple,
) -> None:
    m, r, q, va, vb, om, phi, e, mu = case
    # I from q = m r^2 / I (q 0: the body does not turn).
    inv = tuple(qk / (mk * rk * rk) for qk, mk, rk in zip(q, m, r, strict=True))
    om = tuple(wk if ik else 0.0 for wk, ik in zip(om, inv, strict=True))  # (what turns)
    V0, W0, V1, W1, P, c, x, n = one_impact(m, r, inv, va, vb, om, phi, e, mu)
    if -np.dot(V0[0] - V0[1], -n) <= 0.0:
        return  # not closing (the impacts are only ever found closing)
    scale = sum(mk * (abs(v[0]) + abs(v[1])) for mk, v in zip(m, V0, strict=True))
    scale += sum(abs(w) * rk / ik if ik else 0.0 for w, rk, ik in zip(W0, r, inv, strict=True))
    scale = max(scale, 1.0)
    # Momentum, and the impulse reported is a's change of it.
    for k in range(2):
        assert abs(m[0] * V1[0, k] + m[1] * V1[1, k] - (m[0] * V0[0, k] + m[1] * V0[1, k])) <= (
            1e-12 * scale
        )
        assert abs(m[0] * (V1[0, k] - V0[0, k]) - P[k]) <= 1e-12 * scale
    # Each body that turns keeps its angular momentum about the point of contact (the impulse
    # passes through it), and then the pair its angular momentum about the origin.
    total0 = total1 = 0.0
    for k in range(2):
        rel = x[k] - c
        if inv[k] > 0.0:
            L0 = W0[k] / inv[k] + m[k] * cross(rel, V0[k])
            L1 = W1[k] / inv[k] + m[k] * cross(rel, V1[k])
            assert abs(L1 - L0) <= 1e-12 * scale * max(1.0, r[0] + r[1])
        else:
            assert W1[k] == W0[k]
        total0 += (W0[k] / inv[k] if inv[k] else 0.0) + m[k] * cross(x[k], V0[k])
        total1 += (W1[k] / inv[k] if inv[k] else 0.0) + m[k] * cross(x[k], V1[k])
    if all(inv):
        assert abs(total1 - total0) <= 1e-12 * scale * max(1.0, r[0] + r[1])

    # Energy is never gained (e <= 1).
    def kinetic(V: np.ndarray, W: np.ndarray) -> float:
        lin = sum(0.5 * mk * float(v @ v) for mk, v in zip(m, V, strict=True))
        return lin + sum(0.5 * w * w / ik for w, ik in zip(W, inv, strict=True) if ik)

    E0, E1 = kinetic(V0, W0), kinetic(V1, W1)
    assert E1 <= E0 * (1.0 + 1e-12) + 1e-300

    # The slip at the point of contact is taken toward 0, never reversed.
    def slip(V: np.ndarray, W: np.ndarray) -> np.ndarray:
        pa = V[0] + W[0] * np.array([-(c - x[0])[1], (c - x[0])[0]])
        pb = V[1] + W[1] * np.array([-(c - x[1])[1], (c - x[1])[0]])
        d = pa - pb
        return d - n * float(d @ n)

    s0, s1 = slip(V0, W0), slip(V1, W1)
    assert float(s0 @ s1) >= -1e-12 * scale * scale
    assert float(s1 @ s1) <= float(s0 @ s0) * (1.0 + 1e-12) + 1e-24 * scale * scale
    # Coulomb: the tangential impulse is at most mu times the normal one.
    Jn = abs(float(P @ n))
    Jt = abs(cross(n, P))
    assert Jt <= mu * Jn * (1.0 + 1e-12) + 1e-15 * scale


def test_without_a_body_that_turns_or_without_friction_an_impact_is_todays_to_the_bit() -> None:
    """``Turns`` with no body that turns (or mu = 0) leaves ``bounce`` what it was without."""
    rng = np.random.default_rng(7)
    for lever, mu in ((False, 0.6), (True, 0.0)):
        X = rng.normal(size=(6, 2)) * 3.0
        V = rng.normal(size=(6, 2)) * 4.0
        A = rng.normal(size=(6, 2))
        w, r = rng.uniform(0.2, 2.0, 6), rng.uniform(0.1, 0.5, 6)
        e, m = rng.uniform(0.0, 1.0, 6), np.full(6, mu)
        pa, pb, t = np.array([0, 2, 4]), np.array([1, 3, 5]), np.array([0.01, 0.02, 0.05])
        Xp, Vp = X.copy(), V.copy()
        plain = bounce(pa, pb, t, Xp, Vp, A, w, r, e, m, 0.1)
        om = rng.normal(size=6)
        turns = Turns(
            np.zeros(6), om.copy(), np.zeros(6), np.where(lever, 1.0, 0.0) * np.ones(6),
            np.full(6, 2.0), np.full(6, lever), np.full(6, lever),
        )  # fmt: skip
        if not lever:
            turns = turns._replace(omega=np.zeros(6))
        Xs, Vs = X.copy(), V.copy()
        spun = bounce(pa, pb, t, Xs, Vs, A, w, r, e, m, 0.1, turns)
        assert np.array_equal(Xp, Xs) and np.array_equal(Vp, Vs)
        assert np.array_equal(plain[4], spun[4])
        assert np.array_equal(turns.omega, om if lever else np.zeros(6))


# -- scenes ----------------------------------------------------------------------------------


def free_world() -> World:
    return World()


@pytest.mark.parametrize("u_b, v_a", [(3.0, 0.0), (3.0, -1.0), (0.5, 2.0)])
def test_a_spinning_disc_struck_head_on_with_enough_friction_leaves_without_slip(
    u_b: float, v_a: float
) -> None:
    # a spins in place (omega0) or moves toward b; b comes at it along the line of centres.
    w = free_world()
    ra, rb = 0.5, 0.3
    a = w.add(Body(Vector(0.0, 0.0), Vector(v_a, 0.0), radius=ra, mass=2.0, friction=1.0,
                   restitution=0.5, angular_velocity=7.0))  # fmt: skip
    b = w.add(Body(Vector(1.2, 0.0), Vector(-u_b, 0.0), radius=rb, mass=1.0, friction=1.0,
                   restitution=0.5))  # fmt: skip
    T = (1.2 - ra - rb) / (u_b + v_a)  # the moment they meet
    c = (v_a * T + ra, 0.0)
    L_a, L_b = about(a, c), about(b, c)
    E0 = energy(a, b)
    p0 = a.mass * a.vel.x + b.mass * b.vel.x
    w.step(0.5)
    assert 0.0 < T < 0.5
    # The slip at the point of contact just after the impact is 0: the two material points
    # there move alike along the tangent (y).
    xa, xb = Vector(c[0] - ra, 0.0), Vector(c[0] + rb, 0.0)
    sa = spun_point(a.vel, a.angular_velocity, xa, c)
    sb = spun_point(b.vel, b.angular_velocity, xb, c)
    assert abs(sa[1] - sb[1]) <= 1e-12 * 7.0
    # Each keeps its angular momentum about c, the pair its momentum; no energy is gained.
    assert abs(about(a, c) - L_a) <= 1e-12 * 10.0
    assert abs(about(b, c) - L_b) <= 1e-12 * 10.0
    assert abs(a.mass * a.vel.x + b.mass * b.vel.x - p0) <= 1e-12 * 10.0
    assert abs(a.mass * a.vel.y + b.mass * b.vel.y) <= 1e-12 * 10.0
    assert energy(a, b) < E0
    # The closed form: with K = 1/m_a + 1/m_b + r_a^2 / I_a + r_b^2 / I_b (solid discs:
    # 3 (1/m_a + 1/m_b)) the impulse that stops the slip omega0 r_a is omega0 r_a / K.
    K = 3.0 * (1.0 / a.mass + 1.0 / b.mass)
    Jt = 7.0 * ra / K
    assert abs(b.mass * b.vel.y - Jt) <= 1e-12 * 10.0
    assert abs(a.angular_velocity - (7.0 - ra * Jt / a.moment)) <= 1e-12 * 10.0
    assert abs(b.angular_velocity - (-rb * Jt / b.moment)) <= 1e-12 * 10.0


def test_a_spinning_disc_struck_head_on_with_little_friction_takes_mu_j() -> None:
    w = free_world()
    a = w.add(Body(Vector(0.0, 0.0), Vector(0.0, 0.0), radius=0.5, mass=2.0, friction=0.2,
                   restitution=0.8, angular_velocity=30.0))  # fmt: skip
    b = w.add(Body(Vector(1.2, 0.0), Vector(-3.0, 0.0), radius=0.3, mass=1.0, friction=0.2,
                   restitution=0.8))  # fmt: skip
    w.step(0.5)
    J = b.mass * (b.vel.x - -3.0)  # the normal impulse on b (along +x)
    Jt = b.mass * b.vel.y  # the tangential
    e, mu = 0.8 * 0.8, 0.2 * 0.2
    assert abs(J - (1.0 + e) * 3.0 / (1.0 / a.mass + 1.0 / b.mass)) <= 1e-12 * 10.0
    assert abs(abs(Jt) - mu * J) <= 1e-12 * J
    # It slides: the slip is reduced, not reversed. At c = (r_a, 0) a's material point moves
    # along y at v_a.y + omega_a r_a (15 m/s before) and b's at v_b.y - omega_b r_b (0).
    assert a.angular_velocity > 0.0 and b.angular_velocity < 0.0
    slip = (a.vel.y + a.angular_velocity * 0.5) - (b.vel.y - b.angular_velocity * 0.3)
    assert 0.0 < slip < 15.0


@pytest.mark.parametrize("mu, sticks", [(0.5, True), (0.02, False)])
def test_a_disc_thrown_without_spin_at_anothers_edge_gains_the_closed_form_spin(
    mu: float, sticks: bool
) -> None:
    # Equal solid discs (m, r): a at speed u, offset h above b's centre, strikes b at rest.
    # At contact sin(theta) = h / 2r. With K = 6 / m, the impulse that stops the slip
    # u sin(theta) gives both the spin -u h / (6 r^2) (clockwise: a passes over b, b's top is
    # dragged forward, a's bottom back), if tan(theta) <= 3 mu (1 + e); else friction takes
    # mu J, J = (1 + e) m u cos(theta) / 2, and each spins at -mu (1 + e) u cos(theta) / r.
    r, m, u, h, e_each = 0.5, 1.5, 2.0, 0.3, 0.9
    w = free_world()
    a = w.add(Body(Vector(-1.5, h), Vector(u, 0.0), radius=r, mass=m, friction=math.sqrt(mu),
                   restitution=e_each))  # fmt: skip
    b = w.add(Body(Vector(0.0, 0.0), Vector(0.0, 0.0), radius=r, mass=m, friction=math.sqrt(mu),
                   restitution=e_each))  # fmt: skip
    w.step(1.0)
    e = e_each * e_each
    sin = h / (2.0 * r)
    cos = math.sqrt(1.0 - sin * sin)
    assert (sin / cos <= 3.0 * mu * (1.0 + e)) == sticks
    want = -u * h / (6.0 * r * r) if sticks else -mu * (1.0 + e) * u * cos / r
    assert abs(a.angular_velocity - want) <= 1e-12 * abs(want)
    assert abs(b.angular_velocity - want) <= 1e-12 * abs(want)
    # Momentum, the angular momentum about the origin kept; energy lost.
    assert abs(m * (a.vel.x + b.vel.x) - m * u) <= 1e-12
    assert abs(m * (a.vel.y + b.vel.y)) <= 1e-12
    L = sum(about(k, (0.0, 0.0)) for k in (a, b))
    assert abs(L - m * cross((-1.5, h), (u, 0.0))) <= 1e-12
    assert energy(a, b) < 0.5 * m * u * u


def test_the_event_reports_the_whole_impulse_with_its_tangential_part() -> None:
    r, m, u, h = 0.5, 1.5, 2.0, 0.3
    w = free_world()
    a = w.add(Body(Vector(-1.5, h), Vector(u, 0.0), radius=r, mass=m, friction=0.7,
                   restitution=0.9))  # fmt: skip
    b = w.add(Body(Vector(0.0, 0.0), Vector(0.0, 0.0), radius=r, mass=m, friction=0.7,
                   restitution=0.9))  # fmt: skip
    seen: list[ContactEvent] = []
    w.on_contact(a, begin=seen.append)
    w.step(1.0)
    assert len(seen) == 1 and seen[0].collider is b
    ev = seen[0]
    P = (m * (a.vel.x - u), m * a.vel.y)
    assert abs(ev.impulse.x - P[0]) <= 1e-12 and abs(ev.impulse.y - P[1]) <= 1e-12
    # Its tangential part is friction's: -u h / (6 r^2) of spin needs I |omega| / r of it.
    n = (ev.normal.x, ev.normal.y)
    tangential = abs(cross(n, (ev.impulse.x, ev.impulse.y)))
    assert abs(tangential - a.moment * abs(a.angular_velocity) / r) <= 1e-12
    assert tangential > 0.1


@pytest.mark.parametrize("walls", [False, True], ids=["nothing-spins", "a-collider-far-off"])
@pytest.mark.parametrize(
    ("ra", "rb", "ma", "mb", "u"),
    [(0.1, 0.1, 1.0, 1.0, 30.0), (0.05, 0.2, 0.3, 2.0, 45.0)],
    ids=["equal", "small-into-large"],
)
def test_a_disc_of_a_pile_struck_at_an_exact_impact_takes_the_impulses_turn(
    walls: bool, ra: float, rb: float, ma: float, mb: float, u: float
) -> None:
    # b rests against c, overlapping it (a pile: the soft step's); a comes too fast to join
    # the pile (u dt > CATCH (ra + rb)) and meets b at its exact moment, b a moving wall.
    # b takes the impulse -P at the point of contact, r_b n from its centre: the push and the
    # turn, -r_b (n x P) (as a takes -r_a (n x P)), into the soft step. c's side is smooth
    # (mu 0: the pile's row turns neither), so b ends the step at I_b dw_b / r_b = I_a dw_a /
    # r_a, both = -n x P. It took the push alone (no turn) before.
    w = free_world()
    if walls:
        # A collider far off: the static contacts take part (the other case: no collider,
        # nothing spinning as the step begins; the step's rotation is made all the same).
        w.add_collider(Segment((-50.0, -50.0), (50.0, -50.0)))
    b = w.add(Body(Vector(0.0, 0.0), Vector(0.0, 0.0), radius=rb, mass=mb, friction=0.8,
                   restitution=0.5))  # fmt: skip
    w.add(Body(Vector(0.0, -rb - 0.099), Vector(0.0, 0.0), radius=0.1, friction=0.0,
               restitution=0.5))  # fmt: skip
    a = w.add(Body(Vector(-ra - rb - 0.01, 0.12), Vector(u, 0.0), radius=ra, mass=ma,
                   friction=0.8, restitution=0.5))  # fmt: skip
    seen: list[ContactEvent] = []
    w.on_contact(a, begin=seen.append)
    w.step(1.0 / 60.0)
    assert len(seen) == 1 and seen[0].collider is b
    ev = seen[0]
    nxP = cross((ev.normal.x, ev.normal.y), (ev.impulse.x, ev.impulse.y))
    assert abs(nxP) > 1.0  # friction took a real part of it
    assert abs(a.moment * a.angular_velocity / ra + nxP) <= 1e-12 * abs(nxP)
    assert abs(b.moment * b.angular_velocity / rb + nxP) <= 1e-9 * abs(nxP)


def _oblique(fixed: bool, friction: float) -> tuple[Body, Body]:
    w = free_world()
    kw = {"radius": 0.5, "mass": 1.5, "friction": friction, "restitution": 0.9}
    a = w.add(Body(Vector(-1.5, 0.3), Vector(2.0, 0.0), fixed_rotation=fixed, **kw))
    b = w.add(Body(Vector(0.0, 0.0), Vector(0.0, 0.0), fixed_rotation=fixed, **kw))
    w.step(1.0)
    return a, b


def test_discs_that_do_not_turn_meet_as_they_always_did() -> None:
    # fixed_rotation: friction takes up to mu J of the centres' tangential relative momentum,
    # never reversing it (here it stops it: u sin m / 2 < mu J), and nothing turns.
    a, b = _oblique(True, 0.7)
    assert a.angular_velocity == 0.0 and b.angular_velocity == 0.0
    m, u, sin = 1.5, 2.0, 0.3
    cos = math.sqrt(1.0 - sin * sin)
    n = (-cos, sin)  # toward a
    J = (1.0 + 0.81) * u * cos / (2.0 / m)
    Jt = min(0.49 * J, u * sin / (2.0 / m))  # the centres' tangential speed is u sin
    t = (sin, cos)  # along a's tangential velocity relative to b (u (1, 0) minus its normal part)
    P = (n[0] * J - t[0] * Jt, n[1] * J - t[1] * Jt)
    assert abs(a.vel.x - (u + P[0] / m)) <= 1e-12 and abs(a.vel.y - P[1] / m) <= 1e-12
    assert abs(b.vel.x + P[0] / m) <= 1e-12 and abs(b.vel.y + P[1] / m) <= 1e-12
    # Without friction discs that turn meet as discs that do not, to the bit.
    a0, b0 = _oblique(True, 0.0)
    a1, b1 = _oblique(False, 0.0)
    for p, q in ((a0, a1), (b0, b1)):
        assert (p.pos.x, p.pos.y, p.vel.x, p.vel.y) == (q.pos.x, q.pos.y, q.vel.x, q.vel.y)
        assert q.angular_velocity == 0.0


def test_the_pair_keeps_its_angular_momentum_about_the_origin_over_many_impacts() -> None:
    # Six discs in a row, thrown and spun at random: no walls, no forces; every impact keeps
    # the momentum and the total angular momentum (about any point), and adds no energy.
    w = free_world()
    rng = np.random.default_rng(3)
    bodies = []
    for k in range(6):
        bodies.append(
            w.add(Body(Vector(1.3 * k, float(rng.uniform(-0.3, 0.3))),
                       Vector(float(rng.uniform(-2, 2)), float(rng.uniform(-0.5, 0.5))),
                       radius=0.5, mass=float(rng.uniform(0.5, 2.0)), friction=0.8,
                       restitution=1.0, angular_velocity=float(rng.uniform(-5, 5))))
        )  # fmt: skip
    L0 = sum(about(k, (0.0, 0.0)) for k in bodies)
    E0 = energy(*bodies)
    px0 = sum(k.mass * k.vel.x for k in bodies)
    met = 0
    for _ in range(240):
        w.step(1.0 / 60.0)
        met += len(w.began)
        L = sum(about(k, (0.0, 0.0)) for k in bodies)
        assert abs(L - L0) <= 1e-12 * 50.0
        assert energy(*bodies) <= E0 * (1.0 + 1e-12)
        assert abs(sum(k.mass * k.vel.x for k in bodies) - px0) <= 1e-12 * 20.0
    assert met >= 3
    assert any(abs(k.angular_velocity) > 0.0 for k in bodies)


def test_a_disc_sent_into_a_wall_by_an_impact_turns_as_it_would_off_that_wall_alone() -> None:
    # a strikes b dead centre along phi (no slip: b leaves along phi without spin) and b meets
    # the wall x = 2 within the same step (engine.exact.pair_impacts: wall_hits, wall_bounce); the
    # wall's bounce (the static contacts' rule: engine.dynamics.rotation grip) gives the spin of a
    # disc thrown at that wall alone.
    phi, u, r = 0.5, 4.0, 0.25
    d = (math.cos(phi), math.sin(phi))
    kw = {"radius": r, "mass": 1.0, "friction": 0.6, "restitution": 1.0}

    def scene(with_a: bool) -> Body:
        w = free_world()
        w.add_collider(Segment((2.0, -5.0), (2.0, 5.0), restitution=0.5, friction=0.8))
        if with_a:
            w.add(Body(Vector(1.6 - 0.6 * d[0], 0.0 - 0.6 * d[1]), Vector(u * d[0], u * d[1]),
                       **kw))  # fmt: skip
            b = w.add(Body(Vector(1.6, 0.0), Vector(0.0, 0.0), **kw))
        else:
            b = w.add(Body(Vector(1.6, 0.0), Vector(u * d[0], u * d[1]), **kw))
        w.step(0.1)  # (a's own path stops short of the wall; b's new one meets it at 0.068 s)
        return b

    struck, alone = scene(True), scene(False)
    # The closed form (n = (-1, 0) toward the disc, t = (0, -1), q = 2): u_t = -u sin(phi),
    # the most friction takes mu (1 + e) u cos(phi); a solid disc sticks if |u_t| / 3 is less.
    e, mu = 0.5, 0.6 * 0.8
    ut = -u * d[1]
    cap = mu * (1.0 + e) * u * d[0]
    du = -math.copysign(min(abs(ut) / 3.0, cap), ut)
    want = -du * 2.0 / r
    assert abs(alone.angular_velocity - want) <= 1e-12 * abs(want)
    assert abs(struck.angular_velocity - want) <= 1e-9 * abs(want)
    assert abs(struck.vel.x - alone.vel.x) <= 1e-9 and abs(struck.vel.y - alone.vel.y) <= 1e-9


def test_a_rolling_ball_striking_a_ball_on_a_floor_backspins_it_by_the_closed_form(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Pool: a rolls (omega = -v / r) into b at rest, both on a floor, head on. At the contact
    # (the balls' equator) a's surface runs down at v and b's stands: the slip is v, and with
    # K = 6 / m the impulse that stops it (enough friction: mu (1 + e) >= 1/3) is m v / 6,
    # which gives b the backspin v / (3 r) and leaves a at -2 v / (3 r), at the impact.
    r, m, v = 0.3, 0.17, 3.0
    w = World()
    w.add_force(Gravity(Vector(0.0, -G)))
    w.add_collider(Segment((-10.0, 0.0), (10.0, 0.0), friction=0.4, restitution=0.5))
    kw = {"radius": r, "mass": m, "friction": 0.8, "restitution": 0.95}
    a = w.add(Body(Vector(-1.0, r), Vector(v, 0.0), angular_velocity=-v / r, **kw))
    b = w.add(Body(Vector(0.5, r), Vector(0.0, 0.0), **kw))
    seen: list[tuple[float, float]] = []
    real = pair_impacts.bounce

    def spy(*args, **kwargs):  # the spins right after each impact of the pair
        got = real(*args, **kwargs)
        turns = args[11] if len(args) > 11 else kwargs.get("turns")
        assert turns is not None
        seen.append((float(turns.omega[0]), float(turns.omega[1])))
        return got

    monkeypatch.setattr(pair_impacts, "bounce", spy)
    E0 = energy(a, b) + G * (a.mass * a.pos.y + b.mass * b.pos.y)
    dt = 1.0 / 120.0
    for _ in range(240):
        w.step(dt)
        for k in (a, b):
            assert math.isfinite(k.pos.x + k.pos.y + k.vel.x + k.vel.y + k.angular_velocity)
        E = energy(a, b) + G * (a.mass * a.pos.y + b.mass * b.pos.y)
        assert E <= E0 * (1.0 + 1e-9)
    assert seen, "the balls met at an exact impact"
    wa, wb = seen[0]
    assert abs(wb - v / (3.0 * r)) <= 1e-12 * v / r
    assert abs(wa - -2.0 * v / (3.0 * r)) <= 1e-12 * v / r
    # Afterwards both roll on, b ahead, and neither rose off the floor for long.
    assert b.vel.x > a.vel.x > 0.0 and b.pos.x > a.pos.x
