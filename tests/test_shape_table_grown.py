"""The soft step's table of the bodies' shapes grows with bodies added in play
(engine.geometry.shaped.ShapeTable.extended) and shrinks with bodies taken out (``without``):
the same arrays as a table made afresh, so a game that spawns a body, or takes one out, does
not wait on every body's shape being read again."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine import Body, Circle, Hinge, Polygon, Segment, World
from engine.body_shapes import Compound
from engine.geometry import narrowphase
from engine.geometry.shaped import ShapeTable
from engine.pipeline.game_step import _rows_left

TRIANGLE = Polygon([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)])
BOX = Polygon.box(1.0, 2.0, radius=0.1)
OCTAGON = Polygon([(math.cos(a), math.sin(a)) for a in np.linspace(0.0, 2.0 * math.pi, 9)[:-1]])
STICK = Segment((-1.0, 0.0), (1.0, 0.0), 0.1)
RING = Circle((0.1, 0.2), 0.3)


def arrays(t: ShapeTable) -> list[np.ndarray]:
    out = [t.kind, t.index, t.shaped, t.circles.center, t.circles.radius]
    out += [t.capsules.a, t.capsules.b, t.capsules.radius]
    if t.polygons is not None:
        p = t.polygons
        out += [p.vertices, p.normals, p.count, p.radius]
    return out


def same_table(made: ShapeTable | None, fresh: ShapeTable) -> None:
    """``made`` (grown or shrunk) holds the arrays and extents of ``fresh``, to the bit."""
    assert made is not None
    assert (made.polygons is None) == (fresh.polygons is None)
    for got, want in zip(arrays(made), arrays(fresh), strict=True):
        assert got.dtype == want.dtype and got.shape == want.shape
        assert np.array_equal(got, want)
    for got, want in zip(made.extents(), fresh.extents(), strict=True):
        assert got.dtype == want.dtype and np.array_equal(got, want)


@pytest.mark.parametrize(
    ("before", "added"),
    [
        ([TRIANGLE], [OCTAGON, None]),  # the old rows padded to more corners
        ([OCTAGON], [TRIANGLE]),  # the new padded to the old's
        ([None, STICK], [BOX, RING, STICK]),
        ([None], [None]),
        ([STICK, RING], [None]),  # plain discs added: their own quick way (_with_discs)
        ([TRIANGLE, None], [None, None, None]),
        ([None, None], [TRIANGLE]),  # the first polygon
    ],
)
def test_a_table_grown_by_bodies_added_is_the_one_made_afresh(
    before: list[object], added: list[object]
) -> None:
    radius = np.arange(1, len(before) + len(added) + 1) * 0.5
    fresh = ShapeTable(before + added, radius)
    for with_extents in (False, True):
        first = ShapeTable(before, radius[: len(before)])
        if with_extents:
            first.extents()
        same_table(first.extended(added, radius), fresh)


def test_a_body_of_several_shapes_makes_the_table_afresh() -> None:
    both = Compound([TRIANGLE, RING])
    assert ShapeTable([BOX], np.ones(1)).extended([both], np.ones(2)) is None


def reference(shape: object, radius: float) -> tuple[float, float, tuple[float, float]]:
    """A body's extents, from its own shape, one corner at a time: (least extent, the core's
    farthest point from the centre, the centroid of its corners); a round body's least extent
    is the radius the table holds for it (``radius``)."""
    if shape is None or isinstance(shape, Circle):
        c = (0.0, 0.0) if shape is None else tuple(shape.center)
        return radius, math.hypot(*c), c
    if isinstance(shape, Segment):
        v = np.array([tuple(shape.a), tuple(shape.b)])
        d = v[1] - v[0]
        right = np.array([d[1], -d[0]]) / np.hypot(d[0], d[1])
        nrm, rounding = np.array([right, -right]), shape.radius
    else:
        v, nrm = np.array([tuple(p) for p in shape.vertices]), np.array(shape.normals)
        rounding = shape.radius
    c = v.mean(axis=0)
    least = max(0.0, float(((v - c) * nrm).sum(axis=1).min())) + rounding
    return least, float(np.hypot(v[:, 0], v[:, 1]).max()), (float(c[0]), float(c[1]))


def test_the_extents_are_each_bodys_own_and_grow_with_the_table() -> None:
    shapes = [TRIANGLE, None, STICK, OCTAGON, RING, BOX]
    radius = np.array([0.7, 0.25, 1.1, 1.0, 0.4, 1.2])
    least, core, centroid = ShapeTable(shapes, radius).extents()
    for row, shape in enumerate(shapes):
        want = reference(shape, radius[row])
        assert (least[row], core[row], tuple(centroid[row])) == want, (row, shape)
    # Grown from a table whose extents were made: the old rows' kept, the new rows' made.
    first = ShapeTable(shapes[:2], radius[:2])
    first.extents()
    grown = first.extended(shapes[2:], radius)
    assert grown is not None
    for got, want in zip(grown.extents(), (least, core, centroid), strict=True):
        assert np.array_equal(got, want)


@pytest.mark.parametrize(
    ("shapes", "gone"),
    [
        ([TRIANGLE, OCTAGON, None], [1]),  # the most corners gone: the rest padded to fewer
        ([OCTAGON, TRIANGLE, BOX], [1]),
        ([None, STICK, BOX, RING, STICK], [0, 3]),
        ([None, None], [1]),
        ([STICK, RING, TRIANGLE], [2]),  # the last polygon gone
        ([BOX, BOX, None, BOX], [1]),  # one shape given to three bodies
    ],
)
@pytest.mark.parametrize("with_extents", [False, True])
def test_a_table_shrunk_by_bodies_taken_out_is_the_one_made_afresh(
    shapes: list[object], gone: list[int], with_extents: bool
) -> None:
    """``ShapeTable.without``: the rows left, the same arrays (and extents) as a table made
    afresh of their shapes (a game taking a bullet out does not wait on every shape)."""
    radius = np.arange(1, len(shapes) + 1) * 0.5
    keep = np.ones(len(shapes), dtype=bool)
    keep[gone] = False
    left = [s for s, k in zip(shapes, keep, strict=True) if k]
    fresh = ShapeTable(left, radius[keep])
    whole = ShapeTable(shapes, radius)
    if with_extents:
        whole.extents()
    same_table(whole.without(keep, radius[keep]), fresh)


def test_a_table_shrunk_to_rows_of_other_radii_reads_them() -> None:
    """Two plain discs taken out and one added (a row left may be another body of the same
    shape, here None, with another radius): the extents read the radii given."""
    whole = ShapeTable([None, None, None], np.array([0.3, 0.5, 0.9]))
    whole.extents()
    shrunk = whole.without(np.array([True, True, False]), np.array([0.5, 0.7]))
    fresh = ShapeTable([None, None], np.array([0.5, 0.7]))
    assert shrunk is not None
    for got, want in zip(shrunk.extents(), fresh.extents(), strict=True):
        assert np.array_equal(got, want)


def test_a_table_grown_over_rows_of_other_radii_reads_them() -> None:
    """A plain disc taken out and two added (the first row kept is now another disc's): the
    extents read the radii given."""
    first = ShapeTable([None], np.array([0.3]))
    first.extents()
    grown = first.extended([None], np.array([0.5, 0.7]))
    fresh = ShapeTable([None, None], np.array([0.5, 0.7]))
    assert grown is not None
    for got, want in zip(grown.extents(), fresh.extents(), strict=True):
        assert np.array_equal(got, want)


def test_a_table_with_a_body_of_several_shapes_is_made_afresh_when_one_goes() -> None:
    table = ShapeTable([BOX, Compound([TRIANGLE, RING])], np.ones(2))
    assert table.without(np.array([False, True]), np.ones(1)) is None


def test_rows_left_finds_the_rows_taken_out() -> None:
    """Which rows are left after bodies were taken out (the rest in order); where a shape is
    several bodies' (None, one Polygon given to two), any of them may be named: their rows
    are alike. Not bodies taken out: None."""
    assert _rows_left([BOX, None, STICK], [BOX, STICK]).tolist() == [True, False, True]
    left = _rows_left([None, BOX, None, BOX], [None, BOX])
    assert left is not None and left.sum() == 2
    assert _rows_left([BOX, STICK], [STICK, BOX]) is None  # reordered
    assert _rows_left([BOX], [STICK]) is None


def test_a_soft_world_keeps_its_table_as_bodies_go(monkeypatch: pytest.MonkeyPatch) -> None:
    """In play: crates, balls and a stick taken out one by one between steps; the table the
    soft step keeps (``without`` the rows gone) is the one made afresh from the bodies left,
    each time."""
    shrunk = []
    without = ShapeTable.without

    def counted(table: ShapeTable, keep: np.ndarray, radius: np.ndarray) -> ShapeTable | None:
        shrunk.append(keep.tolist())
        return without(table, keep, radius)

    monkeypatch.setattr(ShapeTable, "without", counted)
    w = World(solver="soft")
    w.add_collider(Segment((-20.0, 0.0), (20.0, 0.0)))
    made = []
    for k, shape in enumerate([BOX, None, STICK, OCTAGON, None, BOX, TRIANGLE]):
        at = (2.5 * k - 8.0, 3.0)
        made.append(w.add(Body(at, mass=1.0, shape=shape) if shape else
                          Body(at, mass=1.0, radius=0.3)))  # fmt: skip
    w.step(1 / 60)
    for gone in (made[3], made[0], made[6], made[1]):
        w.remove(gone)
        w.step(1 / 60)
        store, game = w._s.store, w._s.game
        kept = game._table[2]
        fresh = ShapeTable(store.shapes, store.radius)
        for got, want in zip(arrays(kept), arrays(fresh), strict=True):
            assert np.array_equal(got, want)
    assert [len(k) - sum(k) for k in shrunk] == [1, 1, 1, 1]  # one row gone each time


def test_a_soft_world_keeps_its_places_and_joined_pairs_as_balls_come_and_go() -> None:
    """In play, balls added and taken out between steps, among crates on hinges, a capsule
    and static polygons: the shapes' places the soft step keeps (their polygons' table kept
    while the polygons are) are those made afresh, and the pairs the joints keep apart are
    those found from the joints, each step."""
    w = World(solver="soft")
    w.add_collider(Segment((-20.0, 0.0), (20.0, 0.0)))
    w.add_collider(Polygon([(5.0, 0.0), (7.0, 0.0), (6.0, 1.0)]))
    crates = [w.add(Body((2.0 * k - 6.0, 2.0), mass=1.0, shape=BOX)) for k in range(3)]
    stick = w.add(Body((4.0, 4.0), mass=1.0, shape=STICK))
    w.add_link(Hinge(crates[0], crates[1], (-5.0, 2.5)))
    w.add_link(Hinge(crates[1], crates[2], (-3.0, 2.5)))
    w.add_link(Hinge(stick, w.static_body, (4.0, 4.0)))
    balls: list[Body] = []
    for k in range(8):
        if k == 6:
            w.remove(crates.pop())  # (a polygon's row goes, and its hinge with it)
        elif k % 3 == 2:
            w.remove(balls.pop(0))
        else:
            balls.append(w.add(Body((0.5 * k - 2.0, 6.0), mass=0.2, radius=0.1)))
        w.step(1 / 60)
        state = w._s
        store, game = state.store, state.game
        table, statics, kept = game._places
        narrowphase._POLYGONS[:] = [None, None, None, None]
        fresh = narrowphase.places_of(table, statics)
        assert kept.tables.polygons is not None and fresh.tables.polygons is not None
        for part in ("vertices", "normals", "count", "radius"):
            got, want = getattr(kept.tables.polygons, part), getattr(fresh.tables.polygons, part)
            assert got.dtype == want.dtype and np.array_equal(got, want)
        for name in ("body_circle", "body_index", "static_circle", "static_index"):
            assert np.array_equal(getattr(kept, name), getattr(fresh, name))
        n = len(store)
        rows = [sorted((store.row(j.kept_apart[0].slot), store.row(j.kept_apart[1].slot)))
                for j in w.links if isinstance(j, Hinge) and j.kept_apart is not None]  # fmt: skip
        assert state.joint_apart.tolist() == sorted(a * n + b for a, b in rows)
        assert len(rows) == (2 if k < 6 else 1)
