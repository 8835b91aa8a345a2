"""Static colliders: the world's walls, floors, pegs and rooms, which bodies with a size meet.

Five shapes, each with a material (``restitution``, ``friction``), a ``sensor`` flag and a
``colour`` for drawing (engine.colours; None: ``draw_world``'s ink):

* ``Plane(point, normal)``: an infinite floor or wall; the solid side is behind ``normal``.
* ``Segment(a, b, radius=0.0)``: a thin wall from a to b, or a capsule when ``radius`` > 0
  (its ends are round). A body meets it from either side.
* ``Circle(center, radius)``: a peg or a bumper.
* ``Box(lower_left, upper_right)``: the walls of a room that holds bodies *inside*: its
  solid is everything outside the rectangle.
* ``Polygon(vertices, radius=0.0)``: a convex polygon, solid inside, rounded by ``radius``
  when it is > 0; ``Polygon.box(width, height)`` makes a box-shaped one (a crate, a step).

Add one with ``world.add_collider(c)``. A body of radius r touches a collider when its centre
is at distance r from the collider's surface.

Materials combine by product, as in pymunk: a bounce off a wall uses e = e_body * e_wall and
mu = mu_body * mu_wall. A collider's defaults (restitution 1.0, friction 1.0) therefore leave
the body's own material in force (a body's defaults: restitution 0, friction 0.6, Box2D's).

A sensor is not solid: bodies pass through it, and the World reports when they begin and end
overlapping it (``World.began`` / ``World.ended``). The crumb in the crumb game is one.

Its material can change at any time, in or out of a World (pymunk's habit): writing
``peg.restitution``, ``peg.friction``, ``peg.filter`` or ``peg.sensor`` takes effect at the
World's next step (each World holding it is told: ``WorldState.collider_changed``); a value
refused leaves the old one. A solid collider made a sensor lets bodies through and reports
those it overlaps, from the next step; a sensor made solid pushes out the bodies inside it, as
``add_collider`` does.

Its geometry is fixed once made: the World builds its contact tables from it, so writing
``peg.center = ...`` (or any other attribute) raises an AttributeError that says what to do
instead: take it out and add a new one (``world.remove_collider(peg)``,
``world.add_collider(Circle(...))``), or, for an obstacle that moves every frame, use a
kinematic body (``Body(..., radius=r, kinematic=True)``, moved by writing its ``pos``).

>>> floor = Plane((0, 0), (0, 1))
>>> floor.distance((3, 2))
2.0
>>> Segment((0, 0), (4, 0), radius=0.5).distance((2, 1.5))
1.0
>>> Segment((1, 1), (1, 1))  # doctest: +ELLIPSIS
Traceback (most recent call last):
ValueError: a and b must differ ... use Circle((1.0, 1.0), radius) for a round peg
"""

from __future__ import annotations

import math
import sys
import weakref
from typing import Any

from .. import checks
from ..collision_types import as_collision_type
from ..colours import COLOR_ADVICE, as_colour
from ..filters import DEFAULT as DEFAULT_FILTER
from ..filters import Filter, as_filter
from ..points import point_of
from ..vector import Vector
from . import convex
from .mass import (
    area_for_circle,
    area_for_segment,
    moment_for_circle,
    moment_for_polygon,
    moment_for_segment,
)

__all__ = ["Collider", "Plane", "Segment", "Circle", "Box", "Polygon", "point_of"]


#: What a collider's material is: set any time (``Collider.__setattr__``).
MATERIAL = ("restitution", "friction", "sensor", "filter")


def _fixed(collider: Collider, name: str) -> str:
    """Why ``collider.name`` cannot change, and what to do instead."""
    kind = type(collider).__name__
    if name in MATERIAL:  # (only deleting it is refused)
        return (
            f"a {kind}'s {name} can be set ({kind.lower()}.{name} = ...) but not deleted; to "
            f"take the {kind} out of a World, world.remove_collider({kind.lower()})"
        )
    if name not in collider.__slots__:
        return f"a {kind} has no attribute {name!r} to set"
    return (
        f"a {kind}'s {name} cannot change once it is made (the World built its contacts from "
        f"its geometry): take it out and add a new one, world.remove_collider(old) then "
        f"world.add_collider({kind}(..., {name}=...)); for an obstacle that moves, use a "
        f"kinematic body, Body(position, radius=r, kinematic=True), and write its pos each "
        f"frame (its material, {', '.join(MATERIAL)}, can be set any time)"
    )


def _unit(x: float, y: float) -> tuple[float, float] | None:
    """(x, y) scaled to length 1 (None for (0, 0)); scaled first, so tiny and huge work too."""
    m = max(abs(x), abs(y))
    if m == 0.0:
        return None
    x, y = x / m, y / m  # now the larger is 1: hypot neither underflows nor overflows
    length = math.hypot(x, y)
    return x / length, y / length


def _material(restitution: Any, friction: Any, sensor: Any) -> tuple[float, float, bool]:
    e = checks.real(restitution, "restitution")
    if not 0.0 <= e <= 1.0:
        raise ValueError(
            f"restitution must be in [0, 1] (1.0 leaves the body's own in force), got "
            f"{restitution!r}"
        )
    mu = checks.real(friction, "friction", nonneg=True)
    if not isinstance(sensor, bool):
        raise TypeError(f"sensor must be True or False, got {type(sensor).__name__} {sensor!r}")
    return e, mu, sensor


#: A flat face for the contact kernels: (point p, unit normal n, offset rho, two_sided, lo, hi).
#: The face is the line through p, pushed out along n by rho; a body's centre at distance
#: ``rho + r`` from the line touches it. ``lo <= u <= hi`` bounds the face along the tangent
#: (-n_y, n_x), measured from p. A one-sided face's solid lies behind n.
Line = tuple[tuple[float, float], tuple[float, float], float, bool, float, float]
#: A round face: (centre, radius).
Disc = tuple[tuple[float, float], float]


class Collider:
    """A static shape bodies meet; its subclasses are the shapes. Materials as in the module doc."""

    __slots__ = (
        "restitution",
        "friction",
        "sensor",
        "filter",
        "colour",
        "collision_type",
        "surface_velocity",
        "_worlds",
    )

    def __init__(
        self,
        restitution: float,
        friction: float,
        sensor: bool,
        filter: Filter = DEFAULT_FILTER,  # noqa: A002
        colour: Any = None,
    ) -> None:
        # The Worlds that hold it (weak references to their states), told of a material set.
        self._worlds: tuple[weakref.ref[Any], ...] = ()
        self.restitution, self.friction, self.sensor = _material(restitution, friction, sensor)
        #: Which bodies meet it (engine.Filter, as a body's): a body whose filter and this one
        #: do not collide passes through it, is not sensed by it, and queries filter it alike.
        self.filter = as_filter(filter)
        #: How ``draw_world`` fills it (engine.colours: a pygame colour, None for its own
        #: ink); set it any time, the World never reads it.
        self.colour = as_colour(colour)
        #: Which handlers of ``World.on_collision`` take its contacts (pymunk's
        #: ``shape.collision_type``: an int >= 0, 0 by default); set it any time.
        self.collision_type = 0
        #: How fast its surface moves along itself (length units/s, a Vector; pymunk's
        #: ``shape.surface_velocity``): friction carries what rests on it (a conveyor belt).
        #: Only its part along the surface counts; set it any time.
        self.surface_velocity = Vector(0.0, 0.0)

    def __setattr__(self, name: str, value: Any) -> None:
        # Each public attribute is set once, when the collider is made. After that its material
        # can be set (checked, and the Worlds that hold it told); its geometry is refused (the
        # World built its contact tables from it, so a change would be ignored). Private ones
        # (a leading _) are the engine's own business.
        if name == "color":
            raise AttributeError(f"a {type(self).__name__} has no color: {COLOR_ADVICE}")
        if name == "colour" and hasattr(self, name):
            object.__setattr__(self, name, as_colour(value))
            return
        if name == "collision_type":
            object.__setattr__(self, name, as_collision_type(value))
            return
        if name == "surface_velocity":
            self._set_surface_velocity(value)
            return
        if name[0] != "_" and hasattr(self, name):
            if name not in MATERIAL:
                raise AttributeError(_fixed(self, name))
            self._set_material(name, value)
            return
        object.__setattr__(self, name, value)

    def _set_material(self, name: str, value: Any) -> None:
        """Set ``name`` (one of MATERIAL) to ``value``, checked as when made (a value refused
        leaves the old one), and tell each World that holds this collider."""
        if name == "filter":
            new: Any = as_filter(value)
        else:
            given = {"restitution": self.restitution, "friction": self.friction}
            given["sensor"] = self.sensor
            given[name] = value
            checked = _material(given["restitution"], given["friction"], given["sensor"])
            new = checked[MATERIAL.index(name)]
        if new == getattr(self, name) and type(new) is type(getattr(self, name)):
            return
        object.__setattr__(self, name, new)
        for ref in self._worlds:
            world = ref()
            if world is not None:
                world.collider_changed(self, name)

    def _set_surface_velocity(self, value: Any) -> None:
        """Set ``surface_velocity`` (a finite Vector or pair), and tell each World that holds
        this collider as for a material."""
        x, y = point_of(value, "surface_velocity")
        new = Vector(x, y)
        old = getattr(self, "surface_velocity", None)
        object.__setattr__(self, "surface_velocity", new)
        if old is None or old == new:
            return
        for ref in self._worlds:
            world = ref()
            if world is not None:
                world.collider_changed(self, "surface_velocity")

    def held_by(self, world: Any, held: bool) -> None:
        """A World (its state, which has ``collider_changed(collider, name)``) took this
        collider (``held``) or let it go: it is told of each material set while it holds it."""
        live = tuple(r for r in self._worlds if r() is not None and r() is not world)
        self._worlds = (*live, weakref.ref(world)) if held else live

    def __getstate__(self) -> tuple[None, dict[str, Any]]:
        # A copy (copy, pickle) is held by no World: the Worlds' weak references stay behind.
        names = [n for cls in type(self).__mro__ for n in getattr(cls, "__slots__", ())]
        return None, {n: getattr(self, n) for n in names if n != "_worlds" and hasattr(self, n)}

    def __setstate__(self, state: tuple[None, dict[str, Any]]) -> None:
        object.__setattr__(self, "_worlds", ())
        for name, value in state[1].items():
            object.__setattr__(self, name, value)

    def __delattr__(self, name: str) -> None:
        if name[0] == "_":
            object.__delattr__(self, name)
            return
        raise AttributeError(_fixed(self, name))

    def distance(self, point: Any) -> float:
        """Signed distance (length units) from ``point`` to the surface: > 0 in free space."""
        return self.closest(point)[2]

    def closest(self, point: Any) -> tuple[Vector, Vector, float]:
        """(the nearest surface point, the unit normal there into free space, the distance)."""
        raise NotImplementedError

    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of the solid part (inf for what has no end)."""
        raise NotImplementedError

    def moved(self, dx: float, dy: float) -> Any:
        """A copy moved by (dx, dy) (length units): the same geometry, material and look,
        in no World. A translation keeps a polygon convex with its normals, area and rounding,
        so they are kept, not found again (their bits do not change)."""
        fields = self._moved_fields(checks.real(dx, "dx"), checks.real(dy, "dy"))
        new = object.__new__(type(self))
        put = object.__setattr__  # (a collider refuses a change of its geometry once made)
        for klass in type(self).__mro__:
            for name in getattr(klass, "__slots__", ()):
                if hasattr(self, name):
                    put(new, name, fields.get(name, getattr(self, name)))
        put(new, "_worlds", ())
        return new

    def _moved_fields(self, dx: float, dy: float) -> dict[str, Any]:
        """The attributes a move by (dx, dy) changes, as the moved copy has them."""
        raise TypeError(f"a {type(self).__name__} has no end to move: make a new one instead")

    def lines(self) -> list[Line]:
        """The flat faces, for the contact kernels."""
        return []

    def discs(self) -> list[Disc]:
        """The round faces, for the contact kernels."""
        return []

    def as_body_shape(self) -> float:
        """Check this shape for a Body's ``shape`` (its coordinates then in the body's frame,
        about its position) and return the radius of the circle about the position that holds
        it (length units): what the broadphase and the queries use. A body's material and
        filter are the Body's own, so the shape must leave them at their defaults."""
        raise TypeError(
            f"{type(self).__name__} cannot be a body's shape: give Body(..., shape=...) a "
            f"Circle((0, 0), r), a Polygon (Polygon.box(width, height) for a box) or a "
            f"Segment (a capsule)"
        )

    def _body_material(self) -> None:
        """Refuse a body shape that carries a material, filter or sensor of its own."""
        if self.material_given():
            raise ValueError(
                f"{self!r} as a body's shape: a body's restitution, friction, filter and "
                f"collision_type are the Body's, e.g. Body(..., "
                f"shape={type(self).__name__}(...), friction=0.2, collision_type=1); "
                f"give the shape its geometry only (a sensor body: Body(..., sensor=True))"
            )

    def material_given(self) -> bool:
        """Whether the material, filter or sensor differ from a collider's defaults."""
        return (
            self.restitution != 1.0
            or self.friction != 1.0
            or self.sensor
            or self.filter != DEFAULT_FILTER
            or self.collision_type != 0
            or self.surface_velocity != Vector(0.0, 0.0)
        )

    def _material_repr(self) -> str:
        parts = []
        if self.restitution != 1.0:
            parts.append(f"restitution={self.restitution!r}")
        if self.friction != 1.0:
            parts.append(f"friction={self.friction!r}")
        if self.sensor:
            parts.append("sensor=True")
        if self.filter != DEFAULT_FILTER:
            parts.append(f"filter={self.filter!r}")
        if self.colour is not None:
            parts.append(f"colour={self.colour!r}")
        return "".join(", " + p for p in parts)


class Plane(Collider):
    """An infinite line through ``point``; free space on the side ``normal`` points to."""

    __slots__ = ("point", "normal")

    def __init__(
        self,
        point: Any,
        normal: Any,
        *,
        restitution: float = 1.0,
        friction: float = 1.0,
        sensor: bool = False,
        filter: Filter = DEFAULT_FILTER,  # noqa: A002 - pymunk's name for it
        colour: Any = None,
    ) -> None:
        p = point_of(point, "point")
        unit = _unit(*point_of(normal, "normal"))
        if unit is None:
            raise ValueError(
                f"normal must be a nonzero direction such as (0, 1) (up), got {normal!r}"
            )
        # A point's distance to the line, (x - px) nx + (y - py) ny, is at most
        # |x - px| + |y - py| (|nx|, |ny| <= 1): finite for points near the origin while
        # |px| + |py| is. Past that it overflows (found by the fuzz exploring: a plane through
        # (1.8e308, 1.8e308) with normal (1, 1) told the origin's nearest point as (inf, inf)).
        if not math.isfinite(abs(p[0]) + abs(p[1])):
            raise ValueError(
                f"point must keep the line's distances within the float range: |x| + |y| of "
                f"{point!r} passes 1.8e308; give a point of the line nearer the origin"
            )
        super().__init__(restitution, friction, sensor, filter, colour)
        self.point = Vector(*p)
        self.normal = Vector(*unit)

    def _moved_fields(self, dx: float, dy: float) -> dict[str, Any]:
        return {"point": Vector(self.point.x + dx, self.point.y + dy)}

    def closest(self, point: Any) -> tuple[Vector, Vector, float]:
        x, y = point_of(point, "point")
        n, p = self.normal, self.point
        d = (x - p.x) * n.x + (y - p.y) * n.y
        return Vector(x - d * n.x, y - d * n.y), n, d

    def bounds(self) -> tuple[float, float, float, float]:
        n = self.normal
        inf = math.inf
        # A horizontal or vertical plane's solid is bounded on one side.
        if n.x == 0.0:
            return (-inf, -inf, inf, self.point.y) if n.y > 0 else (-inf, self.point.y, inf, inf)
        if n.y == 0.0:
            return (-inf, -inf, self.point.x, inf) if n.x > 0 else (self.point.x, -inf, inf, inf)
        return (-inf, -inf, inf, inf)

    def lines(self) -> list[Line]:
        return [(tuple(self.point), tuple(self.normal), 0.0, False, -math.inf, math.inf)]  # type: ignore[list-item]

    def __repr__(self) -> str:
        return f"Plane({tuple(self.point)!r}, {tuple(self.normal)!r}{self._material_repr()})"


class Segment(Collider):
    """A wall from ``a`` to ``b``, ``radius`` thick on each side with round ends (a capsule)."""

    __slots__ = ("a", "b", "radius")

    def __init__(
        self,
        a: Any,
        b: Any,
        radius: float = 0.0,
        *,
        restitution: float = 1.0,
        friction: float = 1.0,
        sensor: bool = False,
        filter: Filter = DEFAULT_FILTER,  # noqa: A002 - pymunk's name for it
        colour: Any = None,
    ) -> None:
        pa, pb = point_of(a, "a"), point_of(b, "b")
        r = checks.real(radius, "radius", nonneg=True)
        dx, dy = pb[0] - pa[0], pb[1] - pa[1]
        if pa != pb and not (math.isfinite(dx) and math.isfinite(dy)):
            raise ValueError(
                f"a and b must lie within the float range of each other, got {a!r} and {b!r}"
            )
        if dx * dx + dy * dy < 1e-300:  # zero, or a length whose square underflows
            raise ValueError(
                f"a and b must differ (by more than 1e-150): a Segment from {pa} to {pb} has no "
                f"length to give it a direction; "
                f"use Circle({pa}, radius) for a round peg"
            )
        super().__init__(restitution, friction, sensor, filter, colour)
        self.a, self.b, self.radius = Vector(*pa), Vector(*pb), r

    def closest(self, point: Any) -> tuple[Vector, Vector, float]:
        x, y = point_of(point, "point")
        a, b = self.a, self.b
        dx, dy = b.x - a.x, b.y - a.y
        u = ((x - a.x) * dx + (y - a.y) * dy) / (dx * dx + dy * dy)
        u = min(1.0, max(0.0, u))
        cx, cy = a.x + u * dx, a.y + u * dy
        ox, oy = x - cx, y - cy
        d = math.hypot(ox, oy)
        # On the segment itself: take its left normal.
        nx, ny = _unit(ox, oy) or _unit(-dy, dx) or (0.0, 1.0)
        r = self.radius
        return Vector(cx + r * nx, cy + r * ny), Vector(nx, ny), d - r

    def bounds(self) -> tuple[float, float, float, float]:
        a, b, r = self.a, self.b, self.radius
        return min(a.x, b.x) - r, min(a.y, b.y) - r, max(a.x, b.x) + r, max(a.y, b.y) + r

    def _moved_fields(self, dx: float, dy: float) -> dict[str, Any]:
        a, b = self.a, self.b
        return {"a": Vector(a.x + dx, a.y + dy), "b": Vector(b.x + dx, b.y + dy)}

    def as_body_shape(self) -> float:
        self._body_material()
        a, b = self.a, self.b
        return max(math.hypot(a.x, a.y), math.hypot(b.x, b.y)) + self.radius

    def moment(self, mass: float) -> float:
        """The moment of inertia (kg m^2) of a body of ``mass`` with this capsule for its
        shape, about the body's position (``engine.geometry.mass.moment_for_segment``)."""
        return moment_for_segment(mass, self.a, self.b, self.radius)

    @property
    def area(self) -> float:
        """The capsule's area (length units squared): r (pi r + 2 |b - a|), 0 for a bare
        segment (``engine.geometry.mass.area_for_segment``)."""
        return area_for_segment(self.a, self.b, self.radius)

    @property
    def centroid(self) -> Vector:
        """The capsule's centre of area: the segment's midpoint (length units)."""
        return (self.a + self.b) * 0.5

    def lines(self) -> list[Line]:
        a, b = self.a, self.b
        length = math.hypot(b.x - a.x, b.y - a.y)
        tx, ty = (b.x - a.x) / length, (b.y - a.y) / length
        # The normal (ty, -tx) makes the tangent (-n_y, n_x) = (tx, ty): u runs from a to b.
        return [((a.x, a.y), (ty, -tx), self.radius, True, 0.0, length)]

    def discs(self) -> list[Disc]:
        return [((self.a.x, self.a.y), self.radius), ((self.b.x, self.b.y), self.radius)]

    def __repr__(self) -> str:
        size = "" if self.radius == 0.0 else f", radius={self.radius!r}"
        return f"Segment({tuple(self.a)!r}, {tuple(self.b)!r}{size}{self._material_repr()})"


class Circle(Collider):
    """A round peg or bumper of ``radius`` > 0 around ``center``."""

    __slots__ = ("center", "radius")

    def __init__(
        self,
        center: Any,
        radius: float,
        *,
        restitution: float = 1.0,
        friction: float = 1.0,
        sensor: bool = False,
        filter: Filter = DEFAULT_FILTER,  # noqa: A002 - pymunk's name for it
        colour: Any = None,
    ) -> None:
        c = point_of(center, "center")
        r = checks.real(radius, "radius", positive=True)
        super().__init__(restitution, friction, sensor, filter, colour)
        self.center, self.radius = Vector(*c), r

    def closest(self, point: Any) -> tuple[Vector, Vector, float]:
        x, y = point_of(point, "point")
        c, r = self.center, self.radius
        ox, oy = x - c.x, y - c.y
        d = math.hypot(ox, oy)
        nx, ny = _unit(ox, oy) or (0.0, 1.0)  # at the centre itself: up
        return Vector(c.x + r * nx, c.y + r * ny), Vector(nx, ny), d - r

    def bounds(self) -> tuple[float, float, float, float]:
        c, r = self.center, self.radius
        return c.x - r, c.y - r, c.x + r, c.y + r

    def discs(self) -> list[Disc]:
        return [((self.center.x, self.center.y), self.radius)]

    def _moved_fields(self, dx: float, dy: float) -> dict[str, Any]:
        return {"center": Vector(self.center.x + dx, self.center.y + dy)}

    @property
    def area(self) -> float:
        """The disc's area (length units squared): pi r^2."""
        return area_for_circle(0.0, self.radius)

    @property
    def centroid(self) -> Vector:
        """The disc's centre of area: its centre (length units)."""
        return self.center

    def moment(self, mass: float) -> float:
        """The moment of inertia (kg m^2) of a body of ``mass`` with this disc for its shape,
        about the body's position: m r^2 / 2, and m |center|^2 more for a centre off it
        (``engine.geometry.mass.moment_for_circle``)."""
        return moment_for_circle(mass, 0.0, self.radius, self.center)

    def as_body_shape(self) -> float:
        self._body_material()
        if self.center.x != 0.0 or self.center.y != 0.0:
            raise ValueError(
                f"a kinematic body's round shape is centred on its position, which it turns "
                f"about: Circle((0, 0), {self.radius!r}) (or Body(..., radius="
                f"{self.radius!r})), got centre {tuple(self.center)!r}: move the body by the "
                f"offset instead (a dynamic body is moved so: its position is its centre of "
                f"mass, engine.body_shapes)"
            )
        return self.radius

    def __repr__(self) -> str:
        return f"Circle({tuple(self.center)!r}, {self.radius!r}{self._material_repr()})"


class Box(Collider):
    """The four walls of a room from ``lower_left`` to ``upper_right``; bodies stay inside.

    Its solid is everything *outside* the rectangle; for a solid box-shaped thing that bodies
    bounce off and rest on (a crate, a step), use ``Polygon.box(width, height, center)``.
    """

    __slots__ = ("lower_left", "upper_right")

    def __init__(
        self,
        lower_left: Any,
        upper_right: Any,
        *,
        restitution: float = 1.0,
        friction: float = 1.0,
        sensor: bool = False,
        filter: Filter = DEFAULT_FILTER,  # noqa: A002 - pymunk's name for it
        colour: Any = None,
    ) -> None:
        x0, y0 = point_of(lower_left, "lower_left")
        x1, y1 = point_of(upper_right, "upper_right")
        if not (x0 < x1 and y0 < y1):
            raise ValueError(
                f"upper_right must lie above and right of lower_left (x1 > x0 and y1 > y0), got "
                f"lower_left={lower_left!r}, upper_right={upper_right!r}"
            )
        super().__init__(restitution, friction, sensor, filter, colour)
        self.lower_left, self.upper_right = Vector(x0, y0), Vector(x1, y1)

    def closest(self, point: Any) -> tuple[Vector, Vector, float]:
        x, y = point_of(point, "point")
        (x0, y0), (x1, y1) = self.lower_left, self.upper_right
        # Distance to each wall, positive inside the room; the nearest wall is the contact.
        walls = (
            (x - x0, Vector(1.0, 0.0), Vector(x0, y)),
            (x1 - x, Vector(-1.0, 0.0), Vector(x1, y)),
            (y - y0, Vector(0.0, 1.0), Vector(x, y0)),
            (y1 - y, Vector(0.0, -1.0), Vector(x, y1)),
        )
        d, n, p = min(walls, key=lambda w: w[0])
        return p, n, d

    def _moved_fields(self, dx: float, dy: float) -> dict[str, Any]:
        (x0, y0), (x1, y1) = self.lower_left, self.upper_right
        return {"lower_left": Vector(x0 + dx, y0 + dy), "upper_right": Vector(x1 + dx, y1 + dy)}

    def bounds(self) -> tuple[float, float, float, float]:
        inf = math.inf
        return (-inf, -inf, inf, inf)  # the solid is everything outside

    def lines(self) -> list[Line]:
        (x0, y0), (x1, y1) = self.lower_left, self.upper_right
        inf = math.inf
        return [
            ((x0, y0), (1.0, 0.0), 0.0, False, -inf, inf),
            ((x1, y0), (-1.0, 0.0), 0.0, False, -inf, inf),
            ((x0, y0), (0.0, 1.0), 0.0, False, -inf, inf),
            ((x0, y1), (0.0, -1.0), 0.0, False, -inf, inf),
        ]

    def as_body_shape(self) -> float:
        raise TypeError(
            f"{self!r} is a room (four walls facing in: a collider, world.add_collider); a "
            f"box-shaped body is Body(..., shape=Polygon.box(width, height))"
        )

    def __repr__(self) -> str:
        return (
            f"Box({tuple(self.lower_left)!r}, {tuple(self.upper_right)!r}{self._material_repr()})"
        )


class Polygon(Collider):
    """A solid convex polygon, rounded by ``radius`` (length units) when it is > 0.

    ``vertices`` are 3 to 256 points (``engine.geometry.convex.MAX_VERTICES``, which says why 256),
    in either order round the polygon: clockwise input is reversed, so ``vertices`` always runs
    counter-clockwise.
    A polygon that is not convex is refused (split it into convex ones), as are repeated
    points, a vertex on the line between its neighbours, and points that enclose no area.
    A rounded polygon is every point within ``radius`` of the polygon (Box2D's rounded box):
    its corners are round, which lets things roll off them.

    For the exact contacts each edge is a one-sided flat face pushed out by ``radius`` and
    each vertex a round face of radius ``radius``: a ball of radius r touches the polygon
    when its centre is r from that surface.

    >>> tri = Polygon([(0, 0), (0, 3), (4, 0)])  # clockwise: reversed
    >>> [tuple(v) for v in tri.vertices]
    [(0.0, 0.0), (4.0, 0.0), (0.0, 3.0)]
    >>> tri.area, tuple(tri.centroid), tri.distance((0, 5))
    (6.0, (1.3333333333333333, 1.0), 2.0)
    >>> Polygon.box(2, 1, center=(0, 0.5)).bounds()
    (-1.0, 0.0, 1.0, 1.0)
    """

    __slots__ = ("vertices", "normals", "radius", "centroid", "area")

    def __init__(
        self,
        vertices: Any,
        radius: float = 0.0,
        *,
        restitution: float = 1.0,
        friction: float = 1.0,
        sensor: bool = False,
        filter: Filter = DEFAULT_FILTER,  # noqa: A002 - pymunk's name for it
        colour: Any = None,
    ) -> None:
        if isinstance(vertices, (str, bytes)) or not hasattr(vertices, "__iter__"):
            raise TypeError(
                f"vertices must be a sequence of 2D points such as [(0, 0), (1, 0), (0, 1)], "
                f"got {type(vertices).__name__} {vertices!r}"
            )
        pts = [point_of(v, f"vertices[{i}]") for i, v in enumerate(vertices)]
        ccw = convex.convex_polygon(pts, "vertices", max_count=convex.MAX_VERTICES)
        r = checks.real(radius, "radius", nonneg=True)
        super().__init__(restitution, friction, sensor, filter, colour)
        #: The corners (length units), counter-clockwise, in the world's frame.
        self.vertices = tuple(Vector(x, y) for x, y in ccw)
        #: The outward unit normal of each edge, from vertices[i] to vertices[i + 1].
        self.normals = tuple(Vector(x, y) for x, y in convex.edge_normals(ccw))
        #: The rounding (length units): the solid is every point within it of the polygon.
        self.radius = r
        centroid, area = convex.centroid(ccw, r), convex.area(ccw, r)
        if not (math.isfinite(area) and all(map(math.isfinite, centroid))):
            if not _finite_solid(ccw, 0.0):  # the corners' fault, not the rounding's
                raise ValueError(
                    f"vertices must span a polygon whose area and centroid are within the "
                    f"float range (corners within about 1e150 length units of each other), "
                    f"got {[tuple(v) for v in ccw]!r}"
                )
            raise ValueError(
                f"radius must leave the rounded polygon's area and centroid within the float "
                f"range (a rounding of at most about 1e100 length units), got {radius!r}"
            )
        #: The centroid of the solid, rounding included (length units).
        self.centroid = Vector(*centroid)
        #: The area of the solid, rounding included (length units squared).
        self.area = area

    @classmethod
    def box(
        cls,
        width: float,
        height: float,
        center: Any = (0.0, 0.0),
        radius: float = 0.0,
        *,
        restitution: float = 1.0,
        friction: float = 1.0,
        sensor: bool = False,
        filter: Filter = DEFAULT_FILTER,  # noqa: A002 - pymunk's name for it
        colour: Any = None,
    ) -> Polygon:
        """A solid box ``width`` by ``height`` (length units, full sizes) around ``center``.

        pymunk's ``Poly.create_box`` (Box2D's ``b2MakeOffsetRoundedBox`` takes half sizes);
        with ``radius`` > 0 its corners are rounded and it grows by ``radius`` on every side.
        Not ``Box``, which is a room whose walls keep bodies inside.
        """
        sizes = []
        for name, value in (("width", width), ("height", height)):
            size = checks.real(value, name)
            if not size > 0.0:
                raise ValueError(
                    f"{name} must be > 0 (the box's full {name} in length units, e.g. 1.0), "
                    f"got {value!r}"
                )
            sizes.append(size)
        cx, cy = point_of(center, "center")
        hw, hh = 0.5 * sizes[0], 0.5 * sizes[1]
        corners = [(cx - hw, cy - hh), (cx + hw, cy - hh), (cx + hw, cy + hh), (cx - hw, cy + hh)]
        if not all(math.isfinite(c) for corner in corners for c in corner):
            raise ValueError(
                f"center, width and height must keep the corners within the float range, got "
                f"center={center!r}, width={width!r}, height={height!r}"
            )
        try:  # corners that rounding makes one point, or an area that over- or underflows
            convex.convex_polygon(corners, "the corners")
        except ValueError as exc:
            raise ValueError(
                f"width, height and center must make 4 distinct corners with a finite area in "
                f"floats, got width={width!r}, height={height!r}, center={center!r} ({exc})"
            ) from None
        return cls(
            corners,
            radius,
            restitution=restitution,
            friction=friction,
            sensor=sensor,
            filter=filter,
            colour=colour,
        )

    def _moved_fields(self, dx: float, dy: float) -> dict[str, Any]:
        c = self.centroid
        return {
            "vertices": tuple(Vector(v.x + dx, v.y + dy) for v in self.vertices),
            "centroid": Vector(c.x + dx, c.y + dy),
        }

    def as_body_shape(self) -> float:
        self._body_material()
        return max(math.hypot(v.x, v.y) for v in self.vertices) + self.radius

    def moment(self, mass: float) -> float:
        """The moment of inertia (kg m^2) of a body of ``mass`` with this polygon (rounded by
        its radius) for its shape, about the body's position, the parallel axes' term
        included (``engine.geometry.mass.moment_for_polygon``)."""
        return moment_for_polygon(mass, self.vertices, radius=self.radius)

    def closest(self, point: Any) -> tuple[Vector, Vector, float]:
        x, y = point_of(point, "point")
        verts, normals, r = self.vertices, self.normals, self.radius
        count = len(verts)
        # The separation from edge i's line, s_i = n_i.(x - v_i), is largest for the nearest
        # face when x is inside (all s_i <= 0; the foot of the perpendicular on that face's
        # line lies on the face, since the disc of that radius about x fits inside).
        seps = [n.x * (x - v.x) + n.y * (y - v.y) for v, n in zip(verts, normals, strict=True)]
        k = max(range(count), key=seps.__getitem__)
        s = seps[k]
        if s <= 0.0:
            n = normals[k]
            fx, fy = x - s * n.x, y - s * n.y
            return Vector(fx + r * n.x, fy + r * n.y), n, s - r
        # Outside: the nearest point of the boundary lies on one of the edges.
        best = (math.inf, 0.0, 0.0)
        for i in range(count):
            a, b = verts[i], verts[(i + 1) % count]
            dx, dy = b.x - a.x, b.y - a.y
            u = ((x - a.x) * dx + (y - a.y) * dy) / (dx * dx + dy * dy)
            u = min(1.0, max(0.0, u))
            cx, cy = a.x + u * dx, a.y + u * dy
            d = math.hypot(x - cx, y - cy)
            if d < best[0]:
                best = (d, cx, cy)
        d, cx, cy = best
        # Within rounding of the boundary the direction of (x - c) is rounding's, not the
        # normal's: a point 2e-16 outside a corner gave one outside the corner's cone of
        # normals, and a surface point inside the rounded polygon. There the face of greatest
        # separation, whose line the point is on, gives it.
        scale = max(1.0, abs(x), abs(y))
        near = d <= 8.0 * sys.float_info.epsilon * scale
        nx, ny = (None if near else _unit(x - cx, y - cy)) or tuple(normals[k])
        return Vector(cx + r * nx, cy + r * ny), Vector(nx, ny), d - r

    def bounds(self) -> tuple[float, float, float, float]:
        r = self.radius
        xs = [v.x for v in self.vertices]
        ys = [v.y for v in self.vertices]
        return min(xs) - r, min(ys) - r, max(xs) + r, max(ys) + r

    def lines(self) -> list[Line]:
        # Edge i from v_i to v_{i+1}: its outward normal n = (e_y, -e_x) / L makes the tangent
        # (-n_y, n_x) = e / L, so u runs from 0 at v_i to L at v_{i+1}.
        verts, count = self.vertices, len(self.vertices)
        out: list[Line] = []
        for i, n in enumerate(self.normals):
            a, b = verts[i], verts[(i + 1) % count]
            length = math.hypot(b.x - a.x, b.y - a.y)
            out.append(((a.x, a.y), (n.x, n.y), self.radius, False, 0.0, length))
        return out

    def discs(self) -> list[Disc]:
        return [((v.x, v.y), self.radius) for v in self.vertices]

    def __repr__(self) -> str:
        pts = tuple(tuple(v) for v in self.vertices)
        size = "" if self.radius == 0.0 else f", radius={self.radius!r}"
        return f"Polygon({pts!r}{size}{self._material_repr()})"


def _finite_solid(ccw: Any, radius: float) -> bool:
    """Whether a convex polygon's area and centroid, rounded by ``radius``, are finite."""
    area, centroid = convex.area(ccw, radius), convex.centroid(ccw, radius)
    return math.isfinite(area) and all(map(math.isfinite, centroid))
