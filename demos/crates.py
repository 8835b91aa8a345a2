"""Crates: bodies with shapes stack, slide and ride a platform (``Body(shape=...)``).

Run with ``python -m demos crates``. Two columns of 1 m crates (boxes, 2 kg, friction 0.6)
are let go a hand's breadth apart and land on one another; a plank (a capsule ``Segment``
with a radius) falls across the right column; a ball rolls in from the left at 5 m/s into
the left column and shoves it along the floor; a platform the game moves (a kinematic box)
lifts a small crate and stops; an L of two boxes (``Body(shapes=[...])``), stood on its end
with its centre of mass past its foot, tips over and comes to rest on its hull's edge. The
crates turn: they land, stack and are shoved at their angles, on the soft step (``World()``
chooses it for crates: engine.pipeline.solver_choice). The read-outs: how many of the bodies
sleep, and the deepest overlap of two crates (or a crate and the floor) as a fraction of a
crate's height, measured from the positions, now and the worst so far. They are of the state
the frame shows, at the time its clock says: the frame drawn between two steps (``alpha`` < 1: at 30
frames a second and dt = 1/60 s, exactly on the earlier one) reads the earlier state, so the
frame at t = 0 reads the crates where they were put. Everything is drawn by
``engine.render.draw_world``.
"""

from __future__ import annotations

import math

import numpy as np
import pygame

from demos.cli import Demo
from demos.kept import KeptReadouts
from engine import Body, Plane, Polygon, Segment, Vector, World
from engine.forces import Gravity
from engine.render import INK, MUTED, PAPER, Camera, Scene, draw_text
from engine.render.world_view import draw_world

__all__ = [
    "DEMO", "CratesScene", "crates_world", "deepest_crate_overlap", "CRATE", "LIFT_STOP",
    "ELL_BAR", "ELL_POST", "ELL_AT",
]  # fmt: skip

CRATE = 1.0  # m, a crate's side
SMALL = 0.6  # m, the crate on the platform
DT = 1.0 / 60.0  # s
LIFT_SPEED = 0.5  # m/s
LIFT_STOP = 3.0  # s: the platform stops here
#: The L (m): a bar along +x from its frame's origin, a post up from the bar's left end; put
#: with its frame's origin at (ELL_AT, 0) and turned a quarter turn clockwise, the bar upright.
ELL_BAR = [(0.0, 0.0), (1.2, 0.0), (1.2, 0.3), (0.0, 0.3)]
ELL_POST = [(0.0, 0.3), (0.3, 0.3), (0.3, 1.3), (0.0, 1.3)]
ELL_AT = 5.5
#: (left, bottom, right, top) of the scene in metres.
VIEW = (-1.2, -0.3, 10.2, 6.6)


def crates_world() -> tuple[World, dict[str, list[Body]]]:
    """The scene's World and its bodies by kind: crates, plank, ball, lift, rider, ell."""
    # World() chooses the soft step for crates (engine.pipeline.solver_choice): Box2D's contacts.
    w = World(integrator="auto")
    w.add_force(Gravity((0.0, -9.81)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    w.add_collider(Segment((-1.0, 0.0), (-1.0, 6.0)))
    w.add_collider(Segment((10.0, 0.0), (10.0, 6.0)))

    def crate(x: float, y: float, side: float = CRATE) -> Body:
        return w.add(
            Body(Vector(x, y), shape=Polygon.box(side, side), mass=2.0, restitution=0.0,
                 friction=0.6)
        )  # fmt: skip

    # Two columns, each crate 0.1 m above the one below: they land on one another.
    crates = [crate(1.5, 0.5 + 1.1 * k) for k in range(4)]
    crates += [crate(4.5, 0.5 + 1.1 * k) for k in range(3)]
    plank = w.add(
        Body(Vector(4.6, 4.6), shape=Segment((-1.3, 0.0), (1.3, 0.0), radius=0.1), mass=1.0,
             restitution=0.0, friction=0.6)
    )  # fmt: skip
    ball = w.add(
        Body(Vector(-0.5, 0.35), Vector(5.0, 0.0), radius=0.35, mass=3.0, restitution=0.3,
             friction=0.2)
    )  # fmt: skip
    lift = w.add(
        Body(Vector(8.0, 0.1), Vector(0.0, LIFT_SPEED), shape=Polygon.box(2.0, 0.2),
             kinematic=True)
    )  # fmt: skip
    rider = crate(8.0, 0.2 + SMALL / 2, SMALL)
    # An L of two boxes (Body(shapes=[...]), engine.body_shapes), stood on its bar's end with
    # its post out to the right at the top: its centre of mass is past its foot, so it tips.
    ell = w.add(
        Body(Vector(ELL_AT, 0.0), shapes=[Polygon(ELL_BAR), Polygon(ELL_POST)], density=2.0,
             angle=-0.5 * math.pi, restitution=0.0, friction=0.6)
    )  # fmt: skip
    bodies = {"crates": crates, "plank": [plank], "ball": [ball], "lift": [lift]}
    bodies["rider"], bodies["ell"] = [rider], [ell]
    return w, bodies


def _corners(crate: Body) -> np.ndarray:
    """A crate's corners in the world (4, 2): its box turned by its angle, at its position."""
    c, s = math.cos(crate.angle), math.sin(crate.angle)
    v = np.array([(p.x, p.y) for p in crate.shape.vertices])
    return np.stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]], axis=1) + (
        crate.pos.x,
        crate.pos.y,
    )


def _overlap(p: np.ndarray, q: np.ndarray) -> float:
    """How deep two convex polygons (corners counter-clockwise) overlap: the least overlap of
    their shadows over the normals of both one's edges (separating axes); <= 0: apart."""
    least = math.inf
    for poly in (p, q):
        edges = np.roll(poly, -1, axis=0) - poly
        normals = np.stack([edges[:, 1], -edges[:, 0]], axis=1)
        normals /= np.hypot(normals[:, 0], normals[:, 1])[:, None]
        for n in normals:
            a, b = p @ n, q @ n
            least = min(least, min(a.max(), b.max()) - max(a.min(), b.min()))
    return least


def deepest_crate_overlap(crates: list[Body]) -> float:
    """The deepest overlap (m) of two crates, or of a crate and the floor (y = 0), at their
    angles: the floor's by the lowest corner, two crates' by the separating axes."""
    deepest = 0.0
    corners = [_corners(c) for c in crates]
    for i, p in enumerate(corners):
        deepest = max(deepest, -float(p[:, 1].min()))
        for q in corners[i + 1 :]:
            deepest = max(deepest, _overlap(p, q))
    return deepest


class CratesScene(KeptReadouts, Scene):
    """Crates, a plank, a ball, a platform and an L: bodies with shapes in one World."""

    name = "stack"
    summary = "crates land on one another, a ball shoves a column, a platform lifts a crate"
    duration = 6.0
    dt = DT
    min_size = (480, 270)
    strobe_interval = 0.5
    world: World

    def build(self, size: tuple[int, int]) -> None:
        self.world, self.bodies = crates_world()
        w, h = size
        s = self.s = h / 360
        self.header = round(72 * s)
        m = round(8 * s)
        x0, y0, x1, y1 = VIEW
        scale = min((w - 2 * m) / (x1 - x0), (h - self.header - m) / (y1 - y0))
        self.camera = Camera(
            scale, ((w - scale * (x1 - x0)) / 2 - scale * x0, (h - m) + scale * y0)
        )
        #: The deepest overlap (m) now and the worst of every state stepped through, and both
        #: as they were before the last step (what a frame between the last two states reads).
        crates = self.bodies["crates"] + self.bodies["rider"]
        self.now = self.deepest = self.now_before = self.deepest_before = deepest_crate_overlap(
            crates
        )

    #: The read-outs (beside the World) that a snapshot keeps.
    kept = ("now", "deepest", "now_before", "deepest_before")

    def step(self, dt: float) -> None:
        self.now_before, self.deepest_before = self.now, self.deepest
        self.world.step(dt)
        lift = self.bodies["lift"][0]
        if self.world.t >= LIFT_STOP - 1e-9 and lift.vel.y != 0.0:
            lift.vel = Vector(0.0, 0.0)  # the game stops its platform
        crates = self.bodies["crates"] + self.bodies["rider"]
        self.now = deepest_crate_overlap(crates)
        self.deepest = max(self.deepest, self.now)

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        surface.fill(PAPER)
        draw_world(surface, self.world, self.camera, alpha)
        s, w = self.s, surface.get_width()
        x = round(8 * s)
        t = self.time(alpha)
        everything = self.world.bodies
        asleep = sum(self.world.is_sleeping(b) for b in everything)
        # The state the frame shows: the World's now only at alpha = 1, else the one before.
        now, worst = (
            (self.now, self.deepest) if alpha >= 1.0 else (self.now_before, self.deepest_before)
        )
        draw_text(surface, "Crates: bodies with shapes", (x, 4 * s), round(22 * s))
        draw_text(surface, f"t = {t:4.2f} s", (w - x, 4 * s), round(22 * s), INK, "topright")
        draw_text(
            surface,
            f"asleep {asleep} of {len(everything)}   deepest overlap of crates "
            f"{100 * now / CRATE:.2f}% of a crate (worst so far {100 * worst / CRATE:.2f}%)",
            (x, 32 * s),
            round(15 * s),
            MUTED,
        )
        draw_text(
            surface,
            "crates and the ball turn; blue: awake, grey: asleep, vermillion: moved by the game",
            (x, 50 * s),
            round(15 * s),
            MUTED,
        )


DEMO = Demo(
    name="crates",
    summary="Crates (boxes), a plank (a capsule), a ball and a platform: bodies with shapes",
    scenes={"stack": CratesScene},
)
