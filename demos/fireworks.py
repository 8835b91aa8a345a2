"""Fireworks with gravity, drag, a changing wind and bursts: the demo lesson 1 promises next.

In the spirit of the fireworks demo of Millington's Cyclone engine: rockets leave the ground
with a random velocity in a range and a fuse; when the fuse burns out a rocket bursts into its
payload, sparks whose velocities are the rocket's own plus a random spread; a spark may burst
again (a crossette). Every particle feels gravity and a wind, F = -k (v - air(t)): with no air
it is plain drag, and a spark left long enough drifts at the terminal velocity air + g m / k.
Sparks fade with age.

The kinds of firework are DATA (:data:`KINDS`): a new firework is a new entry, not new code.
All particles live in one :class:`engine.particles.Particles` system, stepped in a handful of
numpy operations; the sparks are drawn with numpy into a pixel array (no per-spark Python).

    python -m demos fireworks --seed 7 --seconds 10
    python -m demos fireworks --wind 3 --window
    python -m demos fireworks --kinds peony,ring
"""

from __future__ import annotations

import argparse
import copy
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from numbers import Real
from typing import Any

import numpy as np
import pygame

from demos.cli import Demo, number_option
from engine.forces import Gravity, Wind
from engine.particles import Particles, ParticlesSnapshot
from engine.render import Camera, Scene, draw_text

__all__ = [
    "KINDS",
    "Kind",
    "FireworksScene",
    "FireworksSnapshot",
    "Finale",
    "SparkPainter",
    "kind_index",
    "DEMO",
]

Color = tuple[int, int, int]


@dataclass(frozen=True)
class Kind:
    """One kind of firework particle: its look, its fuse and what it bursts into.

    ``fuse`` (s): its lifetime, drawn uniformly from this range. ``speed`` (m/s): at birth in
    a burst it gets its parent's velocity plus this much speed, drawn uniformly from the range,
    in a random direction: ``pattern`` "sphere" is a 3D shell seen from the side (a filled disc,
    brighter at the rim), "ring" a flat ring facing us. ``launch`` ((vx_min, vx_max), (vy_min,
    vy_max)) m/s makes it a rocket fired from the ground. ``payload``: (kind name, count) pairs
    emitted where its fuse burns out. ``brightness``: 1 is a normal spark.
    """

    name: str
    color: Color
    fuse: tuple[float, float]
    speed: tuple[float, float] = (0.0, 0.0)
    pattern: str = "sphere"
    payload: tuple[tuple[str, int], ...] = ()
    launch: tuple[tuple[float, float], tuple[float, float]] | None = None
    brightness: float = 1.0


#: Every kind of firework particle. Rockets (with ``launch``) come first.
KINDS: tuple[Kind, ...] = (
    # Rockets: a warm white head; burst near the top of their climb (~2 s, ~25 m).
    Kind("peony", (255, 214, 170), (1.6, 2.0), payload=(("red star", 260),),
         launch=((-4.0, 4.0), (31.0, 36.0)), brightness=2.5),
    Kind("chrysanthemum", (255, 214, 170), (1.6, 2.0), payload=(("gold star", 340),),
         launch=((-4.0, 4.0), (31.0, 36.0)), brightness=2.5),
    Kind("ring", (255, 214, 170), (1.5, 1.9), payload=(("cyan ring", 140), ("white star", 30)),
         launch=((-3.0, 3.0), (30.0, 35.0)), brightness=2.5),
    Kind("crossette", (255, 214, 170), (1.5, 1.8), payload=(("crossette star", 9),),
         launch=((-3.0, 3.0), (31.0, 35.0)), brightness=2.5),
    Kind("willow", (255, 214, 170), (1.8, 2.2), payload=(("willow star", 240),),
         launch=((-3.0, 3.0), (33.0, 37.0)), brightness=2.5),
    # Stars, born in bursts.
    Kind("red star", (255, 64, 52), (1.4, 2.1), speed=(6.0, 16.0), brightness=1.4),
    Kind("gold star", (255, 176, 60), (1.5, 2.3), speed=(5.0, 17.0)),
    Kind("cyan ring", (70, 215, 255), (1.3, 1.7), speed=(13.0, 13.8), pattern="ring",
         brightness=1.5),
    Kind("white star", (235, 235, 255), (0.6, 1.0), speed=(1.0, 6.0), brightness=0.7),
    Kind("crossette star", (180, 255, 120), (0.6, 0.75), speed=(13.0, 14.0), pattern="ring",
         payload=(("green spark", 16),), brightness=2.0),
    Kind("green spark", (120, 255, 90), (0.6, 1.0), speed=(4.0, 7.0), pattern="ring"),
    Kind("willow star", (255, 150, 40), (2.6, 3.4), speed=(4.0, 11.0), brightness=0.8),
)  # fmt: skip

#: Names of the kinds that are rockets (have a launch rule).
ROCKETS: tuple[str, ...] = tuple(k.name for k in KINDS if k.launch is not None)

_BY_NAME = {k.name: i for i, k in enumerate(KINDS)}


def kind_index(name: str) -> int:
    """The index in :data:`KINDS` of the kind called ``name``; ValueError listing the names."""
    if not isinstance(name, str):
        raise TypeError(f"firework kind must be a name (str), got {type(name).__name__} {name!r}")
    try:
        return _BY_NAME[name]
    except KeyError:
        raise ValueError(
            f"unknown firework kind {name!r}; valid kinds: {', '.join(_BY_NAME)}"
        ) from None


def _check_table(kinds: Sequence[Kind]) -> None:
    """Every payload names a known kind, every range is ordered: fail at import, not mid-show."""
    for k in kinds:
        for low, high in (k.fuse, k.speed):
            if not 0 <= low <= high:
                raise ValueError(f"kind {k.name!r}: ranges need 0 <= low <= high, got {k}")
        if k.fuse[0] <= 0:
            raise ValueError(f"kind {k.name!r}: fuse must be > 0 s, got {k.fuse}")
        if k.pattern not in ("sphere", "ring"):
            raise ValueError(f"kind {k.name!r}: pattern must be 'sphere' or 'ring'")
        for child, count in k.payload:
            kind_index(child)
            if count < 0:
                raise ValueError(f"kind {k.name!r}: payload count must be >= 0, got {count}")


_check_table(KINDS)


# ------------------------------------------------------------------------------- drawing


class SparkPainter:
    """Draws many glowing dots with numpy into a pixel array, with a fading afterglow.

    Each spark adds its colour times its brightness to the pixel it lands on (one
    ``np.bincount`` per colour channel over all sparks, no Python loop); a small cross kernel
    spreads that light to the four neighbours, so each spark is a soft dot; the glow of
    earlier frames fades by ``exp(-elapsed / afterglow)``, which leaves short light trails as a
    camera's exposure does. The result is added to a background and blitted to the surface.
    """

    def __init__(
        self, size: tuple[int, int], palette: Iterable[Color], background: np.ndarray
    ) -> None:
        self.width, self.height = size
        self.palette = np.asarray(list(palette), dtype=np.float32) / 255.0  # (K, 3)
        # Everything is (W, H, 3), x major, the layout pygame.surfarray uses.
        self.glow = np.zeros((self.width, self.height, 3), dtype=np.float32)
        self.background = background.astype(np.float32)  # 0..255
        self._side = np.empty_like(self.glow)
        self._light = np.empty_like(self.glow)
        self._out = np.empty((self.width, self.height, 3), dtype=np.uint8)
        self._channel = np.arange(3)

    def clear(self) -> None:
        """Forget the afterglow."""
        self.glow[...] = 0.0

    def paint(
        self,
        surface: pygame.Surface,
        px: np.ndarray,
        py: np.ndarray,
        brightness: np.ndarray,
        kinds: np.ndarray,
        fade: float,
    ) -> None:
        """Fade the old glow by ``fade`` (0..1), add the sparks at pixels (px, py), blit it all."""
        w, h = self.width, self.height
        ix = px.astype(np.intp)  # truncation: floor for the pixels on screen (px >= 0)
        iy = py.astype(np.intp)
        inside = (px >= 0) & (ix < w) & (py >= 0) & (iy < h)
        pixel = ix[inside] * h + iy[inside]  # index into (W, H), x major
        # One bincount for the three channels: index pixel * 3 + channel, weight colour * light.
        flat = (pixel[:, None] * 3 + self._channel).ravel()
        light = (brightness[inside, None] * self.palette[kinds[inside]]).ravel()
        counts = np.bincount(flat, weights=light, minlength=w * h * 3)
        fresh = counts.astype(np.float32).reshape(w, h, 3)
        glow, side = self.glow, self._side
        glow *= np.float32(fade)
        glow += fresh
        # The soft dot: the centre pixel full, its four neighbours at 0.3.
        np.multiply(fresh, np.float32(0.3), out=side)
        glow[1:] += side[:-1]
        glow[:-1] += side[1:]
        glow[:, 1:] += side[:, :-1]
        glow[:, :-1] += side[:, 1:]
        # Light adds up, and saturates towards white where it piles up (dense bursts).
        out = self._light
        np.minimum(glow, np.float32(1.0), out=out)
        out *= np.float32(255.0)
        out += self.background
        np.minimum(out, np.float32(255.0), out=out)
        self._out[...] = out
        pygame.surfarray.blit_array(surface, self._out)


def _sky(size: tuple[int, int]) -> np.ndarray:
    """A night sky (W, H, 3) uint8: deep blue at the top to a faint glow of the town below."""
    w, h = size
    f = np.linspace(0.0, 1.0, h, dtype=np.float32)[None, :, None]
    top = np.array([4, 6, 20], dtype=np.float32)
    low = np.array([26, 22, 44], dtype=np.float32)
    sky = top + (low - top) * f**2
    return np.broadcast_to(sky, (w, h, 3)).astype(np.uint8)


def _skyline(camera: Camera, size: tuple[int, int]) -> list[pygame.Rect]:
    """Main Street's roofs along the bottom (a fixed pattern, the same for every seed), px."""
    w, h = size
    ground = round(camera.to_px(0.0, 0.0)[1])
    rects, x, i = [], 0, 0
    widths = (34, 22, 46, 28, 40, 18, 52, 30, 26, 44, 36, 24)
    heights = (26, 40, 18, 34, 22, 48, 16, 30, 38, 20, 28, 44)
    scale = h / 360
    while x < w:
        bw, bh = round(widths[i % 12] * scale), round(heights[(i * 5) % 12] * scale)
        rects.append(pygame.Rect(x, ground - bh, bw + 1, h - ground + bh))
        x += bw
        i += 1
    return rects


# --------------------------------------------------------------------------------- scenes


@dataclass(frozen=True)
class FireworksSnapshot:
    """Everything a fireworks scene needs to resume: see :meth:`FireworksScene.snapshot`."""

    particles: ParticlesSnapshot
    rng: Mapping[str, Any]  # the random generator's state
    next_launch: float  # s
    launched: int
    last_drawn: float | None  # s: the time of the last frame drawn, for the afterglow's fade
    glow: np.ndarray  # (W, H, 3) the afterglow of the frames drawn so far


def _positive(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be a number, got {type(value).__name__} {value!r}")
    if not math.isfinite(value) or value < 0:
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return float(value)


class FireworksScene(Scene):
    """Rockets launched at random, bursting into sparks in a wind that gusts."""

    name = "show"
    summary = "rockets, bursts and a gusting wind"
    duration = 10.0
    dt = 1.0 / 120.0
    seed = 7

    #: Seconds between launches, drawn uniformly from this range.
    interval: tuple[float, float] = (0.25, 0.6)
    #: Most particles alive at once.
    capacity = 20_000
    #: Mass of each particle (kg) and its drag coefficient k (N s/m): the velocity relaxes to
    #: the air's at the rate k/m = 0.6 1/s; a spark falls at most g m / k = 16 m/s in still air.
    mass = 0.01
    k = 0.006
    #: Seconds the glow of a spark takes to fade to 1/e after it has moved on.
    afterglow = 0.05
    #: Exposure (s) of a spark's streak, and how many dots draw it.
    exposure = 1.0 / 40.0
    streak = 4

    def __init__(self, wind: float = 2.0, kinds: Iterable[str] | None = None) -> None:
        self.wind = wind
        self.kinds = ROCKETS if kinds is None else tuple(kinds)

    @property
    def wind(self) -> float:
        """Mean wind speed (m/s, blowing to the right); it gusts 30 % around this."""
        return self._wind

    @wind.setter
    def wind(self, value: float) -> None:
        if isinstance(value, (tuple, list, np.ndarray)):
            raise TypeError(
                f"wind is a speed in m/s (a number; it blows along +x), got {value!r}; "
                "for a wind in any direction use engine.forces.Wind with a Vector"
            )
        self._wind = _positive(value, "wind")

    @property
    def kinds(self) -> tuple[str, ...]:
        """The rockets this scene launches, by name."""
        return self._kinds

    @kinds.setter
    def kinds(self, names: Iterable[str]) -> None:
        names = tuple(names)
        if not names:
            raise ValueError(f"kinds must name at least one rocket; valid: {', '.join(ROCKETS)}")
        for n in names:
            if kind_index(n) is not None and KINDS[kind_index(n)].launch is None:
                raise ValueError(
                    f"firework kind {n!r} is not a rocket (it has no launch rule); "
                    f"rockets: {', '.join(ROCKETS)}"
                )
        self._kinds = names

    def air(self, t: float) -> tuple[float, float]:
        """The air's velocity (m/s) at time t (s): the mean wind with two slow gusts on top."""
        w = self._wind
        return (w * (1.0 + 0.2 * math.sin(0.9 * t) + 0.1 * math.sin(2.3 * t + 1.0)), 0.0)

    # -- physics --------------------------------------------------------------------------

    def build(self, size: tuple[int, int]) -> None:
        self.size = size
        self.rng = np.random.default_rng(self.seed)
        self.world = self.particles = Particles(
            self.capacity,
            dt=self.dt,
            forces=[Gravity((0.0, -9.81)), Wind(self.air, self.k)],
            mass=self.mass,
        )
        self._rocket_ids = np.array([kind_index(n) for n in self._kinds])
        self.next_launch = 0.6
        self.launched = 0
        # 80 m wide at 16:9, the ground a little above the bottom edge.
        w, h = size
        self.camera = Camera.fit((-40.0, -3.0, 40.0, 42.0), (0, 0, w, h))
        palette = [k.color for k in KINDS]
        self.painter = SparkPainter(size, palette, _sky(size))
        self.brightness = np.array([k.brightness for k in KINDS], dtype=np.float64)
        self.roofs = _skyline(self.camera, size)
        self._last_drawn: float | None = None
        for x in (-15.0, 12.0):  # two rockets already on their way at t = 0
            self.launch(self._kinds[int(self.rng.integers(len(self._kinds)))], x)

    def launch(self, name: str, x: float) -> None:
        """Fire one rocket of kind ``name`` from the ground at x (m)."""
        i = kind_index(name)
        kind = KINDS[i]
        if kind.launch is None:
            raise ValueError(f"firework kind {name!r} is not a rocket; rockets: {ROCKETS}")
        (vx0, vx1), (vy0, vy1) = kind.launch
        v = (self.rng.uniform(vx0, vx1), self.rng.uniform(vy0, vy1))
        fuse = self.rng.uniform(*kind.fuse)
        self.particles.emit(1, (x, 0.0), v, fuse, i)
        self.launched += 1

    def burst(self, position: np.ndarray, velocity: np.ndarray, parent: int) -> None:
        """Emit the payload of a particle of kind ``parent`` that burnt out at ``position``."""
        for child, count in KINDS[parent].payload:
            i = kind_index(child)
            kind = KINDS[i]
            speed = self.rng.uniform(*kind.speed, count)
            if kind.pattern == "sphere":
                # A direction uniform on the unit sphere (z uniform in [-1, 1], phi uniform),
                # seen from the side: we keep x and y, so the disc is brighter at its rim.
                z = self.rng.uniform(-1.0, 1.0, count)
                scale = speed * np.sqrt(1.0 - z * z)
            else:
                scale = speed
            phi = self.rng.uniform(0.0, 2.0 * math.pi, count)
            v = velocity + np.column_stack((scale * np.cos(phi), scale * np.sin(phi)))
            fuse = self.rng.uniform(*kind.fuse, count)
            self.particles.emit(count, position, v, fuse, i)

    def step(self, dt: float) -> None:
        """One step of ``dt`` s (the particles' own step): burst, launch, clear the fallen."""
        p = self.particles
        if p.step(dt):
            gone = p.expired
            for pos, vel, kind in zip(gone.positions, gone.velocities, gone.kinds, strict=True):
                self.burst(pos, vel, int(kind))
        if p.t >= self.next_launch:
            name = self._kinds[int(self.rng.integers(len(self._kinds)))]
            self.launch(name, float(self.rng.uniform(-22.0, 22.0)))
            self.next_launch = p.t + float(self.rng.uniform(*self.interval))
        if p.steps % 8 == 0 and len(p):  # sparks that fell behind the roofs are gone
            p.kill(p.positions[:, 1] < -3.0)

    # -- saving and resuming -------------------------------------------------------------

    def snapshot(self) -> FireworksSnapshot:
        """The particles, the random generator, the launch schedule and the afterglow."""
        return FireworksSnapshot(
            particles=self.particles.snapshot(),
            rng=copy.deepcopy(self.rng.bit_generator.state),
            next_launch=self.next_launch,
            launched=self.launched,
            last_drawn=self._last_drawn,
            glow=self.painter.glow.copy(),
        )

    def restore(self, snapshot: FireworksSnapshot) -> None:
        """Return to the moment ``snapshot()`` was taken: the next frames are the same."""
        if not isinstance(snapshot, FireworksSnapshot):
            raise TypeError(
                f"restore takes a FireworksSnapshot from FireworksScene.snapshot(), got "
                f"{type(snapshot).__name__}"
            )
        if snapshot.glow.shape != self.painter.glow.shape:
            raise ValueError(
                f"the snapshot's afterglow is {snapshot.glow.shape[:2]} px but this scene is "
                f"{self.painter.glow.shape[:2]} px: restore into a scene built at the same size"
            )
        self.particles.restore(snapshot.particles)
        self.rng.bit_generator.state = copy.deepcopy(snapshot.rng)
        self.next_launch, self.launched = snapshot.next_launch, snapshot.launched
        self._last_drawn = snapshot.last_drawn
        self.painter.glow[...] = snapshot.glow

    # -- drawing --------------------------------------------------------------------------

    def draw(self, surface: pygame.Surface, alpha: float) -> None:
        p = self.particles
        t = self.time(alpha)
        elapsed = 1.0 / 30.0 if self._last_drawn is None else max(0.0, t - self._last_drawn)
        self._last_drawn = t
        xy = p.positions_at(alpha)
        # A spark fades as (1 - age/lifetime)^1.5: bright at the burst, gone as its fuse ends.
        life = 1.0 - np.minimum(p.ages / p.lifetimes, 1.0)
        kinds = p.kinds
        bright = self.brightness[kinds] * life * np.sqrt(life)
        # Each spark is a short streak, as in a photograph: samples back along its velocity
        # over the exposure, dimmer towards the tail.
        back = p.velocities * (self.exposure / self.streak)
        n, k = len(p), self.streak
        xs = np.empty((k, n, 2))
        for j in range(k):
            np.subtract(xy, back * j, out=xs[j])
        weights = np.concatenate([bright * (1.0 - j / k) for j in range(k)])
        px, py = self.camera.to_px(xs[..., 0].ravel(), xs[..., 1].ravel())
        fade = math.exp(-elapsed / self.afterglow)
        self.painter.paint(surface, px, py, weights, np.tile(kinds, k), fade)
        self.draw_overlay(surface, t)

    def draw_overlay(self, surface: pygame.Surface, t: float) -> None:
        """The town's roofs, the wind and the counts."""
        w, h = self.size
        for r in self.roofs:
            pygame.draw.rect(surface, (10, 10, 16), r)
        for i, r in enumerate(self.roofs):  # a few lit windows, fixed, the same every frame
            if i % 3 == 1 and r.height > 30:
                win = pygame.Rect(r.x + r.width // 3, r.y + 8, 4, 5)
                pygame.draw.rect(surface, (120, 100, 50), win)
        air = self.air(t)[0]
        s = h / 360
        draw_text(surface, f"wind {air:4.1f} m/s", (10 * s, 10 * s), round(20 * s), (200, 200, 220))
        x0, y0 = 10 * s + 110 * s, 18 * s
        if air > 0.05:
            tip = x0 + min(60.0, 8.0 * air) * s
            pygame.draw.line(surface, (200, 200, 220), (x0, y0), (tip, y0), max(1, round(2 * s)))
            pygame.draw.polygon(
                surface, (200, 200, 220), [(tip + 6 * s, y0), (tip, y0 - 4 * s), (tip, y0 + 4 * s)]
            )
        p = self.particles
        text = f"t = {t:4.1f} s   sparks {len(p):5d}"
        if p.dropped:
            text += f"   dropped {p.dropped} (full)"
        draw_text(surface, text, (w - 10 * s, 10 * s), round(20 * s), (200, 200, 220), "topright")


class Finale(FireworksScene):
    """The finale: a rocket every tenth of a second, thousands of sparks at once."""

    name = "finale"
    summary = "a rocket every 0.1 s: thousands of sparks at once"
    duration = 8.0
    interval = (0.05, 0.15)
    capacity = 40_000


# ------------------------------------------------------------------------------------ CLI


def _kinds_arg(text: str) -> tuple[str, ...]:
    names = tuple(n.strip() for n in text.split(",") if n.strip())
    bad = [n for n in names if n not in ROCKETS]
    if bad or not names:
        raise argparse.ArgumentTypeError(
            f"unknown rocket kind {', '.join(bad) or text!r}; valid: {','.join(ROCKETS)}"
        )
    return names


_wind_arg = number_option(0.0, 30.0, "a wind speed in m/s (it blows to the right)")


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--wind", type=_wind_arg, default=2.0, help="mean wind speed in m/s (default 2; 0 to 30)"
    )
    parser.add_argument(
        "--kinds",
        type=_kinds_arg,
        default=None,
        help=f"comma-separated rockets to launch (default all: {','.join(ROCKETS)})",
    )


def _configure(scene: FireworksScene, args: argparse.Namespace) -> None:
    scene.wind = args.wind
    if args.kinds is not None:
        scene.kinds = args.kinds


DEMO = Demo(
    name="fireworks",
    summary="Rockets, bursts, sparks in gravity, drag and wind (lesson 2's promise)",
    scenes={"show": FireworksScene, "finale": Finale},
    add_arguments=_add_arguments,
    configure=_configure,
)
