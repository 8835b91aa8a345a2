"""Ball-pit benchmark: balls piling up in a box, bodies against bodies, against pymunk.

Run with ``python -m demos.bench pit``. The scene of issue "Contacts II": N balls of radius
0.5 m dropped on a grid (rows 1.1 m apart, every other row shifted by half a ball) into a box
40 m wide, gravity 9.81 m/s^2, restitution 0.5, friction 0.5, dt = 1/60 s; pymunk with its
default 10 iterations (and its default ``collision_slop``, 0.1 m: 20% of the radius).

What is timed is what a game sees: the FIRST 5 s from the drop, balls moving and landing, not
a step of a pile already asleep. Both engines step the same scene side by side, one step each
in turn (the order swapped every step, so a burst of load on a shared machine hits both
alike); each step's wall-clock and CPU time are summed, and the ratio is the median over the
rounds (each round a fresh drop). Besides the time, after every step of the first round (not
timed): the deepest overlap of two balls as a fraction of the radius (the deepest over the
5 s, while the rows land, and at 5 s; centres closer than r would be an overlap past 100%)
and the kinetic energy; at 5 s, how many of this engine's balls sleep (pymunk's sleep is off
by default) and how many balls left the box.

Targets: the 1,000-ball pit's first 5 s at most 3x pymunk's, the deepest overlap
while rows land at most 10% of r, at 5 s at most 1% and asleep; the 10,000-ball pit's first
5 s at most 3x pymunk's, its deepest overlap at most 20% of r and no two centres ever closer
than r. The report writes ``pit_1000.png`` and ``pit_10000.png`` (overlap and kinetic energy
against time, both engines) into its output folder (``out/bench``; ``--out DIR``).
"""

from __future__ import annotations

import math
import statistics
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from engine import Body, Box, StabilityWarning, Vector, World
from engine import kernels as engine_kernels
from engine.exact.collisions import deepest_overlap
from engine.forces import Gravity

__all__ = [
    "report",
    "make_world",
    "make_space",
    "scene",
    "measures",
    "Run",
    "first_seconds",
    "draw_pit",
    "time_chart_class",
    "ENGINE_COLORS",
    "summary",
    "DT",
    "RADIUS",
    "WIDTH",
    "SECONDS",
    "TARGETS",
]

DT = 1.0 / 60.0  # s
RADIUS = 0.5  # m
WIDTH = 40.0  # m
G = 9.81  # m/s^2
SECONDS = 5.0  # s: the window timed, from the drop
E, MU = 0.5, 0.5

#: The targets per pit size: (time / pymunk's, deepest overlap / r over the window,
#: overlap / r at its end or None, asleep at its end, no centres closer than r).
TARGETS: dict[int, tuple[float, float, float | None, bool, bool]] = {
    1_000: (3.0, 0.10, 0.01, True, False),
    10_000: (3.0, 0.20, None, False, True),
}


def scene(n: int, seed: int = 1, *, width: float = WIDTH) -> np.ndarray:
    """Start positions (n, 2): a grid ``width`` - 2 balls wide (38 in the 40 m box), every
    other row shifted by half a ball, with a little seeded jitter so that the columns do not
    stand by symmetry."""
    rng = np.random.default_rng(seed)
    cols = int(width) - 2
    k = np.arange(n)
    row = k // cols
    x = 1.0 + (k % cols) + 0.5 * (row % 2) + rng.uniform(-0.01, 0.01, n)
    y = 1.0 + 1.1 * row
    return np.stack([x, y], axis=1)


def make_world(
    n: int,
    iterations: int | None = None,
    *,
    width: float = WIDTH,
    seed: int = 1,
    kernels: str | None = None,
    fixed_rotation: bool = True,
    solver: str = "exact",
) -> World:
    """The pit as a World ("auto": the closed form under gravity), ``width`` m wide, on the
    path ``kernels`` (None: the default, engine.kernels); ``fixed_rotation=False``: balls
    that turn (the pile's friction turns them: engine.exact.soft, lever arms); ``solver``: the
    World's."""
    world = World(integrator="auto", kernels=kernels, solver=solver)
    if iterations is not None:
        world.contact_iterations = iterations
    world.add_force(Gravity((0.0, -G)))
    world.add_collider(Box((0.0, 0.0), (width, 1e4)))  # walls and a floor; the top far away
    # The balls do not turn by default (fixed_rotation): the pit measures the pile's solver
    # as it did before bodies turned, its numbers comparable from run to run.
    world.add_all(
        Body(Vector(*p), Vector(0, 0), Vector(0, 0), radius=RADIUS, restitution=E, friction=MU,
             fixed_rotation=fixed_rotation)
        for p in scene(n, seed, width=width).tolist()
    )  # fmt: skip
    return world


def make_space(
    n: int, iterations: int = 10, *, width: float = WIDTH, slop: float | None = None
) -> object | None:
    """The pit in pymunk (None without pymunk): the same box, balls and materials.

    ``slop``: pymunk's ``collision_slop`` (m), the overlap it leaves alone; None keeps its
    default, 0.1 (20% of the radius here)."""
    try:
        import pymunk
    except ImportError:
        return None
    space = pymunk.Space()
    space.gravity = (0.0, -G)
    space.iterations = iterations
    if slop is not None:
        space.collision_slop = slop
    for a, b in (((0, 0), (width, 0)), ((0, 0), (0, 1e4)), ((width, 0), (width, 1e4))):
        wall = pymunk.Segment(space.static_body, a, b, 0.0)
        wall.elasticity = wall.friction = 1.0
        space.add(wall)
    for p in scene(n, width=width).tolist():
        body = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0.0, RADIUS))
        body.position = p
        ball = pymunk.Circle(body, RADIUS)
        ball.elasticity, ball.friction = E, MU
        space.add(body, ball)
    return space


def measures(x: np.ndarray, v: np.ndarray, width: float = WIDTH) -> tuple[float, int, float]:
    """(deepest overlap / radius, balls outside the box, kinetic / potential energy)."""
    over = deepest_overlap(x, np.full(len(x), RADIUS)) / RADIUS
    out = int(((x[:, 0] < 0) | (x[:, 0] > width) | (x[:, 1] < 0)).sum())
    kinetic = 0.5 * float((v * v).sum())
    potential = G * float((x[:, 1] - RADIUS).sum())
    return over, out, kinetic / potential if potential > 0 else 0.0


def _space_state(space: object) -> tuple[np.ndarray, np.ndarray]:
    bodies = space.bodies  # type: ignore[attr-defined]
    return np.array([b.position for b in bodies]), np.array([b.velocity for b in bodies])


@dataclass
class Run:
    """One engine's first seconds of a pit: what it cost and what it did.

    ``wall`` and ``cpu``: seconds for the whole window, the median over the rounds; ``rounds``
    the per-round wall-clock totals. ``t``, ``overlap`` (deepest overlap / r) and ``kinetic``
    (J, every ball 1 kg): after each step of the first round. At the window's end: ``asleep``
    bodies (pymunk's: 0, its sleep is off), ``outside`` the box, kinetic over potential energy.
    """

    engine: str
    balls: int
    wall: float
    cpu: float
    rounds: list[float]
    t: np.ndarray
    overlap: np.ndarray
    kinetic: np.ndarray
    asleep: int
    outside: int
    ke_pe: float
    warned: bool = False
    asleep_at: float = math.nan  # s: when every ball first slept (nan: not within the window)

    @property
    def deepest(self) -> float:
        """The deepest overlap / r over the window."""
        return float(self.overlap.max()) if len(self.overlap) else 0.0

    @property
    def deepest_at(self) -> float:
        """When (s) the deepest overlap was."""
        return float(self.t[int(self.overlap.argmax())]) if len(self.overlap) else 0.0

    @property
    def final(self) -> float:
        """The deepest overlap / r at the window's end."""
        return float(self.overlap[-1]) if len(self.overlap) else 0.0

    @property
    def closest(self) -> float:
        """The nearest two centres came over the window, over r (under 1: closer than r)."""
        return 2.0 - self.deepest


def _sims(n: int) -> dict[str, tuple[Any, Any]]:
    """engine -> (its step function, the thing stepped): the World on the numpy path
    ("World"), on the fast path if numba is installed ("fast"), and pymunk if installed."""
    world = make_world(n, kernels="numpy")
    sims: dict[str, tuple[Any, Any]] = {"World": (world.step, world)}
    if engine_kernels.available():
        fast = make_world(n, kernels="fast")
        sims["fast"] = (fast.step, fast)
    space = make_space(n)
    if space is not None:
        sims["pymunk"] = (space.step, space)  # type: ignore[attr-defined]
    return sims


def first_seconds(
    n: int, seconds: float = SECONDS, rounds: int = 1, *, pymunk: bool = True
) -> dict[str, Run]:
    """Drop ``n`` balls ``rounds`` times and step each engine for ``seconds``, side by side.

    Returns engine name -> :class:`Run` ("World", and "pymunk" where it is installed and
    ``pymunk`` is true).
    """
    steps = round(seconds / DT)
    engine_kernels.prepare()  # compiled (or loaded from the cache) before the clock starts
    wall: dict[str, list[float]] = {}
    cpu: dict[str, list[float]] = {}
    traces: dict[str, tuple[list[float], list[float], list[float]]] = {}
    warned: dict[str, bool] = {}
    asleep_at: dict[str, float] = {}
    last: dict[str, Any] = {}
    perf, proc = time.perf_counter, time.process_time
    for r in range(rounds):
        sims = _sims(n)
        if not pymunk:
            sims.pop("pymunk", None)
        names = list(sims)
        spent = {name: [0.0, 0.0] for name in names}
        if r == 0:
            traces = {name: ([], [], []) for name in names}
            warned = {name: False for name in names}
            asleep_at = {name: math.nan for name in names}
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", StabilityWarning)
            for i in range(steps):
                order = names if i % 2 == 0 else names[::-1]
                for name in order:
                    step = sims[name][0]
                    w0, c0 = perf(), proc()
                    step(DT)
                    c1, w1 = proc(), perf()
                    spent[name][0] += w1 - w0
                    spent[name][1] += c1 - c0
                if r == 0:
                    for name in names:
                        x, v = _state(sims[name][1])
                        ts, over, ke = traces[name]
                        ts.append((i + 1) * DT)
                        over.append(deepest_overlap(x, np.full(len(x), RADIUS)) / RADIUS)
                        ke.append(0.5 * float((v * v).sum()))
                        thing = sims[name][1]
                        if (
                            isinstance(thing, World)
                            and math.isnan(asleep_at[name])
                            and thing.sleeping == n
                        ):
                            asleep_at[name] = (i + 1) * DT
            if r == 0:
                warned["World"] = any(issubclass(w.category, StabilityWarning) for w in caught)
        for name in names:
            wall.setdefault(name, []).append(spent[name][0])
            cpu.setdefault(name, []).append(spent[name][1])
        last = {name: sims[name][1] for name in names}
    runs = {}
    for name, thing in last.items():
        x, v = _state(thing)
        _, out, ke_pe = measures(x, v)
        ts, over, ke = traces[name]
        runs[name] = Run(
            name,
            n,
            statistics.median(wall[name]),
            statistics.median(cpu[name]),
            wall[name],
            np.array(ts),
            np.array(over),
            np.array(ke),
            thing.sleeping if isinstance(thing, World) else 0,
            out,
            ke_pe,
            warned.get(name, False),
            asleep_at.get(name, math.nan),
        )
    return runs


def _state(thing: Any) -> tuple[np.ndarray, np.ndarray]:
    if isinstance(thing, World):
        return thing.positions(), thing.velocities()
    return _space_state(thing)


def ratio(runs: dict[str, Run], clock: str = "wall", engine: str = "World") -> float | None:
    """``engine``'s time over pymunk's for the window (``clock`` "wall" or "cpu"), None
    without either. The wall-clock ratio is the median of the rounds' ratios (each round side
    by side)."""
    if "pymunk" not in runs or engine not in runs:
        return None
    w, p = runs[engine], runs["pymunk"]
    if clock == "cpu":
        return w.cpu / p.cpu
    return statistics.median(a / b for a, b in zip(w.rounds, p.rounds, strict=True))


def _met(ok: bool) -> str:
    return "met" if ok else "NOT met"


def summary(runs: dict[str, Run], seconds: float = SECONDS) -> list[str]:
    """The report's lines for one pit: times, overlaps, energy, sleep, and the targets."""
    w = runs["World"]
    n = w.balls
    lines = [f"  {n:,} balls, the first {seconds:g} s from the drop:"]
    for run in runs.values():
        asleep = (
            f", {run.asleep:,} asleep at {seconds:g} s"
            + (f" (all from {run.asleep_at:.2f} s)" if math.isfinite(run.asleep_at) else "")
            if run.engine != "pymunk"
            else " (sleep off)"
        )
        lines.append(
            f"    {run.engine:<7} {run.wall:7.2f} s wall, {run.cpu:7.2f} s CPU; deepest overlap "
            f"{run.deepest:.1%} of r (at {run.deepest_at:.2f} s), at {seconds:g} s "
            f"{run.final:.2%}; nearest centres {run.closest:.2f} r; KE at {seconds:g} s "
            f"{run.kinetic[-1]:.3g} J (KE/PE {run.ke_pe:.1e}); {run.outside} outside{asleep}"
            + ("; warned (StabilityWarning)" if run.warned else "")
        )
    wall, cpu = ratio(runs), ratio(runs, "cpu")
    target = TARGETS.get(n)
    if wall is not None and cpu is not None:
        aim = "" if target is None else f" (target <= {target[0]:g}x: {_met(wall <= target[0])})"
        pairs = zip(w.rounds, runs["pymunk"].rounds, strict=True)
        spread = ", ".join(f"{a / b:.2f}" for a, b in pairs)
        lines.append(
            f"    World / pymunk: {wall:.2f}x wall (rounds: {spread}), {cpu:.2f}x CPU{aim}"
        )
    fast_wall, fast_cpu = ratio(runs, engine="fast"), ratio(runs, "cpu", engine="fast")
    if fast_wall is not None and fast_cpu is not None:
        lines.append(
            f"    fast / pymunk: {fast_wall:.2f}x wall, {fast_cpu:.2f}x CPU (target "
            f"<= 0.5x: {_met(fast_wall <= 0.5)}); fast / World {runs['fast'].wall / w.wall:.2f}x"
        )
    if target is not None:
        _, deep, rest, sleeps, centres = target
        checks = [f"deepest overlap <= {deep:.0%} of r: {_met(w.deepest <= deep)}"]
        if rest is not None:
            checks.append(f"at {seconds:g} s <= {rest:.0%}: {_met(w.final <= rest)}")
        if sleeps:
            checks.append(f"asleep at {seconds:g} s: {_met(w.asleep == n)}")
        if centres:
            checks.append(f"no centres closer than r: {_met(w.closest >= 1.0)}")
        lines.append("    targets: " + "; ".join(checks))
    return lines


# -- the picture: a quantity against time on a log scale, drawn with pygame ------------------
# From the same parts as the tradeoff demo's charts: engine.render.chart.LogLogChart with its
# x axis made linear in seconds. pygame is imported only when a picture is drawn.


def time_chart_class() -> Any:
    """The class of a panel with time along x (linear, s) and a value up y (log10): the pit's
    and the stack's pictures draw on it."""
    import pygame

    from engine.render import INK, MUTED, draw_text, marks
    from engine.render.chart import LogLogChart, draw_power_of_ten
    from engine.render.draw import GRID, font, ink

    class TimeChart(LogLogChart):
        """A panel with time (s) from 0 to ``t_max`` along x, linear, and log10 of the value
        up y, 10^lo .. 10^hi for ``y_decades`` = (lo, hi); x numbered every ``t_step`` s.
        Values at or below 10^lo (a zero overlap) are drawn on the bottom line."""

        def __init__(
            self,
            rect: tuple[int, int, int, int],
            t_max: float,
            y_decades: tuple[int, int],
            title: str,
            y_label: str,
            t_step: float = 1.0,
        ) -> None:
            if not t_max > 0:
                raise ValueError(f"t_max must be > 0 s, got {t_max!r}")
            super().__init__(rect, (0, 1), y_decades, title, "t (s) from the drop", y_label)
            self.t_max, self.t_step = float(t_max), float(t_step)

        def to_px(self, x: Any, y: Any) -> tuple[np.ndarray, np.ndarray]:
            a = self.area
            y0, y1 = self.y_decades
            with np.errstate(divide="ignore", invalid="ignore"):
                fy = (np.log10(np.asarray(y, dtype=float)) - y0) / (y1 - y0)
            fx = np.asarray(x, dtype=float) / self.t_max
            return a.left + fx * (a.width - 1), a.bottom - 1 - fy * (a.height - 1)

        def _draw_frame(self, surface: pygame.Surface) -> None:
            pygame.draw.rect(surface, (255, 255, 255), self.rect, border_radius=4)
            pygame.draw.rect(surface, GRID, self.rect, 1, border_radius=4)
            a = self.area
            for k in range(int(self.t_max / self.t_step + 1e-9) + 1):
                t = k * self.t_step
                px = round(float(self.to_px(t, 1.0)[0]))
                pygame.draw.line(surface, GRID, (px, a.top), (px, a.bottom - 1), 1)
                draw_text(surface, f"{t:g}", (px, a.bottom + 3), 16, MUTED, "midtop")
            y0, y1 = self.y_decades
            every = 2 if y1 - y0 > 8 else 1
            for k in range(y0, y1 + 1):
                py = round(float(self.to_px(1.0, 10.0**k)[1]))
                pygame.draw.line(surface, GRID, (a.left, py), (a.right - 1, py), 1)
                if (k - y0) % every == 0:
                    anchor = "bottomright" if k == y0 else "midright"
                    draw_power_of_ten(surface, k, (a.left - 4, py + (k == y0)), 16, MUTED, anchor)
            pygame.draw.rect(surface, INK, a, 1)
            draw_text(surface, self.title, (self.rect.left + 8, self.rect.top + 6), 20, INK)
            draw_text(surface, self.x_label, (a.centerx, a.bottom + 22), 16, INK, "midtop")
            label = pygame.transform.rotate(font(16).render(self.y_label, True, INK), 90)
            where = label.get_rect(midleft=(self.rect.left + 3, a.centery))
            surface.blit(label, where)
            box = ink(self.y_label, 16)  # turned a quarter left: (x, y) -> (y, width - x)
            turned = pygame.Rect(box.top, where.height - box.right, box.height, box.width)
            marks.note(surface, "text", turned.move(where.topleft), self.y_label)

        def draw_line(
            self, surface: pygame.Surface, ts: Any, ys: Any, color: Any, width: int = 2
        ) -> None:
            """The samples (ts[i] s, ys[i]) as a line ``width`` px wide, no markers; y clamped
            to the axis."""
            floor, top = 10.0 ** self.y_decades[0], 10.0 ** self.y_decades[1]
            y = np.clip(np.nan_to_num(np.asarray(ys, dtype=float), nan=floor), floor, top)
            self.draw_series(surface, list(ts), y.tolist(), color, width=width, radius=0)

        def level(self, surface: pygame.Surface, value: float, label: str) -> None:
            """A dashed line across the panel at ``value``, labelled at its right end."""
            a = self.area
            py = round(float(self.to_px(1.0, value)[1]))
            for x in range(a.left + 2, a.right - 2, 12):
                pygame.draw.line(surface, MUTED, (x, py), (min(x + 6, a.right - 2), py), 1)
            with marks.panel(self.rect):
                draw_text(surface, label, (a.right - 6, py - 2), 15, MUTED, "bottomright")

    return TimeChart


#: This engine and pymunk, in the colours of the tradeoff demo's contacts chart.
ENGINE_COLORS: dict[str, tuple[int, int, int]] = {
    "World": (0, 114, 178),
    "fast": (0, 158, 115),
    "pymunk": (204, 121, 167),
}


def draw_pit(runs: dict[str, Run], size: tuple[int, int] = (1280, 720)) -> Any:
    """The pit's picture: deepest overlap / r and kinetic energy against time, both engines."""
    import pygame

    from engine.render import MUTED, PAPER, draw_text, init_headless
    from engine.render.chart import decade_range, draw_legend

    TimeChart = time_chart_class()  # noqa: N806 - a class

    w = runs["World"]
    n, seconds = w.balls, float(w.t[-1]) if len(w.t) else SECONDS
    init_headless()
    surface = pygame.Surface(size)
    surface.fill(PAPER)
    draw_text(
        surface,
        f"Ball pit: {n:,} balls dropped into a box 40 m wide, the first {seconds:g} s",
        (20, 10),
        30,
    )
    draw_text(
        surface,
        "r 0.5 m, e 0.5, mu 0.5, dt = 1/60 s; this engine (contact_iterations 4) beside pymunk "
        "(10 iterations, slop 0.1 m), the same drop.",
        (20, 42),
        17,
        MUTED,
    )
    width, height = size
    margin, gap, top = 16, 12, 70
    legend_h = 86 + 24 * len(runs)  # a row for each engine's line, then the footnote
    panel_w = (width - 2 * margin - gap) // 2
    panel_h = height - top - legend_h
    target = TARGETS.get(n)
    deep = target[1] if target is not None else None
    overlaps = np.concatenate([r.overlap for r in runs.values()])
    hi = max(0, math.ceil(math.log10(max(float(overlaps.max()), 1e-3))))
    over_chart = TimeChart(
        (margin, top, panel_w, panel_h),
        seconds,
        (-4, hi),
        "Deepest overlap of two balls",
        "deepest overlap / r",
    )
    over_chart.draw_frame(surface)
    energies = np.concatenate([r.kinetic for r in runs.values()])
    ke_chart = TimeChart(
        (margin + panel_w + gap, top, panel_w, panel_h),
        seconds,
        decade_range([float(e) for e in energies if e > 0] or [1.0]),
        "Kinetic energy",
        "kinetic energy (J)",
    )
    ke_chart.draw_frame(surface)
    if deep is not None:
        over_chart.level(surface, deep, f"target while landing: {deep:.0%} of r")
    over_chart.level(surface, 0.01, "1% of r")
    if target is not None and target[4]:
        over_chart.level(surface, 1.0, "centres r apart")
    # The fast path first and wider: it gives the numpy path's numbers, so its curve shows as
    # a border around the numpy one where they agree (everywhere, on the pits measured).
    for name in (name for name in ("fast", "World", "pymunk") if name in runs):
        run, width = runs[name], 6 if name == "fast" else 2
        over_chart.draw_line(surface, run.t, run.overlap, ENGINE_COLORS[name], width)
        ke_chart.draw_line(surface, run.t, run.kinetic, ENGINE_COLORS[name], width)
    labels = {
        "World": "this engine (World, numpy)",
        "fast": "this engine (fast: compiled)",
        "pymunk": "pymunk 7",
    }
    items = [
        (
            f"{labels[name]}: {runs[name].wall:.2f} s for the {seconds:g} s, deepest "
            f"{runs[name].deepest:.1%} of r",
            ENGINE_COLORS[name],
            3,
        )
        for name in ENGINE_COLORS
        if name in runs
    ]
    draw_legend(surface, items, (margin, height - legend_h + 34), width - 2 * margin)
    wall = ratio(runs)
    fast = ratio(runs, engine="fast")
    words = (
        f"World / pymunk {wall:.2f}x by the wall clock"
        + (f" (fast: {fast:.2f}x)" if fast is not None else "")
        + ", side by side in one run. "
        if wall is not None
        else "pymunk is not installed: this engine alone. "
    )
    draw_text(
        surface,
        words + "A zero overlap or energy (asleep) is drawn on the bottom line.",
        (margin, height - 36),
        17,
        MUTED,
    )
    assert isinstance(surface, pygame.Surface)
    return surface


#: Pit sizes the report measures, and rounds of each (full run, quick run).
SIZES: dict[bool, tuple[tuple[int, int], ...]] = {
    False: ((1_000, 3), (10_000, 2)),
    True: ((1_000, 1),),
}


def report(quick: bool = False, out: Path | None = None) -> str:
    """Run the ball-pit benchmark, write its pictures into ``out``; return the text."""
    from engine.render import save_png

    folder = Path("out") / "bench" if out is None else Path(out)
    lines = [
        f"pit: balls (r 0.5 m, e 0.5, mu 0.5) dropped into a box 40 m wide, dt = 1/60 s, "
        f"the first {SECONDS:g} s side by side"
    ]
    for n, rounds in SIZES[quick]:
        runs = first_seconds(n, SECONDS, rounds)
        lines.append(f"  ({rounds} round{'s' if rounds > 1 else ''}; wall time medians)")
        lines += summary(runs)
        path = save_png(draw_pit(runs), folder / f"pit_{n}.png", overwrite=True)
        lines.append(f"    wrote {path}")
    if make_space(1) is None:
        lines.append("  pymunk is not installed (pip install -e '.[bench]'): no comparison")
    return "\n".join(lines)
