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
faster (a light ball struck by a heavy one: ``engine.pair_grid.struck``).

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

from .colliders import Circle
from .impact import TOUCH
from .manifold import StaticShapes, static_shapes
from .pair_grid import Search, deepest_overlap, find_pairs, struck
from .pair_impacts import MAX_ROUNDS, exact
from .pair_math import SLOP, dot, isin_sorted, norm, sorted_unique, unit
from .shaped import ShapeTable, pair_rows, static_rows
from .soft import Rows, SoftStep

if TYPE_CHECKING:
    from .contacts import Contacts

__all__ = ["Collisions", "MAX_ROUNDS", "SLOP", "PUSH", "deepest_overlap"]

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
    B = float((m * dot(V0, dV)).sum())
    C = 0.5 * float((m * dot(dV, dV)).sum())
    KE0 = 0.5 * float((m * dot(V0, V0)).sum())
    if not B + C > 1e-13 * KE0 + 1e-300:
        return V
    s = min(max(-B / (2.0 * C), 0.0), 1.0)
    return V0 + s * dV


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
        self._handed = np.zeros(0, dtype=np.intp)  # a crowd's bodies (``_exact``)
        self._table: ShapeTable | None = None  # the bodies' shapes (``_shapes``)
        # What the struck bodies' search needs (engine.pair_grid; None: no pairs searched).
        self._search: Search | None = None
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
            a, b, self._search = find_pairs(
                x0, v0, x1, v1, A, dt, live, store, self._has_kin, self._plain
            )
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
            dist = norm(d)
            nrm = unit(d, dist)
            gap = dist - store.radius[a] - store.radius[b]
            closing = -dot(v0[a] - v0[b], nrm)
            if held is not None and held.any():
                Ah = np.where(held[:, None], 0.0, A)
                press = dot(Ah[a] - Ah[b], nrm)
            else:
                press = dot(A[a] - A[b], nrm)
            pull = np.maximum(norm(A[a]), norm(A[b]))
            margin = 0.05 * np.minimum(store.radius[a], store.radius[b]) + closing.clip(0) * dt
            near = gap <= margin
            rest = near & (np.abs(closing) <= 2.0 * dt * pull) & (press < -1e-9 * pull)
            # (Overlap past the slop: balls hung touching, as in a cradle, are no pile.)
            seed = loaded | rest | (gap < -SLOP * np.minimum(store.radius[a], store.radius[b]))
            island[a[seed]] = island[b[seed]] = True
            island = self._grow(island, a, b, x0, v0, A, dt, store)
        island &= ~self.asleep  # (a sleeper beside a pile was woken above, or stays put)
        a, b = struck(a, b, island, dt, store, self._search, self._has_kin, self._plain)
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
        Ar = norm(A[a] - A[b])
        rel = norm(v0[a] - v0[b])
        gap = norm(x0[a] - x0[b]) - ra - rb
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
        self.rest_speed = 2.0 * dt * float(norm(P[live]).max())
        self._dt, self._t0 = dt, t0
        x, v = (x1, v1) if self.moved else (x1.copy(), v1.copy())
        self.moved = True
        impacts: list[tuple[np.ndarray, ...]] = []
        exact = ~(island[a] & island[b])
        kick = None
        if exact.any():
            # A chain of impacts past HANDOVER_ROUNDS among bodies under load (rows landing
            # on rows, bouncing off the floor into the next) is given to the pile instead.
            loaded = bool((norm(P[a[exact]]) > 0.0).any())
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
            over = R - norm(x[a] - x[b])
            grew = over > R - norm(x0[a] - x0[b]) + 1e-9 * R
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
        """``engine.pair_impacts.exact`` (the impacts of pairs not both in a pile, in place on
        (x, v)), counting its rounds and a capped step: the impacts and the pile's kick, or
        None when a crowd under load was handed over (its World rows in ``_handed``)."""
        got = exact(
            a, b, island, x, v, A, P, dt, self._t0, store, contacts,
            self.asleep, self._has_kin, handover,
        )  # fmt: skip
        if got.rounds:
            self.last_rounds = got.rounds
        self.capped += int(got.capped)
        if got.impacts is None:
            assert got.handed is not None
            self._handed = got.handed
            return None
        return got.impacts, got.kick

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
        dist = norm(d)
        nrm = unit(d, dist)
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
        speed = norm(v0U) + norm(P[U]) * dt
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
        gap = norm(Xr[lb] - Xr[la]) - r[la] - r[lb]
        touch = gap <= SLOP * np.minimum(r[la], r[lb]) + TOUCH
        pressed = solver.total[:m] > 0.0
        hold = touch | pressed
        # Every other row's gap now: its gap at the start plus the bodies' moves along it.
        moved = np.append(Xr - x0U, [[0.0, 0.0]], axis=0)
        now = sep_all + dot(moved[rb] - moved[ra], nv)
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
            tk = sorted_unique(ua[hs].astype(np.int64) * n + ub[hs])
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

    # -- impacts ---------------------------------------------------------------------------------
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
        keys = sorted_unique(keys)
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
                apart = ~isin_sorted(k, keys)
                if apart.any():
                    self._ended.append(
                        (ga[apart], gb[apart], point[apart], nrm[apart], P[apart], t[apart])
                    )
        struck = sorted_unique(struck)
        new = keys[~isin_sorted(keys, before) & ~isin_sorted(keys, struck)]
        gone = before[~isin_sorted(before, keys) & ~isin_sorted(before, struck)]
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
            touching = norm(x[awake] - x[sleeper]) <= ra + rs + 0.05 * np.minimum(ra, rs)
            moving = (norm(v[awake]) > self._still_speed) | touching
            if moving.any():
                sleeper = sleeper[moving]
                groups = sorted_unique(self._group[sleeper])
                woken = asleep & isin_sorted(self._group, groups)
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
        slow = norm(v[live]) <= self._still_speed
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
        not_ready = sorted_unique(label[member & ~ready])
        sleepers = member & ready & ~isin_sorted(label, not_ready)
        if sleepers.any():
            asleep[sleepers] = True
            self._group = np.where(sleepers, label, self._group)
            v[sleepers] = 0.0


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
        gap_l = dot(x - faces.p[fl], nrm) - faces.rho[fl] - r[bi]
        t_dir = np.stack([-faces.n[fl, 1], faces.n[fl, 0]], axis=1)
        u = dot(x - faces.p[fl], t_dir)
        inside = ~line | ((u >= faces.lo[fl]) & (u <= faces.hi[fl]))
        gap = gap_l
    if len(faces.c):
        fd = np.where(line, 0, f - L)
        d = x - faces.c[fd]
        gap = np.where(line, gap, norm(d) - faces.r[fd] - r[bi])
    keep = inside & (gap <= margin[bi])
    return bi[keep], nrm[keep], gap[keep], faces.mu[f[keep]], f[keep]


def _unpack(parts: list[tuple[Any, ...]]) -> list[tuple[int, int, Any, Any, Any, float]]:
    out: list[tuple[int, int, Any, Any, Any, float]] = []
    for rows, others, points, normals, impulses, times in parts:
        for k in range(len(rows)):
            p = None if points is None else points[k]
            out.append((int(rows[k]), int(others[k]), p, normals[k], impulses[k], float(times[k])))
    return out
