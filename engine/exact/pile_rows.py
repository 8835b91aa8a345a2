"""A pile's rows: what the soft step of a pile (engine.exact.pile) is given and what it leaves.

``step_pile`` assembles its rows from the bodies and faces, warm starts them from the last
step's impulses by key, and afterwards asks which contacts held. Each part here is a numpy
twin (arrays at once) beside its loop kernel (engine.kernels: the fast path, row by row,
compiled by numba), the same algorithm giving the same numbers bit for bit:

* ``disc_rows``: pairs of discs: the unit normal from A to B, the gap, friction mu_a mu_b,
  restitution e_a e_b, the slop and the key a * base + b;
* ``face_rows``: each solid face within reach of a disc: its normal toward the disc, the gap
  from the face grown by the radius, the face's friction;
* ``warm_start``: each row's impulses and colour of the last step, found by its key in the
  sorted keys carried (``Carried``; a binary search, as searchsorted);
* ``held``: after the step, which pairs touch or pressed, which are near enough for sleep to
  join, and every row's gap now;
* ``turning`` and ``lever_arms``: the discs of the pile that turn, and the rows' lever arms
  for them (engine.exact.soft, ``Arms``), the same array calls on both paths.

The kernels do their twin's products and sums in the same order (a - b - c as (a - b) - c, a
dot as x x' + y y', nothing fused), so the two paths give the same bits.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .. import kernels
from ..geometry.faces import face_normals
from ..geometry.impact import TOUCH
from ..geometry.pair_math import SLOP, dot, norm, unit
from .soft import Arms

if TYPE_CHECKING:
    from ..dynamics.rotation import Spin
    from .contacts import Contacts

__all__ = [
    "Carried",
    "Turning",
    "disc_rows",
    "face_rows",
    "held",
    "lever_arms",
    "shape_arms",
    "turning",
    "warm_start",
]


class Carried(NamedTuple):
    """The impulses a pile's contacts carry from one step to the next (the warm start)."""

    #: Each row's key (sorted): a * base + b for a pair, a * base + n + f for a face.
    keys: np.ndarray
    #: (normal, tangent) impulse of each row over the whole step, shape (rows, 2).
    lam: np.ndarray
    #: The step they were taken over (s).
    lam_dt: float
    #: The base of the keys: bodies and faces then.
    base: int
    #: Keys of the rows whose colours are kept (sorted), and the colours.
    color_keys: np.ndarray
    colors: np.ndarray


def disc_rows(
    pa: np.ndarray,
    pb: np.ndarray,
    la: np.ndarray,
    lb: np.ndarray,
    X: np.ndarray,
    r: np.ndarray,
    mu: np.ndarray,
    e: np.ndarray,
    base: int,
    fast: bool = False,
) -> tuple[np.ndarray, ...]:
    """The rows of pairs of discs (World rows pa < pb; la, lb their places in the pile's
    X (positions at the step's start, length units), r (radii), mu and e): (unit normal from
    A to B (m, 2), gap (length units), friction, restitution, slop (length units), key
    a * base + b). ``fast``: the loop kernel ``disc_loop``."""
    if fast:
        return disc_loop(pa, pb, la, lb, X, r, mu, e, base)  # type: ignore[no-any-return]
    d = X[lb] - X[la]
    dist = norm(d)
    nrm = unit(d, dist)
    sep = dist - r[la] - r[lb]
    slop = SLOP * np.minimum(r[la], r[lb])
    return nrm, sep, mu[la] * mu[lb], e[la] * e[lb], slop, pa.astype(np.int64) * base + pb


def warm_start(
    carried: Carried, key: np.ndarray, base: int, dt: float, iterations: int, fast: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Each row's (``key``) warm start: the impulses its key carried from the last step, a
    part's share of them, (rows, 2); and the colour it kept (-1: none). Nothing is carried
    across a change of ``base`` (bodies or faces added). ``fast``: the loop kernel
    ``carry_in``."""
    carry = len(carried.keys) > 0 and base == carried.base
    color = len(carried.color_keys) > 0 and base == carried.base
    if fast:
        scale = dt / (carried.lam_dt * iterations) if carry else 0.0
        z, zi = np.zeros(0, dtype=np.int64), np.zeros((0, 2))
        return carry_in(  # type: ignore[no-any-return]
            key,
            carried.keys if carry else z,
            carried.lam if carry else zi,
            scale,
            carried.color_keys if color else z,
            carried.colors if color else z,
            carry and color and carried.color_keys is carried.keys,
        )
    lam = np.zeros((len(key), 2))
    if carry:
        pos = np.minimum(np.searchsorted(carried.keys, key), len(carried.keys) - 1)
        same = carried.keys[pos] == key
        lam[same] = carried.lam[pos[same]] * (dt / (carried.lam_dt * iterations))
    prior = np.full(len(key), -1, dtype=np.int64)
    if color:
        pos = np.minimum(np.searchsorted(carried.color_keys, key), len(carried.color_keys) - 1)
        same = carried.color_keys[pos] == key
        prior[same] = carried.colors[pos[same]]
    return lam, prior


def held(
    X: np.ndarray,
    X0: np.ndarray,
    la: np.ndarray,
    lb: np.ndarray,
    r: np.ndarray,
    ra: np.ndarray,
    rb: np.ndarray,
    nv: np.ndarray,
    sep: np.ndarray,
    slop: np.ndarray,
    total: np.ndarray,
    fast: bool = False,
) -> tuple[np.ndarray, ...]:
    """Which contacts hold after the soft step moved the pile from X0 to X (length units):
    (the disc pairs (la, lb) touching or pressed, those near enough for sleep to join, every
    row's (ra, rb; normal nv, gap sep at the start) gap now, the rows touching or pressed).
    ``slop`` and ``total`` (each row's impulse) as the soft step had them; the static slot
    (len(X)) does not move. ``fast``: the loop kernel ``held_loop``."""
    if fast:
        return held_loop(X, X0, la, lb, r, ra, rb, nv, sep, slop, total)  # type: ignore[no-any-return]
    gap = norm(X[lb] - X[la]) - r[la] - r[lb]
    touch = gap <= SLOP * np.minimum(r[la], r[lb]) + TOUCH
    hold = touch | (total[: len(la)] > 0.0)
    # Sleep joins bodies as near as engine.exact.sleep.wake_met wakes them by: a group falls asleep
    # whole, or a body left awake beside it would wake it again at once.
    near = gap <= 0.05 * np.minimum(r[la], r[lb])
    # Every other row's gap now: its gap at the start plus the bodies' moves along it.
    moved = np.append(X - X0, [[0.0, 0.0]], axis=0)
    now = sep + dot(moved[rb] - moved[ra], nv)
    held_rows = (now <= slop + TOUCH) | (total > 0.0)
    return hold, near, now, held_rows


def face_rows(
    contacts: Contacts, X: np.ndarray, r: np.ndarray, margin: np.ndarray, fast: bool = False
) -> tuple[np.ndarray, ...]:
    """(body, unit normal toward it, gap, friction, face) of each solid face within ``margin``
    (length units) of a ball (X, r). ``fast``: the loop kernel ``face_loop`` (the grid's
    pairs are found alike on both paths)."""
    grid = contacts.grid
    faces = contacts.faces
    bi, f = grid.pairs(X, r + margin)  # endless faces within reach, and the listed ones
    if not len(bi):
        z = np.zeros(0, dtype=np.intp)
        return z, np.zeros((0, 2)), np.zeros(0), np.zeros(0), z
    if fast:
        got = face_loop(bi, f, X, r, margin, faces.p, faces.n, faces.rho, faces.two,
                        faces.lo, faces.hi, faces.c, faces.r, faces.mu)  # fmt: skip
        return _fronts(faces, X, *got)
    L = len(faces.p)
    x = X[bi]
    nrm, _ = face_normals(faces, f, x)
    line = f < L
    gap = np.empty(len(f))
    inside = np.ones(len(f), dtype=bool)
    if L:
        fl = np.where(line, f, 0)
        gap_l = dot(x - faces.p[fl], nrm) - faces.rho[fl] - r[bi]
        t_dir = np.stack([-faces.n[fl, 1], faces.n[fl, 0]], axis=1)
        u = dot(x - faces.p[fl], t_dir)
        inside = ~line | ((u >= faces.lo[fl]) & (u <= faces.hi[fl]))
        gap = gap_l
    if len(faces.c):
        fd = np.where(line, 0, f - L)
        d = x - faces.c[fd]
        gap = np.where(line, gap, norm(d) - faces.r[fd] - r[bi])
    keep = inside & (gap <= margin[bi])
    return _fronts(faces, X, bi[keep], nrm[keep], gap[keep], faces.mu[f[keep]], f[keep])


def _fronts(faces: Any, X: np.ndarray, *rows: np.ndarray) -> tuple[np.ndarray, ...]:
    """``face_rows``' rows less those of a solid polygon's flat faces that are not its face
    of greatest separation from the ball's centre: a face is one-sided and a polygon's other
    faces lie behind it, so a ball above a polygon floor is far behind its bottom face, which
    is no contact of it (a row there would push the ball out through the floor)."""
    bi, f = rows[0], rows[4]
    if not faces.polygons or not len(bi):
        return rows
    L = len(faces.p)
    poly = np.full(L + len(faces.c), -1, dtype=np.intp)
    for k, cols in enumerate(faces.polygons):
        poly[cols] = k
    mine = np.flatnonzero(poly[f] >= 0)
    if not len(mine):
        return rows
    keep = np.ones(len(bi), dtype=bool)
    x = X[bi[mine]]
    own = dot(x - faces.p[f[mine]], faces.n[f[mine]])
    for k in np.unique(poly[f[mine]]).tolist():
        cols = faces.polygons[k]
        at = poly[f[mine]] == k
        xs = x[at]
        d = (
            xs[:, :1] * faces.n[cols, 0]
            + xs[:, 1:] * faces.n[cols, 1]
            - dot(faces.p[cols], faces.n[cols])
        )
        best = d.max(axis=1)
        keep[mine[at]] = own[at] >= best - 1e-9 * (1.0 + np.abs(best))
    return tuple(a[keep] for a in rows)


class Turning(NamedTuple):
    """The pile's discs that turn, by local body (the static slot last where (n + 1,))."""

    turns: np.ndarray  # (n,) bool
    inv_moment: np.ndarray  # (n + 1,) 1 / I (1/(kg m^2)), 0 for what does not turn
    moment: np.ndarray  # (n,) I (kg m^2), 0 for what does not turn
    omega0: np.ndarray  # (n + 1,) rad/s at the step's start, 0 for what does not turn
    alpha: np.ndarray  # (n + 1,) own angular acceleration tau / I (rad/s^2)


def turning(spin: Spin, store: Any, U: np.ndarray, can: np.ndarray) -> Turning | None:
    """The pile's (World rows ``U``) bodies that turn (discs, bodies with corners), or None
    where none does. Those that cannot be moved (``can`` False: kinematic) turn at their own
    omega, whatever they touch: 1 / I = 0 (and I = 0 in the energy's sums)."""
    t = spin.turns[U]
    if not t.any():
        return None
    i = np.where(t & can, store.inv_moment[U], 0.0)
    moment = np.where(t & can, store.moment[U], 0.0)
    return Turning(
        t,
        np.append(i, 0.0),
        moment,
        np.append(np.where(t, spin.omega0[U], 0.0), 0.0),
        np.append(np.where(t, spin.alpha[U], 0.0), 0.0),
    )


def lever_arms(
    turn: Turning,
    r: np.ndarray,
    ra: np.ndarray,
    rb: np.ndarray,
    sep: np.ndarray,
    m_disc: int,
    m_pairs: int,
    fa: np.ndarray,
    nU: int,
) -> Arms:
    """The rows' lever arms (engine.exact.soft, ``Arms``) for the discs that turn: the rows of
    disc pairs (the first ``m_pairs``) and of a disc on a face (to ``m_disc``; A the static
    slot, B the disc ``fa``); the rows of shapes have none.

    A disc's contact point is on its surface, r along the normal, where the gap is open; where
    two surfaces overlap by -s it is Box2D's, midway between them, r + s / 2 from each centre:
    then l_A + l_B is the distance between the centres, the contact point is one point, and
    the friction between two discs changes no angular momentum about any point (the
    impulse's moment about the origin, (x_B - x_A) x P, is what it gives the spins,
    -(l_A + l_B) n x P, with the opposite sign)."""
    la, lb = np.zeros(len(ra)), np.zeros(len(ra))
    half = 0.5 * np.minimum(sep[:m_disc], 0.0)
    pairs = slice(0, m_pairs)
    a, b = ra[pairs], rb[pairs]
    la[pairs] = np.where(turn.turns[a], r[a] + half[pairs], 0.0)
    lb[pairs] = np.where(turn.turns[b], r[b] + half[pairs], 0.0)
    faces = slice(m_pairs, m_disc)
    lb[faces] = np.where(turn.turns[fa], r[fa] + half[faces], 0.0)
    return Arms(la, lb, turn.inv_moment)


def shape_arms(
    arms: Arms,
    turn: Turning,
    ra: np.ndarray,
    rb: np.ndarray,
    nv: np.ndarray,
    m_disc: int,
    m_pairs: int,
    anchors: list[np.ndarray],
) -> Arms:
    """``arms`` with the lever arms of the rows of shapes (from ``m_disc`` on: ``m_pairs``
    rows of pairs, then those on the colliders, A the static slot) from the manifolds'
    anchors (engine.geometry.shaped: the pairs' points less A's and B's positions, ``anchors[0]``
    and ``[1]``; the colliders' rows' less the body's, ``anchors[2]``), for the bodies that turn:
    with n the row's normal, la = r_A.n, lb = -(r_B.n), na = r_A x n, nb = r_B x n
    (engine.exact.soft, ``Arms``)."""
    rows = len(ra)
    turns = np.append(turn.turns, False)  # the static slot does not turn
    r_a, r_b = np.zeros((rows, 2)), np.zeros((rows, 2))
    pairs = slice(m_disc, m_disc + m_pairs)
    r_a[pairs], r_b[pairs] = anchors[0], anchors[1]
    r_b[m_disc + m_pairs :] = anchors[2]
    r_a[~turns[ra]] = 0.0
    r_b[~turns[rb]] = 0.0
    sh = slice(m_disc, rows)
    la, lb = arms.a.copy(), arms.b.copy()
    na, nb = np.zeros(rows), np.zeros(rows)
    n = nv[sh]
    la[sh] = dot(r_a[sh], n)
    lb[sh] = -dot(r_b[sh], n)
    na[sh] = r_a[sh, 0] * n[:, 1] - r_a[sh, 1] * n[:, 0]
    nb[sh] = r_b[sh, 0] * n[:, 1] - r_b[sh, 1] * n[:, 0]
    return Arms(la, lb, arms.inv_moment, na, nb)


# -- the loop kernels (engine.kernels: the fast path) -----------------------------------------


def _sample_discs() -> tuple[object, ...]:
    """The smallest call of ``disc_loop``: two discs side by side."""
    i, one = np.array([0]), np.array([1])
    return i, one, i, one, np.array([[0.0, 0.0], [1.0, 0.0]]), np.full(2, 0.5), np.ones(2), \
        np.ones(2), 4  # fmt: skip


@kernels.loop(sample=_sample_discs)
def disc_loop(
    pa: np.ndarray,
    pb: np.ndarray,
    la: np.ndarray,
    lb: np.ndarray,
    X: np.ndarray,
    r: np.ndarray,
    mu: np.ndarray,
    e: np.ndarray,
    base: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``disc_rows`` as a loop: (normal (m, 2), gap, friction, restitution, slop, key)."""
    m = len(la)
    nrm, sep = np.empty((m, 2)), np.empty(m)
    fric, rest, slop = np.empty(m), np.empty(m), np.empty(m)
    key = np.empty(m, dtype=np.int64)
    for k in range(m):
        i, j = la[k], lb[k]
        dx, dy = X[j, 0] - X[i, 0], X[j, 1] - X[i, 1]
        dist = np.sqrt(dx * dx + dy * dy)
        # unit: d / dist, straight up where the centres coincide.
        q = dist if dist > 0.0 else 1.0
        nrm[k, 0], nrm[k, 1] = dx / q, dy / q
        if dist == 0.0:
            nrm[k, 0], nrm[k, 1] = 0.0, 1.0
        sep[k] = dist - r[i] - r[j]
        fric[k] = mu[i] * mu[j]
        rest[k] = e[i] * e[j]
        slop[k] = SLOP * min(r[i], r[j])
        key[k] = np.int64(pa[k]) * base + pb[k]
    return nrm, sep, fric, rest, slop, key


def _sample_faces() -> tuple[object, ...]:
    """The smallest call of ``face_loop``: a ball on a floor, a peg beside it."""
    f1 = np.zeros(1)
    return (np.array([0, 0]), np.array([0, 1]), np.array([[0.0, 0.5]]), f1 + 0.5, f1 + 0.1,
            np.zeros((1, 2)), np.array([[0.0, 1.0]]), f1, np.zeros(1, dtype=bool), f1 - 9.0,
            f1 + 9.0, np.array([[1.0, 0.5]]), f1 + 0.5, np.ones(2))  # fmt: skip


@kernels.loop(sample=_sample_faces)
def face_loop(
    bi: np.ndarray,
    f: np.ndarray,
    X: np.ndarray,
    r: np.ndarray,
    margin: np.ndarray,
    p: np.ndarray,
    n: np.ndarray,
    rho: np.ndarray,
    two: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    c: np.ndarray,
    cr: np.ndarray,
    mu: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``face_rows`` after the grid, as a loop over the (body bi, face f) pairs it found: the
    normal as engine.geometry.faces.face_normals has it, the gap, and the pairs kept in order."""
    L, m = len(p), len(bi)
    keep_b, keep_f = np.empty(m, dtype=bi.dtype), np.empty(m, dtype=f.dtype)
    nrm, gap, fric = np.empty((m, 2)), np.empty(m), np.empty(m)
    kept = 0
    for k in range(m):
        i, j = bi[k], f[k]
        x, y = X[i, 0], X[i, 1]
        if j < L:
            # A flat face: its normal, turned toward the ball if it is met from both sides;
            # kept where the ball's centre is over it (lo <= u <= hi along its tangent).
            dx, dy = x - p[j, 0], y - p[j, 1]
            side = -1.0 if two[j] and dx * n[j, 0] + dy * n[j, 1] < 0.0 else 1.0
            nx, ny = n[j, 0] * side, n[j, 1] * side
            g = dx * nx + dy * ny - rho[j] - r[i]
            u = dx * -n[j, 1] + dy * n[j, 0]
            if not (u >= lo[j] and u <= hi[j]):
                continue
        else:
            # A round face: the normal from its centre (d itself where they coincide).
            dx, dy = x - c[j - L, 0], y - c[j - L, 1]
            dist = np.sqrt(dx * dx + dy * dy)
            q = dist if dist > 0.0 else 1.0
            nx, ny = dx / q, dy / q
            g = dist - cr[j - L] - r[i]
        if g <= margin[i]:
            keep_b[kept], keep_f[kept] = i, j
            nrm[kept, 0], nrm[kept, 1] = nx, ny
            gap[kept], fric[kept] = g, mu[j]
            kept += 1
    return keep_b[:kept], nrm[:kept], gap[:kept], fric[:kept], keep_f[:kept]


def _sample_carry() -> tuple[object, ...]:
    """The smallest call of ``carry_in``: one row, found among two carried."""
    k = np.array([3, 7], dtype=np.int64)
    return np.array([7], dtype=np.int64), k, np.ones((2, 2)), 0.25, k, np.array([0, 1]), True


@kernels.loop(sample=_sample_carry)
def carry_in(
    key: np.ndarray,
    keys: np.ndarray,
    lam: np.ndarray,
    scale: float,
    color_keys: np.ndarray,
    colors: np.ndarray,
    shared: bool,
) -> tuple[np.ndarray, np.ndarray]:
    """``warm_start`` as a loop: each key's place in ``keys`` and in ``color_keys`` (the
    same places when ``shared``: one array) as searchsorted finds it, the first place whose
    key is not below it."""
    m = len(key)
    out = np.zeros((m, 2))
    prior = np.full(m, -1, dtype=np.int64)
    found = np.full(m, -1, dtype=np.int64)
    for table in range(1 if shared else 2):
        ks = keys if table == 0 else color_keys
        L, at = len(ks), 0
        for k in range(m):
            v = key[k]
            # A galloping search from the last key's place: the keys come in sorted runs, so
            # the place is most often a step or two on. First a range [lo, hi] that holds it,
            # by steps doubling away from there, then a binary search in it.
            if at < L and ks[at] < v:
                lo = hi = at + 1
                step = 1
                while hi < L and ks[hi] < v:
                    lo = hi + 1
                    hi += step
                    step *= 2
                hi = min(hi, L)
            else:
                lo = hi = at
                step = 1
                while lo > 0 and ks[lo - 1] >= v:
                    hi = lo - 1
                    lo -= step
                    step *= 2
                lo = max(lo, 0)
            while lo < hi:
                mid = (lo + hi) >> 1
                if ks[mid] < v:
                    lo = mid + 1
                else:
                    hi = mid
            at = lo
            if at < L and ks[at] == v:
                if table == 0:
                    out[k, 0] = lam[at, 0] * scale
                    out[k, 1] = lam[at, 1] * scale
                    found[k] = at
                else:
                    prior[k] = colors[at]
    if shared:
        for k in range(m):
            if found[k] >= 0:
                prior[k] = colors[found[k]]
    return out, prior


def _sample_held() -> tuple[object, ...]:
    """The smallest call of ``held_loop``: two discs touching, one on the floor."""
    X = np.array([[0.0, 0.5], [1.0, 0.5]])
    i, j, f = np.array([0, 2]), np.array([1, 0]), np.zeros(2)
    return X, X.copy(), i[:1], j[:1], np.full(2, 0.5), i, j, np.array([[1.0, 0.0], [0.0, 1.0]]), \
        f, f, f  # fmt: skip


@kernels.loop(sample=_sample_held)
def held_loop(
    X: np.ndarray,
    X0: np.ndarray,
    la: np.ndarray,
    lb: np.ndarray,
    r: np.ndarray,
    ra: np.ndarray,
    rb: np.ndarray,
    nv: np.ndarray,
    sep: np.ndarray,
    slop: np.ndarray,
    total: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``held`` as a loop: (hold, near, gap now, held rows)."""
    m, rows, nU = len(la), len(ra), len(X)
    hold, near = np.empty(m, dtype=np.bool_), np.empty(m, dtype=np.bool_)
    for k in range(m):
        i, j = la[k], lb[k]
        dx, dy = X[j, 0] - X[i, 0], X[j, 1] - X[i, 1]
        gap = np.sqrt(dx * dx + dy * dy) - r[i] - r[j]
        low = min(r[i], r[j])
        hold[k] = gap <= SLOP * low + TOUCH or total[k] > 0.0
        near[k] = gap <= 0.05 * low
    now, held_rows = np.empty(rows), np.empty(rows, dtype=np.bool_)
    for k in range(rows):
        i, j = ra[k], rb[k]
        # Each body's move since the start (the static slot's: none).
        ax = X[i, 0] - X0[i, 0] if i < nU else 0.0
        ay = X[i, 1] - X0[i, 1] if i < nU else 0.0
        bx = X[j, 0] - X0[j, 0] if j < nU else 0.0
        by = X[j, 1] - X0[j, 1] if j < nU else 0.0
        now[k] = sep[k] + ((bx - ax) * nv[k, 0] + (by - ay) * nv[k, 1])
        held_rows[k] = now[k] <= slop[k] + TOUCH or total[k] > 0.0
    return hold, near, now, held_rows
