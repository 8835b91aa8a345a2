"""Queries benchmark: a segment query and a point query against pymunk's, on two scenes.

Run with ``python -m demos.bench queries``. A game's ground test, one 13 cm
``world.segment_query_first`` below a player's feet, cost 2.7 ms in a 20-body platformer when
every collider and body was tested (before engine.geometry.query_grid), where pymunk's costs 9 us.
Target: a query costs at most 10x pymunk's, on both paths (numpy and fast), on both scenes:

* the platformer (``make_platformer``): 20 bodies (the player, a box; crates; balls;
  capsules) and 20 static colliders (ground and walls as segments, platforms as polygon
  boxes, capsule slopes, thin ledges, a few polygons). The segment query is the ground
  test: 13 cm down from the player's feet, the player left out by its filter's group. The
  point query is a mouse pick (0.1 m) by a crate's corner.
* the pit (``demos.bench.contacts``' scene): 1,000 balls (r 0.1 m) in a 40 x 30 m box with
  50 segments, as made. The segment query is 13 cm down from a ball's bottom; the
  point query is a pick (0.1 m) at a ball's centre.

Each query is timed side by side with pymunk's on the same scene, in interleaved rounds,
each call on its own (``_medians``: the median of single calls, less the clock's own cost),
so the ratios hold on a shared, loaded machine. "after a move" is the segment query right
after one of our bodies moved by its ``pos`` (as after a step): the World then finds its
bodies anew (their cells are made again on the second query at the same positions;
``engine.geometry.query_grid``); pymunk's query is timed right after the same move, so both start
from the caches the move left. "same answer" checks that both engines met the same thing at
the same fraction.
"""

from __future__ import annotations

import gc
import math
import statistics
import time
from collections.abc import Callable
from functools import partial
from typing import Any

from demos.bench import contacts as pit
from engine import Body, Filter, Polygon, Segment, Vector, World, kernels

__all__ = [
    "PLAYER",
    "LOOK",
    "make_platformer",
    "platformer_space",
    "report",
]

#: The player's filter: the ground test leaves the player out by its group.
PLAYER = Filter(group=1)
#: How far the ground test looks below the feet (m).
LOOK = 0.13
_FEET = 0.9  # m, the player's half height (a box 0.8 x 1.8 m)

# The platformer's static colliders, in the order they are added (both engines):
# ("segment", a, b, radius): a thin wall (radius 0) or a capsule;
# ("box", width, height, centre): a solid polygon box;
# ("poly", vertices): a solid convex polygon.
_STATIC: list[tuple[Any, ...]] = [
    ("segment", (-20.0, 0.0), (20.0, 0.0), 0.0),  # the ground
    ("segment", (-20.0, 0.0), (-20.0, 15.0), 0.0),  # the walls
    ("segment", (20.0, 0.0), (20.0, 15.0), 0.0),
    ("box", 4.0, 0.5, (-12.0, 3.0)),  # platforms
    ("box", 4.0, 0.5, (-5.0, 5.5)),
    ("box", 3.0, 0.5, (3.0, 4.0)),
    ("box", 4.0, 0.5, (10.0, 6.5)),
    ("box", 2.0, 0.5, (15.0, 9.0)),
    ("box", 3.0, 0.5, (-15.0, 8.0)),
    ("segment", (5.0, 0.1), (9.0, 2.0), 0.1),  # capsule slopes
    ("segment", (-9.0, 2.0), (-6.0, 0.1), 0.1),
    ("segment", (12.0, 7.0), (14.0, 8.5), 0.1),
    ("segment", (-3.0, 8.0), (1.0, 9.0), 0.1),
    ("segment", (-19.0, 11.0), (-16.0, 11.0), 0.0),  # thin ledges
    ("segment", (16.0, 12.0), (19.0, 12.0), 0.0),
    ("segment", (-2.0, 12.0), (2.0, 12.0), 0.0),
    ("segment", (6.0, 10.0), (9.0, 10.0), 0.0),
    ("poly", [(-1.0, 0.0), (1.0, 0.0), (0.0, 1.0)]),  # a bump under the floor line
    ("poly", [(17.0, 0.0), (19.5, 0.0), (19.5, 2.5)]),  # a ramp in the corner
    ("poly", [(-18.0, 4.0), (-17.0, 3.5), (-16.0, 4.0), (-16.5, 5.0), (-17.5, 5.0)]),
]

# The platformer's bodies, in the order they are added, resting clear of everything:
# ("player", x, y), ("crate", x, y, size), ("ball", x, y, r), ("capsule", x, y, half length, r).
_BODIES: list[tuple[Any, ...]] = [
    ("player", -3.0, _FEET + 0.01),
    *[("crate", x, 3.26 + 0.5, 1.0) for x in (-13.0, -11.0)],
    *[("crate", x, 0.51, 1.0) for x in (-16.0, -14.5, 11.0, 13.0)],
    ("crate", 3.0, 4.25 + 0.41, 0.8),
    *[("ball", x, 0.31, 0.3) for x in (-18.0, -11.5, -4.5, 2.5, 4.0, 14.5)],
    ("ball", -5.0, 6.11, 0.3),
    ("ball", 10.0, 7.06, 0.3),
    *[("capsule", x, 0.26, 0.4, 0.25) for x in (-8.0, 10.0)],
    ("capsule", -12.5, 8.51, 0.4, 0.25),
    ("capsule", 15.0, 9.51, 0.4, 0.25),
]


def _feet(player: tuple[float, float]) -> tuple[tuple[float, float], tuple[float, float]]:
    """The ground test's segment: from just inside the player's feet, LOOK down."""
    x, y = player
    return (x, y - _FEET + 0.001), (x, y - _FEET - LOOK)


def make_platformer(kernels: str | None = None) -> tuple[World, Body]:
    """The platformer as a World on the path ``kernels`` (None: the default), and its player."""
    world = World(kernels=kernels)
    for kind, *args in _STATIC:
        if kind == "segment":
            world.add_collider(Segment(args[0], args[1], args[2]))
        elif kind == "box":
            world.add_collider(Polygon.box(args[0], args[1], center=args[2]))
        else:
            world.add_collider(Polygon(args[0]))
    player: Body | None = None
    for kind, x, y, *size in _BODIES:
        pos = Vector(x, y)
        if kind == "player":
            body = Body(pos, shape=Polygon.box(0.8, 2 * _FEET), filter=PLAYER, fixed_rotation=True)
            player = body
        elif kind == "crate":
            body = Body(pos, shape=Polygon.box(size[0], size[0]))
        elif kind == "ball":
            body = Body(pos, radius=size[0])
        else:
            half, r = size
            body = Body(pos, shape=Segment((-half, 0.0), (half, 0.0), r))
        world.add(body)
    assert player is not None
    return world, player


def platformer_space() -> tuple[Any, Any] | None:
    """The platformer in pymunk (None without pymunk), and its player's body."""
    try:
        import pymunk
    except ImportError:
        return None
    space = pymunk.Space()
    static = space.static_body
    for kind, *args in _STATIC:
        shape: Any
        if kind == "segment":
            shape = pymunk.Segment(static, args[0], args[1], args[2])
        elif kind == "box":
            (w, h), (cx, cy) = args[:2], args[2]
            corners = [(cx - w / 2, cy - h / 2), (cx + w / 2, cy - h / 2)]
            corners += [(cx + w / 2, cy + h / 2), (cx - w / 2, cy + h / 2)]
            shape = pymunk.Poly(static, corners)
        else:
            shape = pymunk.Poly(static, args[0])
        space.add(shape)
    player = None
    for kind, x, y, *size in _BODIES:
        body = pymunk.Body(1.0, 1.0)
        body.position = (x, y)
        if kind == "player":
            shape = pymunk.Poly.create_box(body, (0.8, 2 * _FEET))
            shape.filter = pymunk.ShapeFilter(group=1)
            player = body
        elif kind == "crate":
            shape = pymunk.Poly.create_box(body, (size[0], size[0]))
        elif kind == "ball":
            shape = pymunk.Circle(body, size[0])
        else:
            half, r = size
            shape = pymunk.Segment(body, (-half, 0.0), (half, 0.0), r)
        space.add(body, shape)
    return space, player


def _pit_pair(kernels_path: str, n: int = 1_000) -> tuple[World, Any]:
    """The pit (contacts' scene) on both engines, as made: the balls where both put them."""
    return pit.make_world(n, kernels=kernels_path), pit.make_space(n)


def _same(ours: Any, theirs: Any) -> str:
    """Whether both engines' first hits agree: both none, or both at the same fraction."""
    if ours is None or theirs is None:
        return "yes" if ours is None and theirs is None else "NO"
    return "yes" if math.isclose(ours.fraction, theirs.alpha, abs_tol=1e-6) else "NO"


def _met(ok: bool) -> str:
    return "met" if ok else "NOT met"


def _medians(
    candidates: dict[str, Callable[[], object]],
    rounds: int,
    calls: int,
    before: dict[str, Callable[[], object]] | None = None,
) -> dict[str, float]:
    """Median seconds of one call of each candidate, each call timed on its own, in
    interleaved rounds of ``calls`` calls each, less the clock's own median (an empty
    call's). ``before``: an untimed call made before each timed one (a move).

    Single calls, not batches: on a shared machine a batch long enough to be preempted
    (a few milliseconds) counts another process's time slice against whichever candidate is
    slower, while the median of single calls is what a call costs."""
    clock = time.perf_counter
    samples: dict[str, list[float]] = {name: [] for name in (*candidates, "clock")}
    nothing = tuple  # a C call of no work, for the clock's own cost
    enabled = gc.isenabled()
    gc.disable()  # as timeit does
    try:
        for fn in candidates.values():
            fn()  # warm up: first-call costs are not the steady state
        for _ in range(rounds):
            for name, fn in (*candidates.items(), ("clock", nothing)):
                first = (before or {}).get(name)
                out = samples[name]
                for _ in range(calls):
                    if first is not None:
                        first()
                    t = clock()
                    fn()
                    out.append(clock() - t)
    finally:
        if enabled:
            gc.enable()
    zero = statistics.median(samples.pop("clock"))
    return {name: statistics.median(times) - zero for name, times in samples.items()}


def _mover(body: Body) -> Callable[[], None]:
    """A call that moves ``body`` 1 mm there and back, by its ``pos``: the World's bins of
    its bodies are then stale, as after a step."""
    here = body.pos
    there = here + Vector(0.001, 0.0)
    flip = [False]

    def move() -> None:
        flip[0] = not flip[0]
        body.pos = there if flip[0] else here

    return move


def report(quick: bool = False) -> str:
    """Time both queries on both scenes, both paths, against pymunk, and return the table."""
    import pymunk

    kernels.prepare()  # compiled (or loaded from the cache) before the clock starts
    paths = ["numpy", "fast"] if kernels.available() else ["numpy"]
    rounds = 7 if quick else 21
    calls = 50 if quick else 200
    lines = [
        f"queries: a {LOOK * 100:.0f} cm segment_query_first down from a player's feet (or a "
        "ball's bottom), and a point_query (0.1 m), against pymunk's",
        f"  (medians of single calls, {rounds} interleaved rounds of {calls} each; 'after a "
        "move': the segment query just after a body of ours moved, as after a step, when the "
        "World finds its bodies anew, against pymunk's just after the same move)",
    ]
    any_filter = pymunk.ShapeFilter()
    feet_filter = pymunk.ShapeFilter(group=1)
    got = platformer_space()
    assert got is not None
    space, _ = got
    for path in paths:
        world, player = make_platformer(kernels=path)
        a, b = _feet((player.pos.x, player.pos.y))
        crate = world.bodies[1].pos
        pick = (crate.x + 0.55, crate.y + 0.55)  # just off a crate's corner
        ours_first = world.segment_query_first(a, b, 0.0, PLAYER)
        theirs_first = space.segment_query_first(a, b, 0.0, feet_filter)
        ours = partial(world.segment_query_first, a, b, 0.0, PLAYER)
        theirs = partial(space.segment_query_first, a, b, 0.0, feet_filter)
        times = _medians(
            {
                "segment": ours,
                "pymunk segment": theirs,
                "point": partial(world.point_query, pick, 0.1),
                "pymunk point": partial(space.point_query, pick, 0.1, any_filter),
                "after a move": ours,
                "pymunk after a move": theirs,
            },
            rounds,
            calls,
            before={
                "after a move": _mover(world.bodies[-5]),
                "pymunk after a move": _mover(world.bodies[-5]),
            },
        )
        lines.append(
            f"  platformer ({len(world.bodies)} bodies, {len(world.colliders)} colliders, "
            f"{path}): same answer {_same(ours_first, theirs_first)}"
        )
        lines += _rows(times)
    for path in paths:
        world, pit_space = _pit_pair(path)
        assert pit_space is not None
        k = len(world.bodies) // 2
        ball = world.bodies[k].pos
        a, b = (ball.x, ball.y - pit.RADIUS - 0.001), (ball.x, ball.y - pit.RADIUS - LOOK)
        centre = (ball.x, ball.y)
        ours_first = world.segment_query_first(a, b)
        theirs_first = pit_space.segment_query_first(a, b, 0.0, any_filter)
        ours = partial(world.segment_query_first, a, b)
        theirs = partial(pit_space.segment_query_first, a, b, 0.0, any_filter)
        times = _medians(
            {
                "segment": ours,
                "pymunk segment": theirs,
                "point": partial(world.point_query, centre, 0.1),
                "pymunk point": partial(pit_space.point_query, centre, 0.1, any_filter),
                "after a move": ours,
                "pymunk after a move": theirs,
            },
            rounds,
            calls,
            before={
                "after a move": _mover(world.bodies[0]),
                "pymunk after a move": _mover(world.bodies[0]),
            },
        )
        lines.append(
            f"  pit ({len(world.bodies):,} balls, {len(world.colliders)} colliders, {path}): "
            f"same answer {_same(ours_first, theirs_first)}"
        )
        lines += _rows(times)
    return "\n".join(lines)


def _rows(times: dict[str, float]) -> list[str]:
    out = []
    rows = [
        ("segment_query", times["segment"], times["pymunk segment"]),
        ("point_query", times["point"], times["pymunk point"]),
        ("after a move", times["after a move"], times["pymunk after a move"]),
    ]
    for name, ours, theirs in rows:
        ratio = ours / theirs
        out.append(
            f"    {name:<14} {ours * 1e6:8.1f} us, pymunk {theirs * 1e6:6.1f} us: {ratio:6.1f}x "
            f"(target <= 10x: {_met(ratio <= 10.0)})"
        )
    return out
