"""Reading a World's state: positions (blended between the last two steps, for drawing),
velocities and the mechanical energy; which bodies sleep, what each rests on, and the
deepest overlap between bodies.
"""

from __future__ import annotations

from numbers import Real
from typing import TYPE_CHECKING

import numpy as np

from ..body import Body, State
from ..exact.collisions import deepest_overlap
from ..geometry.colliders import Collider
from ..geometry.pair_grid import grid_pairs
from ..geometry.pair_math import norm
from ..geometry.shaped import pair_rows, part_pairs

if TYPE_CHECKING:
    from .world_state import WorldState

__all__ = [
    "energy",
    "is_sleeping",
    "overlap",
    "position_of",
    "positions",
    "resting",
    "velocities",
]


def is_sleeping(state: WorldState, body: Body) -> bool:
    """Whether ``body`` sleeps (it stays exactly put until an awake body meets its group)."""
    if not isinstance(body, Body) or body.world is not state.world:
        raise ValueError(f"that body is not in this World: {body!r}")
    asleep = state.collisions.asleep
    assert state.store is not None
    row = state.store.row(body.slot)
    return bool(row < len(asleep) and asleep[row])


def overlap(
    state: WorldState, x: np.ndarray | None = None, angle: np.ndarray | None = None
) -> float:
    """The deepest overlap (length units) between two bodies that collide, now, or with the
    bodies at positions ``x`` (N, 2) and angles ``angle`` (N,) where given: of their shapes
    (a box's at its angle), not of the circles that hold them."""
    store = state.store
    if store is None or store.dim != 2 or not state.bodies:
        return 0.0
    x = store.x if x is None else x
    angle = store.angle if angle is None else angle
    live = state.collisions.live(store.radius, store.group, store.categories, store.mask)
    if len(live) < 2 or state.collisions.one_group:
        return 0.0
    filters = (store.group[live], store.categories[live], store.mask[live])
    table = state.collisions.shape_table(store)
    if not table.shaped[live].any():
        return deepest_overlap(x[live], store.radius[live], filters)
    # Bodies with shapes: the pairs whose bounding circles meet are measured by the
    # narrowphase at their angles (engine.geometry.shaped); two discs by their centres.
    a, b = _circle_pairs(x[live], store.radius[live])
    g, c, m = filters
    ok = ~((g[a] == g[b]) & (g[a] != 0)) & ((c[a] & m[b]) != 0) & ((c[b] & m[a]) != 0)
    a, b = live[a[ok]], live[b[ok]]
    kin = store.kinematic
    a, b = a[~(kin[a] & kin[b])], b[~(kin[a] & kin[b])]  # what the game moves meets no other
    if not len(a):
        return 0.0
    parts = table.parts
    if parts is None:
        sep = pair_rows(table, a, b, x, 0.0, angle)[3]
        return max(-float(sep.min(initial=0.0)), 0.0)
    # Bodies of several shapes (engine.body_shapes): every part of A with every part of B,
    # each at its body's pose.
    pa, pb = part_pairs(parts, a, b)
    owner = parts.owner
    sep = pair_rows(parts.table, pa, pb, x[owner], 0.0, angle[owner])[3]
    return max(-float(sep.min(initial=0.0)), 0.0)


def _circle_pairs(x: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pairs (i < j) of circles at x (N, 2) with radii r (N,) that meet: a grid for the
    ordinary ones; each body over 4 times the median radius (a tumbler's wall, a long
    platform), which would make the grid's cells as large as itself, against every body."""
    big = r > 4.0 * float(np.median(r))
    small = np.flatnonzero(~big)
    i, j = grid_pairs(x[small], 2.0 * float(r[small].max()) + 1e-300)
    i, j = small[i], small[j]
    far = norm(x[i] - x[j]) > r[i] + r[j]
    ai, bj = [i[~far]], [j[~far]]
    for k in np.flatnonzero(big).tolist():
        near = np.flatnonzero(norm(x - x[k]) <= r + r[k])
        near = near[(near != k) & (~big[near] | (near > k))]  # each pair of big ones once
        ai.append(np.minimum(near, k))
        bj.append(np.maximum(near, k))
    return np.concatenate(ai), np.concatenate(bj)


def resting(state: WorldState, body: Body) -> Collider | None:
    """The collider ``body`` rests on (slides or sits on), or None while it is in flight."""
    if not isinstance(body, Body) or body.world is not state.world:
        raise ValueError(f"that body is not in this World: {body!r}")
    contacts, store = state.contacts, state.store
    if contacts is None or store is None:
        return None
    if state.game is not None:
        # The soft step's: the collider of the body's touching contacts that pushed it
        # hardest in the last step (none pushed: in flight).
        serial = state.game.resting(body.slot)
        return None if serial is None else state.events.collider_of(serial)
    f = int(contacts.rest[store.row(body.slot)])
    return None if f < 0 else contacts.colliders[int(contacts.faces.owner[f])]


def _empty(state: WorldState) -> np.ndarray:
    return np.zeros((0,) if state.dim != 2 else (0, 2))


def positions(state: WorldState, alpha: float = 1.0) -> np.ndarray:
    """Positions of all bodies blended from the previous step: prev + (now - prev) alpha.

    ``alpha`` in [0, 1] comes from the fixed-step loop; 1.0 gives the current state.
    Shape (N,) in 1D, (N, 2) in 2D; a new array. As in every fixed-step loop that
    interpolates, what is drawn lies between the last two steps, so up to one step
    behind ``t``: step once ahead before the first frame (as ``engine.render.record``
    does) to draw each frame exactly at its own time.
    """
    if isinstance(alpha, bool) or not isinstance(alpha, Real) or not 0.0 <= alpha <= 1.0:
        raise ValueError(f"alpha must be a number in [0, 1], got {alpha!r}")
    store = state.store
    if store is None or not state.bodies:
        return _empty(state)
    if alpha == 1.0:
        return store.x.copy()
    return store.prev_x + (store.x - store.prev_x) * float(alpha)


def position_of(state: WorldState, body: Body, alpha: float = 1.0) -> State:
    """One body's position, blended like ``positions(alpha)``: a float or a Vector."""
    if not isinstance(body, Body) or body.world is not state.world:
        raise ValueError(f"that body is not in this World: {body!r}")
    if isinstance(alpha, bool) or not isinstance(alpha, Real) or not 0.0 <= alpha <= 1.0:
        raise ValueError(f"alpha must be a number in [0, 1], got {alpha!r}")
    store = state.store
    assert store is not None
    row = store.row(body.slot)
    x, prev = store.x[row], store.prev_x[row]
    return store.value(x if alpha == 1.0 else prev + (x - prev) * float(alpha))


def velocities(state: WorldState) -> np.ndarray:
    """Velocities of all bodies now, shape (N,) or (N, 2); a new array."""
    if state.store is None or not state.bodies:
        return _empty(state)
    return state.store.v.copy()


def energy(state: WorldState) -> float:
    """Total mechanical energy (J): kinetic (m v^2 / 2, and I omega^2 / 2 for a body that
    turns) plus the potential of the forces that have one and the springs' energy.

    A body's own constant acceleration a counts like gravity, with potential -m a . x.
    Kinematic and pinned bodies are left out: the game (or the pin) moves them, and no
    force acts on them.
    """
    if not state.bodies:
        return 0.0
    model = state.ready()
    store = state.store
    assert store is not None
    x, v, m = store.x, store.v, store.mass
    held = store.kinematic
    if held.any():
        m = np.where(held, 0.0, m)
    v2 = v * v if state.dim == 1 else np.einsum("ij,ij->i", v, v)
    total = 0.5 * float(np.sum(m * v2))
    if store.turns_any:
        # Bodies that turn: I omega^2 / 2 (the others have no spin, or an infinite moment).
        spin = store.omega
        total += 0.5 * float(
            np.sum(np.where(store.inv_moment > 0.0, store.moment, 0.0) * spin * spin)
        )
    dot = store.own * x if state.dim == 1 else np.einsum("ij,ij->i", store.own, x)
    total -= float(np.sum(m * dot))
    for attached in state.forces:
        if attached.bodies is None:
            idx = np.flatnonzero(~held) if held.any() else None
        else:
            idx = state.rows_of(attached.bodies)
            idx = idx[~held[idx]]
        if idx is None:
            u = attached.force.potential(x, model.mass)
        else:
            u = attached.force.potential(x[idx], model.mass[idx]) if len(idx) else 0.0
        if u is not None:
            total += float(np.sum(u))
    # And what the springs between bodies store (engine.dynamics.springs).
    return total + sum(s.energy() for s in state.springs.items)
