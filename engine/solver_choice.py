"""Which solver ``World(solver="auto")`` runs: the lesson's exact models or a game's soft step.

"Model no more than a scene needs" decides, as ``integrator="auto"`` picks a method:

- **the soft step** (engine.game_step) where the scene holds a body that is not round and
  that contacts push (a dynamic Box, Polygon or capsule: its contacts have two points, where
  the exact solver's corner contacts fail Box2D's HelloWorld: a crate dropped flat jumps 1 cm
  at restitution 0 and slides 25 mm aside; tests/test_rigid_scenes.py), or a joint that only
  the soft step solves (a link whose class says ``needs_soft``);
- **the exact models** (engine.stepping) otherwise: discs and points, however many, with
  colliders of any shape, rods, cables, pins, hinges and welds (a ball's bounce heights
  h e^(2n), the cradle, a pendulum's period, a hinge held to 1e-9 m, continuous impacts for a
  pinball's ball), and every 1D world (the soft step is 2D).

The choice is made again as the scene is built and kept from the World's first step on: a
solver is not changed under a moving scene (its warm starts, its sleep). A body with corners
or a soft-only joint added later to a World that chose the exact models is warned of once,
naming ``World(solver="soft")``.

It is not the default (``World()`` stays exact): the rule cannot yet tell a lesson's bodies
with corners from a game's. Under it, a chain of planks on hinges held to 1e-9 m, a car
climbing at its closed-form speed and the pinball's flippers would leave their exact models
for the soft step (77 of the suite's tests fail with "auto" as the default, 2026-12-03: the
pinball's 16, joints 12, a free box's angular drag 8 (no contact could push it, so it should
stay exact), the thin walls 6, the mouse joint 5, ...). The soft step sweeps fast bodies to
their moment of impact since (engine.game_continuous), and a pinball's ball as a bullet
(``Body.bullet``) crosses a flipper in none of 1000 throws, but ends a step inside the turning
bat in 7, where the exact solver's impacts leave none.
"""

from __future__ import annotations

import warnings
from typing import Any

__all__ = ["SOLVERS", "choose", "needs_soft", "SolverWarning"]

#: What ``World(solver=...)`` takes.
SOLVERS = ("exact", "soft", "auto")


class SolverWarning(UserWarning):
    """A World's ``solver="auto"`` chose the exact models at its first step, and the scene has
    since taken something only the soft step solves well."""


def _cornered(bodies: Any) -> Any:
    """The first body that is not round and is pushed by its contacts (neither kinematic nor
    static), or None."""
    for body in bodies:
        shape = body.shape
        if shape is not None and type(shape).__name__ != "Circle" and not body.kinematic:
            return body
    return None


def needs_soft(links: Any) -> Any:
    """The first link only the soft step solves (its class' ``needs_soft``), or None."""
    for link in links:
        if getattr(link, "needs_soft", False):
            return link
    return None


def choose(bodies: Any, links: Any, dim: int | None) -> tuple[str, str]:
    """``("soft" | "exact", why)``: what a World of ``bodies``, ``links`` and dimension
    ``dim`` (None: no bodies yet) runs under ``solver="auto"``, and why, in a sentence."""
    if dim == 1:
        return "exact", "a 1D world: the exact models (the soft step is 2D)"
    link = needs_soft(links)
    if link is not None:
        return "soft", f"the soft step: a {type(link).__name__} is one of its rows alone"
    body = _cornered(bodies)
    if body is not None:
        return "soft", (
            f"the soft step: a body with corners ({type(body.shape).__name__}) is pushed by "
            f"its contacts, which the soft step holds as Box2D's tests expect"
        )
    return "exact", (
        "the exact models: every body that contacts push is round (a disc or a point), so "
        "impacts are taken at their moment and joints held to rounding"
    )


def warn_if_outgrown(bodies: Any, links: Any) -> bool:
    """Warn (SolverWarning) if an ``"auto"`` World that chose the exact models now holds
    what would have chosen the soft step; True: it warned (once is enough)."""
    solver, why = choose(bodies, links, 2)
    if solver != "soft":
        return False
    warnings.warn(
        f"World(solver='auto') chose the exact models at its first step, and now holds "
        f"what the soft step solves ({why.removeprefix('the soft step: ')}); a World keeps "
        f"its solver once it moves: make it with World(solver='soft') to have the soft "
        f"step from the start",
        SolverWarning,
        stacklevel=4,
    )
    return True
