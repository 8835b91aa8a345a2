"""How a World moves its springs (engine.dynamics.springs): the closed form where the scene is
linear, else kicks in pymunk's manner made second order; and each spring's stability limit.

The closed form. A DampedSpring of rest length 0 whose moving ends do not turn (or are held at
their centres) pulls with F_a = k (p_b - p_a) + c (v_b - v_a) when its ends move along one line
(its damping acts along the spring, which is then the whole relative velocity; off the line
only an undamped spring stays linear). With constant forces (a0 per body), the bodies on
springs obey z' = A z for z = (x, v, b), per coordinate:

    x' = v,   v' = -W K x - W C v + b,   b' = 0,     b = a0 + W g

with W the inverse masses (0 for a kinematic body), K and C the springs' stiffness and damping
(k on the diagonal at each end, -k between the ends) and g the constant pulls of the anchors'
offsets and of points in the world. The step is z(t + dt) = expm(A dt) z(t): a damped
oscillator's x(t) to round-off at any dt (``tests/test_springs.py``: 1e-9 over many periods).
``integrator="auto"`` takes it when every force is constant and every spring is linear, as it
takes the closed form for constant forces; ``"exact"`` refuses a spring that is not. Each
spring's ``impulse`` is measured from it too (``Springs._measure``): the integral of its
tension over the step, from int_0^dt expm(A s) ds z(t), the positions' integral.

The kicks. Any other spring (a rest length, lever arms on bodies that turn, a rotary spring,
damping off its line, contacts or links in the World) is a pair of half kicks around the
method's step (Strang splitting, velocity Verlet on the spring): half the spring's impulse
from the positions at the start, the step, then the other half from where it ends. The
spring's part is pymunk's impulse (stiffness (|d| - L) dt along n); its damper decays the
ends' relative speed along n exponentially, as pymunk's (its exact flow: no dt overshoots),
with c the damping and 1 / m_eff = 1/m_a + 1/m_b + (r_a x n)^2 / I_a + (r_b x n)^2 / I_b
(a rotary spring's: 1 / I_a + 1 / I_b), around the pulls (below). Kicks are equal and opposite,
so momentum is kept to round-off; undamped, the energy stays within a bound that shrinks as
dt^2, and the limit is velocity Verlet's: omega dt < 2 with omega = sqrt(k / m_eff)
(``warn_if_unstable`` says so before the first step past it).

The dampers. Along one spring, in the ends' relative speed u along n and per unit of
1 / m_eff, with h = dt / 2, x = c h / m_eff and P a half kick's pull: the method's step moves
the ends with the speed w and changes u by its own forces' G1 before it moves them and G2
after (for a constant acceleration a along n: semi-implicit Euler a dt and 0; velocity
Verlet, rk4 and the closed form a dt / 2 each; explicit Euler 0 and a dt). The kicks once
took u -> e^-x (u + P) in both half kicks. At rest (w = 0, the speed u* at each step's end)
that is e^-x (u* + P) + G1 = 0 and u* = e^-x (G2 + P), so P = -(G1 + e^-2x G2) / (e^-x +
e^-2x), where k stretch = m a is P = -(G1 + G2) / 2: the damper decayed the pull that holds
the weight. A crate of 2 kg on 100 N/m and 20 N s/m at dt = 1/60 s rested 25.9 mm low on
semi-implicit Euler (4.778 m for 4.804 m), 8.9 mm on velocity Verlet, however long it
settled; the bias grew as e^x (1000 N/m and 2000 N s/m: 1.38 m, 70 times the stretch).

Now, with s = e^-x (the Strang splitting's half decay) and u_kick = u1 + P the speed after
the second half kick's pull (u1 what the method hands it):

    first half kick:   u -> s u, then the pull: u' = s u + P
    second half kick:  the pull, then u_kick -> (u_kick - (1 - e^-2x) u_end) / s,
                       u_end = u_kick + (G1 - G2) / 2,

the damper's whole step acting on u_end, the speed at the step's end, and the first half
kick's decay undone so that the next first half kick's may take it again. The method's
G1 - G2 is measured, per body (the ends' relative speed along n of the vector 2 W - v' - v1,
W = (x1 - x0) / dt the velocity it moved a body with, v' the velocity it was given, v1 the
one it gave back; angular velocities alike), so that moving ends that turn count as the
method moved them. Velocity Verlet, rk4 and the closed form have G1 = G2: u_end = u_kick,
which goes to e^-2x u_kick / s = e^-x u_kick, and the step is the Strang splitting
u -> e^-x u, + P | the method | + P, u -> e^-x u; semi-implicit and explicit Euler, which
kick before or after they drift, have their asymmetry taken off. Then:
- a lone damper (P = G = 0: u1 = s u) decays u to e^-2x u over a step, exactly, as before;
- at rest (w = 0: s u* + P + G1 = 0, u_kick = G2 + P) the balance P = -(G1 + G2) / 2 gives
  u_end = 0, and u_end = 0 gives u* = u_kick / s back: the dampers give nothing over the
  step, and the rest is k stretch = m a exactly, whatever the method or x, with u* = (G2 -
  G1) / (2 s): 0 for velocity Verlet, rk4, the closed form and a body's free turn
  (engine.dynamics.rotation), -a dt / (2 s) on semi-implicit Euler (its kick of a whole step before
  it drifts, against the pulls' half kicks: undamped, s = 1, the same), +a dt / (2 s) on
  explicit Euler;
- it is second order (the Strang splitting's), where the kicks once were first order in the
  damping (they decayed after each pull), and stable for omega dt < 2 at any x, as before.
Past x = 0.48, s = 1 - e^-2x instead of e^-x, which keeps u* below a dt / 1.24 (s = e^-x would
give u* = a dt e^x / 2). Springs that share a body are damped a colour at a time
(Gauss-Seidel): the first half kick's in the colours' order, the second's in the reverse
order, so that at rest (u_end = 0, each a decay's undoing) it undoes exactly what the first
did.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..accuracy import expm
from ..dynamics.springs import BodySpring, DampedRotarySpring, DampedSpring
from ..stability import OSCILLATION_LIMITS, StabilityWarning

if TYPE_CHECKING:
    from ..body import Body
    from ..dynamics.store import BodyStore

__all__ = ["Springs", "LIMIT"]

#: omega dt limit of the kicks (velocity Verlet's), for every method.
LIMIT = OSCILLATION_LIMITS["velocity_verlet"]

#: Up to this many DampedSprings are kicked in Python floats; more, in arrays (measured on
#: a two-core machine: arrays take about 0.5 ms a kick for 1 to 100 springs, floats about
#: 0.04 ms a spring).
FEW = 12

# Ends, velocities and constant accelerations off one line by more than this share of their
# size leave a damped spring's motion off its line: not linear.
_LINE = 1e-9


def _offset(angle: float, local: Any) -> tuple[float, float]:
    """A body's anchor turned by its angle (m): R(angle) local."""
    c, s = math.cos(angle), math.sin(angle)
    return c * local.x - s * local.y, s * local.x + c * local.y


#: No pairs: what ``Springs.ties`` gives while there are no springs (World rows, (0,) each).
_UNTIED = (np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp))


class Springs:
    """A World's springs, in the order added, and what it keeps of them between steps."""

    def __init__(self) -> None:
        self.items: list[BodySpring] = []
        self._key: Any = None  # (dt, version, revisions) of the cached map
        self._map: np.ndarray | None = None  # expm(A dt) for the rows in _rows
        # int_0^dt expm(A s) ds, its rows of x only: the positions' integral over the step
        self._area: np.ndarray | None = None
        self._rows: np.ndarray = np.zeros(0, dtype=np.intp)
        self._checked: Any = None  # (dt, version, revisions) of the last stability check
        self._tabled: tuple[Any, _Table] | None = None  # the DampedSprings as arrays, keyed
        # The velocities the step's first half kick left (m/s, rad/s), for its second (the
        # module's text, "The dampers").
        self._kicked: tuple[np.ndarray, np.ndarray] | None = None

    def __bool__(self) -> bool:
        return bool(self.items)

    def add(self, spring: BodySpring, world: Any) -> None:
        """Add ``spring`` between bodies of ``world`` (once)."""
        if any(s is spring for s in self.items):
            raise ValueError(f"that spring is already in this World (added only once): {spring!r}")
        for b in spring.bodies:
            if b.world is not world:
                raise ValueError(
                    f"the spring's bodies must be in this World first (world.add(body)): {b!r}"
                )
        self.items.append(spring)

    def remove(self, spring: BodySpring) -> None:
        """Take ``spring`` out."""
        if not any(s is spring for s in self.items):
            raise ValueError(f"that spring is not in this World: {spring!r}")
        self.items = [s for s in self.items if s is not spring]

    def body_removed(self, body: Body) -> None:
        """A body left the World: its springs go with it (and the rows of the bodies after
        it shift: the arrays are made again)."""
        self.items = [s for s in self.items if body not in s.bodies]
        self._tabled = None

    def ties(self, store: BodyStore) -> tuple[np.ndarray, np.ndarray]:
        """The pairs of bodies the springs tie (World rows), which sleep as one group."""
        if not self.items:
            return _UNTIED  # (every step of a World without springs asks)
        pairs = [
            (store.row(s.a.slot), store.row(b.slot))
            for s in self.items
            if (b := s.second) is not None
        ]
        rows = np.array(pairs, dtype=np.intp).reshape(-1, 2)
        return rows[:, 0].copy(), rows[:, 1].copy()

    def revisions(self) -> tuple[int, ...]:
        return tuple(s.revision for s in self.items)

    # -- which bodies turn under the springs ---------------------------------------------------
    def turn(self, store: BodyStore) -> bool:
        """Whether a spring may turn a body (an end that turns: a lever or a rotary spring)."""
        inv = store.inv_moment
        return any(inv[store.row(b.slot)] > 0.0 for s in self.items for b in s.bodies)

    # -- the closed form -------------------------------------------------------------------------
    def linear(self, store: BodyStore, a0: np.ndarray | None = None) -> str | None:
        """None when the springs are linear now (the closed form applies), else why not.

        ``a0``: the bodies' constant accelerations (m/s^2, (N, 2)), for the damped springs'
        line; None: zero."""
        damped = False
        for s in self.items:
            if not isinstance(s, DampedSpring):
                return f"{s!r} is a rotary spring"
            if s.rest_length != 0.0:
                return f"{s!r} has a rest length"
            for b, anchor in ((s.a, s.anchor_a), (s.second, s.anchor_b)):
                if b is None:
                    continue
                row = store.row(b.slot)
                if store.kinematic[row]:
                    return f"{s!r} holds a kinematic body"
                if store.inv_moment[row] > 0.0 and (anchor.x or anchor.y):
                    return f"{s!r} holds a body that turns away from its centre"
            damped = damped or s.damping > 0.0
        if damped and not self._on_one_line(store, a0):
            return "a damped spring's ends move off its line (its damping acts along it only)"
        return None

    def _on_one_line(self, store: BodyStore, a0: np.ndarray | None) -> bool:
        """Whether every spring's ends lie on one line, and the velocities and constant
        accelerations of their bodies point along it: then they stay on it."""
        points, arrows = [], []
        for s in self.items:
            assert isinstance(s, DampedSpring)
            for b, anchor in ((s.a, s.anchor_a), (s.second, s.anchor_b)):
                if b is None:
                    points.append((anchor.x, anchor.y))
                    continue
                row = store.row(b.slot)
                ox, oy = _offset(float(store.angle[row]), anchor)
                points.append((store.x[row, 0] + ox, store.x[row, 1] + oy))
                arrows.append(tuple(store.v[row]))
                if a0 is not None:
                    arrows.append(tuple(a0[row]))
        p = np.array(points, dtype=float)
        vectors = np.concatenate([p[1:] - p[0], np.array(arrows, dtype=float).reshape(-1, 2)])
        sizes = np.hypot(vectors[:, 0], vectors[:, 1])
        big = int(np.argmax(sizes))
        if sizes[big] == 0.0:
            return True  # all at one point, at rest: nothing moves them off it
        u = vectors[big] / sizes[big]
        off = np.abs(vectors[:, 0] * u[1] - vectors[:, 1] * u[0])
        return bool((off <= _LINE * sizes[big]).all())

    def exact(
        self, store: BodyStore, a0: np.ndarray, version: int, dt: float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(rows, x, v): where the bodies on springs are after ``dt`` s, by the closed form
        (the module's text); call only when ``linear`` says so."""
        key = (dt, version, self.revisions())
        if self._key != key:
            self._rows, self._map, self._area = self._matrix(store, dt)
            self._key = key
        rows, m, area = self._rows, self._map, self._area
        assert m is not None and area is not None
        n = len(rows)
        w = np.where(store.kinematic[rows], 0.0, 1.0 / store.mass[rows])
        z = np.empty((3 * n, 2))
        z[:n], z[n : 2 * n] = store.x[rows], store.v[rows]
        z[2 * n :] = a0[rows] + w[:, None] * self._pulls(store, rows)
        z1 = m @ z
        self._measure(store, rows, z[:n], z1[:n], area @ z, dt)
        return rows, z1[:n], z1[n : 2 * n]

    def _measure(
        self,
        store: BodyStore,
        rows: np.ndarray,
        x0: np.ndarray,
        x1: np.ndarray,
        swept: np.ndarray,
        dt: float,
    ) -> None:
        """Set each spring's ``impulse`` (N s, > 0 pulling) over a step of the closed form,
        from the positions of ``rows`` at its start (``x0``, m), at its end (``x1``) and their
        integral over it (``swept``, m s)."""
        # Along the spring, with d = p_b - p_a and n = d / |d|, the tension is
        # T = k |d| + c (v_b - v_a) . n (rest length 0 on the closed form), and
        # (v_b - v_a) . n = d|d|/dt, so the impulse over the step is
        #     J = int T dt = k int |d| dt + c (|d(t + dt)| - |d(t)|).
        # The damper's part is exact. For the spring's, the closed form gives int d dt (the
        # flow's integral, ``_area``), and int |d| dt = |int d dt| exactly while d keeps its
        # direction through the step: its ends move along one line (as a damped spring's must
        # here) and do not pass each other. Where d turns by an angle theta within the step
        # (an undamped spring whose ends circle), |int d dt| falls short of int |d| dt by
        # about theta^2 / 24 of it; where the ends pass each other once, by twice the lesser
        # of the parts of int |d| dt before and after they meet.
        index = {int(r): k for k, r in enumerate(rows)}
        at = (x0.tolist(), x1.tolist(), swept.tolist())  # per row: (x, y), in Python floats
        angles = store.angle[rows].tolist()
        weights = (1.0, 1.0, dt)  # an offset's share of each: at the start, the end, integrated
        for s in self.items:
            assert isinstance(s, DampedSpring)
            i = index[store.row(s.a.slot)]
            oax, oay = _offset(angles[i], s.anchor_a)
            b = s.second
            j = -1 if b is None else index[store.row(b.slot)]
            obx, oby = (s.anchor_b.x, s.anchor_b.y) if j < 0 else _offset(angles[j], s.anchor_b)
            sizes = []
            for xs, wt in zip(at, weights, strict=True):
                bx, by = (0.0, 0.0) if j < 0 else xs[j]  # (a point in the world: its offset)
                ax, ay = xs[i]
                sizes.append(
                    math.hypot(bx + obx * wt - ax - oax * wt, by + oby * wt - ay - oay * wt)
                )
            d0, d1, swept_d = sizes
            s.impulse = s.stiffness * swept_d + s.damping * (d1 - d0)

    def _matrix(self, store: BodyStore, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The rows on springs, expm(A dt) for them (the module's text), and the rows of x of
        int_0^dt expm(A s) ds (``_measure``)."""
        rows = self._spring_rows(store)
        n = len(rows)
        index = {int(r): k for k, r in enumerate(rows)}
        stiff, damp = np.zeros((n, n)), np.zeros((n, n))
        for s in self.items:
            i = index[store.row(s.a.slot)]
            j = None if s.second is None else index[store.row(s.second.slot)]
            for mat, k in ((stiff, s.stiffness), (damp, s.damping)):
                mat[i, i] += k
                if j is not None:
                    mat[j, j] += k
                    mat[i, j] -= k
                    mat[j, i] -= k
        w = np.where(store.kinematic[rows], 0.0, 1.0 / store.mass[rows])
        a = np.zeros((3 * n, 3 * n))
        eye = np.eye(n)
        a[:n, n : 2 * n] = eye
        a[n : 2 * n, :n] = -w[:, None] * stiff
        a[n : 2 * n, n : 2 * n] = -w[:, None] * damp
        a[n : 2 * n, 2 * n :] = eye
        return rows, expm(a * dt), _swept(a, dt)[:n]

    def _spring_rows(self, store: BodyStore) -> np.ndarray:
        rows = {store.row(b.slot) for s in self.items for b in s.bodies}
        return np.array(sorted(rows), dtype=np.intp)

    def _pulls(self, store: BodyStore, rows: np.ndarray) -> np.ndarray:
        """g: the springs' constant forces on ``rows`` (N), k (offset_b - offset_a) on a (and
        k times the point, for a point in the world), the opposite on b."""
        index = {int(r): k for k, r in enumerate(rows)}
        g = np.zeros((len(rows), 2))
        for s in self.items:
            assert isinstance(s, DampedSpring)
            ra = store.row(s.a.slot)
            oa = _offset(float(store.angle[ra]), s.anchor_a)
            if s.second is None:
                ob: tuple[float, float] = (s.anchor_b.x, s.anchor_b.y)
            else:
                ob = _offset(float(store.angle[store.row(s.second.slot)]), s.anchor_b)
            f = (s.stiffness * (ob[0] - oa[0]), s.stiffness * (ob[1] - oa[1]))
            g[index[ra]] += f
            if s.second is not None:
                g[index[store.row(s.second.slot)]] -= f
        return g

    # -- the kicks -------------------------------------------------------------------------------
    def kick(
        self,
        store: BodyStore,
        x: np.ndarray,
        angle: np.ndarray,
        v: np.ndarray,
        omega: np.ndarray,
        h: float,
        first: bool,
    ) -> tuple[np.ndarray, np.ndarray]:
        """New (v, omega) after the springs' impulses over ``h`` s at positions ``x`` and
        angles ``angle`` (the module's text); ``first``: the step's first half kick (the
        impulses counted in ``impulse`` start from 0), else its second, where the method's
        step of 2 h s from ``store.x`` and ``store.angle`` ends."""
        v, omega = v.copy(), omega.copy()
        wm = np.where(store.kinematic, 0.0, 1.0 / store.mass)
        wi = np.where(store.kinematic, 0.0, store.inv_moment)
        odd = None
        kicked = None if first else self._kicked
        if kicked is not None and kicked[0].shape == v.shape:
            # The method's step, from the velocities the first half kick left (v') to the
            # velocities it hands this one (v1), moved the bodies with W = (x1 - x0) / dt: it
            # changed their velocities by (W - v') before it moved them and (v1 - W) after,
            # and the dampers take half their difference, 2 W - v' - v1 (m/s, rad/s).
            dt = 2.0 * h
            odd = (
                (x - store.x) * (2.0 / dt) - kicked[0] - v,
                (angle - store.angle) * (2.0 / dt) - kicked[1] - omega,
            )
        elif not first:
            odd = (np.zeros_like(v), np.zeros_like(omega))
        rotary = [s for s in self.items if isinstance(s, DampedRotarySpring)]
        table = self._table(store)
        # The first half kick's dampers, then the second's in the reverse order (the rotary
        # springs' after the others' in the first, before them in the second).
        for s in rotary if not first else []:
            s.impulse += _kick_rotary(s, store, angle, omega, wi, h, odd)
        if table.springs:
            # (A state blowing up is refused just after, naming the limit: no numpy warning.)
            few = len(table.springs) <= FEW
            with np.errstate(over="ignore", invalid="ignore"):
                kick = _kick_floats if few else _kick_table
                impulses = kick(table, x, angle, v, omega, wm, wi, h, odd)
            for spring, j in zip(table.springs, impulses.tolist(), strict=True):
                spring.impulse = j if first else spring.impulse + j
        for s in rotary if first else []:
            s.impulse = _kick_rotary(s, store, angle, omega, wi, h, None)
        self._kicked = (v.copy(), omega.copy()) if first else None
        return v, omega

    def _table(self, store: BodyStore) -> _Table:
        """The DampedSprings as arrays, made again when the World or a setting changes."""
        # (Rows change only when a body leaves: body_removed forgets the arrays.)
        key = (id(store), self.revisions(), tuple(id(s) for s in self.items))
        if self._tabled is None or self._tabled[0] != key:
            self._tabled = (key, _Table.of(self.items, store))
        return self._tabled[1]

    # -- stability -------------------------------------------------------------------------------
    def warn_if_unstable(
        self,
        store: BodyStore,
        dt: float,
        version: int,
        warned: set[Any],
        level: int,
        substeps: int = 1,
    ) -> None:
        """Warn (StabilityWarning), once per spring, dt and settings, when a spring's kicks are
        past their limit omega h < 2, h = dt / ``substeps`` (the module's text; the soft
        step kicks once a substep: engine.dynamics.solver); looked at again only when dt, the World
        (``version``) or a spring's settings change."""
        checked = (dt, version, self.revisions(), substeps)
        if checked == self._checked:
            return
        self._checked = checked
        h = dt / substeps
        step = "omega*dt" if substeps == 1 else "omega*h"
        how = (
            "a spring's kicks are velocity Verlet's whatever the method"
            if substeps == 1
            else f"the soft step kicks each spring once a substep, h = dt / {substeps}"
        )
        for s in self.items:
            w = self.omega(s, store)
            key = ("spring", id(s), dt, s.revision, substeps)
            if w * h < LIMIT or key in warned:
                continue
            warned.add(key)
            warnings.warn(
                f"{s!r} is unstable at dt={dt:g} s (omega={w:.4g} rad/s, {step}={w * h:.4g}, "
                f"limit {LIMIT:g}: {how}); the run continues and will blow up: use "
                f"dt < {substeps * LIMIT / w:.4g} s or a softer spring (stiffness < "
                f"{s.stiffness * (LIMIT / (w * h)) ** 2:.4g})",
                StabilityWarning,
                stacklevel=level,
            )

    def max_stable_dt(self, store: BodyStore) -> float:
        """The largest dt (s) at which every spring's kicks are stable (inf without springs
        that pull on anything)."""
        omegas = [self.omega(s, store) for s in self.items]
        return min((LIMIT / w for w in omegas if w > 0.0), default=math.inf)

    @staticmethod
    def omega(s: BodySpring, store: BodyStore) -> float:
        """The spring's angular frequency (rad/s) on its bodies, at most: sqrt(k / m_eff), with
        each lever arm's full length for the turning bodies' share of 1 / m_eff."""
        inv = 0.0
        ends: list[tuple[Body | None, Any]] = (
            [(s.a, s.anchor_a), (s.second, s.anchor_b)]
            if isinstance(s, DampedSpring)
            else [(s.a, None), (s.second, None)]
        )
        for b, anchor in ends:
            if b is None:
                continue
            row = store.row(b.slot)
            if store.kinematic[row]:
                continue
            if anchor is None:
                inv += float(store.inv_moment[row])
            else:
                inv += 1.0 / float(store.mass[row])
                inv += float(store.inv_moment[row]) * (anchor.x**2 + anchor.y**2)
        return math.sqrt(s.stiffness * inv)


@dataclass
class _Table:
    """The World's DampedSprings as arrays (k springs), for kicks in a few array operations:
    the ends' rows (b: -1 for the world), the anchors (m; for the world, its point), the
    settings, and the springs in colours that share no body, whose dampers are solved one
    colour after another (Gauss-Seidel, as one at a time) and in one operation within one."""

    springs: list[DampedSpring]
    ia: np.ndarray
    ib: np.ndarray  # -1: the world
    anchor_a: np.ndarray  # (k, 2)
    anchor_b: np.ndarray  # (k, 2)
    rest: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    colours: list[np.ndarray]

    @classmethod
    def of(cls, items: list[BodySpring], store: BodyStore) -> _Table:
        springs = [s for s in items if isinstance(s, DampedSpring)]
        ia = np.array([store.row(s.a.slot) for s in springs], dtype=np.intp)
        ib = np.array(
            [-1 if (b := s.second) is None else store.row(b.slot) for s in springs],
            dtype=np.intp,
        )
        # Greedy colours: each spring takes the least colour neither of its bodies has yet.
        taken: dict[int, set[int]] = {}
        colour = []
        for a, b in zip(ia.tolist(), ib.tolist(), strict=True):
            used = taken.get(a, set()) | (taken.get(b, set()) if b >= 0 else set())
            c = next(c for c in range(len(used) + 1) if c not in used)
            colour.append(c)
            taken.setdefault(a, set()).add(c)
            if b >= 0:
                taken.setdefault(b, set()).add(c)
        colours = np.array(colour, dtype=np.intp)
        return cls(
            springs,
            ia,
            ib,
            np.array([tuple(s.anchor_a) for s in springs], dtype=float).reshape(-1, 2),
            np.array([tuple(s.anchor_b) for s in springs], dtype=float).reshape(-1, 2),
            np.array([s.rest_length for s in springs], dtype=float),
            np.array([s.stiffness for s in springs], dtype=float),
            np.array([s.damping for s in springs], dtype=float),
            [np.flatnonzero(colours == c) for c in range(int(colours.max(initial=-1)) + 1)],
        )


def _swept(a: np.ndarray, dt: float) -> np.ndarray:
    """int_0^dt expm(A s) ds for the square matrix ``a`` and ``dt`` (s): the integral over a
    step of the flow of z' = A z, so that int z dt = (this) z(t)."""
    # As engine.accuracy.expm, by scaling and squaring: with h = dt / 2^s, ||A h|| <= 1/2,
    #     E(h) = sum_k (A h)^k / k!,   S(h) = int_0^h expm(A u) du = h sum_k (A h)^k / (k + 1)!
    # (20 terms, far below round-off), and each doubling S(2h) = S(h) + E(h) S(h) (the second
    # half of the interval is the first, moved on by E(h)), E(2h) = E(h)^2.
    norm = float(np.abs(a).sum(axis=0).max()) * dt
    s = max(0, math.ceil(math.log2(norm / 0.5))) if norm > 0.5 else 0
    h = dt / 2.0**s
    ah = a * h
    term = flow = np.eye(len(a))
    swept = term.copy()
    for k in range(1, 21):
        term = term @ ah / k  # (A h)^k / k!
        flow = flow + term
        swept = swept + term / (k + 1)
    swept = swept * h
    for _ in range(s):
        swept = swept + flow @ swept
        flow = flow @ flow
    return swept


def _turned(angle: np.ndarray, local: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Anchors (k, 2) turned by the angles (k,): R(angle) local (m)."""
    c, s = np.cos(angle), np.sin(angle)
    return c * local[:, 0] - s * local[:, 1], s * local[:, 0] + c * local[:, 1]


def _decays(x: Any) -> tuple[Any, Any]:
    """(s - 1, 1 - e^-2x) of a damper (1; floats or arrays) for x = c h k_n: the first half
    kick's decay s = max(e^-x, 1 - e^-2x) and the step's (the module's text, "The dampers")."""
    # s = e^-x, the half step's decay, is the Strang splitting's; past e^-x < 1 - e^-2x
    # (x > 0.48) s keeps the speed at rest on semi-implicit Euler, a dt / (2 s), below
    # a dt / 1.24. Undamped (x = 0): s - 1 = 0 and 1 - e^-2x = 0, the kicks the pulls alone.
    if isinstance(x, np.ndarray):
        return np.maximum(np.expm1(-x), -np.exp(-2.0 * x)), -np.expm1(-2.0 * x)
    return max(math.expm1(-x), -math.exp(-2.0 * x)), -math.expm1(-2.0 * x)


def _kick_table(
    t: _Table,
    x: np.ndarray,
    angle: np.ndarray,
    v: np.ndarray,
    omega: np.ndarray,
    wm: np.ndarray,
    wi: np.ndarray,
    h: float,
    odd: tuple[np.ndarray, np.ndarray] | None,
) -> np.ndarray:
    """The DampedSprings' kick over ``h`` s, in place on v and omega; each one's impulse (N s,
    > 0 pulls the ends together). ``odd``: None in the step's first half kick; in its second,
    2 W - v' - v1 of each body (m/s, rad/s: ``Springs.kick``; the module's text, "The
    dampers")."""
    ia, ib = t.ia, t.ib
    on_b = ib >= 0
    jb = np.where(on_b, ib, 0)
    rax, ray = _turned(angle[ia], t.anchor_a)
    rbx, rby = _turned(angle[jb], t.anchor_b)
    rbx, rby = np.where(on_b, rbx, 0.0), np.where(on_b, rby, 0.0)
    dx = np.where(on_b, x[jb, 0] + rbx, t.anchor_b[:, 0]) - (x[ia, 0] + rax)
    dy = np.where(on_b, x[jb, 1] + rby, t.anchor_b[:, 1]) - (x[ia, 1] + ray)
    dist = np.hypot(dx, dy)
    # No direction at length 0: pymunk's n = 0 (a spring of rest length 0 at rest).
    safe = np.where(dist > 0.0, dist, 1.0)
    nx, ny = np.where(dist > 0.0, dx / safe, 0.0), np.where(dist > 0.0, dy / safe, 0.0)
    arm_a, arm_b = rax * ny - ray * nx, rbx * ny - rby * nx  # r x n
    wmb, wib = np.where(on_b, wm[jb], 0.0), np.where(on_b, wi[jb], 0.0)
    k_n = wm[ia] + wi[ia] * arm_a * arm_a + wmb + wib * arm_b * arm_b  # 1 / m_eff along n
    live = (dist > 0.0) & (k_n > 0.0)
    safe_k = np.where(live, k_n, 1.0)

    def speed(sel: np.ndarray, vel: np.ndarray, spin: np.ndarray) -> np.ndarray:
        """The ends' relative speed along n (m/s, > 0 parting) of the springs ``sel``."""
        a, b, ok = ia[sel], jb[sel], on_b[sel]
        u = -(
            (vel[a, 0] - spin[a] * ray[sel]) * nx[sel] + (vel[a, 1] + spin[a] * rax[sel]) * ny[sel]
        )
        ub = (vel[b, 0] - spin[b] * rby[sel]) * nx[sel] + (vel[b, 1] + spin[b] * rbx[sel]) * ny[sel]
        return u + np.where(ok, ub, 0.0)

    def damp(sel: np.ndarray, j: np.ndarray) -> None:
        _give(t, sel, nx, ny, arm_a, arm_b, j, v, omega, wm, wi)
        given[sel] += j[sel]

    # The springs: stiffness (|d| - L) h along n pulls a toward b and b toward a; they
    # depend on the positions alone, so all are given at once: in the first half kick after
    # the dampers (which act on the velocities the step starts with), in the second before.
    pull = np.where(live, t.stiffness * (dist - t.rest) * h, 0.0)
    everyone = np.arange(len(ia))
    given = np.zeros(len(ia))
    s1, decay = _decays(t.damping * h * np.where(live, k_n, 0.0))
    colours = [sel[live[sel]] for sel in t.colours]
    # The dampers, a colour at a time (Gauss-Seidel), in the ends' relative speeds along n, u
    # (an impulse j along n, > 0 pulling the ends together, takes j k_n from u).
    if odd is None:
        for sel in colours:  # u to s u
            j = np.zeros(len(ia))
            j[sel] = -speed(sel, v, omega) * s1[sel] / safe_k[sel]
            damp(sel, j)
        _give(t, everyone, nx, ny, arm_a, arm_b, pull, v, omega, wm, wi)
        return pull + given
    _give(t, everyone, nx, ny, arm_a, arm_b, pull, v, omega, wm, wi)
    ahead = 0.5 * speed(everyone, *odd)  # (G1 - G2) / 2 along each spring
    for sel in colours[::-1]:  # u to (u - (1 - e^-2x) (u + (G1 - G2) / 2)) / s
        u = speed(sel, v, omega)
        j = np.zeros(len(ia))
        j[sel] = (u - (u - decay[sel] * (u + ahead[sel])) / (1.0 + s1[sel])) / safe_k[sel]
        damp(sel, j)
    return pull + given


def _kick_floats(
    t: _Table,
    x: np.ndarray,
    angle: np.ndarray,
    v: np.ndarray,
    omega: np.ndarray,
    wm: np.ndarray,
    wi: np.ndarray,
    h: float,
    odd: tuple[np.ndarray, np.ndarray] | None,
) -> np.ndarray:
    """``_kick_table`` for a few springs, in Python floats: the same impulses in the same
    order (the dampers a colour at a time, and every spring's pull: after the dampers in
    the step's first half kick, before them in its second)."""
    rows = sorted({*t.ia.tolist(), *t.ib[t.ib >= 0].tolist()})
    # Each body's [x, y, angle, vx, vy, omega, 1/m, 1/I] by row, as floats, then its
    # 2 W - v' - v1 (the second half kick's ``odd``: the module's text, "The dampers").
    body = {
        r: [*x[r].tolist(), float(angle[r]), *v[r].tolist(), float(omega[r]), wm[r], wi[r]]
        + ([0.0] * 3 if odd is None else [*odd[0][r].tolist(), float(odd[1][r])])
        for r in rows
    }
    world = [0.0] * 11  # the world: still, immovable
    ends: list[tuple[list[float], list[float]]] = []
    geometry: list[tuple[float, ...]] = []
    out = [0.0] * len(t.springs)

    def give(k: int, jn: float) -> None:
        """+jn n to spring k's a, -jn n to its b (N s)."""
        (a, b), (nx, ny, arm_a, arm_b) = ends[k], geometry[k][:4]
        for end, arm, sign in ((a, arm_a, 1.0), (b, arm_b, -1.0)):
            end[3] += sign * nx * jn * end[6]
            end[4] += sign * ny * jn * end[6]
            end[5] += sign * arm * jn * end[7]
        out[k] += jn

    def speed(k: int, at: int) -> float:
        """Spring k's ends' relative speed along n (m/s), of the velocities from ``at``."""
        (a, b), (nx, ny, _, _, _, rax, ray, rbx, rby) = ends[k], geometry[k]
        u = (b[at] - b[at + 2] * rby - a[at] + a[at + 2] * ray) * nx
        return u + (b[at + 1] + b[at + 2] * rbx - a[at + 1] - a[at + 2] * rax) * ny

    pulls = []
    for k, (i, j) in enumerate(zip(t.ia.tolist(), t.ib.tolist(), strict=True)):
        a, b = body[i], body[j] if j >= 0 else world
        ends.append((a, b))
        ca, sa = math.cos(a[2]), math.sin(a[2])
        (lax, lay), (lbx, lby) = t.anchor_a[k].tolist(), t.anchor_b[k].tolist()
        rax, ray = ca * lax - sa * lay, sa * lax + ca * lay
        if j >= 0:
            cb, sb = math.cos(b[2]), math.sin(b[2])
            rbx, rby = cb * lbx - sb * lby, sb * lbx + cb * lby
            dx, dy = b[0] + rbx - a[0] - rax, b[1] + rby - a[1] - ray
        else:
            rbx = rby = 0.0
            dx, dy = lbx - a[0] - rax, lby - a[1] - ray
        dist = math.hypot(dx, dy)
        nx = ny = arm_a = arm_b = k_n = 0.0
        if dist > 0.0:
            nx, ny = dx / dist, dy / dist
            arm_a, arm_b = rax * ny - ray * nx, rbx * ny - rby * nx
            k_n = a[6] + a[7] * arm_a * arm_a + b[6] + b[7] * arm_b * arm_b
        geometry.append((nx, ny, arm_a, arm_b, k_n, rax, ray, rbx, rby))
        pulls.append(float(t.stiffness[k]) * (dist - float(t.rest[k])) * h if k_n > 0.0 else 0.0)
    order = [k for sel in t.colours for k in sel.tolist() if geometry[k][4] > 0.0]
    dampers = [
        (k, geometry[k][4], *_decays(float(t.damping[k]) * h * geometry[k][4])) for k in order
    ]
    if odd is None:
        for k, k_n, s1, _ in dampers:  # u to s u
            give(k, -speed(k, 3) * s1 / k_n)
        for k, p in enumerate(pulls):
            give(k, p)
    else:
        for k, p in enumerate(pulls):
            give(k, p)
        for k, k_n, s1, decay in dampers[::-1]:  # u to (u - (1 - e^-2x) u_end) / s
            u = speed(k, 3)
            give(k, (u - (u - decay * (u + 0.5 * speed(k, 8))) / (1.0 + s1)) / k_n)
    for r in rows:
        v[r] = body[r][3:5]
        omega[r] = body[r][5]
    return np.array(out)


def _give(
    t: _Table,
    sel: np.ndarray,
    nx: np.ndarray,
    ny: np.ndarray,
    arm_a: np.ndarray,
    arm_b: np.ndarray,
    j: np.ndarray,
    v: np.ndarray,
    omega: np.ndarray,
    wm: np.ndarray,
    wi: np.ndarray,
) -> None:
    """Give the springs ``sel`` their impulses j n (N s) at their ends: +j n to a, -j n to b
    (turning each by its lever arm r x n), summed where springs share a body."""
    a = t.ia[sel]
    ja = j[sel]
    np.add.at(v[:, 0], a, nx[sel] * ja * wm[a])
    np.add.at(v[:, 1], a, ny[sel] * ja * wm[a])
    np.add.at(omega, a, arm_a[sel] * ja * wi[a])
    ok = t.ib[sel] >= 0
    b, jb, pick = t.ib[sel][ok], ja[ok], sel[ok]
    np.add.at(v[:, 0], b, -nx[pick] * jb * wm[b])
    np.add.at(v[:, 1], b, -ny[pick] * jb * wm[b])
    np.add.at(omega, b, -arm_b[pick] * jb * wi[b])


def _kick_rotary(
    s: DampedRotarySpring,
    store: BodyStore,
    angle: np.ndarray,
    omega: np.ndarray,
    wi: np.ndarray,
    h: float,
    odd: tuple[np.ndarray, np.ndarray] | None,
) -> float:
    """One DampedRotarySpring's kick over ``h`` s, in place on omega; the angular impulse on a
    (N m s). ``odd``: None in the step's first half kick; in its second, 2 W - v' - v1 of each
    body (``Springs.kick``: its angular part, rad/s; the module's text, "The dampers")."""
    i = store.row(s.a.slot)
    b = s.second
    j = -1 if b is None else store.row(b.slot)
    k_w = wi[i] + (wi[j] if j >= 0 else 0.0)
    if k_w == 0.0:
        return 0.0
    twist = float(angle[i]) - (float(angle[j]) if j >= 0 else 0.0) - s.rest_angle
    spring = -s.stiffness * twist * h
    s1, decay = _decays(s.damping * h * k_w)
    u = float(omega[i]) - (float(omega[j]) if j >= 0 else 0.0)  # (an impulse J adds J k_w)
    if odd is None:
        total = u * s1 / k_w + spring  # the damper first, u to s u; then the pull
    else:
        # The pull, then u less (1 - e^-2x) of u + odd / 2, then to u / s.
        u_odd = float(odd[1][i]) - (float(odd[1][j]) if j >= 0 else 0.0)
        u_kicked = u + spring * k_w
        u_end = (u_kicked - decay * (u_kicked + 0.5 * u_odd)) / (1.0 + s1)
        total = spring + (u_end - u_kicked) / k_w
    omega[i] += total * wi[i]
    if j >= 0:
        omega[j] -= total * wi[j]
    return total
