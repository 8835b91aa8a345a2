"""The pit, board and limits benchmarks: what they report and draw, never how fast.

No test here asserts a time (the machines are shared and noisy): they check the structure of
the reports and pictures, and physics that holds at any speed (what a run measures, the
targets judged from it, the board's ball meeting its pegs).
"""

from __future__ import annotations

import contextlib
import io
import math
from pathlib import Path

import numpy as np
import pygame
import pytest

from demos.bench import board, limits, pit
from demos.bench.__main__ import main
from engine import Circle
from engine.render import marks

pymunk = pytest.importorskip("pymunk")


@pytest.fixture(scope="module")
def small_pit() -> dict[str, pit.Run]:
    # 200 balls (six rows) for 1.5 s, two rounds: the same code path as the 1,000-ball run.
    return pit.first_seconds(200, 1.5, rounds=2)


def test_both_engines_run_the_same_drop_side_by_side(small_pit: dict[str, pit.Run]) -> None:
    from engine import kernels

    assert list(small_pit) == ["World"] + (["fast"] if kernels.available() else []) + ["pymunk"]
    steps = round(1.5 / pit.DT)
    for run in small_pit.values():
        assert run.balls == 200
        assert len(run.rounds) == 2 and all(t > 0 for t in run.rounds)
        assert run.wall > 0 and run.cpu > 0
        assert len(run.t) == len(run.overlap) == len(run.kinetic) == steps
        assert run.t[0] == pytest.approx(pit.DT) and run.t[-1] == pytest.approx(1.5)
        assert np.all(run.overlap >= 0) and np.all(np.isfinite(run.kinetic))
        assert run.outside == 0
        # Both drop from rest: the first step's energy is the same free fall for each.
        v = 9.81 * pit.DT
        assert run.kinetic[0] == pytest.approx(200 * 0.5 * v * v, rel=1e-6)
    world, space = small_pit["World"], small_pit["pymunk"]
    assert world.closest == pytest.approx(2.0 - world.deepest)
    assert world.deepest == world.overlap.max() and world.final == world.overlap[-1]
    ratio = pit.ratio(small_pit)
    assert ratio is not None and ratio > 0
    assert space.asleep == 0  # pymunk's sleep is off


def test_the_world_lands_six_rows_shallowly(small_pit: dict[str, pit.Run]) -> None:
    # Physics, not speed: six rows land within 5% of r (the grid's jitter starts neighbours up
    # to 4% deep; the first step pushes them apart) and come to rest within 1%.
    world = small_pit["World"]
    assert world.deepest < 0.05
    assert world.final < 0.01


def _run(n: int, deepest: float, final: float, asleep: int, wall: float) -> pit.Run:
    t = np.array([1.0, 2.0])
    return pit.Run(
        "World", n, wall, wall, [wall], t, np.array([deepest, final]), np.ones(2), asleep, 0, 0.0
    )


def test_the_targets_are_judged_from_the_numbers() -> None:
    ok = {
        "World": _run(1_000, 0.05, 0.005, 1_000, 2.0),
        "pymunk": _run(1_000, 0.2, 0.2, 0, 1.0),
    }
    ok["pymunk"].engine = "pymunk"
    text = "\n".join(pit.summary(ok))
    assert "World / pymunk: 2.00x wall" in text and "(target <= 3x: met)" in text
    assert "deepest overlap <= 10% of r: met" in text
    assert "at 5 s <= 1%: met" in text and "asleep at 5 s: met" in text
    bad = {
        "World": _run(10_000, 1.2, 0.3, 0, 4.0),
        "pymunk": _run(10_000, 1.9, 1.9, 0, 1.0),
    }
    bad["pymunk"].engine = "pymunk"
    text = "\n".join(pit.summary(bad))
    assert "4.00x wall" in text and "(target <= 3x: NOT met)" in text
    assert "deepest overlap <= 20% of r: NOT met" in text
    assert "no centres closer than r: NOT met" in text  # 120% of r deep: 0.8 r apart
    assert "asleep" not in text.split("targets:")[1]  # no sleep target at 10,000


def test_the_picture_shows_both_engines_in_both_panels(
    small_pit: dict[str, pit.Run], tmp_path: Path
) -> None:
    from engine.render import save_png

    surface = pit.draw_pit(small_pit)
    assert marks.problems(surface) == []
    path = save_png(surface, tmp_path / "pit.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pixels = pygame.surfarray.array3d(pygame.image.load(str(path)))  # (x, y, 3)
    width, height = surface.get_size()
    panels = (pixels[: width // 2, 70:610], pixels[width // 2 :, 70:610])
    for panel in panels:
        for color in pit.ENGINE_COLORS.values():
            assert np.all(panel == color, axis=2).sum() > 50, color


def test_the_bench_command_writes_the_pits_picture(tmp_path: Path) -> None:
    text = io.StringIO()
    with contextlib.redirect_stdout(text):
        assert main(["pit", "--quick", "--out", str(tmp_path)]) == 0
    out = text.getvalue()
    assert "1,000 balls, the first 5 s from the drop:" in out
    assert "World / pymunk:" in out and "targets:" in out
    png = tmp_path / "pit_1000.png"
    assert str(png) in out and png.read_bytes()[:4] == b"\x89PNG"


def test_the_small_board_is_82_pegs_and_6_segments_and_its_ball_meets_them() -> None:
    world, ball = board.make_board()
    pegs = [c for c in world.colliders if isinstance(c, Circle)]
    assert len(pegs) == 82 and len(world.colliders) == 88
    met = set()
    for _ in range(120):
        world.step(board.DT)
        met |= {id(e.collider) for e in world.began if e.body is ball}
    assert len(met & {id(p) for p in pegs}) >= 3  # it bounces down through the pegs
    bare, _ = board.make_board(colliders=False)
    assert bare.colliders == ()


def test_the_board_measurements_have_their_parts() -> None:
    small = board.small_board(seconds=0.2, rounds=1)
    assert set(small) == {"board", "bare", "ratio", "typical"}
    assert small["ratio"] == pytest.approx(small["board"] / small["bare"])
    got = board.changes(48, cycles=2)
    assert set(got) == {"plain", *board.CHANGES}
    assert all(call >= 0 and step > 0 and own > 0 for call, step, own in got.values())
    assert got["plain"][1] == got["plain"][2]


def test_the_limits_table_reads_its_runs() -> None:
    results = limits.measure(quick=True)
    assert [r.label for r in results] == [s.label for s in limits.QUICK]
    for r in results:
        assert 0.0 <= r.final <= r.deepest  # the end is one of the steps
        assert 0.0 < r.deepest_at <= r.seconds
    text = limits.table(results)
    for s in limits.QUICK:
        assert s.label in text
    # The 200-ball pit comes to rest within 1% of r and sleeps within its 5 s.
    small_pit = results[-1]
    assert small_pit.final < 0.01 and math.isfinite(small_pit.asleep_at)
    assert small_pit.seconds == pytest.approx(small_pit.asleep_at)
