"""Contact events, the World's side: what the solvers reported in a step made into events
(engine.dynamics.events keeps the ledger), the gap and impulse of each open contact, and the
on_contact handlers called with them after the step.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING, Any

import numpy as np

from ..body import Body
from ..dynamics.events import (
    ContactEvent,
    collider_keys,
    other_of,
    pair_keys,
    raw_specs,
    same_keys,
    slack_for,
    slot_of,
)
from ..exact.contacts import signed_distance
from ..geometry.colliders import Collider
from ..geometry.faces import face_normals
from .body_sensors import sensed

if TYPE_CHECKING:
    from .world_state import WorldState

__all__ = ["EventView", "add_handler", "gaps", "impulses", "report", "settle"]


class EventView:
    """What the events (engine.dynamics.events) read of a World: bodies by slot, where they are now,
    and the impulses its open contacts carried over the last step."""

    def __init__(self, state: WorldState) -> None:
        self.state = state

    @property
    def t(self) -> float:
        """The World's time now (s)."""
        return self.state.t

    def row(self, slot: int) -> int:
        """The row of the body in ``slot``."""
        store = self.state.store
        assert store is not None
        return store.row(slot)

    def body(self, slot: int) -> Body:
        """The body in ``slot``."""
        return self.state.bodies[self.row(slot)]

    def position(self, slot: int) -> tuple[float, float]:
        """Where the body in ``slot`` is now (length units)."""
        store = self.state.store
        assert store is not None
        x = store.x[store.row(slot)]
        return float(x[0]), float(x[1])

    def radius(self, slot: int) -> float:
        """The radius of the body in ``slot`` (length units)."""
        store = self.state.store
        assert store is not None
        return float(store.radius[store.row(slot)])

    def impulses(self, keys: np.ndarray) -> dict[int, tuple[float, float]]:
        """The impulse (N s) each open contact of ``keys`` carried over the last step."""
        return impulses(self.state, keys)


def settle(state: WorldState, t0: float, t_end: float) -> None:
    """Make the last step's events from what the solvers reported (engine.dynamics.events)."""
    store, contacts = state.store, state.contacts
    events = state.events
    events.forget()
    if store is None or store.dim != 2:
        events.ledger.quiet()
        return
    if state.game is not None:
        _settle_soft(state, t0, t_end)
        return
    slots = store.slots()
    raw = []
    resting = sensing = np.zeros(0, dtype=np.int64)
    if contacts is not None:
        serials = events.serials(contacts.colliders, contacts.edits)
        raw += raw_specs(contacts.began_arrays, True, slots, serials)
        raw += raw_specs(contacts.ended_arrays, False, slots, serials)
        on = np.flatnonzero(contacts.rest >= 0)
        if len(on):
            owner = contacts.faces.owner[contacts.rest[on]]
            resting = collider_keys(slots[on], serials[owner])
        if contacts.inside.size:
            rows, s = np.nonzero(contacts.inside)
            sensors = np.array(contacts.sensor_indices, dtype=np.intp)
            sensing = collider_keys(slots[rows], serials[sensors[s]])
    if state.pairs_on:
        pairs = state.collisions
        rows, faces = pairs.face_touching
        if len(rows) and contacts is not None:
            owner = contacts.faces.owner[faces]
            resting = np.concatenate([resting, collider_keys(slots[rows], serials[owner])])
        raw += raw_specs(pairs.began_arrays, True, slots, None)
        raw += raw_specs(pairs.ended_arrays, False, slots, None)
        touching = pairs.touching
        if len(touching):
            n = len(slots)
            resting = np.concatenate(
                [resting, pair_keys(slots[touching // n], slots[touching % n])]
            )
    # What the sensor bodies overlap now (engine.pipeline.body_sensors), kept open as a sensor's is.
    named = serials if contacts is not None else None
    felt = sensed(state, slots, named)
    if len(felt):
        sensing = np.concatenate([sensing, felt])
    events.ledger.settle(t0, t_end, raw, resting, sensing, partial(gaps, state))


def quiet(state: WorldState) -> None:
    """A step in which every body slept: the open contacts stay open, none begins or ends
    (the ends of things taken out before it are reported)."""
    state.events.forget()
    state.events.ledger.quiet()


def _settle_soft(state: WorldState, t0: float, t_end: float) -> None:
    """The events of a step of the soft solver (engine.pipeline.game_step): a contact begins when it
    first touches and ends when it no longer does; each is open exactly while it touches (as
    a sensor's), so no gap is measured."""
    game = state.game
    assert game is not None
    events = state.events
    now, last = game.report, game.last
    # Begins: touching now, not before (with the point, normal and impulse); ends: the other
    # way round (where it last touched, with no impulse); found when the events are read
    # (the ledger's ``settle_open``), from the two reports, which no later step changes.
    raw = None
    # The same report (a step in which everything slept), or the same keys (most steps: the
    # same contacts touch as in the step before): none is new either way, nothing to search.
    if now is not last and not same_keys(now.keys, last.keys):
        raw = partial(_both_changes, now, last, t_end)
    named = game.serials if state.contacts is not None else None  # this step's colliders'
    felt = sensed(state, None, named)
    sensing = now.keys
    if len(now.sensing) or len(felt):
        sensing = np.concatenate([now.keys, now.sensing, felt])
    events.ledger.settle_open(t0, t_end, raw, sensing, partial(gaps, state))


#: The most keys (a report's and the other's) whose changes ``_changes`` finds in a Python set.
_FEW_KEYS = 64


def _both_changes(now: Any, last: Any, t_end: float) -> list[Any]:
    """The specs of the contacts of report ``now`` that began (not in ``last``), then of
    those of ``last`` that ended (not in ``now``), at ``t_end`` (s)."""
    return _changes(now, last.keys, t_end, True) + _changes(last, now.keys, t_end, False)


def _changes(report: Any, other: np.ndarray, t: float, began: bool) -> list[Any]:
    """The specs (engine.dynamics.events) of the contacts of ``report`` (engine.pipeline.game_step)
    whose keys are not among ``other``: begins with their impulses, or ends with none."""
    keys = report.keys
    if len(keys) + len(other) <= _FEW_KEYS:
        # A game's dozen keys: a Python set and lists (a few microseconds, where the numpy
        # calls below take several times that).
        known = set(other.tolist())
        listed = keys.tolist()
        new = [i for i, k in enumerate(listed) if k not in known]
        if not new:
            return []
        points, normals, impulses = report.points, report.normals, report.impulses
        rows = zip(
            [listed[i] for i in new],
            [points[i].tolist() for i in new],
            [normals[i].tolist() for i in new],
            [impulses[i].tolist() for i in new],
            strict=True,
        )
    else:
        if len(other):
            # A binary search each: the reports are sorted by key.
            at = np.minimum(np.searchsorted(other, keys), len(other) - 1)
            picked = np.flatnonzero(other[at] != keys)
        else:
            picked = np.arange(len(keys))
        if not len(picked):
            return []
        rows = zip(
            keys[picked].tolist(),
            report.points[picked].tolist(),
            report.normals[picked].tolist(),
            report.impulses[picked].tolist(),
            strict=True,
        )
    return [(t, k, began, (p, nrm, j if began else (0.0, 0.0))) for k, p, nrm, j in rows]


def gaps(state: WorldState, keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each contact key's gap now (length units, < 0 overlapping) and the slack a contact
    at rest keeps (engine.dynamics.events.CONTACT_SLACK of the smaller radius)."""
    store = state.store
    assert store is not None
    row_of = store.row_of
    a = row_of[slot_of(keys)]
    is_c, other = other_of(keys)
    gap = np.full(len(keys), np.inf)
    r = store.radius[a].copy()
    pair = np.flatnonzero(~is_c)
    if len(pair):
        b = row_of[other[pair]]
        d = store.x[a[pair]] - store.x[b]
        gap[pair] = np.hypot(d[:, 0], d[:, 1]) - r[pair] - store.radius[b]
        r[pair] = np.minimum(r[pair], store.radius[b])
    for serial in np.unique(other[is_c]).tolist():
        sel = np.flatnonzero(is_c & (other == serial))
        collider = state.events.collider_of(serial)
        if collider is not None:
            gap[sel] = signed_distance(collider, store.x[a[sel]]) - r[sel]
    return gap, slack_for(r)


def impulses(state: WorldState, keys: np.ndarray) -> dict[int, tuple[float, float]]:
    """The impulse (N s, on the key's body) each open contact carried over the last step:
    a body at rest on a collider, the change of momentum the static contacts gave it
    (m (v - v_free)); a pile's contacts (with bodies, and with the faces its bodies touch),
    the resting solver's impulses (engine.exact.collisions)."""
    store, contacts = state.store, state.contacts
    out: dict[int, tuple[float, float]] = {}
    if store is None or not len(keys):
        return out
    if state.game is not None:
        report = state.game.report
        asked = set(np.asarray(keys).tolist())
        for k, j in zip(report.keys.tolist(), report.impulses.tolist(), strict=True):
            if k in asked:
                out[k] = (j[0], j[1])
        return out
    row_of = store.row_of
    a = row_of[slot_of(keys)]
    is_c, other = other_of(keys)
    serials = None
    if contacts is not None:
        serials = state.events.serials(contacts.colliders, contacts.edits)
        dv = state.contact_dv
        if dv is not None and len(dv) == len(store):
            for k, row, c, o in zip(
                keys.tolist(), a.tolist(), is_c.tolist(), other.tolist(), strict=True
            ):
                f = int(contacts.rest[row])
                if c and f >= 0 and serials[contacts.faces.owner[f]] == o:
                    j = dv[row] * store.mass[row]
                    out[k] = (float(j[0]), float(j[1]))
    carried = state.collisions.carried if state.pairs_on else None
    if carried is not None and len(carried.keys):
        n = len(store)
        base = carried.base
        lam_keys, lam = carried.keys, carried.lam
        n_faces = base - n
        for k, row, c, o in zip(
            keys.tolist(), a.tolist(), is_c.tolist(), other.tolist(), strict=True
        ):
            if c:
                if contacts is None or serials is None or n_faces <= 0:
                    continue
                # The pile's rows for the faces of this collider that touch this body.
                faces = np.flatnonzero(serials[contacts.faces.owner] == o)
                wanted = row * base + n + faces
            else:
                b = int(row_of[o])
                wanted = np.array([min(row, b) * base + max(row, b)], dtype=np.int64)
            pos = np.minimum(np.searchsorted(lam_keys, wanted), len(lam_keys) - 1)
            hit = lam_keys[pos] == wanted
            if not hit.any():
                continue
            total = np.zeros(2)
            for f_or_b, p in zip(wanted[hit].tolist(), pos[hit].tolist(), strict=True):
                # The solver's normal points toward the key's body (a face's, or from the
                # other body, whose row is the higher); its tangent is (-n_y, n_x).
                if c:
                    assert contacts is not None
                    f = f_or_b - row * base - n
                    nrm = face_normals(contacts.faces, np.array([f]), store.x[[row]])[0][0]
                else:
                    d = store.x[row] - store.x[int(row_of[o])]
                    nrm = d / max(float(np.hypot(d[0], d[1])), 1e-300)
                tang = np.array([-nrm[1], nrm[0]])
                total += nrm * lam[p, 0] + tang * lam[p, 1]
            prev = out.get(k, (0.0, 0.0))
            out[k] = (prev[0] + float(total[0]), prev[1] + float(total[1]))
    return out


def report(state: WorldState) -> None:
    """Call the on_contact handlers with the last step's events."""
    if not state.handlers:
        return
    events = state.events
    ledger = events.ledger
    # Which kinds of handler there are, read again when one is added or taken off (the list
    # grows in place or is made anew: ``add_handler``).
    handlers = state.handlers
    kinds = state.handler_kinds
    if kinds is None or kinds[0] is not handlers or kinds[1] != len(handlers):
        begin, end, post = (any(h[w] is not None for h in handlers) for w in (1, 2, 3))
        kinds = state.handler_kinds = (handlers, len(handlers), (begin, end, post))
    asked = kinds[2]
    # (A kind with no event this step is passed over before the handlers are looked at:
    # most steps of a game begin and end nothing.)
    nothing = (not ledger.began, not ledger.ended and not ledger.removed, False)
    for which in (1, 2, 3):
        if nothing[which - 1] or not asked[which - 1]:
            continue
        event_list = events.began if which == 1 else events.ended if which == 2 else events.touching
        for ev in event_list:
            for handler in state.handlers:
                fn = handler[which]
                if fn is None:
                    continue
                if handler[0] is ev.body:
                    fn(ev)
                elif handler[0] is ev.collider:
                    fn(ev.flipped() if isinstance(ev.collider, Body) else ev)


def add_handler(
    state: WorldState,
    target: Body | Collider,
    begin: Callable[[ContactEvent], Any] | None = None,
    end: Callable[[ContactEvent], Any] | None = None,
    post_solve: Callable[[ContactEvent], Any] | None = None,
) -> Callable[[], None]:
    """Hold an on_contact handler for ``target``; return the function that takes it off."""
    if not isinstance(target, (Body, Collider)):
        raise TypeError(
            f"target must be a Body or a collider, got {type(target).__name__} {target!r}"
        )
    for name, fn in (("begin", begin), ("end", end), ("post_solve", post_solve)):
        if fn is not None and not callable(fn):
            raise TypeError(f"{name} must be a function of one ContactEvent, got {fn!r}")
    entry = (target, begin, end, post_solve)
    state.handlers.append(entry)

    def remove() -> None:
        """Take this handler off (again: nothing happens)."""
        state.handlers = [h for h in state.handlers if h is not entry]

    return remove
