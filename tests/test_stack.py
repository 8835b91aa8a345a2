"""The stack demo: boxes that turn make a pyramid that sleeps, dominoes that fall in order,
and a tower that stands; the frames show it."""

from __future__ import annotations

import math
import re

import numpy as np
import pygame
import pytest

from demos.stack import (
    MARK,
    DominoScene,
    PyramidScene,
    StressTumblerScene,
    TowerScene,
    TumblerScene,
    tower,
)
from engine import Body, World
from engine.render import iter_frames, marks
from engine.render.world_view import ASLEEP


def run(scene_type: type, seconds: float) -> object:
    s = scene_type()
    s.build((640, 360))
    for _ in range(round(seconds / s.dt)):
        s.step(s.dt)
    return s


@pytest.fixture(scope="module")
def pyramid() -> PyramidScene:
    return run(PyramidScene, 2.0)  # type: ignore[return-value]


@pytest.fixture(scope="module")
def dominoes() -> tuple[DominoScene, list[float]]:
    """The dominoes stepped for 6 s, and when each first leant past 0.3 rad (s; inf: never)."""
    s = DominoScene()
    s.build((640, 360))
    when = [math.inf] * len(s.boxes)
    for _ in range(round(6.0 / s.dt)):
        s.step(s.dt)
        for k, b in enumerate(s.boxes):
            if when[k] == math.inf and abs(b.angle) > 0.3:
                when[k] = s.world.t
    return s, when


def test_the_pyramid_stands_and_sleeps_within_two_seconds(pyramid: PyramidScene) -> None:
    # The numbers: asleep within 2 s, no box more than 1 cm from where it was put.
    assert pyramid.asleep_at is not None and pyramid.asleep_at <= 2.0
    assert pyramid.world.sleeping == len(pyramid.boxes) == 210
    assert float(pyramid.moved().max()) < 0.01
    tilt = max(abs(math.remainder(b.angle, math.pi / 2)) for b in pyramid.boxes)
    assert tilt < 0.005  # still square to the floor (rad)


def test_the_dominoes_fall_in_order(dominoes: tuple[DominoScene, list[float]]) -> None:
    # Each domino ends lying forward (clockwise, angle near -pi/2 less the lean on the next).
    scene, when = dominoes
    assert scene.fallen() == len(scene.boxes) == 30
    angles = np.array([b.angle for b in scene.boxes])
    assert (angles < -0.3).all()
    assert abs(scene.boxes[-1].angle + math.pi / 2) < 0.01  # the last lies on the floor
    # In order: each passed 0.3 rad after the one before it (all passed it: the angles above).
    assert all(a < b for a, b in zip(when, when[1:], strict=False)), when


def test_the_tower_of_twenty_stands_for_ten_seconds() -> None:
    t = run(TowerScene, 10.0)
    top = t.boxes[-1]  # type: ignore[attr-defined]
    assert t.world.sleeping == 0  # type: ignore[attr-defined]
    # Standing still, on the soft step World() chooses for it: the bounds for 60 s
    # (5 mm aside, 10 mm of sag; tests/test_rigid_scenes.py) hold at 10 s (the exact models'
    # walks tens of mm aside by then).
    assert t.world.solver == "soft"  # type: ignore[attr-defined]
    assert abs(top.pos.x) <= 0.005 and 19.5 - top.pos.y <= 0.010
    assert max(abs(b.angle) for b in t.boxes) < 0.01  # type: ignore[attr-defined]


def test_the_pyramid_frame_draws_sleeping_boxes_in_grey(pyramid: PyramidScene) -> None:
    surface = pygame.Surface((640, 360))
    pyramid.draw(surface, 1.0)
    for box in pyramid.boxes[::20]:
        x, y = pyramid.camera.point((box.pos.x + 0.25, box.pos.y + 0.25))
        assert tuple(surface.get_at((round(x), round(y))))[:3] == ASLEEP


def test_the_worlds_warning_is_on_the_frame_not_on_stderr() -> None:
    """A tower on one contact iteration a step is past what the exact models hold (the soft
    step's sags 13 cm and overlaps 2.4 cm, under the warning's 5% of a box's radius): the
    World's StabilityWarning is drawn on the frame, from the moment it came, in place of the
    scene's second line, and none reaches stderr; restored to a snapshot taken before it, the
    scene draws it again from its moment (the World warns once in its life; the scene keeps
    it)."""
    import warnings

    from engine.render import marks

    class ExactTower(TowerScene):
        def make(self) -> tuple[World, list[Body]]:
            return tower(solver="exact")

    s = ExactTower()
    s.build((640, 360))
    s.world.contact_iterations = 1
    saved = s.snapshot()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning printed would fail here
        for _ in range(round(2.0 / s.dt)):
            s.step(s.dt)
    assert s.warning is not None and 0.0 < s.warning[0] <= 2.0

    def texts() -> list[str]:
        surface = pygame.Surface((640, 360))
        s.draw(surface, 1.0)
        return [m.text for m in marks.marks(surface)]

    shown = texts()
    line = f"the World warned at {s.warning[0]:.2f} s: this pile is past what 1 contact iterations"
    assert any(t.startswith(line) for t in shown), shown
    assert not any(t.startswith("the exact models; by 60 s") for t in shown)
    s.restore(saved)
    assert s.world.t == 0.0 and not any(t.startswith("the World warned") for t in texts())
    while s.world.t < s.warning[0] - 1e-9:
        s.step(s.dt)
    assert any(t.startswith(line) for t in texts())


# -- the read-outs describe the state the frame shows, at the time its clock shows ---------------


def _said(scene: object, t: float) -> list[str]:
    """The words of the frame at ``t`` s (30 frames a second) of a recording of ``scene``."""
    k = round(30 * t)
    for _, _, surface in iter_frames(scene, 30, t + 0.1, (640, 360), only={k}):  # type: ignore[arg-type]
        return [m.text for m in marks.marks(surface)]
    raise AssertionError(f"no frame at {t} s")


@pytest.mark.parametrize("t", [0.0, 0.5])
def test_the_pyramids_and_the_towers_read_outs_are_of_the_time_on_the_clock(t: float) -> None:
    """At t = 0 the frame read 'moved 1.7 mm' and '1.7 mm lower than put': the boxes after a
    step, under a clock that said 0. A frame's read-out is now the one of a scene stepped to
    the clock's time (none at 0: the boxes where they were put, 0 mm)."""
    pyramid, tower = run(PyramidScene, t), run(TowerScene, t)
    moved = 1000 * float(pyramid.moved().max())  # type: ignore[attr-defined]
    top = tower.boxes[-1]  # type: ignore[attr-defined]
    drift, sag = 1000 * abs(top.pos.x), 1000 * (19.5 - top.pos.y)
    if t == 0.0:
        assert moved == drift == sag == 0.0
    else:
        assert moved > 1.0 and sag > 1.0  # they have moved by then: the check can tell
    said = _said(PyramidScene(), t)
    assert f"t = {t:4.2f} s" in said
    assert any(text.endswith(f"the most any box moved {moved:.1f} mm") for text in said), said
    said = _said(TowerScene(), t)
    assert f"t = {t:4.2f} s" in said
    line = f"the top box: {drift:.1f} mm sideways, {sag:.1f} mm lower than put"
    assert line in said, said


@pytest.mark.parametrize("scene_class", [TumblerScene, StressTumblerScene])
def test_frames_a_second_apart_show_the_tumbler_turned(scene_class: type[TumblerScene]) -> None:
    """The walls look alike a quarter turn apart: at 90 degrees a second (the stress scene)
    the room at 1 s and 2 s was drawn the same, as if still. A dot marks one wall and the
    frame says the room's angle: the dot is where the angle puts it, ``spin`` on each second
    (25 degrees a second in the tumbler, a quarter turn in the stress scene)."""
    scene = scene_class()
    scene.count = 20  # the room turns the same with fewer boxes in it
    per_second = math.degrees(scene.spin)
    assert round(per_second) == (25 if scene_class is TumblerScene else 90)
    seen = {}
    for k, t, surface in iter_frames(scene, 30, 2.0, (640, 360), only={0, 30, 45, 60}):
        mark = np.all(pygame.surfarray.array3d(surface) == MARK, axis=2)
        assert mark.sum() > 10, k
        xs, ys = np.nonzero(mark)
        cx, cy = scene.camera.point((0.0, 0.0))
        # The dot's direction from the room's centre, in the world's sense (pixel y down).
        angle = math.degrees(math.atan2(-(ys.mean() - cy), xs.mean() - cx)) % 360
        said = [m.text for m in marks.marks(surface)]
        seen[t] = (xs.mean(), ys.mean())
        assert abs((angle - per_second * t + 180) % 360 - 180) < 2.0, (t, angle)
        told = [
            int(m[1]) for text in said if (m := re.fullmatch(r"the walls at (\d+) degrees", text))
        ]
        assert len(told) == 1, said
        assert abs((told[0] - per_second * t + 180) % 360 - 180) <= 0.5 + 1e-9, (t, told)
    # A second apart, the dot is a chord of the room's turn in that second apart (pixels).
    radius = math.dist(seen[0.0], scene.camera.point((0.0, 0.0)))
    chord = 2.0 * radius * math.sin(math.radians(per_second) / 2.0)
    assert math.dist(seen[1.0], seen[2.0]) == pytest.approx(chord, rel=0.05)
