"""The frame writer: numbered PNGs, exact pixels, no overwriting, atomic writes, clear errors."""

import errno
import io
import os
import threading
from pathlib import Path

import numpy as np
import pygame
import pytest

from engine.render import frames as frames_module
from engine.render import init_headless
from engine.render.frames import (
    FramesExistError,
    FrameWriteError,
    FrameWriter,
    encode_png,
    frame_name,
    save_png,
)


@pytest.fixture(autouse=True)
def _pygame():
    init_headless()


def picture(seed: int, size=(64, 40)) -> pygame.Surface:
    """A surface with random pixels: every byte value and every filter case shows up."""
    rng = np.random.default_rng(seed)
    surface = pygame.Surface(size)
    pixels = rng.integers(0, 256, size=(size[0], size[1], 3), dtype=np.uint8)
    pygame.surfarray.blit_array(surface, pixels)
    return surface


def rgb(surface: pygame.Surface) -> np.ndarray:
    return pygame.surfarray.array3d(surface)


def test_encoded_png_decodes_to_the_same_pixels():
    surface = picture(1, (37, 23))  # odd sizes: no row alignment luck
    data = encode_png(pygame.image.tobytes(surface, "RGB"), 37, 23)
    assert data.startswith(b"\x89PNG\r\n\x1a\n")
    loaded = pygame.image.load(io.BytesIO(data), "frame.png")
    assert loaded.get_size() == (37, 23)
    np.testing.assert_array_equal(rgb(loaded), rgb(surface))


def test_encode_png_rejects_a_wrong_byte_count():
    with pytest.raises(ValueError, match="rgb must hold 12 bytes for 2x2"):
        encode_png(b"\x00" * 11, 2, 2)


def test_writes_numbered_frames_with_exact_pixels(tmp_path):
    pictures = [picture(seed) for seed in range(7)]
    with FrameWriter(tmp_path / "new" / "folder", workers=3) as writer:
        for surface in pictures:
            writer.write(surface)
    names = sorted(p.name for p in (tmp_path / "new" / "folder").iterdir())
    assert names == [frame_name(i) for i in range(7)] == [f"frame_{i:05d}.png" for i in range(7)]
    for i, surface in enumerate(pictures):
        loaded = pygame.image.load(str(tmp_path / "new" / "folder" / frame_name(i)))
        np.testing.assert_array_equal(rgb(loaded), rgb(surface))


def test_the_surface_can_be_drawn_on_again_at_once(tmp_path):
    surface = picture(3)
    before = rgb(surface)
    with FrameWriter(tmp_path) as writer:
        writer.write(surface)
        surface.fill((255, 0, 0))  # the writer copied the pixels already
    np.testing.assert_array_equal(rgb(pygame.image.load(str(tmp_path / frame_name(0)))), before)


def test_refuses_a_folder_that_holds_frames(tmp_path):
    with FrameWriter(tmp_path) as writer:
        writer.write(picture(0))
    with pytest.raises(FramesExistError, match="already holds 1 frame.*overwrite"):
        FrameWriter(tmp_path)


def test_other_files_do_not_count_as_frames(tmp_path):
    (tmp_path / "notes.txt").write_text("lesson plan")
    (tmp_path / "strobe.png").write_bytes(b"")
    with FrameWriter(tmp_path) as writer:
        writer.write(picture(0))
    assert (tmp_path / "notes.txt").exists() and (tmp_path / "strobe.png").exists()


def test_overwrite_replaces_old_frames_and_leaves_no_stale_ones(tmp_path):
    with FrameWriter(tmp_path) as writer:
        for seed in range(5):
            writer.write(picture(seed))
    with FrameWriter(tmp_path, overwrite=True) as writer:
        for seed in range(10, 12):
            writer.write(picture(seed))
    assert sorted(p.name for p in tmp_path.iterdir()) == [frame_name(0), frame_name(1)]
    loaded = pygame.image.load(str(tmp_path / frame_name(1)))
    np.testing.assert_array_equal(rgb(loaded), rgb(picture(11)))


def failing_open(fail_from: int, exc: OSError):
    """An open() for the frames module that fails part-way through writing frame >= fail_from."""
    real_open = open

    def fake_open(path, mode="r", *args, **kwargs):
        handle = real_open(path, mode, *args, **kwargs)
        index = int(Path(path).name.split("_")[1].split(".")[0])
        if index < fail_from:
            return handle

        class Failing:
            def __enter__(self):
                return self

            def __exit__(self, *exc_info):
                handle.close()

            def write(self, data):
                handle.write(data[: len(data) // 2])  # half the file reaches the disk
                raise exc

        return Failing()

    return fake_open


def test_a_full_disk_stops_the_run_with_a_clear_error_and_keeps_whole_frames(tmp_path, monkeypatch):
    disk_full = OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(frames_module, "open", failing_open(3, disk_full), raising=False)
    with pytest.raises(FrameWriteError) as info:
        with FrameWriter(tmp_path, workers=1) as writer:
            for seed in range(8):
                writer.write(picture(seed))
    message = str(info.value)
    assert "frame_00003.png" in message and os.strerror(errno.ENOSPC) in message
    names = sorted(p.name for p in tmp_path.iterdir())
    # Only whole frames are left: the three before the failure, no partial or temporary file.
    assert names == [frame_name(i) for i in range(3)]
    for i in range(3):
        loaded = pygame.image.load(str(tmp_path / frame_name(i)))
        np.testing.assert_array_equal(rgb(loaded), rgb(picture(i)))


def test_no_permission_is_a_frame_write_error(tmp_path, monkeypatch):
    denied = PermissionError(errno.EACCES, os.strerror(errno.EACCES))
    monkeypatch.setattr(frames_module, "open", failing_open(0, denied), raising=False)
    writer = FrameWriter(tmp_path, workers=1)
    writer.write(picture(0))
    with pytest.raises(FrameWriteError, match="Permission denied"):
        writer.close()
    assert list(tmp_path.iterdir()) == []


def test_a_failed_rename_leaves_no_partial_frame(tmp_path, monkeypatch):
    real_replace = os.replace

    def replace(src, dst):
        if Path(dst).name == frame_name(1):
            raise OSError(errno.EIO, os.strerror(errno.EIO))
        real_replace(src, dst)

    monkeypatch.setattr(frames_module.os, "replace", replace)
    with pytest.raises(FrameWriteError, match="frame_00001.png"):
        with FrameWriter(tmp_path, workers=1) as writer:
            for seed in range(2):
                writer.write(picture(seed))
    assert sorted(p.name for p in tmp_path.iterdir()) == [frame_name(0)]


def test_a_failure_while_later_frames_finish_leaves_no_gap(tmp_path, monkeypatch):
    # Four workers: frame 3 fails only after frames 4 and 5 are already on disk, the order a
    # real full disk can produce. A gap would make ffmpeg stop at frame 2 and hide 4 and 5.
    real_replace = os.replace
    later_done = threading.Event()
    # Every rename waits until all six frames are queued: the pool starts a new thread only when
    # none is idle, so held workers make it start all four, whatever the machine's timing.
    all_queued = threading.Event()

    def replace(src, dst):
        assert all_queued.wait(timeout=30), "the frames were never all queued"
        name = Path(dst).name
        if name == frame_name(3):
            assert later_done.wait(timeout=30), "frames 4 and 5 were never written"
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        real_replace(src, dst)
        if (tmp_path / frame_name(4)).exists() and (tmp_path / frame_name(5)).exists():
            later_done.set()

    monkeypatch.setattr(frames_module.os, "replace", replace)
    writer = FrameWriter(tmp_path, workers=4)
    with pytest.raises(FrameWriteError) as info:
        with writer:
            for seed in range(6):
                writer.write(picture(seed))
            all_queued.set()
    assert later_done.is_set()  # the out-of-order case really happened
    assert "frame_00003.png" in str(info.value) and "3 whole frame(s) kept" in str(info.value)
    assert writer.written == 3
    assert sorted(p.name for p in tmp_path.iterdir()) == [frame_name(i) for i in range(3)]
    for i in range(3):
        np.testing.assert_array_equal(
            rgb(pygame.image.load(str(tmp_path / frame_name(i)))), rgb(picture(i))
        )


def test_written_counts_the_frames_on_disk(tmp_path):
    with FrameWriter(tmp_path, workers=3) as writer:
        for seed in range(7):
            writer.write(picture(seed))
    assert writer.written == 7 == len(list(tmp_path.iterdir()))


def test_save_png_writes_one_still_and_refuses_to_overwrite(tmp_path):
    path = save_png(picture(5), tmp_path / "stills" / "strobe.png")
    np.testing.assert_array_equal(rgb(pygame.image.load(str(path))), rgb(picture(5)))
    with pytest.raises(FramesExistError, match="already exists"):
        save_png(picture(6), path)
    save_png(picture(6), path, overwrite=True)
    np.testing.assert_array_equal(rgb(pygame.image.load(str(path))), rgb(picture(6)))


def _writer_threads() -> list[threading.Thread]:
    return [t for t in threading.enumerate() if t.name.startswith("frame-writer")]


def test_a_writer_dropped_unclosed_writes_its_frames_and_ends_its_threads(tmp_path):
    import gc

    before = _writer_threads()
    writer = FrameWriter(tmp_path, workers=3)
    pictures = [picture(seed) for seed in range(5)]
    for surface in pictures:
        writer.write(surface)
    assert len(_writer_threads()) == len(before) + 3
    del writer
    gc.collect()
    # Its finalizer let the workers take every frame queued, then stop.
    assert _writer_threads() == before
    names = sorted(os.listdir(tmp_path))
    assert names == [frame_name(i) for i in range(5)]
    for name, surface in zip(names, pictures, strict=True):
        assert np.array_equal(rgb(pygame.image.load(str(tmp_path / name))), rgb(surface))


def test_a_writer_left_open_at_exit_writes_its_frames(tmp_path):
    import subprocess
    import sys

    code = f"""
import os
os.environ["SDL_VIDEODRIVER"] = "dummy"
import pygame
from engine.render import init_headless
from engine.render.frames import FrameWriter
init_headless()
writer = FrameWriter({str(tmp_path)!r}, workers=2)
surface = pygame.Surface((320, 180))
for i in range(12):
    surface.fill((20 * i, 0, 0))
    writer.write(surface)
"""  # no close: the program ends with frames still queued
    root = Path(__file__).resolve().parent.parent
    subprocess.run([sys.executable, "-c", code], cwd=root, check=True, capture_output=True)
    names = sorted(os.listdir(tmp_path))
    assert names == [frame_name(i) for i in range(12)]
    last = pygame.image.load(str(tmp_path / names[-1]))
    assert last.get_at((5, 5))[:3] == (220, 0, 0)
