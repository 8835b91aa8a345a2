"""Newton's cradle demo: the speed passes down the row exactly, and the frames show it."""

from __future__ import annotations

import functools
import hashlib
import io
import math
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pygame
import pytest

import demos.cradle as cradle
from demos.cli import main
from engine import Vector
from engine.render import frame_count, iter_frames, marks

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
    for name in ("five", "two", "heavy", "hung"):
        image = pygame.surfarray.array3d(pygame.image.load(str(tmp_path / name / "strobe.png")))
        # One squashed image of every ball at every time: the last ball's colour in many rows.
        rows = np.all(image == cradle.COLOURS[-1], axis=2).any(axis=0)
        assert rows.sum() > 100, name


# -- the hung cradle -------------------------------------------------------------------------


class HungRun(NamedTuple):
    """The hung scene's cradle stepped through the scene's duration: after every step (and at
    the start), each ball's place and velocity, and the longest rod error seen."""

    cradle: cradle.HungCradle
    places: list[list[tuple[float, float]]]
    velocities: list[list[tuple[float, float]]]
    worst_rod: float


@functools.cache
def hung_run() -> HungRun:
    c = cradle.HungCradle()
    places, velocities, worst = [], [], 0.0
    steps = round(cradle.HungScene.duration / cradle.HUNG_DT)
    for n in range(steps + 1):
        if n:
            c.step(cradle.HUNG_DT)
        places.append([(b.pos.x, b.pos.y) for b in c.balls])
        velocities.append([(b.vel.x, b.vel.y) for b in c.balls])
        for ball, rod in zip(c.balls, c.rods, strict=True):
            top = rod.other
            assert isinstance(top, Vector)
            worst = max(worst, abs((ball.pos - top).length() - cradle.LENGTH))
    return HungRun(c, places, velocities, worst)


def quarter_period(length: float, angle: float) -> float:
    """A quarter of the exact pendulum period, sqrt(L/g) K(sin(theta0 / 2)), K by the AGM."""
    a, b = 1.0, math.cos(math.radians(angle) / 2.0)  # sqrt(1 - k^2)
    for _ in range(30):
        a, b = (a + b) / 2.0, math.sqrt(a * b)
    return math.sqrt(length / cradle.G) * math.pi / (2.0 * a)


def blows(run: HungRun) -> list[int]:
    """The steps in which a blow passed the speed from one end ball to the other: one went
    from above 0.5 m/s to below, the other from below to above."""

    def speeds(n: int) -> tuple[float, float]:
        return math.hypot(*run.velocities[n][0]), math.hypot(*run.velocities[n][-1])

    found = []
    for n in range(1, len(run.velocities)):
        (a0, b0), (a1, b1) = speeds(n - 1), speeds(n)
        if (a0 > 0.5 > a1 and b0 < 0.5 < b1) or (b0 > 0.5 > b1 and a0 < 0.5 < a1):
            found.append(n)
    return found


def energy_per_kg(run: HungRun, n: int, k: int) -> float:
    """Ball k's energy per kg after step n, from its lowest place (y = -LENGTH)."""
    (vx, vy), (_, y) = run.velocities[n][k], run.places[n][k]
    return 0.5 * (vx * vx + vy * vy) + cradle.G * (y + cradle.LENGTH)


def test_the_hung_cradle_passes_the_blow_there_and_back() -> None:
    run = hung_run()
    found = blows(run)
    # Ball 1 comes down at T/4 of the exact pendulum's period; each end ball then swings out
    # and back in T/2, so the blows come at T/4, 3T/4, 5T/4: three in the scene's 4 s.
    quarter = quarter_period(cradle.LENGTH, cradle.ANGLE)
    assert len(found) == 3, [n * cradle.HUNG_DT for n in found]
    for j, n in enumerate(found):
        assert abs(n * cradle.HUNG_DT - (2 * j + 1) * quarter) <= 2 * cradle.HUNG_DT, j
        # Ball 1 sends ball 5 off, ball 5 (come back) sends ball 1 off, and so on: the one
        # that leaves has the speed the other came in with (from their energies, at the
        # bottom), and the rest are at rest.
        incoming, outgoing = (0, cradle.BALLS - 1) if j % 2 == 0 else (cradle.BALLS - 1, 0)
        ratio = energy_per_kg(run, n, outgoing) / energy_per_kg(run, n - 1, incoming)
        assert abs(math.sqrt(ratio) - 1.0) <= 1e-6, j
        assert run.velocities[n][outgoing][0] * (1 if outgoing else -1) > 2.0, j  # outward
        for k in range(cradle.BALLS):
            if k != outgoing:
                assert math.hypot(*run.velocities[n][k]) <= 1e-6, (j, k)
    assert run.worst_rod <= 1e-9


def test_the_hung_cradles_energy_is_kept_and_its_momentum_is_not() -> None:
    run = hung_run()
    history = run.cradle.history
    first = history[0]
    # At rest, ball 1 raised L (1 - cos 30 degrees): all the energy is potential.
    raised = cradle.LENGTH * (1.0 - math.cos(math.radians(cradle.ANGLE)))
    assert first.energy == 0.0 and first.momentum == 0.0
    assert first.potential == pytest.approx(cradle.G * raised, rel=1e-12)
    # E = KE + PE is kept to RATTLE's bounded error, the bound the read-out states (7e-5 J),
    # and the error leaves at the turning points (kinetic energy near its least).
    assert max(abs(s.total - first.total) for s in history) < 7e-5
    turning = [
        s
        for a, s, b in zip(history, history[1:], history[2:], strict=False)
        if s.energy <= min(a.energy, b.energy) and s.energy < 1e-3
    ]
    assert len(turning) >= 2
    assert all(abs(s.total - first.total) <= 1e-5 for s in turning)
    # The kinetic and potential parts trade: the kinetic energy runs from 0 to nearly all of E.
    kinetic = [s.energy for s in history]
    assert min(kinetic) == 0.0 and max(kinetic) > first.total - 1e-3
    # The horizontal momentum swings both ways with the end balls (it is not kept) ...
    speed = math.sqrt(2.0 * cradle.G * raised)
    assert max(s.momentum for s in history) == pytest.approx(speed, rel=1e-3)
    assert min(s.momentum for s in history) == pytest.approx(-speed, rel=1e-3)
    # ... but a blow passes it on: the rods, near upright then, change it little in that step.
    for n in blows(run):
        before, after = history[n - 1].momentum, history[n].momentum
        assert abs(after - before) <= 1e-3 * abs(before), n


def packed(pixels: np.ndarray) -> np.ndarray:
    """Each pixel's colour as one integer, 0xRRGGBB (one comparison a pixel, not three)."""
    rgb = pixels.astype(np.int32)
    return (rgb[..., 0] << 16) | (rgb[..., 1] << 8) | rgb[..., 2]


def code(colour: tuple[int, int, int]) -> int:
    return (colour[0] << 16) | (colour[1] << 8) | colour[2]


def test_the_hung_frames_draw_the_rods_each_ball_where_it_is_and_its_velocity_as_a_bar() -> None:
    run = hung_run()
    scene = cradle.HungScene()
    checked = 0
    for _index, t, surface in iter_frames(scene, fps=10, seconds=scene.duration, size=(640, 360)):
        pixels = packed(pygame.surfarray.array3d(surface))
        n = round(t / cradle.HUNG_DT)  # each frame's time is a step's: the state after step n
        cam = scene.camera
        above = pixels[:, : scene.bars.top]  # the bar, rods and balls, above the panels
        r = cam.length(cradle.RADIUS)
        rod = pixels == code(cradle.ROD)
        for k, colour in enumerate(cradle.COLOURS):
            x, y = run.places[n][k]
            xs, ys = np.nonzero(above == code(colour))
            assert len(xs) > 0.6 * np.pi * r * r, (t, k)  # a whole disc, less its number
            want = cam.to_px(x, y)
            assert abs(xs.mean() - want[0]) < 1.5 and abs(ys.mean() - want[1]) < 1.5, (t, k)
            # Its rod: the rod's colour at (or beside) every point from the bar to the ball.
            top = (2.0 * cradle.RADIUS * k, 0.0)
            for f in np.linspace(0.05, 1.0 - (cradle.RADIUS + 0.05) / cradle.LENGTH, 12):
                px, py = cam.point((top[0] + f * (x - top[0]), top[1] + f * (y - top[1])))
                assert rod[px - 1 : px + 2, py - 1 : py + 2].any(), (t, k, f)
        # The bar the rods hang from, across the row's tops.
        bar = cam.point((0.0, 0.0))[1]
        for xm in (-0.5, 2.0, 4.5):
            assert pixels[cam.point((xm, 0.0))[0], bar] == code(cradle.FLOOR), (t, xm)
        # The bars: each ball's horizontal velocity up (to the right) or down from the zero
        # line, on the scale, above the row of values and numbers.
        box = pixels[scene.bars.left : scene.bars.right, scene.bars.top : scene.bar_values]
        zero = scene.bar_zero - scene.bars.top
        for k, colour in enumerate(cradle.COLOURS):
            v = run.velocities[n][k][0]
            rows = np.nonzero((box == code(colour)).any(axis=0))[0]
            assert abs(len(rows) - abs(v) * scene.bar_scale) <= 1.0, (t, k)
            if len(rows):
                assert (rows < zero).all() if v > 0 else (rows >= zero).all(), (t, k)
        checked += 1
    assert checked == 41


@pytest.mark.parametrize("name", ["five", "two", "heavy"])
def test_every_velocity_arrow_stays_whole_in_the_frame(name: str) -> None:
    # The heavy scene's ball 5 ran its arrowhead into the right edge by frame 105.
    scene = cradle.DEMO.scenes[name]()
    last = frame_count(scene.duration, 30) - 1
    for k, _, surface in iter_frames(scene, fps=30, size=(640, 360), only={0, last // 2, last}):
        heads = [m for m in marks.marks(surface) if m.kind == "arrowhead"]
        assert heads, k
        assert marks.problems(surface) == [], k
