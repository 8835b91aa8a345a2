"""Fuzzing scenes of many bodies that collide with one another (issue "Contacts II").

Scenes: 2 to 10 discs with radii within a factor of 10 of each other or of 1000, masses over
six decades (1e-3 to 1e3), restitution in [0, 1], friction in [0, 2], pymunk filters (groups,
categories, masks, a ghost that meets nothing), with and without gravity, with and without
static colliders (a Box room; a Plane, a Segment and a Circle among the balls), under "auto",
"semi_implicit_euler" and "velocity_verlet", at dt = 1/60 for 1 s (piles: 4 s). The balls
start apart and head for the middle at up to 1, 3 or 20 times the scene's size a second.
Every step of every test checks that no nan or inf enters the state.

What holds, with the tolerances kept (each measured over 300 to 2,000 scenes):

* momentum, without gravity or colliders: to 1e-12 of sum |m v| (measured <= 1.2e-15),
  mass ratios up to 1e6 included; under gravity alone, it changes by M g t to 1e-12;
* kinetic energy, without gravity, never grows (1e-12 of the first, for rounding; measured
  0 over 400 scenes, masses over six decades included), and in MODERATE scenes (masses
  within a decade, restitution >= 0.8, at most 3 sizes a second; in a room or not) neither;
* an overlap past 5% of the smallest radius is warned about (a StabilityWarning) by the
  next step;
* a pile falls asleep overlapping at most 1% of the smaller radius of any pair (measured
  <= 0.35%; the engine's SLOP is 0.2%, and a body sleeps only within 0.75% of its radius),
  and a sleeping body stays exactly where it is, at rest;
* no body ends a step inside a solid collider (past 1e-9 (1 + |x|)): a Box room's walls,
  and pegs, segments and planes among the balls (measured over 300 scenes; a ball pressed
  into the corner of a peg and a wall is put at the corner);
* without gravity or colliders, two worlds filtered apart never exchange momentum (each
  keeps its own to 1e-12), and a ghost that meets nothing keeps its velocity bit for bit;
* elastic balls in a row meet in time order: one step ends where their impacts taken one at a
  time, the earliest first, put them, to 1e-9 m;
* a scene reruns bit for bit; a snapshot taken mid-run replays bit for bit, in the same World
  and in a new one.

What does not hold today: each test marked xfail(strict=True) names the engine bug in its
reason and keeps the scenes that show it as @examples (hypothesis runs the @examples first
and stops at the first failure, so such a test costs one scene; once the bug is fixed, the
strict marker fails the test, and removing the marker lets the whole fuzz run again).
In violent scenes there is no overlap tolerance to state: balls pass through each other.
Scenes of bugs fixed since stay as @examples of their tests, against a regression.

Examples: 120 + 40 + 50 + 100 + 40 + 40 + 25 + 40 + 80 + 80 + 45 = 660 generated scenes in the
eleven tests that pass; about 50 s on a 2-core machine.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from fuzzing import fuzz
from hypothesis import example, given
from hypothesis import strategies as st
from paths import PATHS

from engine import Body, Box, Circle, Collider, Filter, Plane, Segment, Vector, World
from engine.forces import Gravity
from engine.stability import StabilityWarning

G = 9.81
DT = 1 / 60
METHODS = ("auto", "semi_implicit_euler", "velocity_verlet")

#: The filters a ball may carry (an index into this tuple). 0 to 4, in most scenes: most
#: balls meet everyone; two share a group; two meet only some categories; one (a ghost)
#: meets nothing, colliders included. 5 to 8, in the scenes of two worlds in one: 5 and 6
#: meet only each other (and 6 never 6: a group), 7 and 8 the same among themselves.
FILTERS = (
    Filter(),
    Filter(group=1),
    Filter(categories=0b001, mask=0b001),
    Filter(categories=0b010, mask=0b011),
    Filter(categories=0b100, mask=0),
    Filter(categories=0b01000, mask=0b01000),
    Filter(group=5, categories=0b01000, mask=0b01000),
    Filter(categories=0b10000, mask=0b10000),
    Filter(group=6, categories=0b10000, mask=0b10000),
)
#: Filters of the first world (the ghost, 4, meets nothing, so it goes with either).
FIRST = (4, 5, 6)

#: A ball: x, y, vx, vy, radius, mass, restitution, friction, filter (index into FILTERS).
Ball = tuple[float, float, float, float, float, float, float, float, int]
#: A scene: balls, colliders, gravity (bool), method, steps.
Scene = dict[str, Any]

unit = st.floats(0.0, 1.0)
friction = st.floats(0.0, 2.0)


@st.composite
def ball_sets(
    draw: st.DrawFn,
    n: tuple[int, int] = (2, 10),
    spreads: tuple[float, ...] = (1.0, 10.0, 1000.0),
    mass_decades: float = 6.0,
    speeds: tuple[float, ...] = (1.0, 3.0, 20.0),
    restitution: st.SearchStrategy[float] = unit,
    filters: tuple[int, ...] = (0, 0, 0, 0, 1, 1, 2, 3, 4),
) -> tuple[list[Ball], float]:
    """Balls in a square of half side L around the origin, heading for its centre at up to
    ``speed`` L per second; (balls, L). Radii 0.2 * spread**u; masses 10**(+-mass_decades / 2);
    friction in [0, 2]. A ball that would overlap an earlier one moves out until it fits."""
    count = draw(st.integers(*n))
    spread = draw(st.sampled_from(spreads))
    speed = draw(st.sampled_from(speeds))
    half = mass_decades / 2.0
    raw = draw(
        st.lists(
            st.tuples(
                unit,  # radius exponent
                st.floats(-1.0, 1.0),
                st.floats(-1.0, 1.0),  # position, in units of L
                st.floats(-1.0, 1.0),
                st.floats(-1.0, 1.0),  # velocity jitter, in units of speed
                st.floats(-half, half),  # log10 of the mass
                restitution,
                friction,
                st.sampled_from(filters),
            ),
            min_size=count,
            max_size=count,
        )
    )
    radii = [0.2 * spread**u for u, *_ in raw]
    L = 0.7 * math.sqrt(sum((2.0 * r) ** 2 for r in radii)) + max(radii)
    balls: list[Ball] = []
    for r, (_, px, py, jx, jy, lm, e, mu, f) in zip(radii, raw, strict=True):
        x, y = px * L, py * L
        # Where it overlaps a ball placed before, it moves out from the centre till it fits.
        ux, uy = (px, py) if math.hypot(px, py) > 0.1 else (1.0, 0.5)
        while any(math.hypot(x - b[0], y - b[1]) <= r + b[4] for b in balls):
            x, y = x + 0.2 * ux * L, y + 0.2 * uy * L
        # Toward the centre, plus a jitter: bodies meet, often several at once.
        vx = speed * L * (0.5 * jx - px)
        vy = speed * L * (0.5 * jy - py)
        balls.append((x, y, vx, vy, r, 10.0**lm, e, mu, f))
    L = max(max(abs(b[0]) + b[4], abs(b[1]) + b[4]) for b in balls)
    return balls, L


def room_and_pegs(draw: st.DrawFn, balls: list[Ball], L: float, pegs: bool) -> list[Collider]:
    """A Box room around the square of half side L, and maybe a Plane, a Segment and a
    Circle among the balls (each left out where it would touch a ball)."""
    m = 0.3 * L
    room = Box((-L - m, -L - m), (L + m, L + m), restitution=draw(unit), friction=draw(friction))
    if not pegs:
        return [room]
    a = draw(st.floats(-0.3, 0.3))
    x0, x1 = draw(st.floats(-1.0, -0.1)), draw(st.floats(0.1, 1.0))
    more: list[Collider] = [
        Plane(
            (0.0, -L), (math.sin(a), math.cos(a)), restitution=draw(unit), friction=draw(friction)
        ),
        Segment(
            (x0 * L, draw(st.floats(-0.5, 0.5)) * L),
            (x1 * L, draw(st.floats(-0.5, 0.5)) * L),
            draw(st.sampled_from([0.0, 0.05 * L])),
            restitution=draw(unit),
            friction=draw(friction),
        ),
        Circle(
            (draw(st.floats(-0.6, 0.6)) * L, draw(st.floats(-0.6, 0.6)) * L),
            draw(st.floats(0.05, 0.3)) * L,
            restitution=draw(unit),
            friction=draw(friction),
        ),
    ]
    clear = [c for c in more if all(c.distance((b[0], b[1])) > b[4] for b in balls)]
    return [room, *clear]


@st.composite
def scenes(
    draw: st.DrawFn,
    gravity: bool | None = None,
    colliders: bool | None = None,
    pegs: bool | None = None,
    steps: int = 60,
    **balls: Any,
) -> Scene:
    """A scene (None: drawn): the balls, maybe a room with pegs, gravity, a method."""
    bs, L = draw(ball_sets(**balls))
    if colliders is None:
        colliders = draw(st.booleans())
    if pegs is None:
        pegs = draw(st.booleans())
    return {
        "balls": bs,
        "colliders": room_and_pegs(draw, bs, L, pegs) if colliders else [],
        "gravity": draw(st.booleans()) if gravity is None else gravity,
        "method": draw(st.sampled_from(METHODS)),
        "steps": steps,
    }


@st.composite
def rows(draw: st.DrawFn) -> Scene:
    """Balls on the x axis moving along it (no gravity, no colliders, every pair collides):
    radii 0.1 * spread**u, gaps up to 3 radii, speeds up to 1, 10 or 50 m/s either way,
    masses over six decades."""
    count = draw(st.integers(2, 8))
    spread = draw(st.sampled_from((1.0, 10.0, 1000.0)))
    speed = draw(st.sampled_from((1.0, 10.0, 50.0)))
    balls: list[Ball] = []
    x = 0.0
    for _ in range(count):
        r = 0.1 * spread ** draw(unit)
        x += r + draw(st.floats(0.0, 3.0)) * r
        v = speed * draw(st.floats(-1.0, 1.0))
        balls.append(
            (x, 0.0, v, 0.0, r, 10.0 ** draw(st.floats(-3.0, 3.0)), draw(unit), draw(friction), 0)
        )
        x += r
    return {
        "balls": balls,
        "colliders": [],
        "gravity": False,
        "method": draw(st.sampled_from(METHODS)),
        "steps": 60,
    }


def build(scene: Scene, keep: Callable[[Ball], bool] | None = None) -> tuple[World, list[Body]]:
    """The scene's World (balls for which ``keep`` is False left out)."""
    w = World(integrator=scene["method"])
    if scene["gravity"]:
        w.add_force(Gravity((0.0, -G)))
    for c in scene["colliders"]:
        w.add_collider(c)
    bodies = [
        Body(
            Vector(x, y),
            Vector(vx, vy),
            Vector(0.0, 0.0),
            mass=m,
            radius=r,
            restitution=e,
            friction=mu,
            filter=FILTERS[f],
        )
        for x, y, vx, vy, r, m, e, mu, f in scene["balls"]
        if keep is None or keep((x, y, vx, vy, r, m, e, mu, f))
    ]
    w.add_all(bodies)
    return w, bodies


def step(world: World) -> None:
    """One step of DT; the state stays finite."""
    world.step(DT)
    assert np.isfinite(world.positions()).all() and np.isfinite(world.velocities()).all()


class Probe:
    """Measures of a World's bodies: overlaps of pairs that collide, depth in colliders,
    momentum."""

    def __init__(self, world: World, bodies: list[Body], colliders: list[Collider]) -> None:
        self.world = world
        self.bodies = bodies
        self.r = np.array([b.radius for b in bodies])
        self.m = np.array([b.mass for b in bodies])
        self.meets = np.array(
            [[a is not b and a.filter.collides(b.filter) for b in bodies] for a in bodies],
            dtype=bool,
        ).reshape(len(bodies), len(bodies))
        self.rmin = np.minimum.outer(self.r, self.r)
        self.R = np.add.outer(self.r, self.r)
        self.solid = [c for c in colliders if not c.sensor]

    def overlaps(self) -> np.ndarray:
        """(N, N): how deep each pair that collides overlaps, in its smaller radius (else -inf)."""
        X = self.world.positions()
        D = np.sqrt(((X[:, None, :] - X[None, :, :]) ** 2).sum(axis=2))
        return np.where(self.meets, (self.R - D) / self.rmin, -np.inf)

    def overlap(self) -> float:
        """The deepest overlap of two bodies that collide, in the smaller radius (0: none)."""
        return max(float(self.overlaps().max(initial=0.0)), 0.0)

    def inside(self) -> float:
        """How far the deepest body reaches into a solid collider it collides with (its
        filter meets the collider's: a ghost passes through walls), past 1e-9 (1 + |x|)."""
        worst = 0.0
        for x, r, body in zip(self.world.positions(), self.r, self.bodies, strict=True):
            tol = 1e-9 * (1.0 + float(np.abs(x).max()))
            for c in self.solid:
                if body.filter.collides(c.filter):
                    worst = max(worst, r - c.distance(x) - tol)
        return worst

    def momentum(self) -> np.ndarray:
        return (self.m[:, None] * self.world.velocities()).sum(axis=0)

    def momentum_scale(self) -> float:
        """The sum of |m v|: what momentum's round-off is relative to."""
        return float((self.m * np.hypot(*self.world.velocities().T)).sum())


#: Scenes within what the engine holds today (see the module docstring): masses within a
#: decade, restitution 0.8 to 1, at most 3 L per second.
MODERATE: dict[str, Any] = {
    "mass_decades": 1.0,
    "restitution": st.floats(0.8, 1.0),
    "speeds": (1.0, 3.0),
}

#: Piles: balls dropped into a room (with pegs or not) under gravity, for 4 s.
piles = scenes(gravity=True, colliders=True, steps=240, speeds=(1.0,))


def xfail(reason: str) -> pytest.MarkDecorator:
    """An engine bug this test's @example reproduces (strict: a fix turns it into a failure,
    so that the marker is removed and the whole fuzz runs again)."""
    return pytest.mark.xfail(strict=True, raises=AssertionError, reason="engine bug: " + reason)


# -- the engine bugs the @examples below reproduce --------------------------------------------


#: Two worlds that never meet, both under gravity: the first's chain of impacts about a light
#: ball passed HANDOVER_ROUNDS and every impact of the step, the second world's too, went to
#: the pile; alone, the second's pair met at its exact moment (2e-3 m apart by step 20).
#: Now only the chain's own bodies are handed over.
HANDED_OVER_ELSEWHERE: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.43417509793885856, 0.21708754896942928, 1.6281566172707196, 1.4246370401118797,
         0.2, 1.0, 0.0, 2.0, 5),
        (0.8683501958777171, 0.43417509793885856, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (1.3025252938165757, 0.6512626469082878, -0.9158380972147797, -1.6281566172707196,
         0.2, 1.0, 0.0, 0.0, 5),
        (1.7367003917554342, 0.8683501958777171, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.0, 1.0854377448471464, 0.0, -3.256313234541439, 0.2, 1.0, 0.0, 0.0, 4),
        (0.0, -1.0854377448471464, 0.7123185200559399, 3.256313234541439, 0.2, 1.0, 0.0, 0.0,
         5),
        (1.0854377448471464, 0.0, -3.256313234541439, 0.0, 0.2, 0.1, 0.0, 0.5, 5),
        (0.0, 1.519612842786005, 0.0, -3.256313234541439, 0.2, 1.0, 0.0, 0.0, 7),
        (-1.0854377448471464, 0.0, 3.256313234541439, 0.0, 0.2, 1.0, 0.0, 0.0, 7),
    ],
    "colliders": [],
    "gravity": True,
    "method": "auto",
    "steps": 60,
}  # fmt: skip

#: Two piles of two worlds in one room, solved by one soft step: its colouring ordered the
#: rows by a hash of their World row numbers, and its energy guard scaled both piles by one
#: factor, so a pile moved differently with the other world's bodies numbered among its own
#: (5e-6 m by step 44). Now rows go in the order of their bodies and each pile is its own.
#: One pile gained energy and was scaled back (engine.exact.pile.dissipative); the other, which
#: did not, was written as V0 + 1 (V - V0), V only to rounding: 1.4e-17 m/s off its twin alone.
ONE_PILE_SCALED: Scene = {
    "balls": [
        (3.9605110746122123, 0.0, -3.9605110746122123, 1.9802555373061062, 0.2, 1.0, 0.0, 0.0, 7),
        (0.0, 0.0, 0.0, 0.0, 0.632455532033676, 1.0, 0.0, 0.0, 5),
        (1.584204429844885, 0.7921022149224425, -1.9802555373061062, 0.0, 0.632455532033676, 10.0,
         0.0, 0.0, 5),
        (-2.9703833059591593, 0.0, 2.9703833059591593, 0.0, 1.4997884186649117, 1.0, 0.0, 1.0, 7),
    ],
    "colliders": [
        Box((-5.811223242011293, -5.811223242011293), (5.811223242011293, 5.811223242011293),
            restitution=0.0, friction=0.0),
        Plane((0.0, -4.4701717246240715), (0.2474039592545229, 0.9689124217106447),
              restitution=0.0),
    ],
    "gravity": True,
    "method": "semi_implicit_euler",
    "steps": 60,
}  # fmt: skip

PILES_SIDE_BY_SIDE: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.39678383797157335, 0.19839191898578667, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.7935676759431467, 0.39678383797157335, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (1.19035151391472, 0.59517575695736, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.0, 0.49597979746446663, 0.0, -0.49597979746446663, 0.2, 1.0, 0.0, 0.0, 5),
        (0.9919595949289333, 0.0, -0.9919595949289333, 0.0, 0.2, 1.0, 0.0, 0.0, 7),
        (
            0.9919595949289333,
            0.9919595949289333,
            -0.9919595949289333,
            -0.9919595949289333,
            0.2,
            1.0,
            0.0,
            0.0,
            7,
        ),
        (0.0, 0.9919595949289333, 0.0, -0.9919595949289333, 0.2, 1.0, 0.0, 0.0, 5),
    ],
    "colliders": [
        Box(
            (-1.807456968089136, -1.807456968089136),
            (1.807456968089136, 1.807456968089136),
            restitution=0.0,
            friction=0.0,
        )
    ],
    "gravity": True,
    "method": "auto",
    "steps": 60,
}

#: No gravity, restitution 0, a room: the heavy ball comes back out of the floor.
SQUEEZED_ON_A_WALL: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 0),
        (0.0, 0.6, 0.0, -1.8, 0.2, 100.0, 0.0, 0.0, 0),
    ],
    "colliders": [Box((-1.0, -1.0), (1.0, 1.0), restitution=0.0, friction=0.0)],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}
#: A heavy ball strikes a light one at 30 m/s; the light one flies through the ball behind it.
STRUCK_THROUGH: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.1, 1.0, 1.0, 0.0, 0),
        (0.5, 0.0, 0.0, 0.0, 0.1, 0.001, 1.0, 0.0, 0),
        (0.8, 0.0, -30.0, 0.0, 0.1, 1.0, 1.0, 0.0, 0),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}
#: Two heavy balls close on a light one at 10 m/s each: more than MAX_ROUNDS impacts.
SQUEEZED: Scene = {
    "balls": [
        (-0.25, 0.0, 10.0, 0.0, 0.1, 1000.0, 1.0, 0.0, 0),
        (0.0, 0.0, 0.0, 0.0, 0.1, 1.0, 1.0, 0.0, 0),
        (0.25, 0.0, -10.0, 0.0, 0.1, 1000.0, 1.0, 0.0, 0),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}
#: Two 100 kg balls, one at rest and one closing at 1 m/s, crush two 1 kg balls between them,
#: all touching, e = 0 (the fuzz's shrunk example: 1.8% of r into one another at step 2,
#: the impacts' cap having stopped them so, before the cap's plastic impacts took the touching
#: pairs too).
CRUSHED: Scene = {
    "balls": [
        (0.1, 0.0, 0.0, 0.0, 0.1, 100.0, 0.0, 0.0, 0),
        (0.30000000000000004, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
        (0.5, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
        (0.7, 0.0, -1.0, 0.0, 0.1, 100.0, 0.0, 0.0, 0),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}
#: Four touching balls, restitution 0, a light one among them: an inelastic collapse.
COLLAPSE: Scene = {
    "balls": [
        (0.1, 0.0, 1.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
        (0.3, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
        (0.5, 0.0, 0.0, 0.0, 0.1, 0.01, 0.0, 0.0, 0),
        (0.7, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}
#: A ball dropped from 1.3 m onto an equal one lying on the floor, all elastic.
DROPPED_ON_A_BALL: Scene = {
    "balls": [
        (0.0, 0.2, 0.0, 0.0, 0.2, 1.0, 1.0, 0.5, 0),
        (0.05, 1.5, 0.0, 0.0, 0.2, 1.0, 1.0, 0.5, 0),
    ],
    "colliders": [Plane((0.0, 0.0), (0.0, 1.0))],
    "gravity": True,
    "method": "semi_implicit_euler",
    "steps": 60,
}
#: A 1 g ball between two 10 kg ones, no gravity: overlaps of 9 to 19%, no warning.
SQUEEZED_SILENTLY: Scene = {
    "balls": [
        (0.6, 0.1, -0.6, -0.4, 0.21, 0.001, 1.0, 1.0, 0),
        (1.29, 0.0, -1.36, -1.0, 0.4, 10.0, 1.0, 0.0, 0),
        (-0.4, 0.0, 0.0, -0.4, 0.775, 10.0, 0.4, 2.0, 0),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}
#: A heavy ball presses a light one into the 1.6 m gap between a peg and the right wall.
WEDGED: Scene = {
    "balls": [
        (2.7, 3.0, 0.0, 0.0, 1.0, 1.0, 0.5, 0.5, 0),
        (1.6, 8.0, 0.0, 0.0, 1.0, 100.0, 0.5, 0.5, 0),
    ],
    "colliders": [Box((-4.0, 0.0), (4.0, 40.0)), Circle((2.0, 1.5), 0.4)],
    "gravity": True,
    "method": "semi_implicit_euler",
    "steps": 150,
}
#: Two worlds in one under gravity, no colliders: the first's balls (5) move differently
#: when the second's (7) are there.
BANDS_SHARED: Scene = {
    "balls": [
        (-0.1, -1.0, 0.0, 1.0, 0.2, 160.0, 0.0, 2.0, 5),
        (-1.0, -0.9, 0.6, 1.0, 0.2, 1000.0, 0.0, 1.0, 7),
        (0.8, 0.0, -1.0, 0.0, 0.2, 100.0, 1.0, 1.0, 5),
        (-1.3, -1.2, 1.0, 1.0, 0.2, 1000.0, 0.0, 1.0, 7),
        (0.5, 0.9, -1.0, -1.4, 0.2, 100.0, 0.0, 2.0, 5),
        (1.0, 1.0, -0.5, -1.0, 0.2, 100.0, 0.0, 2.0, 5),
    ],
    "colliders": [],
    "gravity": True,
    "method": "semi_implicit_euler",
    "steps": 60,
}
#: Two balls meet head on in the air, elastically (5), while two others (7) slide on the
#: floor into a wall: with them, the collision in the air becomes perfectly inelastic.
WALL_HIT_ELSEWHERE: Scene = {
    "balls": [
        (0.0, 5.0, 3.0, 0.0, 0.5, 1.0, 1.0, 0.0, 5),
        (1.24, 5.0, -3.0, 0.0, 0.5, 1.0, 1.0, 0.0, 5),
        (-4.05, 0.5, -10.0, 0.0, 0.5, 1.0, 1.0, 0.0, 7),
        (-3.04, 0.5, -10.0, 0.0, 0.5, 1.0, 1.0, 0.0, 7),
    ],
    "colliders": [Plane((0.0, 0.0), (0.0, 1.0)), Plane((-5.0, 0.0), (1.0, 0.0), restitution=0.0)],
    "gravity": True,
    "method": "semi_implicit_euler",
    "steps": 10,
}
#: Four balls of the second world (7, 8) and a ghost (4) that meets nothing, no gravity, no
#: colliders: with the ghost there, the pair search lists a pair of the others once instead
#: of twice in step 11, and they move 1.3e-6 m differently.
GHOST_IN_THE_GRID: Scene = {
    "balls": [
        (-1.0, 0.5088564678292608, 12.58, -10.0, 0.2, 0.07943282347242814, 0.0, 0.4, 7),
        (0.0, -0.9, 0.0, 7.4, 0.2, 1.0, 0.0, 0.0, 7),
        (1.0, 0.0, -21.0, -2.3081011349460887, 0.2, 1.0, 1.0, 2.0, 8),
        (-1.5, 1.2574029527642543, 12.02, -17.96, 0.2, 0.0371738567935479, 1.0, 2.0, 8),
        (0.0, 1.0, 0.0, -6.0, 0.2, 0.1, 0.0, 1.0, 4),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}
#: Found by this file, no gravity, no colliders: a 1 g ball between two 100 kg ones (5, 6);
#: ball 3 (8) meets none of them, yet with it in the World they moved 0.6 m differently
#: (fixed on main at a42bf9a; kept against a regression).
UNSEEN_NEIGHBOUR: Scene = {
    "balls": [
        (0.0, 2.0, 0.0, -9.26, 1.1, 0.001, 1.0, 2.0, 5),
        (3.0, 1.82, -3.17, 6.67, 1.0, 100.0, 0.0, 2.0, 6),
        (0.0, -3.0, 0.0, 11.0, 1.0, 100.0, 0.0, 0.16, 6),
        (-1.0, -6.0, 1.0, 11.0, 1.4, 0.01, 0.0, 1.0, 8),
    ],
    "colliders": [],
    "gravity": False,
    "method": "semi_implicit_euler",
    "steps": 60,
}
#: Found by this file on main de83988, no gravity, a floor: balls 0, 2, 3 (5, 6) squeeze the
#: light ball 3 against the floor (64 impact rounds in step 44); ball 1 (7) meets only the
#: floor, and with it there they move 1.8 cm differently.
UNSEEN_ON_THE_FLOOR: Scene = {
    "balls": [
        (-0.0, 2.3, -1.0, -10.0, 0.4, 0.5754399373371569, 0.0, 2.0, 5),
        (0.0, 0.0, -0.0, -6.0, 1.2, 10.0, 0.0, 2.0, 7),
        (1.4, -1.7027098781335037e-07, -5.0, -1.0, 0.2, 1.0, 1.0, 1.0, 6),
        (-2.6, -0.0, 1.0, -6.0, 1.1, 0.01, 0.0, 1.0, 5),
    ],
    "colliders": [
        # A floor tilted by 2.6e-228 rad: a Plane that is not exactly level (as drawn).
        Plane(
            (0.0, -4.554083577501669),
            (2.6375001988529346e-228, 1.0),
            restitution=0.5335919472368472,
            friction=3.347271120057148e-261,
        )
    ],
    "gravity": False,
    "method": "semi_implicit_euler",
    "steps": 60,
}
#: Found exploring (fast path, FUZZ_EXAMPLES=300; numpy alike): no gravity, no colliders; the
#: first world's rough balls 2 and 3 meet at 11 ms of step 55, beside the second world's ball 0,
#: which spins from its impact with ball 1. The first world alone and the two together parted
#: there by 3.7e-4 m/s: alone, nothing spun as the step began (no Spin), and
#: engine.exact.pair_bounce.turns_of gave the impacts one array of zeros for both omega and
#: alpha, so the turn each impact wrote into omega was an angular acceleration too for the
#: later rounds (26 of them); together, alpha was the second world's Spin's, its own array.
CROSSING_A_STRANGER: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.2, 1.0, 0.0, 1.0, 7),
        (0.0, 0.8260990336999412, 0.4130495168499706, -0.8260990336999412, 0.2, 1.0, 0.0, 1.0,
         7),
        (0.0, -0.8260990336999412, 0.0, 0.8260990336999412, 0.2, 1.0, 0.0, 1.0, 5),
        (0.0, -1.321758453919906, 0.0, 0.8260990336999412, 0.2, 1.0, 0.0, 1.0, 5),
        (0.8260990336999412, 0.0, -0.8260990336999412, 0.0, 0.2, 1.0, 0.0, 0.0, 5),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}  # fmt: skip
#: Found exploring on the fast path (the same on numpy), no gravity, a rough room: the 7 g ball
#: 2 of the first world (5), squeezed by ball 3 against the floor, meets the cap of 64 impact
#: rounds every step from step 6; the second world's (7) pair met at 11 ms of step 10 and,
#: capped too, stopped at t = 0 with the first's, 6 m/s off its path alone. Each group linked
#: by the impacts left now stops at its own earliest moment.
STOPPED_WITH_A_STRANGER: Scene = {
    "balls": [
        (0.5111222321992216, 0.0, -10.222444643984433, 0.0, 0.2, 463.29332847080474, 0.0, 0.0,
         7),
        (0.0, -0.4296019024750183, 0.0, 8.592038049500365, 0.2, 1.0, 0.0, 0.0, 7),
        (0.0, -0.868363360379739, 0.0, 7.894212367088537, 0.2, 0.007309934704394241, 0.0,
         0.7714718205563822, 5),
        (0.0, 0.5075808255927536, 0.0, -14.959998303014753, 0.2, 1.0, 0.0, 0.0, 5),
    ],
    "colliders": [
        Box((-1.807456968089136, -1.807456968089136), (1.807456968089136, 1.807456968089136),
            restitution=0.0, friction=1.886180752613483),
    ],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}  # fmt: skip

#: Gravity, a room with a floor and a ledge: balls of world 5 fall past a stack of world 4's.
UNSEEN_UNDER_GRAVITY: Scene = {
    "balls": [
        (0.0, 1.04, 0.0, -1.04, 0.2, 1.0, 0.0, 0.0, 4),
        (0.0, 1.456, 0.0, -1.04, 0.2, 1.0, 0.0, 0.0, 4),
        (0.0, 1.872, 0.52, -1.04, 0.2, 1.0, 0.0, 0.0, 5),
        (0.78, 1.04, -0.26, -1.04, 0.2, 1.0, 0.0, 1.0, 5),
        (0.0, 0.26, 0.52, -0.26, 0.2, 1.0, 0.0, 1.0, 5),
        (0.416, 0.208, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.832, 0.416, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (1.248, 0.624, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (1.664, 0.832, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 7),
    ],
    "colliders": [
        Box((-2.6936, -2.6936), (2.6936, 2.6936), restitution=0.0, friction=0.0),
        Plane((0.0, -2.072), (0.0, 1.0), restitution=0.0, friction=0.0),
        Segment((-2.072, 0.0), (1.036, 0.0), restitution=0.0),
    ],
    "gravity": True,
    "method": "auto",
    "steps": 60,
}
#: Two touching balls in free fall, the upper one closing at 0.2 m/s.
FALLING_PAIR: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0),
        (0.0, 1.001, 0.0, -0.2, 0.5, 1.0, 0.0, 0.0, 0),
    ],
    "colliders": [],
    "gravity": True,
    "method": "auto",
    "steps": 10,
}
#: A pile in a room (found by this file): from step 88, the awake ball 6, at rest against
#: the sleeping ball 0, pushed it into the sleeping ball 4 (fixed on main at 988aca7).
CREEPING: Scene = {
    "balls": [
        (-0.25596229761600453, -0.025, 0.678, 0.0, 0.2, 316.22776601683796, 0.6, 0.21, 0),
        (0.14498493253011507, -0.33, 0.325, 0.33, 0.2, 41.78789907305066, 0.12, 0.29, 0),
        (0.94, -0.14, -0.78, 0.58, 0.2, 1.0, 1.0, 1.2, 0),
        (1.5052965873569368, -0.2, -0.7844476576775162, 0.58, 0.2, 1.0, 0.53, 1.0, 0),
        (-0.67, 0.0, 0.0, -0.128, 0.2, 1.0, 0.0, 1.52, 0),
        (-1.07, 0.077, 1.0336271833985577, -0.314, 0.2, 31.949075515089213, 0.0, 0.26, 0),
        (
            0.3189668515662531,
            -0.723,
            0.32542025101892763,
            0.329,
            0.2,
            41.68693834703355,
            0.0,
            0.29,
            0,
        ),
    ],
    "colliders": [
        Box(
            (-2.2168855635640177, -2.2168855635640177),
            (2.2168855635640177, 2.2168855635640177),
            restitution=0.0,
            friction=1.8627945855541572,
        )
    ],
    "gravity": True,
    "method": "auto",
    "steps": 240,
}

#: Found by this file: on the floor of a room, the light ball 2 slid at 0.09 m/s into ball 3,
#: asleep, which moved while asleep in step 183 (ball 0 is a ghost; fixed at 988aca7).
CREEPING_SLOWLY: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.456, 0.228, -0.095, 0.0, 0.2, 1.0, 0.0, 0.0, 0),
        (-0.456, 0.0, 0.38, 0.0, 0.2, 0.01, 1.0, 0.375, 0),
        (-0.912, 0.0, 0.76, 0.0, 0.2, 1.0, 1.0, 1.0, 0),
    ],
    "colliders": [
        Box((-1.4456, -1.4456), (1.4456, 1.4456), restitution=0.0, friction=0.0),
        Plane((0.0, -1.112), (0.0, 1.0), restitution=0.0),
    ],
    "gravity": True,
    "method": "semi_implicit_euler",
    "steps": 240,
}

#: Found exploring (--hypothesis-profile=explore), no gravity, a room with a rough floor: the
#: 28.6 m ball 0 comes down at 538 m/s onto the 0.43 m ball 3 sliding on the floor at 776 m/s,
#: and their pair meets again at t = 0 in every round of every step from step 10 (MAX_ROUNDS).
#: The capped rounds stopped every body with an impact left at the one earliest moment of all,
#: so in step 12 balls 1 and 2, meeting at 4.6 ms against the left wall, stopped at t = 0 too,
#: and what the cap, the plastic collapse and the walls' push out made of that gained 1.7e-5
#: of the first energy. Now each group of bodies linked by the impacts left stops at its own
#: earliest moment (engine.exact.pair_impacts.impacts_in_order).
STOPPED_ON_THE_FLOOR: Scene = {
    "balls": [
        (63.82573710929791, 59.57634565602905, -1222.4773916600627, -1220.279204048801,
         28.649359308671634, 2.5834782892217794, 0.0, 0.816657504541938, 0),
        (-23.069691923507943, 0.0, 107.28970058378914, -357.1793689139829,
         2.5108077510779045, 1.0, 0.0, 0.0, 0),
        (-63.00200724422925, -53.319819614459206, 1429.8765761020663, 1066.396392289184,
         0.21193242078037972, 0.004832230003884546, 0.09643189263747434, 1.6691569685794465, 0),
        (-31.588026224617494, 0.0, 1047.753792107613, 0.0, 0.4287956602826071,
         0.19912835774080767, 0.0, 0.0, 0),
        (-75.60240869307509, -63.983783537351044, 1260.0401448845848, 1066.396392289184,
         0.21193242078037972, 0.004832230003884546, 0.09643189263747434, 1.6691569685794465, 0),
    ],
    "colliders": [
        Box((-120.21762534336042, -120.21762534336042), (120.21762534336042, 120.21762534336042),
            restitution=0.0, friction=1.8010766467778891),
    ],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}  # fmt: skip

#: Found exploring (numpy, FUZZ_EXAMPLES=300; the same on the fast path): in a room with a rough
#: floor and no gravity, the 105 kg ball 1 heads at 21.6 m/s for the top left corner, where
#: the 1 kg ball 3 sits against the left wall. In step 16 the static contacts bounce ball 1
#: off the left wall at 8.6 ms, its friction spinning it up from -2.1 to 47 rad/s; the
#: impacts then meet it with ball 3 at t = 0, round after round to the cap, and stop it
#: there on its first piece (engine.exact.bent_paths): the bounce's push dropped, but not its
#: spin, so the step ended with 2,254 J more than it began (7% of the first energy). Each
#: piece of a bent path now has its own spin too.
SPUN_BY_A_DROPPED_BOUNCE: Scene = {
    "balls": [
        (0.7965579296277236, -0.49597979746446663, -15.931158582634875, 9.725788313628179,
         0.2, 1.0304446113591337, 0.2913435356184351, 0.9095431978113202, 1),
        (1.1542231675360553, -0.9556045884713794, -18.792328926098758, 15.243104285478285,
         0.2, 104.71285480508996, 0.0, 0.8699228733748041, 1),
        (-0.49597979746446663, 0.0, 9.919595949289333, 4.166230298701519, 0.2,
         0.4641588833612779, 0.0, 1.2371015852173194e-308, 0),
        (0.6413971826843136, 0.0, -12.82794365368627, 0.0, 0.2, 1.0, 0.0, 1.0397462205612513,
         0),
    ],
    "colliders": [
        Box((-1.7604901177968717, -1.7604901177968717), (1.7604901177968717, 1.7604901177968717),
            restitution=0.0, friction=0.35462551974650053),
    ],
    "gravity": False,
    "method": "auto",
    "steps": 20,
}  # fmt: skip

# -- 1. momentum ------------------------------------------------------------------------------


@fuzz(120)
@given(scene=scenes(gravity=False, colliders=False))
def test_without_external_forces_momentum_is_conserved(scene: Scene) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, bodies = build(scene)
        p = Probe(w, bodies, [])
        P0, scale = p.momentum(), p.momentum_scale()
        for k in range(scene["steps"]):
            step(w)
            drift = float(np.abs(p.momentum() - P0).max())
            assert drift <= 1e-12 * scale, (k, drift / scale)


@fuzz(40)
@given(scene=scenes(gravity=True, colliders=False))
@example(scene=FALLING_PAIR)
def test_under_uniform_gravity_momentum_changes_by_m_g_t(scene: Scene) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, bodies = build(scene)
        p = Probe(w, bodies, [])
        P0, M = p.momentum(), float(p.m.sum())
        scale = p.momentum_scale() + M * G * DT * scene["steps"]
        for k in range(scene["steps"]):
            step(w)
            drift = float(np.abs(p.momentum() - P0 - (0.0, -M * G * w.t)).max())
            assert drift <= 1e-12 * scale, (k, drift / scale)


# -- 2. energy --------------------------------------------------------------------------------


def check_energy_never_increases(scene: Scene) -> None:
    """Kinetic energy (no gravity) never grows by more than 1e-12 of the first."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, _ = build(scene)
        E0 = E = w.energy()
        for k in range(scene["steps"]):
            step(w)
            E1 = w.energy()
            assert E1 <= E + 1e-12 * E0, (k, (E1 - E) / E0)
            E = E1


@fuzz(50)
@given(scene=scenes(gravity=False, pegs=False))
@example(scene=SQUEEZED_ON_A_WALL)
@example(scene=STOPPED_ON_THE_FLOOR)
@example(scene=SPUN_BY_A_DROPPED_BOUNCE)
def test_without_gravity_energy_never_increases(scene: Scene) -> None:
    check_energy_never_increases(scene)


@fuzz(100)
@given(scene=scenes(gravity=False, pegs=False, **MODERATE))
def test_moderate_scenes_without_gravity_never_gain_energy(scene: Scene) -> None:
    check_energy_never_increases(scene)


#: Found exploring (numpy; the same on the fast path) with engine.exact.pair_impacts' capped groups
#: stopping each at its own moment: two 5 g balls (3 and 5, e = 0.096, side by side at the
#: same velocity) meet at t = 0 in all 64 rounds of every step from step 11, and kinetic
#: energy grew by 1.8e-9 of the first in step 12 (a strict xfail, put down to the cap's
#: plastic collapse with the walls). It holds since each piece of a bent path has its own
#: spin (SPUN_BY_A_DROPPED_BOUNCE): the gain was a dropped bounce's spin, kept.
CAPPED_PAIR_GAINS: Scene = {
    "balls": [
        (63.82573710929791, 59.57634565602905, -1222.4773916600627, -1220.279204048801,
         28.649359308671634, 2.5834782892217794, 0.6761994097374279, 0.816657504541938, 0),
        (14.478309719226397, 1.5758157208003829e-307, 54.46393704571374, 322.17239841882565,
         6.324555320336759, 343.8851632740583, 0.0, 3.0541482859056625e-96, 4),
        (-23.069691923507943, 6.556358496760509e-118, 107.28970058378914, -357.1793689139829,
         2.5108077510779045, 37.28194339223384, 0.0, 0.0, 0),
        (-63.00200724422925, -53.319819614459206, 1429.8765761020663, 1066.396392289184,
         0.21193242078037972, 0.004832230003884546, 0.09643189263747434, 1.6691569685794465, 0),
        (-31.588026224617494, 0.0, 1047.753792107613, 0.0, 0.4287956602826071,
         0.19912835774080767, 0.0, 0.0, 0),
        (-75.60240869307509, -63.983783537351044, 1429.8765761020663, 1066.396392289184,
         0.21193242078037972, 0.004832230003884546, 0.09643189263747434, 1.6691569685794465, 0),
        (0.0, 0.0, 0.0, 0.0, 6.324555320336759, 1.0, 0.0, 0.0, 4),
    ],
    "colliders": [
        Box((-120.21762534336042, -120.21762534336042), (120.21762534336042, 120.21762534336042),
            restitution=0.0, friction=1.8010766467778891),
    ],
    "gravity": False,
    "method": "auto",
    "steps": 14,
}  # fmt: skip


def test_a_pair_met_at_the_rounds_cap_every_step_gains_no_energy() -> None:
    check_energy_never_increases(CAPPED_PAIR_GAINS)


# -- 3. bodies inside bodies ------------------------------------------------------------------


@fuzz(60)
@given(scene=rows())
@example(scene=CRUSHED)
@example(scene=STRUCK_THROUGH)
@example(scene=SQUEEZED)
@example(scene=COLLAPSE)
def test_balls_on_a_line_never_pass_through_each_other(scene: Scene) -> None:
    check_in_order_on_the_line(scene)


def check_in_order_on_the_line(scene: Scene) -> None:
    """Every step of ``scene`` (balls on the x axis) leaves them in order, each pair
    overlapping by at most 1% of the smaller radius."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, bodies = build(scene)
        r = np.array([b.radius for b in bodies])
        for k in range(scene["steps"]):
            step(w)
            gap = np.diff(w.positions()[:, 0]) - r[1:] - r[:-1]
            assert (gap >= -0.01 * np.minimum(r[1:], r[:-1])).all(), (k, gap)


def one_at_a_time(
    x: list[float], v: list[float], m: list[float], r: float, dt: float
) -> tuple[list[float], list[float]]:
    """Equal elastic discs of radius ``r`` on a line, in order, no forces: their positions and
    velocities after ``dt`` s, each impact resolved alone at its moment, the earliest first
    (1D, e = 1: v_a' = ((m_a - m_b) v_a + 2 m_b v_b) / (m_a + m_b), and B's likewise)."""
    x, v, t = list(x), list(v), 0.0
    while True:
        soonest, k = dt - t, -1
        for i in range(len(x) - 1):
            closing = v[i] - v[i + 1]
            if closing > 0.0 and (x[i + 1] - x[i] - 2.0 * r) / closing < soonest:
                soonest, k = max((x[i + 1] - x[i] - 2.0 * r) / closing, 0.0), i
        x = [xi + vi * soonest for xi, vi in zip(x, v, strict=True)]
        t += soonest
        if k < 0:
            return x, v
        ma, mb, va, vb = m[k], m[k + 1], v[k], v[k + 1]
        v[k] = ((ma - mb) * va + 2.0 * mb * vb) / (ma + mb)
        v[k + 1] = ((mb - ma) * vb + 2.0 * ma * va) / (ma + mb)


@st.composite
def elastic_rows(draw: st.DrawFn) -> tuple[list[float], list[float], list[float]]:
    """3 to 6 discs of 5 cm on a line, 1 um to 30 cm apart, at up to 30 m/s either way, masses
    0.5, 1 or 2 kg: (x, v, m), most of them meeting two or three times within a step. (Not
    touching: balls that touch as the step begins meet at one instant, where no time order
    says which impact comes first; the engine's answer there is the pile's.)"""
    count = draw(st.integers(3, 6))
    x = [0.0]
    for _ in range(count - 1):
        x.append(x[-1] + 0.1 + draw(st.floats(1e-6, 0.3)))
    v = [draw(st.floats(-30.0, 30.0)) for _ in range(count)]
    m = [draw(st.sampled_from((0.5, 1.0, 2.0))) for _ in range(count)]
    return x, v, m


#: Five balls whose impacts a round took together (the fuzz's draw): 2 and 3 met first, then
#: 3 and 4 at 2.3 ms and 1 and 2 at 8 ms, in one round. 3 came back from the heavy 4 at 60
#: m/s into 2 at 4.7 ms, a meeting missed: 2's path was searched from 8 ms on, and 3 ended
#: 0.21 m on the far side of 2.
FIVE_IN_A_ROW = (
    [0.0, 0.34490820159036056, 0.602886332085666, 0.7143439887914773, 0.9411079209497848],
    [-14.564272162287661, 1.147514717844146, 27.518120454795877, -18.668541831497826,
     -27.56475779180554],
    [0.5, 0.5, 0.5, 0.5, 2.0],
)  # fmt: skip


def check_in_time_order(row: tuple[list[float], list[float], list[float]], kernels: str) -> None:
    x, v, m = row
    w = World(solver="exact", kernels=kernels)
    balls = [
        w.add(Body(Vector(xi, 0.0), Vector(vi, 0.0), radius=0.05, restitution=1.0, mass=mi))
        for xi, vi, mi in zip(x, v, m, strict=True)
    ]
    w.step(1 / 60)
    x1, v1 = one_at_a_time(x, v, m, 0.05, 1 / 60)
    assert np.abs(w.positions()[:, 0] - x1).max() < 1e-9, (w.positions()[:, 0], x1)
    assert np.abs(w.velocities()[:, 0] - v1).max() < 1e-9 * 30.0
    assert all(b.pos.y == 0.0 for b in balls)


#: Six balls 1 um apart, the last at 1 m/s into the row (the fuzz's draw): the first ball
#: should leave at 1 m/s, but the struck bodies' search followed the impacts' chain three
#: links (engine.geometry.pair_grid.struck_pairs) and never paired the first two, which stood
#: 1.6 cm apart: the second passed 1 mm into the first.
SPACED_CRADLE = ([0.0, 0.115625, 0.215626, 0.315627, 0.415628, 0.515629], [0.0] * 5 + [-1.0],
                 [0.5] * 6)  # fmt: skip
#: The same with heavy ends (the fuzz's draw): after 1-2 at 15.627 ms, 4-5 at 15.628 ms was
#: taken in the same round; 2's new path met 3 and 3 met 4 before it, a chain of two links
#: that ``first_after`` alone does not see (engine.exact.pair_order: a small group keeps
#: strict time order). 0.15 mm off.
MIXED_CRADLE = ([0.0, 0.100001, 0.200002, 0.300003, 0.400004, 0.515629], [0.0] * 5 + [-1.0],
                [1.0, 0.5, 0.5, 0.5, 0.5, 1.0])  # fmt: skip


@pytest.mark.parametrize("kernels", PATHS)
@pytest.mark.parametrize("name", ["FIVE_IN_A_ROW", "SPACED_CRADLE", "MIXED_CRADLE"])
def test_balls_in_a_row_meet_in_time_order(name: str, kernels: str) -> None:
    # Issue 38's item 10: "two impacts resolved in one round can miss a meeting among 4 or 5
    # balls". A round now takes a pair only where no earlier pair of the round has a body
    # paired with its own (engine.exact.pair_order.first_after), or, in a small group, only
    # the group's first; and the struck bodies' search follows a chain of impacts to its end.
    row = {"FIVE_IN_A_ROW": FIVE_IN_A_ROW, "SPACED_CRADLE": SPACED_CRADLE,
           "MIXED_CRADLE": MIXED_CRADLE}[name]  # fmt: skip
    check_in_time_order(row, kernels)


@fuzz(100)
@given(row=elastic_rows())
def test_balls_in_a_row_end_a_step_as_their_impacts_one_at_a_time_say(
    row: tuple[list[float], list[float], list[float]],
) -> None:
    # Against the closed form of the row's impacts taken one at a time: before the rounds
    # waited, 8 of 300 such rows were wrong by up to 0.47 m (measured).
    check_in_time_order(row, "numpy")


#: A 100 kg ball at 25 m/s into a row of 1 kg balls that touch (e 1 for the second and
#: third, 0 for the rest): the impacts reach MAX_ROUNDS in some steps, and the cap stopped
#: the first and third balls where their impacts were left but let the second, between them
#: and moving with them, fly its whole step: 4 radii past the third (found by the line fuzz
#: exploring, 2026-12-04). The cap asked only where such a ball's path ends, not whether
#: it runs into the stopped one on the way; now it sweeps the path.
STRUCK_TOUCHING: Scene = {
    "balls": [
        (0.1, 0.0, 25.0, 0.0, 0.1, 100.0, 0.0, 0.0, 0),
        (0.30000000000000004, 0.0, 0.0, 0.0, 0.1, 1.0, 1.0, 0.0, 0),
        (0.5, 0.0, 0.0, 0.0, 0.1, 1.0, 1.0, 0.0, 0),
        (0.8, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
        (1.3, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
        (1.5000000000000002, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
        (1.7000000000000004, 0.0, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}


@pytest.mark.parametrize(
    "name", ["STRUCK_THROUGH", "SQUEEZED", "COLLAPSE", "CRUSHED", "STRUCK_TOUCHING"]
)
def test_struck_and_squeezed_balls_never_pass_through(name: str) -> None:
    """A light ball struck toward a ball its own speed did not reach, and one squeezed
    between heavy ones past MAX_ROUNDS impacts in a step, and an inelastic collapse, and two
    light balls crushed between heavy ones at e = 0, and a row that touches struck by a heavy
    ball: in order on the line, overlapping by at most 1% of a radius, momentum kept to
    1e-12."""
    scene = {
        "STRUCK_THROUGH": STRUCK_THROUGH, "SQUEEZED": SQUEEZED, "COLLAPSE": COLLAPSE,
        "CRUSHED": CRUSHED, "STRUCK_TOUCHING": STRUCK_TOUCHING,
    }[name]  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, bodies = build(scene)
        r = np.array([b.radius for b in bodies])
        m = np.array([b.mass for b in bodies])
        p0 = (m[:, None] * w.velocities()).sum(axis=0)
        scale = float((m * np.hypot(*w.velocities().T)).sum())
        for k in range(scene["steps"]):
            step(w)
            gap = np.diff(w.positions()[:, 0]) - r[1:] - r[:-1]
            assert (gap >= -0.01 * np.minimum(r[1:], r[:-1])).all(), (k, gap)
            p = (m[:, None] * w.velocities()).sum(axis=0)
            assert float(np.abs(p - p0).max()) <= 1e-12 * scale, k
            if name == "CRUSHED":
                # e = 0: the row moves as one, at its momentum over its mass, from the first
                # step. It did at step 2, 1.8% of a radius into itself (the impacts' cap left
                # it so); with the plastic impacts of the cap swept only, it took 20 steps.
                v = w.velocities()[:, 0]
                assert float(np.abs(v - p0[0] / m.sum()).max()) < 1e-12, (k, v)
        # Newton's cradle through a light ball: the struck heavy ball stops, the far one
        # leaves with its speed; squeezed, the heavy ones turn back.
        v = w.velocities()[:, 0]
        if name == "STRUCK_THROUGH":
            assert abs(v[0] + 30.0) < 0.1 and abs(v[2]) < 0.1, v
        if name == "SQUEEZED":
            assert v[0] < -9.9 and v[2] > 9.9, v


@fuzz(40)
@given(scene=scenes())
@example(scene=DROPPED_ON_A_BALL)
@example(scene=SQUEEZED_SILENTLY)
def test_an_overlap_past_five_percent_is_warned_about(scene: Scene) -> None:
    w, bodies = build(scene)
    rmin = min(b.radius for b in bodies)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        deep = None
        for k in range(scene["steps"]):
            step(w)
            if deep is None and w.overlap() > 0.05 * rmin:
                deep = k, w.overlap() / rmin
            elif deep is not None:
                break  # the warning may come with the next step
    if deep is not None and deep[0] + 1 < scene["steps"]:
        warned = [c for c in caught if issubclass(c.category, StabilityWarning)]
        assert warned, f"step {deep[0]}: overlap {deep[1]:.1%} of the smallest radius, no warning"


@fuzz(40)
@given(scene=piles)
def test_piles_fall_asleep_overlapping_under_one_percent(scene: Scene) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, bodies = build(scene)
        p = Probe(w, bodies, scene["colliders"])
        was = np.zeros(len(bodies), dtype=bool)
        for k in range(scene["steps"]):
            step(w)
            now = np.array([w.is_sleeping(b) for b in bodies])
            if (now & ~was).any():
                deepest = float(p.overlaps()[now & ~was].max(initial=0.0))
                assert deepest <= 0.01, (k, deepest)
            was = now


@fuzz(25)
@given(scene=piles)
@example(scene=CREEPING)
@example(scene=CREEPING_SLOWLY)
def test_sleeping_bodies_stay_exactly_put(scene: Scene) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, bodies = build(scene)
        was = np.zeros(len(bodies), dtype=bool)
        for k in range(scene["steps"]):
            X0 = w.positions()
            step(w)
            now = np.array([w.is_sleeping(b) for b in bodies])
            assert np.array_equal(w.positions()[was & now], X0[was & now]), k
            assert not w.velocities()[now].any(), k
            was = now


# -- 4. bodies inside colliders ---------------------------------------------------------------


def check_outside_colliders(scene: Scene) -> None:
    """No body ends a step deeper in a solid collider than 1e-9 (1 + |x|)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, bodies = build(scene)
        p = Probe(w, bodies, scene["colliders"])
        for k in range(scene["steps"]):
            step(w)
            assert p.inside() <= 0.0, (k, p.inside())


@fuzz(40)
@given(scene=scenes(colliders=True))
@example(scene=WEDGED)
def test_no_body_ends_a_step_inside_a_solid_collider(scene: Scene) -> None:
    check_outside_colliders(scene)


#: Found exploring (both paths, 2026-12-07; not shrunk: hypothesis ran out of time): eight balls
#: at up to 4 km/s in a room, some spinning from their bounces. In step 36 a light ball
#: spinning at some 2,300 rad/s struck the left wall at 485 m/s and friction sent it down the
#: wall at 1,028 m/s, farther than its speed (668 m/s) let the faces' looks reach: the floor
#: was not listed for it, and it ended the step 0.40 m inside it. The looks now count what
#: friction can turn spin into (engine.exact.contacts' ``_spin_reach``;
#: tests/test_contacts.py, a spinning ball hurled along a wall).
HURLED_ALONG_A_WALL: Scene = {
    "balls": [
        (0.0, 0.0, 2799.243001931209, -2175.069928486572, 0.2, 1.0, 0.0, 0.0, 0),
        (0.0, -89.26206021380818, -2085.542522762427, 3695.093781699525, 0.2, 0.10095573798177992,
         0.0, 1.172335322646792, 0),
        (147.98137021762545, 0.0, -2959.627404352509, -398.40086933206817, 0.2, 75.99421835781159,
         0.0, 0.4643217962710523, 0),
        (-16.685673986676175, 0.0, -1095.9898261856877, -595.080401425388, 0.2,
         0.017940645819523555, 0.0, 2.0, 0),
        (0.0, 131.15018782453615, 1780.7173192916973, -745.4473371053917, 111.27125155239492,
         0.21131801525620914, 0.0, 0.5305441964521661, 0),
        (38.365059116642406, 242.7928037815583, -639.4176519440401, -4046.546729692638, 0.2,
         4.689259764298935, 0.0, 1.6363446871630667, 0),
        (-56.592821388497484, 232.12554078815066, 235.80342245207274, -967.1897532839615, 0.2, 1.0,
         0.0, 0.0, 0),
        (-68.73682163032971, -123.14343796466738, -1663.1727892658175, 1368.2604218296378,
         72.94224663337353, 43.51829531738218, 0.0, 0.0, 0),
    ],
    "colliders": [
        Box((-315.89064491602574, -315.89064491602574), (315.89064491602574, 315.89064491602574),
         restitution=0.0),
    ],
    "gravity": False,
    "method": "auto",
    "steps": 40,
}  # fmt: skip


@fuzz(80)
@given(scene=scenes(colliders=True, pegs=False))
@example(scene=HURLED_ALONG_A_WALL)
def test_no_body_ends_a_step_inside_the_walls_of_a_room(scene: Scene) -> None:
    check_outside_colliders(scene)


# -- 5. filters -------------------------------------------------------------------------------


def check_as_if_alone(scene: Scene) -> None:
    """Balls of the first world (filters 4 to 6) and of the second (7, 8) never meet: each
    world moves as it would alone, bit for bit under an integrator."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        both, _ = build(scene)
        first, _ = build(scene, lambda b: b[8] in FIRST)
        second, _ = build(scene, lambda b: b[8] not in FIRST)
        order = [k for k, b in enumerate(scene["balls"]) if b[8] in FIRST]
        order += [k for k, b in enumerate(scene["balls"]) if b[8] not in FIRST]
        for k in range(scene["steps"]):
            for w in (both, first, second):
                step(w)
            X = np.vstack([w.positions().reshape(-1, 2) for w in (first, second)])
            V = np.vstack([w.velocities().reshape(-1, 2) for w in (first, second)])
            dX = float(np.abs(both.positions()[order] - X).max())
            dV = float(np.abs(both.velocities()[order] - V).max())
            tol = 0.0
            if scene["method"] == "auto":
                # The closed form starts anew from the state after any body's contact: the
                # others' positions round differently, by an ulp or so.
                tol = 1e-9 * (1.0 + float(np.abs(X).max()) + float(np.abs(V).max()))
            assert dX <= tol and dV <= tol, (k, dX, dV)


#: Found exploring (numpy, 2,000 examples, 2026-12-05), reduced to five balls: no gravity,
#: velocity Verlet; at step 5 the first world's four balls take 64 rounds of impacts and
#: collapse (their plastic impulses at once), and with the second world's ball in the World
#: their velocities came out 6e-15 from their own alone: the broadphase listed their pairs in
#: its grid's order, whose cells the stranger moved, and the collapse's solve took them in
#: that order. The impacts now take the pairs in their bodies' rows' order
#: (engine.exact.pair_impacts.exact).
PAIRS_IN_THE_GRIDS_ORDER: Scene = {
    "balls": [
        (0.2301033285318649, 1.922128578993728e-286, -2.107857514256602, 1.3625946496682413e-283,
         0.2, 0.019624012798764152, 2.2250738585072014e-308, 0.7336665616632142, 5),
        (0.7233692446583175, -0.3942946544143305, -2.1701077339749526, 1.1828839632429915, 0.2,
         1.0, 0.10833952851645082, 1.1039664606472244, 6),
        (0.0, -0.969176315457131, 0.0, 2.907528946371393, 0.2, 1.0, 0.0, 0.0, 8),
        (0.0, 0.49597979746446663, 1.024246884041388, -1.4879393923934, 0.2, 1.0, 0.0, 0.0, 6),
        (-0.37532968201469924, 0.0, 2.042111552310664, 0.0, 0.2, 28.998618124491134, 0.0, 0.0,
         5),
    ],
    "colliders": [],
    "gravity": False,
    "method": "velocity_verlet",
    "steps": 60,
}  # fmt: skip


@fuzz(40)
@given(scene=scenes(filters=(4, 5, 5, 6, 7, 7, 8)))
@example(scene=PAIRS_IN_THE_GRIDS_ORDER)
@example(scene=HANDED_OVER_ELSEWHERE)
@example(scene=PILES_SIDE_BY_SIDE)
@example(scene=ONE_PILE_SCALED)
@example(scene=UNSEEN_UNDER_GRAVITY)
@example(scene=BANDS_SHARED)
@example(scene=WALL_HIT_ELSEWHERE)
@example(scene=GHOST_IN_THE_GRID)
@example(scene=UNSEEN_NEIGHBOUR)
@example(scene=UNSEEN_ON_THE_FLOOR)
@example(scene=STOPPED_WITH_A_STRANGER)
@example(scene=CROSSING_A_STRANGER)
def test_filtered_apart_worlds_move_as_if_alone(scene: Scene) -> None:
    check_as_if_alone(scene)


#: Found exploring (numpy path, `--hypothesis-profile=explore`, 2026-12-07; not shrunk: hypothesis
#: ran out of time): under "auto" with gravity, a ball of the first world slides up the slanted
#: segment at 55 m/s and leaves it at its end in step 35, while the second world's ball falls
#: along the room's wall. Alone, and with the other world in the World, it leaves 9.6e-7 m/s
#: apart (1.7e-8 of its speed; 1.2e-8 m at that step, growing as it flies), nine times the
#: 1e-9 relative bound that the closed form's restarts (an ulp of the state) stay within. Till
#: that step the two agree to 3e-14 m. The slide's round ends where the ball's path meets the
#: segment's round end (engine.exact.sweep_one: ``disc_hit_one``), a path tangent to it (the
#: centre slides at r from the face's line): a double root, which the 7e-15 m between the two
#: starts moves by its square root (t = 0.0042410793 s with the stranger, 0.0042410814 alone),
#: and the round end's normal there by 1.8e-8 rad, which the ball's velocity (55 m/s) takes as
#: it goes over the end. A slide's end is now found where the point of contact passes the
#: face's end, a simple root (engine.exact.sweep, "A slide's end").
LEAVES_A_SLIDE_APART: Scene = {
    "balls": [
        (37.78550360924861, 9.446375902312152, -755.7100721849722, -188.92751804624305,
         6.324555320336759, 1.0, 0.5, 0.0, 5),
        (60.45680577479777, 0.0, -755.7100721849722, 0.0, 14.997884186649117, 1.0, 0.0, 0.0, 7),
    ],
    "colliders": [
        Box((-98.09109694988095, -98.09109694988095), (98.09109694988095, 98.09109694988095),
            friction=0.0),
        Plane((0.0, -75.45468996144689), (0.0, 1.0), restitution=0.0, friction=0.0),
        Segment((-37.727344980723444, 18.863672490361722), (37.727344980723444, 0.0),
                restitution=0.0, friction=0.0),
        Circle((0.0, 0.0), 18.863672490361722, restitution=0.25, friction=0.0),
    ],
    "gravity": True,
    "method": "auto",
    "steps": 60,
}  # fmt: skip


def test_a_filtered_apart_world_leaves_a_slide_as_if_alone() -> None:
    check_as_if_alone(LEAVES_A_SLIDE_APART)


#: Found exploring (fast path, 2026-12-07, late; the numpy path alike, and the code before that
#: day's slide's end and spin's reach alike): under "auto" with gravity, the second world's
#: ball falls into the corner between the room's right wall and a peg (touching both: its
#: centre r from the wall and r + 0.158 m from the peg's), where it rocks, its velocity
#: changing sign each step (-0.035, 0.046, -0.0001 m/s). In step 28 its velocity in the World
#: is 2.5e-8 m/s from its own alone (its position 2.4e-10 m), three times the 1e-9 relative
#: bound; the first world's two balls fall clear through the room (filtered out of it) and
#: stay to the bit. The cause: the ball rests on the peg and comes to a stop on it again and
#: again (slid to a stop, or wedged against the wall: its velocity exactly 0), and each time
#: it was put back on the peg's arc (engine.exact.sweep_one's ``_project_one``, engine.exact.
#: resting's ``project``) it was given the speed sqrt(2 W.dx) of the pull's work over that
#: move, in the direction of the arc's tangent that a zero velocity's sign picks: 0.048 m/s
#: up the peg from rest in step 27, then in step 28 kicks of 1.33e-7 and 1.30e-7 m/s in the
#: two worlds from moves of rounding's size (2 W.dx 3.5e-14 and 3.3e-14). A body at rest
#: put back on an arc now keeps no speed from it.
WEDGED_APART: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.41098453567157145, 0.20549226783578572, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 7),
        (0.0, 0.41098453567157145, 0.0, -0.34248711305964286, 0.2, 1.0, 0.0, 0.0, 4),
    ],
    "colliders": [
        Box((-0.794279896373043, -0.794279896373043), (0.794279896373043, 0.794279896373043),
            restitution=0.0, friction=0.0),
        Plane((0.0, -0.6109845356715715), (0.0, 1.0), restitution=0.0, friction=0.0),
        Circle((0.34367880131525896, -0.30549226783578576), 0.15751945060282704,
               restitution=0.0, friction=0.0),
    ],
    "gravity": True,
    "method": "auto",
    "steps": 30,
}  # fmt: skip


def test_a_filtered_apart_world_rocks_in_a_corner_as_if_alone() -> None:
    check_as_if_alone(WEDGED_APART)


#: Found exploring (fast path, 1,500 fresh examples a test, 2026-12-06; the numpy path gives
#: the same bits; not shrunk: hypothesis ran out of time): ten balls of two worlds in one room
#: with a Plane and a Circle, no gravity, semi-implicit Euler. At step 48 one ball's velocity
#: in the two worlds together was 5.6e-17 m/s (an ulp) off what its world alone gives: a chain
#: of impacts in each world reached the rounds' cap and collapsed (engine.exact.pair_impacts,
#: ``plastic``), the two worlds' pairs in one call whose sweeps' count and tolerance were the
#: whole room's. Now each group of linked bodies collapses on its own.
ONE_ULP_APART: Scene = {
    "balls": [
        (-5.03350878850002, -3.6637177258934783, 6.907921583239445, 3.6637177258934783,
         0.33110941608887895, 59.33772564094753, 0.12, 1.671147905774768, 5),
        (-0.7096430903546247, 0.0012398490400717319, 0.726385885433949, -0.0012398490400717319,
         0.2, 0.6308427988712768, 0.9311059619802922, 1.6579031981938623, 4),
        (-6.040210546200024, -4.396461271072174, 6.907921583239445, 3.6637177258934783,
         0.33110941608887895, 59.33772564094753, 0.12, 1.671147905774768, 5),
        (6.845492932809496e-62, 3.38227950658785, -2.7035091924136347, -6.172717448483433,
         1.3696346843501837, 186.9724181943172, 0.6537665977529591, 1.2548788131127446, 8),
        (-7.046912303900028, -5.129204816250869, 6.907921583239445, 3.6637177258934783,
         0.33110941608887895, 59.33772564094753, 0.12, 1.671147905774768, 5),
        (-8.053614061600031, -5.861948361429565, 6.907921583239445, 3.6637177258934783,
         0.33110941608887895, 59.33772564094753, 0.12, 1.671147905774768, 5),
        (4.018330018240274, 1.0045677047594577, -2.70867804490172, 1.7219412965184324,
         1.990729906214189, 1.0, 0.9, 5.960464477539063e-08, 4),
        (-5.2284228477862005, 1.408172732082221e-137, 4.616646174751383, -0.7294996280477457,
         0.2000000000015963, 75.36829979579721, 0.6711101215776679, 0.0, 4),
        (0.0, 5.154736349681525, 0.0, -3.6819545354868035, 0.27340812447556234, 1.0, 0.0, 0.0, 4),
        (0.0, 0.0, 0.0, 0.0, 0.3796181395832032, 0.02115163811415639, 0.0, 0.9805537674266576, 7),
    ],
    "colliders": [
        Box((-10.900140520995583, -10.900140520995583), (10.900140520995583, 10.900140520995583),
            restitution=0.0, friction=0.0),
        Plane((0.0, -8.38472347768891), (0.0, 1.0), restitution=0.0, friction=0.0),
        Circle((0.0, -2.235607316872737),
            1.6494190387004402, restitution=0.0, friction=1.6706420599945249),
    ],
    "gravity": False,
    "method": "semi_implicit_euler",
    "steps": 60,
}  # fmt: skip


def test_filtered_apart_worlds_move_as_if_alone_to_the_last_bit_found_exploring() -> None:
    check_as_if_alone(ONE_ULP_APART)


#: Found exploring (fast path, 2,000 examples, 2026-12-05; numpy alike, and before that day's
#: changes): five balls of the first world, 0.001 to 10 kg and 0.2 to 55 m in radius, thrown
#: at the origin at 1,100 to 3,300 m/s (50 m a step), no colliders, gravity on; a 0.01 kg ball
#: of the second world at rest at the origin.
CONVERGING_AT_THREE_KM_S: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.2, 0.01, 0.0, 0.0, 7),
        (0.0, 146.62170774107855, 0.0, -2932.434154821571, 0.2, 0.1, 0.0, 0.0, 5),
        (-146.62170774107855, 0.0, 2932.434154821571, -1466.2170774107856, 6.324555320336759,
         1.0, 0.0, 0.0, 5),
        (0.0, 54.98314040290445, 0.0, -1099.6628080580892, 35.56558820077846, 1.0, 0.0, 0.0, 4),
        (0.0, 102.63519541875499, 0.0, -1466.2170774107856, 0.2, 10.0, 0.0, 0.0, 5),
        (146.62170774107855, 0.0, -2932.434154821571, 0.0, 54.768392685287225, 0.001, 0.0, 0.0,
         5),
    ],
    "colliders": [],
    "gravity": True,
    "method": "auto",
    "steps": 60,
}  # fmt: skip


# At step 2 the first world's balls were 2.27 m and 274 m/s from where they went alone: the
# struck bodies' search (engine.geometry.pair_grid.struck_pairs) passed gains on through the
# stranger's pairs, which never collide, so the bodies grew their reach in another order and
# a body grown early (each grows once) missed two pairs of its own world. Only pairs that can
# collide pass a gain on now, there and in the bent paths' search.
def test_worlds_filtered_apart_converging_at_three_km_s_move_as_if_alone() -> None:
    check_as_if_alone(CONVERGING_AT_THREE_KM_S)


# Found exploring (test_filtered_apart_worlds_move_as_if_alone at 2,000 examples on numpy,
# 2026-12-05: two worlds 1.3e-8 m/s apart where one ulp of x differed; the fast path alike).
# The end cap's quadratic has a double root at the tangency; the discriminant's rounding
# (1e-16 of its terms) split it by 1e-8 of the step, and an impact was taken that far off
# the tangent point, with an approach speed of that size: up to 1.7e-8 m/s upward in 190 of
# these 400 starts. A tangency within the discriminant's rounding is now a graze
# (engine.geometry.impact.grazes, in all three twins).
@pytest.mark.parametrize("kernels", PATHS)
def test_a_ball_sliding_off_a_segments_end_leaves_it_level(kernels: str) -> None:
    kicked = 0
    for i in range(400):
        w = World(integrator="auto", kernels=kernels)
        w.add_collider(Segment((-0.7959797974644667, 0.0), (0.7959797974644667, 0.0)))
        x0 = -0.7747737367038066 + (i - 200) * 1e-6
        ball = w.add(Body(Vector(x0, 0.2), Vector(-1.7879393923934002, 0.0), radius=0.2))
        for _ in range(3):
            w.step(DT)
        kicked += ball.vel.y != 0.0 or ball.pos.y != 0.2
    assert kicked == 0, f"{kicked} of 400 left the end moving up or off the rest height"


#: Found exploring (numpy; the same on the fast path), after the capped groups stopped each at
#: its own moment: STOPPED_WITH_A_STRANGER with the heavy ball 0 heading down-left too.
ROUNDS_SHARED_WITH_A_STRANGER: Scene = {
    **STOPPED_WITH_A_STRANGER,
    "balls": [
        (0.5111222321992216, 0.28109910327506993, -10.222444643984433, -5.621982065501399, 0.2,
         463.29332847080474, 0.0, 0.0, 7),
        *STOPPED_WITH_A_STRANGER["balls"][1:],
    ],
    "colliders": [
        Box((-2.0653664627706587, -2.0653664627706587), (2.0653664627706587, 2.0653664627706587),
            restitution=0.0, friction=1.886180752613483),
    ],
    "steps": 20,
}  # fmt: skip


def test_a_world_filtered_apart_keeps_its_own_impact_rounds() -> None:
    # The second world's pair left its path alone at step 18 (1.4 cm, 0.83 m/s): the first
    # world's 7 g ball squeezed against the floor meets its neighbour at t = 0 in every round
    # from step 6 on, and the rounds of a step were counted for all bodies together: in step
    # 18 the two worlds' impacts, at t = 0 and at 12.5 ms, took alternate rounds, so the
    # second's pair was capped after 32 of its own where alone it has 64. Each group of
    # linked bodies now counts its own (engine.exact.pair_impacts, "Rounds").
    check_as_if_alone(ROUNDS_SHARED_WITH_A_STRANGER)


#: Found exploring test_filtered_apart_worlds_move_as_if_alone (500 examples, numpy,
#: 2026-12-04), reduced to four balls: the first world's light ball (0.01 kg), resting on the
#: left wall of a room 1,750 m wide, is struck at step 8 by its 200 m ball, in the step in
#: which the second world's ball reaches that wall; with ball 0 of the first world (e 0.31) in
#: the World, its velocity differed from its world's alone by 2.5e-11 m/s (1e-14 of it) and
#: its position by an ulp. The 200 m ball's spin on its bent path (it bounced off the wall in
#: the static contacts, as the stranger did) was what the bounces after each one gave, a
#: cumulative sum over both bodies' bounces less the part before its own: it rounded an ulp
#: off. Each body's bounces are now summed on their own (engine.exact.bent_paths).
AN_ULP_FROM_A_STRANGER: Scene = {
    "balls": [
        (480.001259997165, 240.0006299985825, -9600.0251999433, -4800.01259997165, 0.2, 1.0,
         0.3125, 0.0, 5),
        (0.0, 0.0, 600.0015749964563, 0.0, 200.0, 1.0, 1.0, 1.0, 5),
        (0.0, -360.0009449978737, -3600.0094499787374, 7200.018899957475, 0.2, 0.01, 0.5, 1.0,
         5),
        (480.001259997165, 0.0, -9600.0251999433, 4800.01259997165, 0.2, 1.0, 0.0, 1.0, 7),
    ],
    "colliders": [
        Box((-873.8622931948403, -873.8622931948403), (873.8622931948403, 873.8622931948403),
            restitution=0.0),
    ],
    "gravity": False,
    "method": "semi_implicit_euler",
    "steps": 12,
}  # fmt: skip


def test_a_world_filtered_apart_moves_alone_to_the_bit_beside_a_ball_at_its_wall() -> None:
    check_as_if_alone(AN_ULP_FROM_A_STRANGER)


#: Found replaying on 2026-12-02 (its shrunk example): two worlds filtered apart, where a ball
#: of the second (5) falls onto another (6) across the place where a ball of the first (0)
#: rests. Its three balls left the path they take alone at step 15 (a strict xfail, put down
#: to the impacts' search or order); it holds since CROSSING_A_STRANGER's bug is fixed (omega
#: and alpha one array where nothing spun as the step began).
THROUGH_A_RESTING_STRANGER: Scene = {
    "balls": [
        (0.0, 0.0, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.3763241468392342, 0.1881620734196171, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 4),
        (0.7526482936784684, 0.3763241468392342, 0.0, 0.0, 0.2, 1.0, 0.0, 1.0, 5),
        (1.1289724405177026, 0.5644862202588513, 0.0, -9.408103670980854, 0.2, 1.0, 0.0, 1.0, 5),
        (1.5052965873569368, 0.7526482936784684, -4.704051835490427, 0.0, 0.2, 1.0, 0.0, 1.0, 7),
        (0.0, 0.7056077753235641, 0.0, -14.11215550647128, 0.2, 1.0, 0.0, 1.0, 7),
        (0.0, -0.8232090712108248, 0.0, 16.464181424216495, 0.2, 1.0, 0.0, 0.0, 7),
    ],
    "colliders": [],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}


def test_a_world_filtered_apart_moves_alone_where_its_balls_meet_over_a_stranger() -> None:
    check_as_if_alone(THROUGH_A_RESTING_STRANGER)


@fuzz(80)
@given(scene=scenes(filters=(4, 5, 5, 6, 7, 7, 8), gravity=False, colliders=False))
def test_filtered_apart_worlds_never_exchange_momentum(scene: Scene) -> None:
    """Without gravity or colliders, each world's momentum is its own (1e-12 of its sum of
    |m v|), and a ghost, which meets nothing, keeps its velocity bit for bit."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, bodies = build(scene)
        p = Probe(w, bodies, [])
        kind = np.array([b[8] for b in scene["balls"]])
        worlds = [np.isin(kind, FIRST), ~np.isin(kind, FIRST)]
        mv = p.m[:, None] * w.velocities()
        P0 = [mv[k].sum(axis=0) for k in worlds]
        scale = [float(np.hypot(*mv[k].T).sum()) for k in worlds]
        ghosts = kind == 4
        V0 = w.velocities()[ghosts]
        for k in range(scene["steps"]):
            step(w)
            mv = p.m[:, None] * w.velocities()
            for which, P, size in zip(worlds, P0, scale, strict=True):
                drift = float(np.abs(mv[which].sum(axis=0) - P).max())
                assert drift <= 1e-12 * size, (k, drift / size)
            assert np.array_equal(w.velocities()[ghosts], V0), k


# -- 6. determinism ---------------------------------------------------------------------------


def trace(world: World, steps: int) -> list[bytes]:
    """The state after each of ``steps`` steps, as bytes."""
    out = []
    for _ in range(steps):
        step(world)
        out.append(world.positions().tobytes() + world.velocities().tobytes())
    return out


@fuzz(45)
@given(scene=scenes(), cut=st.integers(1, 59))
def test_a_scene_reruns_bit_for_bit_and_a_snapshot_replays(scene: Scene, cut: int) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        steps = scene["steps"]
        first = trace(build(scene)[0], steps)
        w = build(scene)[0]
        assert trace(w, cut) == first[:cut], "the rerun differs"
        snap = w.snapshot()
        assert trace(w, steps - cut) == first[cut:], "the rerun differs"
        w.restore(snap)
        assert trace(w, steps - cut) == first[cut:], "the restored World replays differently"
        fresh = build(scene)[0]
        fresh.restore(snap)
        assert trace(fresh, steps - cut) == first[cut:], "a new World restored replays differently"


@st.composite
def closing_sets(draw: st.DrawFn) -> tuple[np.ndarray, ...]:
    """2 to 6 bodies (one in three a wall, w = 0) with masses over four decades, 1 to 8 pairs
    of them (no pair twice) with unit normals, velocities up to 10 m/s: (pa, pb, n, V, w)."""
    count = draw(st.integers(2, 6))
    w = np.array([draw(st.sampled_from((0.0, 1.0, 1.0))) / 10.0 ** draw(st.floats(-2, 2))
                  for _ in range(count)])  # fmt: skip
    ends = st.lists(st.integers(0, count - 1), min_size=2, max_size=2, unique=True)
    pairs = sorted({tuple(sorted(draw(ends))) for _ in range(draw(st.integers(1, 8)))})
    pa = np.array([p[0] for p in pairs], dtype=np.intp)
    pb = np.array([p[1] for p in pairs], dtype=np.intp)
    angle = np.array([draw(st.floats(0.0, 2.0 * math.pi)) for _ in pairs])
    n = np.stack([np.cos(angle), np.sin(angle)], axis=1)
    V = np.array([[draw(st.floats(-10.0, 10.0)), draw(st.floats(-10.0, 10.0))]
                  for _ in range(count)])  # fmt: skip
    return pa, pb, n, V, w


@fuzz(100)
@given(case=closing_sets())
# Found exploring (2,000 examples, numpy, 2026-12-05): a body (w 0.1) between a wall at rest
# and a wall coming at it at 1 m/s, the two normals 6e-8 rad apart; K near singular, the
# solve left the pair it pushed closing at 0.015 m/s. Now ``stopping`` returns None there.
@example(
    case=(
        np.array([0, 0, 2]),
        np.array([1, 2, 3]),
        np.array([[1.0, 0.0], [1.0, 0.0], [1.0, math.sin(2.0**-24)]]),
        np.array([[0.0, 0.0], [0.0, 0.0], [0.0, 0.0], [1.0, 0.0]]),
        np.array([0.0, 0.0, 0.1, 0.0]),
    )
)
def test_plastic_impulses_solved_at_once_are_the_sweeps_limit(case: tuple[np.ndarray, ...]) -> None:
    # engine.exact.pair_impacts.stopping, the linear complementarity problem of plastic
    # contacts: impulses >= 0, no pair left closing, a pushed pair parting at 0; the
    # velocities after are the projection of V onto the pairs' cone in the mass metric, so
    # unique (where the impulses need not be): what the sequential impulses' sweeps come to
    # where they settle (within 5,000), to 1e-6 m/s; momentum kept, kinetic energy not grown.
    from engine.exact.pair_impacts import stopping

    pa, pb, n, V, w = case
    ok = w[pa] + w[pb] > 0.0
    pa, pb, n = pa[ok], pb[ok], n[ok]
    if not len(pa):
        return
    scale = float(np.abs(V).max()) + 1.0
    lam = stopping(pa, pb, n, V, w, 1e-12 * scale)
    if lam is None:
        return  # (pairs that hold one another: the sweeps decide)
    V1 = V.copy()
    np.add.at(V1, pa, n * (lam * w[pa])[:, None])
    np.add.at(V1, pb, -n * (lam * w[pb])[:, None])
    after = ((V1[pa] - V1[pb]) * n).sum(axis=1)
    assert (lam >= 0.0).all()
    assert (after >= -1e-9 * scale).all(), after
    assert (np.abs(lam * after) <= 1e-9 * scale * (lam.max() + 1.0)).all()
    moving = w > 0.0
    m = np.where(moving, 1.0 / np.where(moving, w, 1.0), 0.0)
    if (w[pa] > 0.0).all() and (w[pb] > 0.0).all():  # no wall (a moving one does work)
        assert np.abs(((V1 - V) * m[:, None]).sum(axis=0)).max() <= 1e-9 * scale * m.sum()
        kinetic = [float((m * (U * U).sum(axis=1)).sum()) for U in (V, V1)]
        assert kinetic[1] <= kinetic[0] * (1.0 + 1e-12) + 1e-12
    # The sweeps: sequential impulses from zero (plain floats: a few pairs).
    v2 = V.tolist()
    acc = [0.0] * len(pa)
    rows = [(int(a), int(b), float(x), float(y), float(w[a]), float(w[b]))
            for a, b, (x, y) in zip(pa, pb, n, strict=True)]  # fmt: skip
    for _ in range(5000):
        most = 0.0
        for i, (a, b, x, y, wa, wb) in enumerate(rows):
            vn = (v2[a][0] - v2[b][0]) * x + (v2[a][1] - v2[b][1]) * y
            new = max(acc[i] - vn / (wa + wb), 0.0)
            d, acc[i] = new - acc[i], new
            v2[a][0] += x * d * wa
            v2[a][1] += y * d * wa
            v2[b][0] -= x * d * wb
            v2[b][1] -= y * d * wb
            most = max(most, abs(d) * (wa + wb))
        if most <= 1e-13 * scale:
            assert np.abs(np.array(v2) - V1)[moving].max(initial=0.0) <= 1e-6 * scale
            return


@pytest.mark.parametrize("kernels", PATHS)
def test_a_ball_struck_down_a_chain_meets_the_ball_beyond_it(kernels: str) -> None:
    """A 100 kg ball at 30 m/s strikes a 1 kg ball that strikes a 0.01 kg one (e = 1): the
    light one flies off at about 118 m/s, 2 m in the step, where a ball at rest 1.1 m beyond
    it stands. The struck bodies' search (engine.geometry.pair_grid.struck_pairs) grew the
    light ball's reach once, by the slow pair's bound (its neighbour's own speed), and not
    again when the heavy ball's link gave that neighbour 59 m/s: it passed through the
    ball beyond. A body now grows again where its bound rises. Momentum holds, and no two
    balls end a step overlapping."""
    for vb in (0.0, 0.7, 2.0):
        w = World(integrator="auto", solver="exact", kernels=kernels)
        light = w.add(Body(Vector(0.0, 0.0), mass=0.01, radius=0.2, restitution=1.0))
        w.add(Body(Vector(-0.41, 0.0), Vector(vb, 0.0), mass=1.0, radius=0.2, restitution=1.0))
        w.add(Body(Vector(-0.9, 0.0), Vector(30.0, 0.0), mass=100.0, radius=0.2,
                   restitution=1.0))  # fmt: skip
        beyond = w.add(Body(Vector(1.5, 0.0), mass=1.0, radius=0.2, restitution=1.0))
        p0 = 100.0 * 30.0 + 1.0 * vb
        for _ in range(10):
            w.step(DT)
            assert light.pos.x < beyond.pos.x  # never past it
            X = w.positions().reshape(-1, 2)
            gaps = [np.hypot(*(X[i] - X[j])) - 0.4 for i in range(4) for j in range(i + 1, 4)]
            assert min(gaps) >= -1e-9
        p = float((w.velocities().reshape(-1, 2)[:, 0] * np.array([0.01, 1.0, 100.0, 1.0])).sum())
        assert p == pytest.approx(p0, rel=1e-12)


#: Found by the fuzz exploring (fast path, 2,000 examples a test; numpy alike): ten discs
#: in a box 144 m wide without gravity, among them a 1.3 g disc of 8.3 m radius, a 1,000 kg one
#: and a 305 kg one, meet in the box's corner at hundreds of m/s, masses 7.8e5 apart (the
#: contacts guide: 1e4 is past the pile's soft step). The World warns at step 53 that the pile
#: is past what 4 iterations a step hold (an overlap of 401% of the smallest radius); in step
#: 55 the 305 kg disc strikes the light one, which the exact impacts took as a moving wall of
#: the pile (w = 0), and the wall's impulse, 5.6e5 N s, given to the 1.3 g disc in the pile's
#: soft step, sent it off at 4e8 m/s: the kinetic energy grew 2.1e5 times its first. Fixed: a
#: moving wall whose impulse would give the pair energy is struck as the free body it is
#: (engine.exact.pair_bounce, "A moving wall").
ENERGY_FROM_A_CORNER: Scene = {
    "balls": [
        (6.823407938633005e-142, -5.744145388772485e-24, -428.61188362192013,
         468.1219031854223, 0.2, 1.0, 0.5924998436164733, 0.6069431291387756, 0),
        (-23.69636303660115, 1.5665076321855076, 312.69588327605936, 461.3994022225501,
         6.568858267996633, 1.0, 0.9577404603120598, 0.8442264798686996, 0),
        (-38.800232728772365, -1.2490849237952524e-233, 588.289472769305, -240.01153834333135,
         0.4624374843894501, 2.5256559969645482, 0.5215478337319993, 0.896702715828986, 0),
        (-18.27138221774736, -34.20305900535623, 365.4276443549471, 894.0771570493116,
         21.165980057539244, 1.0, 0.9346235461444341, 0.6020854541729218, 1),
        (10.86971837456105, 5.434859187280525, 1.0175742706818097e-215, 7.615859832957822e-43,
         8.27706823216435, 0.0012889072031323483, 1.0, 0.9914214169774735, 0),
        (30.337310475250714, -7.593256199984195, -1041.5349444874562, 80.52485256290339, 0.2,
         1.0, 0.0, 0.0, 4),
        (10.86971837456105, 38.49498734572687, -217.39436749122098, -879.435054435815,
         0.8619319095765198, 999.999999999999, 0.9553532820987758, 0.7986055213907763, 1),
        (21.7394367491221, 10.86971837456105, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 0),
        (32.60915512368315, 16.304577561841576, -139.23107159025463, -489.66463735126763, 0.2,
         1.0, 0.2770382276223274, 0.0, 0),
        (25.40383425148722, -27.932935473885106, -508.0766850297444, 558.6587094777021,
         1.0015926208691464, 304.904722743249, 0.0, 1.6022269490838834, 0),
    ],
    "colliders": [
        Box((-71.97975078176412, -71.97975078176412), (71.97975078176412, 71.97975078176412),
            restitution=0.21015409299314497, friction=0.0),
    ],
    "gravity": False,
    "method": "auto",
    "steps": 60,
}  # fmt: skip


def test_discs_meeting_in_a_corner_with_masses_apart_by_1e6_gain_no_energy() -> None:
    check_energy_never_increases(ENERGY_FROM_A_CORNER)


def test_the_corner_scene_gains_no_energy_at_the_iterations_its_warning_asks() -> None:
    # The warning's advice (raise world.contact_iterations) holds there: at 16, no step gains.
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        w, _ = build(ENERGY_FROM_A_CORNER)
        w.contact_iterations = 4
        for _ in range(53):
            step(w)
    told = [x for x in said if issubclass(x.category, StabilityWarning)]
    assert told and "contact_iterations" in str(told[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w, _ = build(ENERGY_FROM_A_CORNER)
        w.contact_iterations = 16
        E0 = E = w.energy()
        for k in range(ENERGY_FROM_A_CORNER["steps"]):
            step(w)
            E1 = w.energy()
            assert E1 <= E + 1e-12 * E0, (k, (E1 - E) / E0)
            E = E1
