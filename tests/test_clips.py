"""MP4 and GIF clips: decoded back and compared with the PNG frames of the same run.

The clips need the ``video`` extra (imageio-ffmpeg); the tests that write one are skipped
where it is not installed. The ones about its absence run everywhere.
"""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pygame
import pytest

from demos import cli
from engine.render import (
    ClipExistsError,
    ClipWriteError,
    ClipWriter,
    EncoderUnavailableError,
    RecordingInterrupted,
    Scene,
    record,
)
from engine.render import clips as clips_module

ROOT = Path(__file__).resolve().parent.parent
SKIP_REASON = 'clips need the video extra: pip install -e ".[video]" (imageio-ffmpeg)'
FPS = 10
SIZE = (97, 65)  # odd on purpose: the MP4 is cut to 96x64


@pytest.fixture
def ffmpeg():
    """The imageio_ffmpeg module, or a skip where the video extra is not installed."""
    return pytest.importorskip("imageio_ffmpeg", reason=SKIP_REASON)


class Slide(Scene):
    """A 20x20 red square sliding right over blue stripes, from x = 4 px to x = 64 px in 1 s."""

    name = "slide"
    summary = "a square crossing the canvas"
    duration = 1.0
    dt = 1.0 / 20.0
    stop_at: int | None = None  # the frame at which a Ctrl-C is simulated

    def build(self, size):
        self.world = _Clock()
        self.drawn = 0

    def draw(self, surface, alpha):
        if self.stop_at is not None and self.drawn == self.stop_at:
            raise KeyboardInterrupt
        self.drawn += 1
        surface.fill((250, 248, 240))
        for y in range(0, surface.get_height(), 16):
            surface.fill((40, 60, 200), pygame.Rect(0, y, surface.get_width(), 6))
        x = 4 + round(60 * self.time(alpha))
        surface.fill((220, 30, 30), pygame.Rect(x, 20, 20, 20))


class _Clock:
    """A world with nothing in it but its time (s)."""

    def __init__(self) -> None:
        self.t = 0.0

    def step(self, dt: float) -> None:
        self.t += dt

    def snapshot(self) -> float:
        return self.t

    def restore(self, snapshot: float) -> None:
        self.t = snapshot


def decode(ffmpeg, path: Path) -> tuple[dict, list[np.ndarray]]:
    """The clip's metadata and its frames as (height, width, 3) RGB arrays."""
    reader = ffmpeg.read_frames(str(path), pix_fmt="rgb24")
    meta = next(reader)
    width, height = meta["size"]
    frames = [np.frombuffer(data, np.uint8).reshape(height, width, 3) for data in reader]
    return meta, frames


def png(path: Path) -> np.ndarray:
    return pygame.surfarray.array3d(pygame.image.load(str(path))).transpose(1, 0, 2)


def mad(a: np.ndarray, b: np.ndarray) -> float:
    """Mean absolute difference of two pictures, in 8-bit levels."""
    return float(np.abs(a.astype(int) - b.astype(int)).mean())


def test_mp4_and_gif_hold_the_same_frames_as_the_pngs(ffmpeg, tmp_path):
    video, gif = tmp_path / "new" / "slide.mp4", tmp_path / "new" / "slide.gif"
    rec = record(
        Slide(), tmp_path / "frames", fps=FPS, size=SIZE, progress=False, video=video, gif=gif
    )
    assert (rec.video, rec.gif, rec.count) == (video, gif, 11)
    pngs = [png(p) for p in rec.paths()]
    assert mad(pngs[0], pngs[-1]) > 10  # the square moved: a wrong frame would show

    meta, frames = decode(ffmpeg, video)
    assert len(frames) == 11
    assert meta["size"] == rec.video_size == (96, 64)  # the odd row and column are cut
    assert meta["fps"] == FPS
    assert meta["codec"] == "h264" and meta["pix_fmt"].startswith("yuv420p")
    for got, want in ((frames[0], pngs[0]), (frames[-1], pngs[-1])):
        assert mad(got, want[:64, :96]) < 4  # lossy, but the same picture
    data = video.read_bytes()
    assert data.index(b"moov") < data.index(b"mdat")  # +faststart: playable while loading

    meta, frames = decode(ffmpeg, gif)
    assert len(frames) == 11
    assert meta["size"] == SIZE
    assert meta["duration"] == pytest.approx(11 / FPS, abs=0.02)
    for got, want in ((frames[0], pngs[0]), (frames[-1], pngs[-1])):
        assert mad(got, want) < 1  # a palette made from these frames holds their colours
    assert b"NETSCAPE2.0\x03\x01\x00\x00" in gif.read_bytes()  # loop count 0: for ever

    assert sorted(p.name for p in video.parent.iterdir()) == ["slide.gif", "slide.mp4"]


def test_a_clip_alone_writes_no_frames(ffmpeg, tmp_path):
    rec = record(Slide(), fps=FPS, size=(64, 48), progress=False, video=tmp_path / "a.mp4")
    assert rec.folder is None and rec.paths() == []
    assert os.listdir(tmp_path) == ["a.mp4"]
    assert len(decode(ffmpeg, tmp_path / "a.mp4")[1]) == 11


def test_an_existing_clip_is_refused_before_any_work_without_overwrite(ffmpeg, tmp_path):
    target = tmp_path / "slide.gif"
    target.write_bytes(b"the teacher's own file")
    # A library call names its argument; the command line names its option (test_cli).
    with pytest.raises(ClipExistsError, match="pass overwrite=True") as refused:
        record(Slide(), tmp_path / "frames", fps=FPS, size=(64, 48), progress=False, gif=target)
    assert refused.value.path == target
    assert target.read_bytes() == b"the teacher's own file"
    assert sorted(os.listdir(tmp_path)) == ["slide.gif"]  # no frames folder, no temp file
    record(Slide(), fps=FPS, size=(64, 48), progress=False, gif=target, overwrite=True)
    assert target.read_bytes().startswith(b"GIF89a")


def test_an_interrupted_clip_leaves_nothing_under_its_name(ffmpeg, tmp_path):
    old = tmp_path / "old.mp4"
    old.write_bytes(b"a clip from yesterday")
    scene = Slide()
    scene.stop_at = 6  # Ctrl-C while drawing the 7th frame: six are in the encoders
    with pytest.raises(RecordingInterrupted) as stop:
        record(
            scene,
            tmp_path / "frames",
            fps=FPS,
            size=(64, 48),
            progress=False,
            video=tmp_path / "new.mp4",
            gif=old.with_suffix(".gif"),
        )
    # The frame writer finishes the frames being encoded and drops queued ones, without gaps.
    written = stop.value.written
    assert 0 < written <= 6
    assert sorted(os.listdir(tmp_path / "frames")) == [f"frame_{i:05d}.png" for i in range(written)]
    assert set(stop.value.clips) == {tmp_path / "new.mp4", tmp_path / "old.gif"}
    assert sorted(os.listdir(tmp_path)) == ["frames", "old.mp4"]  # no clip, no temp file
    with pytest.raises(RecordingInterrupted):
        record(scene, fps=FPS, size=(64, 48), progress=False, video=old, overwrite=True)
    assert old.read_bytes() == b"a clip from yesterday"  # replaced only by a whole clip
    assert sorted(os.listdir(tmp_path)) == ["frames", "old.mp4"]


def fake_encoder(tmp_path: Path, message: str) -> str:
    """An 'ffmpeg' that takes a few frames, says ``message`` on stderr and fails."""
    script = tmp_path / "ffmpeg"
    script.write_text(
        f"#!{sys.executable}\n"
        "import sys\n"
        "sys.stdin.buffer.read(1000)\n"
        f"sys.stderr.write('frame 1: encoding\\n{message}\\n')\n"
        "sys.exit(1)\n"
    )
    script.chmod(0o755)
    return str(script)


@pytest.mark.skipif(sys.platform == "win32", reason="the fake encoder is a script")
def test_a_failing_encoder_is_a_clear_error_quoting_it_and_leaves_no_file(
    ffmpeg, tmp_path, monkeypatch, capsys
):
    exe = fake_encoder(tmp_path, "Error writing trailer: No space left on device")
    monkeypatch.setattr(clips_module, "ffmpeg_exe", lambda: exe)
    out = tmp_path / "out"
    with pytest.raises(ClipWriteError, match="No space left on device") as failed:
        record(Slide(), fps=FPS, size=(64, 48), progress=False, video=out / "a.mp4")
    assert "exit status 1" in str(failed.value) and str(out / "a.mp4") in str(failed.value)
    assert os.listdir(out) == []
    argv = ["alfred", "--scene", "lazy", "--fps", "2", "--seconds", "1", "--size", "160x90"]
    code = cli.main([*argv, "--gif", str(out / "b.gif")], out=io.StringIO())
    assert code == 1
    err = capsys.readouterr().err
    assert err.startswith("error: could not write") and "No space left on device" in err
    assert os.listdir(out) == []


def test_a_missing_encoder_binary_is_a_clear_error(ffmpeg, tmp_path, monkeypatch):
    monkeypatch.setattr(clips_module, "ffmpeg_exe", lambda: str(tmp_path / "no-ffmpeg"))
    with pytest.raises(ClipWriteError, match="could not start the encoder"):
        ClipWriter(tmp_path / "a.mp4", (64, 48), FPS)
    assert os.listdir(tmp_path) == []


def run_cli(argv: list[str], capsys) -> tuple[int, str, str]:
    out = io.StringIO()
    try:
        code = cli.main(argv, out=out)
    except SystemExit as exc:  # argparse's usage errors
        code = int(exc.code or 0)
    return code, out.getvalue(), capsys.readouterr().err


SHORT = ["alfred", "--fps", "2", "--seconds", "1", "--size", "160x90"]


def test_the_cli_writes_a_clip_per_scene_and_checks_them_all_first(ffmpeg, tmp_path, capsys):
    (tmp_path / "lesson-paper.mp4").write_bytes(b"kept")
    code, out, err = run_cli([*SHORT, "--video", str(tmp_path / "lesson.mp4")], capsys)
    assert code == 1 and "lesson-paper.mp4 already exists" in err
    assert "add --overwrite to replace it" in err and "overwrite=True" not in err
    assert os.listdir(tmp_path) == ["lesson-paper.mp4"]  # refused before the first scene
    code, out, err = run_cli(
        [*SHORT, "--video", str(tmp_path / "lesson.mp4"), "--overwrite"], capsys
    )
    assert code == 0, err
    names = [f"lesson-{scene}.mp4" for scene in ("lazy", "stroll", "sprint", "paper")]
    assert sorted(os.listdir(tmp_path)) == sorted(names)
    assert "alfred/sprint: wrote the video" in out and "H.264 MP4, 160x90" in out
    assert len(decode(ffmpeg, tmp_path / "lesson-sprint.mp4")[1]) == 3


def test_the_cli_writes_frames_beside_the_clip_with_out(ffmpeg, tmp_path, capsys):
    argv = [*SHORT, "--scene", "sprint", "--gif", str(tmp_path / "s.gif")]
    code, out, _ = run_cli([*argv, "--out", str(tmp_path / "frames")], capsys)
    assert code == 0
    assert sorted(os.listdir(tmp_path / "frames")) == [f"frame_0000{i}.png" for i in range(3)]
    assert "wrote 3 frames" in out and "wrote the GIF" in out
    meta, frames = decode(ffmpeg, tmp_path / "s.gif")
    assert len(frames) == 3 and meta["size"] == (160, 90)


@pytest.mark.parametrize(
    ("extra", "named"),
    [
        (["--video", "clip.mov"], "argument --video: must be a file name ending in .mp4"),
        (["--gif", "clip.mp4"], "argument --gif: must be a file name ending in .gif"),
        (["--video", ".mp4"], "argument --video"),
        (["--gif", "c.gif", "--window"], "argument --gif: not allowed with argument --window"),
        (["--video", "c.mp4", "--strobe"], "argument --video: not allowed with argument --strobe"),
        (["--gif", "c.gif", "--fps", "60"], "argument --gif: a GIF plays at most 50 fps"),
    ],
)
def test_bad_clip_options_are_usage_errors_naming_the_option(extra, named, capsys, tmp_path):
    code, _, err = run_cli([*SHORT, *[str(tmp_path / e) if "." in e else e for e in extra]], capsys)
    assert code == 2
    assert named in err
    assert os.listdir(tmp_path) == []


def test_without_the_extra_a_clip_is_a_usage_error_naming_it(monkeypatch, capsys, tmp_path):
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)  # import imageio_ffmpeg fails
    for option, name in (("--video", "a.mp4"), ("--gif", "a.gif")):
        code, _, err = run_cli([*SHORT, option, str(tmp_path / name)], capsys)
        assert code == 2
        assert f"argument {option}: writing a video or GIF needs the imageio-ffmpeg" in err
        assert 'pip install -e ".[video]"' in err and "README" in err
    with pytest.raises(EncoderUnavailableError, match=r"\.\[video\]"):
        record(Slide(), tmp_path / "frames", fps=FPS, size=(64, 48), video=tmp_path / "a.mp4")
    assert os.listdir(tmp_path) == []  # refused before the frames folder was made
    code, _, _ = run_cli([*SHORT, "--scene", "lazy", "--out", str(tmp_path / "f")], capsys)
    assert code == 0  # frames alone need nothing more


def test_importing_the_engine_does_not_import_the_encoder():
    code = (
        "import sys, engine, engine.render, demos.cli; "
        "assert 'imageio_ffmpeg' not in sys.modules, 'imported'"
    )
    subprocess.run([sys.executable, "-c", code], cwd=ROOT, check=True)


def test_a_frame_of_another_size_is_refused(ffmpeg, tmp_path):
    colours = [(200, 30, 30), (30, 200, 30), (30, 30, 200)]
    with ClipWriter(tmp_path / "a.gif", (64, 48), FPS) as clip:
        with pytest.raises(ValueError, match="64x48"):
            clip.write(pygame.Surface((48, 64)))
        surface = pygame.Surface((64, 48))
        for colour in colours:
            surface.fill(colour)
            clip.write(surface)
    frames = decode(ffmpeg, tmp_path / "a.gif")[1]
    assert [tuple(frame[10, 10]) for frame in frames] == colours


def _running(pid: int) -> bool:
    """Whether process ``pid`` runs (not gone, not a zombie waiting to be reaped)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split(") ")[-1][0] != "Z"
    except FileNotFoundError:
        return False


@pytest.mark.skipif(not Path("/proc").is_dir(), reason="reads /proc for the encoder's process")
def test_a_writer_dropped_unclosed_stops_its_encoder_and_leaves_no_file(ffmpeg, tmp_path):
    # Found 2026-12-05: a ClipWriter dropped without close() (no ``with``, an exception on the
    # way) was never collected (its writer thread held it), so its ffmpeg waited on its pipe
    # till the program ended, and then finished a stray ".x.mp4.<pid>.part" beside the target.
    # It is aborted when collected now, and says so as an unclosed file does.
    import gc

    def drop() -> int:
        clip = ClipWriter(tmp_path / "x.mp4", (64, 48), FPS)
        for _ in range(3):
            clip.write(pygame.Surface((64, 48)))
        return clip._process.pid

    with pytest.warns(ResourceWarning, match=r"x\.mp4 was dropped without close\(\)"):
        pid = drop()
        gc.collect()
    assert not _running(pid)
    assert os.listdir(tmp_path) == []  # no clip, no temporary file


def test_a_writer_left_unclosed_at_exit_leaves_no_file(ffmpeg, tmp_path):
    # The same writer kept to the interpreter's exit: aborted there (weakref.finalize's atexit).
    code = (
        "import pygame\n"
        "from engine.render import ClipWriter\n"
        f"clip = ClipWriter({str(tmp_path / 'x.gif')!r}, (64, 48), 10)\n"
        "clip.write(pygame.Surface((64, 48)))\n"
        "print(clip._process.pid)\n"
    )
    env = {**os.environ, "SDL_VIDEODRIVER": "dummy", "SDL_AUDIODRIVER": "dummy"}
    done = subprocess.run(
        [sys.executable, "-W", "always", "-c", code],
        cwd=ROOT, env=env, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "x.gif was dropped without close()" in done.stderr
    assert os.listdir(tmp_path) == []
    if Path("/proc").is_dir():
        assert not _running(int(done.stdout.split()[-1]))
