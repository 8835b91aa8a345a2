"""pymunk's Body habits: the names a Body lacks, and what to write instead.

``body.force = ...`` or ``body.apply_impulse_at_world_point(...)`` is pymunk's habit;
``install`` puts a descriptor on the Body class for each such name, so that reading or writing
one raises an AttributeError that says what to use (engine.habits does the same for a World).
pymunk's ``Body(mass, moment)`` reads here as a body on a line (position, velocity): the errors
it leads to end with ``mass_and_moment``'s line, which says what to write.
"""

from __future__ import annotations

import math
from typing import Any

from .colours import COLOR_ADVICE

__all__ = ["PYMUNK_NAMES", "Advice", "install", "mass_and_moment"]


class Advice:
    """A name from pymunk with no counterpart here: reading or writing it says what to use."""

    def __init__(self, name: str, advice: str) -> None:
        self.name, self.advice = name, advice

    def _refuse(self) -> AttributeError:
        return AttributeError(f"a Body has no {self.name} (pymunk's name): {self.advice}")

    def __get__(self, body: Any, owner: Any = None) -> Any:
        if body is None:
            return self
        raise self._refuse()

    def __set__(self, body: Any, value: Any) -> None:
        raise self._refuse()


_PUSH = (
    "for a push that lasts, set body.own_acc = force / body.mass and body.torque (both kept "
    "until changed), or "
    "world.add_force(ConstantForce(...)) (engine.forces) for every body"
)
_IMPULSE = "body.apply_impulse(impulse, at=world_point) (at: the position by default)"
_IMPULSE_LOCAL = "body.apply_impulse(impulse, at=body.local_to_world(point))"
#: pymunk Body names, and what to write here instead.
PYMUNK_NAMES: dict[str, str] = {
    "force": _PUSH,
    "apply_force_at_world_point": "body.apply_force(force, at=world_point): for the next "
    "step only, as pymunk's",
    "apply_force_at_local_point": "body.apply_force(force, at=body.local_to_world(point)): for "
    "the next step only, as pymunk's",
    "apply_impulse_at_world_point": _IMPULSE,
    "apply_impulse_at_local_point": _IMPULSE_LOCAL,
    "space": "body.world is the World it is in",
    "body_type": "Body(..., kinematic=True) makes a body the game moves; static geometry is a "
    "collider (world.add_collider(Segment(...)))",
    "sleep_with_group": "body.sleep() puts the body to sleep with the awake bodies touching "
    "it, one group",
    "shapes": "a Body has one shape: Body(..., radius=r) for a disc, or Body(..., "
    "shape=Polygon.box(width, height)) (or a Polygon, a Segment); its material is the Body's "
    "(restitution=..., friction=...)",
    "elasticity": "its bounce is body.restitution = e (0 to 1; or Body(..., restitution=e))",
    "color": COLOR_ADVICE,
    "velocity_func": "forces act through the World: world.add_force(...) (engine.forces)",
    "position_func": "a body the game moves is Body(..., kinematic=True): write its pos or vel",
    "kinetic_energy": "world.energy() is the World's total; m v^2 / 2 is "
    "0.5 * body.mass * body.vel.length_squared()",
}


def mass_and_moment(mass: Any = None, moment: Any = None) -> str:
    """Body's order of arguments, what ``Body(mass, moment)`` is in it (when given), and
    pymunk's ``Body(mass, moment)`` (kg, kg m^2) as written here: the end of an error it led to."""
    given = ""
    m, i = "m", "I"
    if mass is not None:
        m, i = _code(mass), _code(moment)
        given = f"Body({m}, {i}) is a body on a line (1D) at position {m} moving at {i}; "
    never = "" if i == "math.inf" else " (moment=math.inf: a body that never turns)"
    return (
        f"Body's arguments are (position, velocity=None, acceleration=None, mass=1.0, *, ..., "
        f"moment=None): {given}pymunk's Body(mass, moment) is written here "
        f"Body(Vector(x, y), mass={m}, moment={i}){never}"
    )


def _code(value: Any) -> str:
    """``value`` as Python source: math.inf or math.nan for such a float."""
    if isinstance(value, float) and not math.isfinite(value):
        return "math.nan" if math.isnan(value) else "math.inf" if value > 0 else "-math.inf"
    return repr(value)


def install(cls: type) -> None:
    """Put an ``Advice`` on the Body class ``cls`` for every name of ``PYMUNK_NAMES`` (a name
    the Body comes to have itself keeps its own meaning)."""
    for name, text in PYMUNK_NAMES.items():
        if not hasattr(cls, name):
            setattr(cls, name, Advice(name, text))
