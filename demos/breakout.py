"""Breakout: knock out a wall of bricks with a ball, using the engine the way your game would.

A ball bounces between three walls and a wall of bricks; the player moves a paddle along the
bottom to keep it in play. Each brick the ball touches is gone, for 10 points. A ball that
gets past the paddle falls into the drain and costs a life; the next ball is served from the
paddle. The game ends when the bricks are gone (cleared) or the 3 lives are (game over).

Every piece is the engine's public API, and the game writes no collision code of its own:

* the walls are ``Segment`` colliders and each brick a capsule (a ``Segment`` with a radius,
  so its ends are round); the ball is a Body with restitution 1 and friction 0, and since
  materials multiply (pymunk's rule) every bounce off a wall or a brick is lossless;
* the paddle is a *kinematic* disc (``Body(kinematic=True)``, radius 0.8 m) lying low: the
  game moves it by writing its ``pos`` each step, and contacts take its mass as infinite. The
  ball bounces off its round top, so where the ball lands on it sets the angle it leaves at:
  hit it off-centre to aim;
* the drain is a sensor (``Segment(..., sensor=True)``) under the paddle: it pushes nothing
  and reports the ball entering it;
* the rules read the World's contact events (``world.on_contact(ball, begin=...)``): a brick
  event removes that brick and scores, a drain event costs a life.

**No gravity**, as in the arcade game and pymunk's breakout example: the ball flies in straight
lines at a constant speed, so its path is easy to read and the autopilot can predict it with
a ruler (straight lines folded at the side walls). The one thing that changes the ball's speed
is the paddle: a moving paddle, being kinematic, hits the ball as a wall moving at its speed
would, which is real physics but would let a rally speed up without end. So after each paddle
hit the game keeps the ball's new direction and sets its speed back to ``SPEED``, as pymunk's
example does with a velocity callback.

The game is a Scene like every other demo (the model is ``demos/crumb.py``): what it steps is
:class:`BreakoutGame`, which speaks :class:`engine.Steppable`, so each fixed step of 1/120 s
moves the paddle, steps the World and applies the rules, whatever the frame rate, and a game
saved mid-run resumes exactly.

    python -m demos breakout --window     # play: arrow keys or the mouse move the paddle
    python -m demos breakout              # headless: an autopilot plays, frames to out/breakout/

Units: metres and seconds. The field is 20 m wide and 10 m high, the ball 0.25 m in radius.
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

from demos.cli import Demo
from demos.games import run_game
from engine import Body, ContactEvent, Segment, Vector, World
from engine.render import Camera, Scene, draw_dot, draw_text
from engine.world import WorldSnapshot

#: The field inside the walls (m): x0, y0 (the paddle's line is near y0), x1, y1 (the ceiling).
FIELD = (0.0, 0.0, 20.0, 10.0)
#: The ball: radius (m) and its speed (m/s), which the paddle never changes.
BALL_RADIUS, SPEED = 0.25, 11.0
#: The paddle: a disc of this radius (m) whose centre runs along y = PADDLE_Y, at most
#: PADDLE_SPEED m/s; only its top 0.5 m shows above the field's floor line.
PADDLE_RADIUS, PADDLE_Y, PADDLE_SPEED = 0.8, -0.3, 14.0
#: The wall of bricks: ROWS x COLUMNS capsules, each BRICK_LENGTH long between its two end
#: centres and BRICK_RADIUS thick on each side; the gaps between them are narrower than the
#: ball, so it never slips through a row.
ROWS, COLUMNS = 5, 10
BRICK_LENGTH, BRICK_RADIUS = 1.2, 0.3
BRICK_BOTTOM, ROW_PITCH = 5.4, 0.7  # the lowest row's line (m) and the rows' spacing (m)
POINTS = 10  # a brick
LIVES = 3
#: Seconds the ball rides on the paddle before each serve.
SERVE_DELAY = 0.75
DT = 1.0 / 120.0
#: The drain: a sensor capsule along this line (m), thick enough that a ball at SPEED cannot
#: cross it within one step (sensors judge where bodies are at the end of each step).
DRAIN_Y, DRAIN_RADIUS = -2.2, 0.5

BACKGROUND, WALL_COLOUR, INK = (22, 24, 38), (150, 156, 180), (236, 236, 244)
BALL_COLOUR, PADDLE_COLOUR, DRAIN_COLOUR = (255, 255, 255), (80, 200, 255), (90, 30, 40)
ROW_COLOURS = [(235, 87, 87), (242, 153, 74), (242, 201, 76), (111, 207, 151), (155, 120, 230)]
#: How long a game in a window may last (s) when no --seconds is given: until it is closed.
WINDOW_SECONDS = 24 * 3600.0
#: A headless run without --seconds stops this long after the game ends, or at MAX_SECONDS.
AFTER_END, MAX_SECONDS = 1.5, 240.0

#: A player: given the game, the x (m) where it wants the paddle's centre now.
Player = Callable[["BreakoutGame"], float]


@dataclass
class Score:
    """Where the game stands."""

    points: int = 0
    bricks: int = 0  # bricks knocked out
    lives: int = LIVES

    @property
    def over(self) -> bool:
        """Whether the game has ended: no bricks left, or no lives."""
        return self.bricks == ROWS * COLUMNS or self.lives == 0


@dataclass(frozen=True)
class BreakoutSnapshot:
    """Everything a game needs to resume: see :meth:`BreakoutGame.snapshot`."""

    world: WorldSnapshot
    rng: Mapping[str, Any]  # the random generator's state, for the next serve
    bricks: tuple[Segment, ...]  # the bricks still standing, in the World's order
    score: Score
    serve_at: float | None  # when the ball riding on the paddle is served (s), or None


class BreakoutGame:
    """The game's state and rules; the physics is an engine World with two bodies in it.

    ``step(dt)`` is one fixed step of the whole game (the paddle moves, the World steps, the
    rules apply); ``t`` is the World's time. ``player`` says where the paddle should go; by
    default the autopilot plays.
    """

    def __init__(self, seed: int = 1, player: Player | None = None) -> None:
        self.rng = np.random.default_rng(seed)
        x0, _, x1, y1 = FIELD
        middle = (x0 + x1) / 2
        self.world = World(integrator="semi_implicit_euler")  # no force: straight lines
        # Restitution 1, friction 0: with the colliders' defaults (1 and 1, multiplied in),
        # every bounce keeps the ball's speed and mirrors its direction.
        self.ball = self.world.add(
            Body(Vector(middle, 1), Vector(0, 0), Vector(0, 0), radius=BALL_RADIUS,
                 restitution=1.0, friction=0.0)
        )  # fmt: skip
        self.paddle = self.world.add(
            Body(Vector(middle, PADDLE_Y), Vector(0, 0), Vector(0, 0), radius=PADDLE_RADIUS,
                 restitution=1.0, friction=0.0, kinematic=True)
        )  # fmt: skip
        # Walls left, top, right, reaching down past the drain so nothing leaves sideways.
        low = DRAIN_Y - DRAIN_RADIUS
        corners = [(x0, low), (x0, y1), (x1, y1), (x1, low)]
        self.walls = [Segment(a, b) for a, b in zip(corners[:-1], corners[1:], strict=True)]
        self.drain = Segment((x0, DRAIN_Y), (x1, DRAIN_Y), DRAIN_RADIUS, sensor=True)
        #: The bricks standing, each with its row (0 is the lowest), in the World's order.
        self.bricks: dict[Segment, int] = {}
        pitch = (x1 - x0) / COLUMNS
        for row in range(ROWS):
            y = BRICK_BOTTOM + row * ROW_PITCH
            for col in range(COLUMNS):
                mid = x0 + (col + 0.5) * pitch
                a, b = (mid - BRICK_LENGTH / 2, y), (mid + BRICK_LENGTH / 2, y)
                self.bricks[Segment(a, b, BRICK_RADIUS)] = row
        for collider in [*self.walls, self.drain, *self.bricks]:
            self.world.add_collider(collider)
        self._rows = dict(self.bricks)  # every brick's row, standing or not (for restore)
        self._hits: list[ContactEvent] = []
        # The World calls this after each step for each contact of the ball that began.
        self.world.on_contact(self.ball, begin=self._hits.append)
        self.score = Score()
        self.serve_at: float | None = None
        self.player: Player = autopilot if player is None else player
        self._ride()

    @property
    def t(self) -> float:
        """The game's time (s): the World's."""
        return self.world.t

    def step(self, dt: float) -> None:
        """One fixed step of ``dt`` s: the paddle moves, the World steps, the rules apply."""
        if not self.score.over:
            x = self.paddle.pos.x
            reach = PADDLE_SPEED * dt
            want = min(max(self.player(self), x - reach), x + reach)
            # The paddle passes through static colliders, so the game keeps it in the field.
            x0, _, x1, _ = FIELD
            want = min(max(want, x0 + PADDLE_RADIUS), x1 - PADDLE_RADIUS)
            # Writing a kinematic body's pos moves it there over the next step.
            self.paddle.pos = Vector(want, PADDLE_Y)
        else:
            self.paddle.vel = Vector(0, 0)
        if self.serve_at is not None:
            self._ride()
        self.world.step(dt)
        self.update()

    def update(self) -> None:
        """Apply the rules to the contacts that began in the last step (``self._hits``)."""
        hits, self._hits[:] = list(self._hits), []
        paddled = False
        for event in hits:
            if event.collider in self.bricks:
                self.world.remove_collider(event.collider)
                del self.bricks[event.collider]
                self.score.bricks += 1
                self.score.points += POINTS
            elif self.paddle in (event.body, event.collider):  # a pair: either order
                paddled = True
            elif event.collider is self.drain and self.serve_at is None:
                self.score.lives -= 1
                self.serve_at = self.t + SERVE_DELAY
                self._ride()
        if paddled and self.serve_at is None:
            vel = self.ball.vel
            self.ball.vel = vel * (SPEED / vel.magnitude())  # the paddle aims, never speeds
        if self.score.over:
            self.serve_at = None
            self.ball.pos, self.ball.vel = self.ball.pos, Vector(0, 0)  # the ball stops
        elif self.serve_at is not None and self.t >= self.serve_at - 1e-9:
            self.serve()

    def _ride(self) -> None:
        """Before a serve the ball sits on top of the paddle and moves with it."""
        if self.serve_at is None:  # the first serve
            self.serve_at = self.t + SERVE_DELAY
        top = PADDLE_Y + PADDLE_RADIUS + BALL_RADIUS + 0.05
        self.ball.pos, self.ball.vel = Vector(self.paddle.pos.x, top), self.paddle.vel

    def serve(self) -> None:
        """Launch the ball upward at SPEED, up to 30 degrees either side of straight up."""
        self.serve_at = None
        angle = math.radians(90.0 + float(self.rng.uniform(-30.0, 30.0)))
        self.ball.vel = Vector(math.cos(angle), math.sin(angle)) * SPEED

    def snapshot(self) -> BreakoutSnapshot:
        """The World, the random generator, the bricks standing, the score and the serve."""
        return BreakoutSnapshot(
            self.world.snapshot(),
            copy.deepcopy(self.rng.bit_generator.state),
            tuple(self.bricks),
            replace(self.score),
            self.serve_at,
        )

    def restore(self, snapshot: BreakoutSnapshot) -> None:
        """Return to the moment ``snapshot()`` was taken."""
        if not isinstance(snapshot, BreakoutSnapshot):
            raise TypeError(
                f"restore takes a BreakoutSnapshot from BreakoutGame.snapshot(), got "
                f"{type(snapshot).__name__}"
            )
        # First the bricks, in their order (the World's contact state fits its colliders).
        for brick in self.bricks:
            self.world.remove_collider(brick)
        self.bricks = {b: self._rows[b] for b in snapshot.bricks}
        for brick in self.bricks:
            self.world.add_collider(brick)
        self.world.restore(snapshot.world)
        self.rng.bit_generator.state = copy.deepcopy(snapshot.rng)
        self.score, self.serve_at = replace(snapshot.score), snapshot.serve_at
        self._hits.clear()

    def draw(self, surface: pygame.Surface, camera: Camera, alpha: float) -> None:
        """Draw the field, the bricks, the paddle, the ball and the score line."""
        surface.fill(BACKGROUND)
        x0, _, x1, _ = FIELD
        drain_top = camera.point((x0, DRAIN_Y + DRAIN_RADIUS))
        pygame.draw.rect(
            surface,
            DRAIN_COLOUR,
            (*drain_top, round(camera.length(x1 - x0)), round(camera.length(2 * DRAIN_RADIUS))),
        )
        for wall in self.walls:
            pygame.draw.line(surface, WALL_COLOUR, camera.point(wall.a), camera.point(wall.b), 3)
        thick = max(2, round(camera.length(2 * BRICK_RADIUS)))
        for brick, row in self.bricks.items():
            colour = ROW_COLOURS[row % len(ROW_COLOURS)]
            a, b = camera.point(brick.a), camera.point(brick.b)
            pygame.draw.line(surface, colour, a, b, thick)
            for end in (a, b):  # the round ends
                pygame.draw.circle(surface, colour, end, thick / 2)
        # The paddle: a disc whose lower part is hidden below the field, as a flat-bottomed dome.
        paddle = camera.point(self.world.position_of(self.paddle, alpha))
        pygame.draw.circle(surface, PADDLE_COLOUR, paddle, camera.length(PADDLE_RADIUS))
        ball = camera.point(self.world.position_of(self.ball, alpha))
        draw_dot(surface, ball, max(2.0, camera.length(BALL_RADIUS)), BALL_COLOUR)
        s = self.score
        line = f"score {s.points}    lives {s.lives}    bricks {len(self.bricks)}"
        draw_text(surface, line, (16, 10), size=26, color=INK)
        draw_text(
            surface, f"t = {self.t:5.1f} s", (surface.get_width() - 16, 10), 26, INK, "topright"
        )
        if s.over:
            verdict = "CLEARED!" if not self.bricks else "GAME OVER"
            centre = (surface.get_width() / 2, surface.get_height() / 2)
            draw_text(surface, verdict, centre, 48, INK, "center", background=BACKGROUND)


def crossing(game: BreakoutGame) -> float | None:
    """Where the ball's centre will cross the paddle's top line (m), if it is coming down.

    With no gravity the ball flies straight, and a bounce off a side wall mirrors its path,
    so the crossing is the straight line's, folded back into the field between the walls.
    Bricks on the way are not foreseen: the answer is asked again every step.
    """
    (x, y), (vx, vy) = game.ball.pos, game.ball.vel
    line = PADDLE_Y + PADDLE_RADIUS + BALL_RADIUS
    if vy >= 0.0:
        return None
    x += vx * (line - y) / vy
    lo, hi = FIELD[0] + BALL_RADIUS, FIELD[2] - BALL_RADIUS
    width = hi - lo
    u = (x - lo) % (2 * width)  # fold: every 2 widths the mirrored path repeats
    return lo + (u if u <= width else 2 * width - u)


#: The autopilot starts for the ball's crossing only once the ball is below this line (m):
#: like a person, it can be too late for a ball that comes down far from it.
REACT = BRICK_BOTTOM + ROWS * ROW_PITCH / 2


def autopilot(game: BreakoutGame) -> float:
    """Where a good player would put the paddle: under the ball's crossing, a little to one
    side, so that the ball leaves toward the nearest of the lowest bricks standing (the
    paddle's round top aims it)."""
    ball = game.ball.pos
    where = crossing(game)
    if game.serve_at is not None:
        return ball.x
    if where is None or ball.y > REACT:
        return game.paddle.pos.x  # it waits until the ball comes down past the bricks
    if not game.bricks:
        return where
    # Aim at the middle of the lowest row standing. For a disc that stays still, the ball
    # leaves mirrored about the normal at the point of contact, so that normal is the
    # bisector of the way in reversed and the way out: n ~ out - in.
    lowest = min(game.bricks.values())
    xs = [(b.a.x + b.b.x) / 2 for b, row in game.bricks.items() if row == lowest]
    nearest = min(xs, key=lambda x: abs(x - where))
    goal = Vector(nearest, BRICK_BOTTOM + lowest * ROW_PITCH)
    out = goal - Vector(where, PADDLE_Y + PADDLE_RADIUS)
    normal = out.normalize() - game.ball.vel.normalize()
    # Keep the contact on the paddle's top, within 35 degrees of its crown.
    reach = (PADDLE_RADIUS + BALL_RADIUS) * math.sin(math.radians(35.0))
    offset = max(-reach, min(reach, (PADDLE_RADIUS + BALL_RADIUS) * normal.normalize().x))
    return where - offset


class Person:
    """The player at the keyboard or mouse: the arrow keys push the paddle at full speed; a
    mouse moved over the window puts the paddle under the pointer."""

    def __init__(self, camera: Camera) -> None:
        self.camera = camera
        self.mouse: tuple[int, int] | None = None  # the pointer when first seen

    def __call__(self, game: BreakoutGame) -> float:
        keys = pygame.key.get_pressed()
        push = keys[pygame.K_RIGHT] - keys[pygame.K_LEFT]
        x = game.paddle.pos.x
        if push:
            self.mouse = None  # the keys take over until the mouse moves again
            return x + push * PADDLE_SPEED
        at = pygame.mouse.get_pos()
        if self.mouse is None:
            self.mouse = at
        if at != self.mouse or not pygame.mouse.get_focused():
            return float(self.camera.to_world(*at)[0])
        return x


class BreakoutScene(Scene):
    """The game as a scene: steps a :class:`BreakoutGame` and draws it."""

    name = "breakout"
    summary = "knock out the bricks: the paddle is a kinematic disc, the drain a sensor"
    duration = MAX_SECONDS
    dt = DT
    seed = 1
    world: BreakoutGame

    def __init__(self, person: bool = False) -> None:
        #: Who plays: a person at the keys or mouse (True), or the autopilot.
        self.person = person

    def build(self, size: tuple[int, int]) -> None:
        """A new game on a ``size`` px canvas: the field fills it below the score line."""
        x0, y0, x1, y1 = FIELD
        view = (x0 - 0.3, DRAIN_Y, x1 + 0.3, y1 + 0.3)  # the drain's upper half shows
        self.camera = Camera.fit(view, (8, 40, size[0] - 16, size[1] - 48))
        player = Person(self.camera) if self.person else None
        self.world = self.game = BreakoutGame(self.seed, player)

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """The field, blended by alpha between steps."""
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
    """Run the game: in a window with the keys or mouse, or headless with the autopilot.

    Headless it writes PNG frames at ``fps`` to ``out`` (default out/breakout), 1/fps s
    apart: for ``seconds`` if given, else until AFTER_END s after the game ends (at most
    MAX_SECONDS).
    """
    scene = BreakoutScene(person=window)
    scene.seed = seed
    run_game(
        scene, window, seconds, fps, size, out or Path("out/breakout"), overwrite,
        WINDOW_SECONDS, MAX_SECONDS, AFTER_END,
    )  # fmt: skip
    return scene.game.score


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.set_defaults(seed=1)


def _run(args: argparse.Namespace) -> int:
    out = args.out or Path("out/breakout")
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
    print(
        f"breakout: {score.points} points, {score.bricks} of {ROWS * COLUMNS} bricks, "
        f"{score.lives} {'life' if score.lives == 1 else 'lives'} left{where}"
    )
    return 0


DEMO = Demo(
    name="breakout",
    summary="A small game: knock out the bricks with the arrow keys or the mouse",
    add_arguments=_add_arguments,
    run=_run,
    # A game, not scenes: no --scene, no motion diagram, no clip (yet).
    takes=frozenset({"--fps", "--seconds", "--size", "--out", "--overwrite", "--window", "--seed"}),
)
