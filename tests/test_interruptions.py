"""Nothing lost, nothing clobbered: a recording stopped by a signal or a failing disk leaves only
whole frames, says how many, and exits non-zero; a folder of frames is never overwritten unasked."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pygame
import pytest

from demos import cli
from engine.render import frames as frames_module

ROOT = Path(__file__).resolve().parent.parent
SIZE = (160, 90)


def _whole_frames(folder: Path) -> list[Path]:
    """Every file in ``folder`` must be a frame that loads, of the right size; return them."""
    names = sorted(os.listdir(folder))
    assert all(re.fullmatch(r"frame_\d{5}\.png", n) for n in names), names  # no temp files
    paths = [folder / n for n in names]
    assert [p.name for p in paths] == [f"frame_{i:05d}.png" for i in range(len(paths))]
    for path in paths:
        assert pygame.image.load(str(path)).get_size() == SIZE
    return paths


def _default_sigint() -> None:
    """In the child, before it runs Python: SIGINT's default, whatever the parent ignored."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _stopped_by(signum: int, tmp_path: Path, extra: list[str]) -> tuple[int, str, Path]:
    """Record Alfred's stroll for 3000 s in a fresh interpreter, send ``signum`` once 20 frames
    are on disk, and return its exit code, what it said on stderr, and the frames' folder."""
    out = tmp_path / "stroll"
    env = {**os.environ, "SDL_VIDEODRIVER": "dummy", "SDL_AUDIODRIVER": "dummy"}
    command = [
        sys.executable,
        "-X",
        "faulthandler",  # a child that hangs is aborted below, and shows where it hung
        "-m",
        "demos",
        "alfred",
        "--scene",
        "stroll",
        "--fps",
        "60",
        "--seconds",
        "3000",
        "--size",
        f"{SIZE[0]}x{SIZE[1]}",
        "--out",
        str(out),
        *extra,
    ]
    # A fresh interpreter with the default SIGINT handling: a shell's background job runs
    # with SIGINT ignored, and an ignored signal is inherited across exec (a suite started
    # that way hung here for 60 s), so the child sets it back to the default before it
    # starts; stderr to a file so a full pipe can never stall the child.
    with open(tmp_path / "stderr.txt", "w") as err:
        child = subprocess.Popen(
            command,
            cwd=ROOT,
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=err,
            preexec_fn=_default_sigint,
        )
        deadline = time.monotonic() + 60
        while not (out.is_dir() and len(os.listdir(out)) >= 20):
            assert child.poll() is None, "the recording ended before it could be stopped"
            assert time.monotonic() < deadline, "no frames appeared within 60 s"
            time.sleep(0.05)
        child.send_signal(signum)
        try:
            code = child.wait(timeout=60)
        except subprocess.TimeoutExpired:
            child.send_signal(signal.SIGABRT)  # faulthandler: every thread's stack on stderr
            child.wait()
            code = None
    message = (tmp_path / "stderr.txt").read_text()
    assert code is not None, f"no exit within 60 s of the signal; the child's stacks:\n{message}"
    return code, message, out


@pytest.mark.parametrize(
    ("signum", "word"), [(signal.SIGINT, "interrupted"), (signal.SIGTERM, "terminated")]
)
def test_a_signal_mid_recording_leaves_whole_frames_and_says_how_many(
    tmp_path: Path, signum: int, word: str
) -> None:
    code, message, out = _stopped_by(signum, tmp_path, [])
    assert code == 128 + signum, message
    written = _whole_frames(out)
    assert 20 <= len(written) < 180_001  # stopped part-way
    match = re.search(rf"{word}.*?(\d+) whole frame\(s\) written to", message)
    assert match, message
    assert int(match.group(1)) == len(written)


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_mid_recording_of_a_clip_leaves_no_clip_and_whole_frames(
    tmp_path: Path, signum: int
) -> None:
    """A clip being written when the stop comes is thrown away (its encoder stopped, its
    temporary file removed), and the frames written beside it are whole."""
    pytest.importorskip("imageio_ffmpeg", reason="clips need the video extra")
    clip = tmp_path / "stroll.mp4"
    code, message, out = _stopped_by(signum, tmp_path, ["--video", str(clip)])
    assert code == 128 + signum, message
    assert "no clip written" in message and str(clip) in message, message
    assert not clip.exists()
    assert [p.name for p in tmp_path.iterdir() if p.suffix not in ("", ".txt")] == []
    written = _whole_frames(out)
    match = re.search(r"(\d+) whole frame\(s\) written to", message)
    assert match and int(match.group(1)) == len(written) >= 20, message


def test_a_failing_disk_stops_the_run_and_keeps_the_frames_already_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "stroll"
    real_replace = os.replace

    def disk_full_after_ten(src: str, dst: str) -> None:
        # By name, not by count: the encoding threads finish frames out of order.
        if int(Path(dst).stem.split("_")[1]) >= 10:
            raise OSError(28, "No space left on device")
        real_replace(src, dst)

    monkeypatch.setattr(frames_module.os, "replace", disk_full_after_ten)
    args = ["alfred", "--scene", "stroll", "--fps", "10", "--size", "160x90", "--out", str(out)]
    code = cli.main(args)
    assert code == 1
    err = capsys.readouterr().err
    assert "No space left on device" in err and str(out) in err
    assert "10 whole frame(s) kept" in err
    monkeypatch.setattr(frames_module.os, "replace", real_replace)
    assert len(_whole_frames(out)) == 10


def test_an_unwritable_folder_is_a_clear_error(tmp_path: Path, capsys) -> None:
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("a file where the frames' folder should be")
    code = cli.main(["alfred", "--scene", "lazy", "--out", str(blocker / "frames")])
    assert code == 1
    assert str(blocker) in capsys.readouterr().err
    assert blocker.read_text() == "a file where the frames' folder should be"


def test_existing_frames_are_never_overwritten_without_overwrite(tmp_path: Path, capsys) -> None:
    out = tmp_path / "lazy"
    args = ["alfred", "--scene", "lazy", "--fps", "5", "--size", "160x90", "--out", str(out)]
    assert cli.main(args) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    (out / "frame_00000.png").write_bytes(b"the teacher's own edit")
    assert cli.main(args) == 1
    assert "--overwrite" in capsys.readouterr().err
    assert (out / "frame_00000.png").read_bytes() == b"the teacher's own edit"
    assert cli.main([*args, "--overwrite"]) == 0
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
