"""The README's code runs and says what it does: the examples a newcomer copies first."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

import pygame
import pytest

from engine import Vector
from engine.integrators import semi_implicit_euler

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
PYTHON_BLOCKS = re.findall(r"```python\n(.*?)```", README, flags=re.S)
#: The first line of a block that goes on from the one before it, in the same namespace.
CONTINUES = "# continues the block above"


def block(needle: str) -> str:
    """The README's Python block holding ``needle``."""
    (found,) = [b for b in PYTHON_BLOCKS if needle in b]
    return found


def test_the_ten_line_example_moves_the_ball_as_semi_implicit_euler_does(capsys) -> None:
    scope: dict[str, object] = {}
    exec(block("Wind(air_velocity=(2, 0)"), scope)  # noqa: S102 - the README's own example
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
    source = block("pygame.display.set_mode")
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
    exec(source, scope)  # noqa: S102 - the README's own example
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
        [sys.executable, "-m", "demos"], cwd=ROOT, capture_output=True, text=True, check=True
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

    scope: dict[str, object] = {}
    exec(block("bricks = ["), scope)  # noqa: S102 - the README's own example
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


# -- every Python block runs as written ---------------------------------------------------------


def _chains() -> list[list[int]]:
    """The blocks in runs: a block that continues the one above joins its run."""
    runs: list[list[int]] = []
    for i, source in enumerate(PYTHON_BLOCKS):
        if source.startswith(CONTINUES):
            assert runs, "the first block cannot continue another"
            runs[-1].append(i)
        else:
            runs.append([i])
    return runs


@pytest.mark.parametrize("run", _chains(), ids=lambda run: "+".join(map(str, run)))
def test_every_python_block_runs_as_written(run, monkeypatch, tmp_path) -> None:
    # The filter example failed on its own (NameError: world): it goes on from the contacts
    # block, and now says so on its first line and runs after it.
    monkeypatch.chdir(tmp_path)  # what a block writes (out/...) lands here
    if any("pygame.display.set_mode" in PYTHON_BLOCKS[i] for i in run):
        run_game_block(monkeypatch, frames=3)  # a window's loop, headless: see above
        return
    if any("ClipWriter" in PYTHON_BLOCKS[i] for i in run):
        pytest.importorskip("imageio_ffmpeg", reason="the clip example needs the video extra")
    scope: dict[str, object] = {}
    for i in run:
        exec(PYTHON_BLOCKS[i], scope)  # noqa: S102 - the README's own example, whole
    assert len(scope) > 2


def test_a_block_that_continues_another_says_so_and_only_that_one() -> None:
    continuing = [b for b in PYTHON_BLOCKS if b.startswith(CONTINUES)]
    assert len(continuing) == 1 and "Filter(group=1)" in continuing[0]
    # Run alone, it would fail: it needs the world of the block above.
    with pytest.raises(NameError, match="world"):
        exec(continuing[0], {})  # noqa: S102


def test_the_contacts_example_meets_the_peg_the_ramp_and_the_floor(capsys) -> None:
    # Its on_contact(floor, ...) never fired (the Box's floor at the same height took every
    # bounce), and the ball never reached the ramp or the peg.
    scope: dict[str, object] = {}
    exec(block("ramp = world.add_collider"), scope)  # noqa: S102
    lines = capsys.readouterr().out.splitlines()
    names = [line.split()[0] for line in lines[:-1]]
    assert names[:3] == ["peg", "ramp", "floor"] and set(names[3:]) == {"floor"}
    assert len(names) > 10  # bounce after bounce
    # The peg first, when the ball's centre is 0.75 m from the peg's: a free fall from 8 m.
    drop = 8 - 5 - math.sqrt(0.75**2 - 0.3**2)
    assert lines[0] == f"peg {math.sqrt(2 * drop / 9.81):.3f} s"
    assert f"It prints the peg at {math.sqrt(2 * drop / 9.81):.3f} s" in " ".join(README.split())
    world, ball, floor = scope["world"], scope["ball"], scope["floor"]
    assert world.resting(ball) is floor  # type: ignore[attr-defined]
    hit = world.segment_query_first((ball.pos.x, 5), (ball.pos.x, -5))  # type: ignore[attr-defined]
    assert hit.shape is ball
    assert lines[-1] == f"{floor!r} {hit!r}"
    # Then the filter example, which goes on from it, adds its ball to the same world.
    exec(PYTHON_BLOCKS[PYTHON_BLOCKS.index(block("Filter(group=1)"))], scope)  # noqa: S102
    assert scope["ball"] in world.bodies  # type: ignore[attr-defined]
    assert scope["ball"].filter.group == 1  # type: ignore[attr-defined]


def test_the_shapes_example_stacks_its_crates_and_carries_its_rider(capsys) -> None:
    scope: dict[str, object] = {}
    exec(block("shape=Polygon.box(1, 1)"), scope)  # noqa: S102
    printed = capsys.readouterr().out.strip()
    assert f"It prints `{printed}`" in " ".join(README.split())
    world, crates = scope["world"], scope["crates"]
    heights = [c.pos.y for c in crates]  # type: ignore[attr-defined]
    # Stacked: each crate 1 m above the one below, within 1% of a crate's height, asleep.
    assert all(abs(h - (0.5 + k)) < 0.01 for k, h in enumerate(heights))
    assert all(world.is_sleeping(c) for c in crates)  # type: ignore[attr-defined]
    rider, lift = scope["rider"], scope["lift"]
    assert rider.pos.y - lift.pos.y == pytest.approx(0.35, abs=0.0035)  # type: ignore[attr-defined]


def test_the_readme_says_the_venv_before_its_first_bare_python_command() -> None:
    # The later sections wrote `python -m demos ...` without saying the venv must be active.
    first_bare = re.search(r"(?<![/\w])python -m demos", README)
    assert first_bare is not None
    note = README.index("<!-- venv-note -->")
    assert note < first_bare.start()
    said = " ".join(README[note:].split("\n\n")[0].split())  # the note's paragraph
    assert "virtual environment" in said and "source .venv/bin/activate" in said
    assert "write `.venv/bin/python`" in said


# -- numbers the README states about the demos' output: produced here from the code ----------


def _compact(x: float) -> str:
    """1.5e-05 -> 1.5e-5, as the README writes them."""
    return re.sub(
        r"e([+-])0*(\d)", lambda m: f"e{'-' if m.group(1) == '-' else ''}{m.group(2)}", f"{x:.1e}"
    )


def test_the_pendulum_periods_the_readme_states_are_the_codes() -> None:
    from test_pendulum import measured_period

    import demos.pendulum as pendulum
    from demos.bench.pendulum import period

    text = " ".join(README.split())
    errors = []
    for degrees in (5.0, 90.0, 170.0):
        th = math.radians(degrees)
        errors.append(_compact(measured_period(th)[0] / period(th) - 1))
    assert f"errs by {errors[0]}, {errors[1]} and {errors[2]} of 4 sqrt(L/g)" in text
    # The demo's own swing from 120 degrees, measured over its 10 s as its frame shows it.
    single = pendulum.Single()
    while single.t < pendulum.SingleScene.duration - 1e-9:
        single.step(pendulum.DT)
    measured, exact = single.measured_period(), period(pendulum.THETA0)
    assert measured is not None
    assert f"{_compact(measured / exact - 1)} at 120° in the demo" in text
    small = 2 * math.pi * math.sqrt(pendulum.LENGTH / pendulum.G)
    assert f"= {exact:.4f} s marked, against {small:.3f} s at small angles" in text


def test_the_hung_cradles_energy_and_passes_the_readme_states_are_the_codes() -> None:
    from demos.cradle import HUNG_DT, HungCradle, HungScene

    cradle = HungCradle()
    e0 = cradle.history[0].total
    leaders, worst = [], 0.0
    while cradle.t < HungScene.duration - 1e-9:
        cradle.step(HUNG_DT)
        v = cradle.sample().velocities
        worst = max(worst, abs(cradle.sample().total - e0))
        for end, rest in ((0, v[1:]), (4, v[:4])):
            if abs(v[end]) > 0.3 and all(abs(u) < 0.05 for u in rest):
                if not leaders or leaders[-1] != end:
                    leaders.append(end)  # this end ball alone moves: the blow has reached it
    passes = len(leaders) - 1  # from ball 1's first swing, each arrival at the other end
    words = {1: "once", 2: "twice", 3: "three times", 4: "four times"}[passes]
    text = " ".join(README.split())
    assert f"the blow passes back and forth, {words} in {HungScene.duration:g} s" in text
    assert worst < 7e-5 and f"(under 7e-5 J of {e0:.2f} J)" in text


def test_the_contacts_rows_say_how_and_when_they_were_measured() -> None:
    # The rows were stale (1 iteration: 0.66% and asleep, where a run gives 1.33% and awake)
    # and stated as facts; the pile solver is being reworked, so they are a dated measurement.
    section = README.split("**Choosing `contact_iterations`: the contacts chart.**")[1]
    section = section.split("### Links, and bodies the game moves")[0]
    head, table = section.split("| setting |")
    assert re.search(r"Measured with `python -m demos tradeoff` on \d{4}-\d\d-\d\d", head)
    rows = [r for r in table.splitlines() if r.startswith("| World")]
    assert len(rows) == 5
    asleep = [r.split("|")[1].split(",")[1].split()[0] for r in rows if ", asleep" in r]
    prose = " ".join(section.split())
    listed = ", ".join(asleep[:-1]) + f" and {asleep[-1]}"
    assert f"while {listed} brought it to rest and to sleep" in prose  # the prose reads its table
    assert "even one of them brings this pile to rest" not in prose


def test_the_readme_says_how_long_the_tradeoff_demo_takes() -> None:
    # The whole tradeoff demo took about 170 s and nothing said so before it started.
    from demos.tradeoff import TAKES

    text = " ".join(README.split())
    said = f"A whole run takes {TAKES[False]} on a 2-core machine (`--quick`: {TAKES[True]})"
    assert said in text


def test_the_rolling_example_prints_what_the_readme_says(capsys) -> None:
    scope: dict[str, object] = {}
    exec(block("slope = math.radians(30)"), scope)  # noqa: S102
    printed = capsys.readouterr().out.strip()
    assert f"It prints `{printed}`" in " ".join(README.split())
    # (2/3) g sin(30 degrees) t at t = 1 s, and the rim's speed equal to it: rolling.
    speed, rim, _ = printed.split()
    assert float(speed) == float(rim) == round(2 / 3 * 9.81 * 0.5, 6)


def test_the_torque_example_prints_what_the_readme_says(capsys) -> None:
    scope: dict[str, object] = {}
    exec(block("AngularDrag(0.5)"), scope)  # noqa: S102
    printed = capsys.readouterr().out.strip()
    assert f"It prints `{printed}`" in " ".join(README.split())
    # omega = (tau / c) (1 - e^(-c t / I)) at t = 1 s: tau = 1, c = 0.5, I = 0.25.
    spun, closed = printed.split()
    assert float(spun) == float(closed) == round(2 * (1 - math.exp(-2)), 9)
