"""The platformer benchmark's scene (``demos.platformer_scene``) and pymunk's twin
(``demos.bench.platformer``): what the game does and what the table says, never how fast.

The scene's script runs its first 2 s on the numpy path (a jump onto the first ledge, two
coins): about 8 s of CPU time on the 2-core machine the project is built on.
"""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest

from demos import platformer_scene as scene
from demos.bench import platformer as bench
from demos.crates import deepest_crate_overlap
from engine import Body, Vector

PLAY = 2.0  # s of the script the numpy scene plays
SLACK = 0.02  # m: how far a corner may sink into the ground or a wall (the soft step's)
INNER = scene.WALLS[0][2]  # m: the walls' half thickness about their axes


def _corners(body: Body) -> np.ndarray:
    """A body's outline in the world (n, 2): a polygon's corners at its angle, or a disc's
    lowest, leftmost and rightmost points."""
    p = body.pos
    if body.shape is None:
        r = body.radius
        return np.array([(p.x, p.y - r), (p.x - r, p.y), (p.x + r, p.y)])
    c, s = math.cos(body.angle), math.sin(body.angle)
    v = np.array([(q.x, q.y) for q in body.shape.vertices])
    return np.stack([c * v[:, 0] - s * v[:, 1] + p.x, s * v[:, 0] + c * v[:, 1] + p.y], axis=1)


@pytest.fixture(scope="module")
def played() -> dict[str, object]:
    """The numpy scene after PLAY s of its script, with what each step showed: the lowest
    corner of any free body, the farthest any went past a wall's inner face, the deepest two
    boxes overlapped, and the ground test before each step."""
    game = scene.build("numpy")
    movers = [game.player, *game.crates, game.ball]
    lowest, outside, overlap, grounded = [], [], [], []
    for _ in range(round(PLAY / scene.DT)):
        grounded.append(game.on_ground())
        game.step(scene.DT)
        corners = np.concatenate([_corners(b) for b in movers])
        lowest.append(float(corners[:, 1].min()))
        left = INNER - float(corners[:, 0].min())
        right = float(corners[:, 0].max()) - (scene.WIDTH - INNER)
        outside.append(max(left, right))
        overlap.append(deepest_crate_overlap([game.player, *game.crates]))
    return {"game": game, "lowest": lowest, "outside": outside, "overlap": overlap,
            "grounded": grounded}  # fmt: skip


def test_nothing_passes_through_anything_while_the_script_plays(played) -> None:
    game = played["game"]
    assert game.world.kernels == "numpy"
    assert game.t == pytest.approx(PLAY)
    assert min(played["lowest"]) > -SLACK  # above the ground segment, every step
    assert max(played["outside"]) < SLACK  # inside the walls, every step
    assert max(played["overlap"]) < SLACK  # no box in another, nor in the ground
    # The player jumped onto the first ledge and stands on it: not through it.
    (a, b, r) = scene.LEDGES[0]
    assert a[0] < game.player.pos.x < b[0]
    assert game.player.pos.y == pytest.approx(a[1] + r + scene.PLAYER_SIZE[1] / 2, abs=SLACK)


def test_the_player_lands_after_a_jump(played) -> None:
    game, grounded = played["game"], played["grounded"]
    assert game.jumps == [0.5]  # the script's first press, on the ground
    jumped = round(0.5 / scene.DT)  # the step the jump was given in
    assert grounded[jumped]  # on the ground when it jumped
    assert not grounded[jumped + 1]  # then in the air
    assert len(game.landings) == 1 and 0.5 < game.landings[0] < PLAY
    landed = round(game.landings[0] / scene.DT)
    assert not any(grounded[jumped + 1 : landed]) and all(grounded[landed:])
    hit = game.ground_hit()
    assert hit is not None and hit.shape is game.ground[len(scene.WALLS) + 1]  # the ledge


def test_coins_collected_by_the_script_are_counted_once_each(played) -> None:
    game = played["game"]
    assert game.collected == [0, 1]  # the first on the run, the second over the ledge
    gone = [c for k, c in enumerate(game.coins) if k in game.collected]
    assert not any(c in game.world.colliders for c in gone)
    assert all(c in game.world.colliders for c in game.coins if c not in gone)


def test_a_coin_counts_once_however_long_the_player_stays_and_only_for_the_player() -> None:
    game = scene.build("numpy")
    coin = 4
    x, y = scene.COINS[coin]
    game.player.pos = Vector(x, y)  # put into the coin: its sensor reports him
    for _ in range(3):
        game.step(scene.DT)
    assert game.collected == [coin] and game.coins[coin] not in game.world.colliders
    game.player.pos = Vector(x, y)  # back where the coin was: it is gone
    game.step(scene.DT)
    game.crates[0].pos = Vector(*scene.COINS[3])  # a crate through another coin: not his
    game.step(scene.DT)
    assert game.collected == [coin]
    assert game.coins[3] in game.world.colliders


def test_the_pymunk_twin_has_the_same_layout() -> None:
    pytest.importorskip("pymunk")
    for hinge in (True, False):
        game, twin = scene.build("numpy", hinge=hinge), bench.PymunkPlatformer(hinge)
        world, space = game.world, twin.space
        planks = scene.BRIDGE_PLANKS
        assert len(world.bodies) == len(space.bodies) == len(twin.bodies) == 10 + planks
        # A body has one shape; the colliders are the static segments and the coins.
        assert len(world.bodies) + len(world.colliders) == len(space.shapes) == 21 + planks
        assert sum(c.sensor for c in world.colliders) == sum(s.sensor for s in space.shapes)
        assert sum(s.sensor for s in space.shapes) == len(scene.COINS)
        # The seesaw's hinge, and the bridge's: one at each end of each plank.
        assert len(world.links) == len(space.constraints) == int(hinge) + planks + 1
        for ours, theirs in zip(world.bodies, twin.bodies, strict=True):
            assert tuple(ours.pos) == tuple(theirs.position)
            assert ours.angle == theirs.angle
            assert ours.kinematic == (theirs.body_type == twin.pymunk.Body.KINEMATIC)
            if not ours.kinematic:
                assert ours.mass == theirs.mass
                assert ours.moment == pytest.approx(theirs.moment, rel=1e-12)
            (shape,) = theirs.shapes
            assert ours.friction == shape.friction
            assert ours.restitution == shape.elasticity
        statics = sorted(
            (tuple(s.a), tuple(s.b), s.radius) for s in space.shapes if hasattr(s, "a")
        )
        assert statics == sorted(scene.STATIC)
        assert [tuple(c.offset) for c in twin.coins] == list(scene.COINS)
        # The bridge's joints hold the same points of the same bodies, which do not collide.
        for ours, theirs in zip(game.bridge_hinges, twin.bridge_hinges, strict=True):
            assert not ours.collide and not theirs.collide_bodies
            for end, body, anchor in ((ours.end_a(), theirs.a, theirs.anchor_a),
                                      (ours.end_b(), theirs.b, theirs.anchor_b)):  # fmt: skip
                their_end = body.local_to_world(anchor)
                assert tuple(end) == pytest.approx(tuple(their_end), abs=1e-12)
        assert all(p.filter == scene.BRIDGE_FILTER for p in game.planks)
        assert all(s.filter.categories == scene.BRIDGE_BIT for p in twin.planks for s in p.shapes)
        assert game.on_ground() and twin.on_ground()  # both stand on the ground at t = 0


def test_the_pymunk_twin_plays_the_script_by_the_same_rules() -> None:
    pytest.importorskip("pymunk")
    twin = bench.PymunkPlatformer()
    lowest = math.inf
    for _ in range(round(scene.SECONDS / scene.DT)):
        twin.step(scene.DT)
        x, y = twin.player.position
        lowest = min(lowest, y - scene.PLAYER_SIZE[1] / 2)
        assert INNER < x < scene.WIDTH - INNER
    assert lowest > -0.05  # pymunk sinks by its slop (1 cm here), not through the ground
    assert twin.jumps[0] == pytest.approx(0.5) and len(twin.jumps) >= 3
    assert any(0.5 < t < 2.0 for t in twin.landings)  # it lands after its first jump
    counts = Counter(twin.collected)
    assert counts and max(counts.values()) == 1
    assert all(twin.coins[k] not in twin.space.shapes for k in twin.collected)


def _run(engine: str, median: float, share_over: float, **kw: object) -> bench.Run:
    """A Run of 100 steps whose engine's step has median ``median`` s by CPU time and of
    which ``share_over`` are longer than a frame (1.5 frames each); the game's whole step
    1 ms more; twice as long by the wall clock."""
    n_over = round(100 * share_over)
    cpu = np.array([median] * (100 - n_over) + [1.5 * bench.FRAME] * n_over)
    physics = np.stack([cpu, 2 * cpu], axis=1)
    return bench.Run(engine, (0.1, 0.2), (0.2, 0.4), physics, physics + 1e-3, [0, 1], **kw)  # type: ignore[arg-type]


def test_the_table_gives_each_engine_against_pymunks_median() -> None:
    runs = {
        "World (numpy)": _run("World (numpy)", 0.0135, 0.3),
        "World (fast)": _run("World (fast)", 0.0066, 0.0, compiled=22),
        "pymunk": _run("pymunk", 27e-6, 0.0),
        "World (numpy), no hinge": _run("World (numpy), no hinge", 0.0092, 0.0),
    }
    lines = bench.table(runs, 20.0, {"World": 2e-3, "pymunk": 2e-6})
    text = "\n".join(lines)
    engine, game, wall = [ln for ln in lines if ln.lstrip().startswith("World (numpy)")]
    assert "13.5 ms" in engine and "500x / 926x / 926x" in engine  # over pymunk's 27 us
    assert "30.0%" in engine and "2 of 5" in engine
    assert "14.5 ms" in game and "14x" in game  # 1 ms more each: 14.5 ms over 1.027 ms
    assert "28.0 ms" in wall and "27x" in wall  # 27 ms + 1 ms, over pymunk's 1.054 ms
    assert "100.0%" in wall  # every step over a frame
    assert "numba's cache was cold: it compiled 22 kernel(s) and loaded 0" in text
    assert "World (numpy) 1.47x" in text  # the hinge: 13.5 ms with it, 9.2 ms without
    assert "1000x" in text  # the ground test: 2 ms against 2 us
    assert not any(ln.lstrip().startswith("World (numpy), no hinge") for ln in lines)


def test_the_table_gives_each_soft_engine_alone_against_pymunk_alone() -> None:
    runs = {"pymunk": _run("pymunk", 27e-6, 0.0)}
    apart = {"soft (numpy)": 2.4e-3, "soft (fast)": 0.14e-3, "pymunk": 5e-6}
    line = [ln for ln in bench.table(runs, 5.0, {"World": 2e-3}, apart) if "alone" in ln]
    assert len(line) == 1
    assert "soft (numpy) 2.4 ms (480x)" in line[0]  # 2.4 ms over pymunk's 5 us alone
    assert "soft (fast) 0.140 ms (28x)" in line[0] and "pymunk 0.005 ms" in line[0]
    assert not any("alone" in ln for ln in bench.table(runs, 5.0, {"World": 2e-3}))


def test_a_short_run_alone_times_each_soft_engine() -> None:
    apart = bench.alone(3 * scene.DT, fast=False, pymunk=False)
    assert list(apart) == ["soft (numpy)"] and apart["soft (numpy)"] > 0.0


def test_a_short_side_by_side_run_times_every_step_of_every_engine() -> None:
    runs = bench.side_by_side(3 * scene.DT, fast=False, pymunk=False)
    assert list(runs) == [
        "World (numpy)",
        "soft (numpy)",
        "World (numpy), no hinge",
        "soft (numpy), no hinge",
    ]
    for r in runs.values():
        assert r.physics.shape == r.game.shape == r.ground.shape == (2, 2)
        assert (r.physics > 0).all() and (r.ground > 0).all()
        assert (r.game >= r.physics).all()  # the whole step holds the engine's
        assert min(r.first) > 0 and min(r.made) > 0
        assert 0.0 <= r.over_frame(bench.GAME, bench.WALL) <= 1.0


def test_the_table_gives_the_ground_test_in_play_against_pymunks() -> None:
    # Each engine's ground test made again after each step: the median by CPU time, over
    # pymunk's; engines whose runs did not time it (and the hinge's twins) are left out.
    ground = np.full((100, 2), 20e-6)
    runs = {
        "soft (fast)": _run("soft (fast)", 0.2e-3, 0.0, ground=ground),
        "soft (fast), no hinge": _run("soft (fast), no hinge", 0.2e-3, 0.0, ground=ground),
        "World (numpy)": _run("World (numpy)", 0.0135, 0.0),
        "pymunk": _run("pymunk", 27e-6, 0.0, ground=ground / 8),
    }
    line = [ln for ln in bench.table(runs, 5.0, {"World": 2e-3}) if "in play" in ln]
    assert len(line) == 1
    assert "soft (fast) 20.0 us (8x)" in line[0] and "pymunk 2.5 us" in line[0]
    assert "World (numpy)" not in line[0] and "no hinge" not in line[0]
