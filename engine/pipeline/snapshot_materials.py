"""The materials a snapshot keeps: each body's and each collider's, set back by a restore.

A body's ``restitution``, ``friction``, ``filter`` and ``bullet`` flag and a collider's, with
its ``sensor`` flag, can be set at any time, and the steps after depend on them: a World
restored must bounce and slide as it did when the snapshot was taken, so the snapshot holds
them (engine.pipeline.snapshot). A snapshot made by hand without them (None) leaves them as they
are. A body's ``data`` and its drawing colour are the game's own and are not kept.
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from ..body_values import material
from ..filters import as_filter
from ..geometry.colliders import MATERIAL, Collider

if TYPE_CHECKING:
    from .world_state import WorldState

__all__ = [
    "take_bodies",
    "take_bullets",
    "take_colliders",
    "check",
    "check_bullets",
    "set_colliders",
    "set_bodies",
    "set_bullets",
]

#: A body's material: (restitution, friction, Filter).
BodyMaterial = tuple[float, float, Any]
#: A collider's: (restitution, friction, sensor, Filter), in MATERIAL's order.
ColliderMaterial = tuple[float, float, bool, Any]


def take_bodies(state: WorldState) -> tuple[BodyMaterial, ...]:
    """Each body's (restitution, friction, filter), in the World's order."""
    return tuple((b.restitution, b.friction, b.filter) for b in state.bodies)


def take_bullets(state: WorldState) -> tuple[bool, ...]:
    """Each body's ``bullet`` flag, in the World's order."""
    return tuple(b.bullet for b in state.bodies)


def take_colliders(state: WorldState) -> tuple[ColliderMaterial, ...]:
    """Each collider's (restitution, friction, sensor, filter), in the World's order."""
    return tuple(_of(c) for c in state.colliders)


def _of(collider: Collider) -> ColliderMaterial:
    return (collider.restitution, collider.friction, collider.sensor, collider.filter)


def check(
    state: WorldState, bodies: Any, colliders: Any
) -> tuple[list[BodyMaterial] | None, list[ColliderMaterial] | None]:
    """The snapshot's ``materials`` and ``collider_materials`` checked against this World (one
    entry per body, per collider; each value as a Body or collider would take it), or a
    TypeError / ValueError that names the field, changing nothing."""
    out_b: list[BodyMaterial] | None = None
    out_c: list[ColliderMaterial] | None = None
    if bodies is not None:
        _count(bodies, len(state.bodies), "materials", "(restitution, friction, filter)")
        out_b = []
        for k, item in enumerate(bodies):
            try:
                _, e, mu = material(0.0, item[0], item[1])
                out_b.append((e, mu, as_filter(item[2])))
            except (TypeError, ValueError) as exc:
                raise type(exc)(f"snapshot.materials[{k}]: {exc}") from None
    if colliders is not None:
        what = "(restitution, friction, sensor, filter)"
        _count(colliders, len(state.colliders), "collider_materials", what)
        out_c = []
        for k, item in enumerate(colliders):
            probe = Collider.__new__(Collider)  # checked as a collider's, on no collider
            try:
                Collider.__init__(probe, item[0], item[1], item[2], item[3])
            except (TypeError, ValueError) as exc:
                raise type(exc)(f"snapshot.collider_materials[{k}]: {exc}") from None
            out_c.append(_of(probe))
    return out_b, out_c


def check_bullets(state: WorldState, bullets: Any) -> list[bool] | None:
    """The snapshot's ``bullets`` checked against this World (one True or False per body), or
    a ValueError that names the field, changing nothing."""
    if bullets is None:
        return None
    n = len(state.bodies)
    ok = isinstance(bullets, tuple) and len(bullets) == n
    if not (ok and all(isinstance(b, bool) for b in bullets)):
        raise ValueError(
            f"snapshot.bullets must be a tuple of {n} bools (each body's Body.bullet), got "
            f"{bullets!r}"
        )
    return list(bullets)


def _count(values: Any, n: int, name: str, what: str) -> None:
    ok = isinstance(values, tuple) and len(values) == n
    if not (ok and all(isinstance(v, tuple) and len(v) == len(what.split(",")) for v in values)):
        raise ValueError(f"snapshot.{name} must be a tuple of {n} tuples {what}, got {values!r}")


def set_colliders(state: WorldState, values: list[ColliderMaterial]) -> list[ColliderMaterial]:
    """Give each collider its material from ``values`` (as ``collider.name = value`` does,
    each World holding it told); return what they had, to set back if the restore is refused
    after all. A sensor made solid pushes out no body here: the bodies' places are the
    snapshot's, set next."""
    before = [_of(c) for c in state.colliders]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for c, new in zip(state.colliders, values, strict=True):
            for name, value in zip(MATERIAL, new, strict=True):
                setattr(c, name, value)
    return before


def set_bodies(state: WorldState, values: list[BodyMaterial]) -> None:
    """Give each body its material from ``values``: the body arrays' columns made anew (the
    World's caches keyed on them are made again; the restore then changes its structure)."""
    store = state.store
    for b, (e, mu, f) in zip(state.bodies, values, strict=True):
        b._e, b._mu, b._filter = e, mu, f
    if store is None or not values:
        return
    store.restitution = np.array([e for e, _, _ in values], dtype=float)
    store.friction = np.array([mu for _, mu, _ in values], dtype=float)
    # (A sensor body's contacts meet nothing, whatever its filter: Body.solid_filter.)
    solid = [b.solid_filter for b in state.bodies]
    store.group = np.array([f.group for f in solid], dtype=np.int64)
    store.categories = np.array([f.categories for f in solid], dtype=np.int64)
    store.mask = np.array([f.mask for f in solid], dtype=np.int64)


def set_bullets(state: WorldState, values: list[bool]) -> None:
    """Give each body its ``bullet`` flag from ``values``: the store's column made anew."""
    for b, flag in zip(state.bodies, values, strict=True):
        b._bullet = flag
    if state.store is not None and values:
        state.store.bullet = np.array(values, dtype=bool)
