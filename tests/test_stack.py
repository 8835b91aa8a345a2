"""The stack demo: boxes that turn make a pyramid that sleeps, dominoes that fall in order,
and a tower that stands; the frames show it."""

from __future__ import annotations

import math

import numpy as np
import pygame
import pytest

from demos.stack import DominoScene, PyramidScene, TowerScene
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
def dominoes() -> DominoScene:
    return run(DominoScene, 6.0)  # type: ignore[return-value]


def test_the_pyramid_stands_and_sleeps_within_two_seconds(pyramid: PyramidScene) -> None:
    # The numbers: asleep within 2 s, no box more than 1 cm from where it was put.
    assert pyramid.asleep_at is not None and pyramid.asleep_at <= 2.0
    assert pyramid.world.sleeping == len(pyramid.boxes) == 210
    assert float(pyramid.moved().max()) < 0.01
    tilt = max(abs(math.remainder(b.angle, math.pi / 2)) for b in pyramid.boxes)
    assert tilt < 0.005  # still square to the floor (rad)


def test_the_dominoes_fall_in_order(dominoes: DominoScene) -> None:
    # Each domino ends lying forward (clockwise, angle near -pi/2 less the lean on the next).
    assert dominoes.fallen() == len(dominoes.boxes) == 30
    angles = np.array([b.angle for b in dominoes.boxes])
    assert (angles < -0.3).all()
    assert abs(dominoes.boxes[-1].angle + math.pi / 2) < 0.01  # the last lies on the floor
    # In order: replayed, each passes 0.3 rad after the one before it.
    s = DominoScene()
    s.build((640, 360))
    when = [math.inf] * len(s.boxes)
    while s.world.t < 6.0:
        s.step(s.dt)
        for k, b in enumerate(s.boxes):
            if when[k] == math.inf and abs(b.angle) > 0.3:
                when[k] = s.world.t
    assert all(a < b for a, b in zip(when, when[1:], strict=False)), when


def test_the_tower_of_twenty_stands_for_ten_seconds() -> None:
    t = run(TowerScene, 10.0)
    top = t.boxes[-1]  # type: ignore[attr-defined]
    assert t.world.sleeping == 0  # type: ignore[attr-defined]
    # Standing (it drifts: tens of mm, the limit the frame shows), not fallen.
    assert abs(top.pos.x) < 0.1 and top.pos.y > 19.0
    assert max(abs(b.angle) for b in t.boxes) < 0.01  # type: ignore[attr-defined]


def test_the_pyramid_frame_draws_sleeping_boxes_in_grey(pyramid: PyramidScene) -> None:
    surface = pygame.Surface((640, 360))
    pyramid.draw(surface, 1.0)
    for box in pyramid.boxes[::20]:
        x, y = pyramid.camera.point((box.pos.x + 0.25, box.pos.y + 0.25))
        assert tuple(surface.get_at((round(x), round(y))))[:3] == ASLEEP


def test_the_worlds_warning_is_on_the_frame_not_on_stderr() -> None:
    """A tower on one contact iteration a step is past what the solver holds: the World's
    StabilityWarning is drawn on the frame, from the moment it came, in place of the scene's
    second line, and none reaches stderr; restored to a snapshot taken before it, the scene
    draws it again from its moment (the World warns once in its life; the scene keeps it)."""
    import warnings

    from engine.render import marks

    s = TowerScene()
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
    assert not any(t.startswith("(the issue asks") for t in shown)
    s.restore(saved)
    assert s.world.t == 0.0 and not any(t.startswith("the World warned") for t in texts())
    while s.world.t < s.warning[0] - 1e-9:
        s.step(s.dt)
    assert any(t.startswith(line) for t in texts())
