"""The soft step's rows of a point on a face that turns: taken again as the face turns.

The soft step's contact rows are linear in the step (engine.dynamics.solver, "Rows"): each
point's normal n and its anchors r_A, r_B are taken where the manifold found them at the
step's start, and the separation moves with the bodies from there. That holds while the
contact stays where it was on both bodies. It does not where a ball rides a bat that turns: the
ball slides along the bat's face while the face turns under it. The row then asks the bat's
point under the ball's start to move along the start's normal, where the bat's face under the
ball has turned and moves faster (omega times the farther lever). A ball flung out along a bar
that a game turns at 3 rad/s (a bead on a turning rod, below) fell 5.9% behind the closed form
in 1 s and sank 11 cm (56% of its radius) into the bar, at any number of substeps: each part
took the same step's rows. Nor does it where two boxes turn against each other (a tumbler's
pile, carried up a turning wall): a corner of one swings across the other's face, which turns
too, and the start's normal and anchors say less of where the corner is the more they turn.

**A face is a line fixed in its body.** Where the manifold's normal is a face's (a polygon's
edge, a capsule's side), the face's unit normal turns with its body, n(t) = R(dq_F) n0, and
every point of the face moves with its body. What meets it is a point of the other body's core
(a disc's centre; a polygon's corner, or a point of its edge, of a polygon or capsule's core
segment) and that body's rounding radius r (a disc's radius, a capsule's, a rounded polygon's;
0 for a box): the point of its surface nearest the face is c - r n(t) at any pose, however it
turns, while the same point meets the face. So the separation at any pose of the two bodies is
exact:

    s = n(t) . (c(t) - x_F(t)) - r - f0,    f0 = n0 . (F0 - x_F0),

with x_F the face body's position, F0 the face's point under the core point at the step's
start (the manifold's point less half the separation: engine.geometry.manifold's rows put the
point midway between the surfaces) and c(t) = x_R(t) + R(dq_R) e0, e0 the core point less its
body's position at the start (the point plus (s0 / 2 + r) n0, less that position). At the
start s = s0. A face on B (the point A's) is the same with n from A to B: the face's own
normal is -n, s = n(t) . (x_B(t) - c_A(t)) + f0 - r, f0 = n0 . (F0 - x_B0), F0 the point plus
s0 / 2 n0.

**The rows taken again.** After each substep's positions move (engine.dynamics.solver: before
the relax, and so for the next substep's warm start and solve, and the restitution after the
last), such a point's normal is n(t), its separation the one above, and its point the one
midway between the core point's surface and the face, where both anchors are taken from:
r = that point less each body's position now. Its masses along the normal and the tangent are
taken again with them, and a two-point manifold's 2 x 2 block (engine.dynamics.solver). The
impulses kept (the warm start) act along the row as it is. The rows are given back as they
were at the step's end (the events report the manifold's own).

Measured, a disc of 0.2 m on a bar of 0.1 m radius turning at 3 rad/s, frictionless, no
gravity, given 1 m/s outward at 1 m from the axis (a bead on a turning rod: it rides the bar's
leading face where 2 omega u' > omega^2 d, u the distance along the bar, d the disc's centre
off its line; along it u'' = omega^2 u, so u = u0 cosh(omega t) + u0' sinh(omega t) / omega):
after 1 s, 4 substeps, u 0.08% short of the closed form (5.9% before), its deepest overlap
43 mm (113 before); 16 substeps 0.02% and 11 mm (5.8% and 109 mm before). The overlap left
is the soft contact's: the load that turns the disc with the bar (2 omega u' m, 180 N here)
presses its spring, which pushes back at a bounded rate. A ball on a 9.8 m bat swung up by
its motor at 9 rad/s sank 21.5 cm (86% of its radius; 19 and 18 cm at 8 and 16 substeps),
and now 9.9 cm (5.3 and 3.0 cm; tests/test_fuzz_joints.py).

Two boxes tumbled in Box2D's drum (demos.stack's tumbler, 8 s, 4 substeps): 500 at 25
degrees a second, the deepest overlap 130 mm before, 82 mm now; at 90, 208 and 132 mm; 50 at
90, steps that ended with two boxes more than 50 mm into each other 216 of 480 before, 6 now
(tests/test_soft_continuous.py). What is left: boxes that meet spinning at 20 rad/s and more,
faster than the threshold below (an impact, whose rows stay), and the contacts' give under
the loads the turning walls put on the pile.

**Which rows.** ``face_rows``: a pair of two bodies (a static shape never turns), not two
discs, whose normal is one of a polygon's (or capsule's) edge normals turned to its angle (to
``ALIGNED``): its face; of two polygons, A's where both are (two faces flat on each other:
either gives the same separation at the start). The solver takes such a row again where the
point does not strike the face (engine.dynamics.solver): its points' normal speed at the
step's start closes at no more than the restitution threshold (1 m/s); from the first
substep after which its bodies have turned (``STILL``). A body that strikes
the face is an impact, which the rows take where it meets, as Box2D's do: its rows stay as they
are, so that an impact's closed form holds (a disc striking a box off its centre spins it as
the closed form says, to 1e-9: tests/test_rotation_shapes.py). ``ended_depth`` measures every
such row exactly at the step's end (engine.dynamics.game_continuous). A disc on a body's
corner or a capsule's end meets a round feature, whose normal turns with neither body, and a
corner on a corner no face: their rows are as before (but against a static shape: below).
The face is a line: a point that slides past its end within the step is taken on the line's
extension (a step's slide). While any body of the World has several shapes
(``Body(shapes=[...])``) no row is taken again (a pair's parts are not known on the numpy
path's rows): the rows are as before.

**Round features.** A disc passing a static shape's corner, a capsule's end or a circle
collider meets a round feature: the separation is the distance from the disc's centre to the
nearest point of the shape's core (the corner, the circle's centre, the capsule's core segment)
less both roundings, and the normal is the line between them, which turns as the disc goes by.
The rows at the step's start take that line where it was: a ball rising past the end of a wall
beside its path closes on the start's line faster than the gap allows, where the true line
turns away from it as the ball passes, and the row stops it, a contact nothing touched (a
ghost; Box2D's speculative rows have it too). Where the nearest point is on a capsule's side,
the row is the side's line, which goes on past the end: a ball that passes the end is stopped
by the line's extension. Measured on the pinball's shooter lane in the table's units
(demos.pinball, ``World(length_units_per_meter=100)``, so the speculative rows reach 2 cm): the
ball shot up the lane, 1 mm from the inlane guide's end and 5 mm (through the lane's wall) from
the right slingshot's top end, was thrown 104 cm/s sideways at the guide, at every shot, and
the game never left the lane. So a disc's row with a static shape that is no half plane and
whose normal is not one of a polygon's faces (``ROUND``: a corner, a circle collider), or with
a static capsule on its side or its end (``SEGMENT``: its whole core segment, two-sided), is
taken again as the disc moves: its normal the line from the disc's centre to the nearest point
of that core, its separation that distance less the two roundings (``round_gap``), from the
first substep after which the line has turned by ``STILL`` (a disc at rest by a corner or on a
capsule's side keeps the rows of its start), whatever the disc's speed (the line where they
meet is an impact's own). The ball now flies up the lane as it would alone, to 1e-9
(tests/test_turning_faces.py), and the game plays. A polygon's face stays as it was (one-sided:
its rows at the start are exact for its line), and two bodies' round features too (the pit's
discs).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import kernels

__all__ = [
    "ALIGNED", "FACE_A", "FACE_B", "FACE_NUMBERS", "ROUND", "SEGMENT", "STILL", "face_gap",
    "face_rows", "face_start", "round_gap", "round_start",
]  # fmt: skip

#: A row's normal is a face's where it and the face's edge normal agree to this (their dot
#: product at least 1 - ALIGNED): a disc's manifold on a face gives the face's normal, turned,
#: to rounding.
ALIGNED = 1e-9
#: A face's rows are taken again from the first substep after which its two bodies have turned
#: by this since the step began, together (|dq_A| + |dq_B|, rad): till then the rows fixed at
#: the start are off by about its square times a lever, and by the slide along the face times
#: it (a pile at rest, or rising back at a few cm/s under its held loads, keeps its cheaper
#: rows: the pyramid of 210 boxes took 30% longer a step with every row taken again from the
#: first substep).
STILL = 1e-4
#: ``face_rows``' kinds: the normal turns with body A (the face is A's, the point B's), or with B;
#: or it is the line from a disc's centre to the nearest point of a static shape's core: a
#: point (a corner, a circle's centre) or a segment (a capsule's core) (module doc, "Round
#: features").
FACE_A = 1
FACE_B = 2
ROUND = 3
SEGMENT = 4
#: The numbers ``face_rows`` gives each row (``numbers``): the rounding of the body whose point
#: meets the face (a ROUND or SEGMENT row's disc's radius), the static shape's rounding, and a
#: SEGMENT row's core segment's two ends (m, the world's axes).
FACE_NUMBERS = 6


def _sample() -> tuple[Any, ...]:
    """The smallest call of ``face_rows``: a disc (row 1) on a unit box (row 0), and the disc
    by the corner of a static box (place 0, polygon 1 of the tables)."""
    i64 = np.int64
    box = np.array([[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]] * 2)
    return (
        np.array([0, 1], dtype=i64), np.array([1, 2], dtype=i64), np.array([0.0, 0.6]),
        np.array([1.0, 0.8]), 2, False, np.zeros(2), np.array([False, True]),
        np.array([0, 0], dtype=i64), np.array([[0, 1], [1, 1]], dtype=i64), box,
        np.array([4, 4], dtype=i64), np.array([0.0, 0.0]), np.array([0.25]),
        np.array([-1, 0], dtype=i64), np.array([False]), np.array([1], dtype=i64), box * 0.5,
    )  # fmt: skip


@kernels.loop(sample=_sample)
def face_rows(
    ca: Any, cb: Any, nx: Any, ny: Any, n: int, several: bool, angle: Any, body_circle: Any,
    body_index: Any, body_parts: Any, Nrm: Any, cnt: Any, prad: Any, rnd: Any, place: Any,
    static_circle: Any, static_index: Any, V: Any,
) -> tuple[Any, Any]:  # fmt: skip
    """Each contact row's face (module doc): 0, or FACE_A where its normal turns with body A
    (a face of A, the point B's), FACE_B with B, ROUND or SEGMENT where it is the line from
    a disc's centre to the nearest point of a static shape's core (a corner or a circle's
    centre; a capsule's core segment); and ``FACE_NUMBERS`` numbers a row (at FACE_NUMBERS k for row
    k): the rounding radius of the body whose point meets the face (m: a disc's radius, a
    capsule's, a rounded polygon's; 0 for none), the static shape's, and a SEGMENT row's
    core segment's ends (m).

    Rows (engine.dynamics.solver.solve's): bodies ``ca``, ``cb`` (rows; ``n`` or more: a
    static shape, its ``place`` among the static shapes; -1 for a pair of bodies), the unit
    normal ``nx``, ``ny`` from A to B. Bodies (``n``; ``several``: one of them has several
    shapes, and no row is taken again): ``angle`` (rad); each body's first part and count
    ``body_parts`` (n, 2), each part's shape (``body_circle``, ``body_index`` in the tables:
    engine.geometry.narrowphase.Places), and each static shape's (``static_circle``,
    ``static_index``: a half plane's < 0); the tables' polygon corners ``V`` and normals
    ``Nrm`` (P, M, 2, a static one's in the world's axes), counts ``cnt`` and radii
    ``prad``, the circles' radii ``rnd``."""
    m = len(ca)
    face = np.zeros(m, dtype=np.int64)
    numbers = np.zeros(FACE_NUMBERS * m)
    # Each body's angle's cosine and sine, once (a pile's rows share their bodies).
    cos_q = np.empty(n if m and not several else 0)
    sin_q = np.empty(n if m and not several else 0)
    for i in range(len(cos_q)):
        cos_q[i] = math.cos(angle[i])
        sin_q[i] = math.sin(angle[i])
    for k in range(m if not several else 0):
        a = ca[k]
        b = cb[k]
        if b >= n:
            # A static shape never turns; a disc against its corner, a capsule's end or a
            # circle collider meets a round feature (module doc, "Round features").
            s = place[k]
            if s < 0 or not body_circle[body_parts[a, 0]] or static_index[s] < 0:
                continue  # (a half plane's normal is its own)
            j = static_index[s]
            f = FACE_NUMBERS * k
            if static_circle[s]:
                face[k] = ROUND
                numbers[f + 1] = rnd[j]
            elif cnt[j] == 2:
                face[k] = SEGMENT
                numbers[f + 1] = prad[j]
                numbers[f + 2], numbers[f + 3] = V[j, 0, 0], V[j, 0, 1]
                numbers[f + 4], numbers[f + 5] = V[j, 1, 0], V[j, 1, 1]
            elif _faces_along(Nrm, cnt, j, 1.0, 0.0, -nx[k], -ny[k]):
                continue  # (a polygon's face: one-sided; its rows at the start are exact)
            else:
                face[k] = ROUND
                numbers[f + 1] = prad[j]
            numbers[f] = rnd[body_index[body_parts[a, 0]]]
            continue
        a_round = body_circle[body_parts[a, 0]]
        b_round = body_circle[body_parts[b, 0]]
        if a_round and b_round:
            continue  # (two discs: no face)
        if not a_round and not b_round:
            # Two polygons (capsules among them): the face is the one whose edge normal the
            # row's normal is, A's first (two faces flat on each other give both; either
            # gives the same separation at the start), the point the other's.
            ia = body_index[body_parts[a, 0]]
            ib = body_index[body_parts[b, 0]]
            if _faces_along(Nrm, cnt, ia, cos_q[a], sin_q[a], nx[k], ny[k]):
                face[k] = FACE_A
                numbers[FACE_NUMBERS * k] = prad[ib]
            elif _faces_along(Nrm, cnt, ib, cos_q[b], sin_q[b], -nx[k], -ny[k]):
                face[k] = FACE_B
                numbers[FACE_NUMBERS * k] = prad[ia]
            continue
        # The polygon's edge normals turned to its angle, against the normal from it to the
        # disc: n where the face is A's, -n where it is B's.
        poly, disc, sign = (a, b, 1.0) if b_round else (b, a, -1.0)
        j = body_index[body_parts[poly, 0]]
        if _faces_along(Nrm, cnt, j, cos_q[poly], sin_q[poly], sign * nx[k], sign * ny[k]):
            face[k] = FACE_A if b_round else FACE_B
            numbers[FACE_NUMBERS * k] = rnd[body_index[body_parts[disc, 0]]]
    return face, numbers


@kernels.helper
def _faces_along(
    Nrm: Any, cnt: Any, j: int, c: float, s: float, tx: float, ty: float
) -> bool:  # fmt: skip
    """Whether one of polygon ``j``'s edge normals (the tables' ``Nrm``, ``cnt``), turned to
    the angle whose cosine and sine are ``c``, ``s``, is the unit vector (``tx``, ``ty``) to
    ``ALIGNED``."""
    for e in range(cnt[j]):
        wx = c * Nrm[j, e, 0] - s * Nrm[j, e, 1]
        wy = s * Nrm[j, e, 0] + c * Nrm[j, e, 1]
        if wx * tx + wy * ty >= 1.0 - ALIGNED:
            return True
    return False


@kernels.helper
def face_start(
    face: int, nx: float, ny: float, rax: float, ray: float, rbx: float, rby: float, sep: float,
    r: float,
) -> tuple[float, float, float]:  # fmt: skip
    """A point on a face that turns, at the step's start (module doc): the core point less
    its body's position (m, the world's axes) and the face's offset f0 (m), of the row's kind
    ``face`` (FACE_A or FACE_B), normal ``nx``, ``ny`` from A to B, anchors (m, the point less
    each body's position: midway between the surfaces), separation ``sep`` (m) and the
    rounding radius ``r`` (m) of the body whose point it is."""
    half = 0.5 * sep
    if face == FACE_A:
        return rbx + (half + r) * nx, rby + (half + r) * ny, (nx * rax + ny * ray) - half
    return rax - (half + r) * nx, ray - (half + r) * ny, (nx * rbx + ny * rby) + half


@kernels.helper
def face_gap(
    face: int, n0x: float, n0y: float, ox: float, oy: float, cf: float, sf: float, cr: float,
    sr: float, ex: float, ey: float, r: float, f0: float,
) -> tuple[float, float, float, float, float]:  # fmt: skip
    """A point's separation now (m) on a face that turns (module doc), its normal now (from A
    to B) and the core point less its body's position now (m): ``face`` FACE_A or FACE_B;
    the normal ``n0x``, ``n0y`` at the step's start; B's position less A's now ``ox``, ``oy``
    (m); cos and sin of the face body's turn since the start ``cf``, ``sf`` and the point
    body's ``cr``, ``sr``; the core point less its body's position at the start ``ex``,
    ``ey`` (m, the world's axes); its rounding radius ``r`` (m); ``f0`` the face's offset
    (module doc, m)."""
    nx = cf * n0x - sf * n0y
    ny = sf * n0x + cf * n0y
    wx = cr * ex - sr * ey
    wy = sr * ex + cr * ey
    if face == FACE_A:
        return nx * (ox + wx) + ny * (oy + wy) - r - f0, nx, ny, wx, wy
    return nx * (ox - wx) + ny * (oy - wy) + f0 - r, nx, ny, wx, wy


@kernels.helper
def round_start(
    face: int, nx: float, ny: float, rax: float, ray: float, rbx: float, rby: float,
    sep: float, ra: float, rb: float, s1x: float, s1y: float, s2x: float, s2y: float,
) -> tuple[float, float, float, float, float, float]:  # fmt: skip
    """A point between a disc and a static shape's round feature at the step's start (module
    doc, "Round features"): the disc's centre less A's position, then the two ends of B's core
    less B's position (the same point twice for a ROUND row) (m, the world's axes), from the
    row's kind ``face`` (ROUND or SEGMENT), normal ``nx``, ``ny`` from A to B, anchors (m, the
    point less each body's position: midway between the surfaces), separation ``sep`` (m),
    the two roundings ``ra``, ``rb`` (m) and, for a SEGMENT row, its core segment's ends
    ``s1x`` ... ``s2y`` less B's position (m; a ROUND row's centre is found from the point)."""
    half = 0.5 * sep
    if face == SEGMENT:
        return rax - (half + ra) * nx, ray - (half + ra) * ny, s1x, s1y, s2x, s2y
    cx = rbx + (half + rb) * nx
    cy = rby + (half + rb) * ny
    return rax - (half + ra) * nx, ray - (half + ra) * ny, cx, cy, cx, cy


@kernels.helper
def round_gap(
    n0x: float, n0y: float, ox: float, oy: float, ca: float, sa: float, cb: float, sb: float,
    eax: float, eay: float, e1x: float, e1y: float, e2x: float, e2y: float, ra: float,
    rb: float,
) -> tuple[float, float, float, float, float]:  # fmt: skip
    """A point's separation now (m) between a disc and the nearest point of a static
    shape's core (module doc, "Round features"), its normal now (from A to B; ``n0x``,
    ``n0y``, the start's, where the two meet) and A's centre less A's position now (m): B's
    position less A's now ``ox``, ``oy`` (m); cos and sin of each body's turn since the start
    ``ca``, ``sa``, ``cb``, ``sb``; A's centre less its position at the start ``eax``,
    ``eay`` and the ends of B's core segment less B's (``e1x`` ... ``e2y``, the same point
    twice for a point) (m, the world's axes); the roundings ``ra``, ``rb`` (m)."""
    wax = ca * eax - sa * eay
    way = sa * eax + ca * eay
    p1x = ox + (cb * e1x - sb * e1y) - wax
    p1y = oy + (sb * e1x + cb * e1y) - way
    ux = cb * (e2x - e1x) - sb * (e2y - e1y)
    uy = sb * (e2x - e1x) + cb * (e2y - e1y)
    # The segment's point nearest A's centre (the origin here): p1 + t u, t in [0, 1].
    uu = ux * ux + uy * uy
    t = 0.0
    if uu > 0.0:
        t = min(max(-(p1x * ux + p1y * uy) / uu, 0.0), 1.0)
    dx = p1x + t * ux
    dy = p1y + t * uy
    d = math.sqrt(dx * dx + dy * dy)
    if d == 0.0:
        return -ra - rb, n0x, n0y, wax, way
    return d - ra - rb, dx / d, dy / d, wax, way
