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
  where the step left the two, and the slip of its points along the tangent (speeds only).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

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
    and only while the two close)."""

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
    ) -> None:
        self.kind, self.bound, self.a, self.b = kind, bound, a, b
        self.aa, self.ab = aa, ab
        # A contact row's normal, contact points less the centres, where the body and the
        # other were (position, angle) as the step ended, and its gap.
        self.touch = touch
        self.n, self.rbod, self.roth, self.refb, self.refo, self.thb, self.tho, self.gap = touch
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
            self.ab[sel], tuple(t[sel] for t in self.touch), self.width,
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
    q = P.cn
    if len(q):
        # A contact: its gap along the normal, linear about where the step left the two
        # (the body, a; the other, b), which the correction may not close; and the slip
        # of its points along t (velocity only).
        nx, ny = P.n[q, 0], P.n[q, 1]
        kb = P.rbod[q, 0] * ny - P.rbod[q, 1] * nx  # r x n, the body's lever
        ko = P.roth[q, 0] * ny - P.roth[q, 1] * nx
        on = P.has[q]
        c[q] = (
            P.gap[q]
            + (Xa[q, 0] - P.refb[q, 0]) * nx + (Xa[q, 1] - P.refb[q, 1]) * ny
            + kb * (TH[P.a[q]] - P.thb[q])
            - np.where(on, (Xb[q, 0] - P.refo[q, 0]) * nx + (Xb[q, 1] - P.refo[q, 1]) * ny
                       + ko * (tb[q] - P.tho[q]), 0.0)
        )  # fmt: skip
        g[0, q], g[1, q], g[2, q] = nx, ny, kb
        g[3, q], g[4, q], g[5, q] = -nx, -ny, -ko
    q = P.ct
    if len(q):
        tx, ty = -P.n[q, 1], P.n[q, 0]
        g[0, q], g[1, q] = tx, ty
        g[2, q] = P.rbod[q, 0] * ty - P.rbod[q, 1] * tx
        g[3, q], g[4, q] = -tx, -ty
        g[5, q] = -(P.roth[q, 0] * ty - P.roth[q, 1] * tx)
    J = np.zeros((R, P.width))
    r = P.r
    J[r, P.a3], J[r, P.a3 + 1], J[r, P.a3 + 2] = g[0], g[1], g[2]
    rb, b3 = P.rb, P.b3
    J[rb, b3], J[rb, b3 + 1], J[rb, b3 + 2] = g[3, rb], g[4, rb], g[5, rb]
    return c, J


# -- the step ------------------------------------------------------------------------
