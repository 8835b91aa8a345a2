"""The crates demo: bodies with shapes stack, get shoved and ride, and the frame shows them."""

from __future__ import annotations

import math

import pygame
import pytest

from demos.crates import CRATE, ELL_BAR, ELL_POST, LIFT_STOP, CratesScene, deepest_crate_overlap
from engine.render import iter_frames, marks
from engine.render.world_view import ASLEEP


@pytest.fixture(scope="module")
def scene() -> CratesScene:
    s = CratesScene()
    s.build((640, 360))
    for _ in range(round(4.0 / s.dt)):
        s.step(s.dt)
    return s


def test_the_crates_stand_in_columns_and_sleep(scene: CratesScene) -> None:
    crates = scene.bodies["crates"]
    left, right = crates[:4], crates[4:]
    # Each column stacked: a crate's centre one crate above the one below, to 1% of a crate.
    for column in (left, right):
        for k in range(1, len(column)):
            assert column[k].pos.y - column[k - 1].pos.y == pytest.approx(CRATE, abs=0.01)
    assert left[0].pos.y == pytest.approx(0.5 * CRATE, abs=0.01)
    # The ball shoved the left column's bottom crate along the floor, to the right.
    assert left[0].pos.x > 1.5 + 0.05
    # The plank lies across the right column: its centre a crate's half and its radius above.
    plank = scene.bodies["plank"][0]
    assert plank.pos.y == pytest.approx(right[-1].pos.y + 0.5 * CRATE + 0.1, abs=0.01)
    assert scene.deepest < 0.01 * CRATE and deepest_crate_overlap(crates) < 0.01 * CRATE
    assert all(scene.world.is_sleeping(b) for b in crates + [plank])


def test_the_l_tips_onto_its_hull_s_edge_and_sleeps(scene: CratesScene) -> None:
    # Stood on its bar's end, its centre of mass past its foot: it tips clockwise and rests on
    # the edge from the bar's tip to the post's top, at -(pi - atan(post / (bar - post's
    # width))) (measured 3.9e-6 rad off: it falls asleep as it settles), beside the right
    # column, which it leaves as it was.
    ell = scene.bodies["ell"][0]
    post, reach = ELL_POST[2][1] - ELL_POST[0][1], ELL_BAR[1][0] - ELL_POST[1][0]
    assert ell.angle == pytest.approx(-(math.pi - math.atan(post / reach)), abs=1e-5)
    assert scene.world.is_sleeping(ell)
    lowest = min(ell.local_to_world(v).y for part in ell.shapes for v in part.vertices)
    assert abs(lowest) < 0.005  # on the floor, within the soft contact's slop


def test_the_platform_lifts_its_crate_and_stops(scene: CratesScene) -> None:
    lift, rider = scene.bodies["lift"][0], scene.bodies["rider"][0]
    assert lift.pos.y == pytest.approx(0.1 + 0.5 * LIFT_STOP, abs=1e-9)
    assert lift.vel.y == 0.0
    assert rider.pos.y - lift.pos.y == pytest.approx(0.1 + 0.3, abs=0.005)


def test_the_frame_draws_the_sleeping_crates_in_grey(scene: CratesScene) -> None:
    surface = pygame.Surface((640, 360))
    scene.draw(surface, 1.0)
    for crate in scene.bodies["crates"]:
        x, y = scene.camera.point((crate.pos.x, crate.pos.y))
        assert tuple(surface.get_at((round(x), round(y))))[:3] == ASLEEP


@pytest.mark.parametrize("t", [0.0, 0.5])
def test_the_read_out_is_of_the_time_on_the_clock(t: float) -> None:
    """At t = 0 the frame read an overlap of 0.01%: the crates after a step, under a clock
    that said 0. A frame's read-out is now the one of a scene stepped to the clock's time
    (none at 0: the crates where they were put, apart)."""
    stepped = CratesScene()
    stepped.build((640, 360))
    for _ in range(round(t / stepped.dt)):
        stepped.step(stepped.dt)
    crates = stepped.bodies["crates"] + stepped.bodies["rider"]
    now, worst = deepest_crate_overlap(crates), stepped.deepest
    if t == 0.0:
        assert now == worst == 0.0
    else:
        assert worst > 1e-4 * CRATE  # they have landed by then: the check can tell
    k = round(30 * t)
    for _, _, surface in iter_frames(CratesScene(), 30, t + 0.1, (640, 360), only={k}):
        said = [m.text for m in marks.marks(surface)]
    assert f"t = {t:4.2f} s" in said
    line = next(text for text in said if "deepest overlap of crates" in text)
    now, worst = 100 * now / CRATE, 100 * worst / CRATE
    assert line.endswith(f"crates {now:.2f}% of a crate (worst so far {worst:.2f}%)"), line


def test_a_restored_scene_reads_out_its_own_moment() -> None:
    # The worst overlap so far was not in the snapshot: restored to 0.5 s after running to
    # 1 s, the frame read 1 s's worst under a clock at 0.5 s.
    s = CratesScene()
    s.build((640, 360))
    for _ in range(round(0.5 / s.dt)):
        s.step(s.dt)
    saved, before = s.snapshot(), (s.now, s.deepest, s.now_before, s.deepest_before)
    for _ in range(round(0.5 / s.dt)):
        s.step(s.dt)
    assert s.deepest > before[1]  # the worst grew after the snapshot: the check can tell
    s.restore(saved)
    assert (s.now, s.deepest, s.now_before, s.deepest_before) == before
