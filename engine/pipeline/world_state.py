"""A World's state, and what is derived from it: the force model, the method's choice, the
affine kernel and the closed form's anchor, each dropped when what it was made from changes.

The World (``engine.world``) is a door onto this state; the modules it composes (the step
pipeline, snapshots, contact events, push-out) read and write it here, by public names.
Time is counted in whole steps: t = t_base + n * dt, with n an integer, so a run of equal
steps never accumulates the round-off of adding dt again and again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Real
from typing import Any

import numpy as np

from ..body import Body
from ..body_habits import mass_and_moment
from ..dynamics.affine import AffineKernel, StepCount, safe_steps
from ..dynamics.events import WorldEvents
from ..dynamics.forcefield import ForceModel
from ..dynamics.joints import Joint
from ..dynamics.links import Link, LinkSolver, Pin, edits
from ..dynamics.mouse_joint import MouseJoints
from ..dynamics.policy import MethodPolicy
from ..dynamics.store import BodyStore
from ..dynamics.torquefield import TorqueModel
from ..exact.collisions import Collisions
from ..exact.contacts import Contacts
from ..exact.joint_solver import JointSolver
from ..exact.overlaps import push_out
from ..exact.spring_step import Springs
from ..forces import Force
from . import solver_choice
from .game_step import GameStep

__all__ = ["AttachedForce", "StepCount", "WorldState"]


@dataclass
class AttachedForce:
    """A force held by a World, and the bodies it acts on."""

    force: Force
    bodies: list[Body] | None  # None: every body in the world


class WorldState:
    """Everything a World holds: bodies and their arrays, forces, colliders and contacts,
    links, time, and the derived parts (force model, kernel, anchor) with their rebuilding."""

    def __init__(self, world: Any, policy: MethodPolicy, kernels: str = "numpy") -> None:
        self.world = world  # the World this is the state of (what Body.world answers)
        self.kernels = kernels  # the hot loops' path (engine.kernels): "numpy" or "fast"
        self.policy = policy
        self.requested = policy.requested
        self.store: BodyStore | None = None  # made when the World's dimension is known
        self.bodies: list[Body] = []
        self.forces: list[AttachedForce] = []
        # Time: t = t_base + n * dt (s), n in count.n.
        self.t_base = 0.0
        self.dt: float | None = None
        self.count = StepCount()  # the steps of dt since t_base
        self.steps_base = 0  # steps taken before the current run of equal dt
        self.model: ForceModel | None = None
        # The generators' torques on the bodies that turn (engine.dynamics.torquefield), once made
        # (``torques``): None when none gives one to a body that turns.
        self.torque_model: TorqueModel | None = None
        self.torques_made = False
        self.evaluations = 0  # force evaluations of models since replaced, and of the kernel
        self.anchor: tuple[Any, Any, float] | None = None  # (x0, v0, t0) for "exact"
        self.version = 0  # bumped whenever bodies, forces or masses change
        self.fast: tuple[Any, ...] | None = None  # (dt, version, method, step, model, affine)
        self.kernel: AffineKernel | None = None
        self.huge = False  # the state is near overflow: step with numpy's warnings off
        # Whether every body slept through the last step (engine.pipeline.stepping): None before a
        # step is taken, or where no part of it asked.
        self.slept: bool | None = None
        self.contacts: Contacts | None = None  # made by the first add_collider
        self.collisions = Collisions()  # contacts between bodies (2D bodies with a radius)
        #: The pairs of bodies a joint keeps from colliding, as sorted keys a n + b of rows
        #: a < b (``_apart``; ``collisions.apart`` adds a pre_solve's pairs within a step).
        self.joint_apart = np.zeros(0, dtype=np.int64)
        self.collisions.fast = kernels == "fast"
        self.pairs_on = False  # whether any two bodies may collide
        # on_contact handlers: (target, begin, end, post_solve).
        self.handlers: list[tuple[Any, Any, Any, Any]] = []
        # Which kinds of them there are (begin, end, post_solve), and the list and its length
        # they were read from (engine.pipeline.event_dispatch.report).
        self.handler_kinds: tuple[list[Any], int, tuple[bool, bool, bool]] | None = None
        # on_collision handlers by collision type (engine.pipeline.collision_handlers).
        self.collision_handlers: list[Any] = []
        self.events = WorldEvents()  # the contacts kept open, and each step's events
        self.events.ledger.fast = kernels == "fast"
        # The sensor bodies' rows, with the store's categories and mask arrays they were found
        # in (engine.pipeline.body_sensors: found again when either array is a new one).
        self.sensor_rows: tuple[np.ndarray, np.ndarray, list[int]] | None = None
        self.contact_dv: np.ndarray | None = None  # velocity change by the static contacts
        # Kinematic bodies whose pos the game wrote: where each is to be after the next step.
        self.targets: dict[Body, Any] = {}
        self.turn_targets: dict[Body, float] = {}  # kinematic bodies' angles (rad), likewise
        self.links: list[Link] = []  # rods, cables and pins (engine.dynamics.links)
        self.link_revisions: tuple[int, ...] = ()  # each link's revision as last taken
        self.link_edits = -1  # engine.dynamics.links.edits() when they were taken
        self.retired: list[Link] = []  # links taken out (a snapshot may bring one back)
        # The links as arrays (engine.dynamics.links), or as rows of the joint solver when a joint
        # or an anchor away from a centre is among them (engine.exact.joint_solver); made when
        # needed.
        self.link_solver: LinkSolver | JointSolver | None = None
        self.jointed = False  # whether the joint solver takes the links
        self.substeps = False  # taking a step again in parts (engine.pipeline.stepping)
        self.springs = (
            Springs()
        )  # springs between bodies (engine.dynamics.springs, engine.exact.spring_step)
        self.spring_revisions: tuple[int, ...] = ()  # each spring's revision as last taken
        self.drags = MouseJoints()  # mouse joints (engine.dynamics.mouse_joint)
        # The solver of contacts and joints: "exact" (the lesson's models: engine.pipeline.stepping)
        # or "soft" (a game's: engine.pipeline.game_step, whose state this is then).
        # solver_asked: what World(solver=...) was given; solver: the one in force ("auto"
        # until the first step chooses: engine.pipeline.solver_choice), and why.
        self.solver = self.solver_asked = "exact"
        #: The World's length units a metre (``World(length_units_per_meter=...)``): the soft
        #: step's lengths are scaled by it (engine.pipeline.game_step).
        self.unit = 1.0
        self.solver_reason = ""
        self.solver_warned = False  # (the exact models outgrown: said once)
        self.game: GameStep | None = None

    # -- time ----------------------------------------------------------------------------------
    @property
    def n(self) -> int:
        """The steps of dt taken since t_base."""
        return self.count.n

    @n.setter
    def n(self, value: int) -> None:
        self.count.n = value

    @property
    def t(self) -> float:
        """Simulated time (s) since the world began."""
        n = self.count.n
        return self.t_base + n * self.dt if self.dt is not None else self.t_base

    @property
    def steps(self) -> int:
        """How many steps have been taken."""
        return self.steps_base + self.count.n

    # -- bodies ----------------------------------------------------------------------------------
    @property
    def dim(self) -> int | None:
        """1 (floats), 2 (Vectors), or None while the world has neither bodies nor shaped forces."""
        return None if self.store is None else self.store.dim

    def check_dim(
        self, dim: int, what: str, world_dim: int | None = None, bodies: bool = False
    ) -> None:
        """TypeError unless ``what``, of dimension ``dim``, fits this World (or ``world_dim``);
        ``bodies``: it is a body or a collider, which pymunk's Body(mass, moment) may have put
        on a line (the error then says what to write)."""
        expected = self.dim if world_dim is None else world_dim
        if expected is not None and dim != expected:
            habit = f"; {mass_and_moment()}" if bodies else ""
            raise TypeError(
                f"{what} is {dim}D but this World is {expected}D: a World holds bodies "
                f"of one dimension (1D: floats, 2D: Vectors){habit}"
            )

    def ensure_store(self, dim: int) -> BodyStore:
        """The body arrays, made of dimension ``dim`` if the World has none yet."""
        if self.store is None:
            self.store = BodyStore(
                dim,
                self.world,
                on_state=self.state_written,
                on_own_acc=self.own_acc_written,
                on_mass=self.changed_structure,
                on_moment=self.moments_changed,
                on_kinematic=self.kinematic_moved,
                on_kinematic_turn=self.kinematic_turned,
                acceleration_at=self.acceleration_at,
                on_sleep=self.set_asleep,
                on_material=self.material_written,
            )
        return self.store

    def rows_of(self, bodies: list[Body]) -> np.ndarray:
        """The rows of ``bodies`` in the body arrays."""
        if not bodies or self.store is None:
            return np.zeros(0, dtype=np.intp)
        return self.store.rows([b.slot for b in bodies])

    # -- the contacts between bodies: sleep and the solver's iterations -------------------------
    def set_sleep_time(self, value: float) -> None:
        """Seconds (>= 0; math.inf: never) a resting group must stay still before it sleeps."""
        if isinstance(value, bool) or not isinstance(value, Real) or not float(value) >= 0.0:
            raise ValueError(
                f"sleep_time must be a number of seconds >= 0 (math.inf: never sleep), "
                f"got {value!r}"
            )
        t = float(value)
        self.collisions.sleep_time = t
        if t == math.inf:
            self.collisions.wake(len(self.bodies))

    def set_contact_iterations(self, value: int) -> None:
        """Iterations (an int >= 1) a step of the solver for bodies resting on one another."""
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise ValueError(f"contact_iterations must be an int >= 1, got {value!r}")
        self.collisions.iterations = value
        if self.game is not None:
            self.game.substeps = value  # the soft step's substeps (engine.pipeline.game_step)

    def settle_solver(self) -> None:
        """Under ``solver="auto"``: choose the solver from the scene now, once (the first
        step), and after it warn once if the scene has outgrown the exact models
        (engine.pipeline.solver_choice)."""
        if self.solver == "auto":
            self.solver, self.solver_reason = solver_choice.choose(
                self.bodies, self.links, self.dim, self.colliders
            )
            if self.solver == "soft":
                self.game = GameStep(self.kernels == "fast", self.unit)
                self.game.substeps = self.collisions.iterations
        elif self.solver == "exact" and not self.solver_warned:
            self.solver_warned = solver_choice.warn_if_outgrown(
                self.bodies, self.links, self.colliders
            )

    def set_asleep(self, row: int, asleep: bool) -> None:
        """Put body ``row`` to sleep now with the awake bodies touching it (Body.sleep), or wake
        it with its sleeping group (Body.activate); ValueError, naming why, where it cannot
        sleep."""
        collisions, store, n = self.collisions, self.store, len(self.bodies)
        if not asleep:
            collisions.wake_body(row, n)
            return
        assert store is not None
        never = store.kinematic.copy()  # moved by the game or held by a Pin
        never[collisions.joined] = True
        why = None
        if never[row]:
            why = (
                "a body the game moves (kinematic), pinned, or held by a joint never sleeps: "
                "a sleeper stays put, and what moves it would pull it"
            )
        elif store.dim != 2 or not collisions.active(
            store.radius, store.group, store.categories, store.mask, store.shapes
        ):
            why = (
                "bodies sleep where they rest on one another, and no two bodies of this World "
                "can meet (bodies meet in a 2D World, with a radius or a shape, where their "
                "filters let them)"
            )
        elif not math.isfinite(collisions.sleep_time):
            why = (
                "sleep is off in this World (world.sleep_time is math.inf): set "
                "world.sleep_time to a number of seconds (0.5 is the default) first"
            )
        if why is not None:
            body = self.bodies[row]
            raise ValueError(f"body.sleep() cannot put this body to sleep: {why}: {body!r}")
        rows = collisions.sleep_group(row, n, never)
        if len(rows):
            store.v[rows] = 0.0  # at rest, as sleep_still leaves a group
            store.omega[rows] = 0.0
            store.spin_written()
            self.anchor = None  # the closed form starts anew from the state now

    @property
    def colliders(self) -> tuple[Any, ...]:
        """The static colliders, in the order they were added."""
        return () if self.contacts is None else tuple(self.contacts.colliders)

    # -- derived state ----------------------------------------------------------------------
    def replan(self) -> None:
        """A mouse joint came or went: choose the method and plan the next step again (the
        closed form and the affine kernel hold none), keeping the sleep and the contacts'
        warm start."""
        if self.model is not None:
            self.evaluations += self.model.evaluations
        self.drop_kernel()
        self.model = None
        self.policy.choice = None
        self.fast = None
        self.anchor = None

    def changed_structure(self, appended: bool = False) -> None:
        """Bodies, forces or masses changed: rebuild the force model and the choice.
        ``appended``: only bodies were added, at the end (the others keep their sleep and
        their contacts' warm start: a game spawning a ball does not wake a pile)."""
        if self.model is not None:
            self.evaluations += self.model.evaluations
        self.drop_kernel()
        self.model = None
        self.torques_made, self.torque_model = False, None
        self.anchor = None
        self.policy.choice = None
        self.version += 1
        if appended:
            self.collisions.grew(len(self.bodies))
        else:
            self.collisions.changed(len(self.bodies))
        self.link_solver = None
        self._apart()

    def colliders_changed(self) -> None:
        """A collider came or went: the next step plans and chooses its method again (whether
        the World holds colliders decides both). On the soft step nothing else reads the
        colliders: the bodies' rows, the forces' model and the joints' rows are kept (a game
        that takes a coin waits on the colliders' tables alone, engine.pipeline.game_step).
        Elsewhere, or where springs are held (their closed form asks whether the World holds
        colliders), as ``changed_structure``."""
        if self.game is None or self.springs:
            self.changed_structure()
            return
        self.drop_kernel()
        self.anchor = None
        self.policy.choice = None
        self.fast = None

    def _apart(self) -> None:
        """Tell the contacts which pairs of bodies a joint keeps from colliding
        (``joint_apart``), and which bodies a joint or an anchored link holds."""
        store = self.store
        pairs: list[int] = []
        joined: list[int] = []
        keys = np.zeros(0, dtype=np.int64)
        rows = np.zeros(0, dtype=np.intp)
        if store is not None:
            for k in self.links:
                pair = k.kept_apart if isinstance(k, Joint) else None
                if pair is not None:
                    pairs += (pair[0].slot, pair[1].slot)
                if isinstance(k, Joint) or k.anchored:
                    joined += [b.slot for b in k.bodies]
            # (The rows of all the slots at once: a game spawning a ball waits on this.)
            if pairs:
                ends = store.rows(pairs).astype(np.int64).reshape(-1, 2)
                keys = np.unique(ends.min(axis=1) * len(self.bodies) + ends.max(axis=1))
            if joined:
                rows = np.unique(store.rows(joined))
        self.joint_apart = keys
        self.collisions.apart = keys
        self.collisions.joined = rows

    def moments_changed(self) -> None:
        """A moment of inertia changed (a body may have stopped turning): the generators'
        torques are folded again, and the next step plans again (its stability check too)."""
        self.torques_made, self.torque_model = False, None
        self.fast = None
        self.drop_kernel()

    def torques(self) -> TorqueModel | None:
        """The generators' torques on the bodies that turn (engine.dynamics.torquefield), made when
        needed; None when no generator gives a torque to a body that turns."""
        if not self.torques_made:
            self.torques_made = True
            store = self.store
            giving = [a for a in self.forces if a.force.gives_torque]
            if store is not None and store.turns_any and giving:
                attached = [
                    (a.force, None if a.bodies is None else self.rows_of(a.bodies)) for a in giving
                ]
                self.torque_model = TorqueModel.compile(store.inv_moment, attached)
        return self.torque_model

    def links_changed(self) -> None:
        """The set of links changed: pinned bodies are held as kinematic ones are."""
        store = self.store
        if store is not None:
            store.kinematic = np.array([b.kinematic for b in self.bodies], dtype=bool)
            for k in self.links:
                if isinstance(k, Pin) and k.holds:
                    store.kinematic[store.row(k.body.slot)] = True
        self.jointed = any(k.anchored or isinstance(k, Joint) for k in self.links)
        self.link_revisions = tuple(k.revision for k in self.links)
        self.link_edits = edits()
        # A body no longer held goes nowhere it was sent while held.
        self.targets = {b: p for b, p in self.targets.items() if b.kinematic}
        self.turn_targets = {b: a for b, a in self.turn_targets.items() if b.kinematic}
        self.changed_structure()

    def note_link_edits(self) -> None:
        """Before a step: a link's length or anchors, or a joint's collide, set since the last
        (Link.revision) are taken: the exact solvers are made again, the pairs a joint keeps
        apart found again, and the edited links' bodies woken (a winch pulls a sleeping
        crate)."""
        if edits() == self.link_edits and len(self.links) == len(self.link_revisions):
            return  # no setting of any link set since they were taken: the same revisions
        revisions = tuple(k.revision for k in self.links)
        self.link_edits = edits()
        if revisions == self.link_revisions:
            return
        store = self.store
        if store is not None and len(revisions) == len(self.link_revisions):
            for k, now, before in zip(self.links, revisions, self.link_revisions, strict=True):
                if now != before:
                    for body in k.bodies:
                        self.collisions.wake_body(store.row(body.slot), len(store))
        self.link_revisions = revisions
        self.jointed = any(k.anchored or isinstance(k, Joint) for k in self.links)
        self.link_solver = None
        self._apart()

    def note_spring_edits(self) -> None:
        """Before a step: the bodies of a spring whose stiffness, damping, rest length or
        anchors were set since the last (BodySpring.revision) wake (a spring made stiffer
        lifts the crate asleep on it). A spring added or taken out wakes every body already
        (changed_structure)."""
        revisions = self.springs.revisions()
        if revisions == self.spring_revisions:
            return
        store = self.store
        if store is not None and len(revisions) == len(self.spring_revisions):
            for k, now, before in zip(
                self.springs.items, revisions, self.spring_revisions, strict=True
            ):
                if now != before:
                    for body in k.bodies:
                        self.collisions.wake_body(store.row(body.slot), len(store))
        self.spring_revisions = revisions

    def drop_kernel(self) -> None:
        """Forget the affine kernel, counting the steps it took."""
        self.void_budget()
        k = self.kernel
        if k is not None:
            self.evaluations += k.taken
        self.kernel = None

    def void_budget(self) -> None:
        """The kernel's step budget was proved for the state before: take back what is left."""
        k = self.kernel
        if k is not None:
            n = self.count.n
            k.taken += max(0, min(n, k.n_stop) - k.n_from)
            k.n_stop = k.n_from = n

    def prepare_affine(self, dt: float, model: ForceModel, name: str) -> bool:
        """Ready the affine Euler kernel for ``dt`` (s); False if its next step might overflow."""
        store = self.store
        assert store is not None
        k = self.kernel
        if k is None or k.dt != dt or k.model is not model or k.store is not store:
            self.drop_kernel()
            damp = None if model.c is None else 1.0 - model.c * dt
            kick = model.a0 * dt
            damp_max = 1.0 if damp is None else float(np.abs(damp).max())
            k = self.kernel = AffineKernel(
                dt,
                model,
                store,
                name == "explicit_euler",
                damp,
                kick,
                damp_max,
                float(np.abs(kick).max()),
                self.count,
            )
            self.anchor = None
        if store.prev_x is store.x:
            store.prev_x = store.x.copy()
        x_max, v_max = float(np.abs(store.x).max()), float(np.abs(store.v).max())
        budget = safe_steps(x_max, v_max, k.damp_max, k.kick_max, dt)
        # ... and the time t_base + (n + 1) dt must stay a finite float too.
        budget = min(budget, int(min((1e308 - self.t_base) / dt, 2.0**62)) - self.n)
        self.void_budget()
        k.n_from, k.n_stop = self.n, self.n + max(budget, 0)
        return budget > 0

    def kinematic_moved(self, row: int, target: Any) -> None:
        """The game moved a kinematic body: to ``target`` over the next step, or (None) by
        writing its velocity. Nothing sleeping wakes unless the body touches it."""
        body = self.bodies[row]
        if target is None:
            self.targets.pop(body, None)
        elif not body.kinematic:
            pin = next(k for k in self.links if isinstance(k, Pin) and k.holds and k.body is body)
            raise ValueError(
                f"pos: that body is pinned at {tuple(pin.point)} and stays there; take the pin "
                f"out (world.remove_link) or add a Pin where it should be: {body!r}"
            )
        else:
            self.targets[body] = target
        self.anchor = None
        self.drop_kernel()

    def kinematic_turned(self, row: int, target: float | None) -> bool:
        """The game turned a kinematic body: to the angle ``target`` (rad) over the next step,
        or (None) by writing its angular velocity. False for a body held by a pin, not the
        game (it is turned by hand, as any other)."""
        body = self.bodies[row]
        if not body.kinematic:
            return False
        if target is None:
            self.turn_targets.pop(body, None)
        else:
            self.turn_targets[body] = target
        self.anchor = None
        self.drop_kernel()
        return True

    def state_written(self, row: int | None = None, moved: bool = False) -> None:
        """A position or velocity was set by hand: the closed form and the kernel start anew.
        The body written (``row``) wakes with its sleeping group, if it slept; with no row
        (the World changed by hand as a whole) every sleeping body wakes. A body moved by hand
        (``row``, ``moved``) is no longer at rest where it was, and is pushed out of any solid
        collider it was put into."""
        self.anchor = None
        self.void_budget()
        if row is None:
            self.collisions.wake(len(self.bodies))
        else:
            self.collisions.wake_body(row, len(self.bodies))
        if moved and row is not None and self.contacts is not None:
            self.contacts.rest[row] = -1
            push_out(self, [row], "was put", stacklevel=5)

    def material_written(self, row: int, filtered: bool) -> None:
        """One body's restitution, friction or filter was set (``filtered``: its filter): the
        next step meets with it. The body wakes with its sleeping group, if it slept (a crate
        whose friction falls may slide now); a filter changes which pairs may meet, so the
        sleepers touching or overlapping it wake, and the bodies that collide and the step's
        plan are found again."""
        c, n = self.collisions, len(self.bodies)
        c.wake_body(row, n)
        if filtered:
            # What it meets changed: the bodies touching it wake too (a crate asleep on a
            # trapdoor made a sensor falls through it; the pairs touching after the last step).
            if len(c.still) == n and len(c._touching):
                a, b = np.divmod(c._touching, n)
                for other in np.concatenate([b[a == row], a[b == row]]).tolist():
                    c.wake_body(other, n)
            # ... and so do the sleepers it overlaps, which it may meet now (a kinematic sensor
            # made solid where a crate sleeps in it pushes the crate out, as pymunk's does).
            store = self.store
            if len(c.still) == n and c.asleep.any() and store is not None and store.dim == 2:
                x, r = store.x, store.radius
                near = np.hypot(*(x - x[row]).T) <= r + r[row]
                for other in np.flatnonzero(near & c.asleep & (r > 0.0)).tolist():
                    c.wake_body(other, n)
            self.collisions.filters_changed()
            self.fast = None
            store = self.store
            if self.contacts is not None and store is not None:
                self.contacts.filters_changed(store.group, store.categories, store.mask)

    def collider_changed(self, collider: Any, name: str) -> None:
        """A collider of this World had its ``name`` (restitution, friction, filter or sensor)
        set: its faces take it for the next step (``Contacts.material_changed``), and every
        body wakes (a crate asleep on a floor made slippery slides). A sensor set or unset
        changes the faces as adding or removing a collider does (the contacts' warm start,
        keyed by face, starts afresh); a sensor made solid pushes out the bodies inside it,
        with an OverlapWarning, as ``add_collider`` does."""
        contacts = self.contacts
        assert contacts is not None
        self.events.settle_reading()
        contacts.material_changed(collider, name)
        if self.game is not None:
            self.game.materials_changed()
        self.collisions.wake(len(self.bodies))
        if name != "sensor":
            self.fast = None
            store = self.store
            if name == "filter" and store is not None:
                contacts.filters_changed(store.group, store.categories, store.mask)
            return
        self.events.collider_changed(collider, self.t)
        if not collider.sensor and self.bodies:
            push_out(self, range(len(self.bodies)), "was (a sensor made solid)", stacklevel=5)
        self.changed_structure()

    def own_acc_written(self, row: int) -> None:
        """One body's own acceleration changed: one entry of a0, no recompiling."""
        if self.model is not None:
            assert self.store is not None
            self.model.set_own_acc(row, self.store.own[row])
        self.anchor = None
        self.drop_kernel()
        self.collisions.wake_body(row, len(self.bodies))

    def ready(self) -> ForceModel:
        """The forces compiled into per-body arrays (engine.dynamics.forcefield), made when
        needed."""
        if self.model is None:
            attached = [
                (a.force, None if a.bodies is None else self.rows_of(a.bodies)) for a in self.forces
            ]
            store = self.store
            if store is None:  # no body and no shaped force yet: nothing to fold
                self.model = ForceModel.compile(np.zeros(0), np.zeros(0), attached)
            else:
                kin = store.kinematic
                if kin.any():
                    # No force acts on a body the game moves.
                    free = np.flatnonzero(~kin)
                    attached = [
                        (f, free if rows is None else rows[~kin[rows]]) for f, rows in attached
                    ]
                self.model = ForceModel.compile(store.mass, store.own, attached)
                if self.springs and self.model.all_constant:
                    # The closed form holds the springs too only where they are linear.
                    self.model.all_constant = self.model.springs = self.springs_closed() is None
                if self.drags:
                    # Nor does it hold a mouse joint: "auto" takes an integrator while one pulls.
                    self.model.all_constant = False
        return self.model

    def springs_closed(self) -> str | None:
        """None when the springs may take the closed form now (engine.exact.spring_step), else
        why not: the World's contacts and links take the kicks' steps."""
        st = self.store
        assert st is not None
        if self.contacts is not None or self.links:
            return "the World holds colliders or links"
        if self.collisions.active(st.radius, st.group, st.categories, st.mask, st.shapes):
            return "bodies of the World may collide"
        return self.springs.linear(st, None if self.model is None else self.model.a0)

    def state_now(self) -> tuple[Any, Any, Any] | None:
        """(x, v, a) of every body now, for the method policy's predictions; None if empty."""
        if not self.bodies:
            return None
        assert self.store is not None
        x, v = self.store.x, self.store.v
        return x, v, self.ready().accel(self.t, x, v)

    def acceleration_at(self, row: int) -> Any:
        """The acceleration of the body in ``row`` now (only that body's forces are evaluated)."""
        assert self.store is not None
        return self.ready().accel_of(row, self.t, self.store.x, self.store.v)

    @property
    def method(self) -> str:
        """The method in use; for "auto", the one chosen at the last step (or "auto" before)."""
        if self.policy.choice is not None:
            return self.policy.choice[1]
        fixed = self.policy.fixed_choice(self.ready())
        return "auto" if fixed is None else fixed[0]

    @property
    def method_reason(self) -> str:
        """One line saying why ``method`` is the method in use."""
        if self.policy.choice is not None:
            return self.policy.choice[2]
        fixed = self.policy.fixed_choice(self.ready())
        return (
            "chosen at the first step, from its dt and the forces held"
            if fixed is None
            else (fixed[1])
        )

    @property
    def capped(self) -> int:
        """How many times impacts passed their cap in one step (static contacts and pairs)."""
        static = 0 if self.contacts is None else self.contacts.capped
        return static + self.collisions.capped

    @property
    def evaluations_now(self) -> int:
        """How many times the forces on all bodies have been evaluated, the kernel's too."""
        k = self.kernel
        n = self.count.n
        kernel = 0 if k is None else k.taken + max(0, min(n, k.n_stop) - k.n_from)
        return self.evaluations + kernel + (0 if self.model is None else self.model.evaluations)
