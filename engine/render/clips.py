"""The clip writer: frames streamed as raw RGB into ffmpeg, to an MP4 or a GIF, whole or not at all.

The encoder is the ffmpeg binary that the optional ``imageio-ffmpeg`` wheel ships (the ``video``
extra: ``pip install -e ".[video]"``), so nothing is installed by hand. It is looked up only when
a clip is asked for: ``import engine.render`` never imports ``imageio_ffmpeg``.

Each frame's pixels are copied out of the surface (``pygame.image.tobytes``, under 1 ms at
640x360) in the caller's thread, so the surface is free to be drawn on again at once, and a
writer thread pipes them into ffmpeg's stdin while the next frame is drawn; ffmpeg encodes in
its own process. No PNG is made on the way.

- MP4: H.264 (libx264, preset ``superfast``, CRF 20), yuv420p, BT.709, ``+faststart`` (the index
  at the front, so a browser starts playing before the whole file has arrived), at the
  recording's fps. yuv420p needs even sides: an odd width or height loses its last column or
  row (the right or bottom edge), so nothing is stretched and no border colour is invented.
- GIF: loops forever; its 256 colours are a palette made from the clip's own frames
  (``palettegen`` and ``paletteuse`` in one filter graph), without dithering, which keeps the
  flat colours of a diagram flat and the file small. ffmpeg holds every frame until the
  palette is made, so a GIF costs about width x height x 4 bytes of memory a frame.

The clip is written under a temporary name in the target's folder and renamed into place
(``os.replace``, atomic on one file system) only once ffmpeg has finished it: an interrupted
or failed run leaves no file under the requested name, and removes the temporary one.
"""

from __future__ import annotations

import os
import queue
import subprocess
import sys
import tempfile
import threading
import warnings
import weakref
from pathlib import Path
from types import TracebackType
from typing import IO

import pygame

__all__ = [
    "CLIP_SUFFIXES",
    "GIF_MAX_FPS",
    "ClipExistsError",
    "ClipWriteError",
    "ClipWriter",
    "EncoderUnavailableError",
    "INSTALL_HINT",
    "check_clip_path",
    "check_gif_fps",
    "even_size",
    "ffmpeg_exe",
]

#: The suffix each kind of clip must have.
CLIP_SUFFIXES = {"mp4": ".mp4", "gif": ".gif"}

#: What to tell a user who asks for a clip without the encoder installed.
INSTALL_HINT = (
    'install the video extra: pip install -e ".[video]" (or pip install imageio-ffmpeg); '
    'see "Lesson clips" in the README'
)

#: x264's speed against size trade-off and its quality (lower CRF: better and larger).
X264_PRESET = "superfast"
X264_CRF = 20

#: Frames waiting for the writer thread, at most (~0.7 MB each at 640x360), and the bytes
#: they may take together, so that a huge canvas keeps memory flat too.
_QUEUE_FRAMES = 8
_QUEUE_BYTES = 64 * 1024 * 1024
#: The highest frame rate a GIF plays at: its frame times are whole hundredths of a second,
#: and browsers slow frames shorter than 2/100 s down to 1/10 s.
GIF_MAX_FPS = 50
#: Lines of ffmpeg's own messages quoted in an error.
_STDERR_LINES = 8


class EncoderUnavailableError(ImportError):
    """A clip was asked for but ``imageio-ffmpeg`` (the ``video`` extra) is not installed."""


class ClipExistsError(FileExistsError):
    """The clip's file (``path``) already exists and overwriting was not asked for."""

    def __init__(self, message: str, path: Path | None = None) -> None:
        super().__init__(message)
        self.path = path


class ClipWriteError(OSError):
    """The clip could not be written (encoder missing or failed, full disk, ...); none is left."""


def ffmpeg_exe() -> str:
    """The path of the ffmpeg binary that ``imageio-ffmpeg`` ships (or ``IMAGEIO_FFMPEG_EXE``).

    Raises :class:`EncoderUnavailableError` naming the ``video`` extra if it is not installed,
    and :class:`ClipWriteError` if it is installed but finds no binary.
    """
    try:
        import imageio_ffmpeg
    except ImportError as exc:
        raise EncoderUnavailableError(
            f"writing a video or GIF needs the imageio-ffmpeg package: {INSTALL_HINT}"
        ) from exc
    try:
        return str(imageio_ffmpeg.get_ffmpeg_exe())
    except RuntimeError as exc:
        raise ClipWriteError(f"no ffmpeg binary found: {exc}") from exc


def check_clip_path(path: object, kind: str, overwrite: bool = False) -> Path:
    """``path`` as a Path if it suits a ``kind`` ("mp4" or "gif") clip; otherwise an error.

    ValueError / TypeError naming the path if its suffix is wrong or it is not a file path,
    :class:`ClipExistsError` if the file exists and not ``overwrite``. A missing folder is fine:
    the writer creates it.
    """
    if kind not in CLIP_SUFFIXES:
        raise ValueError(f"kind must be one of {sorted(CLIP_SUFFIXES)}, got {kind!r}")
    suffix = CLIP_SUFFIXES[kind]
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(
            f"the {kind} path must be a str or pathlib.Path, got {type(path).__name__} {path!r}"
        )
    text = os.fspath(path)
    if isinstance(text, bytes) or "\x00" in text or text.strip() == "":
        raise ValueError(f"the {kind} path must be a file name ending in {suffix}, got {path!r}")
    target = Path(text)
    if target.suffix.lower() != suffix or target.name.lower() == suffix:
        raise ValueError(
            f"the {kind} path must end in {suffix}, such as clip{suffix}, got {text!r}"
        )
    if target.is_dir():
        raise ValueError(
            f"the {kind} path {text!r} is a folder; give a file name ending in {suffix}"
        )
    if target.exists() and not overwrite:
        raise ClipExistsError(
            f"{target} already exists; pass overwrite=True to replace it, or choose another name",
            target,
        )
    return target


def check_gif_fps(fps: int) -> int:
    """``fps`` if a GIF can play at it (at most 50 frames per second); ValueError otherwise."""
    if fps > GIF_MAX_FPS:
        raise ValueError(
            f"a GIF plays at most {GIF_MAX_FPS} fps in browsers (its frame times are whole "
            f"hundredths of a second), got fps={fps}; record it at {GIF_MAX_FPS} fps or less"
        )
    return fps


def even_size(size: tuple[int, int]) -> tuple[int, int]:
    """The largest even (width, height) in px within ``size``: what an MP4 of it shows.

    >>> even_size((641, 360))
    (640, 360)
    """
    return size[0] - size[0] % 2, size[1] - size[1] % 2


def _ffmpeg_args(kind: str, size: tuple[int, int], fps: int, temp: Path) -> list[str]:
    width, height = size
    source = [
        "-hide_banner",
        "-loglevel",
        "error",
        "-f",
        "rawvideo",
        "-pix_fmt",
        "rgb24",
        "-video_size",
        f"{width}x{height}",
        "-framerate",
        str(fps),
        "-i",
        "pipe:0",
        "-an",
    ]
    if kind == "mp4":
        out_w, out_h = even_size(size)
        crop = f"crop={out_w}:{out_h}:0:0," if (out_w, out_h) != size else ""
        return source + [
            "-vf",
            f"{crop}scale=out_color_matrix=bt709:out_range=tv,format=yuv420p,"
            "setparams=colorspace=bt709:color_primaries=bt709:color_trc=bt709:range=tv",
            "-c:v",
            "libx264",
            "-preset",
            X264_PRESET,
            "-crf",
            str(X264_CRF),
            "-pix_fmt",
            "yuv420p",
            "-r",
            str(fps),
            "-movflags",
            "+faststart",
            "-f",
            "mp4",
            "-y",
            str(temp),
        ]
    return source + [
        "-filter_complex",
        "[0:v]split[a][b];[a]palettegen=stats_mode=full[p];"
        "[b][p]paletteuse=dither=none:diff_mode=rectangle",
        "-loop",
        "0",
        "-f",
        "gif",
        "-y",
        str(temp),
    ]


def _describe(exc: BaseException) -> str:
    if isinstance(exc, OSError) and exc.strerror:
        return exc.strerror
    return f"{type(exc).__name__}: {exc}"


class ClipWriter:
    """Streams surfaces of one size into an MP4 or GIF file through ffmpeg.

    Use it as a context manager (or call :meth:`close`, or :meth:`abort` to give up)::

        with ClipWriter("out/stroll.mp4", size=(640, 360), fps=30) as clip:
            for ...:
                draw(surface)
                clip.write(surface)

    The kind of clip follows the suffix (``.mp4`` or ``.gif``); ``size`` is the surfaces'
    (width, height) in px and ``fps`` the frames per second the clip plays at. The target is
    checked at once: :class:`ClipExistsError` if it exists and not ``overwrite``, ValueError if
    its suffix is wrong. Its folder is created if missing. :class:`EncoderUnavailableError` if
    the ``video`` extra is not installed, :class:`ClipWriteError` if ffmpeg cannot start, fails
    or the disk is full; the error quotes ffmpeg's last lines and no file is left behind.
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        size: tuple[int, int],
        fps: int,
        overwrite: bool = False,
    ) -> None:
        named = isinstance(path, (str, os.PathLike))
        kind = "gif" if named and Path(os.fspath(path)).suffix.lower() == ".gif" else "mp4"
        self.path = check_clip_path(path, kind, overwrite)
        self.kind = kind
        try:
            width, height = size
        except (TypeError, ValueError):
            raise ValueError(f"size must be (width, height) in pixels, got {size!r}") from None
        for value, what in ((width, "width"), (height, "height"), (fps, "fps")):
            if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= 8192:
                raise ValueError(f"{what} must be a whole number from 1 to 8192, got {value!r}")
        if kind == "mp4" and (width < 2 or height < 2):
            raise ValueError(f"an MP4 needs a size of at least 2x2 px, got {width}x{height}")
        if kind == "gif":
            check_gif_fps(fps)
        self.size = (width, height)
        #: The size of the clip itself (px): even sides for an MP4, as drawn for a GIF.
        self.clip_size = even_size(self.size) if kind == "mp4" else self.size
        self.fps = fps
        #: Frames handed to :meth:`write`.
        self.count = 0
        #: Whether the clip is whole and under its name (after :meth:`close`).
        self.done = False
        exe = ffmpeg_exe()
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ClipWriteError(
                f"could not create the folder {self.path.parent} for {self.path.name}: "
                f"{_describe(exc)}"
            ) from exc
        # Beside the target (same file system, so the rename is atomic), under a name no one
        # takes for the clip; ffmpeg creates it with the usual permissions.
        self._temp = self.path.with_name(
            f".{self.path.name}.{os.getpid()}.{threading.get_ident()}.part"
        )
        self._stderr: IO[bytes] = tempfile.TemporaryFile()
        #: What the writer thread found wrong (its one slot: the thread holds no reference to
        #: the writer, so a writer dropped unclosed is collected: ``_abandoned``).
        self._failed: list[ClipWriteError] = []
        self._closed = False
        try:
            self._process = subprocess.Popen(
                [exe, *_ffmpeg_args(kind, self.size, fps, self._temp)],
                stdin=subprocess.PIPE,
                stdout=subprocess.DEVNULL,
                stderr=self._stderr,
                # Its own session: a Ctrl-C meant for us must not stop ffmpeg half-way; the
                # writer decides whether the clip is finished or thrown away.
                start_new_session=sys.platform != "win32",
            )
        except OSError as exc:
            self._stderr.close()
            self._discard()
            raise ClipWriteError(
                f"could not start the encoder {exe!r} for {self.path}: {_describe(exc)}; "
                f"reinstall it: {INSTALL_HINT}"
            ) from exc
        frames = max(1, min(_QUEUE_FRAMES, _QUEUE_BYTES // (3 * width * height)))
        # Frames in order, None to end; at most ``frames`` in flight, each taking a slot that
        # the writer thread gives back once it has passed the frame on. C queues only
        # (queue.SimpleQueue): a stop (KeyboardInterrupt, raised between any two bytecodes of
        # the main thread) cannot leave one half-done, as it can a queue.Queue's Python locks.
        self._queue: queue.SimpleQueue[bytes | None] = queue.SimpleQueue()
        self._slots: queue.SimpleQueue[None] = queue.SimpleQueue()
        for _ in range(frames):
            self._slots.put(None)
        self._thread = threading.Thread(
            target=_pipe,
            args=(self._queue, self._slots, self._process, self._stderr, self.path, self._failed),
            name="clip-writer",
            daemon=True,
        )
        self._thread.start()
        # A writer dropped without close() or abort() (no ``with``, an exception on the way)
        # is aborted when it is collected, or at the interpreter's exit: its encoder stopped,
        # its temporary file removed, and a ResourceWarning says so, as an unclosed file's.
        self._finalizer = weakref.finalize(
            self, _abandoned, self._process, self._queue, self._thread, self._stderr,
            self._temp, self.path,
        )  # fmt: skip

    def write(self, surface: pygame.Surface) -> None:
        """Queue ``surface`` (of the writer's size) as the next frame; it is copied at once."""
        if self._closed:
            raise ValueError("write() on a closed ClipWriter")
        if surface.get_size() != self.size:
            raise ValueError(
                f"every frame of {self.path} must be {self.size[0]}x{self.size[1]} px, "
                f"got {surface.get_width()}x{surface.get_height()}"
            )
        self._raise_if_failed()
        data = pygame.image.tobytes(surface, "RGB")
        self._slots.get()  # waits while the queue holds its most frames
        self._queue.put(data)
        self.count += 1

    @property
    def _error(self) -> ClipWriteError | None:
        return self._failed[0] if self._failed else None

    def _encoder_error(self, what: str) -> ClipWriteError:
        return _encoder_error(self._process, self._stderr, self.path, what)

    def _raise_if_failed(self) -> None:
        if self._error is not None:
            error = self._error
            self.abort()
            raise error

    def close(self) -> Path:
        """Finish the clip and rename it into place; return its path. ClipWriteError if not."""
        if self._closed:
            self._raise_if_failed()
            return self.path
        self._queue.put(None)
        self._thread.join()
        if self._error is not None:
            self._raise_if_failed()
        code = self._process.wait()
        if code != 0 or self.count == 0:
            error = (
                self._encoder_error("failed")
                if code != 0
                else ClipWriteError(f"could not write {self.path}: no frames were given")
            )
            self._failed[:] = [error]
            self._raise_if_failed()
        self._closed = True
        self._finalizer.detach()
        self._stderr.close()
        try:
            os.replace(self._temp, self.path)
        except OSError as exc:
            self._discard()
            raise ClipWriteError(f"could not write {self.path}: {_describe(exc)}") from exc
        self.done = True
        return self.path

    def abort(self) -> None:
        """Stop the encoder and remove the unfinished clip; the requested name is left untouched."""
        if self._closed:
            return
        self._closed = True
        self._finalizer.detach()
        _stop(self._process, self._queue, self._thread, self._stderr, self._temp)

    def _discard(self) -> None:
        _remove(self._temp)

    def __enter__(self) -> ClipWriter:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        value: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        if kind is None:
            self.close()
        else:
            self.abort()


def _pipe(
    frames: queue.SimpleQueue[bytes | None],
    slots: queue.SimpleQueue[None],
    process: subprocess.Popen[bytes],
    stderr: IO[bytes],
    path: Path,
    failed: list[ClipWriteError],
) -> None:
    """The writer thread: frames into ffmpeg's stdin. Pipe writes release the GIL, so this
    runs beside the drawing of the next frame. After a failure (put in ``failed``) it keeps
    taking frames (dropping them) so that write() never waits on a full queue for ever. It
    holds no reference to its ClipWriter (which is then collected if dropped unclosed)."""
    stdin = process.stdin
    assert stdin is not None
    broken = False
    while True:
        data = frames.get()
        if data is None:
            break
        try:
            if not broken:
                stdin.write(data)
        except (OSError, ValueError):  # ffmpeg has gone: BrokenPipeError and the like
            broken = True
            failed[:] = [_encoder_error(process, stderr, path, "stopped taking frames")]
        finally:
            slots.put(None)
    try:
        stdin.close()
    except OSError:
        pass  # the encoder's own exit status says what went wrong


def _encoder_error(
    process: subprocess.Popen[bytes], stderr: IO[bytes], path: Path, what: str
) -> ClipWriteError:
    """The error to raise for ``path``: ffmpeg's exit and its last lines, which say why (No
    space left on device, an unknown encoder, ...)."""
    try:
        code = process.wait(timeout=30)
    except subprocess.TimeoutExpired:
        process.kill()
        code = process.wait()
    stderr.seek(0)
    lines = stderr.read().decode("utf-8", "replace").strip().splitlines()
    said = "\n  ".join(lines[-_STDERR_LINES:]) or "(no message)"
    how = f"exit status {code}" if code >= 0 else f"killed by signal {-code}"
    return ClipWriteError(
        f"could not write {path}: the encoder (ffmpeg) {what}, {how}; it said:\n  {said}"
    )


def _stop(
    process: subprocess.Popen[bytes],
    frames: queue.SimpleQueue[bytes | None],
    thread: threading.Thread,
    stderr: IO[bytes],
    temp: Path,
) -> None:
    """Abort a clip: its encoder stopped, its writer thread ended, its temporary file removed."""
    if process.poll() is None:
        process.kill()
    # End the writer thread: its pipe is broken now, so it drops what is left, then ends.
    frames.put(None)
    thread.join()
    process.wait()
    stderr.close()
    _remove(temp)


def _remove(temp: Path) -> None:
    try:
        temp.unlink(missing_ok=True)
    except OSError:
        pass  # the error being raised is the one to act on


def _abandoned(
    process: subprocess.Popen[bytes],
    frames: queue.SimpleQueue[bytes | None],
    thread: threading.Thread,
    stderr: IO[bytes],
    temp: Path,
    path: Path,
) -> None:
    """A ClipWriter collected (or left at the interpreter's exit) neither closed nor aborted:
    aborted (``_stop``), and said with a ResourceWarning, as Python says of a file left open."""
    _stop(process, frames, thread, stderr, temp)
    warnings.warn(
        f"a ClipWriter for {path} was dropped without close(): the clip is not written; "
        "use it in a with block, or call close() to finish it",
        ResourceWarning,
        stacklevel=1,
    )
