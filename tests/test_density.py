"""A body's mass from a density (kg/m^2, a 2D density): ``Body(..., shape=..., density=d)`` is
``Body(..., shape=..., mass=d * shape.area)`` (pymunk's ``shape.density``, Box2D's
``density``), its moment the shape's for that mass; ``body.density`` reads and sets it as
``body.mass`` does, and the errors say what to write."""

from __future__ import annotations

import math
from typing import Any

import pytest

from engine import Body, Circle, Plane, Polygon, Segment, Vector, World
from engine.forces import Gravity
from tests.paths import PATHS

TRIANGLE = [(-0.4, -0.3), (0.5, -0.3), (0.0, 0.4)]  # area 0.9 * 0.7 / 2 = 0.315 m^2

#: Each shape, and its area (m^2) by the schoolbook formula.
SHAPES: dict[str, tuple[Any, float]] = {
    "circle": (Circle((0, 0), 0.3), math.pi * 0.3**2),
    "box": (Polygon.box(1.2, 0.5), 1.2 * 0.5),
    "polygon": (Polygon(TRIANGLE), 0.9 * 0.7 / 2),
    "capsule": (Segment((-0.5, 0.1), (0.5, 0.1), radius=0.2), 0.2 * (math.pi * 0.2 + 2 * 1.0)),
}


@pytest.mark.parametrize("name", SHAPES)
@pytest.mark.parametrize("density", [0.25, 1.0, 7.3, 1000 / 3])
def test_mass_is_density_times_area_and_the_moment_is_that_mass_s(
    name: str, density: float
) -> None:
    shape, area = SHAPES[name]
    body = Body(Vector(0, 0), shape=shape, density=density)
    assert body.mass == pytest.approx(density * area, rel=1e-12, abs=0)
    by_mass = Body(Vector(0, 0), shape=shape, mass=density * shape.area)
    assert body.mass == by_mass.mass
    assert body.moment == by_mass.moment  # the same bits: the same code from the same mass
    assert body.density == density  # the one given, not mass / area rounded


def test_a_disc_made_with_radius_takes_its_density_as_a_circle_shape_does() -> None:
    disc = Body(Vector(0, 0), radius=0.3, density=2.0)
    assert disc.mass == Body(Vector(0, 0), shape=Circle((0, 0), 0.3), density=2.0).mass
    assert disc.moment == Body(Vector(0, 0), radius=0.3, mass=disc.mass).moment


def test_a_moment_given_stays_and_the_mass_comes_from_the_density() -> None:
    body = Body(Vector(0, 0), shape=Polygon.box(2, 1), density=3.0, moment=5.0)
    assert (body.mass, body.moment) == (6.0, 5.0)
    body.density = 1.0
    assert (body.mass, body.moment) == (2.0, 5.0)


def test_density_reads_mass_over_area_for_a_body_made_with_a_mass() -> None:
    body = Body(Vector(0, 0), shape=Polygon.box(2, 1), mass=3.0)
    assert body.density == 1.5
    assert Body(Vector(0, 0), radius=1.0, mass=math.pi).density == 1.0
    made = Body(Vector(0, 0), shape=Polygon.box(2, 1), density=0.7)
    made.mass = 5.0  # a mass set since: mass / area
    assert made.density == 2.5


def test_a_body_with_no_area_has_no_density() -> None:
    assert Body(Vector(0, 0)).density is None  # a point
    assert Body(1.0).density is None  # a 1D body
    assert Body(Vector(0, 0), shape=Segment((-1, 0), (1, 0))).density is None  # a line


@pytest.mark.parametrize("kernels", PATHS)
def test_setting_density_in_a_world_sets_the_mass_and_the_moment(kernels: str) -> None:
    world = World(kernels=kernels)
    box = world.add(Body(Vector(0, 0), shape=Polygon.box(2, 1), mass=1.0))
    box.density = 4.0
    twin = Body(Vector(0, 0), shape=Polygon.box(2, 1), mass=8.0)
    assert (box.mass, box.moment, box.density) == (8.0, twin.moment, 4.0)
    with pytest.raises(ValueError, match="density must be > 0"):
        box.density = 0.0
    assert (box.mass, box.density) == (8.0, 4.0)  # refused: the old one stays


def _drop(kernels: str, by: str, set_after: bool = False) -> World:
    """Each shape dropped, one over another, on a floor: made with a density, or with its
    mass (``by``: "density" or "mass"); ``set_after``: made with density 1 and given its
    density in the World before the first step."""
    world = World(kernels=kernels)
    world.add_force(Gravity((0.0, -9.81)))
    world.add_collider(Plane((0, 0), (0, 1)))
    for k, (name, (shape, _)) in enumerate(SHAPES.items()):
        density = 0.5 + k
        at = Vector(0.15 * k, 0.6 + 0.9 * k)
        if by == "mass":
            body = Body(at, shape=shape, mass=density * shape.area, friction=0.5)
        else:
            given = 1.0 if set_after else density
            body = Body(at, shape=shape, density=given, friction=0.5)
        world.add(body)
        if set_after:
            body.density = density
        # Held as given where it is centred, else about its centroid (engine.body_shapes).
        cx, cy = body.center_of_gravity
        assert body.shape is shape if (cx, cy) == (0, 0) else body.shape.area == shape.area, name
        assert (cx, cy) == pytest.approx(tuple(shape.centroid), abs=1e-12), name
    world.add(Body(Vector(0.3, 4.5), radius=0.25, **({by: 2.5} if by == "density" else {})))
    if by == "mass":
        world.bodies[-1].mass = 2.5 * math.pi * (0.25 * 0.25)
    for _ in range(90):
        world.step(1 / 60)
    return world


def _bits(world: World) -> list[tuple[float, ...]]:
    return [(*b.pos, *b.vel, b.angle, b.angular_velocity, b.mass, b.moment) for b in world.bodies]


@pytest.mark.parametrize("kernels", PATHS)
def test_a_scene_made_with_densities_steps_as_the_same_masses_do_bit_for_bit(kernels: str) -> None:
    by_mass = _bits(_drop(kernels, "mass"))
    assert _bits(_drop(kernels, "density")) == by_mass
    assert _bits(_drop(kernels, "density", set_after=True)) == by_mass
    assert max(abs(b[5]) for b in by_mass) > 0.0  # something turned: the moments mattered


@pytest.mark.parametrize("kernels", PATHS)
def test_snapshot_and_copy_keep_the_density(kernels: str) -> None:
    world = _drop(kernels, "density")
    box = world.bodies[1]
    snap = world.snapshot()
    mass, moment = box.mass, box.moment
    box.density = 9.0
    world.step(1 / 60)
    world.restore(snap)
    assert (box.density, box.mass, box.moment) == (1.5, mass, moment)
    twin = world.copy()
    assert [b.density for b in twin.bodies] == [b.density for b in world.bodies]
    for w in (world, twin):
        w.step(1 / 60)
    assert _bits(twin) == _bits(world)


# -- errors: each names the argument, the value and what to write ----------------------------


def test_mass_and_density_both_given_is_refused_with_what_to_write() -> None:
    with pytest.raises(ValueError) as refused:
        Body(Vector(0, 0), shape=Polygon.box(1, 1), mass=2.0, density=3.0)
    assert str(refused.value) == (
        "give a Body mass=... (kg) or density=... (kg/m^2: mass = density * the shape's area), "
        "not both: got mass=2.0 and density=3.0; write Body(..., mass=2.0) or "
        "Body(..., density=3.0)"
    )
    with pytest.raises(ValueError, match="not both: got mass=2 and density=3"):
        Body(Vector(0, 0), None, None, 2, shape=Polygon.box(1, 1), density=3)  # mass by place
    with pytest.raises(ValueError, match="not both: got mass=1.0 and density=3"):
        Body(Vector(0, 0), shape=Polygon.box(1, 1), mass=1.0, density=3)  # the default's value
    assert Body(Vector(0, 0), shape=Polygon.box(1, 1)).mass == 1.0  # neither: 1 kg


@pytest.mark.parametrize("bad", [0, -1.0, math.inf, -math.inf, math.nan, 10**400])
def test_a_density_not_positive_and_finite_is_refused(bad: Any) -> None:
    with pytest.raises(ValueError) as refused:
        Body(Vector(0, 0), shape=Polygon.box(1, 1), density=bad)
    assert str(refused.value) == (
        "density must be > 0 and finite (kg/m^2: the body's mass per square metre of its "
        f"shape, e.g. 1.0, Box2D's default), got {bad!r}"
    )


@pytest.mark.parametrize("bad", ["1.0", True, None])
def test_a_density_that_is_not_a_number_is_refused(bad: Any) -> None:
    box = Body(Vector(0, 0), shape=Polygon.box(1, 1), density=1.0)
    with pytest.raises(TypeError, match=r"density must be a real number \(kg/m\^2.*got"):
        box.density = bad
    if bad is not None:  # None at Body(...) is no density given: 1 kg
        with pytest.raises(TypeError, match=r"density must be a real number"):
            Body(Vector(0, 0), shape=Polygon.box(1, 1), density=bad)


GIVEN = "density=2.0 kg/m^2 gives the body a mass of density * its shape's area, and "


def test_density_on_a_point_says_to_give_a_shape_or_a_mass() -> None:
    with pytest.raises(ValueError) as refused:
        Body(Vector(0, 0), density=2.0)
    assert str(refused.value) == GIVEN + (
        "this body is a point (no shape, no radius), with no area: give it radius=... (a disc) "
        "or shape=... (a Polygon, a Circle, a Segment with a radius), or give mass=... (kg) "
        "instead"
    )
    point = Body(Vector(0, 0))
    with pytest.raises(ValueError) as refused:
        point.density = 2.0
    assert str(refused.value) == GIVEN + (
        "this body is a point (no shape, no radius), with no area: a Body's shape is fixed when "
        "it is made: set body.mass = ... (kg) instead"
    )
    assert point.mass == 1.0


def test_density_on_a_segment_without_a_radius_says_to_give_it_one() -> None:
    with pytest.raises(ValueError) as refused:
        Body(Vector(0, 0), shape=Segment((0, 0), (1, 0)), density=2.0)
    assert str(refused.value) == GIVEN + (
        "its shape Segment((0.0, 0.0), (1.0, 0.0)) is a line, with no area: give the Segment a "
        "radius (Segment(a, b, radius=0.05): a capsule), or give mass=... (kg) instead"
    )


def test_density_on_a_1d_body_says_to_give_a_mass() -> None:
    with pytest.raises(ValueError) as refused:
        Body(0.0, density=2.0)
    assert str(refused.value) == GIVEN + (
        "a 1D body (made of numbers) has no shape and no area: give mass=... (kg) instead"
    )


def test_a_density_whose_mass_leaves_the_float_range_is_refused() -> None:
    with pytest.raises(ValueError) as refused:
        Body(Vector(0, 0), shape=Polygon.box(1e10, 1e10), density=1e300)
    assert str(refused.value) == (
        "density=1e+300 kg/m^2 gives the body a mass of density * its shape's area, and 1e+300 "
        "* 1e+20 is inf kg, outside the float range (> 0 and finite): give a density nearer "
        "1.0, the shape in other length units, or give mass=... (kg) instead"
    )
