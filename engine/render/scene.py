"""The scene interface shared by the demos, the tests, the benchmarks and users' own games.

A scene is a small class: it builds its World and camera, steps its physics, and draws a frame.
The recorder (:func:`engine.render.record`), the window player (:func:`engine.render.play`) and
the command line (``python -m demos``) drive any scene the same way:

1. ``scene.build(size)``: make ``self.world``, ``self.camera`` and whatever else the scene needs
   for a canvas of ``size`` = (width, height) pixels. Called before the first frame, and again to
   restart, so it must reset everything. ``self.world`` is whatever the scene steps: anything
   that speaks :class:`engine.Steppable` (``step(dt)``, ``t``, ``snapshot()``, ``restore()``),
   such as a :class:`engine.World`, an :class:`engine.particles.Particles` system, or an
   object of the scene's own that steps several of them and the game's rules together. Its
   ``t`` is the scene's one clock.
2. ``scene.step(scene.dt)`` once: the world runs one step ahead of the frame being drawn (see
   below).
3. Each frame: ``scene.step(scene.dt)`` a whole number of times (as the fixed-step loop says),
   then ``scene.draw(surface, alpha)``.

Why one step ahead: ``World.positions(alpha)`` blends the state before the last step with the
state after it. Stepping once before the first frame makes those two states bracket the frame's
time ``T``, so the blend shows the world exactly at ``T`` (no one-step lag, which would be a
whole second for the lesson's sprint at dt = 1 s). :meth:`Scene.time` gives that T.

A minimal scene::

    class Drop(Scene):
        name, summary, duration, dt = "drop", "a ball falls", 2.0, 1 / 120

        def build(self, size):
            self.world = World()
            self.ball = self.world.add(Body((0.0, 10.0), (0.0, 0.0), (0.0, 0.0)))
            self.world.add_force(Gravity((0.0, -9.81)))
            self.camera = Camera.fit((-5, 0, 5, 10), (0, 0, *size))

        def draw(self, surface, alpha):
            surface.fill(PAPER)
            draw_dot(surface, self.camera.to_px(*self.world.position_of(self.ball, alpha)))
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import pygame

from engine.loop import Steppable

__all__ = ["Scene"]


class Scene:
    """Base class for scenes; subclasses set the class attributes and override build/draw."""

    #: Short name used on the command line (``--scene NAME``).
    name: str = "scene"
    #: One line saying what the scene shows.
    summary: str = ""
    #: Simulated seconds a recording lasts by default.
    duration: float = 5.0
    #: Physics time step (s); usually 1/120 s. The fixed-step loop always steps by exactly this.
    dt: float = 1.0 / 120.0
    #: Seed for scenes with randomness; set it before build() (the CLI sets it from --seed).
    seed: int = 0
    #: The smallest canvas (width, height) in px the scene can lay itself out on.
    min_size: tuple[int, int] = (1, 1)

    #: What the scene steps; its ``t`` is the scene's time (s).
    world: Steppable
    camera: Any

    def build(self, size: tuple[int, int]) -> None:
        """Make the world, camera and state for a ``size`` px canvas; called again to restart."""
        raise NotImplementedError(f"{type(self).__name__} must define build(size)")

    def step(self, dt: float) -> None:
        """Advance the physics by exactly ``dt`` seconds (one fixed step)."""
        self.world.step(dt)

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """Draw the whole frame: the state blended ``alpha`` (0 to 1) from previous to current."""
        raise NotImplementedError(f"{type(self).__name__} must define draw(surface, alpha)")

    def time(self, alpha: float) -> float:
        """Simulated time (s) of the state that ``draw`` shows with this ``alpha``.

        The blend runs from the state one step before ``world.t`` (alpha = 0) to the state at
        ``world.t`` (alpha = 1), so the time shown is ``world.t - (1 - alpha) * dt``; never below 0.
        """
        return max(0.0, self.world.t - (1.0 - alpha) * self.dt)

    # --- saving and resuming ---------------------------------------------------------------
    def snapshot(self) -> Any:
        """Everything needed to resume the scene from this moment (default: its world's).

        A scene that keeps state outside ``self.world`` that changes what it draws (a random
        generator, an afterglow) extends both this and :meth:`restore`, so that restoring
        mid-run and drawing on gives the same frames as a run never interrupted. State that
        the physics needs (several worlds, a game's rules and score) is better kept in the
        stepped object itself, which then saves it in its own snapshot.
        """
        return self.world.snapshot()

    def restore(self, snapshot: Any) -> None:
        """Return to the moment ``snapshot()`` was taken."""
        self.world.restore(snapshot)

    # --- motion diagrams ------------------------------------------------------------------

    #: Seconds between the images of a strobe picture (a motion diagram).
    strobe_interval: float = 1.0

    def strobe_times(self) -> list[float]:
        """The times (s) a strobe picture shows: 0, interval, 2 interval, ... up to duration."""
        count = int(self.duration / self.strobe_interval + 1e-9)
        return [k * self.strobe_interval for k in range(count + 1)]

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """Draw one still with the body at each of ``times`` (s), older ones faded, labelled with t.

        Optional: scenes without a motion diagram leave it; the recorder then says so.
        """
        raise NotImplementedError(f"the scene {self.name!r} has no strobe picture")

    @property
    def has_strobe(self) -> bool:
        """Whether this scene draws a strobe picture (overrides draw_strobe)."""
        return type(self).draw_strobe is not Scene.draw_strobe
