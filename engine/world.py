"""The World: bodies, the forces on them, and the one place where time advances.

All bodies' state lives in numpy arrays (positions and velocities of shape
(N,) in a 1D world, (N, 2) in a 2D world) and one integrator call steps them
all. A Body added to the world becomes a live view into those arrays.

Constant forces and linear drag are folded, once, into two per-body arrays,
so that the acceleration of every body is

    a = a0 - c v  (+ the forces that are neither, evaluated each call)

with a0 = own acceleration + gravity + constant forces / m + k air / m and
c = (sum of drag coefficients k) / m. DESIGN.md has the measurements that make
this matter: adding two arrays of the same shape costs a fraction of
broadcasting a small vector over them every step.

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
from dataclasses import dataclass, field
from numbers import Real
from typing import Any

import numpy as np

from .accuracy import HORIZON
from .accuracy import predicted_error as _predicted_error
from .body import Body, State, coerce_mass, coerce_state
from .forces import Force, as_force
from .integrators import INTEGRATORS, Integrator, get_integrator
from .stability import (
    DECAY_LIMITS,
    OSCILLATION_LIMITS,
    SimulationDiverged,
    StabilityWarning,
    is_stable,
    max_stable_dt,
)
from .vector import Vector

__all__ = ["World", "WorldSnapshot", "METHODS"]

#: Every name ``World(integrator=...)`` accepts.
METHODS: tuple[str, ...] = (*INTEGRATORS, "exact", "auto")

# "auto" tries these in order and takes the first that is stable at the step's dt (and,
# with a tolerance, predicted to meet it): semi-implicit Euler costs one force evaluation a
# step, Verlet two, RK4 four. Explicit Euler is never the best: it costs what semi-implicit
# Euler costs, is as accurate on drag and gravity, and is unstable on every spring.
_AUTO_ORDER = ("semi_implicit_euler", "velocity_verlet", "rk4")


def _check_tolerance(tolerance: Any, requested: str) -> float | None:
    """``tolerance`` as a positive finite float (m) or None; errors name it and its range."""
    if tolerance is None:
        return None
    if isinstance(tolerance, bool) or not isinstance(tolerance, Real):
        raise TypeError(
            f"tolerance must be a length in m (e.g. 1e-3) or None, got "
            f"{type(tolerance).__name__} {tolerance!r}"
        )
    try:
        tol = float(tolerance)
    except OverflowError:  # an int beyond the float range
        tol = math.inf
    if not (math.isfinite(tol) and tol > 0.0):
        raise ValueError(f"tolerance must be a finite length > 0 m (e.g. 1e-3), got {tolerance!r}")
    if requested != "auto":
        raise ValueError(
            f"tolerance={tolerance!r} only applies to integrator='auto' (which picks a method to "
            f"meet it); integrator={requested!r} was given"
        )
    return tol


def _array(value: Any) -> Any:
    """A float stays a float; a Vector becomes a (2,) array."""
    return np.array(tuple(value), dtype=float) if isinstance(value, Vector) else float(value)


# np.add.reduce(a, None) sums every entry without the Python wrapper of ndarray.sum.
_sum = np.add.reduce


def _copy(array: Any) -> Any:
    return None if array is None else array.copy()


def check_dt(dt: Any) -> float:
    """``dt`` as a positive finite float (s), else TypeError / ValueError naming it."""
    if isinstance(dt, bool) or not isinstance(dt, Real):
        raise TypeError(f"dt must be a number of seconds, got {type(dt).__name__} {dt!r}")
    try:
        f = float(dt)
    except OverflowError:  # an int beyond the float range
        f = math.inf
    if not (math.isfinite(f) and f > 0.0):
        raise ValueError(f"dt must be a finite number of seconds > 0 (e.g. 1/60), got {dt!r}")
    return f


@dataclass(frozen=True)
class WorldSnapshot:
    """Every bit of a World's state at one moment; hand it to ``World.restore``."""

    n_bodies: int
    x: Any
    v: Any
    prev_x: Any
    masses: tuple[float, ...]
    own_acc: tuple[State, ...]
    t_base: float
    dt: float | None
    n_since_base: int
    steps: int
    anchor: tuple[Any, Any, float] | None
    warned: frozenset[Any] = field(default_factory=frozenset)


@dataclass
class _Attached:
    force: Force
    bodies: list[Body] | None  # None: every body in the world


@dataclass
class _Compiled:
    """What the World derives from its bodies and forces, rebuilt when they change."""

    a0: Any  # per-body constant acceleration, shaped like x
    c: Any  # per-body linear damping rate (1/s), shaped like v, or None
    general: list[tuple[Force, Any]]  # forces called every evaluation, with index or None
    mass: Any  # per-body mass, shaped like x
    all_constant: bool
    omega: np.ndarray  # per-body sqrt(sum stiffness / m) (rad/s)
    rate: np.ndarray  # per-body sum damping / m (1/s)


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
        if isinstance(integrator, str):
            if integrator not in METHODS:
                raise ValueError(
                    f"unknown integrator {integrator!r}; valid names: {', '.join(METHODS)}"
                )
            self._custom: Integrator | None = None
        elif callable(integrator):
            self._custom = integrator
        else:
            raise TypeError(
                f"integrator must be a name ({', '.join(METHODS)}) or a function "
                f"step(x, v, accel, t, dt) -> (x, v), got {type(integrator).__name__}"
            )
        self._requested = integrator if isinstance(integrator, str) else integrator.__name__
        self._tolerance = _check_tolerance(tolerance, self._requested)
        self._bodies: list[Body] = []
        self._forces: list[_Attached] = []
        self._dim: int | None = None
        self._x: Any = None
        self._v: Any = None
        self._prev_x: Any = None
        # Time: t = t_base + n_since_base * dt, with n an integer, so a run of equal
        # steps never accumulates the round-off of adding dt again and again.
        self._t_base = 0.0
        self._dt: float | None = None
        self._n = 0
        self._steps = 0
        self._compiled: _Compiled | None = None
        self._anchor: tuple[Any, Any, float] | None = None  # (x0, v0, t0) for "exact"
        self._choice: tuple[Any, str, str] | None = None  # (key, method, reason)
        self._warned: set[Any] = set()
        self._version = 0  # bumped whenever bodies, forces, masses or own accelerations change
        self._fast: tuple[Any, ...] | None = None  # (dt, version, method, step, compiled)
        self._huge = False  # the state is near overflow: step with numpy's warnings off

    # -- bodies and forces ----------------------------------------------------------------
    @property
    def bodies(self) -> tuple[Body, ...]:
        """The bodies in the world, in the order they were added."""
        return tuple(self._bodies)

    @property
    def forces(self) -> tuple[Force, ...]:
        """The forces in the world, in the order they were added."""
        return tuple(a.force for a in self._forces)

    @property
    def dim(self) -> int | None:
        """1 (floats), 2 (Vectors), or None while the world has neither bodies nor shaped forces."""
        return self._dim

    def _check_dim(self, dim: int, what: str, world_dim: int | None = None) -> None:
        """TypeError unless ``what``, of dimension ``dim``, fits this World (or ``world_dim``)."""
        expected = self._dim if world_dim is None else world_dim
        if expected is not None and dim != expected:
            raise TypeError(
                f"{what} is {dim}D but this World is {expected}D: a World holds bodies "
                f"of one dimension (1D: floats, 2D: Vectors)"
            )

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
        dim = self._dim if self._dim is not None else batch[0].dim
        for b in batch:
            self._check_dim(b.dim, "the body", dim)
        self._dim = dim
        rows = np.array([b.pos for b in batch], dtype=float)
        vrows = np.array([b.vel for b in batch], dtype=float)
        if self._x is None:
            self._x, self._v, self._prev_x = rows, vrows, rows.copy()
        else:
            self._x = np.concatenate([self._x, rows])
            self._v = np.concatenate([self._v, vrows])
            self._prev_x = np.concatenate([self._prev_x, rows])
        for b in batch:
            b._world, b._index = self, len(self._bodies)
            self._bodies.append(b)
        self._changed_structure()
        return batch

    def remove(self, body: Body) -> None:
        """Take ``body`` out of the world; it keeps its last position and velocity."""
        if not isinstance(body, Body) or body.world is not self:
            raise ValueError(f"that body is not in this World: {body!r}")
        i = body._index
        pos, vel = body.pos, body.vel
        keep = np.arange(len(self._bodies)) != i
        self._x, self._v, self._prev_x = self._x[keep], self._v[keep], self._prev_x[keep]
        del self._bodies[i]
        for j, other in enumerate(self._bodies):
            other._index = j
        for attached in self._forces:
            if attached.bodies is not None and body in attached.bodies:
                attached.bodies.remove(body)
        body._world, body._index = None, -1
        body._store_pos(pos)
        body._store_vel(vel)
        self._changed_structure()

    def add_force(
        self, force: Force | Callable[..., Any], bodies: Iterable[Body] | None = None
    ) -> Force:
        """Add a force (a Force, or a callable ``f(t, x, v, mass) -> force``); return it.

        ``bodies``: the bodies it acts on (all of them, now and later, when None).
        """
        f = as_force(force)
        if f.dim is not None:
            self._check_dim(f.dim, repr(f))
        if self._requested == "exact" and not f.constant:
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
            self._dim = f.dim  # checked above; an empty World takes the force's dimension
        self._forces.append(_Attached(f, members))
        self._changed_structure()
        return f

    # -- derived state ----------------------------------------------------------------------
    def _changed_structure(self) -> None:
        """Bodies, forces, masses or own accelerations changed: rebuild derived state."""
        self._compiled = None
        self._anchor = None
        self._choice = None
        self._version += 1

    def _compile(self) -> _Compiled:
        n = len(self._bodies)
        dim = self._dim or 1
        shape = (n,) if dim == 1 else (n, 2)
        masses = np.array([b.mass for b in self._bodies], dtype=float)
        # Per-body arrays take the full shape of x, (N, 2) in 2D, not (N, 1): numpy
        # multiplies two arrays of one shape several times faster than it broadcasts.
        mass = masses if dim == 1 else np.repeat(masses[:, None], 2, axis=1)
        a0 = np.array([b.own_acc for b in self._bodies], dtype=float).reshape(shape)
        damping = np.zeros(n)
        stiffness = np.zeros(n)
        general: list[tuple[Force, Any]] = []
        all_constant = True
        for attached in self._forces:
            f = attached.force
            idx: Any = None
            if attached.bodies is not None:
                idx = np.array([b._index for b in attached.bodies], dtype=np.intp)
            sel = slice(None) if idx is None else idx
            stiffness[sel] += f.stiffness
            all_constant = all_constant and f.constant
            parts = f.affine()
            if parts is None:
                general.append((f, idx))
                continue
            accel, force, k = parts
            # m a = m a0 + f0 - k v  =>  a = a0 + f0 / m - (k / m) v
            a0[sel] += _array(accel) + _array(force) / mass[sel]
            damping[sel] += k
        rate = damping / masses if n else damping
        c = None
        if np.any(rate):
            c = rate if dim == 1 else np.repeat(rate[:, None], 2, axis=1)
        omega = np.sqrt(stiffness / masses) if n else stiffness
        return _Compiled(a0, c, general, mass, all_constant, omega, rate)

    def _ready(self) -> _Compiled:
        if self._compiled is None:
            self._compiled = self._compile()
        return self._compiled

    def _accel(self, t: float, x: Any, v: Any) -> Any:
        """Acceleration of every body at time t (s) in state (x, v): a0 - c v + general / m."""
        comp = self._compiled
        assert comp is not None
        a = comp.a0 if comp.c is None else comp.a0 - comp.c * v
        if comp.general:
            a = a.copy() if comp.c is None else a
            for force, idx in comp.general:
                if idx is None:
                    a += force(t, x, v, comp.mass) / comp.mass
                elif len(idx):
                    m = comp.mass[idx]
                    a[idx] += force(t, x[idx], v[idx], m) / m
        return a

    # -- choosing the method ------------------------------------------------------------------
    def _stability_pairs(self, comp: _Compiled) -> list[tuple[float, float]]:
        """The distinct (omega, damping rate) pairs to check, or an envelope when many."""
        pairs = {(float(w), float(c)) for w, c in zip(comp.omega, comp.rate, strict=True) if w or c}
        if len(pairs) > 32:
            w_max, c_max = float(comp.omega.max()), float(comp.rate.max())
            pairs = {(w_max, 0.0), (0.0, c_max), (w_max, c_max)}
        return sorted(pairs)

    def _integrator_named(self, name: str) -> Integrator:
        return self._custom if self._custom is not None else get_integrator(name)

    def _first_unstable(self, name: str, comp: _Compiled, dt: float) -> tuple[float, float] | None:
        step = self._integrator_named(name)
        for w, c in self._stability_pairs(comp):
            if not is_stable(step, w, c, dt):
                return w, c
        return None

    def max_stable_dt(self, integrator: str | None = None) -> float:
        """The largest stable dt (s) for the springs and drags held, for ``integrator``.

        ``integrator`` defaults to the method in use (for "auto": the best available).
        ``math.inf`` when nothing held limits the step; 0.0 when no dt is stable.
        """
        comp = self._ready()
        name = integrator or self.method
        if name == "exact" or (name == "auto" and comp.all_constant):
            return math.inf
        if name == "auto":
            return max(self.max_stable_dt(n) for n in _AUTO_ORDER)
        step = self._integrator_named(name)
        pairs = self._stability_pairs(comp)
        return min((max_stable_dt(step, w, c) for w, c in pairs), default=math.inf)

    @property
    def tolerance(self) -> float | None:
        """The position error (m) "auto" must keep within over 1 s, or None (stability only)."""
        return self._tolerance

    def predicted_error(self, method: str, dt: float) -> float:
        """Predicted largest position error (m) of any body over the next 1 s of steps of ``dt``.

        Exact for the forces the World folds or knows the stiffness of (constant forces,
        gravity, drag, wind, springs of rest length 0); other forces are frozen at their value
        now. ``math.inf`` when ``method`` blows up within that second. See ``engine.accuracy``.
        """
        dt = check_dt(dt)
        comp = self._ready()
        if method == "exact":
            return 0.0 if comp.all_constant else math.inf
        step = self._integrator_named(method)
        if not self._bodies:
            return 0.0
        acc = self._accel(self.t, self._x, self._v)
        return _predicted_error(step, self._x, self._v, acc, comp.omega, comp.rate, dt)

    def _fixed_choice(self) -> tuple[str, str] | None:
        """(method, reason) when the choice does not depend on dt, else None."""
        if self._requested != "auto":
            return self._requested, f"integrator={self._requested!r} was asked for"
        if self._ready().all_constant:
            return "exact", "every force is constant, so the closed form is exact at any dt"
        return None

    def choose_method(self, dt: float) -> tuple[str, str]:
        """(method, one-line reason) that this World uses for a step of ``dt`` seconds."""
        dt = check_dt(dt)
        fixed = self._fixed_choice()
        if fixed is not None:
            return fixed
        comp = self._ready()

        def cheapest(name: str) -> str:
            evals = INTEGRATORS[name].evaluations
            plural = "s" if evals > 1 else ""
            return f"{name} is the cheapest method ({evals} force evaluation{plural} a step)"

        stable = [name for name in _AUTO_ORDER if self._first_unstable(name, comp, dt) is None]
        if not stable:
            return "rk4", f"no method is stable at dt={dt:g} s; rk4 has the widest limit"
        tol = self._tolerance
        if tol is None:
            return stable[0], f"{cheapest(stable[0])} that is stable at dt={dt:g} s"
        # _AUTO_ORDER is cheapest first: the first stable method predicted to meet the
        # tolerance is the cheapest that does.
        errors: dict[str, float] = {}
        for name in stable:
            errors[name] = err = self.predicted_error(name, dt)
            if err <= tol:
                return name, (
                    f"{cheapest(name)} stable at dt={dt:g} s and predicted within "
                    f"tolerance={tol:g} m over {HORIZON:g} s (error {err:.2g} m)"
                )
        best = min(errors, key=lambda n: errors[n])
        err = errors[best]
        # Global error ~ C dt^p (p the order), so dt (tol / err)^(1/p) would about meet it.
        hint = ""
        if 0.0 < err < math.inf:
            need = dt * (tol / err) ** (1.0 / INTEGRATORS[best].order)
            hint = f"; a dt near {need:.2g} s would meet it"
        return best, (
            f"no stable method meets tolerance={tol:g} m at dt={dt:g} s; {best} is the most "
            f"accurate (predicted error {err:.2g} m over {HORIZON:g} s){hint}"
        )

    @property
    def method(self) -> str:
        """The method in use; for "auto", the one chosen at the last step (or "auto" before)."""
        if self._choice is not None:
            return self._choice[1]
        fixed = self._fixed_choice()
        return "auto" if fixed is None else fixed[0]

    @property
    def method_reason(self) -> str:
        """One line saying why ``method`` is the method in use."""
        if self._choice is not None:
            return self._choice[2]
        fixed = self._fixed_choice()
        return (
            "chosen at the first step, from its dt and the forces held"
            if fixed is None
            else (fixed[1])
        )

    def _method_for(self, dt: float, comp: _Compiled) -> str:
        key = (dt, self._version)
        if self._choice is None or self._choice[0] != key:
            name, reason = self.choose_method(dt)
            self._choice = (key, name, reason)
            if name != "exact":
                self._warn_if_unstable(name, dt, comp)
        return self._choice[1]

    def _limit_text(self, name: str, w: float, c: float, dt: float) -> str:
        limit = max_stable_dt(self._integrator_named(name), w, c)
        parts = []
        if w:
            osc = OSCILLATION_LIMITS.get(name)
            parts.append(f"omega={w:.4g} rad/s, omega*dt={w * dt:.4g}")
            if osc is not None:
                parts.append("never stable on a spring" if osc == 0 else f"limit {osc:.4g}")
        if c:
            dec = DECAY_LIMITS.get(name)
            parts.append(f"damping rate={c:.4g} 1/s, rate*dt={c * dt:.4g}")
            if dec is not None:
                parts.append(f"decay limit {dec:.4g}")
        stable = "no dt is stable" if limit == 0.0 else f"stable for dt < {limit:.4g} s"
        return f"{'; '.join(parts)}; {stable}"

    def _warn_if_unstable(self, name: str, dt: float, comp: _Compiled) -> None:
        bad = self._first_unstable(name, comp, dt)
        key = (name, dt, self._version)
        if bad is None or key in self._warned:
            return
        self._warned.add(key)
        stable = [
            other
            for other in INTEGRATORS
            if other != name and self._first_unstable(other, comp, dt) is None
        ]
        hopeless = max_stable_dt(self._integrator_named(name), *bad) == 0.0
        advice = "a smaller dt will not help" if hopeless else "use a smaller dt"
        if stable:
            joint = "; use" if hopeless else ", or"
            advice += f"{joint} integrator={stable[0]!r}, which is stable at this dt"
        else:
            advice += "; no integrator here is stable at this dt"
        warnings.warn(
            f"{name} is unstable at dt={dt:g} s for the forces in this World "
            f"({self._limit_text(name, bad[0], bad[1], dt)}); the run continues and will "
            f"blow up: {advice}",
            StabilityWarning,
            stacklevel=4,
        )

    # -- time --------------------------------------------------------------------------------
    @property
    def t(self) -> float:
        """Simulated time (s) since the world began."""
        return self._t_base + self._n * self._dt if self._dt is not None else self._t_base

    @property
    def steps(self) -> int:
        """How many steps have been taken."""
        return self._steps

    def step(self, dt: float) -> None:
        """Advance every body by ``dt`` seconds (usually 1/60 or 1/120).

        Raises ValueError for dt <= 0, nan or inf (nothing changes), warns with a
        StabilityWarning the first time dt is past the method's limit for a force
        held, and raises SimulationDiverged, keeping the last finite state, if the
        state stops being finite.
        """
        fast = self._fast
        # type(dt) is float: True == 1.0 and 1 == 1.0, so without it step(True) after
        # step(1.0) would skip check_dt and run a step of "True" seconds.
        if fast is not None and type(dt) is float and fast[0] == dt and fast[1] == self._version:
            # The common case: same dt, nothing changed since the last step.
            _, _, name, step, comp = fast
        else:
            dt = check_dt(dt)
            comp = self._ready()
            name = self._method_for(dt, comp)
            step = None if name == "exact" else self._integrator_named(name)
            self._fast = (dt, self._version, name, step, comp)
        if dt != self._dt:
            # Fold the time so far into the base before counting steps of a new dt.
            self._t_base, self._n, self._dt = self.t, 0, dt
        t0 = self.t
        t1 = self._t_base + (self._n + 1) * dt
        if t1 == math.inf:
            raise ValueError(
                f"dt must keep the time finite: a step of dt={dt!r} s from t={t0!r} s would pass "
                f"the float range (1.8e308 s)"
            )
        if self._bodies:
            if name == "exact":
                if self._anchor is None:
                    self._anchor = (self._x.copy(), self._v.copy(), t0)
                x0, v0, ta = self._anchor
                # Closed form from the anchor: s = s0 + v0 T + a T^2 / 2, v = v0 + a T.
                elapsed = t1 - ta
                a = comp.a0
                x1 = x0 + v0 * elapsed + a * (0.5 * elapsed * elapsed)
                v1 = v0 + a * elapsed
            elif self._huge:
                # Near overflow (a blow-up under way): numpy's own overflow warnings would
                # only come before our clear SimulationDiverged, so silence them.
                with np.errstate(over="ignore", invalid="ignore"):
                    x1, v1 = step(self._x, self._v, self._accel, t0, dt)
            else:
                x1, v1 = step(self._x, self._v, self._accel, t0, dt)
            self._huge = self._check_finite(x1, v1, name, dt, t0) > 1e100
            self._prev_x, self._x, self._v = self._x, x1, v1
        self._n += 1
        self._steps += 1

    def _check_finite(self, x: Any, v: Any, name: str, dt: float, t: float) -> float:
        """Raise SimulationDiverged if x or v has a nan or inf; else return |sum of x and v|."""
        # A sum is nan or inf whenever any of its terms is (nan + anything = nan,
        # inf - inf = nan), so two sums check every entry. Only when one is not finite (or
        # huge finite values overflowed it) look closer. Not a BLAS dot product: OpenBLAS
        # takes milliseconds on arrays that are not 64-byte aligned, which numpy's are not.
        if self._huge:
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
            for i in range(len(self._bodies))
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
    def _state_value(self, row: Any) -> State:
        return float(row) if self._dim == 1 else Vector(float(row[0]), float(row[1]))

    def _read(self, what: str, index: int) -> State:
        if what == "x":
            return self._state_value(self._x[index])
        if what == "v":
            return self._state_value(self._v[index])
        self._ready()
        return self._state_value(self._accel(self.t, self._x, self._v)[index])

    def _write(self, what: str, index: int, value: State) -> None:
        target = self._x if what == "x" else self._v
        target[index] = tuple(value) if isinstance(value, Vector) else value
        if what == "x":
            self._prev_x[index] = target[index]  # a teleport is not blended
        self._anchor = None

    def positions(self, alpha: float = 1.0) -> np.ndarray:
        """Positions of all bodies blended from the previous step: prev + (now - prev) alpha.

        ``alpha`` in [0, 1] comes from the fixed-step loop; 1.0 gives the current state.
        Shape (N,) in 1D, (N, 2) in 2D; a new array. As in every fixed-step loop that
        interpolates, what is drawn lies between the last two steps, so up to one step
        behind ``t``: step once ahead before the first frame (as ``engine.render.record``
        does) to draw each frame exactly at its own time.
        """
        if isinstance(alpha, bool) or not isinstance(alpha, Real) or not 0.0 <= alpha <= 1.0:
            raise ValueError(f"alpha must be a number in [0, 1], got {alpha!r}")
        if self._x is None:
            return np.zeros((0,) if self._dim != 2 else (0, 2))
        if alpha == 1.0:
            return self._x.copy()
        return self._prev_x + (self._x - self._prev_x) * float(alpha)

    def position_of(self, body: Body, alpha: float = 1.0) -> State:
        """One body's position, blended like ``positions(alpha)``: a float or a Vector."""
        if not isinstance(body, Body) or body.world is not self:
            raise ValueError(f"that body is not in this World: {body!r}")
        return self._state_value(self.positions(alpha)[body._index])

    def velocities(self) -> np.ndarray:
        """Velocities of all bodies now, shape (N,) or (N, 2); a new array."""
        if self._v is None:
            return np.zeros((0,) if self._dim != 2 else (0, 2))
        return self._v.copy()

    def energy(self) -> float:
        """Total mechanical energy (J): kinetic plus the potential of the forces that have one.

        A body's own constant acceleration a counts like gravity, with potential -m a . x.
        """
        if not self._bodies:
            return 0.0
        comp = self._ready()
        m = comp.mass if self._dim == 1 else comp.mass[:, 0]
        v2 = self._v * self._v if self._dim == 1 else np.einsum("ij,ij->i", self._v, self._v)
        total = 0.5 * float(np.sum(m * v2))
        own = np.array([b.own_acc for b in self._bodies], dtype=float)
        dot = own * self._x if self._dim == 1 else np.einsum("ij,ij->i", own, self._x)
        total -= float(np.sum(m * dot))
        for attached in self._forces:
            if attached.bodies is None:
                u = attached.force.potential(self._x, comp.mass)
            else:
                idx = np.array([b._index for b in attached.bodies], dtype=np.intp)
                u = attached.force.potential(self._x[idx], comp.mass[idx]) if len(idx) else 0.0
            if u is not None:
                total += float(np.sum(u))
        return total

    # -- snapshot and restore -------------------------------------------------------------------
    def snapshot(self) -> WorldSnapshot:
        """Everything needed to bring this world back to this moment, bit for bit."""
        anchor = None
        if self._anchor is not None:
            anchor = (self._anchor[0].copy(), self._anchor[1].copy(), self._anchor[2])
        return WorldSnapshot(
            n_bodies=len(self._bodies),
            x=_copy(self._x),
            v=_copy(self._v),
            prev_x=_copy(self._prev_x),
            masses=tuple(b.mass for b in self._bodies),
            own_acc=tuple(b.own_acc for b in self._bodies),
            t_base=self._t_base,
            dt=self._dt,
            n_since_base=self._n,
            steps=self._steps,
            anchor=anchor,
            warned=frozenset(self._warned),
        )

    def restore(self, snapshot: WorldSnapshot) -> None:
        """Bring back the state saved by ``snapshot()`` (same bodies, in the same order)."""
        if not isinstance(snapshot, WorldSnapshot):
            raise TypeError(
                f"restore takes a WorldSnapshot from World.snapshot(), got "
                f"{type(snapshot).__name__}"
            )
        if snapshot.n_bodies != len(self._bodies):
            raise ValueError(
                f"the snapshot holds {snapshot.n_bodies} bodies but this World has "
                f"{len(self._bodies)}: restore into the world (or a copy) it was taken from"
            )
        masses, own_acc = self._check_snapshot(snapshot)
        self._x, self._v, self._prev_x = (
            _copy(snapshot.x),
            _copy(snapshot.v),
            _copy(snapshot.prev_x),
        )
        for body, m, a in zip(self._bodies, masses, own_acc, strict=True):
            body._mass, body._acc = m, a
        self._t_base = float(snapshot.t_base)
        self._dt = None if snapshot.dt is None else float(snapshot.dt)
        self._n, self._steps = snapshot.n_since_base, snapshot.steps
        self._changed_structure()
        if snapshot.anchor is not None:
            x0, v0, ta = snapshot.anchor
            self._anchor = (x0.copy(), v0.copy(), ta)
        self._warned = set(snapshot.warned)

    def _check_snapshot(self, snap: WorldSnapshot) -> tuple[list[float], list[State]]:
        """Refuse a snapshot (a plain dataclass, so one can be built or altered by hand) that
        would put nan, inf, a wrong shape or a negative count into this World; return its
        masses and own accelerations, checked."""
        n, dim = len(self._bodies), self._dim or 1
        shape = (n,) if dim == 1 else (n, 2)
        for name in ("x", "v", "prev_x"):
            value = getattr(snap, name)
            if n == 0 and value is None:
                continue
            if not (isinstance(value, np.ndarray) and value.shape == shape):
                raise ValueError(
                    f"snapshot.{name} must be an array of shape {shape} from World.snapshot(), "
                    f"got {value!r}"
                )
            if not np.isfinite(value).all():
                raise ValueError(f"snapshot.{name} must be finite (no nan or inf), got {value!r}")
        if not (isinstance(snap.masses, tuple) and isinstance(snap.own_acc, tuple)):
            raise TypeError("snapshot.masses and snapshot.own_acc must be tuples, one per body")
        if len(snap.masses) != n or len(snap.own_acc) != n:
            raise ValueError(f"snapshot.masses and snapshot.own_acc must hold {n} values each")
        try:
            masses = [coerce_mass(m) for m in snap.masses]
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"snapshot.masses: {exc}") from None
        own_acc = [coerce_state(a, dim, "snapshot.own_acc") for a in snap.own_acc]
        if snap.dt is not None:
            check_dt(snap.dt)
        t = snap.t_base
        try:
            t_ok = not isinstance(t, bool) and isinstance(t, Real) and 0.0 <= float(t) < 1e300
        except OverflowError:  # an int beyond the float range
            t_ok = False
        if not t_ok:
            raise ValueError(f"snapshot.t_base must be a finite time >= 0 s, got {t!r}")
        for name in ("n_since_base", "steps"):
            count = getattr(snap, name)
            if isinstance(count, bool) or not isinstance(count, int) or count < 0:
                raise ValueError(f"snapshot.{name} must be a whole number >= 0, got {count!r}")
        try:  # the time it stands for, t_base + n_since_base * dt, must be a float too
            t_now = float(t) + snap.n_since_base * (0.0 if snap.dt is None else float(snap.dt))
        except OverflowError:
            t_now = math.inf
        if not t_now < 1e300:
            raise ValueError(
                "snapshot.t_base + snapshot.n_since_base * snapshot.dt must be a finite time, "
                f"got {snap.t_base!r} + {snap.n_since_base!r} * {snap.dt!r}"
            )
        return masses, own_acc

    def __repr__(self) -> str:
        """``World(integrator='auto', tolerance=0.001, bodies=3, forces=2, t=1.5)``."""
        tolerance = "" if self._tolerance is None else f"tolerance={self._tolerance:g}, "
        return (
            f"World(integrator={self._requested!r}, {tolerance}bodies={len(self._bodies)}, "
            f"forces={len(self._forces)}, t={self.t:g})"
        )
