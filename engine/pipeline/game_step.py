"""A game scene's step, top to bottom: Box2D v3's stages on a World's bodies, colliders and joints.

``World(solver="soft")`` takes each step here instead of the exact models' pipeline
(engine.pipeline.stepping): one soft-step solver (engine.dynamics.solver) for every contact and
joint, as a game wants it (a pile, a platformer, a pinball table), where the exact models are for a
lesson's scene (a ball that bounces at its exact moment, the cradle, a hinge held to 1e-9 m).
The stages, in the order they run (Box2D v3's ``b2SolverStage`` list):

0. ``_wake`` (sleep, engine.pipeline.game_sleep): a sleeping island an awake body comes near wakes;
   if everything sleeps and nothing moves, the step ends here, changing nothing.
1. ``_bodies``: the solver's bodies: the World's rows, then one static body (the colliders'
   frame: position 0, angle 0, no mass); a kinematic body moves at its velocity and nothing
   pushes it (zero inverse mass), nor a sleeper; the forces' accelerations at the step's
   start, held over the step (gravity is exact so; a drag is taken at the start's speed).
2. ``_candidates`` and engine.pipeline.game_broadphase (``pairs``, ``faces``): the pairs of bodies,
   and of bodies and colliders' shapes, whose bounding circles and boxes come within what the
   two can move in the step, with the filters, sensors, joints that keep their bodies apart
   and pre_solve callbacks applied, one of the two awake.
3. engine.geometry.narrowphase (``collide_pairs``): a manifold for each pair
   (engine.geometry.manifold: Box2D's, up to two points with anchors, separations and feature keys),
   with a speculative margin of what the pair can close in the step: a box falling fast onto a floor
   is stopped on it.
4. ``_found``: each manifold a contact of the solver, its points warm started from the last
   step's impulses by key (the pair and the features that make the point), its friction
   mu_a mu_b, restitution e_a e_b, and the surfaces' speed along it (a conveyor); on the
   fast path, engine.pipeline.game_contacts.contacts_loop.
5. engine.dynamics.game_joints: the hinges, welds, mouse joints, links, springs and pymunk's
   constraints (engine.dynamics.constraints) as the solver's joints, warm started from their last
   impulses, which are reported on each joint after the solve.
6. ``solver.solve``: substeps (integrate velocities, warm start, solve, integrate positions,
   relax), restitution, the impulses kept (engine.dynamics.solver). The bodies move by its
   substeps (semi-implicit Euler, but exact for held forces) whatever the World's integrator,
   which moves them only in a World with nothing to solve (no collider, no pair that may
   touch, no joint).
7. ``_keep``, ``_events``: the impulses kept by key, and which contacts touch after the step
   (a point that pushed, or one within ``LINEAR_SLOP``) and which sensors overlap, as the
   World's events read them (engine.pipeline.event_dispatch); on the fast path,
   engine.pipeline.game_contacts.report_loop.
8. ``_sleep``: still islands fall asleep (engine.pipeline.game_sleep); a sleeper's contacts stay
   open.
9. engine.dynamics.game_continuous (``Continuous.sweep``, on either path): each fast body (one that
   moved more than half its least extent, or ended a quarter of it deep in what the solve does
   not move: ``ended_depth``) swept from its pose at the step's start to its end against
   the colliders and the static and kinematic bodies (a bullet against the dynamic ones too:
   ``Body.bullet``), and set back to its first time of impact, its velocity kept (Box2D v3's
   ``b2SolveContinuous``): a thin box turning fast meets a wall with another corner than its rows
   hold, and is stopped. On the fast path ``step_loop``'s end says whether a body may be fast: a
   step with none asks nothing more.

On the fast path stages 0 (once the World's structure is read) to 8 are one compiled call,
engine.pipeline.game_loop's ``step_loop`` (``_step_fast``): the numpy path's products in its order,
so both paths give the same bits (tests/test_game_loop.py compares them step by step).

What this step does not do yet, and says so (``World.solver``'s error): 1D worlds are the
exact pipeline's. A mouse joint is Box2D's here: a soft spring
that sags by g / omega^2 under a body's weight (the exact pipeline's holds it at the target).
A fast body is swept against the dynamic bodies only as a bullet (``Body.bullet``, off as
Box2D's ``isBullet`` is): a thin box turning fast that is none may pass a free plate.
"""

from __future__ import annotations

import math
from bisect import bisect_left
from operator import is_
from typing import Any, NamedTuple

import numpy as np

from ..body_shapes import MAX_PARTS
from ..dynamics import solver
from ..dynamics.events import COLLIDER, collider_key, collider_keys, pair_key, pair_keys
from ..dynamics.game_continuous import Continuous, ended_depth
from ..dynamics.game_joints import GameJoints
from ..dynamics.turning_faces import FACE_NUMBERS, face_rows
from ..geometry import narrowphase
from ..geometry.colliders import Collider
from ..geometry.manifold import StaticShapes, static_shapes
from ..geometry.manifold_kinds import LINEAR_SLOP, SPECULATIVE_DISTANCE
from ..geometry.pair_grid import grid_pairs
from ..geometry.shaped import Parts, ShapeTable, part_pairs, part_rows
from . import game_broadphase as broad
from . import game_sleep
from .game_contacts import FEATURE, OTHER, PART, STATIC, candidates_loop
from .game_loop import step_loop

#: The World's state (engine.pipeline.world_state.WorldState, which holds a GameStep: named here by
# what : is read of it, not imported, as a lower module must not import a higher one).
WorldState = Any

__all__ = ["GameStep", "unsupported"]

# Warm-start keys (engine.pipeline.game_contacts): (the pair's code << FEATURE) | the point's
# feature id; a pair's code is (slot_a << OTHER) | slot_b, or | STATIC | the static shape's place.
#: Up to this many bodies the broadphase tests every pair (fewer array calls than a grid).
_FEW = 32
#: Every pair of rows a < b below 32, in order (the broadphase's pairs up to _FEW bodies).
_EVERY = tuple(np.asarray(r, dtype=np.int64) for r in np.triu_indices(32, 1))


def _rows_left(before: list[Any], now: list[Any]) -> np.ndarray | None:
    """Which rows of ``before`` (the bodies' shapes, None for a plain disc) are ``now``'s,
    bodies having been taken out (the rest keep their order), as a bool array; None where
    ``now`` is not ``before`` with some rows taken out. Where a row's shape is another's
    too (None, or one shape given to two bodies), which of them is taken changes nothing:
    a table's row is made from its shape alone."""
    keep = np.zeros(len(before), dtype=bool)
    j = 0
    for i, shape in enumerate(before):
        if j < len(now) and now[j] is shape:
            keep[i] = True
            j += 1
    return keep if j == len(now) else None


def _same(kept: tuple[Any, ...], now: tuple[Any, ...]) -> bool:
    """Whether what a kept product was made of is what it would be made of now: the same
    objects (arrays the World makes again, never writes into, where it changes them).
    (map of operator.is_: the test in C, a quarter of a generator's cost.)"""
    return len(kept) == len(now) and all(map(is_, kept, now))


def unsupported(state: WorldState) -> str | None:
    """What in the World the soft step cannot take yet (a phrase), or None."""
    store = state.store
    if store is not None and store.dim != 2:
        return "a 1D world"
    return None


class _Found(NamedTuple):
    """The step's contacts as the solver takes them: ``rows``, solver.solve's contact arrays
    ca ... clt (warm started); ``keys``, each point's (2 a row); ``place``, each row's static
    shape (-1: a pair of bodies); ``point`` (k, 2), each row's first point (m); the sensor
    colliders' overlaps: ``sense_row`` the body's row, ``sense_place`` the collider's place;
    ``real`` (2 k) which of the rows' two point slots hold a point (slot j of a row with
    count > j); ``lists``: ``rows`` as the solver's lists where they were made as lists
    (``_found_few``), else None."""

    rows: list[np.ndarray]
    keys: np.ndarray
    place: np.ndarray
    point: np.ndarray
    sense_row: np.ndarray
    sense_place: np.ndarray
    real: np.ndarray
    lists: list[list[Any]] | None = None


#: The two point slots of a manifold's row (``_Found.real``).
_SLOTS = np.arange(2)
#: Up to this many manifolds ``_found`` is plain Python on lists (``_found_few``), past it
#: numpy on the arrays (measured on the platformer's calls, 2026-12-07: one manifold 28 us
#: against 79, thirteen 107 against 121, fourteen 116 against 91; about 7 us a manifold).
_FEW_FOUND = 8


class _Scene(NamedTuple):
    """What a step reads of the World but its bodies' motion: the bodies' shapes (``table``)
    and their places with the static shapes' (``places``, engine.geometry.narrowphase), the
    colliders' arrays (``cs``), the static shapes with each one's collider place (``owner``) and box
    (``bounds``), which bodies are sensors, and the pairs kept apart and faces ignored (sorted
    keys: engine.pipeline.game_broadphase's ``apart_keys``, ``ignored_keys``)."""

    table: ShapeTable
    places: narrowphase.Places
    cs: broad.Colliders
    statics: StaticShapes
    owner: np.ndarray
    bounds: np.ndarray
    sensors: np.ndarray
    apart: np.ndarray
    ignored: np.ndarray


class _Report:
    """What the last step's contacts did, for the events: the touching contacts' event keys
    (sorted), each with a point, the normal toward the key's first body and the impulse (N s)
    on it, as the columns of one (t, 6) table (``packed``: the fast path's step reads and
    writes it whole); and the keys of what the sensors hold (``sensing``)."""

    __slots__ = ("keys", "packed", "sensing")

    def __init__(
        self,
        keys: np.ndarray | None = None,
        packed: np.ndarray | None = None,
        sensing: np.ndarray | None = None,
    ) -> None:
        self.keys = np.zeros(0, dtype=np.int64) if keys is None else keys
        self.packed = np.zeros((0, 6)) if packed is None else packed
        self.sensing = np.zeros(0, dtype=np.int64) if sensing is None else sensing

    @classmethod
    def of(
        cls, keys: np.ndarray, points: np.ndarray, normals: np.ndarray, impulses: np.ndarray,
        sensing: np.ndarray | None = None,
    ) -> _Report:  # fmt: skip
        """The report of contacts ``keys`` with their points, normals and impulses ((t, 2)
        each) apart."""
        return cls(keys, np.hstack([points, normals, impulses]), sensing)

    # (Views taken when read: the fast path's step makes a report every step, and the events
    # read these only where a contact began or ended.)
    @property
    def points(self) -> np.ndarray:
        """Each contact's point (t, 2), length units."""
        return self.packed[:, 0:2]

    @property
    def normals(self) -> np.ndarray:
        """Each contact's unit normal toward the key's first body (t, 2)."""
        return self.packed[:, 2:4]

    @property
    def impulses(self) -> np.ndarray:
        """Each contact's impulse on the key's first body over the step (t, 2), N s."""
        return self.packed[:, 4:6]


class GameStep:
    """A World's soft step (module doc): what it keeps from step to step (the contacts'
    impulses by key, the shapes, the colliders' shapes) and the stages that use it."""

    keys: np.ndarray  # the last step's points, sorted (``forget`` sets these four)
    lam: np.ndarray  # their (normal, tangent) impulses and held loads, N s a substep
    report: _Report  # this step's touching contacts, for the events
    last: _Report  # the step before's, for begin and end

    def __init__(self, fast: bool, unit: float = 1.0) -> None:
        self.fast = fast  # the compiled solver (engine.kernels) or its plain-Python twin
        #: The World's length units a metre (``World(length_units_per_meter=...)``): the
        #: step's lengths and speeds in metres (the speculative distance, the slop, the push's
        #: and the bounce's speeds, a fresh contact's reach, sleep's speed and rise) are
        #: scaled by it, as Box2D's by its b2_lengthUnitsPerMeter.
        self.unit = unit
        self.continuous = Continuous(fast, LINEAR_SLOP * unit)  # stage 9: fast bodies swept
        self.substeps = solver.SUBSTEPS
        #: The deepest overlap (m) at the last step's end at its contacts' points: what the
        #: World warns of where the pile is past its substeps (engine.pipeline.stepping).
        self.pile = 0.0
        self.joints = GameJoints(fast)  # stage 5: their rows, their impulses
        self.forget()  # the contacts' warm starts and reports: none yet
        self._table: tuple[int, list[Any], ShapeTable] | None = None
        self._statics: tuple[tuple[Any, ...], StaticShapes, np.ndarray, np.ndarray] | None = None
        # The colliders' ids: (the World's Contacts, its edits then, the ids).
        self._ids: tuple[Any, int, tuple[int, ...]] = (None, 0, ())
        self._places: tuple[ShapeTable, StaticShapes, narrowphase.Places] | None = None
        self._part_places: tuple[Parts, StaticShapes, narrowphase.Places] | None = None
        self._kept_layout: tuple[Any, Any, Any] | None = None  # (``_layout``)
        self._kept_args: tuple[Any, ...] | None = None  # (``_scene_args``)
        # The last step's scene and what it was made of (``_scene``).
        self._last_scene: tuple[Any, ...] | None = None
        self._every: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # triu_indices by n
        # The bodies' radii and their median (the radii are a new array when bodies come or go).
        self._median: tuple[np.ndarray, float] | None = None
        self.serials = np.zeros(0, dtype=np.int64)
        # What the fast path's step measured of the bodies after it, for the World's checks
        # (engine.pipeline.stepping): |sum of x and v|, |sum of angle and omega|, whether any
        # body spins; None where the step did not (the numpy path, a body set back).
        self.sums: tuple[float, float, bool] | None = None
        self._cs: tuple[tuple[int, ...], broad.Colliders] | None = None
        self._apart: tuple[Any, np.ndarray] = (None, np.zeros(0, dtype=np.int64))
        # The sensor bodies: (the store's categories and mask arrays they were read from, them).
        self._sensors: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        # The dynamic bodies counted (``_dynamic_count``): (version, mass, kinematic, count).
        # (and which they are, bool (N,))
        self._dynamic: tuple[int, np.ndarray, np.ndarray, int, np.ndarray] | None = None
        # The candidate pairs' filters and what else the broadphase asks of them but their
        # motion (``_allowed``): (the arrays they were read from, meet, allowed).
        self._kept_allowed: tuple[tuple[np.ndarray, ...], np.ndarray, np.ndarray] | None = None
        # The bodies' and static shapes' filters (``_face_filters``): (what they were read
        # of, them).
        self._kept_faces: tuple[tuple[Any, ...], tuple[np.ndarray, np.ndarray]] | None = None
        # What sleep reads of the joints' rows (``_joint_ends``): (the arrays it was read of,
        # it, the World's version and the bodies' count then).
        self._kept_ends: tuple[tuple[Any, ...], tuple[np.ndarray, ...], Any] | None = None
        # The boxes' shapes (``_box_rows``): (the places and parts they were read of, them).
        self._kept_boxes: tuple[Any, Any, broad.BoxRows] | None = None

    # -- the step -------------------------------------------------------------------------
    def step(
        self,
        state: WorldState,
        dt: float,
        accel: np.ndarray,
        ignored_faces: np.ndarray,
        ignored_pairs: np.ndarray,
        torque: np.ndarray | None = None,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """One step of ``dt`` (s) of the World's bodies, ``accel`` (N, 2) the forces'
        accelerations at its start (m/s^2), ``torque`` (N,) the torques then (N m; None: the
        bodies' own); the pairs pre_solve ignored left out (``ignored_faces`` (K, 2) of (body
        row, collider place), ``ignored_pairs`` keys a * n + b of rows a < b). Returns the
        bodies' positions, velocities, angles and angular velocities after it, for the caller
        to check and keep (the World keeps the last finite state)."""
        store = state.store
        assert store is not None
        self.sums = None
        n = len(store)
        c = state.collisions
        # (np.count_nonzero: a C call, where ndarray.any() goes through numpy's Python wrapper
        # at several times its cost on a game's few bodies.)
        # (Fewer asleep than the dynamic bodies: one of them is awake, and the step moves it.)
        sleeping = np.count_nonzero(c.asleep) if len(c.asleep) == n else 0
        if (
            sleeping
            and sleeping >= self._dynamic_count(state, store)
            and not self._stirring(store, c.asleep)
        ):
            # Everything sleeps, and nothing moves to wake it: the step changes nothing, and
            # every contact stays as it was.
            self.last = self.report
            self.pile = 0.0
            return store.x.copy(), store.v.copy(), store.angle.copy(), store.omega.copy()
        if self.fast and n > _FEW:
            # The reach and the pairs in one compiled call (``_reach`` and ``_candidates``).
            f64, asc = np.float64, np.ascontiguousarray
            a, b, margin = candidates_loop(
                asc(store.x, f64), asc(store.v, f64), asc(accel, f64), asc(store.omega, f64),
                asc(store.radius, f64), asc(store.group, np.int64), float(dt),
                self._median_radius(store), self.unit,
            )  # fmt: skip
            candidates = (a, b)
        else:
            # (The fast path's kernel measures the reach itself where the pairs need it not.)
            margin = _reach(store, accel, dt) if n > _FEW or not self.fast else np.zeros(0)
            candidates = self._candidates(store, margin)
        if self.fast:
            return self._step_fast(
                state, store, dt, accel, store.torque if torque is None else torque, margin,
                candidates, ignored_faces, ignored_pairs,
            )  # fmt: skip
        sc = self._scene(state, store, ignored_faces, ignored_pairs)
        parts = None if sc.table.parts is None else (sc.table.parts, self._parts_places(sc))
        boxes = broad.boxes(sc.places, store, parts, self._box_rows(sc.places, parts))
        meet, kept = self._allowed(store, sc, candidates)
        awake = self._wake(state, store, margin, candidates, boxes, meet)
        b = _bodies(store, accel, store.torque if torque is None else torque, awake)
        pairs = broad.pairs(
            store, sc.sensors, awake, margin, candidates, sc.apart, boxes, kept, self.unit
        )
        struck = broad.struck(margin, pairs)
        faces = broad.faces(
            store, sc.cs, sc.owner, sc.bounds, sc.sensors, awake, struck, sc.ignored,
            self._face_filters(store, sc), self.unit,
        )  # fmt: skip
        touches = self._collide(sc, store, pairs, faces, margin, struck, dt)
        found = self._found(store, sc.cs, sc.owner, touches)
        turning = _faces(sc, store, found.rows, found.place)
        joints = self.joints.arrays(state, store, n)
        k = len(found.place)
        unit = self.unit
        params: list[Any] = [dt, self.substeps, solver.CONTACT_HERTZ, solver.CONTACT_DAMPING]
        params += [solver.JOINT_HERTZ, solver.JOINT_DAMPING, solver.PUSH_SPEED * unit]
        params += [solver.THRESHOLD * unit, solver.FIRST_REACH * unit]
        rise = [0.0] * (n + 1)  # out: how far each body's held loads have yet to lift it (m)
        params.append(rise)
        # Plain Python on lists: at a game's size faster than numpy's calls a colour. (The
        # bodies', the contacts' with their totals and most, the joints', the faces'.)
        # (The contacts' rows as lists where ``_found`` made them so: the solver takes them.)
        contacts = found.lists or [a.tolist() for a in found.rows]
        out: list[Any] = [*b.tolist(), *contacts]
        out += [[0.0] * (2 * k), [0.0] * (2 * k)]
        out += self.joints.lists(joints[0])
        out += [a.tolist() for a in turning]
        solver.solve.py(*out, *params)
        # (Each list written into its column: np.stack of two arrays costs several times more.)
        x, v = np.empty((n, 2)), np.empty((n, 2))
        x[:, 0], x[:, 1], v[:, 0], v[:, 1] = out[0][:n], out[1][:n], out[3][:n], out[4][:n]
        angle = np.asarray(out[2][:n], dtype=float)
        omega = np.asarray(out[5][:n], dtype=float)
        # How deep each body ended in what the solve does not move (the continuous stage
        # sweeps one too deep: engine.dynamics.game_continuous.ended_depth, the plain twin).
        # (The plain twin loops over the bodies' angles and whether each is solved: given as
        # lists, the same numbers, read faster than an array's items.)
        solved = [*awake.tolist(), False]
        depth: Any = ended_depth.py
        ended, self.pile = depth(
            store.x, store.angle.tolist(), x, out[2][:n], solved, *found.rows[:10], *turning
        )
        self._keep(found, out)
        self._events(store, sc.cs, sc.owner, found, out)
        self.joints.report(joints[1], out, self.substeps)
        rising = np.asarray(rise[:n]) > game_sleep.RISE * unit
        self._sleep(state, store, dt, awake, v, omega, found, joints[0], x, angle, rising)
        # What each sensor collider holds: a body whose shape overlaps it.
        if len(found.sense_row):
            self.report.sensing = collider_keys(
                store.slots()[found.sense_row], sc.cs.serial[found.sense_place]
            )
        self.continuous.sweep(store, sc, x, angle, ended)  # stage 9
        return x, v, angle, omega

    def _step_fast(
        self, state: WorldState, store: Any, dt: float, accel: np.ndarray, torque: np.ndarray,
        margin: np.ndarray, candidates: tuple[np.ndarray, np.ndarray],
        ignored_faces: np.ndarray, ignored_pairs: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
        """``step`` on the fast path: what changes only with the World made here (the
        shapes, colliders, joints' rows), stages 0 to 8 in one compiled call
        (engine.pipeline.game_loop.step_loop, the numpy path's products in its order)."""
        n = len(store)
        c = state.collisions
        if len(c.asleep) != n or len(c.still) != n or len(c._group) != n:
            c.wake(n)  # bodies came or went: every island wakes (the exact step's rule)
        sc = self._scene(state, store, ignored_faces, ignored_pairs)
        table, places, statics = sc.table, sc.places, sc.statics
        # The shapes by part (engine.geometry.shaped.Parts): a body of one shape is one part,
        # itself; where a body is of several, the parts' tables (``_part_places``).
        layout = self._layout(table, statics, places)
        joints = self.joints.arrays(state, store, n)
        shape_args, static_args = self._scene_args(layout, sc)
        f64, i64 = np.float64, np.int64
        asc = np.ascontiguousarray
        if c._group.dtype != i64:
            c._group = c._group.astype(i64)
        kernel: Any = step_loop
        last = self.report
        out = kernel(
            asc(store.x, f64), asc(store.v, f64), asc(store.angle, f64),
            asc(store.omega, f64), asc(store.mass, f64), asc(store.inv_moment, f64),
            asc(accel, f64), asc(torque, f64), asc(store.kinematic), asc(store.radius, f64),
            asc(margin, f64), sc.sensors, asc(store.group, i64), asc(store.categories, i64),
            asc(store.mask, i64), asc(store.slots(), i64), asc(store.friction, f64),
            asc(store.restitution, f64), *shape_args, c.asleep, c.still, c._group,
            float(c.sleep_time), dt, *candidates, *static_args, sc.apart, sc.ignored,
            self.keys, self.lam, *self.joints.packed, sc.cs.serial, asc(store.row_of, i64),
            asc(last.keys, i64), asc(last.packed, f64), self.substeps,
            solver.CONTACT_HERTZ, solver.CONTACT_DAMPING, solver.JOINT_HERTZ,
            solver.JOINT_DAMPING, solver.PUSH_SPEED * self.unit, solver.THRESHOLD * self.unit,
            LINEAR_SLOP * self.unit, self.unit,
        )  # fmt: skip
        x, v, angle, omega, self.keys, self.lam = out[:6]
        self.last = self.report
        self.report = _Report(out[6], out[7])
        if len(out[8]):
            self.report.sensing = out[8]
        c._touching = out[9]
        # Whether a body may be fast (engine.dynamics.game_continuous); what the World checks.
        self.continuous.maybe = out[10]
        sums = out[11:14]
        # The joints' impulses: solve's outputs in place in their arrays (after the bodies'
        # 11 and the contacts' 18, as the joints' report reads them).
        # The bodies' x, y and angle after it (with the static body's) where a pymunk
        # constraint reports along itself as it is at the step's end.
        head: list[Any] = [None] * 29
        if self.joints.constrained(joints[1]):
            head[:3] = [np.append(x[:, 0], 0.0), np.append(x[:, 1], 0.0), np.append(angle, 0.0)]
        self.joints.report(joints[1], head + joints[0], self.substeps, joints[0])
        # Stage 9: the fast bodies swept to their time of impact (engine.dynamics.game_continuous),
        # where step_loop says a body may be fast.
        self.continuous.sweep(store, sc, x, angle, out[14])
        self.pile = out[15]
        self.sums = None if self.continuous.hits else sums  # (a body set back: summed again)
        return x, v, angle, omega

    def _scene_args(self, layout: Any, sc: _Scene) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
        """The compiled step's arguments that change only with the shapes and the colliders:
        the shapes by part (``_layout``), and the static shapes, colliders and tables, as the
        kernel takes them. Kept while ``layout`` and the scene's colliders' and static shapes'
        arrays are the same objects (each is made again, never written into, where the World
        changes them); made again each step where one had to be copied to be contiguous."""
        kept = self._kept_args
        if (
            kept is not None
            and kept[0] is layout
            and kept[1] is sc.owner
            and kept[2] is sc.bounds
            and kept[3] is sc.cs
            and kept[4] is sc.statics
        ):
            return kept[5], kept[6]
        places, kind, body_parts, part_of = layout
        t, cs, planes = places.tables, sc.cs, sc.statics.half_planes
        f64, i64 = np.float64, np.int64
        asc = np.ascontiguousarray
        shape_args = (places.body_circle, places.body_index, kind, body_parts, part_of)
        taken = (asc(sc.owner, i64), asc(sc.bounds, f64), asc(cs.surface), asc(planes.point, f64),
                 asc(planes.normal, f64))  # fmt: skip
        owner, bounds, surface, point, normal = taken
        static_args = (owner, bounds, places.static_circle, places.static_index, cs.sensor,
                       cs.floats, surface, cs.ints, *t.kernel_polygons, t.center, t.round,
                       point, normal)  # fmt: skip
        original = (sc.owner, sc.bounds, cs.surface, planes.point, planes.normal)
        if all(a is b for a, b in zip(taken, original, strict=True)):
            self._kept_args = (layout, sc.owner, sc.bounds, cs, sc.statics, shape_args, static_args)
        else:
            self._kept_args = None  # (a copy: read again at the next step)
        return shape_args, static_args

    def _layout(
        self, table: ShapeTable, statics: StaticShapes, places: narrowphase.Places
    ) -> tuple[narrowphase.Places, np.ndarray, np.ndarray, np.ndarray]:
        """What the fast path's step reads of the shapes by part: the places (the bodies'
        shapes and the static ones in the tables), each part's kind, each body's first part
        and how many (n, 2), each part's body and number (P, 2); kept while the tables are."""
        kept = self._kept_layout
        if kept is not None and kept[0] is table and kept[1] is places:
            return kept[2]
        parts = table.parts
        i64 = np.int64
        if parts is None:
            rows = np.arange(len(table), dtype=i64)
            body_parts = np.stack([rows, np.ones(len(table), dtype=i64)], axis=1)
            part_of = np.stack([rows, np.zeros(len(table), dtype=i64)], axis=1)
            made = (places, np.ascontiguousarray(table.kind, i64), body_parts, part_of)
        else:
            body_parts = np.stack([parts.first, parts.size], axis=1).astype(i64)
            part_of = np.stack([parts.owner, parts.number], axis=1).astype(i64)
            kind = np.ascontiguousarray(parts.table.kind, i64)
            made = (self._parts_places_of(parts, statics), kind, body_parts, part_of)
        self._kept_layout = (table, places, made)
        return made

    def resting(self, slot: int) -> int | None:
        """The serial of the collider that pushed the body in ``slot`` hardest in the last
        step, among its touching contacts (engine.dynamics.events' keys), or None."""
        r = self.report
        mine = (r.keys >> 32) == slot
        mine &= (r.keys & COLLIDER) != 0
        if not mine.any():
            return None
        push = np.hypot(r.impulses[:, 0], r.impulses[:, 1])
        best = int(np.argmax(np.where(mine, push, -1.0)))
        if push[best] <= 0.0:
            return None
        return int(r.keys[best] & (COLLIDER - 1))

    # -- snapshots ------------------------------------------------------------------------
    def state(self, links: list[Any], plain: Any) -> tuple[Any, ...]:
        """What a snapshot keeps of the soft step (engine.pipeline.snapshot): the contacts' impulses
        by key, each joint's in the order of ``links``, and the last two steps' touching contacts
        (their event keys made plain by ``plain``, engine.dynamics.events.plain_keys)."""
        joints = tuple(self.joints.impulses.get(id(j)) for j in links)

        def report(r: _Report) -> tuple[Any, ...]:
            return (plain(r.keys), r.points.copy(), r.normals.copy(), r.impulses.copy(),
                    plain(r.sensing))  # fmt: skip

        return (self.keys.copy(), self.lam.copy(), joints, report(self.report), report(self.last))

    def set_state(self, saved: tuple[Any, ...], links: list[Any], back: Any) -> None:
        """Bring back ``state()`` (``back`` turns plain keys into this World's)."""
        keys, lam, joints, now, last = saved
        self.keys, self.lam = keys.copy(), lam.copy()
        self.joints.impulses = {
            id(j): v for j, v in zip(links, joints, strict=True) if v is not None
        }

        def report(r: tuple[Any, ...]) -> _Report:
            return _Report.of(back(r[0]), r[1].copy(), r[2].copy(), r[3].copy(), back(r[4]))

        self.report, self.last = report(now), report(last)

    # -- what is kept -----------------------------------------------------------------------
    def _scene(
        self, state: WorldState, store: Any, ignored_faces: np.ndarray, ignored_pairs: np.ndarray
    ) -> _Scene:
        """What the step reads of the World but its bodies' motion (``_Scene``): the tables
        kept from step to step, made again only where the World changed."""
        table = self._shapes(store)
        contacts = state.contacts
        edited = 0 if contacts is None else contacts.edits
        # The pairs a joint keeps apart change with the bodies and the links (a joint's
        # collide bumps its revision); pre_solve's, every step.
        key = (state.version, len(store), id(store), state.link_revisions)
        # The last step's scene, where nothing it was made of changed (a game's plain step:
        # each part below is kept on its own too, but asking each costs the step a few
        # microseconds) and pre_solve left nothing out.
        last = self._last_scene
        if (
            last is not None
            and last[0] is table
            and last[1] is contacts
            and last[2] == edited
            and last[3] is self._cs
            and last[4] is store.categories
            and last[5] is store.mask
            and last[6] == key
            and not len(ignored_faces)
            and not len(ignored_pairs)
        ):
            return last[7]
        colliders = [] if contacts is None else contacts.colliders
        # The colliders' ids, the key of what is kept of them, taken again only when one
        # came or went (``Contacts.edits``).
        kept_ids = self._ids
        if kept_ids[0] is not contacts or kept_ids[1] != edited:
            kept_ids = self._ids = (contacts, edited, tuple(map(id, colliders)))
        ids = kept_ids[2]
        cs = self._colliders(colliders, state.events.serial, ids)
        self.serials = cs.serial  # the colliders' serial numbers, for the events' settle
        statics, owner, bounds = self._static(colliders, ids)
        # Sensor bodies (a sensor's filter meets nothing: only those bodies are asked), kept
        # while the filters' arrays are the same (a filter set, a sensor made or bodies come or
        # go make new ones: engine.dynamics.store).
        made = self._sensors
        if made is None or made[0] is not store.categories or made[1] is not store.mask:
            sensors = np.zeros(len(store), dtype=bool)
            for row in np.flatnonzero((store.categories == 0) & (store.mask == 0)).tolist():
                sensors[row] = state.bodies[row].sensor
            made = self._sensors = (store.categories, store.mask, sensors)
        sensors = made[2]
        kept = self._places
        if kept is None or kept[0] is not table or kept[1] is not statics:
            kept = self._places = (table, statics, narrowphase.places_of(table, statics))
        if self._apart[0] != key:
            self._apart = (key, broad.apart_keys(state, np.zeros(0, dtype=np.int64)))
        apart = self._apart[1]
        if len(ignored_pairs):
            apart = np.union1d(apart, np.asarray(ignored_pairs, dtype=np.int64))
        ignored = broad.ignored_keys(ignored_faces, len(colliders))
        scene = _Scene(table, kept[2], cs, statics, owner, bounds, sensors, apart, ignored)
        self._last_scene = None
        if not len(ignored_faces) and not len(ignored_pairs):
            self._last_scene = (
                table, contacts, edited, self._cs, store.categories, store.mask, key, scene
            )  # fmt: skip
        return scene

    def _shapes(self, store: Any) -> ShapeTable:
        """The bodies' shapes as narrowphase kinds (made again when bodies come or go)."""
        shapes = store.shapes
        kept = self._table
        if kept is None or kept[0] != len(shapes) or kept[1] != shapes:
            table = None
            if kept is not None and kept[0] < len(shapes) and shapes[: kept[0]] == kept[1]:
                # Bodies added at the end (a game spawning one): the rows before are kept.
                table = kept[2].extended(shapes[kept[0] :], store.radius)
            elif kept is not None and kept[0] > len(shapes):
                # Bodies taken out (a game's bullet gone): the rows left are kept.
                keep = _rows_left(kept[1], shapes)
                if keep is not None:
                    table = kept[2].without(keep, store.radius)
            if table is None:
                table = ShapeTable(shapes, store.radius)
            kept = self._table = (len(shapes), list(shapes), table)
        return kept[2]

    def _colliders(
        self, colliders: list[Collider], serial: Any, key: tuple[int, ...]
    ) -> broad.Colliders:
        """The colliders' arrays (engine.pipeline.game_broadphase.collider_arrays), made again when
        colliders come or go (``key``: their ids) or a material is set
        (``materials_changed``)."""
        kept = self._cs
        if kept is None or (kept[0] is not key and kept[0] != key):
            kept = self._cs = (key, broad.collider_arrays(colliders, serial))
        return kept[1]

    def forget(self) -> None:
        """Keep nothing of the steps before (no warm start, no open contacts, the joints'
        impulses none): as made, or once a snapshot taken before this soft step's first step
        was restored."""
        self.keys = np.zeros(0, dtype=np.int64)
        self.lam = np.zeros((0, 3))
        self.joints.impulses = {}
        self.report = _Report()
        self.last = _Report()

    def emptied(self) -> None:
        """A step of a World with no bodies (the last one taken out): nothing touches, so
        the contacts of the step before end (the events would read the gone bodies' keys as
        touching still)."""
        self.last = self.report
        self.report = _Report()

    def materials_changed(self) -> None:
        """A collider's material was set (engine.pipeline.world_state.collider_changed): its arrays
        are read again at the next step."""
        self._cs = None
        self._last_scene = None

    def _static(
        self, colliders: list[Collider], key: tuple[int, ...]
    ) -> tuple[StaticShapes, np.ndarray, np.ndarray]:
        """The colliders as shapes in the world's frame, each static shape's collider place
        and bounding box (xmin, ymin, xmax, ymax; a half plane's infinite), made again when
        colliders come (``key``: their ids). Where colliders only went (a coin taken), the
        shapes are kept and the gone ones' boxes emptied (``_without``): every stage tests a
        static shape's box before its collider, so a shape with an empty box meets nothing."""
        kept = self._statics
        if kept is not None and (kept[0] is key or kept[0] == key):
            return kept[1], kept[2], kept[3]
        if kept is not None:
            left = _without(kept[0], key, kept[2], kept[3])
            if left is not None:
                self._statics = (key, kept[1], *left)
                return kept[1], left[0], left[1]
        shapes = static_shapes(colliders)
        self._statics = (key, shapes, *broad.static_bounds(shapes))
        return shapes, self._statics[2], self._statics[3]

    # -- stages 2 to 4: contacts, as rows -----------------------------------------------------
    def _candidates(self, store: Any, margin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The pairs of bodies the broadphase tests (rows a < b): every pair up to ``_FEW``
        bodies, past that those in the same or neighbouring cells of a grid as wide as the
        farthest two ordinary bodies can reach each other (engine.geometry.pair_grid, no Python
        loop), and each big body with every other."""
        n = len(store)
        if n < 2:
            none = np.zeros(0, dtype=np.int64)
            return none, none
        if n <= _FEW:
            every = self._every.get(n)
            if every is None:
                # (np.triu_indices(n, 1)'s pairs, in its order: those of 32 rows below n.)
                if n <= 32:
                    within = _EVERY[1] < n
                    a, b = _EVERY[0][within], _EVERY[1][within]
                else:
                    a, b = (r.astype(np.int64) for r in np.triu_indices(n, 1))
                every = self._every[n] = (a, b)
            return every
        if (store.group[0] != 0) & (store.group == store.group[0]).all():
            none = np.zeros(0, dtype=np.int64)
            return none, none  # one group: no two bodies meet (balls that pass each other)
        # The cells as wide as the farthest two ordinary bodies can reach each other; a big
        # body (a tumbler's wall, a level's long platform, a bullet: reaching past four times
        # the median radius) is paired with every body instead, so that it does not make one
        # cell of the world.
        r = store.radius + margin
        speculative = SPECULATIVE_DISTANCE * self.unit
        big = r > 4.0 * self._median_radius(store) + speculative
        rows = np.flatnonzero(~big)
        if len(rows):
            h = 2.0 * float(r[rows].max()) + speculative
            a, b = grid_pairs(store.x[rows], h, self.fast)
            a, b = rows[a], rows[b]
        else:  # every body big (all of them fast, say): no grid, each pair below once
            a = b = np.zeros(0, dtype=np.int64)
        if big.any():
            # Each big body with every other body, a pair of big bodies once.
            ends = np.flatnonzero(big)
            ba = np.repeat(ends, n)
            bb = np.tile(np.arange(n), len(ends))
            keep = (bb != ba) & ~(big[bb] & (bb < ba))
            a = np.concatenate([a, ba[keep]])
            b = np.concatenate([b, bb[keep]])
        lo = np.minimum(a, b).astype(np.int64)  # rows a < b, as every pair's test gives
        return lo, np.maximum(a, b).astype(np.int64)

    def _allowed(
        self, store: Any, sc: _Scene, candidates: tuple[np.ndarray, np.ndarray]
    ) -> tuple[np.ndarray | None, np.ndarray | None]:
        """Of the candidate pairs (bool, one a pair): which their filters let meet
        (engine.pipeline.game_broadphase.filters_meet, what waking asks), and which the
        broadphase may keep whatever the bodies' motion (``allowed``). Kept while the
        candidates and what these are read of (the filters, radii, sensors, the pairs kept
        apart) are the same arrays: each is made again, never written into, where the World
        changes it (engine.dynamics.store), and up to ``_FEW`` bodies the candidates are the
        same arrays every step; a game's plain step asks nothing of them again. None, None past
        ``_FEW`` bodies: a grid's candidates are new each step, and the stages ask these of
        the few pairs near enough."""
        if len(store) > _FEW:
            return None, None
        a, b = candidates
        made: tuple[Any, ...] = (a, b, store.group, store.categories, store.mask, store.radius)
        made += (sc.sensors, sc.apart)
        kept = self._kept_allowed
        if kept is None or not _same(kept[0], made):
            meet = broad.filters_meet(store, a, b)
            kept = self._kept_allowed = (
                made,
                meet,
                broad.allowed(store, sc.sensors, a, b, sc.apart),
            )
        return kept[1], kept[2]

    def _box_rows(self, places: narrowphase.Places, parts: Any) -> broad.BoxRows:
        """engine.pipeline.game_broadphase.box_rows of the shapes, kept while their places
        and parts are the same objects (made again when the shapes change)."""
        part = None if parts is None else parts[0]
        kept = self._kept_boxes
        if kept is None or kept[0] is not places or kept[1] is not part:
            kept = self._kept_boxes = (places, part, broad.box_rows(places, parts))
        return kept[2]

    def _face_filters(self, store: Any, sc: _Scene) -> tuple[np.ndarray, np.ndarray]:
        """engine.pipeline.game_broadphase.face_filters of the bodies and the static shapes,
        kept while what they are read of (the bodies' filters, the sensors, the colliders'
        arrays and the shapes' places) are the same objects: each is made again, never
        written into, where the World changes it."""
        made = (store.group, store.categories, store.mask, sc.sensors, sc.cs, sc.owner)
        kept = self._kept_faces
        if kept is None or not _same(kept[0], made):
            filters = broad.face_filters(store, sc.cs, sc.owner, sc.sensors)
            kept = self._kept_faces = (made, filters)
        return kept[1]

    def _median_radius(self, store: Any) -> float:
        """The bodies' median radius (m), kept while their radii are the same array."""
        if self._median is None or self._median[0] is not store.radius:
            self._median = (store.radius, float(np.median(store.radius)))
        return self._median[1]

    # -- sleep (engine.pipeline.game_sleep) --------------------------------------------------------
    def _wake(
        self,
        state: WorldState,
        store: Any,
        margin: np.ndarray,
        candidates: tuple[Any, Any],
        boxes: np.ndarray,
        meet: np.ndarray | None = None,
    ) -> np.ndarray:
        """The bodies the step moves (dynamic and awake), the sleepers an awake body meets
        (by the bodies' ``boxes`` too; ``meet``: the candidates' filters, ``_allowed``)
        woken first with their islands."""
        n = len(store)
        dynamic = self._dynamic_rows(state, store)
        c = state.collisions
        if len(c.asleep) != n or len(c.still) != n or len(c._group) != n:
            c.wake(n)  # bodies came or went: every island wakes (the exact step's rule)
        # (np.count_nonzero for ndarray.any() in this stage and those after it: a C call, as
        # in ``step``.)
        if not np.count_nonzero(c.asleep):
            return dynamic.copy()  # (a copy: the kept mask is not the step's to change)
        asleep = c.asleep
        spins = (store.v != 0.0).any(axis=1) | (store.omega != 0.0)
        active = (dynamic & ~asleep) | (store.kinematic & spins)
        wake = game_sleep.woken(
            asleep, c._group, active, *candidates, store, margin, boxes, meet, self.unit
        )
        if np.count_nonzero(wake):
            asleep[wake] = False
            c.still[wake] = 0.0
        return dynamic & ~asleep

    def _dynamic_count(self, state: WorldState, store: Any) -> int:
        """How many bodies are dynamic (of finite mass, not kinematic), counted again when
        the World's bodies or masses change (``state.version``) or the arrays are new."""
        return self._dynamic_kept(state, store)[3]

    def _dynamic_rows(self, state: WorldState, store: Any) -> np.ndarray:
        """Which bodies are dynamic (bool (N,): of finite mass, not kinematic), kept as
        ``_dynamic_count`` is (not to be written into)."""
        return self._dynamic_kept(state, store)[4]

    def _dynamic_kept(self, state: WorldState, store: Any) -> tuple[Any, ...]:
        kept = self._dynamic
        if (
            kept is None
            or kept[0] != state.version
            or kept[1] is not store.mass
            or kept[2] is not store.kinematic
        ):
            rows = ~store.kinematic & np.isfinite(store.mass)
            count = int(np.count_nonzero(rows))
            kept = self._dynamic = (state.version, store.mass, store.kinematic, count, rows)
        return kept

    @staticmethod
    def _stirring(store: Any, asleep: np.ndarray) -> bool:
        """Whether a body the step would move is awake: a dynamic one not asleep, or a
        kinematic one with a velocity."""
        # (Of bools, a > b is a & ~b: dynamic, not kinematic and of finite mass, and awake,
        # in half the calls: this runs every step in which anything sleeps.)
        if np.count_nonzero((np.isfinite(store.mass) > store.kinematic) > asleep):
            return True
        kin = store.kinematic
        return bool(np.count_nonzero(store.v[kin]) or np.count_nonzero(store.omega[kin]))

    def _sleep(
        self,
        state: WorldState,
        store: Any,
        dt: float,
        awake: np.ndarray,
        v: np.ndarray,
        omega: np.ndarray,
        found: _Found,
        joints: list[np.ndarray],
        x: np.ndarray,
        angle: np.ndarray,
        rising: np.ndarray,
    ) -> None:
        """After the solve: still times counted, still islands put to sleep (their ``v`` and
        ``omega`` zeroed, in place), the contacts of sleepers held open; ``x`` and ``angle``
        the bodies' after it (a pymunk constraint's bodies: how far it moved them);
        ``rising`` the bodies (bool (N,)) their held loads have yet to lift by more than
        engine.pipeline.game_sleep's ``RISE``."""
        c = state.collisions
        n = len(store)
        rows = found.rows
        pair = rows[1] < n
        ends_a, ends_b, never, held_a, held_b = self._joint_ends(state, store, joints)
        a = np.concatenate([rows[0][pair], ends_a])
        b = np.concatenate([rows[1][pair], ends_b])
        a, b = np.minimum(a, b), np.maximum(a, b)
        c._touching = a.astype(np.int64) * n + b  # for Body.sleep's island
        before = c.asleep.copy()  # (those asleep through the step: ~awake, but kinematic)
        # (Not still either: a body its held loads have yet to lift, ``rising``; none drifts
        # where no pymunk constraint holds a body.)
        drift = rising
        if len(held_a):
            drift = rising | game_sleep.drifting(
                store.x, x, store.angle, angle, held_a, held_b, dt, self.unit
            )
        game_sleep.fall_asleep(
            c.still, c.asleep, c._group, awake, never, v, omega, store.radius, a, b, dt,
            c.sleep_time, self.fast, drift, self.unit,
        )  # fmt: skip
        now = c.asleep & ~before
        if np.count_nonzero(now):
            v[now] = 0.0
            omega[now] = 0.0
        if np.count_nonzero(before):
            self._hold(store, before)

    def _joint_ends(
        self, state: WorldState, store: Any, joints: list[np.ndarray]
    ) -> tuple[np.ndarray, ...]:
        """What sleep reads of the joints' rows (solver.solve's joint arrays ``joints``): the
        ends (the solver's B and A) of those that join an island, both ends bodies (either
        may be the world); the bodies that never sleep (kinematic, or dragged by a mouse
        joint: its solver B); and the ends (solver A, B) of a pymunk constraint's rows
        (``_constraint_row``'s bit 2 of jmotor). Kept while the World's bodies and those
        arrays are the same (the numpy path keeps the joints' arrays while no row changes:
        engine.dynamics.game_joints)."""
        numbers = (state.version, len(store))
        made = (store.kinematic, joints[0], joints[1], joints[2], joints[13])
        kept = self._kept_ends
        if kept is None or kept[2] != numbers or not _same(kept[0], made):
            n = len(store)
            both = (joints[1] < n) & (joints[2] < n)
            never = store.kinematic.copy()
            never[joints[2][joints[0] == solver.MOUSE]] = True
            bounded = (joints[13] & 2) != 0
            ends: tuple[np.ndarray, ...] = (joints[2][both], joints[1][both], never)
            ends += (joints[1][bounded], joints[2][bounded])
            kept = self._kept_ends = (made, ends, numbers)
        return kept[1]

    def _hold(self, store: Any, asleep: np.ndarray) -> None:
        """The last step's touching contacts whose bodies slept through this one (``asleep``:
        a sleeper and a collider, or two sleepers) stay open: their rows were not found, nor
        solved, and nothing ends. (A body asleep through the step has no contact in it: an
        awake body near it would have woken it.)"""
        last, now = self.last, self.report
        if not len(last.keys):
            return
        row_of = store.row_of
        a = row_of[last.keys >> 32]
        other = last.keys & (COLLIDER - 1)
        collider = (last.keys & COLLIDER) != 0
        b = row_of[np.where(collider, 0, other)]
        keep = asleep[a] & (collider | asleep[b])
        if np.count_nonzero(keep):
            keys = np.concatenate([now.keys, last.keys[keep]])
            order = np.argsort(keys, kind="stable")  # the report stays sorted by key
            packed = np.concatenate([now.packed, last.packed[keep]])[order]
            self.report = _Report(keys[order], packed, now.sensing)

    def _collide(
        self, sc: _Scene, store: Any, pairs: np.ndarray, faces: np.ndarray, margin: np.ndarray,
        struck: np.ndarray, dt: float,
    ) -> narrowphase.Touches:  # fmt: skip
        """Stage 3, the narrowphase (engine.geometry.narrowphase.collide_pairs) of the pairs
        and faces; where a body is of several shapes (engine.body_shapes), of their parts:
        every part of A against every part of B, and every part against the face, each part at
        its body's pose, the manifolds given back to the bodies' rows (anchors from a part's
        body's position are from its own), the two parts' numbers kept in each point's feature
        id above the pair's code (``PART``), so that each keeps its own warm start."""
        parts = sc.table.parts
        if parts is None:
            return narrowphase.collide_pairs(
                sc.places, sc.table, store, sc.statics, pairs, faces, margin, dt, struck, self.unit
            )
        part_places = self._parts_places(sc)
        pa, pb = part_pairs(parts, pairs[:, 0], pairs[:, 1])
        face, jf = part_rows(parts.size[faces[:, 0]])
        fa = parts.first[faces[face, 0]] + jf
        owner = parts.owner
        view = _PartView(store.x[owner], store.angle[owner], store.v[owner])
        touches = narrowphase.collide_pairs(
            part_places, parts.table, view, sc.statics, np.stack([pa, pb], axis=1),
            np.stack([fa, faces[face, 1]], axis=1), margin[owner], dt, struck[owner], self.unit,
        )  # fmt: skip
        n, p = len(store), len(owner)
        static = touches.b >= p
        body_b = np.where(static, n, owner[np.minimum(touches.b, p - 1)])
        number_b = np.where(static, 0, parts.number[np.minimum(touches.b, p - 1)])
        code = (parts.number[touches.a] * MAX_PARTS + number_b).astype(np.int64) << PART
        m = touches.m
        m.feature[:] = np.where(m.feature >= 0, m.feature | code[:, None], m.feature)
        return narrowphase.Touches(m, owner[touches.a], body_b, touches.place)

    def _parts_places(self, sc: _Scene) -> narrowphase.Places:
        """The places of the bodies' parts (engine.geometry.shaped.Parts) and the static
        shapes in one pair of tables, kept while the parts and the colliders' shapes are."""
        parts = sc.table.parts
        assert parts is not None
        return self._parts_places_of(parts, sc.statics)

    def _parts_places_of(self, parts: Parts, statics: StaticShapes) -> narrowphase.Places:
        kept = self._part_places
        if kept is None or kept[0] is not parts or kept[1] is not statics:
            kept = self._part_places = (parts, statics, narrowphase.places_of(parts.table, statics))
        return kept[2]

    def _found(
        self, store: Any, cs: broad.Colliders, owner: np.ndarray, touches: narrowphase.Touches
    ) -> _Found:
        """The manifolds as the solver's contact rows (solver.solve's order), warm started by
        key; a sensor collider's manifolds as its overlaps (events only: no row pushes its
        body)."""
        if len(touches.a) <= _FEW_FOUND:
            return self._found_few(store, cs, owner, touches)
        n = len(store)
        sensor = np.zeros(len(touches.m), dtype=bool)
        # (mask.nonzero()[0]: np.flatnonzero's answer for a 1D mask, without its Python wrapper.)
        stat = (touches.b >= n).nonzero()[0]
        if len(stat):
            sensor[stat] = cs.sensor[owner[touches.place[stat]]]
        if len(stat) and np.count_nonzero(sensor):
            over = sensor & (touches.m.separation < 0.0).any(axis=1)
            sense_row = touches.a[over].astype(np.int64)
            sense_place = owner[touches.place[over]].astype(np.int64)
            m, ia, ib, other = touches.take(~sensor)
        else:  # (no sensor's manifold: every one is a contact, as it is)
            sense_row = sense_place = np.zeros(0, dtype=np.int64)
            m, ia, ib, other = touches
        k = len(m)
        count = m.count.astype(np.int64)
        real = (count[:, None] > _SLOTS).ravel()  # (2 k): which slots hold a point
        slots = store.slots()
        # The pair's code: body B's slot, or a static shape's place.
        code_b = np.where(ib < n, slots[np.minimum(ib, n - 1)], STATIC + other)
        code = (slots[ia].astype(np.int64) << OTHER) | code_b.astype(np.int64)
        feature = np.where(m.feature >= 0, m.feature, 0).astype(np.int64)
        keys = (code[:, None] << FEATURE) | feature  # (k, 2)
        lam = np.zeros((k, 2, 3))  # each point's normal and tangent impulses, held load
        if len(self.keys) and k:
            flat = keys.ravel()
            at = np.minimum(np.searchsorted(self.keys, flat), len(self.keys) - 1)
            hit = (self.keys[at] == flat) & real
            lam.reshape(-1, 3)[hit] = self.lam[at[hit]]
        # Materials: a body's, or a collider's; friction mu_a mu_b, restitution e_a e_b.
        e_b = np.ones(k)
        mu_b = np.ones(k)
        speed = np.zeros(k)
        pair = ib < n
        e_b[pair] = store.restitution[ib[pair]]
        mu_b[pair] = store.friction[ib[pair]]
        stat = (~pair).nonzero()[0]
        if len(stat):
            places = owner[other[stat]]
            e_b[stat] = cs.restitution[places]
            mu_b[stat] = cs.friction[places]
            # A conveyor: the collider's surface moves at u; the slip is the relative
            # velocity less u's part along the tangent t = (-n_y, n_x).
            u = cs.surface[places]
            speed[stat] = -(u[:, 0] * -m.normal[stat, 1] + u[:, 1] * m.normal[stat, 0])
        sep = np.where(np.isfinite(m.separation), m.separation, 0.0)
        c = np.ascontiguousarray
        rows = [
            c(ia, dtype=np.int64),
            c(ib, dtype=np.int64),
            c(m.normal[:, 0]),
            c(m.normal[:, 1]),
            count,
            c(m.anchor_a[:, :, 0].ravel()),
            c(m.anchor_a[:, :, 1].ravel()),
            c(m.anchor_b[:, :, 0].ravel()),
            c(m.anchor_b[:, :, 1].ravel()),
            c(sep.ravel()),
            store.friction[ia] * mu_b,
            store.restitution[ia] * e_b,
            speed,
            c(lam[:, :, 0].ravel()),
            c(lam[:, :, 1].ravel()),
            c(lam[:, :, 2].ravel()),
        ]
        point = c(m.point[:, 0])
        return _Found(
            rows, keys.ravel(), other.astype(np.int64), point, sense_row, sense_place, real
        )

    def _found_few(
        self, store: Any, cs: broad.Colliders, owner: np.ndarray, touches: narrowphase.Touches
    ) -> _Found:
        """``_found`` of a few manifolds as plain Python on lists, each number the numpy
        code's product, in its order (at a game's few contacts numpy's fixed cost a call is
        most of that code's time): a record a row and one a point, turned into the solver's
        lists and, in three calls, the rows as arrays (the rows of an int table and two
        float tables)."""
        n = len(store)
        m = touches.m
        ta, tb, tplace = touches.a.tolist(), touches.b.tolist(), touches.place.tolist()
        separation = m.separation.tolist()
        sense_row: list[int] = []
        sense_place: list[int] = []
        picked: list[int] = []  # the manifolds that are contacts: not a sensor collider's
        for i, b in enumerate(tb):
            if b >= n and cs.sensor[owner[tplace[i]]]:
                if separation[i][0] < 0.0 or separation[i][1] < 0.0:  # (an overlap)
                    sense_row.append(ta[i])
                    sense_place.append(int(owner[tplace[i]]))
            else:
                picked.append(i)
        normal, count = m.normal.tolist(), m.count.tolist()
        anchor_a, anchor_b = m.anchor_a.tolist(), m.anchor_b.tolist()
        feature, point = m.feature.tolist(), m.point[:, 0].tolist()
        slots = store.slots().tolist()
        friction, restitution = store.friction, store.restitution
        last = self.keys.tolist()  # the last step's keys, sorted (searched as np.searchsorted)
        none = [0.0, 0.0, 0.0]
        # Each row's (A's row, B's (n: static), point count, nx, ny, friction, restitution,
        # surface speed, static place, its first point's x, y) and each point's (the anchors'
        # x and y, A's and B's, separation, warm start: normal and tangent impulses and
        # held load, key, whether it is a point).
        rows: list[tuple[Any, ...]] = []
        points: list[tuple[Any, ...]] = []
        for i in picked:
            a, b, place, c = ta[i], tb[i], tplace[i], count[i]
            nx, ny = normal[i]
            # The pair's code: body B's slot, or a static shape's place.
            code = (slots[a] << OTHER) | (slots[b] if b < n else STATIC + place)
            # Materials: a body's, or a collider's (with a conveyor's surface speed along
            # the tangent t = (-n_y, n_x)).
            speed = 0.0
            if b < n:
                e_b, mu_b = float(restitution[b]), float(friction[b])
            else:
                q = owner[place]
                e_b, mu_b = float(cs.restitution[q]), float(cs.friction[q])
                u0, u1 = cs.surface[q].tolist()
                speed = -(u0 * -ny + u1 * nx)
            mu, e = float(friction[a]) * mu_b, float(restitution[a]) * e_b
            rows.append((a, b, c, nx, ny, mu, e, speed, place, *point[i]))
            for j in (0, 1):
                f = feature[i][j]
                key = (code << FEATURE) | (f if f >= 0 else 0)
                held = none
                if last and j < c:
                    at = min(bisect_left(last, key), len(last) - 1)
                    if last[at] == key:
                        held = self.lam[at].tolist()
                sep = separation[i][j]
                sep = sep if math.isfinite(sep) else 0.0
                points.append((*anchor_a[i][j], *anchor_b[i][j], sep, *held, key, j < c))
        k = len(picked)
        # The records' columns (zip(*records)); lists, as the solver writes its impulses.
        by_row = [list(col) for col in zip(*rows, strict=True)] if k else [[] for _ in range(11)]
        by_point = [list(col) for col in zip(*points, strict=True)]
        if not k:
            by_point = [[] for _ in range(10)]
        ia, ib, cn, nx_, ny_, mu_, e_, speed_, places, px, py = by_row
        ax, ay, bx, by, sep_, lam_n, lam_t, held_, keys, real = by_point
        i64 = np.int64
        ints = np.array([ia, ib, cn], dtype=i64).reshape(3, k)
        own = np.array([nx_, ny_, mu_, e_, speed_], dtype=float).reshape(5, k)
        at_points = np.array(by_point[:8], dtype=float).reshape(8, 2 * k)
        arrays = [ints[0], ints[1], own[0], own[1], ints[2], *at_points[0:5], own[2], own[3]]
        arrays += [own[4], *at_points[5:8]]
        lists = [ia, ib, nx_, ny_, cn, ax, ay, bx, by, sep_, mu_, e_, speed_, lam_n, lam_t, held_]
        point_xy = np.array([px, py], dtype=float).reshape(2, k).T
        return _Found(
            arrays, np.array(keys, dtype=i64), np.array(places, dtype=i64), point_xy,
            np.array(sense_row, dtype=i64), np.array(sense_place, dtype=i64),
            np.array(real, dtype=bool), lists,
        )  # fmt: skip

    def _keep(self, found: _Found, out: list[Any]) -> None:
        """Keep this step's impulses by key, for the next step's warm start."""
        base = 11  # the bodies' arrays come first
        if found.lists is not None:
            # A few rows (``_found_few``): each point's key and its impulses and held load,
            # sorted by key (stably, as np.argsort's "stable"), in plain Python.
            lam_n, lam_t, held = out[base + 13 : base + 16]
            keys, real = found.keys.tolist(), found.real.tolist()
            kept = [(keys[p], (lam_n[p], lam_t[p], held[p])) for p in range(len(keys)) if real[p]]
            kept.sort(key=lambda entry: entry[0])  # (stable: equal keys keep their order)
            self.keys = np.array([key for key, _ in kept], dtype=np.int64)
            self.lam = np.array([lam for _, lam in kept], dtype=float).reshape(len(kept), 3)
            return
        real = found.real
        # (The normal and tangent impulses and held loads, each a list of 2 k, as the rows
        # of one (3, 2 k) array: one call where three were.)
        lam = np.array(out[base + 13 : base + 16], dtype=float)
        keys = found.keys[real]
        order = np.argsort(keys, kind="stable")
        self.keys = keys[order]
        self.lam = lam.T[real][order]
        self._totals = (np.asarray(out[base + 16], dtype=float), lam[1])

    # -- stage 5: joints ----------------------------------------------------------------------
    # -- stage 7: events ----------------------------------------------------------------------
    def _events(
        self,
        store: Any,
        cs: broad.Colliders,
        owner: np.ndarray,
        found: _Found,
        out: list[Any],
    ) -> None:
        """Which contacts touch after the step (a point that pushed in it, or one nearer
        than LINEAR_SLOP at its start)."""
        if found.lists is not None:
            self._events_few(store, cs, owner, found, out)
            return
        rows = found.rows
        ia, ib, sep = rows[0], rows[1], rows[9]
        other = found.place
        n = len(store)
        slots = store.slots()
        total, lam_t = self._totals
        real = found.real
        pushed = (total > 0.0) & real
        near = (sep < LINEAR_SLOP * self.unit) & real
        touch = (pushed | near).reshape(-1, 2).any(axis=1)
        stat = ib >= n
        keys = np.zeros(len(ia), dtype=np.int64)
        pair = ~stat
        if np.count_nonzero(pair):
            keys[pair] = pair_keys(slots[ia[pair]], slots[ib[pair]])
        if np.count_nonzero(stat):
            keys[stat] = collider_keys(slots[ia[stat]], cs.serial[owner[other[stat]]])
        # The impulse on the key's first body: -(lam_n n + lam_t t) on A, the whole step's.
        tn = total.reshape(-1, 2).sum(axis=1) if len(ia) else np.zeros(0)
        tt = np.asarray(lam_t, dtype=float).reshape(-1, 2).sum(axis=1) * self.substeps
        first_a = np.ones(len(ia), dtype=bool)
        first_a[pair] = slots[ia[pair]] <= slots[np.minimum(ib[pair], n - 1)]
        sign = np.where(first_a, 1.0, -1.0)
        self.last = self.report
        # Sorted by key (stably), as the fast path's report: the events' searches need no sort.
        picked = touch.nonzero()[0]
        picked = picked[np.argsort(keys[picked], kind="stable")]
        # The report's columns (``_Report``) of the picked rows: the point, the normal
        # toward the key's first body, and the impulse on it, -(tn n + tt t) on A over the
        # whole step (t = (-n_y, n_x), the tangent).
        nx, ny, sign = rows[2][picked], rows[3][picked], sign[picked]
        tn, tt = tn[picked], tt[picked]
        packed = np.empty((len(picked), 6))
        packed[:, 0:2] = found.point[picked]
        packed[:, 2] = -nx * sign
        packed[:, 3] = -ny * sign
        packed[:, 4] = -(tn * nx + tt * -ny) * sign
        packed[:, 5] = -(tn * ny + tt * nx) * sign
        self.report = _Report(keys[picked], packed)

    def _events_few(
        self, store: Any, cs: broad.Colliders, owner: np.ndarray, found: _Found, out: list[Any]
    ) -> None:
        """``_events`` where ``_found`` made a few rows as lists (``_found_few``): plain
        Python, each number the numpy code's product, in its order."""
        rows = found.rows
        ia, ib, nx_, ny_, count = (rows[r].tolist() for r in range(5))
        sep, point = rows[9].tolist(), found.point.tolist()
        total, lam_t = out[11 + 16], out[11 + 14]  # the solver's (the bodies' 11 first)
        n = len(store)
        slots = store.slots().tolist()
        touching: list[tuple[int, list[float]]] = []  # (key, the report's row)
        slop = LINEAR_SLOP * self.unit
        for i, (a, b, c) in enumerate(zip(ia, ib, count, strict=True)):
            p = 2 * i
            # A point that pushed, or one nearer than the slop at the step's start.
            if not any(total[p + j] > 0.0 or sep[p + j] < slop for j in range(c)):
                continue
            if b < n:
                sa, sb = slots[a], slots[b]
                key, sign = pair_key(sa, sb), 1.0 if sa <= sb else -1.0
            else:
                key, sign = collider_key(slots[a], int(cs.serial[owner[found.place[i]]])), 1.0
            # The impulse on the key's first body: -(tn n + tt t) on A, the whole step's.
            tn = total[p] + total[p + 1]
            tt = (lam_t[p] + lam_t[p + 1]) * self.substeps
            nx, ny = nx_[i], ny_[i]
            impulse = (-(tn * nx + tt * -ny) * sign, -(tn * ny + tt * nx) * sign)
            touching.append((key, [*point[i], -nx * sign, -ny * sign, *impulse]))
        self.last = self.report
        # Sorted by key (stably: Python's sort is), as the fast path's report.
        touching.sort(key=lambda entry: entry[0])
        keys = np.array([key for key, _ in touching], dtype=np.int64)
        packed = np.array([row for _, row in touching], dtype=float).reshape(len(touching), 6)
        self.report = _Report(keys, packed)


def _faces(
    sc: _Scene, store: Any, rows: list[np.ndarray], place: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The numpy path's rows of a point on a face that turns (engine.dynamics.turning_faces'
    ``face_rows``, its plain twin, asked of the rows between two bodies not both discs, and
    of a disc's with a static shape that is no half plane; ``place`` each row's static shape,
    -1 for a pair of bodies): each row's kind and numbers (FACE_NUMBERS a row). None where a
    body has several shapes."""
    ca, cb, nx, ny = rows[0], rows[1], rows[2], rows[3]
    face, fround = np.zeros(len(ca), dtype=np.int64), np.zeros(FACE_NUMBERS * len(ca))
    n = len(store)
    if sc.table.parts is not None or not len(ca):
        return face, fround
    circle = sc.places.body_circle
    static_index = sc.places.static_index
    if len(ca) <= _FEW_FOUND:
        # (A few rows: those to ask picked in plain Python, fewer calls than numpy's.)
        rows_of = zip(ca.tolist(), cb.tolist(), place.tolist(), strict=True)
        picked = [
            i
            for i, (a, b, s) in enumerate(rows_of)
            if (not (circle[a] and circle[b]) if b < n else circle[a] and s >= 0
                and static_index[s] >= 0)
        ]  # fmt: skip
        if not picked:
            return face, fround
        ask = np.array(picked, dtype=np.intp)
    else:
        pair = cb < n
        disc = circle[ca]
        shaped = (place >= 0) & (
            static_index[np.maximum(place, 0)] >= 0 if len(static_index) else False
        )
        ask = np.where(pair, ~(disc & circle[np.where(pair, cb, 0)]), disc & shaped)
        ask = ask.nonzero()[0]
        if not len(ask):
            return face, fround
    rows_n = np.arange(n, dtype=np.int64)
    parts = np.stack([rows_n, np.ones(n, dtype=np.int64)], axis=1)
    corners, normals, count, prad = sc.places.tables.kernel_polygons
    got = face_rows.py(
        ca[ask], cb[ask], nx[ask], ny[ask], n, False, store.angle, circle,
        sc.places.body_index, parts, normals, count, prad, sc.places.tables.round,
        place[ask], sc.places.static_circle, static_index, corners,
    )  # fmt: skip
    face[ask] = got[0]
    fround.reshape(-1, FACE_NUMBERS)[ask] = got[1].reshape(-1, FACE_NUMBERS)
    return face, fround


def _bodies(store: Any, accel: np.ndarray, torque: np.ndarray, moving: np.ndarray) -> np.ndarray:
    """The solver's body arrays (solver.solve's order): the World's rows, then the static
    body; the rows of one array (11, n + 1), so a few array calls make them all. Only
    ``moving`` bodies (dynamic and awake) have mass to push and forces to move them."""
    n = len(store)
    out = np.zeros((11, n + 1))
    out[0:2, :n] = store.x.T
    out[2, :n] = store.angle
    out[3:5, :n] = store.v.T
    out[5, :n] = store.omega
    # 1 / m of a moving body only (of finite mass: no other is divided), 0 for the rest.
    np.divide(1.0, store.mass, out=out[6, :n], where=moving)
    out[7, :n] = store.inv_moment
    out[8:10, :n] = accel.T
    out[10, :n] = torque * store.inv_moment
    out[7:11, :n][:, ~moving] = 0.0  # (nothing moves a body the step does not)
    return out


def _reach(store: Any, accel: np.ndarray, dt: float) -> np.ndarray:
    """How far each body's shape can move in the step (m): |v| dt + |a| dt^2 + |omega| dt r
    (its bounding radius r swept by the turn)."""
    v, r = store.v, store.radius
    speed = np.hypot(v[:, 0], v[:, 1])
    acc = np.hypot(accel[:, 0], accel[:, 1])
    return speed * dt + acc * dt * dt + np.abs(store.omega) * dt * r


class _PartView(NamedTuple):
    """What the narrowphase reads of a store, by part row: each part at its body's pose and
    velocity (``GameStep._collide``)."""

    x: np.ndarray
    angle: np.ndarray
    v: np.ndarray

    def __len__(self) -> int:
        return len(self.x)


#: An empty box (xmin > xmax): a static shape whose collider went meets nothing.
_GONE = (np.inf, np.inf, -np.inf, -np.inf)


def _without(
    before: tuple[int, ...], now: tuple[int, ...], owner: np.ndarray, bounds: np.ndarray
) -> tuple[np.ndarray, np.ndarray] | None:
    """The static shapes' collider places and boxes after the colliders of ``before`` (ids,
    in place order) not in ``now`` went, the rest in their order: the places counted anew,
    the gone ones' shapes given an empty box (``_GONE``) and place 0. None where ``now`` is
    not ``before`` less some (a collider came), or where half the shapes or more would be
    gone (the tables are made again then, so the gone do not pile up). Shapes keep their
    indices, and so the contacts' warm starts by key (engine.pipeline.game_contacts) on every
    other collider (a pile on a ledge is not let go when a coin is taken)."""
    if len(now) >= len(before) or not now:
        return None
    place = np.full(len(before), -1, dtype=np.intp)
    j = 0
    for i, ident in enumerate(before):
        if j < len(now) and now[j] == ident:
            place[i] = j
            j += 1
    if j != len(now):
        return None  # (not a subsequence: a collider came, or the order changed)
    moved = place[owner]
    gone = (moved < 0) | (bounds[:, 0] > bounds[:, 2])  # (gone now, or before: an empty box)
    if 2 * np.count_nonzero(gone) >= len(owner):
        return None
    bounds = bounds.copy()
    bounds[gone] = _GONE
    return np.where(gone, 0, moved).astype(owner.dtype), bounds
