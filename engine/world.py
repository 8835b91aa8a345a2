"""The World: bodies, the forces on them, and the one place where time advances.

The World is a thin door onto a few concepts, each in a module of its own:

* ``engine.pipeline.world_state``: what it holds (``engine.dynamics.store``: the per-body arrays
  behind the Bodies), its time, and the derived parts (``engine.dynamics.forcefield``: the forces
  compiled, a = a0 - c v + the rest; ``engine.dynamics.policy``: the method, "auto", stability
  warnings);
* ``engine.pipeline.stepping``: the step pipeline; ``engine.dynamics.affine``: the fast affine
  kernel;
* ``engine.pipeline.membership``: bodies, forces, links and colliders coming and going
  (``engine.exact.overlaps``: bodies found inside a collider, pushed out);
* ``engine.pipeline.event_dispatch``: contact events; ``engine.pipeline.queries``;
  ``engine.pipeline.snapshot``; ``engine.pipeline.readout``: positions, velocities, energy, sleep.

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
from collections.abc import Callable, Iterable
from copy import deepcopy
from numbers import Real
from typing import Any, NoReturn, TypeVar, overload

import numpy as np

from . import checks, habits
from .body import Body, State
from .dynamics.events import ContactEvent
from .dynamics.forcefield import ForceModel
from .dynamics.links import STATIC, Link, StaticBody
from .dynamics.mouse_joint import MouseJoint
from .dynamics.policy import METHODS, MethodPolicy
from .dynamics.springs import BodySpring
from .exact.contacts import Contacts
from .exact.overlaps import OverlapWarning
from .filters import Filter
from .forces import Force
from .geometry.colliders import Collider
from .geometry.query_grid import QueryIndex
from .habits import PYMUNK_NAMES
from .integrators import Integrator
from .kernels import choose as kernels_path
from .pipeline import (
    collision_handlers,
    event_dispatch,
    membership,
    queries,
    readout,
    solver_choice,
    stepping,
)
from .pipeline import snapshot as snapshots
from .pipeline.game_step import GameStep
from .pipeline.membership import ColliderT, LinkT
from .pipeline.queries import QueryHit
from .pipeline.snapshot import WorldSnapshot
from .pipeline.solver_choice import SOLVERS
from .pipeline.stepping import SUBSTEPS_AT_IMPACT as SUBSTEPS_AT_IMPACT  # README: engine.world's
from .pipeline.world_state import WorldState

#: What add_link hands back for a spring: the very spring given.
SpringT = TypeVar("SpringT", bound=BodySpring)

__all__ = [
    "World",
    "WorldSnapshot",
    "METHODS",
    "check_dt",
    "OverlapWarning",
    "QueryHit",
    "PYMUNK_NAMES",
]


def check_dt(dt: Any) -> float:
    """``dt`` as a positive finite float (s), else TypeError / ValueError naming it."""
    return checks.seconds(dt, "dt")


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

    ``kernels``: the path the hot loops take (``engine.kernels``): ``"fast"`` (numba's
    compiled loops, the ``fast`` extra), ``"numpy"`` (the reference), or None, the default:
    ``ENGINE_KERNELS`` if set, else fast where numba is installed. ``world.kernels`` says
    which this World runs; both give the same numbers to rounding.

    ``solver``: how contacts and joints are solved. ``"exact"``: the lesson's models, each
    impact at its exact moment, joints held to rounding (a ball's bounce heights h e^(2n),
    the cradle, a pendulum's period). ``"soft"``: a game's, Box2D v3's soft step
    (``engine.pipeline.game_step``, ``engine.dynamics.solver``): every contact and joint
    solved together in substeps, fast and steady for piles, platformers and pinball tables,
    with the errors a game accepts (a box rests 0.55 mm into the box it stands on, the floor
    holding its load; a hinge gives under load by what its 60 Hz spring allows). ``"auto"``
    (the default): the World chooses by the scene as it is at its first step
    (engine.pipeline.solver_choice): the soft step where a body with corners could be pushed
    by a contact or a joint only the soft step solves is held, the exact models otherwise
    (discs and points, a 1D world). ``world.solver`` says which this World runs, and
    ``world.solver_reason`` why.

    ``length_units_per_meter``: how many of the World's length units make a metre (Box2D's
    ``b2SetLengthUnitsPerMeter``): 1, the default, for a World in metres; 100 for one in
    centimetres (the pinball table); a pixel scale for one in pixels. The soft step's lengths
    and speeds, set in metres (a 5 mm slop and its 2 cm speculative distance, an overlap pushed
    apart at 3 m/s at most, a bounce only past 1 m/s, sleep under 5 cm/s), are scaled by it,
    so that a scene built in other units moves as the same scene in metres, scaled
    (``tests/test_units.py``). The exact models' tolerances are their own.
    """

    def __init__(
        self,
        integrator: str | Integrator = "semi_implicit_euler",
        tolerance: float | None = None,
        kernels: str | None = None,
        solver: str = "auto",
        length_units_per_meter: float = 1.0,
    ) -> None:
        unit: Any = length_units_per_meter
        if isinstance(unit, bool) or not isinstance(unit, Real) or not 0.0 < float(unit) < math.inf:
            raise ValueError(
                f"length_units_per_meter must be a number > 0: how many of the World's length "
                f"units make a metre (1 for metres, 100 for centimetres, a pixel scale for "
                f"pixels), got {length_units_per_meter!r}"
            )
        if not isinstance(solver, str) or solver not in SOLVERS:
            raise ValueError(
                f"solver must be 'exact' (a lesson's exact models), 'soft' (a game's soft "
                f"step) or 'auto' (chosen by the scene), got {solver!r}"
            )
        self._s = WorldState(self, MethodPolicy(integrator, tolerance), kernels_path(kernels))
        self._s.solver = self._s.solver_asked = solver
        self._s.unit = float(unit)
        if solver == "soft":
            self._s.game = GameStep(self._s.kernels == "fast", self._s.unit)
        self._s.events.view = event_dispatch.EventView(self._s)
        self._queries = QueryIndex()  # colliders and bodies by cell, for queries

    # The parts that tests read: the compiled forces and the static contacts (the World's
    # own modules read its state, self._s, by public names).
    @property
    def _model(self) -> ForceModel | None:
        return self._s.model

    @property
    def _contacts(self) -> Contacts | None:
        return self._s.contacts

    # -- bodies and forces ----------------------------------------------------------------
    @property
    def bodies(self) -> tuple[Body, ...]:
        """The bodies in the world, in the order they were added."""
        return tuple(self._s.bodies)

    @property
    def turning(self) -> tuple[Body, ...]:
        """The bodies that turn (``Body.turns``); with none, a step does no rotation."""
        return tuple(b for b in self._s.bodies if b.turns)

    @property
    def forces(self) -> tuple[Force, ...]:
        """The forces in the world, in the order they were added."""
        return tuple(a.force for a in self._s.forces)

    @property
    def dim(self) -> int | None:
        """1 (floats), 2 (Vectors), or None while the world has neither bodies nor shaped forces."""
        return self._s.dim

    @property
    def integrator(self) -> str:
        """The method asked for: a name from METHODS, or the custom function's name."""
        return self._s.requested

    def add(self, body: Body, *more: NoReturn) -> Body:
        """Add ``body`` and return it; from now on its pos/vel are the world's live state.

        One Body (``more``, typed so that a type checker refuses any, is pymunk's
        ``space.add(body, shape)``: refused, saying what to write).
        """
        if more:
            raise TypeError(habits.several("add", (body, *more)))
        return self.add_all([body])[0]

    def add_all(self, bodies: Iterable[Body]) -> list[Body]:
        """Add many bodies at once (one array copy instead of one per body); return them.

        All or nothing: a batch with one bad body is refused whole and changes nothing.
        """
        return membership.add_all(self._s, bodies)

    def remove(self, body: Body, *more: NoReturn) -> None:
        """Take ``body`` out of the world; it keeps its last position, velocity and mass.

        One Body (``more``, as in ``add``, is pymunk's ``space.remove(body, shape)``: refused,
        saying what to write; a collider goes by ``remove_collider``).
        """
        if more:
            raise TypeError(habits.several("remove", (body, *more)))
        membership.remove(self._s, body)
        if self._s.springs:
            self._s.springs.body_removed(body)  # its springs go with it
            self._s.changed_structure()
        if self._s.drags:
            self._s.drags.body_removed(body)  # its mouse joints go with it
            self._s.replan()

    def add_force(
        self, force: Force | Callable[..., Any], bodies: Iterable[Body] | None = None
    ) -> Force:
        """Add a force (a Force, or a callable ``f(t, x, v, mass) -> force``); return it.

        ``bodies``: the bodies it acts on (all of them, now and later, when None); a torque
        generator (``ConstantTorque``, ``AngularDrag``, ...) turns those that turn, in 2D.
        """
        return membership.add_force(self._s, force, bodies)

    def remove_force(self, force: Force) -> None:
        """Take ``force`` (what ``add_force`` returned; ``world.forces`` lists them) out: it
        acts on nothing from the next step, and every body wakes. Gravity changed in play is
        one removed and another added (pymunk's ``space.gravity = ...``)."""
        membership.remove_force(self._s, force)

    # -- links ------------------------------------------------------------------------------
    @property
    def links(self) -> tuple[Link, ...]:
        """The links and joints (rods, cables, pins, hinges, welds), in the order added."""
        return tuple(self._s.links)

    @property
    def static_body(self) -> StaticBody:
        """The world as a body that never moves: a joint's body_b that holds to a point."""
        return STATIC

    @property
    def springs(self) -> tuple[BodySpring, ...]:
        """The springs between bodies (DampedSpring, DampedRotarySpring), in the order added."""
        return tuple(self._s.springs.items)

    @overload
    def add_link(self, link: LinkT) -> LinkT: ...
    @overload
    def add_link(self, link: SpringT) -> SpringT: ...
    @overload
    def add_link(self, link: MouseJoint) -> MouseJoint: ...
    def add_link(self, link: Any) -> Any:
        """Add a link or joint (engine.dynamics.links, engine.dynamics.joints; membership), a spring
        (engine.dynamics.springs) or a mouse joint (engine.dynamics.mouse_joint) and return it."""
        if isinstance(link, BodySpring):
            self._s.springs.add(link, self)
            self._s.changed_structure()
            return link
        if isinstance(link, MouseJoint):
            if self._s.requested == "exact":
                raise ValueError(
                    "integrator 'exact' moves bodies by the closed form, which holds no mouse "
                    "joint; use integrator='auto' (it takes an integrator while a mouse joint "
                    "pulls) or an integrator such as 'velocity_verlet'"
                )
            self._s.drags.add(link, self)
            link.body.activate()  # a body picked up asleep wakes (the joint keeps it awake)
            self._s.replan()
            return link
        return membership.add_link(self._s, link)

    def remove_link(self, link: Link | BodySpring | MouseJoint) -> None:
        """Take a link, spring or mouse joint out of the world (a pinned body is free again)."""
        if isinstance(link, BodySpring):
            self._s.springs.remove(link)
            self._s.changed_structure()
            return
        if isinstance(link, MouseJoint):
            self._s.drags.remove(link)
            self._s.replan()
            return
        membership.remove_link(self._s, link)

    @property
    def mouse_joints(self) -> tuple[MouseJoint, ...]:
        """The mouse joints (engine.dynamics.mouse_joint), in the order added."""
        return tuple(self._s.drags.items)

    # -- colliders and contacts ---------------------------------------------------------------
    @property
    def colliders(self) -> tuple[Collider, ...]:
        """The static colliders, in the order they were added."""
        return self._s.colliders

    def add_collider(self, collider: ColliderT) -> ColliderT:
        """Add a static collider (``engine.geometry.colliders``) and return it.

        Bodies already inside it are pushed out to its surface, with an OverlapWarning naming
        both. Colliders are 2D: a 1D World refuses them.
        """
        return membership.add_collider(self._s, collider)

    def remove_collider(self, collider: Collider) -> None:
        """Take a collider out of the world."""
        membership.remove_collider(self._s, collider)

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

    def on_collision(
        self,
        type_a: int | None = None,
        type_b: int | None = None,
        *,
        begin: Callable[[ContactEvent], Any] | None = None,
        pre_solve: Callable[[ContactEvent], Any] | None = None,
        post_solve: Callable[[ContactEvent], Any] | None = None,
        separate: Callable[[ContactEvent], Any] | None = None,
    ) -> Callable[[], None]:
        """Call these for the contacts between a body or collider of ``collision_type``
        ``type_a`` and one of ``type_b`` (None: any type), pymunk's ``Space.on_collision``.

        ``begin``, ``separate`` and ``post_solve`` come after each step with the contacts that
        began, ended, or are open after it; ``pre_solve`` before each step for each pair of
        the types within reach of each other, and a False from it ignores that contact for
        the step (a one-way platform). engine.pipeline.collision_handlers says which way round each
        event comes. Returns a function that takes the handler off again.
        """
        handler = collision_handlers.CollisionHandler(
            type_a, type_b, begin, pre_solve, post_solve, separate
        )
        return collision_handlers.add(self._s, handler)

    @property
    def sleeping(self) -> int:
        """How many bodies sleep (a still pile: they cost nothing until something meets them)."""
        return int(self._s.collisions.asleep.sum())

    def is_sleeping(self, body: Body) -> bool:
        """Whether ``body`` sleeps (it stays exactly put until an awake body meets its group)."""
        return readout.is_sleeping(self._s, body)

    def overlap(self) -> float:
        """The deepest overlap (length units) of two bodies that collide, now (their shapes)."""
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
        """Substeps a step of the soft step for bodies resting on one another (default 4,
        Box2D's): more hold deeper piles with less overlap, at a cost per substep."""
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
        in time order; each contact begins once and ends once (``engine.dynamics.events``)."""
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

    # -- queries (engine.pipeline.queries) ---------------------------------------------------------
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
        return queries.segment_query(self._s, start, end, radius, filter, self._queries)

    def segment_query_first(
        self,
        start: Any,
        end: Any,
        radius: float = 0.0,
        filter: Filter | None = None,  # noqa: A002
    ) -> QueryHit | None:
        """The first body or collider (sensors too; a filter can leave them out) a segment
        from ``start`` to ``end`` meets, as ``segment_query``; None when nothing is met."""
        hits = queries.segment_query(self._s, start, end, radius, filter, self._queries, True)
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
        return queries.point_query(self._s, point, max_distance, filter, self._queries)

    def point_query_nearest(
        self,
        point: Any,
        max_distance: float = 0.0,
        filter: Filter | None = None,  # noqa: A002
    ) -> QueryHit | None:
        """The nearest shape within ``max_distance`` of ``point`` (``point_query``'s first),
        or None."""
        hits = queries.point_query(self._s, point, max_distance, filter, self._queries)
        return hits[0] if hits else None

    def bb_query(self, bb: Any, filter: Filter | None = None) -> list[Any]:  # noqa: A002
        """The bodies and colliders that overlap the box ``bb`` = (left, bottom, right, top)."""
        return queries.bb_query(self._s, bb, filter, self._queries)

    def shape_query(self, shape: Any, filter: Filter | None = None) -> list[QueryHit]:  # noqa: A002
        """The bodies and colliders a ``Circle`` or ``Segment`` (placed where asked, not
        added) overlaps, deepest first; ``distance`` < 0 is the depth of each overlap."""
        return queries.shape_query(self._s, shape, filter, self._queries)

    # -- choosing the method ------------------------------------------------------------------
    @property
    def evaluations(self) -> int:
        """How many times the forces on all bodies have been evaluated (a machine-free cost).

        Each step costs the method's evaluations (1 for the Euler methods, 2 for Verlet, 4 for
        RK4, 0 for the closed form); "auto" with a tolerance adds one for each method it
        predicts at a new dt.
        """
        return self._s.evaluations_now

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
        return self._s.t

    @property
    def dt(self) -> float | None:
        """The length (s) of the last step, or None before the first (pymunk's
        ``current_time_step``)."""
        return self._s.dt

    @property
    def steps(self) -> int:
        """How many steps have been taken."""
        return self._s.steps

    @property
    def solver(self) -> str:
        """How this World solves contacts and joints: ``"exact"`` or ``"soft"`` (class doc);
        with ``solver="auto"``, what it chose at its first step, or would choose now before
        it."""
        s = self._s
        if s.solver == "auto":
            return solver_choice.choose(s.bodies, s.links, s.dim, s.colliders)[0]
        return s.solver

    @property
    def solver_reason(self) -> str:
        """One line saying why ``solver`` is the solver in use."""
        s = self._s
        if s.solver_asked != "auto":
            return f"asked for: World(solver={s.solver_asked!r})"
        if s.solver == "auto":
            why = solver_choice.choose(s.bodies, s.links, s.dim, s.colliders)[1]
            return f"auto, before the first step: {why}"
        return f"auto, chosen at the first step: {s.solver_reason}"

    @property
    def length_units_per_meter(self) -> float:
        """How many of this World's length units make a metre (``World(length_units_per_meter=
        ...)``, class doc): what the soft step's lengths and speeds are scaled by."""
        return self._s.unit

    @property
    def kernels(self) -> str:
        """The path this World's hot loops take: ``"fast"`` (compiled) or ``"numpy"``."""
        return self._s.kernels

    def step(self, dt: float) -> None:
        """Advance every body by ``dt`` seconds (usually 1/60 or 1/120).

        Raises ValueError for dt <= 0, nan or inf (nothing changes), warns with a
        StabilityWarning the first time dt is past the method's limit for a force
        held, and raises SimulationDiverged, keeping the last finite state, if the
        state stops being finite.
        """
        s = self._s
        k = s.kernel
        if k is not None and k.take(dt):
            return  # the affine kernel (engine.dynamics.affine): what small scenes take, call-light
        plan = s.fast
        if not (plan is not None and type(dt) is float and plan[0] == dt and plan[1] == s.version):
            # A new dt, or something changed since the last step. (The method is chosen here,
            # so that the policy's StabilityWarning points at the line that called step.)
            dt = check_dt(dt)
            if s.solver_asked == "auto" and s.bodies:
                s.settle_solver()
            model = s.ready()
            name = s.policy.method_for(dt, s.version, model, s.state_now)
            plan = stepping.plan(s, dt, model, name)
        if stepping.advance(s, dt, plan):
            return self.step(dt)  # now the fast path above takes it

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
        """Total mechanical energy (J): kinetic plus the potential of the forces that have one,
        and what the springs between bodies store.

        A body's own constant acceleration a counts like gravity, with potential -m a . x.
        Kinematic and pinned bodies are left out: the game (or the pin) moves them, and no
        force acts on them.
        """
        return readout.energy(self._s)

    # -- snapshot and restore (engine.pipeline.snapshot) -------------------------------------------
    def snapshot(self) -> WorldSnapshot:
        """Everything needed to bring this world back to this moment, bit for bit."""
        return snapshots.take(self._s)

    def restore(self, snapshot: WorldSnapshot) -> None:
        """Bring back the state saved by ``snapshot()`` (same bodies, in the same order)."""
        snapshots.restore(self._s, snapshot)

    # -- copies ---------------------------------------------------------------------------
    def copy(self) -> World:
        """An independent copy of this World, as pymunk's ``space.copy()`` (a deep copy).

        The copy has copies of everything: bodies (``copy.bodies``, in the same order, at the
        same state), forces, colliders, links, springs, mouse joints, the contacts in progress,
        time, settings and contact handlers (a plain function is the same function, called
        with the copy's events, which name the copy's bodies; a bound method's object is
        copied with it, as ``copy.deepcopy`` copies it). Stepping one leaves the other as it
        is; each steps as the other would. ``copy.copy(world)`` and ``copy.deepcopy(world)``
        give the same. To come back to this moment in this same World, ``snapshot()`` is
        cheaper.
        """
        return deepcopy(self)

    def __copy__(self) -> World:
        """``copy.copy(world)``: ``world.copy()``, an independent World (a shallow copy would
        share this World's state, and stepping it would move this World's bodies)."""
        return self.copy()

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
