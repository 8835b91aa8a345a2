"""The README's code runs and says what it does: the examples a newcomer copies first."""

from __future__ import annotations

import math
import re
import subprocess
from pathlib import Path

import pygame
import pytest

from engine import Vector
from engine.integrators import semi_implicit_euler

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
PYTHON_BLOCKS = re.findall(r"```python\n(.*?)```", README, flags=re.S)


def test_the_ten_line_example_moves_the_ball_as_semi_implicit_euler_does(capsys) -> None:
    scope: dict[str, object] = {}
    exec(PYTHON_BLOCKS[0], scope)  # noqa: S102 - the README's own example
    ball = scope["ball"]
    # The same physics by hand: a = g - (k/m)(v - air), stepped 60 times.
    g, k, m, air = Vector(0, -9.81), 0.1, 0.5, Vector(2, 0)

    def accel(t: float, x: Vector, v: Vector) -> Vector:
        return g - (v - air) * (k / m)

    x, v = Vector(0, 0), Vector(3, 4)
    for n in range(60):
        x, v = semi_implicit_euler(x, v, accel, n / 60, 1 / 60)
    assert ball.pos.distance_to(x) < 1e-12  # type: ignore[attr-defined]
    assert str(ball.pos) in capsys.readouterr().out  # type: ignore[attr-defined]


def run_game_block(monkeypatch, frames: int = 40) -> dict[str, object]:
    """Run the README's game loop headless for ``frames`` frames of 1/60 s, RIGHT held."""
    block = next(b for b in PYTHON_BLOCKS if "pygame.display.set_mode" in b)
    polls = {"n": 0}

    def events() -> list[pygame.event.Event]:
        polls["n"] += 1
        return [pygame.event.Event(pygame.QUIT)] if polls["n"] > frames else []

    class RightHeld:
        def __getitem__(self, key: int) -> bool:
            return key == pygame.K_RIGHT

    import engine
    import engine.render

    monkeypatch.setattr(engine.render, "init_window", engine.render.init_headless)
    # Frames of exactly 1/60 s, as in a headless run: 40 frames are 80 steps of 1/120 s.
    monkeypatch.setattr(engine, "RealClock", lambda: engine.VirtualClock(60))
    monkeypatch.setattr(pygame.event, "get", events)
    monkeypatch.setattr(pygame.key, "get_pressed", RightHeld)
    scope: dict[str, object] = {}
    exec(block, scope)  # noqa: S102 - the README's own example
    scope["polls"] = polls["n"]
    return scope


def test_the_game_loop_steers_alfred_with_the_keys(monkeypatch) -> None:
    scope = run_game_block(monkeypatch)
    alfred, world = scope["alfred"], scope["world"]
    assert scope["polls"] == 41
    assert alfred.own_acc == (9.0, 0.0)  # type: ignore[attr-defined]
    assert world.steps == 80  # type: ignore[attr-defined]
    assert alfred.vel.x > 0 and alfred.pos.x > 5.5  # type: ignore[attr-defined]


def test_the_game_loop_is_the_crumb_games_core(monkeypatch) -> None:
    # The README quotes the crumb game's core: the same start, push, wind coupling, step and
    # paper on the same canvas. (Its wind is the gust's main term only, to stay short.)
    import demos.crumb as crumb

    scope = run_game_block(monkeypatch, frames=0)  # set up, then closed before a frame
    alfred, world, loop, camera = (scope[k] for k in ("alfred", "world", "loop", "camera"))
    assert alfred.pos == crumb.CrumbGame().start  # type: ignore[attr-defined]
    pushed = run_game_block(monkeypatch, frames=1)["alfred"]
    assert pushed.own_acc == (crumb.PUSH, 0.0)  # type: ignore[attr-defined]
    (wind,) = world.forces  # type: ignore[attr-defined]
    assert wind.k == crumb.K
    assert loop.dt == crumb.DT  # type: ignore[attr-defined]
    scene = crumb.CrumbScene()
    scene.build((640, 360))
    for corner in ((0.0, 0.0), (11.0, 8.5)):
        assert camera.point(corner) == scene.camera.point(corner)  # type: ignore[attr-defined]
    assert crumb.PAPER == (0.0, 0.0, 11.0, 8.5)
    # The same walls and the same reach: the edge Box and the crumb's sensor.
    game = crumb.CrumbGame()
    edge, sensor = world.colliders  # type: ignore[attr-defined]
    assert repr(edge) == repr(game.edge)
    assert sensor.sensor and sensor.radius == pytest.approx(game.sensor.radius)  # type: ignore[union-attr]
    assert alfred.radius == crumb.RADIUS  # type: ignore[attr-defined]
    for t in (0.0, 1.0, 4.0):
        assert wind.air(t).x == pytest.approx(2.5 * math.sin(0.45 * t))
        assert crumb.gust(t).x - 1.0 * math.sin(1.7 * t) == pytest.approx(wind.air(t).x)


@pytest.mark.parametrize("marker", ["demo-command", "test-command"])
def test_ci_finds_each_start_command_right_after_its_marker(marker: str) -> None:
    # .ci/run reads these lines and runs them: they must be where it looks.
    after = README.split(f"<!-- {marker} -->\n", 1)[1]
    fence, command = after.splitlines()[:2]
    assert fence == "```"
    assert command.startswith("python3 -m venv .venv && .venv/bin/pip install")
    script = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert f"readme_command {marker}" in script


def test_every_image_the_readme_shows_exists() -> None:
    images = re.findall(r"\]\((assets/[^)]+\.png)\)", README)
    assert len(images) >= 7
    missing = [path for path in images if not (ROOT / path).is_file()]
    assert not missing


def test_every_demo_is_in_the_readme() -> None:
    listing = subprocess.run(
        ["python", "-m", "demos"], cwd=ROOT, capture_output=True, text=True, check=True
    ).stdout
    names = re.findall(r"^  (\w+)\s", listing, flags=re.M)
    assert names
    assert [name for name in names if f"`{name}`" not in README] == []


def test_the_vector_names_table_says_where_each_name_comes_from() -> None:
    from pygame.math import Vector2
    from test_vector_pygame import DELIBERATE, NAMES

    pymunk = pytest.importorskip("pymunk")  # the bench extra
    Vec2d = pymunk.Vec2d

    section = README.split("### Vector names", 1)[1].split("\n## ", 1)[0]
    rows = [r for r in section.splitlines() if r.startswith("| `")]
    assert len(rows) > 25
    origins = {"pygame": Vector2, "pymunk": Vec2d}
    for row in rows:
        names_cell, origin = row.split(" | ")[:2]
        origin = origin.strip()
        for name in re.findall(r"`([^`]+)`", names_cell):
            word = re.match(r"(?:Vector\.)?([a-z_]+)", name)
            if word is None:  # an operator or a constructor call, e.g. `v // s`, `Vector(x)`
                continue
            attr = word.group(1)
            if attr in ("v", "s", "round", "x", "y"):
                continue
            assert hasattr(Vector, attr), f"the README lists {name}, which Vector lacks"
            for source, cls in origins.items():
                if source in origin:
                    assert hasattr(cls, attr), f"the README says {name} is {source}'s"
    # pygame's own test class: the counts the README gives.
    if NAMES:
        assert f"{len(NAMES) - len(DELIBERATE)} of its {len(NAMES)} tests pass" in " ".join(
            section.split()
        )
        assert f"the other {len(DELIBERATE)} are" in " ".join(section.split())


def test_the_breakout_core_is_the_breakout_games_and_scores_by_its_events() -> None:
    # The README quotes the breakout game's core: the same walls, drain, bricks, ball and
    # paddle as demos/breakout.py; run as it stands, it scores 10 a brick removed.
    import demos.breakout as bo
    from engine import Body, Segment

    block = next(b for b in PYTHON_BLOCKS if "kinematic=True" in b)
    scope: dict[str, object] = {}
    exec(block, scope)  # noqa: S102 - the README's own example
    world, bricks = scope["world"], scope["bricks"]
    assert isinstance(bricks, list)
    game = bo.BreakoutGame()

    def shape(c: Segment) -> tuple[float, ...]:
        return tuple(round(v, 9) for v in (*c.a, *c.b, c.radius, c.sensor))

    colliders = world.colliders  # type: ignore[attr-defined]
    assert [shape(c) for c in colliders[:4]] == [shape(c) for c in (*game.walls, game.drain)]
    standing = {shape(c) for c in game.bricks}
    assert len(standing) == bo.ROWS * bo.COLUMNS
    assert list(colliders[4:]) == bricks and {shape(c) for c in bricks} <= standing
    for name, theirs in (("ball", game.ball), ("paddle", game.paddle)):
        mine = scope[name]
        assert isinstance(mine, Body)
        assert (mine.radius, mine.restitution, mine.friction, mine.kinematic) == (
            theirs.radius,
            theirs.restitution,
            theirs.friction,
            theirs.kinematic,
        )
    assert scope["paddle"].pos.y == bo.PADDLE_Y  # type: ignore[attr-defined]
    assert scope["score"] == 10 * (len(standing) - len(bricks)) > 0
