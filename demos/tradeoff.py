"""Speed against accuracy: the work-precision chart, the throughput chart, the contacts chart.

    python -m demos tradeoff            # out/tradeoff/work_precision.png + .csv, throughput.*,
                                        # contacts.*
    python -m demos tradeoff --quick    # a coarser sweep (QUICK), in 10 to 20 seconds

The work-precision chart answers "which integrator should I use?": for three problems with
exact answers (a thrown ball, a spring, wind with drag) each method runs for 1 s at steps dt
halved from dot to dot, and each dot shows the error (largest distance from the exact answer,
m) against the cost (run time per simulated second). The lowest line at a given cost is the
best method for that budget. "auto" is the World choosing for itself, given a tolerance.
A fourth panel holds a pendulum on a rod (``demos.bench.pendulum``): each method's largest
energy error over 100 periods (``--quick``: 4) at dt = 1/30 to 1/240 s against its CPU time
per simulated second (its cost per step times the steps a second); the rows go to
``out/tradeoff/pendulum.csv``. Verlet, RK4 and the closed form give the same error at each dt
there, so their lines run parallel, apart by their costs alone.

The throughput chart: cost per body-step against the number of bodies, for the World, the
particle arrays, the lesson's Body loop, pymunk and pygame's Vector2, measured in one run.

The contacts chart answers "how many contact iterations do I need?": for a ball pit (the
deepest overlap left at rest, and the motion left) and Newton's cradle (the speeds after the
impacts), and for a tower of 10 boxes and a pyramid of 210 (the drift: the largest
displacement of any box after 5 s, sleeping off), the error against the cost of an awake step,
for this engine at several ``World.contact_iterations`` and for pymunk at several
``Space.iterations``.

The measuring lives in ``engine.measure``, ``demos.bench.throughput`` and
``demos.bench.solver``; this module draws.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pygame

from demos.bench import pendulum, solver, throughput
from demos.cli import Demo
from engine import measure
from engine.measure import PROBLEMS, Point
from engine.render import (
    INK,
    MUTED,
    PAPER,
    FramesExistError,
    Progress,
    draw_text,
    font,
    init_headless,
    save_png,
)
from engine.render.chart import LogLogChart, decade_range, draw_legend

__all__ = [
    "AUTO_TARGET",
    "COLORS",
    "LABELS",
    "draw_work_precision",
    "draw_throughput",
    "draw_contacts",
    "SOLVER_COLORS",
    "SOLVER_LABELS",
    "FULL",
    "QUICK",
    "Sweep",
    "over_target",
    "summary",
    "run",
    "DEMO",
]

Color = tuple[int, int, int]

#: One colour per method (Okabe-Ito: distinct for colour-blind readers and on a projector).
COLORS: dict[str, Color] = {
    "explicit_euler": (213, 94, 0),  # vermillion
    "semi_implicit_euler": (86, 180, 233),  # sky blue
    "velocity_verlet": (0, 158, 115),  # bluish green
    "rk4": (0, 114, 178),  # blue
    "exact": (204, 121, 167),  # reddish purple
    "auto": (230, 159, 0),  # orange, drawn as a wide band under the others
}

#: Names a reader knows.
LABELS: dict[str, str] = {
    "explicit_euler": "explicit Euler",
    "semi_implicit_euler": "semi-implicit Euler",
    "velocity_verlet": "velocity Verlet",
    "rk4": "RK4",
    "exact": "closed form",
    "auto": "auto (given a tolerance)",
}

#: Colours of the throughput chart's lines.
THROUGHPUT_COLORS: dict[str, Color] = {
    "World": (0, 114, 178),
    "Particles": (0, 158, 115),
    "lesson Body": (213, 94, 0),
    "pymunk": (204, 121, 167),
    "pygame Vector2": (230, 159, 0),
}

#: Colours of the contacts chart's solvers (Okabe-Ito, as above).
SOLVER_COLORS: dict[str, Color] = {
    "World": (0, 114, 178),  # blue: this engine
    "pymunk": (204, 121, 167),  # reddish purple, as on the throughput chart
    "pymunk 1 mm": (213, 94, 0),  # vermillion
}

#: The contacts chart's legend.
SOLVER_LABELS: dict[str, str] = {
    "World": "this engine (World.contact_iterations)",
    "pymunk": "pymunk (Space.iterations), collision_slop 0.1 m: its default",
    "pymunk 1 mm": "pymunk, collision_slop 1 mm: the overlap this engine leaves alone",
}

#: Short names for the contacts chart's captions.
_SHORT = {"World": "this engine", "pymunk": "pymunk", "pymunk 1 mm": "pymunk 1 mm"}

_FLOOR = 1e-16  # m: errors below this (round-off) are drawn on the bottom line
_LEVEL = 1e-3  # m: the accuracy each panel's verdict is given for (1 mm)


def _verdict(points: Sequence[Point], problem: str) -> str:
    """One line: the method with the least work to stay within 1 mm, and the runner-up."""
    best: dict[str, Point] = {}
    for p in points:
        if p.problem != problem or p.method == "auto" or p.warned or not p.finite:
            continue
        if p.error <= _LEVEL and (p.method not in best or p.work < best[p.method].work):
            best[p.method] = p
    if not best:
        return "No method stays within 1 mm at these steps."
    ranked = sorted(best.values(), key=lambda p: p.work)
    first = ranked[0]
    text = f"For 1 mm: {LABELS[first.method]} at dt = 1/{round(1 / first.dt)} s is cheapest"
    if len(ranked) > 1:
        runner = ranked[1]
        text += f"; {LABELS[runner.method]} {runner.work / first.work:.1f}x the work"
    return text + "."


def _hidden_under(points: Sequence[Point]) -> list[tuple[str, str]]:
    """Pairs (below, above) of methods whose lines coincide on the chart, the lower one hidden.

    Coinciding means the same steps, errors within 5% and work (steps + force evaluations, the
    machine-free cost) within 1.5x at every step: explicit and semi-implicit Euler under
    constant gravity, whose errors are -+ g dt t / 2. Work, not the timed cost, so that timer
    noise on one fast point cannot make the label come and go.
    Round-off-level errors (< 1e-12 m) are labelled as exact instead.
    """
    order = [m for m in COLORS if m != "auto"]  # the drawing order: later lines cover earlier
    series = {m: sorted((p for p in points if p.method == m), key=lambda p: p.dt) for m in order}
    pairs = []
    for i, below in enumerate(order):
        for above in order[i + 1 :]:
            a, b = series[below], series[above]
            if (
                a
                and [p.dt for p in a] == [p.dt for p in b]
                and all(
                    p.finite
                    and q.finite
                    and min(p.error, q.error) > 1e-12
                    and math.isclose(p.error, q.error, rel_tol=0.05)
                    and max(p.work, q.work) <= 1.5 * min(p.work, q.work)
                    for p, q in zip(a, b, strict=True)
                )
            ):
                pairs.append((below, above))
                break
    return pairs


def _canvas(size: tuple[int, int], title: str, subtitle: str) -> pygame.Surface:
    """A blank chart page of ``size`` px with its title and a one-line subtitle."""
    init_headless()
    surface = pygame.Surface(size)
    surface.fill(PAPER)
    draw_text(surface, title, (20, 10), 32)
    draw_text(surface, subtitle, (20, 42), 18, MUTED)
    return surface


def _wrap(text: str, width: int, size: int = 16) -> list[str]:
    """``text`` split at spaces into lines no wider than ``width`` px at ``size`` px."""
    lines: list[str] = []
    for word in text.split():
        if lines and font(size).size(f"{lines[-1]} {word}")[0] <= width:
            lines[-1] = f"{lines[-1]} {word}"
        else:
            lines.append(word)
    return lines


#: The pendulum panel's methods, drawn widest first so that lines lying on one another (the
#: three with one error, where their costs come out alike) show as nested bands: (method as
#: measured, colour key, line width, dot radius).
_PENDULUM_STYLE = (
    ("semi_implicit_euler", "semi_implicit_euler", 2, 4),
    ("velocity_verlet", "velocity_verlet", 12, 8),
    ("rk4", "rk4", 7, 6),
    ("auto", "exact", 2, 4),
)


#: The pendulum panel's note: what its three parallel lines are (the same energy error at each
#: dt, each method at its own cost, so the lines lie side by side, not on one another).
PENDULUM_NOTE = ("Verlet, RK4, closed form: same errors,", "their own costs: three parallel lines")


def _pendulum_captions(rows: Sequence[pendulum.Row]) -> list[str]:
    """The pendulum panel's captions: what is measured, and the errors at the smallest dt."""
    dt = min(r.dt for r in rows)
    at = {r.method: r for r in rows if r.dt == dt}
    periods = rows[0].steps * rows[0].dt / pendulum.period(pendulum.THETA0)
    text = [
        f"Energy: largest |E - E0| / (m g L) over {periods:.0f} periods from 90\u00b0, "
        "dt = 1/30 s and halved.",
    ]
    if {"velocity_verlet", "rk4", "auto", "semi_implicit_euler"} <= at.keys():
        same = at["auto"].energy
        text.append(
            f"At dt = 1/{round(1 / dt)} s: Verlet, RK4 and closed form (auto) all {same:.1e}; "
            f"semi-implicit Euler {at['semi_implicit_euler'].energy:.1e}."
        )
    return text


def _pendulum_panel(
    surface: pygame.Surface, rows: Sequence[pendulum.Row], rect: tuple[int, int, int, int]
) -> None:
    """Energy error against CPU time per simulated second, one line per method."""
    costs = [r.cost / r.dt for r in rows]
    chart = LogLogChart(
        rect,
        decade_range(costs),
        decade_range([r.energy for r in rows]),
        "Pendulum on a rod (links)",
        "cost: CPU time per simulated second (s)",
        "largest energy error / (m g L)",
    )
    chart.draw_frame(surface)
    for method, colour, width, radius in _PENDULUM_STYLE:
        series = sorted((r for r in rows if r.method == method), key=lambda r: -r.dt)
        if series:
            chart.draw_series(
                surface,
                [r.cost / r.dt for r in series],
                [r.energy for r in series],
                COLORS[colour],
                width=width,
                radius=radius,
            )
    a = chart.area
    for row, line in enumerate(PENDULUM_NOTE):
        draw_text(surface, line, (a.right - 6, a.top + 4 + 17 * row), 16, INK, "topright")


def draw_work_precision(
    points: Sequence[Point],
    size: tuple[int, int] = (1280, 720),
    pendulum_rows: Sequence[pendulum.Row] = (),
) -> pygame.Surface:
    """The work-precision chart: one panel per problem, error (m) against cost (s per s), and
    with ``pendulum_rows`` a last panel: the pendulum's energy error against its cost."""
    width, height = size
    surface = _canvas(
        size,
        "Speed against accuracy: which integrator should I use?",
        "Each dot: one run of 1 s of simulated time with step dt, halved from dot to dot "
        "(right = smaller dt). Error: largest distance from the exact answer.",
    )
    costs = [p.cost for p in points if p.cost > 0]
    x_dec = decade_range(costs)
    y_dec = (round(math.log10(_FLOOR)), 2)
    names = [name for name in PROBLEMS if any(p.problem == name for p in points)]
    margin, gap, top = 16, 12, 66
    legend_h = 74
    panels = len(names) + (1 if pendulum_rows else 0)
    panel_w = (width - 2 * margin - gap * (panels - 1)) // max(1, panels)
    # The captions under each panel, wrapped to its width; the panels leave room for the most.
    head = "Lower = more accurate, further left = cheaper: lowest line wins."
    captions = [_wrap(head, panel_w - 8) + _wrap(_verdict(points, n), panel_w - 8) for n in names]
    if pendulum_rows:
        captions.append(
            [x for c in _pendulum_captions(pendulum_rows) for x in _wrap(c, panel_w - 8)]
        )
    lines = max([2, *map(len, captions)])
    panel_h = height - top - legend_h - 22 - 19 * lines
    for i, name in enumerate(names):
        left = margin + i * (panel_w + gap)
        chart = LogLogChart(
            (left, top, panel_w, panel_h),
            x_dec,
            y_dec,
            PROBLEMS[name].title,
            "cost: run time per simulated second (s)",
            "largest position error (m)",
            y_label_every=2,
        )
        chart.draw_frame(surface)
        mine = [p for p in points if p.problem == name]
        for method in sorted(COLORS, key=lambda m: m != "auto"):  # auto first, underneath
            # Largest dt first: along the line, dt halves from dot to dot.
            series = sorted((p for p in mine if p.method == method), key=lambda p: -p.dt)
            if not series:
                continue
            auto = method == "auto"
            chart.draw_series(
                surface,
                [p.cost for p in series],
                [p.error if p.finite else math.inf for p in series],
                COLORS[method],
                width=10 if auto else 2,
                radius=8 if auto else 4,
                hollow=None if auto else [p.warned for p in series],
            )
        for row, (below, above) in enumerate(_hidden_under(mine)):
            # Two lines that coincide: say so, or the reader looks for a method that is missing.
            y = chart.area.top + 14 + 38 * row
            where = (chart.area.right - 6, y)
            draw_text(surface, f"{LABELS[below]} lies under", where, 16, COLORS[below], "midright")
            where = (chart.area.right - 6, y + 17)
            draw_text(surface, f"{LABELS[above]}: same error", where, 16, INK, "midright")
        if PROBLEMS[name].closed_form:
            note = "Verlet, RK4, closed form: exact (round-off)"
            exact_y = float(chart.to_px(1.0, 1e-12)[1])
            for row, line in enumerate(_wrap(note, chart.area.width - 12)):
                at = (float(chart.area.right - 6), exact_y + 17 * row)
                draw_text(surface, line, at, 16, INK, "midright")
        cap_y = top + panel_h + 6
        for row, line in enumerate(captions[i]):
            draw_text(surface, line, (left + 4, cap_y + 19 * row), 16, INK)
    if pendulum_rows:
        left = margin + len(names) * (panel_w + gap)
        _pendulum_panel(surface, pendulum_rows, (left, top, panel_w, panel_h))
        for row, line in enumerate(captions[-1]):
            draw_text(surface, line, (left + 4, top + panel_h + 6 + 19 * row), 16, INK)
    items = [(LABELS[m], COLORS[m], 10 if m == "auto" else 2) for m in COLORS]
    draw_legend(surface, items, (margin, height - legend_h), width - 2 * margin)
    draw_text(
        surface,
        "Hollow dot: dt past the method's stability limit (the engine warns). Cross at a panel's "
        "top: the run blew up (no finite answer). Slope -p on these axes means order p.",
        (margin, height - 26),
        17,
        MUTED,
    )
    return surface


def draw_throughput(
    rows: Sequence[throughput.Row], size: tuple[int, int] = (1280, 720)
) -> pygame.Surface:
    """The throughput chart: ns per body-step against the number of bodies, one line each."""
    width, height = size
    surface = _canvas(
        size,
        "Throughput: how many bodies can one step move?",
        "Semi-implicit Euler under gravity, measured side by side in one run (medians). "
        "Lower = faster per body.",
    )
    chart = LogLogChart(
        (16, 66, width - 32, height - 66 - 90),
        decade_range([r.bodies for r in rows]),
        decade_range([r.ns for r in rows]),
        "Cost per body per step",
        "number of bodies",
        "time per body-step (ns)",
    )
    chart.draw_frame(surface)
    names = [n for n in throughput.IMPLEMENTATIONS if any(r.implementation == n for r in rows)]
    for name in names:
        mine = sorted((r for r in rows if r.implementation == name), key=lambda r: r.bodies)
        chart.draw_series(
            surface, [r.bodies for r in mine], [r.ns for r in mine], THROUGHPUT_COLORS[name], 3, 5
        )
    items = [(name, THROUGHPUT_COLORS[name], 3) for name in names]
    draw_legend(surface, items, (16, height - 84), width - 32)
    draw_text(
        surface,
        "Python loops pay per body; arrays pay per step, so their cost per body falls until "
        "memory bandwidth sets the floor.",
        (16, height - 30),
        18,
        MUTED,
    )
    return surface


@dataclass(frozen=True)
class _Panel:
    """One panel of the contacts chart: which scene and measure, its axis and its notes."""

    scene: str
    measure: str  # a Row attribute: "error" or "energy"
    title: str
    y_label: str  # "{seconds}" in it: the scene's run, from its rows (--quick's stacks are short)
    zero: str  # what a value of 0 (drawn on the bottom line) means
    floor: int | None = None  # the bottom decade, if fixed
    level: float | None = None  # a target drawn as a dashed line, with its label
    level_label: str = ""


_CONTACT_PANELS = (
    _Panel(
        "pit",
        "error",
        f"Ball pit ({solver.PIT_BALLS}): overlap at rest",
        f"deepest overlap after {solver.PIT_SETTLE:g} s / radius",
        "",
        level=0.01,
        level_label="1% of r",
    ),
    _Panel(
        "pit",
        "energy",
        "Ball pit: is it still?",
        f"kinetic / potential energy after {solver.PIT_SETTLE:g} s",
        "bottom line: 0, asleep",
    ),
    _Panel(
        "cradle",
        "error",
        "Newton's cradle (5 balls, e = 1)",
        "speed error / v0, largest after the impacts",
        "bottom line: 0, exact",
        floor=-16,
    ),
    _Panel(
        "stack",
        "error",
        f"A tower of {solver.TOWER} boxes: drift",
        "largest displacement of a box after {seconds} s (m)",
        "",
        level=1e-3,
        level_label="1 mm: the issue's, by 60 s",
    ),
    _Panel(
        "pyramid",
        "error",
        f"A pyramid of {solver.PYRAMID_BOXES} boxes: drift",
        "largest displacement of a box after {seconds} s (m)",
        "",
        level=1e-2,
        level_label="1 cm: the issue's, by 60 s",
    ),
)


def _clusters(
    marks: list[tuple[float, float, int]], near: float
) -> list[list[tuple[float, float, int]]]:
    """Group dots (px, py, iterations) that lie within ``near`` px of one another (chained)."""
    groups: list[list[tuple[float, float, int]]] = []
    for mark in sorted(marks, key=lambda m: m[2]):
        for group in groups:
            if any(abs(mark[0] - g[0]) < near and abs(mark[1] - g[1]) < near for g in group):
                group.append(mark)
                break
        else:
            groups.append([mark])
    return groups


def _counts(group: list[tuple[float, float, int]], measured: Sequence[int]) -> str:
    """The label of a group of dots: "8", "1, 2", "1, 5, 10" or, when the group holds every
    count measured from its first to its last (``measured``), "1\u201316"."""
    ks = sorted(k for _, _, k in group)
    if len(ks) >= 3 and [k for k in measured if ks[0] <= k <= ks[-1]] == ks:
        return f"{ks[0]}\u2013{ks[-1]}"
    return ", ".join(map(str, ks))


def _level_spot(
    text: str, area: pygame.Rect, py: int, series: list[list[tuple[float, float, int]]]
) -> tuple[str, str, tuple[int, int]]:
    """A target's label and where it goes (the text, a draw_text anchor and point): beside its
    dashed line at ``py``, above it and then below, as far right as no series' line or dot
    (``series``: their dots in px, in order) crosses it; if the whole label fits nowhere, its
    part before the colon ("1 cm") the same way; else at the right end, above."""
    dots = [pygame.Rect(round(x) - 6, round(y) - 6, 12, 12) for m in series for x, y, _ in m]
    lines = [(p[:2], q[:2]) for m in series for p, q in zip(m[:-1], m[1:], strict=True)]
    texts = [text] + ([text.split(":")[0] + " target"] if ":" in text else [])
    for label in texts:
        image = font(16).render(label, True, MUTED)
        for anchor, y in (("bottomright", py - 2), ("topright", py + 3)):
            for x in range(area.right - 6, area.left + 6 + image.get_width() - 1, -4):
                rect = image.get_rect(**{anchor: (x, y)}).inflate(4, 2)
                if not area.contains(rect) or rect.collidelist(dots) >= 0:
                    continue
                if not any(rect.clipline(p, q) for p, q in lines):
                    return label, anchor, (x, y)
    return text, "bottomright", (area.right - 6, py - 2)


def _label_dots(
    surface: pygame.Surface,
    area: pygame.Rect,
    series: list[tuple[Color, list[tuple[float, float, int]]]],
    taken: list[pygame.Rect],
) -> None:
    """Write each dot's iteration count beside it, in its colour, where no other label, dot or
    rectangle of ``taken`` is: right, left, above, below or a corner; dots a few px apart share
    one label."""
    size = 16
    taken = taken + [
        pygame.Rect(round(x) - 5, round(y) - 5, 10, 10) for _, ms in series for x, y, _ in ms
    ]
    spots = (
        ("midleft", 8, 0),
        ("midright", -8, 0),
        ("midbottom", 0, -7),
        ("midtop", 0, 7),
        ("bottomleft", 5, -5),
        ("topleft", 5, 5),
        ("bottomright", -5, -5),
        ("topright", -5, 5),
        ("midleft", 22, 0),
        ("midright", -22, 0),
        ("midbottom", 0, -20),
        ("midtop", 0, 20),
        ("bottomleft", 5, -18),
        ("bottomright", -5, -18),
    )
    bounds = area.inflate(8, 8)  # a dot on an edge may have its label just over the frame
    for color, marks in series:
        measured = sorted(k for _, _, k in marks)
        for group in _clusters(marks, 11.0):
            text = _counts(group, measured)
            x = sum(m[0] for m in group) / len(group)
            y = sum(m[1] for m in group) / len(group)
            image = font(size).render(text, True, color)
            choice = None
            for anchor, dx, dy in spots:
                rect = image.get_rect(**{anchor: (round(x + dx), round(y + dy))})
                rect = rect.inflate(2, 0)
                if bounds.contains(rect) and rect.collidelist(taken) < 0:
                    choice = rect
                    break
            if choice is None:
                choice = image.get_rect(midleft=(round(x + 8), round(y))).inflate(2, 0)
            taken.append(choice)
            pygame.draw.rect(surface, (255, 255, 255), choice)
            surface.blit(image, image.get_rect(center=choice.center))


def _fewest(rows: Sequence[solver.Row], panel: _Panel, level: float) -> dict[str, solver.Row]:
    """Per solver, its setting with the fewest iterations whose measure is within ``level``
    (by iterations, not by the timed cost, so that timer noise cannot change the answer)."""
    best: dict[str, solver.Row] = {}
    for r in rows:
        if r.scene != panel.scene or not getattr(r, panel.measure) <= level:
            continue
        if r.solver not in best or r.iterations < best[r.solver].iterations:
            best[r.solver] = r
    return best


def _ms(seconds: float) -> str:
    """A step's cost for a caption: "35 ms", "0.55 ms", "9 us"."""
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.2g} ms" if seconds < 0.01 else f"{seconds * 1e3:.0f} ms"
    return f"{seconds * 1e3:.2g} ms" if seconds >= 1e-4 else f"{seconds * 1e6:.2g} us"


def _mm(metres: float) -> str:
    """A drift for a caption: "6.2 mm", "48 mm", "1.3 m"."""
    if metres >= 1.0:
        return f"{metres:.2g} m"
    return f"{metres * 1e3:.2g} mm" if metres < 0.01 else f"{metres * 1e3:.0f} mm"


def _contacts_caption(rows: Sequence[solver.Row], panel: _Panel) -> list[str]:
    """Lines under a panel: the fewest iterations that reach its target, per solver; for the
    stacks, each solver's least drift (no solver comes within the issue's levels at every
    setting, and a level reached by the window's end may still be passed by 60 s)."""
    solvers = [s for s in solver.SOLVERS if any(r.solver == s for r in rows)]
    if panel.scene in ("stack", "pyramid"):
        least: dict[str, solver.Row] = {}
        for r in rows:
            if r.scene == panel.scene and (
                r.solver not in least or r.error < least[r.solver].error
            ):
                least[r.solver] = r
        parts = [
            f"{_SHORT[s]} {_mm(least[s].error)} at {least[s].iterations} ({_ms(least[s].cost)})"
            for s in solvers
            if s in least
        ]
        return [f"Least drift: {', '.join(parts)}."]
    if panel.scene == "cradle":
        level, head = 1e-6, "Fewest iterations within 1e-6: "
    elif panel.measure == "error":
        level, head = 0.01, "Fewest iterations within 1% of r: "
    else:
        level, head = 1e-6, "Fewest iterations for KE < 1e-6 PE: "
    best = _fewest(rows, panel, level)
    parts = [
        f"{_SHORT[s]} {best[s].iterations} ({_ms(best[s].cost)})"
        if s in best
        else f"{_SHORT[s]} none"
        for s in solvers
    ]
    if len(parts) == 1:
        return [head + parts[0] + "."]
    return [head + parts[0] + ",", ", ".join(parts[1:]) + "."]


def _stack_seconds(rows: Sequence[solver.Row]) -> float:
    """The stacks' run (s) in ``rows``: every step of it timed (sleeping off); STACK_TIME when
    there are none (--quick runs them for QUICK_STACK_TIME)."""
    steps = [r.steps for r in rows if r.scene in ("stack", "pyramid")]
    return max(steps) * solver.DT if steps else solver.STACK_TIME


def draw_contacts(
    rows: Sequence[solver.Row], size: tuple[int, int] = (1280, 720)
) -> pygame.Surface:
    """The contacts chart: error against the cost of an awake step, per solver setting."""
    width, height = size
    surface = _canvas(
        size,
        "Contacts: how many solver iterations should I use?",
        "Each dot: one iteration count (the number beside it), its error against the cost of "
        "a step, all measured side by side in one run. dt = 1/60 s.",
    )
    margin, gap, top = 16, 12, 66
    legend_h = 100
    panels = [p for p in _CONTACT_PANELS if any(r.scene == p.scene for r in rows)]
    panel_w = (width - 2 * margin - gap * (len(panels) - 1)) // max(1, len(panels))
    # The captions under each panel, wrapped to its width; the panels leave room for the most.
    captions = [_wrap(" ".join(_contacts_caption(rows, p)), panel_w - 8) for p in panels]
    lines = max([2, *map(len, captions)])
    panel_h = height - top - legend_h - 24 - 19 * lines
    solvers = [s for s in solver.SOLVERS if any(r.solver == s for r in rows)]
    for i, panel in enumerate(panels):
        left = margin + i * (panel_w + gap)
        mine = [r for r in rows if r.scene == panel.scene]
        values = [getattr(r, panel.measure) for r in mine]
        x_dec = decade_range([r.cost for r in mine])
        lo, hi = decade_range([v for v in values if v > 0] + ([panel.level] if panel.level else []))
        lo = panel.floor if panel.floor is not None else lo - (1 if 0.0 in values else 0)
        if panel.level is not None and math.log10(panel.level) <= lo:
            lo -= 1  # the target's dashed line above the bottom edge, not on it
        span = hi - lo
        chart = LogLogChart(
            (left, top, panel_w, panel_h),
            x_dec,
            (lo, hi),
            panel.title,
            "cost: seconds per awake step",
            panel.y_label.replace("{seconds}", f"{_stack_seconds(rows):g}"),
            y_label_every=2 if span > 8 else 1,
        )
        chart.draw_frame(surface)
        a = chart.area
        if panel.level is not None:
            py = round(float(chart.to_px(1.0, panel.level)[1]))
            for x in range(a.left + 2, a.right - 2, 12):
                pygame.draw.line(surface, MUTED, (x, py), (min(x + 6, a.right - 2), py), 1)
        labelled: list[tuple[Color, list[tuple[float, float, int]]]] = []
        for name in solvers:
            series = sorted((r for r in mine if r.solver == name), key=lambda r: r.iterations)
            if not series:
                continue
            xs = [r.cost for r in series]
            ys = [getattr(r, panel.measure) for r in series]
            chart.draw_series(surface, xs, ys, SOLVER_COLORS[name], width=2, radius=5)
            floor = 10.0**lo
            dot_x, dot_y = chart.to_px(np.array(xs), np.maximum(np.array(ys), floor))
            dot_y = np.clip(dot_y, a.top, a.bottom - 1)
            marks = [
                (float(x), float(y), r.iterations)
                for x, y, r in zip(dot_x, dot_y, series, strict=True)
            ]
            labelled.append((SOLVER_COLORS[name], marks))
        taken: list[pygame.Rect] = []
        if panel.level is not None:  # its label is kept clear of the lines and dots' labels
            label, anchor, where = _level_spot(panel.level_label, a, py, [m for _, m in labelled])
            taken.append(draw_text(surface, label, where, 16, MUTED, anchor))
        if panel.zero and 0.0 in values:
            where = (a.left + 6, a.bottom - 4)
            taken.append(draw_text(surface, panel.zero, where, 16, INK, "bottomleft"))
        _label_dots(surface, a, labelled, taken)
        cap_y = top + panel_h + 6
        for row, line in enumerate(captions[i]):
            draw_text(surface, line, (left + 4, cap_y + 19 * row), 16, INK)
    items = [(SOLVER_LABELS[s], SOLVER_COLORS[s], 2) for s in solvers]
    draw_legend(surface, items, (margin, height - legend_h), width - 2 * margin)
    draw_text(
        surface,
        "Lower = more accurate, further left = cheaper. Cost: CPU time of an awake step (this "
        "engine puts a still pile to sleep, and its steps then cost almost nothing), the mean",
        (margin, height - 46),
        17,
        MUTED,
    )
    draw_text(
        surface,
        f"over the pit's first {solver.PIT_WINDOW:g} s (the balls fall and pile up), the "
        f"cradle's {solver.CRADLE_TIME:g} s and the boxes' {_stack_seconds(rows):g} s (sleeping "
        "off), each step's time the median of its runs (the cradle's 9, the others' 2; "
        "--quick: 1).",
        (margin, height - 26),
        17,
        MUTED,
    )
    return surface


def _write(path: Path, lines: Sequence[str]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
    tmp.replace(path)


#: auto's target against the fastest method that reaches its tolerance: at most this many times
#: its work and its run time.
AUTO_TARGET = 1.2


def over_target(ratio: float | None) -> bool:
    """Whether ``ratio`` (auto's over the best's) misses AUTO_TARGET, as printed (2 decimals:
    a row that reads 1.20x is within it, one that reads 1.21x is not)."""
    return ratio is not None and math.isfinite(ratio) and round(ratio, 2) > AUTO_TARGET


def summary(points: Sequence[Point], timed: dict[int, float] | None = None) -> str:
    """Slopes on the spring and auto against the best method at each tolerance, as text.

    ``timed``: auto's run time over the best's, by the row's index, measured side by side. A
    row whose work or time misses AUTO_TARGET ends in "OVER 1.2x" and says which, and a line
    after the table counts them."""
    lines = ["spring: slope of log error against log dt (asymptotic range; expected 1, 1, 2, 4)"]
    for method in ("explicit_euler", "semi_implicit_euler", "velocity_verlet", "rk4"):
        s = measure.slope(points, "spring", method)
        lines.append(f"  {LABELS[method]:<22} {'-' if s is None else f'{s:.3f}'}")
    target = f"{AUTO_TARGET:g}x"
    lines.append(f"auto against the fastest method reaching its tolerance (target <= {target}):")
    ratios = measure.auto_ratios(points)
    over = 0
    for i, r in enumerate(ratios):
        best = "none" if r.best is None else f"{LABELS[r.best.method]} dt={r.best.dt:g}"
        t = timed.get(i) if timed else None
        time_txt = "" if t is None else f", time {t:.2f}x"
        missed = [name for name, x in (("work", r.work_ratio), ("time", t)) if over_target(x)]
        over += bool(missed)
        flag = f"  OVER {target} ({', '.join(missed)})" if missed else ""
        lines.append(
            f"  {r.problem:<8} tol {r.tolerance:<7.0e} auto: {LABELS[r.auto.chosen]} "
            f"dt={r.auto.dt:g} error {r.auto.error:.2g} m{'' if r.met else ' (NOT MET)'}; "
            f"best: {best}; work {r.work_ratio:.2f}x{time_txt}{flag}"
        )
    if ratios:
        lines.append(
            f"  {over} of {len(ratios)} rows over the {target} target (marked OVER)"
            if over
            else f"  every row within the {target} target"
        )
    return "\n".join(lines)


#: What a run writes into its folder.
OUTPUTS = (
    "work_precision.png",
    "work_precision.csv",
    "pendulum.csv",
    "throughput.png",
    "throughput.csv",
    "contacts.png",
    "contacts.csv",
)


@dataclass(frozen=True)
class Sweep:
    """What the work-precision part of a run measures (the full run's, or --quick's)."""

    dts: tuple[float, ...]  # s: each method's steps, halved from one to the next
    tolerances: tuple[float, ...]  # m: the error levels "auto" is given
    repeats: int  # timed repetitions of each point (their median counts)
    min_steps: int  # steps a repetition takes at least (fresh Worlds until then)
    rounds: int  # rounds of auto's side-by-side timing against its best rival


#: The full run's sweep: dt = 1/4 to 1/8192 s, tolerances 1e-1 to 1e-10 m.
FULL = Sweep(tuple(measure.sweep_dts()), tuple(measure.auto_tolerances()), 5, 2000, 9)
#: --quick's: dt = 1/4 to 1/256 s (three steps in the spring's asymptotic range, enough for its
#: slopes), tolerances 1e-1 to 1e-7 m (the finest that RK4 meets at 1/256 s on the spring),
#: short timings. Its other parts are quick too (each bench's ``quick``): the pendulum over 4
#: periods at 2 steps, the throughput to 10^3 bodies, the contacts at 2 iteration counts a
#: solver, the stacks for 2 s. All in 10 to 20 s here (TAKES); most of it is the contacts.
QUICK = Sweep(tuple(2.0**-k for k in range(2, 9)), tuple(10.0**-k for k in range(1, 8)), 2, 50, 3)

#: How long a whole run takes, measured on the 2-core machine the project is built on
#: (`python -m demos tradeoff`: 132 s alone on 2026-11-25, about 170 s beside another job;
#: --quick: 15.3 s on 2026-12-02, 14.8 s of it CPU time, beside one other job, where its
#: measurements before QUICK was cut down took 45.8 s the same way): said before it starts, and
#: on its progress lines. The kernels' first compile (once per install, 20 to 80 s) is not in it.
TAKES = {False: "about 2 to 3 minutes", True: "about 10 to 20 seconds"}


def run(args: argparse.Namespace) -> int:
    """Measure, write the charts and CSVs, print the tables; the CLI's hook."""
    quick = bool(getattr(args, "quick", False))
    out = Path(args.out) if getattr(args, "out", None) else Path("out") / "tradeoff"
    size = tuple(getattr(args, "size", None) or DEMO.size)
    overwrite = bool(getattr(args, "overwrite", False))
    there = [name for name in OUTPUTS if (out / name).exists()]
    if there and not overwrite:  # refused before minutes of measuring, not after
        raise FramesExistError(
            f"{out} already holds {', '.join(there)}; pass overwrite=True to replace them",
            out / there[0],
        )
    takes = TAKES[quick]
    other = (
        f"--quick; the full sweep takes {TAKES[False]}"
        if quick
        else f"--quick: a coarser sweep in {TAKES[True]}"
    )
    print(f"tradeoff: four measurements, {takes} in all on a 2-core machine ({other})")

    def bar_for(step: int, what: str) -> Progress:
        return Progress(label=f"tradeoff {step}/4 ({takes} in all): {what}", unit="runs")

    bar = bar_for(1, "integrators")
    print(f"tradeoff: measuring {'(quick) ' if quick else ''}the work-precision sweep ...")
    plan = QUICK if quick else FULL
    points = measure.sweep(
        PROBLEMS.values(),
        dts=plan.dts,
        repeats=plan.repeats,
        tolerances=plan.tolerances,
        progress=lambda done, total, label: bar(done, total),
        min_steps=plan.min_steps,
    )
    bar.done()
    print("tradeoff: measuring the pendulum on a rod (energy over many periods) ...")
    bar = bar_for(2, "pendulum")
    swing = pendulum.measure(quick, progress=bar)
    bar.done()
    print(pendulum.table(swing))
    _write(out / "pendulum.csv", [pendulum.csv_header(), *map(pendulum.csv_row, swing)])
    csv_path = out / "work_precision.csv"
    _write(csv_path, [measure.csv_header(), *map(measure.csv_row, points)])
    chart = draw_work_precision(points, size, swing)
    png_path = save_png(chart, out / "work_precision.png", True)  # (checked at the start)
    print(
        f"tradeoff: wrote {png_path}, {csv_path} and {out / 'pendulum.csv'} ({len(points)} points)"
    )
    # auto against its best rival, timed side by side (interleaved rounds: fair on a busy box).
    # A rival that is the best at several tolerances is one run, timed once.
    runs: list[tuple[measure.Problem, str, float, float | None]] = []
    where: dict[tuple[str, str, float, float | None], int] = {}

    def slot(problem: str, method: str, dt: float, tolerance: float | None) -> int:
        key = (problem, method, dt, tolerance)
        if key not in where:
            where[key] = len(runs)
            runs.append((PROBLEMS[problem], method, dt, tolerance))
        return where[key]

    pairs = [
        (
            i,
            slot(r.problem, "auto", r.auto.dt, r.tolerance),
            slot(r.problem, r.best.method, r.best.dt, None),
        )
        for i, r in enumerate(measure.auto_ratios(points))
        if r.best is not None
    ]
    times = measure.side_by_side(runs, rounds=plan.rounds, min_steps=plan.min_steps)
    timed = {i: times[a] / times[b] for i, a, b in pairs}
    print(summary(points, timed))
    print(f"tradeoff: measuring throughput (3/4; {takes} in all) ...")
    rows = throughput.measure(quick)
    _write(
        out / "throughput.csv",
        ["implementation,bodies,ns_per_body_step"]
        + [f"{r.implementation},{r.bodies},{r.ns:.6g}" for r in rows],
    )
    tp = save_png(draw_throughput(rows, size), out / "throughput.png", True)
    print(throughput.table(rows))
    print(f"tradeoff: wrote {tp} and {out / 'throughput.csv'}")
    print("tradeoff: measuring contacts (solver iterations, this engine and pymunk) ...")
    bar = bar_for(4, "contacts")
    contact_rows = solver.measure(quick, progress=bar)
    bar.done()
    _write(out / "contacts.csv", [solver.csv_header(), *map(solver.csv_row, contact_rows)])
    cp = save_png(draw_contacts(contact_rows, size), out / "contacts.png", True)
    print(solver.table(contact_rows))
    print(f"tradeoff: wrote {cp} and {out / 'contacts.csv'}")
    sys.stdout.flush()
    return 0


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--quick",
        action="store_true",
        help=f"a coarser sweep, {TAKES[True]} (for CI and tries)",
    )


DEMO = Demo(
    name="tradeoff",
    summary="Work-precision chart (error vs cost per integrator), throughput and contacts charts",
    add_arguments=_add_arguments,
    run=run,
    takes=frozenset({"--size", "--out", "--overwrite"}),
    size=(1280, 720),
    min_size=(1280, 720),  # its smallest: each panel then holds its words
)
