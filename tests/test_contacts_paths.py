"""The contacts' two paths give the same steps.

A few bodies are solved one at a time in Python floats (``Contacts._solve_few``, and the
``*_one`` kernels of ``engine.geometry.impact``), many in numpy arrays (``Contacts._solve``, the
``*s`` kernels): the same operations in the same order, so the same results. Here both run on the
same random pairs and scenes and are compared, the scenes step by step with every state and
event (the paths are chosen with ``Contacts.few`` and ``Contacts.few_resting``: 0 always
takes the arrays, a huge number always the floats).
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import pytest

from engine import Body, Box, Circle, Filter, Plane, Segment, Vector, World
from engine.forces import Gravity
from engine.geometry.impact import (
    disc_hit_one,
    disc_hits,
    line_hit_one,
    line_hits,
    quadratic_first_root,
    quadratic_first_root_one,
)

REL = 1e-12
#: One group: the balls pass through one another (these tests are about the static contacts).
APART = Filter(group=1)


def pairs_of(rng: np.random.Generator, m: int) -> dict[str, np.ndarray]:
    """Random ball paths, a third of them starting exactly on their face (touching)."""
    X = rng.normal(0.0, 1.0, (m, 2))
    V = rng.normal(0.0, 5.0, (m, 2)) * rng.integers(0, 2, (m, 1))  # some at rest
    B = rng.normal(0.0, 10.0, (m, 2)) * rng.integers(0, 2, (m, 1))  # some straight
    angle = rng.uniform(0.0, 2.0 * np.pi, m)
    return {
        "X": X,
        "V": V,
        "B": B,
        "p": rng.normal(0.0, 1.0, (m, 2)),
        "n": np.stack([np.cos(angle), np.sin(angle)], axis=1),
        "rho": rng.choice([0.0, 0.1, 0.5], m),
        "T": rng.uniform(0.0, 0.5, m),
        "touch": rng.random(m) < 0.3,
    }


@pytest.mark.parametrize("seed", range(5))
def test_line_hit_one_is_line_hits(seed: int) -> None:
    rng = np.random.default_rng(seed)
    m = 400
    d = pairs_of(rng, m)
    X, p, n, rho = d["X"], d["p"], d["n"], d["rho"]
    X[d["touch"]] = (p + n * rho[:, None])[d["touch"]]
    two = rng.random(m) < 0.5
    lo = np.where(rng.random(m) < 0.5, -np.inf, -rng.uniform(0.0, 2.0, m))
    hi = np.where(np.isinf(lo), np.inf, rng.uniform(0.0, 2.0, m))
    t, normal = line_hits(X, d["V"], d["B"], p, n, rho, two, lo, hi, d["T"])
    assert np.isfinite(t).sum() > m // 10  # hits enough to mean something
    for i in range(m):
        t1, n1 = line_hit_one(
            tuple(X[i]), tuple(d["V"][i]), tuple(d["B"][i]), tuple(p[i]), tuple(n[i]),
            float(rho[i]), bool(two[i]), float(lo[i]), float(hi[i]), float(d["T"][i]),
        )  # fmt: skip
        assert t1 == t[i] and n1 == tuple(normal[i]), i


def test_a_ball_behind_a_faces_line_beside_its_end_meets_it_coming_down() -> None:
    # The face y = 0 (n up, rho 0.5 from the ball's centre) runs from x = -10 to x = 0; the
    # ball starts beside its end, 5 cm behind its line (g0 = -0.05), flying up and over it:
    # g(t) = -0.05 + 1.5 t - 5 t^2 comes back down through 0 at the later root,
    # t = (1.5 + sqrt(1.25)) / 10 = (3 + sqrt 5) / 20, with x = 0.5 - 2 t within the face. A
    # start behind the line was taken for a touch, and the search looked for the return to
    # the start's depth, t = 0.3, 5 cm inside (found exploring: a disc over a capsule's end).
    X, V, B = np.array([[0.5, 0.45]]), np.array([[-2.0, 1.5]]), np.array([[0.0, -10.0]])
    p, n = np.array([[0.0, 0.0]]), np.array([[0.0, 1.0]])
    args = (np.array([0.5]), np.array([False]), np.array([0.0]), np.array([10.0]), 0.5)
    t, normal = line_hits(X, V, B, p, n, *args)
    exact = (3.0 + math.sqrt(5.0)) / 20.0
    assert t[0] == pytest.approx(exact, rel=1e-15)
    assert tuple(normal[0]) == (0.0, 1.0)
    one = line_hit_one((0.5, 0.45), (-2.0, 1.5), (0.0, -10.0), (0.0, 0.0), (0.0, 1.0), 0.5,
                       False, 0.0, 10.0, 0.5)  # fmt: skip
    assert one == (t[0], (0.0, 1.0))
    # Never up to the line again (g stays below 0): no impact.
    t, _ = line_hits(X, np.array([[-2.0, 0.5]]), B, p, n, *args)
    assert t[0] == math.inf


def test_a_ball_touching_a_face_at_its_end_and_leaving_it_there_does_not_meet_it() -> None:
    # The face y = 0 (n up, rho 0.5 from the ball's centre; its tangent (-n_y, n_x) = (-1, 0),
    # lo = -2 and hi = 3 along it) runs from x = 2 to x = -3; the ball touches it, pulled into
    # it (B down), moving along it. At an end and moving off the face there, the face is not
    # met (the end's round face holds the ball: a ball that slid to a ramp's end flies on,
    # engine.exact.sweep's "A slide's end"); at an end moving back along the face, or a hair
    # inside the face moving off it, it is met at once, as before.
    p, n, B = (0.0, 0.0), (0.0, 1.0), (0.0, -9.81)
    cases = [  # (x, vx, met)
        (-3.0, -2.0, False),
        (-3.0 + 1e-13, -2.0, False),  # (within TOUCH of the end: the end)
        (2.0, 2.0, False),
        (-3.0, 2.0, True),
        (2.0, -2.0, True),
        (-3.0 + 1e-6, -2.0, True),
        (0.5, 2.0, True),
    ]
    for x, vx, met in cases:
        X, V = np.array([[x, 0.5]]), np.array([[vx, 0.0]])
        args = (np.array([[*p]]), np.array([[*n]]), np.array([0.5]), np.array([True]))
        t, _ = line_hits(X, V, np.array([B]), *args, np.array([-2.0]), np.array([3.0]), 0.1)
        one, _ = line_hit_one((x, 0.5), (vx, 0.0), B, p, n, 0.5, True, -2.0, 3.0, 0.1)
        assert one == t[0] == (0.0 if met else math.inf), (x, vx, one, t[0])


@pytest.mark.parametrize("seed", range(5))
def test_disc_hit_one_is_disc_hits(seed: int) -> None:
    rng = np.random.default_rng(100 + seed)
    m = 400
    d = pairs_of(rng, m)
    X, c, rho = d["X"], d["p"], d["rho"] + 0.2
    u = rng.normal(0.0, 1.0, (m, 2))
    u /= np.hypot(u[:, 0], u[:, 1])[:, None]
    X[d["touch"]] = (c + u * rho[:, None])[d["touch"]]
    t = disc_hits(X, d["V"], d["B"], c, rho, d["T"])
    assert np.isfinite(t).sum() > m // 10
    for i in range(m):
        t1 = disc_hit_one(
            tuple(X[i]), tuple(d["V"][i]), tuple(d["B"][i]), tuple(c[i]), float(rho[i]),
            float(d["T"][i]),
        )  # fmt: skip
        assert t1 == t[i], i


def test_a_ball_on_a_peg_leaving_too_slowly_to_get_away_is_pressed_in() -> None:
    """A ball touching a peg of contact distance 3 m, its velocity leaving it at D.v =
    2.3e-10 m^2/s (rounding's rest), pulled into it at 8 m/s^2 (found by the fuzz: a ball at
    rest in the wedge of a peg and a ceiling). |x(t) - c|^2 - rho^2 = k1 t + k2 t^2 + ... with
    k1 = 2 D.v > 0 and k2 = |v|^2 + D.a < 0 is zero again at t = -k1 / k2 = 2e-11 s: the
    ball never gets away, and meets the peg now (t = 0), on every path. Leaving faster (that
    time past 1e-9 of the step) it meets it where it comes back, later in the step."""
    x = (-2.976470224947576, 5.3750000000007025)
    v = (-0.00015822716226831, -0.00125588853952867)
    a, c, rho, T = (8.0, 0.0), (0.0, 5.0), 3.0, 1.0 / 7.0
    D = np.subtract(x, c)
    assert 0.0 < 2.0 * D @ v < 1e-9 and np.hypot(*D) - rho < 1e-12  # touching, leaving
    assert disc_hit_one(x, v, a, c, rho, T) == 0.0
    assert disc_hits(np.array([x]), np.array([v]), np.array([a]), np.array([c]),
                     np.array([rho]), T)[0] == 0.0  # fmt: skip
    # Leaving at 0.1 m/s along D: back after a flight of about 2 k1 / |k2| = 0.0025 s.
    away = tuple(np.array(v) + 0.1 * D / np.hypot(*D))
    t = disc_hit_one(x, away, a, c, rho, T)
    k1, k2 = 2.0 * D @ away, float(np.dot(away, away) + D @ a)
    assert t == pytest.approx(-k1 / k2, rel=1e-3) and t > 1e-9 * T


@pytest.mark.parametrize("seed", range(3))
def test_a_straight_path_tangent_to_a_disc_grazes_it(seed: int) -> None:
    """A ball whose straight path passes a round face at exactly its contact distance rho
    (its closest point a tangency) does not strike it: the discriminant's rounding would split
    the double root by 1e-8 of the step, and a strike taken there has an approach speed 1e-8
    of the ball's. Passing 1e-9 of rho inside, it strikes, where its chord of the disc
    begins; the two twins agree to the bit."""
    rng = np.random.default_rng(7 + seed)
    m, T = 200, 1.0 / 60.0
    angle = rng.uniform(0.0, 2.0 * np.pi, m)
    u = np.stack([np.cos(angle), np.sin(angle)], axis=1)  # the direction of flight
    side = np.stack([-u[:, 1], u[:, 0]], axis=1)
    c = rng.normal(0.0, 1.0, (m, 2))
    rho = rng.uniform(0.05, 1.0, m)
    speed = rng.uniform(0.5, 30.0, m)
    V, B = u * speed[:, None], np.zeros((m, 2))
    s = rng.uniform(0.2, 0.8, m) * T  # the moment it passes closest
    for depth, hits in ((0.0, False), (1e-9, True)):
        X = c + side * (rho * (1.0 - depth))[:, None] - V * s[:, None]
        t = disc_hits(X, V, B, c, rho, T)
        one = [disc_hit_one(tuple(X[i]), tuple(V[i]), (0.0, 0.0), tuple(c[i]), float(rho[i]), T)
               for i in range(m)]  # fmt: skip
        assert np.array_equal(t, one)
        if hits:
            # It enters where the chord begins: half of 2 sqrt(rho^2 - h^2) before closest.
            half = np.sqrt(rho * rho - (rho * (1.0 - depth)) ** 2) / speed
            assert np.allclose(t, s - half, rtol=0.0, atol=1e-3 * half.min())
        else:
            assert np.all(np.isinf(t)), f"{np.isfinite(t).sum()} of {m} tangent paths struck"


def test_quadratic_first_root_one_is_quadratic_first_root() -> None:
    rng = np.random.default_rng(7)
    m = 2000
    # Zeros, ties and signs chosen often: each branch of the array version is taken.
    g = rng.choice([-1.0, 0.0, 1e-300, 1.0, 3.0], (m, 3)) * rng.uniform(0.5, 2.0, (m, 3))
    T = rng.uniform(0.0, 3.0, m)
    t = quadratic_first_root(g[:, 0], g[:, 1], g[:, 2], T, 1e-12)
    for i in range(m):
        assert quadratic_first_root_one(*g[i].tolist(), float(T[i]), 1e-12) == t[i], g[i]


# -- scenes ----------------------------------------------------------------------------------


def scene(seed: int, method: str, kernels: str | None = None) -> tuple[World, list[Body]]:
    """A room with a V, a shelf, pegs, capsules, thin walls and a slanted floor; 40 balls of
    every size and material, thrown at up to 20 m/s: they bounce, settle, wedge in the V, slide
    and stop on slopes, roll over round edges and off the ends of walls; those with friction
    turn (they roll, slip and spin up at bounces), some spinning from the start."""
    rng = np.random.default_rng(seed)
    w = World(integrator=method, kernels=kernels)
    w.add_force(Gravity((float(rng.uniform(-2.0, 2.0)), -9.81)))
    w.add_collider(Box((-10.0, -10.0), (10.0, 10.0), restitution=0.8, friction=0.7))
    w.add_collider(Plane((0.0, -8.0), (0.2, 1.0), restitution=0.5))
    w.add_collider(Segment((-8.0, -2.0), (-5.0, -5.0), friction=0.3))  # the V
    w.add_collider(Segment((-5.0, -5.0), (-2.0, -2.0), friction=0.3))
    w.add_collider(Segment((2.0, 0.0), (7.0, 0.5), 0.05))  # a shelf with round ends
    for _ in range(6):
        a = rng.uniform(-8.0, 8.0, 2)
        angle = rng.uniform(0.0, np.pi)
        b = a + rng.uniform(0.5, 3.0) * np.array([np.cos(angle), np.sin(angle)])
        radius = float(rng.choice([0.0, 0.05, 0.5]))
        w.add_collider(
            Segment(tuple(a), tuple(b), radius, restitution=float(rng.uniform(0.2, 1.0)))
        )
    for _ in range(4):
        w.add_collider(Circle(tuple(rng.uniform(-8.0, 8.0, 2)), float(rng.uniform(0.1, 1.0))))
    bodies = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a ball dropped onto a collider is pushed off it
        for _ in range(40):
            bodies.append(
                w.add(
                    Body(
                        Vector(*rng.uniform(-9.0, 9.0, 2)),
                        Vector(*(rng.uniform(-20.0, 20.0, 2) * rng.integers(0, 2))),
                        Vector(0.0, 0.0),
                        radius=(radius := float(rng.choice([0.0, 0.05, 0.2, 0.5]))),
                        restitution=float(rng.choice([0.0, 0.3, 0.9, 1.0])),
                        friction=float(rng.choice([0.0, 0.2, 0.6, 1.5])),
                        mass=float(rng.uniform(0.5, 2.0)),
                        filter=APART,
                        **spin_of(rng, radius),
                    )
                )
            )
    return w, bodies


def spin_of(rng: np.random.Generator, radius: float) -> dict[str, Any]:
    """A ball's rotation: a third spin from the start, a fifth do not turn (a point never)."""
    k = rng.random()
    if k < 0.2 or radius == 0.0:
        return {"fixed_rotation": True}
    return {"angular_velocity": float(rng.uniform(-30.0, 30.0))} if k < 0.53 else {}


def spins(bodies: list[Body]) -> list[float]:
    """Every body's angle and angular velocity, flat."""
    return [x for b in bodies for x in (b.angle, b.angular_velocity)]


def events(world: World, evs: list[Any]) -> list[tuple[Any, ...]]:
    """Each event as (body's place, what it met and its place, point, normal, impulse, time);
    what it met is a collider, or another body where bodies collide."""
    bodies, colliders = world.bodies, world.colliders

    def place(things: tuple[Any, ...], thing: Any) -> int:
        return next(k for k, t in enumerate(things) if t is thing)

    out = []
    for e in evs:
        met = (
            ("body", place(bodies, e.collider))
            if any(b is e.collider for b in bodies)
            else ("collider", place(colliders, e.collider))
        )
        out.append((place(bodies, e.body), met, *e.point, *e.normal, *e.impulse, e.time))
    return out


def close(a: Any, b: Any) -> bool:
    a, b = np.asarray(a, float), np.asarray(b, float)
    return a.shape == b.shape and bool(
        np.all(np.abs(a - b) <= REL * np.maximum(np.maximum(np.abs(a), np.abs(b)), 1.0))
    )


# Where balls also collide with each other, a crowded spot may warn that a pile overlaps:
# both worlds alike, and beside the point here.
@pytest.mark.filterwarnings("ignore::engine.StabilityWarning")
@pytest.mark.parametrize("method", ["auto", "semi_implicit_euler", "velocity_verlet"])
@pytest.mark.parametrize("seed", range(3))
def test_one_at_a_time_and_arrays_give_the_same_steps(seed: int, method: str) -> None:
    # The arrays on the numpy path; the floats on the default one (with numba, the loop
    # kernel paths_loop takes the free bodies, and the floats the rest).
    arrays, bodies_a = scene(seed, method, kernels="numpy")
    floats, bodies_f = scene(seed, method)
    assert arrays._contacts is not None and floats._contacts is not None
    arrays._contacts.few = arrays._contacts.few_resting = 0
    floats._contacts.few = floats._contacts.few_resting = 10**9
    dt = 1.0 / 60.0
    struck = rested = 0
    for step in range(240):
        arrays.step(dt)
        floats.step(dt)
        assert close(arrays.positions(), floats.positions()), step
        assert close(arrays.velocities(), floats.velocities()), step
        assert close(spins(bodies_a), spins(bodies_f)), step
        ea, ef = events(arrays, arrays.began), events(floats, floats.began)
        assert len(ea) == len(ef) and all(
            x[:2] == y[:2] and close(x[2:], y[2:]) for x, y in zip(ea, ef, strict=True)
        ), step
        ea, ef = events(arrays, arrays.ended), events(floats, floats.ended)
        assert len(ea) == len(ef) and all(
            x[:2] == y[:2] and close(x[2:], y[2:]) for x, y in zip(ea, ef, strict=True)
        ), step
        resting = [arrays.resting(b) for b in bodies_a]
        assert [floats.resting(b) is not None for b in bodies_f] == [
            r is not None for r in resting
        ], step
        struck += len(ea)
        rested += sum(r is not None for r in resting)
    assert arrays.capped == floats.capped
    # The scenes exercise what they are meant to: many impacts, and bodies at rest.
    assert struck > 100 and rested > 100, (struck, rested)
    # ... and bodies that turned under friction.
    turned = [b for b in bodies_a if b.turns and b.friction > 0 and b.angular_velocity != 0]
    assert len(turned) > 5, len(turned)
    assert math.isfinite(float(arrays.positions().sum()))


def rare_cases(method: str) -> World:
    """What the random scenes seldom meet: a ball between two walls 1e-4 apart at 1e5 m/s
    (more than MAX_IMPACTS impacts in a step: capped), and balls rolling over a capsule's round
    end onto its flat side."""
    w = World(integrator=method)
    w.add_force(Gravity((0.0, -9.81)))
    r = 0.1
    w.add_collider(Segment((-100.0, 0.0), (100.0, 0.0)))
    w.add_collider(Segment((-100.0, 2 * r + 1e-4), (100.0, 2 * r + 1e-4)))
    w.add(
        Body(
            Vector(0.0, r + 5e-5),
            Vector(0.0, 1e5),
            Vector(0, 0),
            radius=r,
            restitution=1.0,
            friction=0.0,
        )
    )
    w.add_collider(Segment((0.0, 10.0), (3.0, 10.0), 0.5, friction=0.0))
    for vx, x0 in ((1.0, -0.15), (2.0, -0.3), (3.0, -0.05)):
        w.add(Body(Vector(x0, 10.75), Vector(vx, 0.0), Vector(0, 0), radius=0.2, restitution=0.0))
    return w


@pytest.mark.parametrize("method", ["auto", "semi_implicit_euler"])
def test_rare_cases_give_the_same_steps(method: str) -> None:
    arrays, floats = rare_cases(method), rare_cases(method)
    assert arrays._contacts is not None and floats._contacts is not None
    arrays._contacts.few = arrays._contacts.few_resting = 0
    floats._contacts.few = floats._contacts.few_resting = 10**9
    for step in range(120):
        arrays.step(1.0 / 60.0)
        floats.step(1.0 / 60.0)
        assert close(arrays.positions(), floats.positions()), step
        assert close(arrays.velocities(), floats.velocities()), step
        assert len(arrays.began) == len(floats.began), step
        assert len(arrays.ended) == len(floats.ended), step
    assert arrays.capped == floats.capped > 0


@pytest.mark.parametrize("seed", range(3))
def test_the_grid_lists_every_face_within_reach(seed: int) -> None:
    """The broadphase (also used by engine.exact.collisions): every face a ball can reach is among
    its pairs, both as the solver lists them and as ``FaceGrid.pairs`` does."""
    rng = np.random.default_rng(seed)
    world, _ = scene(seed, "auto")
    contacts = world._contacts
    assert contacts is not None
    faces, grid = contacts.faces, contacts.grid
    X = rng.uniform(-12.0, 12.0, (400, 2))
    reach = rng.choice([0.01, 0.1, 0.5, 3.0], 400)
    L = len(faces.p)
    listed = set(zip(*(a.tolist() for a in grid.pairs(X, reach)), strict=True))
    cell = grid.cells(X)
    fb, ff = grid.listed(reach, cell)
    listed_finite = set(zip(fb.tolist(), ff.tolist(), strict=True))
    for b in range(len(X)):
        for f in range(L + len(faces.c)):
            if f < L:
                d = X[b] - faces.p[f]
                along = d @ np.array([-faces.n[f, 1], faces.n[f, 0]])
                across = d @ faces.n[f]
                if not faces.two[f]:
                    gap = across - faces.rho[f]  # endless and one-sided
                else:
                    off = max(faces.lo[f] - along, along - faces.hi[f], 0.0)
                    gap = math.hypot(across, off) - faces.rho[f]
            else:
                gap = float(np.hypot(*(X[b] - faces.c[f - L]))) - faces.r[f - L]
            if gap <= reach[b]:
                assert (b, f) in listed, (b, f, gap, reach[b])
                assert (f < L and faces.infinite[f]) or (b, f) in listed_finite, (b, f)
