"""The renderer: the only package of the engine that imports pygame.

It draws a World through a :class:`Camera` onto any pygame Surface, writes numbered PNG frames
without a screen, and drives :class:`Scene` objects through the fixed-step loop to frames and
MP4 or GIF clips (:func:`record`), to one still motion diagram (:func:`strobe`) or to a window
(:func:`play`). Clips need the optional ``video`` extra (imageio-ffmpeg), imported only when a
clip is written.

Headless use (no screen, no sound card)::

    from engine.render import init_headless, record
    init_headless()                      # SDL dummy drivers, display + font modules only
    record(MyScene(), "out/my_scene")    # out/my_scene/frame_00000.png, ...
    record(MyScene(), video="out/my_scene.mp4", gif="out/my_scene.gif")  # clips only
"""

import os

# pygame prints a banner on import unless this is set; a user's own setting wins.
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

from engine.render.camera import Camera
from engine.render.clips import (
    ClipExistsError,
    ClipWriteError,
    ClipWriter,
    EncoderUnavailableError,
)
from engine.render.draw import (
    ACCELERATION,
    EULER,
    EXACT,
    GRID,
    INK,
    MUTED,
    PAPER,
    POSITION,
    VELOCITY,
    draw_arrow,
    draw_disc,
    draw_dot,
    draw_grid,
    draw_ruler,
    draw_sprite,
    draw_text,
    draw_trail,
    draw_vector,
    font,
)
from engine.render.frames import (
    FramesExistError,
    FrameWriteError,
    FrameWriter,
    encode_png,
    frame_name,
    save_png,
)
from engine.render.headless import DisplayUnavailableError, init_headless, init_window
from engine.render.plot import Plot
from engine.render.progress import Progress
from engine.render.recorder import (
    Recording,
    RecordingInterrupted,
    frame_count,
    iter_frames,
    play,
    record,
    strobe,
)
from engine.render.scene import Scene
from engine.render.world_view import draw_world

__all__ = [
    "ACCELERATION",
    "EULER",
    "EXACT",
    "GRID",
    "INK",
    "MUTED",
    "PAPER",
    "POSITION",
    "VELOCITY",
    "Camera",
    "ClipExistsError",
    "ClipWriteError",
    "ClipWriter",
    "DisplayUnavailableError",
    "EncoderUnavailableError",
    "FrameWriteError",
    "FrameWriter",
    "FramesExistError",
    "Plot",
    "Progress",
    "Recording",
    "RecordingInterrupted",
    "Scene",
    "draw_arrow",
    "draw_disc",
    "draw_dot",
    "draw_grid",
    "draw_ruler",
    "draw_sprite",
    "draw_text",
    "draw_trail",
    "draw_vector",
    "draw_world",
    "encode_png",
    "font",
    "frame_count",
    "frame_name",
    "iter_frames",
    "init_headless",
    "init_window",
    "play",
    "record",
    "save_png",
    "strobe",
]
