"""Contacts with static colliders: impacts solved at their exact moment, rest, and sliding.

``Contacts`` composes a step against the world's colliders from the modules that hold each
part, cheapest test first (in a typical scene few bodies meet anything):

1. the first looks (engine.geometry.face_looks: ``near``, then ``narrow``, over the face grid of
   engine.geometry.face_grid): which bodies can meet a face this step at all. Bodies that cannot,
   and do not rest on a face, keep the state their method reached, bit for bit;
2. the sweep (engine.exact.sweep): each remaining body's path within the step, x(t) = x0 + v0 t +
   B t^2 / 2 (derived there), meets the faces in time order, bouncing at each impact's exact
   moment (engine.geometry.impact), up to ``MAX_IMPACTS``; a few bodies go one at a time in Python
   floats (engine.exact.sweep_one: the same arithmetic, the same bits, no fixed cost per call);
3. rest (engine.exact.resting): a rebound too slow to fly for one step ends in rest on the face,
   sliding under Coulomb friction to the closed form's stop, lifting off when pulled away;
   a body resting still and held by static friction costs one array write;
4. push-out (engine.exact.push_out) of a body found inside a solid collider, and sensors
   (engine.geometry.sensors), which push nothing and report bodies entering and leaving them.

On the fast path (engine.kernels; ``Contacts.fast``, the World's path) 1 and the resting
bodies' staying put are one loop kernel over the bodies (``face_looks.looks_loop``) and 2 is
another over the bodies solved (``sweep_paths.paths_loop``), each beside its twin and giving
its numbers bit for bit; what a kernel does not take (a round face's quartic, a resting body)
goes the numpy path's way.

It keeps what lasts from step to step (the compiled faces, engine.geometry.faces, updated in place
when a collider comes or goes; the grid; each body's resting face) and the step's events.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ..dynamics.events import ContactEvent
from ..dynamics.rotation import Spin
from ..geometry import sensors
from ..geometry.colliders import Collider
from ..geometry.face_grid import FaceGrid
from ..geometry.face_looks import first_looks, looks_ready, narrow, near
from ..geometry.faces import (
    Faces,
    allowed_pairs,
    compile_faces,
    face_filters,
    face_meets,
    face_normals,
    faces_added,
    faces_rematerialled,
    faces_removed,
    same_faces,
    signed_distance,
)
from ..geometry.shaped import ShapeTable
from . import push_out
from .resting import asleep
from .sweep import MAX_IMPACTS, Paths, sweep
from .sweep_one import asleep_few, solve_few

__all__ = ["Contacts", "ContactEvent", "MAX_IMPACTS", "signed_distance"]


def _spin_reach(radius: np.ndarray, spin: Spin, spun: np.ndarray, dt: float) -> np.ndarray:
    """The radii the faces' looks take (engine.geometry.face_looks): each body's own, grown for
    the ``spun`` rows (those that turn under friction and spin or are made to) by how much
    farther than its speed alone a bounce's friction can carry it within ``dt``.

    The looks bound a body's reach by its speed, a bounce never raising it; but friction at a
    bounce turns spin into speed (a ball spinning at 2,300 rad/s struck a wall at 485 m/s and
    left along it at 1,028 m/s, past the reach its 668 m/s gave it, and ended the step 0.4 m
    into the next wall, whose face the looks had not listed: found exploring). Friction only
    takes energy, so m v'^2 <= m v^2 + I omega^2, v' <= |v| + sqrt(I / m) |omega|, with
    sqrt(I / m) = r / sqrt(q) and |omega| <= |omega0| + |alpha| dt within the step: a reach
    longer by r (|omega0| + |alpha| dt) dt / sqrt(q), which the radius carries (the looks add
    it to the reach, and only keep more pairs for it)."""
    q = np.where(spun, spin.q, 1.0)
    turn = np.abs(spin.omega0) + np.abs(spin.alpha) * dt
    return radius + np.where(spun, radius * turn * dt / np.sqrt(q), 0.0) * (1.0 + 1e-9)


class Contacts:
    """The World's static colliders and the contact state of its bodies (resting or free)."""

    def __init__(self) -> None:
        self.colliders: list[Collider] = []
        #: How many times a collider was added or taken out (what is kept of the colliders
        #: is made again when it changes: engine.pipeline.game_step).
        self.edits = 0
        self._faces: Faces | None = None
        self._sensors: list[int] = []
        self.rest = np.zeros(0, dtype=np.intp) - 1  # (N,) face each body rests on, -1 if free
        self.inside = np.zeros((0, 0), dtype=bool)  # (N, sensors) overlapping each sensor
        self.capped = 0  # bodies placed on a surface after MAX_IMPACTS impacts in one step
        self._began: list[tuple[Any, ...]] = []  # arrays of (rows, colliders, points, ...)
        self._ended: list[tuple[Any, ...]] = []
        self._grid: FaceGrid | None = None
        #: Fewer rows than this to solve in a step are solved one body at a time in Python
        #: floats (``sweep_one.solve_few``), more in numpy arrays (``sweep.sweep``): the same
        #: results. The arrays cost a few hundred numpy calls a round whatever their size, the
        #: floats about 12 us a body: measured, the arrays win from about 100 rows (a 2-core
        #: machine).
        self.few = 100
        #: Fewer resting bodies than this are checked for staying put (``sweep_one.asleep_few``)
        #: in Python floats, more in arrays (``resting.asleep``): a dozen array calls (~30 us)
        #: cost more than a few rows' arithmetic.
        self.few_resting = 8
        self.moved = False  # whether the last step's contacts changed any body's state
        #: Whether the first looks take the loop kernel (engine.geometry.face_looks.looks_loop): the
        #: World's path (engine.kernels), set where the World makes this.
        self.fast = False
        #: The World's bodies' filters (group, categories, mask arrays by row), for colliders
        #: with filters of their own (``allowed``); set by the World (``set_body_filters``).
        self.body_filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        # The bodies' mask array and the faces last looked through for such bodies.
        self._ghosts_seen: tuple[np.ndarray, Faces] | None = None
        #: Pairs a pre_solve ignores for the step under way (engine.pipeline.collision_handlers):
        #: sorted keys row << 32 | collider place; empty between such steps.
        self.ignored = np.zeros(0, dtype=np.int64)
        # The colliders' surface velocities (``surface_velocities``) and the faces they were
        # read for (a material set, a collider added or taken out makes new faces).
        self._surface: tuple[Faces | None, np.ndarray | None] = (None, None)
        self._bounds: tuple[Faces | None, np.ndarray | None] = (None, None)  # likewise

    def set_body_filters(self, group: np.ndarray, categories: np.ndarray, mask: np.ndarray) -> None:
        """The World's bodies' filters, by row. The faces carry no filters while every
        collider has the default one, and then every body meets every face, except a body
        that meets nothing (mask 0) or that nothing meets (categories 0): such a body makes
        the faces' filters explicit (the defaults), so it passes through them as
        ``Filter.collides`` says. Looked at again only when the bodies' arrays or the faces
        (a collider added or taken out) change."""
        self.body_filters = (group, categories, mask)
        faces = self.faces
        seen = self._ghosts_seen
        if faces.filters is not None or (seen is not None and seen[0] is mask and seen[1] is faces):
            return
        self._ghosts_seen = (mask, faces)
        if len(mask) and bool(((mask == 0) | (categories == 0)).any()):
            faces.filters = face_filters(faces)

    # -- colliders and bodies ---------------------------------------------------------------
    def add(self, collider: Collider) -> None:
        """Add a collider (the World checks its type and pushes bodies out of it).

        What it changes is changed in place, in a few array operations whatever the count of
        colliders: its faces are put among the others (``engine.geometry.faces.faces_added``, the
        same arrays as compiling every collider afresh), the faces after them renumbered (bodies
        resting on them follow), and the grid takes them in (``FaceGrid.added``) unless it
        must be laid afresh (then it is, when next needed).
        """
        k = len(self.colliders)
        self.colliders.append(collider)
        self.edits += 1
        old = self._faces
        if old is None:
            self._rebuild()
            return
        if collider.sensor:
            self._sensors.append(k)
            self.inside = np.concatenate(
                [self.inside, np.zeros((len(self.inside), 1), dtype=bool)], axis=1
            )
            self._faces = replace(old)  # a new layout (the same faces) for the caches keyed on it
            return
        faces = self._faces = faces_added(old, self.colliders)
        first, flat = len(old.p), len(faces.p) - len(old.p)
        if flat:
            rest = self.rest
            rest[rest >= first] += flat  # round faces move up past the new flat ones
        if self._grid is not None:
            new_round = len(faces.c) - len(old.c)
            if not self._grid.added(faces, first, flat, new_round):
                self._grid = None

    def remove(self, collider: Collider) -> None:
        """Take a collider out; bodies resting on it are in flight again (in place, as
        ``add``: ``engine.geometry.faces.faces_removed``, ``FaceGrid.removed``)."""
        k = self.colliders.index(collider)
        del self.colliders[k]
        self.edits += 1
        if collider.sensor:
            j = self._sensors.index(k)
            self.inside = np.delete(self.inside, j, axis=1)
            del self._sensors[j]
        self._sensors = [s - (s > k) for s in self._sensors]
        old = self._faces
        if old is None:
            self._rebuild()
            return
        faces, index = faces_removed(old, self.colliders, k)
        self._faces = faces
        if index is None:
            return
        rest = self.rest
        on = rest >= 0
        if on.any():
            rest[on] = index[rest[on]]  # -1 for its own faces: those bodies fall
        if self._grid is not None:
            gone = np.flatnonzero(index < 0)
            if not self._grid.removed(faces, index, gone):
                self._grid = None

    def material_changed(self, collider: Collider, name: str) -> None:
        """``collider``'s ``name`` (restitution, friction, filter or sensor) was set: the
        faces take it (a new Faces, the same arrays as compiling afresh; a new layout for the
        caches keyed on it). A sensor set takes the collider's faces out (bodies resting on
        them fall) and gives it a column of ``inside`` (every body outside it: one overlapping
        it begins to at the next step); unset, the reverse, and the grid is laid again when
        next needed."""
        old = self._faces
        if name != "sensor":
            if old is not None:
                self._faces = faces_rematerialled(old, self.colliders)
            return
        k = next(i for i, c in enumerate(self.colliders) if c is collider)
        j = sum(s < k for s in self._sensors)  # its column among the sensors'
        if collider.sensor:
            self._sensors.insert(j, k)
            self.inside = np.insert(self.inside, j, False, axis=1)
        else:
            del self._sensors[j]
            self.inside = np.delete(self.inside, j, axis=1)
        if old is None:
            return
        new = self._faces = compile_faces(
            self.colliders, [i for i, c in enumerate(self.colliders) if not c.sensor]
        )
        rest = self.rest
        on = rest >= 0
        if on.any():
            rest[on] = same_faces(old, new, rest[on])  # -1 on a sensor's faces: they fall
        self._grid = None

    def filters_changed(self, group: np.ndarray, categories: np.ndarray, mask: np.ndarray) -> None:
        """A body's or a collider's filter was set (the bodies' filters now, by row): a body
        resting on a face it no longer meets is in flight again."""
        self.set_body_filters(group, categories, mask)
        rest = self.rest
        rows = np.flatnonzero(rest >= 0)
        if len(rows):
            rest[rows[~self.allowed(rows, rest[rows])]] = -1

    def _rebuild(self) -> None:
        solid = [k for k, c in enumerate(self.colliders) if not c.sensor]
        self._sensors = [k for k, c in enumerate(self.colliders) if c.sensor]
        self._faces = compile_faces(self.colliders, solid)
        n = len(self.rest)
        if self.inside.shape != (n, len(self._sensors)):
            inside = np.zeros((n, len(self._sensors)), dtype=bool)
            common = min(self.inside.shape[1], len(self._sensors))
            inside[:, :common] = self.inside[:, :common]
            self.inside = inside
        self._grid = None

    @property
    def faces(self) -> Faces:
        if self._faces is None:
            self._rebuild()
        assert self._faces is not None
        return self._faces

    def bodies_added(self, k: int) -> None:
        """k bodies were appended to the World: they start free and outside every sensor."""
        self.rest = np.concatenate([self.rest, np.full(k, -1, dtype=np.intp)])
        self.inside = np.concatenate([self.inside, np.zeros((k, self.inside.shape[1]), dtype=bool)])

    def body_removed(self, row: int) -> None:
        """The body in ``row`` left the World."""
        self.rest = np.delete(self.rest, row)
        self.inside = np.delete(self.inside, row, axis=0)

    # -- state ------------------------------------------------------------------------------
    def state(self) -> tuple[Any, ...]:
        """A copy of the contact state (what a snapshot holds)."""
        return (self.rest.copy(), self.inside.copy(), self.capped)

    def check_state(self, state: Any, n: int) -> None:
        """ValueError unless ``state`` (from ``state()``) fits ``n`` bodies and these colliders."""
        ok = isinstance(state, tuple) and len(state) == 3
        if ok:
            rest, inside, capped = state
            ok = (
                isinstance(rest, np.ndarray)
                and rest.shape == (n,)
                and rest.dtype.kind == "i"
                and isinstance(inside, np.ndarray)
                and inside.shape == (n, len(self._sensors))
                and inside.dtype == bool
                and bool(np.all((rest >= -1) & (rest < len(self.faces.owner))))
                and isinstance(capped, int)
                and not isinstance(capped, bool)
                and capped >= 0
            )
        if not ok:
            raise ValueError(
                "snapshot.contacts must be the contact state from World.snapshot() of a World "
                f"with these colliders and {n} bodies"
            )

    def set_state(self, state: tuple[Any, ...], n: int) -> None:
        """Bring back ``state()``; ValueError if it does not fit ``n`` bodies."""
        self.check_state(state, n)
        rest, inside, capped = state
        self.rest, self.inside, self.capped = rest.copy(), inside.copy(), int(capped)

    def surface_velocities(self) -> np.ndarray | None:
        """The colliders' ``surface_velocity`` (C, 2; length units/s), by place, or None when
        every one is at rest (read again when the faces change)."""
        faces = self.faces
        if self._surface[0] is not faces:
            u = np.array([tuple(c.surface_velocity) for c in self.colliders], dtype=float)
            self._surface = (faces, u.reshape(-1, 2) if u.any() else None)
        return self._surface[1]

    def collider_bounds(self) -> np.ndarray:
        """(C, 4) each collider's (xmin, ymin, xmax, ymax) (length units, inf for what has no
        end), by place (read again when the faces change)."""
        faces = self.faces
        if self._bounds[0] is not faces:
            b = np.array([c.bounds() for c in self.colliders], dtype=float).reshape(-1, 4)
            self._bounds = (faces, b)
        bounds = self._bounds[1]
        assert bounds is not None
        return bounds

    def near_moving(self, store: Any, pull: np.ndarray, dt: float) -> np.ndarray | None:
        """(N,) bool: the bodies (radius > 0, not kinematic) within reach this step of a
        collider whose surface moves (``surface_velocities``), as the pile's faces are
        reached (0.05 r + |v| dt + |a| dt^2); None when no surface moves or none is near."""
        surface = self.surface_velocities()
        if surface is None or not len(store.radius):
            return None
        x, r = store.x, store.radius
        speed = np.hypot(store.v[:, 0], store.v[:, 1]) + np.hypot(pull[:, 0], pull[:, 1]) * dt
        reach = 0.05 * r + speed * dt
        near = np.zeros(len(r), dtype=bool)
        for k in np.flatnonzero(surface.any(axis=1)).tolist():
            c = self.colliders[k]
            if not c.sensor:
                near |= signed_distance(c, x) - r <= reach
        near &= (r > 0.0) & ~store.kinematic
        return near if near.any() else None

    @property
    def filtering(self) -> bool:
        """Whether some body may not meet some face this step (``allowed`` is not all True):
        a collider has a filter, or a pre_solve ignores a pair."""
        return self.faces.filters is not None or len(self.ignored) > 0

    def set_ignored(self, pairs: np.ndarray) -> None:
        """Ignore ``pairs`` (K, 2) of (body row, collider place) for the next step, as if
        their filters did not collide (a pre_solve that returned False); a body resting on
        such a collider is in flight again. An empty ``pairs`` ends the last step's."""
        if not len(pairs) and not len(self.ignored):
            return
        self.ignored = np.sort((pairs[:, 0].astype(np.int64) << 32) | pairs[:, 1])
        if len(pairs):
            rest = self.rest
            rows = np.flatnonzero(rest >= 0)
            if len(rows):
                rest[rows[~self.allowed(rows, rest[rows])]] = -1

    def allowed(self, rows: np.ndarray, faces: np.ndarray) -> np.ndarray:
        """Whether each body (World row) meets each face (pairs of equal length): their
        filters collide (engine.filters), as for two bodies, and no pre_solve ignores the
        pair this step. All True without filters."""
        ok = allowed_pairs(self.faces, self.body_filters, rows, faces)
        ignored = self.ignored
        if len(ignored) and len(rows):
            keys = (np.asarray(rows, dtype=np.int64) << 32) | self.faces.owner[faces]
            pos = np.minimum(np.searchsorted(ignored, keys), len(ignored) - 1)
            ok = ok & (ignored[pos] != keys)
        return ok

    # -- pushing bodies out -----------------------------------------------------------------
    def push_out(
        self, x: np.ndarray, v: np.ndarray, radius: np.ndarray, rows: np.ndarray
    ) -> list[tuple[int, int]]:
        """Move bodies (World ``rows``) that overlap a solid collider they meet to the nearest
        place outside every one (``push_out_rows``), in place; return (place in x, a
        collider it overlapped) for each (engine.exact.push_out).

        The velocity's part into the surfaces it then touches is removed.
        """
        return push_out.push_out(
            self.colliders, self.faces, self.body_filters, x, v, radius, rows, self._grid
        )

    # -- the step ---------------------------------------------------------------------------
    def resolve(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        x1: np.ndarray,
        v1: np.ndarray,
        dt: float,
        t0: float,
        radius: np.ndarray,
        restitution: np.ndarray,
        friction: np.ndarray,
        mass: np.ndarray,
        acceleration: np.ndarray | None = None,
        frozen: np.ndarray | None = None,
        sense: bool = True,
        spin: Spin | None = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The state after dt with every contact on the way applied: new (x, v) arrays.

        ``acceleration`` (N, 2): the bodies' constant acceleration over the step when it is
        known (the closed form); else the path is taken from the step's own update.
        ``frozen`` (N,) bool: bodies left alone here (asleep, moved by the game, or in a pile:
        engine.exact.collisions steps them). ``sense``: report the sensors now (else the World
        calls ``sense`` once the bodies between them have moved too). ``spin``: the rotation
        of the bodies over the step (engine.dynamics.rotation), None when none turns; the friction
        of the faces turns those it touches (its ``angle`` and ``omega`` are written).
        """
        self._began, self._ended = [], []
        faces = self.faces
        x, v = x1, v1
        if acceleration is not None:
            W = B = acceleration
        else:
            W = (v1 - v0) * (1.0 / dt)
            B = (x1 - x0 - v0 * dt) * (2.0 / (dt * dt))
        self.moved = False
        look_friction = friction
        look_radius = radius
        if spin is not None:
            # Bodies that turn and have friction roll, slip and spin on the faces: the look's
            # static-friction test holds one still only where nothing pulls it along the face
            # (friction 0: |a_t| <= 0) and it neither spins nor is made to (the rolling law,
            # engine.exact.resting, leaves exactly such a body where it is); any other is swept
            # (nan fails every comparison).
            rolls = spin.rolls(friction)
            if rolls.any():
                idle = (spin.omega0 == 0.0) & (spin.alpha == 0.0)
                look_friction = np.where(rolls, np.where(idle, 0.0, np.nan), friction)
                look_radius = _spin_reach(radius, spin, rolls & ~idle, dt)
        if len(faces.owner):
            allowed = self.allowed if self.filtering else None
            if self.fast and looks_ready(self.grid):
                # The fast path: both looks and the resting bodies' staying put in one
                # compiled loop over the bodies, the same rows and pairs as below
                # (engine.geometry.face_looks.looks_loop).
                rows, pb, pf, asleep = first_looks(
                    self.grid, faces, x0, v0, B, W, dt, look_radius, look_friction, self.rest,
                    frozen, allowed,
                )  # fmt: skip
            else:
                rows, asleep, cell, reach, a_bound = self._near(
                    x0, v0, B, W, dt, look_radius, look_friction
                )
                if frozen is not None and frozen[rows].any():
                    awake = ~frozen[rows]
                    rows, reach = rows[awake], reach[awake]
                    cell = None if cell is None else cell[awake]
                if len(rows):
                    busy = self.rest.take(rows) >= 0  # resting bodies slide, lift or stay
                    rows, pb, pf = narrow(
                        self.grid, rows, busy, cell, reach, a_bound, x0, v0, dt, look_radius,
                        allowed,
                    )  # fmt: skip
            if len(asleep):
                # Resting and held by friction: they stay put, whatever the method computed.
                x, v = x1.copy(), v1.copy()
                x[asleep], v[asleep] = x0[asleep], 0.0
                self.moved = True
            if len(rows):
                # A few bodies are solved one at a time in Python floats, many in arrays:
                # the same arithmetic, so the same result either way.
                paths = Paths(x0, v0, B, W, dt, t0, radius, restitution, friction, mass)
                # On the fast path a loop kernel takes the free bodies, however many
                # (engine.exact.sweep_paths.paths_loop: the same bits).
                if len(rows) < self.few or self.fast:
                    changed, X, V, capped = solve_few(
                        faces, paths, rows, pb, pf, self.rest, self.push_out_rows,
                        self._began, self._ended, self.fast, spin,
                    )  # fmt: skip
                else:
                    changed, X, V, capped = sweep(
                        faces, paths, rows, pb, pf, self.rest, self.push_out_rows,
                        self._began, self._ended, spin,
                    )  # fmt: skip
                self.capped += capped
                # Only bodies that met something change: the rest keep (x1, v1) bit for bit.
                if len(changed):
                    if not self.moved:
                        x, v = x1.copy(), v1.copy()
                    x[changed], v[changed] = X, V
                    self.moved = True
        if sense:
            self.sense(x, dt, t0, radius)
        return x, v

    def record(
        self,
        rows: np.ndarray,
        colliders: np.ndarray,
        points: np.ndarray,
        normals: np.ndarray,
        impulses: np.ndarray,
        times: np.ndarray,
    ) -> None:
        """Report bounces found elsewhere (engine.exact.collisions: a body sent into a wall by
        another): each begins and ends in the step, as a bounce here does. ``impulses``: the
        bodies' changes of momentum (N s)."""
        if len(rows):
            self._began.append((rows, colliders, points, normals, impulses, times))
            self._ended.append((rows, colliders, points, normals, impulses, times))

    def forget(
        self, rows: np.ndarray, after: np.ndarray, upto: tuple[int, int] | None = None
    ) -> None:
        """Drop the reports of the bodies in ``rows`` (World rows) later than the World times
        ``after`` (s): bounces they never reached, another body having sent them off their
        paths first (engine.exact.bent_paths). ``upto``: only among the first batches of
        ``began`` and of ``ended``, as many as given (the sweep's, not those ``record``ed
        since)."""
        cutoff = np.full(len(self.rest), np.inf)
        cutoff[rows] = after
        upto = upto or (len(self._began), len(self._ended))
        for events, count in zip((self._began, self._ended), upto, strict=True):
            for k, batch in enumerate(events[:count]):
                late = np.asarray(batch[5], dtype=float) > cutoff[np.asarray(batch[0])]
                if late.any():
                    events[k] = tuple(np.asarray(col)[~late] for col in batch)

    def quiet(self) -> None:
        """A step passed in which no body moved (all asleep): no events."""
        self._began, self._ended = [], []
        self.moved = False

    @property
    def began(self) -> list[tuple[int, int, Any, Any, Any, float]]:
        """Contacts that began in the last step: (row, collider index, point, normal, impulse,
        time) each, in the order they were found."""
        return _unpack(self._began)

    @property
    def ended(self) -> list[tuple[int, int, Any, Any, Any, float]]:
        """Contacts that ended in the last step, as ``began``."""
        return _unpack(self._ended)

    @property
    def began_arrays(self) -> list[tuple[Any, ...]]:
        """``began`` as held: (rows, collider indices, points, normals, impulses (N s),
        times (s)) arrays or tuples, a batch a tuple (engine.dynamics.events.raw_specs reads
        them)."""
        return self._began

    @property
    def ended_arrays(self) -> list[tuple[Any, ...]]:
        """``ended`` as held, as ``began_arrays``."""
        return self._ended

    def set_events(self, began: list[tuple[Any, ...]], ended: list[tuple[Any, ...]]) -> None:
        """Hold ``began`` and ``ended`` (batches as ``began_arrays``) as the last step's
        events: a step taken again in substeps reports all of theirs (engine.pipeline.stepping)."""
        self._began, self._ended = began, ended

    @property
    def sensor_indices(self) -> list[int]:
        """The places among ``colliders`` of the sensors, in order (the columns of
        ``inside``). Indices, no unit."""
        return self._sensors

    @property
    def grid(self) -> FaceGrid:
        """The broadphase over the solid faces (engine.geometry.face_grid), built when first
        needed."""
        if self._grid is None:
            self._grid = FaceGrid(self.faces)
        return self._grid

    def _near(
        self,
        x0: np.ndarray,
        v0: np.ndarray,
        B: np.ndarray,
        W: np.ndarray,
        dt: float,
        radius: np.ndarray,
        friction: np.ndarray,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray, float]:
        """(rows whose path this step may come within reach of a solid face or that move on
        one, rows that rest and stay put, the first rows' grid cells or None, their reach,
        a bound on every body's |B| and |W|): ``face_looks.near``, with the resting bodies."""
        need, cell, reach, a_bound = near(self.grid, x0, v0, B, W, dt, radius)
        resting, asleep = self._staying(x0, v0, W, friction)
        if len(resting):
            need[resting] = True
            need[asleep] = False
        rows = np.flatnonzero(need)
        cell_rows = None if cell is None else cell.take(rows)
        return rows, asleep, cell_rows, reach.take(rows), a_bound

    def _staying(
        self, x0: np.ndarray, v0: np.ndarray, W: np.ndarray, friction: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """(the rows resting on a face, those of them that stay put this step: ``_asleep``)."""
        none = np.zeros(0, dtype=np.intp)
        if not len(self.rest) or self.rest.max() < 0:
            return none, none
        resting = np.flatnonzero(self.rest >= 0)
        return resting, self._asleep(resting, x0, v0, W, friction)

    def _asleep(
        self,
        res: np.ndarray,
        x0: np.ndarray,
        v0: np.ndarray,
        W: np.ndarray,
        friction: np.ndarray,
    ) -> np.ndarray:
        """Resting rows that stay exactly where they are this step: still (v = 0), pressed
        onto their face (a_n <= 0) and held by static friction (|a_t| <= mu |a_n|)."""
        few = asleep_few if len(res) < self.few_resting else asleep
        return few(self.faces, self.rest, res, x0, v0, W, friction)

    def touch(
        self, rows: np.ndarray, x: np.ndarray, radius: np.ndarray, friction: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Of World ``rows``, those resting on a face at positions ``x`` (N, 2): (rows, unit
        normal toward each, friction (the body's times the collider's), gap: the signed
        distance less the radius, length units)."""
        on = rows[(self.rest[rows] >= 0) & (radius[rows] > 0.0)]
        f = self.rest[on]
        nrm, _ = face_normals(self.faces, f, x[on])
        gap = np.array(
            [
                float(signed_distance(self.colliders[int(o)], x[r : r + 1])[0]) - radius[r]
                for r, o in zip(on.tolist(), self.faces.owner[f].tolist(), strict=True)
            ]
        )
        return on, nrm, friction[on] * self.faces.mu[f], gap.reshape(-1)

    def push_out_rows(
        self,
        X: np.ndarray,
        V: np.ndarray,
        r: np.ndarray,
        rows: np.ndarray | None = None,
        fast: bool = False,
    ) -> np.ndarray:
        """Push rows of X out of any solid face they overlap (by more than TOUCH), in place;
        return which rows moved (engine.exact.push_out). ``rows``: the World rows of X's rows, whose
        filters say which faces they meet (needed only when a collider has a filter);
        ``fast``: the loop kernel (engine.kernels)."""
        faces = self.faces
        meets = None if rows is None else face_meets(faces, self.body_filters, rows)
        if rows is not None and len(self.ignored) and len(rows):
            n_f = len(faces.owner)
            every = self.allowed(np.repeat(rows, n_f), np.tile(np.arange(n_f), len(rows)))
            meets = every.reshape(len(rows), n_f)
        return push_out.push_out_rows(faces, self.colliders, X, V, r, meets, fast)

    # -- sensors ----------------------------------------------------------------------------
    def sense(
        self,
        x1: np.ndarray,
        dt: float,
        t0: float,
        radius: np.ndarray,
        shapes: ShapeTable | None = None,
        angle: np.ndarray | None = None,
    ) -> None:
        """Report bodies that began or ended overlapping each sensor this step (x1: where the
        bodies ended it; ``shapes`` and ``angle``: the bodies' shapes by row and their angles
        there, for those with a shape other than a disc; engine.geometry.sensors)."""
        sensors.sense(
            self.colliders, self._sensors, self.inside, self.body_filters, x1, dt, t0, radius,
            self._began, self._ended, shapes, angle,
        )  # fmt: skip


def _unpack(parts: list[tuple[Any, ...]]) -> list[tuple[int, int, Any, Any, Any, float]]:
    out: list[tuple[int, int, Any, Any, Any, float]] = []
    for rows, owner, point, normal, impulse, when in parts:
        for j in range(len(rows)):
            out.append(
                (int(rows[j]), int(owner[j]), point[j], normal[j], impulse[j], float(when[j]))
            )
    return out
