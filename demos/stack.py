"""Stacks: boxes that turn stack into a pyramid, topple as dominoes, stand as a tower, tumble.

Run with ``python -m demos stack``. Boxes of 1 kg with friction 0.6 on a floor, dt = 1/60 s:

* ``pyramid``: 210 boxes of 1 m, a base of 20, let go touching: they settle and sleep (grey);
  the read-out says how far any box has moved from where it was put and when all slept (the
  issue "Bodies that turn" asks at most 1 cm by 60 s and asleep within 2 s);
* ``dominoes``: 30 dominoes 0.1 m thick and 1 m tall, 0.5 m apart; the first is flicked at its
  top (an impulse of 0.3 N s, ``apply_impulse(j, at=...)``) and each knocks over the next;
  the read-out counts those down and marks each one's angle by its colour;
* ``tower``: 20 boxes in a column with sleeping off, the scene where iterative solvers fail
  (pymunk's falls at 1.7 s); the read-out gives the top box's drift and the column's sag: on
  the soft step it stands still (no drift and 5.2 mm of sag by 60 s, measured; Box2D v3's
  drifts 16 mm and sags 133 mm), where the exact models' corner contacts walk it 0.5 m aside;
* ``tumbler``: Box2D's tumbler, 500 boxes of 0.25 m (1/16 kg) in a room 19 m wide whose four
  walls, kinematic bodies, turn at 25 degrees a second (``TUMBLE``, Box2D's benchmark): the
  pile lands, is carried up a wall and tumbles down the room as it turns. The read-out counts
  the boxes whose centre is past a wall (none) and the deepest a corner went into a wall and
  two boxes into each other (where a falling box strikes the pile: 9 cm here, 13 cm on the
  soft step, and over a whole side in Box2D v3's own run of the scene);
* ``tumbler90``: the same room turning at 90 degrees a second (``TUMBLE_STRESS``), a stress
  scene: beyond 3.98 m from its centre the room is a centrifuge (omega^2 r > g), so the boxes
  are pinned to the walls, not tumbling, and each corner of the room strikes what it meets at
  up to 21 m/s (pymunk loses 93 boxes through the walls here).

The walls look alike a quarter turn apart, so a frame says the room's angle ("the walls at 135
degrees") and a dot marks one wall: at 90 degrees a second frames a whole second apart would
otherwise show the room as if still.

The dominoes' and the tower's World is ``World()``'s own choice of solver (``solver="auto"``):
boxes that meet something take the soft step (engine.pipeline.solver_choice). The pyramid and
the tumblers take the exact models: let go touching, the soft step's pyramid sags 3 cm before
its contacts have loads to start from, and takes 4.3 s to rise back and sleep, where the scene
asks 2 s; the soft step's tumbler overlaps its boxes as deep (91 against 92 mm over 20 s,
``tumbler(solver="soft")`` on 2026-12-06, since a corner's rows on a face that turns are taken
again as it turns; 130 mm before), and on the numpy path its plain-Python solve takes four
times the exact models' step at 500 boxes. Each read-out names its solver; the builders take
``solver`` (the benchmarks compare both).

Everything is drawn by ``engine.render.draw_world``: awake boxes blue, asleep grey. The
read-outs measure what the frame draws: the boxes where ``draw_world`` blends them for the
frame's time (the clock's), so the frame at t = 0 shows the boxes where they were put and
reads 0; a worst-so-far counts the states the World has stepped through up to that time.
"""

from __future__ import annotations

import math

import numpy as np
import pygame

from demos.cli import Demo
from demos.kept import KeptReadouts
from demos.warned import Warned, headline, step_noting
from engine import Body, Plane, Polygon, Vector, World
from engine.forces import Gravity
from engine.render import INK, MUTED, PAPER, Camera, Scene, draw_text
from engine.render.world_view import angle_of, draw_world

__all__ = [
    "DEMO",
    "MARK",
    "PyramidScene",
    "DominoScene",
    "TowerScene",
    "TumblerScene",
    "StressTumblerScene",
    "pyramid",
    "pyramid_centres",
    "dominoes",
    "tower",
    "tower_centres",
    "tumbler",
    "tumbler_walls",
    "tumbler_centres",
    "in_room",
    "room_frame",
    "into_walls",
    "outside",
    "solved_by",
]

DT = 1.0 / 60.0  # s
G = 9.81  # m/s^2
FRICTION = 0.6  # the boxes'; combined by product: 0.6 on the floor, 0.36 box on box
FLOOR_FRICTION = 1.0
MASS = 1.0  # kg, each box
SIDE = 1.0  # m, a pyramid's and a tower's boxes
BASE = 20  # boxes in the pyramid's bottom row
DOMINOES = 30
FLICK = 0.3  # N s, at the first domino's top
TUMBLED = 500  # boxes in the tumbler
TUMBLED_SIDE = 0.25  # m
TUMBLED_MASS = 0.0625  # kg: Box2D's density 1 on 0.25 x 0.25 m
TUMBLE = math.radians(25.0)  # rad/s: the tumbler's walls turn 25 degrees a second (Box2D's)
TUMBLE_STRESS = math.pi / 2  # rad/s: the stress scene's, 90 degrees a second
ROOM = 9.5  # m: half the tumbler's inside width
#: The dot that marks one of the tumbler's walls (its first, at +x when the room is at 0): a
#: colour no other part of the frame uses, so a test finds it.
MARK = (240, 228, 66)


def _world(kernels: str | None = None, solver: str = "auto") -> World:
    """A floor under gravity, on the path ``kernels`` (None: the default, engine.kernels),
    with ``solver`` (World's)."""
    w = World(integrator="auto", kernels=kernels, solver=solver)
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0), friction=FLOOR_FRICTION))
    return w


def solved_by(world: World) -> str:
    """The solver ``world`` uses, as a read-out says it."""
    return "the soft step" if world.solver == "soft" else "the exact models"


def _box(w: World, x: float, y: float, width: float = SIDE, height: float = SIDE) -> Body:
    return w.add(
        Body(Vector(x, y), shape=Polygon.box(width, height), mass=MASS, friction=FRICTION,
             restitution=0.0)
    )  # fmt: skip


def pyramid_centres(base: int = BASE) -> list[tuple[float, float]]:
    """Where a pyramid's boxes (SIDE m) are put (m): ``base`` in the bottom row, centred on
    x = 0, each row centred on the one below, touching; row by row from the floor up."""
    return [
        (SIDE * (k + 0.5 * row - 0.5 * (base - 1)), SIDE * (0.5 + row))
        for row in range(base)
        for k in range(base - row)
    ]


def pyramid(
    base: int = BASE, *, kernels: str | None = None, solver: str = "auto"
) -> tuple[World, list[Body]]:
    """A pyramid of boxes (``pyramid_centres``) on a floor, on the path ``kernels``, with
    ``solver``."""
    w = _world(kernels, solver)
    return w, [_box(w, x, y) for x, y in pyramid_centres(base)]


def dominoes(
    n: int = DOMINOES, *, kernels: str | None = None, solver: str = "auto"
) -> tuple[World, list[Body]]:
    """``n`` dominoes (0.1 by 1 m) 0.5 m apart, the first flicked forward at its top, on the
    path ``kernels``, with ``solver``."""
    w = _world(kernels, solver)
    row = [_box(w, 0.5 * k, 0.5, 0.1, 1.0) for k in range(n)]
    row[0].apply_impulse(Vector(FLICK, 0.0), at=(0.0, 0.95))
    return w, row


def tower_centres(n: int = 20) -> list[tuple[float, float]]:
    """Where a tower's ``n`` boxes (SIDE m) are put (m): a column on x = 0, touching, from the
    floor up."""
    return [(0.0, SIDE * (0.5 + k)) for k in range(n)]


def tower(
    n: int = 20, *, kernels: str | None = None, solver: str = "auto"
) -> tuple[World, list[Body]]:
    """``n`` 1 m boxes in a column (``tower_centres``), with sleeping off (every step is
    solved), on the path ``kernels``, with ``solver``."""
    w = _world(kernels, solver)
    w.sleep_time = math.inf
    return w, [_box(w, x, y) for x, y in tower_centres(n)]


def tumbler_walls() -> list[list[tuple[float, float]]]:
    """The tumbler's four walls in its frame, each its four corners (m, counter-clockwise):
    1 m thick, their inner faces ``ROOM`` m from the centre."""
    h = ROOM + 0.5  # the walls' middles
    sides = [(h, 0.0, 0.5, h), (-h, 0.0, 0.5, h), (0.0, h, h, 0.5), (0.0, -h, h, 0.5)]
    return [[(cx - a, cy - b), (cx + a, cy - b), (cx + a, cy + b), (cx - a, cy + b)]
            for cx, cy, a, b in sides]  # fmt: skip


def tumbler_centres(n: int = TUMBLED) -> list[tuple[float, float]]:
    """Where the tumbler's ``n`` boxes start (m): a square grid 0.4 m apart about the centre,
    row by row from the lowest (Box2D's sample)."""
    g = math.ceil(math.sqrt(n))
    corner = -0.2 * (g - 1)
    return [(corner + 0.4 * (k % g), corner + 0.4 * (k // g)) for k in range(n)]


def tumbler(
    n: int = TUMBLED, spin: float = TUMBLE, *, kernels: str | None = None, solver: str = "auto"
) -> tuple[World, list[Body], list[Body]]:
    """``n`` boxes of 0.25 m (1/16 kg) at ``tumbler_centres`` in a room ``2 ROOM`` m wide
    whose four walls (kinematic bodies about its centre, ``tumbler_walls``, friction 1.0)
    turn at ``spin`` rad/s, as in Box2D's tumbler (``shared/anchors/box2d``): (world, boxes,
    walls), on the path ``kernels`` (None: the default), with ``solver``. The boxes are all
    alike (``room_frame`` takes their side)."""
    w = World(integrator="auto", kernels=kernels, solver=solver)
    w.add_force(Gravity((0.0, -G)))
    walls = w.add_all(
        Body(Vector(0.0, 0.0), shape=Polygon(corners), kinematic=True, angular_velocity=spin,
             friction=1.0)
        for corners in tumbler_walls()
    )  # fmt: skip
    boxes = w.add_all(
        Body(Vector(x, y), shape=Polygon.box(TUMBLED_SIDE, TUMBLED_SIDE), mass=TUMBLED_MASS,
             friction=FRICTION, restitution=0.0)
        for x, y in tumbler_centres(n)
    )  # fmt: skip
    return w, boxes, walls


def in_room(boxes: list[Body], walls: list[Body]) -> tuple[np.ndarray, np.ndarray]:
    """Each box's centre in the room's frame (the walls', (n, 2), m) and how far its deepest
    corner is past the room's inner faces ((n,), m; <= 0 for a box inside)."""
    frame = walls[0]
    pos = np.array([tuple(b.pos) for b in boxes]) - tuple(frame.pos)
    return room_frame(pos, np.array([b.angle for b in boxes]), frame.angle)


def room_frame(pos: np.ndarray, turn: np.ndarray, angle: float) -> tuple[np.ndarray, np.ndarray]:
    """``in_room`` for boxes of the tumbler's side at ``pos`` (n, 2) from the room's centre,
    turned ``turn`` (n,) in a room turned ``angle`` (rad): (centres in the room's frame, how
    far each one's deepest corner is past the inner faces (m)); any engine's bodies."""
    c, s = np.cos(angle), np.sin(angle)
    centre = pos @ np.array([[c, -s], [s, c]])  # R(-angle) pos, by rows
    h = 0.5 * TUMBLED_SIDE
    corners = np.array([(-h, -h), (h, -h), (h, h), (-h, h)])
    cb, sb = np.cos(turn - angle)[:, None], np.sin(turn - angle)[:, None]
    x = centre[:, :1] + cb * corners[:, 0] - sb * corners[:, 1]
    y = centre[:, 1:] + sb * corners[:, 0] + cb * corners[:, 1]
    return centre, np.maximum(np.abs(x), np.abs(y)).max(axis=1) - ROOM


def boxes_into_each_other(pos: np.ndarray, turn: np.ndarray) -> float:
    """How deep the two of the tumbler's boxes at ``pos`` (n, 2) turned ``turn`` (n,) that go
    deepest into each other do (m; <= 0: none overlaps), any engine's bodies: for each pair
    whose centres are nearer than a box's diagonal, the least of its overlaps along the four
    edge normals (the separating axes: the depth a solver pushes out), box i's half extent
    along a unit u being h (|cos(q_i) u_x + sin(q_i) u_y| + |-sin(q_i) u_x + cos(q_i) u_y|)."""
    reach = TUMBLED_SIDE * math.sqrt(2.0)  # (farther apart than a diagonal: they cannot touch)
    n = len(pos)
    order = np.argsort(pos[:, 0], kind="stable")
    x = pos[order, 0]
    # The pairs a < b (in x order) within ``reach`` along x, then within it.
    count = np.searchsorted(x, x + reach, side="right") - np.arange(n) - 1
    first = np.repeat(np.arange(n), count)
    skip = np.arange(int(count.sum())) - np.repeat(np.cumsum(count) - count, count)
    a, b = order[first], order[first + 1 + skip]
    gap = pos[b] - pos[a]
    near = (gap * gap).sum(axis=1) < reach * reach
    a, b, gap = a[near], b[near], gap[near]
    if not len(a):
        return -math.inf
    h = 0.5 * TUMBLED_SIDE
    ca, sa, cb, sb = np.cos(turn[a]), np.sin(turn[a]), np.cos(turn[b]), np.sin(turn[b])
    depth = np.full(len(a), math.inf)
    for ux, uy in ((ca, sa), (-sa, ca), (cb, sb), (-sb, cb)):
        ra = h * (np.abs(ca * ux + sa * uy) + np.abs(-sa * ux + ca * uy))
        rb = h * (np.abs(cb * ux + sb * uy) + np.abs(-sb * ux + cb * uy))
        depth = np.minimum(depth, ra + rb - np.abs(gap[:, 0] * ux + gap[:, 1] * uy))
    return float(depth.max())


def into_walls(boxes: list[Body], walls: list[Body]) -> float:
    """How far the deepest corner of any box is past the room's inner faces (m)."""
    return float(in_room(boxes, walls)[1].max())


def outside(boxes: list[Body], walls: list[Body]) -> np.ndarray:
    """Which boxes have their centre past a wall's inner face, (n,) bools."""
    return np.abs(in_room(boxes, walls)[0]).max(axis=1) > ROOM


class _StackScene(KeptReadouts, Scene):
    """What the three scenes share: a World of boxes, a camera on ``view``, a title."""

    dt = DT
    min_size = (480, 270)
    strobe_interval = 0.5
    title = ""
    view = (0.0, 0.0, 1.0, 1.0)  # (left, bottom, right, top) in metres
    world: World
    boxes: list[Body]

    def make(self) -> tuple[World, list[Body]]:
        raise NotImplementedError

    def build(self, size: tuple[int, int]) -> None:
        self.world, self.boxes = self.make()
        self.start = np.array([tuple(b.pos) for b in self.boxes])
        rows = {id(b): k for k, b in enumerate(self.world.bodies)}
        #: Each box's row in the World's arrays (``positions``).
        self.rows = np.array([rows[id(b)] for b in self.boxes], dtype=int)
        w, h = size
        s = self.s = h / 360
        header = round(72 * s)
        m = round(8 * s)
        x0, y0, x1, y1 = self.view
        scale = min((w - 2 * m) / (x1 - x0), (h - header - m) / (y1 - y0))
        self.camera = Camera(
            scale, ((w - scale * (x1 - x0)) / 2 - scale * x0, (h - m) + scale * y0)
        )
        self.asleep_at: float | None = None
        #: The World's StabilityWarning, (time s, its text): on the frame from then on. The
        #: World warns once in its life, and a restore does not undo that: the warning is kept
        #: across restores, so a rerun from before it shows it at its moment again.
        self.warning: Warned | None = None

    def step(self, dt: float) -> None:
        self.warning = step_noting(self.world, dt, self.warning)
        if self.asleep_at is None and self.world.sleeping == len(self.boxes):
            self.asleep_at = self.world.t

    #: The scene's own read-outs (beside its World) that a snapshot keeps.
    kept: tuple[str, ...] = ("asleep_at",)

    def drawn(self, alpha: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
        """Where the frame at ``alpha`` draws each box and at what angle: positions (n, 2) (m)
        and angles (n,) (rad), blended as ``draw_world`` blends them (1.0: the World's
        state now). The read-outs measure these, so they describe the state the frame shows
        at the time its clock shows."""
        xy = self.world.positions(alpha)[self.rows]
        turned = [angle_of(self.world, b, alpha) for b in self.boxes]
        angles = [b.angle if a is None else a for a, b in zip(turned, self.boxes, strict=True)]
        return xy, np.array(angles, dtype=float)

    def moved(self, alpha: float = 1.0) -> np.ndarray:
        """How far each box is from where it was put (m), as drawn at ``alpha``."""
        return np.hypot(*(self.drawn(alpha)[0] - self.start).T)

    def lines(self, alpha: float) -> list[str]:
        """The read-outs of the state drawn at ``alpha``, one a line."""
        raise NotImplementedError

    def draw_more(self, surface: pygame.Surface, alpha: float) -> None:
        """What a scene draws over the World (nothing by default)."""

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        surface.fill(PAPER)
        draw_world(surface, self.world, self.camera, alpha)
        s, w = self.s, surface.get_width()
        x = round(8 * s)
        draw_text(surface, self.title, (x, 4 * s), round(22 * s))
        t = self.time(alpha)
        draw_text(surface, f"t = {t:4.2f} s", (w - x, 4 * s), round(22 * s), INK, "topright")
        self.draw_more(surface, alpha)
        lines = self.lines(alpha)
        if self.warning is not None and self.warning[0] <= t + 1e-9:
            # The World's warning takes the place of the scene's second line (what it is
            # made of), where a teacher's frames show it.
            lines[1:2] = [headline(self.warning)]
        for k, line in enumerate(lines):
            draw_text(surface, line, (x, (32 + 18 * k) * s), round(15 * s), MUTED)


class PyramidScene(_StackScene):
    """210 boxes settle into a pyramid and sleep."""

    name = "pyramid"
    summary = "210 boxes of 1 m, a base of 20: they settle and sleep"
    duration = 3.0
    title = "A pyramid of 210 boxes"
    view = (-10.6, -0.3, 10.6, 20.3)

    def make(self) -> tuple[World, list[Body]]:
        # The exact models, where World() chooses the soft step: let go touching, the soft
        # step's pile sags 3 cm at its first steps (no warm start yet) and its contacts lift it
        # back over 4 s, so it sleeps at 4.3 s (its boxes 5.5 mm from where they were put);
        # the exact models' sleeps at 0.8 s, 7 mm off (the scene asks asleep within 2 s).
        return pyramid(solver="exact")

    def lines(self, alpha: float) -> list[str]:
        asleep = self.world.sleeping
        when = ""
        if self.asleep_at is not None and self.asleep_at <= self.time(alpha) + 1e-9:
            when = f", all since {self.asleep_at:.2f} s"
        return [
            f"asleep {asleep} of {len(self.boxes)}{when}   the most any box moved "
            f"{1000 * float(self.moved(alpha).max()):.1f} mm",
            f"mu 0.6, dt 1/60 s, {solved_by(self.world)}; blue: awake, grey: asleep",
        ]


class DominoScene(_StackScene):
    """A row of dominoes, the first flicked: each knocks over the next."""

    name = "dominoes"
    summary = "30 dominoes, the first flicked at its top: each knocks over the next"
    duration = 6.0
    title = "Dominoes"
    view = (-0.8, -0.3, 15.6, 5.0)

    def make(self) -> tuple[World, list[Body]]:
        return dominoes()

    def fallen(self, alpha: float = 1.0) -> int:
        """Dominoes tipped past 0.3 rad, as drawn at ``alpha``."""
        return int((np.abs(self.drawn(alpha)[1]) > 0.3).sum())

    def lines(self, alpha: float) -> list[str]:
        return [
            f"fallen {self.fallen(alpha)} of {len(self.boxes)}   asleep {self.world.sleeping}",
            f"0.1 x 1 m, 0.5 m apart; the first flicked with {FLICK} N s at its top; "
            f"{solved_by(self.world)}",
        ]


class TowerScene(_StackScene):
    """A column of 20 boxes with sleeping off: does it stand?"""

    name = "tower"
    summary = "20 boxes in a column, sleeping off: it stands, and how far it drifts"
    duration = 10.0
    title = "A tower of 20 boxes, sleeping off"
    view = (-6.0, -0.3, 6.0, 20.5)

    def make(self) -> tuple[World, list[Body]]:
        return tower()

    def lines(self, alpha: float) -> list[str]:
        x, y = self.drawn(alpha)[0][-1]  # the top box
        drift = abs(x - self.start[-1, 0])
        sag = self.start[-1, 1] - y
        return [
            f"the top box: {1000 * drift:.1f} mm sideways, {1000 * sag:.1f} mm lower than put",
            f"{solved_by(self.world)}; by 60 s Box2D v3's drifts 16 mm and sags 133 mm, "
            "pymunk's falls at 1.7 s",
        ]


class TumblerScene(_StackScene):
    """500 boxes in a room whose walls turn at 25 degrees a second (Box2D's benchmark)."""

    name = "tumbler"
    summary = "500 boxes of 0.25 m in a room whose walls turn at 25 degrees a second"
    duration = 20.0
    title = "A tumbler: 500 boxes, the walls turning 25 degrees a second"
    #: rad/s: how fast the walls turn.
    spin = TUMBLE
    view = (-14.9, -14.9, 14.9, 14.9)  # the room turned 45 degrees fits
    walls: list[Body]
    #: How many boxes the room holds (a test of the room alone may take fewer).
    count = TUMBLED
    #: The worst so far, of every state stepped through (``deepest``: a corner into a wall,
    #: ``overlap``: two boxes into each other, m), and of those before the last step (the
    #: ``_before`` pair: what a frame between the last two states has seen so far).
    kept = (*_StackScene.kept, "deepest", "overlap", "deepest_before", "overlap_before")

    def make(self) -> tuple[World, list[Body]]:
        # The exact models, where World() chooses the soft step: the soft step's solve on the
        # numpy path is plain Python, at 500 boxes four times the exact models' step (234
        # against 57 ms at 90 degrees a second); its boxes go as deep into each other (91
        # against 92 mm at 25, 132 against 234 at 90, since a corner's rows turn with the
        # face: module doc), and on the fast path it is 2.5 times quicker (demos.bench soft).
        w, boxes, self.walls = tumbler(self.count, self.spin, solver="exact")
        self.deepest = self.overlap = self.deepest_before = self.overlap_before = 0.0
        return w, boxes

    def step(self, dt: float) -> None:
        self.deepest_before, self.overlap_before = self.deepest, self.overlap
        super().step(dt)
        self.deepest = max(self.deepest, into_walls(self.boxes, self.walls))
        self.overlap = max(self.overlap, self.world.overlap())

    def room_angle(self, alpha: float = 1.0) -> float:
        """The angle (rad) the room is drawn at, at ``alpha`` (its walls turn together)."""
        angle = angle_of(self.world, self.walls[0], alpha)
        return float(self.walls[0].angle if angle is None else angle)

    def draw_more(self, surface: pygame.Surface, alpha: float) -> None:
        """A dot on the first wall's middle, and the room's angle left of the room: the four
        walls look alike a quarter turn apart, and they turn a quarter turn a second."""
        angle = self.room_angle(alpha)
        r = ROOM + 0.5  # the wall's middle line
        at = self.camera.point((r * math.cos(angle), r * math.sin(angle)))
        radius = max(3, round(self.camera.length(0.45)))  # within the wall's 1 m
        pygame.draw.circle(surface, MARK, at, radius)
        pygame.draw.circle(surface, INK, at, radius, 1)
        s = self.s
        y = self.camera.point((0.0, 0.0))[1]
        degrees = round(math.degrees(angle)) % 360
        draw_text(surface, f"the walls at {degrees} degrees", (8 * s, y - 18 * s), round(15 * s))
        draw_text(surface, "(the dot marks one)", (8 * s, y), round(15 * s), MUTED)

    def lines(self, alpha: float) -> list[str]:
        xy, turn = self.drawn(alpha)
        centre = room_frame(xy, turn, self.room_angle(alpha))[0]  # the room turns about 0
        out = int((np.abs(centre).max(axis=1) > ROOM).sum())
        now = alpha >= 1.0  # the frame shows the World's state now, else one before it
        deepest = self.deepest if now else self.deepest_before
        overlap = self.overlap if now else self.overlap_before
        return [
            f"outside the room: {out} of {len(self.boxes)}   the deepest any corner "
            f"went into a wall: {1000 * deepest:.0f} mm, two boxes into each other: "
            f"{1000 * overlap:.0f} mm",
            f"the walls: kinematic bodies, angular_velocity = {self.spin:.4g} rad/s "
            f"({math.degrees(self.spin):.0f} degrees/s); mu 0.6, dt 1/60 s, "
            f"{solved_by(self.world)}",
        ]


class StressTumblerScene(TumblerScene):
    """The tumbler at 90 degrees a second: a centrifuge, the boxes pinned to its walls."""

    name = "tumbler90"
    summary = "the tumbler at 90 degrees a second, a stress scene: the boxes pinned to the walls"
    title = "A tumbler at 90 degrees a second (a stress scene)"
    spin = TUMBLE_STRESS


DEMO = Demo(
    name="stack",
    summary="Boxes that turn: a pyramid of 210, a row of dominoes, a tower of 20, a tumbler",
    scenes={
        "pyramid": PyramidScene,
        "dominoes": DominoScene,
        "tower": TowerScene,
        "tumbler": TumblerScene,
        "tumbler90": StressTumblerScene,
    },
)
