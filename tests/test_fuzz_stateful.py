"""A stateful fuzz of the World's public API (hypothesis's RuleBasedStateMachine).

A machine adds and removes bodies, colliders and links, steps, teleports bodies and sets
their velocities, hangs handlers that take things out of the World from inside its events,
and snapshots and restores, in any order hypothesis finds. After every rule:

* valid calls never raise (any exception fails the run);
* the state stays finite;
* no free body (not linked, not moved by the game) ends a step inside a solid collider it
  meets (links act after the contacts: a rod may pull its bob into a wall; that is a
  documented limit, README "Links");
* every contact's end follows its begin, one for one, in time order, ends of removed
  bodies and colliders included, and the contacts open now are the ones that began and did
  not end;
* a restored snapshot replays bit for bit: positions, velocities and events.

CI runs ``EXAMPLES`` runs of up to ``STEPS`` rules each (derandomized); set the environment
variable ``FUZZ_LONG=1`` for a run twenty times as long.
"""

from __future__ import annotations

import math
import os
import random
import warnings
from typing import Any

import numpy as np
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st
from hypothesis.stateful import (
    Bundle,
    RuleBasedStateMachine,
    consumes,
    initialize,
    invariant,
    multiple,
    precondition,
    rule,
)

from engine import (
    Body,
    Box,
    Cable,
    Circle,
    ContactEvent,
    Filter,
    Pin,
    Plane,
    Rod,
    Segment,
    Vector,
    World,
)
from engine.forces import Gravity

LONG = bool(os.environ.get("FUZZ_LONG"))
EXAMPLES = 800 if LONG else 40
STEPS = 60 if LONG else 30

coord = st.floats(-8.0, 8.0, allow_nan=False, allow_infinity=False)
speed = st.floats(-30.0, 30.0, allow_nan=False, allow_infinity=False)
radius = st.sampled_from([0.0, 0.05, 0.2, 0.5, 1.0])
filters = st.sampled_from([Filter(), Filter(), Filter(group=1), Filter(categories=0b10)])
dts = st.sampled_from([1 / 240, 1 / 120, 1 / 60, 1 / 30])


def key(e: ContactEvent) -> tuple[int, int]:
    return id(e.body), id(e.collider)


class WorldMachine(RuleBasedStateMachine):
    """A World driven by random valid calls; the invariants below hold after each."""

    bodies = Bundle("bodies")
    colliders = Bundle("colliders")

    def __init__(self) -> None:
        super().__init__()
        self.world = World(integrator="auto")
        self.world.add_force(Gravity((0.0, -9.81)))
        self.open: set[tuple[int, int]] = set()  # the contacts open, from the events seen
        self.removing = False  # handlers that take things out are live
        warnings.simplefilter("ignore")

    # -- things in the World --------------------------------------------------------------
    @initialize(target=bodies, n=st.integers(0, 14), seed=st.integers(0, 2**16), room=st.booleans())
    def scene(self, n: int, seed: int, room: bool) -> Any:
        """A start: a room (or a floor) with pegs, and a few balls in it."""
        rng = random.Random(seed)
        w = self.world
        if room:
            w.add_collider(Box((-10, -10), (10, 10), restitution=0.6))
        else:
            w.add_collider(Plane((0, -10), (0, 1)))
        for _ in range(rng.randint(0, 3)):
            w.add_collider(Circle((rng.uniform(-8, 8), rng.uniform(-8, 0)), rng.uniform(0.2, 1)))
        made = [
            w.add(
                Body(
                    Vector(rng.uniform(-8, 8), rng.uniform(-5, 9)),
                    Vector(rng.uniform(-5, 5), rng.uniform(-5, 5)),
                    Vector(0, 0),
                    radius=rng.choice([0.2, 0.3, 0.5]),
                    restitution=rng.choice([0.0, 0.5, 0.9]),
                )
            )
            for _ in range(n)
        ]
        return multiple(*made)

    @rule(
        target=bodies,
        x=coord,
        y=coord,
        vx=speed,
        vy=speed,
        r=radius,
        mass=st.sampled_from([0.01, 1.0, 100.0]),
        e=st.sampled_from([0.0, 0.5, 1.0]),
        mu=st.sampled_from([0.0, 0.5]),
        kinematic=st.booleans(),
        f=filters,
    )
    def add_body(
        self,
        x: float,
        y: float,
        vx: float,
        vy: float,
        r: float,
        mass: float,
        e: float,
        mu: float,
        kinematic: bool,
        f: Filter,
    ) -> Body:
        b = Body(
            Vector(x, y),
            Vector(vx, vy),
            Vector(0, 0),
            mass=mass,
            radius=r,
            restitution=e,
            friction=mu,
            kinematic=kinematic and r > 0.0,
            filter=f,
        )
        return self.world.add(b)

    @rule(b=consumes(bodies))
    def remove_body(self, b: Body) -> None:
        if b.world is self.world:
            self.world.remove(b)

    @rule(
        target=colliders,
        kind=st.sampled_from(["plane", "segment", "capsule", "circle", "box"]),
        x=coord,
        y=coord,
        size=st.floats(0.2, 6.0),
        angle=st.floats(0.0, 2 * math.pi),
        sensor=st.booleans(),
        f=filters,
    )
    def add_collider(
        self, kind: str, x: float, y: float, size: float, angle: float, sensor: bool, f: Filter
    ) -> Any:
        c, s = math.cos(angle), math.sin(angle)
        kw: dict[str, Any] = {"sensor": sensor and kind != "plane", "filter": f}
        if kind == "plane":
            made: Any = Plane((x, y - 10.0), (0.3 * c, 1.0), **kw)
        elif kind in ("segment", "capsule"):
            made = Segment(
                (x - size * c, y - size * s),
                (x + size * c, y + size * s),
                0.3 if kind == "capsule" else 0.0,
                **kw,
            )
        elif kind == "circle":
            made = Circle((x, y), size / 4, **kw)
        else:
            made = Box((x - 2 * size - 6, y - 12), (x + 2 * size + 6, y + 12), **kw)
        return self.world.add_collider(made)

    @rule(c=consumes(colliders))
    def remove_collider(self, c: Any) -> None:
        if c in self.world.colliders:
            self.world.remove_collider(c)

    @rule(a=bodies, b=bodies, kind=st.sampled_from(["rod", "cable", "pin"]))
    def add_link(self, a: Body, b: Body, kind: str) -> None:
        w = self.world
        if a.world is not w or b.world is not w or a.kinematic:
            return
        if kind == "pin":
            if not any(isinstance(k, Pin) and k.body is a for k in w.links):
                w.add_link(Pin(a, a.pos))
        elif a is not b and (a.pos - b.pos).magnitude() > 1e-3:
            w.add_link(Rod(a, b) if kind == "rod" else Cable(a, b, (a.pos - b.pos).magnitude()))

    @precondition(lambda self: len(self.world.links) > 0)
    @rule(k=st.integers(0, 100))
    def remove_link(self, k: int) -> None:
        links = self.world.links
        self.world.remove_link(links[k % len(links)])

    # -- moving things by hand -------------------------------------------------------------
    @rule(b=bodies, x=coord, y=coord)
    def teleport(self, b: Body, x: float, y: float) -> None:
        pinned = any(isinstance(k, Pin) and k.body is b for k in self.world.links)
        if b.world is self.world and not pinned:  # (a pinned body refuses: tested elsewhere)
            b.pos = Vector(x, y)

    @rule(b=bodies, vx=speed, vy=speed)
    def set_velocity(self, b: Body, vx: float, vy: float) -> None:
        if b.world is self.world:
            b.vel = Vector(vx, vy)

    # -- handlers that change the World from inside its events ------------------------------
    @rule(b=bodies)
    def hang_removing_handler(self, b: Body) -> None:
        w = self.world
        if b.world is not w:
            return

        def take_out(e: ContactEvent) -> None:
            if not self.removing:
                return
            other = e.collider
            if isinstance(other, Body):
                if other.world is w:
                    w.remove(other)
            elif other in w.colliders:
                w.remove_collider(other)

        w.on_contact(b, begin=take_out)
        self.removing = True

    # -- time ------------------------------------------------------------------------------
    @rule(dt=dts, n=st.integers(1, 5))
    def step(self, dt: float, n: int) -> None:
        for _ in range(n):
            self.world.step(dt)
            self.check_events()
            self.check_outside()

    @precondition(lambda self: len(self.world.bodies) > 0)
    @rule(dt=dts, n=st.integers(1, 6))
    def snapshot_replays_bit_for_bit(self, dt: float, n: int) -> None:
        w = self.world
        removing, self.removing = self.removing, False  # no structural change in the replay
        saved = w.snapshot()
        opened = set(self.open)

        def run() -> list[Any]:
            out = []
            for _ in range(n):
                w.step(dt)
                out.append(
                    (
                        w.positions().tobytes(),
                        w.velocities().tobytes(),
                        [(key(e), e.time, tuple(e.point), tuple(e.impulse)) for e in w.began],
                        [(key(e), e.time, e.removal) for e in w.ended],
                    )
                )
            return out

        first = run()
        w.restore(saved)
        self.open = set(opened)
        second = run()
        assert first == second
        w.restore(saved)
        self.open = opened
        self.removing = removing

    # -- what must hold -------------------------------------------------------------------
    def check_events(self) -> None:
        w = self.world
        for events in (w.began, w.ended):
            times = [e.time for e in events]
            assert times == sorted(times), times
        merged = sorted(
            [(e.time, 0, e) for e in w.began] + [(e.time, 1, e) for e in w.ended],
            key=lambda m: (m[0], m[1]),
        )
        for _, kind, e in merged:
            k = key(e)
            if kind == 0:
                assert k not in self.open, f"began twice: {e}"
                self.open.add(k)
            else:
                assert k in self.open, f"ended without a begin: {e}"
                self.open.discard(k)
        assert self.open == {key(e) for e in w.touching}

    def check_outside(self) -> None:
        w = self.world
        linked = {id(b) for k in w.links for b in k.bodies}
        for b in w.bodies:
            if b.kinematic or id(b) in linked or b.radius == 0.0:
                continue
            for c in w.colliders:
                if c.sensor or not b.filter.collides(c.filter):
                    continue
                depth = b.radius - c.distance(b.pos)
                scale = 1.0 + max(abs(b.pos.x), abs(b.pos.y))
                assert depth <= 1e-9 * scale, (b, c, depth)

    @invariant()
    def finite(self) -> None:
        w = self.world
        if w.bodies:
            assert np.isfinite(w.positions()).all() and np.isfinite(w.velocities()).all()
        assert math.isfinite(w.t)


WorldMachine.TestCase.settings = settings(
    max_examples=EXAMPLES,
    stateful_step_count=STEPS,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
test_world_machine = WorldMachine.TestCase
