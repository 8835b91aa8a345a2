"""A body's shapes about its centre of mass: one shape moved there, or several on one body.

A body is a particle at its centre of mass (the lesson's Body): its position is that point and
it turns about it. A dynamic body given a shape whose centroid c is off the origin of the frame
it was drawn in (``Polygon([(0, 0), (2, 0), (2, 1), (0, 1)])``, a ``Segment((0, 0), (2, 0))``,
a ``Circle((2, 3), 1)``) holds the shape moved by -c, and its position is where c lands: the
position given plus c turned by the body's angle (``centred``). Its moment is then about c
(pymunk's and Box2D's, whose bodies turn about their centre of gravity), and a free body
spinning keeps its centre where it is, as no force moves it. ``Body.center_of_gravity`` is c,
and the frame the shape was drawn in has its origin at ``Body.origin`` (a sprite's; pymunk's
``body.position``). A body not of uniform density (a hammer, a flipper weighted at its pivot
by its shaft) is given its own: ``Body(..., center_of_gravity=(0, 0))`` keeps the shape as
drawn and turns about that point, with the shape's moment about it unless a ``moment`` is
given. A kinematic body turns about its position, where the game put it (Box2D's kinematic
bodies likewise): its shape stays as given.

Several convex shapes make one body (``Body(..., shapes=[...])``: an L of two boxes, a cart, a
concave thing cut into convex parts): ``Compound``. Its mass is spread over the parts by area
(one density; or ``density=[...]``, one a part: m_i = rho_i A_i), its centre c is
sum m_i c_i / m, and its moment is the sum of each part's about c (the parallel axes' term
m_i |c_i - c|^2 in each: the parts are moved by -c first, and ``engine.geometry.mass`` gives
each about the origin). Parts that have no area between them (bare segments) share the mass
equally.

>>> from engine.geometry.colliders import Polygon
>>> L = Compound([Polygon.box(2, 0.4, center=(1, 0.2)), Polygon.box(0.4, 1, center=(0.2, 0.9))])
>>> [round(v, 6) for v in L.offset], round(centred(L)[0].moment(1.2), 6)  # pymunk's
([0.733333, 0.433333], 0.617333)
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

from .vector import Vector

__all__ = ["Compound", "centred", "centre_of", "PARTS", "MAX_PARTS"]

#: The most shapes one body is made of (the soft step's warm-start keys name a part in 3 bits:
#: engine.pipeline.game_contacts).
MAX_PARTS = 8

#: The kinds of shape a body is made of (engine.geometry.colliders), by class name: the core
#: does not import the geometry above it.
PARTS = ("Circle", "Polygon", "Segment")


def centre_of(shape: Any) -> Vector:
    """Where the centre of mass of a uniform ``shape`` (a Circle, Polygon or Segment of
    engine.geometry.colliders, or a Compound) lies in its frame (length units): its centroid."""
    return Vector(*shape.centroid)


def centred(shape: Any, at: Vector | None = None) -> tuple[Any, Vector]:
    """``shape`` moved so that its centre of mass is the origin, and where that centre was
    (length units; module doc): its centroid, or ``at`` where the body's centre of gravity is
    given (a body weighted off its centroid). A shape centred to rounding (the centroid within
    1e-12 of its size of the origin: a regular polygon made from sines) is kept as it is, bit
    for bit."""
    c = centre_of(shape) if at is None else at
    x0, y0, x1, y1 = shape.bounds()
    size = max(abs(x0), abs(y0), abs(x1), abs(y1))
    if (c.x == 0.0 and c.y == 0.0) or (at is None and math.hypot(c.x, c.y) <= 1e-12 * size):
        return shape, Vector(0.0, 0.0)
    return shape.moved(-c.x, -c.y), c


class Compound:
    """Several convex shapes on one body, in its frame (module doc): ``parts``, each a
    ``Circle``, ``Polygon`` or ``Segment`` with no material of its own (the Body's is theirs)."""

    __slots__ = ("parts", "area", "offset", "shares", "densities")

    def __init__(self, shapes: Iterable[Any], densities: Sequence[float] | None = None) -> None:
        if isinstance(shapes, (str, bytes)) or not hasattr(shapes, "__iter__"):
            raise TypeError(
                f"shapes must be a list of convex shapes, e.g. shapes=[Polygon.box(2, 0.4), "
                f"Circle((1, 0.5), 0.3)], got {type(shapes).__name__} {shapes!r}"
            )
        parts = tuple(shapes)
        if not parts:
            raise ValueError(
                "shapes must hold at least one shape, e.g. shapes=[Polygon.box(1, 1)]; for a "
                "disc give radius=..., for a point neither"
            )
        if len(parts) > MAX_PARTS:
            raise ValueError(
                f"shapes holds {len(parts)} shapes, and a body is made of at most {MAX_PARTS}: "
                f"join neighbouring convex parts into one Polygon, or make two bodies and join "
                f"them with a Weld"
            )
        for i, part in enumerate(parts):
            if type(part).__name__ not in PARTS:
                raise TypeError(
                    f"shapes[{i}] must be a Circle, a Polygon (Polygon.box(width, height) for a "
                    f"box) or a Segment (a capsule) from engine.geometry.colliders, got "
                    f"{type(part).__name__} {part!r}"
                )
            part._body_material()
        #: The parts (length units, in the body's frame).
        self.parts: tuple[Any, ...] = parts
        #: The parts' area in all (length units squared).
        self.area: float = math.fsum(float(p.area) for p in parts)
        #: Each part's density where they differ (kg/m^2, pymunk's shape.density), else None.
        self.densities: tuple[float, ...] | None = None
        if densities is not None:
            if len(densities) != len(parts):
                raise ValueError(
                    f"density must be one number, or one for each shape: got {len(densities)} "
                    f"densities for {len(parts)} shapes"
                )
            self.densities = tuple(densities)
        #: Each part's share of the body's mass: its area over the whole's, or its density
        #: times its area over the sum of those; equal shares where the parts have no area.
        self.shares: tuple[float, ...] = self._shares()
        #: The centre of mass in this frame (length units): sum m_i c_i / m.
        self.offset = Vector(
            math.fsum(w * p.centroid.x for w, p in zip(self.shares, parts, strict=True)),
            math.fsum(w * p.centroid.y for w, p in zip(self.shares, parts, strict=True)),
        )

    def _shares(self) -> tuple[float, ...]:
        rho = self.densities or (1.0,) * len(self.parts)
        masses = [d * float(p.area) for d, p in zip(rho, self.parts, strict=True)]
        total = math.fsum(masses)
        if total > 0.0:
            return tuple(m / total for m in masses)
        return (1.0 / len(self.parts),) * len(self.parts)

    def mass_of(self, density: float | None) -> float:
        """The mass (kg) of the parts at ``density`` (kg/m^2, one for all), or at their own
        densities (None): sum rho_i A_i."""
        if density is not None or self.densities is None:
            return (1.0 if density is None else density) * self.area
        return math.fsum(d * float(p.area) for d, p in zip(self.densities, self.parts, strict=True))

    @property
    def centroid(self) -> Vector:
        """The centre of mass in this frame (length units); ``offset``."""
        return self.offset

    def moment(self, mass: float) -> float:
        """The moment of inertia (kg m^2) of a body of ``mass`` made of these parts about the
        origin of their frame: each part's, with its share of the mass, its parallel axes'
        term included (``engine.geometry.mass``)."""
        return math.fsum(
            float(p.moment(mass * w)) for w, p in zip(self.shares, self.parts, strict=True)
        )

    def as_body_shape(self) -> float:
        """The radius (length units) of the circle about the origin that holds every part."""
        out = 0.0
        for p in self.parts:
            if type(p).__name__ == "Circle":
                out = max(out, math.hypot(p.center.x, p.center.y) + p.radius)
            else:
                out = max(out, float(p.as_body_shape()))
        return out

    def bounds(self) -> tuple[float, float, float, float]:
        """The box about every part (length units): xmin, ymin, xmax, ymax."""
        boxes = [p.bounds() for p in self.parts]
        return (
            min(b[0] for b in boxes),
            min(b[1] for b in boxes),
            max(b[2] for b in boxes),
            max(b[3] for b in boxes),
        )

    def moved(self, dx: float, dy: float) -> Compound:
        """A copy with every part moved by (dx, dy) (length units)."""
        return Compound([p.moved(dx, dy) for p in self.parts], self.densities)

    def __len__(self) -> int:
        return len(self.parts)

    def __repr__(self) -> str:
        return f"Compound({list(self.parts)!r})"
