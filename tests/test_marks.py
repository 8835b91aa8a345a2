"""Every demo and scene, run briefly, checked by what its frames hold (engine.render.marks):
no label on another label or on a marker, no label or arrowhead cut at the frame's edge or
leaving its panel. The next demo cannot regress unseen.

Each scene is stepped through (up to ``LONGEST`` s of its time) and drawn at a few frames, at
the default 640x360 and at 480x270 (the README's size for a GIF): the first three, some spread
over the run, the last; its motion diagram too, if it has one. The tradeoff demo's charts are
drawn from made-up rows of every kind (measuring takes minutes).

The allow-list, where overlap is the point: empty. A label that overlaps in a new demo is
added here only with the reason beside it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import pygame
import pytest

import demos.breakout as breakout
import demos.crumb as crumb
from demos.bench import pendulum, solver, throughput
from demos.cli import Demo, discover
from demos.tradeoff import draw_contacts, draw_throughput, draw_work_precision
from engine.measure import Point
from engine.render import frame_count, init_headless, iter_frames, marks
from engine.render.recorder import draw_strobe

#: The most simulated seconds a scene is stepped through here.
LONGEST = 12.0
#: Frames drawn spread over the run, besides the first three and the last.
SPREAD = 6
#: (demo, scene) -> the seconds checked where a scene's whole layout shows sooner than LONGEST
#: and its steps are slow: the tumbler's drum (500 boxes) turns once in 4 s, every phase of
#: its frame, read-outs and pile shown.
SHORTER: dict[tuple[str, str], float] = {("stack", "tumbler"): 4.0}
#: (demo, scene) -> words that may overlap in it, and why. Where overlap is the point only.
ALLOWED: dict[tuple[str, str], tuple[str, ...]] = {}


def _scenes() -> list[tuple[str, str, Callable[[], Any]]]:
    found = []
    for name, demo in discover().items():
        assert isinstance(demo, Demo), name  # every demo imports
        for scene, factory in demo.scenes.items():
            found.append((name, scene, factory))
    # The games are scenes too, driven by their own run hooks.
    found += [("breakout", "game", breakout.BreakoutScene), ("crumb", "game", crumb.CrumbScene)]
    return found


SCENES = _scenes()


def _ids(case: tuple[str, str, Any]) -> str:
    return f"{case[0]}-{case[1]}"


@pytest.fixture(autouse=True)
def _pygame() -> None:
    init_headless()


def _check(surface: pygame.Surface, where: str, allowed: tuple[str, ...]) -> list[str]:
    return [f"{where}: {p}" for p in marks.problems(surface, overlap_ok=allowed)]


#: The canvases checked: the default, and the README's size for a GIF in a slide.
SIZES = [(640, 360), (480, 270)]


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("case", SCENES, ids=_ids)
def test_no_label_overlaps_or_is_cut_in_any_scene(
    case: tuple[str, str, Any], size: tuple[int, int]
) -> None:
    demo, name, factory = case
    scene = factory()
    size = (max(size[0], scene.min_size[0]), max(size[1], scene.min_size[1]))
    if demo == "ballpit":
        scene.balls = 400  # the pit's layout is its own; fewer balls to step
    seconds = min(scene.duration, SHORTER.get((demo, name), LONGEST))
    last = frame_count(seconds, 30) - 1
    chosen = {0, 1, 2, last} | {round(last * k / (SPREAD + 1)) for k in range(1, SPREAD + 1)}
    allowed = ALLOWED.get((demo, name), ())
    found, drawn = [], 0
    for k, _, surface in iter_frames(scene, 30, seconds, size, only=chosen):
        drawn += 1
        assert marks.marks(surface), f"frame {k} noted nothing: is its text drawn by draw_text?"
        found += _check(surface, f"frame {k}", allowed)
    assert drawn == len(chosen)
    assert found == [], "\n".join(found)


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("case", [c for c in SCENES if c[2]().has_strobe], ids=_ids)
def test_no_label_overlaps_or_is_cut_in_any_motion_diagram(
    case: tuple[str, str, Any], size: tuple[int, int]
) -> None:
    demo, name, factory = case
    scene = factory()
    if demo == "ballpit":
        scene.balls = 400
    size = (max(size[0], scene.min_size[0]), max(size[1], scene.min_size[1]))
    surface = pygame.Surface(size)
    scene.build(size)
    draw_strobe(scene, surface)
    assert marks.marks(surface)
    found = _check(surface, "strobe", ALLOWED.get((demo, name), ()))
    assert found == [], "\n".join(found)


# -- the tradeoff charts, from made-up rows of every kind ---------------------------------------


def _points() -> list[Point]:
    """Every method at seven dt on each problem, orders 1, 1, 2, 4; the closed form on gravity,
    exact; auto at three tolerances; one diverged point and one past its stability limit."""
    orders = {"explicit_euler": 1, "semi_implicit_euler": 1, "velocity_verlet": 2, "rk4": 4}
    points = []
    for problem in ("gravity", "spring", "wind"):
        for method, order in orders.items():
            for k in range(2, 9):
                dt = 2.0**-k
                evaluations = {"rk4": 4, "velocity_verlet": 2}.get(method, 1) * 2**k
                points.append(
                    Point(problem, method, method, dt, 2**k, 0.3 * dt**order, True, k == 2,
                          1e-6 * evaluations, 0.0, evaluations, 0)
                )  # fmt: skip
        for i, tolerance in enumerate((1e-2, 1e-4, 1e-6)):
            dt = 2.0 ** -(3 + 2 * i)
            points.append(
                Point(problem, "auto", "rk4", dt, round(1 / dt), tolerance / 3, True, False,
                      4e-6 / dt, 1e-5, round(4 / dt), 8, tolerance)
            )  # fmt: skip
    points.append(Point("gravity", "exact", "exact", 0.25, 4, 1e-16, True, False, 1e-6, 0, 0, 0))
    points.append(Point("spring", "rk4", "rk4", 1.0, 1, math.inf, False, True, 1e-6, 0, 4, 0))
    return points


def _pendulum_rows() -> list[pendulum.Row]:
    return [
        pendulum.Row(m, "exact" if m == "auto" else m, dt, dt * dt * 10, 3e-4, 100)
        for m in pendulum.METHODS
        for dt in (1 / 30, 1 / 60, 1 / 120, 1 / 240)
    ]


def _solver_rows() -> list[solver.Row]:
    rows = []
    for scene in solver.SCENES:
        for engine, counts in (("World", (1, 2, 4, 8, 16)), ("pymunk", (1, 10, 40))):
            for i, k in enumerate(counts):
                error = 10.0 ** -(i + 1)
                rows.append(solver.Row(scene, engine, k, error, 1e-6, 1e-4 * 2**i, i == 0, 0, 120))
    return rows


def _throughput_rows() -> list[throughput.Row]:
    return [
        throughput.Row(impl, n, 100.0 / (1 + i) + 1000.0 / n)
        for i, impl in enumerate(("World", "Particles", "lesson Body", "pymunk", "pygame Vector2"))
        for n in (10, 100, 1000, 10_000, 100_000)
    ]


@pytest.mark.parametrize("size", [(1280, 720), (1920, 1080)], ids=["default", "larger"])
@pytest.mark.parametrize("chart", ["work_precision", "throughput", "contacts"])
def test_no_label_overlaps_or_is_cut_in_the_tradeoff_charts(
    chart: str, size: tuple[int, int]
) -> None:
    draw = {
        "work_precision": lambda: draw_work_precision(_points(), size, _pendulum_rows()),
        "throughput": lambda: draw_throughput(_throughput_rows(), size),
        "contacts": lambda: draw_contacts(_solver_rows(), size),
    }[chart]
    surface = draw()
    assert marks.marks(surface)
    found = _check(surface, chart, ())
    assert found == [], "\n".join(found)
