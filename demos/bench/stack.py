"""Pyramids of boxes that turn, against pymunk: the stacks set as targets for bodies that turn.

Run with ``python -m demos.bench stack`` (``--quick``: the 210-box pyramid for 10 s, one
round). The scene is ``demos.stack``'s pyramid (``pyramid_centres``): boxes of 1 m and 1 kg,
friction 0.6 (by product, as pymunk: 0.6 on a floor of 1.0, 0.36 box on box), restitution 0,
put down touching on a floor, g = 9.81 m/s^2, dt = 1/60 s; a base of 20 (210 boxes) and of 40
(820 boxes). pymunk 7 steps the same boxes (``make_space``: the same centres, sizes, masses,
moments and materials) with its default 10 iterations.

Each pyramid runs twice, side by side in one run, one step each in turn (the order swapped
every step, so a burst of load on a shared machine hits the engines alike):

* **sleeping on**, what a game sees: this World's default (a body still for 0.5 s sleeps),
  pymunk with ``sleep_time_threshold`` 0.5 s (its default is off; "pymunk asleep at 1.5 s",
  as the peers were measured, needs it on);
* **sleeping off**, every step solved, as the peers' drift and step time were measured
  (Box2D's in ``anchors/box2d``: ``enableSleep`` false).

Each step is timed by the wall clock. Reported per engine: the mean time a step over the first
2 s (the phase a user sees: from the placement through settling; the median over ``rounds``
fresh placements, the ratio the median of the rounds' ratios) and over the whole window (one
round); the largest displacement of any box from where it was put at 2 s, 10 s and the
window's end (60 s), and which box it is (its row from the floor, dx, dy, angle: a sag is dy
< 0 with dx small, a slide dx); when every box first slept. This World runs on the numpy
path ("World") and, where numba is installed, on the fast path too ("fast"), each named in
the table whatever ``ENGINE_KERNELS`` says.

Targets: the 210-box pyramid moves at most 0.01 m by 60 s and sleeps within 2 s;
the 820-box pyramid moves at most 0.02 m; a step on the numpy path at most 3x pymunk's, on
the fast path at most 1x. The report writes ``stack_210.png`` and ``stack_820.png``
(the displacement against time, both engines, sleeping on and off) into its output folder
(``out/bench``; ``--out DIR``).
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from demos import stack as scene
from demos.bench.pit import ENGINE_COLORS, time_chart_class
from engine import Body, World
from engine import kernels as engine_kernels

__all__ = [
    "DT",
    "SECONDS",
    "FIRST",
    "ITERATIONS",
    "SLEEP_TIME",
    "TARGETS",
    "SPEED_TARGETS",
    "PEERS",
    "Run",
    "make_world",
    "make_space",
    "add_boxes",
    "space_of",
    "side_by_side",
    "summary",
    "draw_stack",
    "report",
]

DT = scene.DT  # s
SECONDS = 60.0  # s: the window, from the placement
FIRST = 2.0  # s: the phase a user sees, from the placement through settling
ITERATIONS = 10  # pymunk's, its default
SLEEP_TIME = 0.5  # s still before a body sleeps: this World's default, given to pymunk too
FLOOR = 1000.0  # m: half the length of pymunk's floor segment (this World's is a plane)

#: The targets per base: (the most any box may move by the window's end (m), all
#: asleep within (s) or None).
TARGETS: dict[int, tuple[float, float | None]] = {20: (0.01, 2.0), 40: (0.02, None)}
#: The speed targets: a step over the first seconds against pymunk's, per path.
SPEED_TARGETS: dict[str, float] = {"World": 3.0, "fast": 1.0}
#: The peers as they were measured before this bench (sleeping off; not measured here):
#: base -> engine -> (ms a step, the largest displacement by 60 s (m)).
PEERS: dict[int, dict[str, tuple[float, float]]] = {
    20: {"pymunk (10 iterations)": (0.331, 0.047), "Box2D v3 (4 substeps)": (0.118, 0.029)},
    40: {"pymunk (10 iterations)": (1.56, 0.26), "Box2D v3 (4 substeps)": (0.46, 0.116)},
}


def make_world(
    base: int, *, kernels: str | None = None, sleep: bool = True
) -> tuple[World, list[Body]]:
    """``demos.stack``'s pyramid of ``base`` on the exact models (the soft step's are
    demos.bench.soft's), on the path ``kernels`` (None: the default);
    ``sleep=False``: sleeping off (every step solved)."""
    world, boxes = scene.pyramid(base, kernels=kernels, solver="exact")
    if not sleep:
        world.sleep_time = math.inf
    return world, boxes


def make_space(
    base: int, iterations: int = ITERATIONS, *, sleep: bool = True
) -> tuple[Any, list[Any]] | None:
    """The same pyramid in pymunk, and its bodies in the World's order (None without pymunk):
    a floor segment of friction 1.0, boxes of ``demos.stack``'s side, mass and friction;
    ``sleep``: its ``sleep_time_threshold`` SLEEP_TIME (else its default, off)."""
    return space_of(scene.pyramid_centres(base), iterations, sleep=sleep)


def space_of(
    centres: Sequence[tuple[float, float]],
    iterations: int = ITERATIONS,
    *,
    sleep: bool = True,
    slop: float | None = None,
) -> tuple[Any, list[Any]] | None:
    """``demos.stack``'s boxes put at ``centres`` (a pyramid's, a tower's) in pymunk, as
    ``make_space``; ``slop``: its ``collision_slop`` (m; None keeps its default, 0.1)."""
    try:
        import pymunk
    except ImportError:
        return None
    space = pymunk.Space()
    space.gravity = (0.0, -scene.G)
    space.iterations = iterations
    if slop is not None:
        space.collision_slop = slop
    if sleep:
        space.sleep_time_threshold = SLEEP_TIME
    floor = pymunk.Segment(space.static_body, (-FLOOR, 0.0), (FLOOR, 0.0), 0.0)
    floor.friction = scene.FLOOR_FRICTION
    space.add(floor)
    return space, add_boxes(space, centres, scene.SIDE, scene.MASS)


def add_boxes(
    space: Any, centres: Sequence[tuple[float, float]], side: float, mass: float
) -> list[Any]:
    """pymunk boxes of ``side`` (m) and ``mass`` (kg) at ``centres``, of ``demos.stack``'s
    friction and no restitution, added to ``space``; their bodies, in order."""
    import pymunk

    size = (side, side)
    bodies = []
    for x, y in centres:
        body = pymunk.Body(mass, pymunk.moment_for_box(mass, size))
        body.position = (x, y)
        box = pymunk.Poly.create_box(body, size, 0.0)
        box.friction, box.elasticity = scene.FRICTION, 0.0
        space.add(body, box)
        bodies.append(body)
    return bodies


@dataclass(frozen=True)
class _Sim:
    """One engine's pyramid, seen the same way whichever engine it is."""

    step: Callable[[float], object]
    positions: Callable[[], np.ndarray]  # (n, 2) m, in the pyramid's order
    angles: Callable[[], np.ndarray]  # (n,) rad
    asleep: Callable[[], bool]  # every box asleep


def _world_sim(world: World, boxes: list[Body]) -> _Sim:
    def asleep() -> bool:
        return world.sleeping == len(boxes)

    return _Sim(world.step, world.positions, lambda: np.array([b.angle for b in boxes]), asleep)


def _space_sim(space: Any, bodies: list[Any]) -> _Sim:
    def positions() -> np.ndarray:
        return np.array([tuple(b.position) for b in bodies])

    def asleep() -> bool:
        return all(b.is_sleeping for b in bodies)

    return _Sim(space.step, positions, lambda: np.array([b.angle for b in bodies]), asleep)


def _sims(base: int, sleep: bool, pymunk: bool) -> dict[str, _Sim]:
    """engine -> its pyramid: the World on the numpy path ("World"), on the fast path where
    numba is installed ("fast"), and pymunk where it is installed and ``pymunk`` is true."""
    paths = {"World": "numpy", "fast": "fast"} if engine_kernels.available() else {"World": "numpy"}
    sims = {
        name: _world_sim(*make_world(base, kernels=p, sleep=sleep)) for name, p in paths.items()
    }
    space = make_space(base, sleep=sleep) if pymunk else None
    if space is not None:
        sims["pymunk"] = _space_sim(*space)
    return sims


@dataclass
class Run:
    """One engine's pyramid over a window: what it cost and how far its boxes moved.

    ``steps``: the wall-clock seconds of each step (the first round); ``moved``: the largest
    displacement (m) of any box from where it was put, after each step; ``firsts``: the mean
    seconds a step over the first ``first`` s, one a round; ``worst``: the box that moved most
    by the window's end (its index, dx and dy (m), angle (rad)); ``asleep_at``: when every box
    first slept (nan: not within the window, or sleeping off).
    """

    engine: str
    base: int
    sleep: bool
    first: float
    steps: np.ndarray
    moved: np.ndarray
    firsts: list[float]
    worst: tuple[int, float, float, float]
    asleep_at: float = math.nan

    @property
    def boxes(self) -> int:
        return self.base * (self.base + 1) // 2

    @property
    def seconds(self) -> float:
        """The window (s)."""
        return len(self.steps) * DT

    @property
    def t(self) -> np.ndarray:
        """When (s) each step ended."""
        return np.arange(1, len(self.steps) + 1) * DT

    @property
    def first_step(self) -> float:
        """Seconds a step over the first ``first`` s: the median over the rounds."""
        return statistics.median(self.firsts)

    @property
    def mean_step(self) -> float:
        """Seconds a step over the whole window (the first round)."""
        return float(self.steps.mean())

    def moved_at(self, seconds: float) -> float:
        """The largest displacement of any box (m) at ``seconds`` (at most the window's end)."""
        k = min(max(round(seconds / DT), 1), len(self.moved))
        return float(self.moved[k - 1])

    def row(self, index: int) -> int:
        """The row (0: on the floor) of box ``index``."""
        row, start = 0, 0
        while index >= start + self.base - row:
            start += self.base - row
            row += 1
        return row


def side_by_side(
    base: int,
    seconds: float = SECONDS,
    *,
    sleep: bool = True,
    rounds: int = 1,
    first: float = FIRST,
    pymunk: bool = True,
) -> dict[str, Run]:
    """Put the pyramid of ``base`` down and step each engine for ``seconds``, side by side;
    ``rounds`` - 1 more placements time the first ``first`` s again. Returns engine -> Run."""
    steps = round(seconds / DT)
    head = min(steps, max(1, round(first / DT)))
    engine_kernels.prepare()  # compiled (or loaded from the cache) before the clock starts
    perf = time.perf_counter
    firsts: dict[str, list[float]] = {}
    spent: dict[str, np.ndarray] = {}
    moved: dict[str, np.ndarray] = {}
    asleep_at: dict[str, float] = {}
    worst: dict[str, tuple[int, float, float, float]] = {}
    for r in range(rounds):
        sims = _sims(base, sleep, pymunk)
        names = list(sims)
        n = steps if r == 0 else head
        times = {name: np.empty(n) for name in names}
        start = {name: sims[name].positions() for name in names}
        if r == 0:
            moved = {name: np.empty(n) for name in names}
            asleep_at = {name: math.nan for name in names}
        for i in range(n):
            for name in names if i % 2 == 0 else names[::-1]:
                t0 = perf()
                sims[name].step(DT)
                times[name][i] = perf() - t0
            if r == 0:  # measured between the steps, not timed
                for name in names:
                    sim = sims[name]
                    moved[name][i] = np.hypot(*(sim.positions() - start[name]).T).max()
                    if math.isnan(asleep_at[name]) and sim.asleep():
                        asleep_at[name] = (i + 1) * DT
        for name in names:
            firsts.setdefault(name, []).append(float(times[name][:head].mean()))
        if r == 0:
            spent = times
            for name in names:
                d = sims[name].positions() - start[name]
                k = int(np.hypot(*d.T).argmax())
                worst[name] = (k, float(d[k, 0]), float(d[k, 1]), float(sims[name].angles()[k]))
    return {
        name: Run(name, base, sleep, head * DT, spent[name], moved[name], firsts[name],
                  worst[name], asleep_at[name])
        for name in spent
    }  # fmt: skip


def _met(ok: bool) -> str:
    return "met" if ok else "NOT met"


def _ratio(runs: dict[str, Run], engine: str) -> float | None:
    """``engine``'s first seconds over pymunk's: the median of the rounds' ratios."""
    if "pymunk" not in runs or engine not in runs:
        return None
    pairs = zip(runs[engine].firsts, runs["pymunk"].firsts, strict=True)
    return statistics.median(a / b for a, b in pairs)


def _mm(metres: float) -> str:
    return f"{1000 * metres:.2f} mm"


def _table(runs: dict[str, Run]) -> list[str]:
    """One setting's rows: each engine, then ours over pymunk's (times and displacements)."""
    run = next(iter(runs.values()))
    end, head = run.seconds, run.first
    marks = [t for t in (head, 10.0) if t < end] + [end]
    cells = [f"first {head:g} s", f"0-{end:g} s"] + [f"moved at {t:g} s" for t in marks]
    lines = [
        f"    {'engine':<16}" + "".join(f"{c:>16}" for c in cells)
        + f"{'all asleep':>12}   the box that moved most by {end:g} s"
    ]  # fmt: skip
    for r in runs.values():
        asleep = f"{r.asleep_at:.2f} s" if math.isfinite(r.asleep_at) else "never"
        asleep = asleep if r.sleep else "(off)"
        k, dx, dy, angle = r.worst
        row = [f"{1e3 * r.first_step:.3f} ms", f"{1e3 * r.mean_step:.3f} ms"]
        row += [_mm(r.moved_at(t)) for t in marks]
        lines.append(
            f"    {r.engine:<16}" + "".join(f"{c:>16}" for c in row) + f"{asleep:>12}   row "
            f"{r.row(k)}: dx {_mm(dx)}, dy {_mm(dy)}, {math.degrees(angle):.3f} deg"
        )  # fmt: skip
    pymunk = runs.get("pymunk")
    for name in (n for n in ("World", "fast") if n in runs):
        if pymunk is None:
            break
        ours, first = runs[name], _ratio(runs, name)
        row = [f"{first:.2f}x", f"{ours.mean_step / pymunk.mean_step:.2f}x"]
        row += [
            f"{ours.moved_at(t) / pymunk.moved_at(t):.3g}x" if pymunk.moved_at(t) > 0 else "-"
            for t in marks
        ]
        pairs = zip(ours.firsts, pymunk.firsts, strict=True)
        spread = ", ".join(f"{a / b:.2f}" for a, b in pairs)
        lines.append(
            f"    {f'{name} / pymunk':<16}" + "".join(f"{c:>16}" for c in row)
            + (f"   (first {head:g} s, rounds: {spread})" if len(ours.firsts) > 1 else "")
        )  # fmt: skip
    return lines


def summary(on: dict[str, Run], off: dict[str, Run]) -> list[str]:
    """The report's lines for one pyramid: sleeping on, sleeping off, and the targets."""
    w = on["World"]
    base, end = w.base, w.seconds
    lines = [f"  {w.boxes:,} boxes (a base of {base}), the first {end:g} s from the placement:"]
    lines.append(
        f"   sleeping on (this World's {SLEEP_TIME:g} s still; pymunk's sleep_time_threshold "
        f"{SLEEP_TIME:g} s), wall time a step:"
    )
    lines += _table(on)
    lines.append("   sleeping off (every step solved; as the peers were measured):")
    lines += _table(off)
    target = TARGETS.get(base)
    checks = []
    if target is not None:
        most, within = target
        worst = max(off[n].moved_at(end) for n in ("World", "fast") if n in off)
        checks.append(
            f"moved <= {_mm(most)} by {end:g} s: {_met(worst <= most)} (sleeping off, the "
            f"worse path: {_mm(worst)}; on: {_mm(w.moved_at(end))})"
            + ("" if end >= SECONDS else f" [the window is {end:g} s, not {SECONDS:g}]")
        )
        if within is not None:
            ok = math.isfinite(w.asleep_at) and w.asleep_at <= within
            checks.append(f"asleep within {within:g} s: {_met(ok)}")
    for name, most in SPEED_TARGETS.items():
        ratio = _ratio(on, name)
        if ratio is not None:
            checks.append(f"{name} first {w.first:g} s <= {most:g}x pymunk: {_met(ratio <= most)}")
    if checks:
        lines.append("    targets: " + "; ".join(checks))
    peers = PEERS.get(base)
    if peers:
        told = "; ".join(f"{p} {ms:g} ms, {_mm(m)}" for p, (ms, m) in peers.items())
        lines.append(f"    the peers (sleeping off, a step, moved by 60 s; not run here): {told}")
    return lines


def draw_stack(on: dict[str, Run], off: dict[str, Run], size: tuple[int, int] = (1280, 720)) -> Any:
    """The pyramid's picture: the largest displacement of any box against time, both engines,
    sleeping on (left) and off (right)."""
    import pygame

    from engine.render import MUTED, PAPER, draw_text, init_headless
    from engine.render.chart import draw_legend

    TimeChart = time_chart_class()  # noqa: N806 - a class

    w = on["World"]
    seconds = w.seconds
    init_headless()
    surface = pygame.Surface(size)
    surface.fill(PAPER)
    draw_text(
        surface,
        f"A pyramid of {w.boxes:,} boxes (a base of {w.base}), the first {seconds:g} s",
        (20, 10),
        30,
    )
    draw_text(
        surface,
        "1 m, 1 kg, mu 0.6 (0.36 box on box), dt = 1/60 s; this engine beside pymunk "
        f"({ITERATIONS} iterations), the same boxes put down touching.",
        (20, 42),
        17,
        MUTED,
    )
    width, height = size
    margin, gap, top = 16, 12, 70
    names = [n for n in ENGINE_COLORS if n in on]
    legend_h = 86 + 24 * len(names)
    panel_w = (width - 2 * margin - gap) // 2
    panel_h = height - top - legend_h
    step = 10.0 if seconds > 20 else 1.0
    target = TARGETS.get(w.base)
    for k, (runs, title) in enumerate(((on, "sleeping on"), (off, "sleeping off"))):
        chart = TimeChart(
            (margin + k * (panel_w + gap), top, panel_w, panel_h),
            seconds,
            (-5, 0),
            f"Largest displacement of a box, {title}",
            "largest displacement (m)",
            step,
        )
        chart.draw_frame(surface)
        if target is not None:
            chart.level(surface, target[0], f"target: {_mm(target[0])}")
        # The fast path first and wider, as in the pit's picture: where both paths agree the
        # numpy path's line shows inside it.
        for name in (n for n in ("fast", "World", "pymunk") if n in runs):
            run = runs[name]
            chart.draw_line(
                surface, run.t, run.moved, ENGINE_COLORS[name], 6 if name == "fast" else 2
            )
    labels = {
        "World": "this engine (World, numpy)",
        "fast": "this engine (fast: compiled)",
        "pymunk": "pymunk 7",
    }
    items = [
        (
            f"{labels[n]}: {1e3 * on[n].first_step:.2f} ms a step over the first "
            f"{on[n].first:g} s; moved {_mm(on[n].moved_at(seconds))} by {seconds:g} s "
            f"(sleeping off: {_mm(off[n].moved_at(seconds))})",
            ENGINE_COLORS[n],
            3,
        )
        for n in names
    ]
    draw_legend(surface, items, (margin, height - legend_h + 34), width - 2 * margin)
    draw_text(
        surface,
        "Side by side in one run. A box that has not moved is drawn on the bottom line.",
        (margin, height - 36),
        17,
        MUTED,
    )
    assert isinstance(surface, pygame.Surface)
    return surface


#: Pyramid bases the report measures, its window (s) and rounds of the first seconds
#: (full run, quick run).
SIZES: dict[bool, tuple[tuple[int, float, int], ...]] = {
    False: ((20, SECONDS, 3), (40, SECONDS, 3)),
    True: ((20, 10.0, 1),),
}


def report(quick: bool = False, out: Path | None = None) -> str:
    """Run the pyramids, write their pictures into ``out``; return the text."""
    from engine.render import save_png

    folder = Path("out") / "bench" if out is None else Path(out)
    lines = [
        "stack: pyramids of boxes that turn (1 m, 1 kg, mu 0.6 by product with a floor of "
        f"1.0, e 0), put down touching, dt = 1/60 s, g {scene.G:g}; pymunk {ITERATIONS} "
        "iterations; side by side, each step timed by the wall clock (a shared machine: noisy)"
    ]
    for base, seconds, rounds in SIZES[quick]:
        on = side_by_side(base, seconds, sleep=True, rounds=rounds)
        off = side_by_side(base, seconds, sleep=False, rounds=rounds)
        lines.append(f"  ({rounds} round{'s' if rounds > 1 else ''} of the first {FIRST:g} s)")
        lines += summary(on, off)
        path = save_png(
            draw_stack(on, off), folder / f"stack_{on['World'].boxes}.png", overwrite=True
        )
        lines.append(f"    wrote {path}")
    if make_space(1) is None:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    return "\n".join(lines)
