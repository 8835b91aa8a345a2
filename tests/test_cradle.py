"""Newton's cradle demo: the speed passes down the row exactly, and the frames show it."""

from __future__ import annotations

import hashlib
import io
from pathlib import Path

import numpy as np
import pygame
import pytest

import demos.cradle as cradle
from demos.cli import main
from engine.render import iter_frames

#: The moment the first ball (pulled back PULL m, at SPEED m/s) meets the row.
T_HIT = cradle.PULL / cradle.SPEED


def run(sent: int = 1, first_mass: float = 1.0, seconds: float = 3.0) -> cradle.Cradle:
    c = cradle.Cradle(sent, first_mass)
    while c.t < seconds - 1e-9:
        c.step(cradle.DT)
    return c


def sequential(masses: list[float], velocities: list[float]) -> list[float]:
    """The ideal cradle in 1D: touching balls, each blow the closed-form elastic collision of
    one pair, applied one pair at a time while some pair closes (the leftmost first)."""
    v = list(velocities)
    for _ in range(10_000):
        for k in range(len(v) - 1):
            if v[k] > v[k + 1]:  # closing: k is behind k + 1 and faster
                m1, m2 = masses[k], masses[k + 1]
                u1, u2 = v[k], v[k + 1]
                v[k] = ((m1 - m2) * u1 + 2 * m2 * u2) / (m1 + m2)
                v[k + 1] = ((m2 - m1) * u2 + 2 * m1 * u1) / (m1 + m2)
                break
        else:
            return v
    raise AssertionError("the blows never ended")


def test_one_ball_in_sends_the_last_ball_out_at_its_speed_and_leaves_the_rest_still() -> None:
    c = run(1)
    *rest, last = c.balls
    assert abs(last.vel.x - cradle.SPEED) <= 1e-6 and abs(last.vel.y) <= 1e-6
    for ball in rest:
        assert abs(ball.vel.x) <= 1e-6 and abs(ball.vel.y) <= 1e-6
    # The first ball stopped where it met the row, at x = 0; the last left x = 4 m at T_HIT.
    assert abs(c.balls[0].pos.x) <= 1e-9
    assert abs(last.pos.x - (4 * cradle.RADIUS * 2 + cradle.SPEED * (c.t - T_HIT))) <= 1e-9
    assert all(abs(b.pos.y - cradle.RADIUS) <= 1e-12 for b in c.balls)  # on the floor


def test_two_balls_in_send_two_balls_out() -> None:
    c = run(2)
    for ball in c.balls[:3]:
        assert abs(ball.vel.x) <= 1e-6 and abs(ball.vel.y) <= 1e-6
    for ball in c.balls[3:]:
        assert abs(ball.vel.x - cradle.SPEED) <= 1e-6 and abs(ball.vel.y) <= 1e-6


def test_a_heavy_ball_sends_out_a_train_as_the_blows_one_by_one_say() -> None:
    c = run(1, cradle.HEAVY)
    masses = [cradle.HEAVY] + [1.0] * (cradle.BALLS - 1)
    want = sequential(masses, [cradle.SPEED] + [0.0] * (cradle.BALLS - 1))
    assert want == pytest.approx([0.125, 0.375, 0.75, 1.5, 3.0], abs=1e-12)
    assert [b.vel.x for b in c.balls] == pytest.approx(want, abs=1e-9)
    assert all(abs(b.vel.y) <= 1e-9 for b in c.balls)


@pytest.mark.parametrize(("sent", "mass"), [(1, 1.0), (2, 1.0), (1, cradle.HEAVY)])
def test_momentum_and_kinetic_energy_stay_at_their_first_values_to_rounding(
    sent: int, mass: float
) -> None:
    c = run(sent, mass)
    first = c.history[0]
    assert first.momentum == pytest.approx((sent - 1 + mass) * cradle.SPEED)
    assert len(c.history) == 181  # the start and every step of 3 s
    for s in c.history:
        assert abs(s.momentum - first.momentum) <= 1e-12 * first.momentum
        assert abs(s.energy - first.energy) <= 1e-12 * first.energy


def test_the_demos_scenes_are_those_worlds() -> None:
    for scene, sent, mass in (
        (cradle.FiveScene, 1, 1.0),
        (cradle.TwoScene, 2, 1.0),
        (cradle.HeavyScene, 1, cradle.HEAVY),
    ):
        assert (scene.sent, scene.first_mass) == (sent, mass)
    assert cradle.DEMO.scenes == {
        "five": cradle.FiveScene,
        "two": cradle.TwoScene,
        "heavy": cradle.HeavyScene,
        "hung": cradle.HungScene,
    }
    with pytest.raises(ValueError, match="sent"):
        cradle.cradle_world(5)


def exact_x(k: int, t: float) -> float:
    """Ball k's centre (m) at time t in the ``five`` scene, in closed form."""
    if k == 0:
        return -cradle.PULL + cradle.SPEED * min(t, T_HIT)
    if k == cradle.BALLS - 1:
        return 2 * cradle.RADIUS * k + cradle.SPEED * max(0.0, t - T_HIT)
    return 2 * cradle.RADIUS * k


def test_the_frames_draw_each_ball_where_it_is_and_its_velocity_as_a_bar() -> None:
    scene = cradle.FiveScene()
    checked = 0
    for index, t, surface in iter_frames(scene, fps=10, seconds=3.0, size=(640, 360)):
        pixels = pygame.surfarray.array3d(surface)
        if index == 0:
            assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50  # not flat
        row = pixels[:, : scene.bars.top]  # the floor and the balls, above the panels
        if abs(t - T_HIT) < 2 * cradle.DT:
            continue  # a blend across the impact
        for k, colour in enumerate(cradle.COLOURS):
            xs, ys = np.nonzero(np.all(row == colour, axis=2))
            r = scene.camera.length(cradle.RADIUS)
            assert len(xs) > 0.6 * np.pi * r * r, (t, k)  # a whole disc, less its number
            want = scene.camera.to_px(exact_x(k, t), cradle.RADIUS)
            assert abs(xs.mean() - want[0]) < 1.5 and abs(ys.mean() - want[1]) < 1.5, (t, k)
        checked += 1
        # The bars: the moving ball's bar stands SPEED high on the scale, the others' at 0.
        bars = pixels[scene.bars.left : scene.bars.right, scene.bars.top : scene.bar_zero]
        moving = 0 if t < T_HIT else cradle.BALLS - 1
        heights = [np.all(bars == c, axis=2).any(axis=0).sum() for c in cradle.COLOURS]
        assert abs(heights[moving] - scene.bar_scale * cradle.SPEED) <= 1.0, t
        assert all(h == 0 for k, h in enumerate(heights) if k != moving), t
    assert checked >= 25


def _frames(folder: Path, *args: str) -> list[bytes]:
    code = main(
        ["cradle", *args, "--fps", "10", "--seconds", "2", "--out", str(folder)], io.StringIO()
    )
    assert code == 0
    return [p.read_bytes() for p in sorted(folder.rglob("frame_*.png"))]


def test_two_runs_write_identical_frames(tmp_path: Path) -> None:
    first, second = _frames(tmp_path / "a"), _frames(tmp_path / "b")
    assert len(first) == 4 * 21  # four scenes, 2 s at 10 fps with both ends
    digest = [hashlib.sha256(b).hexdigest() for b in first]
    assert digest == [hashlib.sha256(b).hexdigest() for b in second]
    assert len(set(digest)) > 40  # the balls move: identical stills would prove little


def test_the_strobe_is_a_motion_diagram_of_each_scene(tmp_path: Path) -> None:
    assert main(["cradle", "--strobe", "--out", str(tmp_path)], io.StringIO()) == 0
    for name in ("five", "two", "heavy"):
        image = pygame.surfarray.array3d(pygame.image.load(str(tmp_path / name / "strobe.png")))
        # One squashed image of every ball at every time: the last ball's colour in many rows.
        rows = np.all(image == cradle.COLOURS[-1], axis=2).any(axis=0)
        assert rows.sum() > 100, name
