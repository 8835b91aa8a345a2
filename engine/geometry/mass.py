"""Areas and moments of inertia of the shapes, by pymunk's names.

Each moment is in kg m^2 (mass units times length units squared) about the body's origin, for
a body of uniform density whose shape is given in the body's frame: the parallel-axis term
m |d|^2 for a shape whose centroid sits at d from the origin is included. Each area is in
length units squared. Errors name the argument at fault.

Where pymunk (Chipmunk) approximates, these are exact: ``moment_for_segment`` with a radius is
the true capsule (pymunk takes a box of length L + 2r), ``moment_for_polygon`` counts the
rounding ``radius`` (pymunk ignores it), and ``area_for_polygon`` is never negative (pymunk's
is negative for clockwise vertices). With no radius they agree with pymunk to rounding.

>>> moment_for_circle(2.0, 0.0, 1.0)  # a disc: m r^2 / 2
1.0
>>> moment_for_box(12.0, (3.0, 4.0))  # m (w^2 + h^2) / 12
25.0
>>> moment_for_segment(12.0, (-1.0, 0.0), (1.0, 0.0), 0.0)  # a rod: m L^2 / 12
4.0
>>> round(moment_for_polygon(12.0, [(-1.5, -2), (1.5, -2), (1.5, 2), (-1.5, 2)]), 12)
25.0
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from .. import checks
from ..points import point_of
from . import convex

__all__ = [
    "moment_for_circle",
    "moment_for_segment",
    "moment_for_box",
    "moment_for_polygon",
    "area_for_circle",
    "area_for_segment",
    "area_for_polygon",
]


def _radii(inner_radius: Any, outer_radius: Any) -> tuple[float, float]:
    r1 = checks.real(inner_radius, "inner_radius", nonneg=True)
    r2 = checks.real(outer_radius, "outer_radius", nonneg=True)
    if r1 > r2:
        raise ValueError(
            f"inner_radius must be <= outer_radius (a ring from inner to outer; 0 for a solid "
            f"disc), got inner_radius={inner_radius!r}, outer_radius={outer_radius!r}"
        )
    return r1, r2


def _vertices(vertices: Any) -> tuple[tuple[float, float], ...]:
    if isinstance(vertices, (str, bytes)) or not hasattr(vertices, "__iter__"):
        raise TypeError(
            f"vertices must be a sequence of 2D points such as [(0, 0), (1, 0), (0, 1)], got "
            f"{type(vertices).__name__} {vertices!r}"
        )
    pts = [point_of(v, f"vertices[{i}]") for i, v in enumerate(vertices)]
    return convex.convex_polygon(pts, "vertices")


def area_for_circle(inner_radius: float, outer_radius: float) -> float:
    """Area (length^2) of a ring between the radii: pi (r2^2 - r1^2); inner 0 for a disc."""
    r1, r2 = _radii(inner_radius, outer_radius)
    return math.pi * (r2 * r2 - r1 * r1)


def moment_for_circle(
    mass: float, inner_radius: float, outer_radius: float, offset: Any = (0.0, 0.0)
) -> float:
    """Moment (kg m^2) of a ring of ``mass`` centred at ``offset`` from the body's origin.

    A thin ring at radius rho holds dm = m 2 rho drho / (r2^2 - r1^2), so
    I = int rho^2 dm = m (r2^4 - r1^4) / (2 (r2^2 - r1^2)) = m (r1^2 + r2^2) / 2; then the
    parallel axes add m |offset|^2.
    """
    m = checks.mass(mass)
    r1, r2 = _radii(inner_radius, outer_radius)
    dx, dy = point_of(offset, "offset")
    return m * (0.5 * (r1 * r1 + r2 * r2) + dx * dx + dy * dy)


def area_for_segment(a: Any, b: Any, radius: float) -> float:
    """Area (length^2) of the capsule around the segment a-b: r (pi r + 2 |b - a|)."""
    (ax, ay), (bx, by) = point_of(a, "a"), point_of(b, "b")
    r = checks.real(radius, "radius", nonneg=True)
    return r * (math.pi * r + 2.0 * math.hypot(bx - ax, by - ay))


def moment_for_segment(mass: float, a: Any, b: Any, radius: float) -> float:
    """Moment (kg m^2) about the body's origin of a capsule: the segment a-b, ``radius`` thick.

    Box2D's exact capsule (b2ComputeCapsuleMass): with h = L / 2, a box 2r by L of area 2 r L
    (I = A (L^2 + 4 r^2) / 12) and two half discs that make one disc of area pi r^2; a half
    disc's centroid is lc = 4 r / (3 pi) from its flat side, so by parallel axes (to its
    centroid, then to the capsule's centre) it adds A (r^2 / 2 + h^2 + 2 h lc). Per unit
    area, with everything divided by r so that r = 0 (a rod, L^2 / 12) and L = 0 (a disc,
    r^2 / 2) both come out of one formula:
    I / A = (pi r (r^2/2 + h^2) + (8/3) h r^2 + L (L^2 + 4 r^2) / 6) / (pi r + 2 L),
    and the centre (a + b) / 2 adds m |(a + b) / 2|^2.
    """
    m = checks.mass(mass)
    (ax, ay), (bx, by) = point_of(a, "a"), point_of(b, "b")
    r = checks.real(radius, "radius", nonneg=True)
    length = math.hypot(bx - ax, by - ay)
    if not math.isfinite(length):
        raise ValueError(f"a and b must lie within the float range of each other, got {a!r}, {b!r}")
    h = 0.5 * length
    mx, my = 0.5 * (ax + bx), 0.5 * (ay + by)
    # Far from 1 m the cubes of num leave the float range where the moment does not (a rod
    # of 1e-150 m: L^3 / 6 is 0, its L^2 / 12 is 8e-302): there the lengths are taken in
    # units of the larger, s, and per_area is s^2 times theirs (found by the shapes fuzz).
    s = max(length, r)
    if not 1e-100 < s < 1e100 and s > 0.0:
        length, r, h = length / s, r / s, h / s
    else:
        s = 1.0
    den = math.pi * r + 2.0 * length
    per_area = 0.0
    if den > 0.0:  # else a point: no moment of its own
        num = (
            math.pi * r * (0.5 * r * r + h * h)
            + (8.0 / 3.0) * h * r * r
            + length * (length * length + 4.0 * r * r) / 6.0
        )
        per_area = num / den * s * s
    inertia = m * (per_area + mx * mx + my * my)
    if not math.isfinite(inertia):
        raise ValueError(
            f"a and b and radius must keep the moment of inertia within the float range, got "
            f"{inertia!r} kg m^2 for mass {m!r}, a={a!r}, b={b!r}, radius={radius!r}; give the "
            f"shape in other length units"
        )
    return inertia


def moment_for_box(mass: float, size: Any) -> float:
    """Moment (kg m^2) of a solid box ``size`` = (width, height) centred on the body's origin.

    I = int (x^2 + y^2) dm over the box = m (w^2 + h^2) / 12.
    """
    m = checks.mass(mass)
    w, h = point_of(size, "size")
    if not (w > 0.0 and h > 0.0):
        raise ValueError(
            f"size must be (width, height), both > 0 (the box's full width and height), "
            f"got {size!r}"
        )
    return m * (w * w + h * h) / 12.0


def area_for_polygon(vertices: Sequence[Any], radius: float = 0.0) -> float:
    """Area (length^2) of the convex polygon rounded by ``radius``: A + r P + pi r^2.

    ``vertices`` in either winding; a polygon that is not convex is a ValueError.
    """
    pts = _vertices(vertices)
    r = checks.real(radius, "radius", nonneg=True)
    return convex.area(pts, r)


def moment_for_polygon(
    mass: float, vertices: Sequence[Any], offset: Any = (0.0, 0.0), radius: float = 0.0
) -> float:
    """Moment (kg m^2) about the body's origin of a solid convex polygon, rounded by
    ``radius``, with ``offset`` added to each vertex (pymunk's ``moment_for_poly``).

    The polygon's polar second moment of area J (``engine.geometry.convex.second_moment``: triangles
    for the core, rectangles on the edges and sectors at the corners for the rounding) times
    the density m / A.
    """
    m = checks.mass(mass)
    dx, dy = point_of(offset, "offset")
    pts = _vertices(vertices)
    r = checks.real(radius, "radius", nonneg=True)
    # Shifting the shape by the offset is the same as taking the moment about -offset.
    inertia = m * convex.second_moment(pts, r, about=(-dx, -dy)) / convex.area(pts, r)
    if not 0.0 < inertia < math.inf:  # the second moment of area over- or underflowed
        raise ValueError(
            f"vertices, offset and radius must keep the moment of inertia within the float "
            f"range (> 0 and finite), got {inertia!r} kg m^2 for mass {m!r}; give the shape in "
            f"other length units"
        )
    return inertia
