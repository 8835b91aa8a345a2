"""What a World holds, and how things come and go: bodies (added in batches, all or
nothing), forces and the bodies they act on, links (rods, cables, pins) and static colliders.

Adding a body or a collider pushes out any body found inside a solid collider
(engine.exact.overlaps); taking a body out ends its open contacts and its links.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from ..body import Body
from ..dynamics.events import other_of, slot_of
from ..dynamics.links import Link, Pin
from ..exact.contacts import Contacts
from ..exact.overlaps import freed, push_out
from ..forces import Force, as_force
from ..geometry.colliders import Collider
from ..geometry.manifold import static_shapes
from ..geometry.manifold_kinds import LINEAR_SLOP
from ..vector import Vector
from . import solver_choice
from .game_broadphase import static_bounds
from .world_state import AttachedForce

if TYPE_CHECKING:
    from .world_state import WorldState

__all__ = [
    "ColliderT",
    "LinkT",
    "add_all",
    "add_collider",
    "add_force",
    "add_link",
    "remove",
    "remove_collider",
    "remove_force",
    "remove_link",
]

#: What add_collider and add_link hand back: the very object given, with its own type.
ColliderT = TypeVar("ColliderT", bound=Collider)
LinkT = TypeVar("LinkT", bound=Link)


def add_all(state: WorldState, bodies: Iterable[Body]) -> list[Body]:
    """Add many bodies at once (one array copy instead of one per body); return them.

    All or nothing: a batch with one bad body is refused whole and changes nothing.
    """
    batch = list(bodies)
    for b in batch:
        if not isinstance(b, Body):
            raise _not_a_body("add", b)
        if b.world is not None:
            which = "this" if b.world is state.world else "another"
            raise ValueError(f"that body is already in {which} World; remove it first")
    if len({id(b) for b in batch}) != len(batch):
        raise ValueError("World.add_all was given the same body twice")
    if not batch:
        return batch
    several = solver_choice.compound(batch)
    if several is not None and state.solver == "exact":
        why = (
            "solver='auto' chose them at its first step, and keeps them once the World moves"
            if state.solver_asked == "auto"
            else "solver='exact'"
        )
        raise ValueError(
            f"a body of {len(several.shape)} shapes (Body(shapes=[...])) is the soft step's "
            f"alone, and this World runs the exact models ({why}), which take one shape a "
            f"body: make the World with World(solver='soft'), or World(solver='auto'), which "
            f"chooses the soft step when the scene holds such a body at its first step"
        )
    # An empty World takes the dimension of the first body; every body must share it.
    dim = state.dim if state.dim is not None else batch[0].dim
    for b in batch:
        state.check_dim(b.dim, "the body", dim, bodies=True)
    store = state.ensure_store(dim)
    slots = store.append(
        np.array([b.pos for b in batch], dtype=float).reshape((-1,) + store.x.shape[1:]),
        np.array([b.vel for b in batch], dtype=float).reshape((-1,) + store.x.shape[1:]),
        np.array([b.mass for b in batch], dtype=float),
        np.array([b.own_acc for b in batch], dtype=float).reshape((-1,) + store.x.shape[1:]),
        (
            np.array([b.radius for b in batch], dtype=float),
            np.array([b.restitution for b in batch], dtype=float),
            np.array([b.friction for b in batch], dtype=float),
        ),
        (
            np.array([b.solid_filter.group for b in batch], dtype=np.int64),
            np.array([b.solid_filter.categories for b in batch], dtype=np.int64),
            np.array([b.solid_filter.mask for b in batch], dtype=np.int64),
        ),
        np.array([b.kinematic for b in batch], dtype=bool),
        [b.shape for b in batch],
        (
            np.array([b.angle for b in batch], dtype=float),
            np.array([b.angular_velocity for b in batch], dtype=float),
            np.array([b.moment for b in batch], dtype=float),
            np.array([b.torque for b in batch], dtype=float),
        ),
        np.array([b.bullet for b in batch], dtype=bool),
    )
    for b, slot in zip(batch, slots, strict=True):
        b.attach(store, slot)
        state.bodies.append(b)
    if state.contacts is not None:
        state.contacts.bodies_added(len(batch))
        push_out(state, range(len(state.bodies) - len(batch), len(state.bodies)), stacklevel=4)
    state.changed_structure(appended=True)
    return batch


def _not_a_body(verb: str, thing: Any) -> TypeError:
    """World.add or World.remove (``verb``) given ``thing``, not a Body: which method takes it."""
    if isinstance(thing, Collider):
        instead = f"a collider goes by world.{verb}_collider(collider)"
    elif isinstance(thing, Link):
        instead = f"a link or joint goes by world.{verb}_link(link)"
    else:
        instead = f"a collider goes by world.{verb}_collider(...), a link by world.{verb}_link(...)"
    return TypeError(f"World.{verb} takes a Body, got {type(thing).__name__} {thing!r}: {instead}")


def remove(state: WorldState, body: Body) -> None:
    """Take ``body`` out of the world; it keeps its last position, velocity and mass."""
    if not isinstance(body, Body):
        raise _not_a_body("remove", body)
    if body.world is not state.world:
        raise ValueError(f"that body is not in this World: {body!r}")
    store = state.store
    assert store is not None
    pos, vel, mass, own = body.pos, body.vel, body.mass, body.own_acc
    spin = (body.angle, body.angular_velocity, body.torque)
    pushed = store.pushes.get(body.slot)
    if pushed is not None:
        # A push of apply_force was for this World's next step only: the body leaves with
        # its own acceleration and torque as they were before it.
        own, spin = Vector(*pushed[0]), (spin[0], spin[1], pushed[1])
    row = store.row(body.slot)
    # The last step's events are named before the rows shift, and the body's open contacts
    # end (reported with the next step).
    # (The soft step's events read nothing else of the rows: made on demand still.)
    touched = state.events.body_removed(body.slot, state.t, lazy=state.game is not None)
    sleep = _sleep_kept(state, row)
    del state.bodies[row]
    state.targets.pop(body, None)
    state.turn_targets.pop(body, None)
    store.remove(body.slot)
    gone = [k for k in state.links if body in k.bodies]
    if gone:
        # Its links go with it.
        state.links = [k for k in state.links if body not in k.bodies]
        state.links_changed()
    if state.contacts is not None:
        state.contacts.body_removed(row)
        freed(state, [b for k in gone for b in k.bodies if b is not body], stacklevel=5)
    for attached in state.forces:
        if attached.bodies is not None and body in attached.bodies:
            attached.bodies.remove(body)
    body.detach(pos, vel, mass, own, spin)
    state.changed_structure()
    if sleep is not None:
        _wake_touched(state, sleep, body.slot, touched, gone)


def _sleep_kept(state: WorldState, row: int) -> tuple[np.ndarray, ...] | None:
    """On the soft step, the sleep of every body but the one in ``row`` (asleep, still time,
    island), to be kept as a body goes (``_wake_touched``); None elsewhere: the exact
    pipeline wakes every body then."""
    c = state.collisions
    if state.game is None or len(c.asleep) != len(state.bodies) or len(c.still) != len(c.asleep):
        return None
    if len(c._group) != len(c.asleep):
        return None
    return np.delete(c.asleep, row), np.delete(c.still, row), np.delete(c._group, row)


def _wake_touched(
    state: WorldState, sleep: tuple[np.ndarray, ...], slot: int, touched: np.ndarray,
    gone: list[Any],
) -> None:  # fmt: skip
    """The sleep kept (``_sleep_kept``) put back after the body in ``slot`` went, and the
    bodies it touched (``touched``: its contacts' event keys) or was joined to (``gone``: the
    links that went with it) woken, with their sleeping groups, and no other: a bullet taken
    out wakes no pile (Box2D's rule)."""
    c, store = state.collisions, state.store
    assert store is not None
    c.asleep, c.still, c._group = sleep
    is_c, other = other_of(touched)
    firsts = slot_of(touched)
    others = np.where(firsts == slot, other, firsts)[~is_c]  # (a collider wakes nothing)
    slots = {int(s) for s in others.tolist()} | {
        b.slot for k in gone for b in k.bodies if b.world is state.world
    }
    _wake_slots(state, slots - {slot})


def _wake_slots(state: WorldState, slots: Iterable[int]) -> None:
    """Wake the bodies in ``slots``, each with its sleeping group (in the slots' order)."""
    store, n = state.store, len(state.bodies)
    assert store is not None
    for s in sorted(slots):
        state.collisions.wake_body(store.row(s), n)


def add_force(
    state: WorldState, force: Force | Callable[..., Any], bodies: Iterable[Body] | None = None
) -> Force:
    """Add a force (a Force, or a callable ``f(t, x, v, mass) -> force``); return it.

    ``bodies``: the bodies it acts on (all of them, now and later, when None). A generator
    that gives a torque (``Force.torque``) turns those of them that turn, in a 2D World only.
    """
    f = as_force(force)
    turning = f.gives_torque
    if turning and state.dim == 1:
        raise TypeError(
            f"{f!r} gives a torque, and this World is 1D (floats): a torque turns a body, and "
            f"bodies turn in a 2D World only (Vectors: a disc, a shape, or a body given a "
            f"moment); add it to a 2D World, or give the 1D World a force instead"
        )
    dim = 2 if turning else f.dim
    if dim is not None:
        state.check_dim(dim, repr(f))
    if state.requested == "exact" and not f.constant:
        raise ValueError(
            f"integrator 'exact' moves bodies by the closed form, which needs constant "
            f"forces, and {f!r} is not constant; use integrator='auto' or an integrator "
            f"such as 'rk4'"
        )
    members: list[Body] | None = None
    if bodies is not None:
        try:
            members = list(bodies)
        except TypeError:
            raise TypeError(
                f"bodies must be an iterable of bodies in this World, or None for all, "
                f"got {type(bodies).__name__} {bodies!r}"
            ) from None
        for b in members:
            if not isinstance(b, Body) or b.world is not state.world:
                raise ValueError(f"bodies must be bodies already added to this World, got {b!r}")
    if dim is not None:
        state.ensure_store(dim)  # checked above; an empty World takes the force's dim
    state.forces.append(AttachedForce(f, members))
    state.changed_structure()
    return f


def remove_force(state: WorldState, force: Force) -> None:
    """Take ``force`` (as ``add_force`` returned it) out of the World: from the next step it
    acts on nothing, and every body wakes (a game that turns its gravity round moves the
    piles asleep, as pymunk's ``space.gravity`` set does)."""
    for k, attached in enumerate(state.forces):
        if attached.force is force:
            del state.forces[k]
            state.changed_structure()
            return
    held = ", ".join(repr(a.force) for a in state.forces) or "none"
    raise ValueError(
        f"{force!r} is not a force of this World (it holds {held}): give the object "
        f"world.add_force returned, or one of world.forces"
    )


def add_link(state: WorldState, link: LinkT) -> LinkT:
    """Add a link (``engine.dynamics.links``: Rod, Cable, Pin; ``engine.dynamics.joints``: Hinge,
    Weld; ``engine.dynamics.constraints``: pymunk's, the soft step's alone) between bodies of this
    World, or a body and a fixed point, and return it. A pinned body is moved to its pin at once
    (its anchor onto the point)."""
    if not isinstance(link, Link):
        raise TypeError(
            f"add_link takes a link (Rod, Cable, Pin), a joint (Hinge, Weld), a spring "
            f"(DampedSpring, DampedRotarySpring), a MouseJoint or a constraint (SlideJoint, "
            f"GrooveJoint, GearJoint, RatchetJoint, RotaryLimitJoint, SimpleMotor), all from "
            f"engine, got "
            f"{type(link).__name__} {link!r}"
        )
    if any(k is link for k in state.links):
        raise ValueError(
            f"that link is already in this World (a link is added only once): {link!r}"
        )
    if link.needs_soft and state.solver == "exact":
        name = type(link).__name__
        why = (
            "solver='auto' chose them at its first step, and keeps them once the World moves"
            if state.solver_asked == "auto"
            else "solver='exact'"
        )
        raise ValueError(
            f"a {name} is a row of the soft step's solver alone, and this World runs the exact "
            f"models ({why}), which do not hold it: make the World with "
            f"World(solver='soft'), or World(solver='auto'), which chooses the soft step when "
            f"the scene holds a {name} at its first step"
        )
    for b in link.bodies:
        if b.world is not state.world:
            raise ValueError(
                f"the link's bodies must be in this World first (world.add(body)): {b!r}"
            )
    if isinstance(link, Pin) and link.holds:
        if any(isinstance(k, Pin) and k.holds and k.body is link.body for k in state.links):
            raise ValueError(
                f"that body is pinned already: a body takes only one Pin (remove_link the "
                f"old one first): {link.body!r}"
            )
        if link.body.kinematic:
            raise ValueError(
                f"a kinematic body is moved by the game and cannot be pinned: {link.body!r}"
            )
    state.links.append(link)
    state.links_changed()
    if isinstance(link, Pin):
        store = state.store
        assert store is not None
        row = store.row(link.body.slot)
        # The body moves so that its anchor is on the point (its centre, for a pin there).
        off = link.end_a() - link.body.pos
        store.x[row] = store.prev_x[row] = tuple(link.point - off)
        if link.holds:
            store.v[row] = 0.0
        state.state_written()
    return link


def remove_link(state: WorldState, link: Link) -> None:
    """Take a link out of the world (a pinned body is free again)."""
    if not any(k is link for k in state.links):
        raise ValueError(f"that link is not in this World: {link!r}")
    state.links = [k for k in state.links if k is not link]
    state.retired.append(link)
    state.links_changed()
    freed(state, list(link.bodies), stacklevel=5)


def add_collider(state: WorldState, collider: ColliderT) -> ColliderT:
    """Add a static collider (``engine.geometry.colliders``) and return it.

    Bodies already inside it are pushed out to its surface, with an OverlapWarning naming
    both. Colliders are 2D: a 1D World refuses them.
    """
    if not isinstance(collider, Collider):
        raise TypeError(
            f"add_collider takes one of engine's colliders (Plane, Segment, Circle, Box, Polygon), "
            f"got {type(collider).__name__} {collider!r}"
        )
    state.check_dim(2, f"the collider {collider!r}", bodies=True)
    if collider in state.colliders:
        raise ValueError(f"that collider is already in this World: {collider!r}")
    store = state.ensure_store(2)
    if state.contacts is None:
        state.contacts = Contacts()
        state.contacts.fast = state.kernels == "fast"
        state.contacts.bodies_added(len(store))
    state.events.settle_reading()
    state.contacts.add(collider)
    collider.held_by(state, True)
    state.events.collider_added(collider)
    if state.game is None or len(state.collisions.asleep) != len(state.bodies):
        state.collisions.wake(len(state.bodies))
    else:
        _wake_near(state, collider)
    push_out(state, range(len(state.bodies)), stacklevel=4)
    state.colliders_changed()
    return collider


def _wake_near(state: WorldState, collider: Collider) -> None:
    """On the soft step, wake the bodies (with their sleeping groups) whose bounding boxes
    come within ``LINEAR_SLOP`` of the box of one of ``collider``'s shapes, and no other: a
    platform put in play wakes what it may touch (a plane, whose box is the world, every
    body), not a pile across the level (a body it overlaps is pushed out, which wakes all)."""
    store = state.store
    assert store is not None
    _, bounds = static_bounds(static_shapes([collider]))
    if not len(bounds) or not len(store):
        return
    r = store.radius[:, None] + LINEAR_SLOP
    x, y = store.x[:, 0:1], store.x[:, 1:2]
    near = (x + r >= bounds[:, 0]) & (x - r <= bounds[:, 2])
    near &= (y + r >= bounds[:, 1]) & (y - r <= bounds[:, 3])
    n = len(state.bodies)
    for row in np.flatnonzero(near.any(axis=1)).tolist():
        state.collisions.wake_body(row, n)


def remove_collider(state: WorldState, collider: Collider) -> None:
    """Take a collider out of the world."""
    if collider not in state.colliders:
        raise ValueError(f"that collider is not in this World: {collider!r}")
    assert state.contacts is not None
    # The collider's open contacts end (reported with the next step); the last step's
    # events, made when read, still name it (engine.dynamics.events).
    touched = state.events.collider_removed(collider, state.t)
    state.contacts.remove(collider)
    collider.held_by(state, False)
    if state.game is None or state.store is None:
        state.collisions.wake(len(state.bodies))
    else:
        # On the soft step, the bodies it touched wake, with their sleeping groups (a crate on
        # a ledge taken out falls), and no other: a coin taken wakes no pile (Box2D and pymunk
        # wake a removed shape's contacts' bodies alone).
        _wake_slots(state, set(slot_of(touched).tolist()))
    state.colliders_changed()
