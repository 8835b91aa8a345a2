"""The breakout game: whole games to their end, its rules from the contact events, the paddle's
aim, determinism, and its pictures by their pixels."""

from __future__ import annotations

import math

import numpy as np
import pygame
import pytest

import demos.breakout as bo
from demos.cli import main
from engine import Vector
from engine.render import init_headless

BRICKS = bo.ROWS * bo.COLUMNS


def still(game: bo.BreakoutGame) -> float:
    """A player who never moves the paddle."""
    return float(game.paddle.pos.x)


def play_to_the_end(seed: int, player: bo.Player | None = None) -> tuple[bo.BreakoutGame, int]:
    """Play a whole game, checking the rules against the World's events at every step.

    Returns the game and how many balls went down the drain.
    """
    game = bo.BreakoutGame(seed, player)
    x0, _, x1, y1 = bo.FIELD
    r, eps = bo.BALL_RADIUS, 1e-9
    removed, drained = 0, 0
    for _ in range(300 * 120):  # 300 s of game time at most
        standing, lives = set(game.bricks), game.score.lives
        game.step(bo.DT)
        began = game.world.began
        gone = standing - set(game.bricks)
        hit = {event.collider for event in began if event.body is game.ball}
        # Every brick removed is a brick the ball began touching in this step, and every brick
        # it touched is removed; a removed brick is out of the World.
        assert gone == hit & standing
        assert not gone & set(game.world.colliders)
        removed += len(gone)
        # A life is lost exactly when the drain reports the ball.
        down = [e for e in began if e.collider is game.drain and e.body is game.ball]
        if game.score.lives < lives:
            assert len(down) == 1 and lives - game.score.lives == 1
            drained += 1
        elif not game.score.over:
            assert not down
        # The ball never leaves the field but by the drain: between the walls, under the
        # ceiling, never below the drain (a drained ball is served again from the paddle).
        x, y = game.ball.pos
        assert x0 + r - eps <= x <= x1 - r + eps and y <= y1 - r + eps, game.t
        assert y >= bo.DRAIN_Y - bo.DRAIN_RADIUS - r, game.t
        # Every bounce is lossless and the paddle never speeds the ball: its speed is SPEED.
        if game.serve_at is None and not game.score.over:
            assert game.ball.vel.magnitude() == pytest.approx(bo.SPEED, rel=1e-12)
        if game.score.over:
            break
    else:
        pytest.fail(f"the game did not end in 300 s: {game.score}")
    assert game.score.points == bo.POINTS * removed
    assert game.score.bricks == removed == BRICKS - len(game.bricks)
    assert bo.LIVES - game.score.lives == drained
    assert not game.bricks or game.score.lives == 0  # it ends for one of its two reasons
    # The colliders left are the walls, the drain and exactly the bricks standing.
    assert set(game.world.colliders) == {*game.walls, game.drain, *game.bricks}
    assert game.world.capped == 0
    return game, drained


@pytest.fixture(scope="module")
def short_game() -> tuple[bo.BreakoutGame, int]:
    """Seed 4's whole game by the autopilot (a short one), its rules checked at every step."""
    return play_to_the_end(4)


def test_the_autopilot_plays_whole_games_by_the_rules(
    short_game: tuple[bo.BreakoutGame, int],
) -> None:
    # Seed 1 is the demo's default; seed 4 a short game. Between them the autopilot both
    # clears a wall and loses balls, so both ends and the drain are played through.
    results = [play_to_the_end(1), short_game]
    assert any(not game.bricks for game, _ in results)  # a cleared wall
    assert sum(drained for _, drained in results) > 0
    # Left alone, the paddle loses every ball: 3 lives, each a drain event, game over.
    game, drained = play_to_the_end(2, still)
    assert drained == bo.LIVES and game.score.lives == 0 and game.bricks


def test_the_round_top_of_the_paddle_aims_the_ball() -> None:
    # A ball falling straight onto the still paddle, d off its centre, leaves mirrored about
    # the normal at the point of contact: n = (d, h) / (R + r), h = sqrt((R + r)^2 - d^2).
    leaving = []
    for d in (0.0, 0.3, -0.5, 0.7):
        game = bo.BreakoutGame(seed=1, player=still)
        game.serve_at = None
        px = game.paddle.pos.x
        game.ball.pos, game.ball.vel = Vector(px + d, 3.0), Vector(0.0, -bo.SPEED)
        events = []
        while not events:
            game.step(bo.DT)
            events = [e for e in game.world.began if game.paddle in (e.body, e.collider)]
            assert game.t < 1.0
        (event,) = events
        reach = bo.PADDLE_RADIUS + bo.BALL_RADIUS
        normal = Vector(d, math.sqrt(reach**2 - d**2)) / reach
        assert event.normal.distance_to(normal if event.body is game.ball else -normal) < 1e-9
        v_in = Vector(0.0, -bo.SPEED)
        mirrored = v_in - normal * (2 * v_in.dot(normal))
        assert game.ball.vel.distance_to(mirrored) < 1e-9
        # Nothing pushes a kinematic body: the paddle stays where the game put it.
        assert game.paddle.pos == (px, bo.PADDLE_Y) and game.paddle.vel == (0.0, 0.0)
        leaving.append(game.ball.vel)
    straight, right, left, far_right = leaving
    assert straight.x == pytest.approx(0.0, abs=1e-12) and straight.y > 0
    assert left.x < 0 < right.x < far_right.x  # further off centre, a flatter angle


def test_a_ball_past_the_paddle_costs_a_life_and_is_served_again() -> None:
    game = bo.BreakoutGame(seed=3, player=still)
    game.serve_at = None
    game.ball.pos, game.ball.vel = Vector(2.0, 1.0), Vector(0.0, -bo.SPEED)  # far from it
    while game.score.lives == bo.LIVES:
        game.step(bo.DT)
        assert game.t < 1.0
    (down,) = [e for e in game.world.began if e.collider is game.drain]
    assert down.body is game.ball and game.drain.sensor
    # The next ball rides on the paddle, then leaves upward at SPEED within 30 degrees of up.
    assert game.serve_at is not None
    lost = game.t
    while game.serve_at is not None:
        assert game.ball.pos.x == pytest.approx(game.paddle.pos.x)
        game.step(bo.DT)
    assert game.t - lost == pytest.approx(bo.SERVE_DELAY, abs=bo.DT)
    vel = game.ball.vel
    assert vel.magnitude() == pytest.approx(bo.SPEED) and vel.y >= bo.SPEED * math.cos(
        math.radians(30.0)
    )


def test_the_paddle_moves_at_most_its_speed_and_stays_in_the_field() -> None:
    game = bo.BreakoutGame(seed=1, player=lambda g: 1e6)  # a player who wants it far right
    x = game.paddle.pos.x
    game.step(bo.DT)
    assert game.paddle.pos.x == pytest.approx(x + bo.PADDLE_SPEED * bo.DT)
    for _ in range(240):
        game.step(bo.DT)
    assert game.paddle.pos.x == pytest.approx(bo.FIELD[2] - bo.PADDLE_RADIUS)
    assert game.paddle.pos.y == bo.PADDLE_Y


def test_a_game_saved_mid_run_resumes_exactly() -> None:
    game = bo.BreakoutGame(seed=1)
    for _ in range(8 * 120):
        game.step(bo.DT)
    saved, bricks = game.snapshot(), dict(game.bricks)
    assert len(bricks) < BRICKS  # some are gone: restoring has to bring them back

    def run() -> list[tuple[float, ...]]:
        path = []
        for _ in range(6 * 120):
            game.step(bo.DT)
            path.append((*game.ball.pos, *game.paddle.pos, game.score.points))
        return path

    first, after = run(), len(game.bricks)
    assert after < len(bricks)
    game.restore(saved)
    assert game.bricks == bricks and game.world.colliders[-len(bricks) :] == tuple(bricks)
    assert run() == first and len(game.bricks) == after


def test_headless_runs_are_byte_identical_and_end_with_the_game(
    tmp_path, short_game: tuple[bo.BreakoutGame, int]
) -> None:
    runs = []
    for name in ("a", "b"):
        out = tmp_path / name
        score = bo.play(window=False, fps=5, size=(160, 90), seed=4, out=out)
        runs.append((score, [p.read_bytes() for p in sorted(out.glob("frame_*.png"))]))
    (score_a, frames_a), (score_b, frames_b) = runs
    assert score_a.over and score_a == score_b
    assert frames_a == frames_b
    # Without --seconds the recording stops AFTER_END s after the game ends.
    game, _ = short_game
    assert len(frames_a) == math.ceil((game.t + bo.AFTER_END) * 5 - 1e-9)


def test_the_picture_shows_the_paddle_ball_bricks_and_score() -> None:
    init_headless()
    scene = bo.BreakoutScene()
    size = (640, 360)
    scene.build(size)
    game, camera = scene.game, scene.camera
    surface = pygame.Surface(size)

    def pixel(where: Vector) -> tuple[int, int, int]:
        return tuple(surface.get_at(camera.point(where)))[:3]  # type: ignore[return-value]

    scene.draw(surface, 1.0)
    top_before = pygame.surfarray.array3d(surface)[:, :36].copy()
    while game.score.bricks == 0:
        scene.step(bo.DT)
    scene.draw(surface, 1.0)
    assert pixel(game.paddle.pos) == bo.PADDLE_COLOUR
    assert pixel(game.paddle.pos + (bo.PADDLE_RADIUS * 0.9, 0.0)) == bo.PADDLE_COLOUR
    assert pixel(game.paddle.pos + (bo.PADDLE_RADIUS * 1.2, 0.0)) != bo.PADDLE_COLOUR
    assert pixel(game.ball.pos) == bo.BALL_COLOUR
    for brick, row in game._rows.items():
        colour = bo.ROW_COLOURS[row] if brick in game.bricks else bo.BACKGROUND
        assert pixel((brick.a + brick.b) / 2) == colour
    # The score line changed with the score, in the ink's colour.
    top = pygame.surfarray.array3d(surface)[:, :36]
    assert np.all(top == bo.INK, axis=2).any()
    assert (top != top_before).any()


def test_keys_and_mouse_move_the_paddle(monkeypatch) -> None:
    init_headless()
    scene = bo.BreakoutScene(person=True)
    scene.build((640, 360))
    game, person = scene.game, scene.game.player
    assert isinstance(person, bo.Person)
    held = {"key": pygame.K_LEFT}

    class Keys:
        def __getitem__(self, key: int) -> bool:
            return key == held["key"]

    mouse = {"at": (320, 200)}
    monkeypatch.setattr(pygame.key, "get_pressed", Keys)
    monkeypatch.setattr(pygame.mouse, "get_pos", lambda: mouse["at"])
    monkeypatch.setattr(pygame.mouse, "get_focused", lambda: True)
    x = game.paddle.pos.x
    game.step(bo.DT)
    assert game.paddle.pos.x == pytest.approx(x - bo.PADDLE_SPEED * bo.DT)
    held["key"] = -1  # keys up: the paddle waits for the mouse to move
    x = game.paddle.pos.x
    game.step(bo.DT)
    assert game.paddle.pos.x == x
    mouse["at"] = (400, 200)  # the pointer moved: the paddle heads under it
    goal = scene.camera.to_world(400, 200)[0]
    for _ in range(120):
        game.step(bo.DT)
    assert game.paddle.pos.x == pytest.approx(goal)


def test_command_line_runs_headless(tmp_path, capsys) -> None:
    out = tmp_path / "game"
    assert main(["breakout", "--seconds", "1", "--fps", "5", "--out", str(out)]) == 0
    assert len(list(out.glob("frame_*.png"))) == 5
    assert "points" in capsys.readouterr().out
