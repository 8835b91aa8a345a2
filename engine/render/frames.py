"""The frame writer: numbered PNG files, written whole or not at all, encoded off the main thread.

Saving a 640x360 frame with ``pygame.image.save`` costs ~6 ms, 97% of it PNG encoding, while
copying the pixels out with ``pygame.image.tobytes`` costs ~0.4 ms. So the writer copies the
pixels in the caller's thread (the surface is free to be drawn on again at once) and hands the
bytes to a small pool of worker threads that filter, compress and write them. ``zlib`` and
file writes release the GIL, so encoding runs beside the drawing of the next frame. A bounded
number of frames in flight keeps memory flat however long the recording.

A stop (Ctrl-C, or SIGTERM under ``python -m demos``) raises KeyboardInterrupt in the main
thread between any two of its bytecodes, so the main thread's side of the hand-off takes no
lock written in Python (a ``threading.Semaphore`` or ``ThreadPoolExecutor.submit``, which such
an exception can leave half-done): it only gets from and puts on C queues
(``queue.SimpleQueue``), each call whole or not made.

Every file is first written under a temporary name in the same folder and then renamed with
``os.replace``, which is atomic on one file system: an interrupted run leaves only whole frames.
"""

from __future__ import annotations

import os
import re
import struct
import sys
import threading
import weakref
import zlib
from pathlib import Path
from queue import Empty, SimpleQueue
from types import TracebackType

import numpy as np
import pygame

__all__ = [
    "FRAME_PATTERN",
    "FrameWriteError",
    "FrameWriter",
    "FramesExistError",
    "encode_png",
    "frame_name",
    "save_png",
]

#: Names the writer owns in its folder: ``frame_00000.png``, ``frame_00001.png``, ...
FRAME_PATTERN = re.compile(r"frame_\d{5,}\.png")
_TEMP_PATTERN = re.compile(r"\.frame_\d{5,}\.png\.\d+\.tmp")

_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


class FrameWriteError(OSError):
    """A frame could not be written (full disk, no permission, ...); earlier frames stay whole."""


class FramesExistError(FileExistsError):
    """The output folder already holds frames (or a file to be written exists) and
    overwriting was not asked for. ``path`` is the folder or file, ``count`` the frames found
    in the folder (None for a single file)."""

    def __init__(self, message: str, path: Path | None = None, count: int | None = None) -> None:
        super().__init__(message)
        self.path, self.count = path, count


def frame_name(index: int) -> str:
    """File name of frame ``index`` (0-based): ``frame_00042.png``."""
    if index < 0:
        raise ValueError(f"index must be >= 0, got {index}")
    return f"frame_{index:05d}.png"


def _chunk(kind: bytes, data: bytes) -> bytes:
    # A PNG chunk: 4-byte big-endian length, 4-byte type, data, CRC-32 of type + data.
    crc = zlib.crc32(data, zlib.crc32(kind))
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)


def encode_png(rgb: bytes, width: int, height: int, level: int = 2) -> bytes:
    """Encode ``width*height`` packed 8-bit RGB pixels (rows top to bottom) as a PNG file's bytes.

    Each row is stored with PNG filter 2 ("Up": every byte minus the byte above it, modulo 256),
    which turns the large flat areas of a diagram into runs of zeros that zlib packs tightly;
    ``level`` is zlib's effort, 1 (fastest) to 9 (smallest). The pixels decode exactly.
    """
    if width <= 0 or height <= 0:
        raise ValueError(f"size must be positive, got {width}x{height}")
    if len(rgb) != width * height * 3:
        raise ValueError(
            f"rgb must hold {width * height * 3} bytes for {width}x{height}, got {len(rgb)}"
        )
    return _encode_pixels(np.frombuffer(rgb, dtype=np.uint8).reshape(height, width, 3), level)


def _encode_pixels(pixels: np.ndarray, level: int) -> bytes:
    # pixels: (height, width, 3) uint8 RGB, any strides (e.g. a view into a BGRX surface copy).
    height, width, _ = pixels.shape
    filtered = np.empty((height, width * 3 + 1), dtype=np.uint8)
    filtered[:, 0] = 2  # the filter-type byte that starts each row
    rows = filtered[:, 1:].reshape(height, width, 3)  # a view: the pixels after the filter byte
    rows[0] = pixels[0]  # the row above the first row counts as zeros
    np.subtract(pixels[1:], pixels[:-1], out=rows[1:])  # uint8 arithmetic wraps modulo 256
    return _png(filtered, width, height, level)


def _png(filtered: np.ndarray, width: int, height: int, level: int) -> bytes:
    # filtered: each row's filter byte then its filtered RGB bytes.
    # IHDR: width, height, bit depth 8, colour type 2 (RGB), compression 0, filter 0, no interlace.
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"".join(
        (
            _PNG_SIGNATURE,
            _chunk(b"IHDR", header),
            _chunk(b"IDAT", zlib.compress(filtered.data, level)),
            _chunk(b"IEND", b""),
        )
    )


class _Grab:
    """A copy of a surface's pixels, taken fast, turned into (height, width, 3) RGB later."""

    __slots__ = ("data", "width", "height", "pitch", "channels")

    def __init__(self, surface: pygame.Surface) -> None:
        self.width, self.height = surface.get_size()
        shifts = surface.get_shifts()[:3]
        masks = surface.get_masks()[:3]
        if (
            surface.get_bytesize() == 4
            and sys.byteorder == "little"
            and all(mask == 0xFF << shift for mask, shift in zip(masks, shifts, strict=True))
            and all(shift % 8 == 0 for shift in shifts)
        ):
            # The common 32-bit case: copy the raw buffer (a memcpy, ~0.05 ms at 640x360, where
            # converting to RGB costs ~0.3 ms) and pick the channels out on a worker thread.
            self.data = surface.get_buffer().raw
            self.pitch = surface.get_pitch()
            self.channels: tuple[int, ...] | None = tuple(shift // 8 for shift in shifts)
        else:
            self.data = pygame.image.tobytes(surface, "RGB")
            self.pitch = self.width * 3
            self.channels = None

    def rgb(self) -> np.ndarray:
        """The pixels as a (height, width, 3) RGB uint8 array."""
        flat = np.frombuffer(self.data, dtype=np.uint8)
        if self.channels is None:
            return flat.reshape(self.height, self.width, 3)
        pixels = self._words(flat).view(np.uint8).reshape(self.height, self.width, 4)
        return pixels[:, :, list(self.channels)]

    def _words(self, flat: np.ndarray) -> np.ndarray:
        # One 32-bit word per pixel, (height, width); a view unless rows are padded.
        rows = flat.reshape(self.height, self.pitch)[:, : self.width * 4]
        return np.ascontiguousarray(rows).view(np.uint32)

    def encode(self, level: int, scratch: dict[str, np.ndarray]) -> bytes:
        """This frame as PNG bytes; ``scratch`` keeps the work arrays from frame to frame."""
        if self.channels is None:
            return _encode_pixels(self.rgb(), level)
        h, w = self.height, self.width
        if scratch.get("diff", np.empty(0)).shape != (h, w * 4):
            # Reused from frame to frame: fresh ~1 MB arrays would cost page faults each time.
            scratch["diff"] = np.empty((h, w * 4), dtype=np.uint8)
            scratch["filtered"] = np.empty((h, w * 3 + 1), dtype=np.uint8)
        diff, filtered = scratch["diff"], scratch["filtered"]
        # The "Up" filter works byte by byte, so it can run on the whole 4-byte pixels, in
        # contiguous memory (fast), before the three colour bytes are picked out of each word.
        src = self._words(np.frombuffer(self.data, dtype=np.uint8)).view(np.uint8)
        diff[0] = src[0]
        np.subtract(src[1:], src[:-1], out=diff[1:])
        pixels = diff.reshape(h, w, 4)
        filtered[:, 0] = 2
        rows = filtered[:, 1:].reshape(h, w, 3)
        for i, byte in enumerate(self.channels):  # little-endian: byte k is bits 8k..8k+7
            rows[:, :, i] = pixels[:, :, byte]
        return _png(filtered, w, h, level)


def _write_atomically(path: Path, data: bytes) -> None:
    # Write beside the target (same file system, so os.replace is an atomic rename) under a
    # name no reader mistakes for a frame; remove the partial file if anything fails.
    temp = path.with_name(f".{path.name}.{threading.get_ident()}.tmp")
    try:
        with open(temp, "wb") as handle:
            handle.write(data)
        os.replace(temp, path)
    except BaseException:
        try:
            temp.unlink()
        except OSError:
            pass
        raise


def _folder(folder: object) -> Path:
    """``folder`` as a Path; TypeError / ValueError naming it for what no file system takes."""
    if not isinstance(folder, (str, os.PathLike)):
        raise TypeError(
            f"folder must be a path (str or pathlib.Path), got {type(folder).__name__} {folder!r}"
        )
    text = os.fspath(folder)
    if isinstance(text, bytes) or text == "" or "\x00" in text:
        # "" would mean the current folder, a surprise place for hundreds of frames.
        raise ValueError(f"folder must be a non-empty path without NUL characters, got {folder!r}")
    return Path(text)


def _describe(exc: BaseException) -> str:
    if isinstance(exc, OSError) and exc.strerror:
        return exc.strerror
    return f"{type(exc).__name__}: {exc}"


def save_png(
    surface: pygame.Surface, path: str | os.PathLike[str], overwrite: bool = False
) -> Path:
    """Save one surface as a PNG file, atomically; FrameWriteError if it cannot be written."""
    target = Path(path)
    if target.exists() and not overwrite:
        raise FramesExistError(
            f"{target} already exists; pass overwrite=True to replace it", target
        )
    width, height = surface.get_size()
    data = encode_png(pygame.image.tobytes(surface, "RGB"), width, height)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        _write_atomically(target, data)
    except OSError as exc:
        raise FrameWriteError(f"could not write {target}: {_describe(exc)}") from exc
    return target


class _Encoding:
    """A FrameWriter's worker threads and what they share: frames in, whole files out.

    The main thread only puts on and gets from C queues (the module doc says why); the rest
    is the workers'. The threads hold this, not the writer, so a writer dropped unclosed can
    still be collected (its finalizer then calls ``finish``)."""

    def __init__(self, level: int, workers: int) -> None:
        self.level = level
        self.error: FrameWriteError | None = None
        self.failed_at: int | None = None  # the lowest frame index that could not be written
        self.done = 0  # frames renamed into place
        self._lock = threading.Lock()  # the workers' own (the main thread never takes it)
        self._scratch = threading.local()  # each worker's reusable arrays
        # Jobs (index, path, pixels) in frame order; None tells a worker to stop.
        self._jobs: SimpleQueue[tuple[int, Path, _Grab] | None] = SimpleQueue()
        # At most two frames per worker in flight: ~0.7 MB each at 640x360, so memory stays
        # flat. A frame queued takes a slot, a worker gives it back when the frame is done.
        self._slots: SimpleQueue[None] = SimpleQueue()
        for _ in range(2 * workers):
            self._slots.put(None)
        self._threads = [
            threading.Thread(target=self._work, name=f"frame-writer-{i}", daemon=True)
            for i in range(workers)
        ]
        for thread in self._threads:
            thread.start()

    def queue(self, index: int, path: Path, grab: _Grab) -> None:
        """Queue frame ``index`` (waits while 2 x workers frames are in flight)."""
        self._slots.get()
        self._jobs.put((index, path, grab))

    def finish(self, cancel: bool) -> None:
        """Wait for the workers to end: after every frame queued, or (``cancel``) after the
        frames they have taken, the others dropped (the last ones, so no gap opens)."""
        if cancel:
            try:
                while True:
                    self._jobs.get_nowait()
            except Empty:
                pass
        for _ in self._threads:
            self._jobs.put(None)
        for thread in self._threads:
            thread.join()

    def _work(self) -> None:
        # A worker: frames in the order queued, until told to stop. The jobs are taken in
        # frame order and every one taken is finished, so the frames done run without a gap.
        while (job := self._jobs.get()) is not None:
            try:
                self._encode_and_write(*job)
            finally:
                self._slots.put(None)

    def _encode_and_write(self, index: int, path: Path, grab: _Grab) -> None:
        failed_at = self.failed_at
        if failed_at is not None and index > failed_at:
            return  # the run is already failing: a frame after the gap would be removed anyway
        try:
            scratch = self._scratch.__dict__.setdefault("arrays", {})
            _write_atomically(path, grab.encode(self.level, scratch))
            with self._lock:
                self.done += 1
        except Exception as exc:
            with self._lock:
                # Workers finish out of order: the error to report is the first frame's.
                if self.failed_at is None or index < self.failed_at:
                    error = FrameWriteError(f"could not write frame {path}: {_describe(exc)}")
                    error.__cause__ = exc
                    self.error = error
                    self.failed_at = index


class FrameWriter:
    """Writes surfaces as ``frame_00000.png``, ``frame_00001.png``, ... into a folder.

    Use it as a context manager, or call :meth:`close` to wait for the last frames::

        with FrameWriter("out/stroll") as frames:
            for ...:
                draw(surface)
                frames.write(surface)

    ``folder`` is created if missing. A folder that already holds frames is refused with
    :class:`FramesExistError` unless ``overwrite`` is true, in which case its old frames are
    deleted first so no stale frame survives past the new last one. ``workers`` is the number of
    encoding threads (default: the CPU count, at most 4); ``level`` is zlib's effort (1 to 9).
    A failed write raises :class:`FrameWriteError` from the next :meth:`write` or from
    :meth:`close`. The folder then holds whole frames without gaps, frame_00000.png up to the
    one before the frame that failed (frames other workers finished after it are removed, so
    a player or ffmpeg, which stop at the first missing number, see every frame kept);
    :attr:`written` says how many.
    """

    def __init__(
        self,
        folder: str | os.PathLike[str],
        overwrite: bool = False,
        workers: int | None = None,
        level: int = 2,
    ) -> None:
        if workers is None:
            workers = max(1, min(4, os.cpu_count() or 1))
        if not isinstance(workers, int) or isinstance(workers, bool) or not 1 <= workers <= 64:
            raise ValueError(f"workers must be a whole number from 1 to 64, got {workers!r}")
        if not isinstance(level, int) or isinstance(level, bool) or not 0 <= level <= 9:
            raise ValueError(
                f"level must be a zlib level, a whole number from 0 to 9, got {level!r}"
            )
        self.folder = _folder(folder)
        self.level = level
        self.count = 0
        #: Whole frames on disk, numbered without gaps from frame_00000.png, once the writer
        #: has stopped (after :meth:`close`, :meth:`abort` or a :class:`FrameWriteError`).
        self.written = 0
        self._prepare(overwrite)
        self._closed = False
        self._encoding = _Encoding(level, workers)
        # A writer dropped or left open at exit still writes what it was given, as a thread
        # pool's would: then its workers take the frames queued and stop (weakref.finalize
        # runs at exit too, while the daemon workers still run).
        self._finalizer = weakref.finalize(self, self._encoding.finish, False)

    def _prepare(self, overwrite: bool) -> None:
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
            names = os.listdir(self.folder)
        except OSError as exc:
            raise FrameWriteError(
                f"could not create the folder {self.folder}: {_describe(exc)}"
            ) from exc
        frames = [name for name in names if FRAME_PATTERN.fullmatch(name)]
        if frames and not overwrite:
            raise FramesExistError(
                f"{self.folder} already holds {len(frames)} frame(s); "
                "pass overwrite=True to replace them, or choose another folder",
                self.folder,
                len(frames),
            )
        stale = frames + [name for name in names if _TEMP_PATTERN.fullmatch(name)]
        try:
            for name in stale:
                (self.folder / name).unlink()
        except OSError as exc:
            raise FrameWriteError(
                f"could not remove old frames in {self.folder}: {_describe(exc)}"
            ) from exc

    def write(self, surface: pygame.Surface) -> Path:
        """Queue ``surface`` as the next frame and return its path (written in the background)."""
        if self._closed:
            raise ValueError("write() on a closed FrameWriter")
        self._raise_if_failed()
        grab = _Grab(surface)  # a copy: the caller may draw on the surface again now
        index = self.count
        path = self.folder / frame_name(index)
        # Counted first: a stop before the frame is queued leaves the last frame asked for
        # unqueued, and every frame queued below ``count``.
        self.count += 1
        self._encoding.queue(index, path, grab)
        return path

    def _raise_if_failed(self) -> None:
        if self._encoding.error is not None:
            # The error to raise is read after the workers end: one still encoding an earlier
            # frame may fail too, and the first frame's error (with how many frames were kept)
            # is the one that says where the run stopped.
            self._stop(cancel=True)
            error = self._encoding.error
            assert error is not None
            raise error

    def _stop(self, cancel: bool) -> None:
        # Wait for the workers, then leave a gapless run of frames: the workers take frames in
        # order, so without a failure the finished ones are already 0..n-1; after one, frames
        # other workers finished past the failed index are removed.
        if self._closed:
            return
        self._closed = True
        self._finalizer.detach()
        encoding = self._encoding
        encoding.finish(cancel)
        if encoding.failed_at is None:
            self.written = encoding.done
            return
        self.written = encoding.failed_at
        for index in range(encoding.failed_at + 1, self.count):
            try:
                (self.folder / frame_name(index)).unlink(missing_ok=True)
            except OSError:
                pass  # the error already being raised is the one to act on
        error = encoding.error
        assert error is not None
        error.args = (f"{error.args[0]}; {self.written} whole frame(s) kept in {self.folder}",)

    def close(self) -> int:
        """Wait until every queued frame is on disk; return the number of frames written."""
        self._stop(cancel=False)
        self._raise_if_failed()
        return self.count

    def abort(self) -> None:
        """Stop: frames being encoded finish whole, frames still queued are dropped."""
        self._stop(cancel=True)

    def __enter__(self) -> FrameWriter:
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
