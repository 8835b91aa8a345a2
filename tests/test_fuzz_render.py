"""Fuzzing the renderer's Camera and FrameWriter, including odd output paths.

Examples per test: Camera 500, Camera.fit 200, FrameWriter 200. This file: 900.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np
import pygame
import pytest
from fuzzing import anything, attempt, fuzz, junk, moderate, numbers, pairs
from hypothesis import example, given
from hypothesis import strategies as st

from engine.render import Camera, FramesExistError, FrameWriteError, FrameWriter, init_headless


@fuzz(500)
@given(
    scale=st.one_of(st.floats(1e-3, 1e3), numbers, junk),
    origin=st.one_of(st.tuples(moderate, moderate), pairs, junk),
    point=st.one_of(st.tuples(moderate, moderate), moderate, anything),
)
@example(scale=0.001, origin=(17179869184.0, 0.0), point=0.15)  # a far origin at a small scale
def test_camera_round_trips_or_names_scale_or_origin(scale: Any, origin: Any, point: Any) -> None:
    ok, cam = attempt(lambda: Camera(scale, origin), "scale", "origin")
    if not ok:
        return
    assert cam is not None
    assert 0 < cam.scale < math.inf and all(math.isfinite(c) for c in cam.origin)
    ok, px = attempt(lambda: cam.point(point), "point", "p")
    if not ok:
        return
    assert isinstance(px[0], int) and isinstance(px[1], int)
    one_d = isinstance(point, (int, float, np.floating, np.integer))  # bools count as 0 and 1
    x, y = (float(point), 0.0) if one_d else (float(point[0]), float(point[1]))
    if (
        max(abs(x), abs(y), *map(abs, cam.origin)) * cam.scale < 1e12
    ):  # whole pixels are exact well within 2^53
        px_x, px_y = cam.to_px(x, y)
        wx, wy = cam.to_world(px_x, px_y)
        # The pixel coordinate origin + scale x is rounded to a float, an error of up to
        # eps (|origin| + |pixel|) pixels, which is that over scale in world units: a far
        # origin at a small scale (origin 1.7e10 px at 0.001 px/m) costs millimetres.
        ulp = 2.0**-52
        err_x = 4 * ulp * (abs(cam.origin[0]) + abs(px_x)) / cam.scale
        err_y = 4 * ulp * (abs(cam.origin[1]) + abs(px_y)) / cam.scale
        assert abs(wx - x) <= 1e-9 * (1 + abs(x)) + err_x
        assert abs(wy - y) <= 1e-9 * (1 + abs(y)) + err_y
        assert abs(px[0] - cam.to_px(x, y)[0]) <= 0.5 and abs(px[1] - cam.to_px(x, y)[1]) <= 0.5


@fuzz(200)
@given(
    world=st.one_of(st.tuples(moderate, moderate, moderate, moderate), anything),
    rect=st.one_of(st.tuples(*[st.integers(-10, 2000)] * 4), anything),
)
def test_camera_fit_shows_the_box_or_names_world_or_rect(world: Any, rect: Any) -> None:
    ok, cam = attempt(lambda: Camera.fit(world, rect), "world", "rect")
    if not ok:
        return
    assert cam is not None
    x0, y0, x1, y1 = (float(v) for v in world)
    left, top, width, height = (float(v) for v in rect)
    for x, y in ((x0, y0), (x1, y1)):
        px, py = cam.to_px(x, y)
        slack = 1e-6 * (1 + abs(left) + width + abs(top) + height)
        assert left - slack <= px <= left + width + slack
        assert top - slack <= py <= top + height + slack


def _odd_folder(kind: str, base: Path, name: str) -> Any:
    if kind == "plain":
        return base / name
    if kind == "nested":  # parents that do not exist yet
        return base / "a" / name / "b"
    if kind == "file":  # a file where the folder should be
        f = base / "afile"
        f.write_bytes(b"not a folder")
        return f
    if kind == "under_file":  # a folder inside a file
        f = base / "afile2"
        f.write_bytes(b"x")
        return f / name
    if kind == "long":  # a name longer than any file system allows
        return base / ("n" * 300)
    if kind == "nul":
        return str(base / "a\x00b")
    if kind == "empty":
        return ""
    if kind == "bytes":
        return os.fsencode(base / "bytes")
    return name  # junk


WRITTEN: list[str] = []


@fuzz(200)
@given(
    kind=st.sampled_from(
        ["plain", "nested", "file", "under_file", "long", "nul", "empty", "bytes", "junk"]
    ),
    name=st.text(
        alphabet=st.characters(blacklist_categories=("Cs",), blacklist_characters="/\x00"),
        min_size=1,
        max_size=12,
    ).filter(lambda s: s not in (".", "..")),
    workers=st.one_of(st.just(None), st.integers(-2, 3), junk, numbers),
    level=st.one_of(st.integers(-2, 10), junk, numbers),
    junk_folder=junk,
)
def test_frame_writer_writes_whole_frames_or_refuses_with_a_clear_error(
    tmp_path_factory: pytest.TempPathFactory,
    kind: str,
    name: str,
    workers: Any,
    level: Any,
    junk_folder: Any,
) -> None:
    init_headless()
    base = tmp_path_factory.mktemp("fw")
    folder = _odd_folder(kind, base, name) if kind != "junk" else junk_folder
    cwd_before = sorted(os.listdir("."))
    try:
        ok, writer = attempt(
            lambda: FrameWriter(folder, workers=workers, level=level), "folder", "workers", "level"
        )
    except (FrameWriteError, FramesExistError) as exc:
        # The file system refused (a file in the way, a name too long): say which folder.
        assert str(folder) in str(exc) or os.fsdecode(folder) in str(exc), str(exc)
        return
    assert sorted(os.listdir(".")) == cwd_before  # nothing written beside the tests
    if not ok:
        return
    assert writer is not None
    surface = pygame.Surface((8, 5))
    surface.fill((200, 30, 90))
    with writer:
        writer.write(surface)
        writer.write(surface)
    assert writer.count == 2
    WRITTEN.append(kind)
    names = sorted(os.listdir(writer.folder))
    assert names == ["frame_00000.png", "frame_00001.png"]
    image = pygame.image.load(str(writer.folder / names[1]))
    assert image.get_size() == (8, 5) and tuple(image.get_at((3, 2)))[:3] == (200, 30, 90)
    assert np.array_equal(pygame.surfarray.array3d(image), pygame.surfarray.array3d(surface))


def test_the_frame_writer_fuzz_wrote_frames_and_odd_but_valid_folders_take_frames(
    tmp_path: Path,
) -> None:
    # The fuzz above (run first: pytest keeps the file's order) must not have refused
    # everything; and unicode names and missing parents are fine places for frames.
    if WRITTEN:
        assert set(WRITTEN) <= {"plain", "nested"}, WRITTEN
    init_headless()
    surface = pygame.Surface((4, 3))
    for folder in (tmp_path / "a" / "b" / "c", tmp_path / "fourmi-🐜-é", tmp_path / " x "):
        with FrameWriter(folder) as writer:
            writer.write(surface)
        assert sorted(p.name for p in folder.iterdir()) == ["frame_00000.png"]
