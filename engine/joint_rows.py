"""The joint solver's rows (engine.joint_solver): each a scalar equation c(q) on the positions
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
  wherever it turns, engine.joint_contacts), and the slip of its points along the tangent
  (speeds only).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .joint_contacts import polygon_distance
from .manifold_kinds import Polygons

__all__ = [
    "Touch", "Plan", "evaluate", "PX", "PY", "DIST", "ANGLE", "MOTOR", "SOFT_X", "SOFT_Y",
    "SOFT_ANGLE", "CN", "CT",
]  # fmt: skip

# Row kinds.
PX, PY, DIST, ANGLE, MOTOR, SOFT_X, SOFT_Y, SOFT_ANGLE, CN, CT = range(10)


class Touch(NamedTuple):
    """Contacts of the joints' bodies as the step ends, one a row: the body (World row), the
    other (World row; -1: the static world), the unit normal from the other to the body, the
    contact point less each one's centre (``r_body``, ``r_other``; length units), the gap
    (length units; what the correction may not close), friction (both materials'), the
    impulse the contact gave in the step along n and along t = (-n_y, n_x) (N s), and
    ``lift``: a disc resting on a collider (engine.contacts: the joints may take back its
    contact's impulse, it may lift) or a contact of the pile (engine.pile: it only pushes,
    and only where the two touch as the step ends or met in it). ``turn``
    (engine.joint_contacts): 0, a row linear about where the step left the two; +1 (-1), the
    body (the other) is a polygon or a capsule, ``poly`` in engine.joint_contacts.shapes_of,
    and the other end a disc
    of ``radius``, its row exact wherever the polygon turns; its gap is then the one at the
    step's start. ``restitution``: a contact of
    the pile's bounces by it where the joints' solve catches it closing (a disc resting on
    a collider: 0, its contact's own bounce is engine.contacts')."""

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
    """Rows as arrays by row (engine.joint_solver's own): kind, bound, each end's place among
    the joints' bodies (b: -1 for the world), anchors, and a resting disc's normal, point,
    gap and radius; the kinds' row indices and the columns of J, made once."""

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
        self.kind, self.bound, self.a, self.b = kind, bound, a, b
        self.aa, self.ab = aa, ab
        # A contact row's normal, contact points less the centres, where the body and the
        # other were (position, angle) as the step ended (began, for a disc and a polygon),
        # its gap, and a disc and a polygon's (Touch.turn, poly, radius).
        self.touch = touch
        self.n, self.rbod, self.roth, self.refb, self.refo, self.thb, self.tho, self.gap = touch[:8]
        self.turn, self.poly, self.radius = touch[8:]
        self.polygons = polygons
        self.width = width
        self.has = b >= 0
        self.bc = np.maximum(b, 0)
        self.px = np.flatnonzero((kind == PX) | (kind == SOFT_X))
        self.py = np.flatnonzero((kind == PY) | (kind == SOFT_Y))
        self.dist = np.flatnonzero(kind == DIST)
        self.ang = np.flatnonzero((kind == ANGLE) | (kind == SOFT_ANGLE) | (kind == MOTOR))
        self.cn = np.flatnonzero(kind == CN)
        self.ct = np.flatnonzero(kind == CT)
        self.r = np.arange(len(kind))
        self.a3 = 3 * a
        self.rb = np.flatnonzero(self.has)
        self.b3 = 3 * b[self.rb]

    def take(self, sel: np.ndarray) -> Plan:
        """The rows ``sel`` alone."""
        return Plan(
            self.kind[sel], self.bound[sel], self.a[sel], self.b[sel], self.aa[sel],
            self.ab[sel], tuple(t[sel] for t in self.touch), self.width, self.polygons,
        )  # fmt: skip


def evaluate(X: np.ndarray, TH: np.ndarray, P: Plan) -> tuple[np.ndarray, np.ndarray]:
    """Each row's value c and gradient J (rows, 3 m) at the joints' bodies' positions X
    (m, 2) and angles TH (m,)."""
    ta = TH[P.a]
    ca, sa = np.cos(ta), np.sin(ta)
    ax, ay = P.aa[:, 0], P.aa[:, 1]
    rax, ray = ca * ax - sa * ay, sa * ax + ca * ay
    tb = np.where(P.has, TH[P.bc], 0.0)
    cb, sb = np.cos(tb), np.sin(tb)
    bx, by = P.ab[:, 0], P.ab[:, 1]
    rbx = np.where(P.has, cb * bx - sb * by, 0.0)
    rby = np.where(P.has, sb * bx + cb * by, 0.0)
    Xa, Xb = X[P.a], X[P.bc]
    dx = Xa[:, 0] + rax - np.where(P.has, Xb[:, 0] + rbx, bx)
    dy = Xa[:, 1] + ray - np.where(P.has, Xb[:, 1] + rby, by)
    R = len(P.kind)
    c = np.zeros(R)
    g = np.zeros((6, R))  # the gradient: (x, y, theta) on body_a, then on body_b
    q = P.px
    c[q] = dx[q]
    g[0, q], g[2, q], g[3, q], g[5, q] = 1.0, -ray[q], -1.0, rby[q]
    q = P.py
    c[q] = dy[q]
    g[1, q], g[2, q], g[4, q], g[5, q] = 1.0, rax[q], -1.0, -rbx[q]
    q = P.dist
    if len(q):
        length = np.hypot(dx[q], dy[q])
        safe = np.where(length > 0.0, length, 1.0)
        nx, ny = dx[q] / safe, dy[q] / safe
        c[q] = length - P.bound[q]
        g[0, q], g[1, q], g[2, q] = nx, ny, rax[q] * ny - ray[q] * nx
        g[3, q], g[4, q], g[5, q] = -nx, -ny, rby[q] * nx - rbx[q] * ny
    q = P.ang
    if len(q):
        c[q] = ta[q] - tb[q] - P.bound[q]
        g[2, q], g[5, q] = 1.0, -1.0
    q = np.concatenate([P.cn, P.ct])
    if len(q):
        _contacts(q, X, TH, Xa, Xb, tb, P, c, g)
    J = np.zeros((R, P.width))
    r = P.r
    J[r, P.a3], J[r, P.a3 + 1], J[r, P.a3 + 2] = g[0], g[1], g[2]
    rb, b3 = P.rb, P.b3
    J[rb, b3], J[rb, b3 + 1], J[rb, b3 + 2] = g[3, rb], g[4, rb], g[5, rb]
    return c, J


# -- the step ------------------------------------------------------------------------


def _contacts(
    q: np.ndarray,
    X: np.ndarray,
    TH: np.ndarray,
    Xa: np.ndarray,
    Xb: np.ndarray,
    tb: np.ndarray,
    P: Plan,
    c: np.ndarray,
    g: np.ndarray,
) -> None:
    """The contact rows ``q`` (P.cn then P.ct) of ``evaluate``: values into c, gradients
    into g."""
    k = len(P.cn)
    cn, ct = q[:k], q[k:]
    nx, ny = P.n[q, 0], P.n[q, 1]  # (indexed by an array: copies, written below)
    rbx, rby = P.rbod[q, 0], P.rbod[q, 1]
    rox, roy = P.roth[q, 0], P.roth[q, 1]
    # A row linear about where the step left the two (the body, a; the other, b): its gap
    # along the normal, which the correction may not close.
    kb = rbx[:k] * ny[:k] - rby[:k] * nx[:k]  # r x n, the body's lever
    ko = rox[:k] * ny[:k] - roy[:k] * nx[:k]
    on = P.has[cn]
    c[cn] = (
        P.gap[cn]
        + (Xa[cn, 0] - P.refb[cn, 0]) * nx[:k] + (Xa[cn, 1] - P.refb[cn, 1]) * ny[:k]
        + kb * (TH[P.a[cn]] - P.thb[cn])
        - np.where(on, (Xb[cn, 0] - P.refo[cn, 0]) * nx[:k]
                   + (Xb[cn, 1] - P.refo[cn, 1]) * ny[:k] + ko * (tb[cn] - P.tho[cn]), 0.0)
    )  # fmt: skip
    g[0, cn], g[1, cn], g[2, cn] = nx[:k], ny[:k], kb
    g[3, cn], g[4, cn], g[5, cn] = -nx[:k], -ny[:k], -ko
    shaped = np.flatnonzero(P.turn[q] != 0)
    if len(shaped) and P.polygons is not None:
        # A disc against a polygon (engine.joint_contacts): the disc's centre's distance from
        # the polygon where it is now, less where the step began, plus the gap there. With
        # d = x_disc - x_poly and the feature's outward normal m = R(theta) m_local:
        #   a face, dist = m . d - m_local . v: d dist / d theta = m x d;
        #   a corner v, e = d - R(theta) v, dist = |e|, m = e / |e|: d dist / d theta =
        #   -(R(theta) v) x m.
        # The row's normal (from the other to the body) is m, or -m when the body is the
        # polygon; its contact point is the disc's centre less its radius along m.
        rows = q[shaped]
        mine = P.turn[rows] > 0  # the body is the polygon
        Xp = np.where(mine[:, None], Xa[rows], Xb[rows])
        Xd = np.where(mine[:, None], Xb[rows], Xa[rows])
        tp = np.where(mine, TH[P.a[rows]], tb[rows])
        Rp = np.where(mine[:, None], P.refb[rows], P.refo[rows])
        Rd = np.where(mine[:, None], P.refo[rows], P.refb[rows])
        rp = np.where(mine, P.thb[rows], P.tho[rows])
        start = _local(Rd - Rp, rp)
        dist, mx, my, dth, dx, dy = _polygon(P, rows, Xd - Xp, tp, start)
        dist0 = _polygon(P, rows, Rd - Rp, rp, start)[0]
        sg = np.where(mine, -1.0, 1.0)
        nx[shaped], ny[shaped] = sg * mx, sg * my
        rd = P.radius[rows]
        pdx, pdy = -rd * mx, -rd * my  # the contact point less the disc's centre
        ppx, ppy = dx + pdx, dy + pdy  # ... less the polygon's centre
        rbx[shaped] = np.where(mine, ppx, pdx)
        rby[shaped] = np.where(mine, ppy, pdy)
        rox[shaped] = np.where(mine, pdx, ppx)
        roy[shaped] = np.where(mine, pdy, ppy)
        normal = shaped < k
        r_n = rows[normal]
        c[r_n] = (P.gap[rows] + dist - dist0)[normal]
        g[0, r_n], g[1, r_n] = nx[shaped][normal], ny[shaped][normal]
        g[3, r_n], g[4, r_n] = -nx[shaped][normal], -ny[shaped][normal]
        g[2, r_n] = np.where(mine, dth, 0.0)[normal]
        g[5, r_n] = np.where(mine, 0.0, dth)[normal]
    # The slip of its points along t = (-n_y, n_x) (velocity only).
    tx, ty = -ny[k:], nx[k:]
    g[0, ct], g[1, ct] = tx, ty
    g[2, ct] = rbx[k:] * ty - rby[k:] * tx
    g[3, ct], g[4, ct] = -tx, -ty
    g[5, ct] = -(rox[k:] * ty - roy[k:] * tx)


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
