"""Many particles at once: a fixed-capacity structure of numpy arrays (sparks, smoke, fireworks).

A :class:`Particles` system holds up to ``capacity`` independent 2D point
particles of one mass. Each has a position (m), a velocity (m/s), an age and a
lifetime (s), a ``kind`` (a small integer the scene gives meaning to, e.g. a
firework's colour) and a serial ``id``. All the arrays are allocated once, when
the system is made: emitting and expiring particles only copy numbers into
them, so memory stays flat however long the run.

It is stepped by the same integrator functions and the same force objects as
the World (``engine.integrators``, ``engine.forces``): on arrays a force is
``force(t, x, v, mass)`` with x, v of shape (N, 2) and mass of shape (N, 1).

Layout, and the fast path
-------------------------
The living particles are always the first ``count`` slots (a particle that
dies is replaced by the last living one), so a step touches no dead slot and
needs no mask. Coordinates are stored as rows, ``x`` in one contiguous row and
``y`` in the other, shape (2, capacity): then a uniform acceleration is added
to each row as one plain number, with no (2,)-vector broadcast and no folded
per-particle array (measured: broadcasting a (2,) vector over (N, 2) costs ~5
times a contiguous add; refilling a folded array when the wind changes, as
much again).

Velocities are stored as the displacement per step, ``u = v dt`` (m). For the
common case (semi-implicit Euler under gravity, constant forces, drag and wind)
the acceleration is affine in the velocity and the same for every particle::

    a(t, v) = c(t) - d v        c = g + F0/m + (k_wind/m) air(t),  d = (k_drag + k_wind)/m

and semi-implicit Euler, v' = v + a dt then x' = x + v' dt, multiplied through
by dt becomes::

    u' = (1 - d dt) u + c(t) dt^2
    x' = x + u'

which numpy does in four in-place operations (one scale, two row adds, one
add) with no temporary: about the cost of a single add over the positions and
velocities together. Any other force or integrator goes through the general
path, which calls the integrator function exactly as the World does.

>>> from engine.forces import Gravity
>>> sparks = Particles(100, dt=0.5, forces=[Gravity((0, -10))])
>>> sparks.emit(3, position=(0, 0), velocity=(1, 0), lifetime=1.2)
3
>>> sparks.step(), sparks.step()
(0, 0)
>>> sparks.positions[0].tolist(), sparks.velocities[0].tolist()
([1.0, -7.5], [1.0, -10.0])
>>> sparks.step(), len(sparks)   # the third step reaches age 1.5 >= 1.2: all three expire
(3, 0)
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from numbers import Integral, Real
from typing import Any, NamedTuple

import numpy as np

from . import checks
from .dynamics.forcefield import ForceModel
from .dynamics.policy import instability
from .forces import Force, Wind, as_force
from .integrators import INTEGRATORS, Integrator, get_integrator, semi_implicit_euler
from .stability import StabilityWarning

__all__ = ["Particles", "Expired", "ParticlesSnapshot"]

#: The most particles one system may hold (~110 bytes each: 1e8 is ~11 GB).
_MAX_CAPACITY = 10**8
#: The largest ``kind`` (kinds are stored as int32).
_KIND_MAX = int(np.iinfo(np.int32).max)
#: Death step of a particle that never expires (lifetime = inf).
_NEVER = np.iinfo(np.int64).max


class Expired(NamedTuple):
    """The particles whose lifetime ran out in the last step, as they were when they expired."""

    positions: np.ndarray  # (k, 2) m
    velocities: np.ndarray  # (k, 2) m/s
    kinds: np.ndarray  # (k,) int
    ids: np.ndarray  # (k,) int


@dataclass(frozen=True)
class ParticlesSnapshot:
    """Every bit of a Particles system's state at one moment; hand it to ``Particles.restore``.

    The arrays are copies of the living slots (the first ``count``) and of the particles that
    expired in the last step (the first ``expired``): no other slot is ever read.
    """

    dt: float  # s: the step of the system it was taken from
    count: int
    expired: int
    steps: int
    next_death: int  # the first step at which a living particle expires
    emitted: int
    dropped: int
    pos: np.ndarray  # (2, count) m
    disp: np.ndarray  # (2, count) m per step: velocity * dt
    life: np.ndarray  # (count,) s
    birth: np.ndarray  # (count,) step
    death: np.ndarray  # (count,) step
    kind: np.ndarray  # (count,)
    ids: np.ndarray  # (count,)
    x_pos: np.ndarray  # (2, expired) m
    x_disp: np.ndarray  # (2, expired) m per step
    x_kind: np.ndarray  # (expired,)
    x_id: np.ndarray  # (expired,)


def _int_arg(value: Any, name: str, minimum: int) -> int:
    """``value`` as an int >= minimum; TypeError/ValueError naming ``name`` otherwise."""
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise TypeError(f"{name} must be an int >= {minimum}, got {type(value).__name__} {value!r}")
    if value < minimum:
        raise ValueError(f"{name} must be an int >= {minimum}, got {value!r}")
    return int(value)


def _pair(value: Any, name: str) -> tuple[float, float]:
    """A force's constant part (0.0 or a Vector) as (x, y); ValueError for a 1D number."""
    if isinstance(value, Real):
        if value != 0:
            raise ValueError(f"{name} is 1D ({value!r}) but particles are 2D: give it as a Vector")
        return 0.0, 0.0
    return float(value.x), float(value.y)


def _rows(value: Any, name: str, count: int) -> np.ndarray:
    """A 2-vector or a (count, 2) array of finite numbers, as float rows: shape (2, 1 or count)."""
    try:
        arr = np.asarray(value, dtype=float)
    except OverflowError:  # an int beyond the float range
        raise ValueError(f"{name} must be finite numbers, got {value!r}") from None
    except (TypeError, ValueError):
        raise TypeError(
            f"{name} must be a Vector, a pair of numbers or an array of shape ({count}, 2), "
            f"got {type(value).__name__} {value!r}"
        ) from None
    if arr.shape not in ((2,), (count, 2)):
        raise ValueError(
            f"{name} must be a 2-vector or an array of shape (count, 2) = ({count}, 2), "
            f"got shape {arr.shape}"
        )
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} must be finite, got {value!r}")
    return arr.reshape(2, 1) if arr.ndim == 1 else arr.T


class Particles:
    """Up to ``capacity`` 2D point particles of mass ``mass`` (kg), stepped ``dt`` (s) at a time.

    ``forces`` are force objects or callables ``f(t, x, v, mass)`` (see
    ``engine.forces``); ``integrator`` a name from ``engine.integrators.INTEGRATORS``
    or one of those functions. ``fast_path=False`` forces the general path (for
    tests that compare the two).
    """

    def __init__(
        self,
        capacity: int,
        dt: float = 1.0 / 120.0,
        forces: Iterable[Any] = (),
        integrator: str | Integrator = "semi_implicit_euler",
        mass: float = 1.0,
        *,
        fast_path: bool = True,
    ) -> None:
        self._capacity = _int_arg(capacity, "capacity", 1)
        self._dt = checks.seconds(dt, "dt")
        self._mass = checks.mass(mass, "mass")
        if callable(integrator) and integrator in INTEGRATORS.values():
            self._integrator: Integrator = integrator  # type: ignore[assignment]
        else:
            self._integrator = get_integrator(integrator)  # type: ignore[arg-type]
        self._fast_allowed = bool(fast_path)

        c = self._capacity
        # ~110 bytes a particle are allocated here, once: refuse a capacity no machine holds
        # with a message, not a MemoryError from deep inside numpy.
        if c > _MAX_CAPACITY:
            raise ValueError(f"capacity must be an int from 1 to {_MAX_CAPACITY:,}, got {c:,}")
        self._pos = np.zeros((2, c))  # rows x, y (m)
        self._disp = np.zeros((2, c))  # rows u_x, u_y: velocity * dt (m per step)
        self._life = np.zeros(c)  # lifetime (s)
        self._birth = np.zeros(c, dtype=np.int64)  # step at which each was emitted
        self._death = np.zeros(c, dtype=np.int64)  # first step at which age >= lifetime
        self._kind = np.zeros(c, dtype=np.int32)
        self._id = np.zeros(c, dtype=np.int64)
        self._mass_col = np.full((c, 1), self._mass)  # (N, 1) mass for the forces
        self._mask = np.zeros(c, dtype=bool)  # scratch for the expiry test
        # The particles that expired in the last step (filled by _remove, no allocation).
        self._x_pos = np.zeros((2, c))
        self._x_disp = np.zeros((2, c))
        self._x_kind = np.zeros(c, dtype=np.int32)
        self._x_id = np.zeros(c, dtype=np.int64)
        self._n_expired = 0

        self._n = 0
        self._steps = 0
        self._next_death = _NEVER
        self._emitted = 0
        self._dropped = 0
        self._forces: list[Force] = []
        self._fast = False
        try:
            given = list(forces)
        except TypeError:
            raise TypeError(
                f"forces must be an iterable of forces (e.g. [Gravity((0, -9.81))]), "
                f"got {type(forces).__name__} {forces!r}"
            ) from None
        for force in given:
            self._forces.append(self._checked(force))
        self._plan()

    # ------------------------------------------------------------------ set-up

    @staticmethod
    def _checked(force: Any) -> Force:
        f = as_force(force)
        if f.dim == 1:
            raise ValueError(
                f"force {f!r} is 1D but particles are 2D: give its vectors as Vectors or pairs"
            )
        return f

    def add_force(self, force: Any) -> Force:
        """Add a force (a Force or a callable f(t, x, v, mass) -> N) acting on every particle."""
        f = self._checked(force)
        self._forces.append(f)
        self._plan()
        return f

    def _plan(self) -> None:
        """Choose the fast or the general path for the current forces, and check stability."""
        m = self._mass
        # The same compiled force model and stability check as the World's: one body row
        # stands for every particle (they share one mass and every force acts on all).
        model = ForceModel.compile(
            np.array([m]), np.zeros((1, 2)), [(self._checked(f), None) for f in self._forces]
        )
        name = self._integrator.__name__
        message = instability(
            lambda n: self._integrator if n == name else get_integrator(n),
            name,
            model,
            self._dt,
            "these Particles",
        )
        if message is not None:
            warnings.warn(message, StabilityWarning, stacklevel=3)

        self._fast = False
        if not self._fast_allowed or self._integrator is not semi_implicit_euler:
            return
        winds: list[tuple[float, Callable[[float], Any]]] = []  # (k/m, air(t)) of gusty winds
        for f, _ in model.general:
            if not isinstance(f, Wind):
                return  # a force the fast path does not know: general path
            winds.append((f.k / m, f.air))  # F = k air(t) - k v, with air changing in time
        # c = g + F0/m (m/s^2) is the model's folded part; d = (k_drag + k_wind)/m (1/s) is
        # its damping rate, gusty winds included; their k air(t)/m is added at each step.
        self._fast = True
        self._alpha = 1.0 - float(model.rate[0]) * self._dt  # the velocity's decay per step
        self._c_const = (float(model.a0[0, 0]), float(model.a0[0, 1]))
        self._winds = winds

    # -------------------------------------------------------------- properties

    @property
    def capacity(self) -> int:
        """The most particles the system holds at once."""
        return self._capacity

    @property
    def count(self) -> int:
        """How many particles are alive now."""
        return self._n

    def __len__(self) -> int:
        return self._n

    @property
    def full(self) -> bool:
        """True when no more particles can be emitted until some expire."""
        return self._n == self._capacity

    @property
    def emitted(self) -> int:
        """How many particles were emitted in total."""
        return self._emitted

    @property
    def dropped(self) -> int:
        """How many particles ``emit`` was asked for but could not place, the system being full."""
        return self._dropped

    @property
    def dt(self) -> float:
        """The time step (s), fixed when the system is made."""
        return self._dt

    @property
    def mass(self) -> float:
        """The mass of each particle (kg)."""
        return self._mass

    @property
    def steps(self) -> int:
        """How many steps have been taken."""
        return self._steps

    @property
    def t(self) -> float:
        """The time (s): steps * dt, counted in whole steps so that it never drifts."""
        return self._steps * self._dt

    @property
    def forces(self) -> tuple[Force, ...]:
        """The forces acting on every particle."""
        return tuple(self._forces)

    @property
    def integrator(self) -> Integrator:
        """The integrator function used by the general path."""
        return self._integrator

    @property
    def uses_fast_path(self) -> bool:
        """True when steps take the in-place fast path (semi-implicit Euler, affine forces)."""
        return self._fast

    @staticmethod
    def _readonly(a: np.ndarray) -> np.ndarray:
        a.flags.writeable = False
        return a

    @property
    def positions(self) -> np.ndarray:
        """Positions (m) of the living particles, shape (count, 2): a read-only view."""
        return self._readonly(self._pos[:, : self._n].T)

    @property
    def velocities(self) -> np.ndarray:
        """Velocities (m/s) of the living particles, shape (count, 2): a new array."""
        return self._disp[:, : self._n].T / self._dt

    @property
    def ages(self) -> np.ndarray:
        """Ages (s) of the living particles, shape (count,): a new array."""
        return (self._steps - self._birth[: self._n]) * self._dt

    @property
    def lifetimes(self) -> np.ndarray:
        """Lifetimes (s) the living particles were emitted with, shape (count,): read-only view."""
        return self._readonly(self._life[: self._n])

    @property
    def kinds(self) -> np.ndarray:
        """Kinds of the living particles, shape (count,): a read-only view."""
        return self._readonly(self._kind[: self._n])

    @property
    def ids(self) -> np.ndarray:
        """Serial numbers of the living particles (0, 1, 2, ... in emission order), read-only."""
        return self._readonly(self._id[: self._n])

    def positions_at(self, alpha: float) -> np.ndarray:
        """Positions (m) blended back by (1 - alpha) of the last step, for drawing between steps.

        x - (1 - alpha) u: for semi-implicit Euler x - u is exactly the previous
        position; for other integrators it is the previous position to O(dt^2).
        """
        n = self._n
        return self._pos[:, :n].T - (1.0 - float(alpha)) * self._disp[:, :n].T

    @property
    def expired(self) -> Expired:
        """The particles whose lifetime ran out in the last step (copies), e.g. to burst them."""
        k = self._n_expired
        return Expired(
            self._x_pos[:, :k].T.copy(),
            self._x_disp[:, :k].T / self._dt,
            self._x_kind[:k].copy(),
            self._x_id[:k].copy(),
        )

    # ---------------------------------------------------------------- emitting

    def emit(
        self,
        count: int,
        position: Any,
        velocity: Any = (0.0, 0.0),
        lifetime: Any = math.inf,
        kind: Any = 0,
    ) -> int:
        """Emit ``count`` particles now; return how many fitted (the rest count in ``dropped``).

        ``position`` (m) and ``velocity`` (m/s) are each one 2-vector for all or
        an array of shape (count, 2); ``lifetime`` (s, > 0, ``inf`` for never)
        and ``kind`` (int >= 0) one number or an array of shape (count,). When
        the system is full the first particles of the batch are emitted and
        the others dropped: the return value and ``dropped`` say so.
        """
        count = _int_arg(count, "count", 0)
        pos = _rows(position, "position", count)
        vel = _rows(velocity, "velocity", count)
        life = np.asarray(lifetime, dtype=float) if _is_numeric(lifetime) else None
        if life is None or life.shape not in ((), (count,)):
            raise TypeError(
                f"lifetime must be a number > 0 (s) or an array of shape ({count},), "
                f"got {type(lifetime).__name__} {lifetime!r}"
            )
        if np.isnan(life).any() or (life <= 0).any():
            bad = life if life.ndim == 0 else life[np.isnan(life) | (life <= 0)][0]
            raise ValueError(f"lifetime must be > 0 s (inf for never), got {bad!r}")
        kinds = np.asarray(kind) if _is_numeric(kind) else None
        if kinds is None or kinds.shape not in ((), (count,)) or kinds.dtype.kind not in "iu":
            raise TypeError(
                f"kind must be an int >= 0 or an int array of shape ({count},), "
                f"got {type(kind).__name__} {kind!r}"
            )
        if (kinds < 0).any() or (kinds > _KIND_MAX).any():
            raise ValueError(f"kind must be >= 0 and at most {_KIND_MAX} (int32), got {kind!r}")

        n = self._n
        k = min(count, self._capacity - n)
        self._dropped += count - k
        if k == 0:
            return 0
        new = slice(n, n + k)
        self._pos[:, new] = pos[:, :k]
        np.multiply(vel[:, :k], self._dt, out=self._disp[:, new])
        self._life[new] = life if life.ndim == 0 else life[:k]
        self._kind[new] = kinds if kinds.ndim == 0 else kinds[:k]
        self._id[new] = np.arange(self._emitted, self._emitted + k)
        self._birth[new] = self._steps
        # A particle lives ceil(lifetime / dt) whole steps: it expires at the first step
        # at which its age (steps since birth) * dt >= lifetime. The 1e-9 forgives the
        # round-off in lifetime / dt when the lifetime is a whole number of steps.
        life_k = self._life[new]
        with np.errstate(invalid="ignore", over="ignore"):
            n_steps = np.maximum(np.ceil(life_k / self._dt - 1e-9), 1.0)
        death = self._death[new]
        death[:] = _NEVER  # lifetime inf (or longer than any run): never expires
        finite = n_steps < 2.0**62
        death[finite] = self._steps + n_steps[finite].astype(np.int64)
        self._next_death = min(self._next_death, int(self._death[new].min()))
        self._n = n + k
        self._emitted += k
        return k

    # ------------------------------------------------------------------ dying

    def _remove(self, dead: np.ndarray, record: bool) -> int:
        """Remove the particles flagged in the bool array ``dead`` (length count); return how many.

        Each hole below the new count is filled by a living particle from above it,
        so the living stay packed in the first slots and nothing is allocated but
        the index lists (as long as the number removed).
        """
        n = self._n
        idx = np.flatnonzero(dead)
        k = len(idx)
        if record:
            np.take(self._pos[:, :n], idx, axis=1, out=self._x_pos[:, :k])
            np.take(self._disp[:, :n], idx, axis=1, out=self._x_disp[:, :k])
            np.take(self._kind[:n], idx, out=self._x_kind[:k])
            np.take(self._id[:n], idx, out=self._x_id[:k])
            self._n_expired = k
        if k == 0:
            return 0
        m = n - k
        holes = idx[idx < m]
        fillers = np.flatnonzero(~dead[m:]) + m  # as many living above m as dead below it
        for a in (self._pos, self._disp):
            a[:, holes] = a[:, fillers]
        for b in (self._life, self._birth, self._death, self._kind, self._id):
            b[holes] = b[fillers]
        self._n = m
        self._next_death = int(self._death[:m].min()) if m else _NEVER
        return k

    def kill(self, which: Any) -> int:
        """Remove living particles now (not recorded as expired); return how many.

        ``which`` is a bool array of shape (count,) (e.g. ``positions[:, 1] < 0``)
        or an array of indices into the living particles.
        """
        n = self._n
        w = np.asarray(which)
        if w.dtype == bool:
            if w.shape != (n,):
                raise ValueError(f"which: a bool mask must have shape ({n},), got {w.shape}")
            dead = w
        elif w.dtype.kind in "iu" and w.ndim <= 1:
            if w.size and (w.min() < -n or w.max() >= n):
                raise ValueError(f"which: indices must be in [0, {n}), got {which!r}")
            dead = np.zeros(n, dtype=bool)
            dead[w] = True
        else:
            raise TypeError(
                f"which must be a bool mask of shape ({n},) or an int index array, got {which!r}"
            )
        return self._remove(dead, record=False)

    def clear(self) -> None:
        """Remove every particle (counters and time are kept)."""
        self._n = 0
        self._n_expired = 0
        self._next_death = _NEVER

    # ---------------------------------------------------------------- stepping

    def step(self, dt: float | None = None) -> int:
        """Advance every particle by the system's dt (s); return how many expired (see ``expired``).

        ``dt`` may be passed, as a scene's loop does, but must be that fixed step: the arrays
        hold velocity * dt, so the step is chosen once, when the system is made.
        """
        if dt is not None and dt != self._dt:
            raise ValueError(
                f"dt must be this system's step, {self._dt!r} s (fixed when it was made), "
                f"got {dt!r}"
            )
        n = self._n
        if n:
            if self._fast:
                self._step_fast(n)
            else:
                self._step_general(n)
        self._steps += 1
        self._n_expired = 0
        if self._steps >= self._next_death:
            mask = self._mask[:n]
            np.less_equal(self._death[:n], self._steps, out=mask)
            return self._remove(mask, record=True)
        return 0

    def run(self, steps: int) -> int:
        """Take ``steps`` steps; return how many particles expired in all."""
        return sum(self.step() for _ in range(_int_arg(steps, "steps", 0)))

    # ------------------------------------------------------- snapshot, restore

    def snapshot(self) -> ParticlesSnapshot:
        """Everything needed to bring this system back to this moment, bit for bit."""
        n, k = self._n, self._n_expired
        return ParticlesSnapshot(
            dt=self._dt,
            count=n,
            expired=k,
            steps=self._steps,
            next_death=self._next_death,
            emitted=self._emitted,
            dropped=self._dropped,
            pos=self._pos[:, :n].copy(),
            disp=self._disp[:, :n].copy(),
            life=self._life[:n].copy(),
            birth=self._birth[:n].copy(),
            death=self._death[:n].copy(),
            kind=self._kind[:n].copy(),
            ids=self._id[:n].copy(),
            x_pos=self._x_pos[:, :k].copy(),
            x_disp=self._x_disp[:, :k].copy(),
            x_kind=self._x_kind[:k].copy(),
            x_id=self._x_id[:k].copy(),
        )

    def restore(self, snapshot: ParticlesSnapshot) -> None:
        """Bring back the state saved by ``snapshot()``, into this system or one made alike.

        TypeError for anything but a ParticlesSnapshot; ValueError if it was taken with another
        dt or holds more particles than ``capacity``. Nothing changes when it is refused.
        """
        if not isinstance(snapshot, ParticlesSnapshot):
            raise TypeError(
                f"restore takes a ParticlesSnapshot from Particles.snapshot(), got "
                f"{type(snapshot).__name__}"
            )
        if snapshot.dt != self._dt:
            raise ValueError(
                f"snapshot.dt is {snapshot.dt!r} s but this system steps {self._dt!r} s: "
                f"restore into a system made with the same dt"
            )
        n, k = snapshot.count, snapshot.expired
        if not (0 <= n <= self._capacity and 0 <= k <= self._capacity):
            raise ValueError(
                f"the snapshot holds {n} particles ({k} expired) but this system's capacity "
                f"is {self._capacity}: restore into a system at least as large"
            )
        shapes: dict[str, tuple[int, ...]] = {"pos": (2, n), "disp": (2, n), "x_pos": (2, k)}
        shapes["x_disp"] = (2, k)
        shapes.update({name: (n,) for name in ("life", "birth", "death", "kind", "ids")})
        shapes.update({name: (k,) for name in ("x_kind", "x_id")})
        for name, shape in shapes.items():
            value = getattr(snapshot, name)
            if not isinstance(value, np.ndarray) or value.shape != shape:
                got = value.shape if isinstance(value, np.ndarray) else type(value).__name__
                raise ValueError(
                    f"snapshot.{name} must be an array of shape {shape} from "
                    f"Particles.snapshot(), got {got}"
                )
        if not (np.isfinite(snapshot.pos).all() and np.isfinite(snapshot.disp).all()):
            raise ValueError("snapshot.pos and snapshot.disp must be finite (no nan or inf)")
        self._pos[:, :n] = snapshot.pos
        self._disp[:, :n] = snapshot.disp
        self._life[:n] = snapshot.life
        self._birth[:n] = snapshot.birth
        self._death[:n] = snapshot.death
        self._kind[:n] = snapshot.kind
        self._id[:n] = snapshot.ids
        self._x_pos[:, :k] = snapshot.x_pos
        self._x_disp[:, :k] = snapshot.x_disp
        self._x_kind[:k] = snapshot.x_kind
        self._x_id[:k] = snapshot.x_id
        self._n, self._n_expired = n, k
        self._steps, self._next_death = snapshot.steps, snapshot.next_death
        self._emitted, self._dropped = snapshot.emitted, snapshot.dropped

    def _step_fast(self, n: int) -> None:
        # u' = alpha u + c(t) dt^2 ;  x' = x + u'   (module docstring derives it)
        dt = self._dt
        cx, cy = self._c_const
        if self._winds:
            t = self.t
            for k_over_m, air in self._winds:
                a = air(t)
                cx += k_over_m * a.x
                cy += k_over_m * a.y
        u = self._disp[:, :n]
        if self._alpha != 1.0:
            np.multiply(u, self._alpha, out=u)
        if cx != 0.0:
            np.add(u[0], cx * dt * dt, out=u[0])
        if cy != 0.0:
            np.add(u[1], cy * dt * dt, out=u[1])
        x = self._pos[:, :n]
        np.add(x, u, out=x)

    def _step_general(self, n: int) -> None:
        dt = self._dt
        mass = self._mass_col[:n]
        forces = self._forces

        inverse_mass = 1.0 / self._mass  # every particle has the same mass: a plain number

        def accel(t: float, x: Any, v: Any) -> Any:
            if not forces:
                return 0.0 * v
            total = forces[0](t, x, v, mass)
            for f in forces[1:]:
                total = total + f(t, x, v, mass)
            return total * inverse_mass

        x, v = self._integrator(self._pos[:, :n].T, self._disp[:, :n].T / dt, accel, self.t, dt)
        self._pos[:, :n] = np.asarray(x).T
        np.multiply(np.asarray(v).T, dt, out=self._disp[:, :n])


def _is_numeric(value: Any) -> bool:
    """True for a real number or an array-like of real numbers (not bool, not str)."""
    if isinstance(value, (str, bytes)) or value is None:
        return False
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):
        return False
    return arr.dtype.kind in "iuf"
