"""Throughput: cost per body-step against the number of bodies, every way of stepping side by side.

Semi-implicit Euler under gravity, dt = 1/60 s, for 10 to 10^6 bodies, measured in one run
in interleaved rounds (``demos.bench.compare``), as medians:

* ``World``: ``World.step`` on N bodies (numpy arrays, one integrator call);
* ``Particles``: ``engine.particles.Particles.step`` (in-place structure of arrays);
* ``lesson Body``: the lesson's loop, each ``Body`` (holding ``Vector``s) stepping itself;
* ``pymunk``: ``pymunk.Space.step`` with N free bodies, where pymunk is installed;
* ``pygame Vector2``: the same loop on ``pygame.math.Vector2``, where pygame is installed.

Python loops and pymunk stop at 10^5 bodies: a step of 10^6 of them takes about a second and
tells nothing new, the cost per body being flat by then. ``quick`` measures 10 to 10^3 bodies
(making 10^4 of them, in Python, would take most of its time).

    python -c "from demos.bench.throughput import report; print(report(quick=True))"
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from demos.bench import compare
from demos.bench.core import DT, G, lesson_step, pymunk_step, start_state, vector2_step, world_step
from engine.forces import Gravity

__all__ = ["IMPLEMENTATIONS", "Row", "measure", "report", "table"]


#: The ways of stepping compared, in the order they are listed.
IMPLEMENTATIONS: tuple[str, ...] = (
    "World",
    "Particles",
    "lesson Body",
    "pymunk",
    "pygame Vector2",
)


@dataclass(frozen=True)
class Row:
    """One measurement: ``implementation`` stepping ``bodies`` bodies, ``ns`` per body-step."""

    implementation: str
    bodies: int
    ns: float  # nanoseconds per body per step (median)


def _particles(n: int) -> Callable[[], object] | None:
    try:
        from engine.particles import Particles
    except ImportError:
        return None
    pos, vel = start_state(n)
    sparks = Particles(n, dt=DT, forces=[Gravity(G)])
    sparks.emit(n, pos, vel)  # lifetime inf: none expire
    return sparks.step


_MAKERS: dict[str, Callable[[int], Callable[[], object] | None]] = {
    "World": partial(world_step, drag=False),
    "Particles": _particles,
    "lesson Body": lesson_step,
    "pymunk": partial(pymunk_step, drag=False),
    "pygame Vector2": vector2_step,
}
_LOOPS = frozenset({"lesson Body", "pymunk", "pygame Vector2"})


def measure(quick: bool = False) -> list[Row]:
    """Measure every available implementation at every size; rows in IMPLEMENTATIONS order."""
    top = 3 if quick else 6
    sizes = [10**k for k in range(1, top + 1)]
    loop_top = 10**3 if quick else 10**5
    rounds = 5 if quick else 9
    budget = 20_000 if quick else 200_000  # body-steps per timed batch
    rows: list[Row] = []
    for n in sizes:
        candidates: dict[str, tuple[Callable[[], object], int]] = {}
        for name, make in _MAKERS.items():
            if name in _LOOPS and n > loop_top:
                continue
            fn = make(n)
            if fn is not None:
                candidates[name] = (fn, max(1, budget // n))
        times = compare(candidates, rounds=rounds if n < 10**6 else 3)
        rows += [Row(name, n, times[name] / n * 1e9) for name in candidates]
    order = {name: i for i, name in enumerate(IMPLEMENTATIONS)}
    return sorted(rows, key=lambda r: (order[r.implementation], r.bodies))


def _lookup(rows: list[Row], name: str, n: int) -> float | None:
    return next((r.ns for r in rows if r.implementation == name and r.bodies == n), None)


def table(rows: list[Row]) -> str:
    """The rows as a text table (ns per body-step) with the two headline ratios."""
    names = [name for name in IMPLEMENTATIONS if any(r.implementation == name for r in rows)]
    sizes = sorted({r.bodies for r in rows})
    lines = [
        "throughput: semi-implicit Euler under gravity, ns per body-step (median, interleaved)",
        "  " + f"{'bodies':>9}" + "".join(f"{name:>16}" for name in names),
    ]
    for n in sizes:
        cells = []
        for name in names:
            ns = _lookup(rows, name, n)
            cells.append(f"{'-':>16}" if ns is None else f"{ns:16.1f}")
        lines.append("  " + f"{n:>9,}" + "".join(cells))
    world, pm = _lookup(rows, "World", 1000), _lookup(rows, "pymunk", 1000)
    if world is not None and pm is not None:
        lines.append(f"  World / pymunk at 1,000 bodies: {world / pm:.2f}x (target <= 0.5x)")
    else:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    lesson, v2 = _lookup(rows, "lesson Body", 1000), _lookup(rows, "pygame Vector2", 1000)
    if lesson is not None and v2 is not None:
        lines.append(
            f"  lesson Body.step / pygame Vector2 at 1,000 bodies: {lesson / v2:.2f}x "
            "(target <= 3x)"
        )
    return "\n".join(lines)


def report(quick: bool = False) -> str:
    """Run the throughput benchmark and return its table as text."""
    return table(measure(quick))
