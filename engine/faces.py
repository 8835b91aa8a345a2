"""The static colliders' faces, compiled into arrays for the contacts (engine.contacts).

Each solid collider is a set of faces (``Collider.lines()`` and ``Collider.discs()``): a flat
face is a line through p with unit normal n, offset rho from it (a Segment's radius, a
Polygon's rounding), met from one side or both (``two``), and bounded along its tangent
(-n_y, n_x) by lo and hi (both infinite for an endless line: a Plane, a Box's wall); a round
face is a disc of centre c and radius r. A ball of radius R touches a flat face when its
centre is rho + R from the line, and a round one when it is r + R from the centre, so every
test of the contacts is a test of the ball's centre against the faces grown by R.

``compile_faces`` lays them out as arrays, flat faces first and round ones after (a face's
index f is a flat face's when f < L, the count of flat faces, and the round face f - L's
otherwise), each with its owner's material and filter.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .colliders import Box, Circle, Collider, Plane, Polygon, Segment
from .filters import DEFAULT as DEFAULT_FILTER
from .impact import Pair
from .manifold import polygon_distance

__all__ = [
    "Faces",
    "allowed_pairs",
    "compile_faces",
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
    # The same numbers as Python floats, for the one-body-at-a-time path (engine.sweep_one):
    line_list: list[tuple[Pair, Pair, float, bool, float, float]]  # (p, n, rho, two, lo, hi)
    disc_list: list[tuple[Pair, float]]  # (c, r)
    e_list: list[float]
    mu_list: list[float]
    owner_list: list[int]
    # The owners' filters (engine.Filter: group, categories, mask), by face; None when every
    # collider has the default filter (then every body meets every face).
    filters: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
    # The solid polygons' flat faces, one index array each (a body is inside a polygon only
    # when inside every face of it, not behind one: ``engine.push_out``).
    polygons: tuple[np.ndarray, ...] = ()


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
    e = np.array([colliders[k].restitution for k in owner], float)
    mu = np.array([colliders[k].friction for k in owner], float)
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
    filters = None
    if any(colliders[k].filter != DEFAULT_FILTER for k in indices):
        fs = [colliders[k].filter for k in owner.tolist()]
        filters = (
            np.array([f.group for f in fs], dtype=np.int64),
            np.array([f.categories for f in fs], dtype=np.int64),
            np.array([f.mask for f in fs], dtype=np.int64),
        )
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
