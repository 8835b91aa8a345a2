"""Collision types and per-pair callbacks: pymunk's ``collision_type`` and ``on_collision``.

A Body and a collider each carry a ``collision_type`` (an int >= 0, 0 by default).
``World.on_collision(type_a, type_b, begin=..., pre_solve=..., post_solve=..., separate=...)``
holds four callbacks for the contacts between a thing of type ``type_a`` and one of type
``type_b`` (None for either: any type, pymunk's wildcard). Each callback takes one
``ContactEvent`` (engine.dynamics.events) seen from the ``type_a`` side where it can be: for two
bodies, ``event.body`` is of ``type_a``; a contact between a body and a collider always has
the Body as ``event.body``. A handler whose types match the pair either way is called once.

* ``begin`` and ``separate`` come after the step in which the contact began or ended, and
  ``post_solve`` after each step for every contact open then (``World.began``,
  ``World.ended`` and ``World.touching`` list the same events).
* ``pre_solve`` comes before each step, for each body and collider of the matching types
  that may touch in it: the body's bounding circle within its reach of the collider's
  surface (``reach``: what it moves in the step, |v| dt + |g| dt^2, and one radius more).
  Its event has the point on the collider nearest the body, the normal there toward the
  body, no impulse and the time the step begins. It returns False to ignore the contact
  for that step (pymunk 6's return value; pymunk 7 sets ``arbiter.process_collision``):
  the pair is then filtered for the step, as a Filter would, so the body passes through
  the collider in the exact impacts and in the pile's rows alike, on both paths. A one-way
  platform is a ``pre_solve`` that lets a body through unless it is above and coming down.
  Pairs of bodies do not take ``pre_solve`` (yet): a handler with one for them is called
  only for bodies and colliders.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from ..body import Body
from ..collision_types import as_collision_type
from ..dynamics.events import ContactEvent
from ..geometry.faces import signed_distance
from ..vector import Vector

if TYPE_CHECKING:
    from .world_state import WorldState

__all__ = ["CollisionHandler", "add", "ignored_pairs", "report"]

Callback = Callable[[ContactEvent], Any]


class CollisionHandler:
    """The callbacks for the contacts between types ``a`` and ``b`` (None: any type)."""

    __slots__ = ("a", "b", "begin", "pre_solve", "post_solve", "separate")

    def __init__(
        self,
        a: int | None,
        b: int | None,
        begin: Callback | None,
        pre_solve: Callback | None,
        post_solve: Callback | None,
        separate: Callback | None,
    ) -> None:
        self.a = None if a is None else as_collision_type(a)
        self.b = None if b is None else as_collision_type(b)
        for name, fn in (
            ("begin", begin),
            ("pre_solve", pre_solve),
            ("post_solve", post_solve),
            ("separate", separate),
        ):
            if fn is not None and not callable(fn):
                raise TypeError(f"{name} must be a function of one ContactEvent, got {fn!r}")
        self.begin, self.pre_solve = begin, pre_solve
        self.post_solve, self.separate = post_solve, separate

    def side(self, first: int, second: int) -> int:
        """1 if a thing of type ``first`` and one of ``second`` match (a, b) in that order,
        -1 if only the other way round, 0 if neither."""
        if (self.a is None or self.a == first) and (self.b is None or self.b == second):
            return 1
        if (self.a is None or self.a == second) and (self.b is None or self.b == first):
            return -1
        return 0


def add(state: WorldState, handler: CollisionHandler) -> Callable[[], None]:
    """Hold ``handler``; return the function that takes it off again."""
    state.collision_handlers.append(handler)

    def remove() -> None:
        """Take this handler off (again: nothing happens)."""
        state.collision_handlers = [h for h in state.collision_handlers if h is not handler]

    return remove


def _type_of(thing: Any) -> int:
    return int(thing.collision_type)


def report(state: WorldState) -> None:
    """Call the handlers' begin, separate and post_solve with the last step's events."""
    handlers = state.collision_handlers
    if not handlers:
        return
    events = state.events
    for name in ("begin", "separate", "post_solve"):
        mine = [h for h in handlers if getattr(h, name) is not None]
        if not mine:
            continue
        listed = events.began if name == "begin" else events.ended
        if name == "post_solve":
            listed = events.touching
        for ev in listed:
            ta, tb = _type_of(ev.body), _type_of(ev.collider)
            for h in mine:
                side = h.side(ta, tb)
                if side == 0:
                    continue
                flip = side < 0 and isinstance(ev.collider, Body)
                getattr(h, name)(ev.flipped() if flip else ev)


def ignored_pairs(state: WorldState, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Call the pre_solve callbacks for the step of ``dt`` (s) about to be taken; return the
    pairs whose callback returned False, to be filtered for the step: (K, 2) of (body row,
    collider place), and the pairs of bodies as sorted keys a * n + b (World rows a < b, n
    bodies; as ``Collisions.apart``)."""
    handlers = [h for h in state.collision_handlers if h.pre_solve is not None]
    store = state.store
    none = np.zeros((0, 2), dtype=np.int64)
    keys = np.zeros(0, dtype=np.int64)
    if not handlers or store is None or store.dim != 2 or not len(state.bodies):
        return none, keys
    x, v, r = store.x, store.v, store.radius
    # What a body may move in the step, with a margin: |v| dt + |a| dt^2 (twice the
    # parabola's a dt^2 / 2, for the forces the constant part a0 of the model leaves out),
    # and its radius again (a shape turning within its bounding circle).
    model = state.model
    a0 = None if model is None else np.asarray(model.a0, dtype=float)
    accel = np.hypot(a0[:, 0], a0[:, 1]) if a0 is not None and a0.shape == x.shape else 0.0
    speed = np.hypot(v[:, 0], v[:, 1])
    reach = speed * dt + accel * dt * dt + r + 1e-9
    types = [b.collision_type for b in state.bodies]
    faces = _with_colliders(state, handlers, types, reach)
    if state.pairs_on:
        keys = _between_bodies(state, handlers, types, reach)
    return faces, keys


def _event(body: Any, other: Any, point: Any, normal: Any, t: float) -> ContactEvent:
    """A pre_solve's event: no impulse yet, at the step's start."""
    return ContactEvent(
        body,
        other,
        Vector(float(point[0]), float(point[1])),
        Vector(float(normal[0]), float(normal[1])),
        Vector(0.0, 0.0),
        t,
    )


def _with_colliders(
    state: WorldState, handlers: list[CollisionHandler], types: list[int], reach: np.ndarray
) -> np.ndarray:
    """The (body row, collider place) pairs a pre_solve refuses (``ignored_pairs``): pairs
    of the handler's types whose boxes (the collider's bounds, the body's centre +- its
    reach) overlap are measured, and those within reach asked."""
    store, contacts = state.store, state.contacts
    out: list[tuple[int, int]] = []
    if contacts is None or store is None or not contacts.colliders:
        return np.zeros((0, 2), dtype=np.int64)
    x, r, bodies, t = store.x, store.radius, state.bodies, state.t
    colliders = contacts.colliders
    bounds = contacts.collider_bounds()
    typed = np.array(types, dtype=np.int64)
    kinds = np.array([c.collision_type for c in colliders], dtype=np.int64)
    solid = ~np.array([c.sensor for c in colliders], dtype=bool)
    # Boxes that overlap: the collider's bounds against the body's centre +- its reach.
    near = (
        (bounds[:, None, 0] <= x[None, :, 0] + reach[None, :])
        & (bounds[:, None, 2] >= x[None, :, 0] - reach[None, :])
        & (bounds[:, None, 1] <= x[None, :, 1] + reach[None, :])
        & (bounds[:, None, 3] >= x[None, :, 1] - reach[None, :])
        & solid[:, None]
    )
    for h in handlers:
        # The body of type a and the collider of type b, or the other way round.
        body_a = np.ones(len(typed), dtype=bool) if h.a is None else typed == h.a
        body_b = np.ones(len(typed), dtype=bool) if h.b is None else typed == h.b
        coll_a = np.ones(len(kinds), dtype=bool) if h.a is None else kinds == h.a
        coll_b = np.ones(len(kinds), dtype=bool) if h.b is None else kinds == h.b
        match = (coll_b[:, None] & body_a[None, :]) | (coll_a[:, None] & body_b[None, :])
        cand = near & match
        for k in np.flatnonzero(cand.any(axis=1)).tolist():
            c = colliders[k]
            rows = np.flatnonzero(cand[k])
            gap = signed_distance(c, x[rows]) - r[rows]
            for i in rows[gap <= reach[rows]].tolist():
                point, normal, _ = c.closest((float(x[i, 0]), float(x[i, 1])))
                assert h.pre_solve is not None
                if h.pre_solve(_event(bodies[i], c, point, normal, t)) is False:
                    out.append((i, k))
    if not out:
        return np.zeros((0, 2), dtype=np.int64)
    return np.unique(np.array(out, dtype=np.int64), axis=0)


def _between_bodies(
    state: WorldState, handlers: list[CollisionHandler], types: list[int], reach: np.ndarray
) -> np.ndarray:
    """The pairs of bodies a pre_solve refuses, as keys a * n + b (``ignored_pairs``): pairs
    of the handler's types whose bounding circles are within their reaches of each other,
    each asked once a handler, from the ``type_a`` side; the point is on the other body's
    bounding circle, the normal from its centre toward the body's."""
    store = state.store
    assert store is not None
    x, r, bodies, t = store.x, store.radius, state.bodies, state.t
    n = len(bodies)
    out: list[int] = []
    typed = np.array(types, dtype=np.int64)
    solid = r > 0.0  # (points never collide)
    for h in handlers:
        first = solid & (typed == h.a) if h.a is not None else solid
        second = solid & (typed == h.b) if h.b is not None else solid
        ia, ib = np.flatnonzero(first), np.flatnonzero(second)
        if not len(ia) or not len(ib):
            continue
        d = x[ia][:, None, :] - x[ib][None, :, :]
        gap = np.hypot(d[..., 0], d[..., 1]) - r[ia][:, None] - r[ib][None, :]
        near = (gap <= reach[ia][:, None] + reach[ib][None, :]) & (ia[:, None] != ib[None, :])
        seen: set[tuple[int, int]] = set()
        for p, q in zip(*np.nonzero(near), strict=True):
            i, j = int(ia[p]), int(ib[q])  # i of type a, j of type b
            if (min(i, j), max(i, j)) in seen:
                continue  # both of both types: asked once
            seen.add((min(i, j), max(i, j)))
            dx, dy = float(x[i, 0] - x[j, 0]), float(x[i, 1] - x[j, 1])
            dist = float(np.hypot(dx, dy))
            nx, ny = (dx / dist, dy / dist) if dist > 0.0 else (0.0, 1.0)
            point = (float(x[j, 0]) + nx * float(r[j]), float(x[j, 1]) + ny * float(r[j]))
            assert h.pre_solve is not None
            if h.pre_solve(_event(bodies[i], bodies[j], point, (nx, ny), t)) is False:
                out.append(min(i, j) * n + max(i, j))
    return np.unique(np.array(out, dtype=np.int64))
