"""The plan's tests on pairs: which bodies are a pile's as a step begins (engine.exact.collisions).

The rule is stated in engine.exact.collisions ("The plan"); here are its two tests on the pairs
(a, b) that may touch within the step, and the growth of the piles they seed:

* **rest** (``rest_seeds``): a pair seeds a pile if it carried load in the last step
  (``loaded``); or it is near enough to touch (gap <= 5% of the smaller radius plus what it
  closes in the step), closes or parts no faster than 2 dt |A| (the speed the strongest
  pull adds in two steps) and is pressed together by the pulls (``press`` < 0; a body
  resting on a collider counts as held up: its pull is not pressing); or it overlaps past
  ``SLOP`` of the smaller radius;
* **join** (``join_masks``): a pair whose gap can close within the step (by the relative
  speed and pull, and by twice either body's speed along the normal: a pile may stop a
  body or send it back, so one moving with it in formation closes by up to twice its
  speed) joins the pile of either body, if it closes by at most ``CATCH`` times the two
  radii (a speculative contact catches it; a faster body meets the pile at its exact
  moments); a body the game moves always joins;
* **grow** (``grow``): four rounds, each joining to the piles every body that a joining pair
  links to one.

The arithmetic is row by row (engine.geometry.pair_math: two multiplications and an addition a dot),
and the loop kernel ``plan_pairs`` (engine.kernels, the fast path) does the same operations in
the same order, pair by pair, so both paths mark the same bodies.
"""

from __future__ import annotations

import math

import numpy as np

from .. import kernels
from ..geometry.pair_math import SLOP, dot, norm, unit

__all__ = ["CATCH", "GROW_ROUNDS", "rest_seeds", "join_masks", "grow", "plan_pairs"]

#: A body joins a pile by closing on it within the step by at most this many times the sum
#: of the two radii (a speculative contact catches it); faster, it meets the pile's bodies
#: at the exact moments.
CATCH = 2.0
#: Rounds of growth: a pile takes in what reaches it, and what reaches that, four deep.
GROW_ROUNDS = 4


def rest_seeds(
    a: np.ndarray,
    b: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    A: np.ndarray,
    Ah: np.ndarray,
    r: np.ndarray,
    dt: float,
    loaded: np.ndarray,
) -> np.ndarray:
    """Which pairs (a, b) seed a pile (module text): (P,) bool. x0, v0 (N, 2): the step's
    start; A (N, 2): the pulls; Ah: the same with bodies held up by a collider at zero;
    r (N,): radii; ``loaded`` (P,): the pairs that carried load in the last step."""
    d = x0[a] - x0[b]
    dist = norm(d)
    nrm = unit(d, dist)
    gap = dist - r[a] - r[b]
    closing = -dot(v0[a] - v0[b], nrm)
    press = dot(Ah[a] - Ah[b], nrm)
    pull = np.maximum(norm(A[a]), norm(A[b]))
    small = np.minimum(r[a], r[b])
    margin = 0.05 * small + closing.clip(0) * dt
    near = gap <= margin
    rest = near & (np.abs(closing) <= 2.0 * dt * pull) & (press < -1e-9 * pull)
    # (Overlap past the slop: balls hung touching, as in a cradle, are no pile.)
    return loaded | rest | (gap < -SLOP * small)


def join_masks(
    a: np.ndarray,
    b: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    A: np.ndarray,
    r: np.ndarray,
    dt: float,
) -> tuple[np.ndarray, np.ndarray]:
    """(near_a, near_b), (P,) bool each: the pair joins the pile if a is the pile's (near_a)
    or if b is (near_b) (module text)."""
    ra, rb = r[a], r[b]
    Ar = norm(A[a] - A[b])
    rel = norm(v0[a] - v0[b])
    d = x0[a] - x0[b]
    dist = norm(d)
    gap = dist - ra - rb
    reach = rel * dt + 0.5 * Ar * dt * dt + 0.05 * np.minimum(ra, rb)
    caught = (rel + Ar * dt) * dt <= CATCH * (ra + rb)
    nrm = unit(d, dist)
    turn_a = 2.0 * np.abs(dot(v0[a], nrm)) * dt
    turn_b = 2.0 * np.abs(dot(v0[b], nrm)) * dt
    return (gap <= reach + turn_a) & caught, (gap <= reach + turn_b) & caught


def grow(
    island: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    near_a: np.ndarray,
    near_b: np.ndarray,
) -> np.ndarray:
    """The piles (``island``, (N,) bool, in place) grown by ``GROW_ROUNDS`` rounds: each
    round, every pair that joins (``join_masks``) a pile's body brings the other in."""
    for _ in range(GROW_ROUNDS):
        joins = (island[a] & ~island[b] & near_a) | (island[b] & ~island[a] & near_b)
        if not joins.any():
            break
        island[a[joins]] = island[b[joins]] = True
    return island


def _sample_plan() -> tuple[object, ...]:
    """The smallest call of ``plan_pairs``: two discs resting on one another."""
    x = np.array([[0.0, 0.5], [0.0, 1.5]])
    z = np.zeros((2, 2))
    g = np.array([[0.0, -9.8], [0.0, -9.8]])
    one, no = np.ones(2), np.zeros(2, dtype=bool)

    i, j = np.array([0]), np.array([1])
    return (i, j, x, z, g, g, one * 0.5, 1 / 60, np.zeros(1, dtype=bool), no.copy(), no, no, True)


@kernels.loop(sample=_sample_plan)
def plan_pairs(
    a: np.ndarray,
    b: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    A: np.ndarray,
    Ah: np.ndarray,
    r: np.ndarray,
    dt: float,
    loaded: np.ndarray,
    island: np.ndarray,
    kin: np.ndarray,
    asleep: np.ndarray,
    seeding: bool,
) -> None:
    """``rest_seeds`` (if ``seeding``), ``join_masks`` and ``grow`` in one pass over the
    pairs, in place on ``island``. ``kin`` (N,): bodies the game moves (their pairs always
    join); ``asleep`` (N,): sleepers (their pairs never join)."""
    m = len(a)
    near_a = np.zeros(m, dtype=np.bool_)
    near_b = np.zeros(m, dtype=np.bool_)
    seed = np.zeros(m, dtype=np.bool_)
    for k in range(m):
        i, j = a[k], b[k]
        dx, dy = x0[i, 0] - x0[j, 0], x0[i, 1] - x0[j, 1]
        dist = math.sqrt(dx * dx + dy * dy)
        if dist > 0.0:
            nx, ny = dx / dist, dy / dist
        else:
            nx, ny = 0.0, 1.0
        ri, rj = r[i], r[j]
        small = min(ri, rj)
        # rest_seeds
        gap = dist - ri - rj
        wx, wy = v0[i, 0] - v0[j, 0], v0[i, 1] - v0[j, 1]
        closing = -(wx * nx + wy * ny)
        hx, hy = Ah[i, 0] - Ah[j, 0], Ah[i, 1] - Ah[j, 1]
        press = hx * nx + hy * ny
        pi = math.sqrt(A[i, 0] * A[i, 0] + A[i, 1] * A[i, 1])
        pj = math.sqrt(A[j, 0] * A[j, 0] + A[j, 1] * A[j, 1])
        pull = max(pi, pj)
        margin = 0.05 * small + max(closing, 0.0) * dt
        if seeding:
            rest = gap <= margin and abs(closing) <= 2.0 * dt * pull and press < -1e-9 * pull
            seed[k] = loaded[k] or rest or gap < -SLOP * small
        # join_masks
        gx, gy = A[i, 0] - A[j, 0], A[i, 1] - A[j, 1]
        Ar = math.sqrt(gx * gx + gy * gy)
        rel = math.sqrt(wx * wx + wy * wy)
        reach = rel * dt + 0.5 * Ar * dt * dt + 0.05 * small
        caught = (rel + Ar * dt) * dt <= CATCH * (ri + rj)
        turn_a = 2.0 * abs(v0[i, 0] * nx + v0[i, 1] * ny) * dt
        turn_b = 2.0 * abs(v0[j, 0] * nx + v0[j, 1] * ny) * dt
        na = gap <= reach + turn_a and caught
        nb = gap <= reach + turn_b and caught
        if kin[i] or kin[j]:
            na = nb = True
        if asleep[i] or asleep[j]:
            na = nb = False
        near_a[k], near_b[k] = na, nb
    for k in range(m):
        if seed[k]:
            island[a[k]] = True
            island[b[k]] = True
    joins = np.zeros(m, dtype=np.bool_)
    for _ in range(GROW_ROUNDS):
        # Each round decided on the piles as the round began, as the numpy twin's does.
        any_join = False
        for k in range(m):
            ia, ib = island[a[k]], island[b[k]]
            joins[k] = (ia and not ib and near_a[k]) or (ib and not ia and near_b[k])
            any_join = any_join or joins[k]
        if not any_join:
            break
        for k in range(m):
            if joins[k]:
                island[a[k]] = True
                island[b[k]] = True
