"""How a World moves its springs (engine.springs): the closed form where the scene is linear,
else kicks in pymunk's manner made second order; and each spring's stability limit.

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
spring's part is pymunk's impulse (stiffness (|d| - L) dt along n), its damping pymunk's
implicit decay: the ends' relative speed along n is multiplied by exp(-c h / m_eff) (c the
damping, 1 / m_eff = 1/m_a + 1/m_b + (r_a x n)^2 / I_a + (r_b x n)^2 / I_b), which no dt can
overshoot. Kicks are equal and opposite, so momentum is kept to round-off; undamped, the energy
stays within a bound that shrinks as dt^2, and the limit is velocity Verlet's: omega dt < 2
with omega = sqrt(k / m_eff) (``warn_if_unstable`` says so before the first step past it).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .accuracy import expm
from .springs import BodySpring, DampedRotarySpring, DampedSpring
from .stability import OSCILLATION_LIMITS, StabilityWarning

if TYPE_CHECKING:
    from .body import Body
    from .store import BodyStore

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
        impulses counted in ``impulse`` start from 0)."""
        v, omega = v.copy(), omega.copy()
        wm = np.where(store.kinematic, 0.0, 1.0 / store.mass)
        wi = np.where(store.kinematic, 0.0, store.inv_moment)
        table = self._table(store)
        if table.springs:
            # (A state blowing up is refused just after, naming the limit: no numpy warning.)
            few = len(table.springs) <= FEW
            with np.errstate(over="ignore", invalid="ignore"):
                kick = _kick_floats if few else _kick_table
                impulses = kick(table, x, angle, v, omega, wm, wi, h)
            for spring, j in zip(table.springs, impulses.tolist(), strict=True):
                spring.impulse = j if first else spring.impulse + j
        for s in self.items:
            if isinstance(s, DampedRotarySpring):
                j = _kick_rotary(s, store, angle, omega, wi, h)
                s.impulse = j if first else s.impulse + j
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
        step kicks once a substep: engine.solver); looked at again only when dt, the World
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


def _kick_table(
    t: _Table,
    x: np.ndarray,
    angle: np.ndarray,
    v: np.ndarray,
    omega: np.ndarray,
    wm: np.ndarray,
    wi: np.ndarray,
    h: float,
) -> np.ndarray:
    """The DampedSprings' kick over ``h`` s, in place on v and omega; each one's impulse
    (N s, > 0 pulls the ends together)."""
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
    # The springs: stiffness (|d| - L) h along n pulls a toward b and b toward a; they
    # depend on the positions alone, so all are given at once.
    pull = np.where(live, t.stiffness * (dist - t.rest) * h, 0.0)
    _give(t, np.arange(len(ia)), nx, ny, arm_a, arm_b, pull, v, omega, wm, wi)
    # The dampers, implicit, a colour at a time: the ends' relative speed along n, u, decays
    # to u e^(-c h k_n), by the impulse u (1 - e^(-c h k_n)) / k_n.
    damp = np.zeros(len(ia))
    for sel in t.colours:
        sel = sel[live[sel]]
        a, b, ok = ia[sel], jb[sel], on_b[sel]
        u = -((v[a, 0] - omega[a] * ray[sel]) * nx[sel] + (v[a, 1] + omega[a] * rax[sel]) * ny[sel])
        ub = (v[b, 0] - omega[b] * rby[sel]) * nx[sel] + (v[b, 1] + omega[b] * rbx[sel]) * ny[sel]
        u = u + np.where(ok, ub, 0.0)
        damp[sel] = -u * np.expm1(-t.damping[sel] * h * k_n[sel]) / k_n[sel]
        _give(t, sel, nx, ny, arm_a, arm_b, damp, v, omega, wm, wi)
    return pull + damp


def _kick_floats(
    t: _Table,
    x: np.ndarray,
    angle: np.ndarray,
    v: np.ndarray,
    omega: np.ndarray,
    wm: np.ndarray,
    wi: np.ndarray,
    h: float,
) -> np.ndarray:
    """``_kick_table`` for a few springs, in Python floats: the same impulses in the same
    order (every spring's pull, then the dampers a colour at a time, as pymunk gives its
    springs' impulses before it solves their dampers)."""
    rows = sorted({*t.ia.tolist(), *t.ib[t.ib >= 0].tolist()})
    # Each body's [x, y, angle, vx, vy, omega, 1/m, 1/I], by row, as floats.
    body = {
        r: [*x[r].tolist(), float(angle[r]), *v[r].tolist(), float(omega[r]), wm[r], wi[r]]
        for r in rows
    }
    world = [0.0] * 8  # the world: still, immovable
    ends, geometry = [], []
    out = [0.0] * len(t.springs)

    def give(a: list[float], b: list[float], g: tuple[float, ...], jn: float) -> None:
        nx, ny, arm_a, arm_b = g[:4]
        for end, arm, sign in ((a, arm_a, 1.0), (b, arm_b, -1.0)):
            end[3] += sign * nx * jn * end[6]
            end[4] += sign * ny * jn * end[6]
            end[5] += sign * arm * jn * end[7]

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
        if k_n > 0.0:
            out[k] = float(t.stiffness[k]) * (dist - float(t.rest[k])) * h
            give(a, b, geometry[k], out[k])
    for sel in t.colours:
        for k in sel.tolist():
            nx, ny, arm_a, arm_b, k_n, rax, ray, rbx, rby = geometry[k]
            if k_n == 0.0:
                continue
            a, b = ends[k]
            u = (b[3] - b[5] * rby - a[3] + a[5] * ray) * nx
            u += (b[4] + b[5] * rbx - a[4] - a[5] * rax) * ny
            damp = -u * math.expm1(-float(t.damping[k]) * h * k_n) / k_n
            give(a, b, geometry[k], damp)
            out[k] += damp
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
) -> float:
    """One DampedRotarySpring's kick over ``h`` s, in place on omega; the angular impulse on a
    (N m s)."""
    i = store.row(s.a.slot)
    b = s.second
    j = -1 if b is None else store.row(b.slot)
    k_w = wi[i] + (wi[j] if j >= 0 else 0.0)
    if k_w == 0.0:
        return 0.0
    twist = float(angle[i]) - (float(angle[j]) if j >= 0 else 0.0) - s.rest_angle
    spring = -s.stiffness * twist * h
    omega[i] += spring * wi[i]
    if j >= 0:
        omega[j] -= spring * wi[j]
    u = float(omega[i]) - (float(omega[j]) if j >= 0 else 0.0)
    damp = u * math.expm1(-s.damping * h * k_w) / k_w  # -u (1 - e^(-c h k_w)) / k_w
    omega[i] += damp * wi[i]
    if j >= 0:
        omega[j] -= damp * wi[j]
    return spring + damp
