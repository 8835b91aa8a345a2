"""Bodies of several shapes (``Body(shapes=[...])``, engine.body_shapes) on the soft step: an L
of two boxes, a dumbbell of two discs. Checked against the closed forms (mass, centre and moment;
free rotation; the pose an L comes to rest in, flat or tipped by its centre of gravity; a
resting body's impulses m g dt), on both paths, and by what a game reads of them (events,
queries, frames' pixels, snapshots)."""

from __future__ import annotations

import math

import pygame
import pytest
import swings
from paths import PATHS

from engine import Body, Circle, Filter, Hinge, Plane, Polygon, Segment, Vector, World
from engine.forces import Gravity
from engine.render import Camera, draw_world

G = 9.81
BAR = [(0, 0), (2, 0), (2, 0.4), (0, 0.4)]


def post(height: float = 1.0) -> list[tuple[float, float]]:
    return [(0, 0.4), (0.4, 0.4), (0.4, 0.4 + height), (0, 0.4 + height)]


def ell(at: Vector, angle: float = 0.0, height: float = 1.0, **kw: object) -> Body:
    """The L: a 2 x 0.4 bar along +x from the origin, a 0.4 wide post of ``height`` on its left
    end; density 1."""
    return Body(at, shapes=[Polygon(BAR), Polygon(post(height))], density=1.0, angle=angle, **kw)


def floor_world(kernels: str) -> World:
    w = World(kernels=kernels)
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0, 0), (0, 1)))
    return w


def test_an_l_has_the_mass_centre_and_moment_of_its_parts() -> None:
    # Area 0.8 + 0.4; the centre sum A_i c_i / A = (0.8 (1, 0.2) + 0.4 (0.2, 0.9)) / 1.2; the
    # moment about it sum m_i (w_i^2 + h_i^2) / 12 + m_i |c_i - c|^2 (pymunk's numbers).
    L = ell(Vector(0, 0))
    cx, cy = (0.8 * 1.0 + 0.4 * 0.2) / 1.2, (0.8 * 0.2 + 0.4 * 0.9) / 1.2
    assert L.mass == pytest.approx(1.2, rel=1e-15)
    assert L.center_of_gravity.x == pytest.approx(cx, rel=1e-15)
    assert L.center_of_gravity.y == pytest.approx(cy, rel=1e-15)
    moment = 0.8 * (4 + 0.16) / 12 + 0.8 * ((1 - cx) ** 2 + (0.2 - cy) ** 2)
    moment += 0.4 * (0.16 + 1) / 12 + 0.4 * ((0.2 - cx) ** 2 + (0.9 - cy) ** 2)
    assert L.moment == pytest.approx(moment, rel=1e-12)
    assert L.pos == L.center_of_gravity and len(L.shapes) == 2
    # The parts are held about the centre; the frame's origin is where the body was put.
    assert L.shapes[0].vertices[0].x == pytest.approx(-cx, abs=1e-15)
    origin = L.local_to_world(-L.center_of_gravity)
    assert origin.length() < 1e-15
    # A mass given is spread over the parts by area: the same centre.
    heavy = Body(Vector(0, 0), shapes=[Polygon(BAR), Polygon(post())], mass=12.0)
    assert heavy.center_of_gravity == L.center_of_gravity
    assert heavy.moment == pytest.approx(10 * moment, rel=1e-12)


def test_a_hammer_takes_each_shape_s_own_density() -> None:
    # A 0.1 x 1 handle at density 1 and a 0.4 x 0.2 head on its top at density 10 (pymunk's
    # shape.density each): m_i = rho_i A_i, the centre sum m_i c_i / m, the moment about it.
    hammer = Body(Vector(0, 0), shapes=[Polygon.box(0.1, 1.0, center=(0, 0.5)),
                  Polygon.box(0.4, 0.2, center=(0, 1.1))], density=[1.0, 10.0])  # fmt: skip
    m1, m2 = 0.1, 0.8
    cy = (m1 * 0.5 + m2 * 1.1) / (m1 + m2)
    moment = m1 * (0.01 + 1) / 12 + m1 * (0.5 - cy) ** 2 + m2 * (0.16 + 0.04) / 12
    moment += m2 * (1.1 - cy) ** 2
    assert hammer.mass == pytest.approx(m1 + m2, rel=1e-14)
    assert hammer.center_of_gravity.y == pytest.approx(cy, rel=1e-14)
    assert abs(hammer.center_of_gravity.x) < 1e-15
    assert hammer.moment == pytest.approx(moment, rel=1e-12)
    assert hammer.density == pytest.approx((m1 + m2) / 0.18, rel=1e-14)  # mass / area
    with pytest.raises(ValueError, match="one for each shape: got 1 densities for 2 shapes"):
        Body(Vector(0, 0), shapes=[Polygon(BAR), Polygon(post())], density=[1.0])
    with pytest.raises(ValueError, match=r"density\[1\] must be > 0"):
        Body(Vector(0, 0), shapes=[Polygon(BAR), Polygon(post())], density=[1.0, 0.0])


def test_shapes_is_checked_and_the_errors_say_what_to_write() -> None:
    box = Polygon.box(1, 1)
    with pytest.raises(TypeError, match="shape=... .* or shapes=.*not both"):
        Body(Vector(0, 0), shape=box, shapes=[box])
    with pytest.raises(ValueError, match="at least one shape"):
        Body(Vector(0, 0), shapes=[])
    with pytest.raises(TypeError, match=r"shapes\[1\] must be a Circle, a Polygon"):
        Body(Vector(0, 0), shapes=[box, Plane((0, 0), (0, 1))])
    with pytest.raises(ValueError, match="at most 8"):
        Body(Vector(0, 0), shapes=[Polygon.box(1, 1, center=(k, 0)) for k in range(9)])
    with pytest.raises(ValueError, match="are the Body's"):
        Body(Vector(0, 0), shapes=[box, Polygon.box(1, 1, center=(1, 0), friction=0.1)])
    with pytest.raises(TypeError, match="a list of convex shapes"):
        Body(Vector(0, 0), shapes=box)
    # One shape in a list is that shape.
    assert Body(Vector(0, 0), shapes=[box]).shape is box


def test_the_exact_models_refuse_a_body_of_several_shapes_and_auto_chooses_the_soft_step() -> None:
    w = World(solver="exact")
    with pytest.raises(ValueError, match=r"soft step's alone.*World\(solver='soft'\)"):
        w.add(ell(Vector(0, 2)))
    assert not w.bodies  # refused whole
    auto = World()
    auto.add(ell(Vector(0, 2)))
    auto.step(1 / 60)
    assert auto.solver == "soft" and "2 shapes" in auto.solver_reason


@pytest.mark.parametrize("kernels", PATHS)
def test_a_free_dumbbell_spins_about_its_centre(kernels: str) -> None:
    # Two discs of radius 0.25 at (0, 0) and (2, 0): the centre (1, 0) stays put and the frame's
    # origin goes round it, (1 - cos w t, -sin w t); I = 2 (m_1 r^2 / 2 + m_1 1^2).
    w = World(kernels=kernels, solver="soft")
    d = w.add(Body(Vector(0, 0), shapes=[Circle((0, 0), 0.25), Circle((2, 0), 0.25)],
                   density=1.0, angular_velocity=3.0))  # fmt: skip
    m1 = math.pi * 0.25**2
    assert d.moment == pytest.approx(2 * (m1 * 0.25**2 / 2 + m1), rel=1e-12)
    for _ in range(100):
        w.step(1 / 60)
    assert d.pos == (1, 0)
    t = 100 / 60
    origin = d.local_to_world(-d.center_of_gravity)
    assert origin.x == pytest.approx(1 - math.cos(3 * t), abs=1e-12)
    assert origin.y == pytest.approx(-math.sin(3 * t), abs=1e-12)


@pytest.fixture(scope="module", params=PATHS)
def landed(request: pytest.FixtureRequest) -> tuple[str, World, Body, list[str]]:
    """An L dropped from 2 m tilted 0.1 rad onto a floor, stepped 4 s (the floor's begins)."""
    w = floor_world(request.param)
    L = w.add(ell(Vector(0, 2), angle=0.1, friction=0.6))
    began: list[str] = []
    w.on_contact(L, begin=lambda e: began.append(type(e.collider).__name__))
    for _ in range(240):
        w.step(1 / 60)
    return request.param, w, L, began


def test_an_l_dropped_tilted_lands_flat_on_its_bar(
    landed: tuple[str, World, Body, list[str]],
) -> None:
    _, w, L, began = landed
    assert abs(L.angle) < 1e-6
    # Its bar lies on the floor: the frame's origin (the bar's bottom left corner) at y = 0,
    # within the soft contact's give (LINEAR_SLOP, 5 mm; measured 7e-9 m).
    assert abs(L.local_to_world(-L.center_of_gravity).y) < 1e-6
    assert w.is_sleeping(L)
    # It met the floor on its corner first, which left it for a step as it turned down: two
    # begins, and it touches at the end.
    assert began == ["Plane", "Plane"] and [type(e.collider) for e in w.touching] == [Plane]


@pytest.mark.parametrize("kernels", PATHS)
def test_an_l_dropped_flat_begins_to_touch_once(kernels: str) -> None:
    # Both parts meet the floor in one step: the events are the body's (one begin for the L and
    # the floor, as for a box whose two corners meet it), and it stays.
    w = floor_world(kernels)
    L = w.add(ell(Vector(0, 1)))
    began: list[object] = []
    ended: list[object] = []
    w.on_contact(L, begin=lambda e: began.append(e.collider), end=ended.append)
    for _ in range(120):
        w.step(1 / 60)
    assert len(began) == 1 and isinstance(began[0], Plane) and ended == []


@pytest.mark.parametrize("kernels", PATHS)
def test_an_l_at_rest_is_held_by_its_weight(kernels: str) -> None:
    # Laid flat, sleep off: it stays where it is put, and the floor's impulses on it sum to
    # m g dt a step (each part's contact keeps its own warm start).
    w = floor_world(kernels)
    w.sleep_time = math.inf
    L = w.add(ell(Vector(0, 0), friction=0.6))
    start = L.pos
    for _ in range(120):
        w.step(1 / 60)
    assert (L.pos - start).length() < 1e-9 and abs(L.angle) < 1e-9
    push = sum(e.impulse.y for e in w.touching if e.body is L)
    assert push == pytest.approx(L.mass * G / 60, rel=1e-9)


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("height", [1.0, 0.1])
def test_an_l_stood_on_its_end_tips_only_if_its_centre_is_past_its_foot(
    kernels: str, height: float
) -> None:
    # Stood on the bar's end (turned -90 degrees), the post out to the right at the top. With a
    # post of 1 m the centre is at x = 0.433, past the foot's 0 to 0.4: it tips clockwise and
    # rests on its hull's edge from the bar's tip to the post's top, at -(pi - atan(1 / 1.6)).
    # With a post of 0.1 m the centre is at x = 0.2125, over the foot: it stands.
    w = World(kernels=kernels, solver="soft")
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Segment((-10, 0), (10, 0)))
    L = w.add(ell(Vector(0, 2), angle=-math.pi / 2, height=height, friction=0.6))
    for _ in range(300):
        w.step(1 / 60)
    want = -(math.pi - math.atan(1 / 1.6)) if height == 1.0 else -math.pi / 2
    assert L.angle == pytest.approx(want, abs=1e-6)  # (measured: 4e-9 rad, and 0)


@pytest.mark.parametrize("kernels", PATHS)
def test_an_l_thrown_at_a_thin_wall_does_not_pass_it(kernels: str) -> None:
    # At 200 m/s a step moves it 3.3 m, past the 2 cm wall: the continuous stage sweeps each of
    # its parts and sets it back to the first one's impact.
    w = World(kernels=kernels, solver="soft")
    w.add_collider(Segment((5, -5), (5, 5), 0.01))
    L = w.add(ell(Vector(0, 0), velocity=Vector(200.0, 0.0)))
    for _ in range(30):
        w.step(1 / 60)
    parts = [L.local_to_world(v).x for part in L.shapes for v in part.vertices]
    assert max(parts) < 5.0


@pytest.mark.parametrize("kernels", PATHS)
def test_queries_meet_each_part_and_name_the_body_once(kernels: str) -> None:
    w = World(kernels=kernels, solver="soft")
    L = w.add(ell(Vector(0, 0)))  # its bar from x 0 to 2, y 0 to 0.4; its post up to y 1.4
    w.step(1 / 60)
    assert [h.shape for h in w.point_query((0.2, 1.2), 0.0, Filter())] == [L]  # the post
    assert w.point_query((1.5, 1.2), 0.1, Filter()) == []  # beside the post, over the bar
    assert w.bb_query((0.1, 0.1, 0.3, 1.3), Filter()) == [L]  # both parts, one body
    hit = w.segment_query_first((-1, 1.0), (3, 1.0), 0.0, Filter())
    assert hit is not None and hit.shape is L and hit.point.x == pytest.approx(0.0, abs=1e-12)
    hit = w.segment_query_first((1.5, 3), (1.5, -1), 0.0, Filter())  # down onto the bar
    assert hit is not None and hit.point.y == pytest.approx(0.4, abs=1e-12)
    assert [h.shape for h in w.shape_query(Circle((1.9, 0.5), 0.2))] == [L]


def test_a_frame_shows_each_part() -> None:
    pygame.init()
    w = World(solver="soft")
    w.add(ell(Vector(0, 0), colour=(200, 30, 30)))
    surface = pygame.Surface((300, 300))
    surface.fill((255, 255, 255))
    camera = Camera(100.0, (50.0, 250.0))  # 100 px a metre, the origin 50 px in and up
    draw_world(surface, w, camera)

    def at(x: float, y: float) -> tuple[int, int, int]:
        return tuple(surface.get_at(camera.point((x, y))))[:3]  # type: ignore[return-value]

    assert at(1.5, 0.2) == (200, 30, 30)  # the bar
    assert at(0.2, 1.1) == (200, 30, 30)  # the post
    assert at(1.5, 1.1) == (255, 255, 255)  # the L's inner corner is empty


@pytest.mark.parametrize("kernels", PATHS)
def test_a_snapshot_of_a_falling_l_replays_to_the_bit(kernels: str) -> None:
    w = floor_world(kernels)
    L = w.add(ell(Vector(0, 2), angle=0.3))
    for _ in range(40):
        w.step(1 / 60)
    snap = w.snapshot()
    for _ in range(40):
        w.step(1 / 60)
    first = (tuple(L.pos), L.angle, tuple(L.vel), L.angular_velocity)
    w.restore(snap)
    for _ in range(40):
        w.step(1 / 60)
    assert (tuple(L.pos), L.angle, tuple(L.vel), L.angular_velocity) == first


def test_both_paths_step_an_l_on_a_pile_alike() -> None:
    pytest.importorskip("numba")
    ends = []
    for kernels in ("numpy", "fast"):
        w = floor_world(kernels)
        bodies = [ell(Vector(0, 1), angle=0.2), ell(Vector(0.5, 3), angle=-0.4)]
        bodies += [Body(Vector(x, 5), radius=0.2) for x in (0.2, 0.9, 1.6)]
        bodies.append(Body(Vector(1, 7), shape=Polygon.box(0.5, 0.5)))
        w.add_all(bodies)
        for _ in range(180):
            w.step(1 / 60)
        ends.append([(tuple(b.pos), b.angle) for b in w.bodies])
    assert ends[0] == ends[1]


@pytest.mark.parametrize("kernels", PATHS)
def test_a_sensor_l_feels_what_overlaps_a_part_and_overlap_measures_the_parts(
    kernels: str,
) -> None:
    # A sensor L over two balls: one in its post, one in its inner corner (inside the circle
    # that holds the L, touching neither part); world.overlap measures two solid Ls' parts.
    w = World(kernels=kernels, solver="soft")
    L = w.add(ell(Vector(0, 0), sensor=True))
    inside = w.add(Body(Vector(0.2, 1.0), radius=0.1))
    corner = w.add(Body(Vector(1.2, 1.0), radius=0.1))
    w.step(1 / 60)
    felt = {e.collider for e in w.touching if e.body is L} | {
        e.body for e in w.touching if e.collider is L
    }
    assert inside in felt and corner not in felt
    solid = World(kernels=kernels, solver="soft")
    solid.add(ell(Vector(0, 0)))
    solid.add(ell(Vector(0.5, 0.35)))  # its bar 5 cm into the first one's, beside its post
    assert solid.overlap() == pytest.approx(0.05, abs=1e-12)


@pytest.mark.parametrize("kernels", PATHS)
def test_an_l_hung_on_a_hinge_swings_about_it_as_a_physical_pendulum(kernels: str) -> None:
    # Hung from its frame's origin (the bar's outer corner), let go 0.05 rad from where its
    # centre hangs straight below: T = 2 pi sqrt(I_p / (m g d)) (1 + theta0^2 / 16), I_p the
    # moment about the pivot, I_c + m d^2, d = |c|.
    w = World(kernels=kernels, solver="soft")
    w.add_force(Gravity((0.0, -G)))
    probe = ell(Vector(0, 0))
    c = probe.center_of_gravity
    d = c.length()
    theta0 = 0.05
    # Turned so that the centre hangs at -pi/2 + theta0 from the pivot at the origin.
    angle = -math.pi / 2 + theta0 - math.atan2(c.y, c.x)
    L = w.add(ell(Vector(0, 0), angle=angle))
    w.add_link(Hinge(L, w.static_body, (0, 0)))
    period = 2 * math.pi * math.sqrt((probe.moment + probe.mass * d * d) / (probe.mass * G * d))
    period *= 1 + theta0**2 / 16
    crossings = swings.crossings(w, L, 1 / 240, 2.5 * period)
    assert len(crossings) >= 2
    assert crossings[1] - crossings[0] == pytest.approx(period, rel=2e-5)


@pytest.mark.parametrize("kernels", PATHS)
def test_a_kinematic_body_of_two_shapes_carries_what_rests_on_either(kernels: str) -> None:
    # A lift of two platforms drawn about its position (a kinematic body keeps its shapes as
    # drawn), going up at 0.5 m/s: a ball on each rides it, each 0.35 m over its platform's
    # middle (the platform's top 0.1 m over it, the ball's radius 0.25 m).
    w = World(kernels=kernels, solver="soft")
    w.add_force(Gravity((0.0, -G)))
    lift = w.add(Body(Vector(0, 0), Vector(0, 0.5), kinematic=True, shapes=[
        Polygon.box(1, 0.2, center=(-2, 0)), Polygon.box(1, 0.2, center=(2, 1))]))  # fmt: skip
    assert lift.center_of_gravity == (0, 0) and lift.shapes[1].vertices[0] == (1.5, 0.9)
    left = w.add(Body(Vector(-2, 0.35), radius=0.25))
    right = w.add(Body(Vector(2, 1.35), radius=0.25))
    for _ in range(120):
        w.step(1 / 60)
    assert lift.pos.y == pytest.approx(1.0, abs=1e-12)
    assert left.pos.y - lift.pos.y == pytest.approx(0.35, abs=1e-12)  # (it holds its load)
    assert right.pos.y - lift.pos.y == pytest.approx(1.35, abs=1e-12)
    assert abs(left.pos.x + 2) < 1e-9 and abs(right.pos.x - 2) < 1e-9
