"""The time of impact: when a ball on a known path first touches a line or a disc.

Within one step a body's centre follows the parabola

    x(t) = X + V t + B t^2 / 2,        0 <= t <= T,

which is exact under constant acceleration B (lesson 1's s = s0 + v0 t + a t^2 / 2) and is the
step's own position update for an integrator (``engine.exact.contacts`` says how). A ball of
radius r touches a face when its centre is at distance rho (face offset plus r) from it, so
the moment of impact is a root of a polynomial in t, found exactly, never guessed by checking
where the ball ended up: a fast ball cannot jump over a thin wall.

* A flat face (a line with unit normal n through p): g(t) = s n.(x(t) - p) - rho, with s = +1
  or -1 the side the ball starts on, is the quadratic
  g(t) = g0 + g1 t + g2 t^2 with g0 = s n.(X - p) - rho, g1 = s n.V, g2 = s n.B / 2.
* A round face (centre C): f(t) = |x(t) - C|^2 - rho^2 is the quartic, with D = X - C,
  f(t) = |B|^2 / 4 t^4 + V.B t^3 + (|V|^2 + D.B) t^2 + 2 D.V t + |D|^2 - rho^2.

The first root in [0, T] is the impact (starting outside, the first crossing is inward). The
functions ending in ``s`` work on numpy arrays of pairs (one row per ball-face pair) and return
the times (``inf`` where there is no impact within T). Each has a twin ending in ``_one`` for a
single pair in Python floats, for when the pairs are few: numpy's fixed cost per call (about a
microsecond) then outweighs the arithmetic. A twin does the same operations in the same order
(numpy and Python floats round each +, -, *, / and sqrt alike), with an ``if`` where the array
version computes both branches and picks with ``np.where``, so the two give the same bits.

>>> import numpy as np
>>> z = np.zeros((1, 2))
>>> X, V, B = np.array([[0.0, 10.0]]), z, np.array([[0.0, -9.81]])
>>> t = line_hits(X, V, B, z, np.array([[0.0, 1.0]]), np.array([0.5]), np.array([False]),
...               np.array([-np.inf]), np.array([np.inf]), 5.0)[0]
>>> bool(abs(t[0] - (2 * 9.5 / 9.81) ** 0.5) < 1e-15)
True
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.linalg import _umath_linalg  # private, kept: 6.2 us a call, eigvals 8.9 (measured)

# The LAPACK eigenvalue routine np.linalg.eigvals calls, without its checks (about 10 us a
# call: most of a lone quartic's cost). _eigvals_one checks what they would and otherwise
# falls back to np.linalg.eigvals, so the answers and errors are the same.
_LAPACK_EIGVALS = getattr(_umath_linalg, "eigvals", None)

__all__ = [
    "quadratic_first_root",
    "quadratic_first_root_one",
    "line_hits",
    "leaves_end_one",
    "line_hit_one",
    "disc_hits",
    "disc_hit_one",
    "grazes",
    "graze_one",
    "GRAZE_ROUNDING",
    "TOUCH",
]

Pair = tuple[float, float]

#: Distances (length units) within this of a face count as touching it, not as a gap.
TOUCH = 1e-12


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]


def quadratic_first_root(
    g0: Any, g1: Any, g2: Any, T: Any, slack: Any = 0.0, behind: bool = False
) -> np.ndarray:
    """Smallest t in [0, T] with g0 + g1 t + g2 t^2 = 0 when g0 > 0; ``inf`` if none.

    Where g0 <= 0 (touching) the answer is 0 if g is heading down (g1 < -slack, or
    |g1| <= slack and g2 < 0), else where it curves back (below) or ``inf``: a grazing touch
    whose rate is rounding noise (within ``slack``) is no impact unless the curvature carries
    it in. Roots by the stable form q = -(g1 + sign(g1) sqrt(disc)) / 2, t = q / g2 and
    g0 / q, which loses no digits when g1^2 >> 4 g0 g2.

    ``behind``: where g0 < 0, heading up and curving back, the later root, where g comes back
    down through 0 (a ball beside a finite face's end, behind its line: ``line_hits``); else
    -g1 / g2, which is that root where g0 = 0.
    """
    g0, g1, g2 = np.asarray(g0, float), np.asarray(g1, float), np.asarray(g2, float)
    inf = np.inf
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        disc = g1 * g1 - 4.0 * g2 * g0
        sq = np.sqrt(np.maximum(disc, 0.0))
        q = -0.5 * (g1 + np.copysign(sq, g1))
        r1 = np.where(g2 != 0.0, q / g2, inf)
        r2 = np.where(q != 0.0, g0 / q, inf)
        r1 = np.where(r1 >= 0.0, r1, inf)
        r2 = np.where(r2 >= 0.0, r2, inf)
        t = np.minimum(r1, r2)
        t = np.where(disc < 0.0, inf, t)
        # Linear case (g2 = 0): t = -g0 / g1 when heading down.
        lin = np.where(g1 < 0.0, -g0 / g1, inf)
        t = np.where(g2 == 0.0, lin, t)
        # Touching and leaving, but curving back (g2 < 0): g = g1 t + g2 t^2 (g0 = 0) is zero
        # again at t = -g1 / g2, where the ball comes back down onto the face.
        back = np.where((g2 < 0.0) & (g1 > 0.0), -g1 / g2, inf)
        if behind:
            # g0 < 0: the later root q / g2 (g1 > 0: q = -(g1 + sqrt(disc)) / 2), none if
            # g never comes up to 0.
            later = np.where(disc >= 0.0, q / g2, inf)
            back = np.where((g0 < 0.0) & (g2 < 0.0) & (g1 > 0.0), later, back)
    touching = g0 <= 0.0
    heading_in = (g1 < -slack) | ((g1 <= slack) & (g2 < 0.0))
    t = np.where(touching, np.where(heading_in, 0.0, back), t)
    return np.where(t <= T, t, inf)


def quadratic_first_root_one(
    g0: float, g1: float, g2: float, T: float, slack: float = 0.0
) -> float:
    """``quadratic_first_root`` for one quadratic, in Python floats (the same bits).

    The array version computes every case and picks the one that applies, in the order
    touching, linear, no real root, roots; here only that one is computed.
    """
    inf = math.inf
    if g0 <= 0.0:  # touching: now if heading in, else where it curves back (if it does)
        if g1 < -slack or (g1 <= slack and g2 < 0.0):
            t = 0.0
        else:
            t = -g1 / g2 if g2 < 0.0 and g1 > 0.0 else inf
    elif g2 == 0.0:  # linear: t = -g0 / g1 when heading down
        t = -g0 / g1 if g1 < 0.0 else inf
    else:
        # max() keeps a nan first argument, as np.maximum does; each division is guarded by
        # the test np.where makes.
        disc = g1 * g1 - 4.0 * g2 * g0
        if disc < 0.0:
            return inf
        sq = math.sqrt(max(disc, 0.0))
        q = -0.5 * (g1 + math.copysign(sq, g1))
        r1 = q / g2
        r2 = g0 / q if q != 0.0 else inf
        r1 = r1 if r1 >= 0.0 else inf
        r2 = r2 if r2 >= 0.0 else inf
        t = r1 if r1 < r2 else r2
    return t if t <= T else inf


def line_hits(
    X: np.ndarray,
    V: np.ndarray,
    B: np.ndarray,
    p: np.ndarray,
    n: np.ndarray,
    rho: np.ndarray,
    two_sided: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    T: Any,
) -> tuple[np.ndarray, np.ndarray]:
    """First impact time of each pair with its flat face, and the face normal toward the ball.

    A two-sided face (a segment's side) is met from the side the ball starts on; the impact
    counts only where the ball's centre lies within [lo, hi] along the face's tangent.
    """
    d0 = _dot(X - p, n)
    side = np.where(two_sided & (d0 < 0.0), -1.0, 1.0)
    # A ball exactly on a two-sided line (d0 = 0) takes the side it moves away from.
    on_line = two_sided & (d0 == 0.0)
    side = np.where(on_line & (_dot(V, n) > 0.0), -1.0, side)
    g0 = side * d0 - rho
    g0 = np.where(np.abs(g0) <= TOUCH * (1.0 + rho), 0.0, g0)
    speed = np.sqrt(_dot(V, V))
    # A ball that starts behind the line (g0 < 0) beside the face's end meets the face where
    # it comes back down onto the line (``behind``), if it is within the face then.
    g1, g2 = side * _dot(V, n), 0.5 * side * _dot(B, n)
    t = quadratic_first_root(g0, g1, g2, T, 1e-12 * speed, True)
    now = (t == 0.0) & (g0 == 0.0) & (g1 >= -1e-12 * speed)
    if now.any():
        # Touching at an end and leaving the face that way: the end's round face's, not this
        # one's (``leaves_end_one``).
        u0 = (X[:, 0] - p[:, 0]) * -n[:, 1] + (X[:, 1] - p[:, 1]) * n[:, 0]
        ut = V[:, 0] * -n[:, 1] + V[:, 1] * n[:, 0]
        edge = TOUCH * (1.0 + np.abs(u0))
        off = ((ut > 0.0) & (u0 >= hi - edge)) | ((ut < 0.0) & (u0 <= lo + edge))
        t = np.where(now & off, np.inf, t)
    hit = np.isfinite(t)
    if hit.any():
        tt = np.where(hit, t, 0.0)[:, None]
        xt = X + V * tt + B * (0.5 * tt * tt)
        u = (xt[:, 0] - p[:, 0]) * -n[:, 1] + (xt[:, 1] - p[:, 1]) * n[:, 0]
        t = np.where(hit & (u >= lo) & (u <= hi), t, np.inf)
    return t, n * side[:, None]


def line_hit_one(
    X: Pair,
    V: Pair,
    B: Pair,
    p: Pair,
    n: Pair,
    rho: float,
    two_sided: bool,
    lo: float,
    hi: float,
    T: float,
) -> tuple[float, Pair]:
    """``line_hits`` for one pair, in Python floats (the same bits): (time or inf, normal)."""
    x, y = X
    vx, vy = V
    bx, by = B
    px, py = p
    nx, ny = n
    d0 = (x - px) * nx + (y - py) * ny
    vn = vx * nx + vy * ny
    side = -1.0 if two_sided and d0 < 0.0 else 1.0
    if two_sided and d0 == 0.0 and vn > 0.0:
        side = -1.0
    g0 = side * d0 - rho
    if abs(g0) <= TOUCH * (1.0 + rho):
        g0 = 0.0
    g1 = side * vn
    g2 = 0.5 * side * (bx * nx + by * ny)
    # quadratic_first_root_one(g0, g1, g2, T, 1e-12 |V|), inlined (the same operations; the
    # speed only where it is used): this is the innermost test of a step.
    inf = math.inf
    if g0 <= 0.0:
        slack = 1e-12 * math.sqrt(vx * vx + vy * vy)
        if g1 < -slack or (g1 <= slack and g2 < 0.0):
            t = 0.0
        elif g2 < 0.0 and g1 > 0.0:
            if g0 < 0.0:  # behind the line: the later root (``quadratic_first_root``)
                disc = g1 * g1 - 4.0 * g2 * g0
                t = -0.5 * (g1 + math.sqrt(disc)) / g2 if disc >= 0.0 else inf
            else:
                t = -g1 / g2
        else:
            t = inf
    elif g2 == 0.0:
        t = -g0 / g1 if g1 < 0.0 else inf
    else:
        disc = g1 * g1 - 4.0 * g2 * g0
        if disc < 0.0:
            return inf, (nx * side, ny * side)
        sq = math.sqrt(max(disc, 0.0))
        q = -0.5 * (g1 + math.copysign(sq, g1))
        r1 = q / g2
        r2 = g0 / q if q != 0.0 else inf
        r1 = r1 if r1 >= 0.0 else inf
        r2 = r2 if r2 >= 0.0 else inf
        t = r1 if r1 < r2 else r2
    if not t <= T:
        t = inf
    if t == 0.0 and g0 == 0.0 and leaves_end_one(x, y, vx, vy, px, py, nx, ny, lo, hi, g1):
        t = inf
    if t != math.inf:
        xt = x + vx * t + bx * (0.5 * t * t)
        yt = y + vy * t + by * (0.5 * t * t)
        u = (xt - px) * -ny + (yt - py) * nx
        if not lo <= u <= hi:
            t = math.inf
    return t, (nx * side, ny * side)


def leaves_end_one(
    x: float, y: float, vx: float, vy: float, px: float, py: float, nx: float, ny: float,
    lo: float, hi: float, g1: float,
) -> bool:  # fmt: skip
    """Whether a ball touching a flat face (its centre at x, y; velocity vx, vy), not moving
    into it (its normal speed ``g1`` within ``line_hits``' slack), touches it at an end, lo or
    hi along the tangent (-n_y, n_x) from p, and leaves it that way: no impact with this
    face, but the end's round face's (a ball that slid to the end of a ramp flies on over
    it: engine.exact.sweep, "A slide's end"). At the end to ``TOUCH`` of its place."""
    slack = 1e-12 * math.sqrt(vx * vx + vy * vy)
    if g1 < -slack:
        return False
    u0 = (x - px) * -ny + (y - py) * nx
    ut = vx * -ny + vy * nx
    edge = TOUCH * (1.0 + abs(u0))
    return (ut > 0.0 and u0 >= hi - edge) or (ut < 0.0 and u0 <= lo + edge)


#: A tangency is a graze, not an impact, where the straight path's discriminant is within
#: this many units of rounding (2^-53) of its terms: 16 covers the products (each within one
#: unit), |D|^2 - rho^2 and D.V (whose errors are in units of |D|^2 and |D| |V|, not of the
#: small difference), and the sums.
GRAZE_ROUNDING = 16.0 * 2.0**-53


def grazes(k0: Any, k1: Any, k2: Any, dd: Any, rho: Any) -> np.ndarray:
    """Whether the straight path k0 + k1 tau + k2 tau^2 (k0 = |D|^2 - rho^2 > 0 apart) only
    grazes the disc: its discriminant k1^2 - 4 k2 k0 is no larger than its own rounding.

    A path tangent to the disc has a double root. Rounding the discriminant (by ~1e-16 of
    its terms) splits it by ~1e-8 of the step, and an impact taken there meets the disc
    1e-8 rad from its tangent point, with an approach speed of 1e-8 of the ball's: a ball
    sliding at rest height off a segment's end would be kicked up. Within that rounding the
    path is called tangent: it passes, as it would with the discriminant rounded down. The
    paths so let by enter the disc by at most a few 1e-16 of its size.
    """
    k0, k1, k2 = np.asarray(k0, float), np.asarray(k1, float), np.asarray(k2, float)
    with np.errstate(invalid="ignore", over="ignore"):
        disc = k1 * k1 - 4.0 * k2 * k0
        bound = GRAZE_ROUNDING * (k1 * k1 + 4.0 * np.abs(k2) * (dd + rho * rho))
    return (k0 > 0.0) & (disc <= bound)


def graze_one(k0: float, k1: float, k2: float, dd: float, rho: float) -> bool:
    """``grazes`` for one path, in Python floats (the same bits)."""
    disc = k1 * k1 - 4.0 * k2 * k0
    return k0 > 0.0 and disc <= GRAZE_ROUNDING * (k1 * k1 + 4.0 * abs(k2) * (dd + rho * rho))


def disc_hits(
    X: np.ndarray,
    V: np.ndarray,
    B: np.ndarray,
    c: np.ndarray,
    rho: np.ndarray,
    T: Any,
    graze: np.ndarray | bool = True,
) -> np.ndarray:
    """First impact time of each pair with its round face (centre c, contact distance rho).
    ``graze`` (bool, or one a pair): a straight path tangent to the face within its rounding
    (``grazes``) passes it; False for a ball resting on a face, whose support ends where its
    path touches the face's round end (the edge it slides off), so that moment is kept.

    The quartic f(t) = |x(t) - c|^2 - rho^2 is written in tau = t / T in [0, 1]. Pairs whose
    face lies beyond the path's reach (|V| T + |B| T^2 / 2 from X) are skipped; a straight
    path (B = 0) is a quadratic solved in closed form; a curved one is solved by the
    eigenvalues of its companion matrix and polished by Newton's method on f.
    """
    m = len(X)
    t = np.full(m, np.inf)
    if m == 0:
        return t
    T = np.broadcast_to(np.asarray(T, dtype=float), (m,))
    D = X - c
    dd, vv = _dot(D, D), _dot(V, V)
    dist0 = np.sqrt(dd) - rho
    # The path stays within |V| T + |B| T^2 / 2 of X: farther discs cannot be met.
    reach = np.sqrt(vv) * T + np.sqrt(_dot(B, B)) * (0.5 * T * T)
    touching = dist0 <= TOUCH * (1.0 + rho)
    todo = ~touching & (dist0 <= reach * (1.0 + 1e-9))
    if touching.any():
        # Touching: an impact now if heading in. The rate of |D|^2, 2 D.V, is rounding noise
        # only for a graze; then the curvature |V|^2 + D.B decides.
        k1 = 2.0 * _dot(D, V)
        slack = 1e-12 * np.sqrt(dd * vv)
        k2 = vv + _dot(D, B)
        heading_in = (k1 < -slack) | ((k1 <= slack) & (k2 < 0.0))
        # Leaving so slowly that the curvature brings it back within 1e-9 of the step (at
        # t = -k1 / k2, where f = k1 t + k2 t^2 is zero again): pressed in now. The search
        # below takes such a root for the departure itself, and would let the ball through
        # (a ball at rest in a wedge, pulled into a peg, leaving it at 2e-10 m^2/s).
        heading_in |= (k2 < 0.0) & (k1 <= -k2 * T * 1e-9)
        t[touching & heading_in] = 0.0
        # Touching and leaving: the path may curve back onto the disc later in the step.
        leaving = touching & ~heading_in & (reach > 0.0)
        todo |= leaving
    else:
        leaving = touching
    if not todo.any():
        return t
    idx = np.flatnonzero(todo)
    # Tighter: the path strays at most |B| T^2 / 2 from the chord X + V t; a chord that passes
    # the disc farther than that cannot bring the ball onto it (the ones leaving stay in).
    Di, Vi, Ti = D[idx], V[idx], T[idx]
    vvi = vv[idx]
    s = np.clip(-_dot(Di, Vi) / np.where(vvi > 0.0, vvi, 1.0), 0.0, Ti)
    C = Di + Vi * s[:, None]
    stray = 0.5 * np.sqrt(_dot(B[idx], B[idx])) * Ti * Ti
    keep = (np.sqrt(_dot(C, C)) - stray <= rho[idx] * (1.0 + 1e-9) + TOUCH) | leaving[idx]
    if not keep.all():
        idx = idx[keep]
        if not len(idx):
            return t
    Di, Vi, Bi, Ti = D[idx], V[idx], B[idx], T[idx]
    # The powers of T by products, not **: numpy's power may use a vectorized pow whose last
    # bit differs from the C library's (and from machine to machine).
    T2 = Ti * Ti
    K = np.stack(
        [
            dd[idx] - rho[idx] * rho[idx],
            2.0 * _dot(Di, Vi) * Ti,
            (vv[idx] + _dot(Di, Bi)) * T2,
            _dot(Vi, Bi) * (T2 * Ti),
            0.25 * _dot(Bi, Bi) * (T2 * T2),
        ],
        axis=1,
    )
    # For those leaving, f = tau (k1 + k2 tau + k3 tau^2 + k4 tau^3): its next root is the
    # first root of the cubic in the brackets.
    lv = leaving[idx]
    if lv.any():
        K[lv] = np.concatenate([K[lv, 1:], np.zeros((int(lv.sum()), 1))], axis=1)
    scale = np.abs(K).max(axis=1)
    tau = np.full(len(idx), np.inf)
    small = 1e-9 * scale
    deg = np.where(np.abs(K[:, 4]) > small, 4, np.where(np.abs(K[:, 3]) > small, 3, 2))
    # No root at all: on [0, 1], where tau^i <= 1, the polynomial is at least k0 plus its
    # negative coefficients. When that is above zero by 1e-6 of the largest coefficient, far
    # beyond what rounding can move a root by (a near-real complex root of a curve so clear of
    # zero needs it within ~1e-11), the eigenvalues are not computed (degree 0: none sought).
    neg = np.minimum(K, 0.0)
    clear = K[:, 0] + neg[:, 1] + neg[:, 2] + neg[:, 3] + neg[:, 4] > 1e-6 * scale
    deg = np.where(clear, 0, deg)
    # A ball leaving the disc comes back only after a real flight: its root of the deflated
    # cubic must lie clear of 0 (a root within rounding of 0 is the departure itself).
    lower = np.where(lv, 1e-9, -1e-9) if lv.any() else np.full(len(idx), -1e-9)
    for d in (4, 3):
        sel = np.flatnonzero(deg == d)
        if len(sel):
            tau[sel] = _first_root_eig(K[sel, : d + 1], lower[sel])
    sel = np.flatnonzero(deg == 2)
    if len(sel):
        tau[sel] = quadratic_first_root(K[sel, 0], K[sel, 1], K[sel, 2], 1.0)
        tau[sel] = np.where(tau[sel] > lower[sel], tau[sel], np.inf)
        passes = grazes(K[sel, 0], K[sel, 1], K[sel, 2], dd[idx[sel]], rho[idx[sel]])
        passes &= ~lv[sel] & np.broadcast_to(graze, (m,))[idx[sel]]
        tau[sel] = np.where(passes, np.inf, tau[sel])
    ok = np.isfinite(tau)
    if ok.any():
        tau[ok] = _polish(K[ok], tau[ok])
    t[idx] = np.where(ok & (tau <= 1.0), np.maximum(tau, 0.0) * T[idx], np.inf)
    return t


def disc_hit_one(
    X: Pair, V: Pair, B: Pair, c: Pair, rho: float, T: float, graze: bool = True
) -> float:
    """``disc_hits`` for one pair, in Python floats (the same bits; the cubic and quartic go
    to the same eigenvalue solver, one row)."""
    inf = math.inf
    x, y = X
    vx, vy = V
    bx, by = B
    Dx, Dy = x - c[0], y - c[1]
    dd, vv = Dx * Dx + Dy * Dy, vx * vx + vy * vy
    dv, db, bb = Dx * vx + Dy * vy, Dx * bx + Dy * by, bx * bx + by * by
    dist0 = math.sqrt(dd) - rho
    reach = math.sqrt(vv) * T + math.sqrt(bb) * (0.5 * T * T)
    leaving = False
    if dist0 <= TOUCH * (1.0 + rho):  # touching
        k1 = 2.0 * dv
        slack = 1e-12 * math.sqrt(dd * vv)
        k2 = vv + db
        if k1 < -slack or (k1 <= slack and k2 < 0.0) or (k2 < 0.0 and k1 <= -k2 * T * 1e-9):
            return 0.0  # (heading in, or back within 1e-9 of the step: disc_hits)
        if not reach > 0.0:
            return inf
        leaving = True
    elif not dist0 <= reach * (1.0 + 1e-9):
        return inf
    # The chord test: the path strays at most |B| T^2 / 2 from the chord X + V t.
    s = -dv / (vv if vv > 0.0 else 1.0)
    s = min(max(s, 0.0), T)
    Cx, Cy = Dx + vx * s, Dy + vy * s
    stray = 0.5 * math.sqrt(bb) * T * T
    if not (math.sqrt(Cx * Cx + Cy * Cy) - stray <= rho * (1.0 + 1e-9) + TOUCH or leaving):
        return inf
    T2 = T * T
    K = [
        dd - rho * rho,
        2.0 * dv * T,
        (vv + db) * T2,
        (vx * bx + vy * by) * (T2 * T),
        0.25 * bb * (T2 * T2),
    ]
    if leaving:
        K = K[1:] + [0.0]
    k0, k1, k2, k3, k4 = K
    scale = max(abs(k0), abs(k1), abs(k2), abs(k3), abs(k4))
    if math.isnan(k0 + k1 + k2 + k3 + k4):
        scale = math.nan  # as np.max: a nan (or inf - inf) leaves only the quadratic
    small = 1e-9 * scale
    deg = 4 if abs(k4) > small else 3 if abs(k3) > small else 2
    if k0 + min(k1, 0.0) + min(k2, 0.0) + min(k3, 0.0) + min(k4, 0.0) > 1e-6 * scale:
        return inf  # clear of zero on [0, 1]: no root
    lower = 1e-9 if leaving else -1e-9
    if deg > 2:
        tau = _first_root_eig_one(K[: deg + 1], lower)
    else:
        tau = quadratic_first_root_one(K[0], K[1], K[2], 1.0)
        tau = tau if tau > lower else inf
        if graze and not leaving and graze_one(k0, k1, k2, dd, rho):
            tau = inf
    if tau == inf:
        return inf
    tau = _polish_one(K, tau)
    return max(tau, 0.0) * T if tau <= 1.0 else inf


def _first_root_eig(K: np.ndarray, lower: np.ndarray) -> np.ndarray:
    """Smallest real root in (lower, 1] of each row's polynomial k0 + k1 x + ... (degree 3
    or 4)."""
    n, d = K.shape[0], K.shape[1] - 1
    lead = K[:, d]
    comp = np.zeros((n, d, d))
    # Companion matrix of the monic polynomial x^d + (k_{d-1}/k_d) x^{d-1} + ... + k0/k_d.
    comp[:, 0, :] = -K[:, d - 1 :: -1][:, :d] / lead[:, None]
    for i in range(1, d):
        comp[:, i, i - 1] = 1.0
    roots = np.linalg.eigvals(comp)
    real = np.abs(roots.imag) <= 1e-6 * (1.0 + np.abs(roots.real))
    r = np.where(real, roots.real, np.inf)
    r = np.where((r > lower[:, None]) & (r <= 1.0 + 1e-9), r, np.inf)
    return r.min(axis=1)


def _first_root_eig_one(K: list[float], lower: float) -> float:
    """``_first_root_eig`` for one polynomial: the same companion matrix, solved by the same
    LAPACK routine (numpy calls it matrix by matrix, so one alone gives the same roots)."""
    d = len(K) - 1
    lead = K[d]
    comp = [[0.0] * d for _ in range(d)]
    comp[0] = [-K[d - 1 - j] / lead for j in range(d)]
    for i in range(1, d):
        comp[i][i - 1] = 1.0
    roots = _eigvals_one(comp)
    best = math.inf
    for re, im in zip(roots.real.tolist(), roots.imag.tolist(), strict=True):
        if abs(im) <= 1e-6 * (1.0 + abs(re)) and lower < re <= 1.0 + 1e-9 and re < best:
            best = re
    return best


def _eigvals_one(comp: list[list[float]]) -> np.ndarray:
    """``np.linalg.eigvals`` of one small real matrix (a list of rows), the same bits: the
    same LAPACK routine, called directly when the matrix is finite (np.linalg.eigvals checks
    that first) and kept only when every eigenvalue came out finite (LAPACK did not fail);
    anything else goes to np.linalg.eigvals itself, for its answer or its error."""
    a = np.array(comp)
    if _LAPACK_EIGVALS is not None and math.isfinite(sum(map(sum, comp))):
        with np.errstate(all="ignore"):
            w = _LAPACK_EIGVALS(a, signature="d->D")
        if math.isfinite(float(np.abs(w).sum())):
            return w
    return np.linalg.eigvals(a)


def _polish(K: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Three Newton steps on k0 + k1 x + k2 x^2 + k3 x^3 + k4 x^4 from x (kept if they stray)."""
    x0 = x.copy()
    for _ in range(3):
        f = K[:, 0] + x * (K[:, 1] + x * (K[:, 2] + x * (K[:, 3] + x * K[:, 4])))
        df = K[:, 1] + x * (2.0 * K[:, 2] + x * (3.0 * K[:, 3] + x * 4.0 * K[:, 4]))
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(df != 0.0, f / df, 0.0)
        x = x - step
    # Newton can run off at a double root (a graze): keep the eigenvalue's root there.
    return np.where(np.abs(x - x0) <= 1e-6, x, x0)


def _polish_one(K: list[float], x: float) -> float:
    """``_polish`` for one polynomial, in Python floats (the same bits)."""
    k0, k1, k2, k3, k4 = K
    x0 = x
    for _ in range(3):
        f = k0 + x * (k1 + x * (k2 + x * (k3 + x * k4)))
        df = k1 + x * (2.0 * k2 + x * (3.0 * k3 + x * 4.0 * k4))
        x = x - (f / df if df != 0.0 else 0.0)
    return x if abs(x - x0) <= 1e-6 else x0
