"""Recording benchmark: the frame writer against ``pygame.image.save`` for the same frames.

Run with ``python -m demos.bench render``. Both sides drive the same scene through the same
fixed-step loop and draw the same picture at 640x360 (a ruler, three plot panels, a moving body
with its arrows, labels); the baseline saves each frame with ``pygame.image.save``, the recorder
hands it to :class:`engine.render.FrameWriter` (pixels copied out, PNG encoded on worker
threads). Target: recording at least 3x the baseline's frames per second, with the
same pixels in the files, which the report checks frame by frame.

With the ``video`` extra installed, the same frames are also streamed to an MP4 and to a GIF
(:class:`engine.render.ClipWriter`, ffmpeg in its own process). Target: writing
the MP4 costs at most what writing the PNG frames costs, i.e. at least their frames per second.
"""

from __future__ import annotations

import math
import os
import statistics
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from engine import Body, Vector, World

__all__ = ["BenchScene", "report"]

SIZE = (640, 360)
FPS = 30


def _scene_class() -> type:
    # Imported here: ``import demos.bench.render`` alone must not start pygame.
    from engine.render import (
        ACCELERATION,
        INK,
        PAPER,
        VELOCITY,
        Camera,
        Plot,
        Scene,
        draw_dot,
        draw_ruler,
        draw_text,
        draw_vector,
    )

    class BenchScene(Scene):
        """A body accelerating along a ruler, with live s, v, a plots: a lesson-like frame."""

        name = "bench"
        summary = "a lesson-like frame for timing the frame writer"
        duration = 3.0
        dt = 1.0 / 120.0
        world: World

        def build(self, size: tuple[int, int]) -> None:
            self.world = World(integrator="exact")
            self.body = self.world.add(Body(0.0, 0.5, 1.0))
            w, h = size
            self.camera = Camera((w - 40) / 11.4, (20 + 0.7 * (w - 40) / 11.4, 0.33 * h))
            pw, ph, top = (w - 48) // 3, h - round(0.5 * h) - 6, round(0.5 * h)
            self.plots = [
                Plot((12 + i * (pw + 12), top, pw, ph), self.duration, rng, title, color=c)
                for i, (title, rng, c) in enumerate(
                    [("s(t) in", (0, 10), INK), ("v(t) in/s", (0, 4), VELOCITY)]
                    + [("a(t) in/s2", (0, 2), ACCELERATION)]
                )
            ]

        def draw(self, surface, alpha: float) -> None:
            t = self.time(alpha)
            surface.fill(PAPER)
            draw_text(surface, "Benchmark frame", (12, 8), 24)
            draw_text(surface, f"t = {t:.2f} s", (surface.get_width() - 12, 8), 26, INK, "topright")
            s = self.world.position_of(self.body, alpha)
            assert not isinstance(s, Vector)  # a 1D world
            draw_ruler(surface, self.camera, 0.0, 10.0, -0.3, unit="in")
            draw_dot(surface, self.camera.to_px(s, 0.1), 9, (156, 66, 33))
            draw_vector(surface, self.camera, (s, 0.8), 0.5 + t, 1.0, VELOCITY, "v")
            draw_vector(surface, self.camera, (s, 1.4), 1.0, 1.0, ACCELERATION, "a")
            ts = np.linspace(0.0, t, 100)
            for plot, ys in zip(
                self.plots, (0.5 * ts + ts * ts / 2, 0.5 + ts, np.ones_like(ts)), strict=True
            ):
                plot.draw(surface, ts, ys, shade=plot is self.plots[1])

    return BenchScene


def BenchScene():  # noqa: N802  (a factory that reads like the class it returns)
    """A new lesson-like benchmark scene (an :class:`engine.render.Scene`)."""
    return _scene_class()()


def _baseline(folder: Path, seconds: float) -> int:
    import pygame

    from engine.render import frame_name, iter_frames

    folder.mkdir(parents=True, exist_ok=True)
    count = 0
    for index, _t, surface in iter_frames(BenchScene(), FPS, seconds, SIZE):
        pygame.image.save(surface, str(folder / frame_name(index)))
        count += 1
    return count


def _recorder(folder: Path, seconds: float) -> int:
    from engine.render import record

    return record(BenchScene(), folder, FPS, seconds, SIZE, overwrite=True, progress=False).count


def _clip(path: Path, seconds: float, kind: str) -> int:
    from engine.render import record

    clip = {"video" if kind == "mp4" else "gif": path}
    return record(BenchScene(), None, FPS, seconds, SIZE, True, False, **clip).count


def _clips_available() -> bool:
    import importlib.util

    return importlib.util.find_spec("imageio_ffmpeg") is not None


def _same_pixels(a: Path, b: Path, count: int) -> bool:
    import pygame

    from engine.render import frame_name

    for i in range(count):
        pa = pygame.surfarray.array3d(pygame.image.load(str(a / frame_name(i))))
        pb = pygame.surfarray.array3d(pygame.image.load(str(b / frame_name(i))))
        if not np.array_equal(pa, pb):
            return False
    return True


def _folder_bytes(folder: Path) -> int:
    return sum(p.stat().st_size for p in folder.iterdir())


def _cpu() -> float:
    # CPU seconds of this process (all threads) and of its finished child processes, so the
    # clips' column includes ffmpeg, which encodes in a process of its own.
    try:
        import resource
    except ImportError:  # Windows: this process only
        return time.process_time()
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def _timed(fn: Callable[[], int]) -> tuple[float, float, int]:
    # Wall-clock and CPU seconds (all threads of this process and its encoders) of one call,
    # and its frames.
    wall, cpu = time.perf_counter(), _cpu()
    count = fn()
    return time.perf_counter() - wall, _cpu() - cpu, count


def report(quick: bool = False) -> str:
    """Time both ways of saving the same frames, side by side; return the table as text.

    Each round records the frames once each way (alternating, so a burst of load on a shared
    machine hits both alike); the table gives medians over the rounds. Besides wall-clock
    frames per second it gives CPU milliseconds per frame, summed over all threads: the
    writer's speed-up comes from using less CPU (a lighter PNG encoder) and from using a
    second core (encoding beside drawing), and the two columns tell them apart.
    """
    from engine.render import init_headless

    init_headless()
    seconds = 1.0 if quick else 3.0
    rounds = 3 if quick else 7
    frames = math.floor(seconds * FPS + 1e-9) + 1
    with tempfile.TemporaryDirectory(prefix="bench-render-") as tmp:
        base_dir, ours_dir = Path(tmp) / "save", Path(tmp) / "writer"
        ways: dict[str, Callable[[], int]] = {
            "save": lambda: _baseline(base_dir, seconds),
            "writer": lambda: _recorder(ours_dir, seconds),
        }
        clips = _clips_available()
        if clips:
            mp4, gif = Path(tmp) / "clip.mp4", Path(tmp) / "clip.gif"
            ways["mp4"] = lambda: _clip(mp4, seconds, "mp4")
            ways["gif"] = lambda: _clip(gif, seconds, "gif")
        for fn in ways.values():
            fn()  # warm up: fonts, imports, thread pool start-up are not the steady state
        walls: dict[str, list[float]] = {name: [] for name in ways}
        cpus: dict[str, list[float]] = {name: [] for name in ways}
        for _ in range(rounds):
            for name, fn in ways.items():
                wall_s, cpu_s, count = _timed(fn)
                walls[name].append(wall_s / count)
                cpus[name].append(cpu_s / count)
        same = _same_pixels(base_dir, ours_dir, frames)
        size_base, size_ours = _folder_bytes(base_dir), _folder_bytes(ours_dir)
        if clips:
            size_mp4, size_gif = mp4.stat().st_size, gif.stat().st_size
    wall = {name: statistics.median(v) for name, v in walls.items()}
    cpu = {name: statistics.median(v) for name, v in cpus.items()}
    ratio = wall["save"] / wall["writer"]
    rows = [
        ("draw + pygame.image.save", "save", size_base),
        ("draw + FrameWriter (threads)", "writer", size_ours),
    ]
    lines = [
        f"render: recording {frames} frames of {SIZE[0]}x{SIZE[1]} at {FPS} fps "
        f"(median of {rounds} rounds, {os.cpu_count()} CPUs, load {_load()})",
        f"  {'method':<32}{'frames/s':>9}{'ms/frame':>10}{'CPU ms/frame':>14}{'KB/frame':>10}",
    ]
    if clips:
        rows += [
            ("draw + ClipWriter MP4 (H.264)", "mp4", size_mp4),
            ("draw + ClipWriter GIF", "gif", size_gif),
        ]
    for label, name, size in rows:
        lines.append(
            f"  {label:<32}{1 / wall[name]:>9.0f}{1e3 * wall[name]:>10.2f}"
            f"{1e3 * cpu[name]:>14.2f}{size / frames / 1024:>10.1f}"
        )
    lines.append(
        f"  speed-up {ratio:.1f}x in frames/s (target >= 3x: {'met' if ratio >= 3 else 'NOT met'})"
        f", {cpu['save'] / cpu['writer']:.1f}x less CPU per frame; "
        f"same pixels in every frame: {'yes' if same else 'NO'}"
    )
    if clips:
        mp4_ratio = wall["writer"] / wall["mp4"]
        lines.append(
            f"  MP4 against PNG frames: {mp4_ratio:.2f}x the frames/s (target >= 1x: "
            f"{'met' if mp4_ratio >= 1 else 'NOT met'}); GIF {wall['writer'] / wall['gif']:.2f}x; "
            "CPU ms/frame includes ffmpeg's own process"
        )
    else:
        lines.append(
            "  MP4 and GIF: not measured, the video extra is not installed "
            '(pip install -e ".[video]")'
        )
    return "\n".join(lines)


def _load() -> str:
    # The 1-minute load average, where the system reports one: other work on a shared machine
    # takes the second core the writer's threads would use.
    try:
        return f"{os.getloadavg()[0]:.1f}"
    except (AttributeError, OSError):
        return "unknown"
