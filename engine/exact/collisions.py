"""Contacts between bodies: impacts in the order physics gives them, piles that rest, sleep.

Bodies with a radius > 0 collide with each other (unless a :class:`engine.Filter` turns the
pair off; points never collide). The World hands ``Collisions`` each step's start state
(x0, v0), the state after its method and the static contacts (x1, v1), and each body's
acceleration A over the step (the constant one under the closed form; the step's own for an
integrator; zero for a body that rested on a collider). Within the step a body's centre is
taken on the path that ends at (x1, v1),

    x(t) = x1 - v1 s + A s^2 / 2,    v(t) = v1 - A s,    s = dt - t,

the exact parabola under the closed form. ``Collisions`` coordinates a step in this order,
each stage in a module of its own:

1. **Pairs** (engine.geometry.pair_grid): the pairs that may touch within the step, through a grid
   of sorted cell keys, with the fast few tested against everyone.
2. **Sleep** (engine.exact.sleep, ``wake_met``): pairs of two sleepers are dropped; an awake body
   that meets a sleeper wakes its group.
3. **The plan** (``plan``, here): one rule gives each pair to one of two solvers, as the step
   begins (below).
4. **Impacts** (engine.exact.pair_impacts): the pairs that are no pile's meet at their exact
   moments, in time order, in rounds; a pile's bodies are moving walls to them. A body the static
   contacts bounced off a collider within the step is taken along its bent path, piece by piece,
   with the pairs that path may bring within touch (engine.exact.bent_paths).
5. **Piles** (engine.exact.pile): the bodies that rest on one another are stepped again from the
   step's start by Box2D v3's soft step (engine.exact.soft), warm started from the last step's
   impulses.
6. **Events** (engine.dynamics.pair_events): which contacts began and which ended.
7. **Sleep** (engine.exact.sleep, ``sleep_still``): groups still for ``sleep_time`` fall asleep.

**The plan** decides which pairs are a pile's and which meet at their exact moments, by one
rule:

* a pair rests (is a pile's) if it carried load in the last step, or if it is near enough to
  touch within the step, closes or parts no faster than its rest speed (2 |a| dt, what the
  forces add in two steps) and is pressed together by the forces (a ball landing softly on
  another; a body resting on a collider counts as held up, so a ball landing on a ball
  that rests on a peg presses it), or if it overlaps by more than ``SLOP``;
* whatever can reach a resting pair's body within the step joins the pile too (a ball
  falling onto it: its contact is a speculative one, stopped where it touches), if it closes
  on it by at most ``CATCH`` times the two radii (``_grow``; the tests themselves are in
  engine.exact.pair_plan); a faster body (a bullet) stays out and meets the pile's bodies at its
  exact moments;
* a body with a shape is always the soft step's, and so is what may touch it;
* every other pair (two balls that meet in flight, a ball striking a ball that rests alone on
  a floor, Newton's cradle on a frictionless floor, whose balls touch but carry nothing)
  meets at its exact moment.

A chain of impacts among bodies under load that runs past HANDOVER_ROUNDS (rows landing
on rows, bounced off the floor into the next) is given up, and its bodies join the pile.
Afterwards the deepest overlap any pair was left with (``last_overlap``, what the World warns
about) and each body's overlap (which keeps a group awake) are measured here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..dynamics.pair_events import events_of, unpack
from ..geometry.colliders import Circle
from ..geometry.manifold_kinds import Polygons
from ..geometry.pair_grid import Search, deepest_overlap, find_pairs, grid_pairs, struck
from ..geometry.pair_math import SLOP, isin_sorted, norm, sorted_unique
from ..geometry.shaped import ShapeTable, pair_rows, static_rows
from .bent_paths import Bends, bends_of, bent_rows, new_pairs
from .joint_contacts import shapes_of
from .pair_impacts import MAX_ROUNDS, exact
from .pair_plan import grow, join_masks, plan_pairs, rest_seeds
from .pile import PUSH, Carried, Statics, components, keep_asleep, step_pile
from .sleep import sleep_still, wake_met

if TYPE_CHECKING:
    from ..dynamics.rotation import Spin
    from .contacts import Contacts

__all__ = ["Collisions", "MAX_ROUNDS", "SLOP", "PUSH", "deepest_overlap"]

_NONE = np.zeros(0, dtype=np.intp)  # no rows


class Collisions:
    """The contacts of a World's bodies with one another (see the module's docstring)."""

    def __init__(self) -> None:
        #: Parts (substeps) a step of a pile takes in the soft step (engine.exact.soft).
        self.iterations = 4
        #: Whether the stages run their loop kernels (engine.kernels: the fast path).
        self.fast = False
        #: Seconds a touching group must stay still before it sleeps (inf: never).
        self.sleep_time = 0.5
        #: Speed (length units / s) under which a body counts as still; None: |a| dt, the
        #: speed the largest acceleration adds in one step (Chipmunk's idle speed).
        self.sleep_speed: float | None = None
        self.capped = 0  # steps whose impacts reached MAX_ROUNDS
        self._handed = np.zeros(0, dtype=np.intp)  # a crowd's bodies (``_exact``)
        self._table: ShapeTable | None = None  # the bodies' shapes (``_shapes``)
        # What the struck bodies' search needs (engine.geometry.pair_grid; None: no pairs searched).
        self._search: Search | None = None
        self._static = Statics()  # the colliders as narrowphase kinds (engine.exact.pile)
        #: After the last step, each shaped body's deepest overlap (length units).
        self._shape_over = np.zeros(0)
        # What ``ended_overlap`` measures again: the plan's pairs with a shape and the shaped
        # bodies; the discs' pairs and each one's overlap at the start (a hair over); the
        # stray pairs' overlap.
        self._shape_pairs: tuple[np.ndarray, ...] | None = None
        self._disc_pairs: tuple[np.ndarray, ...] | None = None
        self._stray_over = 0.0
        #: The deepest overlap the World has warned of (length units; 0: none yet): a pile
        #: past the solver is told again only where it sinks AGAIN times as deep.
        self.warned = 0.0
        self.moved = False  # whether the last step changed any body's state
        #: The spin (engine.dynamics.rotation) the last step's impacts made, when the step had none
        #: and an impact turned a body (two discs at rest that strike each other off centre).
        self.spun: Spin | None = None
        self.last_rounds = 0  # impact rounds in the last step
        self.last_overlap = 0.0  # deepest overlap left after the last step (length units)
        self._live: np.ndarray | None = None  # rows with radius > 0
        self._plain = True  # every live body has the default filter
        self._one_group = False  # every live body shares one nonzero group: no pair collides
        #: Pairs that never collide, as sorted keys a * N + b (a < b, World rows): bodies
        #: joined by a joint (engine.dynamics.joints, ``collide=False``).
        self.apart = np.zeros(0, dtype=np.int64)
        #: Bodies held by joints (World rows): they never sleep, nor what they touch (a
        #: sleeper stays put, and a joint would pull it).
        self.joined = np.zeros(0, dtype=np.intp)
        #: Pairs of bodies tied by springs (World rows, (k,) each; engine.exact.spring_step): they
        #: sleep as one group, so a spring never pulls on a sleeper beside a body awake.
        self.tied: tuple[np.ndarray, np.ndarray] = (_NONE, _NONE)
        #: The last step's pile contacts of those bodies (engine.exact.pile, ``Pile.joined``).
        self.joint_rows: tuple[np.ndarray, ...] | None = None
        #: The World's polygons and capsules, which those rows index (engine.exact.joint_contacts;
        #: made with the shapes' table, ``_shapes``).
        self.joint_polygons: Polygons | None = None
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
        self._reports = (0, 0)  # the static contacts' batches of reports in the step

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

    def filters_changed(self) -> None:
        """A body's filter was set: which bodies collide is found again (``live``)."""
        self._live = None

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
            # (The rows of bodies with shapes, keyed past old * base, start afresh.) The
            # colours too: the next step solves its rows in the same order, so a pile goes on
            # as in a World without the new bodies (the order matters while it moves).
            base = self._base
            shared = self._color_keys is self._keys
            keys, self._lam = self._renumber(self._keys, self._lam, old, base, extra)
            self._color_keys, self._colors = self._renumber(
                self._color_keys, self._colors, old, base, extra
            )
            self._keys = self._color_keys if shared else keys
            self._base += extra
        else:
            self._keys, self._lam = np.zeros(0, dtype=np.int64), np.zeros((0, 2))
            self._color_keys = np.zeros(0, dtype=np.int64)  # coloured afresh
        a, b = np.divmod(self._touching, old)  # a * n + b for the pairs touching
        self._touching = a * n + b
        self.still = np.concatenate([self.still, np.zeros(extra)])
        self.asleep = np.concatenate([self.asleep, np.zeros(extra, dtype=bool)])
        self._group = np.concatenate([self._group, np.zeros(extra, dtype=np.intp)])

    @staticmethod
    def _renumber(
        keys: np.ndarray, values: np.ndarray, old: int, base: int, extra: int
    ) -> tuple[np.ndarray, np.ndarray]:
        """Carried (keys, values) of the discs' rows (keys below old * base) renumbered for
        ``extra`` bodies added after the ``old`` ones: a face's b = old + f moves by extra,
        in the new base (the order, and so the sorting, is kept)."""
        disc = keys < old * base
        keys, values = keys[disc], values[disc]
        a, b = np.divmod(keys, base)
        b[b >= old] += extra
        return a * (base + extra) + b, values

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

    def wake_body(self, row: int, n: int) -> None:
        """Body ``row`` was written by hand (its position, velocity or own acceleration): it
        is no longer still, and if it slept, its sleeping group wakes with it. The other
        groups sleep on: a body sent into one of them wakes it when it meets it (wake_met),
        as a kinematic body does, so a game that sets its player's velocity every step does
        not keep a sleeping pile across the level awake."""
        if len(self.still) != n:
            self.wake(n)
            return
        self.still[row] = 0.0
        if self.asleep[row]:
            group = self.asleep & (self._group == self._group[row])
            self.asleep[group] = False
            self.still[group] = 0.0
            self._group[group] = 0

    def sleep_group(self, row: int, n: int, never: np.ndarray) -> np.ndarray:
        """Put body ``row`` to sleep now with the awake bodies touching it, one through another
        (the pairs touching after the last step), as one sleeping group; none of ``never``
        (N,) bool, the bodies that never sleep, which pass no sleep on. The rows put to sleep
        (none when ``row`` slept already): each stays put until woken (``wake_met``)."""
        if len(self.still) != n:
            self.wake(n)
        if self.asleep[row]:
            return np.zeros(0, dtype=np.intp)
        a, b = np.divmod(self._touching, n)
        off = never | self.asleep
        keep = ~(off[a] | off[b])
        label = components(n, a[keep], b[keep], self.fast)
        rows = np.flatnonzero(label == label[row])
        self.asleep[rows] = True
        self._group[rows] = label[row]  # the group's least row, as sleep_still labels
        return rows

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

    def live(
        self, radius: np.ndarray, group: np.ndarray, cat: np.ndarray, mask: np.ndarray
    ) -> np.ndarray:
        """The World rows of the bodies that collide (radius > 0), from the store's radius,
        group, categories and mask arrays (kept until bodies are added or removed)."""
        return self._prepare(radius, group, cat, mask)

    @property
    def one_group(self) -> bool:
        """Whether every body that collides shares one nonzero group (so no pair collides),
        as of the last ``live``."""
        return self._one_group

    @property
    def carried(self) -> Carried:
        """The impulses the pile's contacts carried over the last step, by key
        (engine.exact.pile)."""
        return self._carried()

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
        carried: np.ndarray | None = None,
    ) -> np.ndarray | None:
        """Find the step's pairs and which bodies the pile's soft step takes (module text):
        their mask (N,), or None. Called before the static contacts, which leave those
        bodies to the soft step (it steps them again from the step's start). ``held`` (N,):
        bodies resting on a collider at the start (it bears their weight: a ball landing on
        one resting on a peg presses it into the peg, as into a pile); ``carried`` (N,) or
        None: bodies the soft step takes whatever they touch (near a moving surface)."""
        self._plan = None
        n = len(x1)
        if len(self.still) != n:
            self.wake(n)
        live = self._prepare(store.radius, store.group, store.categories, store.mask)
        shaped = self._shapes(store).shaped
        if (len(live) < 2 or self._one_group) and not shaped.any() and carried is None:
            return None
        if self.asleep.any():
            x1, v1 = x1.copy(), v1.copy()
            x1[self.asleep], v1[self.asleep] = x0[self.asleep], 0.0
        self._has_kin = bool(store.kinematic.any())
        self._kin = store.kinematic
        if len(live) >= 2 and not self._one_group:
            a, b, self._search = find_pairs(
                x0, v0, x1, v1, A, dt, live, store, self._has_kin, self._plain, fast=self.fast
            )
        else:
            a = b = np.zeros(0, dtype=np.intp)
            self._search = None
        if len(a) and len(self.apart):
            keep = ~np.isin(a.astype(np.int64) * n + b, self.apart)
            a, b = a[keep], b[keep]
        if len(a) and self.asleep.any():
            a, b = wake_met(
                a, b, x1, v1, store.radius, self.asleep, self.still, self._group,
                self._still_speed, shaped if shaped.any() else None, self._touching,
            )  # fmt: skip
        island = np.zeros(n, dtype=bool)
        if shaped.any():
            # A body with a shape is always the soft step's (engine.geometry.shaped), and so is what
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
            # The rule's tests on the pairs (engine.exact.pair_plan): what rests seeds a pile, and
            # the pile grows by what can reach it within the step.
            Ah = A if held is None or not held.any() else np.where(held[:, None], 0.0, A)
            r = store.radius
            if self.fast:
                kin = store.kinematic if self._has_kin else np.zeros(n, dtype=bool)
                plan_pairs(a, b, x0, v0, A, Ah, r, dt, loaded, island, kin, self.asleep, True)
            else:
                seed = rest_seeds(a, b, x0, v0, A, Ah, r, dt, loaded)
                island[a[seed]] = island[b[seed]] = True
                island = self._grow(island, a, b, x0, v0, A, dt, store)
        if carried is not None:
            island |= carried
        island &= ~self.asleep  # (a sleeper beside a pile was woken above, or stays put)
        a, b = struck(a, b, island, dt, store, self._search, self._has_kin, self._plain, self.fast)
        self._plan = (a, b, island)
        return island if island.any() else None

    def _never_sleep(self, n: int) -> np.ndarray | None:
        """Bodies that never sleep (moved by the game, or held by a joint), or None."""
        if not len(self.joined):
            return self._kin if self._has_kin else None
        out = self._kin.copy() if self._has_kin else np.zeros(n, dtype=bool)
        out[self.joined] = True
        return out

    def has_shapes(self, store: Any) -> bool:
        """Whether any body has a shape other than a disc (a box that may be turned by the
        bodies it meets, even where nothing spins and there are no colliders)."""
        return bool(self._shapes(store).shaped.any())

    def shape_table(self, store: Any) -> ShapeTable:
        """The bodies' shapes as narrowphase kinds, by World row (engine.geometry.shaped)."""
        return self._shapes(store)

    def _shapes(self, store: Any) -> ShapeTable:
        """The bodies' shapes as narrowphase kinds (built again when bodies change)."""
        table = self._table
        if table is None or len(table) != len(store.radius):
            shapes = getattr(store, "shapes", None)
            if shapes is None or len(shapes) != len(store.radius):
                shapes = [None] * len(store.radius)
            table = self._table = ShapeTable(shapes, store.radius)
            self.joint_polygons = shapes_of(table)
        return table

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
        if self.fast:  # the plan's kernel without its seeds (engine.exact.pair_plan)
            kin = store.kinematic if self._has_kin else np.zeros(len(island), dtype=bool)
            no = np.zeros(len(a), dtype=bool)
            plan_pairs(a, b, x0, v0, A, A, store.radius, dt, no, island, kin, self.asleep, False)
            return island
        near_a, near_b = join_masks(a, b, x0, v0, A, store.radius, dt)
        if self._has_kin:
            kin = store.kinematic[a] | store.kinematic[b]  # moved by the game: joins
            near_a, near_b = near_a | kin, near_b | kin
        if self.asleep.any():
            awake = ~(self.asleep[a] | self.asleep[b])
            near_a, near_b = near_a & awake, near_b & awake
        return grow(island, a, b, near_a, near_b)

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
        spin: Spin | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The state after dt with every contact between bodies applied: new (x, v) arrays.

        ``A`` (N, 2): each body's acceleration along its path this step (the forces' pull
        ``A_force``, and what a static contact carried for one resting on a collider).
        Pairs of bodies that are not in a pile meet at their exact moments; the bodies of a
        pile (``plan``) are stepped again from (x0, v0) by the soft step. Bodies that meet
        no other keep (x1, v1) bit for bit. ``spin``: the step's rotation
        (engine.dynamics.rotation): the exact impacts and the soft step turn the discs that turn (in
        place on its angle and omega; without one, the impacts make one if they turn a body:
        ``spun``), and a disc that spins is not still (sleep).
        """
        self.moved = False
        self.spun = None
        self._began, self._ended = [], []
        self.last_rounds = 0
        self._overlap = np.zeros(0)
        self._shape_over = np.zeros(0)
        self._shape_pairs = self._disc_pairs = None
        self._stray_over = 0.0
        self.face_touching = (np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp))
        n = len(x1)
        self.joint_rows = None
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
        x_free = x1.copy()  # where each body's own path ends: what the pairs were found on
        # A body that bounced off a collider took a bent path (engine.exact.bent_paths): the
        # impacts take it piece by piece, with the pairs its later pieces may meet.
        bends, a, b = self._bent(a, b, island, x0, v0, x1, v1, A, dt, t0, store, contacts, spin)
        x, v = (x1, v1) if self.moved else (x1.copy(), v1.copy())
        self.moved = True
        impacts: list[tuple[np.ndarray, ...]] = []
        exact = ~(island[a] & island[b])
        kick = turn = None
        if exact.any():
            # A chain of impacts past HANDOVER_ROUNDS among bodies under load (rows landing
            # on rows, bouncing off the floor into the next) is given to the pile instead.
            loaded = bool((norm(P[a[exact]]) > 0.0).any())
            got = self._exact(
                a[exact], b[exact], island, x, v, A, P, dt, store, contacts, spin, loaded, bends
            )
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
                got = ([], None, None)
                if exact.any():
                    got = self._exact(
                        a[exact], b[exact], island, x, v, A, P, dt, store, contacts, spin,
                        bends=bends,
                    )  # fmt: skip
                assert got is not None
            impacts, kick, turn = got
        touching = np.zeros(0, dtype=np.int64)
        pa = pb = np.zeros(0, dtype=np.intp)
        if island.any():
            if kick is not None:
                v0 = v0.copy()
                v0[island] += kick[island] / store.mass[island, None]
            if turn is not None:
                # The moments they took, into their spin at the step's start, as the push
                # into v0. (The step makes a spin for every World whose bodies meet and turn:
                # engine.pipeline.stepping.)
                assert spin is not None
                k = island & (turn != 0.0)
                spin.omega0 = spin.omega0.copy()  # (it may be the store's own)
                spin.omega0[k] += turn[k] * store.inv_moment[k]
            held_by = None
            if len(self.joined):
                held_by = np.zeros(n, dtype=bool)
                held_by[self.joined] = True
            pile = step_pile(
                island, a, b, x0, v0, x, v, P, dt, store, contacts, self._shapes(store),
                self._static, self._carried(), self.asleep, self.iterations, self.rest_speed,
                fast=self.fast, spin=spin, joined=held_by,
            )  # fmt: skip
            self.joint_rows = pile.joined
            touching, pa, pb = pile.touching, pile.near_a, pile.near_b
            self.face_touching, self._shape_over = pile.face_touching, pile.shape_over
            self._carry(pile.carried)
        else:
            self._carry(keep_asleep(self._carried(), self.asleep, n))
        # The deepest overlap of any pair (what the World warns about), resting or not, that
        # this step made or deepened: bodies put inside each other are being pushed apart.
        self._overlap = np.zeros(n)
        self.last_overlap = 0.0
        all_a, all_b = a, b
        if len(a) and self._table is not None and self._table.shaped.any():
            # A shape's bounding circle says nothing of its overlaps: the soft step's rows do.
            disc = ~(self._table.shaped[a] | self._table.shaped[b])
            a, b = a[disc], b[disc]
        if len(self._shape_over) == n:
            self._overlap = self._shape_over / np.where(store.radius > 0.0, store.radius, 1.0)
            self.last_overlap = float(self._shape_over.max(initial=0.0))
            if self.last_overlap > 0.0 and self._table is not None:
                shaped = self._table.shaped
                with_shape = shaped[all_a] | shaped[all_b]
                # (On the colliders: the pile's shapes that the game does not move.)
                on_walls = np.flatnonzero(shaped & island & ~store.kinematic)
                self._shape_pairs = (all_a[with_shape], all_b[with_shape], on_walls)
        if len(a):
            R = store.radius[a] + store.radius[b]
            over = R - norm(x[a] - x[b])
            before = R - norm(x0[a] - x0[b]) + 1e-9 * R  # (a hair over the start's)
            grew = over > before
            deepest = max(float(over[grew].max()), 0.0) if grew.any() else 0.0
            self.last_overlap = max(self.last_overlap, deepest)
            self._disc_pairs = (a, b, before)
            # The overlap each body is left with, in the smaller radius of each pair: a group
            # sleeps only once it is small.
            share = over / np.minimum(store.radius[a], store.radius[b])
            np.maximum.at(self._overlap, a, share)
            np.maximum.at(self._overlap, b, share)
        # A pair the plan did not list can meet too: a body the impacts or the pile sent off
        # its own path (a ball struck within the step into one that stood still). Such a
        # pair left overlapping is counted here, so that the World warns of it.
        stray = self._stray_overlap(x, x_free, live, a, b, store)
        if stray is not None:
            sa, sb, over = stray
            self.last_overlap = max(self.last_overlap, float(over.max()))
            self._stray_over = float(over.max())
            share = over / np.minimum(store.radius[sa], store.radius[sb])
            if len(self._overlap) == n:
                np.maximum.at(self._overlap, sa, share)
                np.maximum.at(self._overlap, sb, share)
        self._touching = events_of(
            touching, impacts, n, t0, dt, self._touching, self._began, self._ended
        )
        if self.asleep.any():
            # Sleepers stay exactly put (nothing above moves a body of infinite mass, but a
            # wall's push-out or rounding must not either).
            x[self.asleep], v[self.asleep] = x0[self.asleep], 0.0
        turned = spin if spin is not None else self.spun
        ta, tb = self.tied
        if len(ta):
            pa, pb = np.concatenate([pa, ta]), np.concatenate([pb, tb])
        self._group = sleep_still(
            v, dt, live, pa, pb, contacts, self.still, self.asleep, self._group,
            self.sleep_time, self._still_speed, self._never_sleep(n),
            self._overlap, self.face_touching[0], self.fast,
            None if turned is None else np.abs(turned.omega) * store.radius,
        )  # fmt: skip
        return x, v

    def ended_overlap(
        self, x: np.ndarray, angle: np.ndarray, store: Any, contacts: Contacts | None
    ) -> float:
        """``last_overlap`` (length units) with the shapes' part measured where the bodies
        ended the step (``x``, ``angle``: after the joints' solve too), not by the pile's rows:
        a row's separation is linearised about the step's start (a point of a turning bat
        moves on an arc), and the joints' solve holds a jointed body's contacts exactly after
        the pile (engine.exact.joint_contacts). What the World warns of is then what is there:
        a ball carried on a swinging bat and struck ended on it, its row 5 cm in. Asked only
        before a warning."""
        deepest = self._stray_over
        if self._disc_pairs is not None:
            a, b, before = self._disc_pairs
            if len(a) and len(x) == len(store.radius):
                over = store.radius[a] + store.radius[b] - norm(x[a] - x[b])
                grew = over > before
                deepest = max(deepest, float(over[grew].max(initial=0.0)))
        got = self._shape_pairs
        if got is None or self._table is None or len(self._table) != len(x):
            return deepest
        a, b, shaped = got
        table = self._table
        if len(a):
            sep = pair_rows(table, a, b, x, 0.0, angle, self.fast)[3]
            deepest = max(deepest, float(-sep.min(initial=0.0)))
        if contacts is not None and len(contacts.faces.owner) and len(shaped):
            statics, solid, first = self._static.of(contacts)
            meets = None
            if contacts.filtering:
                allowed = contacts.allowed
                meets = lambda rows, cols: allowed(rows, first[cols])  # noqa: E731
            sep = static_rows(table, shaped, x, statics, solid, 0.0, angle, meets, self.fast)[3]
            deepest = max(deepest, float(-sep.min(initial=0.0)))
        return deepest

    def _stray_overlap(
        self,
        x: np.ndarray,
        x_free: np.ndarray,
        live: np.ndarray,
        a: np.ndarray,
        b: np.ndarray,
        store: Any,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """Pairs of discs overlapping at the step's end that the plan did not list, one of
        them off its own path by more than 5% of its radius (the plan's margin): (a, b,
        overlap in length units), or None. One grid over the live discs, only when a body
        strayed that far (a pile at rest does not: gravity's dt^2 is far less)."""
        r = store.radius
        off = norm(x[live] - x_free[live]) > 0.05 * r[live]
        if not off.any() or len(live) < 2:
            return None
        round_ = live if self._table is None else live[~self._table.shaped[live]]
        if len(round_) < 2:
            return None
        strayed = np.zeros(len(x), dtype=bool)
        strayed[live[off]] = True
        i, j = grid_pairs(x[round_], 2.0 * float(r[round_].max()) + 1e-300, fast=self.fast)
        pa, pb = round_[i], round_[j]
        keep = strayed[pa] | strayed[pb]
        pa, pb = np.minimum(pa[keep], pb[keep]), np.maximum(pa[keep], pb[keep])
        if not self._plain:
            g, c, m = store.group, store.categories, store.mask
            ok = ~((g[pa] == g[pb]) & (g[pa] != 0)) & ((c[pa] & m[pb]) != 0)
            ok &= (c[pb] & m[pa]) != 0
            pa, pb = pa[ok], pb[ok]
        over = r[pa] + r[pb] - norm(x[pa] - x[pb])
        deep = over > SLOP * np.minimum(r[pa], r[pb])
        if not deep.any():
            return None
        pa, pb, over = pa[deep], pb[deep], over[deep]
        if len(a):
            n = np.int64(len(x))
            listed = sorted_unique(np.minimum(a, b).astype(np.int64) * n + np.maximum(a, b))
            new = ~isin_sorted(pa.astype(np.int64) * n + pb, listed)
            pa, pb, over = pa[new], pb[new], over[new]
        return (pa, pb, over) if len(pa) else None

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
        spin: Spin | None,
        handover: bool = False,
        bends: Bends | None = None,
    ) -> tuple[list[tuple[np.ndarray, ...]], np.ndarray | None, np.ndarray | None] | None:
        """``engine.exact.pair_impacts.exact`` (the impacts of pairs not both in a pile, in place on
        (x, v)), counting its rounds and a capped step: the impacts and the pile's kick and
        turn (the impulses and their moments its bodies took as moving walls), or
        None when a crowd under load was handed over (its World rows in ``_handed``). The
        impacts turn the discs that turn (in place on ``spin``; one made when there was none
        and an impact turned a body is kept in ``spun``). ``bends``: the paths the static
        contacts bent (engine.exact.bent_paths); the contacts' reports of the bounces an impact
        sent a body off before are dropped."""
        got = exact(
            a, b, island, x, v, A, P, dt, self._t0, store, contacts,
            self.asleep, self._has_kin, handover, self.fast, spin, bends,
        )  # fmt: skip
        if spin is None and got.spin is not None:
            self.spun = got.spin
        if got.rounds:
            self.last_rounds = got.rounds
        self.capped += int(got.capped)
        if got.impacts is None:
            assert got.handed is not None
            self._handed = got.handed
            return None
        if got.cut is not None and contacts is not None:
            contacts.forget(got.cut[0], self._t0 + got.cut[1], self._reports)
        return got.impacts, got.kick, got.turn

    def _bent(
        self,
        a: np.ndarray,
        b: np.ndarray,
        island: np.ndarray,
        x0: np.ndarray,
        v0: np.ndarray,
        x1: np.ndarray,
        v1: np.ndarray,
        A: np.ndarray,
        dt: float,
        t0: float,
        store: Any,
        contacts: Contacts | None,
        spin: Spin | None = None,
    ) -> tuple[Bends | None, np.ndarray, np.ndarray]:
        """The paths the static contacts bent in the step (engine.exact.bent_paths; None if none),
        and the pairs (a, b) with those appended that a bent path may bring within touch
        (World rows, a < b), less those never to collide, with a shape (the soft step's), or
        of two sleepers. ``spin``: the step's rotation (the discs the bounces turned)."""
        search = self._search
        if contacts is None or not contacts.began_arrays or search is None:
            return None, a, b
        q_turn = None
        if spin is not None:
            # The discs the bounces' friction turned (engine.dynamics.rotation, ``rolling``).
            turned = spin.turns & (spin.q > 0.0) & (store.friction > 0.0)
            q_turn = np.where(turned, spin.q, 0.0)
        bends = bends_of(
            contacts.began_arrays, contacts.ended_arrays, x0, v0, x1, v1, A, store.radius,
            store.mass, contacts.rest, dt, t0, q_turn,
        )  # fmt: skip
        if bends is None:
            return None, a, b
        # The sweep's reports, before any the impacts add (``Contacts.record``).
        self._reports = (len(contacts.began_arrays), len(contacts.ended_arrays))
        na, nb = bent_rows(bends, search, A, dt, store, island, self._has_kin, self._plain)
        n = len(x0)
        keep = new_pairs(a, b, na, nb, n)
        if len(self.apart):
            keep &= ~np.isin(na.astype(np.int64) * n + nb, self.apart)
        shaped = self._shapes(store).shaped
        if shaped.any():
            keep &= ~(shaped[na] | shaped[nb])
        if self.asleep.any():
            keep &= ~(self.asleep[na] & self.asleep[nb])
        return bends, np.concatenate([a, na[keep]]), np.concatenate([b, nb[keep]])

    def _carried(self) -> Carried:
        """The impulses the last step's contacts carry (engine.exact.pile), from this object's."""
        return Carried(
            self._keys, self._lam, self._lam_dt, self._base, self._color_keys, self._colors
        )

    def _carry(self, carried: Carried) -> None:
        """Keep ``carried`` for the next step."""
        self._keys, self._lam = carried.keys, carried.lam
        self._lam_dt, self._base = carried.lam_dt, carried.base
        self._color_keys, self._colors = carried.color_keys, carried.colors

    # -- events ----------------------------------------------------------------------------------
    @property
    def touching(self) -> np.ndarray:
        """Keys (a * N + b, World rows a < b, N bodies) of the pairs touching after the last
        step, sorted."""
        return self._touching

    @property
    def began_arrays(self) -> list[tuple[Any, ...]]:
        """``began`` as held: (rows, other rows, points or None, normals, impulses, times)
        arrays, a batch a tuple (engine.dynamics.pair_events)."""
        return self._began

    @property
    def ended_arrays(self) -> list[tuple[Any, ...]]:
        """``ended`` as held, as ``began_arrays``."""
        return self._ended

    @property
    def struck_arrays(self) -> list[tuple[Any, ...]]:
        """The batches of ``began_arrays`` that are impacts (a blow, found on the bodies' free
        paths: their points given), not pairs that began to touch at rest or that the joints'
        solve held touching (points None: engine.dynamics.pair_events)."""
        return [batch for batch in self._began if batch[2] is not None]

    def hold_touching(self, keys: np.ndarray) -> None:
        """Pairs (a * n + b) that the joints' solve held touching at the step's end
        (engine.exact.joint_solver: a ball it caught on a bat): they touch now, for the events, as
        the pile's pairs do; one that did not touch before begins, one the pile let go of
        has not ended."""
        n = len(self.asleep)
        keys = sorted_unique(keys)
        new = keys[~isin_sorted(keys, self._touching)]
        if not len(new):
            return
        kept = []
        for rows, others, *rest in self._ended:
            gone = isin_sorted(rows.astype(np.int64) * n + others, new)
            if gone.any():
                ended_now = rows.astype(np.int64)[gone] * n + others[gone]
                new = new[~isin_sorted(new, sorted_unique(ended_now))]
                rest = [r if r is None else r[~gone] for r in rest]
                rows, others = rows[~gone], others[~gone]
            if len(rows):
                kept.append((rows, others, *rest))
        self._ended = kept
        if len(new):
            zero = np.zeros((len(new), 2))
            self._began.append(
                (new // n, new % n, None, zero, zero, np.full(len(new), self._t0 + self._dt))
            )
        self._touching = sorted_unique(np.concatenate([self._touching, keys]))

    def set_events(self, began: list[tuple[Any, ...]], ended: list[tuple[Any, ...]]) -> None:
        """Hold ``began`` and ``ended`` (batches as ``began_arrays``) as the last step's
        events: a step taken again in substeps reports all of theirs (engine.pipeline.stepping)."""
        self._began, self._ended = began, ended

    @property
    def began(self) -> list[tuple[int, int, Any, Any, Any, float]]:
        """Contacts between bodies that began in the last step: (row, other row, point, normal
        toward row, impulse on row, time) each; point None where it is taken from the state."""
        return unpack(self._began)

    @property
    def ended(self) -> list[tuple[int, int, Any, Any, Any, float]]:
        """Contacts between bodies that ended in the last step, as ``began``."""
        return unpack(self._ended)
