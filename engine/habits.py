"""pymunk's Space habits on a World: the names a World lacks, and what to write instead.

``world.gravity = (0, -9.8)`` is pymunk's habit; a World that kept the attribute and ignored
it would fail silently. ``install`` puts a descriptor on the World class for every name of
``PYMUNK_NAMES`` the class does not have, so that reading or writing one raises an
AttributeError that says what to use; ``World.__setattr__`` refuses every other unknown name
with ``unknown``'s message, which lists what can be set. pymunk's ``space.add(body, shape)``
hands several things at once: ``several`` says what World.add and World.remove take instead.

A class attribute costs nothing on the names the World has: no ``__getattr__`` (it would slow
every attribute read).
"""

from __future__ import annotations

from typing import Any

__all__ = ["PYMUNK_NAMES", "Advice", "unknown", "several", "install"]

#: pymunk Space names, and what to write here instead.
PYMUNK_NAMES: dict[str, str] = {
    "gravity": "gravity is a force: world.add_force(Gravity((0, -9.81))) "
    "(from engine.forces import Gravity); to change it in play, world.remove_force(the one "
    "add_force returned) and add another",
    "damping": "damping is a force: world.add_force(Drag(k)) (F = -k v; pymunk's damping d "
    "is k = -m ln(d)), from engine.forces",
    "iterations": "world.contact_iterations (default 4, the soft step's substeps)",
    "sleep_time_threshold": "world.sleep_time (s; math.inf never sleeps)",
    "idle_speed_threshold": "a resting group sleeps once slower than |a| dt for "
    "world.sleep_time seconds",
    "collision_slop": "there is no slop: overlaps past 0.2% of a radius are pushed out",
    "collision_bias": "there is no bias: overlaps past 0.2% of a radius are pushed out",
    "collision_persistence": "contacts carry their impulses from step to step by themselves",
    "shapes": "world.colliders (static shapes); a Body has one shape: Body(..., shape=...)",
    "constraints": "world.links (rods, cables, pins, hinges, welds)",
    "add_collision_handler": "world.on_contact(body_or_collider, begin=..., end=...)",
    "add_wildcard_collision_handler": "world.on_contact(body_or_collider, begin=..., end=...)",
    "add_default_collision_handler": "world.on_contact(...), or read world.began and "
    "world.ended after each step",
    "on_collision": "world.on_contact(body_or_collider, begin=..., end=...)",
    "current_time_step": "the dt you pass to world.step(dt); world.t is the time",
    "debug_draw": "draw with engine.render (Camera, draw_dot, ...)",
    "bb_query": "world.point_query(point, max_distance)",
    "shape_query": "world.point_query(point, max_distance)",
    "add_post_step_callback": "act after world.step(dt) returns: events are in world.began",
    "threads": "the World steps in one thread",
    "threaded": "the World steps in one thread",
}


def unknown(cls: type, name: str, how: str) -> str:
    """The message for an attribute ``name`` that the class ``cls`` (the World) does not have
    (``how``: "read" or "set")."""
    advice = PYMUNK_NAMES.get(name)
    if advice is not None:
        return f"a World has no {name} (pymunk's name): {advice}"
    settable = sorted(
        n
        for n, v in vars(cls).items()
        if isinstance(v, property) and v.fset is not None and n[0] != "_"
    )
    return (
        f"a World has no attribute {name!r} to {how}; what can be set on it is "
        f"{', '.join(settable)} (and it is changed through add, add_force, add_collider, "
        f"add_link and step)"
    )


def several(verb: str, things: tuple[Any, ...]) -> str:
    """The message for World.add or World.remove (``verb``) handed ``things``, several, as
    pymunk's ``space.add(body, shape)`` and ``space.remove(body, shape)`` take them."""
    given = ", ".join(repr(thing) for thing in things)
    if verb == "add":
        what = (
            "a Body carries its shape (Body(..., radius=r), or Body(..., shape=Polygon.box(w, "
            "h))), so write world.add(body); many bodies go by world.add_all([...]), colliders "
            "by world.add_collider(...), links by world.add_link(...)"
        )
    else:
        what = (
            "a body's shape goes out with it, so write world.remove(body); colliders go by "
            "world.remove_collider(...), links by world.remove_link(...)"
        )
    return (
        f"World.{verb} takes one Body, got {len(things)} things ({given}): pymunk's "
        f"space.{verb}(body, shape) takes several at once; here {what}"
    )


class Advice:
    """A pymunk Space name the World lacks: reading or writing it says what to use instead."""

    def __init__(self, cls: type, name: str) -> None:
        self.cls, self.name = cls, name

    def __get__(self, world: Any, owner: Any = None) -> Any:
        if world is None:
            return self
        raise AttributeError(unknown(self.cls, self.name, "read"))

    def __set__(self, world: Any, value: Any) -> None:
        raise AttributeError(unknown(self.cls, self.name, "set"))


def install(cls: type) -> None:
    """Put an ``Advice`` on ``cls`` for every pymunk name it does not have (a name the World
    comes to have keeps its own meaning)."""
    for name in PYMUNK_NAMES:
        if not hasattr(cls, name):
            setattr(cls, name, Advice(cls, name))
