"""Snapshots: every bit of a World's state at one moment, and bringing it back.

``World.snapshot()`` copies the state (positions, velocities, time, the closed form's anchor,
the contacts' and links' state, the open contact events, and the bodies' and colliders'
materials and the bodies' bullet flags, which can be set at any time:
engine.pipeline.snapshot_materials) into a WorldSnapshot;
``World.restore(snapshot)`` puts it back, bit for bit, into the World it was taken from or
one built afresh with the same bodies, colliders and links in the same order. A snapshot is a
plain dataclass, so one can be built or altered by hand: restore checks every field first and
refuses, changing nothing, what would put nan, inf, a wrong shape or a negative count into the
World.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from numbers import Real
from typing import TYPE_CHECKING, Any

import numpy as np

from ..body import Body
from ..body_values import State, coerce_mass, coerce_state
from ..checks import seconds
from ..dynamics.events import ContactEvent, keys_of, plain_keys
from ..dynamics.joints import KINDS, apply_settings, check_settings, geometry, rebuild, settings
from ..dynamics.links import Link
from ..vector import Vector
from . import snapshot_materials

if TYPE_CHECKING:
    from .world_state import WorldState

__all__ = ["WorldSnapshot", "take", "restore"]


def _copy(array: Any) -> Any:
    return None if array is None else array.copy()


@dataclass(frozen=True)
class WorldSnapshot:
    """Every bit of a World's state at one moment; hand it to ``World.restore``."""

    n_bodies: int
    x: Any
    v: Any
    prev_x: Any
    masses: tuple[float, ...]
    own_acc: tuple[State, ...]
    t_base: float
    dt: float | None
    n_since_base: int
    steps: int
    anchor: tuple[Any, Any, float] | None
    warned: frozenset[Any] = field(default_factory=frozenset)
    contacts: tuple[Any, ...] | None = None  # which bodies rest on what, sensors overlapped
    pairs: tuple[Any, ...] | None = None  # contacts between bodies: warm start, sleep
    #: Each link or joint in force: (what it joins, warned, last impulse, its settings).
    links: tuple[Any, ...] = ()
    moves: tuple[Any, ...] = ()  # (row, target): kinematic bodies' pos written, not yet reached
    turns: tuple[Any, ...] = ()  # (row, angle): kinematic bodies' angle written, likewise
    events: tuple[Any, ...] | None = (
        None  # the contacts open (engine.dynamics.events), by row and place
    )
    #: Rotation by row: (angle, angular velocity, moment, torque) arrays (engine.dynamics.rotation).
    spin: tuple[Any, ...] | None = None
    #: Each body's (restitution, friction, filter); None: left as they are
    #: (engine.pipeline.snapshot_materials).
    materials: tuple[Any, ...] | None = None
    #: Each collider's (restitution, friction, sensor, filter); None: left as they are.
    collider_materials: tuple[Any, ...] | None = None
    #: The soft step's warm starts and last contacts (engine.pipeline.game_step); None: not soft.
    game: tuple[Any, ...] | None = None
    #: Each body's ``bullet`` flag; None: left as they are (engine.pipeline.snapshot_materials).
    bullets: tuple[bool, ...] | None = None


def take(state: WorldState) -> WorldSnapshot:
    """Everything needed to bring this world back to this moment, bit for bit."""
    anchor = None
    if state.anchor is not None:
        anchor = (state.anchor[0].copy(), state.anchor[1].copy(), state.anchor[2])
    store = state.store
    empty = store is None or not state.bodies
    for k in state.links:
        if type(k).__name__ not in KINDS:
            # (engine.dynamics.constraints: a snapshot could not bring them back; said now, not at
            # the restore, when the game would have lost the moment it meant to keep.)
            raise ValueError(
                f"World.snapshot() does not take a {type(k).__name__} yet (it keeps "
                f"{', '.join(KINDS)}, springs and mouse joints): remove it for the snapshot "
                f"and add it again after, or copy the World with world.copy()"
            )
    return WorldSnapshot(
        n_bodies=len(state.bodies),
        x=None if empty else _copy(store.x),  # type: ignore[union-attr]
        v=None if empty else _copy(store.v),  # type: ignore[union-attr]
        prev_x=None if empty else _copy(store.prev_x),  # type: ignore[union-attr]
        masses=tuple(b.mass for b in state.bodies),
        own_acc=tuple(b.own_acc for b in state.bodies),
        t_base=state.t_base,
        dt=state.dt,
        n_since_base=state.n,
        steps=state.steps,
        anchor=anchor,
        warned=frozenset(state.policy.warned),
        contacts=None if state.contacts is None else state.contacts.state(),
        pairs=state.collisions.state(),
        events=_events_state(state),
        links=tuple((_describe(state, k), k.warned, k.impulse, settings(k)) for k in state.links),
        spin=None
        if empty
        else tuple(
            a.copy()
            for a in (store.angle, store.omega, store.moment, store.torque)  # type: ignore[union-attr]
        ),
        moves=tuple(
            (state.bodies.index(b), tuple(float(c) for c in target))
            for b, target in state.targets.items()
        ),
        turns=tuple((state.bodies.index(b), float(a)) for b, a in state.turn_targets.items()),
        materials=snapshot_materials.take_bodies(state),
        collider_materials=snapshot_materials.take_colliders(state),
        game=_game_state(state),
        bullets=snapshot_materials.take_bullets(state),
    )


def _game_state(state: WorldState) -> tuple[Any, ...] | None:
    """The soft step's state (engine.pipeline.game_step), its event keys plain (by row and
    place)."""
    store = state.store
    if state.game is None or store is None:
        return None
    index_of = {state.events.serial(c): k for k, c in enumerate(state.colliders)}
    row_of = store.row_of

    def plain(keys: np.ndarray) -> np.ndarray:
        return plain_keys(keys, row_of, index_of)

    return state.game.state(state.links, plain)


def restore(state: WorldState, snapshot: WorldSnapshot) -> None:
    """Bring back the state saved by ``snapshot()`` (same bodies, in the same order)."""
    if not isinstance(snapshot, WorldSnapshot):
        raise TypeError(
            f"restore takes a WorldSnapshot from World.snapshot(), got {type(snapshot).__name__}"
        )
    if snapshot.n_bodies != len(state.bodies):
        raise ValueError(
            f"the snapshot holds {snapshot.n_bodies} bodies but this World has "
            f"{len(state.bodies)}: restore into the world (or a copy) it was taken from"
        )
    masses, own_acc = _check_snapshot(state, snapshot)
    links = _check_links(state, snapshot.links)
    moves = _check_moves(state, snapshot.moves)
    turns = _check_turns(state, snapshot.turns)
    materials, collider_materials = snapshot_materials.check(
        state, snapshot.materials, snapshot.collider_materials
    )
    bullets = snapshot_materials.check_bullets(state, snapshot.bullets)
    # The colliders' materials first: which are sensors says what contact state fits.
    undo = None
    if collider_materials is not None:
        undo = snapshot_materials.set_colliders(state, collider_materials)
    if state.contacts is not None and snapshot.contacts is not None:
        try:
            state.contacts.check_state(snapshot.contacts, len(state.bodies))
        except ValueError:
            if undo is not None:
                snapshot_materials.set_colliders(state, undo)
            raise
    if materials is not None:
        snapshot_materials.set_bodies(state, materials)
    if bullets is not None:
        snapshot_materials.set_bullets(state, bullets)
    store = state.store
    if store is not None and state.bodies:
        store.x, store.v, store.prev_x = (
            _copy(snapshot.x),
            _copy(snapshot.v),
            _copy(snapshot.prev_x),
        )
        store.mass = np.array(masses, dtype=float)
        store.own = np.array(own_acc, dtype=float).reshape(store.x.shape)
        if snapshot.spin is not None:
            store.angle, store.omega, store.moment, store.torque = (a.copy() for a in snapshot.spin)
            store.set_moments(store.moment)
    state.t_base = float(snapshot.t_base)
    state.dt = None if snapshot.dt is None else float(snapshot.dt)
    state.void_budget()
    state.n = snapshot.n_since_base
    state.steps_base = snapshot.steps - snapshot.n_since_base
    chosen = _links_of(state, [d for d, _, _, _ in links])
    if [id(k) for k in chosen] != [id(k) for k in state.links]:
        state.links = chosen
        state.links_changed()
    for k, (_, warned, impulse, values) in zip(chosen, links, strict=True):
        k.warned, k.impulse = warned, impulse
        apply_settings(k, values)
    state.targets = {state.bodies[row]: target for row, target in moves}
    state.turn_targets = {state.bodies[row]: angle for row, angle in turns}
    state.changed_structure()
    if snapshot.anchor is not None:
        x0, v0, ta = snapshot.anchor
        state.anchor = (x0.copy(), v0.copy(), ta)
    state.policy.warned = set(snapshot.warned)
    if state.contacts is not None:
        if snapshot.contacts is None:
            state.contacts.rest[:] = -1
            state.contacts.inside[:] = False
        else:
            state.contacts.set_state(snapshot.contacts, len(state.bodies))
    if snapshot.pairs is not None:
        state.collisions.set_state(snapshot.pairs)
    _set_events_state(state, snapshot.events)
    store = state.store
    if snapshot.game is not None and state.game is None and state.solver == "auto":
        # Taken of a World that chose the soft step, restored into one that has not chosen
        # yet (made afresh, not stepped): it chooses now, so that the warm starts and open
        # contacts come back with the bodies (a saved game resumed in a new process).
        state.settle_solver()
    if state.game is not None and snapshot.game is not None and store is not None:
        slots = store.slots()
        serials = np.array([state.events.serial(c) for c in state.colliders], np.int64)

        def back(plain: np.ndarray) -> np.ndarray:
            return keys_of(plain, slots, serials.reshape(-1))

        state.game.set_state(snapshot.game, state.links, back)
    elif state.game is not None:
        # Taken before the soft step's first step (World(solver="auto") chooses it then): the
        # step replayed from it starts, as the first did, with nothing kept.
        state.game.forget()


def _events_state(state: WorldState) -> tuple[Any, ...] | None:
    """The open contacts and their held ends, by body row and collider place."""
    store = state.store
    if store is None or store.dim != 2:
        return None
    index_of = {state.events.serial(c): k for k, c in enumerate(state.colliders)}
    keys, exact, held = state.events.ledger.state()
    row_of = store.row_of

    def plain(k: np.ndarray) -> np.ndarray:
        return plain_keys(k, row_of, index_of)

    held_plain = tuple(
        (tuple(plain(np.array([k], dtype=np.int64))[0].tolist()), spec[0], spec[3])
        for k, spec in held
    )
    # The ends of things taken out, waiting for the next step's report, as they are.
    return plain(keys), plain(exact), held_plain, tuple(state.events.ledger.pending)


def _set_events_state(state: WorldState, saved: Any) -> None:
    """Bring back ``_events_state()`` (None: no contact open)."""
    store = state.store
    ledger = state.events.ledger
    if saved is None or store is None:
        ledger.set_state((np.zeros(0, np.int64), np.zeros(0, np.int64), ()))
        return
    n, m = len(store), len(state.colliders)
    ok = isinstance(saved, tuple) and len(saved) == 4
    ok = ok and all(isinstance(e, ContactEvent) for e in saved[3])
    if ok:
        arrays = [a for a in saved[:2] if isinstance(a, np.ndarray)]
        ok = len(arrays) == 2 and all(a.ndim == 2 and a.shape[1:] == (2,) for a in arrays)
        ok = ok and all(
            ((a[:, 0] >= 0) & (a[:, 0] < n) & (a[:, 1] >= -m) & (a[:, 1] < n)).all() for a in arrays
        )
    if not ok:
        raise ValueError(
            "snapshot.events must be the open contacts from World.snapshot() of a World "
            "with these bodies and colliders"
        )
    slots = store.slots()
    serials = np.array([state.events.serial(c) for c in state.colliders], np.int64)
    serials = serials.reshape(-1)
    held = []
    for (a, b), t, payload in saved[2]:
        (k,) = keys_of(np.array([[a, b]], dtype=np.int64), slots, serials).tolist()
        held.append((k, (t, k, False, payload)))
    ledger.set_state(
        (
            np.sort(keys_of(saved[0], slots, serials)),
            np.sort(keys_of(saved[1], slots, serials)),
            tuple(held),
        )
    )
    ledger.pending = list(saved[3])
    state.events.forget()


def _check_moves(state: WorldState, moves: Any) -> list[tuple[int, tuple[float, float]]]:
    """The snapshot's pending kinematic moves, checked: (row of a kinematic body, a
    finite point)."""
    if not isinstance(moves, tuple):
        raise TypeError("snapshot.moves must be a tuple of (row, point) from World.snapshot")
    out = []
    for item in moves:
        ok = isinstance(item, tuple) and len(item) == 2 and isinstance(item[0], int)
        ok = ok and 0 <= item[0] < len(state.bodies) and state.bodies[item[0]].kinematic
        # (Only a body kinematic by itself has moves: a pinned one refuses them.)
        if ok:
            try:
                point = Vector.coerce(item[1], "snapshot.moves")
            except (TypeError, ValueError):
                ok = False
            else:
                ok = point.is_finite()
        if not ok:
            raise ValueError(
                f"snapshot.moves holds (row of a kinematic body, finite point) pairs, got {item!r}"
            )
        out.append((item[0], (float(point[0]), float(point[1]))))
    return out


def _check_turns(state: WorldState, turns: Any) -> list[tuple[int, float]]:
    """The snapshot's pending kinematic turns, checked: (row of a kinematic body, a finite
    angle in rad)."""
    if not isinstance(turns, tuple):
        raise TypeError("snapshot.turns must be a tuple of (row, angle) from World.snapshot")
    out = []
    for item in turns:
        ok = isinstance(item, tuple) and len(item) == 2 and isinstance(item[0], int)
        ok = ok and 0 <= item[0] < len(state.bodies) and state.bodies[item[0]].kinematic
        ok = ok and isinstance(item[1], float) and math.isfinite(item[1])
        if not ok:
            raise ValueError(
                f"snapshot.turns holds (row of a kinematic body, finite angle) pairs, got {item!r}"
            )
        out.append((item[0], item[1]))
    return out


def _describe(state: WorldState, link: Link) -> tuple[Any, ...]:
    """What a link joins, in plain numbers: (kind, body row, other row or -1, fixed point
    or None, length, restitution, geometry: engine.dynamics.joints). A snapshot holds this, not the
    link, so that it can be restored into a World built afresh (its own bodies and links)."""
    store = state.store
    assert store is not None
    other = link.other
    return (
        type(link).__name__,
        store.row(link.body.slot),
        store.row(other.slot) if isinstance(other, Body) else -1,
        None if isinstance(other, Body) else (float(other[0]), float(other[1])),
        link.length,
        link.restitution,
        geometry(link),
    )


def _identity(description: tuple[Any, ...]) -> tuple[Any, ...]:
    """A link's description less what a game may set on it since it was made (a rod's or
    cable's length and anchors, a joint's collide: the snapshot's settings put them back), so
    that a link set since is still the one the snapshot saved."""
    kind, row, other_row, point, length, e, shape = description
    if kind in ("Rod", "Cable"):
        return (kind, row, other_row, point, e)
    return (kind, row, other_row, point, length, e, shape[:-1])


def _links_of(state: WorldState, descriptions: list[tuple[Any, ...]]) -> list[Link]:
    """Links matching ``descriptions``: this World's own where one matches (in force now,
    or taken out since), else new ones."""
    known = state.links + [
        k for k in state.retired if all(b.world is state.world for b in k.bodies)
    ]
    mine = [(_identity(_describe(state, k)), k) for k in known]
    out: list[Link] = []
    for d in descriptions:
        key = _identity(d)
        match = next((k for dk, k in mine if dk == key and all(k is not o for o in out)), None)
        if match is None:
            kind, row, other_row, point, length, e, shape = d
            other: Any = state.bodies[other_row] if other_row >= 0 else point
            match = rebuild(kind, state.bodies[row], other, length, e, shape)
        out.append(match)
    return out


def _check_links(
    state: WorldState, links: Any
) -> list[tuple[tuple[Any, ...], bool, float, tuple[Any, ...]]]:
    """The snapshot's links, checked: ((kind, row, other row, point, length, e, geometry),
    warned, impulse, settings) each, joining bodies of this World."""
    if not isinstance(links, tuple):
        raise TypeError("snapshot.links must be a tuple from World.snapshot")
    n = len(state.bodies)
    out = []
    for item in links:
        ok = isinstance(item, tuple) and len(item) == 4 and isinstance(item[0], tuple)
        ok = ok and len(item[0]) == 7 and isinstance(item[1], bool)
        ok = ok and isinstance(item[2], float) and math.isfinite(item[2])
        if ok:
            kind, row, other_row, point, length, e, shape = item[0]
            ok = kind in KINDS and type(row) is int and 0 <= row < n
            ok = ok and type(other_row) is int and -1 <= other_row < n and other_row != row
            ok = ok and (other_row >= 0) == (point is None)
            if ok and point is not None:
                ok = _floats(point, 2)
            ok = ok and isinstance(length, float) and math.isfinite(length) and length >= 0.0
            ok = ok and isinstance(e, float) and 0.0 <= e <= 1.0
            ok = ok and (length > 0.0) == (kind in ("Rod", "Cable"))
            ok = ok and check_settings(kind, item[3]) and _geometry_ok(shape)
        if not ok:
            raise ValueError(
                f"snapshot.links holds ((kind, row, other row, point, length, restitution, "
                f"geometry), warned, impulse, settings) for links between this World's "
                f"bodies, got {item!r}"
            )
        out.append((item[0], item[1], item[2], item[3]))
    return out


def _floats(value: Any, size: int) -> bool:
    """Whether ``value`` is a tuple of ``size`` finite floats."""
    return (
        isinstance(value, tuple)
        and len(value) == size
        and all(isinstance(c, float) and math.isfinite(c) for c in value)
    )


def _geometry_ok(shape: Any) -> bool:
    """Whether ``shape`` is a link's geometry (engine.dynamics.joints): five finite floats, a hertz
    (None or > 0), a damping ratio >= 0 and a bool."""
    if not (isinstance(shape, tuple) and len(shape) == 8 and _floats(shape[:5], 5)):
        return False
    hz, zeta, collide = shape[5:]
    ok = hz is None or (isinstance(hz, float) and math.isfinite(hz) and hz > 0.0)
    return ok and _floats((zeta,), 1) and zeta >= 0.0 and isinstance(collide, bool)


def _check_snapshot(state: WorldState, snap: WorldSnapshot) -> tuple[list[float], list[State]]:
    """Refuse a snapshot (a plain dataclass, so one can be built or altered by hand) that
    would put nan, inf, a wrong shape or a negative count into this World; return its
    masses and own accelerations, checked."""
    n, dim = len(state.bodies), state.dim or 1
    shape = (n,) if dim == 1 else (n, 2)
    for name in ("x", "v", "prev_x"):
        value = getattr(snap, name)
        if n == 0 and value is None:
            continue
        if not (isinstance(value, np.ndarray) and value.shape == shape):
            raise ValueError(
                f"snapshot.{name} must be an array of shape {shape} from World.snapshot(), "
                f"got {value!r}"
            )
        if not np.isfinite(value).all():
            raise ValueError(f"snapshot.{name} must be finite (no nan or inf), got {value!r}")
    if not (isinstance(snap.masses, tuple) and isinstance(snap.own_acc, tuple)):
        raise TypeError("snapshot.masses and snapshot.own_acc must be tuples, one per body")
    if len(snap.masses) != n or len(snap.own_acc) != n:
        raise ValueError(f"snapshot.masses and snapshot.own_acc must hold {n} values each")
    try:
        masses = [coerce_mass(m) for m in snap.masses]
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"snapshot.masses: {exc}") from None
    own_acc = [coerce_state(a, dim, "snapshot.own_acc") for a in snap.own_acc]
    if snap.dt is not None:
        seconds(snap.dt, "dt")
    t = snap.t_base
    try:
        t_ok = not isinstance(t, bool) and isinstance(t, Real) and 0.0 <= float(t) < 1e300
    except OverflowError:  # an int beyond the float range
        t_ok = False
    if not t_ok:
        raise ValueError(f"snapshot.t_base must be a finite time >= 0 s, got {t!r}")
    for name in ("n_since_base", "steps"):
        count = getattr(snap, name)
        if isinstance(count, bool) or not isinstance(count, int) or count < 0:
            raise ValueError(f"snapshot.{name} must be a whole number >= 0, got {count!r}")
    try:  # the time it stands for, t_base + n_since_base * dt, must be a float too
        t_now = float(t) + snap.n_since_base * (0.0 if snap.dt is None else float(snap.dt))
    except OverflowError:
        t_now = math.inf
    if not t_now < 1e300:
        raise ValueError(
            "snapshot.t_base + snapshot.n_since_base * snapshot.dt must be a finite time, "
            f"got {snap.t_base!r} + {snap.n_since_base!r} * {snap.dt!r}"
        )
    return masses, own_acc
