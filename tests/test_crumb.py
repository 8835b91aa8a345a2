"""The small game: its physics against the exact solution, its rules, its pixels, determinism."""

from __future__ import annotations

import math

import numpy as np
import pygame
import pytest
from pixels import angle_between, long_axis

import demos.crumb as crumb
from demos.alfred import ANT_BODY
from demos.cli import main
from engine import Vector
from engine.render import Camera, init_headless


def test_steering_in_a_steady_wind_follows_the_exact_solution(monkeypatch) -> None:
    # With a constant air velocity w and a push P d, Alfred's velocity obeys
    # v' = P d - K (v - w), whose solution from v0 is
    #   v(t) = u + (v0 - u) e^{-K t},  u = w + P d / K  (the terminal velocity).
    air = Vector(1.5, -0.5)
    monkeypatch.setattr(crumb, "gust", lambda t: air)
    game = crumb.CrumbGame(seed=3)
    game.steer(1.0, 0.0)
    steps = 120  # 1 s: about 3.8 in to the right of the middle, well short of the edge
    for _ in range(steps):
        game.world.step(crumb.DT)
    t = steps * crumb.DT
    u = air + Vector(crumb.PUSH / crumb.K, 0.0)
    exact = u + (Vector(0, 0) - u) * math.exp(-crumb.K * t)
    # Euler on v' = -K (v - u) multiplies v - u by (1 - K dt) a step instead of e^{-K dt};
    # after n = t / dt steps the error is |u| (e^{-K t} - (1 - K dt)^n)
    #   ~ |u| (K dt / 2) (K t) e^{-K t}  to leading order. Allow twice that.
    bound = u.magnitude() * crumb.K * crumb.DT * crumb.K * t * math.exp(-crumb.K * t)
    assert game.alfred.vel.distance_to(exact) < bound
    assert game.alfred.vel.distance_to(exact) > 0.0  # a numerical method, not the formula


def test_eating_the_crumb_is_the_sensors_event_and_places_a_new_one() -> None:
    game = crumb.CrumbGame(seed=5, player=lambda: (0.0, 0.0))
    old, sensor = game.crumb, game.sensor
    assert sensor is not None and sensor.sensor and sensor.center == old
    game.alfred.pos, game.alfred.vel = old + (crumb.REACH + 0.05, 0.0), Vector(0, 0)
    game.step(crumb.DT)
    assert game.score.crumbs == 0  # just out of reach: no event, no crumb
    game.alfred.pos = old + (crumb.REACH - 0.05, 0.0)  # within reach
    game.step(crumb.DT)
    (event,) = game.world.began
    assert event.collider is sensor and event.body is game.alfred
    assert game.score.crumbs == 1
    assert game.crumb != old and game.sensor is not sensor and game.sensor.center == game.crumb
    assert sensor not in game.world.colliders and game.sensor in game.world.colliders
    x0, y0, x1, y1 = crumb.PAPER
    assert x0 < game.crumb.x < x1 and y0 < game.crumb.y < y1
    game.step(crumb.DT)  # still where the old crumb was: nothing more to eat
    assert game.score.crumbs == 1


def test_the_paper_edge_is_a_wall_he_bumps_off() -> None:
    game = crumb.CrumbGame(seed=5, player=lambda: (0.0, 0.0))
    x1 = crumb.PAPER[2]
    game.alfred.pos, game.alfred.vel = Vector(x1 - 0.25, 2.0), Vector(12.0, 0.0)
    game.step(crumb.DT)
    (event,) = game.world.began
    assert event.collider is game.edge and event.normal == (-1.0, 0.0)
    assert game.score.bumps == 1
    assert game.alfred.pos.x <= x1 - crumb.RADIUS and game.alfred.vel.x < 0.0


def test_the_ant_never_leaves_the_paper_and_every_crumb_is_a_sensor_event() -> None:
    # Random keys held for random spells, in the gusting wind, for 20 s of game time.
    rng = np.random.default_rng(11)
    keys = {"held": (0.0, 0.0), "left": 0}

    def restless() -> tuple[float, float]:
        if keys["left"] == 0:
            keys["held"] = (float(rng.integers(-1, 2)), float(rng.integers(-1, 2)))
            keys["left"] = int(rng.integers(20, 400))
        keys["left"] -= 1
        return keys["held"]

    game = crumb.CrumbGame(seed=7, player=restless)
    eaten = []
    for _ in range(20 * 120):
        sensor = game.sensor
        game.step(crumb.DT)
        eaten += [ev for ev in game.world.began if ev.collider is sensor]
        x, y = game.alfred.pos
        r = crumb.RADIUS
        assert r <= x <= crumb.PAPER[2] - r and r <= y <= crumb.PAPER[3] - r, game.t
    assert game.score.bumps > 0  # he did run into the edge
    assert len(eaten) == game.score.crumbs and all(ev.body is game.alfred for ev in eaten)


def test_steering_is_normalised_so_diagonals_are_not_faster() -> None:
    game = crumb.CrumbGame()
    game.steer(1.0, 1.0)
    assert game.alfred.own_acc.magnitude() == pytest.approx(crumb.PUSH, rel=1e-12)
    game.steer(0.0, 0.0)
    assert game.alfred.own_acc == (0.0, 0.0)


def test_alfred_is_drawn_where_the_camera_puts_him() -> None:
    init_headless()
    game = crumb.CrumbGame(seed=2)
    size = (640, 360)
    camera = Camera.fit(crumb.PAPER, (16, 40, size[0] - 32, size[1] - 56))
    surface = pygame.Surface(size)
    directions = []
    for _ in range(4):
        for _ in range(45):
            game.steer(*game.autopilot())
            game.world.step(crumb.DT)
            game.update()
        game.draw(surface, camera, alpha=1.0)
        pixels = pygame.surfarray.pixels3d(surface)
        body = np.all(pixels == ANT_BODY, axis=2)
        del pixels
        # Seen from above and centred on his position, his head along his velocity: the
        # camera turns the world's (vx, vy), y up, into the pixel direction (vx, -vy).
        centroid, axis, _, _ = long_axis(body)
        assert np.abs(centroid - np.array(camera.point(game.alfred.pos))).max() < 2.0
        vel = game.alfred.vel
        assert vel.magnitude() > 1.0  # walking, so he has a direction to face
        assert angle_between(axis, np.array([vel.x, -vel.y])) < 6.0
        directions.append(math.degrees(math.atan2(vel.y, vel.x)))
    assert max(directions) - min(directions) > 30  # he turned, and the sprite turned with him


def test_standing_still_he_keeps_facing_the_way_he_walked() -> None:
    game = crumb.CrumbGame(seed=2)
    game.alfred.vel = Vector(-3.0, 0.0)
    game.update()
    assert game.heading == pytest.approx(180.0)
    game.alfred.vel = Vector(0.0, 0.0)
    game.update()
    assert game.heading == pytest.approx(180.0)


def test_headless_runs_are_byte_identical_and_eat_crumbs(tmp_path) -> None:
    runs = []
    for name in ("a", "b"):
        out = tmp_path / name
        score = crumb.play(window=False, seconds=6.0, fps=10, size=(160, 90), seed=4, out=out)
        runs.append((score, [p.read_bytes() for p in sorted(out.glob("frame_*.png"))]))
    (score_a, frames_a), (score_b, frames_b) = runs
    assert len(frames_a) == 60
    assert frames_a == frames_b and score_a == score_b
    assert score_a.crumbs >= 1  # the autopilot reaches at least one crumb in 6 s


def test_command_line_runs_headless_and_refuses_bad_options(tmp_path, capsys) -> None:
    out = tmp_path / "game"
    assert main(["crumb", "--seconds", "1", "--fps", "5", "--out", str(out)]) == 0
    assert len(list(out.glob("frame_*.png"))) == 5
    assert "crumbs eaten" in capsys.readouterr().out
    with pytest.raises(SystemExit) as exit_info:
        main(["crumb", "--fps", "0"])
    assert exit_info.value.code == 2
    assert "--fps" in capsys.readouterr().err


def test_in_a_window_the_keys_steer_inside_each_fixed_step(monkeypatch) -> None:
    # The window is the Scene machinery's (engine.render.play), run here on the dummy driver
    # with frames of exactly 1/60 s and the right arrow held, closed after 30 frames.
    import engine.render.recorder as recorder
    from engine import VirtualClock

    polls = {"n": 0}

    def events() -> list[pygame.event.Event]:
        polls["n"] += 1
        return [pygame.event.Event(pygame.QUIT)] if polls["n"] > 30 else []

    class RightHeld:
        def __getitem__(self, key: int) -> bool:
            return key == pygame.K_RIGHT

    monkeypatch.setattr(recorder, "init_window", init_headless)
    monkeypatch.setattr(recorder, "RealClock", lambda: VirtualClock(60))
    monkeypatch.setattr(pygame.event, "get", events)
    monkeypatch.setattr(pygame.key, "get_pressed", RightHeld)
    scene = crumb.CrumbScene(crumb.arrow_keys)
    scene.seed = 4
    steered = []
    monkeypatch.setattr(crumb.CrumbGame, "steer", lambda g, r, u: steered.append((r, u)))
    recorder.play(scene, fps=1000, size=(160, 90), seconds=10.0)
    # One step ahead, then 2 steps in each of the 30 frames of 1/60 s: each step asked the keys.
    assert scene.world.world.steps == 1 + 2 * 30
    assert steered == [(1.0, 0.0)] * scene.world.world.steps
    assert isinstance(crumb.play(window=True, seconds=0.1, size=(160, 90)), crumb.Score)
