"""The World: bodies, the forces on them, and the one place where time advances.

The World is a thin door onto a few concepts, each in a module of its own:

* ``engine.store``: every per-body array (positions, velocities, masses, own accelerations),
  and the Bodies that are live handles into them;
* ``engine.forcefield``: the forces compiled into per-body arrays, a = a0 - c v + the rest;
* ``engine.policy``: which method moves the bodies ("auto" and its tolerance) and the
  stability warnings;
* ``engine.integrators`` and the closed form: how one step is taken.

The World owns time: ``step(dt)`` is the only way it moves, and it keeps the last finite
state if a step would make any number nan or inf.

>>> from engine import Body, Vector
>>> from engine.forces import Gravity
>>> world = World(integrator="auto")
>>> ball = world.add(Body(Vector(0, 0), Vector(3, 4), Vector(0, 0)))
>>> _ = world.add_force(Gravity((0, -10)))
>>> world.method
'exact'
>>> for _ in range(10):
...     world.step(0.1)
>>> ball.pos                      # (3 t, 4 t - 5 t^2) at t = 1 s, exactly
Vector(3.0, -1.0)
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Iterable
from typing import Any, TypeVar

import numpy as np

from . import checks, event_dispatch, habits, queries, readout
from . import snapshot as snapshots
from .affine import EULERS, prepare_affine
from .body import Body, State
from .colliders import Collider
from .collisions import Collisions
from .contacts import Contacts
from .events import ContactEvent
from .filters import Filter
from .forcefield import ForceModel
from .forces import Force, as_force
from .habits import PYMUNK_NAMES
from .integrators import Integrator
from .links import Link, LinkSolver, Pin
from .overlaps import OverlapWarning, freed, push_out
from .policy import AUTO_ORDER, METHODS, MethodPolicy
from .queries import QueryHit
from .snapshot import WorldSnapshot
from .stability import SimulationDiverged, StabilityWarning
from .store import BodyStore
from .world_state import AttachedForce, WorldState

__all__ = [
    "World",
    "WorldSnapshot",
    "METHODS",
    "check_dt",
    "OverlapWarning",
    "QueryHit",
    "PYMUNK_NAMES",
]

# Kept for code that imported it from here: "auto" tries these, cheapest first.
_AUTO_ORDER = AUTO_ORDER

# np.add.reduce(a, None) sums every entry without the Python wrapper of ndarray.sum.
_sum = np.add.reduce


def check_dt(dt: Any) -> float:
    """``dt`` as a positive finite float (s), else TypeError / ValueError naming it."""
    return checks.seconds(dt, "dt")


#: How many parts a step is taken again in when a linked body is struck in it.
SUBSTEPS_AT_IMPACT = 16

#: What add_collider and add_link hand back: the very object given, with its own type.
ColliderT = TypeVar("ColliderT", bound=Collider)
LinkT = TypeVar("LinkT", bound=Link)


class World:
    """Point bodies, the forces on them, and ``step(dt)``: the only way time moves.

    ``integrator`` is a name from ``METHODS``: ``"explicit_euler"``,
    ``"semi_implicit_euler"`` (the default), ``"velocity_verlet"``, ``"rk4"``,
    ``"exact"`` (the closed form; all forces must be constant) or ``"auto"`` (the
    closed form when the forces allow it, else the cheapest method that is stable
    at the step's dt). A function with the integrator signature is accepted too.

    ``tolerance`` (m, only with "auto"): the largest position error any body may build up,
    against the exact solution of the same forces, over ``engine.accuracy.HORIZON`` = 1 s of
    simulated time from the state at the first step of each new dt. "auto" then takes the
    cheapest stable method predicted to meet it (``predicted_error``, derived in
    ``engine.accuracy``), or the most accurate stable one when none does (``method_reason``
    then says which dt would meet it).
    """

    def __init__(
        self, integrator: str | Integrator = "semi_implicit_euler", tolerance: float | None = None
    ) -> None:
        self._s = WorldState(self, MethodPolicy(integrator, tolerance))
        self._s.events._view = event_dispatch.EventView(self._s)

    # The parts that tests and engine.queries read: the body arrays, the bodies, the compiled
    # forces, the static contacts and the contacts between bodies.
    @property
    def _store(self) -> BodyStore | None:
        return self._s.store

    @property
    def _bodies(self) -> list[Body]:
        return self._s.bodies

    @property
    def _model(self) -> ForceModel | None:
        return self._s.model

    @property
    def _contacts(self) -> Contacts | None:
        return self._s.contacts

    @property
    def _collisions(self) -> Collisions:
        return self._s.collisions

    # -- bodies and forces ----------------------------------------------------------------
    @property
    def bodies(self) -> tuple[Body, ...]:
        """The bodies in the world, in the order they were added."""
        return tuple(self._s.bodies)

    @property
    def forces(self) -> tuple[Force, ...]:
        """The forces in the world, in the order they were added."""
        return tuple(a.force for a in self._s.forces)

    @property
    def dim(self) -> int | None:
        """1 (floats), 2 (Vectors), or None while the world has neither bodies nor shaped forces."""
        return None if self._s.store is None else self._s.store.dim

    @property
    def integrator(self) -> str:
        """The method asked for: a name from METHODS, or the custom function's name."""
        return self._s.requested

    def add(self, body: Body) -> Body:
        """Add ``body`` and return it; from now on its pos/vel are the world's live state."""
        return self.add_all([body])[0]

    def add_all(self, bodies: Iterable[Body]) -> list[Body]:
        """Add many bodies at once (one array copy instead of one per body); return them.

        All or nothing: a batch with one bad body is refused whole and changes nothing.
        """
        batch = list(bodies)
        for b in batch:
            if not isinstance(b, Body):
                raise TypeError(f"World.add takes a Body, got {type(b).__name__} {b!r}")
            if b.world is not None:
                which = "this" if b.world is self else "another"
                raise ValueError(f"that body is already in {which} World; remove it first")
        if len({id(b) for b in batch}) != len(batch):
            raise ValueError("World.add_all was given the same body twice")
        if not batch:
            return batch
        # An empty World takes the dimension of the first body; every body must share it.
        dim = self.dim if self.dim is not None else batch[0].dim
        for b in batch:
            self._s.check_dim(b.dim, "the body", dim)
        store = self._s.ensure_store(dim)
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
                np.array([b.filter.group for b in batch], dtype=np.int64),
                np.array([b.filter.categories for b in batch], dtype=np.int64),
                np.array([b.filter.mask for b in batch], dtype=np.int64),
            ),
            np.array([b.kinematic for b in batch], dtype=bool),
            [b.shape for b in batch],
        )
        for b, slot in zip(batch, slots, strict=True):
            b._store, b._slot = store, slot
            self._s.bodies.append(b)
        if self._s.contacts is not None:
            self._s.contacts.bodies_added(len(batch))
            push_out(self._s, range(len(self._s.bodies) - len(batch), len(self._s.bodies)))
        self._s.changed_structure(appended=True)
        return batch

    def remove(self, body: Body) -> None:
        """Take ``body`` out of the world; it keeps its last position, velocity and mass."""
        if not isinstance(body, Body) or body.world is not self:
            raise ValueError(f"that body is not in this World: {body!r}")
        store = self._s.store
        assert store is not None
        pos, vel, mass, own = body.pos, body.vel, body.mass, body.own_acc
        row = store.row(body._slot)
        # The last step's events are named now, before the rows shift, and the body's open
        # contacts end (reported with the next step).
        self._s.events.body_removed(body._slot, self.t)
        del self._s.bodies[row]
        self._s.targets.pop(body, None)
        store.remove(body._slot)
        gone = [k for k in self._s.links if body in k.bodies]
        if gone:
            # Its links go with it.
            self._s.links = [k for k in self._s.links if body not in k.bodies]
            self._s.links_changed()
        if self._s.contacts is not None:
            self._s.contacts.body_removed(row)
            freed(self._s, [b for k in gone for b in k.bodies if b is not body])
        for attached in self._s.forces:
            if attached.bodies is not None and body in attached.bodies:
                attached.bodies.remove(body)
        body._store, body._slot = None, -1
        body._store_pos(pos)
        body._store_vel(vel)
        body._mass, body._acc = mass, own
        self._s.changed_structure()

    def add_force(
        self, force: Force | Callable[..., Any], bodies: Iterable[Body] | None = None
    ) -> Force:
        """Add a force (a Force, or a callable ``f(t, x, v, mass) -> force``); return it.

        ``bodies``: the bodies it acts on (all of them, now and later, when None).
        """
        f = as_force(force)
        if f.dim is not None:
            self._s.check_dim(f.dim, repr(f))
        if self._s.requested == "exact" and not f.constant:
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
                if not isinstance(b, Body) or b.world is not self:
                    raise ValueError(
                        f"bodies must be bodies already added to this World, got {b!r}"
                    )
        if f.dim is not None:
            self._s.ensure_store(f.dim)  # checked above; an empty World takes the force's dim
        self._s.forces.append(AttachedForce(f, members))
        self._s.changed_structure()
        return f

    # -- links ------------------------------------------------------------------------------
    @property
    def links(self) -> tuple[Link, ...]:
        """The links (rods, cables, pins), in the order they were added."""
        return tuple(self._s.links)

    def add_link(self, link: LinkT) -> LinkT:
        """Add a link (``engine.links``: Rod, Cable, Pin) between bodies of this World, or a
        body and a fixed point, and return it. A pinned body is moved to its pin at once."""
        if not isinstance(link, Link):
            raise TypeError(
                f"add_link takes a link from engine.links (Rod, Cable, Pin), got "
                f"{type(link).__name__} {link!r}"
            )
        if any(k is link for k in self._s.links):
            raise ValueError(
                f"that link is already in this World (a link is added only once): {link!r}"
            )
        for b in link.bodies:
            if b.world is not self:
                raise ValueError(
                    f"the link's bodies must be in this World first (world.add(body)): {b!r}"
                )
        if isinstance(link, Pin):
            if any(isinstance(k, Pin) and k.body is link.body for k in self._s.links):
                raise ValueError(
                    f"that body is pinned already: a body takes only one Pin (remove_link the "
                    f"old one first): {link.body!r}"
                )
            if link.body.kinematic:
                raise ValueError(
                    f"a kinematic body is moved by the game and cannot be pinned: {link.body!r}"
                )
        self._s.links.append(link)
        self._s.links_changed()
        if isinstance(link, Pin):
            store = self._s.store
            assert store is not None
            row = store.row(link.body._slot)
            store.x[row] = store.prev_x[row] = tuple(link.point)
            store.v[row] = 0.0
            self._s.state_written()
        return link

    def remove_link(self, link: Link) -> None:
        """Take a link out of the world (a pinned body is free again)."""
        if not any(k is link for k in self._s.links):
            raise ValueError(f"that link is not in this World: {link!r}")
        self._s.links = [k for k in self._s.links if k is not link]
        self._s.retired.append(link)
        self._s.links_changed()
        freed(self._s, list(link.bodies))

    def _solve_links(
        self,
        store: BodyStore,
        x1: np.ndarray,
        v1: np.ndarray,
        dt: float,
        kinked: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Correct the step's end state for the links (engine.links), warning once per link
        stretched past what a step can hold."""
        solver = self._s.link_solver
        if solver is None:
            solver = self._s.link_solver = LinkSolver(self._s.links, lambda b: store.row(b._slot))
        w = np.where(store.kinematic, 0.0, 1.0 / store.mass)
        x1, v1 = solver.resolve(store.x, x1, store.v, v1, w, dt, kinked)
        if solver.moved:
            self._s.anchor = None
        for link in solver.stretched:
            if not link.warned:
                link.warned = True
                warnings.warn(
                    f"{link!r} was stretched past what one step of dt={dt:g} s can pull back "
                    f"along it: it was put back to its length directly; take a smaller dt",
                    StabilityWarning,
                    stacklevel=4,
                )
        return x1, v1

    # -- colliders and contacts ---------------------------------------------------------------
    @property
    def colliders(self) -> tuple[Collider, ...]:
        """The static colliders, in the order they were added."""
        return () if self._s.contacts is None else tuple(self._s.contacts.colliders)

    def add_collider(self, collider: ColliderT) -> ColliderT:
        """Add a static collider (``engine.colliders``) and return it.

        Bodies already inside it are pushed out to its surface, with an OverlapWarning naming
        both. Colliders are 2D: a 1D World refuses them.
        """
        if not isinstance(collider, Collider):
            raise TypeError(
                f"add_collider takes a collider from engine.colliders (Plane, Segment, Circle, "
                f"Box), got {type(collider).__name__} {collider!r}"
            )
        self._s.check_dim(2, f"the collider {collider!r}")
        if collider in self.colliders:
            raise ValueError(f"that collider is already in this World: {collider!r}")
        store = self._s.ensure_store(2)
        if self._s.contacts is None:
            self._s.contacts = Contacts()
            self._s.contacts.bodies_added(len(store))
        self._s.events.settle_reading()
        self._s.contacts.add(collider)
        self._s.events.collider_added(collider)
        self._s.collisions.wake(len(self._s.bodies))
        push_out(self._s, range(len(self._s.bodies)))
        self._s.changed_structure()
        return collider

    def remove_collider(self, collider: Collider) -> None:
        """Take a collider out of the world."""
        if collider not in self.colliders:
            raise ValueError(f"that collider is not in this World: {collider!r}")
        assert self._s.contacts is not None
        # The last step's events are named now, and the collider's open contacts end
        # (reported with the next step).
        self._s.events.collider_removed(collider, self.t)
        self._s.contacts.remove(collider)
        self._s.collisions.wake(len(self._s.bodies))
        self._s.changed_structure()

    def on_contact(
        self,
        target: Body | Collider,
        begin: Callable[[ContactEvent], Any] | None = None,
        end: Callable[[ContactEvent], Any] | None = None,
        post_solve: Callable[[ContactEvent], Any] | None = None,
    ) -> Callable[[], None]:
        """Call ``begin(event)`` / ``end(event)`` after each step for the contacts of ``target``
        that began or ended in it, and ``post_solve(event)`` for each of its contacts that is
        open after the step (pymunk's name: ``event.impulse`` is what the contact carried over
        the step; a 2 kg ball resting on a floor under g gets 2 g dt).

        ``target`` is a Body in this World or a collider; the calls come after the step, in the
        order the contacts happened (``World.began``, ``World.ended`` and ``World.touching``
        list them too). For a Body, ``event.body`` is that Body (the other is
        ``event.collider``). Returns a function that takes the handler off again.
        """
        return event_dispatch.add_handler(self._s, target, begin, end, post_solve)

    @property
    def sleeping(self) -> int:
        """How many bodies sleep (a still pile: they cost nothing until something meets them)."""
        return int(self._s.collisions.asleep.sum())

    def is_sleeping(self, body: Body) -> bool:
        """Whether ``body`` sleeps (it stays exactly put until an awake body meets its group)."""
        return readout.is_sleeping(self._s, body)

    def overlap(self) -> float:
        """The deepest overlap (length units) between two bodies that collide, now."""
        return readout.overlap(self._s)

    @property
    def sleep_time(self) -> float:
        """Seconds a group of resting bodies must stay still before it sleeps (default 0.5;
        math.inf: never, every body stays awake)."""
        return self._s.collisions.sleep_time

    @sleep_time.setter
    def sleep_time(self, value: float) -> None:
        self._s.set_sleep_time(value)

    @property
    def contact_iterations(self) -> int:
        """Iterations a step of the solver for bodies resting on one another (default 8):
        more hold deeper piles with less overlap, at a cost per iteration."""
        return self._s.collisions.iterations

    @contact_iterations.setter
    def contact_iterations(self, value: int) -> None:
        self._s.set_contact_iterations(value)

    @property
    def capped(self) -> int:
        """How many times impacts passed their cap in one step: a body that met more than
        MAX_IMPACTS impacts with colliders (placed on a surface instead), or a step whose
        impacts between bodies passed MAX_ROUNDS rounds (the bodies with impacts left
        stopped at the first of them, to go on next step)."""
        return self._s.capped

    def resting(self, body: Body) -> Collider | None:
        """The collider ``body`` rests on (slides or sits on), or None while it is in flight."""
        return readout.resting(self._s, body)

    @property
    def began(self) -> list[ContactEvent]:
        """The contacts that began in the last step (a bounce, a landing, entering a sensor),
        in time order; each contact begins once and ends once (``engine.events``)."""
        return self._s.events.began

    @property
    def ended(self) -> list[ContactEvent]:
        """The contacts that ended in the last step (a bounce ends as it begins; a rest ends
        when the body lifts off; leaving a sensor; a body or collider taken out since the
        step before, with ``removal`` True), in time order."""
        return self._s.events.ended

    @property
    def touching(self) -> list[ContactEvent]:
        """Every contact open after the last step, with the impulse (N s) it carried over the
        step (pymunk's arbiters and their ``total_impulse``)."""
        return self._s.events.touching

    # -- queries (engine.queries) ---------------------------------------------------------
    def segment_query(
        self,
        start: Any,
        end: Any,
        radius: float = 0.0,
        filter: Filter | None = None,  # noqa: A002
    ) -> list[QueryHit]:
        """Every body and collider (sensors too) a segment from ``start`` to ``end`` meets, in
        the order met: a QueryHit each with ``fraction`` (0 at start, 1 at end), the point
        where the swept centre first touches and the normal there. ``radius`` > 0 sweeps a
        disc; ``filter`` (an engine.Filter) sees only the shapes it collides with."""
        return queries.segment_query(self, start, end, radius, filter)

    def segment_query_first(
        self,
        start: Any,
        end: Any,
        radius: float = 0.0,
        filter: Filter | None = None,  # noqa: A002
    ) -> QueryHit | None:
        """The first body or collider (sensors too; a filter can leave them out) a segment
        from ``start`` to ``end`` meets, as ``segment_query``; None when nothing is met."""
        hits = queries.segment_query(self, start, end, radius, filter)
        return hits[0] if hits else None

    def point_query(
        self,
        point: Any,
        max_distance: float = 0.0,
        filter: Filter | None = None,  # noqa: A002
    ) -> list[QueryHit]:
        """Bodies and colliders whose surface lies within ``max_distance`` of ``point``.

        Nearest first; ``distance`` is from the shape's surface (< 0 inside), ``point`` the
        nearest point of that surface. A mouse pick is ``world.point_query(mouse, 0.1)``.
        """
        return queries.point_query(self, point, max_distance, filter)

    def point_query_nearest(
        self,
        point: Any,
        max_distance: float = 0.0,
        filter: Filter | None = None,  # noqa: A002
    ) -> QueryHit | None:
        """The nearest shape within ``max_distance`` of ``point`` (``point_query``'s first),
        or None."""
        hits = queries.point_query(self, point, max_distance, filter)
        return hits[0] if hits else None

    def bb_query(self, bb: Any, filter: Filter | None = None) -> list[Any]:  # noqa: A002
        """The bodies and colliders that overlap the box ``bb`` = (left, bottom, right, top)."""
        return queries.bb_query(self, bb, filter)

    def shape_query(self, shape: Any, filter: Filter | None = None) -> list[QueryHit]:  # noqa: A002
        """The bodies and colliders a ``Circle`` or ``Segment`` (placed where asked, not
        added) overlaps, deepest first; ``distance`` < 0 is the depth of each overlap."""
        return queries.shape_query(self, shape, filter)

    # -- derived state ----------------------------------------------------------------------
    def _apply_targets(self, dt: float) -> dict[Body, np.ndarray]:
        """Each kinematic body with a target takes the velocity that reaches it in ``dt``;
        return the velocities they had, to be given back after the step."""
        store = self._s.store
        assert store is not None
        before = {}
        moves = {}
        for body, target in self._s.targets.items():
            row = store.row(body._slot)
            with np.errstate(over="ignore", invalid="ignore"):
                v = (np.asarray(target, dtype=float) - store.x[row]) * (1.0 / dt)
            if not np.isfinite(v).all():
                del self._s.targets[body]
                raise ValueError(
                    f"pos={target!r} of a kinematic body is too far to reach in one step of "
                    f"dt={dt!r} s (the speed passes the float range): the move was dropped; "
                    f"give a nearer position"
                )
            moves[row] = v
        for body in self._s.targets:
            row = store.row(body._slot)
            before[body] = store.v[row].copy()
            store.v[row] = moves[row]
        self._s.targets.clear()
        self._s.anchor = None
        return before

    @property
    def evaluations(self) -> int:
        """How many times the forces on all bodies have been evaluated (a machine-free cost).

        Each step costs the method's evaluations (1 for the Euler methods, 2 for Verlet, 4 for
        RK4, 0 for the closed form); "auto" with a tolerance adds one for each method it
        predicts at a new dt.
        """
        return self._s.evaluations_now

    # -- choosing the method ------------------------------------------------------------------
    def max_stable_dt(self, integrator: str | None = None) -> float:
        """The largest stable dt (s) for the springs and drags held, for ``integrator``.

        ``integrator`` defaults to the method in use (for "auto": the best available).
        ``math.inf`` when nothing held limits the step; 0.0 when no dt is stable.
        """
        return self._s.policy.max_stable_dt(integrator or self.method, self._s.ready())

    @property
    def tolerance(self) -> float | None:
        """The position error (m) "auto" must keep within over 1 s, or None (stability only)."""
        return self._s.policy.tolerance

    def predicted_error(self, method: str, dt: float) -> float:
        """Predicted largest position error (m) of any body over the next 1 s of steps of ``dt``.

        Exact for the forces the World folds or knows the stiffness of (constant forces,
        gravity, drag, wind, springs of rest length 0); other forces are frozen at their value
        now. ``math.inf`` when ``method`` blows up within that second. See ``engine.accuracy``.
        """
        dt = check_dt(dt)
        return self._s.policy.predicted_error(method, dt, self._s.ready(), self._s.state_now)

    def choose_method(self, dt: float) -> tuple[str, str]:
        """(method, one-line reason) that this World uses for a step of ``dt`` seconds."""
        dt = check_dt(dt)
        return self._s.policy.choose(dt, self._s.ready(), self._s.state_now)

    @property
    def method(self) -> str:
        """The method in use; for "auto", the one chosen at the last step (or "auto" before)."""
        return self._s.method

    @property
    def method_reason(self) -> str:
        """One line saying why ``method`` is the method in use."""
        return self._s.method_reason

    # -- time --------------------------------------------------------------------------------
    @property
    def t(self) -> float:
        """Simulated time (s) since the world began."""
        n = self._s.count.n
        return self._s.t_base + n * self._s.dt if self._s.dt is not None else self._s.t_base

    @property
    def dt(self) -> float | None:
        """The length (s) of the last step, or None before the first (pymunk's
        ``current_time_step``)."""
        return self._s.dt

    @property
    def steps(self) -> int:
        """How many steps have been taken."""
        return self._s.steps_base + self._s.count.n

    def step(self, dt: float) -> None:
        """Advance every body by ``dt`` seconds (usually 1/60 or 1/120).

        Raises ValueError for dt <= 0, nan or inf (nothing changes), warns with a
        StabilityWarning the first time dt is past the method's limit for a force
        held, and raises SimulationDiverged, keeping the last finite state, if the
        state stops being finite.
        """
        k = self._s.kernel
        if k is not None and k.take(dt):
            return  # the affine kernel (engine.affine): what small scenes take, call-light
        count = self._s.count
        fast = self._s.fast
        if fast is not None and type(dt) is float and fast[0] == dt and fast[1] == self._s.version:
            # Same dt, nothing changed since the last step.
            _, _, name, step, model, affine = fast
        else:
            dt = check_dt(dt)
            model = self._s.ready()
            name = self._s.policy.method_for(dt, self._s.version, model, self._s.state_now)
            step = None if name == "exact" else self._s.policy.integrator(name)
            # Either Euler method on forces that are all folded (a = a0 - c v) is a fixed
            # affine map of the state: the World takes it in four array operations.
            st = self._s.store
            self._s.pairs_on = (
                st is not None
                and st.dim == 2
                and self._s.collisions.active(
                    st.radius, st.group, st.categories, st.mask, st.shapes
                )
            )
            affine = (
                name in EULERS
                and self._s.policy.custom is None
                and model.affine
                and self._s.contacts is None
                and not self._s.pairs_on
                and not self._s.links
                and not self._s.events.busy
            )
            self._s.fast = (dt, self._s.version, name, step, model, affine)
        if dt != self._s.dt:
            # Fold the time so far into the base before counting steps of a new dt.
            self._s.void_budget()
            self._s.t_base, self._s.steps_base = self.t, self._s.steps_base + self._s.n
            self._s.n, self._s.dt = 0, dt
        if self._s.t_base + (count.n + 1) * dt == math.inf:
            raise ValueError(
                f"dt must keep the time finite: a step of dt={dt!r} s from t={self.t!r} s would "
                f"pass the float range (1.8e308 s)"
            )
        after = self._apply_targets(dt) if self._s.targets else None
        if self._s.bodies and affine and after is None and prepare_affine(self._s, dt, model, name):
            return self.step(dt)  # now the fast path above takes it
        if self._s.bodies:
            self._step_general(dt, name, step, model)
        else:
            self._quiet()  # nothing moved: no solver reports anything
        count.n += 1
        if after is not None:
            # A kinematic body moved by pos stops there: its velocity is what it was before.
            held = self._s.store
            assert held is not None
            for body, v in after.items():
                held.v[held.row(body._slot)] = v
        if self._s.contacts is not None or self._s.pairs_on or self._s.events.busy:
            # The step ran from t0 = t_base + (n - 1) dt (the time it started at, summed the
            # same way) to t.
            event_dispatch.settle(self._s, self._s.t_base + (self._s.n - 1) * dt, self.t)
            event_dispatch.report(self._s)

    def _quiet(self) -> None:
        """A step in which no body moved: the solvers report nothing."""
        if self._s.contacts is not None:
            self._s.contacts.quiet()
        self._s.collisions.quiet()

    def _step_general(
        self, dt: float, name: str, step: Integrator | None, model: ForceModel
    ) -> None:
        """One step by the closed form or an integrator function, every entry checked.

        With links and contacts both in the World, a step in which a linked body is struck
        is taken again as SUBSTEPS_AT_IMPACT steps: the blow is found on each body's free
        path, which misses the links' pull within the step, so its error is second order in
        the step (engine.links; README "Links"), and 16 times smaller steps make it 256
        times smaller where it matters, at the cost of one step's work 17 times.
        """
        store = self._s.store
        assert store is not None
        t0 = self.t
        t1 = self._s.t_base + (self._s.count.n + 1) * dt
        contacts = self._s.contacts
        if not self._s.links or self._s.substeps or (contacts is None and not self._s.pairs_on):
            self._step_once(dt, name, step, model, t0, t1)
            return
        saved = (
            store.x.copy(),
            store.v.copy(),
            store.prev_x,
            self._s.anchor,
            self._s.huge,
            self._s.collisions.state(),
            None if contacts is None else contacts.state(),
        )
        self._step_once(dt, name, step, model, t0, t1)
        if not self._struck_linked():
            return
        store.x, store.v, store.prev_x = saved[0], saved[1], saved[2]
        self._s.anchor, self._s.huge = saved[3], saved[4]
        self._s.collisions.set_state(saved[5])
        if contacts is not None and saved[6] is not None:
            contacts.set_state(saved[6], len(store))
        k = SUBSTEPS_AT_IMPACT
        h = dt / k
        sources = [self._s.collisions] + ([] if contacts is None else [contacts])
        events: list[tuple[list[Any], list[Any]]] = [([], []) for _ in sources]
        self._s.substeps = True
        try:
            for i in range(k):
                end = t1 if i == k - 1 else t0 + (i + 1) * h
                self._step_once(h, name, step, model, t0 + i * h, end)
                for source, (began, ended) in zip(sources, events, strict=True):
                    began += source._began
                    ended += source._ended
        finally:
            self._s.substeps = False
        for source, (began, ended) in zip(sources, events, strict=True):
            source._began, source._ended = began, ended
        store.prev_x = saved[0]  # drawing blends from where the whole step began

    def _struck_linked(self) -> bool:
        """Whether a contact began in the last step for a body with a link."""
        solver = self._s.link_solver
        if solver is None:
            return False
        linked = np.zeros(len(self._s.bodies), dtype=bool)
        linked[solver.i] = True
        linked[solver.j[solver.j >= 0]] = True
        for rows, others, *_ in self._s.collisions._began if self._s.pairs_on else []:
            if linked[np.asarray(rows, dtype=np.intp)].any():
                return True
            if linked[np.asarray(others, dtype=np.intp)].any():
                return True
        if self._s.contacts is not None:
            # (The few-bodies path lists its rows as a tuple, the arrays' as an array.)
            for rows, *_ in self._s.contacts._began:
                if linked[np.asarray(rows, dtype=np.intp)].any():
                    return True
        return False

    def _step_once(
        self,
        dt: float,
        name: str,
        step: Integrator | None,
        model: ForceModel,
        t0: float,
        t1: float,
    ) -> None:
        """One step of ``dt`` from time t0 to t1 (what _step_general takes, once or in parts)."""
        store = self._s.store
        assert store is not None
        if self._s.pairs_on and self._s.collisions.all_asleep(len(store)):
            # Every body sleeps: nothing moves until something wakes them.
            store.prev_x = store.x
            self._s.collisions.quiet()
            if self._s.contacts is not None:
                self._s.contacts.quiet()
            return
        if step is None:
            if self._s.anchor is None:
                self._s.anchor = (store.x.copy(), store.v.copy(), t0)
            x0, v0, ta = self._s.anchor
            # Closed form from the anchor: s = s0 + v0 T + a T^2 / 2, v = v0 + a T.
            elapsed = t1 - ta
            a = model.a0
            x1 = x0 + v0 * elapsed + a * (0.5 * elapsed * elapsed)
            v1 = v0 + a * elapsed
        elif self._s.huge:
            # Near overflow (a blow-up under way): numpy's own overflow warnings would
            # only come before our clear SimulationDiverged, so silence them.
            with np.errstate(over="ignore", invalid="ignore"):
                x1, v1 = step(store.x, store.v, model.accel, t0, dt)
        else:
            x1, v1 = step(store.x, store.v, model.accel, t0, dt)
        self._s.huge = self._check_finite(x1, v1, name, dt, t0) > 1e100
        v_method = v1
        v_free = v1
        contacts = self._s.contacts
        pairs = self._s.collisions
        pull = model.a0 if step is None else (v_method - store.v) * (1.0 / dt)
        frozen = self._frozen(store)
        if self._s.pairs_on:
            # Which bodies are in a pile (engine.collisions): the soft step takes them, from
            # the start of the step; the static contacts leave them to it.
            held = None if contacts is None else contacts.rest >= 0
            pile = pairs.plan(store.x, store.v, x1, v1, pull, dt, store, held)
            if pile is not None:
                frozen = pile if frozen is None else frozen | pile
                if contacts is not None:
                    contacts.rest[pile] = -1  # their faces are the pile's rows now
        if contacts is not None:
            # The path of the step is swept for impacts (engine.contacts); under the closed
            # form it is the exact parabola.
            contacts.body_filters = (store.group, store.categories, store.mask)
            x1, v1 = contacts.resolve(
                store.x,
                store.v,
                x1,
                v1,
                dt,
                t0,
                store.radius,
                store.restitution,
                store.friction,
                store.mass,
                model.a0 if step is None else None,
                frozen,
                sense=not self._s.pairs_on,
            )
            if contacts.moved:
                self._s.anchor = None  # the closed form starts anew from the changed state
            # What the static contacts did to each velocity (a resting contact's impulse).
            self._s.contact_dv = v1 - v_free if contacts.moved else None
        if not self._s.pairs_on:
            pairs.quiet()  # no pair solved: none of its reports is this step's
        if self._s.pairs_on:
            # Bodies meet one another (engine.collisions) on the paths that end where the
            # method and the static contacts left them.
            A = pull
            if contacts is not None and contacts.moved:
                # A body resting on a collider is carried by it: its acceleration along the
                # path is the step's mean one.
                on = contacts.rest >= 0
                if on.any():
                    A = A.copy()
                    A[on] = (v1[on] - store.v[on]) * (1.0 / dt)
            x1, v1 = pairs.resolve(store.x, store.v, x1, v1, A, dt, t0, store, contacts, pull)
            if pairs.moved:
                self._s.anchor = None
            if contacts is not None:
                contacts.sense(x1, dt, t0, store.radius)  # where every body ended
            if pairs.last_overlap > 0.05 * pairs.rmin and not pairs.warned:
                # The resting solver's limit: a pile too deep for its iterations sinks into
                # itself (README: "Limits of the contact solver").
                pairs.warned = True
                warnings.warn(
                    f"bodies overlap by {pairs.last_overlap:.3g} length units "
                    f"({100 * pairs.last_overlap / pairs.rmin:.0f}% of the smallest radius): "
                    f"this pile is past what {pairs.iterations} contact iterations a step can "
                    f"hold; raise world.contact_iterations or take a smaller dt",
                    StabilityWarning,
                    stacklevel=3,
                )
        if self._s.links:
            kinked = None
            if v1 is not v_free:
                kinked = (v1 != v_free).any(axis=1)
            x1, v1 = self._solve_links(store, x1, v1, dt, kinked)
        store.prev_x, store.x, store.v = store.x, x1, v1
        self._s.void_budget()

    def _frozen(self, store: BodyStore) -> np.ndarray | None:
        """Bodies the static contacts leave alone: asleep, or moved by the game."""
        frozen = (
            self._s.collisions.asleep
            if self._s.pairs_on and self._s.collisions.any_asleep
            else None
        )
        kin = store.kinematic
        if kin.any():
            frozen = kin if frozen is None else frozen | kin
        return frozen

    def _check_finite(self, x: Any, v: Any, name: str, dt: float, t: float) -> float:
        """Raise SimulationDiverged if x or v has a nan or inf; else return |sum of x and v|."""
        # A sum is nan or inf whenever any of its terms is (nan + anything = nan,
        # inf - inf = nan), so two sums check every entry. Only when one is not finite (or
        # huge finite values overflowed it) look closer. Not a BLAS dot product: OpenBLAS
        # takes milliseconds on arrays that are not 64-byte aligned, which numpy's are not.
        if self._s.huge:
            with np.errstate(over="ignore", invalid="ignore"):
                s = abs(float(_sum(x, None) + _sum(v, None)))
        else:
            s = abs(float(_sum(x, None) + _sum(v, None)))
        if math.isfinite(s):
            return s
        if np.isfinite(x).all() and np.isfinite(v).all():
            return math.inf
        bad = [
            f"{i}"
            for i in range(len(self._s.bodies))
            if not (np.isfinite(x[i]).all() and np.isfinite(v[i]).all())
        ]
        limit = self.max_stable_dt(name) if name != "exact" else None
        hint = ""
        if limit is not None and limit < math.inf:
            hint = (
                f"; for the springs and drags held, {name} is stable only for dt < {limit:.4g} s"
                if limit > 0
                else f"; {name} is unstable at every dt for the springs held"
            )
        raise SimulationDiverged(
            f"{name} diverged in the step from t={t:g} s with dt={dt:g} s: body "
            f"{', '.join(bad[:5])}{' ...' if len(bad) > 5 else ''} would become non-finite "
            f"(nan or inf){hint}. The last finite state is kept.",
            integrator=name,
            dt=dt,
            t=t,
            max_stable_dt=limit,
        )

    # -- reading the state ---------------------------------------------------------------------
    def positions(self, alpha: float = 1.0) -> np.ndarray:
        """Positions of all bodies blended from the previous step: prev + (now - prev) alpha.

        ``alpha`` in [0, 1] comes from the fixed-step loop; 1.0 gives the current state.
        Shape (N,) in 1D, (N, 2) in 2D; a new array. As in every fixed-step loop that
        interpolates, what is drawn lies between the last two steps, so up to one step
        behind ``t``: step once ahead before the first frame (as ``engine.render.record``
        does) to draw each frame exactly at its own time.
        """
        return readout.positions(self._s, alpha)

    def position_of(self, body: Body, alpha: float = 1.0) -> State:
        """One body's position, blended like ``positions(alpha)``: a float or a Vector."""
        return readout.position_of(self._s, body, alpha)

    def velocities(self) -> np.ndarray:
        """Velocities of all bodies now, shape (N,) or (N, 2); a new array."""
        return readout.velocities(self._s)

    def energy(self) -> float:
        """Total mechanical energy (J): kinetic plus the potential of the forces that have one.

        A body's own constant acceleration a counts like gravity, with potential -m a . x.
        Kinematic and pinned bodies are left out: the game (or the pin) moves them, and no
        force acts on them.
        """
        return readout.energy(self._s)

    # -- snapshot and restore (engine.snapshot) ---------------------------------------------------
    def snapshot(self) -> WorldSnapshot:
        """Everything needed to bring this world back to this moment, bit for bit."""
        return snapshots.take(self._s)

    def restore(self, snapshot: WorldSnapshot) -> None:
        """Bring back the state saved by ``snapshot()`` (same bodies, in the same order)."""
        snapshots.restore(self._s, snapshot)

    # -- names the World does not have ----------------------------------------------------
    def __setattr__(self, name: str, value: Any) -> None:
        """Set the World's own attributes; refuse a name it does not have, saying what to use.

        Without this, ``world.gravity = (0, -9.8)`` (pymunk's habit) would be kept and
        ignored. A subclass may add names of its own. (No ``__getattr__``: it would slow every
        attribute read; pymunk's names are class attributes that say what to use instead.)
        """
        if name[0] == "_" or hasattr(type(self), name) or type(self) is not World:
            object.__setattr__(self, name, value)
        else:
            raise AttributeError(habits.unknown(World, name, "set"))

    def __repr__(self) -> str:
        """``World(integrator='auto', tolerance=0.001, bodies=3, forces=2, t=1.5)``."""
        tol = self._s.policy.tolerance
        tolerance = "" if tol is None else f"tolerance={tol:g}, "
        return (
            f"World(integrator={self._s.requested!r}, {tolerance}bodies={len(self._s.bodies)}, "
            f"forces={len(self._s.forces)}, t={self.t:g})"
        )


habits.install(World)
