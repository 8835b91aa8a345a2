"""The face grid's in-place updates: a collider added or taken out between steps.

A game adds a peg to a board, or takes a brick out of a wall, between steps. Building the
broadphase (engine.geometry.face_grid) afresh costs the whole board; ``FaceGridEdits.added`` and
``removed`` change the grid in place and cost the one collider, and leave it exactly as a
fresh build would (the same bounds, the lists in the same order, the same capsules), which
tests/test_collider_changes.py checks bit for bit. When a fresh build would lay the grid
differently (the faces' extent or its endless faces change, or a table outgrows
``engine.geometry.cell_table.TABLE_SIZE``) they change nothing and answer False, and the caller
drops the grid.

What a face gives the grid. Each finite face is a capsule, the points within rad of a
segment a-b (a flat face is the middle of its segment's, a round face one with a = b). Its
distance from a point x is |x - (a + u (b - a))| - rad with
u = clip((x - a).(b - a) / |b - a|^2, 0, 1), the parameter of the segment's nearest point.
No point of a cell of side h is nearer than the cell's centre less half its diagonal,
h / sqrt(2), so the face gives each cell the lower bound ``distances``: the distance from
the centre less h / sqrt(2). A cell's bound is the least over the faces, kept up to ``far``
(16 h), so a face changes only the cells of its window (``window``): its box grown by
rad + far + h. A cell lists the faces whose own bound there is at most ``pad`` (4 h).

Adding a face is then a minimum: bound <- min(bound, its distances) over its window, and the
face put into the lists of the cells it is within pad of. Taking one out is not (a minimum
cannot be undone): only the cells whose bound it gave (its distance there equals the bound)
change, to the least of the faces left whose windows hold them (``_least``), or ``far``.
Each number comes from the same operations on the same coordinates as in a fresh build, so
the bits agree: the order of a minimum's operands does not change its value.

The lists' order. A fresh build lists each cell's faces by face index, endless ones first.
Faces are renumbered by a change (a new collider's flat faces go before every round face;
taking one out moves the later faces down), so the lists hold slots, each a face's index
when it was listed, and ``_slot_face`` gives each slot's index now (``_face_slot`` the
reverse). A new round face is last in every list, as it is by index; a new flat face goes in
its place by the slots' keys (``_keys``). When more than half the slots are let go, the
tables are renumbered once (``_compact``).

The state below is the grid's (engine.geometry.face_grid lays it out when it builds one); this class
holds the part of the grid's code that changes it.
"""

from __future__ import annotations

import math

import numpy as np

from .cell_table import insert_slot, take_out_slot
from .faces import Faces

__all__ = ["FaceGridEdits", "length2"]


def length2(a: np.ndarray, b: np.ndarray) -> float:
    """|b - a|^2 of two points (2,), as ``FaceGridEdits.distances`` has always taken it."""
    ab = b - a
    return float(ab @ ab)


_FLIP = np.array([1, -1, 1, -1], dtype=np.intp)  # for ``FaceGridEdits._least``'s test of windows


class FaceGridEdits:
    """What a face gives the grid's cells (``window``, ``distances``), and the grid changed
    in place when a collider is added (``added``) or taken out (``removed``): the base of
    ``engine.geometry.face_grid.FaceGrid``, which builds the state declared here."""

    #: The grid: its lower-left corner, cell side h (length units) and cells (nx, ny).
    lo: np.ndarray
    h: float
    shape: tuple[int, int]
    #: A body reaching at most pad meets only its cell's list; bounds are kept up to far.
    pad: float
    far: float
    #: The cells' centres, x by column and y by row, and half a cell's diagonal.
    gx: np.ndarray
    gy: np.ndarray
    half_diag: float
    #: Each cell's lower bound on the distance to the finite faces (nx, ny).
    bound: np.ndarray
    #: The finite faces' indices and count; the endless faces' indices.
    finite: np.ndarray
    n_finite: int
    inf_ids: np.ndarray
    #: The lists as tables (engine.geometry.cell_table): with the endless faces, and without.
    table: np.ndarray | None
    fin_table: np.ndarray | None
    #: Each face's capsule numbers for the narrow pass: a, b - a, 1 / |b - a|^2, rad grown.
    cap: np.ndarray
    _ext: tuple[np.ndarray, np.ndarray, float]
    _slot_face: np.ndarray
    _face_slot: np.ndarray
    _slot_inf: np.ndarray
    _seg: np.ndarray
    _win: np.ndarray
    _ident: bool
    _inf_bound: np.ndarray | None
    _gap_inner: np.ndarray

    def window(self, a: np.ndarray, b: np.ndarray, rr: float) -> tuple[int, int, int, int]:
        """The cells (i0:i1, j0:j1) that can hold a bound from the capsule a-b of radius rr:
        those within ``far`` of it (its box, grown)."""
        h, (nx, ny) = self.h, self.shape
        grow = rr + self.far + h
        i0 = max(int((min(a[0], b[0]) - grow - self.lo[0]) / h), 0)
        i1 = min(int((max(a[0], b[0]) + grow - self.lo[0]) / h) + 1, nx)
        j0 = max(int((min(a[1], b[1]) - grow - self.lo[1]) / h), 0)
        j1 = min(int((max(a[1], b[1]) + grow - self.lo[1]) / h) + 1, ny)
        return i0, i1, j0, j1

    def distances(
        self, a: np.ndarray, b: np.ndarray, rr: float, win: tuple[int, int, int, int]
    ) -> np.ndarray:
        """The lower bound the capsule a-b of radius rr gives the cells of ``win``: the
        distance from each cell's centre less half its diagonal (no point of a cell is
        nearer). Cell by cell the same numbers whatever the window."""
        i0, i1, j0, j1 = win
        # The cells' centres as a column of x and a row of y, broadcast: each cell's numbers
        # come from the same operations on the same two coordinates as over a full mesh.
        dx = self.gx[i0:i1, None] - a[0]
        dy = self.gy[None, j0:j1] - a[1]
        ab = b - a
        ab2 = length2(a, b)
        if ab2 > 0:
            u = (dx * ab[0] + dy * ab[1]) / ab2
            np.clip(u, 0.0, 1.0, out=u)
            dist = np.hypot(dx - u * ab[0], dy - u * ab[1])
        else:  # a point: u = 0, and x - 0 * 0 is x
            dist = np.hypot(dx, dy)
        dist -= rr
        dist -= self.half_diag
        return dist

    def added(self, faces: Faces, first: int, flat: int, round_: int) -> bool:
        """Take in the faces of a collider just added (``engine.geometry.faces.faces_added``: its
        ``flat`` flat faces are ``first``..., its ``round_`` round ones the last), in place:
        its lists, bounds and capsules, the same as building the grid afresh. False (and
        nothing changed) when the grid must be built afresh instead: it has no finite faces
        or no tables, the collider has an endless face, or it reaches past the extent the
        grid was laid over."""
        if not self.n_finite or self.fin_table is None or self.table is None:
            return False
        if flat and bool(faces.infinite[first : first + flat].any()):
            return False
        F, D = len(faces.owner), len(faces.c)
        # Each new face's capsule a-b of radius rad, as FaceGrid's build takes it.
        A: list[np.ndarray] = []
        Bq: list[np.ndarray] = []
        rad: list[float] = []
        if flat:
            fl = slice(first, first + flat)
            n = faces.n[fl]
            tang = np.stack([-n[:, 1], n[:, 0]], axis=1)
            A += list(faces.p[fl] + tang * faces.lo[fl, None])
            Bq += list(faces.p[fl] + tang * faces.hi[fl, None])
            rad += faces.rho[fl].tolist()
        A += list(faces.c[D - round_ :])
        Bq += A[flat:]
        rad += faces.r[D - round_ :].tolist()
        lo, hi, rmax = self._ext
        for a, b, rr in zip(A, Bq, rad, strict=True):
            if (
                rr > rmax
                or min(a[0], b[0]) < lo[0]
                or min(a[1], b[1]) < lo[1]
                or max(a[0], b[0]) > hi[0]
                or max(a[1], b[1]) > hi[1]
            ):
                return False  # a grid laid afresh would be laid differently
        count = flat + round_
        ids = list(range(first, first + flat)) + list(range(F - round_, F))
        S = len(self._slot_face)
        slots = list(range(S, S + count))
        sf = self._slot_face
        shifted = flat and D > round_  # round faces before it move up past its flat ones
        if shifted:
            sf[sf >= first] += flat
        self._slot_face = np.concatenate([sf, ids])
        fs = self._face_slot
        if flat:
            self._face_slot = np.concatenate([fs[:first], slots[:flat], fs[first:], slots[flat:]])
        else:
            self._face_slot = np.concatenate([fs, slots])
        self._slot_inf = np.concatenate([self._slot_inf, np.zeros(count, dtype=bool)])
        # Capsule rows, as FaceGrid's build makes them (the same operations, in floats).
        seg, rows, wins = [], [], []
        for a, b, rr in zip(A, Bq, rad, strict=True):
            abx, aby = float(b[0] - a[0]), float(b[1] - a[1])
            ab2 = abx * abx + aby * aby
            inv = 1.0 / ab2 if ab2 > 0.0 else 0.0
            rows.append(
                (a[0], a[1], abx, aby, inv, rr * (1.0 + 1e-8) + 1e-10 * (1.0 + math.sqrt(ab2)))
            )
            seg.append((a[0], a[1], b[0], b[1], rr, length2(a, b)))
            wins.append(self.window(a, b, rr))
        self._seg = np.concatenate([self._seg, seg])
        self._win = np.concatenate([self._win, wins])
        cap, new_rows = self.cap, np.array(rows)
        if flat:
            self.cap = np.concatenate([cap[:first], new_rows[:flat], cap[first:], new_rows[flat:]])
        else:
            self.cap = np.concatenate([cap, new_rows])
        self._ident = self._ident and not shifted
        if flat:
            self._renumbered(faces)
        else:
            self.finite = np.concatenate([self.finite, ids])
            self.n_finite = len(self.finite)
        key = self._keys() if shifted else None
        ny = self.shape[1]
        for k in range(count):
            s, f = slots[k], ids[k]
            i0, i1, j0, j1 = win = wins[k]
            dist = self.distances(A[k], Bq[k], rad[k], win)
            np.minimum(self.bound[i0:i1, j0:j1], dist, out=self.bound[i0:i1, j0:j1])
            self._bounds_changed(win)
            di, dj = np.nonzero(dist <= self.pad)
            cells = (i0 + di + 1) * (ny + 2) + (j0 + dj + 1)
            for which in ("table", "fin_table"):
                if which == "fin_table" and self.fin_table is self.table:
                    continue
                table = getattr(self, which)
                # The face goes last in each list unless it is flat and round faces are
                # listed after it (then by ``key``).
                grown = insert_slot(table, cells, s, f, key)
                if grown is None:
                    return False  # the caller drops this grid
                if grown is not table:
                    if self.fin_table is table:
                        self.fin_table = grown
                    setattr(self, which, grown)
        return True

    def removed(self, faces: Faces, index: np.ndarray, gone: np.ndarray) -> bool:
        """Let go of the faces ``gone`` of a collider just taken out (old indices;
        ``index``: each old face's new index, ``engine.geometry.faces.faces_removed``), in place:
        the same lists, bounds and capsules as building the grid afresh. False when it must be
        built afresh instead (as for ``added``, or when the extent the grid was laid over
        shrinks)."""
        if not self.n_finite or self.fin_table is None or self.table is None:
            return False
        slots = self._face_slot[gone]
        if bool(self._slot_inf[slots].any()):
            return False
        live = (self._slot_face >= 0) & ~self._slot_inf
        live[slots] = False
        if not live.any():
            return False
        lo, hi, rmax = self._ext
        inner = all(
            rr < rmax
            and min(a0, b0) > lo[0]
            and min(a1, b1) > lo[1]
            and max(a0, b0) < hi[0]
            and max(a1, b1) < hi[1]
            for a0, a1, b0, b1, rr, _ in self._seg[slots].tolist()
        )
        if not inner:
            # It touches the extent the grid was laid over: is that extent still the same?
            seg = self._seg[live]
            A, Bq, rad = seg[:, :2], seg[:, 2:4], seg[:, 4]
            if not (
                np.array_equal(np.minimum(A, Bq).min(axis=0), lo)
                and np.array_equal(np.maximum(A, Bq).max(axis=0), hi)
                and float(rad.max()) == rmax
            ):
                return False
        tables = [self.table] if self.fin_table is self.table else [self.table, self.fin_table]
        sf = self._slot_face
        self._slot_face = np.where(sf >= 0, index[np.maximum(sf, 0)], -1)
        kept = index >= 0
        self._face_slot = self._face_slot[kept]
        self.cap = self.cap[kept]
        self._renumbered(faces)
        ny = self.shape[1]
        for s in slots.tolist():
            sg = self._seg[s]
            i0, i1, j0, j1 = w = tuple(self._win[s].tolist())
            dist = self.distances(sg[:2], sg[2:4], sg[4], w)
            di, dj = np.nonzero(dist <= self.pad)
            cells = (i0 + di + 1) * (ny + 2) + (j0 + dj + 1)
            for table in tables:
                take_out_slot(table, cells, s)
            # The cells it was the least bound of (or tied): only there the bound changes,
            # to the least of the faces left whose windows hold the cell, or ``far``.
            di, dj = np.nonzero(dist <= self.bound[i0:i1, j0:j1])
            if len(di):
                self.bound[i0 + di, j0 + dj] = self._least(live, i0 + di, j0 + dj)
                self._bounds_changed(w)
            self._seg[s] = np.nan
        if 2 * int(live.sum()) + 64 < len(self._slot_face):
            self._compact()
        return True

    def _least(self, live: np.ndarray, ci: np.ndarray, cj: np.ndarray) -> np.ndarray:
        """The bounds of cells (ci, cj) from the ``live`` faces (by slot) whose windows hold
        them, at most ``far``: what building afresh gives them, by the same operations as
        ``distances`` on each face's numbers, all faces at once."""
        win = self._win
        # Windows (i0, i1, j0, j1) that meet the cells' box: i0 <= i_max, -i1 <= -i_min - 1,
        # j0 <= j_max and -j1 <= -j_min - 1, all at once.
        i_lo, i_hi, j_lo, j_hi = int(ci.min()), int(ci.max()), int(cj.min()), int(cj.max())
        meets = (win * _FLIP <= (i_hi, -i_lo - 1, j_hi, -j_lo - 1)).all(axis=1)
        near = np.flatnonzero(meets & live)
        least = np.full(len(ci), self.far)
        if not len(near):
            return least
        sg, w = self._seg[near], win[near]
        a0, a1, b0, b1 = (sg[:, k : k + 1] for k in range(4))
        rr, ab2 = sg[:, 4:5], sg[:, 5:6]
        held = (ci >= w[:, 0:1]) & (ci < w[:, 1:2]) & (cj >= w[:, 2:3]) & (cj < w[:, 3:4])
        dx = self.gx[ci] - a0  # (faces, cells)
        dy = self.gy[cj] - a1
        abx, aby = b0 - a0, b1 - a1
        point = ab2 <= 0.0
        u = (dx * abx + dy * aby) / np.where(point, 1.0, ab2)
        np.clip(u, 0.0, 1.0, out=u)
        u[np.broadcast_to(point, u.shape)] = 0.0  # a point: x - 0 * 0 is x
        dist = np.hypot(dx - u * abx, dy - u * aby)
        dist -= rr
        dist -= self.half_diag
        dist[~held] = np.inf
        np.minimum(least, dist.min(axis=0), out=least)
        return least

    def _renumbered(self, faces: Faces) -> None:
        """After faces were added or taken out: the endless and finite faces' indices, and
        whether every slot is its face's index."""
        L = len(faces.p)
        self.inf_ids = np.flatnonzero(faces.infinite)
        self.finite = np.concatenate([np.flatnonzero(~faces.infinite), L + np.arange(len(faces.c))])
        self.finite = self.finite.astype(np.intp)
        self.n_finite = len(self.finite)
        sf = self._slot_face
        self._ident = len(sf) == len(faces.owner) and bool(np.array_equal(sf, np.arange(len(sf))))

    def _keys(self) -> np.ndarray:
        """Each slot's place in a table's rows: the endless faces first (-1), then by index."""
        return np.where(self._slot_inf, -1, self._slot_face)

    def _bounds_changed(self, win: tuple[int, int, int, int]) -> None:
        """``gap``'s bounds over ``win`` from ``bound`` (the ring's share the same numbers)."""
        i0, i1, j0, j1 = win
        if self._inf_bound is not None:
            np.minimum(
                self.bound[i0:i1, j0:j1],
                self._inf_bound[i0:i1, j0:j1],
                out=self._gap_inner[i0:i1, j0:j1],
            )

    def _compact(self) -> None:
        """Slots renumbered as the faces' indices (many faces were taken out)."""
        sf = self._slot_face
        live = sf >= 0
        order = sf[live]  # the faces of the live slots, slot order
        for name in ("table", "fin_table"):
            table = getattr(self, name)
            if table is None or (name == "fin_table" and table is self.table):
                continue
            ok = table >= 0
            table[ok] = sf[table[ok]]
        F = len(self._face_slot)
        seg = np.full((F, 6), np.nan)
        win = np.zeros((F, 4), dtype=np.intp)
        inf = np.zeros(F, dtype=bool)
        seg[order] = self._seg[live]
        win[order] = self._win[live]
        inf[order] = self._slot_inf[live]
        self._seg, self._win, self._slot_inf = seg, win, inf
        self._slot_face = np.arange(F, dtype=np.intp)
        self._face_slot = np.arange(F, dtype=np.intp)
        self._ident = True
