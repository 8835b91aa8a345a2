"""Which solver ``World(solver="auto")`` runs: the lesson's exact models or a game's soft step.

"Model no more than a scene needs" decides, as ``integrator="auto"`` picks a method:

- **the soft step** (engine.pipeline.game_step) where the scene holds a body that is not round and
  that a contact could push (a dynamic, solid Box, Polygon or capsule whose filter meets a
  solid collider or another solid body that no joint keeps apart from it: its contacts have
  two points, where the exact solver's corner contacts fail Box2D's HelloWorld: a crate dropped
  flat jumps 1 cm at restitution 0 and slides 25 mm aside; tests/test_rigid_scenes.py), or a
  joint that only the soft step solves (a link whose class says ``needs_soft``), or a body of
  several shapes (``Body(shapes=[...])``, engine.body_shapes), which the exact models refuse;
- **the exact models** (engine.pipeline.stepping) otherwise: discs and points, however many, with
  colliders of any shape, rods, cables, pins, hinges and welds (a ball's bounce heights
  h e^(2n), the cradle, a pendulum's period, a hinge held to 1e-9 m, continuous impacts for a
  pinball's ball), a body with corners that nothing can touch (a box spinning free in empty
  space, a plank on a hinge whose joint keeps it from its one neighbour), and every 1D world
  (the soft step is 2D).

The choice is made again as the scene is built and kept from the World's first step on: a
solver is not changed under a moving scene (its warm starts, its sleep). A body with corners
or a soft-only joint added later to a World that chose the exact models is warned of once,
naming ``World(solver="soft")``.

It is the default (``World()`` is ``World(solver="auto")``): a game's crates take the soft
step without being asked, and a lesson's discs keep their exact impacts. A lesson whose
bodies with corners meet something and must keep an exact model says so with
``World(solver="exact")``: the hinges demo's car and chain, the pinball table, whose flippers'
impacts are taken at their moment, so that no ball passes a bat at any speed (on the soft
step, ``PinballGame(solver="soft")``, its ball, a bullet (``Body.bullet``), passes a bat in
none of demos.bench.pinball's 1,000 throws at the game's speeds, 1 to 6 m/s, and in 11 of the
bench's 1,000 at 1 to 40 m/s, all at 22 to 37 m/s: engine/guide/games.md).
"""

from __future__ import annotations

import warnings
from typing import Any

from ..dynamics.joints import Joint

__all__ = ["SOLVERS", "choose", "needs_soft", "SolverWarning"]

#: What ``World(solver=...)`` takes.
SOLVERS = ("exact", "soft", "auto")


class SolverWarning(UserWarning):
    """A World's ``solver="auto"`` chose the exact models at its first step, and the scene has
    since taken something only the soft step solves well."""


def _kept_apart(links: Any) -> set[tuple[int, int]]:
    """The pairs of bodies (by ``id``, each pair in both orders) that a joint keeps from
    colliding (``Joint.kept_apart``)."""
    apart: set[tuple[int, int]] = set()
    for link in links:
        pair = link.kept_apart if isinstance(link, Joint) else None
        if pair is not None:
            a, b = id(pair[0]), id(pair[1])
            apart |= {(a, b), (b, a)}
    return apart


def _pushed(body: Any, bodies: Any, colliders: Any, apart: set[tuple[int, int]]) -> bool:
    """Whether a contact could push ``body``: a solid collider its filter meets, or another
    solid body its filter meets that no joint keeps apart from it."""
    mine = body.filter
    for collider in colliders:
        if not collider.sensor and mine.collides(collider.filter):
            return True
    for other in bodies:
        if (
            other is not body
            and not other.sensor
            and mine.collides(other.filter)
            and (id(body), id(other)) not in apart
        ):
            return True
    return False


def _cornered(bodies: Any, links: Any, colliders: Any) -> Any:
    """The first body that is not round and that a contact could push (dynamic, solid, and
    meeting a collider or another body by its filter), or None."""
    apart: set[tuple[int, int]] | None = None
    for body in bodies:
        shape = body.shape
        if shape is None or type(shape).__name__ == "Circle" or body.kinematic or body.sensor:
            continue
        if apart is None:
            apart = _kept_apart(links)
        if _pushed(body, bodies, colliders, apart):
            return body
    return None


def compound(bodies: Any) -> Any:
    """The first body of several shapes (``Body(shapes=[...])``, engine.body_shapes), or None:
    the exact models take one shape a body, so such a body is the soft step's alone."""
    for body in bodies:
        if type(body.shape).__name__ == "Compound":
            return body
    return None


def needs_soft(links: Any) -> Any:
    """The first link only the soft step solves (its class' ``needs_soft``), or None."""
    for link in links:
        if getattr(link, "needs_soft", False):
            return link
    return None


def choose(bodies: Any, links: Any, dim: int | None, colliders: Any = ()) -> tuple[str, str]:
    """``("soft" | "exact", why)``: what a World of ``bodies``, ``links``, static
    ``colliders`` and dimension ``dim`` (None: no bodies yet) runs under ``solver="auto"``,
    and why, in a sentence."""
    if dim == 1:
        return "exact", "a 1D world: the exact models (the soft step is 2D)"
    link = needs_soft(links)
    if link is not None:
        return "soft", f"the soft step: a {type(link).__name__} is one of its rows alone"
    body = compound(bodies)
    if body is not None:
        return "soft", (
            f"the soft step: a body of {len(body.shape)} shapes (Body(shapes=[...])) is its "
            f"alone (the exact models take one shape a body)"
        )
    body = _cornered(bodies, links, colliders)
    if body is not None:
        return "soft", (
            f"the soft step: a body with corners ({type(body.shape).__name__}) is pushed by "
            f"its contacts, which the soft step holds as Box2D's tests expect"
        )
    return "exact", (
        "the exact models: every body that contacts push is round (a disc or a point), so "
        "impacts are taken at their moment and joints held to rounding"
    )


def warn_if_outgrown(bodies: Any, links: Any, colliders: Any = ()) -> bool:
    """Warn (SolverWarning) if an ``"auto"`` World that chose the exact models now holds
    what would have chosen the soft step; True: it warned (once is enough)."""
    solver, why = choose(bodies, links, 2, colliders)
    if solver != "soft":
        return False
    warnings.warn(
        f"this World (solver='auto', the default) chose the exact models at its first "
        f"step, and now holds "
        f"what the soft step solves ({why.removeprefix('the soft step: ')}); a World keeps "
        f"its solver once it moves: make it with World(solver='soft') to have the soft "
        f"step from the start",
        SolverWarning,
        stacklevel=4,
    )
    return True
