"""The platformer game: the autopilot's run takes every coin, crosses the rope bridge (which
holds it and gives under it), rides the moving platform without slipping, the run ends alike
on the numpy and the fast path, the one-way ledge and the conveyor, the keys, and the picture
by its pixels.

The scene's step is slow (about 19 ms on numpy): the autopilot's run is played once per path
(a module-scoped fixture), only as long as it takes to collect every coin and ride the
platform 2 s."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import pygame
import pytest
from paths import FAST, PATHS

import demos.platformer as pf
from demos import platformer_scene as ps
from demos.cli import main
from engine import Vector
from engine.render import init_headless

#: The ride measured: from this long after the player lands on the platform, for RIDE s.
SETTLE, RIDE = 0.3, 2.0
#: The numpy and the fast path end this close (m, rad): the same run, to round-off (they end
#: bit for bit alike today; 1e-9 leaves room for a sum taken in another order).
PATHS_AGREE = 1e-9


class OnBridge(NamedTuple):
    """A step that ended with the player standing on the rope bridge."""

    t: float  # s
    x: float  # m: the player's centre
    feet: float  # m: the height of its soles
    plank: int  # the plank the ground test found under it
    give: float  # m: the farthest apart the two ends of any of the bridge's hinges were
    clearance: float  # m: its soles above the highest point of the deck under them


@dataclass
class Run:
    """What the autopilot's run did, read from the World step by step."""

    game: pf.PlatformerGame
    taken: dict[int, float] = field(default_factory=dict)  # coin -> when the player met it
    touches: int = 0  # contacts of the player with a coin that began, all told
    landed: float | None = None  # when the player first stood on the platform
    ride: list[tuple[float, float, bool]] = field(default_factory=list)  # (t, x - xp, on it)
    bridge: list[OnBridge] = field(default_factory=list)


def deck_top(game: pf.PlatformerGame, low: float, high: float) -> float:
    """The highest point (m) of the bridge's deck, its planks' tops, between x = low and
    x = high; -inf where no plank is."""
    length, thickness = ps.BRIDGE_PLANK
    top = -math.inf
    for plank in game.level.planks:
        a = plank.local_to_world(Vector(-length / 2, thickness / 2))
        b = plank.local_to_world(Vector(length / 2, thickness / 2))
        lo, hi = max(low, min(a.x, b.x)), min(high, max(a.x, b.x))
        for x in (lo, hi) if lo <= hi else ():  # a straight edge: highest at an end
            top = max(top, a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x))
    return top


def hinge_give(game: pf.PlatformerGame) -> float:
    """The farthest apart (m) the two ends of any of the bridge's hinges are now."""
    return max(abs(h.end_a() - h.end_b()) for h in game.level.bridge_hinges)


def on_bridge(game: pf.PlatformerGame) -> OnBridge | None:
    """The step's record if the player stands on a plank of the bridge, else None."""
    hit = game.ground()
    planks = game.level.planks
    if hit is None or not any(hit.shape is p for p in planks):
        return None
    hero = game.level.player
    w, h = ps.PLAYER_SIZE
    feet = hero.pos.y - h / 2
    plank = next(k for k, p in enumerate(planks) if p is hit.shape)
    deck = deck_top(game, hero.pos.x - w / 2, hero.pos.x + w / 2)
    return OnBridge(game.t, hero.pos.x, feet, plank, hinge_give(game), feet - deck)


@functools.cache
def _play(kernels: str) -> Run:
    """The autopilot's run on the path ``kernels``, played once per test session."""
    game = pf.PlatformerGame(kernels)
    run = Run(game)
    level = game.level
    while game.t < pf.MAX_SECONDS:
        game.step(pf.DT)
        for event in game.world.began:  # the World's own report, not the game's count
            if event.body is level.player and event.collider in level.coins:
                run.touches += 1
                run.taken.setdefault(level.coins.index(event.collider), game.t)
        crossing = on_bridge(game)
        if crossing is not None:
            run.bridge.append(crossing)
        on = game.on_platform()
        if on and run.landed is None:
            run.landed = game.t
        if run.landed is not None:
            run.ride.append((game.t, level.player.pos.x - level.platform.pos.x, on))
            if game.score.over and game.t >= run.landed + SETTLE + RIDE + 2 * pf.DT:
                break
    return run


@pytest.fixture(scope="module", params=PATHS)
def played(request: pytest.FixtureRequest) -> Run:
    """The autopilot's run on one path, to every coin and 2 s on the platform."""
    return _play(request.param)


def test_the_autopilot_takes_every_coin(played: Run) -> None:
    game = played.game
    score = game.score
    assert score.over and sorted(score.coins) == list(range(len(ps.COINS)))
    assert score.points == pf.COIN_POINTS * len(ps.COINS)
    # The game counted each coin in the order the World reported the player meeting it; a
    # coin taken senses nothing more (it never reported the player again).
    assert list(played.taken) == score.coins
    assert played.touches == len(ps.COINS)
    assert all(coin.filter == pf.TAKEN for coin in game.level.coins)
    # The last coin is the one over the platform's far end, taken riding the platform.
    last = max(played.taken, key=played.taken.__getitem__)
    assert ps.COINS[last] == max(ps.COINS)
    assert played.landed is not None and played.taken[last] > played.landed


def test_the_player_rides_the_platform_without_slipping(played: Run) -> None:
    assert played.landed is not None
    start = min(t for t, _, _ in played.ride if t >= played.landed + SETTLE)
    window = [(t, dx, on) for t, dx, on in played.ride if start <= t <= start + RIDE + 1e-9]
    assert window[-1][0] - window[0][0] >= RIDE - 1e-9
    assert all(on for _, _, on in window)  # standing on it throughout
    offsets = np.array([dx for _, dx, _ in window])
    assert offsets.max() - offsets.min() <= 1e-3  # the bound: 1 mm over 2 s
    # The platform turned at its right end within the window: the feet kept it through that.
    speeds = {ps.platform_velocity(t) for t, _, _ in window}
    assert speeds == {ps.PLATFORM_SPEED, -ps.PLATFORM_SPEED}


def test_the_player_crosses_the_rope_bridge_which_holds_it(played: Run) -> None:
    bridge = played.bridge
    (x0, ends), (x1, _) = ps.BRIDGE_ENDS
    half = ps.PLAYER_SIZE[0] / 2
    # It stepped onto the first plank from the ledge and walked the planks in their order to
    # the last, from one end of the span to the other.
    firsts = [min((r.t for r in bridge if r.plank == k), default=math.inf)
              for k in range(ps.BRIDGE_PLANKS)]  # fmt: skip
    assert firsts == sorted(firsts) and firsts[-1] < math.inf
    assert min(r.x for r in bridge) < x0 + half and max(r.x for r in bridge) > x1 - half
    # The third coin hangs over the bridge, out of reach from the floor under it: the player
    # took it standing on the planks.
    x, y = ps.COINS[2]
    assert x0 < x < x1 and y - ps.COIN_RADIUS > ps.PLAYER_SIZE[1]
    assert bridge[0].t <= played.taken[2] <= bridge[-1].t
    # It walked down into the bridge's sag (0.32 m at the middle, as built) and up out of it.
    assert min(r.feet for r in bridge) < ends - 0.25
    # The bridge held: every hinge's two ends within 1 cm all the while (the soft step's
    # joints give; 5.0 mm at most, measured), and no plank came up through the player's
    # soles by more than its contacts give (7.9 mm measured, walking up a plank at 2 m/s).
    assert max(r.give for r in bridge) < 0.01
    assert min(r.clearance for r in bridge) > -0.015


def test_the_bridge_gives_under_the_player_standing_at_its_middle() -> None:
    game = pf.PlatformerGame(player=_still)
    for _ in range(60):  # the bridge comes to rest from its shape as built
        game.step(pf.DT)
    middle = ps.BRIDGE_PLANKS // 2  # the hinge at the middle of the span
    rest = game.level.bridge_hinges[middle].end_a()
    hero = game.level.player
    w, h = ps.PLAYER_SIZE
    hero.pos = Vector(rest.x, deck_top(game, rest.x - w / 2, rest.x + w / 2) + h / 2 + 0.005)
    hero.vel = Vector(0.0, 0.0)
    heights, records = [], []
    for _ in range(180):
        game.step(pf.DT)
        heights.append(game.level.bridge_hinges[middle].end_a().y)
        records.append(on_bridge(game))
    assert all(r is not None for r in records)  # it stood on the planks throughout
    held = [r for r in records if r is not None]
    # The deck under it went down, into a V: by at most what the deck's length allows, the
    # V's depth sqrt((L/2)^2 - (S/2)^2) below the ends less the depth it hung at, plus what
    # the joints give.
    (x0, ends), (x1, _) = ps.BRIDGE_ENDS
    length, span = ps.BRIDGE_PLANKS * ps.BRIDGE_PLANK[0], x1 - x0
    most = math.sqrt((length / 2) ** 2 - (span / 2) ** 2) - (ends - rest.y)
    drop = rest.y - float(np.mean(heights[-60:]))  # over the last second: it sways
    assert 0.005 < drop < most + 0.005  # 7.9 mm, measured, of at most 3.9 cm
    # It held: its hinges within 3 mm (1.8 mm measured), the player on the planks, not in
    # them (1 mm as it lands from 5 mm up), where it was put.
    assert max(r.give for r in held) < 0.003
    assert min(r.clearance for r in held) > -0.002
    assert abs(hero.pos.x - rest.x) < 0.01


def _state(game: pf.PlatformerGame) -> np.ndarray:
    level = game.level
    bodies = [level.player, *level.crates, level.seesaw, level.platform, level.ball, *level.planks]
    return np.array([[b.pos.x, b.pos.y, b.angle] for b in bodies])


@FAST
def test_the_run_ends_alike_on_both_paths() -> None:
    numpy, fast = _play("numpy"), _play("fast")
    assert numpy.game.t == fast.game.t
    assert numpy.game.score == fast.game.score
    assert list(numpy.taken) == list(fast.taken)
    assert numpy.taken == pytest.approx(fast.taken, abs=1e-9)
    assert numpy.landed == fast.landed
    assert np.abs(_state(numpy.game) - _state(fast.game)).max() <= PATHS_AGREE


def _still(game: pf.PlatformerGame) -> pf.Controls:
    return pf.Controls()


def test_the_player_jumps_up_through_the_one_way_ledge_and_lands_on_it() -> None:
    game = pf.PlatformerGame(player=_still)
    hero = game.level.player
    (x0, y0), (x1, _), r = pf.ONE_WAY
    # Under the ledge's middle, its head 0.2 m below it, going up at the jump's speed: its
    # feet rise to y0 - r - 0.2 - h + v^2 / 2g = 4.97 m, over the ledge's top (4.1 m).
    h = ps.PLAYER_SIZE[1]
    hero.pos = Vector((x0 + x1) / 2, y0 - r - 0.2 - h / 2)
    hero.vel = Vector(0.0, ps.JUMP_SPEED)
    low = hero.pos.y
    for _ in range(90):
        game.step(pf.DT)
    # Resting on its top: the game's soft contacts give by hundredths of a millimetre under
    # the player's weight (Box2D's may by its linear slop, 5 mm).
    assert hero.pos.y == pytest.approx(y0 + r + h / 2, abs=1e-4)
    assert hero.pos.y > low + 1.0 and hero.vel.length() < 1e-6
    assert game.ground() is not None and game.ground().shape is game.ledge  # type: ignore[union-attr]


def test_the_conveyor_carries_a_player_standing_on_it_at_its_speed() -> None:
    game = pf.PlatformerGame(player=_still)
    hero = game.level.player
    (xa, ya), (xb, _), r = ps.LEDGES[1]
    hero.pos = Vector(xb - 0.6, ya + r + ps.PLAYER_SIZE[1] / 2)
    hero.vel = Vector(0.0, 0.0)
    game.step(pf.DT)
    xs = []
    for _ in range(20):
        game.step(pf.DT)
        xs.append(hero.pos.x)
    # Standing still on it, the player moves with the belt's surface: -BELT_SPEED dt a step.
    assert np.diff(xs) == pytest.approx(-pf.BELT_SPEED * pf.DT, abs=1e-12)


def test_keys_run_and_jump(monkeypatch) -> None:
    init_headless()
    scene = pf.PlatformerScene(person=True)
    scene.build((640, 360))
    game = scene.game
    assert isinstance(game.player, pf.Person)
    held = {pygame.K_RIGHT}
    monkeypatch.setattr(pygame.key, "get_pressed", lambda: type("K", (), {
        "__getitem__": lambda self, k: k in held})())  # fmt: skip
    hero = game.level.player
    for _ in range(15):  # 0.25 s: up to full speed at RUN_ACCEL
        game.step(pf.DT)
    assert hero.vel.x == pytest.approx(ps.RUN_SPEED)
    held.add(pygame.K_SPACE)
    game.step(pf.DT)
    assert game.level.jumps and hero.vel.y > 0.5 * ps.JUMP_SPEED
    vy = hero.vel.y
    game.step(pf.DT)  # held: no second jump
    assert hero.vel.y < vy and len(game.level.jumps) == 1


def test_the_picture_shows_the_player_the_coins_and_the_score() -> None:
    init_headless()
    scene = pf.PlatformerScene()
    size = (640, 360)
    scene.build(size)
    game, camera = scene.game, scene.camera
    surface = pygame.Surface(size)

    def pixel(where: tuple[float, float]) -> tuple[int, int, int]:
        return tuple(surface.get_at(camera.point(where)))[:3]  # type: ignore[return-value]

    scene.draw(surface, 1.0)
    hero = game.level.player.pos
    w, h = ps.PLAYER_SIZE
    assert pixel((hero.x - w / 4, hero.y - h / 4)) == pf.PLAYER_COLOUR
    assert pixel((hero.x - w * 0.7, hero.y)) != pf.PLAYER_COLOUR
    for coin in ps.COINS:
        assert pixel(coin) == pf.COIN_COLOUR
    crate = game.level.crates[0].pos
    assert pixel((crate.x - 0.25, crate.y - 0.25)) == pf.CRATE_COLOUR
    for plank in game.level.planks:  # the bridge, each plank (2.5 px thick, outlined)
        along = [plank.local_to_world(Vector(d, 0.0)) for d in (-0.1, 0.0, 0.1)]
        assert any(pixel((p.x, p.y)) == pf.PLANK_COLOUR for p in along)
    top = pygame.surfarray.array3d(surface)[:, :36]
    assert np.all(top == pf.INK, axis=2).any()
    # A coin taken is drawn no more: the sky's colour where it was.
    game.level.collected.append(0)
    scene.draw(surface, 1.0)
    assert pixel(ps.COINS[0]) == pf.SKY
    assert pixel(ps.COINS[1]) == pf.COIN_COLOUR


def test_command_line_runs_headless(tmp_path, capsys) -> None:
    out = tmp_path / "game"
    assert main(["platformer", "--seconds", "0.4", "--fps", "5", "--out", str(out)]) == 0
    assert len(list(out.glob("frame_*.png"))) == 2
    assert "0/5 coins" in capsys.readouterr().out


def test_a_game_saved_before_a_coin_resumes_exactly() -> None:
    game = pf.PlatformerGame()
    for _ in range(18):  # t = 0.3 s: the first coin is taken at 0.45 s
        game.step(pf.DT)
    saved = game.snapshot()
    for _ in range(18):
        game.step(pf.DT)
    first, coins = _state(game), list(game.score.coins)
    assert coins == [0]
    game.restore(saved)
    assert game.score.coins == [] and game.level.coins[0].filter != pf.TAKEN
    for _ in range(18):
        game.step(pf.DT)
    assert game.score.coins == coins
    assert np.array_equal(_state(game), first)
