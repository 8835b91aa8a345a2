"""The state of a World's bodies: every per-body array, and the handles (Bodies) that view it.

A World keeps its bodies' state as numpy arrays: positions and velocities of shape (N,) in a
1D world and (N, 2) in a 2D world, the position before the last step (for drawing between
steps), each body's mass (N,) and own constant acceleration (shaped like x). A
:class:`engine.Body` added to a World becomes a handle into these arrays: it holds a slot
number that never changes (pymunk keeps a reference from body to space; Box2D hands out ids),
and the store maps slots to rows. Removing a body shifts the rows after it with one array
operation; no other body is touched.

>>> import numpy as np
>>> store = BodyStore(2)
>>> store.append(np.array([[0.0, 1.0], [2.0, 3.0]]), np.zeros((2, 2)), np.ones(2),
...              np.zeros((2, 2)))
[0, 1]
>>> store.remove(0)
>>> store.row(1), store.x.tolist()
(0, [[2.0, 3.0]])
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..body_values import FRICTION, RESTITUTION
from ..geometry.colliders import Circle
from ..vector import Vector

__all__ = ["BodyStore"]


class BodyStore:
    """Per-body arrays of one dimension (1 or 2) and the slot -> row map behind Body handles."""

    def __init__(
        self,
        dim: int,
        owner: Any = None,
        *,
        on_state: Callable[[int, bool], None] = lambda row, moved: None,
        on_own_acc: Callable[[int], None] = lambda row: None,
        on_mass: Callable[[], None] = lambda: None,
        on_moment: Callable[[], None] = lambda: None,
        on_kinematic: Callable[[int, Any], None] | None = None,
        on_kinematic_turn: Callable[[int, float | None], bool] | None = None,
        acceleration_at: Callable[[int], Any] | None = None,
        on_sleep: Callable[[int, bool], None] = lambda row, asleep: None,
        on_material: Callable[[int, bool], None] = lambda row, filtered: None,
    ) -> None:
        self.dim = dim
        #: The World these arrays belong to (what ``Body.world`` answers).
        self.owner = owner
        # What the owner must hear of: a position or velocity written by hand (a teleport), one
        # own acceleration written, a mass or a moment written; and how to read one body's
        # acceleration.
        self._on_state, self._on_own_acc, self._on_mass = on_state, on_own_acc, on_mass
        self._on_moment = on_moment  # a moment of inertia written
        # A kinematic body's move (row, target position or None for a velocity written): the
        # owner takes it without waking the World's sleepers (those it touches wake).
        self._on_kinematic = on_kinematic
        # A kinematic body turned (row, target angle or None for an angular velocity
        # written): True where the owner took it so (a pinned body is turned by hand).
        self._on_kinematic_turn = on_kinematic_turn
        self._acceleration_at = acceleration_at
        # A body put to sleep (row, True) or woken (row, False) by the game (the owner's sleep).
        self._on_sleep = on_sleep
        # A body's restitution, friction or filter set (row, whether its filter changed).
        self._on_material = on_material
        shape: tuple[int, ...] = (0,) if dim == 1 else (0, 2)
        self.x = np.zeros(shape)  # positions (length units)
        self.v = np.zeros(shape)  # velocities (length units / s)
        self.prev_x = np.zeros(shape)  # positions before the last step
        self.mass = np.zeros(0)  # (N,) masses (kg)
        self.own = np.zeros(shape)  # own constant accelerations (length units / s^2)
        # Size (fixed once a body is made) and material (``set_material``), for contacts.
        self.radius = np.zeros(0)  # (N,) radii (length units, 0 for a point)
        self.restitution = np.zeros(0)  # (N,) e in [0, 1]
        self.friction = np.zeros(0)  # (N,) Coulomb mu >= 0
        # Collision filters (engine.filters): group (0: none), category and mask bits.
        self.group = np.zeros(0, dtype=np.int64)
        self.categories = np.zeros(0, dtype=np.int64)
        self.mask = np.zeros(0, dtype=np.int64)
        # Bodies held by the game or a pin (Body.kinematic, engine.dynamics.links.Pin): no force
        # acts on them, and contacts and links take their mass as infinite.
        self.kinematic = np.zeros(0, dtype=bool)
        #: Bullets (Body.bullet): swept against the dynamic bodies too by the soft step's
        #: continuous stage (engine.dynamics.game_continuous). A new array when one is set.
        self.bullet = np.zeros(0, dtype=bool)
        #: Each body's shape (Body.shape: engine.geometry.colliders, in the body's frame), None for
        # a : disc or a point (engine.geometry.shaped turns them into narrowphase kinds).
        self.shapes: list[Any] = []
        # Rotation (engine.dynamics.rotation), used in 2D only: each body's angle (rad), angular
        # velocity (rad/s), moment of inertia (kg m^2; inf for a body that does not turn), its
        # inverse (0 for one that does not turn) and own constant torque (N m).
        self.angle = np.zeros(0)
        self.omega = np.zeros(0)
        self.moment = np.zeros(0)
        self.inv_moment = np.zeros(0)
        self.torque = np.zeros(0)
        #: Whether any body turns (1 / I > 0): a World with none does no rotation at all.
        self.turns_any = False
        self._spinning = False  # any angular velocity or torque (``spins``)
        #: Forces applied for the next step only (Body.apply_force): slot -> the own
        #: acceleration and torque to go back to after it.
        self.pushes: dict[int, tuple[Any, float]] = {}
        self._row_of = np.zeros(0, dtype=np.intp)  # slot -> row, -1 once removed
        # ``slots()`` as last made: (the _row_of it was made from, the count of rows then, it).
        self._slots: tuple[np.ndarray, int, np.ndarray] | None = None

    def __len__(self) -> int:
        return len(self.mass)

    def round(self, rows: np.ndarray) -> np.ndarray:
        """Which of ``rows`` are discs or points (no shape, or a Circle), as a bool array."""
        shapes = self.shapes
        return np.array(
            [shapes[i] is None or isinstance(shapes[i], Circle) for i in rows.tolist()],
            dtype=bool,
        ).reshape(len(rows))

    def append(
        self,
        x: np.ndarray,
        v: np.ndarray,
        mass: np.ndarray,
        own: np.ndarray,
        material: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
        filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
        kinematic: np.ndarray | None = None,
        shapes: list[Any] | None = None,
        rotation: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None,
        bullet: np.ndarray | None = None,
    ) -> list[int]:
        """Add rows for new bodies; return their slots (one array copy for the whole batch).

        ``material``: (radius, restitution, friction) arrays; points of Body's default
        restitution and friction (engine.body_values) when None. ``filters``: (group,
        categories, mask) integer arrays; engine.filters' default (no group, every bit) when None.
        ``kinematic``: (k,) bools, all False when None. ``shapes``: each body's shape (None:
        a disc or a point), all None when None. ``rotation``: (angle, angular velocity,
        moment, torque) arrays; at rest, not turning (moment inf) when None. ``bullet``: (k,)
        bools, all False when None.
        """
        n0, k = len(self), len(mass)
        if material is None:
            material = (np.zeros(k), np.full(k, RESTITUTION), np.full(k, FRICTION))
        self.radius = np.concatenate([self.radius, material[0]])
        self.restitution = np.concatenate([self.restitution, material[1]])
        self.friction = np.concatenate([self.friction, material[2]])
        if filters is None:
            every = np.full(k, 0xFFFFFFFF, dtype=np.int64)
            filters = (np.zeros(k, dtype=np.int64), every, every)
        self.group = np.concatenate([self.group, filters[0]])
        self.categories = np.concatenate([self.categories, filters[1]])
        self.mask = np.concatenate([self.mask, filters[2]])
        kin = np.zeros(k, dtype=bool) if kinematic is None else kinematic
        self.kinematic = np.concatenate([self.kinematic, kin])
        bul = np.zeros(k, dtype=bool) if bullet is None else bullet
        self.bullet = np.concatenate([self.bullet, bul])
        self.shapes.extend([None] * k if shapes is None else shapes)
        if rotation is None:
            rotation = (np.zeros(k), np.zeros(k), np.full(k, np.inf), np.zeros(k))
        self.angle = np.concatenate([self.angle, rotation[0]])
        self.omega = np.concatenate([self.omega, rotation[1]])
        self.moment = np.concatenate([self.moment, rotation[2]])
        self.torque = np.concatenate([self.torque, rotation[3]])
        self._moments_changed()
        self.x = np.concatenate([self.x, x])
        self.v = np.concatenate([self.v, v])
        self.prev_x = np.concatenate([self.prev_x, x])
        self.mass = np.concatenate([self.mass, mass])
        self.own = np.concatenate([self.own, own])
        first = len(self._row_of)
        self._row_of = np.concatenate([self._row_of, np.arange(n0, n0 + k, dtype=np.intp)])
        return list(range(first, first + k))

    def remove(self, slot: int) -> None:
        """Drop the row of ``slot``; the rows after it move up by one (one array operation)."""
        i = self.row(slot)
        keep = np.arange(len(self)) != i
        self.x, self.v, self.prev_x = self.x[keep], self.v[keep], self.prev_x[keep]
        self.mass, self.own = self.mass[keep], self.own[keep]
        self.radius, self.restitution = self.radius[keep], self.restitution[keep]
        self.friction = self.friction[keep]
        self.group, self.categories = self.group[keep], self.categories[keep]
        self.mask, self.kinematic = self.mask[keep], self.kinematic[keep]
        self.bullet = self.bullet[keep]
        del self.shapes[i]
        self.angle, self.omega = self.angle[keep], self.omega[keep]
        self.moment, self.torque = self.moment[keep], self.torque[keep]
        self._moments_changed()
        rows = self._row_of
        rows[slot] = -1
        self.pushes.pop(slot, None)
        rows[rows > i] -= 1

    def _moments_changed(self) -> None:
        """Recompute 1 / I (0 where I is inf: the body does not turn) and ``turns_any``."""
        with np.errstate(divide="ignore"):
            self.inv_moment = np.where(np.isfinite(self.moment), 1.0 / self.moment, 0.0)
        self.turns_any = bool((self.inv_moment > 0.0).any())
        self.spin_written()
        self._on_moment()

    def spins(self) -> bool:
        """Whether any body turns now or is made to (an angular velocity or a torque): kept
        as a flag (``spin_written``), so a step of bodies that do not spin costs no look."""
        return self._spinning

    def spin_written(self, spinning: bool | None = None) -> None:
        """Angular velocities or torques were written (by hand, or by a step): look again
        whether any body spins (``spinning``: whether any omega is not 0, where the step
        knows it)."""
        # (Only bodies that turn, and kinematic bodies, which the game turns, have an omega.)
        # (np.count_nonzero, a C call: ndarray.any() costs several times more on a game's
        # few bodies, and this runs every step. A nan counts as nonzero for both.)
        if spinning is None:
            spinning = bool(np.count_nonzero(self.omega))
        self._spinning = spinning or (self.turns_any and bool(np.count_nonzero(self.torque)))

    def set_spin(self, slot: int, angle: float | None, omega: float | None) -> None:
        """Set one body's angle (rad) and/or angular velocity (rad/s): a state written by
        hand, as a velocity is (a sleeping body wakes). A kinematic body's angle is turned to
        over the next step instead, as its position is moved (engine.pipeline.stepping)."""
        row = self.row(slot)
        turn = self._on_kinematic_turn
        steered = turn is not None and bool(self.kinematic[row])
        if steered and turn is not None and not turn(row, angle):
            steered = False  # a pinned body: turned by hand like any other
        if angle is not None and not steered:
            self.angle[row] = angle
        if omega is not None:
            self.omega[row] = omega
        self.spin_written()
        if not steered:
            self._on_state(row, False)  # a disc turned in place has not moved

    def push(self, slot: int, acc: tuple[float, float], torque: float) -> None:
        """Add ``acc`` (length units / s^2) to one body's own acceleration and ``torque``
        (N m) to its torque for the next step only (``release_pushes`` takes them back)."""
        row = self.row(slot)
        if slot not in self.pushes:
            self.pushes[slot] = (tuple(self.own[row].tolist()), float(self.torque[row]))
        own = self.own[row]
        self.set_own_acc(slot, (float(own[0]) + acc[0], float(own[1]) + acc[1]))
        if torque:
            self.set_torque(slot, float(self.torque[row]) + torque)

    def release_pushes(self) -> None:
        """A step has passed: the bodies pushed for it go back to their own acceleration and
        torque, exactly as they were."""
        pushes, self.pushes = self.pushes, {}
        for slot, (own, torque) in pushes.items():
            if self._row_of[slot] >= 0:  # (not removed meanwhile)
                self.set_own_acc(slot, own)
                self.set_torque(slot, torque)

    def set_torque(self, slot: int, value: float) -> None:
        """Set one body's own constant torque (N m)."""
        row = self.row(slot)
        self.torque[row] = value
        self.spin_written()
        self._on_state(row, False)

    def set_moments(self, moments: np.ndarray) -> None:
        """Set every body's moment of inertia at once (a snapshot restored)."""
        self.moment = moments
        self._moments_changed()

    def set_moment(self, slot: int, value: float) -> None:
        """Set one body's moment of inertia (kg m^2; inf: it does not turn)."""
        self.moment[self.row(slot)] = value
        self._moments_changed()

    @property
    def row_of(self) -> np.ndarray:
        """Each slot's row (-1 once removed), an index array."""
        return self._row_of

    def slots(self) -> np.ndarray:
        """Each row's slot (rows keep the order of their slots), an index array (kept while
        no body comes or goes: one added makes a new ``_row_of``, one removed a row fewer)."""
        kept = self._slots
        rows = self._row_of
        if kept is None or kept[0] is not rows or kept[1] != len(self.x):
            kept = self._slots = (rows, len(self.x), np.flatnonzero(rows >= 0))
        return kept[2]

    def row(self, slot: int) -> int:
        """The current row of the body in ``slot``."""
        return int(self._row_of[slot])

    def rows(self, slots: list[int]) -> np.ndarray:
        """The current rows of the bodies in ``slots``, as an index array."""
        return self._row_of[np.asarray(slots, dtype=np.intp)]

    def value(self, row: Any) -> Any:
        """One row of a state array as a float (1D) or a Vector (2D)."""
        return float(row) if self.dim == 1 else Vector(float(row[0]), float(row[1]))

    @staticmethod
    def _entry(value: Any) -> Any:
        return tuple(value) if isinstance(value, Vector) else value

    def set_position(self, slot: int, value: Any) -> None:
        """Move one body to ``value`` (a teleport: not blended with where it was); a
        kinematic body in a World moves there over the next step instead."""
        row = self.row(slot)
        if self._on_kinematic is not None and self.kinematic[row]:
            self._on_kinematic(row, self._entry(value))
            return
        self.x[row] = self.prev_x[row] = self._entry(value)
        self._on_state(row, True)

    def set_velocity(self, slot: int, value: Any) -> None:
        """Set one body's velocity to ``value``."""
        row = self.row(slot)
        self.v[row] = self._entry(value)
        if self._on_kinematic is not None and self.kinematic[row]:
            self._on_kinematic(row, None)
        else:
            self._on_state(row, False)

    def set_own_acc(self, slot: int, value: Any) -> None:
        """Set one body's own constant acceleration: one array entry, nothing recompiled."""
        row = self.row(slot)
        self.own[row] = self._entry(value)
        self._on_own_acc(row)

    def set_asleep(self, slot: int, asleep: bool) -> None:
        """Put one body to sleep now with its group (True), or wake it with its group (False):
        the owner's sleep does it (Body.sleep, Body.activate)."""
        self._on_sleep(self.row(slot), asleep)

    def set_material(self, slot: int, e: float, mu: float, filter: Any) -> None:  # noqa: A002
        """Set one body's restitution ``e``, friction ``mu`` and, unless None, its filter
        (engine.Filter), for the next step. A new filter makes new group, categories and mask
        arrays: what is kept from them (by identity) is made again."""
        row = self.row(slot)
        self.restitution[row] = e
        self.friction[row] = mu
        if filter is not None:
            self.group, self.categories, self.mask = (
                self.group.copy(),
                self.categories.copy(),
                self.mask.copy(),
            )
            self.group[row] = filter.group
            self.categories[row] = filter.categories
            self.mask[row] = filter.mask
        self._on_material(row, filter is not None)

    def set_bullet(self, slot: int, value: bool) -> None:
        """Make one body a bullet or not (Body.bullet), for the next step: a new array, so
        that what is kept from it (by identity) is made again."""
        self.bullet = self.bullet.copy()
        self.bullet[self.row(slot)] = value

    def set_mass(self, slot: int, value: float) -> None:
        """Set one body's mass (the forces' folded parts depend on it: the owner recompiles)."""
        self.mass[self.row(slot)] = value
        self._on_mass()

    def acceleration(self, slot: int) -> Any:
        """One body's total acceleration now (own + forces / mass): a float or a Vector."""
        row = self.row(slot)
        if self._acceleration_at is None:
            return self.value(self.own[row])
        return self.value(self._acceleration_at(row))

    def copy_arrays(self) -> tuple[np.ndarray, ...]:
        """Copies of (x, v, prev_x, mass, own): everything a snapshot of the bodies needs."""
        return self.x.copy(), self.v.copy(), self.prev_x.copy(), self.mass.copy(), self.own.copy()
