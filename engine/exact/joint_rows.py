"""The joint solver's rows (engine.exact.joint_solver): each a scalar equation c(q) on the positions
and angles of one or two bodies, and its gradient, evaluated for many rows at once.

An anchor a in body i's frame is at p = x_i + R(theta_i) a, with lever arm r = R(theta_i) a,
and moves with dp/dtheta_i = perp(r) = (-r_y, r_x). The kinds:

- ``PX``, ``PY``: a point two bodies share (a Hinge, a Weld, a Pin with an anchor), c = p_a - p_b;
- ``DIST``: a distance (a Rod; a Cable, at most), c = |p_a - p_b| - L, gradient n = d / |d|
  (n . perp(r) = r x n on the angle);
- ``ANGLE``: theta_a - theta_b - ref - bound (a Weld; a Hinge's limits); ``MOTOR``: the same
  row, for speeds only; ``SOFT_*``: a soft weld's rows, for speeds only;
- ``CN``, ``CT``: a contact of a joined body (``Touch``): its gap along the normal, linear about
  where the step left the two (a disc against a polygon: its distance from the polygon
  wherever it turns, engine.exact.joint_contacts), and the slip of its points along the tangent
  (speeds only).

On the fast path (engine.kernels) the rows are evaluated by the loop kernel ``rows_loop``, a
row at a time, beside its numpy twin ``_rows``, a kind at a time; the rows of a disc against a
polygon that turns are then rewritten by ``turned_loop`` there and by its twin ``_turned``
on numpy, to the same bits (a ball on a pinball's bat: about a quarter of the time of the
steps in which the two touch went to ``_turned``'s numpy calls on the fast path). The
Newton steps of engine.exact.joint_solver evaluate the rows a few times a step, and at a
game's few joints numpy's fixed cost per call was most of that.
"""

from __future__ import annotations

from functools import cached_property
from typing import NamedTuple

import numpy as np

from .. import kernels
from ..geometry.manifold_kinds import Polygons
from .joint_contacts import polygon_distance

__all__ = [
    "Touch", "Plan", "evaluate", "PX", "PY", "DIST", "ANGLE", "MOTOR", "SOFT_X", "SOFT_Y",
    "SOFT_ANGLE", "CN", "CT", "rows_loop", "turned_loop",
]  # fmt: skip

# Row kinds.
PX, PY, DIST, ANGLE, MOTOR, SOFT_X, SOFT_Y, SOFT_ANGLE, CN, CT = range(10)


class Touch(NamedTuple):
    """Contacts of the joints' bodies as the step ends, one a row: the body (World row), the
    other (World row; -1: the static world), the unit normal from the other to the body, the
    contact point less each one's centre (``r_body``, ``r_other``; length units), the gap
    (length units; what the correction may not close), friction (both materials'), the
    impulse the contact gave in the step along n and along t = (-n_y, n_x) (N s), and
    ``lift``: a disc resting on a collider (engine.exact.contacts: the joints may take back its
    contact's impulse, it may lift) or a contact of the pile (engine.exact.pile: it only pushes,
    and only where the two touch as the step ends or met in it). ``turn``
    (engine.exact.joint_contacts): 0, a row linear about where the step left the two; +1 (-1), the
    body (the other) is a polygon or a capsule, ``poly`` in engine.exact.joint_contacts.shapes_of,
    and the other end a disc
    of ``radius``, its row exact wherever the polygon turns; its gap is then the one at the
    step's start. ``restitution``: a contact of
    the pile's bounces by it where the joints' solve catches it closing (a disc resting on
    a collider: 0, its contact's own bounce is engine.exact.contacts')."""

    body: np.ndarray
    other: np.ndarray
    normal: np.ndarray
    r_body: np.ndarray
    r_other: np.ndarray
    gap: np.ndarray
    mu: np.ndarray
    pn: np.ndarray
    pt: np.ndarray
    lift: np.ndarray
    turn: np.ndarray
    poly: np.ndarray
    radius: np.ndarray
    restitution: np.ndarray

    @staticmethod
    def join(parts: list[Touch | None]) -> Touch | None:
        """The contacts of ``parts`` together (None: none)."""
        given = [t for t in parts if t is not None and len(t.body)]
        if not given:
            return None
        if len(given) == 1:
            return given[0]
        return Touch(*(np.concatenate(field) for field in zip(*given, strict=True)))


class Plan:
    """Rows as arrays by row (engine.exact.joint_solver's own): kind, bound, each end's place among
    the joints' bodies (b: -1 for the world), anchors, and a resting disc's normal, point,
    gap and radius; the kinds' row indices and the columns of J, made when first asked for
    (the loop kernel needs none of them)."""

    def __init__(
        self,
        kind: np.ndarray,
        bound: np.ndarray,
        a: np.ndarray,
        b: np.ndarray,
        aa: np.ndarray,
        ab: np.ndarray,
        touch: tuple[np.ndarray, ...],
        width: int,
        polygons: Polygons | None = None,
    ) -> None:
        # A contact row's normal, contact points less the centres, where the body and the
        # other were (position, angle) as the step ended (began, for a disc and a polygon),
        # its gap, and a disc and a polygon's (Touch.turn, poly, radius).
        n, rbod, roth, refb, refo, thb, tho, gap, turn, poly, radius = touch
        ints = np.stack([kind, a, b, turn, poly], 1).astype(np.int64)
        floats = np.column_stack([bound, aa, ab, n, rbod, roth, refb, refo, thb, tho, gap, radius])
        self._set(ints, floats, width, polygons)

    @classmethod
    def packed(
        cls, ints: np.ndarray, floats: np.ndarray, width: int, polygons: Polygons | None
    ) -> Plan:
        """A plan of the rows' packed arrays: ``ints`` (rows, 5: kind, a, b, turn, poly) and
        ``floats`` (rows, 19: bound, aa, ab, n, rbod, roth, refb, refo, thb, tho, gap,
        radius; the pairs as two columns), as ``Plan`` packs them."""
        plan = cls.__new__(cls)
        plan._set(ints, floats, width, polygons)
        return plan

    def _set(
        self, ints: np.ndarray, floats: np.ndarray, width: int, polygons: Polygons | None
    ) -> None:
        """Hold the packed arrays (what the loop kernel takes: two arguments, not sixteen,
        whose unboxing cost more than its loop) and each field as a view of its columns."""
        self.ints, self.floats = ints, floats
        self.kind, self.a, self.b, self.turn, self.poly = (ints[:, k] for k in range(5))
        f = floats
        self.bound, self.aa, self.ab = f[:, 0], f[:, 1:3], f[:, 3:5]
        self.n, self.rbod, self.roth = f[:, 5:7], f[:, 7:9], f[:, 9:11]
        self.refb, self.refo = f[:, 11:13], f[:, 13:15]
        self.thb, self.tho, self.gap, self.radius = f[:, 15], f[:, 16], f[:, 17], f[:, 18]
        self.polygons = polygons
        self.width = width

    @cached_property
    def has(self) -> np.ndarray:
        """The rows with a second body (not the static world)."""
        return self.b >= 0

    @cached_property
    def bc(self) -> np.ndarray:
        """The second body's place, 0 for the world (masked by ``has``)."""
        return np.maximum(self.b, 0)

    @cached_property
    def turned(self) -> np.ndarray:
        """The rows of a disc against a polygon that turns (engine.exact.joint_contacts)."""
        if self.polygons is None:
            return np.zeros(0, dtype=np.intp)
        return np.flatnonzero(self.turn != 0)

    def take(self, sel: np.ndarray) -> Plan:
        """The rows ``sel`` alone."""
        return Plan.packed(self.ints[sel], self.floats[sel], self.width, self.polygons)


def evaluate(
    X: np.ndarray, TH: np.ndarray, P: Plan, fast: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Each row's value c and gradient J (rows, 3 m) at the joints' bodies' positions X
    (m, 2) and angles TH (m,). ``fast``: the loop kernel ``rows_loop`` for every row as it
    stands, in place of its numpy twin ``_rows``; the rows of a disc against a polygon that
    turns are then rewritten by ``_turned`` (the kernel ``turned_loop`` on the fast path)."""
    if fast:
        c, J = rows_loop(X, TH, P.ints, P.floats, P.width)
        if len(P.turned):
            poly = P.polygons
            assert poly is not None
            turned_loop(X, TH, P.ints, P.floats, P.turned, poly.vertices, poly.normals,
                        poly.count, poly.radius, c, J)  # fmt: skip
        return c, J
    c, J = _rows(X, TH, P)
    if len(P.turned):
        _turned(X, TH, P, c, J)
    return c, J


def _rows(X: np.ndarray, TH: np.ndarray, P: Plan) -> tuple[np.ndarray, np.ndarray]:
    """``evaluate``'s rows in numpy, a contact's linear about where the step left the two."""
    has, bc = P.has, P.bc
    kind = P.kind
    ta = TH[P.a]
    ca, sa = np.cos(ta), np.sin(ta)
    ax, ay = P.aa[:, 0], P.aa[:, 1]
    rax, ray = ca * ax - sa * ay, sa * ax + ca * ay
    tb = np.where(has, TH[bc], 0.0)
    cb, sb = np.cos(tb), np.sin(tb)
    bx, by = P.ab[:, 0], P.ab[:, 1]
    rbx = np.where(has, cb * bx - sb * by, 0.0)
    rby = np.where(has, sb * bx + cb * by, 0.0)
    Xa, Xb = X[P.a], X[bc]
    dx = Xa[:, 0] + rax - np.where(has, Xb[:, 0] + rbx, bx)
    dy = Xa[:, 1] + ray - np.where(has, Xb[:, 1] + rby, by)
    R = len(kind)
    c = np.zeros(R)
    g = np.zeros((6, R))  # the gradient: (x, y, theta) on body_a, then on body_b
    q = np.flatnonzero((kind == PX) | (kind == SOFT_X))
    c[q] = dx[q]
    g[0, q], g[2, q], g[3, q], g[5, q] = 1.0, -ray[q], -1.0, rby[q]
    q = np.flatnonzero((kind == PY) | (kind == SOFT_Y))
    c[q] = dy[q]
    g[1, q], g[2, q], g[4, q], g[5, q] = 1.0, rax[q], -1.0, -rbx[q]
    q = np.flatnonzero(kind == DIST)
    if len(q):
        length = np.hypot(dx[q], dy[q])
        safe = np.where(length > 0.0, length, 1.0)
        nx, ny = dx[q] / safe, dy[q] / safe
        c[q] = length - P.bound[q]
        g[0, q], g[1, q], g[2, q] = nx, ny, rax[q] * ny - ray[q] * nx
        g[3, q], g[4, q], g[5, q] = -nx, -ny, rby[q] * nx - rbx[q] * ny
    q = np.flatnonzero((kind == ANGLE) | (kind == SOFT_ANGLE) | (kind == MOTOR))
    if len(q):
        c[q] = ta[q] - tb[q] - P.bound[q]
        g[2, q], g[5, q] = 1.0, -1.0
    cn = np.flatnonzero(kind == CN)
    if len(cn):
        # A row linear about where the step left the two (the body, a; the other, b): its
        # gap along the normal, which the correction may not close.
        nx, ny = P.n[cn, 0], P.n[cn, 1]
        kb = P.rbod[cn, 0] * ny - P.rbod[cn, 1] * nx  # r x n, the body's lever
        ko = P.roth[cn, 0] * ny - P.roth[cn, 1] * nx
        c[cn] = (
            P.gap[cn]
            + (Xa[cn, 0] - P.refb[cn, 0]) * nx + (Xa[cn, 1] - P.refb[cn, 1]) * ny
            + kb * (ta[cn] - P.thb[cn])
            - np.where(has[cn], (Xb[cn, 0] - P.refo[cn, 0]) * nx
                       + (Xb[cn, 1] - P.refo[cn, 1]) * ny + ko * (tb[cn] - P.tho[cn]), 0.0)
        )  # fmt: skip
        g[0, cn], g[1, cn], g[2, cn] = nx, ny, kb
        g[3, cn], g[4, cn], g[5, cn] = -nx, -ny, -ko
    ct = np.flatnonzero(kind == CT)
    if len(ct):
        # The slip of its points along t = (-n_y, n_x) (velocity only).
        tx, ty = -P.n[ct, 1], P.n[ct, 0]
        g[0, ct], g[1, ct] = tx, ty
        g[2, ct] = P.rbod[ct, 0] * ty - P.rbod[ct, 1] * tx
        g[3, ct], g[4, ct] = -tx, -ty
        g[5, ct] = -(P.roth[ct, 0] * ty - P.roth[ct, 1] * tx)
    J = np.zeros((R, P.width))
    r = np.arange(R)
    a3 = 3 * P.a
    J[r, a3], J[r, a3 + 1], J[r, a3 + 2] = g[0], g[1], g[2]
    rb = np.flatnonzero(has)
    b3 = 3 * P.b[rb]
    J[rb, b3], J[rb, b3 + 1], J[rb, b3 + 2] = g[3, rb], g[4, rb], g[5, rb]
    return c, J


def _sample_rows() -> tuple[object, ...]:
    """The smallest call of ``rows_loop``: a hinge's two rows to the world, a contact's two
    rows between its two bodies."""
    ints = np.array([[PX, 0, -1, 0, -1], [PY, 0, -1, 0, -1], [CN, 1, 0, 0, -1], [CT, 1, 0, 0, -1]])
    return np.zeros((2, 2)), np.zeros(2), ints.astype(np.int64), np.zeros((4, 19)), 6


@kernels.loop(sample=_sample_rows)
def rows_loop(
    X: np.ndarray, TH: np.ndarray, ints: np.ndarray, floats: np.ndarray, width: int
) -> tuple[np.ndarray, np.ndarray]:
    """``_rows`` as a loop over the rows of the Plan's packed arrays (``Plan.packed``): each
    row's value and its six entries of J, with the twin's products in the twin's order."""
    R = len(ints)
    c = np.zeros(R)
    J = np.zeros((R, width))
    for r in range(R):
        k, i = ints[r, 0], ints[r, 1]
        has = ints[r, 2] >= 0
        j = ints[r, 2] if has else 0
        f = floats[r]
        ta = TH[i]
        ca, sa = np.cos(ta), np.sin(ta)
        ax, ay = f[1], f[2]
        rax, ray = ca * ax - sa * ay, sa * ax + ca * ay
        tb = TH[j] if has else 0.0
        cb, sb = np.cos(tb), np.sin(tb)
        bx, by = f[3], f[4]
        rbx = cb * bx - sb * by if has else 0.0
        rby = sb * bx + cb * by if has else 0.0
        dx = X[i, 0] + rax - (X[j, 0] + rbx if has else bx)
        dy = X[i, 1] + ray - (X[j, 1] + rby if has else by)
        g0 = g1 = g2 = g3 = g4 = g5 = 0.0
        if k == PX or k == SOFT_X:
            c[r] = dx
            g0, g2, g3, g5 = 1.0, -ray, -1.0, rby
        elif k == PY or k == SOFT_Y:
            c[r] = dy
            g1, g2, g4, g5 = 1.0, rax, -1.0, -rbx
        elif k == DIST:
            length = np.hypot(dx, dy)
            safe = length if length > 0.0 else 1.0
            nx, ny = dx / safe, dy / safe
            c[r] = length - f[0]
            g0, g1, g2 = nx, ny, rax * ny - ray * nx
            g3, g4, g5 = -nx, -ny, rby * nx - rbx * ny
        elif k == ANGLE or k == SOFT_ANGLE or k == MOTOR:
            c[r] = ta - tb - f[0]
            g2, g5 = 1.0, -1.0
        elif k == CN:
            # (f: bound 0, aa 1-2, ab 3-4, n 5-6, rbod 7-8, roth 9-10, refb 11-12, refo 13-14,
            # thb 15, tho 16, gap 17, radius 18)
            nx, ny = f[5], f[6]
            kb = f[7] * ny - f[8] * nx
            ko = f[9] * ny - f[10] * nx
            other = 0.0
            if has:
                other = (X[j, 0] - f[13]) * nx + (X[j, 1] - f[14]) * ny + ko * (tb - f[16])
            c[r] = (
                f[17] + (X[i, 0] - f[11]) * nx + (X[i, 1] - f[12]) * ny + kb * (ta - f[15])
                - other
            )  # fmt: skip
            g0, g1, g2 = nx, ny, kb
            g3, g4, g5 = -nx, -ny, -ko
        elif k == CT:
            tx, ty = -f[6], f[5]
            g0, g1 = tx, ty
            g2 = f[7] * ty - f[8] * tx
            g3, g4 = -tx, -ty
            g5 = -(f[9] * ty - f[10] * tx)
        J[r, 3 * i], J[r, 3 * i + 1], J[r, 3 * i + 2] = g0, g1, g2
        if has:
            J[r, 3 * j], J[r, 3 * j + 1], J[r, 3 * j + 2] = g3, g4, g5
    return c, J


def _turned(X: np.ndarray, TH: np.ndarray, P: Plan, c: np.ndarray, J: np.ndarray) -> None:
    """The rows of a disc against a polygon that turns (``P.turned``, engine.exact.joint_contacts),
    rewritten in place in c and J: the disc's centre's distance from the polygon where it is
    now, less where the step began, plus the gap there. With d = x_disc - x_poly and the
    feature's outward normal m = R(theta) m_local:

    * a face, dist = m . d - m_local . v: d dist / d theta = m x d;
    * a corner v, e = d - R(theta) v, dist = |e|, m = e / |e|: d dist / d theta =
      -(R(theta) v) x m.

    The row's normal (from the other to the body) is m, or -m when the body is the polygon;
    its contact point is the disc's centre less its radius along m, which the slip row
    (along t = (-n_y, n_x)) turns about."""
    rows = P.turned
    has = P.has[rows]
    Xa, Xb = X[P.a[rows]], X[P.bc[rows]]
    ta = TH[P.a[rows]]
    tb = np.where(has, TH[P.bc[rows]], 0.0)
    mine = P.turn[rows] > 0  # the body is the polygon
    Xp = np.where(mine[:, None], Xa, Xb)
    Xd = np.where(mine[:, None], Xb, Xa)
    tp = np.where(mine, ta, tb)
    Rp = np.where(mine[:, None], P.refb[rows], P.refo[rows])
    Rd = np.where(mine[:, None], P.refo[rows], P.refb[rows])
    rp = np.where(mine, P.thb[rows], P.tho[rows])
    start = _local(Rd - Rp, rp)
    dist, mx, my, dth, dx, dy = _polygon(P, rows, Xd - Xp, tp, start)
    dist0 = _polygon(P, rows, Rd - Rp, rp, start)[0]
    sg = np.where(mine, -1.0, 1.0)
    nx, ny = sg * mx, sg * my
    rd = P.radius[rows]
    pdx, pdy = -rd * mx, -rd * my  # the contact point less the disc's centre
    ppx, ppy = dx + pdx, dy + pdy  # ... less the polygon's centre
    rbx, rby = np.where(mine, ppx, pdx), np.where(mine, ppy, pdy)
    rox, roy = np.where(mine, pdx, ppx), np.where(mine, pdy, ppy)
    normal = P.kind[rows] == CN
    g = np.zeros((6, len(rows)))
    c[rows[normal]] = (P.gap[rows] + dist - dist0)[normal]
    g[0], g[1], g[3], g[4] = nx, ny, -nx, -ny
    g[2] = np.where(mine, dth, 0.0)
    g[5] = np.where(mine, 0.0, dth)
    slip = ~normal
    tx, ty = -ny[slip], nx[slip]
    g[0, slip], g[1, slip] = tx, ty
    g[2, slip] = rbx[slip] * ty - rby[slip] * tx
    g[3, slip], g[4, slip] = -tx, -ty
    g[5, slip] = -(rox[slip] * ty - roy[slip] * tx)
    a3 = 3 * P.a[rows]
    J[rows, a3], J[rows, a3 + 1], J[rows, a3 + 2] = g[0], g[1], g[2]
    on = np.flatnonzero(has)
    b3 = 3 * P.b[rows[on]]
    J[rows[on], b3], J[rows[on], b3 + 1], J[rows[on], b3 + 2] = g[3, on], g[4, on], g[5, on]


def _local(d: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Vectors d (k, 2) in frames turned theta (k,): R(-theta) d."""
    cs, sn = np.cos(theta), np.sin(theta)
    return np.stack([cs * d[:, 0] + sn * d[:, 1], -sn * d[:, 0] + cs * d[:, 1]], 1)


def _polygon(
    P: Plan, rows: np.ndarray, d: np.ndarray, theta: np.ndarray, start: np.ndarray
) -> tuple[np.ndarray, ...]:
    """The disc's centre's distance from the polygon less the radii (its centre d from the
    polygon's, which is turned theta; ``start``: where the centre was in the polygon's frame
    as the step began), the feature's world normal (mx, my), d dist / d theta, and d
    (dx, dy)."""
    assert P.polygons is not None
    cs, sn = np.cos(theta), np.sin(theta)
    dx, dy = d[:, 0], d[:, 1]
    dist, m, corner, at = polygon_distance(P.polygons, P.poly[rows], _local(d, theta), start)
    mx, my = cs * m[:, 0] - sn * m[:, 1], sn * m[:, 0] + cs * m[:, 1]
    vx, vy = cs * at[:, 0] - sn * at[:, 1], sn * at[:, 0] + cs * at[:, 1]
    dth = np.where(corner, -(vx * my - vy * mx), mx * dy - my * dx)
    dist = dist - P.radius[rows] - P.polygons.radius[P.poly[rows]]
    return dist, mx, my, dth, dx, dy


def _sample_turned() -> tuple[object, ...]:
    """The smallest call of ``turned_loop``: a disc's two rows against a box that turns."""
    ints = np.array([[CN, 0, 1, 1, 0], [CT, 0, 1, 1, 0]], dtype=np.int64)
    floats = np.zeros((2, 19))
    floats[:, 18] = 0.1
    box = np.array([[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]])
    normals = np.array([[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]])
    X, TH = np.array([[0.0, 0.0], [0.0, 1.2]]), np.zeros(2)
    rows = np.array([0, 1], dtype=np.intp)
    count, rounding = np.array([4], dtype=np.intp), np.zeros(1)
    return X, TH, ints, floats, rows, box, normals, count, rounding, np.zeros(2), np.zeros((2, 6))


@kernels.loop(sample=_sample_turned)
def turned_loop(
    X: np.ndarray,
    TH: np.ndarray,
    ints: np.ndarray,
    floats: np.ndarray,
    rows: np.ndarray,
    V: np.ndarray,
    N: np.ndarray,
    count: np.ndarray,
    rounding: np.ndarray,
    c: np.ndarray,
    J: np.ndarray,
) -> None:
    """``_turned`` as a loop over its rows (``rows``: ``Plan.turned``), writing c and J in
    place: the twin's products in the twin's order, so the same bits (the polygons'
    vertices ``V``, normals ``N``, ``count`` and ``rounding``: ``Plan.polygons``')."""
    for r in rows:
        kind, i, j, turn, q = ints[r, 0], ints[r, 1], ints[r, 2], ints[r, 3], ints[r, 4]
        has = j >= 0
        jc = j if has else 0
        f = floats[r]
        ta = TH[i]
        tb = TH[jc] if has else 0.0
        mine = turn > 0  # the body is the polygon
        if mine:
            xp, yp, xd, yd, tp = X[i, 0], X[i, 1], X[jc, 0], X[jc, 1], ta
            rpx, rpy, rdx, rdy, rp = f[11], f[12], f[13], f[14], f[15]
        else:
            xp, yp, xd, yd, tp = X[jc, 0], X[jc, 1], X[i, 0], X[i, 1], tb
            rpx, rpy, rdx, rdy, rp = f[13], f[14], f[11], f[12], f[16]
        # start = _local(Rd - Rp, rp)
        ex, ey = rdx - rpx, rdy - rpy
        cs, sn = np.cos(rp), np.sin(rp)
        sx, sy = cs * ex + sn * ey, -sn * ex + cs * ey
        dist, mx, my, dth = _polygon_one(V[q], N[q], count[q], xd - xp, yd - yp, tp, sx, sy)
        dist0 = _polygon_one(V[q], N[q], count[q], ex, ey, rp, sx, sy)[0]
        radius = f[18]
        dist = dist - radius - rounding[q]
        dist0 = dist0 - radius - rounding[q]
        dx, dy = xd - xp, yd - yp
        sg = -1.0 if mine else 1.0
        nx, ny = sg * mx, sg * my
        pdx, pdy = -radius * mx, -radius * my  # the contact point less the disc's centre
        ppx, ppy = dx + pdx, dy + pdy  # ... less the polygon's centre
        rbx, rby = (ppx, ppy) if mine else (pdx, pdy)
        rox, roy = (pdx, pdy) if mine else (ppx, ppy)
        g0, g1, g3, g4 = nx, ny, -nx, -ny
        g2 = dth if mine else 0.0
        g5 = 0.0 if mine else dth
        if kind == CN:
            c[r] = f[17] + dist - dist0
        else:
            tx, ty = -ny, nx
            g0, g1 = tx, ty
            g2 = rbx * ty - rby * tx
            g3, g4 = -tx, -ty
            g5 = -(rox * ty - roy * tx)
        J[r, 3 * i], J[r, 3 * i + 1], J[r, 3 * i + 2] = g0, g1, g2
        if has:
            J[r, 3 * j], J[r, 3 * j + 1], J[r, 3 * j + 2] = g3, g4, g5


@kernels.helper
def _polygon_one(
    V: np.ndarray,
    N: np.ndarray,
    count: int,
    dx: float,
    dy: float,
    theta: float,
    sx: float,
    sy: float,
) -> tuple[float, float, float, float]:
    """``_polygon`` for one row (the distance before the radii are taken off): the disc's
    centre (dx, dy) from the polygon's, which is turned theta, and where it was in the
    polygon's frame as the step began (sx, sy)."""
    cs, sn = np.cos(theta), np.sin(theta)
    px, py = cs * dx + sn * dy, -sn * dx + cs * dy
    dist, m0, m1, corner, at0, at1 = _distance_one(V, N, count, px, py, sx, sy)
    mx, my = cs * m0 - sn * m1, sn * m0 + cs * m1
    vx, vy = cs * at0 - sn * at1, sn * at0 + cs * at1
    dth = -(vx * my - vy * mx) if corner else mx * dy - my * dx
    return dist, mx, my, dth


@kernels.helper
def _distance_one(
    V: np.ndarray, N: np.ndarray, count: int, px: float, py: float, sx: float, sy: float
) -> tuple[float, float, float, bool, float, float]:
    """engine.exact.joint_contacts.polygon_distance for one point (px, py) that came from
    (sx, sy), both in the polygon's frame, over all of its padded vertices as the twin's
    rows are: (distance, the feature's normal, whether a corner, the corner)."""
    M = V.shape[0]
    # Each face's separation s (its argmax f, the face nearest), and the path (sx, sy) ->
    # (px, py) clipped by each face's half-plane (Cyrus-Beck: s0 where it came from), in one
    # pass over the vertices.
    f, s_f = 0, -np.inf
    t_in, t_out, g, g_best, s_g = -np.inf, np.inf, 0, -np.inf, 0.0
    missed = False
    for m in range(M):
        s_m = N[m, 0] * (px - V[m, 0]) + N[m, 1] * (py - V[m, 1])
        s0 = N[m, 0] * (sx - V[m, 0]) + N[m, 1] * (sy - V[m, 1])
        if m == 0 or s_m > s_f:
            f, s_f = m, s_m
        t = s0 / (s0 - s_m if s0 != s_m else 1.0)
        enters = s0 > 0.0 and s_m <= 0.0
        if enters and t > t_in:
            t_in = t
        if s0 <= 0.0 and s_m > 0.0 and t < t_out:
            t_out = t
        if s0 > 0.0 and s_m > 0.0:
            missed = True
        w = t if enters else -np.inf
        if m == 0 or w > g_best:
            g, g_best, s_g = m, w, s_m
    f2 = (f + 1) % count
    v1x, v1y, v2x, v2y = V[f, 0], V[f, 1], V[f2, 0], V[f2, 1]
    before = (px - v1x) * (v2x - v1x) + (py - v1y) * (v2y - v1y) < 0.0
    past = (px - v2x) * (v1x - v2x) + (py - v2y) * (v1y - v2y) < 0.0
    corner = (s_f > 0.0) and (before or past)
    atx, aty = (v1x, v1y) if before else (v2x, v2y)
    ex, ey = px - atx, py - aty
    length = np.hypot(ex, ey)
    safe = length if length > 0.0 else 1.0
    if corner:
        nx, ny, dist = ex / safe, ey / safe, length
    else:
        nx, ny, dist = N[f, 0], N[f, 1], s_f
    crossed = (not missed) and t_in <= t_out and np.isfinite(t_in)
    if count == 2:
        # A capsule's core has no ends to clip by: within the segment?
        tt = t_in if np.isfinite(t_in) else 0.0
        qx, qy = sx + tt * (px - sx), sy + tt * (py - sy)
        g2 = (g + 1) % count
        ax, ay, bx, by = V[g, 0], V[g, 1], V[g2, 0], V[g2, 1]
        along = (qx - ax) * (bx - ax) + (qy - ay) * (by - ay)
        within = along >= 0.0 and along <= (bx - ax) * (bx - ax) + (by - ay) * (by - ay)
        crossed = crossed and within
    if crossed:
        dist, nx, ny, corner = s_g, N[g, 0], N[g, 1], False
    return dist, nx, ny, corner, atx, aty
