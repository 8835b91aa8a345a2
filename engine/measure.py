"""Speed against accuracy, measured: test problems with exact answers, error and cost per method.

Three problems whose exact solutions are known in closed form (each runs for
``duration`` = 1 s, the horizon over which a World's ``tolerance`` is promised):

* ``gravity``: a ball thrown under constant gravity, x(t) = x0 + v0 t + g t^2 / 2;
* ``spring``: a mass on a spring of rest length 0 (the harmonic oscillator),
  x(t) = x0 cos(w t) + (v0 / w) sin(w t), w = sqrt(k / m) = 2 pi rad/s (1 Hz);
* ``wind``: linear drag toward the air's velocity u, m v' = -k (v - u), so
  v(t) = u + (v0 - u) e^(-c t) and x(t) = x0 + u t + (v0 - u)(1 - e^(-c t)) / c,
  c = k / m = 2 1/s: an exponential approach to the air's velocity.

For each (problem, method, dt) :func:`measure` steps a World exactly as a user
would (``world.step(dt)`` in a loop) and records

* ``error``: the largest distance (m) between the body and the exact solution
  at any step of the run (``inf`` if the run diverged);
* ``cost``: seconds of run time per simulated second (the median of several
  repetitions), counting the steady steps; the one-time choice a World makes at
  its first step of a new dt is reported apart (``choose_s``);
* ``evaluations``: how many times the World evaluated the acceleration of its
  bodies (machine independent); ``work`` = steps + evaluations, the model cost
  (a step's own bookkeeping costs about one evaluation; see ``work``).

No pygame here: the chart is drawn by ``demos/tradeoff.py``.
"""

from __future__ import annotations

import gc
import math
import statistics
import time
import warnings
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from .body import Body
from .forces import Force, Gravity, Spring, Wind
from .integrators import INTEGRATORS
from .stability import SimulationDiverged, StabilityWarning
from .vector import Vector
from .world import World

__all__ = [
    "METHODS",
    "Problem",
    "PROBLEMS",
    "Point",
    "sweep_dts",
    "measure",
    "plan_auto",
    "auto_tolerances",
    "csv_header",
    "csv_row",
    "sweep",
    "slope",
    "auto_ratios",
    "AutoRatio",
    "side_by_side",
]

#: The methods compared, in the order they are drawn: "exact" is the closed form, "auto" the
#: World's own choice (with a tolerance: see :func:`plan_auto`).
METHODS: tuple[str, ...] = (*INTEGRATORS, "exact", "auto")

_TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Problem:
    """A one-body test problem with an exact answer: forces, start state, ``exact(t)`` in m."""

    name: str
    title: str
    x0: tuple[float, float]
    v0: tuple[float, float]
    forces: Callable[[], list[Force]]
    exact: Callable[[np.ndarray], np.ndarray]  # times (n,) s -> positions (n, 2) m
    closed_form: bool  # whether the closed form ("exact") applies: every force constant
    duration: float = 1.0  # s

    def world(self, method: str, tolerance: float | None = None) -> tuple[World, Body]:
        """A fresh World holding this problem's body and forces, stepped by ``method``."""
        world = World(integrator=method, tolerance=tolerance)
        body = world.add(Body(Vector(*self.x0), Vector(*self.v0), Vector(0.0, 0.0)))
        for force in self.forces():
            world.add_force(force)
        return world, body


def _ballistic(t: np.ndarray) -> np.ndarray:
    # x = x0 + v0 t + g t^2 / 2 with x0 = (0, 0), v0 = (4, 8) m/s, g = (0, -9.81) m/s^2.
    t = np.asarray(t, dtype=float)
    return np.stack([4.0 * t, 8.0 * t - 0.5 * 9.81 * t * t], axis=-1)


def _oscillator(t: np.ndarray) -> np.ndarray:
    # x'' = -w^2 x: x = x0 cos(w t) + (v0 / w) sin(w t), x0 = (1, 0) m, v0 = (0, pi) m/s.
    t = np.asarray(t, dtype=float)
    w = _TWO_PI
    c, s = np.cos(w * t), np.sin(w * t)
    return np.stack([1.0 * c, (math.pi / w) * s], axis=-1)


_AIR = (5.0, 0.0)  # m/s
_RATE = 2.0  # c = k / m, 1/s


def _drift(t: np.ndarray) -> np.ndarray:
    # v' = -c (v - u): v = u + (v0 - u) e^(-c t); integrating, x = u t + (v0 - u)(1 - e^(-c t))/c.
    t = np.asarray(t, dtype=float)
    decay = -np.expm1(-_RATE * t) / _RATE  # (1 - e^(-c t)) / c, accurate for small c t
    v0 = (0.0, 4.0)
    return np.stack([_AIR[i] * t + (v0[i] - _AIR[i]) * decay for i in range(2)], axis=-1)


#: The test problems by name.
PROBLEMS: dict[str, Problem] = {
    "gravity": Problem(
        "gravity",
        "Thrown ball (constant gravity)",
        (0.0, 0.0),
        (4.0, 8.0),
        lambda: [Gravity((0.0, -9.81))],
        _ballistic,
        closed_form=True,
    ),
    "spring": Problem(
        "spring",
        "Spring (oscillator, 1 Hz)",
        (1.0, 0.0),
        (0.0, math.pi),
        lambda: [Spring((0.0, 0.0), k=_TWO_PI**2)],
        _oscillator,
        closed_form=False,
    ),
    "wind": Problem(
        "wind",
        "Wind with linear drag",
        (0.0, 0.0),
        (0.0, 4.0),
        lambda: [Wind(_AIR, k=_RATE)],
        _drift,
        closed_form=False,
    ),
}


def sweep_dts(quick: bool = False) -> list[float]:
    """The time steps (s) of a sweep: powers of two from 1/4 s down to 1/8192 s (quick: 1/512)."""
    last = 9 if quick else 13
    return [2.0**-k for k in range(2, last + 1)]


@dataclass(frozen=True)
class Point:
    """One measured point: ``method`` on ``problem`` at ``dt`` (s); a row of the CSV."""

    problem: str
    method: str  # as asked for ("auto" included)
    chosen: str  # the method the World used (differs from ``method`` for "auto")
    dt: float  # s
    steps: int
    error: float  # largest position error over the run (m); inf when it diverged
    finite: bool  # False when the World raised SimulationDiverged
    warned: bool  # True when the World warned that dt is past the method's stability limit
    cost: float  # run time per simulated second (s/s), median of the repetitions
    choose_s: float  # the first step's extra time (s): the World's one-time choice of method
    evaluations: int  # accelerations evaluated by the World's steps over the run
    choose_evaluations: int  # extra evaluations at the first step (auto's one-time prediction)
    tolerance: float | None = None  # for "auto": the tolerance (m) it was given

    @property
    def work(self) -> int:
        """Machine-independent cost: steps + force evaluations of the steps over the 1 s run.

        A World step's bookkeeping (dt check, finiteness check, swapping arrays) costs about
        as much as one evaluation of a folded force on one body, so a step of a method with
        e evaluations costs about 1 + e units, and the closed form's step 1 unit. The one-time
        choice at the first step is left out, as in ``cost`` (a game pays it once per dt).
        """
        return self.steps + self.evaluations


_CSV_FIELDS = (
    "problem",
    "method",
    "chosen",
    "tolerance_m",
    "dt_s",
    "steps",
    "error_m",
    "finite",
    "warned",
    "cost_s_per_s",
    "choose_s",
    "evaluations",
    "choose_evaluations",
    "work",
)


def csv_header() -> str:
    """The CSV's header line (no newline)."""
    return ",".join(_CSV_FIELDS)


def csv_row(p: Point) -> str:
    """One CSV line for ``p`` (no newline); floats with 17 significant digits."""
    tol = "" if p.tolerance is None else f"{p.tolerance:.17g}"
    values = (
        p.problem,
        p.method,
        p.chosen,
        tol,
        f"{p.dt:.17g}",
        str(p.steps),
        f"{p.error:.17g}",
        str(int(p.finite)),
        str(int(p.warned)),
        f"{p.cost:.6g}",
        f"{p.choose_s:.6g}",
        str(p.evaluations),
        str(p.choose_evaluations),
        str(p.work),
    )
    return ",".join(values)


def _error_run(
    problem: Problem, method: str, dt: float, tolerance: float | None
) -> tuple[float, bool, bool, int, int, str]:
    """(error m, finite, warned, step evaluations, choice evaluations, chosen) from one run.

    The body is read at every step. The first step's evaluations beyond those of a later
    step are the one-time choice's (auto's prediction reads the acceleration once a method).
    """
    world, body = problem.world(method, tolerance)
    start = world.evaluations
    n = round(problem.duration / dt)
    xs = np.empty((n, 2))
    done = 0
    first = 0
    finite = True
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", StabilityWarning)
        try:
            for k in range(n):
                world.step(dt)
                xs[k] = tuple(body.pos)
                done = k + 1
                if k == 0:
                    first = world.evaluations - start
        except SimulationDiverged:
            finite = False
    warned = any(issubclass(w.category, StabilityWarning) for w in caught)
    total = world.evaluations - start
    per_step = (total - first) // (done - 1) if done > 1 else first
    choose = max(0, first - per_step)
    evaluations = total - choose
    if not finite:
        return math.inf, False, warned, evaluations, choose, world.method
    ts = np.arange(1, done + 1) * dt
    with np.errstate(over="ignore", invalid="ignore"):
        dist = np.hypot(*(xs[:done] - problem.exact(ts)).T)
    error = float(dist.max()) if done else 0.0
    return error, True, warned, evaluations, choose, world.method


def _time_run(
    problem: Problem,
    method: str,
    dt: float,
    tolerance: float | None,
    repeats: int,
    min_steps: int = 2000,
) -> tuple[float, float]:
    """(median run time per simulated second, median first-step extra time), both in s.

    Each repetition steps enough fresh Worlds to take ``min_steps`` steps (less timer noise),
    with the garbage collector paused so that its pauses land on no one method.
    """
    n = round(problem.duration / dt)
    loops = max(1, math.ceil(min_steps / n))
    costs: list[float] = []
    firsts: list[float] = []
    collecting = gc.isenabled()
    gc.disable()
    try:
        return _time_loops(problem, method, dt, tolerance, repeats, n, loops, costs, firsts)
    finally:
        if collecting:
            gc.enable()


def _time_loops(
    problem: Problem,
    method: str,
    dt: float,
    tolerance: float | None,
    repeats: int,
    n: int,
    loops: int,
    costs: list[float],
    firsts: list[float],
) -> tuple[float, float]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        for _ in range(repeats):
            worlds = [problem.world(method, tolerance)[0] for _ in range(loops)]
            steady = first = 0.0
            steps = 0
            for world in worlds:
                step = world.step
                t0 = time.perf_counter()
                try:
                    step(dt)
                    t1 = time.perf_counter()
                    for _ in range(n - 1):
                        step(dt)
                        steps += 1
                except SimulationDiverged:
                    t1 = t0
                t2 = time.perf_counter()
                first += t1 - t0
                steady += t2 - t1
            per_step = steady / max(1, steps)
            costs.append(per_step * n / problem.duration)
            firsts.append(max(0.0, first / loops - per_step))
    return statistics.median(costs), statistics.median(firsts)


def measure(
    problem: Problem,
    method: str,
    dt: float,
    repeats: int = 5,
    tolerance: float | None = None,
    min_steps: int = 2000,
) -> Point:
    """Measure ``method`` on ``problem`` at ``dt`` (s): error, cost and evaluations (a Point).

    ``repeats`` timed repetitions of at least ``min_steps`` steps each; the median counts.
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if not (isinstance(repeats, int) and repeats >= 1):
        raise ValueError(f"repeats must be a whole number >= 1, got {repeats!r}")
    error, finite, warned, evaluations, choose, chosen = _error_run(problem, method, dt, tolerance)
    cost, first = _time_run(problem, method, dt, tolerance, repeats, min_steps)
    steps = round(problem.duration / dt)
    return Point(
        problem.name,
        method,
        chosen,
        dt,
        steps,
        error,
        finite,
        warned,
        cost,
        first,
        evaluations,
        choose,
        tolerance,
    )


def plan_auto(problem: Problem, tolerance: float, dts: Sequence[float]) -> tuple[float, str]:
    """(dt, method): the cheapest step among ``dts`` at which "auto" meets ``tolerance`` (m).

    For each dt the World with ``integrator="auto", tolerance=tolerance`` chooses its method
    (the cheapest stable one predicted to meet the tolerance); of the dts where that choice is
    predicted to meet it, the one with the least work per simulated second, steps * (1 +
    evaluations a step), wins. When none meets it, the smallest dt (the most accurate).
    """
    best: tuple[float, float, str] | None = None
    for dt in dts:
        world, _ = problem.world("auto", tolerance)
        name, _ = world.choose_method(dt)
        if world.predicted_error(name, dt) > tolerance:
            continue
        evals = 0 if name == "exact" else INTEGRATORS[name].evaluations
        work = (1 + evals) * problem.duration / dt
        if best is None or work < best[0]:
            best = (work, dt, name)
    if best is None:
        dt = min(dts)
        world, _ = problem.world("auto", tolerance)
        return dt, world.choose_method(dt)[0]
    return best[1], best[2]


def auto_tolerances(quick: bool = False) -> list[float]:
    """The error levels (m) at which "auto" is put on the chart: decades 1e-1 to 1e-10."""
    return [10.0**-k for k in range(1, (8 if quick else 10) + 1)]


def sweep(
    problems: Iterable[Problem],
    methods: Sequence[str] = METHODS,
    dts: Sequence[float] | None = None,
    repeats: int = 5,
    tolerances: Sequence[float] | None = None,
    progress: Callable[[int, int, str], None] | None = None,
    min_steps: int = 2000,
) -> list[Point]:
    """Measure every method at every dt on every problem; "auto" once per tolerance.

    "auto" is given each tolerance in ``tolerances`` (m) and stepped at the dt that
    :func:`plan_auto` picks. The closed form ("exact") is measured only where it applies.
    ``progress(done, total, label)`` is called after each point.
    """
    dts = list(sweep_dts() if dts is None else dts)
    tolerances = list(auto_tolerances() if tolerances is None else tolerances)
    jobs: list[tuple[Problem, str, float, float | None]] = []
    for problem in problems:
        for method in methods:
            if method == "exact" and not problem.closed_form:
                continue
            if method == "auto":
                for level in tolerances:
                    dt, _ = plan_auto(problem, level, dts)
                    jobs.append((problem, method, dt, level))
            else:
                jobs.extend((problem, method, dt, None) for dt in dts)
    points = []
    for i, (problem, method, dt, tol) in enumerate(jobs):
        points.append(measure(problem, method, dt, repeats, tol, min_steps))
        if progress is not None:
            progress(i + 1, len(jobs), f"{problem.name} {method} dt={dt:g}")
    return points


def slope(
    points: Iterable[Point], problem: str, method: str, max_step: float = 0.25
) -> float | None:
    """Least-squares slope of log(error) against log(dt) in the asymptotic range, or None.

    The asymptotic range: finite errors above round-off (1e-11 m) at steps small enough that
    the leading error term dominates, ``rate * dt <= max_step`` with rate = 2 pi rad/s (the
    test problems' fastest rate). Global order p shows up as slope p.
    """
    rows = [
        (math.log(p.dt), math.log(p.error))
        for p in points
        if p.problem == problem
        and p.method == method
        and p.finite
        and 1e-11 < p.error < math.inf
        and _TWO_PI * p.dt <= max_step
    ]
    if len(rows) < 3:
        return None
    x, y = np.array(rows).T
    return float(np.polyfit(x, y, 1)[0])


@dataclass(frozen=True)
class AutoRatio:
    """ "auto" at one tolerance against the fastest measured point that is as accurate."""

    problem: str
    tolerance: float  # m: the error level
    auto: Point
    best: Point | None  # the fastest non-auto point with error <= tolerance (None: none)

    @property
    def met(self) -> bool:
        """Whether auto's measured error is within its tolerance."""
        return self.auto.finite and self.auto.error <= self.tolerance

    @property
    def time_ratio(self) -> float:
        """auto's run time / the best point's (1.0 = as fast; target <= 1.2)."""
        return math.nan if self.best is None else self.auto.cost / self.best.cost

    @property
    def work_ratio(self) -> float:
        """auto's work (steps + evaluations) / the best point's by the same measure."""
        return math.nan if self.best is None else self.auto.work / self.best.work


def auto_ratios(points: Sequence[Point], by: str = "work") -> list[AutoRatio]:
    """For each "auto" point: the fastest other point reaching its tolerance, ``by`` work or time.

    "The same error level" is the tolerance: the candidates are the measured points of every
    other method whose error is at most the tolerance auto was given, leaving out points past
    the method's stability limit (the World warned: no user should run there).
    """
    if by not in ("work", "time"):
        raise ValueError(f"by must be 'work' or 'time', got {by!r}")

    def key(p: Point) -> float:
        return float(p.work) if by == "work" else p.cost

    out = []
    for a in points:
        if a.method != "auto" or a.tolerance is None:
            continue
        rivals = [
            p
            for p in points
            if p.problem == a.problem
            and p.method != "auto"
            and p.finite
            and not p.warned
            and p.error <= a.tolerance
        ]
        best = min(rivals, key=key) if rivals else None
        out.append(AutoRatio(a.problem, a.tolerance, a, best))
    return out


def side_by_side(
    runs: Sequence[tuple[Problem, str, float, float | None]], rounds: int = 9, min_steps: int = 2000
) -> list[float]:
    """Run time per simulated second (s/s) of each (problem, method, dt, tolerance), interleaved.

    Each round times every run once, so a burst of load on a shared machine hits all alike;
    the median of ``rounds`` is returned, in the order given. As in :func:`measure`, the
    first step (the World's one-time choice) is taken before the clock starts.
    """
    samples: list[list[float]] = [[] for _ in runs]
    collecting = gc.isenabled()
    gc.disable()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", StabilityWarning)
            for _ in range(rounds):
                for i, (problem, method, dt, tol) in enumerate(runs):
                    n = round(problem.duration / dt)
                    loops = max(1, math.ceil(min_steps / n))
                    worlds = [problem.world(method, tol)[0] for _ in range(loops)]
                    for w in worlds:
                        w.step(dt)
                    t0 = time.perf_counter()
                    for w in worlds:
                        step = w.step
                        for _ in range(n - 1):
                            step(dt)
                    elapsed = time.perf_counter() - t0
                    samples[i].append(elapsed / (loops * max(1, n - 1)) * n / problem.duration)
    finally:
        if collecting:
            gc.enable()
    return [statistics.median(s) for s in samples]
