"""The incline demo: the race's finishing times and the slip's accelerations against their
closed forms, the frame's radius lines and labels, and the frames the command line writes."""

from __future__ import annotations

import io
import math
from pathlib import Path

import pygame
import pytest

from demos.cli import main
from demos.incline import (
    DISC,
    HOOP,
    LENGTH,
    RACE_SLOPE,
    RADIUS,
    SLIP_MU,
    SLIP_RADIUS,
    SLIP_SLOPE,
    G,
    RaceScene,
    SlipScene,
    crossing_time,
)
from engine.render import INK


@pytest.fixture(scope="module")
def race() -> RaceScene:
    scene = RaceScene()
    scene.build((640, 360))
    for _ in range(round(scene.duration / scene.dt)):
        scene.step(scene.dt)
    return scene


@pytest.fixture(scope="module")
def slip() -> SlipScene:
    scene = SlipScene()
    scene.build((640, 360))
    for _ in range(round(scene.duration / scene.dt)):
        scene.step(scene.dt)
    return scene


def test_each_racer_finishes_at_the_closed_forms_time(race: RaceScene) -> None:
    """t = sqrt(2 L / a), a = g sin(theta) / (1 + I / (m r^2)): measured within the step by
    the step's own constant acceleration, the times agree to 1e-12 (5e-15 at most seen)."""
    gs = G * math.sin(RACE_SLOPE)
    slider, disc, hoop = race.race.racers
    for racer, ratio in ((slider, 0.0), (disc, 0.5), (hoop, 1.0)):
        assert racer.finish is not None, f"the {racer.name} did not finish"
        exact = math.sqrt(2 * LENGTH * (1 + ratio) / gs)
        assert racer.finish == pytest.approx(exact, rel=1e-12)
        assert racer.theory == pytest.approx(exact, rel=1e-15)
    assert slider.finish is not None and disc.finish is not None and hoop.finish is not None
    assert disc.finish / slider.finish == pytest.approx(math.sqrt(1.5), rel=1e-12)
    assert hoop.finish / slider.finish == pytest.approx(math.sqrt(2.0), rel=1e-12)


def test_the_rollers_roll_and_the_slider_never_turns(race: RaceScene) -> None:
    slider, disc, hoop = race.race.racers
    assert slider.body.angular_velocity == 0.0 and slider.body.angle == 0.0
    for racer in (disc, hoop):
        _, v = racer.along()
        # Rolling downhill to the right is clockwise: v = -omega r.
        assert racer.body.angular_velocity * RADIUS == pytest.approx(-v, rel=1e-9)


def test_the_crossing_time_solves_the_steps_motion() -> None:
    # s = 1 + 2 tau + 3 tau^2 over a step of 0.5 s from t0 = 10 (a = 6): s = 2 at tau = 1/3.
    t = crossing_time(10.0, 0.5, 1.0, 2.0, 1.0 + 1.0 + 0.75, 2.0 + 3.0, 2.0)
    assert t == pytest.approx(10.0 + 1.0 / 3.0, rel=1e-15)
    assert crossing_time(10.0, 0.5, 1.0, 2.0, 1.5, 0.0, 2.0) is None  # did not reach it


def test_the_slipping_disc_matches_g_sin_minus_mu_cos_and_its_spin_up(slip: SlipScene) -> None:
    th = SLIP_SLOPE
    a = G * (math.sin(th) - SLIP_MU * math.cos(th))
    spin = 2 * SLIP_MU * G * math.cos(th) / SLIP_RADIUS
    assert slip.slip.accel == pytest.approx(a, rel=1e-9)
    assert slip.slip.angular == pytest.approx(spin, rel=1e-9)
    t = slip.slip.t
    v, wr = slip.slip.speeds()
    assert v == pytest.approx(a * t, rel=1e-9)
    assert wr == pytest.approx(spin * SLIP_RADIUS * t, rel=1e-9)
    # The slip speed v - omega r grows at g (sin - 3 mu cos) (q = 2 for a disc).
    slips = [v - w for _, v, w in slip.slip.samples]
    assert all(b > a for a, b in zip(slips, slips[1:], strict=False))
    assert slips[-1] == pytest.approx(G * (math.sin(th) - 3 * SLIP_MU * math.cos(th)) * t)


def test_the_readout_is_the_state_at_the_frames_time(slip: SlipScene) -> None:
    th = SLIP_SLOPE
    a = G * (math.sin(th) - SLIP_MU * math.cos(th))
    v, _ = slip.slip.at(1.0 + 1 / 240)
    assert v == pytest.approx(a * (1.0 + 1 / 240), rel=1e-9)


def test_the_race_frame_draws_radius_lines_and_labels(race: RaceScene) -> None:
    surface = pygame.Surface((640, 360))
    race.draw(surface, 1.0)
    slider, disc, hoop = race.race.racers
    cam = race.camera

    def ink_along(racer, angle: float) -> int:
        p = racer.body.pos
        points = [
            (p.x + f * RADIUS * math.cos(angle), p.y + f * RADIUS * math.sin(angle))
            for f in (0.4, 0.55, 0.7)  # inside the hoop's rim
        ]
        return sum(tuple(surface.get_at(cam.point(q)))[:3] == INK for q in points)

    # The disc's and the hoop's radius lines lie at their angles, and not across them.
    for racer in (disc, hoop):
        angle = racer.body.angle
        assert ink_along(racer, angle) == 3
        assert ink_along(racer, angle + math.pi / 2) == 0
    # Nothing turns the slider: its line stays along +x, where it started.
    assert ink_along(slider, 0.0) == 3
    assert all(ink_along(slider, k * math.pi / 4) == 0 for k in range(1, 8))
    # Each racer's name is written in its colour.
    colours = {tuple(c)[:3] for c in pygame.surfarray.array3d(surface).reshape(-1, 3)}
    assert DISC in colours and HOOP in colours


def test_the_command_line_writes_the_frames(tmp_path: Path) -> None:
    out = tmp_path / "incline"
    args = ["incline", "--seconds", "0.5", "--fps", "4", "--size", "480x270"]
    assert main([*args, "--out", str(out)], io.StringIO()) == 0
    for scene in ("race", "slip"):
        frames = sorted((out / scene).glob("frame_*.png"))
        assert [f.name for f in frames] == [f"frame_{k:05d}.png" for k in range(3)]
        image = pygame.image.load(str(frames[-1]))
        assert image.get_size() == (480, 270)
        assert (
            len({tuple(image.get_at((x, y))) for x in range(0, 480, 7) for y in range(0, 270, 7)})
            > 3
        )
    assert main(["incline", "--strobe", "--out", str(tmp_path / "strobe")], io.StringIO()) == 0
    assert (tmp_path / "strobe" / "race" / "strobe.png").is_file()
