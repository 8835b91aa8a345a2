"""Each grid cell's list of faces as a row of one table, and the lists' in-place edits.

The broadphase for static faces (engine.geometry.face_grid) keeps, for every cell of its grid, the
faces a body in that cell may meet, in a fixed order. Sorted by cell they are three arrays
(each cell's start, count, and the faces end to end); as a table they are one array of shape
(cells, width), row c holding cell c's list from column 0 and -1 past its end, width being
the longest list. A body's faces are then one ``take`` of its cell's row, and a list gains or
loses a face in place, without moving any other cell's.

Sorted lists to a table (``as_table``): with counts n_c and starts s_c = n_0 + ... + n_(c-1),
the k-th entry of the sorted faces, of cell c_k, goes to column k - s_(c_k) of row c_k.

Putting a face into a list in its place (``insert_slot``): with ``key`` giving each listed
entry's place in the order, the new one goes to column p, the count of entries before it
(key < its face). Row by row the new row is the old row in columns < p, the new entry at p,
and the old row shifted right by one past p: three masks on a column index, all rows at once.
A full list widens the whole table by half its width (at least 2), so a run of insertions
costs O(log) reallocations. Taking one out (``take_out_slot``) is the mirror: the old row in
columns < p (p its column), shifted left by one from p, -1 into the last column.

A table holds at most ``TABLE_SIZE`` entries; past that (faces crowded in a cell, so every
row is as wide as the crowded one) the grid reads the sorted lists instead, and a change of
the colliders builds it afresh.
"""

from __future__ import annotations

import numpy as np

__all__ = ["TABLE_SIZE", "as_table", "insert_slot", "take_out_slot"]

#: The most entries a cell table (``FaceGrid.table``) may hold: beyond it (faces crowded in a
#: cell) the lists are read from their sorted form.
TABLE_SIZE = 4_000_000


def as_table(
    cells_sorted: np.ndarray, faces_sorted: np.ndarray, counts: np.ndarray
) -> np.ndarray | None:
    """Lists sorted by cell (each cell's faces in order, ``counts`` of them) as the rows of a
    table, -1 past each list's end; None when it would hold more than TABLE_SIZE entries."""
    width = max(int(counts.max()), 1)
    if len(counts) * width > TABLE_SIZE:
        return None
    start = np.cumsum(counts) - counts
    table = np.full((len(counts), width), -1, dtype=np.int32)
    table[cells_sorted, np.arange(len(cells_sorted)) - start[cells_sorted]] = faces_sorted
    return table


def insert_slot(
    table: np.ndarray, cells: np.ndarray, slot: int, face: int, key: np.ndarray | None
) -> np.ndarray | None:
    """Put ``slot`` (face index ``face``) into the lists of ``cells``, each in its place by
    ``key`` (the slots' order: ``FaceGrid._keys``; None: last, after every face listed), in
    place; a wider table when a list is full (the old one otherwise), None when a wider one
    would hold more than TABLE_SIZE."""
    if not len(cells):
        return table
    rows = table.take(cells, axis=0)
    has = rows >= 0
    count = has.sum(axis=1)
    width = table.shape[1]
    if int(count.max()) >= width:
        wider = width + max(2, width // 2)
        if len(table) * wider > TABLE_SIZE:
            return None
        grown = np.full((len(table), wider), -1, dtype=table.dtype)
        grown[:, :width] = table
        table = grown
        rows = table.take(cells, axis=0)
        has = rows >= 0
        width = wider
    if key is None:  # it goes last
        table[cells, count] = slot
        return table
    before = has & (key.take(np.where(has, rows, 0)) < face)
    pos = before.sum(axis=1)[:, None]
    col = np.arange(width)
    shifted = np.empty_like(rows)
    shifted[:, 0] = -1
    shifted[:, 1:] = rows[:, :-1]
    table[cells] = np.where(col < pos, rows, np.where(col == pos, slot, shifted))
    return table


def take_out_slot(table: np.ndarray, cells: np.ndarray, slot: int) -> None:
    """Take ``slot`` out of the lists of ``cells`` (each holds it), in place."""
    if not len(cells):
        return
    rows = table.take(cells, axis=0)
    pos = np.argmax(rows == slot, axis=1)[:, None]
    shifted = np.empty_like(rows)
    shifted[:, -1] = -1
    shifted[:, :-1] = rows[:, 1:]
    table[cells] = np.where(np.arange(rows.shape[1]) < pos, rows, shifted)
