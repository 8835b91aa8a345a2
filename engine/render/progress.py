"""A progress line on standard error for long renders, silent when stderr is not a terminal."""

from __future__ import annotations

import sys
import time
from typing import TextIO

__all__ = ["Progress"]


class Progress:
    """Call it with (done, total) after each frame; it shows ``label 120/331 frames 36%``.

    ``unit`` names what is counted ("frames"; a measurement counts "runs").

    Nothing is printed until ``delay`` seconds (default 2 s) have passed, so short renders stay
    quiet, and nothing at all when ``stream`` is not a terminal (pipes, logs, tests). The line is
    redrawn in place at most ``rate`` times a second and ended with a newline by :meth:`done`.
    """

    def __init__(
        self,
        label: str = "",
        stream: TextIO | None = None,
        delay: float = 2.0,
        rate: float = 10.0,
        force: bool = False,
        unit: str = "frames",
    ) -> None:
        self.stream = sys.stderr if stream is None else stream
        self.label = label
        self.unit = unit
        self.delay = delay
        self.interval = 1.0 / rate
        isatty = getattr(self.stream, "isatty", None)
        self.enabled = force or bool(isatty and isatty())
        self._start = time.monotonic()
        self._last = -1.0
        self._shown = False

    def __call__(self, done: int, total: int) -> None:
        """Report that ``done`` of ``total`` frames are finished."""
        if not self.enabled:
            return
        now = time.monotonic()
        if now - self._start < self.delay or (now - self._last < self.interval and done < total):
            return
        self._last = now
        percent = 100 * done // total if total else 100
        elapsed = now - self._start
        rate = done / elapsed if elapsed > 0 else 0.0
        prefix = f"{self.label} " if self.label else ""
        unit = self.unit
        self.stream.write(f"\r{prefix}{done}/{total} {unit} {percent:3d}%  {rate:5.0f} {unit}/s ")
        self.stream.flush()
        self._shown = True

    def done(self) -> None:
        """End the line (if one was shown) so the next output starts on a fresh line."""
        if self._shown:
            self.stream.write("\n")
            self.stream.flush()
            self._shown = False
