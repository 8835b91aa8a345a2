"""The loop kernel of the exact impacts (engine.exact.pair_impacts.pair_times) against its numpy
twin, and whole scenes of exact impacts on both paths.

``times_of_impact`` on the fast path runs ``pair_times``, pair by pair, the same operations
in the same order as the twin (``times_of_impact`` with ``engine.geometry.impact.disc_hits``), so
the two give the same bits; the pairs whose polynomial is a cubic or a quartic (the bodies'
accelerations differ) go to the twin on both paths. Without numba the kernel runs as the plain
Python it is written in (``LoopKernel.py``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine import Body, Vector, World, kernels
from engine.exact import pair_impacts
from engine.exact.pair_impacts import pair_times, times_of_impact
from engine.kernels import LoopKernel

COMPILED = kernels.available()
PATHS = ["numpy", "fast"] if COMPILED else ["numpy"]


@pytest.fixture(autouse=True)
def _kernels_run(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without numba, a kernel's call runs its plain Python (the same loop, uncompiled)."""
    if not COMPILED:
        monkeypatch.setattr(LoopKernel, "fast", property(lambda self: self.py))


def random_pairs(seed: int, bodies: int, pairs: int, kind: str) -> tuple[np.ndarray, ...]:
    """Pairs of bodies on parabolic paths within a step: (pa, pb, R, X, V, A, ts, dt).

    The bodies start (at time 0) near each other, some pairs exactly touching (heading in or
    leaving), and fly for dt under ``kind`` of acceleration: "none", "shared" (gravity: the
    pairs' quadratics), "own" (each body its own: cubics and quartics, the twin's) or "mixed".
    Some bodies' paths start later in the step (ts > 0), as after an impact.
    """
    rng = np.random.default_rng(seed)
    dt = float(rng.choice([1 / 240, 1 / 60, 0.1, 1.0]))
    pa = rng.integers(0, bodies, pairs)
    pb = (pa + rng.integers(1, bodies, pairs)) % bodies
    r = rng.uniform(0.05, 1.0, bodies)
    R = r[pa] + r[pb]
    x0 = rng.normal(scale=2.0, size=(bodies, 2))
    v0 = rng.normal(scale=rng.choice([0.1, 3.0, 30.0]), size=(bodies, 2))
    if bodies > 1:
        # Some pairs touching now: b put at distance R from a along a random direction.
        for k in np.flatnonzero(rng.random(pairs) < 0.3):
            angle = rng.uniform(0.0, 2.0 * np.pi)
            x0[pb[k]] = x0[pa[k]] - R[k] * np.array([np.cos(angle), np.sin(angle)])
    # Some aimed: a flies at b fast enough to close the gap within the step, or nearly.
    for k in np.flatnonzero(rng.random(pairs) < 0.4):
        d = x0[pb[k]] - x0[pa[k]]
        dist = float(np.hypot(*d))
        if dist > 0.0:
            v0[pa[k]] = d / dist * (abs(dist - R[k]) / dt * rng.uniform(0.5, 2.0))
            v0[pa[k]] += rng.normal(scale=0.2 * float(np.hypot(*v0[pa[k]])), size=2)
    A = np.zeros((bodies, 2))
    if kind in ("shared", "mixed"):
        A[:] = (0.0, -9.81)
    if kind in ("own", "mixed"):
        own = rng.random(bodies) < (1.0 if kind == "own" else 0.3)
        A[own] = rng.normal(scale=10.0, size=(int(own.sum()), 2))
    # The end state of each path (what the engine holds), from the start state.
    X = x0 + v0 * dt + A * (0.5 * dt * dt)
    V = v0 + A * dt
    ts = np.where(rng.random(bodies) < 0.3, rng.uniform(0.0, dt, bodies), 0.0)
    return pa, pb, R, X, V, A, ts, np.float64(dt)


def both(args: tuple[np.ndarray, ...]) -> tuple[np.ndarray, np.ndarray]:
    """The times of impact on the numpy path and on the fast path."""
    pa, pb, R, X, V, A, ts, dt = args
    want = times_of_impact(pa, pb, R, X, V, A, ts, float(dt))
    got = times_of_impact(pa, pb, R, X, V, A, ts, float(dt), fast=True)
    return want, got


@settings(max_examples=300, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    bodies=st.integers(2, 12),
    pairs=st.integers(0, 40),
    kind=st.sampled_from(["none", "shared", "own", "mixed"]),
)
def test_times_of_impact_kernel_is_its_numpy_twin(
    seed: int, bodies: int, pairs: int, kind: str
) -> None:
    """On random pairs (apart, touching, leaving; straight, parabolic, curving apart; paths
    starting later), the fast path's times of impact are the numpy twin's, bit for bit."""
    want, got = both(random_pairs(seed, bodies, pairs, kind))
    assert np.array_equal(got, want)


def test_the_kernel_answers_for_itself() -> None:
    """The kernel alone, on pairs with one acceleration (its quadratics), marks none curved
    and finds impacts (not all inf), which are the twin's."""
    pa, pb, R, X, V, A, ts, dt = random_pairs(5, 12, 200, "shared")
    t = np.empty(len(pa))
    curved = np.ones(len(pa), dtype=np.bool_)
    pair_times(pa, pb, R, X, V, A, ts, float(dt), t, curved)
    assert not curved.any()
    assert np.isfinite(t).sum() > 10
    assert np.array_equal(t, times_of_impact(pa, pb, R, X, V, A, ts, float(dt)))


def test_curved_pairs_are_left_to_the_twin() -> None:
    """Bodies with accelerations of their own meet on quartics: the kernel marks them."""
    pa, pb, R, X, V, A, ts, dt = random_pairs(3, 12, 200, "own")
    t = np.empty(len(pa))
    curved = np.zeros(len(pa), dtype=np.bool_)
    pair_times(pa, pb, R, X, V, A, ts, float(dt), t, curved)
    assert curved.any()


def test_balls_passing_at_their_contact_distance_graze_on_both_paths() -> None:
    """Two balls on parallel straight paths, their centres passing exactly R apart, only
    graze (no impact on either path: a tangency within the discriminant's rounding, as
    ``engine.geometry.impact.grazes``); passing 1e-9 of R closer, they meet, at the same
    bits on both paths."""
    rng = np.random.default_rng(11)
    n, dt = 100, 1.0 / 60.0
    angle = rng.uniform(0.0, 2.0 * np.pi, n)
    u = np.stack([np.cos(angle), np.sin(angle)], axis=1)
    side = np.stack([-u[:, 1], u[:, 0]], axis=1)
    r = rng.uniform(0.05, 1.0, (n, 2))
    R = r[:, 0] + r[:, 1]
    closing = rng.uniform(0.5, 30.0, n)
    pa, pb = np.arange(0, 2 * n, 2), np.arange(1, 2 * n, 2)
    for depth, meet in ((0.0, False), (1e-9, True)):
        X = np.empty((2 * n, 2))
        V = np.zeros((2 * n, 2))
        X[pa] = rng.normal(0.0, 1.0, (n, 2))
        V[pa] = u * closing[:, None]
        # b passes a at R (1 - depth) at mid-step; X is the end of the step.
        X[pb] = X[pa] + side * (R * (1.0 - depth))[:, None] - V[pa] * (0.5 * dt)
        A, ts = np.zeros((2 * n, 2)), np.zeros(2 * n)
        want, got = both((pa, pb, R, X, V, A, ts, np.float64(dt)))
        assert np.array_equal(got, want)
        assert np.isfinite(want).all() if meet else np.isinf(want).all()


def test_the_comparison_can_fail() -> None:
    """The comparison is sharp: radii 1e-9 larger (a kernel that rounded them differently)
    give other times, which it catches."""
    pa, pb, R, X, V, A, ts, dt = random_pairs(5, 12, 200, "shared")
    want = times_of_impact(pa, pb, R, X, V, A, ts, float(dt))
    other = times_of_impact(pa, pb, R * (1.0 + 1e-9), X, V, A, ts, float(dt), fast=True)
    assert not np.array_equal(other, want)


# -- whole scenes on both paths ----------------------------------------------------------------


def gas(n: int = 60, seed: int = 2) -> World:
    """n balls in a square box, no gravity, restitution 1: every meeting an exact impact."""
    from engine import Box

    rng = np.random.default_rng(seed)
    world = World(integrator="auto")
    cols = int(np.ceil(np.sqrt(n)))
    world.add_collider(Box((0.0, 0.0), (1.1 * cols + 1.0, 1.1 * cols + 1.0)))
    k = np.arange(n)
    for (x, y), (vx, vy) in zip(
        np.stack([0.8 + 1.1 * (k % cols), 0.8 + 1.1 * (k // cols)], axis=1).tolist(),
        rng.normal(scale=4.0, size=(n, 2)).tolist(),
        strict=True,
    ):
        world.add(Body(Vector(x, y), Vector(vx, vy), radius=0.3, restitution=1.0, friction=0.0))
    return world


def cradle() -> World:
    """Newton's cradle (demos.cradle): five balls in a row on a floor, the first sent."""
    from demos.cradle import cradle_world

    return cradle_world()[0]


def breakout() -> Any:
    """The breakout game (demos.breakout), played by its autopilot: the ball meets the
    kinematic paddle, a body, on exact impacts."""
    from demos.breakout import BreakoutGame

    return BreakoutGame()


@pytest.mark.parametrize("scene", [gas, cradle, breakout])
def test_scenes_of_impacts_are_the_same_on_both_paths(
    scene: object, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A gas of 60 balls, Newton's cradle and breakout, 240 steps on each path: the same
    state to the bit (every time of impact is the same, so every impulse is)."""
    calls = []
    kernel = pair_impacts.pair_times

    def spy(*args: object) -> None:
        calls.append(len(args[0]))  # type: ignore[arg-type]
        kernel(*args)

    monkeypatch.setattr(pair_impacts, "pair_times", spy)
    steppers = []
    for path in PATHS:
        monkeypatch.setenv("ENGINE_KERNELS", path)
        steppers.append(scene())  # type: ignore[operator]
    worlds = [getattr(one, "world", one) for one in steppers]
    assert [w.kernels for w in worlds] == PATHS
    for _ in range(240):
        for one in steppers:
            one.step(1 / 60)
    assert bool(calls) == COMPILED  # the fast World took the kernel, the numpy one did not
    p0, v0 = worlds[0].positions(), worlds[0].velocities()
    for world in worlds[1:]:
        assert np.array_equal(world.positions(), p0)
        assert np.array_equal(world.velocities(), v0)
