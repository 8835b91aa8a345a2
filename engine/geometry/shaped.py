"""Bodies with a shape (a box, a polygon, a capsule): their contacts as rows of the soft step.

A body made with ``Body(..., shape=...)`` carries a convex shape in its own frame, about its
position (``engine.geometry.colliders``: a ``Polygon``, ``Polygon.box(width, height)``, or a
``Segment``, a capsule), turned by the body's angle (``angle``: the angles at the step's
start, by World row; None: 0, a body that does not turn).

Such a body is always stepped with the piles (``engine.exact.soft``): its contacts are the points
of Box2D's manifolds (``engine.geometry.manifold``), up to two a pair, each a row with a normal and
a separation, solved with the pile's contacts of discs. A body that does not turn moves by
translation only, so a row's point does not matter, only its normal and gap: the same
row as two discs'. A body that turns needs the point too: each row comes with its anchors,
the point less each body's position (r_A, r_B), of which the pile makes the lever arms
(engine.exact.pile_rows, ``shape_arms``). A disc meets a shape as a ``Circles`` row of the table.

The rows are speculative (Box2D's): a wall within ``margin`` of a body at the step's start,
or a pair within twice it, gets its rows, which hold the gap from closing past zero. The
margin is the farthest any body of the pile moves in the step (its speed at the start and
what the forces add in dt) plus 5% of a radius, so a box thrown at a thin wall, or two
thrown at each other, are caught whatever their speed (tested to 1,000 m/s). What the rows
cannot see is a body sent faster within the step by another's push (its new path is not
swept), nor a pair that turns far within the step (a row is linear in it): a fast pair left
deep in each other or through is taken again from its moment of impact
(engine.exact.shape_impacts); the exact impacts in time order are for discs.

>>> import numpy as np
>>> from engine.geometry.colliders import Polygon
>>> table = ShapeTable([Polygon.box(1.0, 1.0), None], np.array([0.7071, 0.5]))
>>> a, b, n, s, k, ra, rb = pair_rows(table, np.array([0]), np.array([1]),
...                                   np.array([[0.0, 0.0], [1.0, 0.0]]), 0.1)
>>> a.tolist(), b.tolist(), n.tolist(), s.tolist(), ra.tolist(), rb.tolist()
([0], [1], [[1.0, 0.0]], [0.0], [[0.5, 0.0]], [[-0.5, 0.0]])
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np

from ..body_shapes import Compound
from .colliders import Circle, Polygon, Segment
from .manifold import (
    Capsules,
    Circles,
    HalfPlanes,
    Kind,
    Manifold,
    Polygons,
    StaticShapes,
    collide,
    half_plane_polygon_loop,
)
from .manifold_polygon import polygon_loop

__all__ = [
    "ShapeTable", "Parts", "part_pairs", "part_rows", "pair_rows", "static_rows",
    "DISC", "CAPSULE", "POLYGON", "COMPOUND",
]  # fmt: skip

#: The kinds of a body's shape, by code: a COMPOUND body is of several (engine.body_shapes),
#: each a row of the table's ``parts``.
DISC, CAPSULE, POLYGON, COMPOUND = 0, 1, 2, 3


class Parts(NamedTuple):
    """The parts of a World's bodies where one is of several shapes (engine.body_shapes): one
    row a part, a body of one shape (or a disc, or a point) one part; ``table`` their shapes
    (a ShapeTable of no COMPOUND row), ``owner`` each part's body row, ``number`` its place
    among its body's parts, ``first`` and ``size`` each body's first part's row and how many
    it has."""

    table: ShapeTable
    owner: np.ndarray
    number: np.ndarray
    first: np.ndarray
    size: np.ndarray


class ShapeTable:
    """The shapes of a World's bodies, by row, as narrowphase kinds (built once for a set of
    bodies: a shape never changes). A round shape's centre is its Circle's in the body's frame
    (a body's own disc's is its position; a part's may be off it)."""

    def __init__(self, shapes: Sequence[Any], radius: np.ndarray) -> None:
        n = len(shapes)
        self.kind = np.zeros(n, dtype=np.int8)
        self.index = np.zeros(n, dtype=np.intp)  # the row's place in its kind's arrays
        caps: list[Segment] = []
        polys: list[Polygon] = []
        centre = np.zeros((n, 2))
        for row, shape in enumerate(shapes):
            if shape is None:
                continue
            if isinstance(shape, Circle):
                centre[row] = tuple(shape.center)
                continue
            if isinstance(shape, Compound):
                self.kind[row] = COMPOUND
                continue
            if isinstance(shape, Segment):
                self.kind[row], self.index[row] = CAPSULE, len(caps)
                caps.append(shape)
            elif isinstance(shape, Polygon):
                self.kind[row], self.index[row] = POLYGON, len(polys)
                polys.append(shape)
            else:  # Body checked it: only the kinds above reach here
                raise TypeError(f"no narrowphase for a body's shape {shape!r}")
        #: Which rows carry a shape other than a disc (the soft step always takes them).
        self.shaped = self.kind != DISC
        self.index[~self.shaped] = np.arange(n)[~self.shaped]
        self.circles = Circles(centre, np.asarray(radius, dtype=float))
        self.capsules = Capsules(
            np.array([(s.a.x, s.a.y) for s in caps], dtype=float).reshape(-1, 2),
            np.array([(s.b.x, s.b.y) for s in caps], dtype=float).reshape(-1, 2),
            np.array([s.radius for s in caps], dtype=float),
        )
        self.polygons = Polygons.of_shapes(polys) if polys else None

        #: The bodies' parts (``Parts``), where a body is of several shapes; else None.
        self.parts = _parts(shapes, radius) if (self.kind == COMPOUND).any() else None
        self._extents: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None

    def extended(self, shapes: Sequence[Any], radius: np.ndarray) -> ShapeTable | None:
        """This table with the rows of ``shapes`` added after its own (bodies added at the
        end; ``radius`` every row's, the new ones' after), the same arrays as a table made
        afresh of all of them (a polygon's rows padded with its last corner, as ``Polygons``
        pads). None where a body is of several shapes, here or among the new (made afresh)."""
        if self.parts is not None or any(isinstance(sh, Compound) for sh in shapes):
            return None
        if all(sh is None for sh in shapes):
            return self._with_discs(len(shapes), radius)
        added = ShapeTable(shapes, radius[len(self) :])
        out = ShapeTable.__new__(ShapeTable)
        n_caps = len(self.capsules)
        n_polys = 0 if self.polygons is None else len(self.polygons)
        index = added.index.copy()
        index[added.kind == CAPSULE] += n_caps
        index[added.kind == POLYGON] += n_polys
        index[added.kind == DISC] += len(self)
        out.kind = np.concatenate([self.kind, added.kind])
        out.index = np.concatenate([self.index, index])
        out.shaped = out.kind != DISC
        out.circles = Circles(
            np.concatenate([self.circles.center, added.circles.center]),
            np.asarray(radius, dtype=float),
        )
        out.capsules = Capsules(
            *(
                np.concatenate([getattr(self.capsules, f), getattr(added.capsules, f)])
                for f in ("a", "b", "radius")
            )
        )
        out.polygons = _polygons_joined(self.polygons, added.polygons)
        out.parts = None
        out._extents = None
        if self._extents is not None:
            least, core, centroid = (
                np.concatenate([mine, theirs])
                for mine, theirs in zip(self._extents, added.extents(), strict=True)
            )
            out._extents = out._radii_read(least, core, centroid)
        return out

    def _with_discs(self, k: int, radius: np.ndarray) -> ShapeTable:
        """``extended`` by ``k`` plain discs (a game's bullets and balls): each a round row at
        its body's centre, its own place; the capsules and polygons as they are."""
        n = len(self)
        out = ShapeTable.__new__(ShapeTable)
        out.kind = np.concatenate([self.kind, np.zeros(k, dtype=self.kind.dtype)])
        out.index = np.concatenate([self.index, np.arange(n, n + k, dtype=self.index.dtype)])
        out.shaped = out.kind != DISC
        out.circles = Circles(np.concatenate([self.circles.center, np.zeros((k, 2))]),
                              np.asarray(radius, dtype=float))  # fmt: skip
        out.capsules, out.polygons, out.parts = self.capsules, self.polygons, None
        out._extents = None
        if self._extents is not None:
            least, core, centroid = self._extents
            # A disc's extents: its radius, 0 (its centre is the body's), the origin.
            grown = (np.concatenate([least, np.zeros(k)]), np.concatenate([core, np.zeros(k)]),
                     np.concatenate([centroid, np.zeros((k, 2))]))  # fmt: skip
            out._extents = out._radii_read(*grown)
        return out

    def without(self, keep: np.ndarray, radius: np.ndarray) -> ShapeTable | None:
        """This table with only the rows ``keep`` (bool, a row each) left (bodies taken out;
        ``radius`` the rows' left), the same arrays as a table made afresh of their shapes
        (a polygon's rows padded to the most corners among those left, as ``Polygons`` pads),
        and its extents where they were made. None where a body is of several shapes (made
        afresh)."""
        if self.parts is not None:
            return None
        out = ShapeTable.__new__(ShapeTable)
        out.kind = self.kind[keep]
        # A capsule's and a polygon's place in its kind's arrays is its rank among the rows of
        # its kind (they were listed in row order); a disc's, its row.
        index = np.arange(len(out.kind), dtype=np.intp)
        for code in (CAPSULE, POLYGON):
            mine = out.kind == code
            index[mine] = np.arange(int(np.count_nonzero(mine)))
        out.index = index
        out.shaped = out.kind != DISC
        out.circles = Circles(self.circles.center[keep], np.asarray(radius, dtype=float))
        caps = keep[self.kind == CAPSULE]
        out.capsules = self.capsules  # (every capsule left: the same arrays, kept)
        if not caps.all():
            out.capsules = Capsules(self.capsules.a[caps], self.capsules.b[caps],
                                    self.capsules.radius[caps])  # fmt: skip
        out.polygons = None
        if self.polygons is not None:
            polys = np.flatnonzero(keep[self.kind == POLYGON])
            if len(polys) == len(self.polygons):
                out.polygons = self.polygons  # (every polygon left: a ball taken out)
            elif len(polys):
                out.polygons = self.polygons.take(polys)
        out.parts = None
        out._extents = None
        if self._extents is not None:
            out._extents = out._radii_read(*(e[keep] for e in self._extents))
        return out

    def _radii_read(
        self, least: np.ndarray, core: np.ndarray, centroid: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Extents kept from another table, each round row's least extent read from this
        table's radii: a row kept may be another plain disc's now (bodies taken out and
        added between two steps: engine.pipeline.game_step's ``_rows_left``), of another
        radius."""
        disc = self.kind == DISC
        least[disc] = self.circles.radius[disc]
        return least, core, centroid

    def extents(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each row's least extent (m: a disc's or capsule's radius, a polygon's least distance
        from its centroid to an edge's line plus its rounding), its core's farthest point from
        its centre (m) and its shape's centroid (n, 2) in its frame (the corners' mean); zeros
        for a body of several shapes (its ``parts`` have their own). Made once a table, and for
        a table ``extended``, only for the rows added."""
        if self._extents is None:
            self._extents = _extents(self)
        return self._extents

    def __len__(self) -> int:
        return len(self.kind)

    def kinds(self, rows: np.ndarray) -> Kind:
        """The shapes of ``rows`` (all of one kind) as one narrowphase kind."""
        code = int(self.kind[rows[0]]) if len(rows) else DISC
        idx = self.index[rows]
        if code == CAPSULE:
            return self.capsules.take(idx)
        if code == POLYGON:
            assert self.polygons is not None
            return self.polygons.take(idx)
        return self.circles.take(idx)


def part_pairs(parts: Parts, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pairs of bodies (rows a, b) as pairs of their parts' rows: every part of A with
    every part of B, in the pairs' order, A's parts the outer loop (the compiled step's
    order, engine.pipeline.game_contacts.contacts_loop)."""
    ka, kb = parts.size[a], parts.size[b]
    item, j = part_rows(ka * kb)
    return parts.first[a][item] + j // kb[item], parts.first[b][item] + j % kb[item]


def part_rows(k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each of len(k) items repeated k[i] times (its index), and j = 0 .. k[i] - 1 within it."""
    item = np.repeat(np.arange(len(k)), k)
    j = np.arange(int(k.sum())) - np.repeat(np.cumsum(k) - k, k)
    return item, j


def _parts(shapes: Sequence[Any], radius: np.ndarray) -> Parts:
    """Every body's parts as rows of a table (``Parts``), in body order."""
    kids: list[Any] = []
    radii: list[float] = []
    owner: list[int] = []
    number: list[int] = []
    first = np.zeros(len(shapes), dtype=np.intp)
    size = np.ones(len(shapes), dtype=np.intp)
    for row, shape in enumerate(shapes):
        first[row] = len(kids)
        parts = shape.parts if isinstance(shape, Compound) else (shape,)
        size[row] = len(parts)
        for j, part in enumerate(parts):
            kids.append(part)
            radii.append(part.radius if isinstance(part, Circle) else float(radius[row]))
            owner.append(row)
            number.append(j)
    table = ShapeTable(kids, np.array(radii, dtype=float))
    ints = np.intp
    return Parts(table, np.array(owner, dtype=ints), np.array(number, dtype=ints), first, size)


def _points(m: Manifold) -> tuple[np.ndarray, np.ndarray]:
    """(pair index, point slot) of each point the manifolds hold (count 0 to 2 each)."""
    pair = np.repeat(np.arange(len(m)), 2)
    slot = np.tile(np.arange(2), len(m))
    has = slot < np.repeat(m.count, 2)
    return pair[has], slot[has]


def pair_rows(
    table: ShapeTable,
    a: np.ndarray,
    b: np.ndarray,
    x: np.ndarray,
    margin: float,
    angle: np.ndarray | None = None,
    fast: bool = False,
) -> tuple[np.ndarray, ...]:
    """The rows of pairs (World rows a, b) at positions x (N, 2) and angles ``angle`` (N,)
    (rad; None: all 0): (a, b, the unit normal from a to b (R, 2), the separation (R,), the
    point's key within its pair: its feature id (Box2D's: the vertices that make it, < 2^16,
    so a point keeps its warm start while the same features touch), the point less a's
    position (R, 2), less b's),
    one row a point of each pair's manifold (``engine.geometry.manifold.collide``), every pair of
    kinds at once a kind pair. ``margin`` (length units) is the farthest one body may move
    in the step, slack included: both bodies of a pair may close on each other, so a pair
    gets its rows while its gap is within twice that. ``fast``: pairs of polygons by the loop
    kernel ``engine.geometry.manifold_polygon.polygon_loop``, straight from the table."""
    out: list[list[np.ndarray]] = [[], [], [], [], [], [], []]
    reach = 2.0 * margin
    q = np.zeros(len(x)) if angle is None else angle
    # The kind pair of each pair as one code 3 ka + kb; only the codes present are visited.
    code = table.kind[a].astype(np.intp) * 3 + table.kind[b]
    present = np.bincount(code, minlength=9)
    for code_a in (DISC, CAPSULE, POLYGON):
        for code_b in (DISC, CAPSULE, POLYGON):
            if not present[3 * code_a + code_b]:
                continue
            sel = np.flatnonzero(code == 3 * code_a + code_b)
            ia, ib = a[sel], b[sel]
            if fast and code_a == code_b == POLYGON:
                m = _polygon_pairs(table, ia, ib, x, q, reach)
            else:
                m = collide(table.kinds(ia), x[ia], q[ia], table.kinds(ib), x[ib], q[ib], reach)
            pair, slot = _points(m)
            out[0].append(ia[pair])
            out[1].append(ib[pair])
            out[2].append(m.normal[pair])
            out[3].append(m.separation[pair, slot])
            out[4].append(m.feature[pair, slot] & 0xFFFF)
            out[5].append(m.anchor_a[pair, slot])
            out[6].append(m.anchor_b[pair, slot])
    return _joined(out)


def _polygon_pairs(
    table: ShapeTable, ia: np.ndarray, ib: np.ndarray, x: np.ndarray, q: np.ndarray, reach: float
) -> Manifold:
    """The manifolds of pairs of polygon bodies (World rows ia, ib), by the loop kernel on the
    table's own arrays (no ``take`` of the shapes): ``collide_polygons(fast=True)``."""
    P = table.polygons
    assert P is not None
    return Manifold(
        *polygon_loop(
            P.vertices, P.normals, P.count, P.radius, table.index[ia], x[ia], q[ia],
            P.vertices, P.normals, P.count, P.radius, table.index[ib], x[ib], q[ib], reach,
        )
    )  # fmt: skip


def _on_half_planes(
    table: ShapeTable,
    body: np.ndarray,
    x: np.ndarray,
    q: np.ndarray,
    walls: HalfPlanes,
    c: np.ndarray,
    margin: float,
) -> Manifold:
    """The manifolds of polygon bodies (World rows ``body``) against half planes ``c`` of
    ``walls`` (the static body: at the origin, angle 0), the body as A, by the loop kernel on
    the table's own arrays: ``collide(..., fast=True)``."""
    P = table.polygons
    assert P is not None
    zero = np.zeros(len(body))
    return Manifold(
        *half_plane_polygon_loop(
            walls.point, walls.normal, c, np.zeros((len(body), 2)), zero,
            P.vertices, P.normals, P.count, P.radius, table.index[body], x[body], q[body], margin,
        )
    ).flipped()  # fmt: skip


def static_rows(
    table: ShapeTable,
    rows: np.ndarray,
    x: np.ndarray,
    statics: StaticShapes,
    solid: np.ndarray,
    margin: float,
    angle: np.ndarray | None = None,
    meets: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
    fast: bool = False,
) -> tuple[np.ndarray, ...]:
    """The rows of bodies ``rows`` (World rows, with shapes) against the World's colliders
    (``statics``, ``engine.geometry.manifold.static_shapes``; ``solid`` (C,) bool: which colliders
    are solid, not sensors): (row, the collider's index, the unit normal from the collider
    to the body (R, 2), the separation (R,), the point's key: 2^16 c + its feature id for the
    c-th static shape of its kind, the point less the body's position (R, 2)), the bodies at their
    ``angle`` (N,) (rad; None: all 0). ``meets(rows, colliders)``: which body-collider pairs
    their filters let meet (None: all). ``fast``: each kind pair's loop kernel where it has
    one (polygons on half planes straight from the table)."""
    out: list[list[np.ndarray]] = [[], [], [], [], [], []]
    q = np.zeros(len(x)) if angle is None else angle
    for code in (DISC, CAPSULE, POLYGON):
        mine = rows[table.kind[rows] == code]
        if not len(mine):
            continue
        shapes = table.kinds(mine)
        for base, (kind, owner) in enumerate(statics.kinds()):
            keep = np.flatnonzero(solid[owner])
            if not len(keep):
                continue
            r_i = np.repeat(np.arange(len(mine)), len(keep))
            c_i = np.tile(keep, len(mine))
            if meets is not None:
                ok = meets(mine[r_i], owner[c_i])
                r_i, c_i = r_i[ok], c_i[ok]
                if not len(r_i):
                    continue
            gap = _gaps(kind, c_i, x[mine[r_i]])
            if gap is not None:
                # Only the shapes the body's bounding circle comes within the margin of: the
                # narrowphase would give the others no rows (the same rows, in the same
                # order, for far less work on a table of many colliders).
                gap -= table.circles.radius[mine[r_i]]
                near = gap <= margin * (1.0 + 1e-9) + 1e-12
                r_i, c_i = r_i[near], c_i[near]
                if not len(r_i):
                    continue
            body = mine[r_i]
            if fast and code == POLYGON and isinstance(kind, HalfPlanes):
                m = _on_half_planes(table, body, x, q, kind, c_i, margin)
            else:
                shape, wall = shapes.take(r_i), kind.take(c_i)
                m = collide(shape, x[body], q[body], wall, (0.0, 0.0), 0.0, margin, fast)
            pair, slot = _points(m)
            out[0].append(mine[r_i[pair]])
            out[1].append(owner[c_i[pair]])
            out[2].append(-m.normal[pair])
            out[3].append(m.separation[pair, slot])
            out[4].append((base * 1_000_003 + c_i[pair]) * 65536 + (m.feature[pair, slot] & 0xFFFF))
            out[5].append(m.anchor_a[pair, slot])
    return _joined(out)


def _gaps(kind: Kind, c: np.ndarray, p: np.ndarray) -> np.ndarray | None:
    """A lower bound on the gap (length units) from points ``p`` (R, 2) to the static shapes
    ``c`` (R,) of ``kind``: to a circle or a capsule exactly, to a polygon its bounding
    circle; None for half planes (no end)."""
    if isinstance(kind, Circles):
        d = p - kind.center[c]
        return np.sqrt(np.einsum("ij,ij->i", d, d)) - kind.radius[c]
    if isinstance(kind, Capsules):
        a, ab = kind.a[c], kind.b[c] - kind.a[c]
        u = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.einsum("ij,ij->i", ab, ab), 0.0, 1.0)
        d = p - a - u[:, None] * ab
        return np.sqrt(np.einsum("ij,ij->i", d, d)) - kind.radius[c]
    if isinstance(kind, Polygons):
        v = kind.vertices[c]
        centre = v.mean(axis=1)
        e = v - centre[:, None, :]
        reach = np.sqrt(np.einsum("ijk,ijk->ij", e, e)).max(axis=1) + kind.radius[c]
        d = p - centre
        return np.sqrt(np.einsum("ij,ij->i", d, d)) - reach
    return None


def _joined(out: list[list[np.ndarray]]) -> tuple[np.ndarray, ...]:
    anchors = tuple(np.zeros((0, 2)) for _ in out[5:])
    if not out[0]:
        return (
            np.zeros(0, dtype=np.intp),
            np.zeros(0, dtype=np.intp),
            np.zeros((0, 2)),
            np.zeros(0),
            np.zeros(0, dtype=np.int64),
            *anchors,
        )
    return (
        np.concatenate(out[0]),
        np.concatenate(out[1]),
        np.concatenate(out[2]),
        np.concatenate(out[3]),
        np.concatenate(out[4]).astype(np.int64),
        *(np.concatenate(k) for k in out[5:]),
    )


def _polygons_joined(first: Polygons | None, then: Polygons | None) -> Polygons | None:
    """Two tables of polygons as one, ``first``'s rows then ``then``'s, each padded to the
    longer's corners with its last corner and normal (as ``Polygons`` pads)."""
    if first is None or then is None:
        return then if first is None else first
    m = max(first.vertices.shape[1], then.vertices.shape[1])

    def padded(what: np.ndarray) -> np.ndarray:
        extra = m - what.shape[1]
        if not extra:
            return what
        return np.concatenate([what, np.repeat(what[:, -1:], extra, axis=1)], axis=1)

    return Polygons(
        np.concatenate([padded(first.vertices), padded(then.vertices)]),
        np.concatenate([padded(first.normals), padded(then.normals)]),
        np.concatenate([first.count, then.count]),
        np.concatenate([first.radius, then.radius]),
    )


def _extents(table: ShapeTable) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``ShapeTable.extents``: a few array calls whatever the rows (a corner place at a time:
    each polygon's own corners, in their order, as a loop over bodies took them; a capsule as
    its two-corner polygon, engine.geometry.manifold_kinds.Polygons.from_capsules)."""
    n = len(table)
    least, core, centroid = np.zeros(n), np.zeros(n), np.zeros((n, 2))
    disc = table.kind == DISC
    c = table.circles.center[disc]
    centroid[disc] = c
    core[disc] = np.hypot(c[:, 0], c[:, 1])
    least[disc] = table.circles.radius[disc]
    caps = Polygons.from_capsules(table.capsules) if len(table.capsules) else None
    for kind, polys in ((POLYGON, table.polygons), (CAPSULE, caps)):
        rows = np.flatnonzero(table.kind == kind)
        if not len(rows) or polys is None:
            continue
        j = table.index[rows]
        k = polys.count[j]
        v, nrm = polys.vertices[j], polys.normals[j]
        # The corners' mean: summed corner by corner (a body's own corners only), over k.
        total = v[:, 0].copy()
        for e in range(1, int(k.max())):
            on = e < k
            total[on] += v[on, e]
        mean = total / k[:, None]
        far = np.full(len(j), -np.inf)
        depth = np.full(len(j), np.inf)
        for e in range(int(k.max())):
            on = e < k
            d = v[:, e] - mean
            inward = d[:, 0] * nrm[:, e, 0] + d[:, 1] * nrm[:, e, 1]  # (< 0: the centroid in)
            far = np.where(on, np.maximum(far, np.hypot(v[:, e, 0], v[:, e, 1])), far)
            depth = np.where(on, np.minimum(depth, inward), depth)
        centroid[rows] = mean
        core[rows] = far
        least[rows] = np.maximum(depth, 0.0) + polys.radius[j]
    return least, core, centroid
