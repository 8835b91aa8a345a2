"""Paths the static contacts bent: a body that bounced off a collider within the step, as its
pieces in time order, for the pairs' broadphase and their impacts (engine.exact.collisions).

The static contacts (engine.exact.contacts) sweep each body's path against the colliders before
the bodies meet one another. A body that bounced there took, within the step, a path of
pieces, one from each bounce to the next; the pairs (engine.exact.pair_impacts) would otherwise
see only the last of them, extended back to the step's start, and a ball that bounced off a
wall into another within the step would pass through it.

**Pieces.** The pairs' impacts take a body on a path that ends at an end state (X, V) after
dt under its pull A (engine.geometry.pair_math ``state_at``),

    x(t) = X - V s + A s^2 / 2,    v(t) = V - A s,    s = dt - t,

so each piece is held as such an end state: the one its own parabola would reach at dt. The
piece that leaves bounce k (at t_k, from the centre c_k, the reported point of contact plus
r n, with velocity u_k) ends at

    X_k = c_k + u_k S + A S^2 / 2,    V_k = u_k + A S,    S = dt - t_k.

The pull is constant within the step, so the velocity is the start one plus what the pull and
the bounces' impulses J_1 ... J_k (momentum, N s) gave:

    u_k = v0 + A t_k + (J_1 + ... + J_k) / m.

The first piece leaves the start (x0, v0) and ends at (x0 + v0 dt + A dt^2 / 2, v0 + A dt);
the last is the contacts' own end state (x1, v1), bit for bit. A body whose path the static
contacts made otherwise (one that slid on a face, rests there at the end, or lifted off one)
is not held here: its path is taken as before, the one that ends at its end state.

**Replaying** (``Replay``). The impacts start each bent body on its first piece and, at each
bounce's moment, in the time order of every impact, put it on the next (a round, as a wall's
bounce is, that counts toward no limit), after which its pairs are searched again from that
moment. Bounces are kept in time order among bodies linked by pairs (engine.exact.pair_order): a
bounce waits for everything before it there, and nothing after it is resolved before it, for
the next piece may meet any of them sooner (a ball bounced off a wall at 0.25 s meets, at
0.34 s, one that a floor bounces only at 0.44 s). An impact with another body before a bounce sends
it off the path: its later bounces are dropped (``Replay.cut``), and so are their reports
(engine.exact.contacts ``Contacts.forget``); the new path's walls are searched by the impacts
themselves.

**Broadphase** (``bent_pairs``). The pairs were found (engine.geometry.pair_grid) around where each
body's free path ends, before the static contacts: a bent body's later pieces may reach
beyond. A piece is a parabola, which strays from the chord of its ends by at most
|A| tau^2 / 8 <= |A| dt^2 / 8 (x(t) - chord(t) = A t (t - tau) / 2), so a bent body's whole
path lies in the box of its pieces' ends grown by that. Each bent body's box, grown by its
radius, is tested against every other body's (``box_pairs``): another bent one's, or the
square around the disc its reach holds (r + reach about where its free path ends). A body a
bent one may strike is searched again with its box grown by what the impact may give it, as
engine.geometry.pair_grid's struck bodies are.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..geometry.pair_grid import GROWTHS, Search, collide, impact_gain, rows_of
from ..geometry.pair_math import isin_sorted, norm, sorted_unique

if TYPE_CHECKING:
    from .pair_bounce import Turns

__all__ = ["Bends", "Replay", "bends_of", "bent_pairs", "bent_rows", "box_pairs", "new_pairs"]


class Bends(NamedTuple):
    """The bodies the static contacts bent in the step and their pieces (module text)."""

    rows: np.ndarray  # (m,) World rows, sorted
    first: np.ndarray  # (m + 1,) body k's bounces are [first[k], first[k + 1])
    t: np.ndarray  # (q,) each bounce's time in the step (s), each body's in order
    X: np.ndarray  # (q, 2) the piece after each bounce: its position at dt (length units)
    V: np.ndarray  # (q, 2) and its velocity at dt (length units / s)
    X0: np.ndarray  # (m, 2) the first piece's position at dt
    V0: np.ndarray  # (m, 2) and its velocity at dt
    lo: np.ndarray  # (m, 2) the low corner of the box of the pieces' ends (length units)
    hi: np.ndarray  # (m, 2) its high corner
    #: (q,) the piece after each bounce: its angular velocity at dt less the contacts' end
    #: one (rad/s; 0 for the last: the bounces after it not taken), and its angle's (rad)
    W: np.ndarray | None = None
    Q: np.ndarray | None = None
    W0: np.ndarray | None = None  # (m,) the first piece's
    Q0: np.ndarray | None = None


def _columns(batches: list[tuple[Any, ...]]) -> list[np.ndarray]:
    """The static contacts' reports (batches of rows, colliders, points, normals, impulses,
    times; arrays or tuples) as six arrays."""
    cols: list[np.ndarray] = []
    for j, kind in enumerate((np.intp, np.intp, float, float, float, float)):
        parts = [np.asarray(batch[j], dtype=kind) for batch in batches]
        if j in (2, 3, 4):
            parts = [p.reshape(-1, 2) for p in parts]
        cols.append(np.concatenate(parts))
    return cols


def bends_of(
    began: list[tuple[Any, ...]],
    ended: list[tuple[Any, ...]],
    x0: np.ndarray,
    v0: np.ndarray,
    x1: np.ndarray,
    v1: np.ndarray,
    A: np.ndarray,
    radius: np.ndarray,
    mass: np.ndarray,
    rest: np.ndarray,
    dt: float,
    t0: float,
    q_turn: np.ndarray | None = None,
) -> Bends | None:
    """The pieces of the bodies that bounced off a collider in the step (module text), from
    the static contacts' reports ``began`` and ``ended``, or None if none did. (x0, v0),
    (x1, v1): the step's start and the contacts' end states, (N, 2); A (N, 2): the pull
    along the path; ``rest`` (N,): each body's resting face after the contacts, or -1; dt,
    t0: the step (s) and the World's time at its start (s); ``q_turn`` (N,): m r^2 / I of
    the discs the bounces' friction turns, 0 for the others (None: none turns)."""
    if not began:
        return None
    rows, _, point, normal, impulse, when = _columns(began)
    if not len(rows):
        return None
    n = len(x0)
    # Every bounce that flies on is reported as begun and ended at once; a settling one
    # (rest) begins only, a lift-off ends only: a body with as many of each that ends free
    # flew from bounce to bounce.
    count = np.bincount(rows, minlength=n)
    if ended:
        count -= np.bincount(_columns(ended)[0], minlength=n)
    ok = (count[rows] == 0) & (rest[rows] < 0)
    if not ok.any():
        return None
    rows, point, normal, impulse, when = rows[ok], point[ok], normal[ok], impulse[ok], when[ok]
    order = np.lexsort((np.arange(len(rows)), when, rows))  # by body, then in time
    rows, point, normal = rows[order], point[order], normal[order]
    impulse, when = impulse[order], when[order]
    start = np.ones(len(rows), dtype=bool)
    start[1:] = rows[1:] != rows[:-1]
    first = np.append(np.flatnonzero(start), len(rows))
    body = rows[first[:-1]]
    group = np.cumsum(start) - 1  # each bounce's body, by place in ``body``
    t = np.clip(when - t0, 0.0, dt)
    c = point + normal * radius[rows, None]
    # u_k = v0 + A t_k + (J_1 + ... + J_k) / m: the bounces' kicks summed within each body,
    # each body's on its own (a sum over all the bodies' bounces less what came before a
    # body's first rounds differently for each other body there: a world filtered apart
    # moved an ulp off its path alone).
    place = np.arange(len(rows)) - first[:-1][group]  # each bounce's place among its body's
    places = int(place.max()) + 1
    kick = np.empty((len(rows), 2))
    acc = np.zeros((len(body), 2))
    for p in range(places):
        k = np.flatnonzero(place == p)
        acc[group[k]] += impulse[k] / mass[rows[k], None]
        kick[k] = acc[group[k]]
    Ar = A[rows]
    u = v0[rows] + Ar * t[:, None] + kick
    S = (dt - t)[:, None]
    X = c + u * S + Ar * (0.5 * S * S)
    V = u + Ar * S
    last = first[1:] - 1
    X[last], V[last] = x1[body], v1[body]
    Ab = A[body]
    X0 = x0[body] + v0[body] * dt + Ab * (0.5 * dt * dt)
    V0 = v0[body] + Ab * dt
    # The box of every piece's two ends, on the paths the impacts take (``state_at``): the
    # first piece from x0 to its place at t_1, each other from t_k to the next bounce or dt.
    s1 = (dt - t[first[:-1]])[:, None]
    ends = [x0[body], X0 - V0 * s1 + Ab * (0.5 * s1 * s1)]
    nxt = np.append(t[1:], dt)
    nxt[last] = dt
    for tt in (t, nxt):
        s = (dt - tt)[:, None]
        at = X - V * s + Ar * (0.5 * s * s)
        ends += [np.minimum.reduceat(at, first[:-1]), np.maximum.reduceat(at, first[:-1])]
    lo = np.minimum.reduce(ends)
    hi = np.maximum.reduce(ends)
    if q_turn is None or not q_turn[body].any():
        return Bends(body, first, t, X, V, X0, V0, lo, hi)
    # The spin: friction at a bounce turns a disc by -du q / r (engine.dynamics.rotation,
    # ``grip``: du its tangential impulse per mass, along t = (-n_y, n_x)), which turns it
    # on by that times the rest of the step. Each piece's spin is the contacts' end one less
    # what the bounces after it gave, so that the last piece's is the contacts' own, bit for
    # bit, and a body an impact sends off a piece before a bounce keeps none of that
    # bounce's turn (as none of its push).
    du = (normal[:, 0] * impulse[:, 1] - normal[:, 1] * impulse[:, 0]) / mass[rows]
    r = radius[rows]
    dw = -du * q_turn[rows] / np.where(r > 0.0, r, 1.0)
    dq = dw * (dt - t)
    # What the bounces after each one gave (summed from its body's last, each body on its
    # own), and what all of a body's gave.
    after_w, after_q = np.empty(len(rows)), np.empty(len(rows))
    sum_w, sum_q = np.zeros(len(body)), np.zeros(len(body))
    for p in range(places - 1, -1, -1):
        k = np.flatnonzero(place == p)
        g = group[k]
        after_w[k], after_q[k] = sum_w[g], sum_q[g]
        sum_w[g] += dw[k]
        sum_q[g] += dq[k]
    W, Q = -after_w, -after_q
    W[last], Q[last] = 0.0, 0.0
    return Bends(body, first, t, X, V, X0, V0, lo, hi, W, Q, -sum_w, -sum_q)


def box_pairs(lo: np.ndarray, hi: np.ndarray, k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (lower, higher) of the bodies k against every other body whose box overlaps
    theirs (boxes lo, hi: (L, 2), length units). The boxes whose left sides lie between the
    widest box's width left of a box k's left side and its right side are those it may
    overlap along x (a sort and two binary searches); they are tested on both axes."""
    order = np.argsort(lo[:, 0], kind="stable")
    left = lo[order, 0]
    width = float((hi[:, 0] - lo[:, 0]).max())
    i0 = np.searchsorted(left, lo[k, 0] - width, "left")
    i1 = np.searchsorted(left, hi[k, 0], "right")
    cnt = i1 - i0
    ka = np.repeat(k, cnt)
    kb = order[np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt - i0, cnt)]
    meet = (ka != kb) & np.all((lo[ka] <= hi[kb]) & (lo[kb] <= hi[ka]), axis=1)
    return np.minimum(ka[meet], kb[meet]), np.maximum(ka[meet], kb[meet])


def _colliding(
    pairs: tuple[np.ndarray, np.ndarray],
    can: Callable[[np.ndarray, np.ndarray], np.ndarray | None] | None,
) -> tuple[np.ndarray, np.ndarray]:
    """The pairs that ``can`` says can collide (all, without it)."""
    ia, ib = pairs
    ok = None if can is None else can(ia, ib)
    return (ia, ib) if ok is None else (ia[ok], ib[ok])


def bent_pairs(
    bends: Bends,
    search: Search,
    A: np.ndarray,
    dt: float,
    w: np.ndarray,
    e: np.ndarray,
    free: np.ndarray,
    can: Callable[[np.ndarray, np.ndarray], np.ndarray | None] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Pairs of places in ``search.live`` (lower, higher, sorted) that a bent path may bring
    within touch (module text, "Broadphase"): each bent body's box against every other
    body's, and those of the bodies it may strike. ``search``: what engine.geometry.pair_grid found
    the pairs with (each live body's free end, radius, velocities, pull, reach); A (N, 2):
    the pulls by World row; w, e, ``free`` (by place in live): inverse masses (0: moved by
    the game), restitutions, and which bodies are no pile's; ``can``: which pairs can
    collide (a mask, None for all; engine.geometry.pair_grid ``collide``): only they pass a
    gain on, as in ``struck_pairs``."""
    P, r, v0, v1, Al, reach, live = search
    where = np.minimum(np.searchsorted(live, bends.rows), len(live) - 1)
    inside = live[where] == bends.rows
    k = where[inside]
    if not len(k):
        return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
    grow = r + reach
    lo, hi = P - grow[:, None], P + grow[:, None]
    # A bent body's box: its pieces' ends, grown by the curvature, a margin (5% of its
    # radius, as reach's) and its radius.
    bend = (norm(A[bends.rows[inside]]) * (0.125 * dt * dt) + 1.05 * r[k])[:, None]
    lo[k], hi[k] = bends.lo[inside] - bend, bends.hi[inside] + bend
    ia, ib = _colliding(box_pairs(lo, hi, k), can)
    # A body a bent one strikes may be sent off faster than its own reach (engine.geometry.pair_grid
    # ``struck_pairs``, whose rule this is): by at most (1 + e) w_b / (w_a + w_b) times the
    # closing speed, which is at most the sum of the two top speeds in the step (a bent
    # path's velocity is no end's), plus what impacts gave either. Such a body's box grows
    # by that gain times dt, and is searched again, three links down, and again where its
    # gain rises past what it grew by (``struck_pairs``' rule, up to GROWTHS times).
    top = np.maximum(norm(v0), norm(v1)) + norm(Al) * dt
    got = np.zeros(len(P))
    times = np.zeros(len(P), dtype=np.intp)  # how often each has grown (``GROWTHS``)
    lo0, hi0 = lo.copy(), hi.copy()
    for _ in range(3 * GROWTHS):
        rel = top[ia] + top[ib] + got[ia] + got[ib]
        gain = impact_gain(ia, ib, rel, w, e, len(P))
        grown = np.flatnonzero(
            ((gain - got) * dt > 0.05 * r) & (gain * dt > 0.05 * r) & (times < GROWTHS) & free
        )
        if not len(grown):
            break
        times[grown] += 1
        got[grown] = gain[grown]
        lo[grown] = lo0[grown] - (gain[grown] * dt)[:, None]
        hi[grown] = hi0[grown] + (gain[grown] * dt)[:, None]
        na, nb = _colliding(box_pairs(lo, hi, grown), can)
        ia, ib = np.concatenate([ia, na]), np.concatenate([ib, nb])
    key = sorted_unique(ia.astype(np.int64) * len(P) + ib)
    return key // len(P), key % len(P)


def bent_rows(
    bends: Bends,
    search: Search,
    A: np.ndarray,
    dt: float,
    store: Any,
    island: np.ndarray,
    has_kin: bool,
    plain: bool,
) -> tuple[np.ndarray, np.ndarray]:
    """World rows (a < b) of the pairs a bent path may bring within touch (``bent_pairs``),
    less those that never collide (engine.geometry.pair_grid ``rows_of``): ``store``, the World's
    bodies; ``island``, the piles' (N,); ``has_kin``, some body is kinematic; ``plain``,
    every live body has the default filter."""
    live = search.live
    w = 1.0 / store.mass[live]
    if has_kin:
        w[store.kinematic[live]] = 0.0  # moved by the game: no impulse moves it
    ia, ib = bent_pairs(
        bends, search, A, dt, w, store.restitution[live], ~island[live],
        lambda ia, ib: collide(live[ia], live[ib], store, has_kin, plain),
    )  # fmt: skip
    return rows_of(ia, ib, live, store, has_kin, plain)


def new_pairs(a: np.ndarray, b: np.ndarray, na: np.ndarray, nb: np.ndarray, n: int) -> np.ndarray:
    """Which of the pairs (na, nb) (World rows, a < b) are not among (a, b): a mask."""
    listed = sorted_unique(a.astype(np.int64) * n + b)
    return ~isin_sorted(na.astype(np.int64) * n + nb, listed)


class Replay:
    """The bent bodies among the impacts' local bodies (World rows U) and the piece each is
    on (module text, "Replaying"); ``t``: when each next leaves its piece (s, in the step;
    inf: on its last, or not bent)."""

    def __init__(self, bends: Bends, U: np.ndarray) -> None:
        self.bends = bends
        nU = len(U)
        where = np.minimum(np.searchsorted(bends.rows, U), len(bends.rows) - 1)
        held = bends.rows[where] == U
        #: Which local bodies are bent.
        self.bent = held
        self._body = np.where(held, where, -1)  # place in bends.rows
        self._next = np.zeros(nU, dtype=np.intp)  # the next bounce, into bends.t
        self._next[held] = bends.first[where[held]]
        self.t = np.full(nU, np.inf)
        self.t[held] = bends.t[self._next[held]]
        self._cut_rows: list[np.ndarray] = []
        self._cut_t: list[np.ndarray] = []
        self._turns: Turns | None = None
        self._omega = self._angle = np.zeros(0)

    def begin(self, X: np.ndarray, V: np.ndarray, turns: Turns | None = None) -> None:
        """Put the bent bodies on their first pieces, in place on the end states (X, V) and
        on the spins ``turns`` (engine.exact.pair_bounce; None: nothing turns)."""
        i = np.flatnonzero(self.bent)
        X[i], V[i] = self.bends.X0[self._body[i]], self.bends.V0[self._body[i]]
        self._turns = None
        b = self.bends
        if turns is None or b.W0 is None or b.Q0 is None:
            return
        self._turns = turns
        self._omega = turns.omega.copy()  # the contacts' end spins
        self._angle = turns.angle.copy()
        self._put(i, b.W0[self._body[i]], b.Q0[self._body[i]])

    def _spin(self, i: np.ndarray, q: np.ndarray) -> None:
        """Bodies i's spins, on the pieces after bounces q."""
        b = self.bends
        if self._turns is not None and b.W is not None and b.Q is not None:
            self._put(i, b.W[q], b.Q[q])

    def _put(self, i: np.ndarray, w: np.ndarray, q: np.ndarray) -> None:
        """Bodies i's spins the contacts' end ones plus (w, q) (where 0: theirs, bit for bit)."""
        turns = self._turns
        assert turns is not None
        turns.omega[i] = np.where(w != 0.0, self._omega[i] + w, self._omega[i])
        turns.angle[i] = np.where(q != 0.0, self._angle[i] + q, self._angle[i])

    def advance(self, i: np.ndarray, X: np.ndarray, V: np.ndarray) -> np.ndarray:
        """Put bodies i on the pieces after their next bounces (in place on X, V): the
        bounces' times (s, in the step), when the new pieces start."""
        q = self._next[i]
        X[i], V[i] = self.bends.X[q], self.bends.V[q]
        self._spin(i, q)
        when = self.t[i].copy()
        q = q + 1
        more = q < self.bends.first[self._body[i] + 1]
        self._next[i] = q
        self.t[i] = np.where(more, self.bends.t[np.where(more, q, 0)], np.inf)
        return when

    def finish(self, X: np.ndarray, V: np.ndarray, ts: np.ndarray) -> np.ndarray:
        """Put every body with bounces left on its last piece (in place on X, V, and on ts,
        when each body's piece starts); the bodies moved."""
        i = np.flatnonzero(np.isfinite(self.t))
        if len(i):
            q = self.bends.first[self._body[i] + 1] - 1
            X[i], V[i], ts[i] = self.bends.X[q], self.bends.V[q], self.bends.t[q]
            self._spin(i, q)
            self.t[i] = np.inf
        return i

    def cut(self, i: np.ndarray, t: np.ndarray, w: np.ndarray) -> None:
        """An impact at times t (s, in the step) sent bodies i off their pieces: the bounces
        they had left are dropped (a body no impulse moves, w = 0, keeps its path)."""
        off = np.isfinite(self.t[i]) & (w[i] > 0.0)
        if off.any():
            self._cut_rows.append(i[off])
            self._cut_t.append(t[off])
            self.t[i[off]] = np.inf

    @property
    def cuts(self) -> tuple[np.ndarray, np.ndarray]:
        """(local bodies, times in the step) of the bodies sent off before a bounce."""
        if not self._cut_rows:
            return np.zeros(0, dtype=np.intp), np.zeros(0)
        return np.concatenate(self._cut_rows), np.concatenate(self._cut_t)
