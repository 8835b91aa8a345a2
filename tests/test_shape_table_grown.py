"""The soft step's table of the bodies' shapes grows with bodies added in play
(engine.geometry.shaped.ShapeTable.extended): the same arrays as a table made afresh, so a game
that spawns a body does not wait on every body's shape being read again."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine import Circle, Polygon, Segment
from engine.body_shapes import Compound
from engine.geometry.shaped import ShapeTable

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


@pytest.mark.parametrize(
    ("before", "added"),
    [
        ([TRIANGLE], [OCTAGON, None]),  # the old rows padded to more corners
        ([OCTAGON], [TRIANGLE]),  # the new padded to the old's
        ([None, STICK], [BOX, RING, STICK]),
        ([None], [None]),
        ([STICK, RING], [None]),
        ([None, None], [TRIANGLE]),  # the first polygon
    ],
)
def test_a_table_grown_by_bodies_added_is_the_one_made_afresh(
    before: list[object], added: list[object]
) -> None:
    radius = np.arange(1, len(before) + len(added) + 1) * 0.5
    fresh = ShapeTable(before + added, radius)
    grown = ShapeTable(before, radius[: len(before)]).extended(added, radius)
    assert grown is not None
    assert (grown.polygons is None) == (fresh.polygons is None)
    for got, want in zip(arrays(grown), arrays(fresh), strict=True):
        assert got.dtype == want.dtype and got.shape == want.shape
        assert np.array_equal(got, want)


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
