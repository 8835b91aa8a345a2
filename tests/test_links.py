"""Links (engine.dynamics.links): rods hold their length, cables at most theirs, pins their point.

Each behaviour is checked against physics: the length a rod holds after every step, the
tension of a pendulum against m g + m v^2 / L, momentum and angular momentum of a spinning
pair in free space, a cable's free fall while slack, a pinned body as immovable as a wall.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import pytest

from engine import Body, Box, Cable, OverlapWarning, Pin, Rod, StabilityWarning, Vector, World
from engine.forces import Gravity
from engine.pipeline import stepping

G = 9.81
DT = 1.0 / 240.0


def ball(x: float, y: float, vx: float = 0.0, vy: float = 0.0, **kw: float) -> Body:
    return Body(Vector(x, y), Vector(vx, vy), Vector(0, 0), **kw)  # type: ignore[arg-type]


def gravity_world(integrator: str = "auto") -> World:
    world = World(integrator=integrator)
    world.add_force(Gravity((0.0, -G)))
    return world


def distance(link: Rod | Cable) -> float:
    other = link.other
    end = other.pos if isinstance(other, Body) else other
    return float((link.body.pos - end).length())


@pytest.mark.parametrize("integrator", ["auto", "semi_implicit_euler", "velocity_verlet", "rk4"])
def test_a_rod_holds_its_length_after_every_step(integrator: str) -> None:
    world = gravity_world(integrator)
    bob = world.add(ball(0.6, -0.8, 3.0, 1.0))
    rod = world.add_link(Rod(bob, (0.0, 0.0)))
    assert rod.length == pytest.approx(1.0, rel=1e-15)
    worst = 0.0
    for _ in range(10_000):
        world.step(DT)
        worst = max(worst, abs(distance(rod) - 1.0))
    assert worst <= 1e-9  # the bound; the solver's own is 1e-12
    # ... and the velocity is along the circle: no speed along the rod.
    assert abs(bob.vel.dot(bob.pos)) <= 1e-9 * bob.vel.length()


def test_a_pendulum_keeps_its_energy_and_its_period() -> None:
    # 90 degrees: the exact period is 4 sqrt(L/g) K(sin 45 deg) (K by the AGM).
    world = gravity_world()
    bob = world.add(ball(1.0, 0.0))
    world.add_link(Rod(bob, (0.0, 0.0)))
    a, b = 1.0, math.sqrt(1.0 - 0.5)
    for _ in range(30):
        a, b = (a + b) / 2.0, math.sqrt(a * b)
    period = 4.0 * math.sqrt(1.0 / G) * math.pi / (2.0 * a)
    crossings, x_prev, t_prev = [], bob.pos.x, 0.0
    while world.t < 5.2 * period:
        world.step(DT)
        x = bob.pos.x
        if x_prev > 0.0 >= x:
            crossings.append(t_prev + DT * x_prev / (x_prev - x))
        x_prev, t_prev = x, world.t
    measured = (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    assert measured == pytest.approx(period, rel=1e-4)
    # Energy (0 at the start): RATTLE's error stays bounded, a small fraction of m g L.
    assert abs(world.energy()) <= 1e-3 * G


def test_tension_is_m_g_at_rest_and_m_g_plus_m_v2_over_l_at_the_bottom() -> None:
    world = gravity_world()
    bob = world.add(ball(0.0, -2.0, mass=3.0))
    rod = world.add_link(Rod(bob, (0.0, 0.0)))
    for _ in range(10):
        world.step(DT)
    assert rod.tension(DT) == pytest.approx(3.0 * G, rel=1e-9)
    assert bob.pos.y == pytest.approx(-2.0, rel=1e-12)
    # Swinging through the bottom at speed v: T = m g + m v^2 / L, to the step's resolution.
    bob.vel = Vector(4.0, 0.0)
    world.step(DT)
    v = bob.vel.length()
    assert rod.tension(DT) == pytest.approx(3.0 * G + 3.0 * v * v / 2.0, rel=2e-3)


def test_a_spinning_pair_in_free_space_keeps_momentum_and_angular_momentum() -> None:
    world = World(integrator="auto")
    a = world.add(ball(-1.0, 0.0, 0.3, 2.0, mass=1.0))
    b = world.add(ball(2.0, 0.0, 0.3, -0.5, mass=4.0))
    world.add_link(Rod(a, b))

    def totals() -> tuple[float, float, float, float]:
        p = a.vel * a.mass + b.vel * b.mass
        lz = sum(x.mass * (x.pos.x * x.vel.y - x.pos.y * x.vel.x) for x in (a, b))
        e = sum(0.5 * x.mass * x.vel.length() ** 2 for x in (a, b))
        return p.x, p.y, lz, e

    before = totals()
    for _ in range(5_000):
        world.step(DT)
    after = totals()
    assert after[0] == pytest.approx(before[0], abs=1e-12)
    assert after[1] == pytest.approx(before[1], abs=1e-12)
    assert after[2] == pytest.approx(before[2], rel=1e-6)
    assert after[3] == pytest.approx(before[3], rel=1e-6)
    assert (a.pos - b.pos).length() == pytest.approx(3.0, rel=1e-12)


def test_a_slack_cable_does_nothing_and_a_taut_one_holds() -> None:
    world = gravity_world()
    bob = world.add(ball(0.0, 0.0))
    cable = world.add_link(Cable(bob, (0.0, 0.0), 1.0))
    # Slack: free fall, exactly the closed form, until the cable's length is reached.
    steps = 0
    while world.t + DT < math.sqrt(2.0 / G) - DT:
        world.step(DT)
        steps += 1
        assert bob.pos.y == pytest.approx(-0.5 * G * world.t**2, rel=1e-12, abs=1e-15)
        assert cable.impulse == 0.0
    # Taut, with restitution 0: it stops the fall and holds the bob at its length.
    for _ in range(480):
        world.step(DT)
        assert distance(cable) <= 1.0 + 1e-12
    assert bob.pos.y == pytest.approx(-1.0, rel=1e-12)
    assert bob.vel.length() <= 1e-9
    assert cable.tension(DT) == pytest.approx(G, rel=1e-9)


def test_an_elastic_cable_bounces_back_with_the_speed_it_snapped_at() -> None:
    world = gravity_world()
    bob = world.add(ball(0.0, 0.0))
    world.add_link(Cable(bob, (0.0, 0.0), 1.0, restitution=1.0))
    highest_after, down = -2.0, True
    for _ in range(int(0.9 / DT)):
        world.step(DT)
        assert distance(world.links[0]) <= 1.0 + 1e-12  # type: ignore[arg-type]
        if bob.vel.y > 0.0:
            down = False
        if not down:
            highest_after = max(highest_after, bob.pos.y)
    assert not down
    # It climbs back to where it fell from, up to the step's error in the snap.
    assert highest_after == pytest.approx(0.0, abs=0.02)


def test_a_pinned_body_is_an_anchor_that_nothing_moves() -> None:
    world = gravity_world()
    anchor = world.add(ball(5.0, 5.0, 3.0, 3.0, radius=0.5, restitution=1.0))
    world.add_link(Pin(anchor, (0.0, 0.0)))
    assert anchor.pos == Vector(0.0, 0.0) and anchor.vel == Vector(0.0, 0.0)
    bob = world.add(ball(1.0, 0.0, radius=0.1))
    world.add_link(Rod(bob, anchor))
    # A ball thrown at the pinned one bounces as off a wall (infinite mass), e = 1 * 1.
    shot = world.add(ball(0.0, 3.0, 0.0, -10.0, radius=0.5, restitution=1.0))
    world.remove_link(world.links[1])
    world.remove(bob)
    speed_before: float | None = None
    for _ in range(60):
        if shot.pos.y > 1.2:
            speed_before = math.hypot(shot.vel.x, shot.vel.y)
        world.step(DT)
        assert anchor.pos == Vector(0.0, 0.0)
    assert shot.vel.y > 0.0  # it came back up
    assert speed_before is not None
    # Energy of the shot alone is kept (the anchor took none of it).
    e_now = 0.5 * shot.vel.length() ** 2 + G * shot.pos.y
    assert e_now == pytest.approx(0.5 * 10.0**2 + G * 3.0, rel=1e-9)


def test_a_chain_from_a_pin_holds_every_link() -> None:
    world = gravity_world()
    bobs = world.add_all(ball(0.3 * k, 0.0) for k in range(8))
    world.add_link(Pin(bobs[0], (0.0, 0.0)))
    rods = [world.add_link(Rod(bobs[k], bobs[k + 1])) for k in range(7)]
    for _ in range(2_400):
        world.step(DT)
        assert max(abs(distance(r) - 0.3) for r in rods) <= 1e-9 * 0.3
    assert bobs[0].pos == Vector(0.0, 0.0)
    # The chain hangs below its pin and moved (it swung down from horizontal).
    assert bobs[-1].pos.y < -0.5


def test_removing_a_body_takes_its_links_with_it() -> None:
    world = gravity_world()
    a, b, c = world.add_all([ball(0, 0), ball(1, 0), ball(2, 0)])
    world.add_link(Rod(a, b))
    keep = world.add_link(Rod(b, c))
    world.add_link(Pin(a, (0.0, 0.0)))
    world.remove(a)
    assert world.links == (keep,)
    world.step(DT)  # the rest still steps
    assert distance(keep) == pytest.approx(1.0, rel=1e-12)


def test_snapshot_and_restore_bring_back_the_links() -> None:
    world = gravity_world()
    a, b = world.add_all([ball(1, 0), ball(2, 0)])
    world.add_link(Rod(a, (0.0, 0.0)))
    snap = world.snapshot()
    for _ in range(50):
        world.step(DT)
    first = (a.pos, b.pos)
    world.restore(snap)
    for _ in range(50):
        world.step(DT)
    assert (a.pos, b.pos) == first  # bit for bit
    extra = world.add_link(Rod(b, a))
    world.restore(snap)
    assert extra not in world.links and len(world.links) == 1


def test_a_link_flung_past_what_a_step_holds_is_warned_and_still_held() -> None:
    world = gravity_world()
    bob = world.add(ball(0.0, -1.0))
    rod = world.add_link(Rod(bob, (0.0, 0.0)))
    bob.vel = Vector(1e4, 0.0)  # 40 m in one step on a 1 m rod
    with pytest.warns(StabilityWarning, match="smaller dt"):
        world.step(DT)
    assert distance(rod) == pytest.approx(1.0, rel=1e-9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        world.step(DT)  # warned once per link


@pytest.mark.parametrize(
    ("make", "error", "match"),
    [
        (lambda a, b: Rod(a, a), ValueError, "itself"),
        (lambda a, b: Rod(a, (0.0, 0.0)), ValueError, "one point"),
        (lambda a, b: Rod(a, b, length=0.0), ValueError, "length must be > 0"),
        (lambda a, b: Rod(a, b, length=math.nan), ValueError, "length must be finite"),
        (lambda a, b: Rod(a, (math.nan, 0.0)), ValueError, "other must be finite"),
        (lambda a, b: Rod(a, "b"), TypeError, "other must be a Body or a point"),
        (lambda a, b: Rod("a", b), TypeError, "body must be a Body"),
        (lambda a, b: Rod(Body(0.0, 0.0, 0.0), b), TypeError, "2D body"),
        (lambda a, b: Cable(a, b, None), TypeError, "length must be a real number"),
        (lambda a, b: Cable(a, b, 1.0, restitution=2.0), ValueError, "restitution"),
        (lambda a, b: Pin(a, b), TypeError, "use a Rod"),
        (lambda a, b: Pin(a, (math.inf, 0.0)), ValueError, "point must be finite"),
    ],
)
def test_bad_links_are_clear_errors(make, error, match) -> None:  # type: ignore[no-untyped-def]
    a, b = ball(0.0, 0.0), ball(1.0, 0.0)
    with pytest.raises(error, match=match):
        make(a, b)


def test_add_link_refuses_what_cannot_be_linked() -> None:
    world = World()
    a = world.add(ball(0, 0))
    outside = ball(1, 0)
    with pytest.raises(ValueError, match="must be in this World"):
        world.add_link(Rod(a, outside))
    with pytest.raises(TypeError, match="add_link takes a link"):
        world.add_link("rod")  # type: ignore[arg-type]
    rod = world.add_link(Rod(a, (1.0, 0.0)))
    with pytest.raises(ValueError, match="already in this World"):
        world.add_link(rod)
    world.add_link(Pin(a, (0.0, 0.0)))
    with pytest.raises(ValueError, match="pinned already"):
        world.add_link(Pin(a, (1.0, 1.0)))
    paddle = world.add(ball(3, 0, kinematic=True))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="kinematic"):
        world.add_link(Pin(paddle, (0.0, 0.0)))
    assert len(world.links) == 2  # the refusals changed nothing
    with pytest.raises(ValueError, match="not in this World"):
        world.remove_link(Rod(a, (5.0, 0.0)))


def test_links_in_a_world_step_as_arrays_without_nan() -> None:
    # Many pendulums at once, random starts: every length held, nothing non-finite.
    rng = np.random.default_rng(4)
    world = gravity_world()
    for _ in range(50):
        angle = rng.uniform(-3.0, 3.0)
        length = rng.uniform(0.2, 3.0)
        bob = world.add(
            ball(length * math.sin(angle), -length * math.cos(angle), *rng.uniform(-5, 5, 2))
        )
        world.add_link(Rod(bob, (0.0, 0.0)))
    for _ in range(500):
        world.step(DT)
    assert np.isfinite(world.positions()).all()
    assert max(abs(distance(r) / r.length - 1.0) for r in world.links) <= 1e-9  # type: ignore[arg-type]


def hung_cradle(dt: float) -> tuple[list[float], float, float]:
    """Five touching balls (e = 1) on rods of 1 m; the first let go from 30 degrees. Returns
    the balls' speeds just after the blow, the last ball's energy then over the first's just
    before it (kinetic + potential, from the lowest point), and the longest rod error."""
    radius, length = 0.1, 1.0
    world = gravity_world()
    balls, rods = [], []
    for k in range(5):
        top = Vector(2.0 * radius * k, 0.0)
        angle = math.radians(30.0) if k == 0 else 0.0
        start = top + Vector(-math.sin(angle), -math.cos(angle)) * length
        b = world.add(
            Body(start, Vector(0, 0), Vector(0, 0), radius=radius, restitution=1.0, friction=0.0)
        )
        rods.append(world.add_link(Rod(b, top)))
        balls.append(b)

    def energy(b: Body) -> float:  # per kg, from the lowest point
        return 0.5 * b.vel.length() ** 2 + G * (b.pos.y + length)

    e_first = 0.0
    while abs(balls[4].vel.x) < 0.5:
        e_first = energy(balls[0])  # as it comes in (the method's own energy error included)
        world.step(dt)
    speeds = [b.vel.length() for b in balls]
    worst = max(abs(distance(r) - length) for r in rods)
    return speeds, energy(balls[4]) / e_first, worst


def test_a_cradle_hung_on_rods_passes_the_blow_down_the_row() -> None:
    # The blow is found on the step's free path and the rods act after it, so a step in
    # which a linked body is struck is taken again in 16 parts (README: "Links"): the last
    # ball leaves with the first one's speed (from its energy, at the bottom) to 1e-6.
    for dt in (1.0 / 240.0, 1.0 / 960.0):
        speeds, ratio, worst = hung_cradle(dt)
        assert max(speeds[:4]) <= 1e-6
        assert abs(math.sqrt(ratio) - 1.0) <= 1e-6
        assert worst <= 1e-12
    # The error left is second order: 4 times smaller steps, about 16 times smaller error.
    coarse = abs(hung_cradle(1.0 / 60.0)[1] - 1.0)
    fine = abs(hung_cradle(1.0 / 240.0)[1] - 1.0)
    assert 8.0 <= coarse / fine <= 32.0


def bob_and_ball(drop: float) -> tuple[World, Body, Body]:
    """A bob of radius 0.1 m at rest on a 1 m rod from the origin, and a free ball of its size
    above it, ``drop`` m over touching."""
    world = gravity_world()
    bob = world.add(ball(0.0, -1.0, radius=0.1))
    world.add_link(Rod(bob, (0.0, 0.0)))
    top = world.add(ball(0.0, -0.8 + drop, radius=0.1))
    return world, bob, top


def test_only_a_blow_to_a_linked_body_takes_its_step_again(monkeypatch: pytest.MonkeyPatch) -> None:
    # The step is taken again in 16 parts for a blow (the cradle above; a bat swung into a
    # ball: the README's pinball core), not for a contact that begins at rest, which took
    # 17 steps' work for nothing.
    taken: list[int] = []
    step_once = stepping._step_once

    def counted(*args: Any, **kwargs: Any) -> None:
        taken.append(1)
        step_once(*args, **kwargs)

    monkeypatch.setattr(stepping, "_step_once", counted)

    def steps_taken(drop: float) -> list[int]:
        world, _, _ = bob_and_ball(drop)
        per_step = []
        for _ in range(40):
            taken.clear()
            world.step(1.0 / 60.0)
            per_step.append(len(taken))
        return per_step

    assert steps_taken(0.0) == [1] * 40  # set down touching: it begins to touch at rest
    dropped = steps_taken(0.3)  # dropped from 0.3 m: struck after about 0.25 s
    assert dropped.count(1 + stepping.SUBSTEPS_AT_IMPACT) == 1
    assert dropped.count(1) == 39


@pytest.mark.xfail(
    strict=True,
    reason="the exact models' links act after the pile's contacts: a ball resting on a bob "
    "hung from a rod sits 9 mm inside it, its velocity read as -2 g dt, still (found 2026-12-07)",
)
def test_a_ball_rests_on_a_bob_hung_from_a_rod() -> None:
    world, bob, top = bob_and_ball(0.0)
    for _ in range(120):
        world.step(1.0 / 60.0)
    assert abs((top.pos - bob.pos).length() - 0.2) <= 1e-6
    assert top.vel.length() <= 1e-6


def test_a_snapshot_restores_into_a_world_built_afresh_and_brings_back_a_removed_link() -> None:
    def build() -> tuple[World, Rod]:
        world = gravity_world()
        a, b = world.add_all([ball(1, 0), ball(2, 0)])
        rod = world.add_link(Rod(a, (0.0, 0.0)))
        world.add_link(Cable(b, a, 1.5, restitution=0.5))
        return world, rod

    first, rod = build()
    for _ in range(30):
        first.step(DT)
    snap = first.snapshot()
    for _ in range(30):
        first.step(DT)
    ahead = first.positions().copy(), rod.impulse
    # A fresh World with the same bodies and links takes the snapshot: its own links stay.
    second, rod2 = build()
    second.restore(snap)
    assert second.links[0] is rod2
    assert rod2.impulse == pytest.approx(snap.links[0][2], rel=0.0)
    for _ in range(30):
        second.step(DT)
    assert np.array_equal(second.positions(), ahead[0]) and rod2.impulse == ahead[1]
    # In the first World a link taken out comes back as the same object.
    first.remove_link(rod)
    first.restore(snap)
    assert first.links[0] is rod


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "auto"])
@pytest.mark.parametrize("speed", [120.0, 200.0, 400.0])
def test_a_cable_end_flung_past_its_anchor_in_one_step_is_caught_at_its_length(
    integrator: str, speed: float
) -> None:
    # Slack as the step begins (0.9 m below a 1 m cable's anchor), the body passes the anchor
    # and would end far above it: the cable snaps taut above, as a rod there would hold it.
    w = World(integrator=integrator)
    w.add_force(Gravity((0.0, -9.81)))
    b = w.add(Body(Vector(0.0, -0.9), Vector(0.01, speed), Vector(0.0, 0.0)))
    w.add_link(Cable(b, (0.0, 0.0), length=1.0))
    w.step(1 / 60)
    assert abs(b.pos.magnitude() - 1.0) <= 1e-9 and b.pos.y > 0.0
    # It stopped parting from the anchor (restitution 0): no speed outward along the cable.
    assert b.vel.dot(b.pos.normalize()) <= 1e-9
    for _ in range(30):
        w.step(1 / 60)
        assert b.pos.magnitude() <= 1.0 + 1e-9


def test_a_chain_of_cables_flung_past_its_anchor_is_caught_at_its_length() -> None:
    # Two cables sharing a body (solved together in arrays): the same across the anchor.
    w = World()
    a = w.add(Body(Vector(0.0, -0.5), Vector(0.0, 200.0), Vector(0.0, 0.0)))
    b = w.add(Body(Vector(0.0, -1.2), Vector(0.0, 200.0), Vector(0.0, 0.0)))
    w.add_link(Cable(a, (0.0, 0.0), length=1.0))
    w.add_link(Cable(b, a, length=1.0))
    with pytest.warns(StabilityWarning, match="smaller dt"):
        w.step(1 / 60)  # far past what one step can pull back along the links: said so
    for _ in range(5):
        assert a.pos.magnitude() <= 1.0 + 1e-9
        assert (b.pos - a.pos).magnitude() <= 1.0 + 1e-9
        assert a.pos.y > 0.0 and b.pos.y > a.pos.y  # caught above, in order
        w.step(1 / 60)


def test_writing_pos_of_a_pinned_body_is_refused_and_a_freed_one_goes_nowhere_it_was_sent() -> None:
    w = World()
    b = w.add(Body(Vector(0.0, 2.0), Vector(0.0, 0.0), Vector(0.0, 0.0), radius=0.05))
    pin = w.add_link(Pin(b, b.pos))
    with pytest.raises(ValueError, match="pinned"):
        b.pos = Vector(1.0, -4.0)
    assert b.pos == Vector(0.0, 2.0)
    w.remove_link(pin)
    w.step(1 / 240)
    assert b.pos == Vector(0.0, 2.0) and b.vel == Vector(0.0, 0.0)  # free, unmoved


def test_a_body_freed_from_its_pin_inside_a_collider_is_pushed_out() -> None:
    # A room was added around a pinned body, its wall through it (a pinned body is held, not
    # pushed); taking the pin out frees it there: it is pushed out, as a teleport is.
    w = World()
    b = w.add(Body(Vector(6.8, 2.0), Vector(0.0, 0.0), Vector(0.0, 0.0), radius=0.5))
    pin = w.add_link(Pin(b, b.pos))
    w.add_collider(Box((-7.0, -12.0), (7.0, 12.0)))
    assert b.pos == Vector(6.8, 2.0)
    with pytest.warns(OverlapWarning, match="was freed"):
        w.remove_link(pin)
    assert b.pos.x == pytest.approx(6.5) and w.colliders[0].distance(b.pos) >= 0.5 - 1e-12


def test_a_body_its_rod_held_in_a_wall_is_pushed_out_when_the_rod_goes_with_its_partner() -> None:
    w = World()
    a = w.add(Body(Vector(7.5, 0.0), Vector(0.0, 0.0), Vector(0.0, 0.0), radius=0.2))
    b = w.add(Body(Vector(5.5, 0.0), Vector(0.0, 0.0), Vector(0.0, 0.0), radius=0.2))
    w.add_link(Rod(a, b))
    with pytest.warns(OverlapWarning):
        w.add_collider(Box((-8.0, -8.0), (7.0, 8.0)))
    w.step(1 / 240)  # the rod, acting after the contacts, holds a 2 m from b: in the wall
    assert w.colliders[0].distance(a.pos) < 0.2
    with pytest.warns(OverlapWarning, match="was freed"):
        w.remove(b)
    assert w.colliders[0].distance(a.pos) >= 0.2 - 1e-12
