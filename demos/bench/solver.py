"""The contact solver's settings: error against cost per iteration count, this engine and pymunk.

Run with ``python -m demos.bench solver``; ``python -m demos tradeoff`` draws the rows as the
contacts chart (``out/tradeoff/contacts.png``). Two scenes of issue "Contacts II" and two of
"Bodies that turn", dt = 1/60 s:

* ``pit``: 240 balls (r 0.5 m, e 0.5, mu 0.5) dropped in rows into a box 14 m wide
  (``demos.bench.pit`` at that width), settled for 4 s. Error: the deepest overlap of two
  balls at the end, as a fraction of the radius. Energy: the kinetic energy left at the end
  over the potential energy (a pile at rest has none).
* ``cradle``: Newton's cradle, 5 touching balls (r 0.5 m, e = 1, no friction) lying on a
  frictionless floor under gravity, the first sent in at 2 m/s from 0.2 m away. The floor's
  restitution is 0 (it only holds the balls up: on an elastic floor pymunk's balls hop at
  g dt, a contact at rest bounced every step, which would hide the cradle's own error). After the
  impacts the last ball must roll on at 2 m/s and the others stand still. Error: the largest
  (|v_last - v0| + the other balls' speeds) / v0 over t = 0.5 to 1 s (vertical speeds count:
  a ball hopping on the floor is wrong too). Energy: the largest |KE - KE0| / KE0 over the
  same time (the collisions are elastic: kinetic energy must come through unchanged).
* ``stack``: a tower of 10 boxes (``demos.stack.tower``: 1 m, 1 kg, friction 0.6, put down
  touching on a floor, sleeping off), run 5 s; ``pyramid``: the pyramid of 210 boxes (a base of
  20, ``demos.bench.stack.make_world``), the same. Error: the drift, the largest displacement
  of any box from where it was put after 5 s (m; the targets, 1 mm for the tower's top
  and 1 cm for the pyramid, are over 60 s). Energy: KE (linear and turning) / PE left at the
  end. pymunk's twins are ``demos.bench.stack.space_of`` at the same centres. A 5 s window
  keeps the run short: the pyramid's drift has settled by 2 s, the tower's still creeps.

Solvers, each at several iteration counts:

* ``World``: this engine, ``World.contact_iterations`` 1, 2, 4 (the default), 8, 16: the
  substeps of its soft step (``engine.exact.soft``), each one pass of the contacts and one of
  relaxing;
* ``pymunk``: ``Space.iterations`` 1, 2, 5, 10 (its default), 20, 40, with its default
  ``collision_slop`` of 0.1 m (it leaves overlaps up to that alone: 20% of these radii);
* ``pymunk 1 mm``: the same with ``collision_slop`` = 1 mm, the overlap this engine leaves
  alone (``engine.exact.collisions.SLOP``, 0.2% of the radius), so that the solvers are compared at
  the same tolerance.

Cost: seconds of CPU time per step, timed step by step with every setting of a scene stepping in
turn (the order rotating from step to step), so that a burst of load on a shared machine hits
them alike; each step's time is the median over ``rounds`` runs, and the cost is the mean over
the steps of the timed window; the stacks' window is their whole 5 s (sleeping off: every step
awake), after a few untimed steps that let numba compile or load the boxes' kernels.
CPU time (``time.process_time``), not wall-clock time: on a
machine with more running programs than cores, a step is paused whenever the scheduler runs
another program, so wall-clock time charges a 10 ms step for far more of the others' work than
a 10 us step (measured here: this engine's pit looked 100x pymunk's by the wall clock, 45x by
CPU time, at a load of 7 on 2 cores).

This engine puts a pile that has been still for 0.5 s to sleep, after which a step costs
almost nothing; the cost counted is that of awake steps, the honest measure of the solver: the
pit's window is its first 2 s (the balls fall and pile up; every setting is awake throughout,
and a step in which a World's bodies all sleep would not be counted), the cradle's its whole
1 s.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import numpy as np

from demos import stack
from demos.bench import pit
from demos.bench import stack as stack_bench
from engine import Body, Plane, StabilityWarning, Vector, World
from engine.forces import Gravity

__all__ = [
    "SOLVERS",
    "ITERATIONS",
    "QUICK_ITERATIONS",
    "QUICK_STACK_TIME",
    "SCENES",
    "Row",
    "measure",
    "cradle_error",
    "csv_header",
    "csv_row",
    "table",
    "report",
]

DT = 1.0 / 60.0  # s
G = 9.81  # m/s^2

#: The solvers compared, in the order they are drawn and listed.
SOLVERS: tuple[str, ...] = ("World", "pymunk", "pymunk 1 mm")
#: Iteration counts measured per solver (the full run).
ITERATIONS: dict[str, tuple[int, ...]] = {
    "World": (1, 2, 4, 8, 16),
    "pymunk": (1, 2, 5, 10, 20, 40),
    "pymunk 1 mm": (1, 2, 5, 10, 20, 40),
}
#: The quick run's: each solver's default and one that is too few.
QUICK_ITERATIONS: dict[str, tuple[int, ...]] = {
    "World": (1, 4),
    "pymunk": (1, 10),
    "pymunk 1 mm": (1, 10),
}
#: pymunk's collision_slop (m) per solver; None keeps pymunk's default (0.1).
_SLOP: dict[str, float | None] = {"pymunk": None, "pymunk 1 mm": 1e-3}

#: Scene name -> title.
SCENES: dict[str, str] = {
    "pit": "Ball pit",
    "cradle": "Newton's cradle",
    "stack": "Tower of boxes",
    "pyramid": "Pyramid of boxes",
}

# The pit: 240 balls, 12 a row, in a box 14 m wide; settled 4 s, timed over the first 2 s.
PIT_BALLS = 240
PIT_WIDTH = 14.0  # m
PIT_SETTLE = 4.0  # s
PIT_WINDOW = 2.0  # s
# The cradle: 5 balls, the first in at V0 from GAP away; run 1 s, judged from JUDGE on.
CRADLE_BALLS = 5
V0 = 2.0  # m/s
GAP = 0.2  # m
RADIUS = 0.5  # m
CRADLE_TIME = 1.0  # s
JUDGE = 0.5  # s
# The stacks (demos.stack): a tower of TOWER boxes, a pyramid of base PYRAMID_BASE, sleeping
# off, run and timed over STACK_TIME (the quick run's: QUICK_STACK_TIME).
TOWER = 10
PYRAMID_BASE = 20
PYRAMID_BOXES = PYRAMID_BASE * (PYRAMID_BASE + 1) // 2  # 210
STACK_TIME = 5.0  # s
#: The quick run's window for the stacks: by 2 s the pyramid's drift has settled and one
#: iteration has let the tower walk (pymunk's falls), at 2/5 of the full run's cost.
QUICK_STACK_TIME = 2.0  # s
#: The scenes of boxes (their error is a drift in m, their window the whole run).
_STACKS = ("stack", "pyramid")


@dataclass(frozen=True)
class Row:
    """One setting measured on one scene; a row of the CSV."""

    scene: str  # one of SCENES
    solver: str  # one of SOLVERS
    iterations: int
    error: float  # pit: deepest overlap / radius at rest; cradle: speed error / v0; stack,
    # pyramid: the largest displacement of a box from where it was put (m)
    energy: float  # pit, stack, pyramid: KE / PE left at the end; cradle: max |KE - KE0| / KE0
    cost: float  # CPU s per awake step (median over rounds, mean over the timed window)
    warned: bool  # the World warned (StabilityWarning: too few contact_iterations)
    asleep: int  # bodies asleep at the end (this engine's; pymunk's sleep is off)
    steps: int  # steps in the timed window


@dataclass
class _Sim:
    """A scene in one solver: ``step()`` advances dt, ``state()`` is (x, v) as arrays."""

    step: Callable[[], object]
    state: Callable[[], tuple[np.ndarray, np.ndarray]]
    asleep: Callable[[], int] = lambda: 0
    bodies: int = 0
    spin: Callable[[], float] = lambda: 0.0  # rotational kinetic energy (J)
    warned: bool = False
    samples: list[float] = field(default_factory=list)


def _world_sim(world: World) -> _Sim:
    def spin() -> float:
        return sum(0.5 * b.moment * b.angular_velocity**2 for b in world.bodies)

    return _Sim(
        partial(world.step, DT),
        lambda: (world.positions(), world.velocities()),
        lambda: world.sleeping,
        len(world.bodies),
        spin,
    )


def _space_sim(space: Any, bodies: Sequence[Any]) -> _Sim:
    def state() -> tuple[np.ndarray, np.ndarray]:
        return (
            np.array([tuple(b.position) for b in bodies]),
            np.array([tuple(b.velocity) for b in bodies]),
        )

    def spin() -> float:
        return sum(0.5 * b.moment * b.angular_velocity**2 for b in bodies)

    return _Sim(partial(space.step, DT), state, bodies=len(bodies), spin=spin)


def _pit(solver: str, iterations: int) -> _Sim:
    if solver == "World":
        return _world_sim(pit.make_world(PIT_BALLS, iterations, width=PIT_WIDTH))
    space: Any = pit.make_space(PIT_BALLS, iterations, width=PIT_WIDTH, slop=_SLOP[solver])
    return _space_sim(space, [b for b in space.bodies])


def _boxes(scene: str, solver: str, iterations: int) -> _Sim:
    """The tower (``scene`` "stack") or the pyramid of ``demos.stack``, sleeping off."""
    if solver == "World":
        if scene == "stack":
            world, _ = stack.tower(TOWER, solver="exact")
        else:
            world, _ = stack_bench.make_world(PYRAMID_BASE, sleep=False)
        world.contact_iterations = iterations
        return _world_sim(world)
    centres = (
        stack.tower_centres(TOWER) if scene == "stack" else stack.pyramid_centres(PYRAMID_BASE)
    )
    made = stack_bench.space_of(centres, iterations, sleep=False, slop=_SLOP[solver])
    assert made is not None  # pymunk's settings are measured only where it is installed
    return _space_sim(*made)


def stack_energy(x: np.ndarray, v: np.ndarray, spin: float) -> float:
    """Kinetic energy (linear, of 1 kg boxes, and ``spin``) over the potential energy above
    the floor, for centres ``x`` and velocities ``v`` (n, 2).

    >>> stack_energy(np.array([[0.0, 0.5]]), np.array([[0.0, 0.0]]), 0.0)
    0.0
    """
    ke = 0.5 * stack.MASS * float((v * v).sum()) + spin
    return ke / (stack.MASS * G * float(x[:, 1].sum()))


def _cradle_x() -> list[float]:
    """Start x (m) of the balls: the others touching in a row from 0, the first GAP short."""
    return [-(2 * RADIUS + GAP)] + [2 * RADIUS * k for k in range(CRADLE_BALLS - 1)]


def _cradle(solver: str, iterations: int) -> _Sim:
    if solver == "World":
        world = World(integrator="auto")
        world.contact_iterations = iterations
        world.add_force(Gravity((0.0, -G)))
        world.add_collider(Plane((0.0, -RADIUS), (0.0, 1.0), restitution=0.0, friction=0.0))
        for k, x in enumerate(_cradle_x()):
            v = Vector(V0 if k == 0 else 0.0, 0.0)
            world.add(
                Body(Vector(x, 0.0), v, Vector(0, 0), radius=RADIUS, restitution=1.0, friction=0.0)
            )
        return _world_sim(world)
    import pymunk

    space = pymunk.Space()
    space.gravity = (0.0, -G)
    space.iterations = iterations
    slop = _SLOP[solver]
    if slop is not None:
        space.collision_slop = slop
    floor = pymunk.Segment(space.static_body, (-10.0, -RADIUS), (20.0, -RADIUS), 0.0)
    floor.elasticity, floor.friction = 0.0, 0.0  # products with the balls': e = 0, mu = 0
    space.add(floor)
    bodies = []
    for k, x in enumerate(_cradle_x()):
        body = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0.0, RADIUS))
        body.position = (x, 0.0)
        body.velocity = (V0 if k == 0 else 0.0, 0.0)
        ball = pymunk.Circle(body, RADIUS)
        ball.elasticity, ball.friction = 1.0, 0.0
        space.add(body, ball)
        bodies.append(body)
    return _space_sim(space, bodies)


def cradle_error(v: np.ndarray, v0: float = V0) -> float:
    """(|v_last - (v0, 0)| + the other balls' speeds) / v0 for velocities ``v`` (n, 2).

    >>> cradle_error(np.array([[0.0, 0.0], [0.0, 0.0], [2.0, 0.0]]))
    0.0
    >>> cradle_error(np.array([[0.4, 0.0], [0.8, 0.0], [0.8, 0.0]]))  # spread over the row
    1.2
    """
    v = np.asarray(v, dtype=float)
    last = math.hypot(v[-1, 0] - v0, v[-1, 1])
    others = float(np.hypot(v[:-1, 0], v[:-1, 1]).sum())
    return (last + others) / v0


#: The clock of the timings: CPU time of this process (see the module's docstring).
_CLOCK = time.process_time


def _timer_overhead() -> float:
    """The time (s) two back-to-back calls of the clock report: taken off each sample."""
    clock = _CLOCK
    samples = []
    for _ in range(201):
        t = clock()
        samples.append(clock() - t)
    return float(np.median(samples))


def _step_all(sims: dict[tuple[str, int], _Sim], i: int, timed: bool, overhead: float) -> None:
    """Step every sim once, in an order rotated by i; time the step of each awake one."""
    keys = list(sims)
    shift = i % len(keys)
    clock = _CLOCK
    for key in keys[shift:] + keys[:shift]:
        sim = sims[key]
        awake = sim.asleep() < sim.bodies
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            t = clock()
            sim.step()
            elapsed = clock() - t
        if any(issubclass(w.category, StabilityWarning) for w in caught):
            sim.warned = True
        if timed:
            sim.samples.append(max(elapsed - overhead, 0.0) if awake else math.nan)


def _run(
    scene: str,
    settings: Sequence[tuple[str, int]],
    rounds: int,
    progress: Callable[[int, int], None] | None,
    done: list[int],
    total: int,
    stack_time: float = STACK_TIME,
) -> list[Row]:
    make: Callable[[str, int], _Sim]
    if scene in _STACKS:
        make = partial(_boxes, scene)
        _warm(make("World", 1))  # numba compiles the boxes' kernels (or loads them) untimed
    else:
        make = _pit if scene == "pit" else _cradle
    steps, window = _steps(scene, stack_time)
    judge = round(JUDGE / DT)
    overhead = _timer_overhead()
    per_round: dict[tuple[str, int], list[list[float]]] = {key: [] for key in settings}
    worst: dict[tuple[str, int], tuple[float, float]] = {}
    sims: dict[tuple[str, int], _Sim] = {}
    ke0 = 0.5 * V0 * V0
    for r in range(rounds):
        last = r == rounds - 1
        sims = {key: make(*key) for key in settings}
        start = {key: sim.state()[0].copy() for key, sim in sims.items()}
        worst = {key: (0.0, 0.0) for key in settings}
        for i in range(steps if last else window):
            _step_all(sims, i, i < window, overhead)
            done[0] += 1
            if progress is not None:
                progress(done[0], total)
            if scene == "cradle" and i + 1 >= judge:
                for key, sim in sims.items():
                    v = sim.state()[1]
                    ke = 0.5 * float((v * v).sum())
                    err, en = worst[key]
                    worst[key] = (max(err, cradle_error(v)), max(en, abs(ke - ke0) / ke0))
        for key, sim in sims.items():
            per_round[key].append(sim.samples)
    rows = []
    for key, sim in sims.items():
        times = np.array(per_round[key], dtype=float)  # (rounds, window)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # a step asleep in every round
            per_step = np.nanmedian(times, axis=0)
        awake = per_step[np.isfinite(per_step)]
        cost = float(awake.mean()) if len(awake) else math.nan
        if scene == "pit":
            x, v = sim.state()
            error, _, energy = pit.measures(x, v, PIT_WIDTH)
        elif scene in _STACKS:
            x, v = sim.state()
            error = float(np.hypot(*(x - start[key]).T).max())
            energy = stack_energy(x, v, sim.spin())
        else:
            error, energy = worst[key]
        rows.append(
            Row(scene, key[0], key[1], error, energy, cost, sim.warned, sim.asleep(), len(awake))
        )
    return rows


def _warm(sim: _Sim, steps: int = 30) -> None:
    """Step ``sim`` a few times untimed, its warnings dropped."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for _ in range(steps):
            sim.step()


def _steps(scene: str, stack_time: float = STACK_TIME) -> tuple[int, int]:
    """(steps of a scene's run, steps of its timed window); the stacks run ``stack_time`` s."""
    if scene in _STACKS:
        steps = round(stack_time / DT)
        return steps, steps
    steps = round((PIT_SETTLE if scene == "pit" else CRADLE_TIME) / DT)
    return steps, round(PIT_WINDOW / DT) if scene == "pit" else steps


def _has_pymunk() -> bool:
    try:
        import pymunk  # noqa: F401
    except ImportError:
        return False
    return True


def measure(
    quick: bool = False,
    *,
    rounds: int | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> list[Row]:
    """Measure every solver setting on every scene; rows by scene, solver, iterations.

    pymunk's rows are left out where pymunk is not installed. ``rounds``: runs whose step
    times are combined (default 2, quick 1 for the pit and the stacks; 9, quick 1 for the
    cradle). ``quick`` runs the stacks for QUICK_STACK_TIME, not STACK_TIME.
    """
    counts = QUICK_ITERATIONS if quick else ITERATIONS
    solvers = [s for s in SOLVERS if s == "World" or _has_pymunk()]
    settings = [(s, k) for s in solvers for k in counts[s]]
    pit_rounds = rounds or (1 if quick else 2)
    cradle_rounds = rounds or (1 if quick else 9)
    plan = [("pit", pit_rounds), ("cradle", cradle_rounds)]
    plan += [(scene, pit_rounds) for scene in _STACKS]
    stack_time = QUICK_STACK_TIME if quick else STACK_TIME
    total = 0
    for scene, n in plan:
        steps, window = _steps(scene, stack_time)
        total += (n - 1) * window + steps
    done = [0]
    rows = []
    for scene, n in plan:
        rows += _run(scene, settings, n, progress, done, total, stack_time)
    return rows


_CSV_FIELDS = (
    "scene",
    "solver",
    "iterations",
    "error",
    "energy",
    "cost_s_per_step",
    "warned",
    "asleep",
    "timed_steps",
)


def csv_header() -> str:
    """The CSV's header line (no newline)."""
    return ",".join(_CSV_FIELDS)


def csv_row(r: Row) -> str:
    """One CSV line for ``r`` (no newline); errors with 17 significant digits."""
    return ",".join(
        (
            r.scene,
            r.solver,
            str(r.iterations),
            f"{r.error:.17g}",
            f"{r.energy:.17g}",
            f"{r.cost:.6g}",
            str(int(r.warned)),
            str(r.asleep),
            str(r.steps),
        )
    )


def table(rows: Sequence[Row]) -> str:
    """The rows as a text table, one block per scene."""
    lines = []
    for scene, title in SCENES.items():
        mine = [r for r in rows if r.scene == scene]
        if not mine:
            continue
        if scene == "pit":
            head = (
                f"{title}: {PIT_BALLS} balls in a box {PIT_WIDTH:g} m wide, dt = 1/60 s, error = "
                f"deepest overlap / r after {PIT_SETTLE:g} s, energy = KE / PE left; cost per "
                f"awake step over the first {PIT_WINDOW:g} s"
            )
        elif scene in _STACKS:
            what = f"{TOWER} boxes" if scene == "stack" else f"{PYRAMID_BOXES} boxes"
            seconds = max(r.steps for r in mine) * DT  # sleeping off: every step is timed
            head = (
                f"{title}: {what} of 1 m, 1 kg, mu 0.6, sleeping off, dt = 1/60 s; error = "
                f"the largest displacement of a box from where it was put after {seconds:g} s "
                f"(m), energy = KE / PE left; cost per step over the {seconds:g} s"
            )
        else:
            head = (
                f"{title}: {CRADLE_BALLS} balls, e = 1, first in at {V0:g} m/s; error = "
                f"(|v_last - v0| + others' speeds) / v0, energy = |KE - KE0| / KE0 (largest over "
                f"{JUDGE:g} to {CRADLE_TIME:g} s); cost per step over {CRADLE_TIME:g} s"
            )
        lines.append(head)
        lines.append(
            f"  {'solver':<12} {'iterations':>10} {'error':>10} {'energy':>10} "
            f"{'ms a step':>10}  notes"
        )
        for r in mine:
            notes = []
            if r.warned:
                notes.append("warned")
            if r.asleep:
                notes.append(f"{r.asleep} asleep at the end")
            lines.append(
                f"  {r.solver:<12} {r.iterations:>10} {r.error:>10.3g} {r.energy:>10.3g} "
                f"{r.cost * 1e3:>10.4f}  {', '.join(notes)}"
            )
    if not any(r.solver != "World" for r in rows):
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    return "\n".join(lines)


def report(quick: bool = False) -> str:
    """Run the measurements and return their table as text."""
    return table(measure(quick))
