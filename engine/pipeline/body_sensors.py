"""Sensor bodies: what each overlaps at the end of a step (a player's feet sensor).

A Body made with ``sensor=True`` meets nothing in the contacts (its contacts' filter is one
that meets nothing: ``Body.solid_filter``), so it passes through everything and pushes
nothing. At the end of each step the World finds what it overlaps, as a sensor collider's
overlaps are found (engine.geometry.sensors), and the contact events keep each overlap open exactly
while it lasts (engine.dynamics.events: the ``sensing`` keys), so ``World.began``, ``World.ended``,
``World.on_contact`` and ``World.on_collision`` report them:

* another body (not a sensor, radius > 0) whose filter and the sensor's collide
  (``Filter.collides``), overlapping it: the distance of their centres less than the sum of
  their radii, and where either has a shape other than a disc, a point of their manifold
  made with no margin of negative separation (engine.geometry.manifold), each turned by its angle;
* a solid collider whose filter and the sensor's collide, overlapping it: the gap of the
  sensor's centre from the collider's surface less than its radius, and for a sensor with a
  shape, by its shape (engine.geometry.sensors, ``shape_overlaps``; a Box room by the bounding
  circle).

It costs a pass over the sensor bodies (few: a player's feet) against every body's bounding
circle and every collider, in numpy.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..dynamics.events import collider_keys, pair_keys
from ..geometry.colliders import Box
from ..geometry.faces import signed_distance
from ..geometry.manifold import collide
from ..geometry.sensors import shape_overlaps

if TYPE_CHECKING:
    from .world_state import WorldState

__all__ = ["sensed"]

#: No keys (read only: returned by ``sensed`` every step where no sensor body overlaps anything).
_NONE = np.zeros(0, dtype=np.int64)
_NONE.flags.writeable = False


def sensed(state: WorldState, slots: np.ndarray | None, serials: np.ndarray | None) -> np.ndarray:
    """The contact keys (engine.dynamics.events) of what each sensor body overlaps now: with other
    bodies (``pair_keys``) and with colliders (``collider_keys``, by ``serials``, the
    colliders' serial numbers in the World's order; None: no colliders). ``slots``: the
    bodies' slots by row (None: the store's, read only where a body is a sensor)."""
    store = state.store
    if store is None or store.dim != 2:
        return _NONE
    rows = _sensor_rows(state)
    if not rows:
        return _NONE
    if slots is None:
        slots = store.slots()
    bodies = state.bodies
    x, r = store.x, store.radius
    angle = store.angle
    table = state.collisions.shape_table(store)
    found: list[np.ndarray] = []
    others = np.array([not b.sensor for b in bodies]) & (r > 0.0)
    contacts = state.contacts
    for s in rows:
        mine = bodies[s].filter
        d = x - x[s]
        near = others & (np.hypot(d[:, 0], d[:, 1]) < r + r[s])
        near[s] = False
        hits = []
        for j in np.flatnonzero(near).tolist():
            if not mine.collides(bodies[j].filter):
                continue
            if (table.shaped[s] or table.shaped[j]) and not _overlap(table, s, j, x, angle):
                continue
            hits.append(j)
        if hits:
            found.append(pair_keys(np.full(len(hits), slots[s]), slots[np.array(hits)]))
        if contacts is None or serials is None:
            continue
        for k, c in enumerate(contacts.colliders):
            if c.sensor or not mine.collides(c.filter):
                continue
            if float(signed_distance(c, x[s : s + 1])[0]) >= r[s]:
                continue
            if table.shaped[s] and not isinstance(c, Box):
                shapes, rows = _parts_of(table, s)
                if not any(
                    shape_overlaps(shapes.kinds(np.array([p])), x[s], float(angle[s]), c)
                    for p in rows
                ):
                    continue
            found.append(collider_keys(np.array([slots[s]]), serials[[k]]))
    return np.concatenate(found) if found else _NONE


def _parts_of(table: Any, row: int) -> tuple[Any, list[int]]:
    """The table a body's shapes are rows of, and their rows: its own row, or where a body is of
    several shapes (engine.body_shapes) its parts' rows of the parts' table."""
    parts = table.parts
    if parts is None:
        return table, [row]
    start = int(parts.first[row])
    return parts.table, list(range(start, start + int(parts.size[row])))


def _overlap(table: Any, s: int, j: int, x: np.ndarray, angle: np.ndarray) -> bool:
    """Whether the shapes of bodies s and j overlap (any part of one with any of the other)."""
    shapes, mine = _parts_of(table, s)
    _, theirs = _parts_of(table, j)
    for p in mine:
        for q in theirs:
            m = collide(
                shapes.kinds(np.array([p])), x[s : s + 1], angle[s : s + 1],
                shapes.kinds(np.array([q])), x[j : j + 1], angle[j : j + 1], 0.0,
            )  # fmt: skip
            n = int(m.count[0])
            if n and float(m.separation[0, :n].min()) < 0.0:
                return True
    return False


def _sensor_rows(state: WorldState) -> list[int]:
    """The rows of the sensor bodies, found again only when the store's categories or mask
    array is a new one: a body added or taken out, a filter or ``sensor`` set, a snapshot
    brought back each makes them anew (engine.dynamics.store, ``BodyStore.set_material``), and a
    body is a sensor only by ``Body.sensor``, whose setter sets its filter."""
    store = state.store
    assert store is not None
    kept = state.sensor_rows
    if kept is not None and kept[0] is store.categories and kept[1] is store.mask:
        return kept[2]
    # A sensor's contacts meet nothing: categories and mask 0 (few bodies have both).
    maybe = np.flatnonzero((store.categories == 0) & (store.mask == 0))
    bodies = state.bodies
    rows = [int(i) for i in maybe if bodies[i].sensor]
    state.sensor_rows = (store.categories, store.mask, rows)
    return rows
