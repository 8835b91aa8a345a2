"""The fixed-timestep game loop: physics in whole steps of dt, drawing in between.

Frames arrive at whatever rate the screen (or the frame writer) allows; the
physics must always advance by the same dt, or its results would depend on
the frame rate. So each frame's time is put in an accumulator, as many whole
steps of dt are taken out as fit, and what is left over, a fraction
``alpha`` of a step, tells the renderer how far to blend from the previous
state to the current one:

    accumulator += frame_time
    steps = floor(accumulator / dt);  accumulator -= steps * dt
    alpha = accumulator / dt          in [0, 1)

Time is kept exactly, as fractions (a float is an exact binary fraction), so
a million frames of 1/60 s with dt = 1/120 s make exactly two million steps:
no drift from adding floats. A frame longer than ``max_frame`` (a stall, a
breakpoint) is clamped, and the dropped time is reported, so the simulation
slows down for a moment instead of spiralling into ever more catch-up steps.

>>> loop = FixedStep(dt=0.01)
>>> loop.advance(0.025), round(loop.alpha, 6)
(2, 0.5)
>>> clock = VirtualClock(fps=30)
>>> sum(loop.advance(clock.tick()) for _ in range(30)), loop.steps
(100, 102)
"""

from __future__ import annotations

import math
import sys
import time
from fractions import Fraction
from numbers import Integral, Real
from typing import Any, Protocol, runtime_checkable

__all__ = ["FixedStep", "VirtualClock", "RealClock", "Clock", "Steppable"]

_BELOW_ONE = math.nextafter(1.0, 0.0)  # the largest float < 1
_FLOAT_ROUNDING = Fraction(1, 2**52)  # relative spacing of floats: rounding is below this
_MAX_SECONDS = Fraction(sys.float_info.max)  # beyond it, dt and t could not be floats
_MIN_SECONDS = Fraction(5e-324)  # the smallest float above 0: below it a dt would read as 0


def _seconds(value: Any, name: str, *, allow_zero: bool = False) -> Fraction:
    """``value`` (seconds) as an exact Fraction; TypeError/ValueError naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, (Real, Fraction)):
        raise TypeError(f"{name} must be a number of seconds, got {type(value).__name__} {value!r}")
    if isinstance(value, Fraction):
        exact = value
    elif isinstance(value, Integral):
        exact = Fraction(int(value))  # int(): a numpy int would overflow in Fraction arithmetic
    else:
        seconds = float(value)  # exact for floats of any width (numpy's float32 too)
        if not math.isfinite(seconds):
            raise ValueError(f"{name} must be finite, got {value!r}")
        exact = Fraction(seconds)
    if abs(exact) > _MAX_SECONDS or 0 < abs(exact) < _MIN_SECONDS:
        raise ValueError(
            f"{name} must be seconds within the float range (5e-324 to 1.8e308), got {value!r}"
        )
    if exact < 0 or (exact == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} must be {bound} seconds, got {value!r}")
    return exact


def _as_meant(exact: Fraction) -> Fraction:
    """The fraction (denominator up to 10^6) whose float ``exact`` is, else ``exact`` itself.

    A float such as 1/120 or 1/60 is not exactly 1/120 or 1/60; read as the fraction the
    user meant, 120 steps make exactly one second, and frames of float 1/60 s make exactly
    two steps of 1/120 s. "Whose float" means within float rounding (2^-52 relative); a
    value with no such fraction that near (2.5e-7, which would round to 0, or a real
    clock's 0.0167341) keeps its exact binary value.
    """
    near = exact.limit_denominator(1_000_000)
    return near if abs(near - exact) <= exact * _FLOAT_ROUNDING else exact


@runtime_checkable
class Steppable(Protocol):
    """Anything whose time moves in fixed steps: what a scene steps and the loop drives.

    ``step(dt)`` is the only way its time moves (dt in s, usually 1/120 or 1/60); ``t`` is that
    time (s), counted in whole steps so that it never drifts; ``snapshot()`` returns everything
    needed to come back to this moment and ``restore(snapshot)`` comes back to it, bit for bit,
    so that a run paused, saved and resumed gives the states of a run never interrupted.
    :class:`engine.World` and :class:`engine.particles.Particles` speak it, and so does any
    object a game steps as a whole (several worlds, a world and the game's rules).
    """

    @property
    def t(self) -> float:
        """The time (s) of the current state."""
        ...

    def step(self, dt: float) -> object:
        """Advance by exactly ``dt`` seconds (one fixed step)."""
        ...

    def snapshot(self) -> Any:
        """Everything needed to return to this moment."""
        ...

    def restore(self, snapshot: Any) -> None:
        """Return to the moment ``snapshot`` was taken."""
        ...


class Clock(Protocol):
    """Something that answers, each frame, how many seconds passed since the last one."""

    def tick(self) -> float | Fraction: ...


class VirtualClock:
    """A clock for headless runs: every frame lasts exactly 1/fps s, however long drawing takes."""

    def __init__(self, fps: int = 60) -> None:
        if isinstance(fps, bool) or not isinstance(fps, int):
            raise TypeError(f"fps must be a whole number of frames per second, got {fps!r}")
        if fps <= 0:
            raise ValueError(f"fps must be > 0, got {fps!r}")
        self.fps = fps
        self.frames = 0
        self._frame = Fraction(1, fps)

    def tick(self) -> Fraction:
        """Start the next frame; returns its length, exactly 1/fps seconds."""
        self.frames += 1
        return self._frame

    @property
    def t(self) -> float:
        """Seconds of virtual time handed out so far (frames / fps)."""
        return self.frames / self.fps


class RealClock:
    """A wall clock for windows: each tick returns the seconds since the previous tick."""

    def __init__(self) -> None:
        self._last: float | None = None

    def tick(self) -> float:
        """Seconds since the previous tick (0.0 on the first)."""
        now = time.perf_counter()
        elapsed = 0.0 if self._last is None else now - self._last
        self._last = now
        return elapsed


class FixedStep:
    """Turns frame times into whole physics steps of ``dt`` (s) and a blend fraction ``alpha``.

    ``max_frame`` (s, usually 0.25) is the longest frame that is simulated in full;
    anything beyond it is dropped and added to ``dropped``. With a VirtualClock nothing
    stalls, so make it at least two frames (``max(0.25, 2 / fps)``) or a slow frame rate
    (below 4 fps with the default) would lose time on every frame.
    """

    def __init__(self, dt: float, max_frame: float = 0.25) -> None:
        # A float dt such as 1/120 is not exactly 1/120; read it as the nearest fraction
        # with a denominator up to 10^6 (what the user meant), so that 120 steps make
        # exactly one second and a million frames of 1/60 s exactly two million steps.
        self._dt = _as_meant(_seconds(dt, "dt"))
        self._max_frame = _seconds(max_frame, "max_frame")
        if self._max_frame < self._dt:
            raise ValueError(
                f"max_frame ({max_frame} s) must be at least one step dt ({dt} s), "
                f"or no step could ever run"
            )
        self.dt = float(dt)
        self.max_frame = float(max_frame)
        self._acc = Fraction(0)
        self._dropped = Fraction(0)
        self.steps = 0
        self.frames = 0

    def advance(self, frame_seconds: float | Fraction) -> int:
        """Add one frame's time (s); return how many whole steps of dt to run now."""
        frame = _seconds(frame_seconds, "frame_seconds", allow_zero=True)
        if type(frame_seconds) is not Fraction:
            frame = _as_meant(frame)  # read a float frame like dt (see _as_meant)
        dropped = self._dropped
        if frame > self._max_frame:
            dropped += frame - self._max_frame
            frame = self._max_frame
        acc = self._acc + frame
        steps = int(acc // self._dt)
        if (self.steps + steps) * self._dt > _MAX_SECONDS:
            raise ValueError(
                f"frame_seconds must keep the time within the float range (1.8e308 s): "
                f"{frame_seconds!r} would pass it; nothing was advanced"
            )
        self._dropped = dropped
        self._acc = acc - steps * self._dt
        self.steps += steps
        self.frames += 1
        return steps

    def run(self, world: Any, frame_seconds: float | Fraction) -> float:
        """Advance by one frame and step ``world`` (anything with ``step(dt)``, such as a
        :class:`Steppable`) the whole steps it holds; return alpha."""
        for _ in range(self.advance(frame_seconds)):
            world.step(self.dt)
        return self.alpha

    @property
    def alpha(self) -> float:
        """Fraction of a step left in the accumulator, in [0, 1): how far to blend for drawing."""
        # The exact ratio is < 1, but float() may round 1 - 1e-17 up to 1.0.
        return min(float(self._acc / self._dt), _BELOW_ONE)

    @property
    def t(self) -> float:
        """Simulated time (s): the whole steps taken times dt, computed exactly."""
        return float(self.steps * self._dt)

    @property
    def dropped(self) -> float:
        """Seconds of frame time dropped by the clamp so far (inf past the float range)."""
        try:
            return float(self._dropped)
        except OverflowError:  # frames of 1e308 s, dropped again and again
            return math.inf

    @property
    def accumulated(self) -> float:
        """Seconds waiting in the accumulator (less than one dt)."""
        return float(self._acc)
