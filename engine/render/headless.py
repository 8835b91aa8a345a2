"""Start pygame without a screen or a sound card: the only place the renderer initialises SDL.

SDL reads ``SDL_VIDEODRIVER`` when the display module starts, so setting it to ``dummy``
before :func:`init_headless` is enough; ``setdefault`` keeps a user's own choice. Only the
display and font modules are started: ``pygame.init()`` would also open audio and print ALSA
errors on a machine without sound.
"""

from __future__ import annotations

import os
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import pygame  # noqa: E402  (the prompt variable must be set before the import)

__all__ = ["DisplayUnavailableError", "init_headless", "init_window"]


class DisplayUnavailableError(RuntimeError):
    """Raised when a real window is asked for where there is no display."""


def init_headless() -> None:
    """Initialise pygame's display and font modules with the dummy video and audio drivers."""
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    if not pygame.display.get_init():
        pygame.display.init()
    if not pygame.font.get_init():
        pygame.font.init()


def init_window() -> None:
    """Initialise pygame for a real window; DisplayUnavailableError if there is no display."""
    driver = os.environ.get("SDL_VIDEODRIVER", "")
    if driver in ("dummy", "offscreen"):
        raise DisplayUnavailableError(
            f"no window can open: SDL_VIDEODRIVER={driver!r} selects a driver without a screen; "
            "unset it on a machine with a display, or record frames instead (drop --window)"
        )
    try:
        if not pygame.display.get_init():
            with _runtime_dir():
                pygame.display.init()
    except pygame.error as exc:
        raise DisplayUnavailableError(
            f"no window can open: SDL found no display ({exc}); "
            "record frames instead (drop --window)"
        ) from exc
    if pygame.display.get_driver() in ("dummy", "offscreen"):
        raise DisplayUnavailableError(
            f"no window can open: pygame chose the {pygame.display.get_driver()!r} video driver; "
            "record frames instead (drop --window)"
        )
    if not pygame.font.get_init():
        pygame.font.init()


@contextmanager
def _runtime_dir() -> Iterator[None]:
    """While SDL starts its video: an empty private XDG_RUNTIME_DIR where it is unset or not
    an absolute path (Linux and the BSDs), removed afterwards.

    SDL tries Wayland among its drivers, and the Wayland client library prints
    "error: XDG_RUNTIME_DIR is invalid or not set in the environment." on stderr where that
    variable is missing (a container, ssh, a CI job), before any message of ours; with an empty
    folder it finds no Wayland socket there and says nothing. A session with a display sets the
    variable itself, and is left alone.
    """
    current = os.environ.get("XDG_RUNTIME_DIR", "")
    if sys.platform in ("win32", "darwin") or current.startswith("/"):
        yield
        return
    with tempfile.TemporaryDirectory(prefix="engine-runtime-") as folder:
        os.environ["XDG_RUNTIME_DIR"] = folder
        try:
            yield
        finally:
            if current:
                os.environ["XDG_RUNTIME_DIR"] = current
            else:
                del os.environ["XDG_RUNTIME_DIR"]
