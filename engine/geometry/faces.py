"""The static colliders' faces, compiled into arrays for the contacts (engine.exact.contacts).

Each solid collider is a set of faces (``Collider.lines()`` and ``Collider.discs()``): a flat
face is a line through p with unit normal n, offset rho from it (a Segment's radius, a
Polygon's rounding), met from one side or both (``two``), and bounded along its tangent
(-n_y, n_x) by lo and hi (both infinite for an endless line: a Plane, a Box's wall); a round
face is a disc of centre c and radius r. A ball of radius R touches a flat face when its
centre is rho + R from the line, and a round one when it is r + R from the centre, so every
test of the contacts is a test of the ball's centre against the faces grown by R.

``compile_faces`` lays them out as arrays, flat faces first and round ones after (a face's
index f is a flat face's when f < L, the count of flat faces, and the round face f - L's
otherwise), each with its owner's material and filter. ``faces_added`` and ``faces_removed``
give the layout after one collider is added or taken out, the same as compiling the new list
afresh, in a few array operations (a game adding a peg pays for the peg, not for the board).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..filters import DEFAULT as DEFAULT_FILTER
from .colliders import Box, Circle, Collider, Plane, Polygon, Segment
from .impact import Pair
from .manifold import polygon_distance

__all__ = [
    "behind_solid",
    "Faces",
    "allowed_pairs",
    "compile_faces",
    "faces_added",
    "faces_rematerialled",
    "faces_removed",
    "same_faces",
    "dot",
    "face_meets",
    "face_normals",
    "signed_distance",
]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row by row dot products of two (N, 2) arrays: (N,)."""
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]


def signed_distance(collider: Collider, X: np.ndarray) -> np.ndarray:
    """Signed distance (length units) from each row of X (N, 2) to the collider's surface.

    Positive in free space (inside a Box, outside everything else).
    """
    if isinstance(collider, Plane):
        return (X[:, 0] - collider.point.x) * collider.normal.x + (
            X[:, 1] - collider.point.y
        ) * collider.normal.y
    if isinstance(collider, Circle):
        return np.hypot(X[:, 0] - collider.center.x, X[:, 1] - collider.center.y) - collider.radius
    if isinstance(collider, Segment):
        a, b = collider.a, collider.b
        dx, dy = b.x - a.x, b.y - a.y
        u = ((X[:, 0] - a.x) * dx + (X[:, 1] - a.y) * dy) / (dx * dx + dy * dy)
        u = np.clip(u, 0.0, 1.0)
        return np.hypot(X[:, 0] - a.x - u * dx, X[:, 1] - a.y - u * dy) - collider.radius
    if isinstance(collider, Box):
        (x0, y0), (x1, y1) = collider.lower_left, collider.upper_right
        return np.minimum(
            np.minimum(X[:, 0] - x0, x1 - X[:, 0]), np.minimum(X[:, 1] - y0, y1 - X[:, 1])
        )
    if isinstance(collider, Polygon):
        return polygon_distance(collider, X)
    raise TypeError(f"unknown collider {collider!r}")


@dataclass
class Faces:
    """The solid colliders' faces as arrays: flat ones first, then round ones."""

    p: np.ndarray  # (L, 2) a point on each flat face's line
    n: np.ndarray  # (L, 2) its unit normal
    rho: np.ndarray  # (L,) offset of the face from the line
    two: np.ndarray  # (L,) bool: met from either side
    lo: np.ndarray  # (L,) extent along the tangent
    hi: np.ndarray
    c: np.ndarray  # (D, 2) round faces' centres
    r: np.ndarray  # (D,) their radii
    owner: np.ndarray  # (L + D,) index of the collider each face belongs to
    e: np.ndarray  # (L + D,) the owner's restitution
    mu: np.ndarray  # (L + D,) the owner's friction
    infinite: np.ndarray  # (L,) bool: a line with no end (a Plane or a Box wall)
    boxed: bool  # every line with no end is a Box's wall (none is a Plane's)
    # The same numbers as Python floats, for the one-body-at-a-time path (engine.exact.sweep_one):
    line_list: list[tuple[Pair, Pair, float, bool, float, float]]  # (p, n, rho, two, lo, hi)
    disc_list: list[tuple[Pair, float]]  # (c, r)
    e_list: list[float]
    mu_list: list[float]
    owner_list: list[int]
    # The owners' filters (engine.Filter: group, categories, mask), by face; None when every
    # collider has the default filter (then every body meets every face).
    filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
    # The solid polygons' flat faces, one index array each (a body is inside a polygon only
    # when inside every face of it, not behind one: ``engine.exact.push_out``).
    polygons: tuple[np.ndarray, ...] = ()
    #: ``polygons`` as arrays, made with the faces: each flat face's polygon (-1: none), and
    #: each polygon's faces as one flat list with its start (P + 1,) (``behind_solid``).
    solid: tuple[np.ndarray, ...] = field(init=False, repr=False, compare=False)
    #: Each face's round ends (``_ends``): (L + D + 1, 2), the round face at a flat face's lo
    #: and hi ends (a face index, L + its place among the round ones), -2 where it has none
    #: (a round face, an endless line; the last row, for a body resting on no face: -1);
    #: and the flat faces' as a list of pairs (engine.exact.sweep_one).
    ends: np.ndarray = field(init=False, repr=False, compare=False)
    ends_list: list[tuple[int, int]] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.solid = _solid(len(self.p), self.polygons)
        self.ends = _ends(self.p, self.n, self.rho, self.lo, self.hi, self.c, self.r, self.owner)
        self.ends_list = [(a, b) for a, b in self.ends[: len(self.p)].tolist()]


def compile_faces(colliders: list[Collider], indices: list[int]) -> Faces:
    """The faces of ``colliders[k]`` for each k in ``indices`` (the solid ones), as arrays;
    ``owner`` holds each face's k."""
    lines: list[Any] = []
    discs: list[Any] = []
    lown: list[int] = []
    down: list[int] = []
    for k in indices:
        c = colliders[k]
        for line in c.lines():
            lines.append(line)
            lown.append(k)
        for disc in c.discs():
            discs.append(disc)
            down.append(k)
    L = len(lines)
    p = np.array([ln[0] for ln in lines], float).reshape(L, 2)
    n = np.array([ln[1] for ln in lines], float).reshape(L, 2)
    rho = np.array([ln[2] for ln in lines], float)
    two = np.array([ln[3] for ln in lines], bool)
    lo = np.array([ln[4] for ln in lines], float)
    hi = np.array([ln[5] for ln in lines], float)
    centres = np.array([d[0] for d in discs], float).reshape(len(discs), 2)
    r = np.array([d[1] for d in discs], float)
    owner = np.array(lown + down, dtype=np.intp)
    e, mu, filters = _owners_material(colliders, owner.tolist())
    infinite = np.isinf(lo) & np.isinf(hi)
    boxed = all(isinstance(colliders[k], Box) for k in owner[: len(lo)][infinite].tolist())
    line_list = [
        ((px, py), (nx, ny), rh, tw, a, b)
        for (px, py), (nx, ny), rh, tw, a, b in zip(
            p.tolist(),
            n.tolist(),
            rho.tolist(),
            two.tolist(),
            lo.tolist(),
            hi.tolist(),
            strict=True,
        )
    ]
    disc_list = [((cx, cy), rd) for (cx, cy), rd in zip(centres.tolist(), r.tolist(), strict=True)]
    lines_of = np.array(lown, dtype=np.intp)
    polygons = tuple(
        np.flatnonzero(lines_of == k) for k in indices if isinstance(colliders[k], Polygon)
    )
    return Faces(
        p,
        n,
        rho,
        two,
        lo,
        hi,
        centres,
        r,
        owner,
        e,
        mu,
        infinite,
        boxed,
        line_list,
        disc_list,
        e.tolist(),
        mu.tolist(),
        owner.tolist(),
        filters,
        polygons,
    )


def _owners_material(
    colliders: list[Collider], owner: list[int]
) -> tuple[np.ndarray, np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray] | None]:
    """Each face's owner's restitution, friction and filter (group, categories, mask; None
    when every owner has the default filter), by face."""
    e = np.array([colliders[k].restitution for k in owner], float)
    mu = np.array([colliders[k].friction for k in owner], float)
    fs = [colliders[k].filter for k in owner]
    filters = None
    if any(f != DEFAULT_FILTER for f in fs):
        filters = (
            np.array([f.group for f in fs], dtype=np.int64),
            np.array([f.categories for f in fs], dtype=np.int64),
            np.array([f.mask for f in fs], dtype=np.int64),
        )
    return e, mu, filters


def faces_rematerialled(faces: Faces, colliders: list[Collider]) -> Faces:
    """The same faces with their owners' restitution, friction and filter read again (one
    was set), as a new Faces (what is kept keyed on the old one is made again); the same
    arrays as compiling afresh."""
    e, mu, filters = _owners_material(colliders, faces.owner_list)
    return replace(faces, e=e, mu=mu, e_list=e.tolist(), mu_list=mu.tolist(), filters=filters)


def same_faces(old: Faces, new: Faces, f: np.ndarray) -> np.ndarray:
    """Where each of ``old``'s faces ``f`` is in ``new`` (-1: not there): the face of the same
    owner, kind (flat or round) and place among that owner's faces of its kind, which
    ``compile_faces`` lays out as one run."""
    out = np.full(len(f), -1, dtype=np.intp)
    L0, L1 = len(old.p), len(new.p)
    for q, face in enumerate(f.tolist()):
        flat = face < L0
        k = int(old.owner[face])
        run0 = (
            np.flatnonzero(old.owner[:L0] == k)
            if flat
            else L0 + np.flatnonzero(old.owner[L0:] == k)
        )
        run1 = (
            np.flatnonzero(new.owner[:L1] == k)
            if flat
            else L1 + np.flatnonzero(new.owner[L1:] == k)
        )
        place = face - int(run0[0])
        if place < len(run1):
            out[q] = run1[place]
    return out


def _ends(
    p: np.ndarray,
    n: np.ndarray,
    rho: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    c: np.ndarray,
    r: np.ndarray,
    owner: np.ndarray,
) -> np.ndarray:
    """``Faces.ends``: the round face at each end of each flat face with ends, where a ball
    that slides off that end goes on around it (engine.exact.sweep, "A slide's end").

    A collider lists its faces in order (``compile_faces``): a Segment one line from a to b and
    its two ends' discs, a, b; a Polygon's edge i runs from vertex i to vertex i + 1, and its
    discs are its vertices. So the flat face i of an owner ends at lo on its round face i and at
    hi on its round face i + 1 (mod their count), and each such end is checked to be that
    disc: its centre at p + lo t or p + hi t (t = (-n_y, n_x); to 1e-9 of the sizes) and its
    radius the face's offset rho; any other (an endless line, a collider of another layout) has
    none (-2)."""
    L, D = len(p), len(c)
    ends = np.full((L + D + 1, 2), -2, dtype=np.int64)
    if not L or not D:
        return ends
    lown, down = owner[:L], owner[L:]
    f = np.flatnonzero(np.isfinite(lo) & np.isfinite(hi) & np.isin(lown, down))
    if not len(f):
        return ends
    # Each owner's first flat face, and its first round face and their count (a collider's
    # faces are listed together).
    lines_by, line_first = np.unique(lown, return_index=True)
    rank = np.arange(L) - line_first[np.searchsorted(lines_by, lown)]
    discs_by, disc_first, disc_count = np.unique(down, return_index=True, return_counts=True)
    at = np.searchsorted(discs_by, lown[f])
    m = disc_count[at]
    t = np.stack([-n[f, 1], n[f, 0]], axis=1)
    for side, (edge, disc) in enumerate(((lo, rank[f] % m), (hi, (rank[f] + 1) % m))):
        j = disc_first[at] + disc
        point = p[f] + t * edge[f][:, None]
        size = 1.0 + np.abs(point).max(axis=1) + rho[f]
        there = np.hypot(*(c[j] - point).T) <= 1e-9 * size
        same = there & (r[j] == rho[f]) & (down[j] == lown[f])
        ends[f[same], side] = L + j[same]
    return ends


def _solid(lines: int, polygons: tuple[np.ndarray, ...]) -> tuple[np.ndarray, ...]:
    """``Faces.solid`` for ``lines`` flat faces and the solid polygons' face lists."""
    poly = np.full(lines, -1, dtype=np.intp)
    sizes = [len(cols) for cols in polygons]
    start = np.zeros(len(sizes) + 1, dtype=np.intp)
    start[1:] = np.cumsum(sizes)
    for k, cols in enumerate(polygons):
        poly[cols] = k
    flat = np.concatenate(polygons).astype(np.intp) if polygons else np.zeros(0, dtype=np.intp)
    return poly, start, flat


def behind_solid(faces: Faces, X: np.ndarray, bi: np.ndarray, fj: np.ndarray) -> np.ndarray:
    """Which (body, face) pairs are a solid polygon's flat face with the body's centre X[bi]
    behind it but not behind it least of its polygon's faces: no contact of it. A face is
    one-sided and a convex polygon's other faces lie behind it, so a ball beside (or below)
    a polygon is behind its far faces, which it never meets: only its face of greatest
    separation holds a centre that is inside (engine.exact.pile_rows' ``_fronts`` for the rows;
    this for the impacts, whose contact branch meets a face at once when the ball's centre is
    behind it and the pull holds it there)."""
    out = np.zeros(len(bi), dtype=bool)
    if not faces.polygons or not len(bi):
        return out
    poly, start, flat = faces.solid
    L = len(faces.p)
    line = np.flatnonzero(fj < L)
    if not len(line):
        return out
    mine = line[poly[fj[line]] >= 0]
    if not len(mine):
        return out
    x, f = X[bi[mine]], fj[mine]
    d0 = dot(x - faces.p[f], faces.n[f])
    back = np.flatnonzero(d0 < 0.0)
    for q in back.tolist():
        k = poly[f[q]]
        cols = flat[start[k] : start[k + 1]]
        best = float(dot(x[q] - faces.p[cols], faces.n[cols]).max())
        out[mine[q]] = bool(d0[q] < best - 1e-9 * (1.0 + abs(best)))
    return out


def face_normals(faces: Faces, f: np.ndarray, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals toward X of faces f (one per row), and 1 / radius (0 for flat faces)."""
    L = len(faces.p)
    line = f < L
    fl = np.where(line, f, 0)
    fd = np.where(line, 0, f - L)
    nrm = np.zeros((len(f), 2))
    curve = np.zeros(len(f))
    if L:
        n = faces.n[fl]
        side = np.where(faces.two[fl] & (dot(X - faces.p[fl], n) < 0.0), -1.0, 1.0)
        nrm = n * side[:, None]
    if len(faces.c) and not line.all():
        d = X - faces.c[fd]
        dist = np.sqrt(dot(d, d))
        safe = np.where(dist > 0.0, dist, 1.0)
        nrm = np.where(line[:, None], nrm, d / safe[:, None])
        curve = np.where(line, 0.0, 1.0 / safe)
    return nrm, curve


def allowed_pairs(
    faces: Faces,
    body_filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None,
    rows: np.ndarray,
    f: np.ndarray,
) -> np.ndarray:
    """Whether each body (World row) meets each face (pairs of equal length): their
    filters collide (engine.filters), as for two bodies. All True without filters.
    ``body_filters``: the World's bodies' (group, categories, mask) arrays by row."""
    ff, bf = faces.filters, body_filters
    if ff is None or bf is None:
        return np.ones(len(rows), dtype=bool)
    g, c, m = bf[0][rows], bf[1][rows], bf[2][rows]
    fg, fc, fm = ff[0][f], ff[1][f], ff[2][f]
    ok = ((c & fm) != 0) & ((fc & m) != 0)
    return ok & ~((g == fg) & (g != 0))


def face_meets(
    faces: Faces,
    body_filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None,
    rows: np.ndarray,
) -> np.ndarray | None:
    """(len(rows), faces) bool: whether each body (World row) meets each face
    (``allowed_pairs``), or None when no filter stands between any body and any face."""
    if faces.filters is None or body_filters is None:
        return None
    n_f = len(faces.owner)
    meets = allowed_pairs(
        faces, body_filters, np.repeat(rows, n_f), np.tile(np.arange(n_f), len(rows))
    )
    return meets.reshape(len(rows), n_f)


def face_filters(faces: Faces) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The faces' owners' filters (group, categories, mask), the defaults when ``filters`` is
    None."""
    if faces.filters is not None:
        return faces.filters
    F = len(faces.owner)
    d = DEFAULT_FILTER
    return (
        np.full(F, d.group, dtype=np.int64),
        np.full(F, d.categories, dtype=np.int64),
        np.full(F, d.mask, dtype=np.int64),
    )


def faces_added(faces: Faces, colliders: list[Collider]) -> Faces:
    """``compile_faces`` of ``colliders`` (the solid ones) when ``faces`` are those of all but
    the last and the last is solid and new: its flat faces go at the end of the flat ones,
    its round faces at the end (every round face before them moves up by its count of flat
    ones). The same arrays as compiling afresh, bit for bit."""
    k = len(colliders) - 1
    collider = colliders[k]
    new = compile_faces([collider], [0])
    L0 = len(faces.p)
    nl = len(new.p)
    owner_new = np.full(len(new.owner), k, dtype=np.intp)

    def merge(old: np.ndarray, add: np.ndarray) -> np.ndarray:
        # Flat faces first, then round ones: old flat, new flat, old round, new round.
        return np.concatenate([old[:L0], add[:nl], old[L0:], add[nl:]])

    def merge_list(old: list[Any], add: list[Any]) -> list[Any]:
        return old[:L0] + add[:nl] + old[L0:] + add[nl:]

    owner = merge(faces.owner, owner_new)
    boxed = faces.boxed and (isinstance(collider, Box) or not bool(new.infinite.any()))
    filters = None
    if faces.filters is not None or new.filters is not None:
        old_f, add_f = face_filters(faces), face_filters(new)
        filters = (
            merge(old_f[0], add_f[0]),
            merge(old_f[1], add_f[1]),
            merge(old_f[2], add_f[2]),
        )
    polygons = faces.polygons
    if isinstance(collider, Polygon):
        polygons = (*polygons, np.arange(L0, L0 + nl, dtype=np.intp))
    nd = len(new.c)

    def cat(old: np.ndarray, add: np.ndarray, count: int) -> np.ndarray:
        # (No faces of a kind added: the old array, unchanged, as the new layout's.)
        return np.concatenate([old, add]) if count else old

    return Faces(
        cat(faces.p, new.p, nl),
        cat(faces.n, new.n, nl),
        cat(faces.rho, new.rho, nl),
        cat(faces.two, new.two, nl),
        cat(faces.lo, new.lo, nl),
        cat(faces.hi, new.hi, nl),
        cat(faces.c, new.c, nd),
        cat(faces.r, new.r, nd),
        owner,
        merge(faces.e, new.e),
        merge(faces.mu, new.mu),
        cat(faces.infinite, new.infinite, nl),
        boxed,
        faces.line_list + new.line_list if nl else faces.line_list,
        faces.disc_list + new.disc_list if nd else faces.disc_list,
        merge_list(faces.e_list, new.e_list),
        merge_list(faces.mu_list, new.mu_list),
        merge_list(faces.owner_list, [k] * len(new.owner)),
        filters,
        polygons,
    )


def faces_removed(
    faces: Faces, colliders: list[Collider], k: int
) -> tuple[Faces, np.ndarray | None]:
    """``compile_faces`` of ``colliders`` (the solid ones) when ``faces`` are those of the same
    list with collider k still in it (``colliders`` is the list without it), and each old
    face's new index (-1 for k's own faces), or None when no face moved (k was a sensor, or
    had no faces). The same arrays as compiling afresh, bit for bit."""
    L, F = len(faces.p), len(faces.owner)
    mine = np.flatnonzero(faces.owner == k)
    owner = faces.owner - (faces.owner > k)
    if not len(mine):
        # A sensor (no faces): only the owners after it move down.
        return replace(faces, owner=owner, owner_list=owner.tolist()), None
    flat = mine[mine < L]
    disc = mine[mine >= L]
    # A collider's faces of each kind are one run (compile_faces goes collider by collider).
    a, nl = (int(flat[0]), len(flat)) if len(flat) else (L, 0)
    b, nd = (int(disc[0]), len(disc)) if len(disc) else (F, 0)
    keep = np.ones(F, dtype=bool)
    keep[mine] = False
    index = np.cumsum(keep) - 1
    index[mine] = -1

    def cut(arr: np.ndarray) -> np.ndarray:  # both runs out of an array over every face
        return np.concatenate([arr[:a], arr[a + nl : b], arr[b + nd :]])

    def drop(arr: np.ndarray, at: int, count: int) -> np.ndarray:  # one run out
        return np.concatenate([arr[:at], arr[at + count :]]) if count else arr

    def cut_list(old: list[Any]) -> list[Any]:
        return old[:a] + old[a + nl : b] + old[b + nd :]

    owner = cut(owner)
    p, n = drop(faces.p, a, nl), drop(faces.n, a, nl)
    infinite = drop(faces.infinite, a, nl)
    inf_owner = owner[: len(p)][infinite]
    boxed = all(isinstance(colliders[j], Box) for j in inf_owner.tolist())
    filters = None
    if faces.filters is not None:
        cols = tuple(cut(col) for col in faces.filters)
        d = DEFAULT_FILTER
        if bool(np.any((cols[0] != d.group) | (cols[1] != d.categories) | (cols[2] != d.mask))):
            filters = (cols[0], cols[1], cols[2])
    polygons = tuple(
        np.where(cols >= a + nl, cols - nl, cols)
        for cols in faces.polygons
        if not (nl and a <= int(cols[0]) < a + nl)
    )
    return (
        Faces(
            p,
            n,
            drop(faces.rho, a, nl),
            drop(faces.two, a, nl),
            drop(faces.lo, a, nl),
            drop(faces.hi, a, nl),
            drop(faces.c, b - L, nd),
            drop(faces.r, b - L, nd),
            owner,
            cut(faces.e),
            cut(faces.mu),
            infinite,
            boxed,
            faces.line_list[:a] + faces.line_list[a + nl :] if nl else faces.line_list,
            faces.disc_list[: b - L] + faces.disc_list[b - L + nd :] if nd else faces.disc_list,
            cut_list(faces.e_list),
            cut_list(faces.mu_list),
            owner.tolist(),
            filters,
            polygons,
        ),
        index,
    )
