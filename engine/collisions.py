"""Contacts between bodies: impacts in the order physics gives them, piles that rest, sleep.

Bodies with a radius > 0 collide with each other (unless a :class:`engine.Filter` turns the
pair off; points never collide). The World hands this module each step's start state
(x0, v0), the state after its method and the static contacts (x1, v1), and each body's
acceleration A over the step (the constant one under the closed form; the step's own for an
integrator; zero for a body that rested on a collider). Within the step a body's centre is
taken on the path that ends at (x1, v1),

    x(t) = x1 - v1 s + A s^2 / 2,    v(t) = v1 - A s,    s = dt - t,

the exact parabola under the closed form. A step has two phases.

**Impacts**, solved at their exact moment and in time order. Two balls touch when the
distance of their centres is R = r_a + r_b; along the paths, the difference
d(t) = x_a(t) - x_b(t) is itself a parabola, so the moment of impact is the first root of
|d(t)|^2 = R^2 (``engine.impact.disc_hits``, a quadratic when both share one acceleration, as
under gravity). At that moment, with the unit normal n = d / R toward a and the closing speed
u = -(v_a - v_b).n > 0, the impulse along n is

    J = (1 + e) u / (1/m_a + 1/m_b),        e = e_a e_b (pymunk's product rule),

which conserves momentum exactly and, with e = 1, energy: it is the closed-form 2D collision
of two discs. Coulomb friction (mu = mu_a mu_b) takes up to mu J of the tangential relative
momentum, never reversing it. Each velocity changes by dv = J n / m, and the position at the
end of the step by dv (dt - t): the rest of the step is flown on the new path. Impacts are
taken in rounds: in each, every pair that is the earliest impact of both its bodies is
resolved (they share no body, so they are independent), then the paths of the bodies that
changed are searched again. Newton's cradle is the test: the first ball stops, the second
takes its speed at the same instant and meets the third, and so on down the row; a solver
that spreads one impulse over the row (plain Jacobi) fails it. Rounds stop after
``MAX_ROUNDS`` (a light ball squeezed between heavy ones bounces about pi sqrt(M/m) times);
then each body with an impact still to come stops where its path is at the earliest one left
(its velocity the step's end one, so momentum changes by the forces' impulse alone), and so
does every body that would run into a stopped one, and goes on from there next step: bodies
never fly through each other for want of rounds, at the cost of the rest of that step's
motion for those bodies. Pairs still closing there with restitution up to ``COLLAPSE_E``
are an inelastic collapse (impacts without end, ever slower: balls in a row with e = 0)
and take their plastic impulses at once instead (``_plastic``: sequential impulses, which
never add energy). The count of steps that reached the cap is kept in ``capped``.
The impacts are found on each body's path as a parabola to its end state; a body that
bounced off a wall within the step took another path before, and may end inside a ball that
path never met: such pairs, rare (two balls meeting on a Galton board's peg), are moved
apart at the end, their closing stopped (``_separate``). The pairs searched are those a
body's speed can bring together within the step, and those of a body an impact may send off
faster (a light ball struck by a heavy one: ``_struck_pairs``).

**Piles: the bodies that rest on one another are solved together** (``engine.soft``). Which
pairs are a pile's and which meet at their exact moments is decided as the step begins
(``plan``), by one rule:

* a pair rests (is a pile's) if it carried load in the last step, or if it is near enough to
  touch within the step, closes or parts no faster than its rest speed (2 |a| dt, what the
  forces add in two steps) and is pressed together by the forces (a ball landing softly on
  another; a body resting on a collider counts as held up, so a ball landing on a ball
  that rests on a peg presses it), or if it overlaps by more than ``SLOP``;
* whatever can reach a resting pair's body within the step joins the pile too (a ball
  falling onto it: its contact is a speculative one, stopped where it touches);
* every other pair (two balls that meet in flight, a ball striking a ball that rests alone on
  a floor, Newton's cradle on a frictionless floor, whose balls touch but carry nothing)
  meets at its exact moment, as above.

The bodies of a pile are stepped again from the start of the step by Box2D v3's soft step,
``iterations`` parts (``World.contact_iterations``) with their pairs and the faces they can
reach (the static contacts leave them to it), warm started from the last step's impulses:
it holds a pile many layers deep, keeps rows landing at speed from sinking into it, and
adds no energy (the push that takes out an overlap is relaxed out of the speeds; what the
few iterations still add is scaled back: ``_dissipative``). Nothing it moves is left inside
a wall (``Contacts.push_out_rows``). A sleeping group keeps its contacts' impulses, so that
it wakes holding its weight.

**Sleep.** A group of bodies resting on one another (or one body held still on a collider)
that has been still for ``sleep_time`` seconds (every speed below |A| dt, the speed the
acceleration adds in one step: Chipmunk's idle speed), and overlaps by at most
``SLEEP_OVERLAP`` of a radius, falls asleep: its bodies stay exactly where they are,
velocity 0, and cost nothing, until an awake body meets one of them (the whole group wakes)
or the World is changed by hand (adding bodies wakes nobody: a new body wakes the group it
touches, as any awake body does). A body in flight never sleeps, however slow.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from . import coloring
from .colliders import Circle
from .impact import TOUCH, disc_hits, line_hits
from .manifold import StaticShapes, static_shapes
from .shaped import ShapeTable, pair_rows, static_rows
from .soft import Rows, SoftStep

if TYPE_CHECKING:
    from .contacts import Contacts

__all__ = ["Collisions", "MAX_ROUNDS", "SLOP", "PUSH", "deepest_overlap"]

#: Impact rounds in one step (each resolves every pair that comes first for both bodies).
MAX_ROUNDS = 64
#: Overlap (fraction of the smaller radius) that counts as touching: contacts touch, they do
#: not chatter.
SLOP = 0.002
#: Rounds of impacts after which a crowd under load (rows landing on rows) is given to the
#: pile's soft step instead of being taken on impact by impact (a cradle needs one a ball).
HANDOVER_ROUNDS = 16
#: Restitution up to which pairs still closing at the impact cap take plastic impacts at once
#: (three balls in a line collapse inelastically, without end, below 7 - 4 sqrt(3) = 0.072).
COLLAPSE_E = 0.1
#: A body sleeps only while it overlaps others by at most this fraction of its radius.
SLEEP_OVERLAP = 0.0075
#: The fastest the soft step pushes overlapping bodies apart, in smallest radii a second
#: (Box2D's 3 m/s for bodies of half a metre).
PUSH = 6.0
#: A body joins a pile by closing on it within the step by at most this many times the sum
#: of the two radii (a speculative contact catches it); faster, it meets the pile's bodies
#: at the exact moments.
CATCH = 2.0
THRESH = 3.0
PUSHOUT = True


def _separate(
    la: np.ndarray, lb: np.ndarray, X: np.ndarray, V: np.ndarray, w: np.ndarray, r: np.ndarray
) -> bool:
    """Move the pairs (la, lb) that overlap past SLOP apart, in place on X, each body by
    its share w_a / (w_a + w_b) of the excess (a body of w = 0 stays), averaged over its
    pairs (one Jacobi sweep), after stopping their closing (``_plastic``). Whether any
    moved."""
    d = X[la] - X[lb]
    dist = _norm(d)
    R = r[la] + r[lb]
    over = R - dist - SLOP * np.minimum(r[la], r[lb])
    ws = w[la] + w[lb]
    k = np.flatnonzero((over > 0.0) & (ws > 0.0))
    if not len(k):
        return False
    a, b = la[k], lb[k]
    _plastic(a, b, X, V, w, 0.0)
    push = _unit(d[k], dist[k]) * (over[k] / ws[k])[:, None]
    move = np.zeros_like(X)
    count = np.zeros(len(X))
    np.add.at(move, a, push * w[a, None])
    np.add.at(move, b, -push * w[b, None])
    np.add.at(count, a, 1.0)
    np.add.at(count, b, 1.0)
    X += move / np.maximum(count, 1.0)[:, None]
    return True


def _plastic(
    pa: np.ndarray, pb: np.ndarray, X: np.ndarray, V: np.ndarray, w: np.ndarray, rest: float
) -> None:
    """Stop the closing of pairs (pa, pb) at once, in place on V: sequential plastic
    impulses (restitution 0, along the line of centres, each at most what stops its pair, the
    pair's total never pulling) swept over the pairs in colours (engine.coloring) until none
    closes faster than ``rest`` plus rounding. Each impulse is a projection in the mass metric,
    so kinetic energy never grows, and momentum is kept."""
    d = X[pa] - X[pb]
    nrm = _unit(d, _norm(d))
    ws = w[pa] + w[pb]
    ok = ws > 0.0
    pa, pb, nrm, ws = pa[ok], pb[ok], nrm[ok], ws[ok]
    if not len(pa):
        return
    moves = w > 0.0
    order = coloring.batches(coloring.colors(pa, pb, moves), pa, pb, moves)
    lam = np.zeros(len(pa))
    speed = float(_norm(V).max())
    for _ in range(200):
        worst = 0.0
        for rows in order:
            a, b, n = pa[rows], pb[rows], nrm[rows]
            vn = _dot(V[a] - V[b], n)  # < 0: closing
            new = np.maximum(lam[rows] - vn / ws[rows], 0.0)
            dl = new - lam[rows]
            lam[rows] = new
            V[a] += n * (dl * w[a])[:, None]
            V[b] -= n * (dl * w[b])[:, None]
            worst = max(worst, float(-vn.min()))
        if worst <= rest + 1e-12 * speed:
            break


def _dissipative(V: np.ndarray, V0: np.ndarray, m: np.ndarray) -> np.ndarray:
    """The pile's velocities V (the forces alone would give V0), with the contacts' change
    scaled back if it gained kinetic energy.

    Contacts only take energy (an exact solution of resting contacts is a projection of V0
    in the mass metric, which never lengthens it; friction dissipates; restitution e <= 1
    gives back at most what the impact took), but the soft step's few iterations, and its
    push apart of an overlap, can stop short and add a little. Then the change dV = V - V0
    is scaled by the s in [0, 1] that leaves the least energy: KE(s) = KE0 + s B + s^2 C
    with B = sum m V0.dV, C = sum m |dV|^2 / 2, so s = -B / (2 C). Momentum is kept: the
    contacts' impulses between bodies are equal and opposite at any s (a wall's are not,
    and lose only what s takes off them).
    """
    dV = V - V0
    B = float((m * _dot(V0, dV)).sum())
    C = 0.5 * float((m * _dot(dV, dV)).sum())
    KE0 = 0.5 * float((m * _dot(V0, V0)).sum())
    if not B + C > 1e-13 * KE0 + 1e-300:
        return V
    s = min(max(-B / (2.0 * C), 0.0), 1.0)
    return V0 + s * dV


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]


def _norm(a: np.ndarray) -> np.ndarray:
    return np.sqrt(a[:, 0] * a[:, 0] + a[:, 1] * a[:, 1])


def _unit(d: np.ndarray, dist: np.ndarray) -> np.ndarray:
    """d / dist row by row; where two centres coincide (dist 0), straight up (0, 1), so that
    bodies placed on top of one another are still pushed apart."""
    out = d / np.where(dist > 0.0, dist, 1.0)[:, None]
    same = dist == 0.0
    if same.any():
        out[same] = (0.0, 1.0)
    return out


def _pairs_of(
    bodies: np.ndarray, P: np.ndarray, r: np.ndarray, reach: np.ndarray
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Each of ``bodies`` (a few) against every body it can reach this step: pairs (lower
    index, higher index) as one array per body, from the positions P, radii r and reaches."""
    fa, fb = [], []
    for k in bodies.tolist():
        near = _norm(P - P[k]) <= r + r[k] + reach + reach[k]
        near[k] = False
        j = np.flatnonzero(near)
        fa.append(np.minimum(j, k))
        fb.append(np.maximum(j, k))
    return fa, fb


def _sorted_unique(a: np.ndarray) -> np.ndarray:
    """``np.unique(a)`` for integers: sorted, without repeats (a sort and a mask; numpy 2's
    np.unique hashes first, several times slower on the ~10^4 keys of a pile)."""
    s = np.sort(a)
    if len(s) > 1:
        s = s[np.concatenate(([True], s[1:] != s[:-1]))]
    return s


def _isin_sorted(a: np.ndarray, s: np.ndarray) -> np.ndarray:
    """``np.isin(a, s)`` for ``s`` sorted without repeats: one binary search per element."""
    if not len(s):
        return np.zeros(len(a), dtype=bool)
    pos = np.searchsorted(s, a)
    pos[pos == len(s)] = 0
    return s[pos] == a


def _grid_pairs(P: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs (a < b) of points in the same or neighbouring cells of a grid of side h.

    Cells are keyed by one integer, the points sorted by key; each point looks up its own
    cell and four of its eight neighbours (the other four look it up), each a range of the
    sorted keys found by binary search. No Python loop over points.
    """
    n = len(P)
    c = np.floor(P * (1.0 / h))
    c -= c.min(axis=0)
    c = c.astype(np.int64)
    ny = int(c[:, 1].max()) + 3
    key = (c[:, 0] + 1) * ny + (c[:, 1] + 1)
    order = np.argsort(key, kind="stable")
    sk = key[order]
    offsets = np.array([0, 1, ny - 1, ny, ny + 1], dtype=np.int64)
    q = (key[:, None] + offsets[None, :]).ravel()
    lo = np.searchsorted(sk, q, "left")
    cnt = np.searchsorted(sk, q, "right") - lo
    total = int(cnt.sum())
    if not total:
        return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
    a = np.repeat(np.arange(n * 5) // 5, cnt)
    first = np.cumsum(cnt) - cnt
    b = order[np.arange(total) - np.repeat(first - lo, cnt)]
    same = np.repeat(np.arange(n * 5) % 5 == 0, cnt)
    keep = np.where(same, a < b, True)
    return a[keep], b[keep]


def deepest_overlap(
    x: np.ndarray,
    radius: np.ndarray,
    filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
) -> float:
    """The deepest overlap (length units, 0 if none) of discs at positions x (N, 2) with radii
    ``radius`` (N,): max of r_a + r_b - |x_a - x_b| over every pair (that ``filters``, arrays of
    group, categories and mask, lets collide), found through a grid.

    >>> deepest_overlap(np.array([[0.0, 0.0], [0.9, 0.0], [5.0, 0.0]]), np.full(3, 0.5))
    0.09999999999999998
    """
    x = np.asarray(x, dtype=float).reshape(-1, 2)
    radius = np.broadcast_to(np.asarray(radius, dtype=float), (len(x),))
    if len(x) < 2:
        return 0.0
    a, b = _grid_pairs(x, 2.0 * float(radius.max()) + 1e-300)
    if filters is not None and len(a):
        g, c, m = filters
        ok = ~((g[a] == g[b]) & (g[a] != 0)) & ((c[a] & m[b]) != 0) & ((c[b] & m[a]) != 0)
        a, b = a[ok], b[ok]
    if not len(a):
        return 0.0
    over = radius[a] + radius[b] - _norm(x[a] - x[b])
    return max(float(over.max()), 0.0)


class Collisions:
    """The contacts of a World's bodies with one another (see the module's docstring)."""

    def __init__(self) -> None:
        #: Parts (substeps) a step of a pile takes in the soft step (engine.soft).
        self.iterations = 4
        #: Seconds a touching group must stay still before it sleeps (inf: never).
        self.sleep_time = 0.5
        #: Speed (length units / s) under which a body counts as still; None: |a| dt, the
        #: speed the largest acceleration adds in one step (Chipmunk's idle speed).
        self.sleep_speed: float | None = None
        self.capped = 0  # steps whose impacts reached MAX_ROUNDS
        self._handed = np.zeros(0, dtype=np.intp)  # a crowd's bodies (``_impacts``)
        self._table: ShapeTable | None = None  # the bodies' shapes (``_shapes``)
        # What the struck bodies' search needs from ``_pairs`` (None: no pairs searched).
        self._search: tuple[np.ndarray, ...] | None = None
        self._static: tuple[Any, StaticShapes, np.ndarray, np.ndarray] | None = None
        #: After the last step, each shaped body's deepest overlap (length units).
        self._shape_over = np.zeros(0)
        self.warned = False  # the World has warned that a pile is past the solver
        self.moved = False  # whether the last step changed any body's state
        self.last_rounds = 0  # impact rounds in the last step
        self.last_overlap = 0.0  # deepest overlap left after the last step (length units)
        self._live: np.ndarray | None = None  # rows with radius > 0
        self._plain = True  # every live body has the default filter
        self._one_group = False  # every live body shares one nonzero group: no pair collides
        self._has_kin = False  # some body is kinematic (infinite mass here)
        self._kinU: np.ndarray | None = None  # which of the step's paired bodies are kinematic
        self._kin = np.zeros(0, dtype=bool)  # the World's kinematic bodies, by row
        # Warm start: the last step's resting contacts, keyed a * N + b, and their impulses.
        self._keys = np.zeros(0, dtype=np.int64)
        self._lam = np.zeros((0, 2))
        self._color_keys = np.zeros(0, dtype=np.int64)  # the last step's rows' colours, by key
        self._colors = np.zeros(0, dtype=np.int64)
        # Pairs touching after the last step (for began / ended), keyed as above.
        self._touching = np.zeros(0, dtype=np.int64)
        self._began: list[tuple[Any, ...]] = []
        self._ended: list[tuple[Any, ...]] = []
        self.still = np.zeros(0)  # (N,) seconds each body has been still
        self.asleep = np.zeros(0, dtype=bool)  # (N,)
        self._group = np.zeros(0, dtype=np.intp)  # (N,) the sleeping group of each sleeper
        self._lam_dt = 1.0
        # The step's pairs and the bodies of piles, found before the static contacts (plan).
        self._plan: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        #: The contacts of piles' bodies with faces after the last step: (World rows, faces).
        self.face_touching = (np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp))
        self._base = 0
        self.rest_speed = 0.0  # 2 dt times the largest pull in the last step
        self._P = np.zeros((0, 2))
        self.rmin = 0.0  # the smallest radius of a body that collides
        self._overlap = np.zeros(0)  # (N,) each body's deepest overlap / its radius
        self._still_speed = 0.0

    # -- bodies --------------------------------------------------------------------------------
    def changed(self, n: int) -> None:
        """Bodies were added or removed (now n): drop what was keyed by row, wake everyone."""
        self._live = None
        self._table = None
        self._keys = np.zeros(0, dtype=np.int64)
        self._lam = np.zeros((0, 2))
        self._color_keys = np.zeros(0, dtype=np.int64)
        self._touching = np.zeros(0, dtype=np.int64)
        self.wake(n)

    def grew(self, n: int) -> None:
        """Bodies were added at the end (now n): the rows before them keep their sleep and
        the last step's impulses (warm start), the new ones start awake. A new body that
        touches a sleeper wakes its group as any awake body does."""
        old = len(self.still)
        extra = n - old
        if old == 0 or extra <= 0:
            self.changed(n)
            return
        self._live = None  # the new rows may have a radius; the old ones keep their places
        self._table = None
        # Keys are a * base + b with b < old for a pair and b = old + f for face f (base: the
        # bodies and faces then); rows keep their numbers, so only the faces' b moves. The
        # mapping keeps their order, so the keys stay sorted.
        if len(self._keys) and self._base > old:
            # (The rows of bodies with shapes, keyed past old * base, start afresh.)
            disc = self._keys < old * self._base
            self._keys, self._lam = self._keys[disc], self._lam[disc]
            a, b = np.divmod(self._keys, self._base)
            b[b >= old] += extra
            self._base += extra
            self._keys = a * self._base + b
        else:
            self._keys, self._lam = np.zeros(0, dtype=np.int64), np.zeros((0, 2))
        self._color_keys = np.zeros(0, dtype=np.int64)  # coloured afresh
        a, b = np.divmod(self._touching, old)  # a * n + b for the pairs touching
        self._touching = a * n + b
        self.still = np.concatenate([self.still, np.zeros(extra)])
        self.asleep = np.concatenate([self.asleep, np.zeros(extra, dtype=bool)])
        self._group = np.concatenate([self._group, np.zeros(extra, dtype=np.intp)])

    @property
    def any_asleep(self) -> bool:
        """Whether any body sleeps."""
        return bool(self.asleep.any())

    def all_asleep(self, n: int) -> bool:
        """Whether all n bodies sleep (then a step moves nothing)."""
        asleep = self.asleep
        return len(asleep) == n and n > 0 and bool(asleep.all())

    def quiet(self) -> None:
        """A step passed with everyone asleep: no contact began or ended."""
        self._began, self._ended = [], []
        self.moved = False

    def wake(self, n: int) -> None:
        """Wake every body (the World was changed by hand)."""
        self.still = np.zeros(n)
        self.asleep = np.zeros(n, dtype=bool)
        self._group = np.zeros(n, dtype=np.intp)

    def _prepare(
        self, radius: np.ndarray, group: np.ndarray, cat: np.ndarray, mask: np.ndarray
    ) -> np.ndarray:
        live = self._live
        if live is None:
            live = self._live = np.flatnonzero(radius > 0.0)
            self.rmin = float(radius[live].min()) if len(live) else 0.0
            g, c, m = group[live], cat[live], mask[live]
            every = 0xFFFFFFFF
            self._plain = bool(np.all(g == 0) & np.all(c == every) & np.all(m == every))
            self._one_group = bool(len(g) and g[0] != 0 and np.all(g == g[0]))
        return live

    def state(self) -> tuple[Any, ...]:
        """A copy of everything the next step depends on (what a snapshot holds)."""
        return (
            self._keys.copy(),
            self._lam.copy(),
            self._lam_dt,
            self._base,
            self._touching.copy(),
            self.still.copy(),
            self.asleep.copy(),
            self._group.copy(),
            self.capped,
            self.warned,
            self._color_keys.copy(),
            self._colors.copy(),
        )

    def set_state(self, state: tuple[Any, ...]) -> None:
        """Bring back a state from ``state()``."""
        keys, lam, lam_dt, base, touching, still, asleep, group, capped, warned, ck, cv = state
        self._color_keys, self._colors = ck.copy(), cv.copy()
        self._keys, self._lam, self._lam_dt, self._base = keys.copy(), lam.copy(), lam_dt, base
        self._touching = touching.copy()
        self.still, self.asleep, self._group = still.copy(), asleep.copy(), group.copy()
        self.capped, self.warned = capped, warned

    def active(
        self,
        radius: np.ndarray,
        group: np.ndarray,
        cat: np.ndarray,
        mask: np.ndarray,
        shapes: list[Any] | None = None,
    ) -> bool:
        """Whether any pair of bodies may collide at all, or a body has a shape (whose
        contacts, with the colliders too, are the soft step's): else a step costs nothing
        here."""
        live = self._prepare(radius, group, cat, mask)
        if shapes is not None and any(s is not None and not isinstance(s, Circle) for s in shapes):
            return True
        return len(live) >= 2 and not self._one_group

    # -- the step ------------------------------------------------------------------------------
    def plan(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        x1: np.ndarray,
        v1: np.ndarray,
        A: np.ndarray,
        dt: float,
        store: Any,
        held: np.ndarray | None = None,
    ) -> np.ndarray | None:
        """Find the step's pairs and which bodies the pile's soft step takes (module text):
        their mask (N,), or None. Called before the static contacts, which leave those
        bodies to the soft step (it steps them again from the step's start). ``held`` (N,):
        bodies resting on a collider at the start (it bears their weight: a ball landing on
        one resting on a peg presses it into the peg, as into a pile)."""
        self._plan = None
        n = len(x1)
        if len(self.still) != n:
            self.wake(n)
        live = self._prepare(store.radius, store.group, store.categories, store.mask)
        shaped = self._shapes(store).shaped
        if (len(live) < 2 or self._one_group) and not shaped.any():
            return None
        if self.asleep.any():
            x1, v1 = x1.copy(), v1.copy()
            x1[self.asleep], v1[self.asleep] = x0[self.asleep], 0.0
        self._has_kin = bool(store.kinematic.any())
        self._kin = store.kinematic
        if len(live) >= 2 and not self._one_group:
            a, b = self._pairs(x0, v0, x1, v1, A, dt, live, store)
        else:
            a = b = np.zeros(0, dtype=np.intp)
            self._search = None
        if len(a) and self.asleep.any():
            a, b = self._wake_met(a, b, x1, v1, store.radius)
        island = np.zeros(n, dtype=bool)
        if shaped.any():
            # A body with a shape is always the soft step's (engine.shaped), and so is what
            # may touch it.
            island |= shaped
            with_shape = shaped[a] | shaped[b]
            island[a[with_shape]] = island[b[with_shape]] = True
        if len(a):
            # A pair that carried load in the last step rests on.
            loaded = np.zeros(len(a), dtype=bool)
            if len(self._keys):
                keys = a.astype(np.int64) * self._base + b
                pos = np.minimum(np.searchsorted(self._keys, keys), len(self._keys) - 1)
                loaded = (self._keys[pos] == keys) & (self._lam[pos, 0] > 0.0)
            # A pair that closes no faster than its rest speed while the forces press it
            # together, near enough to touch, comes to rest: a ball landing softly on one.
            d = x0[a] - x0[b]
            dist = _norm(d)
            nrm = _unit(d, dist)
            gap = dist - store.radius[a] - store.radius[b]
            closing = -_dot(v0[a] - v0[b], nrm)
            if held is not None and held.any():
                Ah = np.where(held[:, None], 0.0, A)
                press = _dot(Ah[a] - Ah[b], nrm)
            else:
                press = _dot(A[a] - A[b], nrm)
            pull = np.maximum(_norm(A[a]), _norm(A[b]))
            margin = 0.05 * np.minimum(store.radius[a], store.radius[b]) + closing.clip(0) * dt
            near = gap <= margin
            rest = near & (np.abs(closing) <= 2.0 * dt * pull) & (press < -1e-9 * pull)
            # (Overlap past the slop: balls hung touching, as in a cradle, are no pile.)
            seed = loaded | rest | (gap < -SLOP * np.minimum(store.radius[a], store.radius[b]))
            island[a[seed]] = island[b[seed]] = True
            island = self._grow(island, a, b, x0, v0, A, dt, store)
        island &= ~self.asleep  # (a sleeper beside a pile was woken above, or stays put)
        a, b = self._struck(a, b, island, dt, store)
        self._plan = (a, b, island)
        return island if island.any() else None

    def _shapes(self, store: Any) -> ShapeTable:
        """The bodies' shapes as narrowphase kinds (built again when bodies change)."""
        table = self._table
        if table is None or len(table) != len(store.radius):
            shapes = getattr(store, "shapes", None)
            if shapes is None or len(shapes) != len(store.radius):
                shapes = [None] * len(store.radius)
            table = self._table = ShapeTable(shapes, store.radius)
        return table

    def _statics(self, contacts: Contacts) -> tuple[StaticShapes, np.ndarray, np.ndarray]:
        """The colliders as narrowphase kinds, which are solid, and each collider's first
        face (what the events and filters name a shape's contact with it by)."""
        faces = contacts.faces
        if self._static is None or self._static[0] is not faces:
            cols = contacts.colliders
            solid = np.array([not c.sensor for c in cols], dtype=bool)
            first = np.full(len(cols), -1, dtype=np.intp)
            owner = faces.owner
            order = np.arange(len(owner))[::-1]
            first[owner[order]] = order
            self._static = (faces, static_shapes(cols), solid, first)
        return self._static[1], self._static[2], self._static[3]

    def _grow(
        self,
        island: np.ndarray,
        a: np.ndarray,
        b: np.ndarray,
        x0: np.ndarray,
        v0: np.ndarray,
        A: np.ndarray,
        dt: float,
        store: Any,
    ) -> np.ndarray:
        """The piles (mask ``island``) with what can reach them within the step at a speed
        their contacts can catch (a ball landing on one) joined; a faster body (a bullet)
        stays out, and meets the pile's bodies at its exact moments, as moving walls
        (``_exact``)."""
        if not len(a):
            return island
        # Only pairs that can touch within the step (their gap closes by at most the relative
        # speed's and acceleration's reach, plus a margin): a crowd falling in formation
        # beside a pile stays out of it until it lands.
        ra, rb = store.radius[a], store.radius[b]
        Ar = _norm(A[a] - A[b])
        rel = _norm(v0[a] - v0[b])
        gap = _norm(x0[a] - x0[b]) - ra - rb
        reach = rel * dt + 0.5 * Ar * dt * dt + 0.05 * np.minimum(ra, rb)
        catch = (gap <= reach) & ((rel + Ar * dt) * dt <= CATCH * (ra + rb))
        if self._has_kin:
            catch |= store.kinematic[a] | store.kinematic[b]  # moved by the game: joins
        if self.asleep.any():
            catch &= ~(self.asleep[a] | self.asleep[b])
        for _ in range(4):
            grow = (island[a] != island[b]) & catch
            if not grow.any():
                break
            island[a[grow]] = island[b[grow]] = True
        return island

    def resolve(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        x1: np.ndarray,
        v1: np.ndarray,
        A: np.ndarray,
        dt: float,
        t0: float,
        store: Any,
        contacts: Contacts | None,
        A_force: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The state after dt with every contact between bodies applied: new (x, v) arrays.

        ``A`` (N, 2): each body's acceleration along its path this step (the forces' pull
        ``A_force``, and what a static contact carried for one resting on a collider).
        Pairs of bodies that are not in a pile meet at their exact moments; the bodies of a
        pile (``plan``) are stepped again from (x0, v0) by the soft step. Bodies that meet
        no other keep (x1, v1) bit for bit.
        """
        self.moved = False
        self._began, self._ended = [], []
        self.last_rounds = 0
        self._overlap = np.zeros(0)
        self._shape_over = np.zeros(0)
        self.face_touching = (np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp))
        n = len(x1)
        plan = self._plan
        live = self._prepare(store.radius, store.group, store.categories, store.mask)
        if plan is None:
            return x1, v1
        a, b, island = plan
        asleep = self.asleep
        if asleep.any():
            # Sleeping bodies stay exactly where they were, whatever the method computed.
            x1, v1 = x1.copy(), v1.copy()
            x1[asleep], v1[asleep] = x0[asleep], 0.0
            self.moved = True
            if asleep[live].all():
                return x1, v1  # nothing touches or parts: no events either
        if self.sleep_speed is None:
            a_max = float(np.abs(A[live]).max()) if len(live) else 0.0
            self._still_speed = a_max * dt
        else:
            self._still_speed = self.sleep_speed
        P = A if A_force is None else A_force
        self.rest_speed = 2.0 * dt * float(_norm(P[live]).max())
        self._dt, self._t0 = dt, t0
        x, v = (x1, v1) if self.moved else (x1.copy(), v1.copy())
        self.moved = True
        impacts: list[tuple[np.ndarray, ...]] = []
        exact = ~(island[a] & island[b])
        kick = None
        if exact.any():
            # A chain of impacts past HANDOVER_ROUNDS among bodies under load (rows landing
            # on rows, bouncing off the floor into the next) is given to the pile instead.
            loaded = bool((_norm(P[a[exact]]) > 0.0).any())
            got = self._exact(a[exact], b[exact], island, x, v, A, P, dt, store, contacts, loaded)
            if got is None:
                handed = np.zeros(n, dtype=bool)
                handed[self._handed] = True
                handed &= ~self.asleep
                if self._has_kin:
                    handed &= ~store.kinematic
                island = self._grow(island | handed, a, b, x0, v0, A, dt, store)
                if contacts is not None and len(contacts.rest) == n:
                    contacts.rest[island] = -1  # their faces are the pile's rows now
                exact = ~(island[a] & island[b])
                got = ([], None)
                if exact.any():
                    got = self._exact(a[exact], b[exact], island, x, v, A, P, dt, store, contacts)
                assert got is not None
            impacts, kick = got
        touching = np.zeros(0, dtype=np.int64)
        pa = pb = np.zeros(0, dtype=np.intp)
        if island.any():
            if kick is not None:
                v0 = v0.copy()
                v0[island] += kick[island] / store.mass[island, None]
            touching, pa, pb = self._pile(island, a, b, x0, v0, x, v, P, dt, store, contacts)
        else:
            kept = self._asleep_rows(n, self._base)
            self._color_keys, self._colors = self._keys[kept], self._slept_colors(kept)
            self._keys, self._lam = self._keys[kept], self._lam[kept]
        # The deepest overlap of any pair (what the World warns about), resting or not, that
        # this step made or deepened: bodies put inside each other are being pushed apart.
        self._overlap = np.zeros(n)
        self.last_overlap = 0.0
        if len(a) and self._table is not None and self._table.shaped.any():
            # A shape's bounding circle says nothing of its overlaps: the soft step's rows do.
            disc = ~(self._table.shaped[a] | self._table.shaped[b])
            a, b = a[disc], b[disc]
        if len(self._shape_over) == n:
            self._overlap = self._shape_over / np.where(store.radius > 0.0, store.radius, 1.0)
            self.last_overlap = float(self._shape_over.max(initial=0.0))
        if len(a):
            R = store.radius[a] + store.radius[b]
            over = R - _norm(x[a] - x[b])
            grew = over > R - _norm(x0[a] - x0[b]) + 1e-9 * R
            deepest = max(float(over[grew].max()), 0.0) if grew.any() else 0.0
            self.last_overlap = max(self.last_overlap, deepest)
            # The overlap each body is left with, in the smaller radius of each pair: a group
            # sleeps only once it is small.
            share = over / np.minimum(store.radius[a], store.radius[b])
            np.maximum.at(self._overlap, a, share)
            np.maximum.at(self._overlap, b, share)
        self._events_of(touching, impacts, n, t0, dt)
        if self.asleep.any():
            # Sleepers stay exactly put (nothing above moves a body of infinite mass, but a
            # wall's push-out or rounding must not either).
            x[self.asleep], v[self.asleep] = x0[self.asleep], 0.0
        self._sleep_still(v, dt, live, pa, pb, contacts)
        return x, v

    def _exact(
        self,
        a: np.ndarray,
        b: np.ndarray,
        island: np.ndarray,
        x: np.ndarray,
        v: np.ndarray,
        A: np.ndarray,
        P: np.ndarray,
        dt: float,
        store: Any,
        contacts: Contacts | None,
        handover: bool = False,
    ) -> tuple[list[tuple[np.ndarray, ...]], np.ndarray | None] | None:
        """Impacts of the pairs (World rows a, b) not both in a pile, at their exact moments,
        in place on the end state (x, v): what ``_impacts`` found, for the events, and the
        impulses (N, 2) the pile's bodies took (None if none): a body of a pile meets a body
        from outside it as a moving wall (infinite mass on its free path), and takes the
        impulse in the soft step, from its start."""
        present = np.zeros(len(x), dtype=bool)
        present[a] = present[b] = True
        U = np.flatnonzero(present)
        local = np.cumsum(present) - 1  # World row -> local index, for the rows in U
        la, lb = local[a], local[b]
        X, V, AU = x[U], v[U], A[U]
        self._U = U
        self._P = P[U]
        w = 1.0 / store.mass[U]
        # A kinematic body (moved by the game) has infinite mass here: no impulse moves it.
        self._kinU = store.kinematic[U] if self._has_kin else None
        if self._kinU is not None:
            w[self._kinU] = 0.0
        walls = island[U]
        w[walls] = 0.0
        if self.asleep.any():
            w[self.asleep[U]] = 0.0  # a sleeper an awake body did not wake stays put
        r = store.radius[U]
        found = self._impacts(
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
            contacts,
            U,
            handover,
        )
        if found is None:
            # A crowd under load: nothing written back; the World rows of its bodies.
            self._handed = U[self._handed]
            return None
        impacts = found
        walled = contacts if contacts is not None and len(contacts.faces.owner) else None
        r_wall = r if self._kinU is None else np.where(self._kinU, -np.inf, r)
        if impacts and walled is not None:
            # Nothing the pairs pushed is left inside a wall (with its speed into it taken).
            # (A kinematic body is no wall's business: its radius is taken as -inf there.)
            walled.push_out_rows(X, V, r_wall, U)
        for _ in range(3):
            # The impacts are found on each body's path as a parabola to its end state: a
            # body that bounced off a wall in the step took another path before the bounce,
            # and may end inside a ball that path never met; a ball struck against a wall
            # in the step it lands there is put back out of the wall, into the ball that
            # struck it. Such pairs are moved apart (positions), their closing stopped
            # (plastic impulses), and out of the walls again, a few times.
            if not _separate(la, lb, X, V, w, r):
                break
            if walled is not None:
                walled.push_out_rows(X, V, r_wall, U)
        kick = None
        if walls.any() and impacts:
            kick = np.zeros((len(x), 2))
            for pa, pb, _, _, J, _ in impacts:
                np.add.at(kick, U[pa[walls[pa]]], J[walls[pa]])
                np.add.at(kick, U[pb[walls[pb]]], -J[walls[pb]])
            X[walls], V[walls] = x[U[walls]], v[U[walls]]  # the soft step moves those
        x[U], v[U] = X, V
        # Events are given in World rows.
        return [(U[pa], U[pb], pt, nrm, J, t) for pa, pb, pt, nrm, J, t in impacts], kick

    def _pile(
        self,
        island: np.ndarray,
        a: np.ndarray,
        b: np.ndarray,
        x0: np.ndarray,
        v0: np.ndarray,
        x: np.ndarray,
        v: np.ndarray,
        P: np.ndarray,
        dt: float,
        store: Any,
        contacts: Contacts | None,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Step the bodies of the pile (``island``) again from (x0, v0) by the soft step
        (engine.soft), with every contact among them and with the faces they can reach, in
        place on (x, v). Returns the keys (a * N + b) of pairs touching now, and the pairs
        that pressed (for sleep)."""
        n = len(x)
        U = np.flatnonzero(island)
        nU = len(U)
        local = np.full(n, -1, dtype=np.intp)
        local[U] = np.arange(nU)
        table = self._shapes(store)
        shapedU = table.shaped[U]
        both = island[a] & island[b]
        pa, pb = a[both], b[both]
        with_shape = table.shaped[pa] | table.shaped[pb]
        sa, sb = pa[with_shape], pb[with_shape]  # pairs with a shape: engine.shaped
        pa, pb = pa[~with_shape], pb[~with_shape]
        la, lb = local[pa], local[pb]
        r = store.radius[U]
        x0U, v0U = x0[U], v0[U]
        # Pairs: A the lower row, B the higher; the normal from A to B.
        d = x0U[lb] - x0U[la]
        dist = _norm(d)
        nrm = _unit(d, dist)
        sep = dist - r[la] - r[lb]
        mu, e = store.friction[U], store.restitution[U]
        rows_a, rows_b = [la], [lb]
        normals, seps = [nrm], [sep]
        fric, rest = [mu[la] * mu[lb]], [e[la] * e[lb]]
        slops = [SLOP * np.minimum(r[la], r[lb])]
        n_faces = 0 if contacts is None else len(contacts.faces.owner)
        base = n + n_faces
        keys = [pa.astype(np.int64) * base + pb]
        fa = fk = np.zeros(0, dtype=np.intp)
        speed = _norm(v0U) + _norm(P[U]) * dt
        kin = store.kinematic[U]
        if n_faces and contacts is not None:
            # Faces within reach of a body this step: the static world is B, the slot nU.
            fa, fn, fg, fmu, fk = _face_rows(contacts, x0U, r, 0.05 * r + speed * dt)
            ok = ~kin[fa] & ~shapedU[fa]  # walls do not hold what the game moves
            if contacts.faces.filters is not None:
                ok &= contacts.allowed(U[fa], fk)  # faces a body's filter does not meet
            fa, fn, fg, fmu, fk = fa[ok], fn[ok], fg[ok], fmu[ok], fk[ok]
            rows_a.append(np.full(len(fa), nU))
            rows_b.append(fa)
            normals.append(fn)
            seps.append(fg)
            fric.append(mu[fa] * fmu)
            rest.append(e[fa] * contacts.faces.e[fk])
            slops.append(SLOP * r[fa])
            keys.append(U[fa].astype(np.int64) * base + n + fk)
        m_disc = sum(len(k) for k in keys)
        # Bodies with shapes (engine.shaped): a row a point of each manifold, keyed past the
        # discs' keys (n * base), by pair and point, or by body, static shape and point.
        s_off = np.int64(n) * base
        margin = float((0.05 * r + speed * dt).max()) if nU else 0.0
        m_pairs = 0
        if len(sa):
            ia, ib, sn, ss, slot = pair_rows(table, sa, sb, x0, margin)
            m_pairs = len(ia)
            rows_a.append(local[ia])
            rows_b.append(local[ib])
            normals.append(sn)
            seps.append(ss)
            fric.append(store.friction[ia] * store.friction[ib])
            rest.append(store.restitution[ia] * store.restitution[ib])
            slops.append(SLOP * np.minimum(store.radius[ia], store.radius[ib]))
            keys.append(s_off + (ia.astype(np.int64) * n + ib) * 2 + slot)
        s_rows = s_col = np.zeros(0, dtype=np.intp)
        if n_faces and contacts is not None and (shapedU & ~kin).any():
            statics, solid, first = self._statics(contacts)
            mine = U[shapedU & ~kin]
            s_rows, s_col, sn, ss, skey = static_rows(table, mine, x0, statics, solid, margin)
            if contacts.faces.filters is not None:
                ok = contacts.allowed(s_rows, first[s_col])
                s_rows, s_col, sn, ss, skey = s_rows[ok], s_col[ok], sn[ok], ss[ok], skey[ok]
            rows_a.append(np.full(len(s_rows), nU))
            rows_b.append(local[s_rows])
            normals.append(sn)
            seps.append(ss)
            cols = contacts.colliders
            fric.append(store.friction[s_rows] * np.array([cols[k].friction for k in s_col]))
            rest.append(store.restitution[s_rows] * np.array([cols[k].restitution for k in s_col]))
            slops.append(SLOP * store.radius[s_rows])
            keys.append(s_off + 2 * np.int64(n) * n + s_rows.astype(np.int64) * 2**40 + skey)
        ra, rb = np.concatenate(rows_a), np.concatenate(rows_b)
        nv = np.concatenate(normals)
        sep_all = np.concatenate(seps)
        key = np.concatenate(keys)
        static = ra == nU
        w = np.append(1.0 / store.mass[U], 0.0)
        moves = np.append(~kin, False)
        w[:-1][~moves[:-1]] = 0.0
        # Warm start: the last step's impulses of the same contacts, per part of this step.
        lam = np.zeros((len(key), 2))
        if len(self._keys) and base == self._base:
            pos = np.minimum(np.searchsorted(self._keys, key), len(self._keys) - 1)
            same = self._keys[pos] == key
            lam[same] = self._lam[pos[same]] * (dt / (self._lam_dt * self.iterations))
        rows = Rows(
            ra,
            rb,
            nv[:, 0] + 1j * nv[:, 1],
            sep_all,
            np.concatenate(fric),
            np.concatenate(rest),
            lam[:, 0].copy(),
            lam[:, 1].copy(),
            static,
        )
        rmin = float(r.min())
        slop_rows = np.concatenate(slops)
        # Each row keeps its colour from the last step where its key did (engine.coloring).
        prior = np.full(len(key), -1, dtype=np.int64)
        if len(self._color_keys) and base == self._base:
            pos = np.minimum(np.searchsorted(self._color_keys, key), len(self._color_keys) - 1)
            same = self._color_keys[pos] == key
            prior[same] = self._colors[pos[same]]
        solver = SoftStep(
            rows,
            w,
            moves,
            dt,
            self.iterations,
            push_speed=PUSH * rmin,
            threshold=THRESH * self.rest_speed,
            slop=slop_rows,
            prior=prior,
        )
        acc = np.append(P[U, 0] + 1j * P[U, 1], 0.0)
        acc[:-1][~moves[:-1]] = 0.0
        X, V = solver.run(
            np.append(x0U[:, 0] + 1j * x0U[:, 1], 0.0),
            np.append(v0U[:, 0] + 1j * v0U[:, 1], 0.0),
            acc,
        )
        Xr = np.stack([X[:nU].real, X[:nU].imag], axis=1)
        Vr = np.stack([V[:nU].real, V[:nU].imag], axis=1)
        # A kinematic body goes where the game sends it, whatever it touched.
        if not kin.any():
            Vr = _dissipative(Vr, v0U + P[U] * dt, store.mass[U])
        if kin.any():
            Xr[kin], Vr[kin] = x[U][kin], v[U][kin]
        if n_faces and contacts is not None:
            # No disc of the pile ends inside a wall: the soft contacts give a little. (A
            # shape is held out by its rows alone; a kinematic body is no wall's business.)
            if PUSHOUT:
                contacts.push_out_rows(Xr, Vr, np.where(kin | shapedU, -np.inf, r), U)
        x[U], v[U] = Xr, Vr
        # The impulses over the whole step, kept by key (sorted) for the next one.
        kept = self._asleep_rows(n, base)
        key = np.concatenate([key, self._keys[kept]])
        lam = np.concatenate(
            [np.stack([rows.lam_n, rows.lam_t], axis=1) * self.iterations, self._lam[kept]]
        )
        color = np.concatenate([solver.color, self._slept_colors(kept)])
        order = np.argsort(key)
        self._keys, self._lam = key[order], lam[order]
        self._lam_dt, self._base = dt, base
        self._color_keys, self._colors = self._keys, color[order]
        # Which contacts touch now: the pairs for the events and sleep, the faces too.
        m = len(pa)
        gap = _norm(Xr[lb] - Xr[la]) - r[la] - r[lb]
        touch = gap <= SLOP * np.minimum(r[la], r[lb]) + TOUCH
        pressed = solver.total[:m] > 0.0
        hold = touch | pressed
        # Every other row's gap now: its gap at the start plus the bodies' moves along it.
        moved = np.append(Xr - x0U, [[0.0, 0.0]], axis=0)
        now = sep_all + _dot(moved[rb] - moved[ra], nv)
        held_rows = (now <= slop_rows + TOUCH) | (solver.total > 0.0)
        f = slice(m, m_disc)
        self.face_touching = (U[fa[held_rows[f]]], fk[held_rows[f]])
        touching = pa[hold].astype(np.int64) * n + pb[hold]
        # Sleep joins bodies as near as ``_wake_met`` wakes them by: a group falls asleep
        # whole, or a body left awake beside it would wake it again at once.
        near = gap <= 0.05 * np.minimum(r[la], r[lb])
        near_a, near_b = pa[near], pb[near]
        self._shape_over = np.zeros(n)
        if m_disc < len(key) - int(kept.sum()):
            # The rows of shapes: touching pairs and faces for the events, sleep joined by
            # them, and their overlaps (a shape's bounding circle says nothing of them).
            sp = slice(m_disc, m_disc + m_pairs)
            st = slice(m_disc + m_pairs, len(ra))
            ua, ub = U[ra[sp]], U[rb[sp]]
            hs = held_rows[sp]
            tk = _sorted_unique(ua[hs].astype(np.int64) * n + ub[hs])
            touching = np.concatenate([touching, tk])
            near_s = now[sp] <= 0.05 * np.minimum(store.radius[ua], store.radius[ub])
            near_a = np.concatenate([near_a, ua[near_s]])
            near_b = np.concatenate([near_b, ub[near_s]])
            hf = held_rows[st]
            if contacts is not None and hf.any():
                first = self._statics(contacts)[2]
                self.face_touching = (
                    np.concatenate([self.face_touching[0], s_rows[hf]]),
                    np.concatenate([self.face_touching[1], first[s_col[hf]]]),
                )
            over = np.maximum(-now[m_disc:], 0.0)
            body = np.concatenate([ua, ub, U[rb[st]]])
            depth = np.concatenate([over[:m_pairs], over[:m_pairs], over[m_pairs:]])
            np.maximum.at(self._shape_over, body, depth)
        return touching, near_a, near_b

    def _asleep_rows(self, n: int, base: int) -> np.ndarray:
        """Which of the last step's contact rows (``_keys``) join only sleepers: they keep
        their impulses while the group sleeps, so that it wakes holding its weight (without
        them a woken pile would sag for a step and ring)."""
        keys = self._keys
        if not len(keys) or base != self._base or len(self.asleep) != n:
            return np.zeros(len(keys), dtype=bool)
        disc = keys < n * base  # the rows of bodies with shapes are keyed past those
        a, b = np.divmod(np.where(disc, keys, 0), base)
        face = b >= n
        return disc & self.asleep[a] & (face | self.asleep[np.where(face, 0, b)])

    def _slept_colors(self, kept: np.ndarray) -> np.ndarray:
        """The colours of the kept rows, where the cache still has them (else -1)."""
        if len(self._color_keys) == len(self._keys) and len(self._colors) == len(self._keys):
            return self._colors[kept]
        return np.full(int(kept.sum()), -1, dtype=np.int64)

    # -- finding pairs ---------------------------------------------------------------------------
    def _pairs(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        x1: np.ndarray,
        v1: np.ndarray,
        A: np.ndarray,
        dt: float,
        live: np.ndarray,
        store: Any,
    ) -> tuple[np.ndarray, np.ndarray]:
        """World rows (a < b) of the pairs that may touch within the step or are near enough
        to rest on each other: a grid for the many, every body for the fast few."""
        P = x1[live]
        r = store.radius[live]
        # How far a centre can be from its end position during the step: its speed on a
        # parabola peaks at an end, and a bounce off a wall never speeds it up.
        speed = np.maximum(_norm(v0[live]), _norm(v1[live])) + _norm(A[live]) * dt
        reach = speed * dt + 0.05 * r  # plus a margin for resting contacts about to close
        rmax = float(r.max())
        # The grid's cells hold a body's reach: up to a radius, or to what all but the
        # fastest 2% reach (a falling crowd), at most four radii. Faster bodies, few, are
        # tested against everyone.
        fast = reach > rmax
        if fast.any():
            cap = min(
                float(
                    np.partition(reach, int(0.98 * (len(reach) - 1)))[int(0.98 * (len(reach) - 1))]
                ),
                4.0 * rmax,
            )
            fast = reach > max(rmax, cap)
        slow_reach = float(reach[~fast].max()) if (~fast).any() else 0.0
        h = 2.0 * (rmax + slow_reach)
        span = float((P.max(axis=0) - P.min(axis=0)).max())
        h = max(h, span / 2.0**30)  # keeps cell keys within int64
        ia, ib = _grid_pairs(P, h)
        # Each pair as (lower row, higher row): one key per pair, step after step (the warm
        # start and the events find it by that key), and no pair listed twice below.
        ia, ib = np.minimum(ia, ib), np.maximum(ia, ib)
        F = np.flatnonzero(fast)
        if len(F):
            # Fast bodies against every body (few of them; a grid of their size would make
            # every cell hold everyone).
            fa, fb = _pairs_of(F, P, r, reach)
            ia = np.concatenate([ia, *fa])
            ib = np.concatenate([ib, *fb])
            key = _sorted_unique(ia.astype(np.int64) * len(P) + ib)
            ia, ib = key // len(P), key % len(P)
        if len(ia):
            D = P[ia] - P[ib]
            far = r[ia] + r[ib] + reach[ia] + reach[ib]
            keep = _dot(D, D) <= far * far
            ia, ib = ia[keep], ib[keep]
        # What the struck bodies' search needs, once the piles are known (``_struck``).
        self._search = (P, r, v0[live], v1[live], A[live], reach, live)
        return self._rows_of(ia, ib, live, store)

    def _struck(
        self, a: np.ndarray, b: np.ndarray, island: np.ndarray, dt: float, store: Any
    ) -> tuple[np.ndarray, np.ndarray]:
        """The pairs (a, b) with those of bodies not in a pile that an impact may send off
        faster than their own speed reaches (``_struck_pairs``); a pile's bodies meet what
        they meet as contacts of the soft step, which needs no such search."""
        if self._search is None:
            return a, b
        P, r, v0l, v1l, Al, reach, live = self._search
        free = ~island[live]
        if not free.any() or not len(a):
            return a, b
        where = np.full(len(island), -1, dtype=np.intp)
        where[live] = np.arange(len(live))
        ia, ib = where[a], where[b]
        both = free[ia] & free[ib]
        ja, jb = self._struck_pairs(
            ia[both], ib[both], P, r, v0l, v1l, Al, reach, dt, live, store, free
        )
        if len(ja) == int(both.sum()):
            return a, b  # nobody is struck faster than it reaches: the same pairs
        na, nb = self._rows_of(ja, jb, live, store)
        keys = _sorted_unique(
            np.concatenate([a, na]).astype(np.int64) * len(island) + np.concatenate([b, nb])
        )
        return keys // len(island), keys % len(island)

    def _rows_of(
        self, ia: np.ndarray, ib: np.ndarray, live: np.ndarray, store: Any
    ) -> tuple[np.ndarray, np.ndarray]:
        """Pairs of places in ``live`` as World rows, less those that never collide."""
        a, b = live[ia], live[ib]
        if self._has_kin and len(a):
            # Two bodies the game moves pass through each other (as in pymunk).
            kin = store.kinematic
            ok = ~(kin[a] & kin[b])
            a, b = a[ok], b[ok]
        if not self._plain and len(a):
            g, c, m = store.group, store.categories, store.mask
            ok = ~((g[a] == g[b]) & (g[a] != 0))
            ok &= ((c[a] & m[b]) != 0) & ((c[b] & m[a]) != 0)
            a, b = a[ok], b[ok]
        return a, b

    def _struck_pairs(
        self,
        ia: np.ndarray,
        ib: np.ndarray,
        P: np.ndarray,
        r: np.ndarray,
        v0: np.ndarray,
        v1: np.ndarray,
        A: np.ndarray,
        reach: np.ndarray,
        dt: float,
        live: np.ndarray,
        store: Any,
        free: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The pairs (ia, ib) (places in live) with those of bodies an impact may send farther
        than their own speed reaches: a light ball struck by a fast one flies off at up to
        (1 + e) times their closing speed, and must meet the balls beyond it, not pass them.

        An impact changes a body's velocity by at most (1 + e) w_a / (w_a + w_b) times the
        pair's closing speed (w = 1 / m; a kinematic body, w = 0, gains nothing), and that
        is at most their relative speed over the step, |v_a - v_b| at its start or end plus
        |A_a - A_b| dt, plus what impacts gave either. A body whose gain over the step passes
        the margin its reach already has (5% of its radius) is searched again against every
        body with the larger reach, and so on down a chain of such impacts (three links). A
        crowd falling together, or a pile, has small relative speeds and gains nothing here.
        """
        w = 1.0 / store.mass[live]
        if self._has_kin:
            w[store.kinematic[live]] = 0.0
        e = store.restitution[live]
        got = np.zeros(len(P))  # what impacts may add to each body's speed
        done = np.zeros(len(P), dtype=bool)
        for _ in range(3):
            rel = np.maximum(_norm(v0[ia] - v0[ib]), _norm(v1[ia] - v1[ib]))
            rel += _norm(A[ia] - A[ib]) * dt + got[ia] + got[ib]
            tot = w[ia] + w[ib]
            close = (1.0 + e[ia] * e[ib]) * rel / np.where(tot > 0.0, tot, 1.0)
            gain = np.zeros(len(P))
            np.maximum.at(gain, ia, close * w[ia])
            np.maximum.at(gain, ib, close * w[ib])
            grown = np.flatnonzero((gain * dt > 0.05 * r) & ~done & free)
            if not len(grown):
                break
            done[grown] = True
            got[grown] = gain[grown]
            reach = reach.copy()
            reach[grown] += gain[grown] * dt
            fa, fb = _pairs_of(grown, P, r, reach)
            key = _sorted_unique(
                np.concatenate([ia, *fa]).astype(np.int64) * len(P) + np.concatenate([ib, *fb])
            )
            ia, ib = key // len(P), key % len(P)
        return ia, ib

    # -- impacts ---------------------------------------------------------------------------------
    def _impacts(
        self,
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
        contacts: Contacts | None = None,
        U: np.ndarray | None = None,
        handover: bool = False,
    ) -> list[tuple[np.ndarray, ...]] | None:
        """Resolve the step's impacts in time order, in place on the end state (X, V).

        ``handover``: past ``HANDOVER_ROUNDS`` rounds, give up instead (return None, with
        the bodies of every impact found or left in ``self._handed``, local): a crowd under
        load (rows landing on rows) is the pile's, not a chain of exact impacts."""
        nU = len(X)
        R = r[la] + r[lb]
        # Pairs that close at all within the step can meet (``_toi`` finds when, if ever).
        P = self._P
        Vr = V[la] - V[lb]
        Ar = A[la] - A[lb]
        can = (_norm(Vr) + _norm(Ar) * dt) > 0.0
        if not can.any():
            return []
        pa, pb, pR = la, lb, R
        ts = np.zeros(nU)  # when each body's current path starts
        toi = np.full(len(pa), np.inf)
        todo = can  # the others are searched once a body of theirs changes path
        found: list[tuple[np.ndarray, ...]] = []
        pid = np.arange(len(pa))
        # A body sent off by an impact may meet a wall on its new path within the step: those
        # impacts (face_t: when, face_f: which face) take their place in the time order too.
        walls = contacts is not None and len(contacts.faces.owner) > 0
        face_t = np.full(nU, np.inf)
        face_f = np.zeros(nU, dtype=np.intp)
        face_n = np.zeros((nU, 2))
        changed = np.zeros(nU, dtype=bool)
        for k in range(HANDOVER_ROUNDS if handover else MAX_ROUNDS):
            idx = np.flatnonzero(todo)
            if len(idx):
                toi[idx] = self._toi(pa[idx], pb[idx], pR[idx], X, V, A, ts, dt)
                todo[idx] = False
            if walls and changed.any():
                assert contacts is not None
                moved = np.flatnonzero(changed)
                face_t[moved], face_f[moved], face_n[moved] = _wall_hits(
                    contacts, moved, X, V, A, r, ts, dt, self._P[moved], U
                )
            hit = np.isfinite(toi)
            if not hit.any() and not np.isfinite(face_t).any():
                break
            self.last_rounds = k + 1
            # The pairs that come first for both their bodies (ties: the lower pair index),
            # and before either body meets a wall.
            h = np.flatnonzero(hit)
            best = face_t.copy()
            np.minimum.at(best, pa[h], toi[h])
            np.minimum.at(best, pb[h], toi[h])
            first = np.full(nU, len(pa))
            ca = h[toi[h] == best[pa[h]]]
            cb = h[toi[h] == best[pb[h]]]
            np.minimum.at(first, pa[ca], pid[ca])
            np.minimum.at(first, pb[cb], pid[cb])
            s = h[(first[pa[h]] == pid[h]) & (first[pb[h]] == pid[h])]
            s = s[(toi[s] < face_t[pa[s]]) & (toi[s] < face_t[pb[s]])]
            # A body whose wall comes before any pair of its own.
            wall = np.flatnonzero(np.isfinite(face_t) & (face_t <= best))
            changed = np.zeros(nU, dtype=bool)
            if len(s):
                found.append(self._bounce(pa[s], pb[s], toi[s], X, V, A, w, r, e, mu, dt))
                ts[pa[s]] = toi[s]
                ts[pb[s]] = toi[s]
                changed[pa[s]] = changed[pb[s]] = True
            if len(wall):
                assert contacts is not None
                self._wall_bounce(
                    contacts,
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
                )
                ts[wall] = face_t[wall]
                changed[wall] = True
            # Every pair of a body whose path changed is searched again, and its walls.
            face_t[changed] = np.inf
            again = changed[pa] | changed[pb]
            toi[again] = np.inf
            todo |= again
        else:
            if handover:
                involved = np.zeros(nU, dtype=bool)
                for fa, fb, *_ in found:
                    involved[fa] = involved[fb] = True
                idx = np.flatnonzero(todo)
                if len(idx):
                    toi[idx] = self._toi(pa[idx], pb[idx], pR[idx], X, V, A, ts, dt)
                hit = np.isfinite(toi)
                involved[pa[hit]] = involved[pb[hit]] = True
                self._handed = involved
                return None
            # Impacts are left: rather than let the bodies fly through each other on their
            # paths, each body with an impact still to come stops at the earliest one left,
            # where its path is then (no overlap yet), and goes on from there next step. Only
            # those bodies lose the rest of this step's motion; their velocities keep what
            # the forces gave them over the whole step, so momentum changes by exactly the
            # forces' impulse, as in every other step.
            self.capped += 1
            idx = np.flatnonzero(todo)
            if len(idx):
                toi[idx] = self._toi(pa[idx], pb[idx], pR[idx], X, V, A, ts, dt)
            hit = np.isfinite(toi)
            left = np.zeros(nU, dtype=bool)
            left[pa[hit]] = left[pb[hit]] = True
            left |= np.isfinite(face_t)
            t_first = min(float(toi[hit].min()) if hit.any() else math.inf, float(face_t.min()))
            if math.isfinite(t_first):
                # A body resting against a stopped one (no impact of theirs pending) would
                # run into it: it stops too, and so on along the contacts.
                T = np.full(nU, t_first)
                end = self._state_at(np.arange(nU), T, X, V, A, dt)[0]
                for _ in range(nU):
                    one = left[pa] != left[pb]
                    if not one.any():
                        break
                    ia, ib = pa[one], pb[one]
                    qa = np.where(left[ia, None], end[ia], X[ia])
                    qb = np.where(left[ib, None], end[ib], X[ib])
                    meet = _norm(qa - qb) < pR[one]
                    if not meet.any():
                        break
                    left[ia[meet]] = left[ib[meet]] = True
                i = np.flatnonzero(left)
                X[i] = end[i]
            plastic = hit & (e[pa] * e[pb] <= COLLAPSE_E)
            if plastic.any():
                # An inelastic collapse (impacts without end, closing ever slower: a light
                # ball between heavy ones, e small) would meet the cap again every step, and
                # stop there: its pairs take their plastic impacts all at once instead.
                _plastic(pa[plastic], pb[plastic], X, V, w, 2.0 * dt * float(_norm(P).max()))
        return found

    @staticmethod
    def _state_at(
        i: np.ndarray, t: np.ndarray, X: np.ndarray, V: np.ndarray, A: np.ndarray, dt: float
    ) -> tuple[np.ndarray, np.ndarray]:
        """Position and velocity of local bodies i at times t, on the paths ending at (X, V)."""
        s = (dt - t)[:, None]
        Ai = A[i]
        return X[i] - V[i] * s + Ai * (0.5 * s * s), V[i] - Ai * s

    def _toi(
        self,
        pa: np.ndarray,
        pb: np.ndarray,
        R: np.ndarray,
        X: np.ndarray,
        V: np.ndarray,
        A: np.ndarray,
        ts: np.ndarray,
        dt: float,
    ) -> np.ndarray:
        """Time of the first impact (closing faster than its rest speed) of each pair, or inf."""
        start = np.maximum(ts[pa], ts[pb])
        xa, va = self._state_at(pa, start, X, V, A, dt)
        xb, vb = self._state_at(pb, start, X, V, A, dt)
        D, Vr, Ar = xa - xb, va - vb, A[pa] - A[pb]
        tau = disc_hits(D, Vr, Ar, np.zeros_like(D), R, dt - start)
        t = start + tau
        ok = np.flatnonzero(np.isfinite(tau))
        if len(ok):
            # Closing speed at the moment of contact: a slow one is a contact at rest.
            T = tau[ok, None]
            d = D[ok] + Vr[ok] * T + Ar[ok] * (0.5 * T * T)
            dn = np.maximum(_norm(d), 1e-300)
            u = -_dot(Vr[ok] + Ar[ok] * T, d) / dn
            # Only rounding: two discs that an inelastic impact left moving together close
            # at ~1e-16 of their speed, which is no impact. (A pair closing slowly under
            # the forces, to rest on each other, is a pile's: ``plan`` gave it to the soft
            # step; any other meeting is an impact, however slow.)
            speed = _norm(va[ok]) + _norm(vb[ok])
            t[ok[u <= 1e-12 * speed]] = np.inf
        return t

    def _bounce(
        self,
        pa: np.ndarray,
        pb: np.ndarray,
        t: np.ndarray,
        X: np.ndarray,
        V: np.ndarray,
        A: np.ndarray,
        w: np.ndarray,
        r: np.ndarray,
        e: np.ndarray,
        mu: np.ndarray,
        dt: float,
    ) -> tuple[np.ndarray, ...]:
        """Apply the impulses of impacts (pa, pb) at times t; return them for the events."""
        xa, va = self._state_at(pa, t, X, V, A, dt)
        xb, vb = self._state_at(pb, t, X, V, A, dt)
        d = xa - xb
        # hypot, not sqrt(d.d): centres 1e-200 apart would square to 0; coincident ones
        # part straight up (_unit).
        nrm = _unit(d, np.hypot(d[:, 0], d[:, 1]))
        vr = va - vb
        vn = _dot(vr, nrm)  # < 0: closing
        wsum = w[pa] + w[pb]
        J = -(1.0 + e[pa] * e[pb]) * vn / wsum
        # Friction: up to mu J against the tangential relative velocity, never reversing it.
        tang = vr - nrm * vn[:, None]
        vt = _norm(tang)
        Jt = np.minimum(mu[pa] * mu[pb] * J, vt / wsum)
        tdir = tang / np.where(vt > 0.0, vt, 1.0)[:, None]
        P = nrm * J[:, None] - tdir * Jt[:, None]  # impulse on a; -P on b
        dva, dvb = P * w[pa, None], -P * w[pb, None]
        rem = (dt - t)[:, None]
        V[pa] += dva
        V[pb] += dvb
        X[pa] += dva * rem
        X[pb] += dvb * rem
        return pa, pb, xb + nrm * r[pb, None], nrm, P, t

    def _wall_bounce(
        self,
        contacts: Contacts,
        i: np.ndarray,
        t: np.ndarray,
        f: np.ndarray,
        nrm: np.ndarray,
        X: np.ndarray,
        V: np.ndarray,
        A: np.ndarray,
        w: np.ndarray,
        r: np.ndarray,
        e: np.ndarray,
        mu: np.ndarray,
        dt: float,
    ) -> None:
        """Bounce local bodies i off faces f at times t, as the static contacts do: the normal
        speed v_n becomes -e v_n and friction takes up to mu (1 + e) |v_n| off the tangential
        speed, never reversing it (e, mu: the body's times the face's)."""
        faces = contacts.faces
        x, v = self._state_at(i, t, X, V, A, dt)
        vn = np.minimum(_dot(v, nrm), 0.0)
        ee, mm = e[i] * faces.e[f], mu[i] * faces.mu[f]
        tang = v - nrm * _dot(v, nrm)[:, None]
        speed_t = _norm(tang)
        keep = np.maximum(speed_t + mm * (1.0 + ee) * vn, 0.0)
        scale = keep / np.where(speed_t > 0.0, speed_t, 1.0)
        v_new = tang * scale[:, None] - nrm * (ee * vn)[:, None]
        dv = v_new - v
        V[i] += dv
        X[i] += dv * (dt - t)[:, None]
        U = self._U
        contacts.record(U[i], faces.owner[f], x - nrm * r[i, None], nrm, dv, self._t0 + t)

    # -- events ----------------------------------------------------------------------------------
    def _events_of(
        self,
        keys: np.ndarray,
        impacts: list[tuple[np.ndarray, ...]],
        n: int,
        t0: float,
        dt: float,
    ) -> None:
        """Began: each impact, and each pair at rest touching now that did not before; ended:
        each impact whose pair no longer touches, and each pair that touched and no longer
        does. Held as (rows, other rows, points, normals, impulses, times) arrays."""
        keys = _sorted_unique(keys)
        before = self._touching
        self._touching = keys
        if not impacts and np.array_equal(keys, before):
            return  # the same pairs touch as before: nothing began or ended
        struck = np.zeros(0, dtype=np.int64)
        if impacts:
            for ga, gb, point, nrm, P, tau in impacts:  # (World rows)
                t = t0 + tau
                self._began.append((ga, gb, point, nrm, P, t))
                k = ga.astype(np.int64) * n + gb
                struck = np.concatenate([struck, k])
                apart = ~_isin_sorted(k, keys)
                if apart.any():
                    self._ended.append(
                        (ga[apart], gb[apart], point[apart], nrm[apart], P[apart], t[apart])
                    )
        struck = _sorted_unique(struck)
        new = keys[~_isin_sorted(keys, before) & ~_isin_sorted(keys, struck)]
        gone = before[~_isin_sorted(before, keys) & ~_isin_sorted(before, struck)]
        for which, sel in ((self._began, new), (self._ended, gone)):
            if len(sel):
                zero = np.zeros((len(sel), 2))
                which.append((sel // n, sel % n, None, zero, zero, np.full(len(sel), t0 + dt)))

    @property
    def began(self) -> list[tuple[int, int, Any, Any, Any, float]]:
        """Contacts between bodies that began in the last step: (row, other row, point, normal
        toward row, impulse on row, time) each; point None where it is taken from the state."""
        return _unpack(self._began)

    @property
    def ended(self) -> list[tuple[int, int, Any, Any, Any, float]]:
        """Contacts between bodies that ended in the last step, as ``began``."""
        return _unpack(self._ended)

    # -- sleep -----------------------------------------------------------------------------------
    def _wake_met(
        self, a: np.ndarray, b: np.ndarray, x: np.ndarray, v: np.ndarray, radius: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Drop pairs of two sleepers; wake the group of a sleeper an awake body meets."""
        asleep = self.asleep
        sa, sb = asleep[a], asleep[b]
        mixed = np.flatnonzero(sa != sb)
        if len(mixed):
            awake = np.where(sa[mixed], b[mixed], a[mixed])
            sleeper = np.where(sa[mixed], a[mixed], b[mixed])
            # An awake body that moves near a sleeper, or touches it at any speed, wakes its
            # group (a sleeper pushed while asleep would be put back every step).
            ra, rs = radius[awake], radius[sleeper]
            touching = _norm(x[awake] - x[sleeper]) <= ra + rs + 0.05 * np.minimum(ra, rs)
            moving = (_norm(v[awake]) > self._still_speed) | touching
            if moving.any():
                sleeper = sleeper[moving]
                groups = _sorted_unique(self._group[sleeper])
                woken = asleep & _isin_sorted(self._group, groups)
                asleep[woken] = False
                self.still[woken] = 0.0
        # The pairs of two sleepers left asleep are dropped (after the waking: a woken
        # group's own pairs are its contacts this step).
        keep = ~(asleep[a] & asleep[b])
        return a[keep], b[keep]

    def _sleep_still(
        self,
        v: np.ndarray,
        dt: float,
        live: np.ndarray,
        pa: np.ndarray,
        pb: np.ndarray,
        contacts: Contacts | None,
    ) -> None:
        """Count how long each body has been still; put to sleep each group (bodies resting
        on one another, or one resting on a collider) that has been still for sleep_time."""
        if not math.isfinite(self.sleep_time):
            return
        still = self.still
        slow = _norm(v[live]) <= self._still_speed
        still[live] = np.where(slow, still[live] + dt, 0.0)
        asleep = self.asleep
        ready = (still >= self.sleep_time) & ~asleep
        if self._has_kin:
            # A body the game moves never sleeps, nor does a group it touches.
            ready &= ~self._kin
        if len(self._overlap) == len(ready):
            # ... and overlapping by at most SLEEP_OVERLAP of its radius.
            ready &= self._overlap <= SLEEP_OVERLAP
        # Who may sleep: a body in a resting pair, or one resting on a collider; a body in
        # flight never does, however slow.
        member = np.zeros(len(v), dtype=bool)
        member[pa] = member[pb] = True
        member[self.face_touching[0]] = True  # a pile's body resting on a wall alone
        if contacts is not None and len(contacts.rest) == len(v):
            # Held still on a collider by friction (exactly still: a slow frictionless puck
            # glides on).
            on = np.zeros(len(v), dtype=bool)
            on[live] = (contacts.rest[live] >= 0) & (v[live, 0] == 0.0) & (v[live, 1] == 0.0)
            member |= on
        member &= ~asleep
        if not (member & ready).any():
            return
        # Groups: connected pieces of the graph of resting pairs among awake bodies (each
        # body takes the smallest label of its neighbours, then labels follow labels).
        keep = ~asleep[pa] & ~asleep[pb]
        pa, pb = pa[keep], pb[keep]
        label = np.arange(len(v))
        while len(pa):
            low = np.minimum(label[pa], label[pb])
            new = label.copy()
            np.minimum.at(new, pa, low)
            np.minimum.at(new, pb, low)
            new = new[new]
            if np.array_equal(new, label):
                break
            label = new
        # A group sleeps when every body in it is ready.
        not_ready = _sorted_unique(label[member & ~ready])
        sleepers = member & ready & ~_isin_sorted(label, not_ready)
        if sleepers.any():
            asleep[sleepers] = True
            self._group = np.where(sleepers, label, self._group)
            v[sleepers] = 0.0


def _wall_hits(
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
    its ``pull`` along the normal); time inf where none (``engine.impact`` solves for the
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
    reach = r[i] + _norm(v) * T + _norm(Ai) * (0.5 * T * T) + TOUCH
    bi, f = contacts._grid_of().pairs(x, reach)
    if len(bi) and U is not None and contacts.faces.filters is not None:
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
        n[k] = d / np.maximum(_norm(d), 1e-300)[:, None]
    # Only an impact closing faster than rest counts (a ball rolling along a floor meets it
    # at every moment).
    ok = np.flatnonzero(np.isfinite(t))
    if len(ok):
        tt = t[ok, None]
        vt = v[bi[ok]] + Ai[bi[ok]] * tt
        slow = -_dot(vt, n[ok]) <= 2.0 * dt * np.abs(_dot(pull[bi[ok]], n[ok]))
        t[ok[slow]] = np.inf
    order = np.lexsort((t, bi))  # by body, earliest first
    bi, t, f, n = bi[order], t[order], f[order], n[order]
    first = np.ones(len(bi), dtype=bool)
    first[1:] = bi[1:] != bi[:-1]
    b = bi[first]
    t_out[b], f_out[b], n_out[b] = t[first], f[first], n[first]
    return ts[i] + t_out, f_out, n_out


def _face_rows(
    contacts: Contacts, X: np.ndarray, r: np.ndarray, margin: np.ndarray
) -> tuple[np.ndarray, ...]:
    """(body, unit normal toward it, gap, friction, face) of each solid face within ``margin``
    of a ball (X, r)."""
    grid = contacts._grid_of()
    faces = contacts.faces
    bi, f = grid.pairs(X, r + margin)  # endless faces within reach, and the listed ones
    if not len(bi):
        z = np.zeros(0, dtype=np.intp)
        return z, np.zeros((0, 2)), np.zeros(0), np.zeros(0), z
    L = len(faces.p)
    x = X[bi]
    nrm, _ = contacts._normals(f, x)
    line = f < L
    gap = np.empty(len(f))
    inside = np.ones(len(f), dtype=bool)
    if L:
        fl = np.where(line, f, 0)
        gap_l = _dot(x - faces.p[fl], nrm) - faces.rho[fl] - r[bi]
        t_dir = np.stack([-faces.n[fl, 1], faces.n[fl, 0]], axis=1)
        u = _dot(x - faces.p[fl], t_dir)
        inside = ~line | ((u >= faces.lo[fl]) & (u <= faces.hi[fl]))
        gap = gap_l
    if len(faces.c):
        fd = np.where(line, 0, f - L)
        d = x - faces.c[fd]
        gap = np.where(line, gap, _norm(d) - faces.r[fd] - r[bi])
    keep = inside & (gap <= margin[bi])
    return bi[keep], nrm[keep], gap[keep], faces.mu[f[keep]], f[keep]


def _unpack(parts: list[tuple[Any, ...]]) -> list[tuple[int, int, Any, Any, Any, float]]:
    out: list[tuple[int, int, Any, Any, Any, float]] = []
    for rows, others, points, normals, impulses, times in parts:
        for k in range(len(rows)):
            p = None if points is None else points[k]
            out.append((int(rows[k]), int(others[k]), p, normals[k], impulses[k], float(times[k])))
    return out
