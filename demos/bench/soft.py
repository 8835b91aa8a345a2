"""The soft step on the big scenes, against the exact pipeline and pymunk, side by side.

Run with ``python -m demos.bench soft`` (``--quick``: the smaller scenes, 5 s each). Issue
"Games at C speed" sets the fast path's targets on these scenes at 1.0x pymunk's step; a game
takes ``World(solver="soft")`` (Box2D v3's soft step: engine.pipeline.game_step), so each scene is
run three ways, one step each in turn (the order turned about every step, so a burst of load on
a shared machine hits them alike), on the fast path (numba; the scenes are too big for the
soft step's plain-Python solver on the numpy path):

* ``soft``: ``World(solver="soft", kernels="fast")``;
* ``exact``: the same scene as the benches of each scene build it (``solver="exact"``);
* ``pymunk``: pymunk 7 with its default 10 iterations.

The scenes (each the same numbers in all three; see the bench each comes from):

* ``pyramid 210``, ``pyramid 820``: demos.stack's pyramids of 1 m boxes on a floor, sleeping
  off, the mean step over steps 60 to 300 (after the first second's settling, as
  ``demos.bench.stack`` measures); quality: the largest any box has moved (mm).
* ``tumbler 25 deg/s``: demos.stack's tumbler of 500 boxes at Box2D's benchmark speed;
  quality: the boxes whose centre ended a step past a wall (none may).
* ``pit 1,000``, ``pit 10,000``: demos.bench.pit's balls dropped as a dense grid, the first
  5 s; quality: the deepest overlap at the end, over the radius.
* ``segments 1,000``: demos.bench.contacts' balls among 50 segments in a box; quality: the
  balls outside the box.

Reported per scene: each engine's mean step (ms) and the soft step's and the exact one's over
pymunk's, each engine's quality measure, and how many steps of the soft and the exact World
warned (a ``StabilityWarning``: a pile past what its iterations hold), counted here rather than
printed among the table's lines. Nothing here is asserted: the table is what a
run measured, on this machine, with what else it ran.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from demos import stack
from demos.bench import contacts, pit, tumbler
from demos.bench.stack import make_space as pyramid_space
from engine import kernels as engine_kernels

__all__ = ["DT", "Sim", "SCENES", "side_by_side", "report"]

DT = 1.0 / 60.0  # s
#: One engine's scene: its step (dt) and its quality measure now.
Sim = tuple[Callable[[float], Any], Callable[[], float]]


def _moved(positions: Callable[[], np.ndarray]) -> Callable[[], float]:
    """The largest distance (mm) any body has moved since now."""
    start = positions().copy()
    return lambda: 1e3 * float(np.hypot(*(positions() - start).T).max())


def _pyramid(base: int) -> Callable[[str], Sim | None]:
    def made(engine: str) -> Sim | None:
        if engine == "pymunk":
            space = pyramid_space(base, sleep=False)
            if space is None:
                return None
            s, bodies = space
            return s.step, _moved(lambda: np.array([tuple(b.position) for b in bodies]))
        world, _boxes = stack.pyramid(base, kernels="fast", solver=engine)
        world.sleep_time = math.inf
        return world.step, _moved(world.positions)

    return made


def _tumbler(engine: str) -> Sim | None:
    spin = math.radians(25.0)
    if engine == "pymunk":
        made = tumbler.make_space()
        if made is None:
            return None
        space, walls, bodies = made
        walls.angular_velocity = spin

        def lost() -> float:
            pos = np.array([tuple(b.position) for b in bodies])
            turn = np.array([b.angle for b in bodies])
            return float(tumbler._room(pos, turn, walls.angle)[0].sum())

        return space.step, lost
    world, boxes, room = stack.tumbler(spin=spin, kernels="fast", solver=engine)
    return world.step, lambda: float(stack.outside(boxes, room).sum())


def _pit(n: int) -> Callable[[str], Sim | None]:
    def overlap(x: np.ndarray) -> float:
        return pit.deepest_overlap(x, np.full(len(x), pit.RADIUS)) / pit.RADIUS

    def made(engine: str) -> Sim | None:
        if engine == "pymunk":
            space: Any = pit.make_space(n)
            if space is None:
                return None
            return space.step, lambda: overlap(np.array([tuple(b.position) for b in space.bodies]))
        world = pit.make_world(n, kernels="fast", solver=engine)
        return world.step, lambda: overlap(world.positions())

    return made


def _segments(n: int) -> Callable[[str], Sim | None]:
    def made(engine: str) -> Sim | None:
        if engine == "pymunk":
            space: Any = contacts.make_space(n)
            if space is None:
                return None
            return space.step, lambda: float(
                contacts._outside(np.array([tuple(b.position) for b in space.bodies]))
            )
        world = contacts.make_world(n, kernels="fast", solver=engine)
        return world.step, lambda: float(contacts._outside(world.positions()))

    return made


@dataclass(frozen=True)
class Scene:
    """A scene of the table: its ``name``, how each engine makes it, how many ``steps`` are
    run and from which step on they are timed (``timed_from``), and what its quality
    measure is (``quality``), and whether the quick run has it."""

    name: str
    made: Callable[[str], Sim | None]
    steps: int
    timed_from: int
    quality: str
    quick: bool


SCENES = (
    Scene("pyramid 210", _pyramid(20), 300, 60, "moved (mm)", True),
    Scene("pyramid 820", _pyramid(40), 300, 60, "moved (mm)", False),
    Scene("tumbler 25 deg/s", _tumbler, 300, 0, "centres past a wall", True),
    Scene("pit 1,000", _pit(1000), 300, 0, "deepest overlap / r", True),
    Scene("pit 10,000", _pit(10000), 300, 0, "deepest overlap / r", False),
    Scene("segments 1,000", _segments(1000), 300, 0, "balls outside", True),
)
ENGINES = ("soft", "exact", "pymunk")


def side_by_side(scene: Scene, steps: int | None = None) -> dict[str, tuple[float, float, int]]:
    """engine -> (its mean step over the timed steps (s, by the wall clock), its quality
    measure at the end, how many of its steps warned), the engines one step each in turn
    (``steps``: the scene's)."""
    engine_kernels.prepare()  # compiled (or loaded) before the clock starts
    sims = {e: s for e in ENGINES if (s := scene.made(e)) is not None}
    steps = scene.steps if steps is None else steps
    first = min(scene.timed_from, steps - 1)
    spent = dict.fromkeys(sims, 0.0)
    warned = dict.fromkeys(sims, 0)
    names = list(sims)
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        for i in range(steps):
            for name in names if i % 2 == 0 else names[::-1]:
                before = len(said)
                t0 = time.perf_counter()
                sims[name][0](DT)
                if i >= first:
                    spent[name] += time.perf_counter() - t0
                warned[name] += len(said) > before
    timed = steps - first
    return {name: (spent[name] / timed, sims[name][1](), warned[name]) for name in names}


def report(quick: bool = False) -> str:
    """The table (module doc): the quick run's scenes, or all of them."""
    if not engine_kernels.available():
        return "soft: needs the fast extra (numba): the soft step's big scenes run compiled"
    lines = [
        "soft: the soft step (World(solver='soft')) on the big scenes, fast path, against the "
        "exact pipeline and pymunk (10 iterations), one step each in turn; mean step by the "
        "wall clock",
        f"  {'scene':<18} {'soft':>9} {'exact':>9} {'pymunk':>9} {'soft/pm':>8} "
        f"{'exact/pm':>9}   quality: soft / exact / pymunk; steps warned: soft / exact",
    ]
    for scene in SCENES:
        if quick and not scene.quick:
            continue
        got = side_by_side(scene)
        pm = got.get("pymunk", (math.nan, math.nan))[0]
        ms = {e: f"{got[e][0] * 1e3:7.3f}ms" if e in got else "      -  " for e in ENGINES}
        quality = " / ".join(f"{got[e][1]:.3g}" if e in got else "-" for e in ENGINES)
        warned = f"{got['soft'][2]} / {got['exact'][2]}"
        lines.append(
            f"  {scene.name:<18} {ms['soft']:>9} {ms['exact']:>9} {ms['pymunk']:>9} "
            f"{got['soft'][0] / pm:7.2f}x {got['exact'][0] / pm:8.2f}x   "
            f"{scene.quality}: {quality}; warned: {warned}"
        )
    return "\n".join(lines)
