"""The rigid-body scenes of the issue "Rigid bodies as Box2D's own tests expect", shared.

Each scene is built by one function and measured by another, which returns plain numbers:
tests/test_rigid_scenes.py asserts the issue's bounds on them, on each path (numpy, fast)
and with each solver (``path`` is ``"numpy"`` or ``"fast"`` for the exact solver, the World's
default, and ``"soft-numpy"`` or ``"soft-fast"`` for the game's soft step, ``solver="soft"``),
and a benchmark or a demo can run the same scene and print the same numbers.

Materials combine by product here (pymunk's rule, ``engine.geometry.colliders``), not as Box2D mixes
them (friction by the geometric mean, restitution by the larger). So a scene's bodies carry the
material the issue names (HelloWorld's box: restitution 0, friction 0.3) and the colliders the
product's identity, friction 1.0 (and restitution 1.0 where a scene bounces, 0 where it must
not): the pair then has the issue's numbers, 0.3 x 1.0 = 0.3. (Box2D's own HelloWorld leaves
its ground at the default friction 0.6, so its pair has sqrt(0.3 x 0.6) = 0.42; the test runs
that pair too, and the product of 0.3 on both sides, 0.09.) Two boxes of friction 0.6 meet at
0.36 here (0.6 in Box2D), as in demos.stack and the DESIGN's measured tower.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

from engine import Body, Plane, Polygon, Vector, World
from engine.forces import Gravity

DT = 1.0 / 60.0  # s, every scene's step
G = 9.81  # m/s^2, every scene's gravity but HelloWorld's (Box2D's 10)
#: The integrator every scene's World is made with: the closed form in flight, the soft step
#: in contact (the World's choice for a game's scene, as tests/test_rotation_shapes.py makes
#: them).
INTEGRATOR = "auto"


def world(kernels: str, gravity: float = G) -> World:
    """A World on the path ``kernels`` with gravity ``gravity`` (m/s^2) down (none at 0):
    ``"numpy"`` or ``"fast"`` with the exact solver, ``"soft-numpy"`` or ``"soft-fast"`` with
    the soft step (``solver="soft"``) on that path's kernels."""
    solver, _, path = kernels.rpartition("-")
    w = World(integrator=INTEGRATOR, kernels=path, solver=solver or "exact")
    if gravity:
        w.add_force(Gravity((0.0, -gravity)))
    return w


def run(w: World, steps: int) -> None:
    for _ in range(steps):
        w.step(DT)


# -- 1. Box2D's HelloWorld (test/test_world.c) ------------------------------------------------

HELLO_STEPS = 90


def hello_world(kernels: str, ground_friction: float = 1.0) -> tuple[World, Body]:
    """Box2D's HelloWorld: gravity -10, a static ground box 100 x 20 centred at (0, -10) (its
    top at y = 0; a static Polygon collider is this engine's static body with a shape), and a
    2 x 2 dynamic box of density 1 (4 kg), friction 0.3, restitution 0, dropped from y = 4.
    The ground's restitution is 0, its friction ``ground_friction`` (1.0: the pair's mu is the
    box's 0.3)."""
    w = world(kernels, gravity=10.0)
    w.add_collider(
        Polygon.box(100.0, 20.0, center=(0.0, -10.0), restitution=0.0, friction=ground_friction)
    )
    box = w.add(
        Body(Vector(0.0, 4.0), shape=Polygon.box(2.0, 2.0), mass=4.0, restitution=0.0,
             friction=0.3)
    )  # fmt: skip
    return w, box


@dataclass
class Hello:
    x: float  # m, at the end (Box2D: |x| < 0.01)
    y: float  # m, at the end (Box2D: |y - 1| < 0.01)
    angle: float  # rad, at the end (Box2D: |angle| < 0.01)
    landing_speed: float  # m/s, the fastest it fell
    bounce: float  # m, the most it rose after its lowest point so far, once it had landed
    drift: float  # m, the most |x| over the run
    tilt: float  # rad, the most |angle| over the run


def measure_hello_world(kernels: str, ground_friction: float = 1.0) -> Hello:
    w, box = hello_world(kernels, ground_friction)
    fastest = 0.0
    lowest = math.inf
    bounce = drift = tilt = 0.0
    for _ in range(HELLO_STEPS):
        w.step(DT)
        fastest = max(fastest, -box.vel.y)
        y = box.pos.y
        if y < 1.0 + 0.01:  # landed (within Box2D's bound of its resting height)
            lowest = min(lowest, y)
            bounce = max(bounce, y - lowest)
        drift = max(drift, abs(box.pos.x))
        tilt = max(tilt, abs(box.angle))
    return Hello(box.pos.x, box.pos.y, box.angle, fastest, bounce, drift, tilt)


# -- 2. A flat box dropped on a floor ----------------------------------------------------------

DROP_HEIGHT = 2.0  # m, the box's underside above the floor as it is let go
SIDE = 1.0  # m, a unit box


def dropped_box(kernels: str, restitution: float) -> tuple[World, Body]:
    """A unit box (1 kg, friction 0.5) lying flat, let go with its underside ``DROP_HEIGHT``
    above a floor (a Plane at y = 0, the body's restitution in force: the floor's is 1.0)."""
    w = world(kernels)
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    box = w.add(
        Body(Vector(0.0, DROP_HEIGHT + 0.5 * SIDE), shape=Polygon.box(SIDE, SIDE),
             restitution=restitution, friction=0.5)
    )  # fmt: skip
    return w, box


@dataclass
class Drop:
    landing_speed: float  # m/s
    rise: float  # m, the most it rose after its lowest point so far, once it had landed
    sideways: float  # m, the most |x| over the run
    tilt: float  # degrees, the most |angle| over the run
    apexes: list[float] = field(default_factory=list)  # m above the resting height (0.5 m)


def measure_drop(kernels: str, restitution: float, seconds: float = 3.0) -> Drop:
    """The dropped box over ``seconds``: how it landed and what it did after. The apexes are
    the highest points between landings (above its resting height, SIDE / 2), in order."""
    w, box = dropped_box(kernels, restitution)
    rest = 0.5 * SIDE
    fastest = 0.0
    lowest = math.inf
    rise = sideways = tilt = 0.0
    apexes: list[float] = []
    landed = False
    vy_before = 0.0
    for _ in range(round(seconds / DT)):
        w.step(DT)
        y, vy = box.pos.y, box.vel.y
        fastest = max(fastest, -vy)
        if y < rest + 0.01:
            landed = True
        if landed:
            lowest = min(lowest, y)
            rise = max(rise, y - lowest)
        # An apex: the vertical velocity turned from up to down within this step; the
        # parabola through it peaks (v^2 / 2g above the point where it turned).
        if landed and vy_before > 0.0 >= vy:
            apexes.append(y + vy * vy / (2.0 * G) - rest)
        vy_before = vy
        sideways = max(sideways, abs(box.pos.x))
        tilt = max(tilt, abs(math.degrees(box.angle)))
    return Drop(fastest, rise, sideways, tilt, apexes)


# -- 3. A tower of 20 unit boxes ---------------------------------------------------------------

TOWER = 20
TOWER_SECONDS = 60.0
TOWER_FRICTION = 0.6  # the boxes'; 0.6 on the floor (1.0), 0.36 box on box


def tower(kernels: str, count: int = TOWER) -> tuple[World, list[Body]]:
    """``count`` unit boxes (1 kg, friction 0.6, restitution 0) put in a column, each resting
    on the one below, on a floor (a Plane at y = 0); sleeping off."""
    w = world(kernels)
    w.sleep_time = math.inf
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    boxes = w.add_all(
        Body(Vector(0.0, 0.5 * SIDE + SIDE * k), shape=Polygon.box(SIDE, SIDE),
             restitution=0.0, friction=TOWER_FRICTION)
        for k in range(count)
    )  # fmt: skip
    return w, boxes


@dataclass
class Tower:
    sideways: float  # m, the top box's most |x| over the run
    sag: float  # m, how far the top box's centre is below where it was put, at the end
    lowest_box: float  # m, how far the bottom box sank
    tilt: float  # degrees, the most |angle| of any box at the end
    seconds: float  # s of wall time the run took


def measure_tower(kernels: str, seconds: float = TOWER_SECONDS) -> Tower:
    w, boxes = tower(kernels)
    top = boxes[-1]
    y0 = top.pos.y
    sideways = 0.0
    start = time.perf_counter()
    for _ in range(round(seconds / DT)):
        w.step(DT)
        sideways = max(sideways, abs(top.pos.x))
    spent = time.perf_counter() - start
    tilt = max(abs(math.degrees(b.angle)) for b in boxes)
    return Tower(sideways, y0 - top.pos.y, 0.5 * SIDE - boxes[0].pos.y, tilt, spent)


# -- 4. Friction: a box on a slope, a box sliding to a stop ------------------------------------

SLOPE_MU = 0.5


def slope(kernels: str, degrees: float, mu: float = SLOPE_MU) -> tuple[World, Body, Vector]:
    """A unit box (1 kg, friction ``mu``, restitution 0) lying at rest flat on a plane through
    the origin that rises at ``degrees``, its underside touching it; and the unit vector down
    the slope. Sleeping off: friction must hold it, not sleep (a sleeping body stays put)."""
    theta = math.radians(degrees)
    n = Vector(-math.sin(theta), math.cos(theta))
    w = world(kernels)
    w.sleep_time = math.inf
    w.add_collider(Plane((0.0, 0.0), (n.x, n.y)))
    box = w.add(
        Body(n * (0.5 * SIDE), shape=Polygon.box(SIDE, SIDE), friction=mu, restitution=0.0,
             angle=theta)
    )  # fmt: skip
    return w, box, Vector(-math.cos(theta), -math.sin(theta))


@dataclass
class Slide:
    moved: float  # m, how far the box's centre is from where it was put
    along: float  # m, its displacement down the slope
    want: float  # m, the closed form's displacement down the slope
    start: float  # s, the moment it started sliding (its first step with a speed)
    speed: float  # m/s, at the end


def measure_slope(kernels: str, degrees: float, seconds: float) -> Slide:
    """The box on the slope after ``seconds``: what it moved, and its displacement down the
    slope against g (sin - mu cos) (t - t0)^2 / 2 from the moment t0 it started sliding (the
    start of the first step after which it moves; 0 for a box let go at rest on a slope it
    slides down; the closed form's 0 where it should stay)."""
    w, box, down = slope(kernels, degrees)
    theta = math.radians(degrees)
    a = max(0.0, G * (math.sin(theta) - SLOPE_MU * math.cos(theta)))
    x0 = box.pos
    start = math.nan
    for _ in range(round(seconds / DT)):
        t = w.t
        w.step(DT)
        if math.isnan(start) and abs(box.vel) > 0.0:
            start = t
    t0 = 0.0 if math.isnan(start) else start
    return Slide(
        abs(box.pos - x0),
        (box.pos - x0).dot(down),
        0.5 * a * (w.t - t0) ** 2,
        start,
        abs(box.vel),
    )


SLIDE_SPEED = 5.0  # m/s


def slider(kernels: str, mu: float = SLOPE_MU) -> tuple[World, Body]:
    """A unit box (1 kg, friction ``mu``, restitution 0) resting flat on a floor (a Plane at
    y = 0), sliding along it at ``SLIDE_SPEED``."""
    w = world(kernels)
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    box = w.add(
        Body(Vector(0.0, 0.5 * SIDE), Vector(SLIDE_SPEED, 0.0), shape=Polygon.box(SIDE, SIDE),
             friction=mu, restitution=0.0)
    )  # fmt: skip
    return w, box


def measure_slider(kernels: str, seconds: float = 3.0) -> tuple[float, float, float]:
    """The sliding box after ``seconds`` (it stops at about 1 s): how far it went (m), the
    closed form's v0^2 / (2 mu g) (m), and its speed at the end (m/s)."""
    w, box = slider(kernels)
    run(w, round(seconds / DT))
    return box.pos.x, SLIDE_SPEED**2 / (2.0 * SLOPE_MU * G), abs(box.vel)


# -- 5. What the contacts of a box at rest report ----------------------------------------------


def resting_box(kernels: str) -> tuple[World, Body, Plane]:
    """A unit box (2 kg, restitution 0) put flat on a floor (a Plane at y = 0), at rest."""
    w = world(kernels)
    floor = w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    box = w.add(
        Body(Vector(0.0, 0.5 * SIDE), shape=Polygon.box(SIDE, SIDE), mass=2.0, restitution=0.0,
             friction=0.5)
    )  # fmt: skip
    return w, box, floor


@dataclass
class Report:
    resting_on: object  # what world.resting(box) names (the floor, or None)
    weight: Vector  # N s, m g dt up: what the floor must give the box over a step
    touching: Vector  # N s, the sum of the box's impulses in world.touching over the step
    post_solve: Vector  # N s, the sum of the impulses its post_solve handler got
    speed: float  # m/s, the box's speed after the step (at rest: about 0)


def measure_resting_box(kernels: str, settle: float = 1.0) -> tuple[Report, Plane]:
    """The box of ``resting_box`` with sleeping off, left ``settle`` s, then one step: what
    the World says it rests on and the impulses its contacts report over that step."""
    w, box, floor = resting_box(kernels)
    w.sleep_time = math.inf
    run(w, round(settle / DT))
    got: list[Vector] = []
    w.on_contact(box, post_solve=lambda event: got.append(event.impulse))
    w.step(DT)
    # The box is the only body: each contact of it lists it as ``body`` (the impulse is on it).
    touching = sum((e.impulse for e in w.touching if e.body is box), Vector(0.0, 0.0))
    report = Report(
        w.resting(box),
        Vector(0.0, box.mass * G * DT),
        touching,
        sum(got, Vector(0.0, 0.0)),
        abs(box.vel),
    )
    return report, floor


# -- 6. A box spinning in free space -----------------------------------------------------------


def spinner(kernels: str) -> tuple[World, Body]:
    """A 0.8 x 0.3 box (1.5 kg) moving at (1.2, -0.7) m/s and turning at 3 rad/s, off the
    origin, with no force and nothing to meet."""
    w = world(kernels, gravity=0.0)
    box = w.add(
        Body(Vector(2.0, 1.0), Vector(1.2, -0.7), shape=Polygon.box(0.8, 0.3), mass=1.5,
             angular_velocity=3.0, angle=0.4)
    )  # fmt: skip
    return w, box


def energy_and_momentum(box: Body) -> tuple[float, float]:
    """Kinetic energy (J) and angular momentum about the origin, m r x v + I omega (kg m^2/s)."""
    v, omega = box.vel, box.angular_velocity
    energy = 0.5 * box.mass * v.dot(v) + 0.5 * box.moment * omega * omega
    return energy, box.mass * box.pos.cross(v) + box.moment * omega


# -- 7. Sleep ----------------------------------------------------------------------------------


def crate_on_its_corner(kernels: str, off: float = 1.0) -> tuple[World, Body]:
    """A unit crate (1 kg, friction 0.6, restitution 0) let go at rest standing on one corner,
    turned ``off`` degrees from balance (45 degrees, its diagonal upright), its corner touching
    a floor (a Plane at y = 0); sleeping on (the World's default)."""
    w = world(kernels)
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    angle = math.radians(45.0 + off)
    # The lowest corner of a unit box turned by ``angle`` is sqrt(1/2) cos(angle - 45 deg)
    # below its centre (the corner at -135 degrees in its frame, turned to -90 + off), and
    # off to the right of it: the crate falls over that corner, counter-clockwise, to 90.
    h = math.sqrt(0.5) * math.cos(angle - math.radians(45.0))
    crate = w.add(
        Body(Vector(0.0, h), shape=Polygon.box(SIDE, SIDE), restitution=0.0, friction=0.6,
             angle=angle)
    )  # fmt: skip
    return w, crate


@dataclass
class Crate:
    off_flat: float  # degrees from the nearest multiple of 90 at the end
    angle: float  # degrees at the end
    asleep_at: float  # s, when it first slept (nan: never)
    height: float  # m, its centre above the floor at the end (0.5 lying flat)


def measure_crate(kernels: str, seconds: float = 5.0) -> Crate:
    w, crate = crate_on_its_corner(kernels)
    asleep_at = math.nan
    for _ in range(round(seconds / DT)):
        w.step(DT)
        if math.isnan(asleep_at) and w.is_sleeping(crate):
            asleep_at = w.t
    return Crate(quarter_turns_off(crate.angle), math.degrees(crate.angle), asleep_at, crate.pos.y)


def quarter_turns_off(angle: float) -> float:
    """How far (degrees) ``angle`` (rad) is from the nearest multiple of 90 degrees."""
    d = math.degrees(angle) % 90.0
    return min(d, 90.0 - d)


def disc_and_kinematic(kernels: str) -> tuple[World, Body, Body]:
    """A disc (r 0.5, 1 kg) put at rest on a floor, and a kinematic box held still beside it;
    sleeping on."""
    w = world(kernels)
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    disc = w.add(Body(Vector(0.0, 0.5), radius=0.5, restitution=0.0, friction=0.5))
    kin = w.add(Body(Vector(3.0, 0.5), shape=Polygon.box(SIDE, SIDE), kinematic=True))
    return w, disc, kin


#: A domino has begun to fall once it leans this far (rad); the wave reaches the next then.
LEANING = 0.05


@dataclass
class Dominoes:
    slept: list[float]  # s, when each first slept (nan: never)
    woke: list[float]  # s, when each first woke after it had slept (nan: never)
    leaning: list[float]  # s, when each first leant past LEANING (nan: never)
    asleep: int  # bodies asleep at the end


def measure_dominoes(kernels: str, seconds: float = 5.0) -> Dominoes:
    """demos.stack's dominoes (30, 0.1 by 1 m, 0.5 m apart, the first flicked at its top), on
    ``kernels`` (this module's path names), stepped for ``seconds``."""
    from demos.stack import dominoes

    solver, _, path = kernels.rpartition("-")
    w, row = dominoes(kernels=path, solver=solver or "exact")
    nan = math.nan
    slept, woke, leaning = [nan] * len(row), [nan] * len(row), [nan] * len(row)
    for _ in range(round(seconds / DT)):
        w.step(DT)
        for i, b in enumerate(row):
            if w.is_sleeping(b):
                slept[i] = w.t if math.isnan(slept[i]) else slept[i]
            elif not math.isnan(slept[i]) and math.isnan(woke[i]):
                woke[i] = w.t
            if math.isnan(leaning[i]) and abs(b.angle) > LEANING:
                leaning[i] = w.t
    return Dominoes(slept, woke, leaning, w.sleeping)


def crate_on_a_platform(kernels: str, shape: str) -> tuple[World, Body, Body]:
    """A 4 m by 0.5 m kinematic platform held still (its top at y = 0.25), and on it a unit
    crate (a box, or a disc of radius 0.5: ``shape``) put at rest, friction 0.6 (the
    platform's 1.0: the pair's is the crate's); sleeping on."""
    w = world(kernels)
    platform = w.add(
        Body(Vector(0.0, 0.0), shape=Polygon.box(4.0, 0.5), kinematic=True, friction=1.0)
    )
    made = {"shape": Polygon.box(SIDE, SIDE)} if shape == "box" else {"radius": 0.5 * SIDE}
    crate = w.add(Body(Vector(0.0, 0.75), restitution=0.0, friction=0.6, **made))
    return w, crate, platform
