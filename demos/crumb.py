"""Alfred and the crumb: a small game that uses the engine the way your own game would.

Steer Alfred across his sheet of paper to the crumb with the arrow keys while the wind
gusts. Walk off the edge and he falls (the lesson: "if he moves left or right, he will fall
off!") and starts again from the middle. The game owns its window, its loop and its Surface;
from the engine it takes only the public pieces: a World with a Body and a Wind, the
fixed-step loop with a clock, and the camera and drawing helpers.

    python -m demos crumb --window     # play: arrow keys steer, Esc quits
    python -m demos crumb              # headless: an autopilot plays, frames to out/crumb/

Units: inches and seconds, like the lesson's Alfred.
"""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pygame

from demos.alfred import ant_sprite
from demos.cli import Demo
from engine import Body, FixedStep, RealClock, Vector, VirtualClock, World
from engine.forces import Wind
from engine.render import (
    VELOCITY,
    Camera,
    FrameWriter,
    draw_dot,
    draw_sprite,
    draw_text,
    draw_vector,
    init_headless,
    init_window,
)

#: The sheet of paper (in): x0, y0, x1, y1 of a letter page lying landscape.
PAPER = (0.0, 0.0, 11.0, 8.5)
#: How hard Alfred's legs push (in/s^2) while an arrow key is held.
PUSH = 9.0
#: Wind coupling k / m (1/s): the air drags Alfred toward its own velocity at this rate, so
#: with a key held his top speed relative to the air is PUSH / K = 7.5 in/s.
K = 1.2
#: Alfred eats the crumb when he is this close (in).
REACH = 0.35
DT = 1.0 / 120.0
PAPER_COLOUR, TABLE_COLOUR, CRUMB_COLOUR = (250, 248, 240), (120, 94, 70), (214, 170, 90)
INK = (40, 40, 40)


def gust(t: float) -> Vector:
    """The air's velocity (in/s) at time t (s): a slow swirl with gusts, never still."""
    return Vector(2.5 * math.sin(0.45 * t) + 1.0 * math.sin(1.7 * t), 1.5 * math.cos(0.3 * t))


@dataclass
class Score:
    """What the player has done so far."""

    crumbs: int = 0
    falls: int = 0


class CrumbGame:
    """The game's state and rules; the physics is an engine World with one Body in it."""

    def __init__(self, seed: int = 1) -> None:
        self.rng = np.random.default_rng(seed)
        self.world = World(integrator="semi_implicit_euler")
        self.alfred = self.world.add(Body(self.start, Vector(0, 0), Vector(0, 0)))
        self.world.add_force(Wind(air_velocity=gust, k=K))  # Alfred's mass is 1
        self.crumb = self._new_crumb()
        self.score = Score()
        #: The way Alfred faces (degrees counter-clockwise from +x): his velocity's direction,
        #: kept while he stands still (a zero velocity has no direction).
        self.heading = 90.0

    @property
    def start(self) -> Vector:
        """The middle of the paper (in), where Alfred starts and restarts."""
        return Vector((PAPER[0] + PAPER[2]) / 2, (PAPER[1] + PAPER[3]) / 2)

    def _new_crumb(self) -> Vector:
        margin = 0.8
        x = self.rng.uniform(PAPER[0] + margin, PAPER[2] - margin)
        y = self.rng.uniform(PAPER[1] + margin, PAPER[3] - margin)
        return Vector(float(x), float(y))

    def steer(self, right: float, up: float) -> None:
        """Point Alfred's legs: right and up each in [-1, 1] (the arrow keys held)."""
        direction = Vector(right, up)
        if direction:
            direction = direction.normalized()
        # His own acceleration is the lesson's Body.acc: the push of his legs.
        self.alfred.own_acc = direction * PUSH

    def update(self) -> None:
        """Apply the rules after the physics steps: eat the crumb, fall off the edge, turn."""
        vel = self.alfred.vel
        if vel.magnitude() > 1e-6:
            self.heading = math.degrees(math.atan2(vel.y, vel.x))
        pos = self.alfred.pos
        if pos.distance_to(self.crumb) < REACH:
            self.score.crumbs += 1
            self.crumb = self._new_crumb()
        if not (PAPER[0] <= pos.x <= PAPER[2] and PAPER[1] <= pos.y <= PAPER[3]):
            self.score.falls += 1
            self.alfred.pos, self.alfred.vel = self.start, Vector(0, 0)

    def autopilot(self) -> tuple[float, float]:
        """Keys a simple player would press: toward the crumb, minus some of the velocity."""
        aim = self.crumb - self.alfred.pos - self.alfred.vel * 0.35
        return (float(np.sign(round(aim.x, 1))), float(np.sign(round(aim.y, 1))))

    def draw(self, surface: pygame.Surface, camera: Camera, alpha: float) -> None:
        """Draw the table, the paper, the crumb and Alfred, blended by alpha between steps."""
        surface.fill(TABLE_COLOUR)
        (left, top), (right, bottom) = camera.point(PAPER[:2]), camera.point(PAPER[2:])
        pygame.draw.rect(surface, PAPER_COLOUR, (left, bottom, right - left, top - bottom))
        draw_dot(surface, camera.point(self.crumb), 6, CRUMB_COLOUR, outline=INK)
        here = self.world.position_of(self.alfred, alpha)
        vel = self.alfred.vel
        # Seen from above, head to +x: rotate turns him counter-clockwise on screen (y down)
        # while the camera flips y, so the world angle needs no change (see Paper.facing).
        sprite = pygame.transform.rotate(ant_sprite(top=True), self.heading)
        draw_vector(surface, camera, here, vel, 0.3, VELOCITY)  # from under him, ahead
        draw_sprite(surface, sprite, camera.point(here))
        air = gust(self.world.t)
        draw_text(
            surface,
            f"crumbs {self.score.crumbs}    falls {self.score.falls}    t = {self.world.t:4.1f} s",
            (16, 10),
            size=26,
            color=PAPER_COLOUR,
        )
        draw_text(surface, "wind", (surface.get_width() - 150, 10), 22, PAPER_COLOUR)
        draw_vector(
            surface, camera, camera.to_world(surface.get_width() - 60, 20), air, 0.25, PAPER_COLOUR
        )


def play(
    window: bool,
    seconds: float | None = None,
    fps: int = 60,
    size: tuple[int, int] = (640, 360),
    seed: int = 1,
    out: Path | None = None,
    overwrite: bool = False,
) -> Score:
    """Run the game: in a window with the keys, or headless with the autopilot to PNG frames."""
    if window:
        init_window()
        surface = pygame.display.set_mode(size)
        pygame.display.set_caption("Alfred and the crumb: arrow keys steer, Esc quits")
    else:
        init_headless()
        surface = pygame.Surface(size)
    game = CrumbGame(seed)
    camera = Camera.fit(PAPER, (16, 40, size[0] - 32, size[1] - 56))
    loop = FixedStep(dt=DT)
    clock = RealClock() if window else VirtualClock(fps)
    frames = None if window else FrameWriter(out or Path("out/crumb"), overwrite=overwrite)
    limit = math.inf if seconds is None and window else (seconds or 20.0)
    try:
        while game.world.t < limit:
            if window:
                if any(e.type == pygame.QUIT for e in pygame.event.get()):
                    break
                keys = pygame.key.get_pressed()
                if keys[pygame.K_ESCAPE]:
                    break
                right: float = keys[pygame.K_RIGHT] - keys[pygame.K_LEFT]
                up: float = keys[pygame.K_UP] - keys[pygame.K_DOWN]
            else:
                right, up = game.autopilot()
            game.steer(right, up)
            alpha = loop.run(game.world, clock.tick())  # whole physics steps of DT
            game.update()
            game.draw(surface, camera, alpha)
            if frames is not None:
                frames.write(surface)
            else:
                pygame.display.flip()
                pygame.time.wait(1)
    finally:
        if frames is not None:
            frames.close()
    return game.score


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.set_defaults(seed=1)


def _run(args: argparse.Namespace) -> int:
    out = args.out or Path("out/crumb")
    score = play(
        window=args.window,
        seconds=args.seconds,
        fps=args.fps or (60 if args.window else 30),
        size=args.size,
        seed=args.seed,
        out=out,
        overwrite=args.overwrite,
    )
    where = "" if args.window else f"; frames in {out}/frame_00000.png ..."
    print(f"crumb: {score.crumbs} crumbs eaten, {score.falls} falls{where}")
    return 0


DEMO = Demo(
    name="crumb",
    summary="A small game: steer Alfred to the crumb with the arrow keys, in the wind",
    add_arguments=_add_arguments,
    run=_run,
)
