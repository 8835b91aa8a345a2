"""The pinball table against pymunk: balls through flippers, and the step time of a game.

Run with ``python -m demos.bench pinball`` (``--quick``: fewer flips and a shorter game).

**Pass-throughs.** The table's left flipper alone (its shape, mass, hinge, limits and motor,
from ``demos.pinball``; the walls left out so that a ball can come from anywhere), under the
table's gravity, at the game's step of 1/120 s. Each trial throws one ball at it: at a speed
drawn from 1 to 40 m/s (100 to 4,000 cm/s), in a direction up to 60 degrees either side of
straight into the bat, aimed at a point along the bat's top (from a fifth of its length to its
tip), timed to arrive there (had the bat stayed at rest) at a moment drawn from 0 to 0.1 s;
the key is pressed at FLIP_AT = 0.03 s, so balls arrive before, during (the swing takes about
42 ms) and after the flip. A trial runs 0.15 s past the arrival.

A ball *passes through* when its centre crosses the bat's centre line between two steps at a
point within the bat's length (seen in the bat's frame at each step), or ends a step with its
centre inside the bat: a ball that goes round the tip does not count. The same trials (the
same draws) run in this engine and in pymunk 7 (its defaults: 10 iterations, collision slop
0.1 (here 1 mm), no continuous detection), each with the other's model of the same table
(``PymunkTable`` below); each pass is listed with the ball's speed, the bat's angular
velocity and when it arrived relative to the key. ``tunnelling(..., solver="soft")`` runs
the same trials on the soft step, where the game's ball, a bullet (``Body.bullet``), is swept
against the bat too; ``bullet=False`` shows what a ball that is none meets there.

**Step time.** The whole table in each engine, played by the same autopilot
(``demos.pinball.autopilot``) with the same rules (the kicks of bumpers and slingshots, the
plunger, the drain), timed as CPU seconds a step (the game's step: the controls, the physics,
the rules), each step timed alone, in rounds that alternate the engines; each engine's median
step, its ratio to pymunk's, its 99th percentile and its worst step (a hitch in play: a
game's 99th percentile should be at most 3x its median), and the share of a 60 fps frame
(16.7 ms) our two steps of 1/120 s take. The same game on the soft step
(``PinballGame(solver="soft")``, the game's own World on the exact models otherwise) is timed
in the same rounds. On the exact models a step in which the ball and a flipper (a body on a
hinge) meet in a blow (the ball falling onto it, or the bat swung up into the ball) is taken
again as 16 steps (engine.pipeline.stepping, ``SUBSTEPS_AT_IMPACT``): 17 times a step's work.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

import demos.pinball as pb
from engine import Vector, World
from engine.forces import Gravity

__all__ = [
    "FLIP_AT",
    "Pass",
    "Tunnelling",
    "PymunkTable",
    "PymunkGame",
    "tunnelling",
    "step_times",
    "report",
]

#: When the key is pressed in each trial (s).
FLIP_AT = 0.03
#: The fastest ball thrown (cm/s): 40 m/s.
TOP_SPEED = 4000.0


@dataclass(frozen=True)
class Pass:
    """A ball that went through the bat: its speed (cm/s), the bat's angular velocity (rad/s)
    and the joint's angle (rad) at the step it crossed, and when it was due relative to the
    key (s; > 0: after it was pressed)."""

    trial: int
    speed: float
    omega: float
    angle: float
    arrival: float
    inside: bool  # it ended a step with its centre inside the bat (not only crossed it)


@dataclass
class Tunnelling:
    """The pass-throughs of one engine over ``flips`` trials."""

    engine: str
    flips: int
    passes: list[Pass] = field(default_factory=list)
    hits: int = 0  # trials whose ball touched the bat at all (turned back or deflected)


def _trials(
    flips: int, seed: int, top_speed: float = TOP_SPEED
) -> list[tuple[float, float, float, float]]:
    """(speed cm/s, direction offset rad, aim along the bat cm, arrival s) for each trial."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(flips):
        speed = float(rng.uniform(0.0, 1.0)) * (top_speed - 100.0) + 100.0
        offset = float(rng.uniform(-1.0, 1.0)) * math.radians(60)
        aim = float(rng.uniform(0.2, 1.0)) * pb.FLIPPER_LENGTH
        out.append((speed, offset, aim, float(rng.uniform(0.0, 0.1))))
    return out


def _throw(aim_u: float, offset: float, speed: float, arrival: float) -> tuple[Vector, Vector]:
    """Where the ball starts and its velocity, to be at the aim point (on the left bat at
    rest, a ball's radius above its top) at ``arrival`` s under the table's gravity."""
    rest = -math.radians(pb.REST)
    along = Vector(math.cos(rest), math.sin(rest))
    up = Vector(-along.y, along.x)
    half = pb.FLIPPER_ROOT + (pb.FLIPPER_TIP - pb.FLIPPER_ROOT) * aim_u / pb.FLIPPER_LENGTH
    aim = Vector(*pb.LEFT_PIVOT) + along * aim_u + up * (half + pb.BALL_RADIUS)
    direction = (-up).rotate_rad(offset)
    vel = direction * speed
    g = Vector(0.0, -pb.GRAVITY)
    start = aim - vel * arrival - g * (0.5 * arrival * arrival)
    return start, vel


def _frame(pos: Vector, pivot: Vector, angle: float) -> tuple[float, float]:
    """A point in the bat's frame: (along the bat from the pivot, across it; + is the top)."""
    rel = pos - pivot
    c, s = math.cos(angle), math.sin(angle)
    return rel.x * c + rel.y * s, -rel.x * s + rel.y * c


def _crossed(trial: int, path: list[tuple[float, float, float, float, float]],
             speed: float, arrival: float) -> Pass | None:  # fmt: skip
    """The first pass of a ball through the bat along ``path`` (u, s, omega, joint angle,
    ball speed at each step), or None."""
    length = pb.FLIPPER_LENGTH
    for (u0, s0, *_), (u1, s1, omega, angle, _) in zip(path[:-1], path[1:], strict=True):
        half = (
            pb.FLIPPER_ROOT + (pb.FLIPPER_TIP - pb.FLIPPER_ROOT) * min(max(u1, 0), length) / length
        )
        inside = 0.0 <= u1 <= length and abs(s1) < half
        crossed = s0 > 0.0 >= s1 and 0.0 <= u0 + (u1 - u0) * s0 / (s0 - s1) <= length
        if inside or crossed:
            return Pass(trial, speed, omega, angle, arrival - FLIP_AT, inside)
    return None


def _ours(
    trials: list[tuple[float, float, float, float]], mass: float, solver: str = "exact",
    bullet: bool = True,
) -> Tunnelling:  # fmt: skip
    result = Tunnelling("this engine", len(trials))
    pivot = Vector(*pb.LEFT_PIVOT)
    for k, (speed, offset, aim_u, arrival) in enumerate(trials):
        world = World(integrator="auto", solver=solver, length_units_per_meter=pb.UNITS_PER_METER)
        world.add_force(Gravity((0.0, -pb.GRAVITY)))
        flipper, hinge = pb.add_flipper(world, -1, mass)
        start, vel = _throw(aim_u, offset, speed, arrival)
        ball = pb.add_ball(world, (start.x, start.y))
        ball.vel = vel
        ball.bullet = bullet
        touched: list[Any] = []
        world.on_contact(ball, begin=touched.append)
        path = [(*_frame(ball.pos, pivot, flipper.angle), 0.0, 0.0, speed)]
        for _ in range(round((arrival + 0.15) / pb.DT)):
            pb.drive(hinge, -1, world.t >= FLIP_AT - 1e-12)
            world.step(pb.DT)
            u, s = _frame(ball.pos, pivot, flipper.angle)
            path.append((u, s, flipper.angular_velocity, hinge.angle, ball.vel.length()))
        result.hits += bool(touched)
        found = _crossed(k, path, speed, arrival)
        if found is not None:
            result.passes.append(found)
    return result


# -- the same table in pymunk -----------------------------------------------------------------
class PymunkTable:
    """The table of ``demos.pinball`` built in a pymunk Space: the same walls, bumpers,
    slingshots, lanes, drain (sensors), flippers (a Poly on a body with the engine's mass and
    moment, a PivotJoint to the static body, a RotaryLimitJoint and a SimpleMotor with
    ``max_force`` = FLIP_TORQUE) and ball; materials multiply as in the engine. ``flippers``:
    which to build (the tunnelling trials take the left one alone, without the table)."""

    def __init__(self, table: bool = True, flippers: tuple[int, ...] = (-1, 1)) -> None:
        import pymunk

        self.pymunk = pymunk
        self.space = space = pymunk.Space()
        space.gravity = (0.0, -pb.GRAVITY)
        static = space.static_body
        wall_filter = pymunk.ShapeFilter(categories=pb.TABLE_BIT)
        self.kinds: dict[Any, str] = {}
        self.drain: Any = None
        if table:
            # The engine's own table, read back from a World (the one source of its geometry).
            probe = pb.build_table(World())
            shapes: list[Any] = []
            for wall in probe.walls:
                shapes.append(pymunk.Segment(static, tuple(wall.a), tuple(wall.b), wall.radius))
            for bumper in probe.bumpers:
                disc = pymunk.Circle(static, bumper.radius, tuple(bumper.center))
                self.kinds[disc] = "bumper"
                shapes.append(disc)
            for sling in probe.slings:
                c = pymunk.Segment(static, tuple(sling.a), tuple(sling.b), sling.radius)
                self.kinds[c] = "sling"
                shapes.append(c)
            for lane in probe.lanes:
                c = pymunk.Segment(static, tuple(lane.a), tuple(lane.b), lane.radius)
                c.sensor = True
                self.kinds[c] = "lane"
                shapes.append(c)
            d = probe.drain
            self.drain = pymunk.Segment(static, tuple(d.a), tuple(d.b), d.radius)
            self.drain.sensor = True
            shapes.append(self.drain)
            for shape in shapes:
                shape.elasticity, shape.friction, shape.filter = 1.0, 1.0, wall_filter
                shape.collision_type = 2
            space.add(*shapes)
        # The flippers, with the engine's mass and moment about the pivot.
        probe_world = World()
        self.flippers: list[Any] = []
        self.motors: list[Any] = []
        for side in flippers:
            body_e, _ = pb.add_flipper(probe_world, side)
            pivot = pb.LEFT_PIVOT if side < 0 else pb.RIGHT_PIVOT
            body = pymunk.Body(pb.FLIPPER_MASS, body_e.moment)
            body.position, body.angle = pivot, body_e.angle
            poly = pymunk.Poly(body, [tuple(v) for v in body_e.shape.vertices])
            poly.elasticity, poly.friction = pb.FLIPPER_RESTITUTION, pb.FLIPPER_FRICTION
            poly.filter = pymunk.ShapeFilter(categories=pb.FLIPPER_BIT, mask=pb.BALL_BIT)
            swing = math.radians(pb.SWING)
            lo, hi = (0.0, swing) if side < 0 else (-swing, 0.0)
            limit = pymunk.RotaryLimitJoint(static, body, body_e.angle + lo, body_e.angle + hi)
            # SimpleMotor(a, b, rate) keeps b.w - a.w at -rate: with a the flipper and b the
            # static body, the flipper turns at +rate.
            motor = pymunk.SimpleMotor(body, static, side * pb.FLIP_SPEED)
            motor.max_force = pb.FLIP_TORQUE
            space.add(body, poly, pymunk.PivotJoint(static, body, pivot), limit, motor)
            self.flippers.append(body)
            self.motors.append(motor)
        self.ball = pymunk.Body(
            pb.BALL_MASS, pymunk.moment_for_circle(pb.BALL_MASS, 0, pb.BALL_RADIUS)
        )
        self.ball.position = pb.PLUNGER_REST
        ball_shape = pymunk.Circle(self.ball, pb.BALL_RADIUS)
        ball_shape.elasticity, ball_shape.friction = pb.BALL_RESTITUTION, pb.BALL_FRICTION
        ball_shape.filter = pymunk.ShapeFilter(categories=pb.BALL_BIT)
        ball_shape.collision_type = 1
        space.add(self.ball, ball_shape)
        self.began: list[tuple[Any, Vector]] = []

        def begin(arbiter: Any, space: Any, data: Any) -> None:
            other = arbiter.shapes[1]
            n = arbiter.normal  # from the ball (shape a) to the other
            self.began.append((other, Vector(-n.x, -n.y)))

        space.on_collision(1, 2, begin=begin)

    def drive(self, k: int, side: int, up: bool) -> None:
        """Flipper k's motor, as ``demos.pinball.drive``."""
        self.motors[k].rate = (-side if up else side) * pb.FLIP_SPEED


class _Ball:
    """The pymunk ball read as the autopilot reads the engine's: pos and vel as Vectors."""

    def __init__(self, body: Any) -> None:
        self.body = body

    @property
    def pos(self) -> Vector:
        return Vector(*self.body.position)

    @property
    def vel(self) -> Vector:
        return Vector(*self.body.velocity)


class PymunkGame:
    """``demos.pinball.PinballGame``'s rules on a ``PymunkTable``: what the autopilot reads
    (``ball``, ``t``, ``memory``, ``rng``, ``on_plunger``, ``pulled``) and ``step(dt)``."""

    def __init__(self, seed: int = 1) -> None:
        self.table = PymunkTable()
        self.rng = np.random.default_rng(seed)
        self.memory: dict[str, Any] = {}
        self.ball = _Ball(self.table.ball)
        self.on_plunger, self.pulled, self.t, self.points, self.drained = True, 0.0, 0.0, 0, 0

    def step(self, dt: float) -> None:
        controls = pb.autopilot(self)  # type: ignore[arg-type]
        self.table.drive(0, -1, controls.left)
        self.table.drive(1, 1, controls.right)
        body = self.table.ball
        if self.on_plunger:
            if controls.pull:
                self.pulled = min(self.pulled + dt, pb.PULL_TIME)
            elif self.pulled > 0.0:
                frac = self.pulled / pb.PULL_TIME
                speed = pb.PLUNGE_MIN + (pb.PLUNGE_MAX - pb.PLUNGE_MIN) * frac
                body.apply_impulse_at_local_point((0.0, pb.BALL_MASS * speed))
                self.pulled, self.on_plunger = 0.0, False
        self.table.space.step(dt)
        self.t += dt
        began, self.table.began = self.table.began, []
        x, y = body.position
        if not self.on_plunger and x > pb.WIDTH and y < pb.PLUNGER_REST[1] + 1.0:
            self.on_plunger = body.velocity.length < 10.0
        for shape, normal in began:
            kind = self.table.kinds.get(shape)
            if kind is not None:
                self.points += pb.POINTS[kind]
                if kind != "lane":
                    kick = pb.BUMPER_KICK if kind == "bumper" else pb.SLING_KICK
                    along = self.ball.vel.dot(normal)
                    if along < kick:
                        j = normal * (pb.BALL_MASS * (kick - along))
                        body.apply_impulse_at_world_point((j.x, j.y), body.position)
            elif shape is self.table.drain and not self.on_plunger:
                self.drained += 1
                body.position, body.velocity, body.angular_velocity = pb.PLUNGER_REST, (0, 0), 0
                self.on_plunger, self.pulled = True, 0.0


def _pymunk(trials: list[tuple[float, float, float, float]]) -> Tunnelling:
    result = Tunnelling("pymunk", len(trials))
    pivot = Vector(*pb.LEFT_PIVOT)
    for k, (speed, offset, aim_u, arrival) in enumerate(trials):
        table = PymunkTable(table=False, flippers=(-1,))
        flipper, ball = table.flippers[0], table.ball
        start, vel = _throw(aim_u, offset, speed, arrival)
        ball.position, ball.velocity = (start.x, start.y), (vel.x, vel.y)
        touched: list[int] = []

        def touch(arbiter: Any, space: Any, data: list[int]) -> None:
            data.append(1)

        table.space.on_collision(1, None, begin=touch, data=touched)
        rest = flipper.angle
        path = [(*_frame(Vector(*ball.position), pivot, flipper.angle), 0.0, 0.0, speed)]
        t = 0.0
        for _ in range(round((arrival + 0.15) / pb.DT)):
            table.drive(0, -1, t >= FLIP_AT - 1e-12)
            table.space.step(pb.DT)
            t += pb.DT
            u, s = _frame(Vector(*ball.position), pivot, flipper.angle)
            path.append((u, s, flipper.angular_velocity, flipper.angle - rest,
                         ball.velocity.length))  # fmt: skip
        result.hits += bool(touched)
        found = _crossed(k, path, speed, arrival)
        if found is not None:
            result.passes.append(found)
    return result


def tunnelling(
    flips: int = 1000,
    seed: int = 26,
    engine: str = "ours",
    top_speed: float = TOP_SPEED,
    mass: float = pb.FLIPPER_MASS,
    *,
    solver: str = "exact",
    bullet: bool = True,
) -> Tunnelling:
    """Throw ``flips`` balls at the flipper as it flips (module doc), in ``engine`` ("ours"
    or "pymunk"), at speeds up to ``top_speed`` (cm/s), and return the passes. Ours only:
    ``mass`` the bat's (g), the motor's torque scaled with it; ``solver`` the World's (the
    game's exact one, or "soft"); ``bullet`` whether the ball is one (the game's is: on the
    soft step it is swept against the bat too, engine.Body.bullet)."""
    trials = _trials(flips, seed, top_speed)
    return _ours(trials, mass, solver, bullet) if engine == "ours" else _pymunk(trials)


def throw(trial: int, flips: int = 1000, seed: int = 26) -> Tunnelling:
    """Trial ``trial`` of ``tunnelling(flips, seed)`` alone, in this engine."""
    return _ours([_trials(flips, seed, TOP_SPEED)[trial]], pb.FLIPPER_MASS)


def step_times(seconds: float = 20.0, rounds: int = 5, seed: int = 1) -> dict[str, np.ndarray]:
    """The CPU seconds of each game step of the whole table, ours ("ours": the game's World,
    the exact models; "soft": the same game on the soft step) and pymunk's, in rounds of
    ``seconds`` of game each, in turn (each game continues from round to round): every step
    timed alone, so that a step's median, its 99th percentile and its worst can be read."""
    ours, soft, theirs = pb.PinballGame(seed), pb.PinballGame(seed, solver="soft"), PymunkGame(seed)
    steps = round(seconds / pb.DT)
    samples: dict[str, list[float]] = {"ours": [], "soft": [], "pymunk": []}
    runs: list[tuple[str, Callable[[], None]]] = [
        ("ours", lambda: ours.step(pb.DT)),
        ("soft", lambda: soft.step(pb.DT)),
        ("pymunk", lambda: theirs.step(pb.DT)),
    ]
    for _, fn in runs:  # warm up (the fast path's kernels load)
        for _ in range(10):
            fn()
    clock = time.process_time
    for r in range(rounds):
        for name, fn in runs if r % 2 == 0 else runs[::-1]:
            times = samples[name]
            for _ in range(steps):
                start = clock()
                fn()
                times.append(clock() - start)
            if name == "ours" and ours.score.over:
                ours = pb.PinballGame(seed + r + 1)  # a new game when one ends
            if name == "soft" and soft.score.over:
                soft = pb.PinballGame(seed + r + 1, solver="soft")
    return {name: np.array(s) for name, s in samples.items()}


def fastest_ball(seconds: float = 60.0, seed: int = 1) -> float:
    """The fastest the ball goes (cm/s, at the end of any step) in ``seconds`` of the game
    played by the autopilot (new games as each ends)."""
    game, top = pb.PinballGame(seed), 0.0
    for _ in range(round(seconds / pb.DT)):
        game.step(pb.DT)
        top = max(top, game.ball.vel.length())
        if game.score.over:
            seed += 1
            game = pb.PinballGame(seed)
    return top


def contact_step(trial: int, seed: int = 26) -> tuple[float, float, float, float]:
    """Trial ``trial`` of ``tunnelling`` in this engine, up to the step in which the ball's
    contact with the bat begins: (the ball's speed into the bat before that step, after it
    (cm/s, along the bat's normal at its top; > 0: still approaching), the bat's angular
    velocity after it (rad/s), and the joint's angle (rad))."""
    speed, offset, aim_u, arrival = _trials(trial + 1, seed)[trial]
    world = World(integrator="auto", solver="exact")  # the game's (demos.pinball)
    world.add_force(Gravity((0.0, -pb.GRAVITY)))
    flipper, hinge = pb.add_flipper(world, -1)
    start, vel = _throw(aim_u, offset, speed, arrival)
    ball = pb.add_ball(world, (start.x, start.y))
    ball.vel = vel
    touched: list[Any] = []
    world.on_contact(ball, begin=touched.append)
    before = 0.0
    for _ in range(round((arrival + 0.15) / pb.DT)):
        pb.drive(hinge, -1, world.t >= FLIP_AT - 1e-12)
        up = Vector(-math.sin(flipper.angle), math.cos(flipper.angle))
        before = -ball.vel.dot(up)
        world.step(pb.DT)
        if touched:
            up = Vector(-math.sin(flipper.angle), math.cos(flipper.angle))
            return before, -ball.vel.dot(up), flipper.angular_velocity, hinge.angle
    raise ValueError(f"the ball of trial {trial} never touched the bat")


def report(quick: bool = False) -> str:
    """The pass-throughs and the step times, ours beside pymunk's."""
    flips = 100 if quick else 1000
    lines = [
        f"pinball: {flips} balls thrown at a flipper as it flips (1 to 40 m/s, arriving "
        f"0 to 0.1 s after the throw, the key at {FLIP_AT} s), dt = 1/{round(1 / pb.DT)} s",
    ]
    heavy = 10 * pb.FLIPPER_MASS
    for engine, mass in (("ours", pb.FLIPPER_MASS), ("pymunk", pb.FLIPPER_MASS), ("ours", heavy)):
        result = tunnelling(flips, engine=engine, mass=mass)
        name = (
            result.engine if mass == pb.FLIPPER_MASS else f"{result.engine}, a bat of {mass:.0f} g"
        )
        lines.append(
            f"  {name}: passed through: {len(result.passes)} of {flips} "
            f"(touched the bat: {result.hits})"
        )
        fastest = sorted(result.passes, key=lambda p: p.speed)
        for p in fastest[:3] + (["..."] if len(fastest) > 6 else []) + fastest[3:][-3:]:  # type: ignore[operator]
            if isinstance(p, str):
                lines.append("      ...")
                continue
            lines.append(
                f"      trial {p.trial}: {p.speed / 100:.1f} m/s, bat at {p.omega:+.1f} rad/s "
                f"and {math.degrees(p.angle):.0f} deg, due {1000 * p.arrival:+.0f} ms from the key"
                f"{' (ended inside)' if p.inside else ''}"
            )
        if result.passes:
            slowest = min(result.passes, key=lambda p: p.speed)
            lines.append(f"      the slowest that passed: {slowest.speed / 100:.1f} m/s")
            if engine == "ours" and mass == pb.FLIPPER_MASS:
                into, after, omega, angle = contact_step(slowest.trial)
                lines.append(
                    f"      its step of contact: into the bat at {into / 100:.2f} m/s before, "
                    f"{after / 100:.2f} m/s after (> 0: still approaching), the bat then at "
                    f"{omega:+.1f} rad/s and {math.degrees(angle):.1f} deg"
                )
    top = fastest_ball(10.0 if quick else 60.0)
    lines.append(
        f"  the game's own ball, {'10' if quick else '60'} s of autopilot play: at most "
        f"{top / 100:.2f} m/s"
    )
    times = step_times(seconds=5.0 if quick else 20.0, rounds=3 if quick else 5)
    median = {name: float(np.median(t)) for name, t in times.items()}
    theirs = median["pymunk"]
    frame = 1.0 / 60.0
    per_frame = round(frame / pb.DT)
    lines += [
        "",
        f"pinball: a game step of the whole table (CPU time of each step, "
        f"{3 if quick else 5} rounds of {'5' if quick else '20'} s of autopilot play each, "
        f"in turn)",
    ]
    names = {"ours": "this engine (exact)", "soft": "on the soft step", "pymunk": "pymunk"}
    for name, label in names.items():
        t = times[name]
        p99, worst = float(np.percentile(t, 99)), float(t.max())
        ratio = "" if name == "pymunk" else f", {median[name] / theirs:.0f}x pymunk's"
        lines.append(
            f"  {label:20s} median {1e6 * median[name]:6.0f} us{ratio}; 99th percentile "
            f"{1e6 * p99:6.0f} us ({p99 / median[name]:.1f}x its median), worst "
            f"{1e3 * worst:.1f} ms"
        )
    ours, soft = median["ours"], median["soft"]
    share = 100 * per_frame / frame
    lines.append(
        f"  a 60 fps frame ({per_frame} steps): {per_frame * 1e3 * ours:.2f} ms of physics "
        f"(the median), {share * ours:.0f}% of the frame (on the soft step {share * soft:.0f}%, "
        f"pymunk {share * theirs:.1f}%)"
    )
    return "\n".join(lines)
