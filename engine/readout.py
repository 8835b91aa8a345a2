"""Reading a World's state: positions (blended between the last two steps, for drawing),
velocities and the mechanical energy; which bodies sleep, what each rests on, and the
deepest overlap between bodies.
"""

from __future__ import annotations

from numbers import Real
from typing import TYPE_CHECKING

import numpy as np

from .body import Body, State
from .colliders import Collider
from .collisions import deepest_overlap

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


def overlap(state: WorldState) -> float:
    """The deepest overlap (length units) between two bodies that collide, now."""
    store = state.store
    if store is None or store.dim != 2 or not state.bodies:
        return 0.0
    live = state.collisions.live(store.radius, store.group, store.categories, store.mask)
    if len(live) < 2 or state.collisions.one_group:
        return 0.0
    filters = (store.group[live], store.categories[live], store.mask[live])
    return deepest_overlap(store.x[live], store.radius[live], filters)


def resting(state: WorldState, body: Body) -> Collider | None:
    """The collider ``body`` rests on (slides or sits on), or None while it is in flight."""
    if not isinstance(body, Body) or body.world is not state.world:
        raise ValueError(f"that body is not in this World: {body!r}")
    contacts, store = state.contacts, state.store
    if contacts is None or store is None:
        return None
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
    turns) plus the potential of the forces that have one.

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
    return total
