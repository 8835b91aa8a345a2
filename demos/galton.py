"""A Galton board: balls poured through a triangle of pegs land in bins as B(12, 1/2) says.

    python -m demos galton                    # frames: out/galton/board/
    python -m demos galton --window
    python -m demos galton --strobe           # the paths of the first three balls, one still
    python -m demos galton --seed 7 --seconds 120

Balls leave a funnel one at a time (every ``POUR_INTERVAL`` s, each a little off centre: a
seeded jitter) and fall through ``rows`` = 12 rows of pegs. At each row a ball goes left or
right of the peg it meets; a ball that went right k times ends in bin k. If every choice is a
fair coin, independent of the others, bin k gets the share C(12, k) / 2^12 of the balls: the
binomial distribution B(12, 1/2). Under the board the bins' counts grow as bars, with
B(12, 1/2) scaled to the number counted drawn over them, and a chi-square test says how well
they agree.

The physics is the engine's, nothing scripted: pegs are ``Circle`` colliders, the walls,
funnel, bin dividers and floor ``Segment`` colliders, the balls Bodies with a radius under
gravity, in a World stepped at ``DT``. Units: centimetres and seconds (g = 981 cm/s^2).

What makes the choice at each peg close to a fair, independent coin (see ``Board``):

* Narrow channels. The pegs (radius 0.55 cm, 2 cm apart in a triangular lattice) leave gaps
  of 0.9 cm for balls of 0.8 cm, between neighbours in a row and between rows alike, so a
  ball cannot build up sideways speed and skip a peg: it squeezes through a gap onto the top
  of the peg below, where a small difference decides its side.
* Bounces. Each bounce off a round peg spreads nearby paths apart (a convex mirror), so after
  a few rows the jitter of the start is amplified into a choice no smooth rule predicts.
  Without friction a ball cannot stick on a peg (the engine's particles do not roll, and
  static friction would hold one near a peg's top for ever).
* Balls differ a little, as real ones do. Each ball's restitution is drawn (seeded) from 0.5
  to 0.7. How much a ball's choices depend on each other varies sharply with restitution
  (with one value for all, 0.67 gives a variance of the bins 29% too small and 0.73 one 45%
  too large, 1,000 balls each, measured on 2026-11-25); a spread of values averages those
  resonances out.
* The step. The engine brings a rebound slower than |a_n| dt / 2 to rest on the peg, so dt
  is part of the model: in the test's pour of 1,000 balls the bins' variance is 0.98 times
  the binomial's at ``DT`` = 1/60 s and 1.05 times at 1/120 s (measured on 2026-11-25).
* Guard pegs and walls. The outer pegs of each row have a guard peg beside them, half in the
  side wall, where the next peg of an endless lattice would be, so a ball at the edge of the
  triangle chooses as freely as one in the middle, and no pocket between a wall and a peg
  can hold a ball.

A ball is counted in its bin the moment its centre crosses a line under the last row of pegs,
between the dividers, where nothing can change its bin any more; it is taken out of the World
when it lands on the bins' floor. So the counts do not depend on what happens in the bins
(balls landing on one another there).
The pour is sparse enough (one ball every 0.5 s, each taking about 2 s to cross the board)
that balls seldom meet on the pegs: of the first 300, 5 touched another one above the counting
line (2026-11-25). Two balls that meet there, one of them bounced off a peg or lying on one in
that very step, could sink into each other (the impacts are found on paths that do not know of the
peg's bounce); the contacts then move such a pair apart at once, so in the default run (seed
1, 60 s) no two balls sink into each other at all (``tests/test_galton.py`` checks it; the
deepest was 0.4% of a radius, at 21.4 s, before a ball stopped on a peg was no longer kicked as
it is put back on the peg's arc, 2026-12-07), and in the same 60 s for seeds 2 to 8 it was 0
to 5% (measured on 2026-11-25). A pour ten times
as dense (``--interval 0.05``) crowds the pegs deeper; past 5% the World says so once, with a
``StabilityWarning``, and the frame shows it and the deepest overlap so far
(``Galton.deepest``) instead of a line on stderr. It changes no count: the balls part again
and each still lands in one bin.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pygame
from numpy.typing import ArrayLike

from demos.cli import Demo, number_option
from demos.warned import step_noting
from engine import Body, Circle, Segment, Vector, World
from engine.forces import Gravity
from engine.render import GRID, INK, MUTED, PAPER, Camera, Scene, draw_text
from engine.world import WorldSnapshot

__all__ = [
    "G",
    "DT",
    "Board",
    "BOARD",
    "POUR_INTERVAL",
    "SEED",
    "ALPHA",
    "binomial_pmf",
    "pool",
    "chi_square",
    "chi_square_sf",
    "chi_square_critical",
    "Galton",
    "GaltonSnapshot",
    "GaltonScene",
    "DEMO",
]

#: Gravity (cm/s^2) and the physics step (s).
G = 981.0
DT = 1.0 / 60.0

Color = tuple[int, int, int]
#: Colours no other drawing uses, so tests find each by its colour.
BALL: Color = (196, 40, 60)
PEG: Color = (70, 74, 92)
BAR: Color = (86, 180, 233)
EXPECTED: Color = (213, 94, 0)
FRAME: Color = (222, 212, 192)
WALL: Color = (92, 74, 56)
FITS: Color = (0, 140, 95)
MISFITS: Color = (200, 50, 40)
#: The first balls' colours in the strobe picture.
PATHS: tuple[Color, ...] = ((230, 159, 0), (0, 158, 115), (0, 114, 178))


@dataclass(frozen=True)
class Board:
    """The board's geometry and materials (cm): a triangle of ``rows`` rows of pegs with guard
    pegs and walls along its sides, a funnel above it and ``rows + 1`` bins below it.

    Row j (0 at the top) holds j + 1 pegs at x = (i - j / 2) ``spacing``, y = -j ``row_height``
    (i = 0 .. j): the top peg is at the origin. A ball that meets exactly one peg a row and
    passes it on the left or the right ends in bin k = (the number of rights), centred at
    x = (k - rows / 2) ``spacing``.
    """

    rows: int = 12
    spacing: float = 2.0
    #: An equilateral lattice: every peg is ``spacing`` from its six neighbours.
    row_height: float = math.sqrt(3.0)
    peg_radius: float = 0.55
    ball_radius: float = 0.4
    #: Each ball's restitution is drawn uniformly from this range; pegs and walls keep the
    #: default material (1.0, 1.0), so the ball's own is in force. No friction: see the module.
    restitution: tuple[float, float] = (0.5, 0.7)
    friction: float = 0.0
    #: Half the width of the funnel's neck, and the largest jitter of a ball's start in x.
    neck: float = 0.8
    jitter: float = 0.3
    #: How deep the bins are under the dividers' tops.
    bin_depth: float = 3.0
    #: How high the funnel stands above its neck.
    funnel: float = 2.5

    # -- geometry ----------------------------------------------------------------------------
    def pegs(self) -> list[tuple[float, float]]:
        """The pegs' centres, row by row from the top, left to right, guards included.

        Each row's j + 1 pegs of the triangle have a guard peg on each side (i = -1 and
        i = j + 1), where the next pegs of an endless lattice would be: a ball going round
        the outside of an outer peg passes between it and the guard, as between any two
        pegs. The side walls run through the guards' centres.
        """
        d, h = self.spacing, self.row_height
        return [((i - j / 2) * d, -j * h) for j in range(self.rows) for i in range(-1, j + 2)]

    def guards(self) -> list[bool]:
        """For each peg of :meth:`pegs`, whether it is a guard peg (half in a side wall)."""
        return [i in (-1, j + 1) for j in range(self.rows) for i in range(-1, j + 2)]

    def side_x(self, y: float) -> float:
        """x of the left side wall at height y: the line through the left guard pegs'
        centres (from (-spacing, 0), out by half a spacing per row down). The right wall is
        its mirror image."""
        return -self.spacing + y * self.spacing / (2.0 * self.row_height)

    def side_y(self, x: float) -> float:
        """Height at which the left side wall is at x (the inverse of :meth:`side_x`)."""
        return (x + self.spacing) * 2.0 * self.row_height / self.spacing

    @property
    def neck_y(self) -> float:
        """Height of the funnel's neck, where the side walls are ``neck`` from the middle."""
        return self.side_y(-self.neck)

    @property
    def top_y(self) -> float:
        """Height of the top of the funnel."""
        return self.neck_y + self.funnel

    @property
    def spawn_y(self) -> float:
        """Height at which each ball is let go, in the funnel just above its neck."""
        return self.neck_y + 1.0

    @property
    def last_row_y(self) -> float:
        """Height of the last row of pegs."""
        return -(self.rows - 1) * self.row_height

    @property
    def divider_top(self) -> float:
        """Top of the bin dividers: under the last row's pegs, too close for a ball to pass."""
        return self.last_row_y - self.peg_radius - 0.15

    @property
    def count_y(self) -> float:
        """A ball is counted in its bin when its centre crosses this line, between dividers."""
        return self.divider_top - 2.0 * self.ball_radius

    @property
    def floor_y(self) -> float:
        """The bins' floor; a ball that lands on it leaves the board."""
        return self.divider_top - self.bin_depth

    @property
    def half_width(self) -> float:
        """Half the width of the row of bins: the outer bin walls hang under the last row's
        guard pegs, at x = -+ (rows + 1) spacing / 2."""
        return (self.rows + 1) / 2.0 * self.spacing

    def bin_of(self, x: Any) -> Any:
        """The bin (0 to rows) holding x: bin k is centred at (k - rows / 2) spacing."""
        k = np.floor(np.asarray(x) / self.spacing + (self.rows + 1) / 2.0).astype(int)
        return np.clip(k, 0, self.rows)

    def walls(self) -> list[tuple[tuple[float, float], tuple[float, float]]]:
        """Every wall as a segment (a, b): the funnel, the sides of the triangle, the bins'
        outer walls and dividers, and last the floor."""
        d, n, w = self.spacing, self.rows, self.half_width
        neck, top, last = self.neck_y, self.top_y, self.last_row_y
        corner = (self.side_x(last), last)  # at the last guard peg, over the bin wall
        left = [
            ((-self.neck - self.funnel * d / (2.0 * self.row_height), top), (-self.neck, neck)),
            ((-self.neck, neck), corner),
            (corner, (-w, self.floor_y)),  # the outer wall of bin 0
        ]
        walls = left + [((-a[0], a[1]), (-b[0], b[1])) for a, b in left]
        for i in range(n):  # under the last row's pegs
            x = (i - (n - 1) / 2.0) * d
            walls.append(((x, self.divider_top), (x, self.floor_y)))
        walls.append(((-w, self.floor_y), (w, self.floor_y)))
        return walls

    def pour(self, seed: int, count: int) -> tuple[np.ndarray, np.ndarray]:
        """The first ``count`` balls of the pour seeded ``seed``: each one's start x (cm,
        uniform within +-jitter of the middle) and restitution (uniform in the range).

        Ball k's values do not depend on ``count``: a longer pour begins with a shorter one.
        """
        u = np.random.default_rng(seed).random((count, 2))  # ball by ball, x then e
        lo, hi = self.restitution
        return self.jitter * (2.0 * u[:, 0] - 1.0), lo + (hi - lo) * u[:, 1]


#: The board the demo shows and the tests pour.
BOARD = Board()
#: Seconds between two balls let go from the funnel, and the pour's default seed.
POUR_INTERVAL = 0.5
SEED = 1
#: The chi-square test's significance: B(rows, 1/2) is rejected when p < ALPHA.
ALPHA = 0.001


# -- the binomial distribution and the chi-square test -----------------------------------------


def binomial_pmf(n: int) -> np.ndarray:
    """P(k) = C(n, k) / 2^n for k = 0 .. n: B(n, 1/2), the bins' shares on an ideal board."""
    return np.array([math.comb(n, k) for k in range(n + 1)], dtype=float) / 2.0**n


def pool(
    observed: ArrayLike, expected: ArrayLike, minimum: float = 5.0
) -> tuple[np.ndarray, np.ndarray]:
    """Merge neighbouring bins, left to right, until each group expects at least ``minimum``
    (the chi-square test's rule of thumb); a short last group joins the one before it.

    >>> pool([1, 2, 30, 2], [0.5, 4.5, 30.0, 0.5])
    (array([ 3., 32.]), array([ 5. , 30.5]))
    """
    obs_groups: list[float] = []
    exp_groups: list[float] = []
    o_sum = e_sum = 0.0
    for o, e in zip(np.asarray(observed), np.asarray(expected), strict=True):
        o_sum, e_sum = o_sum + float(o), e_sum + float(e)
        if e_sum >= minimum:
            obs_groups.append(o_sum)
            exp_groups.append(e_sum)
            o_sum = e_sum = 0.0
    if e_sum > 0.0 or o_sum > 0.0:
        if exp_groups:
            obs_groups[-1] += o_sum
            exp_groups[-1] += e_sum
        else:
            obs_groups, exp_groups = [o_sum], [e_sum]
    return np.array(obs_groups), np.array(exp_groups)


def chi_square(counts: ArrayLike, probabilities: ArrayLike) -> tuple[float, int]:
    """Pearson's goodness-of-fit statistic of ``counts`` against ``probabilities``, with bins
    pooled so each expects at least 5: (X^2 = sum (O - E)^2 / E, degrees of freedom = groups
    - 1). Under the hypothesis, X^2 follows the chi-square distribution of that many degrees
    of freedom; :func:`chi_square_sf` gives the chance of a value as large."""
    total = float(np.sum(counts))
    observed, expected = pool(counts, total * np.asarray(probabilities, dtype=float))
    if len(observed) < 2:
        return 0.0, 0
    return float(np.sum((observed - expected) ** 2 / expected)), len(observed) - 1


def chi_square_sf(x: float, df: int) -> float:
    """P(X^2 >= x) for the chi-square distribution with ``df`` (a whole number >= 1) degrees
    of freedom, in closed form (no tables, no scipy).

    With m = x / 2: for even df = 2k, P = exp(-m) (1 + m + m^2 / 2! + ... + m^(k-1) / (k-1)!)
    (the Poisson sum); for odd df, P = erfc(sqrt(m)) + exp(-m) / sqrt(pi m) (2m + (2m)^2 / 3
    + (2m)^3 / (3 * 5) + ... , (df - 1) / 2 terms).

    >>> round(chi_square_sf(10.828, 1), 5), round(chi_square_sf(29.588, 10), 5)
    (0.001, 0.001)
    """
    if df < 1:
        raise ValueError(f"df must be a whole number >= 1, got {df!r}")
    if x <= 0.0:
        return 1.0
    m = x / 2.0
    if df % 2 == 0:
        term = total = 1.0
        for k in range(1, df // 2):
            term *= m / k
            total += term
        return math.exp(-m) * total
    total = math.erfc(math.sqrt(m))
    term = math.exp(-m) / math.sqrt(math.pi * m)
    for k in range(1, (df - 1) // 2 + 1):
        term *= x / (2 * k - 1)
        total += term
    return total


def chi_square_critical(df: int, alpha: float = 0.001) -> float:
    """The value X^2 exceeds with probability ``alpha`` when the hypothesis holds (bisection
    on :func:`chi_square_sf`): above it, the test rejects at significance ``alpha``."""
    low, high = 0.0, 10.0 * df + 100.0
    for _ in range(200):
        mid = 0.5 * (low + high)
        if chi_square_sf(mid, df) > alpha:
            low = mid
        else:
            high = mid
    return 0.5 * (low + high)


# -- the board in a World --------------------------------------------------------------------


@dataclass(frozen=True)
class GaltonSnapshot:
    """Everything a :class:`Galton` needs to resume: see :meth:`Galton.snapshot`."""

    world: WorldSnapshot
    balls: tuple[int, ...]  # the pour index of each ball in the World, in the World's order
    counted: frozenset[int]
    poured: int
    counts: tuple[int, ...]
    landed: tuple[tuple[float, int], ...]
    lost: int
    deeper: tuple[tuple[float, float], ...] = ()
    warning: tuple[float, str] | None = None


class Galton:
    """The board in a World, balls poured into it one after another, and the bin counts.

    A Steppable (``step(dt)``, ``t``, ``snapshot()``, ``restore()``): each step lets go the
    balls whose time has come (ball k at k ``interval`` s, from ``board.pour(seed, count)``),
    steps the World, counts each ball in its bin the moment its centre crosses
    ``board.count_y``, and takes out of the World the balls that land on the bins' floor.
    ``counts[k]`` is the number of balls counted in bin k so far.

    ``lanes`` > 1 sets that many copies of the board side by side in the one World, ``pitch``
    cm apart, and pours ball k into copy k % lanes at (k // lanes) ``interval`` s: each copy
    gets a pour as sparse as the demo's, and one step of the World moves them all (a test pours
    1,000 balls that way, several times faster). The counts are the copies' together.
    """

    #: A ball still on the board this long after it was let go is taken out and counted as
    #: lost (it would have to be stuck: a ball crosses the board in about 2 s).
    STALL = 30.0

    def __init__(
        self,
        board: Board = BOARD,
        seed: int = SEED,
        count: int = 1000,
        interval: float = POUR_INTERVAL,
        lanes: int = 1,
    ) -> None:
        if count < 0 or lanes < 1 or not interval > 0.0:
            raise ValueError(
                f"count must be >= 0, lanes >= 1 and interval > 0 s, got {count}, {lanes}, "
                f"{interval}"
            )
        self.board, self.seed, self.count = board, seed, count
        self.interval, self.lanes = interval, lanes
        self.pitch = 2.0 * board.half_width + 4.0
        self.world = World(integrator="auto")  # gravity alone: the closed form, exact
        self.world.add_force(Gravity((0.0, -G)))
        self.pegs: list[Circle] = []
        self.walls: list[Segment] = []
        self._floors: set[int] = set()
        for lane in range(lanes):
            dx = lane * self.pitch
            self.pegs += [Circle((x + dx, y), board.peg_radius) for x, y in board.pegs()]
            walls = [Segment((a[0] + dx, a[1]), (b[0] + dx, b[1])) for a, b in board.walls()]
            self._floors.add(id(walls[-1]))
            self.walls += walls
        for collider in [*self.pegs, *self.walls]:
            self.world.add_collider(collider)
        self.start_x, self.restitution = board.pour(seed, count)
        self.balls: list[Body] = []  # the balls in the World, in the World's order
        self._index: dict[int, int] = {}  # id(ball) -> its pour index
        self.counted: set[int] = set()  # the pour indices counted so far
        self.poured = 0
        self.counts = np.zeros(board.rows + 1, dtype=int)
        #: (time s, bin) of each ball counted, in order.
        self.landed: list[tuple[float, int]] = []
        #: Balls taken out before they were counted (see STALL): none, on this board.
        self.lost = 0
        #: Each new deepest overlap of two balls, (time s, depth cm), measured after each step.
        self.deeper: list[tuple[float, float]] = []
        #: The World's StabilityWarning, (time s, its text), once it came (it comes once).
        self.warning: tuple[float, str] | None = None

    @property
    def t(self) -> float:
        """The time (s): the World's."""
        return self.world.t

    def lane_of(self, k: int) -> int:
        """The copy of the board that ball k is poured into."""
        return k % self.lanes

    def released_at(self, k: int) -> float:
        """When ball k is let go (s)."""
        return (k // self.lanes) * self.interval

    def index_of(self, ball: Body) -> int:
        """The pour index of a ball in the World."""
        return self._index[id(ball)]

    def _ball(self, k: int, pos: tuple[float, float]) -> Body:
        body = Body(
            Vector(*pos),
            Vector(0.0, 0.0),
            Vector(0.0, 0.0),
            radius=self.board.ball_radius,
            restitution=float(self.restitution[k]),
            friction=self.board.friction,
        )
        self._index[id(body)] = k
        return body

    def step(self, dt: float) -> None:
        """Let go the balls due, step the World, count the balls that crossed the line and
        take out those that landed."""
        due = []
        while self.poured < self.count and self.released_at(self.poured) <= self.world.t:
            k = self.poured
            x = float(self.start_x[k]) + self.lane_of(k) * self.pitch
            due.append(self._ball(k, (x, self.board.spawn_y)))
            self.poured += 1
        if due:
            self.balls.extend(self.world.add_all(due))
        # The World's warning goes on the frame, not to stderr.
        self.warning = step_noting(self.world, dt, self.warning)
        if len(self.balls) > 1:
            depth = self.world.overlap()
            if depth > self.deepest()[1]:
                self.deeper.append((self.world.t, depth))
        if not self.balls:
            return
        xy = self.world.positions()
        for row in np.flatnonzero(xy[:, 1] < self.board.count_y):
            k = self._index[id(self.balls[row])]
            if k not in self.counted:
                self.counted.add(k)
                b = int(self.board.bin_of(xy[row, 0] - self.lane_of(k) * self.pitch))
                self.counts[b] += 1
                self.landed.append((self.world.t, b))
        out = {id(e.body) for e in self.world.began if id(e.collider) in self._floors}
        t = self.world.t
        for body in list(self.balls):
            k = self._index[id(body)]
            if id(body) in out or t - self.released_at(k) > self.STALL:
                self.world.remove(body)
                self.balls.remove(body)
                del self._index[id(body)]
                self.lost += k not in self.counted

    def deepest(self, t: float = math.inf) -> tuple[float, float]:
        """The deepest two balls had sunk into each other by time t (s): (when s, depth cm)."""
        return next(((w, d) for w, d in reversed(self.deeper) if w <= t + 1e-9), (0.0, 0.0))

    @property
    def done(self) -> bool:
        """Whether every ball has been poured and has left the board."""
        return self.poured == self.count and not self.balls

    def run(self) -> None:
        """Step until every ball has been poured and has left the board."""
        while not self.done:
            self.step(DT)

    def snapshot(self) -> GaltonSnapshot:
        """The World, the balls in it (by pour index), what was counted and lost."""
        return GaltonSnapshot(
            self.world.snapshot(),
            tuple(self._index[id(b)] for b in self.balls),
            frozenset(self.counted),
            self.poured,
            tuple(int(c) for c in self.counts),
            tuple(self.landed),
            self.lost,
            tuple(self.deeper),
            self.warning,
        )

    def restore(self, snapshot: GaltonSnapshot) -> None:
        """Return to the moment ``snapshot()`` was taken: the balls then on the board are made
        again (at their saved places), then the World takes its saved state."""
        if not isinstance(snapshot, GaltonSnapshot):
            raise TypeError(
                f"restore takes a GaltonSnapshot from Galton.snapshot(), got "
                f"{type(snapshot).__name__}"
            )
        for body in self.balls:
            self.world.remove(body)
        self._index.clear()
        saved = snapshot.world.x
        self.balls = self.world.add_all(
            [
                self._ball(k, (float(saved[row, 0]), float(saved[row, 1])))
                for row, k in enumerate(snapshot.balls)
            ]
        )
        self.world.restore(snapshot.world)
        self.counted = set(snapshot.counted)
        self.poured = snapshot.poured
        self.counts = np.array(snapshot.counts, dtype=int)
        self.landed = list(snapshot.landed)
        self.lost = snapshot.lost
        self.deeper, self.warning = list(snapshot.deeper), snapshot.warning


# -- drawing -----------------------------------------------------------------------------------


def _text(
    surface: pygame.Surface,
    text: str,
    pos: tuple[float, float],
    size: float,
    color: Color = INK,
    anchor: str = "topleft",
) -> pygame.Rect:
    """The renderer's draw_text with the size kept legible (at least 11 px)."""
    return draw_text(surface, text, pos, max(11, round(size)), color, anchor)


def _dashed(surface: pygame.Surface, color: Color, y: int, x0: int, x1: int, dash: int) -> None:
    for x in range(x0, x1, 2 * dash):
        pygame.draw.line(surface, color, (x, y), (min(x + dash, x1), y))


class GaltonScene(Scene):
    """The board with the balls on it, and under it the bins' counts against B(rows, 1/2)."""

    name = "board"
    summary = "balls poured through 12 rows of pegs; the bins' counts against B(12, 1/2)"
    duration = 60.0
    dt = DT
    seed = SEED
    min_size = (480, 270)
    strobe_interval = 1.0 / 30.0
    world: Galton

    def __init__(self, board: Board = BOARD, interval: float = POUR_INTERVAL) -> None:
        self.board, self.interval = board, interval

    def build(self, size: tuple[int, int]) -> None:
        """A new pour on a ``size`` px canvas: the board in the middle, the bars under it,
        words on the left, the table of counts on the right."""
        b = self.board
        count = math.floor(max(self.duration, 3600.0) / self.interval) + 1
        self.world = self.galton = Galton(b, self.seed, count, self.interval)
        w, h = size
        s = self.s = h / 360.0
        self.size = size
        margin = 0.4
        box = (-b.half_width - margin, b.floor_y - margin, b.half_width + margin, b.top_y + margin)
        self.camera = Camera.fit(box, (0, 4 * s, w, round(h * 0.68)))
        cam = self.camera
        floor_px = cam.to_px(0.0, b.floor_y)[1]
        self.hist = pygame.Rect(
            round(cam.to_px(-b.half_width, 0.0)[0]),
            round(floor_px + 4 * s),
            round(cam.length(2.0 * b.half_width)),
            round(h - 20 * s - (floor_px + 4 * s)),
        )
        self.pmf = binomial_pmf(b.rows)
        self.background = self._background(size)

    # -- the static picture: frame, walls, pegs ---------------------------------------------
    def _background(self, size: tuple[int, int]) -> pygame.Surface:
        b, cam, s = self.board, self.camera, self.s
        surface = pygame.Surface(size)
        surface.fill(PAPER)
        peg_px = max(2, round(cam.length(b.peg_radius)))
        for x, y in b.pegs():
            pygame.draw.circle(surface, PEG, cam.point((x, y)), peg_px)
        # The frame outside the walls, left and right (over the guard pegs' outer halves).
        view_x, view_top = b.half_width + 0.4, b.top_y + 0.4
        funnel, side, _ = b.walls()[:3]
        left = [
            (-view_x, view_top),
            (funnel[0][0], view_top),
            funnel[0],
            funnel[1],
            side[1],
            (-b.half_width, b.floor_y),
            (-view_x, b.floor_y),
        ]
        for sign in (-1.0, 1.0):
            pygame.draw.polygon(surface, FRAME, [cam.point((sign * -x, y)) for x, y in left])
        width = max(2, round(3 * s))
        for i, (p, q) in enumerate(b.walls()):
            divider = 6 <= i < len(b.walls()) - 1
            pygame.draw.line(
                surface, WALL, cam.point(p), cam.point(q), max(1, width - 1) if divider else width
            )
        # The counting line, between the dividers' tops and the floor.
        left, y = cam.point((-b.half_width, b.count_y))
        right, _ = cam.point((b.half_width, b.count_y))
        _dashed(surface, GRID, y, left, right, max(2, round(3 * s)))
        return surface

    # -- each frame ----------------------------------------------------------------------------
    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        """The board, the balls on it (blended ``alpha`` between steps), the bars, the words."""
        galton, cam, b = self.galton, self.camera, self.board
        surface.blit(self.background, (0, 0))
        ball_px = max(2, round(cam.length(b.ball_radius)))
        for p in galton.world.positions(alpha) if galton.balls else ():
            pygame.draw.circle(surface, BALL, cam.point(p), ball_px)
        t = self.time(alpha)
        self._histogram(surface, t)
        self._words(surface, t)

    def counts_at(self, t: float) -> np.ndarray:
        """The counts as they stood at time t (s): a frame shows the state at its own time,
        while the World is a step ahead of it."""
        counts = self.galton.counts.copy()
        for when, k in reversed(self.galton.landed):
            if when <= t + 1e-9:
                break
            counts[k] -= 1
        return counts

    def histogram_top(self, counts: np.ndarray) -> float:
        """The count at the top of the histogram: room above the tallest bar and the curve."""
        return max(5.0, 1.15 * float(max(counts.max(), counts.sum() * self.pmf.max())))

    def _histogram(self, surface: pygame.Surface, t: float) -> None:
        b, r, s = self.board, self.hist, self.s
        counts = self.counts_at(t)
        total = int(counts.sum())
        expected = total * self.pmf
        top = self.histogram_top(counts)
        bins = b.rows + 1
        width = r.width / bins
        gap = max(1, round(width * 0.12))
        for k, c in enumerate(counts):
            height = round(r.height * c / top)
            if height > 0:
                left = round(r.left + k * width) + gap // 2 + 1
                bar = pygame.Rect(left, r.bottom - height, round(width) - gap, height)
                pygame.draw.rect(surface, BAR, bar)
        for when, k in self.galton.landed[-8:]:
            if 0.0 <= t - when < 0.4:  # a ball just counted: a flash on its bar
                height = round(r.height * counts[k] / top)
                x0 = round(r.left + k * width) + gap // 2 + 1
                pygame.draw.rect(
                    surface, BALL, (x0, r.bottom - height, round(width) - gap, max(2, round(3 * s)))
                )
        pygame.draw.line(surface, INK, (r.left, r.bottom), (r.right, r.bottom), max(1, round(s)))
        points = [
            (r.left + (k + 0.5) * width, r.bottom - r.height * e / top)
            for k, e in enumerate(expected)
        ]
        if total:
            pygame.draw.lines(surface, EXPECTED, False, points, max(2, round(2 * s)))
            for p in points:
                pygame.draw.circle(
                    surface, EXPECTED, (round(p[0]), round(p[1])), max(2, round(3 * s))
                )
        for k in range(bins):
            _text(
                surface,
                str(k),
                (r.left + (k + 0.5) * width, r.bottom + 2 * s),
                13 * s,
                MUTED,
                "midtop",
            )

    def _words(self, surface: pygame.Surface, t: float) -> None:
        b, s, galton = self.board, self.s, self.galton
        counts = self.counts_at(t)
        total = int(counts.sum())
        x, y = 10 * s, 8 * s
        _text(surface, "Galton board", (x, y), 24 * s)
        y += 26 * s
        _text(surface, f"t = {t:5.1f} s", (x, y), 16 * s, MUTED)
        y += 18 * s
        _text(surface, f"{total} balls counted", (x, y), 16 * s)
        y += 26 * s
        for line in (
            f"{b.rows} rows of pegs: left or",
            "right at each one; a ball",
            "with k rights ends in bin k",
        ):
            _text(surface, line, (x, y), 14 * s, MUTED)
            y += 15 * s
        y += 10 * s
        pygame.draw.rect(surface, BAR, (x, y + 2 * s, 14 * s, 10 * s))
        _text(surface, "counted", (x + 20 * s, y), 15 * s)
        y += 17 * s
        pygame.draw.line(
            surface, EXPECTED, (x, y + 7 * s), (x + 14 * s, y + 7 * s), max(2, round(2 * s))
        )
        pygame.draw.circle(
            surface, EXPECTED, (round(x + 7 * s), round(y + 7 * s)), max(2, round(3 * s))
        )
        _text(surface, f"B({b.rows}, 1/2) x {total}", (x + 20 * s, y), 15 * s)
        y += 28 * s
        self._table(surface, counts)
        stat, df = chi_square(counts, self.pmf)
        _text(surface, "chi-square test", (x, y), 16 * s)
        y += 18 * s
        if df < 1:
            _text(surface, "(waiting for balls)", (x, y), 14 * s, MUTED)
            return
        p = chi_square_sf(stat, df)
        _text(surface, f"X\u00b2 = {stat:.1f} on {df} df, p = {p:.2g}", (x, y), 15 * s)
        y += 16 * s
        if p >= ALPHA:
            _text(surface, f"B({b.rows}, 1/2) not rejected", (x, y), 15 * s, FITS)
        else:
            _text(surface, f"B({b.rows}, 1/2) rejected", (x, y), 15 * s, MISFITS)
        _text(surface, f"at significance {ALPHA:g}", (x, y + 16 * s), 15 * s, MUTED)
        if galton.lost:
            _text(surface, f"{galton.lost} lost", (x, y + 34 * s), 15 * s, MISFITS)
        self._overlap(surface, t, (x, y + 56 * s))

    def _overlap(self, surface: pygame.Surface, t: float, at: tuple[float, float]) -> None:
        """Once two balls have sunk into each other past 5% of a radius: how deep, when, and
        that the World warned (its StabilityWarning, shown here rather than on stderr)."""
        galton, s = self.galton, self.s
        when, depth = galton.deepest(t)
        share = depth / self.board.ball_radius
        if share <= 0.05:
            return
        x, y = at
        warned = galton.warning is not None and galton.warning[0] <= t + 1e-9
        lines = [
            ("two balls met on a peg:", INK),
            (f"{share:.0%} of r deep at {when:.1f} s", MISFITS),
            ("(the World warned: StabilityWarning)" if warned else "", MUTED),
        ]
        for text, colour in lines:
            if text:
                _text(surface, text, (x, y), 14 * s, colour)
            y += 15 * s

    def _table(self, surface: pygame.Surface, counts: np.ndarray) -> None:
        s, w = self.s, self.size[0]
        x = self.hist.right + (w - self.hist.right) * 0.25
        y = 8 * s
        _text(surface, "bin  count  expected", (x, y), 14 * s, MUTED)
        step = 15 * s
        y += 18 * s
        total = int(counts.sum())
        for k, c in enumerate(counts):
            _text(surface, f"{k:>3}", (x, y), 14 * s, MUTED)
            _text(surface, f"{c:>5}", (x + 28 * s, y), 14 * s, INK)
            _text(surface, f"{total * self.pmf[k]:8.1f}", (x + 64 * s, y), 14 * s, EXPECTED)
            y += step
        if total:
            n, bins = self.board.rows, np.arange(len(counts))
            mean = float((counts * bins).sum()) / total
            variance = float((counts * (bins - mean) ** 2).sum()) / total
            y += 6 * s
            _text(surface, f"mean {mean:5.2f}", (x, y), 14 * s, INK)
            _text(surface, f"{n / 2:g}", (x + 92 * s, y), 14 * s, EXPECTED, "topright")
            _text(surface, f"variance {variance:5.2f}", (x, y + step), 14 * s, INK)
            _text(surface, f"{n / 4:g}", (x + 92 * s, y + step), 14 * s, EXPECTED, "topright")

    # -- the strobe picture -------------------------------------------------------------------
    def strobe_times(self) -> list[float]:
        """Every 1/30 s until the first three balls have left the board."""
        end = 2 * self.interval + 3.0
        return [k * self.strobe_interval for k in range(math.floor(end / self.strobe_interval) + 1)]

    def draw_strobe(self, surface: pygame.Surface, times: Sequence[float]) -> None:
        """The first three balls of the pour at each of ``times``, a dot each: their paths
        through the pegs (dots crowd where a ball bounces, spread where it falls freely)."""
        self.build(surface.get_size())
        galton = self.world = self.galton = Galton(self.board, self.seed, 3, self.interval)
        cam, s = self.camera, self.s
        paths: list[list[tuple[int, int]]] = [[], [], []]
        for t in times:
            while galton.t < t - 1e-9:
                galton.step(self.dt)
            for ball, p in zip(galton.balls, galton.world.positions(), strict=True):
                paths[galton.index_of(ball)].append(cam.point(p))
        surface.blit(self.background, (0, 0))
        dot = max(2, round(1.6 * s))
        for colour, path in zip(PATHS, paths, strict=True):
            if len(path) > 1:
                pygame.draw.lines(surface, colour, False, path, 1)
            for p in path:
                pygame.draw.circle(surface, colour, p, dot)
        self._histogram(surface, galton.t)
        x, y = 10 * s, 8 * s
        _text(surface, "Galton board", (x, y), 24 * s)
        _text(surface, "the first three balls,", (x, y + 28 * s), 15 * s, MUTED)
        _text(
            surface,
            f"a dot every {self.strobe_interval * 1000:.0f} ms",
            (x, y + 44 * s),
            15 * s,
            MUTED,
        )
        for k, (_, b) in enumerate(galton.landed):
            _text(surface, f"ball {k + 1}: bin {b}", (x, y + (70 + 18 * k) * s), 15 * s, PATHS[k])


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--interval",
        type=number_option(0.05, 10.0, "seconds between two balls"),
        default=POUR_INTERVAL,
        help=f"seconds between two balls let go from the funnel (default {POUR_INTERVAL:g}; "
        "the shorter, the more often balls meet on the pegs)",
    )


def _configure(scene: GaltonScene, args: argparse.Namespace) -> None:
    scene.interval = args.interval


DEMO = Demo(
    name="galton",
    summary="A Galton board: balls through 12 rows of pegs pile up as B(12, 1/2)",
    scenes={"board": GaltonScene},
    add_arguments=_add_arguments,
    configure=_configure,
)
