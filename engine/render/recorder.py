"""Drive a scene through the fixed-step loop: to numbered PNG frames and/or an MP4 or GIF clip,
to a still, or to a window.

Recording uses a virtual clock, so every frame lasts exactly 1/fps s of simulated time however
long it takes to draw and save; the physics always steps by the scene's own dt, and each frame
draws the state blended to the frame's exact time (see :mod:`engine.render.scene`). Recording
the same scene twice gives byte-identical files.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Container, Iterator
from dataclasses import dataclass
from pathlib import Path

import pygame

from engine.loop import FixedStep, RealClock, VirtualClock
from engine.render import marks
from engine.render.clips import (
    ClipWriter,
    check_clip_path,
    check_gif_fps,
    even_size,
    ffmpeg_exe,
)
from engine.render.frames import FrameWriter, save_png
from engine.render.headless import init_headless, init_window
from engine.render.mouse_drag import MouseDrag
from engine.render.progress import Progress
from engine.render.scene import Scene

__all__ = [
    "Recording",
    "RecordingInterrupted",
    "check_size",
    "frame_count",
    "iter_frames",
    "play",
    "record",
    "strobe",
]

#: The largest canvas accepted, a guard against a typo such as 64000x360.
MAX_SIDE = 8192
#: The highest frame rate accepted (frames per second).
MAX_FPS = 1000


@dataclass(frozen=True)
class Recording:
    """What :func:`record` wrote: ``count`` frames of ``size`` px at ``fps`` into ``folder``.

    ``folder`` is None when only a clip was asked for; ``video`` and ``gif`` are the clips
    written (None if not asked for). The MP4's own size is :attr:`video_size`.
    """

    folder: Path | None
    count: int
    fps: int
    seconds: float
    size: tuple[int, int]
    video: Path | None = None
    gif: Path | None = None

    def paths(self) -> list[Path]:
        """The frame files, in order (none if no frames were written)."""
        if self.folder is None:
            return []
        return [self.folder / f"frame_{i:05d}.png" for i in range(self.count)]

    @property
    def video_size(self) -> tuple[int, int]:
        """The MP4's (width, height) in px: ``size`` with an odd side cut to even."""
        return even_size(self.size)


def check_scene_size(scene: Scene, size: tuple[int, int]) -> tuple[int, int]:
    """``size`` checked as by :func:`check_size`, and at least the scene's ``min_size``."""
    width, height = check_size(size)
    need_w, need_h = scene.min_size
    if width < need_w or height < need_h:
        raise ValueError(
            f"size {width}x{height} is too small for the scene {scene.name!r}: it needs at "
            f"least {need_w}x{need_h} px"
        )
    return width, height


def check_size(size: tuple[int, int]) -> tuple[int, int]:
    """``size`` as (width, height) whole pixels, each 1 to 8192; ValueError naming it otherwise."""
    try:
        width, height = size
    except (TypeError, ValueError):
        raise ValueError(f"size must be (width, height) in pixels, got {size!r}") from None
    for side in (width, height):
        if isinstance(side, bool) or not isinstance(side, int) or not 1 <= side <= MAX_SIDE:
            raise ValueError(
                f"size must be two whole numbers of pixels from 1 to {MAX_SIDE}, got {size!r}"
            )
    return width, height


def _check_fps(fps: int) -> int:
    if isinstance(fps, bool) or not isinstance(fps, int) or not 1 <= fps <= MAX_FPS:
        raise ValueError(
            f"fps must be a whole number of frames per second from 1 to {MAX_FPS}, got {fps!r}"
        )
    return fps


def _check_seconds(seconds: float) -> float:
    if isinstance(seconds, bool) or not isinstance(seconds, (int, float)):
        raise TypeError(f"seconds must be a number, got {seconds!r}")
    if not (math.isfinite(seconds) and seconds > 0):
        raise ValueError(f"seconds must be a finite number > 0, got {seconds!r}")
    return float(seconds)


def frame_count(seconds: float, fps: int) -> int:
    """Frames in a recording of ``seconds`` at ``fps``: one at t = 0 and one every 1/fps s after,
    up to and including ``seconds`` (so the last frame shows the final state).

    >>> frame_count(10.0, 30)
    301
    """
    # The tiny tolerance keeps 0.1 s * 30 fps (2.9999999999999996 in floats) at 3 frames after 0.
    return math.floor(seconds * fps + 1e-9) + 1


def iter_frames(
    scene: Scene,
    fps: int = 30,
    seconds: float | None = None,
    size: tuple[int, int] = (640, 360),
    only: Container[int] | None = None,
) -> Iterator[tuple[int, float, pygame.Surface]]:
    """Build ``scene`` and yield (index, t, surface) for each frame; the surface is reused.

    ``only``: the frame indices to draw and yield (default: every one); the scene is stepped
    through the others as for a whole recording, so frame k is the same picture either way.

    Frame ``index`` shows the simulated time ``t = index / fps`` s. The same surface object is
    drawn on for every frame, so save or copy it before asking for the next one. While a frame
    is yielded, ``engine.render.marks.marks(surface)`` lists the labels and arrowheads on it.
    """
    fps = _check_fps(fps)
    seconds = _check_seconds(scene.duration if seconds is None else seconds)
    size = check_scene_size(scene, size)
    init_headless()
    surface = pygame.Surface(size)
    scene.build(size)
    # The clamp is for stalls of a real clock; every virtual frame must be simulated in full.
    loop = FixedStep(scene.dt, max_frame=max(0.25, 2 * scene.dt, 2.0 / fps))
    clock = VirtualClock(fps)
    # One step ahead: the blend of the states before and after the world's last step then
    # covers the frame's time exactly (see engine.render.scene).
    scene.step(scene.dt)
    for index in range(frame_count(seconds, fps)):
        if index > 0:
            for _ in range(loop.advance(clock.tick())):
                scene.step(scene.dt)
        if only is not None and index not in only:
            continue
        marks.clear(surface)
        scene.draw(surface, loop.alpha)
        yield index, index / fps, surface


class RecordingInterrupted(KeyboardInterrupt):
    """A recording was stopped part-way (Ctrl-C, or SIGTERM under ``python -m demos``).

    ``written`` whole frames are in ``folder``, numbered from frame_00000.png without gaps
    (frames are encoded in order, and one being encoded when the stop came is finished).
    A clip being written is never left: ``clips`` names those not written.
    """

    def __init__(self, folder: Path | None, written: int, clips: tuple[Path, ...] = ()) -> None:
        parts = [] if folder is None else [f"{written} whole frame(s) written to {folder}"]
        if clips:
            parts.append(f"no clip written ({', '.join(str(c) for c in clips)} left as before)")
        super().__init__("; ".join(parts))
        self.folder = folder
        self.written = written
        self.clips = clips


def record(
    scene: Scene,
    out_dir: str | os.PathLike[str] | None = None,
    fps: int = 30,
    seconds: float | None = None,
    size: tuple[int, int] = (640, 360),
    overwrite: bool = False,
    progress: Callable[[int, int], None] | bool | None = None,
    video: str | os.PathLike[str] | None = None,
    gif: str | os.PathLike[str] | None = None,
) -> Recording:
    """Record ``scene`` headless to PNG frames in ``out_dir`` and/or clips; say what was written.

    ``seconds`` defaults to the scene's duration; ``size`` is (width, height) px. ``video`` (a
    path ending in .mp4) and ``gif`` (ending in .gif) also stream the frames, as they are drawn,
    into an H.264 MP4 and a looping GIF at ``fps`` (they need the ``video`` extra, see
    :mod:`engine.render.clips`); ``out_dir`` may then be None for the clips alone. ``progress``:
    None or True shows a line on stderr for renders over ~2 s when stderr is a terminal, False
    is silent, a callable is called with (done, total) after each frame.

    Every target is checked before any work starts: raises
    :class:`~engine.render.frames.FramesExistError` if ``out_dir`` holds frames and
    :class:`~engine.render.clips.ClipExistsError` if a clip exists, unless ``overwrite``;
    :class:`~engine.render.clips.EncoderUnavailableError` for a clip without the extra;
    :class:`~engine.render.frames.FrameWriteError` /
    :class:`~engine.render.clips.ClipWriteError` if a frame or clip cannot be written (no
    partial clip is left under its name).
    """
    fps = _check_fps(fps)
    seconds = _check_seconds(scene.duration if seconds is None else seconds)
    size = check_scene_size(scene, size)
    if out_dir is None and video is None and gif is None:
        raise ValueError("record() needs somewhere to write: out_dir, video or gif")
    targets = [(kind, path) for kind, path in (("mp4", video), ("gif", gif)) if path is not None]
    clip_paths = [check_clip_path(path, kind, overwrite) for kind, path in targets]
    if gif is not None:
        check_gif_fps(fps)
    if clip_paths:
        ffmpeg_exe()  # EncoderUnavailableError now, before any frame folder is touched
    total = frame_count(seconds, fps)
    bar: Progress | None = None
    if progress is None or progress is True:
        bar = Progress(label=scene.name)
        report: Callable[[int, int], None] | None = bar
    elif progress is False:
        report = None
    else:
        report = progress
    writer = FrameWriter(out_dir, overwrite=overwrite) if out_dir is not None else None
    clips: list[ClipWriter] = []
    try:
        try:
            for path in clip_paths:
                clips.append(ClipWriter(path, size, fps, overwrite=overwrite))
            try:
                for index, _t, surface in iter_frames(scene, fps, seconds, size):
                    if writer is not None:
                        writer.write(surface)
                    for clip in clips:
                        clip.write(surface)
                    if report is not None:
                        report(index + 1, total)
            finally:
                if bar is not None:
                    bar.done()
            if writer is not None:
                writer.close()
            for clip in clips:
                clip.close()
        except BaseException:
            # The frame writer finishes the frames being encoded and drops queued ones; every
            # clip not yet renamed into place is stopped and its temporary file removed.
            if writer is not None:
                writer.abort()
            for clip in clips:
                clip.abort()
            raise
    except KeyboardInterrupt as stop:
        # Every frame file is renamed into place only once whole, without gaps.
        folder = writer.folder if writer is not None else None
        written = writer.written if writer is not None else 0
        done = {clip.path for clip in clips if clip.done}
        unwritten = tuple(path for path in clip_paths if path not in done)
        raise RecordingInterrupted(folder, written, unwritten) from stop
    return Recording(
        None if out_dir is None else Path(out_dir),
        total if writer is None else writer.count,
        fps,
        seconds,
        size,
        video=clip_paths[0] if video is not None else None,
        gif=clip_paths[-1] if gif is not None else None,
    )


def strobe(
    scene: Scene,
    path: str | os.PathLike[str],
    size: tuple[int, int] = (640, 360),
    times: list[float] | None = None,
    overwrite: bool = False,
) -> Path:
    """Save one still motion diagram of ``scene`` (its :meth:`Scene.draw_strobe`) as a PNG file.

    ``times`` (s) defaults to :meth:`Scene.strobe_times`. NotImplementedError if the scene has no
    strobe picture.
    """
    size = check_scene_size(scene, size)
    if not scene.has_strobe:
        raise NotImplementedError(f"the scene {scene.name!r} has no strobe picture")
    init_headless()
    surface = pygame.Surface(size)
    scene.build(size)
    draw_strobe(scene, surface, times)
    return save_png(surface, path, overwrite=overwrite)


def draw_strobe(scene: Scene, surface: pygame.Surface, times: list[float] | None = None) -> None:
    """Draw ``scene``'s motion diagram (built already) on ``surface``, its marks noted afresh."""
    marks.clear(surface)
    scene.draw_strobe(surface, scene.strobe_times() if times is None else times)


def play(
    scene: Scene,
    fps: int = 60,
    size: tuple[int, int] = (640, 360),
    seconds: float | None = None,
) -> None:
    """Show ``scene`` in a real-time window until it is closed (Esc or q), using the real clock.

    Space pauses, r restarts, and the left mouse button drags a body (engine.render.mouse_drag:
    a MouseJoint to the pointer while the button is held). The motion stops at ``seconds``
    (default: the scene's duration) and the last frame stays up. Raises
    :class:`~engine.render.headless.DisplayUnavailableError` where there is no display.
    """
    fps = _check_fps(fps)
    seconds = _check_seconds(scene.duration if seconds is None else seconds)
    size = check_scene_size(scene, size)
    init_window()
    try:
        screen = pygame.display.set_mode(size)
        pygame.display.set_caption(
            f"{scene.name}: {scene.summary}  (space: pause, r: restart, mouse: drag a body)"
        )
        limiter = pygame.time.Clock()
        drag = MouseDrag()
        while True:
            drag.release()
            scene.build(size)
            scene.step(scene.dt)
            loop = FixedStep(scene.dt, max_frame=max(0.25, 2 * scene.dt))
            clock = RealClock()
            clock.tick()
            paused = restart = False
            while not restart:
                for event in pygame.event.get():
                    if event.type == pygame.QUIT:
                        return
                    if event.type == pygame.KEYDOWN:
                        if event.key in (pygame.K_ESCAPE, pygame.K_q):
                            return
                        if event.key == pygame.K_SPACE:
                            paused = not paused
                        elif event.key == pygame.K_r:
                            restart = True
                    drag.handle(event, scene)
                elapsed = clock.tick()
                # Stop the motion at the end of the scene: hold the last state on screen.
                remaining = seconds - (loop.t + loop.alpha * loop.dt)
                frame = 0.0 if paused else max(0.0, min(elapsed, remaining))
                for _ in range(loop.advance(frame)):
                    scene.step(scene.dt)
                marks.clear(screen)
                scene.draw(screen, loop.alpha)
                drag.draw(screen, scene)
                pygame.display.flip()
                limiter.tick(fps)
    finally:
        pygame.display.quit()
