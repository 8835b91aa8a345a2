"""A point particle: the lesson's ``rbpbodies.Body`` with position, velocity and acceleration.

A 1D body (Alfred on his tube) holds three floats; a 2D body (Alfred on his
sheet of paper) holds three Vectors. A point has no size, so it has no
rotation either (lesson, section 3.1).

Out of a World a Body just stores what it is given. Once added to a
:class:`engine.World`, its ``pos`` and ``vel`` read and write the world's live
state, and ``acc`` reads the total acceleration at this instant: the body's own
constant acceleration (the ``acceleration`` it was made with, kept as
``own_acc``) plus the forces' pull divided by the mass. In a World the Body is a handle: the
World's arrays hold its state, mass and own acceleration (``engine.dynamics.store``).

>>> b = Body(Vector(0, 0), Vector(1, 0), Vector(0, 0))
>>> print(b)
Position: X: 0.0 Y: 0.0
Velocity: X: 1.0 Y: 0.0
Acceleration: X: 0.0 Y: 0.0
<BLANKLINE>
>>> Body(2, 1, 0).pos
2.0
"""

from __future__ import annotations

import math
from numbers import Real
from typing import TYPE_CHECKING, Any, Protocol, cast

from .body_habits import install as install_habits
from .body_habits import mass_and_moment
from .body_shapes import PARTS, Compound, centred
from .body_values import (
    DEFAULT_MASS,
    FRICTION,
    RESTITUTION,
    State,
    coerce_density,
    coerce_mass,
    coerce_state,
    dim_of,
    finite,
    material,
    pair,
    real_number,
    refuse_change,
)
from .collision_types import as_collision_type
from .colours import Colour, as_colour
from .filters import DEFAULT as DEFAULT_FILTER
from .filters import Filter, as_filter
from .vector import Vector, new_unchecked

if TYPE_CHECKING:
    from .dynamics.store import BodyStore

__all__ = ["Body", "State", "WorldLike"]

_isfinite = math.isfinite

#: Whether bodies with corners (a Polygon, a Segment's capsule) turn, with the moment of their
#: shape (``shape.moment(mass)``), in the piles' soft step (engine.exact.soft: lever arms r x n on
#: the normal rows too): a box tips, topples and stacks (tests/test_rotation_shapes.py).
#: False gives the earlier version's boxes, which keep their angle. Read as a body is made or
#: added: set it before.
CORNERS_TURN = True


class WorldLike(Protocol):
    """``body.world``: the World that holds the body, by what a game asks of it through one."""

    # engine.world imports this module, so a Body names its World by these members (which
    # engine.world.World has), not by its class.

    @property
    def t(self) -> float:
        """Simulated time (s) since the world began."""
        ...

    @property
    def bodies(self) -> tuple[Body, ...]:
        """The bodies in the world, in the order they were added."""
        ...

    def step(self, dt: float) -> None:
        """Advance every body by ``dt`` seconds."""
        ...

    def remove(self, body: Body) -> None:
        """Take ``body`` out of the world."""
        ...

    def position_of(self, body: Body, alpha: float = 1.0) -> State:
        """One body's position (length units), blended from the previous step by ``alpha``."""
        ...

    def is_sleeping(self, body: Body) -> bool:
        """Whether ``body`` sleeps (it stays exactly put until an awake body meets its group)."""
        ...


#: A sensor body's filter for the contacts: in no category, meeting none (engine.filters).
NO_CONTACT = Filter(categories=0, mask=0)


def _flag(value: Any, name: str, meaning: str) -> bool:
    """``value`` if it is True or False; else a TypeError that says what the flag ``name``
    is (True: ``meaning``)."""
    if not isinstance(value, bool):
        raise TypeError(
            f"{name} must be True ({meaning}) or False, got {type(value).__name__} {value!r}"
        )
    return value


#: The shapes a dynamic body holds about their centre of mass (engine.body_shapes).
CENTRED = (*PARTS, "Compound")


#: ``density`` read from each of a body's shapes (``_of_parts``).
_OWN: Any = object()


def _of_parts(shape: Any, shapes: Any, dim: int, density: Any) -> tuple[Any, Any]:
    """The body's shape made of ``shapes`` (engine.body_shapes): the one shape of a list of one,
    else a Compound of them; and its density: as given, or ``_OWN`` where a list gives each
    shape's (pymunk's shape.density). A TypeError where ``shape`` is given too, or the body is
    1D; a ValueError for a list of densities that is not one for each shape."""
    if shape is not None:
        raise TypeError(
            f"give a Body shape=... (one shape) or shapes=[...] (several on one body), not "
            f"both: got shape={shape!r} and shapes={shapes!r}"
        )
    if dim != 2:
        raise TypeError(f"only a 2D body takes shapes, got shapes={shapes!r} on a 1D body")
    each = None
    if isinstance(density, (list, tuple)):
        each = [coerce_density(d, f"density[{i}]") for i, d in enumerate(density)]
    made = Compound(shapes, each)
    if len(made) == 1:
        return made.parts[0], density if each is None else each[0]
    return made, density if each is None else _OWN


def _sensor_flag(value: Any) -> bool:
    """``Body.sensor``'s value, checked (``_flag``)."""
    return _flag(value, "sensor", "the body pushes nothing; its overlaps are reported")


def _bullet_flag(value: Any) -> bool:
    """``Body.bullet``'s value, checked (``_flag``)."""
    return _flag(
        value,
        "bullet",
        "on the soft step, swept to its time of impact against the dynamic bodies too",
    )


class Body:
    """A particle: position (m), velocity (m/s), acceleration (m/s^2) and mass (kg).

    Units are the scene's own: inches and seconds for Alfred, metres and seconds for the car.
    ``radius`` (length units, 0 for a point) gives it a size for contacts; ``restitution``
    (0: no bounce, 1: elastic; 0 unless given) and ``friction`` (Coulomb's mu, >= 0; 0.6 unless
    given: Box2D's defaults, so nothing bounces unless asked to) are its material, combined
    with a collider's by product (pymunk's rule); they and its ``filter`` can be set at any
    time, and the World's next step takes them. A disc or a body with corners turns
    (``angle``, ``angular_velocity``, ``moment``, ``torque``; engine.dynamics.rotation): friction
    makes a disc roll and a box tip; a point or a body made with ``fixed_rotation=True`` does not.
    Bodies with a radius collide with each other unless their ``filter`` (engine.Filter: a
    group, category bits) says not.
    A ``kinematic`` body is moved by the game, not by forces (see ``Body.kinematic``); a
    ``bullet`` is swept against the dynamic bodies too on the soft step (see ``Body.bullet``).

    Its mass is ``mass`` (kg; 1.0 when neither is given) or ``density`` (kg/m^2, a 2D density:
    mass = density * the shape's area, pymunk's ``shape.density`` and Box2D's ``density``), one
    of the two; either way the moment follows from the shape and mass (``Body.density``).

    ``velocity`` and ``acceleration`` default to zero (``Body(Vector(0, 5))`` is at rest at
    (0, 5); ``Body(0.0)`` at rest at 0 on a line). pymunk's names answer beside the lesson's:
    ``position`` is ``pos``, ``velocity`` is ``vel`` and ``acceleration`` is ``acc``; a pymunk
    name with no counterpart here (``force``, ``space``, ``body_type``, ...) raises an
    AttributeError that says what to use instead.

    ``colour`` (None by default; ``Body(..., colour="red")`` or ``body.colour = (255, 0, 0)``)
    is how ``draw_world`` fills it (engine.colours).

    ``data`` (None by default; ``Body(..., data=brick)``, or set it later) holds the game's own
    things: a Body takes no other new attribute. The engine never reads it, and it is not part
    of the physics' state: ``World.restore`` leaves each body's ``data`` as it is, and a body
    taken out of a World keeps it.
    """

    # Position and velocity are kept as plain floats (y parts unused in 1D): a lone body's
    # step is then float arithmetic with no Vector made at all, and a Vector is made only
    # when someone reads pos or vel.
    __slots__ = (
        "_px",
        "_py",
        "_vx",
        "_vy",
        "_acc",
        "_mass",
        "_density",
        "_radius",
        "_shape",
        "_cog",
        "_e",
        "_mu",
        "_filter",
        "_kinematic",
        "_dim",
        "_store",
        "_slot",
        "_angle",
        "_omega",
        "_moment",
        "_fixed",
        "_torque",
        "_colour",
        "_ctype",
        "_sensor",
        "_bullet",
        "data",
    )

    def __init__(
        self,
        position: Any,
        velocity: Any = None,
        acceleration: Any = None,
        mass: float = DEFAULT_MASS,
        *,
        radius: float = 0.0,
        restitution: float = RESTITUTION,
        friction: float = FRICTION,
        filter: Filter = DEFAULT_FILTER,  # noqa: A002 - pymunk's name for it
        kinematic: bool = False,
        shape: Any = None,
        density: float | None = None,
        angle: float = 0.0,
        angular_velocity: float = 0.0,
        moment: float | None = None,
        fixed_rotation: bool = False,
        torque: float = 0.0,
        data: Any = None,
        colour: Any = None,
        collision_type: int = 0,
        sensor: bool = False,
        bullet: bool = False,
        center_of_gravity: Any = None,
        shapes: Any = None,
    ) -> None:
        if velocity is None or acceleration is None:
            # Left out: zero, of the position's dimension (a float in 1D, a Vector in 2D).
            zero: Any = {1: 0.0, 2: Vector(0.0, 0.0)}.get(dim_of(position) or 0, 0.0)
            velocity = zero if velocity is None else velocity
            acceleration = zero if acceleration is None else acceleration
        given = {"position": position, "velocity": velocity, "acceleration": acceleration}
        dims = {name: dim_of(value) for name, value in given.items()}
        for name, d in dims.items():
            if d is None:
                value = given[name]
                raise TypeError(
                    f"Body {name} must be a real number (1D body) or a Vector / pair of "
                    f"numbers (2D body), got {type(value).__name__} {value!r}"
                )
        if len(set(dims.values())) != 1:
            kinds = ", ".join(f"{n} is {'1D' if d == 1 else '2D'}" for n, d in dims.items())
            raise TypeError(
                f"Body arguments mix dimensions ({kinds}): give three numbers for a 1D body "
                f"or three Vectors for a 2D body"
            )
        dim = dims["position"]
        assert dim is not None
        self._dim: int = dim
        try:
            self._store_pos(coerce_state(position, dim, "position"))
            self._store_vel(coerce_state(velocity, dim, "velocity"))
        except ValueError as exc:
            if dim != 1:
                raise
            # pymunk's Body(mass, math.inf) lands here: say what it is, and what to write.
            raise ValueError(f"{exc}: {mass_and_moment(position, velocity)}") from None
        self._acc: State = coerce_state(acceleration, dim, "acceleration")
        if density is not None and mass is not DEFAULT_MASS:
            raise ValueError(
                f"give a Body mass=... (kg) or density=... (kg/m^2: mass = density * the "
                f"shape's area), not both: got mass={mass!r} and density={density!r}; write "
                f"Body(..., mass={mass!r}) or Body(..., density={density!r})"
            )
        # With a density, the mass is density * area, known once the shape is taken (below).
        self._mass: float = coerce_mass(mass)
        self._radius, self._e, self._mu = material(radius, restitution, friction)
        self._shape: Any = None
        #: Where the centre of mass lies in the frame the shape was given in (length units):
        #: the shape is held moved by it, and the position is there (engine.body_shapes).
        self._cog = Vector(0.0, 0.0)
        if shapes is not None:
            shape, density = _of_parts(shape, shapes, dim, density)
        at = self._given_cog(center_of_gravity, dim, kinematic)
        if at is not None and (shape is None or type(shape).__name__ == "Circle"):
            if shape is None or tuple(at) != tuple(shape.center):
                raise ValueError(
                    f"a round body turns about its centre, which is its centre of gravity: got "
                    f"center_of_gravity={center_of_gravity!r} for "
                    f"{'a disc or point' if shape is None else repr(shape)} (leave it out)"
                )
        if shape is not None:
            if dim == 2 and kinematic is not True and type(shape).__name__ in CENTRED:
                shape, self._cog = centred(shape, at)
            self._radius = self._take_shape(shape, dim)
            self._shape = shape
        #: The density given (kg/m^2), or None: what ``density`` reads while the mass is still
        #: density * area (once a mass set or a snapshot restored makes it another, mass / area).
        self._density: float | None = None
        if density is _OWN:
            # Each shape's own density (engine.body_shapes): the mass sum rho_i A_i.
            self._mass = self._mass_of(1.0, made=True, mass=shape.mass_of(None))
        elif density is not None:
            per_area = coerce_density(density)
            self._mass, self._density = self._mass_of(per_area, made=True), per_area
        self._filter = as_filter(filter)
        if not isinstance(kinematic, bool):
            raise TypeError(
                f"kinematic must be True (moved by the game) or False, got "
                f"{type(kinematic).__name__} {kinematic!r}"
            )
        self._kinematic = kinematic
        self._store: BodyStore | None = None  # set by the World that holds this body
        self._slot: int = -1
        self._take_rotation(angle, angular_velocity, moment, fixed_rotation, torque)
        if self._cog.x != 0.0 or self._cog.y != 0.0:
            # The position given is the shape's frame's origin: the body's is its centre of
            # mass, that frame's cog turned by the angle (engine.body_shapes).
            c, s_ = math.cos(self._angle), math.sin(self._angle)
            cx, cy = self._cog
            p = cast(Vector, self.pos)
            self._store_pos(Vector(p.x + c * cx - s_ * cy, p.y + s_ * cx + c * cy))
        #: The game's own (a sprite, a score, a name; pymunk users set attributes on a Body):
        #: the engine never reads it; a World's snapshot does not keep it.
        self.data: Any = data
        self._colour = as_colour(colour)
        self._ctype = as_collision_type(collision_type)
        self._sensor = _sensor_flag(sensor)
        self._bullet = _bullet_flag(bullet)

    def _take_rotation(self, angle: Any, omega: Any, moment: Any, fixed: Any, torque: Any) -> None:
        """Check and keep the rotation arguments (engine.dynamics.rotation says what they mean)."""
        if not isinstance(fixed, bool):
            raise TypeError(
                f"fixed_rotation must be True (the body never turns) or False, got "
                f"{type(fixed).__name__} {fixed!r}"
            )
        self._fixed = fixed
        self._moment: float | None = None
        if moment is not None:
            m = real_number(moment, "moment")
            if not m > 0.0:
                raise ValueError(
                    f"moment must be a moment of inertia > 0 in kg m^2 (math.inf: the body "
                    f"never turns), or None to take it from the shape and mass, got {moment!r}"
                )
            self._moment = m
        self._angle = finite(angle, "angle")
        self._omega = finite(omega, "angular_velocity")
        self._torque = finite(torque, "torque")
        if self._shape is not None and self._moment is None:
            # A shape so large or small that its moment leaves the float range would turn
            # with a nan or zero moment: refused, by the name of the argument given.
            try:
                inertia = self._own_moment()
            except ValueError as exc:
                inertia, why = math.nan, f" ({exc})"
            else:
                why = ""
            if not inertia > 0.0:
                raise ValueError(
                    f"shape must have a moment of inertia > 0 and finite for mass "
                    f"{self._mass!r}, got {inertia!r} kg m^2 for {self._given_shape()!r}{why}; "
                    f"give the shape in other length units, or moment=... or fixed_rotation=True"
                )
        if (self._angle or self._omega) and not self._steered() or self._torque and not self.turns:
            raise ValueError(self._why_not("angle", self._angle, self._omega, self._torque))

    def _steered(self) -> bool:
        """Whether the body can be given an angle and an angular velocity: one that turns, or a
        kinematic body in 2D (the game turns it, as it moves it)."""
        return self.turns or (self._kinematic and self._dim == 2)

    def _why_not(self, name: str, *values: float, given: float | None = None) -> str:
        """Why this body cannot take a rotation (``name``: the argument given; ``values``: the
        angle, angular velocity and torque given, or ``given``: the value of ``name``)."""
        said = (
            ", ".join(
                f"{n}={v!r}"
                for n, v in zip(("angle", "angular_velocity", "torque"), values, strict=False)
                if v
            )
            or f"{name}={'...' if given is None else repr(given)}"
        )
        if self._dim != 2:
            why = "a 1D body does not turn"
        elif self._kinematic:
            why = (
                "a kinematic body is turned by the game, not by a torque: set its "
                "angular_velocity (rad/s) or its angle"
            )
        elif self._fixed:
            why = "the body was made with fixed_rotation=True"
        elif not self._round() and not CORNERS_TURN:
            why = (
                "a body with corners (a Polygon or Segment shape) does not turn in this "
                "version: it stays upright, like a platformer's crate"
            )
        elif self._moment is None and self._radius == 0.0:
            why = (
                "a point has no moment of inertia: give it a radius=... (a disc) or a "
                "moment=... (kg m^2)"
            )
        else:
            why = f"its moment is {self.moment!r}: set body.moment = ... (kg m^2) to turn it"
        return f"this body cannot turn ({said}): {why}"

    def _round(self) -> bool:
        shape = self._shape
        return shape is None or type(shape).__name__ == "Circle"

    def _own_moment(self) -> float:
        """The moment of inertia (kg m^2) the body turns with; inf for one that does not."""
        return self._moment_with(self._moment)

    def _moment_with(self, given: float | None) -> float:
        """The moment of inertia (kg m^2) the body would turn with were its ``moment`` the
        ``given`` one (None: from its shape and mass); inf for one that would not turn."""
        # What the body is made as (1D, kinematic, fixed_rotation, corners in a version where
        # they do not turn) decides first; a moment given, finite or inf, then wins over the
        # shape's.
        if self._dim != 2 or self._kinematic or self._fixed:
            return math.inf
        if not CORNERS_TURN and not self._round():
            return math.inf
        if given is not None:
            return given
        if self._radius == 0.0:
            return math.inf  # a point: nothing can make it turn
        mass = self.mass
        shape = self._shape
        if shape is None:
            return 0.5 * mass * self._radius * self._radius  # a solid disc: m r^2 / 2
        if not self._round():
            # A body with corners (a Polygon, a Segment's capsule): the shape's own moment
            # about the body's position (engine.geometry.mass, exact; the parallel axes' term in
            # it).
            return float(shape.moment(mass))
        # A Circle about its centre c in the body's frame: m r^2 / 2 + m |c|^2.
        cx, cy = shape.center
        return mass * (0.5 * shape.radius * shape.radius + cx * cx + cy * cy)

    def _area(self) -> float:
        """The area (length units squared) of the body's shape: its shape's, pi r^2 for a disc
        made with ``radius``; 0.0 for a point, a 1D body or a Segment without a radius."""
        if self._dim != 2:
            return 0.0
        shape = self._shape
        if shape is not None:
            return float(shape.area)
        r = self._radius
        return math.pi * (
            r * r
        )  # Circle((0, 0), r).area's bits (engine.geometry.mass.area_for_circle)

    def _mass_of(self, density: float, made: bool, mass: float | None = None) -> float:
        """The mass (kg) ``density`` (kg/m^2, checked) gives this body: density times its
        shape's area (``mass``: the sum of its shapes' own, where each has one); a ValueError
        that says why not and what to write instead (``made``: as the body is made, whose shape
        is then fixed)."""
        area = self._area()
        mass = density * area if mass is None else mass
        if area > 0.0 and math.isfinite(mass) and mass > 0.0:
            return mass
        given = f"density={density!r} kg/m^2 gives the body a mass of density * its shape's area"
        fix = "give mass=... (kg) instead" if made else "set body.mass = ... (kg) instead"
        if area > 0.0:
            raise ValueError(
                f"{given}, and {density!r} * {area!r} is {mass!r} kg, outside the float range "
                f"(> 0 and finite): give a density nearer 1.0, the shape in other length units, "
                f"or {fix}"
            )
        shape = self._given_shape()
        if self._dim != 2:
            why = "a 1D body (made of numbers) has no shape and no area"
        elif shape is None:
            why = "this body is a point (no shape, no radius), with no area"
            if made:
                fix = (
                    f"give it radius=... (a disc) or shape=... (a Polygon, a Circle, a Segment "
                    f"with a radius), or {fix}"
                )
        elif type(shape).__name__ == "Segment" and shape.radius == 0.0:
            why = f"its shape {shape!r} is a line, with no area"
            if made:
                fix = f"give the Segment a radius (Segment(a, b, radius=0.05): a capsule), or {fix}"
        else:
            why = f"its shape {shape!r} has an area of {area!r} in floats"
            if made:
                fix = f"give the shape in other length units, or {fix}"
        if not made:
            fix = f"a Body's shape is fixed when it is made: {fix}"
        raise ValueError(f"{given}, and {why}: {fix}")

    @staticmethod
    def _given_cog(value: Any, dim: int, kinematic: Any) -> Vector | None:
        """The ``center_of_gravity`` given (length units, in the shape's frame), checked; None
        where it is left to the shape (its centroid)."""
        if value is None:
            return None
        if dim != 2:
            raise TypeError(
                f"only a 2D body takes a center_of_gravity, got center_of_gravity={value!r} "
                f"on a 1D body"
            )
        cx, cy = pair(value, "center_of_gravity")
        if kinematic is True and (cx != 0.0 or cy != 0.0):
            raise ValueError(
                f"a kinematic body turns about its position, where the game puts it, so it "
                f"takes no center_of_gravity off it: got center_of_gravity={value!r} (leave it "
                f"out, or make the body dynamic)"
            )
        return Vector(cx, cy)

    def _given_shape(self) -> Any:
        """The shape as it was given (an error names it so): the one held, moved back by the
        centre of gravity it was moved by."""
        shape, (cx, cy) = self._shape, self._cog
        return shape if shape is None or (cx == 0.0 and cy == 0.0) else shape.moved(cx, cy)

    def _take_shape(self, shape: Any, dim: int) -> float:
        """Check ``shape`` for this body; its bounding radius (length units)."""
        if self._radius != 0.0:
            raise TypeError(
                f"give a Body radius=... or shape=..., not both (radius={self._radius!r} is "
                f"short for shape=Circle((0, 0), {self._radius!r})), got shape={shape!r}"
            )
        if dim != 2:
            raise TypeError(f"only a 2D body takes a shape, got shape={shape!r} on a 1D body")
        take = getattr(shape, "as_body_shape", None)
        if take is None:
            raise TypeError(
                f"shape must be a Circle((0, 0), r), a Polygon (Polygon.box(width, height) for "
                f"a box) or a Segment (a capsule) from engine.geometry.colliders, got "
                f"{type(shape).__name__} {shape!r}"
            )
        return float(take())

    def _store_pos(self, state: State) -> None:
        if self._dim == 1:
            self._px, self._py = cast(float, state), 0.0
        else:
            self._px, self._py = cast(Vector, state)

    def _store_vel(self, state: State) -> None:
        if self._dim == 1:
            self._vx, self._vy = cast(float, state), 0.0
        else:
            self._vx, self._vy = cast(Vector, state)

    # -- what the lesson's Body holds ------------------------------------------------------
    @property
    def dim(self) -> int:
        """1 for a body on a line (floats), 2 for a body on a plane (Vectors)."""
        return self._dim

    @property
    def world(self) -> WorldLike | None:
        """The World this body is in, or None."""
        return None if self._store is None else self._store.owner

    # -- the World's handle (engine.pipeline.membership sets it; the World's modules read ``slot``)
    @property
    def slot(self) -> int:
        """The body's slot in its World's arrays (``engine.dynamics.store``: ``store.row(slot)`` is
        its row now), kept while it is in the World; -1 out of a World. A count, no unit."""
        return self._slot

    def attach(self, store: BodyStore, slot: int) -> None:
        """Become a handle onto ``slot`` of ``store`` (a World's arrays, which now hold its
        position, velocity, mass and own acceleration): the World's side of adding it."""
        self._store, self._slot = store, slot

    def detach(
        self,
        pos: State,
        vel: State,
        mass: float,
        own_acc: State,
        spin: tuple[float, float, float] = (0.0, 0.0, 0.0),
    ) -> None:
        """Stop being a World's handle and hold its own state again: ``pos`` (length units),
        ``vel`` (length units / s), ``mass`` (kg), ``own_acc`` (length units / s^2) and
        ``spin`` (angle in rad, angular velocity in rad/s, torque in N m), as they were in
        the World (taken unchecked): the World's side of removing it."""
        self._store, self._slot = None, -1
        self._store_pos(pos)
        self._store_vel(vel)
        self._mass, self._acc = mass, own_acc
        self._angle, self._omega, self._torque = spin

    @property
    def pos(self) -> Any:
        """Position (length units): a float in 1D, a Vector in 2D."""
        store = self._store
        if store is not None:
            return store.value(store.x[store.row(self._slot)])
        return self._px if self._dim == 1 else new_unchecked(Vector, (self._px, self._py))

    @pos.setter
    def pos(self, value: Any) -> None:
        try:
            state = coerce_state(value, self._dim, "pos")
        except TypeError as exc:
            raise self._on_a_line(exc, value) from None
        if self._store is not None:
            self._store.set_position(self._slot, state)
        else:
            self._store_pos(state)

    @property
    def vel(self) -> Any:
        """Velocity (length units per second): a float in 1D, a Vector in 2D."""
        store = self._store
        if store is not None:
            return store.value(store.v[store.row(self._slot)])
        return self._vx if self._dim == 1 else new_unchecked(Vector, (self._vx, self._vy))

    @vel.setter
    def vel(self, value: Any) -> None:
        try:
            state = coerce_state(value, self._dim, "vel")
        except TypeError as exc:
            raise self._on_a_line(exc, value) from None
        if self._store is not None:
            self._store.set_velocity(self._slot, state)
        else:
            self._store_vel(state)

    def _on_a_line(self, exc: TypeError, value: Any) -> TypeError:
        """``exc``, for a 2D ``value`` written to a 1D body, with what pymunk's Body(mass,
        moment), which made such a body, is written as here."""
        if self._dim == 1 and dim_of(value) == 2:
            return TypeError(f"{exc}: this body is 1D, made of numbers; {mass_and_moment()}")
        return exc

    @property
    def acc(self) -> Any:
        """Acceleration now (length units per s^2): own_acc plus, in a World, forces / mass."""
        if self._store is not None:
            return self._store.acceleration(self._slot)
        return self._acc

    @acc.setter
    def acc(self, value: Any) -> None:
        if self._store is not None:
            raise AttributeError(
                "in a World, body.acc is the total acceleration (own_acc + forces / mass) and "
                "cannot be set; set body.own_acc for the body's own constant acceleration, "
                "or add a force"
            )
        self._acc = coerce_state(value, self._dim, "acc")

    @property
    def own_acc(self) -> Any:
        """The body's own constant acceleration (length units per s^2), before any force."""
        store = self._store
        if store is not None:
            return store.value(store.own[store.row(self._slot)])
        return self._acc

    @own_acc.setter
    def own_acc(self, value: Any) -> None:
        state = coerce_state(value, self._dim, "own_acc")
        if self._store is not None:
            self._store.set_own_acc(self._slot, state)  # one array entry, nothing recompiled
        else:
            self._acc = state

    # -- pymunk's names for the same three (and the constructor's) --------------------------
    @property
    def position(self) -> Any:
        """The same as ``pos`` (pymunk's name): length units, a float in 1D, a Vector in 2D."""
        return self.pos

    @position.setter
    def position(self, value: Any) -> None:
        self.pos = value

    @property
    def velocity(self) -> Any:
        """The same as ``vel`` (pymunk's name): length units per second."""
        return self.vel

    @velocity.setter
    def velocity(self, value: Any) -> None:
        self.vel = value

    @property
    def acceleration(self) -> Any:
        """The same as ``acc`` (the constructor's name): length units per s^2."""
        return self.acc

    @acceleration.setter
    def acceleration(self, value: Any) -> None:
        self.acc = value

    @property
    def mass(self) -> float:
        """Mass (kg, or the scene's mass unit); always positive and finite."""
        store = self._store
        if store is not None:
            return float(store.mass[store.row(self._slot)])
        return self._mass

    @mass.setter
    def mass(self, value: Any) -> None:
        m = coerce_mass(value)
        if self._store is not None:
            self._store.set_mass(self._slot, m)
        else:
            self._mass = m
        if self._store is not None and self._moment is None and self.turns:
            self._store.set_moment(self._slot, self._own_moment())  # m r^2 / 2 follows m
        self._density = None  # ``density`` now reads mass / area

    @property
    def density(self) -> float | None:
        """Mass per unit of the shape's area (kg/m^2): the density given while the mass is
        still density * area, else mass / area; None for a body with no area (a point, a 1D
        body, a Segment without a radius). Set it (> 0) as ``mass`` is set: the mass becomes
        density * area, and the moment follows it unless one was given."""
        area = self._area()
        if not area > 0.0:
            return None
        mass, given = self.mass, self._density
        if given is not None and given * area == mass:
            return given
        return mass / area

    @density.setter
    def density(self, value: Any) -> None:
        d = coerce_density(value)
        self.mass = self._mass_of(d, made=False)  # the moment follows, as for a mass set
        self._density = d

    @property
    def radius(self) -> float:
        """Radius (length units) for contacts; 0.0 for a point. For a body with a shape other
        than a circle: the radius of the circle about its position that holds the shape."""
        return self._radius

    @radius.setter
    def radius(self, value: Any) -> None:
        refuse_change("radius", value)

    @property
    def shape(self) -> Any:
        """The shape given as ``Body(..., shape=...)`` (engine.geometry.colliders: a Circle, Polygon
        or Segment, in the body's frame, about its position: a dynamic body's centre of mass,
        ``center_of_gravity``), a ``Compound`` of the parts of ``shapes=[...]``
        (engine.body_shapes; ``body.shapes`` lists them), or None for a round body made with
        ``radius`` (a disc of that radius) or a point."""
        return self._shape

    @shape.setter
    def shape(self, value: Any) -> None:
        refuse_change("shape", value)

    @property
    def shapes(self) -> tuple[Any, ...]:
        """The body's shapes (pymunk's ``body.shapes``), as it holds them, about its position:
        the parts of a body made with ``shapes=[...]``, the one shape of ``shape=...``, none for
        a disc made with ``radius`` or a point."""
        shape = self._shape
        if shape is None:
            return ()
        return tuple(shape.parts) if isinstance(shape, Compound) else (shape,)

    @property
    def center_of_gravity(self) -> Vector:
        """Where the body's centre of mass lies in the frame its shape was given in (length
        units; pymunk's name): (0, 0) for a shape centred on the origin, a disc, a point and a
        kinematic body (which turns about its position). A dynamic body's position is its centre
        of mass: ``Body(p, shape=Polygon([(0, 0), (2, 0), (2, 1), (0, 1)]))`` holds the box
        about (1, 0.5) and is at p + (1, 0.5), so the frame's origin (a sprite's) is
        ``body.origin`` (engine.body_shapes)."""
        return self._cog

    @center_of_gravity.setter
    def center_of_gravity(self, value: Any) -> None:
        raise AttributeError(
            f"a Body's center_of_gravity follows from its shapes (their centre of mass), or is "
            f"given when it is made, so body.center_of_gravity = {value!r} cannot change it: "
            f"make a new Body(..., center_of_gravity={value!r}) instead (world.remove(body), "
            f"then world.add(new))"
        )

    @property
    def origin(self) -> Vector:
        """Where the origin of the frame the body's shapes were drawn in is now (length units,
        2D): ``local_to_world(-center_of_gravity)``, the position itself for a shape centred
        on it. pymunk's ``body.position`` is this point (its centre of gravity is apart from
        it), where here ``pos`` is the centre of mass. Set it to move the body so that the
        frame's origin is there, at the body's angle (a sprite drawn about the origin)."""
        if self._dim != 2:
            raise TypeError("only a 2D body has a frame of shapes: read body.pos for a 1D body")
        return self.local_to_world(-self._cog)

    @origin.setter
    def origin(self, value: Any) -> None:
        if self._dim != 2:
            raise TypeError(f"only a 2D body has a frame of shapes: set body.pos = {value!r}")
        x, y = pair(value, "origin")
        c, s = math.cos(self.angle), math.sin(self.angle)
        cx, cy = self._cog
        self.pos = Vector(x + c * cx - s * cy, y + s * cx + c * cy)

    @property
    def restitution(self) -> float:
        """Restitution e in [0, 1]: the fraction of the normal speed kept by a bounce. Set it
        any time (``body.restitution = 0.9``): the next step bounces with it."""
        return self._e

    @restitution.setter
    def restitution(self, value: Any) -> None:
        e = material(self._radius, value, self._mu)[1]  # refused: the old value stays
        self._e = e
        if self._store is not None:
            self._store.set_material(self._slot, e, self._mu, None)

    @property
    def friction(self) -> float:
        """Coulomb friction coefficient mu >= 0. Set it any time (``body.friction = 0.2``):
        the next step slides or holds with it."""
        return self._mu

    @friction.setter
    def friction(self, value: Any) -> None:
        mu = material(self._radius, self._e, value)[2]  # refused: the old value stays
        self._mu = mu
        if self._store is not None:
            self._store.set_material(self._slot, self._e, mu, None)

    @property
    def filter(self) -> Filter:
        """Which other bodies and colliders this one collides with (engine.Filter; bodies of
        radius 0 never). Set it any time: from the next step, pairs it turns off pass through
        each other."""
        return self._filter

    @filter.setter
    def filter(self, value: Any) -> None:
        self._filter = as_filter(value)
        if self._store is not None:
            self._store.set_material(self._slot, self._e, self._mu, self.solid_filter)

    @property
    def sensor(self) -> bool:
        """A sensor body pushes nothing and nothing pushes it (pymunk's ``shape.sensor``): the
        World reports the bodies and colliders it overlaps, by its shape, at the end of each
        step (``World.began``, ``World.on_contact``; its filter says which it senses). A
        player's feet sensor is a kinematic sensor body the game moves with the player. Set
        it any time: the next step takes it."""
        return self._sensor

    @sensor.setter
    def sensor(self, value: Any) -> None:
        self._sensor = _sensor_flag(value)
        if self._store is not None:
            self._store.set_material(self._slot, self._e, self._mu, self.solid_filter)

    @property
    def bullet(self) -> bool:
        """Box2D's ``isBullet`` (``b2Body_SetBullet``), False by default: on the soft step
        (``World(solver="soft")``) a fast body is swept to its time of impact against the
        colliders and the static and kinematic bodies, and a bullet against the dynamic ones
        too (a pinball's ball past a flipper, a thin box turning fast at a free plate). Set it
        any time: the next step takes it. The exact solver (``World()``) finds every impact
        at its moment already: there it is kept and changes nothing."""
        return self._bullet

    @bullet.setter
    def bullet(self, value: Any) -> None:
        self._bullet = _bullet_flag(value)
        if self._store is not None:
            self._store.set_bullet(self._slot, self._bullet)

    @property
    def solid_filter(self) -> Filter:
        """The filter the contacts use: ``filter``, or for a sensor one that meets nothing
        (categories and mask 0), so that it passes through everything."""
        return NO_CONTACT if self._sensor else self._filter

    @property
    def collision_type(self) -> int:
        """Which handlers of ``World.on_collision`` take this body's contacts (pymunk's
        ``shape.collision_type``: an int >= 0, 0 by default); set it any time."""
        return self._ctype

    @collision_type.setter
    def collision_type(self, value: Any) -> None:
        self._ctype = as_collision_type(value)

    @property
    def colour(self) -> Colour:
        """How ``draw_world`` fills the body (engine.colours: an (r, g, b) tuple, a pygame
        colour name such as ``"red"`` or a hex string; None, the default: blue, grey asleep,
        vermillion when the game moves it). Set it any time; the physics never reads it, and
        a snapshot does not keep it."""
        return self._colour

    @colour.setter
    def colour(self, value: Any) -> None:
        self._colour = as_colour(value)

    @property
    def kinematic(self) -> bool:
        """True for a body the game moves (a paddle, a platform): no force acts on it, and
        contacts take its mass as infinite. In a World, writing its ``vel`` sets how it moves;
        writing its ``pos`` moves it there over the next step, at the velocity that takes
        (what the contacts in that step see), after which its ``vel`` is again the one last
        written (zero by default): a paddle the game places each frame stops when it does.
        It turns the same way (2D): ``angular_velocity`` sets how (rad/s: a windmill, a
        tumbler), and writing ``angle`` turns it there over the next step."""
        return self._kinematic

    @kinematic.setter
    def kinematic(self, value: Any) -> None:
        refuse_change("kinematic", value)

    # -- rotation (engine.dynamics.rotation) -------------------------------------------------------
    @property
    def turns(self) -> bool:
        """Whether this body turns: a disc, a body with corners (a Polygon, a Segment) or one
        given a ``moment``, not kinematic, not ``fixed_rotation``. A point does not."""
        return math.isfinite(self._own_moment())

    @property
    def fixed_rotation(self) -> bool:
        """True for a body made never to turn (pymunk: a moment of inf)."""
        return self._fixed

    @fixed_rotation.setter
    def fixed_rotation(self, value: Any) -> None:
        refuse_change("fixed_rotation", value)

    @property
    def moment(self) -> float:
        """Moment of inertia about the body's position (kg m^2): the one given, else from the
        shape and mass (m r^2 / 2 for a disc); inf for a body that does not turn. Set it any
        time (> 0): math.inf stops the body turning, and a finite one makes it turn (again),
        from the angular velocity it has; a 1D, kinematic or fixed_rotation body refuses a
        finite one."""
        store = self._store
        if store is not None:
            return float(store.moment[store.row(self._slot)])
        return self._own_moment()

    @moment.setter
    def moment(self, value: Any) -> None:
        m = real_number(value, "moment")
        if not m > 0.0:
            raise ValueError(f"moment must be > 0 in kg m^2 (math.inf: never turns), got {value!r}")
        # Whether the body can turn with the new moment, not with the one it has: a body
        # whose moment was inf (pymunk's Body(mass, math.inf)) turns again when given a
        # finite one, from the angular velocity it has (0 unless set).
        if math.isfinite(m) and not math.isfinite(self._moment_with(m)):
            raise ValueError(self._why_not("moment", given=m))
        self._moment = m
        if self._store is not None:
            self._store.set_moment(self._slot, self._own_moment())

    @property
    def angle(self) -> float:
        """The angle the body has turned through (rad, counter-clockwise; not wrapped). For a
        kinematic body in a World, writing it turns the body there over the next step."""
        store = self._store
        if store is not None:
            return float(store.angle[store.row(self._slot)])
        return self._angle

    @angle.setter
    def angle(self, value: Any) -> None:
        a = finite(value, "angle")
        if a and not self._steered():
            raise ValueError(self._why_not("angle", a))
        if self._store is not None:
            self._store.set_spin(self._slot, a, None)
        else:
            self._angle = a

    @property
    def angular_velocity(self) -> float:
        """Angular velocity (rad/s, counter-clockwise)."""
        store = self._store
        if store is not None:
            return float(store.omega[store.row(self._slot)])
        return self._omega

    @angular_velocity.setter
    def angular_velocity(self, value: Any) -> None:
        w = finite(value, "angular_velocity")
        if w and not self._steered():
            raise ValueError(self._why_not("angular_velocity", 0.0, w))
        if self._store is not None:
            self._store.set_spin(self._slot, None, w)
        else:
            self._omega = w

    @property
    def torque(self) -> float:
        """The body's own constant torque (N m, counter-clockwise), kept until changed (as
        ``own_acc`` is): its angular acceleration is torque / moment."""
        store = self._store
        if store is not None:
            return float(store.torque[store.row(self._slot)])
        return self._torque

    @torque.setter
    def torque(self, value: Any) -> None:
        tau = finite(value, "torque")
        if tau and not self.turns:
            raise ValueError(self._why_not("torque", 0.0, 0.0, tau))
        if self._store is not None:
            self._store.set_torque(self._slot, tau)
        else:
            self._torque = tau

    def apply_impulse(self, impulse: Any, at: Any = None) -> None:
        """Give the body an impulse (N s, a Vector) at the world point ``at`` (its position
        by default): v += J / m, and a body that turns gains (at - pos) x J / I in angular
        velocity (pymunk's ``apply_impulse_at_world_point``)."""
        if self._dim != 2:
            raise TypeError("apply_impulse takes a 2D body; for a 1D body set body.vel")
        if self._kinematic:
            raise ValueError(
                "a kinematic body is moved by the game and takes no impulse: set its vel"
            )
        jx, jy = pair(impulse, "impulse")
        pos = self.pos
        px, py = (pos.x, pos.y) if at is None else pair(at, "at")
        m = self.mass
        vel = self.vel
        self.vel = Vector(vel.x + jx / m, vel.y + jy / m)
        if self.turns:
            rx, ry = px - pos.x, py - pos.y
            self.angular_velocity = self.angular_velocity + (rx * jy - ry * jx) / self.moment

    def apply_force(self, force: Any, at: Any = None) -> None:
        """Push the body with ``force`` (N, a Vector) at the world point ``at`` (its position
        by default) over the World's next step only, as pymunk's ``apply_force_at_world_point``
        does (call it every frame for a force that lasts; ``own_acc`` and ``torque`` keep
        theirs). A body that turns takes the torque (at - pos) x F too."""
        if self._dim != 2:
            raise TypeError("apply_force takes a 2D body; for a 1D body set body.own_acc")
        fx, fy = pair(force, "force")
        store = self._store
        if store is None:
            raise ValueError(
                "apply_force acts over a World's next step: add the body to a World first "
                "(or set body.own_acc for its own constant acceleration)"
            )
        if self._kinematic:
            raise ValueError("a kinematic body is moved by the game and takes no force")
        pos = self.pos
        px, py = (pos.x, pos.y) if at is None else pair(at, "at")
        torque = (px - pos.x) * fy - (py - pos.y) * fx if self.turns else 0.0
        m = self.mass
        store.push(self._slot, (fx / m, fy / m), torque)

    def local_to_world(self, point: Any) -> Vector:
        """A point given in the body's own frame (length units), in world coordinates:
        pos + R(angle) point."""
        x, y = pair(point, "point")
        c, s = math.cos(self.angle), math.sin(self.angle)
        pos = self.pos
        return Vector(pos.x + c * x - s * y, pos.y + s * x + c * y)

    def world_to_local(self, point: Any) -> Vector:
        """A world point (length units) in the body's own frame: R(-angle) (point - pos)."""
        x, y = pair(point, "point")
        c, s = math.cos(self.angle), math.sin(self.angle)
        pos = self.pos
        dx, dy = x - pos.x, y - pos.y
        return Vector(c * dx + s * dy, -s * dx + c * dy)

    def velocity_at_world_point(self, point: Any) -> Vector:
        """The velocity (length units / s) of the body's point at the world point ``point``:
        v + omega x (point - pos), pymunk's name; v for a body that does not turn."""
        x, y = self._plane_point(point, "velocity_at_world_point")
        pos = self.pos
        return self._velocity_at(x - pos.x, y - pos.y)

    def velocity_at_local_point(self, point: Any) -> Vector:
        """The velocity (length units / s, world frame) of the point ``point`` given in the
        body's own frame: v + omega x R(angle) point, pymunk's name."""
        x, y = self._plane_point(point, "velocity_at_local_point")
        c, s = math.cos(self.angle), math.sin(self.angle)
        return self._velocity_at(c * x - s * y, s * x + c * y)

    def _plane_point(self, point: Any, name: str) -> tuple[float, float]:
        """``point`` as two floats, for ``name``, which takes a 2D body."""
        if self._dim != 2:
            raise TypeError(
                f"{name} takes a 2D body, got point={point!r} for a 1D body: every point of a "
                f"body on a line moves at body.vel"
            )
        return pair(point, "point")

    def _velocity_at(self, rx: float, ry: float) -> Vector:
        """v + omega x r (length units / s) for the offset r = (rx, ry) from the position."""
        vel, w = self.vel, self.angular_velocity
        # omega x r in the plane: (-omega r_y, omega r_x).
        return Vector(vel.x - w * ry, vel.y + w * rx)

    # -- sleep (engine.exact.sleep: a World's bodies at rest cost nothing) -------------------------
    @property
    def is_sleeping(self) -> bool:
        """Whether the body sleeps in its World (pymunk's name; ``world.is_sleeping(body)``);
        False out of a World."""
        world = self.world
        return False if world is None else world.is_sleeping(self)

    def sleep(self) -> None:
        """Put the body to sleep now, with the awake bodies touching it, one through another
        (its group; pymunk's name): they stay exactly put, at rest, until an awake body meets
        one of them, a state of one is written, or ``activate()`` wakes them."""
        store = self._store
        if store is None:
            raise ValueError(
                "body.sleep() puts a body to sleep in its World, and this body is in none: add "
                f"it first (world.add(body)), then call body.sleep(): {self!r}"
            )
        store.set_asleep(self._slot, True)

    def activate(self) -> None:
        """Wake the body and its sleeping group now (pymunk's name); a body awake, or in no
        World (where nothing sleeps), is left as it is."""
        store = self._store
        if store is not None:
            store.set_asleep(self._slot, False)

    # -- moving a lone body ------------------------------------------------------------------
    def step(self, dt: float, acceleration: Any = None) -> None:
        """Move this body on its own by ``dt`` seconds with semi-implicit Euler.

        The lesson's figure 10, for one body: velocity first, then position with the new
        velocity (v += a dt; x += v dt), where a is ``acceleration`` if given (a prebuilt
        Vector or float, e.g. gravity) or else the body's own acceleration. Bit for bit
        what ``integrators.semi_implicit_euler`` does; in a World, use ``world.step``.

        >>> alfred = Body(0.0, 0.0, 1.0)          # from rest at 1 in/s^2
        >>> for _ in range(4):
        ...     alfred.step(1.0)
        >>> alfred.pos                             # 1, 3, 6, 10: the lesson's "4 s"
        10.0
        """
        if self._store is not None:
            raise RuntimeError("this body is in a World: advance it with world.step(dt)")
        if type(dt) is not float or not 0.0 < dt < math.inf:
            if isinstance(dt, bool) or not isinstance(dt, Real):
                raise TypeError(f"dt must be a number of seconds, got {type(dt).__name__}")
            try:
                seconds = float(dt)
            except OverflowError:  # an int beyond the float range
                seconds = math.inf
            if not 0.0 < seconds < math.inf:
                raise ValueError(f"dt must be a finite number of seconds > 0, got {dt!r}")
            dt = seconds
        a = self._acc if acceleration is None else acceleration
        if type(a) is not (float if self._dim == 1 else Vector):
            a = coerce_state(a, self._dim, "acceleration")
        if self._dim == 1:
            vx = self._vx + cast(float, a) * dt
            px = self._px + vx * dt
            vy = py = 0.0
        else:
            ax, ay = cast(Vector, a)
            vx = self._vx + ax * dt
            vy = self._vy + ay * dt
            px = self._px + vx * dt
            py = self._py + vy * dt
        # One sum is nan or inf whenever any term is (or when huge terms overflow).
        if not _isfinite(px + py + vx + vy) and not all(map(_isfinite, (px, py, vx, vy))):
            raise ValueError(
                f"the step of dt={dt!r} s would make this body's state non-finite "
                f"(nan or inf); the state is kept: use a smaller dt or acceleration"
            )
        self._vx, self._vy, self._px, self._py = vx, vy, px, py

    # -- copies -----------------------------------------------------------------------------
    def __copy__(self) -> Body:
        """``copy.copy(body)``: a new Body in no World, with this one's state now.

        As pymunk's body copy, it leaves the World, links and forces behind: a body in a World
        is copied out of it (not a second handle onto its row, which stepping or removing one
        would leave pointing elsewhere); add the copy to a World to step it. It has the
        position (length units), velocity (length units / s), own acceleration (length units
        / s^2), mass (kg), moment (kg m^2), angle (rad), angular velocity (rad/s) and torque
        (N m) the body has now, its shape, material, filter, colour, collision type, sensor
        and bullet flags and ``data`` (the same object, not a copy). A force given by
        ``apply_force`` is for the World's next step only, so the copy does not keep it.
        ``copy.deepcopy(body)`` and pickle copy the World the body is in with it (the copy is
        that World copy's body); ``world.copy()`` copies a whole World.
        """
        cls = type(self)
        new = cls.__new__(cls)
        for name in Body.__slots__:
            object.__setattr__(new, name, getattr(self, name))
        if hasattr(self, "__dict__"):  # a subclass's own attributes
            new.__dict__.update(self.__dict__)
        store = self._store
        if store is not None:
            own, torque = self.own_acc, self.torque
            pushed = store.pushes.get(self._slot)
            if pushed is not None:  # (2D only) the own acceleration and torque without the push
                own, torque = Vector(*pushed[0]), pushed[1]
            spin = (self.angle, self.angular_velocity, torque)
            new.detach(self.pos, self.vel, self.mass, own, spin)
        return new

    # -- text -------------------------------------------------------------------------------
    def __str__(self) -> str:
        """The lesson's text: three lines, Position, Velocity and Acceleration."""
        return f"Position: {self.pos}\nVelocity: {self.vel}\nAcceleration: {self.acc}\n"

    def __repr__(self) -> str:
        size = "" if self._radius == 0.0 else f", radius={self._radius!r}"
        if isinstance(self._shape, Compound):
            size = f", shapes={list(self._shape.parts)!r}"
        elif self._shape is not None:
            size = f", shape={self._shape!r}"
        kin = ", kinematic=True" if self._kinematic else ""
        return (
            f"Body(position={self.pos!r}, velocity={self.vel!r}, "
            f"acceleration={self.own_acc!r}, mass={self.mass!r}{size}{kin})"
        )


# pymunk's Body names the Body lacks, each with what to write instead (engine.body_habits).
install_habits(Body)
