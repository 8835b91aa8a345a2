"""The queries' spatial index: the few colliders and bodies a query need test exactly.

A query (``engine.pipeline.queries``) meets only what lies near it: a 13 cm ground test under a
player's feet has no business with a platform across the level. The index answers, for a
query's region (a segment grown by a radius, a point grown by a distance, a box), the
colliders and body rows whose boxes reach it, ascending; the queries then run their exact
tests on those alone, in the World's order, so they find what testing everything would.

**Colliders** (``ColliderGrid``) sit in a uniform grid of square cells of side h, a dict
from a cell (column * rows + row) to the ascending indices of the colliders listed there. A
collider is listed in the cells its box overlaps; a segment or capsule, which may run far on
a slant, only in the cells along it (``cells_along``: column by column). h is the median of
the colliders' sizes (a typical collider spans a cell or two), at least 1/1024 of their
whole extent, and doubled while the lists would hold more than 32 entries a collider. A
collider with no finite bounds (a ``Plane``; a ``Box``, whose solid is everything outside
its room) is on every query's list. Each collider's flat and round faces are kept with it.
The grid is made on the first query after the colliders change (the World's list is
compared with the one it was made from, member by member: the same objects in the same
order) and kept till then.

**Bodies** move every step. What moving leaves alone (radii, filters, which bodies have
shapes: ``BodyTable``) is kept till bodies come or go; where they are (``BodyBins``: their
positions as floats, and the rows in each cell of side about their spacing, sqrt(area / N),
at least twice their mean radius) is made again when their positions differ, byte for byte
(one ``tobytes``), from the ones the bins were made from. A query looks in the cells its
region reaches grown by the largest radius binned, and tests each body found by its box: its
position +- its radius (``store.radius``: for a body with a shape, the circle about its
position that holds the shape). A body of radius more than half a cell is in no cell but on
every query's list. Bins cost a few array operations and lists of every body, worth it for
the second query before the bodies move again but not for a game's one ground test a step:
so past ``QueryIndex.FEW_BODIES`` bodies, the first query at new positions tests every
body's box at once in numpy (``bodies_near``), as does a region of more than 256 cells, and
the second makes the bins; fewer bodies are binned at once, in no cells (a loop over them
all is quicker than a numpy call).

**Margins.** The exact tests round, and a hit they report may lie a little outside the
shape it is on: by a few units in the last place of the numbers involved, and for a ray
that grazes a round face by up to sqrt(2.2e-16) ~ 1.5e-8 of the distance from the ray's
start (the root of a discriminant that cancels). So every region is grown before it is
compared: a query's by ``margin`` (1e-6 of its coordinates, length and radius, plus 1e-6
length units), each collider's box by 1e-6 of its coordinates and size (``pads``; a room's
or a plane's of its corners or point), each body's radius by 1e-6 of itself. Growing a
region only adds candidates, which the exact tests turn down; the queries' own shortcuts
(a start farther than these margins from a collider is not inside it) use the same.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from typing import Any

import numpy as np

from .colliders import Box as Room
from .colliders import Circle, Collider, Disc, Line, Plane, Segment

__all__ = [
    "GROW",
    "BodyBins",
    "BodyTable",
    "ColliderGrid",
    "QueryIndex",
    "bodies_near",
    "looks",
    "margin",
]

#: The relative growth of every region compared (see the module doc: Margins).
GROW = 1e-6
#: The most cells a region's box may cover for its cells to be taken whole, not along it.
_FEW_CELLS = 16
#: The cells a side the collider grid has at least (h is at most 1/1024 of the extent).
_SIDE_CELLS = 1024
#: Entries a collider the lists may hold on average before h doubles.
_ENTRIES_EACH = 32
#: The most cells a side the bodies' bins have.
_BIN_SIDE = 4096
#: The most cells of bins a query looks in; past it, every body's box is tested in numpy.
_WIDE = 256

Box = tuple[float, float, float, float]


def margin(x0: float, y0: float, x1: float, y1: float, length: float, radius: float) -> float:
    """How far a query's region is grown: 1e-6 of its coordinates (the two corners of its
    box), its length and its radius, plus 1e-6 length units."""
    return GROW * (1.0 + abs(x0) + abs(y0) + abs(x1) + abs(y1) + abs(length) + radius)


def _pad_without_end(c: Collider) -> float:
    """The margin of a collider with no finite bounds: 1e-6 of a room's corners and size,
    of a plane's point (inf for what else might come: every test then asks it)."""
    if isinstance(c, Room):
        (x0, y0), (x1, y1) = c.lower_left, c.upper_right
        return GROW * (max(abs(x0), abs(y0), abs(x1), abs(y1)) + (x1 - x0) + (y1 - y0))
    if isinstance(c, Plane):
        return GROW * (abs(c.point.x) + abs(c.point.y))
    return math.inf


def looks(c: Collider) -> tuple[list[Line], list[Disc], Box, float]:
    """What a query's exact test reads of a collider (or a body's shape, in its frame), once:
    its flat and round faces (``Collider.lines``, ``Collider.discs``), its box grown by its pad
    (1e-6 of its coordinates and size: the module doc's Margins), and the pad."""
    x0, y0, x1, y1 = c.bounds()
    m = GROW * (max(abs(x0), abs(y0), abs(x1), abs(y1)) + (x1 - x0) + (y1 - y0))
    return c.lines(), c.discs(), (x0 - m, y0 - m, x1 + m, y1 + m), m


def _finite(box: Box) -> bool:
    """Whether a box's width and height (so its sides too) are finite numbers."""
    return math.isfinite(box[2] - box[0]) and math.isfinite(box[3] - box[1])


# -- colliders -------------------------------------------------------------------------------
class ColliderGrid:
    """The colliders of a World at one moment, listed by cell (see the module doc)."""

    def __init__(self, colliders: Iterable[Collider]) -> None:
        #: The colliders it was made from, in the World's order (its key: the same objects).
        self.colliders = list(colliders)
        #: Each collider's box, grown by its margin (infinite where it has no end).
        self.boxes: list[Box] = []
        #: How far each box is grown past the collider's bounds: 1e-6 of its coordinates and
        #: size (of a room's corners, a plane's point, for those without end).
        self.pads: list[float] = []
        #: Each collider's flat and round faces (``Collider.lines``, ``Collider.discs``).
        self.faces: list[tuple[list[Line], list[Disc]]] = []
        #: The colliders on every query's list (no finite bounds), ascending.
        self.everywhere: tuple[int, ...] = ()
        #: Cell (column * rows + row) -> the colliders listed there, ascending.
        self.cells: dict[int, tuple[int, ...]] = {}
        self.h = 1.0  # a cell's side (length units)
        self.ox = self.oy = 0.0  # the lower left corner of cell (0, 0)
        self.columns = self.rows = 0
        everywhere: list[int] = []
        gridded: list[int] = []
        for k, c in enumerate(self.colliders):
            lines, discs, grown, m = looks(c)
            self.faces.append((lines, discs))
            if math.isfinite(m) and _finite(grown):
                self.boxes.append(grown)
                self.pads.append(m)
                gridded.append(k)
            else:
                self.boxes.append((-math.inf, -math.inf, math.inf, math.inf))
                self.pads.append(_pad_without_end(c))
                everywhere.append(k)
        self.everywhere = tuple(everywhere)
        if gridded:
            self._build(gridded)

    def _build(self, gridded: list[int]) -> None:
        boxes = [self.boxes[k] for k in gridded]
        x0 = min(b[0] for b in boxes)
        y0 = min(b[1] for b in boxes)
        x1 = max(b[2] for b in boxes)
        y1 = max(b[3] for b in boxes)
        sizes = sorted(max(b[2] - b[0], b[3] - b[1]) for b in boxes)
        extent = max(x1 - x0, y1 - y0)
        h = max(sizes[len(sizes) // 2], extent / _SIDE_CELLS, 1e-300)
        self.ox, self.oy = x0, y0
        limit = _ENTRIES_EACH * len(gridded) + 4096
        while True:
            self.h = h
            self.columns = math.floor((x1 - x0) / h) + 1
            self.rows = math.floor((y1 - y0) / h) + 1
            lists: dict[int, list[int]] = {}
            entries = 0
            for k in gridded:
                c = self.colliders[k]
                if isinstance(c, Segment):
                    # Along its core, as wide as its radius and the box's growth.
                    w = c.radius + self.pads[k]
                    cells = self.cells_along(c.a.x, c.a.y, c.b.x, c.b.y, w)
                else:
                    cells = self.cells_of_box(self.boxes[k])
                for cell in cells:
                    lists.setdefault(cell, []).append(k)
                    entries += 1
                    if entries > limit:
                        break
                if entries > limit:
                    break
            else:
                break
            h *= 2.0
        self.cells = {cell: tuple(ks) for cell, ks in lists.items()}

    def _span(self, lo: float, hi: float, axis: int) -> tuple[int, int]:
        """The cells (first, last) along ``axis`` (0: x, 1: y) that [lo, hi] overlaps,
        clipped to the grid (first > last: none)."""
        o, n = (self.ox, self.columns) if axis == 0 else (self.oy, self.rows)
        a, b = (lo - o) / self.h, (hi - o) / self.h
        if b < 0.0 or a >= n:
            return 0, -1
        return (math.floor(a) if a > 0.0 else 0), (math.floor(b) if b < n - 1 else n - 1)

    def cells_of_box(self, box: Box) -> list[int]:
        """The cells that ``box`` overlaps."""
        i0, i1 = self._span(box[0], box[2], 0)
        j0, j1 = self._span(box[1], box[3], 1)
        rows = self.rows
        return [i * rows + j for i in range(i0, i1 + 1) for j in range(j0, j1 + 1)]

    def cells_along(self, ax: float, ay: float, bx: float, by: float, w: float) -> list[int]:
        """The cells that hold a point within ``w`` (in x and in y) of the segment a-b.

        Column by column along the longer way: the part of the segment whose x lies within
        w of the column spans, being straight, the y between its ends' y, which grown by w
        gives the column's rows. A box of few cells is taken whole."""
        i0, i1 = self._span(min(ax, bx) - w, max(ax, bx) + w, 0)
        j0, j1 = self._span(min(ay, by) - w, max(ay, by) + w, 1)
        rows = self.rows
        if (i1 - i0 + 1) * (j1 - j0 + 1) <= _FEW_CELLS:
            return [i * rows + j for i in range(i0, i1 + 1) for j in range(j0, j1 + 1)]
        out: list[int] = []
        if i1 - i0 >= j1 - j0:
            for i, ja, jb in self._sweep(ax, ay, bx, by, w, i0, i1, 0):
                out += range(i * rows + max(ja, j0), i * rows + min(jb, j1) + 1)
        else:
            for j, ia, ib in self._sweep(ay, ax, by, bx, w, j0, j1, 1):
                out += range(max(ia, i0) * rows + j, min(ib, i1) * rows + j + 1, rows)
        return out

    def _sweep(
        self, ax: float, ay: float, bx: float, by: float, w: float, i0: int, i1: int, axis: int
    ) -> Iterator[tuple[int, int, int]]:
        """(column, first row, last row) of ``cells_along`` along ``axis`` (0: x; 1: y, the
        roles of the coordinates swapped)."""
        o, h = (self.ox if axis == 0 else self.oy), self.h
        dx, dy = bx - ax, by - ay
        for i in range(i0, i1 + 1):
            lo, hi = o + i * h - w, o + (i + 1) * h + w
            if dx == 0.0:
                t0, t1 = 0.0, 1.0
            else:
                t0, t1 = (lo - ax) / dx, (hi - ax) / dx
                if t0 > t1:
                    t0, t1 = t1, t0
                t0, t1 = max(t0, 0.0), min(t1, 1.0)
                if t0 > t1:
                    continue
            ya, yb = ay + dy * t0, ay + dy * t1
            ja, jb = self._span(min(ya, yb) - w, max(ya, yb) + w, 1 - axis)
            yield i, ja, jb

    def near_segment(self, ax: float, ay: float, bx: float, by: float, w: float) -> list[int]:
        """The colliders whose boxes come within ``w`` (in x and in y) of the segment a-b,
        ascending."""
        x0, x1 = (ax - w, bx + w) if ax <= bx else (bx - w, ax + w)
        y0, y1 = (ay - w, by + w) if ay <= by else (by - w, ay + w)
        return self._sift(self._listed(x0, y0, x1, y1, (ax, ay, bx, by, w)), x0, y0, x1, y1)

    def near_box(self, box: Box) -> list[int]:
        """The colliders whose boxes overlap ``box`` = (left, bottom, right, top), ascending."""
        x0, y0, x1, y1 = box
        return self._sift(self._listed(x0, y0, x1, y1, None), x0, y0, x1, y1)

    def _listed(
        self,
        x0: float,
        y0: float,
        x1: float,
        y1: float,
        along: tuple[float, float, float, float, float] | None,
    ) -> list[tuple[int, ...]]:
        """The lists of the cells that the box (x0, y0, x1, y1) overlaps; of those along
        the segment (ax, ay, bx, by) grown by w, ``along``, when the box has many."""
        cells = self.cells
        if not cells:
            return []
        if not (x1 - x0 < math.inf and y1 - y0 < math.inf):
            return list(cells.values())  # a region without end (or past the float range)
        # The common case first, inline: a short query's box of few cells.
        h, n, m = self.h, self.columns, self.rows
        i0, i1 = (x0 - self.ox) / h, (x1 - self.ox) / h
        j0, j1 = (y0 - self.oy) / h, (y1 - self.oy) / h
        if i1 < 0.0 or j1 < 0.0 or i0 >= n or j0 >= m:
            return []
        i0 = math.floor(i0) if i0 > 0.0 else 0
        j0 = math.floor(j0) if j0 > 0.0 else 0
        i1 = math.floor(i1) if i1 < n - 1 else n - 1
        j1 = math.floor(j1) if j1 < m - 1 else m - 1
        get = cells.get
        if i0 == i1 and j0 == j1:
            listed = get(i0 * m + j0)
            return [] if listed is None else [listed]
        count = (i1 - i0 + 1) * (j1 - j0 + 1)
        if count <= _FEW_CELLS or (along is None and count <= len(cells)):
            return [
                listed
                for i in range(i0 * m, i1 * m + 1, m)
                for key in range(i + j0, i + j1 + 1)
                if (listed := get(key)) is not None
            ]
        if along is None:  # more cells than listed: the listed ones in range
            return [
                listed
                for key, listed in cells.items()
                if i0 <= key // m <= i1 and j0 <= key % m <= j1
            ]
        return [listed for key in self.cells_along(*along) if (listed := get(key)) is not None]

    def _sift(
        self, found: list[tuple[int, ...]], x0: float, y0: float, x1: float, y1: float
    ) -> list[int]:
        """The colliders of the lists ``found`` and everywhere whose boxes overlap the box
        (x0, y0, x1, y1), ascending."""
        everywhere = self.everywhere
        if not found:
            ks: Iterable[int] = everywhere
        elif len(found) == 1:  # one cell's list, which no collider everywhere is in
            ks = sorted(found[0] + everywhere) if everywhere else found[0]
        else:  # a collider may be listed in several cells
            ks = sorted(set().union(*found, everywhere))
        boxes = self.boxes
        return [
            k for k in ks if (b := boxes[k])[0] <= x1 and b[2] >= x0 and b[1] <= y1 and b[3] >= y0
        ]


# -- bodies -----------------------------------------------------------------------------------
class BodyTable:
    """What the queries need of a World's bodies that moving them leaves alone: radii,
    filters, which bodies have shapes. Made again when bodies come or go (the store then
    makes new arrays of every per-body value: ``fits`` compares two by identity)."""

    def __init__(self, store: Any) -> None:
        self.radius, self.filters = store.radius, store.group
        #: Radii (length units), as floats and grown by the margin (floats and array).
        self.r: list[float] = store.radius.tolist()
        self.reach_array: np.ndarray = store.radius * (1.0 + GROW)
        self.reach: list[float] = self.reach_array.tolist()
        #: Filters as ints, by row.
        self.group: list[int] = store.group.tolist()
        self.categories: list[int] = store.categories.tolist()
        self.mask: list[int] = store.mask.tolist()
        #: The rows of bodies with a shape other than a circle about their position.
        shapes = store.shapes
        self.shaped: set[int] = (
            set()
            if shapes.count(None) == len(shapes)
            else {k for k, s in enumerate(shapes) if s is not None and not isinstance(s, Circle)}
        )

        #: id(shape) -> (the shape, ``looks(shape)``): a body's shape as a query's exact test
        #: reads it, made when a query first meets it (a body's shape never changes).
        self._looks: dict[int, tuple[Any, tuple[list[Line], list[Disc], Box, float]]] = {}

    def fits(self, store: Any) -> bool:
        """Whether this table is of ``store``'s bodies."""
        return self.radius is store.radius and self.filters is store.group

    def looks(self, shape: Any) -> tuple[list[Line], list[Disc], Box, float]:
        """``looks(shape)`` for a body's shape (or a part of it), in its body's frame: made
        once, on the first query that meets it."""
        kept = self._looks.get(id(shape))
        if kept is None or kept[0] is not shape:
            kept = self._looks[id(shape)] = (shape, looks(shape))
        return kept[1]


class BodyBins:
    """A World's 2D bodies where they are, put in cells by their centres (the module doc);
    ``cells`` False: in none, every body on every query's list (for a few bodies)."""

    def __init__(self, store: Any, table: BodyTable, x_bytes: bytes, cells: bool = True) -> None:
        x, r = store.x, store.radius
        #: What they were made from: the table of their bodies, the positions' bytes.
        self.table, self.x_bytes = table, x_bytes
        n = len(r)
        #: Positions (length units) as floats, by row.
        self.xy: list[list[float]] = x.tolist()
        self.cells: dict[int, list[int]] = {}
        self.big: list[int] = list(range(n))  # on every query's list
        self.h = 1.0
        self.ox = self.oy = 0.0
        self.columns = self.rows = 1
        self.r_binned = 0.0
        if n and cells:
            self._bin(x, r)

    def _bin(self, x: np.ndarray, r: np.ndarray) -> None:
        lo, hi = x.min(axis=0), x.max(axis=0)
        width, height = float(hi[0] - lo[0]), float(hi[1] - lo[1])
        n = len(r)
        spacing = max(math.sqrt(width * height / n), max(width, height) / n)
        h = max(spacing, 2.0 * float(r.mean()), width / _BIN_SIDE, height / _BIN_SIDE)
        if not (math.isfinite(h) and h > 0.0):
            return  # all at one point with no size, or spread past the float range: all big
        small = r <= 0.5 * h
        self.h, (self.ox, self.oy) = h, (float(lo[0]), float(lo[1]))
        self.columns = math.floor(width / h) + 1
        self.rows = math.floor(height / h) + 1
        ij = np.floor((x - lo) / h).astype(np.int64)
        key = ij[:, 0] * self.rows + ij[:, 1]
        key[~small] = -1
        order = np.argsort(key, kind="stable")
        sorted_key = key[order]
        starts = np.flatnonzero(np.diff(sorted_key)) + 1
        bounds = [0, *starts.tolist(), n]
        rows = order.tolist()
        keys = sorted_key[bounds[:-1]].tolist()
        self.cells = {k: rows[s:e] for k, s, e in zip(keys, bounds, bounds[1:], strict=False)}
        self.big = self.cells.pop(-1, [])
        self.big.sort()
        self.r_binned = float(r.max(initial=0.0, where=small)) * (1.0 + GROW)

    def near(self, box: Box) -> list[int] | None:
        """The rows (ascending) of the bodies whose boxes overlap ``box``; None when the box
        covers more than ``_WIDE`` cells (``bodies_near`` tests them all at once then)."""
        x0, y0, x1, y1 = box
        cells = self.cells
        if cells:
            if not (x1 - x0 < math.inf and y1 - y0 < math.inf):
                return None
            g, h, n, m = self.r_binned, self.h, self.columns, self.rows
            i0, i1 = (x0 - g - self.ox) / h, (x1 + g - self.ox) / h
            j0, j1 = (y0 - g - self.oy) / h, (y1 + g - self.oy) / h
            if i1 < 0.0 or j1 < 0.0 or i0 >= n or j0 >= m:
                found = self.big
            else:
                i0 = math.floor(i0) if i0 > 0.0 else 0
                j0 = math.floor(j0) if j0 > 0.0 else 0
                i1 = math.floor(i1) if i1 < n - 1 else n - 1
                j1 = math.floor(j1) if j1 < m - 1 else m - 1
                if i0 == i1 and j0 == j1:
                    found = cells.get(i0 * m + j0, [])
                elif (i1 - i0 + 1) * (j1 - j0 + 1) > _WIDE:
                    return None
                else:
                    get = cells.get
                    found = [
                        k
                        for i in range(i0 * m, i1 * m + 1, m)
                        for key in range(i + j0, i + j1 + 1)
                        if (listed := get(key)) is not None
                        for k in listed
                    ]
                if self.big:
                    found = found + self.big
        elif len(self.big) > _WIDE:
            return None
        else:
            found = self.big
        xy, reach = self.xy, self.table.reach
        out = [
            k
            for k in found
            if (p := xy[k])[0] + (s := reach[k]) >= x0
            and p[0] - s <= x1
            and p[1] + s >= y0
            and p[1] - s <= y1
        ]
        if len(out) > 1:
            out.sort()
        return out


def bodies_near(x: np.ndarray, reach: np.ndarray, box: Box) -> np.ndarray:
    """The rows (ascending) of bodies at ``x`` (N, 2) whose boxes, +- ``reach`` (N,: their
    radii grown by the margin), overlap ``box`` = (left, bottom, right, top), in a few array
    operations on all of them."""
    x0, y0, x1, y1 = box
    px, py = x[:, 0], x[:, 1]
    ok = (px + reach >= x0) & (px - reach <= x1) & (py + reach >= y0) & (py - reach <= y1)
    return np.flatnonzero(ok)


# -- the World's index ------------------------------------------------------------------------
class QueryIndex:
    """A World's index for queries: its collider grid, its bodies' table and their bins,
    each made again when what it was made from changes (the module doc)."""

    __slots__ = ("_grid", "_table", "_bins", "_asked")

    #: Bodies up to which bins are made at once, in no cells; past it, on the second query
    #: at the same positions (the first tests every body's box in numpy).
    FEW_BODIES = 32

    def __init__(self) -> None:
        self._grid: ColliderGrid | None = None
        self._table: BodyTable | None = None
        self._bins: BodyBins | None = None
        self._asked: bytes | None = None  # the positions of the last unbinned query

    def colliders(self, current: list[Collider]) -> ColliderGrid:
        """The grid of ``current`` (the World's colliders, in order): the one made before
        if they are the same objects in the same order, else a new one."""
        grid = self._grid
        if grid is None or grid.colliders != current:
            grid = self._grid = ColliderGrid(current)
        return grid

    def table(self, store: Any) -> BodyTable:
        """The table of ``store``'s bodies: the one made before if it fits, else a new one."""
        table = self._table
        if table is None or not table.fits(store):
            table = self._table = BodyTable(store)
            self._bins, self._asked = None, None
        return table

    def bodies(self, store: Any, table: BodyTable) -> BodyBins | None:
        """The bins of ``store``'s bodies (of ``table``) where they are now: the ones made
        before if at the same positions, or None: test them all (see the class doc)."""
        x_bytes = store.x.tobytes()
        bins = self._bins
        if bins is not None and bins.table is table and bins.x_bytes == x_bytes:
            return bins
        few = len(table.r) <= self.FEW_BODIES
        if few or self._asked == x_bytes:
            self._asked = None
            bins = self._bins = BodyBins(store, table, x_bytes, cells=not few)
            return bins
        self._asked, self._bins = x_bytes, None
        return None
