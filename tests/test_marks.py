"""Every demo and scene, run briefly, checked by what its frames hold (engine.render.marks):
no label on another label or on a marker, no label or arrowhead cut at the frame's edge or
leaving its panel; and by what its drawing helpers drew (tests/pixels.py: ``watching``): no
label written over a drawn body or sprite (``draw_world``, ``draw_disc``, ``draw_sprite``;
a body drawn over a label, as a moving one crosses an axis's numbers, is motion), no arrow
hidden under a sprite or body drawn after it. A body a demo draws with pygame itself is not
seen: draw it with those helpers. The next demo cannot regress unseen.

Each scene is stepped through (up to ``LONGEST`` s of its time) and drawn at a few frames, at
the default 640x360 and at 480x270 (the README's size for a GIF): the first three, some spread
over the run, the last; its motion diagram too, if it has one; and each game's end screen,
its verdict over the table. The tradeoff demo's charts are drawn from made-up rows of every
kind (measuring takes minutes).

The allow-list, where overlap is the point: empty. A label that overlaps in a new demo is
added here only with the reason beside it. ``KNOWN`` lists a fault found in a demo and not
yet fixed, with what it is: it must still be found, so that its fix shows.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterator, Sequence
from typing import Any

import numpy as np
import pygame
import pytest
from pixels import Drawn, Layers, hidden_arrows, labels_on_bodies, watching

import demos.breakout as breakout
import demos.crumb as crumb
import demos.pinball as pinball
from demos.bench import pendulum, solver, throughput
from demos.cli import Demo, discover
from demos.tradeoff import draw_contacts, draw_throughput, draw_work_precision
from engine import FixedStep, VirtualClock
from engine.measure import Point
from engine.render import frame_count, init_headless, iter_frames, marks
from engine.render.recorder import draw_strobe
from tests.paths import drawn_on_numpy  # noqa: F401 (used by name below)

#: The drawing checks run on the numpy path alone (tests.paths.drawn_on_numpy).
pytestmark = pytest.mark.usefixtures("drawn_on_numpy")

#: The most simulated seconds a scene is stepped through here.
LONGEST = 12.0
#: Frames drawn spread over the run, besides the first three and the last.
SPREAD = 6
#: (demo, scene) -> the seconds checked where a scene's whole layout shows sooner than LONGEST
#: and its steps are slow: the tumblers' drums (500 boxes) show their frame, read-outs and
#: landed pile within 4 s; the stress scene's, at 90 degrees a second, turns once in that time
#: (its 12 s took 87 s of the suite), Box2D's at 25 a quarter turn, its pile tumbling.
SHORTER: dict[tuple[str, str], float] = {("stack", "tumbler"): 4.0, ("stack", "tumbler90"): 4.0}
#: (demo, scene) -> words that may overlap in it, and why. Where overlap is the point only.
ALLOWED: dict[tuple[str, str], tuple[str, ...]] = {}
#: (demo, scene) -> a fault the checks of the drawn bodies found in a demo this test's change
#: did not own, and what it is: its problems must still be found (so a fix shows, and its
#: entry goes), and are then set aside. Other problems of the scene fail as ever.
KNOWN: dict[tuple[str, str], tuple[str, str]] = {
    ("crumb", "game"): (
        "hidden under sprite",
        "Alfred's velocity arrow starts at his middle and is shorter than he is when he walks "
        "slowly: drawn under his sprite (the paper's fault, issue 40 item 8a, in the crumb)",
    ),
}


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


@pytest.fixture
def layers() -> Iterator[Layers]:
    """What the drawing helpers draw during the test (tests/pixels.py)."""
    with watching() as watched:
        yield watched


def _check(
    surface: pygame.Surface, where: str, allowed: tuple[str, ...], drawn: Sequence[Drawn] = ()
) -> list[str]:
    found = marks.problems(surface, overlap_ok=allowed)
    found += labels_on_bodies(marks.marks(surface), drawn, allowed)
    found += hidden_arrows(drawn)
    return [f"{where}: {p}" for p in found]


#: The canvases checked: the default, and the README's size for a GIF in a slide.
SIZES = [(640, 360), (480, 270)]


def _made(
    demo: str, factory: Callable[[], Any], size: tuple[int, int]
) -> tuple[Any, tuple[int, int]]:
    """A scene of ``factory`` built for a ``size`` px canvas (grown to its least size)."""
    scene = factory()
    if demo == "ballpit":
        scene.balls = 400  # the pit's layout is its own; fewer balls to step
    size = (max(size[0], scene.min_size[0]), max(size[1], scene.min_size[1]))
    scene.build(size)
    return scene, size


def _same(a: Any, b: Any) -> bool:
    """Whether two snapshots hold the same numbers (arrays compared entry by entry)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a), np.asarray(b))
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        fields = [f.name for f in dataclasses.fields(a)]
        return type(a) is type(b) and all(_same(getattr(a, f), getattr(b, f)) for f in fields)
    if isinstance(a, (tuple, list)):
        return (
            isinstance(b, (tuple, list))
            and len(a) == len(b)
            and all(_same(x, y) for x, y in zip(a, b, strict=True))
        )
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    try:
        return bool(a == b)
    except (TypeError, ValueError):
        return a is b


@pytest.mark.parametrize("case", SCENES, ids=_ids)
def test_no_label_overlaps_or_is_cut_in_any_scene(
    case: tuple[str, str, Any], layers: Layers
) -> None:
    """Each scene stepped once (as the recorder steps it) and drawn at each size of SIZES: a
    scene built alike at every size (the same snapshot: its world does not depend on the
    canvas, only its camera does) is restored into its twin at each chosen frame and drawn
    there (engine.render.Scene.snapshot: what a frame shows, bit for bit, tests/test_resume);
    one built otherwise is stepped at each size."""
    demo, name, factory = case
    allowed = ALLOWED.get((demo, name), ())
    built = [_made(demo, factory, size) for size in SIZES]
    first = built[0][0]
    shared = all(_same(first.snapshot(), scene.snapshot()) for scene, _ in built[1:])
    runs = [built] if shared else [[b] for b in built]
    found, drawn = [], 0
    for run in runs:
        lead = run[0][0]
        seconds = min(lead.duration, SHORTER.get((demo, name), LONGEST))
        last = frame_count(seconds, 30) - 1
        chosen = {0, 1, 2, last} | {round(last * k / (SPREAD + 1)) for k in range(1, SPREAD + 1)}
        surfaces = [pygame.Surface(size) for _, size in run]
        # As engine.render.iter_frames steps a scene: one step ahead, then the fixed-step loop
        # on a virtual clock.
        loop = FixedStep(lead.dt, max_frame=max(0.25, 2 * lead.dt, 2.0 / 30))
        clock = VirtualClock(30)
        lead.step(lead.dt)
        for k in range(last + 1):
            if k > 0:
                for _ in range(loop.advance(clock.tick())):
                    lead.step(lead.dt)
            if k not in chosen:
                continue
            saved = lead.snapshot() if len(run) > 1 else None
            for (scene, size), surface in zip(run, surfaces, strict=True):
                if scene is not lead:
                    scene.restore(saved)
                marks.clear(surface)
                scene.draw(surface, loop.alpha)
                drawn += 1
                where = f"{size[0]}x{size[1]} frame {k}"
                assert marks.marks(surface), (
                    f"{where} noted nothing: is its text drawn by draw_text?"
                )
                found += _check(surface, where, allowed, layers.take(surface))
        assert drawn % len(chosen) == 0
    assert drawn == len(SIZES) * len(chosen)
    if (demo, name) in KNOWN:
        words, why = KNOWN[demo, name]
        assert any(words in p for p in found), f"fixed? then drop KNOWN's entry: {why}"
        found = [p for p in found if words not in p]
    assert found == [], "\n".join(found)


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("case", [c for c in SCENES if c[2]().has_strobe], ids=_ids)
def test_no_label_overlaps_or_is_cut_in_any_motion_diagram(
    case: tuple[str, str, Any], size: tuple[int, int], layers: Layers
) -> None:
    demo, name, factory = case
    scene, size = _made(demo, factory, size)
    surface = pygame.Surface(size)
    draw_strobe(scene, surface)
    assert marks.marks(surface)
    found = _check(surface, "strobe", ALLOWED.get((demo, name), ()), layers.take(surface))
    assert found == [], "\n".join(found)


#: The games' end screens, each made by its rule: no balls left (the pinball), no lives (the
#: breakout). Their verdict ("GAME OVER") is written over the table.
ENDED: dict[str, Callable[[], Any]] = {
    "pinball": lambda: _ended(pinball.PinballScene(), "balls"),
    "breakout": lambda: _ended(breakout.BreakoutScene(), "lives"),
}


def _ended(scene: Any, left: str) -> Any:
    build = scene.build

    def build_ended(size: tuple[int, int]) -> None:
        build(size)
        setattr(scene.world.score, left, 0)
        assert scene.world.score.over

    scene.build = build_ended
    return scene


@pytest.mark.parametrize("size", [*SIZES, pinball.SIZE], ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("game", list(ENDED))
def test_no_label_overlaps_or_is_cut_on_a_games_end_screen(
    game: str, size: tuple[int, int], layers: Layers
) -> None:
    scene = ENDED[game]()
    size = (max(size[0], scene.min_size[0]), max(size[1], scene.min_size[1]))
    found = []
    for k, _, surface in iter_frames(scene, 30, 0.5, size, only={0, 15}):
        assert "GAME OVER" in [m.text for m in marks.marks(surface)]
        found += _check(surface, f"frame {k}", (), layers.take(surface))
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
