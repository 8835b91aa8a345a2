"""The tumbler, against pymunk: 500 boxes in a room whose walls turn (issue "Bodies that turn").

Run with ``python -m demos.bench tumbler`` (``--quick``: 2 s). The scene is ``demos.stack``'s
tumbler, Box2D's sample (``shared/anchors/box2d``): 500 boxes of 0.25 m and 1/16 kg, friction
0.6 (by product, as pymunk: 0.6 on walls of 1.0, 0.36 box on box), restitution 0, in a square
grid at the middle of a room 19 m wide whose four walls, 1 m thick, are shapes of one
kinematic body turning at 25 degrees a second, as Box2D's benchmark turns it (here four
kinematic bodies about one point, a body having one shape; the demo's ``tumbler90`` turns at
90, a stress scene); g = 9.81 m/s^2, dt = 1/60 s, 20 s. pymunk 7 steps the same (one
kinematic body with four polygons) with its default 10 iterations; neither sleeps (the walls
keep every box moving).

The engines step side by side, one step each in turn (the order swapped every step). Reported
per engine: the mean wall-clock time a step over the first 2 s (the drop) and over the 20 s;
how many boxes ever had their centre past a wall's inner face (the target: none may end a step
inside a wall; at 90 degrees a second pymunk lost 93 by the end as first measured, and Box2D
v3, with shared/anchors/box2d, none at the end but up to 10 during the run; at 25, up to 3);
the deepest any box's corner went past a wall's inner face; the deepest any two boxes went
into each other at a step's end (``demos.stack.boxes_into_each_other``: the separating axes'
least overlap) and in how many steps that was past a tenth of a side (25 mm, issue "Rigid
bodies as Box2D's own tests expect"; Box2D v3 on the same scene, measured alike with its own
``b2CollidePolygons``: 217 mm at the deepest, 1,119 of the 1,200 steps past 25 mm). This World
runs the exact models on the numpy path ("World") and, where numba is installed, on the fast
path ("fast"), and there the soft step too ("soft", ``tumbler(solver="soft")``).

Targets: a step at most 3x pymunk's on the numpy path, 1x on the fast path.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from demos import stack as scene
from demos.bench.stack import add_boxes
from engine import kernels as engine_kernels

__all__ = ["SECONDS", "FIRST", "ITERATIONS", "make_space", "side_by_side", "report"]

DT = scene.DT  # s
SECONDS = 20.0  # s
FIRST = 2.0  # s: the drop
ITERATIONS = 10  # pymunk's default


def make_space(spin: float = scene.TUMBLE) -> tuple[Any, Any, list[Any]] | None:
    """The tumbler in pymunk, its walls turning at ``spin`` (rad/s): (space, the walls'
    kinematic body, the boxes), or None without pymunk."""
    try:
        import pymunk
    except ImportError:
        return None
    space = pymunk.Space()
    space.gravity = (0.0, -scene.G)
    space.iterations = ITERATIONS
    walls = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
    walls.angular_velocity = spin
    space.add(walls)
    for corners in scene.tumbler_walls():
        wall = pymunk.Poly(walls, corners)
        wall.friction = 1.0
        space.add(wall)
    boxes = add_boxes(space, scene.tumbler_centres(), scene.TUMBLED_SIDE, scene.TUMBLED_MASS)
    return space, walls, boxes


def _room(pos: np.ndarray, turn: np.ndarray, angle: float) -> tuple[np.ndarray, np.ndarray]:
    """Boxes at ``pos`` (n, 2) turned ``turn`` (n,) in a room turned ``angle`` (rad, about the
    origin): (which have their centre past a wall's inner face, how far each one's deepest
    corner is past one (m)), by ``demos.stack.room_frame``."""
    centre, deep = scene.room_frame(pos, turn, angle)
    return np.abs(centre).max(axis=1) > scene.ROOM, deep


def side_by_side(seconds: float = SECONDS, pymunk: bool = True) -> dict[str, dict[str, float]]:
    """Step each engine's tumbler for ``seconds``, side by side: engine -> {"first", "mean":
    s a step over the first FIRST s and over all; "lost": boxes whose centre ever passed a
    wall; "deepest": m the deepest corner went past one; "between": m the deepest two boxes
    went into each other at a step's end; "past": in how many steps that was past a tenth of
    a side}."""
    engine_kernels.prepare()  # compiled (or loaded from the cache) before the clock starts
    paths = {"World": ("numpy", "exact")}
    if engine_kernels.available():
        paths |= {"fast": ("fast", "exact"), "soft": ("fast", "soft")}
    sims: dict[str, tuple[Any, Any]] = {}
    for name, (path, solver) in paths.items():
        w, boxes, walls = scene.tumbler(kernels=path, solver=solver)

        def look(w: Any = w, boxes: Any = boxes, walls: Any = walls) -> tuple[Any, ...]:
            return w.positions()[len(walls) :], np.array([b.angle for b in boxes]), walls[0].angle

        sims[name] = (w.step, look)
    made = make_space() if pymunk else None
    if made is not None:
        space, body, bodies = made

        def look_pm(body: Any = body, bodies: Any = bodies) -> tuple[Any, ...]:
            pos = np.array([tuple(b.position) for b in bodies])
            return pos, np.array([b.angle for b in bodies]), body.angle

        sims["pymunk"] = (space.step, look_pm)
    names = list(sims)
    steps, head = round(seconds / DT), round(min(FIRST, seconds) / DT)
    times = {name: np.empty(steps) for name in names}
    lost = {name: np.zeros(len(scene.tumbler_centres()), dtype=bool) for name in names}
    deepest = dict.fromkeys(names, -math.inf)
    between = dict.fromkeys(names, -math.inf)
    past = dict.fromkeys(names, 0)
    perf = time.perf_counter
    for i in range(steps):
        for name in names if i % 2 == 0 else names[::-1]:
            t0 = perf()
            sims[name][0](DT)
            times[name][i] = perf() - t0
        for name in names:  # measured between the steps, not timed
            pos, turn, angle = sims[name][1]()
            out, deep = _room(pos, turn, angle)
            lost[name] |= out
            deepest[name] = max(deepest[name], float(deep.max()))
            into = scene.boxes_into_each_other(pos, turn)
            between[name] = max(between[name], into)
            past[name] += into > 0.1 * scene.TUMBLED_SIDE
    return {
        name: {
            "first": float(times[name][:head].mean()),
            "mean": float(times[name].mean()),
            "lost": float(lost[name].sum()),
            "deepest": deepest[name],
            "between": between[name],
            "past": float(past[name]),
        }
        for name in names
    }


def report(quick: bool = False) -> str:
    """Run the tumbler; return the text."""
    seconds = 2.0 if quick else SECONDS
    got = side_by_side(seconds)
    steps = round(seconds / DT)
    lines = [
        f"tumbler: {len(scene.tumbler_centres())} boxes of {scene.TUMBLED_SIDE:g} m, walls "
        f"turning {math.degrees(scene.TUMBLE):g} degrees/s, {seconds:g} s at dt = 1/60 s; "
        f"pymunk {ITERATIONS} iterations; side by side (a shared machine: noisy)",
        f"  {'engine':8} {'first 2 s':>10} {'ratio':>7} {'whole run':>10} {'ratio':>7} "
        f"{'centres past a wall':>20} {'deepest corner':>15} {'box into box':>13} "
        f"{'steps past 25 mm':>17}",
    ]
    peer = got.get("pymunk")
    for name, r in got.items():
        ratio_first = f"{r['first'] / peer['first']:.2f}x" if peer else "-"
        ratio_mean = f"{r['mean'] / peer['mean']:.2f}x" if peer else "-"
        lines.append(
            f"  {name:8} {1e3 * r['first']:8.3f} ms {ratio_first:>7} {1e3 * r['mean']:8.3f} ms "
            f"{ratio_mean:>7} {int(r['lost']):>20} {1e3 * r['deepest']:12.0f} mm "
            f"{1e3 * max(r['between'], 0.0):10.0f} mm {int(r['past']):>11} of {steps}"
        )
    if peer is None:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    lines.append(
        "  targets: no centre past a wall; a step at most 3x pymunk's (numpy), 1x (fast); no "
        "box more than 25 mm (a tenth of a side) into another (Box2D v3: 217 mm, 1,119 of "
        "1,200 steps past it, its anchor's run of 20 s)"
    )
    return "\n".join(lines)
