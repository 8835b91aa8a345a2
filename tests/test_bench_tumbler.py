"""The tumbler benchmark: the same scene in both engines, and what a run reports, never how fast."""

from __future__ import annotations

import math

import numpy as np
import pytest

from demos import stack as scene
from demos.bench import tumbler

pymunk = pytest.importorskip("pymunk")


def test_both_engines_build_the_same_tumbler() -> None:
    w, boxes, walls = scene.tumbler(kernels="numpy")
    made = tumbler.make_space()
    assert made is not None
    space, body, bodies = made
    assert len(bodies) == len(boxes) == 500
    ours = np.array([tuple(b.pos) for b in boxes])
    theirs = np.array([tuple(b.position) for b in bodies])
    assert np.array_equal(ours, theirs)
    assert {b.mass for b in bodies} == {b.mass for b in boxes} == {0.0625}
    assert [b.moment for b in bodies] == pytest.approx([b.moment for b in boxes], rel=1e-12)
    assert body.angular_velocity == walls[0].angular_velocity == math.radians(25)  # Box2D's
    # The walls: the same four polygons about the same point.
    ours_walls = sorted(tuple(sorted(tuple(v) for v in wl.shape.vertices)) for wl in walls)
    theirs_walls = sorted(
        tuple(sorted(tuple(v) for v in s.get_vertices())) for s in space.shapes if s.body is body
    )
    assert ours_walls == theirs_walls


def test_the_room_test_finds_a_box_past_a_wall_in_the_turned_room() -> None:
    # A room turned a quarter turn: a box 9.3 m up the world's y is 9.3 m along the room's
    # x; turned with it, its corners reach 9.425 m: inside; at 9.45 m, 0.075 m past the
    # face; at 9.6 m its centre is past.
    pos = np.array([[0.0, 9.3], [0.0, 9.45], [0.0, 9.6]])
    out, deep = tumbler._room(pos, np.full(3, math.pi / 2), math.pi / 2)
    assert out.tolist() == [False, False, True]
    assert deep == pytest.approx([9.425 - 9.5, 9.575 - 9.5, 9.725 - 9.5], abs=1e-12)


def test_a_short_run_reports_every_engine() -> None:
    got = tumbler.side_by_side(seconds=3 * tumbler.DT)
    assert "World" in got and "pymunk" in got
    for r in got.values():
        assert r["first"] > 0 and r["mean"] > 0
        assert r["lost"] == 0  # three steps: nothing has reached a wall
        assert r["deepest"] < -3.0  # the grid's outer boxes are metres from the walls
        # The grid's boxes are 0.4 m apart, farther than a diagonal: none near another yet.
        assert r["between"] == -math.inf and r["past"] == 0


def test_two_boxes_into_each_other_by_their_separating_axes() -> None:
    h = 0.5 * scene.TUMBLED_SIDE
    level = np.zeros(2)
    # Side by side, level: as deep as the sides overlap along x.
    pos = np.array([[0.0, 0.0], [0.2, 0.0]])
    assert scene.boxes_into_each_other(pos, level) == pytest.approx(2 * h - 0.2, abs=1e-15)
    # The second turned 45 degrees, its corner toward the first's face: h + h sqrt 2 - x.
    pos = np.array([[0.0, 0.0], [0.25, 0.0]])
    got = scene.boxes_into_each_other(pos, np.array([0.0, math.pi / 4]))
    assert got == pytest.approx(h + h * math.sqrt(2.0) - 0.25, abs=1e-15)
    # Apart along x by 1 cm (within a diagonal): -1 cm; farther than a diagonal: no pair.
    pos = np.array([[0.0, 0.0], [2 * h + 0.01, 0.0]])
    assert scene.boxes_into_each_other(pos, level) == pytest.approx(-0.01, abs=1e-15)
    pos = np.array([[0.0, 0.0], [0.4, 0.0]])
    assert scene.boxes_into_each_other(pos, level) == -math.inf
    # The pairs found whatever the order along x: three boxes, the deepest pair last.
    pos = np.array([[0.3, 0.0], [0.0, 0.0], [0.1, 0.0]])
    assert scene.boxes_into_each_other(pos, np.zeros(3)) == pytest.approx(2 * h - 0.1, abs=1e-15)
