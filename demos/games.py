"""What the games share (``breakout``, ``pinball``): a whole game played in a window or, headless,
by its autopilot into PNG frames until a little after it ends."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from engine.render import FrameWriter, iter_frames
from engine.render import play as play_window

__all__ = ["run_game"]


def run_game(
    scene: Any,
    window: bool,
    seconds: float | None,
    fps: int,
    size: tuple[int, int],
    out: Path,
    overwrite: bool,
    window_seconds: float,
    max_seconds: float,
    after_end: float,
) -> None:
    """Play ``scene`` (a Scene whose ``game.score.over`` says the game has ended): in a window
    for ``seconds`` (``window_seconds`` if None), or headless, writing PNG frames at ``fps`` to
    ``out`` 1/fps s apart: for ``seconds`` if given, else until ``after_end`` s after the game
    ends (at most ``max_seconds``)."""
    if window:
        play_window(scene, fps, size, window_seconds if seconds is None else seconds)
        return
    ended: float | None = None
    with FrameWriter(out, overwrite=overwrite) as frames:
        for index, t, surface in iter_frames(scene, fps, seconds or max_seconds, size):
            if index > 0:  # the game's frames start one frame in
                frames.write(surface)
            if seconds is None and scene.game.score.over:
                ended = t if ended is None else ended
                if t >= ended + after_end:
                    break
