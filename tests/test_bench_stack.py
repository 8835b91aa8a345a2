"""The stack benchmark: the same pyramid in both engines, and what a run reports, never how fast.

No test here asserts a time (the machines are shared and noisy): they check that the bench's
two pyramids are the same scene, the structure of the report and picture, and the targets
judged from given numbers.
"""

from __future__ import annotations

import contextlib
import io
import math
from pathlib import Path

import numpy as np
import pygame
import pytest

from demos import stack as scene
from demos.bench import pit, stack
from demos.bench.__main__ import main
from engine import kernels
from engine.render import marks

pymunk = pytest.importorskip("pymunk")

ENGINES = ["World"] + (["fast"] if kernels.available() else []) + ["pymunk"]


def _pair(base: int, sleep: bool = True) -> tuple[object, list, object, list]:
    world, boxes = stack.make_world(base, sleep=sleep)
    made = stack.make_space(base, sleep=sleep)
    assert made is not None
    return world, boxes, *made


@pytest.mark.parametrize("base", [4, 20, 40])
def test_both_engines_put_down_the_same_pyramid(base: int) -> None:
    world, boxes, space, bodies = _pair(base)
    n = base * (base + 1) // 2
    assert len(boxes) == len(bodies) == len(space.bodies) == n  # type: ignore[attr-defined]
    ours = world.positions()  # type: ignore[attr-defined]
    theirs = np.array([tuple(b.position) for b in bodies])
    assert np.array_equal(ours, theirs)
    assert np.array_equal(ours, np.array(scene.pyramid_centres(base)))
    # Touching and centred: rows 1 m apart from y = 0.5, the bottom row from -(base-1)/2.
    assert ours[:base, 1].tolist() == [0.5] * base and ours[0, 0] == -(base - 1) / 2
    assert ours[-1].tolist() == [0.0, base - 0.5]


def test_the_boxes_have_the_same_size_mass_moment_and_materials() -> None:
    world, boxes, space, bodies = _pair(4)
    assert space.iterations == stack.ITERATIONS == 10  # type: ignore[attr-defined]
    assert tuple(space.gravity) == (0.0, -9.81)  # type: ignore[attr-defined]
    assert stack.scene.G == 9.81
    for box, body in zip(boxes, bodies, strict=True):
        (shape,) = body.shapes
        corners = sorted((round(v.x, 12), round(v.y, 12)) for v in shape.get_vertices())
        ours = sorted(tuple(round(c, 12) for c in tuple(v)) for v in box.shape.vertices)
        assert ours == corners == [(-0.5, -0.5), (-0.5, 0.5), (0.5, -0.5), (0.5, 0.5)]
        assert box.mass == body.mass == 1.0
        assert box.moment == pytest.approx(body.moment, rel=1e-12)
        assert box.moment == pytest.approx(1.0 / 6.0, rel=1e-12)  # m (w^2 + h^2) / 12
        assert box.friction == shape.friction == 0.6
        assert box.restitution == shape.elasticity == 0.0
    (floor,) = space.static_body.shapes  # type: ignore[attr-defined]
    assert floor.friction == scene.FLOOR_FRICTION == world.colliders[0].friction  # type: ignore[attr-defined]
    assert floor.a.y == floor.b.y == 0.0 and floor.radius == 0.0


def test_sleeping_is_on_or_off_in_both_alike() -> None:
    world, _, space, _ = _pair(4, sleep=True)
    assert world.sleep_time == space.sleep_time_threshold == stack.SLEEP_TIME  # type: ignore[attr-defined]
    world, _, space, _ = _pair(4, sleep=False)
    assert world.sleep_time == space.sleep_time_threshold == math.inf  # type: ignore[attr-defined]


@pytest.fixture(scope="module")
def short() -> tuple[dict[str, stack.Run], dict[str, stack.Run]]:
    # Ten boxes for 0.25 s (15 steps), the first 0.1 s timed in two rounds: the full run's path.
    on = stack.side_by_side(4, 0.25, sleep=True, rounds=2, first=0.1)
    off = stack.side_by_side(4, 0.25, sleep=False, rounds=1, first=0.1)
    return on, off


def test_a_short_run_gives_each_engine_its_fields(
    short: tuple[dict[str, stack.Run], dict[str, stack.Run]],
) -> None:
    on, off = short
    for runs, rounds, sleep in ((on, 2, True), (off, 1, False)):
        assert list(runs) == ENGINES
        for run in runs.values():
            assert run.base == 4 and run.boxes == 10 and run.sleep is sleep
            assert len(run.steps) == len(run.moved) == 15 == len(run.t)
            assert run.seconds == pytest.approx(0.25) and run.first == pytest.approx(0.1)
            assert len(run.firsts) == rounds and all(f > 0 for f in run.firsts)
            assert np.all(run.steps > 0) and run.mean_step == pytest.approx(run.steps.mean())
            assert np.all(np.isfinite(run.moved)) and np.all(run.moved >= 0)
            assert run.moved_at(0.25) == run.moved[-1] and run.moved_at(0.1) == run.moved[5]
            k, dx, dy, angle = run.worst
            assert 0 <= k < 10 and math.hypot(dx, dy) == pytest.approx(run.moved[-1])
            assert math.isfinite(angle)
            if not sleep:
                assert math.isnan(run.asleep_at)
    # Nothing moves far in a quarter of a second: the boxes were put down touching.
    assert max(r.moved.max() for r in (*on.values(), *off.values())) < 0.05


def test_rows_count_from_the_floor() -> None:
    run = stack.Run("World", 4, True, 0.1, np.ones(1), np.zeros(1), [1.0], (0, 0, 0, 0))
    assert [run.row(k) for k in range(10)] == [0, 0, 0, 0, 1, 1, 1, 2, 2, 3]


def test_the_summary_reads_both_settings(
    short: tuple[dict[str, stack.Run], dict[str, stack.Run]],
) -> None:
    text = "\n".join(stack.summary(*short))
    assert "10 boxes (a base of 4), the first 0.25 s" in text
    assert "sleeping on" in text and "sleeping off" in text
    assert text.count("World / pymunk") == 2 and text.count("moved at 0.25 s") == 2
    assert "World first 0.1 s <= 3x pymunk:" in text
    assert "moved <=" not in text  # no drift target for a base of 4


def _run(engine: str, moved: float, asleep_at: float, first: float, sleep: bool) -> stack.Run:
    steps = round(60.0 / stack.DT)
    return stack.Run(
        engine, 20, sleep, 2.0, np.full(steps, first), np.full(steps, moved), [first],
        (0, moved, 0.0, 0.0), asleep_at,
    )  # fmt: skip


def test_the_targets_are_judged_from_the_numbers() -> None:
    def runs(moved: float, asleep_at: float, first: float, sleep: bool) -> dict[str, stack.Run]:
        return {
            "World": _run("World", moved, asleep_at, first, sleep),
            "pymunk": _run("pymunk", 0.047, 1.5, 1e-3, sleep),
        }

    on, off = runs(0.005, 0.8, 2e-3, True), runs(0.007, math.nan, 2e-3, False)
    good = "\n".join(stack.summary(on, off))
    assert "moved <= 10.00 mm by 60 s: met (sleeping off, the worse path: 7.00 mm" in good
    assert "asleep within 2 s: met" in good and "World first 2 s <= 3x pymunk: met" in good
    on, off = runs(0.005, 2.5, 4e-3, True), runs(0.012, math.nan, 4e-3, False)
    bad = "\n".join(stack.summary(on, off))
    assert "moved <= 10.00 mm by 60 s: NOT met" in bad
    assert "asleep within 2 s: NOT met" in bad and "World first 2 s <= 3x pymunk: NOT met" in bad
    assert "pymunk (10 iterations) 0.331 ms, 47.00 mm" in bad  # the peers, quoted


def test_the_picture_shows_both_engines_in_both_panels(
    short: tuple[dict[str, stack.Run], dict[str, stack.Run]], tmp_path: Path
) -> None:
    from engine.render import save_png

    surface = stack.draw_stack(*short)
    assert marks.problems(surface) == []
    path = save_png(surface, tmp_path / "stack.png")
    pixels = pygame.surfarray.array3d(pygame.image.load(str(path)))  # (x, y, 3)
    width = surface.get_size()[0]
    for panel in (pixels[: width // 2, 70:560], pixels[width // 2 :, 70:560]):
        for name in ENGINES:
            color = pit.ENGINE_COLORS[name]
            assert np.all(panel == color, axis=2).sum() > 20, name


def test_the_bench_command_runs_the_stack_topic(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(stack.SIZES, True, ((4, 0.2, 1),))
    text = io.StringIO()
    with contextlib.redirect_stdout(text):
        assert main(["stack", "--quick", "--out", str(tmp_path)]) == 0
    out = text.getvalue()
    assert "10 boxes (a base of 4)" in out and "World / pymunk" in out
    png = tmp_path / "stack_10.png"
    assert str(png) in out and png.read_bytes()[:4] == b"\x89PNG"
