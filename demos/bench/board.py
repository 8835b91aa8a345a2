"""A small game board: one ball among round pegs, and what adding or removing a thing costs.

Run with ``python -m demos.bench board``. The board: ``pegs`` round pegs (``Circle``, r 0.15 m)
in staggered rows 1.2 m apart and 6 segments (floor, walls, ceiling and the two slants of a
funnel at the top), gravity 9.81 m/s^2, dt = 1/60 s; one ball (r 0.25 m, e 0.7) let go in
the funnel, bouncing down through the pegs. Two measurements, each side by side in one run
(one step of each candidate in turn, the order swapped every step; medians over the rounds):

* the small board (82 pegs and 6 segments): a step against the same World's step with no
  colliders at all (the ball falling freely), over the first 2 s of play, the ball among the
  pegs. Target: at most 5x.
* a change: on a board of 48 colliders (42 pegs) and of 1,000 (994 pegs), adding one collider
  (a peg) or one body (a ball), and taking it out again, each followed by a step, against a
  plain step of the same World. Target: the change and the step after it cost no more than
  two plain steps (the change no more than a step).
"""

from __future__ import annotations

import math
import statistics
import time
import warnings
from collections.abc import Callable
from functools import partial

from engine import Body, Circle, Segment, Vector, World, kernels
from engine.forces import Gravity

__all__ = [
    "DT",
    "SMALL_PEGS",
    "CHANGE_COLLIDERS",
    "make_board",
    "small_board",
    "changes",
    "report",
]

DT = 1.0 / 60.0  # s
G = 9.81  # m/s^2
SPACING = 1.2  # m between pegs, and between rows
PEG = 0.15  # m, a peg's radius
BALL = 0.25  # m, the ball's radius
SEGMENTS = 6
SMALL_PEGS = 82
#: The boards a change is measured on: colliders in all (pegs + 6 segments).
CHANGE_COLLIDERS = (48, 1_000)


def _size(pegs: int) -> tuple[int, int, float, float]:
    """(columns, rows, width m, height m) of a board of ``pegs`` pegs."""
    cols = max(9, round(math.sqrt(pegs)))
    rows = math.ceil(pegs / cols)
    return cols, rows, (cols + 1) * SPACING, (rows + 4) * SPACING


def make_board(
    pegs: int = SMALL_PEGS, *, colliders: bool = True, kernels: str | None = None
) -> tuple[World, Body]:
    """The board of ``pegs`` pegs and 6 segments (none with ``colliders=False``) and its ball,
    on the path ``kernels`` (None: the default, engine.kernels)."""
    cols, rows, w, h = _size(pegs)
    world = World(integrator="auto", kernels=kernels)
    world.add_force(Gravity((0.0, -G)))
    if colliders:
        placed = 0
        for j in range(rows):
            for i in range(cols):
                if placed < pegs:
                    x = SPACING * (i + 0.75 + 0.5 * (j % 2))
                    world.add_collider(Circle((x, SPACING * (j + 2)), PEG))
                    placed += 1
        for a, b in (
            ((0.0, 0.0), (w, 0.0)),
            ((0.0, 0.0), (0.0, h)),
            ((w, 0.0), (w, h)),
            ((0.0, h), (w, h)),
            ((0.0, h - 1.0), (w / 2 - 1.0, h - 2.5)),
            ((w, h - 1.0), (w / 2 + 1.0, h - 2.5)),
        ):
            world.add_collider(Segment(a, b))
    ball = world.add(
        Body(Vector(w / 2 + 0.1, h - 3.0), Vector(0.5, 0.0), radius=BALL, restitution=0.7)
    )
    return world, ball


def _timed(fn: Callable[[], object]) -> float:
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


def small_board(
    seconds: float = 2.0, rounds: int = 5, kernels: str | None = None
) -> dict[str, float]:
    """Seconds a step, the mean over the first ``seconds`` of play of each step's median over
    ``rounds`` fresh drops: "board" (82 pegs, 6 segments) and "bare" (the same World, no
    colliders); "ratio", board / bare; "typical", the same for the median step (the steps
    between bounces). ``kernels``: the Worlds' path."""
    steps = round(seconds / DT)
    per: dict[str, list[list[float]]] = {"board": [], "bare": []}
    for _ in range(rounds):
        worlds = {
            "board": make_board(kernels=kernels)[0],
            "bare": make_board(colliders=False, kernels=kernels)[0],
        }
        for world in worlds.values():
            world.step(DT)  # the first step builds what later ones reuse: not the steady state
        times: dict[str, list[float]] = {name: [] for name in worlds}
        names = list(worlds)
        for i in range(steps):
            for name in names if i % 2 == 0 else names[::-1]:
                times[name].append(_timed(partial(worlds[name].step, DT)))
        for name in names:
            per[name].append(times[name])
    medians = {
        name: [statistics.median(col) for col in zip(*rows, strict=True)]
        for name, rows in per.items()
    }
    out = {name: statistics.fmean(steps) for name, steps in medians.items()}
    out["ratio"] = out["board"] / out["bare"]
    out["typical"] = statistics.median(medians["board"]) / statistics.median(medians["bare"])
    return out


#: The changes measured, in the order they are made (each followed by a step).
CHANGES = ("add a collider", "remove it", "add a body", "remove it again")


def changes(
    colliders: int, cycles: int = 40, kernels: str | None = None
) -> dict[str, tuple[float, float, float]]:
    """On a board of ``colliders`` colliders (pegs + 6 segments), after 0.5 s of play: per
    cycle a plain step, then each change of CHANGES followed by two steps, all timed, on the
    path ``kernels``. The second step is the changed World's own plain step: a board with a
    second ball steps the pairs of bodies, which a board of one never enters, and that is not
    a cost of adding it.

    Returns "plain" -> (0, seconds a plain step, the same) and each change -> (seconds of
    the change's call, of the step after it, of the step after that), medians over the
    cycles.
    """
    world, _ = make_board(colliders - SEGMENTS, kernels=kernels)
    _, _, w, h = _size(colliders - SEGMENTS)
    for _ in range(30):
        world.step(DT)
    samples: dict[str, list[tuple[float, float, float]]] = {
        name: [] for name in ("plain", *CHANGES)
    }
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a ball that lands on the new peg is pushed off it
        for _ in range(cycles):
            step = partial(world.step, DT)
            plain = _timed(step)
            samples["plain"].append((0.0, plain, plain))
            peg = Circle((0.4, 0.8), 0.1)  # in the bottom corner, below the lattice
            ball = Body(Vector(0.6, h - 0.4), radius=BALL, restitution=0.7)  # by the ceiling
            made: tuple[Callable[[], object], ...] = (
                partial(world.add_collider, peg),
                partial(world.remove_collider, peg),
                partial(world.add, ball),
                partial(world.remove, ball),
            )
            for name, change in zip(CHANGES, made, strict=True):
                call = _timed(change)
                after = _timed(step)
                samples[name].append((call, after, _timed(step)))
    return {
        name: (
            statistics.median(c for c, _, _ in runs),
            statistics.median(a for _, a, _ in runs),
            statistics.median(n for _, _, n in runs),
        )
        for name, runs in samples.items()
    }


def _met(ok: bool) -> str:
    return "met" if ok else "NOT met"


def report(quick: bool = False) -> str:
    """Run both board measurements, on each path, and return their table as text."""
    kernels.prepare()  # compiled (or loaded from the cache) before the clock starts
    paths = ["numpy", "fast"] if kernels.available() else ["numpy"]
    lines = [
        f"board: one ball (r {BALL:g} m, e 0.7) among round pegs (r {PEG:g} m) and "
        f"{SEGMENTS} segments, dt = 1/60 s"
    ]
    for path in paths:
        small = small_board(seconds=1.0 if quick else 2.0, rounds=3 if quick else 7, kernels=path)
        lines.append(
            f"  {SMALL_PEGS} pegs ({path}): a step {small['board'] * 1e6:.0f} us against "
            f"{small['bare'] * 1e6:.1f} us for the same World with no colliders: "
            f"{small['ratio']:.1f}x (target <= 5x: {_met(small['ratio'] <= 5.0)}); the median "
            f"step (between bounces) {small['typical']:.1f}x"
        )
    for total, path in ((total, path) for total in CHANGE_COLLIDERS for path in paths):
        got = changes(total, cycles=10 if quick else 40, kernels=path)
        plain = got["plain"][1]
        lines.append(
            f"  {total:,} colliders ({path}): a plain step {plain * 1e6:.0f} us; each change, "
            "then the step after it (medians):"
        )
        for name in CHANGES:
            # The change and the step after it, less what the changed World's own step
            # costs beyond a plain one: in plain steps, 1 for a change that costs nothing.
            call, after, own = got[name]
            cost = (call + after - own + plain) / plain
            lines.append(
                f"    {name:<16} {call * 1e6:8.0f} us + step {after * 1e6:8.0f} us "
                f"(its own step {own * 1e6:5.0f} us) = {cost:6.1f} plain steps "
                f"(target <= 2: {_met(cost <= 2.0)})"
            )
    return "\n".join(lines)
