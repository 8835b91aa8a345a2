"""Contact events: the contacts kept open from step to step, and what began and ended.

The solvers report what they met in a step: impacts (a bounce begins and, unless the body
comes to rest, ends at its exact moment), contacts that came to rest, lift-offs, sensors
entered and left. Taken raw, those reports do not balance: a ball placed on a floor comes
to rest without an impact, so nothing began, yet it ends when thrown; a ball resting on
another rebounds by a hair each step and would begin and end again and again. This module
keeps the contacts that are open between steps (Box2D's contact store, pymunk's arbiters)
and makes the events from them, so that:

* every contact begins once and ends once, in that order: a ``began`` for a key that is
  open already is dropped, as is an ``ended`` for one that is not; a contact the solvers
  hold at rest but that nothing reported is opened (a ball placed on a floor); one that is
  open but no longer touches is closed (a ball teleported away);
* a contact at rest does not chatter: once open, it stays open while the two stay within
  ``CONTACT_SLACK`` of the smaller radius of touching (Box2D keeps a contact while the
  shapes are within a small speculative distance; pymunk keeps an arbiter for three steps),
  and an impact on an open contact is part of it;
* the events of a step come in time order (the exact moments of the impacts; the end of
  the step for what is found only then), ``World.began`` and ``World.ended`` list them;
* a contact of a body or collider taken out of the World ends (``removal`` is True), and
  is reported with the next step's events.

Contacts are keyed by the two things in touch: the body's slot (which never changes while
it is in the World) and the other body's slot, or a collider's serial number, in one int64:
``slot << 32 | other`` with ``other = slot_b`` (the higher slot of two bodies: the body
added first is always ``event.body``) or ``COLLIDER | serial``.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any, NamedTuple

import numpy as np

from .. import kernels
from ..geometry.impact import TOUCH
from ..kernels import stable_order
from ..vector import Vector

__all__ = ["ContactEvent", "ContactLedger", "CONTACT_SLACK", "COLLIDER"]

#: A contact at rest stays open while the gap is at most this fraction of the smaller radius
#: (2%: a pile's rebounds are far smaller; a bounce leaves it within a step or two).
CONTACT_SLACK = 0.02

#: The bit of a key's low word that marks a collider's serial (else another body's slot).
COLLIDER = 1 << 31

_LOW = (1 << 32) - 1

_NONE = np.zeros(0, dtype=np.int64)  # no keys (never written to)


class ContactEvent(NamedTuple):
    """A contact that began, ended or continues: which body and what it touches, where, how
    hard.

    ``body`` is a Body; ``collider`` is a collider, or the other Body for a contact between
    two bodies (then ``body`` is the one added to the World first, in ``World.began`` and
    ``World.ended``; a handler from ``World.on_contact`` on a Body always gets that Body as
    ``body``). ``point`` is on the collider's (or the other body's) surface, ``normal`` the
    unit normal there toward ``body``, ``impulse`` (N s, a Vector) the change of ``body``'s
    momentum through this contact (an impact's at its moment; over the last step for a
    contact that continues; zero where a contact begins or ends without one), ``time`` (s)
    the World time of the event. ``removal`` is True for the end of a contact whose body or
    collider was taken out of the World (pymunk's ``is_removal``).
    """

    body: Any
    collider: Any  # a Collider, or the other Body
    point: Vector
    normal: Vector
    impulse: Vector
    time: float
    removal: bool = False

    def flipped(self) -> ContactEvent:
        """The same contact between two bodies seen from the other one: ``body`` and
        ``collider`` swapped, the normal and the impulse reversed (Newton's third law)."""
        return ContactEvent(
            self.collider,
            self.body,
            self.point,
            -self.normal,
            -self.impulse,
            self.time,
            self.removal,
        )


#: One event before it is made a ContactEvent: (time, key, began?, payload), the payload
#: (point, normal, impulse) as pairs of floats from the solver, or None to be measured from
#: the state.
Spec = tuple[float, int, bool, Any]


def pair_keys(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Keys of contacts between the bodies in slots a and b (either order)."""
    lo, hi = np.minimum(a, b).astype(np.int64), np.maximum(a, b).astype(np.int64)
    return (lo << 32) | hi


def pair_key(a: int, b: int) -> int:
    """``pair_keys`` of one pair of slots, in Python ints (a game's few contacts)."""
    return (min(a, b) << 32) | max(a, b)


def collider_key(slot: int, serial: int) -> int:
    """``collider_keys`` of one body's slot and one collider's serial, in Python ints."""
    return (slot << 32) | (serial | COLLIDER)


def collider_keys(slots: np.ndarray, serials: np.ndarray) -> np.ndarray:
    """Keys of contacts between the bodies in ``slots`` and the colliders ``serials``."""
    return (np.asarray(slots, dtype=np.int64) << 32) | (
        np.asarray(serials, dtype=np.int64) | COLLIDER
    )


def _unique(a: np.ndarray) -> np.ndarray:
    """``np.unique`` of int64 keys by a sort (numpy 2's np.unique hashes first: several times
    slower on a pile's thousands of keys)."""
    s = np.sort(a)
    if len(s) > 1:
        s = s[np.concatenate(([True], s[1:] != s[:-1]))]
    return s


def same_keys(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two 1D arrays of keys hold the same keys in the same order: of one dtype, the
    same bytes (integers are equal exactly when their bits are; a tenth of a microsecond for
    a game's dozen keys, where ``np.array_equal`` takes 1.7)."""
    return a.dtype == b.dtype and a.tobytes() == b.tobytes()


def _isin(a: np.ndarray, sorted_b: np.ndarray) -> np.ndarray:
    """Which entries of a are in the sorted array b."""
    if not len(sorted_b) or not len(a):
        return np.zeros(len(a), dtype=bool)
    pos = np.minimum(np.searchsorted(sorted_b, a), len(sorted_b) - 1)
    return sorted_b[pos] == a


def _merge(
    prev: np.ndarray,
    touched: np.ndarray,
    opened: np.ndarray,
    resting: np.ndarray,
    sensing: np.ndarray,
    exact: np.ndarray,
) -> tuple[np.ndarray, ...]:
    """The keys a step's ledger looks at (sorted, once each: the contacts open before it
    ``prev``, those its reports ``touched``, those held at rest ``resting`` and inside sensors
    ``sensing``; all sorted but ``touched``), and of each: open after the reports (``opened``
    for one touched, else open before), a sensor's (in ``exact``), held now (resting or
    sensing), inside a sensor now."""
    cand = _unique(np.concatenate([prev, touched, resting, sensing]))
    after = _isin(cand, prev)
    if len(touched):
        after[np.searchsorted(cand, touched)] = opened
    sensed = _isin(cand, sensing)
    return cand, after, _isin(cand, exact), _isin(cand, resting) | sensed, sensed


def _sample_merge() -> tuple[object, ...]:
    """The smallest call of ``merge_loop``: one contact open, one reported, one resting."""
    k = np.array([5], dtype=np.int64)
    return k, np.array([7], dtype=np.int64), np.array([True]), k, k[:0], k[:0]


@kernels.loop(sample=_sample_merge)
def merge_loop(
    prev: np.ndarray,
    touched: np.ndarray,
    opened: np.ndarray,
    resting: np.ndarray,
    sensing: np.ndarray,
    exact: np.ndarray,
) -> tuple[np.ndarray, ...]:
    """``_merge`` as one walk over the five sorted lists at once (``touched`` sorted here,
    with its flags): each key once, in order, with its flags as it passes."""
    order = stable_order(touched)
    t_keys, t_open = touched[order], opened[order]
    np_, nt, nr, ns = len(prev), len(t_keys), len(resting), len(sensing)
    total = np_ + nt + nr + ns
    cand = np.empty(total, dtype=np.int64)
    after = np.zeros(total, dtype=np.bool_)
    is_exact = np.zeros(total, dtype=np.bool_)
    final = np.zeros(total, dtype=np.bool_)
    sensed = np.zeros(total, dtype=np.bool_)
    i = j = k = m = e = 0
    count = 0
    while i < np_ or j < nt or k < nr or m < ns:
        # The least key at the head of any list not yet spent.
        key = np.int64(0)
        first = True
        if i < np_:
            key, first = prev[i], False
        if j < nt and (first or t_keys[j] < key):
            key, first = t_keys[j], False
        if k < nr and (first or resting[k] < key):
            key, first = resting[k], False
        if m < ns and (first or sensing[m] < key):
            key = sensing[m]
        was = False
        while i < np_ and prev[i] == key:
            was = True
            i += 1
        # A key reported: open or not after the reports (each once: ``state`` is a dict).
        while j < nt and t_keys[j] == key:
            was = t_open[j]
            j += 1
        held = False
        while k < nr and resting[k] == key:
            held = True
            k += 1
        inside = False
        while m < ns and sensing[m] == key:
            inside = True
            m += 1
        while e < len(exact) and exact[e] < key:
            e += 1
        cand[count] = key
        after[count] = was
        is_exact[count] = e < len(exact) and exact[e] == key
        final[count] = held or inside
        sensed[count] = inside
        count += 1
    return cand[:count], after[:count], is_exact[:count], final[:count], sensed[:count]


def _in_step(raw: list[Spec], t0: float, t_end: float) -> list[Spec]:
    """A step's reports in time order (stable: a bounce begins, then ends), each within the
    step from ``t0`` to ``t_end`` (s; a time the solver summed as t0 + dt may pass the
    World's t by an ulp)."""
    out = [s if t0 <= s[0] <= t_end else (min(max(s[0], t0), t_end), *s[1:]) for s in raw]
    out.sort(key=lambda s: s[0])
    return out


#: The most keys (open before a step and touching after it) whose changes ``settle_open`` finds
#: in Python sets, not numpy's binary searches (a microsecond a call).
_FEW = 256


def _open_changes(
    prev: np.ndarray,
    keys: np.ndarray,
    state: dict[int, bool],
    before: set[int] | None,
    touching: set[int] | None = None,
) -> tuple[list[int], list[int]]:
    """Of a step of ``settle_open``: the keys touching now (``keys``) that were not open after
    the reports, and the keys open before (``prev``) and after the reports that no longer
    touch, each by key. Open after the reports: ``state``'s value for a key a report named,
    else whether it was open before (in ``before``, ``prev`` as a set, where given;
    ``touching``: ``keys`` as a set, where made already)."""
    if before is not None:
        now = keys.tolist()
        if touching is None:
            touching = set(now)
        return (
            [k for k in now if not state.get(k, k in before)],
            [k for k in prev.tolist() if k not in touching and state.get(k, True)],
        )
    after = _isin(keys, prev)
    gone = prev[~_isin(prev, keys)]
    parted = np.ones(len(gone), dtype=bool)
    if state:
        named = np.array(list(state), dtype=np.int64)
        opened = np.array(list(state.values()), dtype=bool)
        for into, flags in ((keys, after), (gone, parted)):
            if len(into):
                at = np.minimum(np.searchsorted(into, named), len(into) - 1)
                hit = into[at] == named
                flags[at[hit]] = opened[hit]
    return keys[~after].tolist(), gone[parted].tolist()


def _open_events(
    t0: float,
    t_end: float,
    raw: Callable[[], list[Spec]] | None,
    prev: np.ndarray,
    keys: np.ndarray,
) -> tuple[list[Spec], list[Spec]]:
    """The began and ended specs of a step of ``ContactLedger.settle_open`` (its doc), from
    the keys open before it (``prev``) to those touching after it (``keys``, sorted), with
    the reports ``raw()`` (None: none) between them."""
    # A game's dozen keys in Python sets; a pile's thousands by binary searches.
    few = len(prev) + len(keys) <= _FEW
    before = set(prev.tolist()) if few else None
    touching_set: set[int] | None = None  # (keys as a set: made where needed)
    state: dict[int, bool] = {}  # open after the reports, of the keys they name
    began: list[Spec] = []
    ended: list[Spec] = []
    specs = [] if raw is None else raw()
    if specs:
        specs = _in_step(specs, t0, t_end)
        named = [s[1] for s in specs]
        if before is not None:
            known = [k in before for k in named]
        else:
            known = _isin(np.array(named, dtype=np.int64), prev).tolist()
        for spec, was_open in zip(specs, known, strict=True):
            k = spec[1]
            s = state.get(k, was_open)
            if spec[2]:
                if not s:
                    state[k] = True
                    began.append(spec)
            elif s:
                state[k] = False
                ended.append(spec)
        opened = [k for k, s in state.items() if s]
        if few:
            touching_set = set(keys.tolist())
            inside = all(k in touching_set for k in opened)
        else:
            inside = bool(_isin(np.array(opened, dtype=np.int64), keys).all())
        # (settle_open's caller's promise: a begin is of a key touching at the step's end.)
        assert inside, "a contact began that does not touch at the step's end"
    opens, parts = _open_changes(prev, keys, state, before, touching_set)
    began += [(t_end, k, True, None) for k in opens]
    ended += [(t_end, k, False, None) for k in parts]
    ended.sort(key=lambda s: s[0])
    return began, ended


class ContactLedger:
    """The contacts open after the last step, and the events that opened and closed them.

    ``settle`` takes a step's raw reports and what the solvers hold at rest now; the World
    hands it ``gaps``, a function from keys to their gaps now and the slack each may keep.
    The keys it looks at are merged by ``_merge`` (numpy) or, on the fast path, by the loop
    kernel ``merge_loop``: a pile keeps thousands open, and the twin's sorts and searches of
    them were most of the ledger's array calls.
    """

    def __init__(self) -> None:
        self.keys = np.zeros(0, dtype=np.int64)  # the open contacts, sorted
        self.exact = np.zeros(0, dtype=np.int64)  # of them, sensors': open exactly while inside
        self._began: list[Spec] = []  # the last step's (``began``), in time order
        self._ended: list[Spec] = []
        # The last step's began and ended lists yet to be made (``settle_open``), or None.
        self._later: Callable[[], tuple[list[Spec], list[Spec]]] | None = None
        self.pending: list[ContactEvent] = []  # ends by removal, for the next step's report
        self.removed: list[ContactEvent] = []  # those reported with the last step
        # Ends the solvers reported for contacts still within their slack: if the contact
        # then parts with nothing else in between, this end, with its moment, is the one.
        self.held: dict[int, Spec] = {}
        #: Merge the keys by the loop kernel ``merge_loop`` (the fast path, engine.kernels).
        self.fast = False
        # The last ``sensing`` as given (its bytes) and sorted (``_sorted``): a game's step
        # most often senses what the step before did.
        self._sensed: tuple[bytes, np.ndarray] = (b"", np.zeros(0, dtype=np.int64))

    @property
    def began(self) -> list[Spec]:
        """The specs of the contacts that began in the last step, in time order."""
        if self._later is not None:
            self._make_later()
        return self._began

    @began.setter
    def began(self, specs: list[Spec]) -> None:
        self._later = None
        self._began = specs

    @property
    def ended(self) -> list[Spec]:
        """The specs of the contacts that ended in the last step, in time order."""
        if self._later is not None:
            self._make_later()
        return self._ended

    @ended.setter
    def ended(self, specs: list[Spec]) -> None:
        self._later = None
        self._ended = specs

    def _make_later(self) -> None:
        """Make the last step's began and ended lists that ``settle_open`` left to be made."""
        later, self._later = self._later, None
        assert later is not None
        self._began, self._ended = later()

    def state(self) -> tuple[Any, ...]:
        """A copy of the open contacts and the ends held for them (what a snapshot holds)."""
        return self.keys.copy(), self.exact.copy(), tuple(self.held.items())

    def set_state(self, state: Any) -> None:
        """Bring back ``state()``; ValueError if it is not one."""
        ok = isinstance(state, tuple) and len(state) == 3
        ok = ok and all(isinstance(a, np.ndarray) and a.dtype == np.int64 for a in state[:2])
        ok = ok and isinstance(state[2], tuple)
        if not ok:
            raise ValueError("snapshot.events must be the open contacts from World.snapshot()")
        self.keys, self.exact = state[0].copy(), state[1].copy()
        self.began, self.ended, self.pending, self.removed = [], [], [], []
        self.held = dict(state[2])

    def _sorted(self, sensing: np.ndarray) -> np.ndarray:
        """``_unique(sensing)`` (int64 keys), taken again only when the keys are not the last
        step's, as given (the result is never written to: it may be the last step's)."""
        keys = np.asarray(sensing, dtype=np.int64)
        raw = keys.tobytes()
        if raw != self._sensed[0]:
            # The soft step's keys come sorted, each once (its report's): checked in a tenth of
            # the time a sort takes (5 us against 47 us for a pile's 3,000 keys).
            ordered = len(keys) < 2 or bool((keys[1:] > keys[:-1]).all())
            self._sensed = (raw, keys.copy() if ordered else _unique(keys))
        return self._sensed[1]

    def _report_removed(self, t0: float) -> None:
        """The ends of things taken out since the step before, reported with the step from
        ``t0`` (s): they happened before it (a time summed another way may pass it by an ulp)."""
        if not self.pending:
            self.removed = []  # (most steps: nothing was taken out)
            return
        self.removed = [e if e.time <= t0 else e._replace(time=t0) for e in self.pending]
        self.pending = []

    def quiet(self) -> None:
        """A step passed in which nothing moved: the pending ends are reported, nothing else."""
        self.removed, self.pending = self.pending, []
        self.began, self.ended = [], []

    def settle(
        self,
        t0: float,
        t_end: float,
        raw: list[Spec],
        resting: np.ndarray,
        sensing: np.ndarray,
        gaps: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    ) -> None:
        """Make the step's events and the open contacts after it.

        ``t0`` and ``t_end``: the step's start and end (s); ``raw``: the solvers' reports
        (time, key, began?, payload), their times kept within the step. ``resting``: the keys of
        the contacts the solvers hold at rest now (a body on a face, a pair in a pile);
        ``sensing``: the keys of bodies inside sensors now. ``gaps(keys)`` gives each key's
        gap (length units, < 0 overlapping) and the slack it may keep and stay open.
        """
        self._report_removed(t0)
        self.began, self.ended = [], []
        prev = self.keys
        if not raw and not len(resting) and not len(sensing) and not len(prev):
            return
        # A quiet step: nothing reported, nothing at rest, no end held, and every open
        # contact a sensor's (exact = prev), the contacts inside sensors now being the open
        # ones (_unique(sensing) = prev). Then exact stays prev, touched is empty, and the
        # merge's cand = prev with after (open before), is_exact, final (held: sensed) and
        # sensed True for each key: need, final & ~after and after & ~final are empty, so
        # nothing is measured, begins or ends, and keys = cand[final] and exact =
        # cand[final & sensed] are prev again. (prev and exact are sorted, each key once;
        # ``sensing`` equal to prev as it comes is so too, and needs no sort.)
        quiet = not raw and not len(resting) and not self.held and same_keys(prev, self.exact)
        if quiet and same_keys(sensing, prev):
            return
        sensing = self._sorted(sensing)
        if quiet and same_keys(sensing, prev):
            return
        resting = _unique(resting)
        exact = _unique(np.concatenate([self.exact, sensing])) if len(sensing) else self.exact
        state: dict[int, bool] = {}
        if raw:
            raw = _in_step(raw, t0, t_end)
            # An end of an open contact at rest that still touches is dropped: the contact
            # goes on (a rebound of a hair in a pile).
            ends = np.array([s[1] for s in raw if not s[2]], dtype=np.int64)
            ends = _unique(ends[_isin(ends, prev) & ~_isin(ends, exact)])
            still: set[int] = set()
            if len(ends):
                gap, slack = gaps(ends)
                still = set(ends[gap <= slack].tolist())
            began, ended = self.began, self.ended
            # Whether each report's contact was open as the step began (one binary search
            # each, not a set of every open contact: a pile holds thousands).
            known = _isin(np.array([s[1] for s in raw], dtype=np.int64), prev).tolist()
            held = self.held
            for spec, was_open in zip(raw, known, strict=True):
                k = spec[1]
                s = state.get(k)
                if s is None:
                    s = was_open
                if spec[2]:
                    held.pop(k, None)  # it touched again: an end held for it is void
                    if not s:
                        state[k] = True
                        began.append(spec)
                elif s and k not in still:
                    state[k] = False
                    ended.append(spec)
                elif s:
                    held[k] = spec  # still within the slack: held, in case it parts
        touched = np.array(list(state), dtype=np.int64)
        opened = np.array(list(state.values()), dtype=bool)
        if self.fast:
            cand, after, is_exact, final, sensed = merge_loop(
                prev, touched, opened, resting, sensing, exact
            )
        else:
            cand, after, is_exact, final, sensed = _merge(
                prev, touched, opened, resting, sensing, exact
            )
        need = after & ~final & ~is_exact
        if need.any():
            gap, slack = gaps(cand[need])
            final[np.flatnonzero(need)[gap <= slack]] = True
        for k in cand[final & ~after].tolist():
            self.began.append((t_end, k, True, None))
        held = self.held
        for k in cand[after & ~final].tolist():
            # Parted past the slack: the end the solver reported as it lifted off, if any.
            self.ended.append(held.pop(k) if k in held else (t_end, k, False, None))
        self.ended.sort(key=lambda s: s[0])
        self.keys = cand[final]
        self.exact = cand[final & sensed]
        if held:
            # Held ends are void for contacts the solvers hold at rest again, or gone.
            keys = np.array(list(held), dtype=np.int64)
            void = _isin(keys, resting) | ~_isin(keys, self.keys)
            for k in keys[void].tolist():
                del held[k]

    def settle_open(
        self,
        t0: float,
        t_end: float,
        raw: Callable[[], list[Spec]] | None,
        touching: np.ndarray,
        gaps: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    ) -> None:
        """``settle`` for a solver whose contacts are open exactly while they touch (the soft
        step, engine.pipeline.game_step: Box2D's and pymunk's rule), with nothing held at rest:
        ``touching``, the keys touching now (and inside sensors), as ``settle``'s ``sensing``;
        ``raw``, a function giving the reports (None: there are none), each begin among them
        of a key in ``touching`` (the soft step's: a contact begins where it touches at the
        step's end).

        Where every open contact is such (``exact`` is ``keys``) and no end is held, ``settle``
        measures no gap and holds no end, so its merge reduces to what is done here: the keys
        open after are ``touching``'s; the reports' begins of contacts not open and ends of
        open ones, in time order; then, by key, a begin for each key touching now and not open
        after the reports, and an end for each open one no longer touching. The same events
        in the same order (tests/test_events_open.py), without the merge of every key: a
        game's contacts change in a tenth of its steps, and there the merge was most of the
        events' cost. Otherwise (a World that switched from the exact solvers) ``settle``.

        The open keys are settled now; the began and ended lists (and ``raw``) are made when
        first read (``began``, ``ended``): from the keys and reports as this step left them, so
        the same lists whenever they are read, and never, where nothing reads them before the
        next step (a pile of a thousand balls, nobody listening: a fifth of its step)."""
        prev = self.keys
        if self.held or not same_keys(prev, self.exact):
            self.settle(t0, t_end, [] if raw is None else raw(), _NONE, touching, gaps)
            return
        self._report_removed(t0)
        if raw is None and same_keys(touching, prev):
            self.began, self.ended = [], []
            return
        keys = self._sorted(touching)
        self.keys = self.exact = keys
        self._later = partial(_open_events, t0, t_end, raw, prev, keys)

    def drop(self, involved: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """Close the open contacts for which ``involved(keys)`` is True (a body or collider
        taken out); return their keys (the caller makes their ends)."""
        gone = involved(self.keys)
        out = self.keys[gone]
        self.keys = self.keys[~gone]
        self.exact = self.exact[~_isin(self.exact, out)]
        for k in out.tolist():
            self.held.pop(k, None)
        return out


def slot_of(keys: np.ndarray) -> np.ndarray:
    """The body slot of each key (the first body of a pair)."""
    return keys >> 32


def other_of(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(whether the other is a collider, its serial or the other body's slot) of each key."""
    low = keys & _LOW
    return (low & COLLIDER) != 0, low & (COLLIDER - 1)


def slack_for(radius: np.ndarray) -> np.ndarray:
    """The gap (length units) a contact at rest may open and stay open, for the smaller
    radius of its two bodies (the body's radius against a collider)."""
    return CONTACT_SLACK * radius + TOUCH * (1.0 + radius)


class WorldEvents:
    """A World's contact events: its ledger, the names of its colliders, and the events of
    the last step made on demand (``World.began``, ``World.ended``, ``World.touching``)."""

    def __init__(self) -> None:
        self.ledger = ContactLedger()
        self._serial: dict[Any, int] = {}  # collider (by identity) -> serial
        self._collider: dict[int, Any] = {}  # serial -> collider
        self._next = 0
        self._began: list[ContactEvent] | None = None
        self._ended: list[ContactEvent] | None = None
        self._touching: list[ContactEvent] | None = None
        # What the last step's events, made on demand, read that taking a collider out
        # changes, kept until the next step (``_hold_reading``): the open contacts' keys, and
        # the colliders taken out by serial.
        self._open: np.ndarray | None = None
        self._gone: dict[int, Any] = {}
        # Bodies taken out since the last step, by slot: (the body, where it was, its
        # radius), for the last step's events made on demand (``body_removed``'s ``lazy``).
        self._gone_bodies: dict[int, tuple[Any, tuple[float, float], float]] = {}
        self._view: Any = None  # how to read the World now (set by the World)
        # The colliders' serials in their order (``serials``): (the list, its edits, the
        # serials given so far, the array).
        self._kept_serials: tuple[Any, int, int, np.ndarray] | None = None

    @property
    def busy(self) -> bool:
        """Whether any contact is open or any end is waiting to be reported."""
        return bool(len(self.ledger.keys) or self.ledger.pending)

    @property
    def view(self) -> Any:
        """How the events read the World now (engine.pipeline.event_dispatch.EventView: bodies by
        slot, their positions in length units, impulses in N s); None until the World sets it."""
        return self._view

    @view.setter
    def view(self, value: Any) -> None:
        self._view = value

    # -- names -------------------------------------------------------------------------------
    def collider_added(self, collider: Any) -> None:
        """Give a new collider its serial number (kept while it is in the World)."""
        self._serial[collider] = self._next
        self._collider[self._next] = collider
        self._next += 1

    def serial(self, collider: Any) -> int:
        """The serial number of a collider in the World."""
        return self._serial[collider]

    def serials(self, colliders: list[Any], edits: int) -> np.ndarray:
        """The serial numbers of ``colliders`` (the World's, in their order) as an int64 array,
        not to be written into: kept while the list is the same and the World's colliders
        unchanged (``edits``: engine.exact.contacts.Contacts.edits, which counts every collider
        added or taken out), where each step's events read them (a Galton board's 120 pegs
        looked up one by one took 6% of its step)."""
        kept = self._kept_serials
        if kept is None or kept[0] is not colliders or kept[1] != edits or kept[2] != self._next:
            serial = self._serial
            out = np.array([serial[c] for c in colliders], dtype=np.int64).reshape(-1)
            out.flags.writeable = False  # (shared by every reader until the colliders change)
            kept = self._kept_serials = (colliders, edits, self._next, out)
        return kept[3]

    def collider_of(self, serial: int) -> Any | None:
        """The collider in the World with serial number ``serial``, or None (taken out)."""
        return self._collider.get(serial)

    def collider_removed(self, collider: Any, t: float) -> np.ndarray:
        """A collider leaves: its open contacts end (reported with the next step); returns
        their keys."""
        serial = self._serial[collider]
        keys = self._collider_ends(serial, t, removal=True)
        del self._serial[collider], self._collider[serial]
        self._gone[serial] = collider  # (named in the last step's events, until the next)
        return keys

    def collider_changed(self, collider: Any, t: float) -> None:
        """A collider became a sensor or solid again: its open contacts end (reported with
        the next step, ``removal`` False), and what it touches then begins afresh."""
        self._collider_ends(self._serial[collider], t, removal=False)

    def _collider_ends(self, serial: int, t: float, removal: bool) -> np.ndarray:
        """The open contacts of the collider numbered ``serial`` end, reported with the next
        step; returns their keys."""
        self._hold_reading()

        def involved(keys: np.ndarray) -> np.ndarray:
            is_c, other = other_of(keys)
            return is_c & (other == serial)

        keys = self.ledger.drop(involved)
        self._removal_ends(keys, t, removal)
        return keys

    def body_removed(self, slot: int, t: float, lazy: bool = False) -> np.ndarray:
        """A body leaves (still readable at its row): its open contacts end; returns their
        keys. ``lazy``: the last step's events are still made on demand, the body as it is now
        kept for them (a World whose events read nothing else of its rows: the soft step's);
        else they are made now, before the rows they name shift."""
        if lazy:
            self._hold_reading()
            view = self._view
            self._gone_bodies[slot] = (view.body(slot), view.position(slot), view.radius(slot))
        else:
            self.settle_reading()

        def involved(keys: np.ndarray) -> np.ndarray:
            is_c, other = other_of(keys)
            return (slot_of(keys) == slot) | (~is_c & (other == slot))

        keys = self.ledger.drop(involved)
        self._removal_ends(keys, t)
        return keys

    def _removal_ends(self, keys: np.ndarray, t: float, removal: bool = True) -> None:
        for k in keys.tolist():
            ev = self._event((t, k, False, None))
            self.ledger.pending.append(ev._replace(impulse=Vector(0.0, 0.0), removal=removal))

    # -- the step ----------------------------------------------------------------------------
    def settle_reading(self) -> None:
        """Make the last step's events now (before the rows or colliders they name change)."""
        _ = self.began, self.ended, self.touching

    def _hold_reading(self) -> None:
        """Keep what the last step's events read that a collider taken out or changed alters
        (the open contacts' keys; ``collider_removed`` keeps the collider's name), so that
        they are made on demand still as the step left them, and not all now (``settle_reading``:
        a game that takes a coin would wait on every contact's event being made)."""
        if self._touching is None and self._open is None:
            self._open = self.ledger.keys

    def forget(self) -> None:
        """The last step's events are made again on demand."""
        self._began = self._ended = self._touching = None
        self._open = None
        self._gone = {}
        self._gone_bodies = {}

    def _event(self, spec: Spec) -> ContactEvent:
        """The ContactEvent of one spec, read from the World now where it has no payload."""
        t, key, _, payload = spec
        slot = key >> 32
        low = key & _LOW
        body = self._body(slot)
        if low & COLLIDER:
            serial = low & (COLLIDER - 1)
            other = self._collider[serial] if serial in self._collider else self._gone[serial]
            if payload is None:
                point, normal, _ = other.closest(self._position(slot))
                return ContactEvent(body, other, point, normal, Vector(0.0, 0.0), t)
        else:
            other = self._body(low)
            if payload is None:
                xa, xb, rb = self._position(slot), self._position(low), self._radius(low)
                d = Vector(xa[0] - xb[0], xa[1] - xb[1])
                dist = d.length()
                normal = d * (1.0 / dist) if dist > 0.0 else Vector(0.0, 1.0)
                point = Vector(*xb) + normal * rb
                return ContactEvent(body, other, point, normal, Vector(0.0, 0.0), t)
        p, n, j = payload
        return ContactEvent(
            body,
            other,
            Vector(float(p[0]), float(p[1])),
            Vector(float(n[0]), float(n[1])),
            Vector(float(j[0]), float(j[1])),
            t,
        )

    def _gone_body(self, slot: int) -> tuple[Any, tuple[float, float], float] | None:
        """The body in ``slot`` as it was when taken out since the last step (``body_removed``'s
        ``lazy``: (it, where it was in length units, its radius)), or None: it is in the World."""
        if not self._gone_bodies:
            return None
        gone = self._gone_bodies.get(slot)
        return gone if gone is not None and self._view.row(slot) < 0 else None

    def _body(self, slot: int) -> Any:
        gone = self._gone_body(slot)
        return self._view.body(slot) if gone is None else gone[0]

    def _position(self, slot: int) -> tuple[float, float]:
        gone = self._gone_body(slot)
        return self._view.position(slot) if gone is None else gone[1]  # type: ignore[no-any-return]

    def _radius(self, slot: int) -> float:
        gone = self._gone_body(slot)
        return self._view.radius(slot) if gone is None else gone[2]  # type: ignore[no-any-return]

    @property
    def began(self) -> list[ContactEvent]:
        """The contacts that began in the last step, in time order."""
        if self._began is None:
            self._began = [self._event(s) for s in self.ledger.began]
        return self._began

    @property
    def ended(self) -> list[ContactEvent]:
        """The contacts that ended in the last step (with those of things taken out since
        the step before), in time order."""
        if self._ended is None:
            made = self.ledger.removed + [self._event(s) for s in self.ledger.ended]
            # In time order, the removals' first where times tie (an end held within its
            # slack and reported once it parted keeps the moment it lifted off).
            self._ended = sorted(made, key=lambda e: e.time)
        return self._ended

    @property
    def touching(self) -> list[ContactEvent]:
        """Every contact open after the last step, with the impulse it carried over it."""
        if self._touching is None:
            view = self._view
            keys = self.ledger.keys if self._open is None else self._open
            impulses = view.impulses(keys) if view is not None else {}
            out = []
            for k in keys.tolist():
                ev = self._event((view.t, k, True, None))
                j = impulses.get(k)
                out.append(ev if j is None else ev._replace(impulse=Vector(*j)))
            self._touching = out
        return self._touching


def raw_specs(
    parts: list[tuple[Any, ...]], began: bool, slots: np.ndarray, serials: np.ndarray | None
) -> list[Spec]:
    """A solver's reports as specs: ``parts`` of (rows, others, points, normals, impulses,
    times) arrays, ``others`` being colliders' places among the World's colliders (turned to
    their ``serials``) or, with ``serials`` None, other bodies' rows (then the normal points
    toward the first body, and points None are measured from the state when read)."""
    out: list[Spec] = []
    for rows, others, points, normals, impulses, times in parts:
        a = slots[np.asarray(rows, dtype=np.intp)]
        if serials is None:
            b = slots[np.asarray(others, dtype=np.intp)]
            keys = pair_keys(a, b)
            flip = a > b  # the normal and impulse are on the first body's side
        else:
            keys = collider_keys(a, serials[np.asarray(others, dtype=np.intp)])
            flip = np.zeros(len(a), dtype=bool)
        pts = None if points is None else np.asarray(points, dtype=float).tolist()
        nrm = np.asarray(normals, dtype=float).tolist()
        imp = np.asarray(impulses, dtype=float).tolist()
        for k, (key, t) in enumerate(zip(keys.tolist(), np.asarray(times).tolist(), strict=True)):
            if pts is None:
                payload = None
            elif flip[k]:
                n, j = nrm[k], imp[k]
                payload = (pts[k], (-n[0], -n[1]), (-j[0], -j[1]))
            else:
                payload = (pts[k], nrm[k], imp[k])
            out.append((float(t), key, began, payload))
    return out


def plain_keys(keys: np.ndarray, row_of: np.ndarray, index_of: dict[int, int]) -> np.ndarray:
    """Keys as (row, other) pairs (N, 2): the body's row and the other body's row, or
    -1 - the collider's place among the World's colliders, so that a snapshot fits a World
    built afresh (other slots and serials, the same bodies and colliders in order)."""
    is_c, other = other_of(keys)
    a = row_of[slot_of(keys)]
    b = np.where(is_c, -1, 0)
    if len(keys):
        b = np.array(
            [
                -1 - index_of[o] if c else int(row_of[o])
                for c, o in zip(is_c.tolist(), other.tolist(), strict=True)
            ],
            dtype=np.int64,
        )
    return np.stack([a.astype(np.int64), b.astype(np.int64)], axis=1).reshape(-1, 2)


def keys_of(plain: np.ndarray, slots: np.ndarray, serials: np.ndarray) -> np.ndarray:
    """``plain_keys`` back to keys, with this World's slots (by row) and serials (by place)."""
    a, b = plain[:, 0], plain[:, 1]
    coll = b < 0
    keys = np.empty(len(plain), dtype=np.int64)
    if coll.any():
        keys[coll] = collider_keys(slots[a[coll]], serials[-1 - b[coll]])
    if (~coll).any():
        keys[~coll] = pair_keys(slots[a[~coll]], slots[b[~coll]])
    return keys
