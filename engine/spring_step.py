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
takes the closed form for constant forces; ``"exact"`` refuses a spring that is not.

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

# Ends, velocities and constant accelerations off one line by more than this share of their
# size leave a damped spring's motion off its line: not linear.
_LINE = 1e-9


def _offset(angle: float, local: Any) -> tuple[float, float]:
    """A body's anchor turned by its angle (m): R(angle) local."""
    c, s = math.cos(angle), math.sin(angle)
    return c * local.x - s * local.y, s * local.x + c * local.y


class Springs:
    """A World's springs, in the order added, and what it keeps of them between steps."""

    def __init__(self) -> None:
        self.items: list[BodySpring] = []
        self._key: Any = None  # (dt, version, revisions) of the cached map
        self._map: np.ndarray | None = None  # expm(A dt) for the rows in _rows
        self._rows: np.ndarray = np.zeros(0, dtype=np.intp)
        self._checked: Any = None  # (dt, version, revisions) of the last stability check

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
        """A body left the World: its springs go with it."""
        self.items = [s for s in self.items if body not in s.bodies]

    def ties(self, store: BodyStore) -> tuple[np.ndarray, np.ndarray]:
        """The pairs of bodies the springs tie (World rows), which sleep as one group."""
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
            self._rows, self._map = self._matrix(store, dt)
            self._key = key
        rows, m = self._rows, self._map
        assert m is not None
        n = len(rows)
        w = np.where(store.kinematic[rows], 0.0, 1.0 / store.mass[rows])
        z = np.empty((3 * n, 2))
        z[:n], z[n : 2 * n] = store.x[rows], store.v[rows]
        z[2 * n :] = a0[rows] + w[:, None] * self._pulls(store, rows)
        z1 = m @ z
        for s in self.items:
            s.impulse = 0.0  # (not measured on the closed form)
        return rows, z1[:n], z1[n : 2 * n]

    def _matrix(self, store: BodyStore, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """The rows on springs, and expm(A dt) for them (the module's text)."""
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
        return rows, expm(a * dt)

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
        for s in self.items:
            if first:
                s.impulse = 0.0
            if isinstance(s, DampedSpring):
                s.impulse += _kick_linear(s, store, x, angle, v, omega, wm, wi, h)
            else:
                assert isinstance(s, DampedRotarySpring)
                s.impulse += _kick_rotary(s, store, angle, omega, wi, h)
        return v, omega

    # -- stability -------------------------------------------------------------------------------
    def warn_if_unstable(
        self, store: BodyStore, dt: float, version: int, warned: set[Any], level: int
    ) -> None:
        """Warn (StabilityWarning), once per spring, dt and settings, when a spring's kicks are
        past their limit omega dt < 2 (the module's text); looked at again only when dt, the
        World (``version``) or a spring's settings change."""
        checked = (dt, version, self.revisions())
        if checked == self._checked:
            return
        self._checked = checked
        for s in self.items:
            w = self.omega(s, store)
            key = ("spring", id(s), dt, s.revision)
            if w * dt < LIMIT or key in warned:
                continue
            warned.add(key)
            warnings.warn(
                f"{s!r} is unstable at dt={dt:g} s (omega={w:.4g} rad/s, omega*dt={w * dt:.4g}, "
                f"limit {LIMIT:g}: a spring's kicks are velocity Verlet's whatever the method); "
                f"the run continues and will blow up: use dt < {LIMIT / w:.4g} s or a softer "
                f"spring (stiffness < {s.stiffness * (LIMIT / (w * dt)) ** 2:.4g})",
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


def _end(
    b: Body | None, anchor: Any, store: BodyStore, x: np.ndarray, angle: np.ndarray
) -> tuple[int, float, float, float, float]:
    """(row or -1, px, py, rx, ry): where a spring holds ``b`` and its lever arm (m)."""
    if b is None:
        return -1, anchor.x, anchor.y, 0.0, 0.0
    row = store.row(b.slot)
    rx, ry = _offset(float(angle[row]), anchor)
    return row, float(x[row, 0]) + rx, float(x[row, 1]) + ry, rx, ry


def _push(
    row: int, nx: float, ny: float, arm: float, j: float, v: Any, omega: Any, wm: Any, wi: Any
) -> None:
    """Give body ``row`` the impulse j n (N s) at a point whose lever arm crosses n as ``arm``."""
    if row >= 0:
        v[row, 0] += nx * j * wm[row]
        v[row, 1] += ny * j * wm[row]
        omega[row] += arm * j * wi[row]


def _kick_linear(
    s: DampedSpring,
    store: BodyStore,
    x: np.ndarray,
    angle: np.ndarray,
    v: np.ndarray,
    omega: np.ndarray,
    wm: np.ndarray,
    wi: np.ndarray,
    h: float,
) -> float:
    """One DampedSpring's kick over ``h`` s, in place on v and omega; its impulse (N s, > 0
    pulls the ends together)."""
    i, ax, ay, rax, ray = _end(s.a, s.anchor_a, store, x, angle)
    j, bx, by, rbx, rby = _end(s.second, s.anchor_b, store, x, angle)
    dx, dy = bx - ax, by - ay
    dist = math.hypot(dx, dy)
    if dist == 0.0:
        return 0.0  # no direction: pymunk's n = 0 (a spring of rest length 0 at rest)
    nx, ny = dx / dist, dy / dist
    arm_a, arm_b = rax * ny - ray * nx, rbx * ny - rby * nx  # r x n
    k_n = 0.0  # 1 / m_eff along n
    if i >= 0:
        k_n += wm[i] + wi[i] * arm_a * arm_a
    if j >= 0:
        k_n += wm[j] + wi[j] * arm_b * arm_b
    if k_n == 0.0:
        return 0.0
    # The spring: stiffness (|d| - L) h along n pulls a toward b and b toward a.
    pull = s.stiffness * (dist - s.rest_length) * h
    _push(i, nx, ny, arm_a, pull, v, omega, wm, wi)
    _push(j, nx, ny, arm_b, -pull, v, omega, wm, wi)
    # The damper, implicit: the ends' relative speed along n, u, decays to u e^(-c h k_n),
    # by the impulse u (1 - e^(-c h k_n)) / k_n.
    u = 0.0
    if i >= 0:
        u -= (v[i, 0] - omega[i] * ray) * nx + (v[i, 1] + omega[i] * rax) * ny
    if j >= 0:
        u += (v[j, 0] - omega[j] * rby) * nx + (v[j, 1] + omega[j] * rbx) * ny
    damp = -u * math.expm1(-s.damping * h * k_n) / k_n
    _push(i, nx, ny, arm_a, damp, v, omega, wm, wi)
    _push(j, nx, ny, arm_b, -damp, v, omega, wm, wi)
    return pull + damp


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
