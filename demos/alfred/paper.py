"""``paper``: Alfred's 2D walk on a sheet of paper (figures 15 to 18).

x(t) = t^2 / 2, y(t) = 2t - t^2, with his position vector from the origin and his velocity
(t, 2 - 2t) tangent to the path; the strobe picture shows him every half second.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence

import numpy as np
import pygame

from engine import Body, Vector, World, kinematics
from engine.render import (
    ACCELERATION,
    GRID,
    INK,
    MUTED,
    PAPER,
    POSITION,
    VELOCITY,
    Camera,
    Scene,
    draw_arrow,
    draw_dot,
    draw_grid,
    draw_sprite,
    draw_text,
    draw_vector,
    font,
)
from engine.render.marks import marks, panel

from .common import ant_sprite, fmt, font_size, number, sprite_zoom


class Paper(Scene):
    """Alfred's 2D walk on a sheet of paper (figures 15 to 18)."""

    name = "paper"
    summary = (
        "2D walk x = t\u00b2/2, y = 2t - t\u00b2: position vector and tangent velocity (figs 15-18)"
    )
    duration = 3.0
    dt = 1.0 / 120.0
    strobe_interval = 0.5
    #: The sheet of paper, in inches: x0, y0, x1, y1 (build() widens it to hold his whole
    #: walk, every velocity arrow and his body around them).
    box = (-0.4, -3.4, 5.4, 1.5)
    #: A velocity arrow shows this many seconds of travel.
    arrow_seconds = 0.25
    s0 = Vector(0.0, 0.0)
    v0 = Vector(0.0, 2.0)
    a = Vector(1.0, -2.0)
    world: World

    def build(self, size: tuple[int, int]) -> None:
        """The paper on the left, the numbers on the right."""
        self.size = size
        w, h = size
        self.world = World(integrator="exact")
        # x(t) = t^2/2 and y(t) = 2t - t^2 are s0 + v0 t + a t^2/2 with s0 = 0, v0 = (0, 2),
        # a = (1, -2): constant acceleration, so the closed form moves Alfred exactly.
        self.alfred = self.world.add(Body(self.s0, self.v0, self.a))
        # Seen from above, head to +x; facing() turns him to his velocity.
        self.sprite = ant_sprite(top=True, zoom=sprite_zoom(size))
        title_h = font_size(size, 24) + 14
        paper_w = min(w * 0.6, (h - title_h - 10) * 1.1)
        self.paper_rect = pygame.Rect(10, title_h, round(paper_w), h - title_h - 10)
        self.fit(arrows=True)

    def fit(self, arrows: bool) -> None:
        """Fit the camera to what the paper must hold: the walk and, with ``arrows``, the tip
        of every velocity arrow along it (world inches), and around them his body turned any
        way and the arrowheads (px). The grid then fills the paper (``box``)."""
        inner = self.paper_rect.inflate(-16, -16)
        ts = np.linspace(0.0, self.duration, 301)
        walk = [self.exact(float(t)) for t in ts]
        points = [p for p, _ in walk]
        if arrows:
            points += [p + v * self.arrow_seconds for p, v in walk]
        x0, _, _, y1 = type(self).box
        xs, ys = [p.x for p in points] + [x0], [p.y for p in points] + [y1]
        reach = round(math.hypot(*self.sprite.get_size()) / 2) + 4
        reach = min(reach, min(inner.w, inner.h) // 4)  # a tiny canvas keeps some paper
        fit = inner.inflate(-2 * reach, -2 * reach)
        self.camera = Camera.fit((min(xs), min(ys), max(xs), max(ys)), (fit.x, fit.y, fit.w, fit.h))
        left, top = self.camera.to_world(inner.left, inner.top)
        right, bottom = self.camera.to_world(inner.right, inner.bottom)
        self.box = (left, bottom, right, top)

    def exact(self, t: float) -> tuple[Vector, Vector]:
        """Alfred's position (in) and velocity (in/s) at time t by the closed form."""
        return kinematics.position(self.s0, self.v0, self.a, t), kinematics.velocity(
            self.v0, self.a, t
        )

    def heading(self, t: float, vel: Vector) -> float:
        """The way Alfred faces at time t (s) with velocity vel (in/s): degrees counter-clockwise
        from the world's +x (y up)."""
        # At a stop, a velocity stepped back from the world's time is rounding noise (1e-16
        # in/s), whose atan2 points anywhere: below 1e-9 in/s he counts as stopped.
        if vel.magnitude() > 1e-9:
            direction = vel
        elif t > 0 and self.a.magnitude() > 0:
            # Stopped for an instant: keep the way he was walking. Just before, with constant a,
            # v(t - h) = v(t) - a h = -a h, so he was walking along -a.
            direction = -self.a
        elif self.a.magnitude() > 0:
            # Starting from rest: v(h) = a h, the way he is about to walk.
            direction = self.a
        else:
            return 0.0  # he never moves: the sprite's own heading, +x
        return math.degrees(math.atan2(direction.y, direction.x))

    def facing(self, t: float, vel: Vector) -> pygame.Surface:
        """Alfred's top-view sprite turned to face his velocity vel (in/s) at time t (s)."""
        # The sprite's head points along pixel +x. pygame.transform.rotate(image, theta) turns
        # it theta degrees counter-clockwise as seen on screen; pixel y points down, so the head
        # then points along the pixel direction (cos theta, -sin theta). The camera maps a world
        # direction (vx, vy), y up, to the pixel direction (vx, -vy) (times a positive scale).
        # Equal when (cos theta, sin theta) is along (vx, vy): theta = atan2(vy, vx), the
        # world angle as it is; the two y flips cancel. rotate samples the nearest pixel, so
        # his body keeps its exact colour (rotozoom would blend it).
        return pygame.transform.rotate(self.sprite, self.heading(t, vel))

    def draw_paper(self, surface: pygame.Surface, t: float) -> None:
        """The sheet with its grid and axes, and the whole path, faint."""
        surface.fill(PAPER)
        draw_text(surface, "Alfred on a sheet of paper", (12, 8), font_size(self.size, 24), INK)
        pygame.draw.rect(surface, (255, 255, 255), self.paper_rect)
        pygame.draw.rect(surface, GRID, self.paper_rect, 1)
        with panel(self.paper_rect):
            draw_grid(surface, self.camera, self.box, 1.0, unit="in", size=font_size(self.size, 15))
        ts = np.linspace(0.0, self.duration, 120)
        xs, ys = ts * ts / 2, 2 * ts - ts * ts
        px, py = self.camera.to_px(xs, ys)
        pygame.draw.aalines(
            surface, (190, 190, 196), False, list(zip(px.tolist(), py.tolist(), strict=True))
        )

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """Path so far, position vector, velocity arrow, Alfred, and the numbers."""
        t = self.time(alpha)
        self.draw_paper(surface, t)
        pos = self.world.position_of(self.alfred, alpha)
        assert isinstance(pos, Vector)  # the paper is a 2D world
        # The world's velocity is at world.t, a step ahead; a is constant, so step it back.
        vel = kinematics.velocity(self.alfred.vel, self.a, t - self.world.t)
        # The path walked so far.
        ts = np.linspace(0.0, t, max(2, int(t * 60)))
        px, py = self.camera.to_px(ts * ts / 2, 2 * ts - ts * ts)
        if t > 0:
            pygame.draw.lines(
                surface, POSITION, False, list(zip(px.tolist(), py.tolist(), strict=True)), 2
            )
        # Seen from above, he stands centred on his position.
        anchor = self.camera.to_px(pos.x, pos.y)
        image = self.facing(t, vel)
        rect = draw_sprite(surface, image, anchor, "center")
        body = (rect, pygame.mask.from_surface(image))
        # Position vector from the origin up to him, velocity arrow from him along the path:
        # each starts or ends where his body does along it, so that neither lies under him
        # (0.25 s of travel is shorter than he is at walking speeds). His middle, where both
        # meet, is the dot.
        origin = self.camera.to_px(0.0, 0.0)
        toward = (anchor[0] - origin[0], anchor[1] - origin[1])
        short = _reach(body, anchor, (-toward[0], -toward[1])) + 2
        length = math.hypot(*toward)
        with panel(self.paper_rect):
            if length > short:
                k = 1.0 - short / length
                end = (origin[0] + k * toward[0], origin[1] + k * toward[1])
                draw_arrow(surface, origin, end, POSITION, 3)
            # His heading in pixels (vx, -vy), from his nose on: it lies on the tangent.
            ahead = _reach(body, anchor, (vel.x, -vel.y)) + 2
            speed = vel.magnitude() * self.camera.scale
            nose = anchor
            if speed > 0:
                nose = (anchor[0] + ahead * vel.x * self.camera.scale / speed,
                        anchor[1] - ahead * vel.y * self.camera.scale / speed)  # fmt: skip
            draw_vector(
                surface,
                self.camera,
                self.camera.to_world(*nose),
                vel,
                self.arrow_seconds,
                VELOCITY,
                label="v",
                label_side=-1,
            )
        draw_dot(surface, anchor, 3, INK)
        self.draw_numbers(surface, t, pos, vel)

    def draw_numbers(self, surface: pygame.Surface, t: float, pos: Vector, vel: Vector) -> None:
        """The readout on the right: t, s, v, a with their formulas."""
        x = self.paper_rect.right + 14
        fs = font_size(self.size, 20)
        small = font_size(self.size, 16)
        y = self.paper_rect.top + 2
        lines = [
            (f"t = {t:.2f} s", INK, fs + 6),
            ("position  s = (x, y)", POSITION, fs),
            ("  x = t\u00b2/2,  y = 2t \u2212 t\u00b2", MUTED, small),
            (f"  s = ({fmt(pos.x)}, {fmt(pos.y)}) in", POSITION, fs),
            ("velocity  v = (t, 2 \u2212 2t)", VELOCITY, fs),
            (f"  v = ({fmt(vel.x)}, {fmt(vel.y)}) in/s", VELOCITY, fs),
            (f"  |v| = {fmt(vel.magnitude())} in/s", VELOCITY, small),
            ("acceleration", ACCELERATION, fs),
            (f"  a = ({fmt(self.a.x, 0)}, {fmt(self.a.y, 0)}) in/s\u00b2", ACCELERATION, fs),
            ("", INK, small // 2),
            ("green: s from the origin", MUTED, small),
            (f"blue: v, drawn as {self.arrow_seconds:g} s of travel,", MUTED, small),
            ("  tangent to the path", MUTED, small),
        ]
        for text, color, size in lines:
            if text:
                draw_text(surface, text, (x, y), size, color)
            y += size + 4

    def strobe_times(self) -> list[float]:
        """Every half second from 0 to 3 s."""
        return [
            k * self.strobe_interval for k in range(int(self.duration / self.strobe_interval) + 1)
        ]

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """Alfred at equal time steps along his path, older images fainter, each labelled t.

        No velocity arrows here: the paper holds his walk alone, drawn larger than in the frames.
        """
        self.fit(arrows=False)
        self.draw_paper(surface, max(times))
        n = len(times)
        # Each time's age (0 newest, 1 oldest), pixel position and velocity (in/s).
        states = []
        for i, t in enumerate(times):
            pos, vel = self.exact(t)
            states.append((1.0 - i / max(1, n - 1), self.camera.to_px(pos.x, pos.y), vel))
        images = [self.facing(t, vel) for t, (_, _, vel) in zip(times, states, strict=True)]
        # Where each image's pixels are (a rotated image is mostly empty corners).
        drawn: list[tuple[pygame.Rect, pygame.mask.Mask]] = []
        for image, (_, anchor, _) in zip(images, states, strict=True):
            rect = image.get_rect(center=tuple(math.floor(c + 0.5) for c in anchor))
            drawn.append((rect, pygame.mask.from_surface(image)))
        origin = self.camera.to_px(0.0, 0.0)
        # An Alfred standing on the origin (at t = 0 he starts there) covers it.
        start = [body for body, (_, at, _) in zip(drawn, states, strict=True)
                 if math.dist(at, origin) < 1.0]  # fmt: skip
        # Every arrow first, under all the ants, each from where the one on the origin ends
        # to where its own ant's body begins: its head shows (the dot is his middle). One
        # with no room between the two is left out.
        for body, (age, anchor, _) in zip(drawn, states, strict=True):
            toward = (anchor[0] - origin[0], anchor[1] - origin[1])
            length = math.hypot(*toward)
            if length < 1.0:
                continue  # he is on the origin: no position vector to draw
            out = max((_reach(b, origin, toward) + 2 for b in start), default=0.0)
            short = _reach(body, anchor, (-toward[0], -toward[1])) + 2
            if length > out + short:
                a, b = out / length, 1.0 - short / length
                tail = (origin[0] + a * toward[0], origin[1] + a * toward[1])
                end = (origin[0] + b * toward[0], origin[1] + b * toward[1])
                draw_arrow(surface, tail, end, _fade(POSITION, age), 2, 8)
        for image, (age, anchor, _) in zip(images, states, strict=True):
            draw_sprite(surface, image, anchor, "center", alpha=round(255 - 175 * age))
            draw_dot(surface, anchor, 3, INK)
        # Each label goes beside its image, where it covers no ant, no position arrow and no
        # other words (the grid's numbers, the labels placed before it): the nearest such place
        # around him, trying across his heading first (the outside of the bend, away from a,
        # where the path is not), then along it and between. If no place is free, the one that
        # breaks the fewest of these rules, nearest first.
        size = font_size(self.size, 16)
        reach = self.sprite.get_height() / 2  # his legs' reach either side of his axis (px)
        ax, ay = self.a.x, -self.a.y  # a as a pixel direction (pixel y points down)
        arrows = [(origin, anchor) for _, anchor, _ in states]
        inside = self.paper_rect
        arrows += [((inside.left, origin[1]), (inside.right, origin[1]))]  # the axes
        arrows += [((origin[0], inside.top), (origin[0], inside.bottom))]
        words = [m.rect for m in marks(surface) if m.kind == "text"]
        paper = self.paper_rect.inflate(-4, -4)
        for i, t in enumerate(times):
            _, anchor, vel = states[i]
            text = f"t = {number(t)} s"
            box = pygame.Rect((0, 0), font(size).size(text))
            theta = math.radians(self.heading(t, vel))
            # His heading in pixels is (cos theta, -sin theta) (see facing); across it are
            # (sin theta, cos theta) and its opposite (their dot product with it is 0).
            ahead = (math.cos(theta), -math.sin(theta))
            across = [(math.sin(theta), math.cos(theta)), (-math.sin(theta), -math.cos(theta))]
            across.sort(key=lambda d: d[0] * ax + d[1] * ay)  # against a first
            ways = [*across, ahead, (-ahead[0], -ahead[1])]
            ways += [(a[0] + b[0], a[1] + b[1]) for a in across for b in ways[2:]]
            places = []
            for gap in (2, 6, 10, 16, 24, 34):
                for dx, dy in ways:
                    norm = math.hypot(dx, dy)
                    dx, dy = dx / norm, dy / norm
                    # A box w x h reaches |dx| w/2 + |dy| h/2 from its centre in the direction
                    # (dx, dy): centred this far out, all of it lies gap px beyond his legs.
                    r = reach + abs(dx) * box.w / 2 + abs(dy) * box.h / 2 + gap
                    places.append((anchor[0] + dx * r, anchor[1] + dy * r))

            others = [state[1] for state in states]
            faults = functools.partial(_faults, box, anchor, others, words, drawn, arrows, paper)
            point = min(places, key=faults)  # the first of the fewest: nearest, in order
            words.append(draw_text(surface, text, point, size, INK, "center"))
        pos, vel = self.exact(max(times))
        self.draw_numbers(surface, max(times), pos, vel)


def _faults(
    box: pygame.Rect,
    anchor: tuple[float, float],
    anchors: Sequence[tuple[float, float]],
    words: Sequence[pygame.Rect],
    images: Sequence[tuple[pygame.Rect, pygame.mask.Mask]],
    lines: Sequence[tuple[tuple[float, float], tuple[float, float]]],
    paper: pygame.Rect,
    place: tuple[float, float],
) -> int:
    """How many rules a label ``box`` centred at ``place`` breaks, for the Alfred at ``anchor``
    (px): off the ``paper`` (counts 99), on other ``words`` (with a few px to spare), on an
    Alfred among ``images``, across one of ``lines`` (the arrows and axes), nearer another of
    the ``anchors`` than its own."""
    box.center = (round(place[0]), round(place[1]))
    if not paper.contains(box):
        return 99
    mine = math.dist(box.center, anchor)
    return (
        (box.inflate(6, 4).collidelist(list(words)) >= 0)
        + _covers(box, images)
        + any(box.clipline(a, b) for a, b in lines)
        + any(math.dist(box.center, other) < mine for other in anchors)
    )


def _reach(
    image: tuple[pygame.Rect, pygame.mask.Mask],
    centre: tuple[float, float],
    direction: tuple[float, float],
) -> float:
    """How far (px) from ``centre`` the visible pixels of ``image`` (its box on the frame and
    its mask) reach along ``direction`` (pixel axes): the furthest one on that ray."""
    rect, mask = image
    norm = math.hypot(*direction)
    if norm == 0.0:
        return 0.0
    dx, dy = direction[0] / norm, direction[1] / norm
    w, h = mask.get_size()
    furthest = 0.0
    for r in range(math.ceil(math.hypot(w, h)) + 1):
        x = math.floor(centre[0] + r * dx) - rect.x
        y = math.floor(centre[1] + r * dy) - rect.y
        if 0 <= x < w and 0 <= y < h and mask.get_at((x, y)):
            furthest = float(r)
    return furthest


def _covers(box: pygame.Rect, images: Sequence[tuple[pygame.Rect, pygame.mask.Mask]]) -> bool:
    """Whether the pixel rectangle ``box`` covers a visible pixel of any of ``images``."""
    solid = pygame.mask.Mask(box.size, fill=True)
    return any(
        mask.overlap(solid, (box.x - rect.x, box.y - rect.y)) is not None for rect, mask in images
    )


def _fade(color: tuple[int, int, int], age: float) -> tuple[int, int, int]:
    # Mix toward white: age 0 is the full colour, age 1 is 70% white.
    return tuple(round(c + (255 - c) * 0.7 * age) for c in color)  # type: ignore[return-value]
