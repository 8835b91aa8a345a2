"""The stability lesson: one spring, four integrators side by side, and where each one breaks.

    python -m demos stability              # frames: out/stability/orbits/, out/stability/limits/
    python -m demos stability --window     # the same in a window

Scene ``orbits``: a mass on a spring (1 Hz, rest length 0) set moving on a circle, stepped by
explicit Euler, semi-implicit Euler, velocity Verlet and RK4 at the same dt (omega dt = 0.63),
with each one's energy E/E0 plotted under it. Explicit Euler multiplies the energy by exactly
1 + (omega dt)^2 every step and spirals out; semi-implicit Euler and Verlet keep a slightly
squashed orbit with bounded energy; RK4 follows the circle but loses a little energy each step.

Scene ``limits``: the same four, with dt raised every second across each method's limit
(omega dt < 2 for the Eulers' and Verlet's spring, 2 sqrt(2) for RK4; explicit Euler has no
stable dt). The engine's StabilityWarning is shown as each limit is passed and its
SimulationDiverged error when a method blows up; the World keeps the last finite state, so no
non-finite number is ever drawn.
"""

from __future__ import annotations

import copy
import math
import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np
import pygame

from demos.cli import Demo
from engine import Body, SimulationDiverged, StabilityWarning, Vector, World
from engine.forces import Spring
from engine.integrators import INTEGRATORS
from engine.render import GRID, INK, MUTED, PAPER, Plot, Scene, draw_text, font, marks
from engine.stability import OSCILLATION_LIMITS

__all__ = ["OrbitsScene", "LimitsScene", "wrap", "fitting", "DEMO"]

Color = tuple[int, int, int]

OMEGA = 2.0 * math.pi  # rad/s: the spring's angular frequency (1 Hz on 1 kg)
METHODS = tuple(INTEGRATORS)  # explicit Euler, semi-implicit Euler, Verlet, RK4
COLORS: dict[str, Color] = {
    "explicit_euler": (213, 94, 0),
    "semi_implicit_euler": (86, 180, 233),
    "velocity_verlet": (0, 158, 115),
    "rk4": (0, 114, 178),
}
LABELS = {
    "explicit_euler": "explicit Euler",
    "semi_implicit_euler": "semi-implicit Euler",
    "velocity_verlet": "velocity Verlet",
    "rk4": "RK4",
}
WARN: Color = (200, 120, 0)
ERROR: Color = (190, 30, 30)
VIEW = 1.7  # m: each orbit panel shows [-VIEW, VIEW] in x and y


def wrap(text: str, size: int, width: int) -> list[str]:
    """``text`` broken into lines of at most ``width`` px in the built-in font at ``size``."""
    f = font(size)
    lines: list[str] = []
    line = ""
    for word in text.split():
        trial = f"{line} {word}".strip()
        if f.size(trial)[0] <= width or not line:
            line = trial
        else:
            lines.append(line)
            line = word
    if line:
        lines.append(line)
    return lines


def fitting(options: Sequence[str], size: int, width: float) -> str:
    """The first of ``options`` (longest first) that fits ``width`` px at ``size``, or the last."""
    f = font(size)
    return next((text for text in options if f.size(text)[0] <= width), options[-1])


def _spring_world(method: str) -> tuple[World, Body]:
    """A World with one 1 kg body on a circular orbit of radius 1 m around a spring's anchor."""
    world = World(integrator=method)
    body = world.add(Body(Vector(1.0, 0.0), Vector(0.0, OMEGA), Vector(0.0, 0.0)))
    world.add_force(Spring((0.0, 0.0), k=OMEGA * OMEGA))
    return world, body


class _FourSprings(Scene):
    """Shared parts: four worlds, their panels, messages from the engine, what was drawn."""

    #: Four panels with their energy plots need this much room (px).
    min_size = (300, 190)

    def build(self, size: tuple[int, int]) -> None:
        self.size = size
        self.worlds: dict[str, tuple[World, Body]] = {m: _spring_world(m) for m in METHODS}
        self.status: dict[str, str] = dict.fromkeys(METHODS, "stable")  # stable/warned/diverged
        self.messages: dict[str, str] = {}  # method -> the engine's latest warning or error text
        self.latest: tuple[str, str] | None = None  # (method, text) of the message on show
        self.queue: list[tuple[str, str]] = []  # messages waiting for their turn on screen
        self.shown_for = 0  # scene steps the message on show has been up
        self.drawn_text: list[str] = []  # every string the last draw() wrote (for tests)
        self.drawn_positions: list[tuple[float, float]] = []  # world points the last draw() used
        self.e0 = 0.5 * OMEGA * OMEGA + 0.5 * OMEGA * OMEGA  # J: kinetic + spring at the start
        self.world = self.worlds["rk4"][0]  # the scene's clock for Scene.time()
        self.camera = None
        self.trail_length = 40
        self.trails: dict[str, list[tuple[float, float]]] = {m: [] for m in METHODS}

    #: What the scene notes beside its worlds, saved with them by :meth:`snapshot`.
    saved: tuple[str, ...] = ("status", "messages", "latest", "queue", "shown_for", "trails")

    def snapshot(self) -> dict[str, Any]:
        """Every method's World, and the notes beside them (``saved``), copied."""
        notes = {name: copy.deepcopy(getattr(self, name)) for name in self.saved}
        return {"worlds": {m: world.snapshot() for m, (world, _) in self.worlds.items()}, **notes}

    def restore(self, snapshot: dict[str, Any]) -> None:
        """Return every World and note to the moment ``snapshot()`` was taken."""
        for method, (world, _) in self.worlds.items():
            world.restore(snapshot["worlds"][method])
        for name in self.saved:
            setattr(self, name, copy.deepcopy(snapshot[name]))

    def _step_method(self, method: str, dt: float) -> None:
        """One step of ``method``'s world, turning the engine's warning/error into messages."""
        if self.status[method] == "diverged":
            return
        world = self.worlds[method][0]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", StabilityWarning)
            try:
                world.step(dt)
            except SimulationDiverged as exc:
                self.status[method] = "diverged"
                self._message(method, f"SimulationDiverged: {exc}")
        for w in caught:
            if issubclass(w.category, StabilityWarning):
                if self.status[method] == "stable":
                    self.status[method] = "warned"
                self._message(method, f"StabilityWarning: {w.message}")

    def _message(self, method: str, text: str) -> None:
        self.messages[method] = text
        self.queue.append((method, text))

    def _next_message(self, hold: int) -> None:
        """Put the next queued message on show once the current one was up ``hold`` steps."""
        self.shown_for += 1
        if self.queue and (self.latest is None or self.shown_for >= hold):
            self.latest = self.queue.pop(0)
            self.shown_for = 0

    def _text(
        self,
        surface: pygame.Surface,
        text: str,
        pos: Any,
        size: int,
        color: Color,
        anchor: str = "topleft",
    ) -> pygame.Rect:
        self.drawn_text.append(text)
        return draw_text(surface, text, pos, size, color, anchor)

    def _orbit_panel(
        self,
        surface: pygame.Surface,
        rect: pygame.Rect,
        method: str,
        alpha: float,
        ahead: bool = False,
    ) -> None:
        """The orbit of ``method`` in ``rect``: the true circle, the recent path, the body.

        ``ahead``: the world's last step is past the time shown, so its trail leaves it out.
        """
        pygame.draw.rect(surface, (255, 255, 255), rect, border_radius=4)
        pygame.draw.rect(surface, GRID, rect, 1, border_radius=4)
        world, body = self.worlds[method]
        scale = (min(rect.width, rect.height) - 8) / (2 * VIEW)  # px per m
        cx, cy = rect.center

        # A runaway body is drawn at the edge of the orbit's square, kept clear of the rows of
        # words along the panel's top and bottom.
        room = rect.inflate(-2 * 9, -2 * 24)

        def px(p: tuple[float, float]) -> tuple[float, float]:
            x = min(max(p[0], -VIEW), VIEW)
            y = min(max(p[1], -VIEW), VIEW)
            return (
                min(max(cx + x * scale, room.left), room.right),
                min(max(cy - y * scale, room.top), room.bottom),
            )

        pygame.draw.circle(surface, GRID, (cx, cy), round(scale), 1)  # the exact orbit
        pygame.draw.circle(surface, INK, (cx, cy), 3)  # the spring's anchor
        trail = self.trails[method][:-1] if ahead else self.trails[method]
        if len(trail) >= 2:
            pts = [px(p) for p in trail]
            pygame.draw.lines(surface, COLORS[method], False, pts, 2)
        pos = world.position_of(body, alpha if self.status[method] != "diverged" else 1.0)
        assert isinstance(pos, Vector)
        p = (float(pos.x), float(pos.y))
        self.drawn_positions.append(p)
        self.drawn_positions.extend(trail)
        q = px(p)
        pygame.draw.line(surface, MUTED, (cx, cy), q, 1)  # the spring
        pygame.draw.circle(surface, COLORS[method], (round(q[0]), round(q[1])), 7)
        marks.note(surface, "marker", pygame.Rect(round(q[0]) - 7, round(q[1]) - 7, 15, 15))
        if abs(p[0]) > VIEW or abs(p[1]) > VIEW:
            r = math.hypot(*p)
            options = [f"off the panel: |x| = {r:.2g} m", f"off: |x| = {r:.2g} m", f"{r:.2g} m"]
            self._text(
                surface,
                fitting(options, 14, rect.width - 6),
                (rect.centerx, rect.bottom - 4),
                14,
                ERROR,
                "midbottom",
            )

    def _remember(self) -> None:
        for method in METHODS:
            world, body = self.worlds[method]
            pos = body.pos
            self.trails[method].append((float(pos[0]), float(pos[1])))
            del self.trails[method][: -self.trail_length]


class OrbitsScene(_FourSprings):
    """Four integrators on one spring at omega dt = 0.63, with each one's energy below."""

    name = "orbits"
    summary = "one spring, four integrators at the same dt, energy of each plotted under it"
    duration = 6.0
    dt = 0.1  # s: omega dt = 0.63
    saved = (*_FourSprings.saved, "energy")

    def build(self, size: tuple[int, int]) -> None:
        super().build(size)
        self.trail_length = 400
        self.energy: dict[str, list[tuple[float, float]]] = {m: [(0.0, 1.0)] for m in METHODS}
        self._remember()

    def step(self, dt: float) -> None:
        """One step of dt for each of the four worlds; record each one's energy E/E0."""
        for method in METHODS:
            self._step_method(method, dt)
            world = self.worlds[method][0]
            self.energy[method].append((world.t, world.energy() / self.e0))
        self._remember()

    def shown(self, alpha: float) -> tuple[float, bool]:
        """(the time of the frame, whether the worlds' last step is past it).

        A method knows its state only at whole steps, so a frame shows each world as it was
        at its last step at or before the frame's time: the state, its energy and its path
        so far are the method's own, never a blend of two steps nor one from after the frame.
        """
        t = self.time(alpha)
        return t, self.world.t > t + 1e-9

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """Four orbit panels side by side, each with its energy plot under it."""
        self.drawn_text, self.drawn_positions = [], []
        w, h = surface.get_size()
        surface.fill(PAPER)
        t, ahead = self.shown(alpha)
        step_t = self.world.t - self.dt if ahead else self.world.t
        clock = f"t = {t:.2f} s: step {round(step_t / self.dt)}"
        room = w - 16 - 12 - font(20).size(clock)[0]
        titles = [
            f"One spring, four integrators, the same dt = {self.dt:g} s "
            f"(omega dt = {OMEGA * self.dt:.2f})",
            f"Four integrators, dt = {self.dt:g} s (omega dt = {OMEGA * self.dt:.2f})",
            f"dt = {self.dt:g} s",
        ]
        self._text(surface, fitting(titles, 20, room), (8, 4), 20, INK)
        self._text(surface, clock, (w - 8, 4), 20, INK, "topright")
        col = w // 4
        orbit_h = int(h * 0.50)
        for i, method in enumerate(METHODS):
            left = i * col + 4
            self._text(surface, LABELS[method], (left + 4, 26), 18, COLORS[method])
            rect = pygame.Rect(left, 44, col - 8, orbit_h)
            self._orbit_panel(surface, rect, method, 0.0 if ahead else 1.0, ahead)
            ts, es = zip(*[p for p in self.energy[method] if p[0] <= t + 1e-9], strict=True)
            plot = Plot(
                (left, 48 + orbit_h, col - 8, h - orbit_h - 52),
                self.duration,
                (0.0, 2.0),
                "energy E/E0",
                t_step=2.0,
                y_step=0.5,
                color=COLORS[method],
            )
            plot.draw(surface, ts, es)
            now = es[-1]
            self._text(
                surface,
                f"E/E0 = {now:.3g}",
                (rect.left + 6, rect.top + 4),
                16,
                ERROR if now > 2 else INK,
            )


class LimitsScene(_FourSprings):
    """dt raised every second across each method's limit: the engine warns, then raises."""

    name = "limits"
    summary = "dt swept upward across each method's stability limit: warnings, then blow-ups"
    #: omega dt of each phase; each lasts PHASE seconds of the scene, the last one longer.
    STEPS = (0.5, 1.0, 1.5, 1.9, 2.1, 2.4, 2.7, 2.9, 3.2, 3.6)
    PHASE = 1.0  # s
    SUBSTEPS = 16  # method steps per scene step: the blow-ups need hundreds of steps
    duration = 11.5
    dt = 1.0 / 30.0
    saved = (*_FourSprings.saved, "scene_steps", "omega_dt")

    def build(self, size: tuple[int, int]) -> None:
        super().build(size)
        self.scene_steps = 0
        self.omega_dt = self.STEPS[0]
        self._remember()

    def step(self, dt: float) -> None:
        """Advance each live method SUBSTEPS steps at this phase's dt (omega dt from STEPS)."""
        phase = min(int(self.scene_steps * dt / self.PHASE), len(self.STEPS) - 1)
        self.omega_dt = self.STEPS[phase]
        h = self.omega_dt / OMEGA
        for method in METHODS:
            for _ in range(self.SUBSTEPS):
                self._step_method(method, h)
        self.scene_steps += 1
        self._next_message(hold=12)  # each message stays up at least 0.4 s
        self._remember()

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """Four orbits with their state, the omega dt ruler with the limits, the engine's text."""
        self.drawn_text, self.drawn_positions = [], []
        w, h = surface.get_size()
        surface.fill(PAPER)
        self._text(surface, f"Raising dt: omega dt = {self.omega_dt:.2f}", (8, 4), 20, INK)
        col = w // 4
        strip = max(64, h // 4)
        ruler_h = 52
        orbit_h = h - 44 - strip - ruler_h - 8
        for i, method in enumerate(METHODS):
            left = i * col + 4
            self._text(surface, LABELS[method], (left + 4, 26), 18, COLORS[method])
            rect = pygame.Rect(left, 44, col - 8, orbit_h)
            self._orbit_panel(surface, rect, method, 1.0)
            state = self.status[method]
            texts, color = {
                "stable": (["stable"], (0, 130, 60)),
                "warned": (["WARNING: past its limit", "WARNING"], WARN),
                "diverged": (["DIVERGED: stopped", "DIVERGED"], ERROR),
            }[state]
            self._text(surface, fitting(texts, 15, rect.width - 10), (left + 6, 46), 15, color)
        self._ruler(surface, pygame.Rect(16, 44 + orbit_h + 4, w - 32, ruler_h))
        top = h - strip
        pygame.draw.rect(surface, (255, 255, 255), (4, top, w - 8, strip - 4), border_radius=4)
        if self.latest is None:
            self._text(
                surface,
                "The engine has said nothing: every method is within its limit.",
                (10, top + 4),
                16,
                MUTED,
            )
            return
        method, message = self.latest
        color = ERROR if message.startswith("SimulationDiverged") else WARN
        self._text(
            surface, f"The engine, about {LABELS[method]}:", (10, top + 3), 16, COLORS[method]
        )
        y = top + 20
        for line in wrap(message, 15, w - 24):
            if y > h - 16:
                break
            self._text(surface, line, (10, y), 15, color)
            y += 14

    def _ruler(self, surface: pygame.Surface, rect: pygame.Rect) -> None:
        """omega dt from 0 to 4 with each method's limit marked and the current value."""
        hi = 4.0

        def x_of(v: float) -> int:
            return round(rect.left + v / hi * rect.width)

        # Three rows: the limits' names on top, the marker of omega dt now just above the
        # line, the numbers under it; so the marker never covers a name, wherever it is.
        y = rect.top + 24
        pygame.draw.line(surface, INK, (rect.left, y), (rect.right, y), 2)
        for v in range(5):
            pygame.draw.line(surface, INK, (x_of(v), y - 4), (x_of(v), y + 4), 1)
            draw_text(surface, str(v), (x_of(v), y + 5), 14, MUTED, "midtop")
        for limit, label in ((2.0, "Euler, Verlet: 2"), (OSCILLATION_LIMITS["rk4"], "RK4: 2.83")):
            pygame.draw.line(surface, ERROR, (x_of(limit), y - 22), (x_of(limit), y + 10), 2)
            self._text(surface, label, (x_of(limit) + 3, y - 24), 14, ERROR)
        x = x_of(self.omega_dt)
        pygame.draw.polygon(surface, INK, [(x, y - 2), (x - 6, y - 12), (x + 6, y - 12)])
        marks.note(surface, "marker", pygame.Rect(x - 6, y - 12, 13, 11), "omega dt now")
        draw_text(surface, "omega dt", (rect.right, y - 24), 14, MUTED, "topright")


def _finite(points: list[tuple[float, float]]) -> bool:
    return bool(np.isfinite(np.asarray(points, dtype=float)).all()) if points else True


DEMO = Demo(
    name="stability",
    summary="Four integrators on one spring, and the warning and error as dt passes each limit",
    scenes={"orbits": OrbitsScene, "limits": LimitsScene},
)
