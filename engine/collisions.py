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
(its velocity the step's end one, so momentum changes by the forces' impulse alone) and goes
on from there next step: bodies never fly through each other for want of rounds, at the cost
of the rest of that step's motion for those bodies. The count of steps
that reached the cap is kept in ``capped``. The pairs searched are those a body's speed can
bring together within the step, and those of a body an impact may send off faster (a light
ball struck by a heavy one: ``_struck_pairs``).

**Resting contacts.** A closing speed below ``rest_speed`` (2 |A| dt: what the acceleration
adds in two steps), or a pair that carried load in the last step, is not a bounce but a
contact at rest, the one a pile is made of (a pile does not bounce inside). Those pairs, and
the bodies' contacts with static faces, are solved together as constraints, in four passes:

1. *Velocities, all at once.* The normal impulse lam >= 0 makes the normal velocity >= 0 (or
   lets a gap close in one step, no faster), friction keeps |lam_t| <= mu lam. Jacobi
   iterations over all contacts at once (``iterations``, each body's mass split between its
   contacts so that the sum converges, Tonge et al. 2012; sped up by Chebyshev's
   semi-iteration, Wang 2015), started from the last step's impulses (warm starting: a
   settled pile is already solved). The exact solution never adds kinetic energy; if the
   iterations stop short with more than they began with, their change is scaled back
   (``_dissipative``).
2. *Velocities, from the ground up.* Jacobi passes information one contact per iteration,
   so a pile many layers deep is not held by a few iterations. Shock propagation
   (Guendelman, Bridson and Fedkiw 2003) ends the solve with one pass from the bottom up:
   bodies are sorted into bands of height (up being against the mean acceleration), and
   each band's contacts with the bands below, already final, are made to hold (no closing,
   no sliding past friction) with the lower body taken as immovable, by Gauss-Seidel over
   each body's two or three supports (a ball wedged between a ball and a wall is held).
   Contacts within one band (side by side) are left to the iterations.
3. A resting contact acts as a force through the step, so its velocity change dv moves the
   body by the method's share of dv dt (1/2 under the closed form, velocity Verlet and RK4,
   1 under semi-implicit Euler, 0 under explicit Euler: each method's own rule for a
   constant force), but only for a body whose loaded contacts were closed as the step
   began: one still closing a gap met its contact late in the step and keeps its end
   position (else it would hover at its start).
4. *Positions.* Overlap past ``SLOP`` of a radius is removed by moving positions, never
   velocities, so no energy is added: Jacobi iterations, then the same pass from the
   ground up.

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

from .impact import TOUCH, disc_hits, line_hits

if TYPE_CHECKING:
    from .contacts import Contacts

__all__ = ["Collisions", "MAX_ROUNDS", "SLOP", "BAUMGARTE", "deepest_overlap"]

#: Impact rounds in one step (each resolves every pair that comes first for both bodies).
MAX_ROUNDS = 64
#: Overlap (fraction of the smaller radius) left alone: contacts touch, they do not chatter.
SLOP = 0.002
#: Gauss-Seidel sweeps over each band's contacts in the shock passes (a body rests on two or
#: three; a wedge of normals 120 degrees apart keeps 1/16 of its error after two).
SHOCK_ITERATIONS = 2
#: Thickness of the shock passes' bands of height, in smallest radii: contacts steeper than
#: asin(BAND / 2) (44 degrees; a pile's are 60) always join two bands.
BAND = 1.4
#: A body sleeps only while it overlaps others by at most this fraction of its radius.
SLEEP_OVERLAP = 0.0075
#: Most position iterations a step takes while overlaps are past twice SLOP.
MAX_POSITION_ITERATIONS = 8
#: Fraction of the overlap past SLOP removed per step by moving positions.
BAUMGARTE = 1.0


def _clip_two_calls(x: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    return np.minimum(np.maximum(x, lo), hi)


# np.clip's ufunc, called directly: the np.clip wrapper costs 3 us a call, and the pile
# passes call it thousands of times a step (numpy 2; else two calls, the same numbers).
_clip = getattr(getattr(getattr(np, "_core", None), "umath", None), "clip", _clip_two_calls)


def _dissipative(
    V: np.ndarray, V0: np.ndarray, w: np.ndarray, lam: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The resting contacts' velocities V (from V0) and impulses lam, scaled back if they
    gained kinetic energy.

    The exact solution of the resting contacts (no closing faster than a gap allows: a
    convex set of velocities that holds 0) is a projection of V0 in the mass metric, which
    never lengthens it, and Coulomb friction only dissipates, so it never adds kinetic energy
    (when no body the game moves is among them). The iterations stop short of it, and the
    impulses they start from, the last step's, can push contacts that already part: a
    heavy ball that has just stopped on a light one against a wall is sent back (kinetic
    energy x36 in 4 steps). Then the change dV = V - V0 is scaled by the s in [0, 1] that
    leaves the least energy, KE(s) = KE0 + s B + s^2 C with B = sum m V0.dV and
    C = sum m |dV|^2 / 2: s = -B / (2 C), or 0 if B >= 0. Momentum is kept, impulses between
    bodies being equal and opposite at any s.
    """
    m = np.where(w > 0.0, 1.0 / np.where(w > 0.0, w, 1.0), 0.0)
    dV = V - V0
    B = float((m * (V0[:, 0] * dV[:, 0] + V0[:, 1] * dV[:, 1])).sum())
    C = 0.5 * float((m * (dV[:, 0] * dV[:, 0] + dV[:, 1] * dV[:, 1])).sum())
    # KE(1) - KE0 = B + C: past rounding of KE0 itself, the iterations added energy.
    KE0 = 0.5 * float((m * (V0[:, 0] * V0[:, 0] + V0[:, 1] * V0[:, 1])).sum())
    if not B + C > 1e-12 * KE0 + 1e-300:
        return V, lam
    s = min(max(-B / (2.0 * C), 0.0), 1.0)
    return V0 + s * dV, lam * s


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
        #: Jacobi iterations of the resting-contact solver per step.
        self.iterations = 8
        #: Spectral radius assumed for Chebyshev's acceleration (0: plain Jacobi).
        self.rho = 0.97
        #: Position iterations removing overlap per step.
        self.position_iterations = 2
        #: Seconds a touching group must stay still before it sleeps (inf: never).
        self.sleep_time = 0.5
        #: Speed (length units / s) under which a body counts as still; None: |a| dt, the
        #: speed the largest acceleration adds in one step (Chipmunk's idle speed).
        self.sleep_speed: float | None = None
        self.capped = 0  # steps whose impacts reached MAX_ROUNDS
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
        # Pairs touching after the last step (for began / ended), keyed as above.
        self._touching = np.zeros(0, dtype=np.int64)
        self._began: list[tuple[Any, ...]] = []
        self._ended: list[tuple[Any, ...]] = []
        self.still = np.zeros(0)  # (N,) seconds each body has been still
        self.asleep = np.zeros(0, dtype=bool)  # (N,)
        self._group = np.zeros(0, dtype=np.intp)  # (N,) the sleeping group of each sleeper
        self._lam_dt = 1.0
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
        self._keys = np.zeros(0, dtype=np.int64)
        self._lam = np.zeros((0, 2))
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
        # Keys are a * base + b with b < old for a pair and b = old + f for face f (base: the
        # bodies and faces then); rows keep their numbers, so only the faces' b moves. The
        # mapping keeps their order, so the keys stay sorted.
        if len(self._keys) and self._base > old:
            a, b = np.divmod(self._keys, self._base)
            b[b >= old] += extra
            self._base += extra
            self._keys = a * self._base + b
        else:
            self._keys, self._lam = np.zeros(0, dtype=np.int64), np.zeros((0, 2))
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
        )

    def set_state(self, state: tuple[Any, ...]) -> None:
        """Bring back a state from ``state()``."""
        keys, lam, lam_dt, base, touching, still, asleep, group, capped, warned = state
        self._keys, self._lam, self._lam_dt, self._base = keys.copy(), lam.copy(), lam_dt, base
        self._touching = touching.copy()
        self.still, self.asleep, self._group = still.copy(), asleep.copy(), group.copy()
        self.capped, self.warned = capped, warned

    def active(
        self, radius: np.ndarray, group: np.ndarray, cat: np.ndarray, mask: np.ndarray
    ) -> bool:
        """Whether any pair of bodies may collide at all (else a step costs nothing here)."""
        live = self._prepare(radius, group, cat, mask)
        return len(live) >= 2 and not self._one_group

    # -- the step ------------------------------------------------------------------------------
    def resolve(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        x1: np.ndarray,
        v1: np.ndarray,
        A: np.ndarray,
        dt: float,
        t0: float,
        share: float,
        store: Any,
        contacts: Contacts | None,
        A_force: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The state after dt with every contact between bodies applied: new (x, v) arrays.

        ``A`` (N, 2): each body's acceleration along its path this step. ``share``: the
        fraction of dv dt by which a resting contact's velocity change dv moves the body
        (1/2 for the closed form, velocity Verlet and RK4, 1 for semi-implicit Euler, 0 for
        explicit Euler). ``store``: the World's BodyStore (radius, material, filters, mass).
        Bodies that meet no other keep (x1, v1) bit for bit.
        """
        self.moved = False
        self._began, self._ended = [], []
        self.last_rounds = 0
        self._overlap = np.zeros(0)
        n = len(x1)
        if len(self.still) != n:
            self.wake(n)
        live = self._prepare(store.radius, store.group, store.categories, store.mask)
        if len(live) < 2 or self._one_group:
            return x1, v1
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
        self._has_kin = bool(store.kinematic.any())
        self._kin = store.kinematic
        a, b = self._pairs(x0, v0, x1, v1, A, dt, live, store)
        if len(a) and self.moved:
            a, b = self._wake_met(a, b, x1, v1, store.radius)
        if not len(a):
            self._events_of(np.zeros(0, dtype=np.int64), [], n, t0, dt, live)
            none = np.zeros(0, dtype=np.intp)
            self._sleep_still(v1, dt, live, none, none, contacts)
            return x1, v1
        # Solve on the bodies in pairs only, in local arrays (U: local -> World row).
        present = np.zeros(n, dtype=bool)
        present[a] = present[b] = True
        U = np.flatnonzero(present)
        local = np.cumsum(present) - 1  # World row -> local index, for the rows in U
        la, lb = local[a], local[b]
        X, V, AU = x1[U], v1[U], A[U]
        self._U, self._t0 = U, t0
        # Each body's pull (its forces' acceleration; not a wall's push) sets the rest speeds.
        self._P = (A if A_force is None else A_force)[U]
        self.rest_speed = 2.0 * dt * float(_norm(self._P).max())
        self._dt = dt
        w = 1.0 / store.mass[U]
        # A kinematic body (moved by the game) has infinite mass here: no impulse moves it.
        self._kinU = store.kinematic[U] if self._has_kin else None
        if self._kinU is not None:
            w[self._kinU] = 0.0
        r = store.radius[U]
        impacts = self._impacts(
            la, lb, X, V, AU, w, r, store.restitution[U], store.friction[U], dt, contacts, U
        )
        rest_a, rest_b = self._resting(
            la, lb, X, x0[U], V, AU, w, r, store.friction[U], dt, share, U, n, contacts
        )
        if contacts is not None and len(contacts.faces.owner):
            # Nothing the pairs pushed is left inside a wall (with its speed into it taken).
            # (A kinematic body is no wall's business: its radius is taken as -inf there.)
            contacts.push_out_rows(
                X, V, r if self._kinU is None else np.where(self._kinU, -np.inf, r), U
            )
        # The overlap each body is left with: a group sleeps only once it is small.
        over = r[rest_a] + r[rest_b] - _norm(X[rest_a] - X[rest_b])
        deepest = np.zeros(len(U))
        np.maximum.at(deepest, rest_a, over)
        np.maximum.at(deepest, rest_b, over)
        self._overlap = np.zeros(n)
        self._overlap[U] = deepest / r
        # The deepest overlap of any pair (what the World warns about), resting or not.
        every = r[la] + r[lb] - _norm(X[la] - X[lb])
        self.last_overlap = max(float(every.max()), 0.0) if len(every) else 0.0
        x, v = (x1, v1) if self.moved else (x1.copy(), v1.copy())
        x[U], v[U] = X, V
        self.moved = True
        # Which pairs touch now, at rest: events, and the groups that may sleep.
        D = X[rest_a] - X[rest_b]
        touch = _norm(D) <= (r[rest_a] + r[rest_b]) * (1.0 + 1e-9) + TOUCH
        keys = U[rest_a[touch]].astype(np.int64) * n + U[rest_b[touch]]
        self._events_of(keys, impacts, n, t0, dt, U)
        self._sleep_still(v, dt, live, U[rest_a], U[rest_b], contacts)
        return x, v

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
            ia, ib = self._struck_pairs(
                ia, ib, P, r, v0[live], v1[live], A[live], reach, dt, live, store
            )
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
            grown = np.flatnonzero((gain * dt > 0.05 * r) & ~done)
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
    ) -> list[tuple[np.ndarray, ...]]:
        """Resolve the step's impacts in time order, in place on the end state (X, V)."""
        nU = len(X)
        R = r[la] + r[lb]
        # A closing speed below rest, 2 |a_n| dt for the larger pull a_n of the pair's bodies
        # along the normal, is a contact at rest, not a bounce (in a pile, below 2 g dt along a
        # contact; two balls lying on a floor meet sideways, where gravity adds nothing, so
        # every meeting of theirs is an impact). Only pairs that can close faster than that
        # (bounded here by the pulls' sizes) can have an impact.
        P = self._P
        rest = 2.0 * dt * np.maximum(_norm(P[la]), _norm(P[lb]))
        Vr = V[la] - V[lb]
        Ar = A[la] - A[lb]
        can = _norm(Vr) + _norm(Ar) * dt > rest
        if len(self._keys) and len(la):
            # A pair that carried load at rest in the last step rests on: its contact is
            # solved with the pile's (a pile does not bounce inside).
            keys = self._U[la].astype(np.int64) * self._base + self._U[lb]
            pos = np.clip(np.searchsorted(self._keys, keys), 0, len(self._keys) - 1)
            loaded = (self._keys[pos] == keys) & (self._lam[pos, 0] > 0.0)
            can &= ~loaded
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
        for k in range(MAX_ROUNDS):
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
            i = np.flatnonzero(left)
            if len(i) and math.isfinite(t_first):
                X[i] = self._state_at(i, np.full(len(i), t_first), X, V, A, dt)[0]
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
            P = self._P
            pulls = np.maximum(np.abs(_dot(P[pa[ok]], d)), np.abs(_dot(P[pb[ok]], d)))
            rest = 2.0 * dt * pulls / dn
            t[ok[u <= rest]] = np.inf
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

    # -- resting contacts ------------------------------------------------------------------------
    def _resting(
        self,
        la: np.ndarray,
        lb: np.ndarray,
        X: np.ndarray,
        X0: np.ndarray,
        V: np.ndarray,
        A: np.ndarray,
        w: np.ndarray,
        r: np.ndarray,
        mu: np.ndarray,
        dt: float,
        share: float,
        U: np.ndarray,
        n: int,
        contacts: Contacts | None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Solve the contacts at rest (pairs and the static faces their bodies touch) in place
        on (X, V); return the local pairs that rest on each other."""
        nU = len(X)
        R = r[la] + r[lb]
        D = X[la] - X[lb]
        dist = _norm(D)
        margin = 0.05 * np.minimum(r[la], r[lb])
        # Resting: near and closing no faster than rest_speed (a faster pair just touching at
        # the end of the step is an impact early in the next one).
        closing = -_dot(V[la] - V[lb], D) / np.where(dist > 0.0, dist, 1.0)
        P = self._P
        pulls = np.maximum(np.abs(_dot(P[la], D)), np.abs(_dot(P[lb], D)))
        rest = 2.0 * dt * pulls / np.where(dist > 0.0, dist, 1.0)
        near = (dist - R <= margin) & ((closing <= rest) | (dist < R))
        ra, rb = la[near], lb[near]
        nrm = _unit(D[near], dist[near])
        gap = dist[near] - R[near]
        fric = mu[ra] * mu[rb]
        # Keys of the contacts, for warm starting: a * base + b for a pair, a * base + n + f
        # for body a on face f.
        n_faces = 0 if contacts is None else len(contacts.faces.owner)
        base = n + n_faces
        if base != self._base:
            self._keys, self._base = np.zeros(0, dtype=np.int64), base
        keys = U[ra].astype(np.int64) * base + U[rb]
        if n_faces and contacts is not None:
            fa, fn, fg, fmu, fk = _face_rows(contacts, X, r, 0.05 * r)
            if contacts.faces.filters is not None:
                ok = contacts.allowed(U[fa], fk)  # faces a body's filter does not meet
                fa, fn, fg, fmu, fk = fa[ok], fn[ok], fg[ok], fmu[ok], fk[ok]
            # As for pairs: a body closing on a wall faster than rest_speed, not yet in it,
            # meets it early in the next step (the static contacts bounce it exactly).
            slow = (-_dot(V[fa], fn) <= 2.0 * dt * np.abs(_dot(P[fa], fn))) | (fg < 0.0)
            if self._kinU is not None:
                slow &= ~self._kinU[fa]  # walls do not hold what the game moves
            fa, fn, fg, fmu, fk = fa[slow], fn[slow], fg[slow], fmu[slow], fk[slow]
            if len(fa):
                ra = np.concatenate([ra, fa])
                # nU: the static world. Pairs first, then faces: _project splits them so.
                rb = np.concatenate([rb, np.full(len(fa), nU)])
                nrm = np.concatenate([nrm, fn])
                gap = np.concatenate([gap, fg])
                fric = np.concatenate([fric, mu[fa] * fmu])
                keys = np.concatenate([keys, U[fa].astype(np.int64) * base + n + fk])
        if not len(ra):
            return ra[:0], rb[:0]
        wx = np.append(w, 0.0)
        # Each body's mass is split between its contacts (so Jacobi converges).
        count = np.bincount(ra, minlength=nU + 1) + np.bincount(rb, minlength=nU + 1)
        count[nU] = 0
        eff = 1.0 / (wx[ra] * count[ra] + wx[rb] * count[rb])
        tang = np.stack([-nrm[:, 1], nrm[:, 0]], axis=1)
        # A contact not yet closed may close by its gap this step, no more.
        target = np.where(gap > 0.0, -gap / dt, 0.0)
        # Warm start from the last step's impulses of the same contacts.
        lam = np.zeros((len(ra), 2))
        if len(self._keys):
            pos = np.clip(np.searchsorted(self._keys, keys), 0, len(self._keys) - 1)
            same = self._keys[pos] == keys
            lam[same] = self._lam[pos[same]] * (dt / self._lam_dt)
            lam[:, 0] = np.maximum(lam[:, 0], 0.0)
            cap = fric * lam[:, 0]
            lam[:, 1] = np.clip(lam[:, 1], -cap, cap)
        Vx = np.vstack([V, np.zeros((1, 2))])
        V_before = Vx.copy()
        X_ref = X.copy()  # where the gaps were measured
        idx = np.concatenate([ra, rb])
        if lam.any():
            self._apply(Vx, idx, lam, nrm, tang, wx, ra, rb, nU)
        # Chebyshev's semi-iteration (Wang 2015) speeds Jacobi up: each iterate is pushed
        # on from the one two before by omega, which grows from 1 toward its limit for the
        # spectral radius rho of the plain iteration.
        #
        # The iterations work in complex numbers, a vector (x, y) being x + iy: with the
        # normal n, the relative velocity d gives d conj(n) = (d.n) + i (d.t), t = i n the
        # tangent, both parts in one product; an impulse (p_n, p_t) is n (p_n + i p_t).
        nc = nrm[:, 0] + 1j * nrm[:, 1]
        ncc = np.conj(nc)
        Vc = Vx[:, 0] + 1j * Vx[:, 1]
        w2 = np.concatenate([wx[ra], -wx[rb]])
        lam_n, lam_t = lam[:, 0].copy(), lam[:, 1].copy()
        old_n, old_t = lam_n, lam_t
        rho2 = self.rho * self.rho
        omega = 1.0
        size = nU + 1
        w_max = float(wx.max())
        tol_v = 1e-6 * self.rest_speed + 1e-300
        for k in range(self.iterations):
            z = (Vc[ra] - Vc[rb]) * ncc
            new_n = lam_n - eff * (z.real - target)
            new_t = lam_t - eff * z.imag
            if k >= 1:
                omega = 2.0 / (2.0 - rho2) if k == 1 else 4.0 / (4.0 - rho2 * omega)
                new_n = omega * (new_n - old_n) + old_n
                new_t = omega * (new_t - old_t) + old_t
            np.maximum(new_n, 0.0, out=new_n)
            cap = fric * new_n
            np.clip(new_t, -cap, cap, out=new_t)
            d_n, d_t = new_n - lam_n, new_t - lam_t
            # Converged (no impulse would change any speed by a millionth of rest_speed): stop.
            if float(np.abs(d_n).max() + np.abs(d_t).max()) * w_max <= tol_v:
                break
            P = nc * (d_n + 1j * d_t)
            old_n, old_t, lam_n, lam_t = lam_n, lam_t, new_n, new_t
            P2 = np.concatenate([P, P]) * w2
            Vc += np.bincount(idx, P2.real, minlength=size) + 1j * np.bincount(
                idx, P2.imag, minlength=size
            )
            Vc[nU] = 0.0
        lam = np.stack([lam_n, lam_t], axis=1)
        Vx = np.stack([Vc.real, Vc.imag], axis=1)
        if self._kinU is None or not self._kinU.any():
            Vx, lam = _dissipative(Vx, V_before, wx, lam)
        bands = _Bands.of(ra, rb, nU, X, A, self.rmin, self._kinU)
        if bands is not None:
            tol = 1e-6 * self.rest_speed + 1e-300
            bands.velocity(Vx, nrm, target, fric, lam[:, 0], wx, tol)
        V[:] = Vx[:nU]
        # The contact forces acted through the step on a body whose contacts were closed as
        # it began: they move it by the method's share of dv dt. A body that was still
        # closing a gap met its contact only late in the step: it keeps its end position
        # (the position passes below take back any overlap), else it would hover.
        if share:
            d0 = X0[ra] - np.vstack([X0, X0[:1]])[rb]
            gap0 = np.where(
                rb < nU, _norm(d0) - r[ra] - np.append(r, 0.0)[rb], gap + _dot(X0[ra] - X[ra], nrm)
            )
            late = (gap0 > SLOP * r[ra]) & (lam[:, 0] > 0.0)  # pushing, and open at the start
            open_ = np.zeros(nU + 1, dtype=bool)
            open_[ra[late]] = True
            open_[rb[late]] = True
            moving = (Vx[:nU] - V_before[:nU]) * (share * dt)
            moving[open_[:nU]] = 0.0
            X += moving
        order = np.argsort(keys)
        self._keys, self._lam, self._lam_dt = keys[order], lam[order], dt
        self._project(ra, rb, nU, X, X_ref, nrm, gap, wx, r, eff)
        if bands is not None:
            bands.position(X, X_ref, nrm, gap, r)
        sel = rb < nU
        return ra[sel], rb[sel]

    @staticmethod
    def _apply(
        Vx: np.ndarray,
        idx: np.ndarray,
        d_lam: np.ndarray,
        nrm: np.ndarray,
        tang: np.ndarray,
        wx: np.ndarray,
        ra: np.ndarray,
        rb: np.ndarray,
        nU: int,
    ) -> None:
        """Add the impulses d_lam (normal, tangential) of each contact to both its bodies."""
        P = nrm * d_lam[:, :1] + tang * d_lam[:, 1:]
        Pa, Pb = P * wx[ra, None], P * -wx[rb, None]
        both = np.concatenate([Pa, Pb])
        Vx[:, 0] += np.bincount(idx, both[:, 0], minlength=nU + 1)
        Vx[:, 1] += np.bincount(idx, both[:, 1], minlength=nU + 1)
        Vx[nU] = 0.0

    def _project(
        self,
        ra: np.ndarray,
        rb: np.ndarray,
        nU: int,
        X: np.ndarray,
        X_ref: np.ndarray,
        nrm: np.ndarray,
        gap: np.ndarray,
        wx: np.ndarray,
        r: np.ndarray,
        eff: np.ndarray,
    ) -> None:
        """Move positions (never velocities) to remove BAUMGARTE of each overlap past SLOP.

        A pair's overlap is measured anew each iteration; a face's is its gap when measured
        plus how far the body has moved along the face's normal since (a face does not move).
        The rows are the pairs, then the faces (rb == nU), as ``_resting`` lists them; each
        part is worked on alone, in complex numbers (x + iy), as the iterations are.
        """
        m = int(np.count_nonzero(rb < nU))
        pa, pb, fa = ra[:m], rb[:m], ra[m:]
        Xc = X[:, 0] + 1j * X[:, 1]
        # Pairs: overlap R - |x_a - x_b|, pushed apart along the line of centres.
        R = r[pa] + r[pb]
        slop_p = SLOP * np.minimum(r[pa], r[pb])
        k = BAUMGARTE * eff[:m]
        ka, kb = k * wx[pa], k * -wx[pb]
        # Faces: overlap base - x.n, with base = -gap + x_ref.n; pushed out along n.
        nf = nrm[m:, 0] + 1j * nrm[m:, 1]
        nfc = np.conj(nf)
        base = -gap[m:] + _dot(X_ref[fa], nrm[m:])
        slop_f = SLOP * r[fa]
        kf = BAUMGARTE * eff[m:] * wx[fa]
        deepest_rest = 0.0  # the deepest overlap among pairs left out of later iterations
        # At least position_iterations over every row; then, up to MAX_POSITION_ITERATIONS,
        # more over the rows near an overlap past twice SLOP (a pile settling, or a ball just
        # landed on it: the work goes where the overlap is).
        for it in range(MAX_POSITION_ITERATIONS + 1):
            D = Xc[pa] - Xc[pb]
            dist = np.abs(D)
            over_p = R - dist
            over_f = base - (Xc[fa] * nfc).real
            push_p = np.maximum(over_p - slop_p, 0.0)
            push_f = np.maximum(over_f - slop_f, 0.0)
            if it == MAX_POSITION_ITERATIONS or not (push_p.any() or push_f.any()):
                break
            if it >= self.position_iterations:
                deep_p, deep_f = over_p > 2.0 * slop_p, over_f > 2.0 * slop_f
                if not (deep_p.any() or deep_f.any()):
                    break
                if it == self.position_iterations:
                    hot = np.zeros(nU, dtype=bool)
                    hot[pa[deep_p]] = hot[pb[deep_p]] = hot[fa[deep_f]] = True
                    keep_p, keep_f = hot[pa] | hot[pb], hot[fa]
                    if not keep_p.all():
                        left = over_p[~keep_p]
                        deepest_rest = float(left.max())
                        pa, pb, R, slop_p, ka, kb = (
                            pa[keep_p], pb[keep_p], R[keep_p], slop_p[keep_p], ka[keep_p],
                            kb[keep_p],
                        )  # fmt: skip
                        D, dist, push_p = D[keep_p], dist[keep_p], push_p[keep_p]
                    if not keep_f.all():
                        fa, nf, nfc, base = fa[keep_f], nf[keep_f], nfc[keep_f], base[keep_f]
                        slop_f, kf, push_f = slop_f[keep_f], kf[keep_f], push_f[keep_f]
            # Straight up where two centres coincide, so that they are still pushed apart.
            # (Subnormal distances count as coinciding: complex division by them overflows.)
            apart = dist > 1e-290
            unit = D / np.where(apart, dist, 1.0)
            if not apart.all():
                unit[~apart] = 1j
            Pp = unit * push_p
            Pf = nf * push_f
            idx = np.concatenate([pa, pb, fa])
            P = np.concatenate([Pp * ka, Pp * kb, Pf * kf])
            Xc += np.bincount(idx, P.real, minlength=nU) + 1j * np.bincount(
                idx, P.imag, minlength=nU
            )
        deepest = max(float(over_p.max()) if len(over_p) else 0.0, deepest_rest)
        X[:, 0], X[:, 1] = Xc.real, Xc.imag
        self.last_overlap = max(deepest, 0.0)

    # -- events ----------------------------------------------------------------------------------
    def _events_of(
        self,
        keys: np.ndarray,
        impacts: list[tuple[np.ndarray, ...]],
        n: int,
        t0: float,
        dt: float,
        U: np.ndarray,
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
            for pa, pb, point, nrm, P, tau in impacts:
                t = t0 + tau
                ga, gb = U[pa], U[pb]
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
        keep = ~(sa & sb)
        a, b, sa, sb = a[keep], b[keep], sa[keep], sb[keep]
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
        return a, b

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


class _Bands:
    """The contacts of a pile in layers from the ground up, for shock propagation.

    Jacobi passes information one contact per iteration, so a pile many layers deep cannot
    be held by a few iterations. Shock propagation (Guendelman, Bridson and Fedkiw 2003) ends
    the solve with one pass from the bottom up: bodies are sorted into bands of height (up
    being against the mean acceleration, BAND smallest radii thick), and each band's contacts
    with the bands below, already final, are made to hold with the lower body taken as
    immovable. Contacts within one band (side by side) are left to the iterations.

    Within a band the upper bodies are independent (the bodies below are held), but one body
    may rest on two or three rows at once: a ball in the groove of two below, or wedged
    between a ball and a wall. Those rows are solved by Gauss-Seidel, not Jacobi: a body's
    first rows (slot 0) all at once, then its second rows (slot 1), and so on, each taking
    the full correction, in SHOCK_ITERATIONS sweeps. For a wedge whose two normals are 120
    degrees apart, Jacobi with the mass split between the rows keeps (1 + |cos|) / 2 = 3/4 of
    the error an iteration, Gauss-Seidel cos^2 = 1/4 a sweep: Jacobi left a ball against a
    wall slipping at 0.2 m/s for a step now and then, and a pile that could not fall asleep.

    The passes are a Python loop over the bands (each band waits for the ones below), so
    each band's work is kept to a few array calls on short slices (``np.count_nonzero``, not
    ``.any()``, whose Python wrapper costs 2 us a call). Rows are kept in flat arrays sorted
    by (band, slot, upper body): a band is a slice, and so is each of its slots, in which a
    body appears once. Vectors are complex numbers (x + iy), as in the iterations: with the
    unit normal n, d conj(n) is (d.n) + i (d.t) for the tangent t = i n, and the impulse
    (p_n, p_t) is n (p_n + i p_t).
    """

    def __init__(
        self,
        rows: np.ndarray,
        upper: np.ndarray,
        lower: np.ndarray,
        sign: np.ndarray,
        bounds: np.ndarray,
        nU: int,
    ) -> None:
        # Sorted by (band, upper body): runs of one upper body, each body's rows in a band
        # being one run (a band starts a run, even on the same body).
        nb = len(bounds) - 1
        new = np.ones(len(rows), dtype=bool)
        new[1:] = upper[1:] != upper[:-1]
        new[bounds[1:-1]] = True
        starts = np.flatnonzero(new)
        run = np.cumsum(new) - 1
        run_bounds = np.append(run[bounds[:-1]], len(starts))
        band_of_row = np.repeat(np.arange(nb), np.diff(bounds))
        slot = np.arange(len(rows)) - starts[run]
        self.run_body = upper[starts]
        # Re-sorted by (band, slot, run): each band's slots are slices within it.
        perm = np.lexsort((run, slot, band_of_row))
        rows, upper, lower, sign = rows[perm], upper[perm], lower[perm], sign[perm]
        run, slot = run[perm], slot[perm]
        self.rows, self.upper, self.lower, self.sign = rows, upper, lower, sign
        self.bounds, self.nU = bounds, nU
        self.run_bounds = run_bounds
        # Each row's body among its band's: the index into that band's bodies.
        self.local_run = run - run_bounds[:-1][band_of_row]
        # Slot slices: cut where the slot changes within a band, and at every band.
        cut_at = np.ones(len(rows), dtype=bool)
        cut_at[1:] = slot[1:] != slot[:-1]
        cut_at[bounds[:-1]] = True
        seg = np.append(np.flatnonzero(cut_at), len(rows))
        first = np.searchsorted(seg, bounds).tolist()
        seg_list = seg.tolist()
        self.slots = [seg_list[first[i] : first[i + 1] + 1] for i in range(nb)]
        self.face = lower == nU
        self.band_has_face = np.logical_or.reduceat(self.face, bounds[:-1]).tolist()

    @classmethod
    def of(
        cls,
        ra: np.ndarray,
        rb: np.ndarray,
        nU: int,
        X: np.ndarray,
        A: np.ndarray,
        rmin: float,
        fixed: np.ndarray | None = None,
    ) -> _Bands | None:
        """The bands of contacts (ra, rb) (rb == nU: a static face); None without "up".
        ``fixed`` (nU,) bool: kinematic bodies, which lie below everything, as the static
        world does (they hold what rests on them and are never moved)."""
        g = A.sum(axis=0)
        size = math.hypot(float(g[0]), float(g[1]))
        if not size > 0.0 or not len(ra):
            return None
        up = -g / size
        h = X @ up
        # Bands from a fixed origin, in the World's smallest radius (not those of the bodies
        # paired now): a pile's bands do not depend on bodies it never touches.
        band = np.floor(h / (BAND * rmin)).astype(np.int64)
        bandx = np.append(band, -1)  # the static world lies below everything
        hx = np.append(h, -np.inf)
        if fixed is not None:
            bandx[:nU][fixed], hx[:nU][fixed] = -1, -np.inf
        a_up = hx[ra] > hx[rb]
        upper = np.where(a_up, ra, rb)
        rows = np.flatnonzero(bandx[np.where(a_up, rb, ra)] < bandx[upper])
        if not len(rows):
            return None
        # Sorted by (band, upper body): bands are slices, a body's rows in a band are a run.
        key = bandx[upper[rows]] * (nU + 1) + upper[rows]
        order = np.argsort(key, kind="stable")
        rows, key = rows[order], key[order]
        band_of = key // (nU + 1)
        cut = np.flatnonzero(band_of[1:] != band_of[:-1]) + 1
        bounds = np.concatenate([[0], cut, [len(rows)]])
        up_rows = upper[rows]
        lo_rows = np.where(a_up[rows], rb[rows], ra[rows])
        sign = np.where(a_up[rows], 1.0, -1.0)
        # Only the rows that rest on something held (a face, a kinematic body, or a body
        # that rests on one, band below band) are worked on: bodies falling freely together
        # are left alone (taking a lower one as immovable would take momentum out of them),
        # and their contacts to the iterations.
        held = np.zeros(nU + 1, dtype=bool)
        held[nU] = True  # the static world
        if fixed is not None:
            held[:nU][fixed] = True
        sup = np.zeros(len(rows), dtype=bool)
        for i in range(len(bounds) - 1):
            a0, a1 = bounds[i], bounds[i + 1]
            s = held[lo_rows[a0:a1]]
            if np.count_nonzero(s):
                sup[a0:a1] = s
                held[up_rows[a0:a1][s]] = True
        if not np.count_nonzero(sup):
            return None
        if not sup.all():
            band_of_row = np.repeat(np.arange(len(bounds) - 1), np.diff(bounds))[sup]
            rows, up_rows, lo_rows, sign = rows[sup], up_rows[sup], lo_rows[sup], sign[sup]
            cut = np.flatnonzero(band_of_row[1:] != band_of_row[:-1]) + 1
            bounds = np.concatenate([[0], cut, [len(rows)]])
        return cls(rows, up_rows, lo_rows, sign, bounds, nU)

    def velocity(
        self,
        Vx: np.ndarray,
        nrm: np.ndarray,
        target: np.ndarray,
        fric: np.ndarray,
        lam_n: np.ndarray,
        wx: np.ndarray,
        tol: float,
    ) -> None:
        """From the ground up: no body left closing on a body below it (faster than its gap
        allows in one step), nor sliding on it past what friction allows.

        Friction may take up to mu times the speed the iterations' normal impulse ``lam_n``
        gave the upper body, plus mu times this pass's own normal change, off the sliding.
        A band is skipped unless one of its rows needs a change above ``tol`` or a body
        below it has moved in this pass.
        """
        rows, up, lo = self.rows, self.upper, self.lower
        n = nrm[rows] * self.sign[:, None]
        nc = n[:, 0] + 1j * n[:, 1]
        ncc = np.conj(nc)
        inc = 1j * nc  # the tangent
        least, mu = target[rows], fric[rows]
        budget = mu * lam_n[rows] * wx[up]
        Vc = Vx[:, 0] + 1j * Vx[:, 1]
        z = (Vc[up] - Vc[lo]) * ncc
        need = np.logical_or.reduceat(
            (least - z.real > tol) | (np.abs(z.imag) > tol), self.bounds[:-1]
        ).tolist()
        moved = np.zeros(len(Vc), dtype=bool)
        b, rb, local_run, run_body = self.bounds, self.run_bounds, self.local_run, self.run_body
        for i, segs in enumerate(self.slots):
            a0, a1 = b[i], b[i + 1]
            low = lo[a0:a1]
            if not need[i] and not np.count_nonzero(moved[low]):
                continue
            uu = run_body[rb[i] : rb[i + 1]]
            Vu = Vc[uu]
            Vl = Vc[low]  # final already: lower bands came first
            changed = False
            for _ in range(SHOCK_ITERATIONS):
                acted = False
                for s0, s1 in zip(segs[:-1], segs[1:], strict=True):
                    inv = local_run[s0:s1]  # each body once in a slot
                    vi = Vu[inv]
                    z = (vi - Vl[s0 - a0 : s1 - a0]) * ncc[s0:s1]
                    push = least[s0:s1] - z.real
                    np.maximum(push, 0.0, out=push)
                    bud = budget[s0:s1]
                    bud += mu[s0:s1] * push
                    slide = _clip(z.imag, -bud, bud)
                    bud -= np.abs(slide)
                    if np.count_nonzero(push) or np.count_nonzero(slide):
                        # dv = n push - t slide
                        Vu[inv] = vi + (nc[s0:s1] * push - inc[s0:s1] * slide)
                        acted = True
                if not acted:
                    break
                changed = True
            if changed:
                Vc[uu] = Vu
                moved[uu] = True
        Vx[:, 0], Vx[:, 1] = Vc.real, Vc.imag

    def position(
        self, X: np.ndarray, X_ref: np.ndarray, nrm: np.ndarray, gap: np.ndarray, r: np.ndarray
    ) -> None:
        """From the ground up: each body moved out of the bodies below it (past SLOP)."""
        nU = self.nU
        rows, up, lo, face = self.rows, self.upper, self.lower, self.face
        Xc = np.zeros(nU + 1, dtype=complex)
        Xc[:nU] = X[:, 0] + 1j * X[:, 1]
        rx = np.append(r, 0.0)
        n0 = nrm[rows] * self.sign[:, None]
        nc = n0[:, 0] + 1j * n0[:, 1]
        ncc = np.conj(nc)
        ru = r[up]
        # The overlap past SLOP that a push removes: R - |d| - slop for a pair, and for a
        # face -gap as measured less how far the body has moved along the face's normal
        # since (base - X.n), less slop. (The static world's X is 0: d = X for a face.)
        R_slop = ru + rx[lo] - SLOP * np.where(face, ru, np.minimum(ru, rx[lo]))
        base_slop = -gap[rows] + _dot(X_ref[up], n0) - SLOP * ru
        d = Xc[up] - Xc[lo]
        over = np.where(face, base_slop - (d * ncc).real, R_slop - np.abs(d))
        need = np.logical_or.reduceat(over > 0.0, self.bounds[:-1]).tolist()
        moved = np.zeros(nU + 1, dtype=bool)
        b, rb, local_run, run_body = self.bounds, self.run_bounds, self.local_run, self.run_body
        has_face = self.band_has_face
        for i, segs in enumerate(self.slots):
            a0, a1 = b[i], b[i + 1]
            low = lo[a0:a1]
            if not need[i] and not np.count_nonzero(moved[low]):
                continue
            uu = run_body[rb[i] : rb[i + 1]]
            faces = has_face[i]
            Xu = Xc[uu]
            Xl = Xc[low]
            changed = False
            for _ in range(SHOCK_ITERATIONS):
                acted = False
                for s0, s1 in zip(segs[:-1], segs[1:], strict=True):
                    inv = local_run[s0:s1]  # each body once in a slot
                    xi = Xu[inv]
                    d = xi - Xl[s0 - a0 : s1 - a0]
                    dist = np.abs(d)
                    push = R_slop[s0:s1] - dist
                    if faces:
                        bf = face[s0:s1]
                        np.copyto(push, base_slop[s0:s1] - (d * ncc[s0:s1]).real, where=bf)
                    np.maximum(push, 0.0, out=push)
                    if not np.count_nonzero(push):
                        continue
                    # Along the line of centres (straight up where two centres coincide), or
                    # the face's normal.
                    unit = d / np.where(dist > 0.0, dist, 1.0)
                    if np.count_nonzero(dist) < len(dist):
                        unit[dist == 0.0] = 1j
                    if faces:
                        np.copyto(unit, nc[s0:s1], where=bf)
                    Xu[inv] = xi + push * unit
                    acted = True
                if not acted:
                    break
                changed = True
            if changed:
                Xc[uu] = Xu
                moved[uu] = True
        X[:, 0], X[:, 1] = Xc[:nU].real, Xc[:nU].imag


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
