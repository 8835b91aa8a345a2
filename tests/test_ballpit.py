"""The ball pit demo: the pile settles inside the box and sleeps, and the frames show it.

The demo drops 2,000 balls; these tests drop a few hundred, which settle within 2 s of
simulated time, so that the file runs in seconds.
"""

from __future__ import annotations

import argparse
import hashlib
import io
import warnings
from pathlib import Path

import numpy as np
import pygame
import pytest

import demos.ballpit as ballpit
from demos.cli import main
from engine import StabilityWarning
from engine.render import init_headless, iter_frames

#: Balls in the tests' pit: ten rows and a bit.
BALLS = 400
R = ballpit.RADIUS


def brute_force_overlap(x: np.ndarray) -> float:
    """The deepest overlap (m) of two balls, or of a ball and the box, pair by pair."""
    d = np.linalg.norm(x[:, None] - x[None], axis=-1)
    np.fill_diagonal(d, np.inf)
    walls = max((R - x[:, 0]).max(), (x[:, 0] - (ballpit.WIDTH - R)).max(), (R - x[:, 1]).max())
    return max(0.0, float((2 * R - d).max()), float(walls))


def settled(balls: int = BALLS, seconds: float = 3.0) -> ballpit.Pit:
    pit = ballpit.Pit(balls)
    while pit.t < seconds - 1e-9:
        pit.step(ballpit.DT)
    return pit


def test_the_drop_grid_starts_every_ball_apart_and_inside_the_box() -> None:
    for balls in (1, 37, BALLS, ballpit.BALLS):
        x = ballpit.drop_grid(balls)
        assert x.shape == (balls, 2)
        assert brute_force_overlap(x) == 0.0
        assert (x[:, 0] >= R).all() and (x[:, 0] <= ballpit.WIDTH - R).all()
        assert (x[:, 1] >= R).all() and (x[:, 1] <= ballpit.box_height(balls) - R).all()
    # Every other row shifted by half the space between balls... so a row nests in the gaps.
    x = ballpit.drop_grid(2 * ballpit.COLUMNS)
    assert x[ballpit.COLUMNS, 0] - x[0, 0] == pytest.approx(2 * ballpit.SHIFT)
    world, bodies = ballpit.pit_world(BALLS)
    assert world.method == "exact" and len(bodies) == BALLS
    assert {(b.radius, b.restitution, b.friction) for b in bodies} == {(R, 0.5, 0.5)}


def test_the_overlap_read_out_is_the_brute_force_answer() -> None:
    rng = np.random.default_rng(5)
    for _ in range(20):
        P = np.column_stack([rng.uniform(0.4, 8.0, 60), rng.uniform(0.45, 6.0, 60)])
        walls = max(0.0, (R - P[:, 0]).max(), (P[:, 0] - (ballpit.WIDTH - R)).max())
        walls = max(walls, (R - P[:, 1]).max())
        assert ballpit.wall_overlap(P) == pytest.approx(walls, abs=1e-12)
    assert ballpit.wall_overlap(np.zeros((0, 2))) == 0.0
    # In a pit that is landing, the read-out is the deepest of every pair and every wall.
    pit = ballpit.Pit(BALLS)
    for _ in range(40):
        pit.step(ballpit.DT)
    x = pit.world.positions()
    assert brute_force_overlap(x) > 0.001 * R
    assert pit.now.overlap * R == pytest.approx(brute_force_overlap(x), rel=1e-9)


def test_the_pit_settles_inside_the_box_overlapping_at_most_1_percent_and_sleeps() -> None:
    pit = settled()
    x, v = pit.world.positions(), pit.world.velocities()
    assert (x[:, 0] >= R - 1e-9).all() and (x[:, 0] <= ballpit.WIDTH - R + 1e-9).all()
    assert (x[:, 1] >= R - 1e-9).all() and (x[:, 1] <= ballpit.box_height(BALLS)).all()
    now = pit.now
    assert now.overlap <= 0.01
    assert brute_force_overlap(x) <= 0.01 * R
    assert now.asleep == BALLS and (v == 0.0).all() and now.kinetic == 0.0
    # Piled up: about 39 balls a row, rows 2 r sin(60 deg) apart, so about 11 rows deep.
    assert x[:, 1].max() < R + 12 * 2 * R * np.sin(np.pi / 3)
    # The read-outs of every step: time, the count, the energy lost to the collisions.
    first = pit.history[0]
    assert len(pit.history) == 181 and first.kinetic == 0.0 and first.asleep == 0
    assert now.potential < 0.8 * first.potential
    assert max(r.kinetic for r in pit.history) > 0.05 * first.potential


def test_the_frames_show_the_balls_awake_then_asleep() -> None:
    scene = ballpit.PitScene()
    scene.balls = BALLS
    shots = {}
    for index, t, surface in iter_frames(scene, fps=2, seconds=3.0, size=(640, 360)):
        shots[t] = pygame.surfarray.array3d(surface)
        if index == 0:
            assert len(np.unique(shots[t].reshape(-1, 3), axis=0)) > 50  # not flat
    left = round(scene.camera.to_px(0.0, 0.0)[0]) - 2  # the pit; the panel lies left of it
    r_px = round(scene.camera.length(R))
    for t, awake, asleep in ((0.0, BALLS, 0), (3.0, 0, BALLS)):
        pit = shots[t][left:]
        for colour, count in ((ballpit.AWAKE, awake), (ballpit.ASLEEP, asleep)):
            xs, ys = np.nonzero(np.all(pit == colour, axis=2))
            if not count:
                assert len(xs) == 0, (t, colour)
                continue
            # Discs of r_px, a little overlapped by their neighbours.
            assert 0.6 * count * np.pi * r_px**2 < len(xs) < 1.2 * count * np.pi * r_px**2
    # At t = 0 the balls are drawn on the grid: the pixels' mean is the grid's, in pixels.
    xs, ys = np.nonzero(np.all(shots[0.0][left:] == ballpit.AWAKE, axis=2))
    want = scene.camera.to_px(*ballpit.drop_grid(BALLS).mean(axis=0))
    assert abs(xs.mean() + left - want[0]) < 1.0 and abs(ys.mean() - want[1]) < 1.0


def test_the_measured_step_time_is_drawn_only_in_a_window() -> None:
    init_headless()
    scene = ballpit.PitScene()
    scene.balls = 50
    scene.build((640, 360))
    for _ in range(3):
        scene.step(scene.dt)
    assert len(scene.pit.step_ms) == 3  # measured all the same

    def drawn() -> bytes:
        surface = pygame.Surface((640, 360))
        scene.draw(surface, 1.0)
        return pygame.image.tobytes(surface, "RGB")

    before = drawn()
    scene.pit.step_ms.extend([123.0, 456.0])
    assert drawn() == before  # frames never show it: they stay the same run to run
    scene.live = True
    assert drawn() != before
    parser = argparse.ArgumentParser()
    ballpit._add_arguments(parser)
    for window in (False, True):
        configured = ballpit.PitScene()
        ballpit._configure(configured, argparse.Namespace(balls=77, window=window))
        assert configured.balls == 77 and configured.live is window
    assert parser.parse_args([]).balls == ballpit.BALLS


def _frames(folder: Path) -> list[bytes]:
    args = ["ballpit", "--balls", "300", "--fps", "4", "--seconds", "2", "--size", "480x270"]
    assert main([*args, "--out", str(folder)], io.StringIO()) == 0
    return [p.read_bytes() for p in sorted(folder.glob("frame_*.png"))]


def test_two_runs_write_identical_frames(tmp_path: Path) -> None:
    first, second = _frames(tmp_path / "a"), _frames(tmp_path / "b")
    assert len(first) == 9  # 2 s at 4 fps, both ends
    digest = [hashlib.sha256(b).hexdigest() for b in first]
    assert digest == [hashlib.sha256(b).hexdigest() for b in second]
    assert len(set(digest)) == len(digest)  # every frame differs: the balls fall and pile


@pytest.mark.parametrize("balls", ["0", "-3", "20001", "many", "1.5"])
def test_a_bad_ball_count_is_a_usage_error_naming_the_option(balls: str, capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        main(["ballpit", "--balls", balls], io.StringIO())
    assert stop.value.code == 2
    assert "--balls" in capsys.readouterr().err
    with pytest.raises(ValueError, match="balls"):
        ballpit.pit_world(0)


def test_the_strobe_shows_the_pit_at_a_few_moments(tmp_path: Path) -> None:
    code = main(
        ["ballpit", "--balls", "200", "--strobe", "--out", str(tmp_path)],
        io.StringIO(),
    )
    assert code == 0
    image = pygame.surfarray.array3d(pygame.image.load(str(tmp_path / "strobe.png")))
    assert np.all(image == ballpit.AWAKE, axis=2).sum() > 200  # the first panels
    assert np.all(image == ballpit.ASLEEP, axis=2).sum() > 200  # the last: asleep


def test_the_worlds_one_warning_shows_at_its_moment_in_a_rerun_from_a_snapshot(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The World warns once in its life (a restore does not undo that), as a stand-in does here
    # at its fifth step: the pit shows the warning from then on, in a rerun too.
    pit = ballpit.Pit(40)
    step, told = pit.world.step, []

    def once(dt: float) -> None:
        step(dt)
        if pit.world.steps == 5 and not told:
            told.append(True)
            warnings.warn("past the solver", StabilityWarning, stacklevel=2)

    monkeypatch.setattr(pit.world, "step", once)
    snap = pit.snapshot()
    seen = []
    for _ in range(8):
        pit.step(ballpit.DT)
        seen.append(pit.warning)
    assert seen[:4] == [None] * 4 and seen[4] == (5 * ballpit.DT, "past the solver")
    pit.restore(snap)
    assert pit.warning is None
    again = []
    for _ in range(8):
        pit.step(ballpit.DT)
        again.append(pit.warning)
    assert again == seen and len(told) == 1
