"""A pendulum on a rod: each method's energy error over many periods against its cost per step.

Run with ``python -m demos.bench pendulum``; ``python -m demos tradeoff`` draws the rows as the
pendulum panel of the work-precision chart (``out/tradeoff/work_precision.png``) and writes
them to ``out/tradeoff/pendulum.csv``.

The pendulum: a 1 kg bob on a massless ``Rod`` of L = 1 m from a fixed point, under gravity
g = 9.81 m/s^2, let go from rest at THETA0 = 90 degrees (a large, nonlinear swing). Its period
is T = 4 sqrt(L / g) K(sin(THETA0 / 2)) = 2.368 s (K the complete elliptic integral of the
first kind). Each (method, dt) runs for ``periods`` periods of T.

* Energy error: the largest |E(t) - E(0)| / (m g L) over the run, E = m |v|^2 / 2 + m g y, taken
  after every step (1 is the whole drop from the pivot's height to the bottom).
* Cost: CPU seconds per step (``time.process_time``, the step alone, not the energy read-out).
  At one dt every method's World steps in turn, one step each, the order rotating, so that a
  burst of load on a shared machine hits them alike.

Methods: ``semi_implicit_euler``, ``velocity_verlet``, ``rk4`` and ``auto`` (gravity and rods
alone: it picks the closed form, "exact"). Under constant gravity the free step of Verlet and
RK4 is exact as well (a quadratic in t), so those three give the same states and the same
energy error; they differ only in cost. What limits them is the links' RATTLE step, whose
energy error is bounded and O(dt^2) (it oscillates over a few hundred seconds, it does not
grow). Semi-implicit Euler's free step is first order, and so is its error.

How long: the full sweep runs FULL_PERIODS periods (237 s of simulated time) at four steps, as
many as a run of a minute affords (a step with one link costs 18 to 45 us here: the link is
solved in floats, and RK4's four force evaluations show); ``quick`` runs QUICK_PERIODS periods
at two steps, for the tests. ``measure(periods=10_000)`` runs 10^4 periods at every step
(about 25 minutes). Run by hand for 10^4 periods at dt = 1/30 s, the closed form never
passed the largest error of its first 100 periods (4.1e-3), and semi-implicit Euler passed its
(4.7e-2) by 1e-10: the errors are bounded, so 100 periods show them.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from engine import Body, Rod, Vector, World
from engine.forces import Gravity

__all__ = [
    "G",
    "LENGTH",
    "THETA0",
    "METHODS",
    "FULL_DTS",
    "QUICK_DTS",
    "FULL_PERIODS",
    "QUICK_PERIODS",
    "Row",
    "period",
    "pendulum_world",
    "measure",
    "csv_header",
    "csv_row",
    "table",
    "report",
]

G = 9.81  # m/s^2
LENGTH = 1.0  # m
THETA0 = math.radians(90.0)  # rad, from rest
#: The methods compared, as World(integrator=...) names them.
METHODS: tuple[str, ...] = ("semi_implicit_euler", "velocity_verlet", "rk4", "auto")
FULL_DTS: tuple[float, ...] = (1 / 30, 1 / 60, 1 / 120, 1 / 240)  # s
QUICK_DTS: tuple[float, ...] = (1 / 30, 1 / 60)  # s
FULL_PERIODS = 100
QUICK_PERIODS = 4


def agm(a: float, b: float) -> float:
    """The arithmetic-geometric mean of a, b > 0: a, b -> (a + b) / 2, sqrt(a b) until equal.

    The gap squares every round (quadratic convergence), so 2 to 1e-16 takes about 5 rounds;
    the loop stops when the pair stops changing (comparing a == b could cycle by one ulp).
    """
    for _ in range(64):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        if abs(a - b) <= 4e-16 * a:
            break
    return a


def period(theta0: float, length: float = LENGTH, g: float = G) -> float:
    """The exact period (s) of a pendulum let go from rest at ``theta0`` rad (0 < theta0 < pi).

    T = 4 sqrt(L / g) K(k), k = sin(theta0 / 2), and Gauss's K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
    """
    k = math.sin(0.5 * theta0)
    return 4.0 * math.sqrt(length / g) * math.pi / (2.0 * agm(1.0, math.sqrt(1.0 - k * k)))


@dataclass(frozen=True)
class Row:
    """One (method, dt) run: the method asked for and the one the World used, the step (s),
    the largest energy error / (m g L), the cost (CPU s per step) and the steps taken."""

    method: str
    chosen: str
    dt: float
    energy: float
    cost: float
    steps: int


def pendulum_world(method: str, theta0: float = THETA0) -> tuple[World, Body, Rod]:
    """A World with gravity and one 1 kg bob on a rod of LENGTH from the origin, at rest at
    ``theta0`` rad from straight down (counterclockwise)."""
    world = World(integrator=method)
    world.add_force(Gravity((0.0, -G)))
    bob = world.add(
        Body(
            Vector(LENGTH * math.sin(theta0), -LENGTH * math.cos(theta0)),
            Vector(0.0, 0.0),
            Vector(0.0, 0.0),
            mass=1.0,
        )
    )
    rod = Rod(bob, (0.0, 0.0))
    world.add_link(rod)
    return world, bob, rod


def _energy(bob: Body) -> float:
    """E / (m g L): kinetic plus potential energy with y = 0 at the pivot, per m g L."""
    v, y = bob.vel, bob.pos.y
    return (0.5 * (v.x * v.x + v.y * v.y) + G * y) / (G * LENGTH)


def measure(
    quick: bool = False,
    periods: int | None = None,
    dts: Sequence[float] | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> list[Row]:
    """Every method at every dt for ``periods`` periods (default: FULL or QUICK's)."""
    count = periods if periods is not None else QUICK_PERIODS if quick else FULL_PERIODS
    steps_of = list(dts if dts is not None else QUICK_DTS if quick else FULL_DTS)
    span = count * period(THETA0)
    total = sum(math.ceil(span / dt) for dt in steps_of) * len(METHODS)
    done = 0
    rows = []
    clock = time.process_time
    for dt in steps_of:
        n = math.ceil(span / dt)
        runs = [pendulum_world(m) for m in METHODS]
        e0 = [_energy(bob) for _, bob, _ in runs]
        worst = [0.0] * len(runs)
        spent = [0.0] * len(runs)
        for i in range(n):
            for j in range(len(runs)):
                k = (i + j) % len(runs)  # the order rotates from step to step
                world, bob, _ = runs[k]
                start = clock()
                world.step(dt)
                spent[k] += clock() - start
                worst[k] = max(worst[k], abs(_energy(bob) - e0[k]))
            done += len(runs)
            if progress is not None and i % 500 == 0:
                progress(done, total)
        for k, (world, _, _) in enumerate(runs):
            rows.append(Row(METHODS[k], world.method, dt, worst[k], spent[k] / n, n))
    if progress is not None:
        progress(total, total)
    return rows


_CSV_FIELDS = ("method", "chosen", "dt_s", "energy_error", "cost_s_per_step", "steps")


def csv_header() -> str:
    """The CSV's header line (no newline)."""
    return ",".join(_CSV_FIELDS)


def csv_row(r: Row) -> str:
    """One CSV line for ``r`` (no newline); the error with 17 significant digits."""
    return f"{r.method},{r.chosen},{r.dt!r},{r.energy:.17g},{r.cost:.6g},{r.steps}"


def table(rows: Sequence[Row]) -> str:
    """The rows as a text table."""
    if not rows:
        return "pendulum: no rows"
    periods = rows[0].steps * rows[0].dt / period(THETA0)
    lines = [
        f"Pendulum on a rod (L = {LENGTH:g} m, from rest at 90 deg, T = {period(THETA0):.4f} s): "
        f"largest |E - E0| / (m g L) over {periods:.0f} periods; CPU time per step",
        f"  {'method':<20} {'chosen':<20} {'dt':>7} {'energy error':>13} {'ms a step':>10}",
    ]
    for r in rows:
        lines.append(
            f"  {r.method:<20} {r.chosen:<20} 1/{round(1 / r.dt):<5} {r.energy:>13.3e} "
            f"{r.cost * 1e3:>10.3f}"
        )
    return "\n".join(lines)


def report(quick: bool = False) -> str:
    """Measure and return the table (``python -m demos.bench pendulum``)."""
    return table(measure(quick))
