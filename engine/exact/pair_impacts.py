"""Impacts between bodies at their exact moments, in time order, within one step.

The pairs that are no pile's (engine.exact.collisions, ``plan``) meet at their exact moments. Within
the step a body's centre is taken on the path that ends at its end state (x1, v1),

    x(t) = x1 - v1 s + A s^2 / 2,    v(t) = v1 - A s,    s = dt - t,

the exact parabola under the closed form (``state_at``). Two balls touch when the distance of
their centres is R = r_a + r_b; along the paths, the difference d(t) = x_a(t) - x_b(t) is
itself a parabola, so the moment of impact is the first root of |d(t)|^2 = R^2
(``times_of_impact``, with ``engine.geometry.impact.disc_hits``: a quadratic when both share one
acceleration, as under gravity). At that moment, with the unit normal n = d / R toward a and
the closing speed u = -(v_a - v_b).n > 0, the impulse along n is

    J = (1 + e) u / (1/m_a + 1/m_b),        e = e_a e_b (pymunk's product rule),

which conserves momentum exactly and, with e = 1, energy: it is the closed-form 2D collision
of two discs (``bounce``, engine.exact.pair_bounce). Coulomb friction (mu = mu_a mu_b) takes up to
mu J of the tangential relative momentum, never reversing it; for discs that turn it acts at
the point of contact, on the slip there, and turns them (engine.exact.pair_bounce). Each velocity
changes by dv = P / m, and the position at the end of the step by dv (dt - t): the rest of the
step is flown on the new path (and turned on the new spin). A body sent off by an impact may
meet a wall on its new path within the step (``wall_hits``); that impact takes its place in
the time order too, and bounces as the static contacts do (``wall_bounce``, with their rule
for a disc that turns).

**Rounds** (``impacts_in_order``). In each, every pair that is the earliest impact of both its
bodies is resolved (they share no body), unless an earlier one of the round has a body paired
with one of its bodies (whose new path may meet it first), then the paths of the bodies that
changed are searched again; a wall's bounce waits for everything before it among the bodies
linked to its body by pairs, and no pair after it there goes first (engine.exact.pair_order
says which moments a round takes). Newton's cradle is the test: the first ball stops, the
second takes its speed at the same instant and meets the third, and so on down the row; a
solver that spreads one impulse over the row (plain Jacobi) fails it. A group's rounds (the
bodies linked by the pairs that can meet in the step; rounds counted group by group, so two
worlds filtered apart share none) stop after ``MAX_ROUNDS`` (a light ball squeezed between
heavy ones bounces about pi sqrt(M/m) times);
then each body with an impact still to come stops where its path is at the earliest one left
among the bodies those impacts link it to (its velocity the step's end one, so momentum
changes by the forces' impulse alone; bodies that never meet them, a world filtered apart,
move as if they were not there), and so does every body whose path runs into a stopped one,
and goes on from there next step: bodies never fly through each other for want of rounds,
at the cost of the rest of that step's motion for those bodies. Pairs still closing there
with restitution up to ``COLLAPSE_E`` are an inelastic collapse (impacts without end, ever
slower: balls in a row with e = 0) and take their plastic impulses at once instead
(``plastic``: a few pairs solved at once, or sequential impulses, which never add energy),
and so do the pairs of their bodies that touch where they stopped (two heavy balls crushing
two light ones move as one from that step on, none into another). A crowd
under load (rows landing on rows, bounced off the floor into the next) that runs past
``HANDOVER_ROUNDS`` is given up instead, and its bodies join the pile's soft step.

**Moving walls.** A body of a pile met by one from outside it is a wall to it (w = 1/m = 0 and
1 / I = 0 on its free path; its free spin still moves its surface), and takes the impulse in
the soft step, from the step's start (``exact``'s kick: the impulse's push, and for a body that
turns its moment about the centre at the point of contact, -r (n x P), as a disc met at an
exact impact takes it); so are a kinematic body (whose surface the game turns, and which
takes nothing) and a sleeper the impact does not wake. The wall's impulse is bounded by what
the pair could take without gaining energy, with the wall's own mass (engine.exact.pair_bounce,
"A moving wall"): a light body of a pile struck by a heavy one leaves no faster than it would
alone.

**Bent paths** (engine.exact.bent_paths). A body that bounced off a collider in the static contacts,
before the impacts, took a path of pieces within the step, not one parabola: the impacts take
it on its first piece, and put it on the next at each bounce's moment, in time order (a round
that resolves no impact), so that it meets, on each piece, what that piece meets; an impact
before a bounce sends it off, and that bounce's report is dropped.

**Afterwards** (``separate``). A pair can still be left overlapping (a ball struck against a
wall in the step it lands there is put back out of the wall, into the ball that struck it):
such pairs, rare, are moved apart at the end, their closing stopped, and out of the walls
again.

**Two paths** (engine.kernels). The times of impact, searched again for every pair of a body
an impact sent off, round after round, are found on the fast path by the loop kernel
``pair_times``, pair by pair with the twin's operations in its order (the same bits; a cubic
or quartic, whose eigenvalues numba has no LAPACK for, is left to the twin).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .. import kernels
from ..dynamics import coloring
from ..dynamics.rotation import Spin
from ..geometry.impact import GRAZE_ROUNDING, TOUCH, disc_hits, line_hits
from ..geometry.pair_math import SLOP, dot, norm, state_at, unit
from .bent_paths import Bends, Replay
from .pair_bounce import Turns, bounce, turns_of, wall_bounce
from .pair_order import Order

if TYPE_CHECKING:
    from .contacts import Contacts

__all__ = [
    "COLLAPSE_E",
    "Exact",
    "HANDOVER_ROUNDS",
    "MAX_ROUNDS",
    "Rounds",
    "bounce",
    "exact",
    "impacts_in_order",
    "plastic",
    "separate",
    "state_at",
    "times_of_impact",
    "wall_bounce",
    "wall_hits",
]

#: Impact rounds in one step (each resolves every pair that comes first for both bodies).
MAX_ROUNDS = 64
#: Rounds of impacts after which a crowd under load (rows landing on rows) is given to the
#: pile's soft step instead of being taken on impact by impact (a cradle needs one a ball).
HANDOVER_ROUNDS = 16
#: Restitution up to which pairs still closing at the impact cap take plastic impacts at once
#: (three balls in a line collapse inelastically, without end, below 7 - 4 sqrt(3) = 0.072).
COLLAPSE_E = 0.1


class Rounds(NamedTuple):
    """What ``impacts_in_order`` did: the impacts found (local rows), None if given up."""

    #: Each round's impacts as (a, b, point, normal toward a, impulse on a, time in the step);
    #: None: a crowd under load was given up past ``HANDOVER_ROUNDS``.
    found: list[tuple[np.ndarray, ...]] | None
    #: Rounds that resolved an impact.
    rounds: int
    #: Whether the rounds reached ``MAX_ROUNDS`` with impacts left.
    capped: bool
    #: When given up: the bodies of every impact found or left (mask over the local rows).
    handed: np.ndarray | None


class Exact(NamedTuple):
    """What ``exact`` did, in World rows."""

    #: The impacts, as ``Rounds.found`` in World rows; None: given up (``handed``).
    impacts: list[tuple[np.ndarray, ...]] | None
    #: The impulses (N, 2) the pile's bodies took as moving walls, or None.
    kick: np.ndarray | None
    #: Rounds that resolved an impact.
    rounds: int
    #: Whether the rounds reached ``MAX_ROUNDS`` with impacts left.
    capped: bool
    #: When given up: the World rows of the crowd's bodies.
    handed: np.ndarray | None
    #: The step's spin with what the impacts turned written in (engine.dynamics.rotation; the one
    #: given, or one made here when none was and an impact turned a body), or None.
    spin: Spin | None = None
    #: (World rows, times in the step (s)) of the bodies an impact sent off a path the
    #: static contacts bent, before its later bounces (engine.exact.bent_paths), or None.
    cut: tuple[np.ndarray, np.ndarray] | None = None
    #: The angular impulses (N,) (N m s) the pile's bodies that turn took as moving walls,
    #: with ``kick``: the impulse's moment about the centre, at the point of contact; or None.
    turn: np.ndarray | None = None


def exact(
    a: np.ndarray,
    b: np.ndarray,
    island: np.ndarray,
    x: np.ndarray,
    v: np.ndarray,
    A: np.ndarray,
    P: np.ndarray,
    dt: float,
    t0: float,
    store: Any,
    contacts: Contacts | None,
    asleep: np.ndarray,
    has_kin: bool,
    handover: bool = False,
    fast: bool = False,
    spin: Spin | None = None,
    bends: Bends | None = None,
) -> Exact:
    """Impacts of the pairs (World rows a, b) not both in a pile, at their exact moments,
    in place on the end state (x, v): what ``impacts_in_order`` found, for the events, and
    the impulses (N, 2) the pile's bodies took (None if none): a body of a pile meets a body
    from outside it as a moving wall (infinite mass on its free path), and takes the
    impulse in the soft step, from its start. ``P`` (N, 2): the forces' pull on each body;
    ``t0``: the time at the step's start; ``asleep`` (N,): the sleepers (an awake body that
    meets one without waking it meets a wall); ``has_kin``: some body is kinematic.
    ``handover``: a crowd under load past ``HANDOVER_ROUNDS`` is given up (``Exact``);
    ``fast``: the times of impact by the loop kernel (``pair_times``: the same bits).
    ``spin``: the step's rotation (engine.dynamics.rotation), None if nothing spins: discs that turn
    turn each other (engine.exact.pair_bounce), and their spins are written into it (``Exact``).
    ``bends``: the paths the static contacts bent (engine.exact.bent_paths), taken piece by
    piece."""
    present = np.zeros(len(x), dtype=bool)
    present[a] = present[b] = True
    U = np.flatnonzero(present)
    local = np.cumsum(present) - 1  # World row -> local index, for the rows in U
    la, lb = local[a], local[b]
    # The pairs in one order whatever else the World holds: by their bodies' rows (the
    # broadphase lists them in its grid's order, and the grid's cells depend on every body,
    # a world filtered apart too), so that what is summed over them (the collapse's plastic
    # impulses, pairs moved apart) rounds alike: found exploring, a world's velocities 6e-15
    # from its own alone after a capped step.
    key = la.astype(np.int64) * len(U) + lb
    if len(key) > 1 and not (key[1:] > key[:-1]).all():
        by = np.argsort(key, kind="stable")
        la, lb = la[by], lb[by]
    X, V, AU = x[U], v[U], A[U]
    pull = P[U]
    w = 1.0 / store.mass[U]
    # A kinematic body (moved by the game) has infinite mass here: no impulse moves it.
    kinU = store.kinematic[U] if has_kin else None
    if kinU is not None:
        w[kinU] = 0.0
    walls = island[U]
    # The pile's bodies' own inverse masses, for the bound on a moving wall's impulse (the
    # module's text): a kinematic body and a sleeper stay walls there.
    own = w.copy() if walls.any() else None
    w[walls] = 0.0
    if asleep.any():
        w[asleep[U]] = 0.0  # a sleeper an awake body did not wake stays put
        if own is not None:
            own[asleep[U]] = 0.0
    r = store.radius[U]
    # A disc resting on a face turned as the static contacts turned it: its mean spin-up.
    on = None if contacts is None or len(contacts.rest) != len(x) else contacts.rest[U] >= 0
    turns = turns_of(spin, store, U, w, dt, on)
    replay = None if bends is None else Replay(bends, U)
    if replay is not None and not replay.bent.any():
        replay = None
    rounds = impacts_in_order(
        la,
        lb,
        X,
        V,
        AU,
        w,
        r,
        store.restitution[U],
        store.friction[U],
        dt,
        pull,
        t0,
        contacts,
        U,
        handover,
        fast,
        turns,
        replay,
        own,
    )
    if rounds.found is None:
        # A crowd under load: nothing written back; the World rows of its bodies.
        assert rounds.handed is not None
        return Exact(None, None, rounds.rounds, rounds.capped, U[rounds.handed])
    impacts = rounds.found
    walled = contacts if contacts is not None and len(contacts.faces.owner) else None
    r_wall = r if kinU is None else np.where(kinU, -np.inf, r)
    if impacts and walled is not None:
        # Nothing the pairs pushed is left inside a wall (with its speed into it taken).
        # (A kinematic body is no wall's business: its radius is taken as -inf there.)
        walled.push_out_rows(X, V, r_wall, U)
    for _ in range(3):
        # A pair left overlapping (module text, "Afterwards": a ball struck against a wall
        # in the step it lands there is put back out of the wall, into the ball that struck
        # it) is moved apart (positions), its closing stopped (plastic impulses), and out
        # of the walls again, a few times.
        if not separate(la, lb, X, V, w, r):
            break
        if walled is not None:
            walled.push_out_rows(X, V, r_wall, U)
    kick = turn = None
    if walls.any() and impacts:
        kick = np.zeros((len(x), 2))
        # A wall's impulse P (on a; -P on b) acts at the point of contact, -r_a n from a's
        # centre and r_b n from b's: it turns a by (-r_a n) x P = -r_a (n x P) and b by
        # (r_b n) x (-P), the same -r_b (n x P) (engine.exact.pair_bounce); the normal part
        # turns neither. A body of the pile that turns takes that moment with the push.
        lever = walls & (store.inv_moment[U] > 0.0)
        if kinU is not None:
            lever &= ~kinU
        turn = np.zeros(len(x)) if lever.any() else None
        for pa, pb, _, nrm, J, _ in impacts:
            np.add.at(kick, U[pa[walls[pa]]], J[walls[pa]])
            np.add.at(kick, U[pb[walls[pb]]], -J[walls[pb]])
            if turn is not None:
                nxP = nrm[:, 0] * J[:, 1] - nrm[:, 1] * J[:, 0]
                ka, kb = lever[pa], lever[pb]
                np.add.at(turn, U[pa[ka]], -r[pa[ka]] * nxP[ka])
                np.add.at(turn, U[pb[kb]], -r[pb[kb]] * nxP[kb])
        X[walls], V[walls] = x[U[walls]], v[U[walls]]  # the soft step moves those
    x[U], v[U] = X, V
    if turns is not None and impacts:
        spin = _write_spin(turns, U, spin, store, dt)
    # Events are given in World rows.
    found: list[tuple[np.ndarray, ...]] = [
        (U[pa], U[pb], pt, nrm, J, t) for pa, pb, pt, nrm, J, t in impacts
    ]
    cut = None
    if replay is not None and len(replay.cuts[0]):
        cut = (U[replay.cuts[0]], replay.cuts[1])
    return Exact(found, kick, rounds.rounds, rounds.capped, None, spin, cut, turn)


def _write_spin(
    turns: Turns, U: np.ndarray, spin: Spin | None, store: Any, dt: float
) -> Spin | None:
    """Write the spins the impacts gave (the bodies an impulse turns) into ``spin``, made
    first if there was none (every body free, at rest: engine.dynamics.rotation ``Spin.free``) and
    some body now turns."""
    k = np.flatnonzero(turns.inv_moment > 0.0)
    if spin is None:
        if not turns.omega[k].any():
            return None
        spin = Spin.free(
            store.angle, store.omega, store.inv_moment, store.torque, store.mass,
            store.radius, dt, None, store.kinematic,
        )  # fmt: skip
    spin.angle[U[k]], spin.omega[U[k]] = turns.angle[k], turns.omega[k]
    return spin


def impacts_in_order(
    la: np.ndarray,
    lb: np.ndarray,
    X: np.ndarray,
    V: np.ndarray,
    A: np.ndarray,
    w: np.ndarray,
    r: np.ndarray,
    e: np.ndarray,
    mu: np.ndarray,
    dt: float,
    pull: np.ndarray,
    t0: float,
    contacts: Contacts | None,
    U: np.ndarray,
    handover: bool = False,
    fast: bool = False,
    turns: Turns | None = None,
    replay: Replay | None = None,
    own: np.ndarray | None = None,
) -> Rounds:
    """Resolve the step's impacts in time order, in place on the end state (X, V) of the
    local bodies (World rows U), with inverse masses w (0: a wall), radii r, restitutions e,
    frictions mu and the forces' ``pull`` (what a slow impact is measured against); ``t0``:
    the time at the step's start, for the walls' events.

    ``handover``: when a group's rounds reach ``HANDOVER_ROUNDS``, give up instead
    (``found`` None, with the bodies of the impacts left in such groups and those linked to
    them by impacts in ``handed``, local): a crowd under load (rows landing on rows) is the
    pile's, not a chain of exact impacts. ``fast``: the times of
    impact by the loop kernel (``times_of_impact``). ``turns``: the spin of the bodies that
    turn (engine.exact.pair_bounce), changed in place by the impacts' friction. ``replay``: the
    bodies whose paths the static contacts bent (engine.exact.bent_paths), each put on its next
    piece at each bounce's moment, in the time order of the impacts (a round that resolves
    no impact: it counts toward no limit)."""
    nU = len(X)
    R = r[la] + r[lb]
    # Pairs that close at all within the step can meet (``times_of_impact``: when, if ever).
    P = pull
    rounds = 0
    Vr = V[la] - V[lb]
    Ar = A[la] - A[lb]
    # (Two bodies that no impulse moves, a sleeper and a pile's body, cannot bounce.)
    can = ((norm(Vr) + norm(Ar) * dt) > 0.0) & (w[la] + w[lb] > 0.0)
    if replay is not None:
        # A bent path's pieces move at other speeds than its end state's.
        can |= (replay.bent[la] | replay.bent[lb]) & (w[la] + w[lb] > 0.0)
    if not can.any():
        return Rounds([], rounds, False, None)
    if replay is not None:
        replay.begin(X, V, turns)
    pa, pb, pR = la, lb, R
    ts = np.zeros(nU)  # when each body's current path starts
    toi = np.full(len(pa), np.inf)
    todo = can  # the others are searched once a body of theirs changes path
    found: list[tuple[np.ndarray, ...]] = []
    order = Order(pa, pb, nU)  # which moments each round resolves (engine.exact.pair_order)
    # A body sent off by an impact may meet a wall on its new path within the step: those
    # impacts (face_t: when, face_f: which face) take their place in the time order too.
    walls = contacts is not None and len(contacts.faces.owner) > 0
    face_t = np.full(nU, np.inf)
    face_f = np.zeros(nU, dtype=np.intp)
    face_n = np.zeros((nU, 2))
    changed = np.zeros(nU, dtype=bool)
    replayed = np.zeros(nU, dtype=bool)  # put on their next piece (walls: the contacts')
    capped = False
    # The rounds are counted group by group (bodies linked by the pairs that can meet in the
    # step): a group that reaches the limit takes no more, and the others go on, as they
    # would alone (two worlds filtered apart share no round).
    limit = HANDOVER_ROUNDS if handover else MAX_ROUNDS
    group = order.group()
    count = np.zeros(nU, dtype=np.intp)  # rounds of each group (by its label)
    full = np.zeros(nU, dtype=bool)  # the bodies of a group at the limit
    while True:
        idx = np.flatnonzero(todo)
        if len(idx):
            toi[idx] = times_of_impact(pa[idx], pb[idx], pR[idx], X, V, A, ts, dt, fast)
            todo[idx] = False
        if walls and changed.any():
            assert contacts is not None
            moved = np.flatnonzero(changed & ~replayed)
            face_t[moved], face_f[moved], face_n[moved] = wall_hits(
                contacts, moved, X, V, A, r, ts, dt, pull[moved], U
            )
        # Each body's next moment other than its pairs': a wall, or a bounce of a bent path
        # (a body never has both: an impact ends the bent path, and the replayed pieces'
        # walls were the contacts'); none for a group at the limit.
        bend = None if replay is None else replay.t
        toi_on, face_on, bend_on = toi, face_t, bend
        if full.any():
            toi_on = np.where(full[pa], np.inf, toi)
            face_on = np.where(full, np.inf, face_t)
            bend_on = None if bend is None else np.where(full, np.inf, bend)
        if not np.isfinite(toi_on).any() and not np.isfinite(face_on).any():
            if bend_on is None or not np.isfinite(bend_on).any():
                break
        # The pairs that come first for both their bodies, the walls and the bounces that
        # come before any pair of their own, in time order among linked bodies.
        s, wall, knot = order.choose(toi_on, face_on, bend_on)
        changed = np.zeros(nU, dtype=bool)
        replayed = np.zeros(nU, dtype=bool)
        if len(s):
            found.append(bounce(pa[s], pb[s], toi[s], X, V, A, w, r, e, mu, dt, turns, own))
            ts[pa[s]] = toi[s]
            ts[pb[s]] = toi[s]
            changed[pa[s]] = changed[pb[s]] = True
            if replay is not None:
                replay.cut(pa[s], toi[s], w)
                replay.cut(pb[s], toi[s], w)
        if len(wall):
            assert contacts is not None
            wall_bounce(
                contacts,
                U,
                t0,
                wall,
                face_t[wall],
                face_f[wall],
                face_n[wall],
                X,
                V,
                A,
                w,
                r,
                e,
                mu,
                dt,
                turns,
            )
            ts[wall] = face_t[wall]
            changed[wall] = True
        if len(s) or len(wall):
            rounds += 1
            count[np.unique(group[np.concatenate([pa[s], wall])])] += 1
            full = count[group] >= limit
        if len(knot):
            # A bent body goes on its next piece (from that moment; the bounce itself is
            # the contacts' report).
            assert replay is not None
            ts[knot] = replay.advance(knot, X, V)
            changed[knot] = replayed[knot] = True
        # Every pair of a body whose path changed is searched again, and its walls.
        face_t[changed] = np.inf
        again = changed[pa] | changed[pb]
        toi[again] = np.inf
        todo |= again
    if full.any():
        if handover:
            # The crowd: the bodies with an impact still to come, and every body linked to
            # them by an impact of this step or one to come. A chain elsewhere that ended
            # stays exact: bodies that never meet the crowd move as if it were not there.
            idx = np.flatnonzero(todo)
            if len(idx):
                toi[idx] = times_of_impact(pa[idx], pb[idx], pR[idx], X, V, A, ts, dt, fast)
            hit = np.isfinite(toi)
            involved = np.zeros(nU, dtype=bool)
            involved[pa[hit]] = involved[pb[hit]] = True
            ea = np.concatenate([np.asarray(f[0], dtype=np.intp) for f in found] + [pa[hit]])
            eb = np.concatenate([np.asarray(f[1], dtype=np.intp) for f in found] + [pb[hit]])
            for _ in range(nU):
                grow = involved[ea] != involved[eb]
                if not grow.any():
                    break
                involved[ea[grow]] = involved[eb[grow]] = True
            return Rounds(None, rounds, False, involved)
        # Impacts are left: rather than let the bodies fly through each other on their
        # paths, each body with an impact still to come stops at the earliest one left,
        # where its path is then (no overlap yet), and goes on from there next step. Only
        # those bodies lose the rest of this step's motion; their velocities keep what
        # the forces gave them over the whole step, so momentum changes by exactly the
        # forces' impulse, as in every other step.
        capped = True
        if replay is not None:
            # Bent bodies with bounces left go on their last pieces, as the contacts left
            # them (their pairs searched there).
            moved = np.zeros(nU, dtype=bool)
            moved[replay.finish(X, V, ts)] = True
            todo |= moved[pa] | moved[pb]
        idx = np.flatnonzero(todo)
        if len(idx):
            toi[idx] = times_of_impact(pa[idx], pb[idx], pR[idx], X, V, A, ts, dt, fast)
        hit = np.isfinite(toi)
        left = np.zeros(nU, dtype=bool)
        left[pa[hit]] = left[pb[hit]] = True
        left |= np.isfinite(face_t)
        if left.any():
            # Each group of bodies linked by the impacts left stops at its own earliest one
            # (bodies that never meet it, a world filtered apart, move as if it were not
            # there). A body that would run into a stopped one (no impact of theirs pending:
            # resting against it, or following it) stops too, at the earlier of their
            # moments, and so on along the contacts.
            T = face_t.copy()
            ha, hb, ht = pa[hit], pb[hit], toi[hit]
            np.minimum.at(T, ha, ht)
            np.minimum.at(T, hb, ht)
            for _ in range(nU):
                low = np.minimum(T[ha], T[hb])
                if (T[ha] == low).all() and (T[hb] == low).all():
                    break
                np.minimum.at(T, ha, low)
                np.minimum.at(T, hb, low)
            for _ in range(2 * nU):
                one = (left[pa] | left[pb]) & (T[pa] != T[pb])
                if not one.any():
                    break
                ia, ib = pa[one], pb[one]
                meet = _runs_into(ia, ib, pR[one], T, ts, X, V, A, dt)
                if not meet.any():
                    break
                ia, ib = ia[meet], ib[meet]
                low = np.minimum(T[ia], T[ib])
                np.minimum.at(T, ia, low)
                np.minimum.at(T, ib, low)
                left[ia] = left[ib] = True
            i = np.flatnonzero(left)
            X[i] = state_at(i, T[i], X, V, A, dt)[0]
        soft = e[pa] * e[pb] <= COLLAPSE_E
        collapse = hit & soft
        if collapse.any():
            # An inelastic collapse (impacts without end, closing ever slower: a light
            # ball between heavy ones, e small) would meet the cap again every step, and
            # stop there: its pairs take their plastic impacts all at once instead, and so
            # do the pairs of its bodies that touch where they stopped (one parting now
            # may close as those impacts push it: the crushed row moves as one).
            its = np.zeros(nU, dtype=bool)
            its[pa[collapse]] = its[pb[collapse]] = True
            near = norm(X[pa] - X[pb]) <= pR * (1.0 + 1e-9)
            collapse |= soft & near & (its[pa] | its[pb])
            # Group by group (bodies linked by pairs that can meet), each with its own rest
            # speed: a world filtered apart collapses as if the other were not there (its
            # sweeps' count and tolerance were the whole room's: an ulp off, found exploring).
            ca, cb = pa[collapse], pb[collapse]
            labels = group[ca]
            for g in np.unique(labels):
                k = labels == g
                own_bodies = np.union1d(ca[k], cb[k])
                plastic(ca[k], cb[k], X, V, w, 2.0 * dt * float(norm(P[own_bodies]).max()))
    return Rounds(found, rounds, capped, None)


def _runs_into(
    ia: np.ndarray,
    ib: np.ndarray,
    R: np.ndarray,
    T: np.ndarray,
    ts: np.ndarray,
    X: np.ndarray,
    V: np.ndarray,
    A: np.ndarray,
    dt: float,
) -> np.ndarray:
    """Whether each pair (ia, ib), one of them stopped by the cap at the earlier of their
    moments T (inf: not stopped), meets on the other's path from then to its own stop (or the
    step's end): the stopped one is a disc at rest there. Not only where the paths end: a
    ball that rests against a stopped one, both moving as one (touching, no impact pending),
    runs into it at once, however far past it its own path ends. The moving one's path is
    taken from its own start ``ts`` if later (before that it was on another path)."""
    Ta, Tb = np.minimum(T[ia], dt), np.minimum(T[ib], dt)
    early = Ta <= Tb
    s = np.where(early, ia, ib)  # stopped first
    m = np.where(early, ib, ia)  # still moving then
    Ts, Tm = np.minimum(Ta, Tb), np.maximum(Ta, Tb)
    xs = state_at(s, Ts, X, V, A, dt)[0]
    start = np.minimum(np.maximum(Ts, ts[m]), Tm)
    xm, vm = state_at(m, start, X, V, A, dt)
    hit = np.isfinite(disc_hits(xm, vm, A[m], xs, R, Tm - start))
    # Already into it where the moving one's path ends (a path that began inside it).
    xe = state_at(m, Tm, X, V, A, dt)[0]
    return hit | (norm(xe - xs) < R)


def times_of_impact(
    pa: np.ndarray,
    pb: np.ndarray,
    R: np.ndarray,
    X: np.ndarray,
    V: np.ndarray,
    A: np.ndarray,
    ts: np.ndarray,
    dt: float,
    fast: bool = False,
) -> np.ndarray:
    """Time (s, in the step) of the first impact (closing faster than its rest speed) of each
    pair, or inf. ``fast``: by the loop kernel ``pair_times`` (the same bits), which leaves
    the pairs whose paths curve apart (a cubic or quartic: eigenvalues) to this numpy twin."""
    if fast:
        t = np.empty(len(pa))
        curved = np.zeros(len(pa), dtype=np.bool_)
        pair_times(pa, pb, R, X, V, A, ts, float(dt), t, curved)
        if curved.any():
            k = np.flatnonzero(curved)  # each pair's time is its own: a subset is the same
            t[k] = times_of_impact(pa[k], pb[k], R[k], X, V, A, ts, dt)
        return t
    start = np.maximum(ts[pa], ts[pb])
    xa, va = state_at(pa, start, X, V, A, dt)
    xb, vb = state_at(pb, start, X, V, A, dt)
    D, Vr, Ar = xa - xb, va - vb, A[pa] - A[pb]
    tau = disc_hits(D, Vr, Ar, np.zeros_like(D), R, dt - start)
    t = start + tau
    ok = np.flatnonzero(np.isfinite(tau))
    if len(ok):
        # Closing speed at the moment of contact: a slow one is a contact at rest.
        T = tau[ok, None]
        d = D[ok] + Vr[ok] * T + Ar[ok] * (0.5 * T * T)
        dn = np.maximum(norm(d), 1e-300)
        u = -dot(Vr[ok] + Ar[ok] * T, d) / dn
        # Only rounding: two discs that an inelastic impact left moving together close
        # at ~1e-16 of their speed, which is no impact. (A pair closing slowly under
        # the forces, to rest on each other, is a pile's: ``plan`` gave it to the soft
        # step; any other meeting is an impact, however slow.)
        speed = norm(va[ok]) + norm(vb[ok])
        t[ok[u <= 1e-12 * speed]] = np.inf
    return t


# -- the loop kernel of times_of_impact (engine.kernels: the fast path) ---------------------
# times_of_impact with engine.geometry.impact.disc_hits (the disc's centre 0: the difference of two
# paths), pair by pair: the same operations in the same order, with an ``if`` where the twin
# picks with np.where (as impact.disc_hit_one does), so the two give the same bits. A pair
# whose polynomial is a cubic or a quartic (accelerations that differ) needs the eigenvalues
# of its companion matrix: it is marked ``curved`` and left to the twin.


def _sample_pairs() -> tuple[object, ...]:
    """The smallest call of ``pair_times``: two balls 3 m apart closing at 2 m/s."""
    x, v = np.array([[0.0, 0.0], [3.0, 0.0]]), np.array([[1.0, 0.0], [-1.0, 0.0]])
    i, j = np.array([0]), np.array([1])
    return (i, j, np.ones(1), x, v, np.zeros((2, 2)), np.zeros(2), 1.0, np.empty(1),
            np.zeros(1, dtype=np.bool_))  # fmt: skip


@kernels.loop(sample=_sample_pairs)
def pair_times(
    pa: np.ndarray,
    pb: np.ndarray,
    R: np.ndarray,
    X: np.ndarray,
    V: np.ndarray,
    A: np.ndarray,
    ts: np.ndarray,
    dt: float,
    t: np.ndarray,
    curved: np.ndarray,
) -> None:
    """``times_of_impact``'s times (s) into t, pair by pair; the pairs marked in ``curved``
    (their t unset) are the twin's."""
    inf = math.inf
    for k in range(len(pa)):
        i, j = pa[k], pb[k]
        curved[k] = False
        # Both bodies where their paths are when the later of them starts (state_at).
        start = max(ts[i], ts[j])
        s = dt - start
        h = 0.5 * s * s
        ax, ay = X[i, 0] - V[i, 0] * s + A[i, 0] * h, X[i, 1] - V[i, 1] * s + A[i, 1] * h
        bx, by = X[j, 0] - V[j, 0] * s + A[j, 0] * h, X[j, 1] - V[j, 1] * s + A[j, 1] * h
        vax, vay = V[i, 0] - A[i, 0] * s, V[i, 1] - A[i, 1] * s
        vbx, vby = V[j, 0] - A[j, 0] * s, V[j, 1] - A[j, 1] * s
        Dx, Dy, Vx, Vy = ax - bx, ay - by, vax - vbx, vay - vby
        Bx, By = A[i, 0] - A[j, 0], A[i, 1] - A[j, 1]
        rho, T = R[k], s
        # disc_hits: |D + V t + B t^2 / 2|^2 = rho^2, first root in [0, T].
        dd, vv = Dx * Dx + Dy * Dy, Vx * Vx + Vy * Vy
        dv, db, bb = Dx * Vx + Dy * Vy, Dx * Bx + Dy * By, Bx * Bx + By * By
        dist0 = math.sqrt(dd) - rho
        reach = math.sqrt(vv) * T + math.sqrt(bb) * (0.5 * T * T)
        tau = inf
        leaving = False
        search = False
        if dist0 <= TOUCH * (1.0 + rho):  # touching: now if heading in
            k1 = 2.0 * dv
            slack = 1e-12 * math.sqrt(dd * vv)
            if k1 < -slack or (k1 <= slack and vv + db < 0.0):
                tau = 0.0
            elif reach > 0.0:
                leaving = search = True  # it may curve back within the step
        elif dist0 <= reach * (1.0 + 1e-9):
            search = True
        if search:
            # The chord test: the path strays at most |B| T^2 / 2 from D + V t.
            c = -dv / (vv if vv > 0.0 else 1.0)
            c = min(max(c, 0.0), T)
            Cx, Cy = Dx + Vx * c, Dy + Vy * c
            stray = 0.5 * math.sqrt(bb) * T * T
            near = math.sqrt(Cx * Cx + Cy * Cy) - stray <= rho * (1.0 + 1e-9) + TOUCH
            search = leaving or near
        if search:
            # The quartic in tau = t / T, deflated by tau for a pair leaving contact.
            T2 = T * T
            k0, k1, k2 = dd - rho * rho, 2.0 * dv * T, (vv + db) * T2
            k3, k4 = (Vx * Bx + Vy * By) * (T2 * T), 0.25 * bb * (T2 * T2)
            if leaving:
                k0, k1, k2, k3, k4 = k1, k2, k3, k4, 0.0
            scale = max(abs(k0), abs(k1), abs(k2), abs(k3), abs(k4))
            if math.isnan(k0 + k1 + k2 + k3 + k4):
                scale = math.nan  # as np.max: a nan leaves only the quadratic
            small = 1e-9 * scale
            low = k0 + min(k1, 0.0) + min(k2, 0.0) + min(k3, 0.0) + min(k4, 0.0)
            clear = low > 1e-6 * scale  # above zero on [0, 1]: no root
            if not clear and (abs(k4) > small or abs(k3) > small):
                curved[k] = True  # a cubic or a quartic: the twin's eigenvalues
                continue
            if not clear:
                # quadratic_first_root(k0, k1, k2, 1.0), as impact.quadratic_first_root_one.
                if k0 <= 0.0:
                    if k1 < 0.0 or (k1 <= 0.0 and k2 < 0.0):
                        r = 0.0
                    else:
                        r = -k1 / k2 if k2 < 0.0 and k1 > 0.0 else inf
                elif k2 == 0.0:
                    r = -k0 / k1 if k1 < 0.0 else inf
                else:
                    disc = k1 * k1 - 4.0 * k2 * k0
                    r = inf
                    if disc >= 0.0:
                        q = -0.5 * (k1 + math.copysign(math.sqrt(max(disc, 0.0)), k1))
                        r1 = q / k2
                        r2 = k0 / q if q != 0.0 else inf
                        r1 = r1 if r1 >= 0.0 else inf
                        r2 = r2 if r2 >= 0.0 else inf
                        r = r1 if r1 < r2 else r2
                r = r if r <= 1.0 else inf
                if not leaving and r != inf and k0 > 0.0:
                    # impact.graze_one: a tangency within the discriminant's rounding.
                    disc = k1 * k1 - 4.0 * k2 * k0
                    if disc <= GRAZE_ROUNDING * (k1 * k1 + 4.0 * abs(k2) * (dd + rho * rho)):
                        r = inf
                if r > (1e-9 if leaving else -1e-9) and r != inf:
                    # _polish: three Newton steps, kept unless they stray (a double root).
                    x = r
                    for _ in range(3):
                        f = k0 + x * (k1 + x * (k2 + x * (k3 + x * k4)))
                        df = k1 + x * (2.0 * k2 + x * (3.0 * k3 + x * 4.0 * k4))
                        x = x - (f / df if df != 0.0 else 0.0)
                    x = x if abs(x - r) <= 1e-6 else r
                    tau = max(x, 0.0) * T if x <= 1.0 else inf
        t[k] = start + tau
        if math.isfinite(tau):
            # Closing speed at the moment of contact: a slow one is a contact at rest.
            g = 0.5 * tau * tau
            dx, dy = Dx + Vx * tau + Bx * g, Dy + Vy * tau + By * g
            dn = max(math.sqrt(dx * dx + dy * dy), 1e-300)
            u = -((Vx + Bx * tau) * dx + (Vy + By * tau) * dy) / dn
            speed = math.sqrt(vax * vax + vay * vay) + math.sqrt(vbx * vbx + vby * vby)
            if u <= 1e-12 * speed:
                t[k] = inf


def wall_hits(
    contacts: Contacts,
    i: np.ndarray,
    X: np.ndarray,
    V: np.ndarray,
    A: np.ndarray,
    r: np.ndarray,
    ts: np.ndarray,
    dt: float,
    pull: np.ndarray,
    U: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(time, face, unit normal toward the body) of the first wall each local body i meets
    on its path from ts to the end of the step closing faster than its rest speed (2 dt times
    its ``pull`` along the normal); time inf where none (``engine.geometry.impact`` solves for the
    times)."""
    faces = contacts.faces
    L = len(faces.p)
    m = len(i)
    t_out = np.full(m, np.inf)
    f_out = np.zeros(m, dtype=np.intp)
    n_out = np.zeros((m, 2))
    T = dt - ts[i]
    s = T[:, None]
    Ai = A[i]
    x = X[i] - V[i] * s + Ai * (0.5 * s * s)  # the state at ts, on the path ending at (X, V)
    v = V[i] - Ai * s
    reach = r[i] + norm(v) * T + norm(Ai) * (0.5 * T * T) + TOUCH
    bi, f = contacts.grid.pairs(x, reach)
    if len(bi) and U is not None and contacts.filtering:
        ok = contacts.allowed(U[i[bi]], f)  # faces a body's filter does not meet
        bi, f = bi[ok], f[ok]
    if not len(bi):
        return t_out, f_out, n_out
    t = np.full(len(bi), np.inf)
    n = np.zeros((len(bi), 2))
    line = f < L
    if line.any():
        k, fl = np.flatnonzero(line), f[line]
        b = bi[k]
        t[k], n[k] = line_hits(
            x[b],
            v[b],
            Ai[b],
            faces.p[fl],
            faces.n[fl],
            faces.rho[fl] + r[i][b],
            faces.two[fl],
            faces.lo[fl],
            faces.hi[fl],
            T[b],
        )
    if (~line).any():
        k, fd = np.flatnonzero(~line), f[~line] - L
        b = bi[k]
        t[k] = disc_hits(x[b], v[b], Ai[b], faces.c[fd], faces.r[fd] + r[i][b], T[b])
        ok = np.isfinite(t[k])
        tt = np.where(ok, t[k], 0.0)[:, None]
        d = x[b] + v[b] * tt + Ai[b] * (0.5 * tt * tt) - faces.c[fd]
        n[k] = d / np.maximum(norm(d), 1e-300)[:, None]
    # Only an impact closing faster than rest counts (a ball rolling along a floor meets it
    # at every moment).
    ok = np.flatnonzero(np.isfinite(t))
    if len(ok):
        tt = t[ok, None]
        vt = v[bi[ok]] + Ai[bi[ok]] * tt
        slow = -dot(vt, n[ok]) <= 2.0 * dt * np.abs(dot(pull[bi[ok]], n[ok]))
        t[ok[slow]] = np.inf
    order = np.lexsort((t, bi))  # by body, earliest first
    bi, t, f, n = bi[order], t[order], f[order], n[order]
    first = np.ones(len(bi), dtype=bool)
    first[1:] = bi[1:] != bi[:-1]
    b = bi[first]
    t_out[b], f_out[b], n_out[b] = t[first], f[first], n[first]
    return ts[i] + t_out, f_out, n_out


def separate(
    la: np.ndarray, lb: np.ndarray, X: np.ndarray, V: np.ndarray, w: np.ndarray, r: np.ndarray
) -> bool:
    """Move the pairs (la, lb) that overlap past SLOP apart, in place on X, each body by
    its share w_a / (w_a + w_b) of the excess (a body of w = 0 stays), averaged over its
    pairs (one Jacobi sweep), after stopping their closing (``plastic``). Whether any
    moved."""
    d = X[la] - X[lb]
    dist = norm(d)
    R = r[la] + r[lb]
    over = R - dist - SLOP * np.minimum(r[la], r[lb])
    ws = w[la] + w[lb]
    k = np.flatnonzero((over > 0.0) & (ws > 0.0))
    if not len(k):
        return False
    a, b = la[k], lb[k]
    plastic(a, b, X, V, w, 0.0)
    push = unit(d[k], dist[k]) * (over[k] / ws[k])[:, None]
    move = np.zeros_like(X)
    count = np.zeros(len(X))
    np.add.at(move, a, push * w[a, None])
    np.add.at(move, b, -push * w[b, None])
    np.add.at(count, a, 1.0)
    np.add.at(count, b, 1.0)
    X += move / np.maximum(count, 1.0)[:, None]
    return True


#: The most pairs ``plastic`` solves at once (``stopping``: a dense system of that size).
DIRECT = 32


def stopping(
    pa: np.ndarray, pb: np.ndarray, n: np.ndarray, V: np.ndarray, w: np.ndarray, tol: float
) -> np.ndarray | None:
    """The plastic impulses (N s, >= 0, one a pair) that stop every pair (pa, pb) closing
    along its normal n (toward a) at once, or None for more than ``DIRECT`` pairs or where
    the set is not found. The linear complementarity problem of contacts: the normal speeds
    after, vn + K lam with K = J W J^T (J a pair's row, +n on a and -n on b; W the inverse
    masses w), are >= -tol, each lam >= 0, and a pair pushed (lam > 0) parts at 0. By active
    sets: the pairs closing are solved together, a pair that would pull is let go, a pair
    left closing is taken in, until none is either."""
    k = len(pa)
    if k > DIRECT:
        return None
    vn = dot(V[pa] - V[pb], n)
    # K_ij = n_i.n_j (w_ai ([a_i = a_j] - [a_i = b_j]) - w_bi ([b_i = a_j] - [b_i = b_j])).
    a_i, b_i = pa[:, None], pb[:, None]
    K = (n @ n.T) * (
        w[pa][:, None] * ((a_i == pa[None, :]) * 1.0 - (a_i == pb[None, :]))
        - w[pb][:, None] * ((b_i == pa[None, :]) * 1.0 - (b_i == pb[None, :]))
    )
    active = vn < -tol
    for _ in range(4 * k + 4):
        lam = np.zeros(k)
        if active.any():
            A = np.flatnonzero(active)
            try:
                lam[A] = np.linalg.solve(K[np.ix_(A, A)], -vn[A])
            except np.linalg.LinAlgError:
                return None  # (pairs that hold one another: the sweeps decide)
            if not np.isfinite(lam).all():
                return None
            if (lam[A] < 0.0).any():
                active[A[np.argmin(lam[A])]] = False
                continue
        after = vn + K @ lam
        if (after[active] < -tol).any():
            # The solve left a pair it pushed still closing: normals all but parallel (a
            # body between a wall and a wall coming at it 6e-8 rad apart), K near singular.
            return None  # (the sweeps decide)
        left = ~active & (after < -tol)
        if not left.any():
            return lam
        active[np.argmin(np.where(left, after, np.inf))] = True
    return None


def plastic(
    pa: np.ndarray, pb: np.ndarray, X: np.ndarray, V: np.ndarray, w: np.ndarray, rest: float
) -> None:
    """Stop the closing of pairs (pa, pb) at once, in place on V: sequential plastic
    impulses (restitution 0, along the line of centres, each at most what stops its pair, the
    pair's total never pulling) swept over the pairs in colours (engine.dynamics.coloring) until
    none closes faster than ``rest`` plus rounding. Each impulse is a projection in the mass metric,
    so kinetic energy never grows, and momentum is kept. A few pairs (at most ``DIRECT``) are
    solved at once first (``stopping``), and the sweeps only confirm it: a light ball crushed
    between heavy ones takes hundreds of sweeps per decade of its closing speed."""
    d = X[pa] - X[pb]
    nrm = unit(d, norm(d))
    ws = w[pa] + w[pb]
    ok = ws > 0.0
    pa, pb, nrm, ws = pa[ok], pb[ok], nrm[ok], ws[ok]
    if not len(pa):
        return
    moves = w > 0.0
    order = coloring.batches(coloring.colors(pa, pb, moves), pa, pb, moves)
    speed = float(norm(V[np.union1d(pa, pb)]).max())  # (the pairs' own bodies': their rounding)
    lam = stopping(pa, pb, nrm, V, w, rest + 1e-12 * speed)
    if lam is None:
        lam = np.zeros(len(pa))
    else:
        J = nrm * lam[:, None]
        np.add.at(V, pa, J * w[pa, None])
        np.add.at(V, pb, -J * w[pb, None])
    for _ in range(200):
        worst = 0.0
        for rows in order:
            a, b, n = pa[rows], pb[rows], nrm[rows]
            vn = dot(V[a] - V[b], n)  # < 0: closing
            new = np.maximum(lam[rows] - vn / ws[rows], 0.0)
            dl = new - lam[rows]
            lam[rows] = new
            V[a] += n * (dl * w[a])[:, None]
            V[b] -= n * (dl * w[b])[:, None]
            worst = max(worst, float(-vn.min()))
        if worst <= rest + 1e-12 * speed:
            break
