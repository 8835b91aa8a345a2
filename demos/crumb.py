"""Alfred and the crumb: a small game that uses the engine the way your own game would.

Steer Alfred across his sheet of paper to the crumb with the arrow keys while the wind
gusts. The paper's edges are the World's walls (a ``Box`` collider): Alfred bumps off them
and can never leave the paper. The crumb is a sensor (a ``Circle`` with ``sensor=True``):
bodies pass through it, and the World reports when Alfred begins to overlap it, which is
when he eats it. From the engine it takes only the public pieces: a World with a Body, a
Wind and two colliders, its contact events, and the Scene machinery with the camera and
drawing helpers. The game writes no distance or edge check of its own.

The game is a Scene like every other demo, so the recorder, ``--window`` and the tests drive
it the same way. What it steps is :class:`CrumbGame`, which speaks :class:`engine.Steppable`:
each fixed step of 1/120 s reads the keys (or asks the autopilot), lets the World step, and
applies the rules (eat the crumb when the sensor says so, count the bumps against the edge),
so the rules never depend on the frame
rate, and a game saved mid-run resumes exactly.

    python -m demos crumb --window     # play: arrow keys steer, space pauses, Esc quits
    python -m demos crumb              # headless: an autopilot plays, frames to out/crumb/

Units: inches and seconds, like the lesson's Alfred.
"""

from __future__ import annotations

import argparse
import copy
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
import pygame

from demos.alfred import ant_sprite
from demos.cli import Demo
from engine import Body, Box, Circle, Vector, World
from engine.forces import Wind
from engine.render import (
    VELOCITY,
    Camera,
    FrameWriter,
    Scene,
    draw_dot,
    draw_sprite,
    draw_text,
    draw_vector,
    iter_frames,
)
from engine.render import play as play_window
from engine.world import WorldSnapshot

#: The sheet of paper (in): x0, y0, x1, y1 of a letter page lying landscape.
PAPER = (0.0, 0.0, 11.0, 8.5)
#: How hard Alfred's legs push (in/s^2) while an arrow key is held.
PUSH = 9.0
#: Wind coupling k / m (1/s): the air drags Alfred toward its own velocity at this rate, so
#: with a key held his top speed relative to the air is PUSH / K = 7.5 in/s.
K = 1.2
#: Alfred eats the crumb when his centre is this close to it (in).
REACH = 0.35
#: Alfred's size (in): the walls keep his centre this far inside the paper's edge.
RADIUS = 0.2
#: Alfred's own restitution and friction, and the paper's edge as a wall: materials multiply,
#: so he keeps 0.5 x 0.5 = 0.25 of his speed into an edge, and slides along it at mu 0.1.
RESTITUTION, FRICTION = 0.5, 0.5
EDGE_RESTITUTION, EDGE_FRICTION = 0.5, 0.2
#: A contact with the edge counts as a bump when it changes his velocity by this much (in/s):
#: pressed into a corner, the engine reports many contacts of no impulse every step.
BUMP = 0.5
DT = 1.0 / 120.0
PAPER_COLOUR, TABLE_COLOUR, CRUMB_COLOUR = (250, 248, 240), (120, 94, 70), (214, 170, 90)
INK = (40, 40, 40)
#: How long a game in a window may last (s) when no --seconds is given: until it is closed.
WINDOW_SECONDS = 24 * 3600.0

#: A player: the keys held now, as (right, up), each in [-1, 1].
Player = Callable[[], tuple[float, float]]


def gust(t: float) -> Vector:
    """The air's velocity (in/s) at time t (s): a slow swirl with gusts, never still."""
    return Vector(2.5 * math.sin(0.45 * t) + 1.0 * math.sin(1.7 * t), 1.5 * math.cos(0.3 * t))


@dataclass
class Score:
    """What the player has done so far."""

    crumbs: int = 0
    bumps: int = 0  # times he ran into the paper's edge


@dataclass(frozen=True)
class CrumbSnapshot:
    """Everything a game needs to resume: see :meth:`CrumbGame.snapshot`."""

    world: WorldSnapshot
    rng: Mapping[str, Any]  # the random generator's state, for the next crumb
    crumb: Vector  # in
    score: Score
    heading: float  # degrees


class CrumbGame:
    """The game's state and rules; the physics is an engine World with one Body in it.

    It speaks :class:`engine.Steppable`, so a Scene steps it: ``step(dt)`` is one fixed step
    of the whole game (steer, physics, rules), ``t`` is the World's time, the game's one
    clock. ``player`` gives the keys held at each step; by default the autopilot plays.
    """

    def __init__(self, seed: int = 1, player: Player | None = None) -> None:
        self.rng = np.random.default_rng(seed)
        self.world = World(integrator="semi_implicit_euler")
        self.alfred = self.world.add(
            Body(self.start, radius=RADIUS, restitution=RESTITUTION, friction=FRICTION)
        )
        self.world.add_force(Wind(air_velocity=gust, k=K))  # Alfred's mass is 1
        #: The paper's edges: a room he stays inside.
        self.edge = self.world.add_collider(
            Box(PAPER[:2], PAPER[2:], restitution=EDGE_RESTITUTION, friction=EDGE_FRICTION)
        )
        self.sensor: Circle | None = None
        self.crumb = self._new_crumb()
        self._place_crumb(self.crumb)
        self.score = Score()
        #: The way Alfred faces (degrees counter-clockwise from +x): his velocity's direction,
        #: kept while he stands still (a zero velocity has no direction).
        self.heading = 90.0
        self.player: Player = self.autopilot if player is None else player

    @property
    def t(self) -> float:
        """The game's time (s): the World's."""
        return self.world.t

    def step(self, dt: float) -> None:
        """One fixed step of ``dt`` s: the player steers, the World steps, the rules apply."""
        self.steer(*self.player())
        self.world.step(dt)
        self.update()

    def snapshot(self) -> CrumbSnapshot:
        """The World, the random generator, the crumb, the score and Alfred's heading."""
        return CrumbSnapshot(
            self.world.snapshot(),
            copy.deepcopy(self.rng.bit_generator.state),
            self.crumb,
            replace(self.score),
            self.heading,
        )

    def restore(self, snapshot: CrumbSnapshot) -> None:
        """Return to the moment ``snapshot()`` was taken."""
        if not isinstance(snapshot, CrumbSnapshot):
            raise TypeError(
                f"restore takes a CrumbSnapshot from CrumbGame.snapshot(), got "
                f"{type(snapshot).__name__}"
            )
        self._place_crumb(snapshot.crumb)  # first: the World's contact state fits its sensor
        self.world.restore(snapshot.world)
        self.rng.bit_generator.state = copy.deepcopy(snapshot.rng)
        self.crumb, self.score = snapshot.crumb, replace(snapshot.score)
        self.heading = snapshot.heading

    @property
    def start(self) -> Vector:
        """The middle of the paper (in), where Alfred starts."""
        return Vector((PAPER[0] + PAPER[2]) / 2, (PAPER[1] + PAPER[3]) / 2)

    def _new_crumb(self) -> Vector:
        margin = 0.8
        x = self.rng.uniform(PAPER[0] + margin, PAPER[2] - margin)
        y = self.rng.uniform(PAPER[1] + margin, PAPER[3] - margin)
        return Vector(float(x), float(y))

    def _place_crumb(self, where: Vector) -> None:
        """Put the crumb's sensor at ``where``: Alfred eats it when his edge meets it."""
        if self.sensor is not None:
            self.world.remove_collider(self.sensor)
        # The sensor reports when his centre comes within his radius of its rim: REACH.
        self.sensor = Circle(where, REACH - RADIUS, sensor=True)
        self.world.add_collider(self.sensor)

    def steer(self, right: float, up: float) -> None:
        """Point Alfred's legs: right and up each in [-1, 1] (the arrow keys held)."""
        direction = Vector(right, up)
        if direction:
            direction = direction.normalized()
        # His own acceleration is the lesson's Body.acc: the push of his legs.
        self.alfred.own_acc = direction * PUSH

    def update(self) -> None:
        """Apply the rules after each physics step, from the World's contact events: eat the
        crumb when its sensor reports Alfred, count his bumps against the edge, turn him."""
        vel = self.alfred.vel
        if vel.magnitude() > 1e-6:
            self.heading = math.degrees(math.atan2(vel.y, vel.x))
        bumped = False
        for event in self.world.began:
            if event.collider is self.edge:
                bumped = bumped or event.impulse.magnitude() / self.alfred.mass >= BUMP
            elif event.collider is self.sensor:
                self.score.crumbs += 1
                self.crumb = self._new_crumb()
                self._place_crumb(self.crumb)
        self.score.bumps += bumped  # at most one a step

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
            f"crumbs {self.score.crumbs}    bumps {self.score.bumps}    t = {self.world.t:4.1f} s",
            (16, 10),
            size=26,
            color=PAPER_COLOUR,
        )
        draw_text(surface, "wind", (surface.get_width() - 150, 10), 22, PAPER_COLOUR)
        draw_vector(
            surface, camera, camera.to_world(surface.get_width() - 60, 20), air, 0.25, PAPER_COLOUR
        )


def arrow_keys() -> tuple[float, float]:
    """The player at the keyboard: (right, up) from the arrow keys held now."""
    keys = pygame.key.get_pressed()
    return (
        float(keys[pygame.K_RIGHT] - keys[pygame.K_LEFT]),
        float(keys[pygame.K_UP] - keys[pygame.K_DOWN]),
    )


class CrumbScene(Scene):
    """The game as a scene: steps a :class:`CrumbGame`, draws the paper, the crumb and Alfred."""

    name = "crumb"
    summary = "steer Alfred to the crumb with the arrow keys, in the wind"
    duration = 20.0
    dt = DT
    seed = 1
    world: CrumbGame

    def __init__(self, player: Player | None = None) -> None:
        #: Who steers: None for the autopilot, :func:`arrow_keys` for a person at the keyboard.
        self.player = player

    def build(self, size: tuple[int, int]) -> None:
        """A new game on a ``size`` px canvas: the paper fills it below the score line."""
        self.world = self.game = CrumbGame(self.seed, self.player)
        self.camera = Camera.fit(PAPER, (16, 40, size[0] - 32, size[1] - 56))

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """The table, the paper, the crumb and Alfred, blended by alpha between steps."""
        self.game.draw(surface, self.camera, alpha)


def play(
    window: bool,
    seconds: float | None = None,
    fps: int = 60,
    size: tuple[int, int] = (640, 360),
    seed: int = 1,
    out: Path | None = None,
    overwrite: bool = False,
) -> Score:
    """Run the game: in a window with the keys, or headless with the autopilot to PNG frames.

    In a window it runs until it is closed (or for ``seconds``). Headless, it records
    ``seconds`` (default 20) at ``fps`` to ``out`` (default out/crumb): frames at 1/fps s,
    2/fps s, ... up to ``seconds``, so ``seconds * fps`` frames.
    """
    scene = CrumbScene(arrow_keys if window else None)
    scene.seed = seed
    if window:
        play_window(scene, fps, size, WINDOW_SECONDS if seconds is None else seconds)
        return scene.game.score
    with FrameWriter(out or Path("out/crumb"), overwrite=overwrite) as frames:
        for index, _t, surface in iter_frames(scene, fps, seconds, size):
            if index > 0:  # the game's frames start one frame in
                frames.write(surface)
    return scene.game.score


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
    print(f"crumb: {score.crumbs} crumbs eaten, {score.bumps} bumps against the edge{where}")
    return 0


DEMO = Demo(
    name="crumb",
    summary="A small game: steer Alfred to the crumb with the arrow keys, in the wind",
    add_arguments=_add_arguments,
    run=_run,
    # A game, not scenes: no --scene, no motion diagram, no clip (yet).
    takes=frozenset({"--fps", "--seconds", "--size", "--out", "--overwrite", "--window", "--seed"}),
)
