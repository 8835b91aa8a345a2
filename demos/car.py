"""The car on Main Street: the lesson's opening story, in metres and seconds (mph on screen).

"We could tell the computer to move the car at, say, 10 m.p.h., to the third traffic light on
Main Street." Here the car does exactly that. Every phase of its trip has a constant
acceleration (speed up, cruise, brake, stopped), so it is moved by the closed form of
``engine.kinematics`` at each frame's exact time, with no error piling up:

    s(t) = s0 + v0 (t - t0) + a (t - t0)^2 / 2,    v(t) = v0 + a (t - t0)

Braking at a constant deceleration b from speed v takes the distance v^2 / (2 b) (from
v^2 = v0^2 - 2 b s), so the driver who wants to stop exactly at the line starts braking that
far before it. ``too-fast`` is the car of the lesson's figure 1: it drives at 25 mph but
brakes where a 10 mph car would, and runs the red light.

    python -m demos car
    python -m demos car --scene main-street --window
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import pygame

from demos.cli import Demo
from engine import kinematics
from engine.render import (
    ACCELERATION,
    INK,
    MUTED,
    PAPER,
    VELOCITY,
    Camera,
    Plot,
    Scene,
    draw_sprite,
    draw_text,
)

__all__ = [
    "MPH",
    "Phase",
    "Trip",
    "plan_trip",
    "MainStreet",
    "TooFast",
    "DEMO",
]

#: One mile per hour in metres per second (1609.344 m / 3600 s).
MPH = 1609.344 / 3600.0
#: The stop lines of the three traffic lights on Main Street (m from where the car starts).
LIGHTS = (30.0, 60.0, 90.0)
#: Length of the car (m); its position is its front bumper.
CAR_LENGTH = 4.5
ASSETS = Path(__file__).resolve().parent.parent / "assets"


@dataclass(frozen=True)
class Phase:
    """A stretch of the trip with constant acceleration ``a`` (m/s^2), from time ``t0`` (s)."""

    name: str
    t0: float
    s0: float  # m
    v0: float  # m/s
    a: float  # m/s^2
    duration: float  # s (inf for the last phase)


class Trip:
    """A 1D trip made of constant-acceleration phases, moved by the closed form.

    It is the car scene's "world" and speaks :class:`engine.Steppable`: ``step(dt)`` advances
    the time in whole steps (the only way time moves), ``t`` is that time, the scene's one
    clock, and ``snapshot()`` / ``restore()`` save and bring back the clock. The phases are
    fixed when the trip is planned, so ``position(t)`` / ``velocity(t)`` give the exact state
    at any time.
    """

    def __init__(self, phases: list[Phase]) -> None:
        self.phases = phases
        self.steps = 0
        self.dt = 0.0
        # The time is t_base + n * dt: n whole steps of the current dt after t_base, so that
        # it never drifts; a new dt folds the time so far into t_base.
        self._t_base = 0.0
        self._n = 0

    def step(self, dt: float) -> None:
        """Advance the time by ``dt`` s (a fixed step: the time is counted in whole steps)."""
        if isinstance(dt, bool) or not (isinstance(dt, (int, float)) and 0 < dt < math.inf):
            raise ValueError(f"dt must be a finite number of seconds > 0, got {dt!r}")
        if dt != self.dt:
            self._t_base, self._n, self.dt = self.t, 0, float(dt)
        self._n += 1
        self.steps += 1

    @property
    def t(self) -> float:
        """The time (s)."""
        return self._t_base + self._n * self.dt

    def snapshot(self) -> tuple[float, int, float, int]:
        """The clock at this moment: (t_base s, steps of dt since it, dt s, steps in all)."""
        return self._t_base, self._n, self.dt, self.steps

    def restore(self, snapshot: tuple[float, int, float, int]) -> None:
        """Return the clock to the moment ``snapshot()`` was taken."""
        try:
            t_base, n, dt, steps = snapshot
        except (TypeError, ValueError):
            raise TypeError(
                f"restore takes the tuple Trip.snapshot() returns, got {snapshot!r}"
            ) from None
        self._t_base, self._n, self.dt, self.steps = float(t_base), int(n), float(dt), int(steps)

    def phase_at(self, t: float) -> Phase:
        """The phase the car is in at time ``t`` (s)."""
        for phase in self.phases:
            if t < phase.t0 + phase.duration:
                return phase
        return self.phases[-1]

    def position(self, t: float) -> float:
        """Where the front of the car is (m) at time ``t`` (s)."""
        p = self.phase_at(t)
        return kinematics.position(p.s0, p.v0, p.a, max(0.0, t - p.t0))

    def velocity(self, t: float) -> float:
        """The car's velocity (m/s) at time ``t`` (s)."""
        p = self.phase_at(t)
        return kinematics.velocity(p.v0, p.a, max(0.0, t - p.t0))

    def time_at(self, s: float) -> float:
        """The first time (s) the front of the car reaches ``s`` (m); ``math.inf`` if never."""
        for phase in self.phases:
            # Within a phase the motion is s0 + v0 t + a t^2 / 2: solved exactly.
            t = kinematics.time_to_reach(phase.s0, phase.v0, phase.a, s)
            if t <= phase.duration:
                return phase.t0 + t
        return math.inf

    def acceleration(self, t: float) -> float:
        """The car's acceleration (m/s^2) at time ``t`` (s)."""
        return self.phase_at(t).a

    @property
    def end(self) -> Phase:
        """The last phase: the car at rest."""
        return self.phases[-1]


def plan_trip(
    cruise: float, speed_up: float, brake: float, brake_at: float, hold: float = 0.0
) -> Trip:
    """A trip from rest: speed up at ``speed_up`` (m/s^2) to ``cruise`` (m/s), cruise, brake
    at ``brake`` (m/s^2) from the point ``brake_at`` (m) to a stop; ``hold`` s of rest before.
    """
    for value, name in ((cruise, "cruise"), (speed_up, "speed_up"), (brake, "brake")):
        if not (value > 0 and math.isfinite(value)):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    t_up = cruise / speed_up  # v = a t
    s_up = kinematics.stopping_distance(cruise, speed_up)  # v^2 / (2 a), the same formula
    if brake_at < s_up:
        raise ValueError(
            f"brake_at = {brake_at} m is before the car reaches its cruise speed at {s_up:.2f} m"
        )
    t_cruise = (brake_at - s_up) / cruise
    t_brake = cruise / brake
    s_stop = brake_at + kinematics.stopping_distance(cruise, brake)
    t = hold
    phases = [Phase("waiting", 0.0, 0.0, 0.0, 0.0, hold)] if hold > 0 else []
    phases.append(Phase("speeding up", t, 0.0, 0.0, speed_up, t_up))
    t += t_up
    phases.append(Phase("cruising", t, s_up, cruise, 0.0, t_cruise))
    t += t_cruise
    phases.append(Phase("braking", t, brake_at, cruise, -brake, t_brake))
    t += t_brake
    phases.append(Phase("stopped", t, s_stop, 0.0, 0.0, math.inf))
    return Trip(phases)


@cache
def car_sprite(length_px: int) -> pygame.Surface:
    """The car (assets/car.png, or a drawn one if it is missing) scaled to ``length_px`` wide."""
    path = ASSETS / "car.png"
    if path.exists():
        image = pygame.image.load(str(path))
    else:  # pygame primitives: body, cabin, two wheels
        image = pygame.Surface((64, 32), pygame.SRCALPHA)
        pygame.draw.rect(image, (196, 42, 54), (2, 12, 60, 12), border_radius=4)
        pygame.draw.rect(image, (196, 42, 54), (16, 3, 28, 12), border_radius=4)
        for x in (16, 48):
            pygame.draw.circle(image, (30, 30, 34), (x, 25), 6)
    w, h = image.get_size()
    return pygame.transform.smoothscale(image, (length_px, max(1, round(h * length_px / w))))


class MainStreet(Scene):
    """A car pulls away, cruises at 10 mph and stops exactly at the third light, which is red."""

    #: The road, the lights and the v(t) panel need this much room (px).
    min_size = (160, 168)

    name = "main-street"
    summary = "10 mph to the third traffic light, stopping exactly at its line"
    dt = 1.0 / 120.0
    #: Cruise speed (m/s), how hard it speeds up and brakes (m/s^2).
    cruise = 10.0 * MPH
    speed_up = 1.5
    brake = 2.0
    #: The speed the driver plans the braking for (m/s): the cruise speed, for a good driver.
    planned = 10.0 * MPH
    hold = 0.5

    def __init__(self) -> None:
        line = LIGHTS[2]
        # Start braking where the stopping distance v^2 / (2 b) says: it ends at the line.
        self.brake_at = line - kinematics.stopping_distance(self.planned, self.brake)
        trip = plan_trip(self.cruise, self.speed_up, self.brake, self.brake_at, self.hold)
        self.duration = math.ceil(trip.end.t0 + 1.5)

    def build(self, size: tuple[int, int]) -> None:
        self.size = size
        self.world = self.trip = plan_trip(
            self.cruise, self.speed_up, self.brake, self.brake_at, self.hold
        )
        w, h = size
        s = h / 360
        self.s = s
        street_end = LIGHTS[2] + 12.0 if self.cruise <= self.planned + 1e-9 else 125.0
        # The street from 6 m behind the start to past the last line fills the width; the
        # road surface (y = 0) sits at 60 % of the height.
        scale = (w - 20 * s) / (street_end + 6.0)
        self.camera = Camera(scale, (10 * s + 6.0 * scale, 0.60 * h))
        self.car = car_sprite(max(36, round(self.camera.length(CAR_LENGTH) * 1.6)))
        top_mph = max(12.0, math.ceil(self.cruise / MPH / 5.0) * 5.0 + 2.0)
        self.plot = Plot(
            (round(w * 0.52), round(h * 0.745), round(w * 0.46), round(h * 0.245)),
            t_max=self.duration,
            y_range=(0.0, top_mph),
            title="v(t)  mph",
            t_step=5.0,
            y_step=5.0 if top_mph <= 15 else 10.0,
            color=VELOCITY,
        )

    # -- drawing --------------------------------------------------------------------------

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        t = self.time(alpha)
        trip = self.trip
        x, v = trip.position(t), trip.velocity(t)
        surface.fill(PAPER)
        self.draw_street(surface)
        cam, s = self.camera, self.s
        px, py = cam.to_px(x, 0.0)
        draw_sprite(surface, self.car, (px, py + 2 * s), anchor="bottomright")  # front at x
        self.draw_panel(surface, t, x, v)

    def draw_street(self, surface: pygame.Surface) -> None:
        """The road, the braking point and the three lights (the third red)."""
        cam, s = self.camera, self.s
        w, _ = self.size
        _, road_y = cam.to_px(0.0, 0.0)
        pygame.draw.rect(surface, (70, 72, 78), (0, road_y, w, 26 * s))
        for x in range(0, w, round(36 * s)):  # lane marks
            pygame.draw.rect(surface, (230, 230, 200), (x, road_y + 12 * s, 18 * s, 2 * s))
        draw_text(surface, "Main Street", (8 * s, road_y + 30 * s), round(18 * s), MUTED)
        for i, line in enumerate(LIGHTS):
            lx, _ = cam.to_px(line, 0.0)
            red = i == 2
            pygame.draw.rect(surface, (245, 245, 245), (lx - 1 * s, road_y, 3 * s, 26 * s))
            pole_x = lx + 6 * s
            pygame.draw.line(
                surface, INK, (pole_x, road_y), (pole_x, road_y - 70 * s), max(1, round(3 * s))
            )
            box = pygame.Rect(0, 0, 14 * s, 38 * s)
            box.midbottom = (round(pole_x), round(road_y - 66 * s))
            pygame.draw.rect(surface, (40, 40, 44), box, border_radius=round(3 * s))
            lamps = (
                (230, 40, 30) if red else (70, 30, 30),
                (70, 60, 20),
                (60, 80, 50) if red else (40, 200, 80),
            )
            for j, colour in enumerate(lamps):
                pygame.draw.circle(
                    surface, colour, (box.centerx, box.top + round((7 + 12 * j) * s)), round(5 * s)
                )
            draw_text(
                surface,
                f"light {i + 1}",
                (pole_x, road_y - 108 * s),
                round(16 * s),
                MUTED,
                "midbottom",
            )
        # Where braking starts: the stopping distance before the third line.
        bx, _ = cam.to_px(self.brake_at, 0.0)
        pygame.draw.line(
            surface, ACCELERATION, (bx, road_y - 4 * s), (bx, road_y + 26 * s), max(1, round(2 * s))
        )
        draw_text(
            surface, "brake here", (bx, road_y + 27 * s), round(16 * s), ACCELERATION, "midtop"
        )

    def draw_panel(self, surface: pygame.Surface, t: float, x: float, v: float) -> None:
        """Speedometer, distance to the third light, the phase and the v(t) plot."""
        s = self.s
        line = LIGHTS[2]
        mph = v / MPH
        size = round(22 * s)
        draw_text(surface, f"{mph:5.1f} mph", (14 * s, 12 * s), round(34 * s), VELOCITY)
        draw_text(surface, f"= {v:4.2f} m/s", (14 * s, 44 * s), size, MUTED)
        to_go = line - x
        if to_go >= -0.005:
            text = f"to the red light: {max(0.0, to_go):6.2f} m"
            colour = INK
        else:
            crossing = self.trip.velocity(self.trip.time_at(line)) / MPH
            text = f"RAN THE RED LIGHT at {crossing:4.1f} mph, {-to_go:5.2f} m past it"
            colour = (200, 30, 30)
        draw_text(surface, text, (14 * s, 68 * s), size, colour)
        phase = self.trip.phase_at(t)
        draw_text(
            surface,
            f"t = {t:5.2f} s   {phase.name}, a = {phase.a:+.1f} m/s\u00b2",
            (14 * s, self.camera.to_px(0.0, 0.0)[1] + 50 * s),
            round(18 * s),
            MUTED,
        )
        ts, vs = self._curve(t)
        self.plot.draw_frame(surface)
        # The 10 mph limit the lesson asks for, as a dashed line.
        _, ly = self.plot.to_px(0.0, 10.0)
        a = self.plot.area
        for x0 in range(a.left, a.right, 8):
            pygame.draw.line(surface, MUTED, (x0, float(ly)), (min(x0 + 4, a.right), float(ly)), 1)
        self.plot.draw_curve(surface, ts, vs, shade=True)

    def _curve(self, t: float) -> tuple[list[float], list[float]]:
        """v(t) in mph sampled every 0.05 s up to t, plus the phase corners (exact, no lag)."""
        n = int(t / 0.05)
        ts = [k * 0.05 for k in range(n + 1)]
        ts += [p.t0 for p in self.trip.phases if p.t0 < t]
        ts = sorted(set(ts)) + [t]
        return ts, [self.trip.velocity(tk) / MPH for tk in ts]


class TooFast(MainStreet):
    """The lesson's figure 1: 25 mph, braking where a 10 mph car would stop; it runs the light."""

    name = "too-fast"
    summary = "25 mph, braking where 10 mph would stop: it runs the red light"
    cruise = 25.0 * MPH
    speed_up = 2.5
    planned = 10.0 * MPH


DEMO = Demo(
    name="car",
    summary="The car on Main Street: 10 mph to the third light, and one that brakes too late",
    scenes={"main-street": MainStreet, "too-fast": TooFast},
)
