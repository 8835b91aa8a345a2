"""The recorder drives a scene through the fixed-step loop, drawing each frame at its own time."""

import argparse
import math
import subprocess
import sys

import numpy as np
import pygame
import pytest

from engine import Body, World
from engine.render import (
    Camera,
    FramesExistError,
    Progress,
    Scene,
    frame_count,
    iter_frames,
    record,
    strobe,
)

MARK = (255, 0, 255)  # the dot's colour, used nowhere else


class Glide(Scene):
    """A dot gliding at 2 units/s along x from x = 1: x(t) = 1 + 2 t, exactly, at any dt."""

    name = "glide"
    summary = "a dot at constant velocity"
    duration = 1.0
    dt = 0.07  # not a divisor of the frame time: frames fall between steps

    def build(self, size):
        self.world = World(integrator="semi_implicit_euler")
        self.dot = self.world.add(Body(1.0, 2.0, 0.0))
        self.camera = Camera(scale=40.0, origin=(10.0, size[1] / 2))
        self.builds = getattr(self, "builds", 0) + 1

    def draw(self, surface, alpha):
        surface.fill((255, 255, 255))
        x, y = self.camera.point(self.world.position_of(self.dot, alpha))
        surface.fill(MARK, pygame.Rect(x, y, 1, 1))


def mark_x(surface: pygame.Surface) -> int:
    pixels = pygame.surfarray.pixels3d(surface)
    xs, _ = np.nonzero((pixels == MARK).all(axis=-1))
    assert len(xs) == 1
    return int(xs[0])


def test_frame_count_includes_both_ends():
    assert frame_count(10.0, 30) == 301
    assert frame_count(0.1, 30) == 4  # 0.1 * 30 is 2.9999999999999996 in floats
    assert frame_count(1 / 3, 3) == 2


@pytest.mark.parametrize("fps", [2, 25])  # 2 fps: frames longer than the loop's stall clamp
def test_each_frame_shows_the_state_at_its_own_time(fps):
    scene = Glide()
    seen = []
    for index, t, surface in iter_frames(scene, fps=fps, size=(160, 20)):
        assert t == index / fps
        expected = scene.camera.point(1.0 + 2.0 * t)[0]
        seen.append((mark_x(surface), expected))
    assert len(seen) == fps + 1
    assert all(abs(got - want) <= 1 for got, want in seen), seen


def test_scene_time_matches_the_frame_time():
    scene = Glide()
    times = []
    original = Glide.draw

    def draw(self, surface, alpha):
        times.append(self.time(alpha))
        original(self, surface, alpha)

    scene.draw = draw.__get__(scene)
    list(iter_frames(scene, fps=10, size=(120, 20)))
    np.testing.assert_allclose(times, [k / 10 for k in range(11)], atol=1e-12)


def test_record_writes_the_frames_and_reports_them(tmp_path):
    calls = []
    rec = record(
        Glide(), tmp_path / "glide", fps=10, size=(120, 20), progress=lambda *a: calls.append(a)
    )
    assert rec.count == 11 and rec.fps == 10 and rec.size == (120, 20) and rec.seconds == 1.0
    assert [p.name for p in rec.paths()] == sorted(p.name for p in (tmp_path / "glide").iterdir())
    assert calls == [(i, 11) for i in range(1, 12)]
    first = pygame.image.load(str(rec.paths()[0]))
    assert first.get_size() == (120, 20)


def test_record_refuses_a_folder_with_frames(tmp_path):
    record(Glide(), tmp_path, fps=5, size=(60, 20), progress=False)
    with pytest.raises(FramesExistError):
        record(Glide(), tmp_path, fps=5, size=(60, 20), progress=False)
    assert (
        record(Glide(), tmp_path, fps=5, size=(60, 20), overwrite=True, progress=False).count == 6
    )


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"fps": 0}, "fps must be a whole number"),
        ({"fps": 2.5}, "fps must be a whole number"),
        ({"seconds": -1.0}, "seconds must be a finite number > 0"),
        ({"seconds": math.inf}, "seconds must be a finite number > 0"),
        ({"size": (0, 10)}, "size must be two whole numbers"),
        ({"size": (640,)}, "size must be"),
    ],
)
def test_record_rejects_bad_arguments_naming_them(tmp_path, kwargs, message):
    with pytest.raises(ValueError, match=message):
        record(Glide(), tmp_path, **kwargs)
    assert not list(tmp_path.iterdir())


def test_strobe_needs_a_scene_that_draws_one(tmp_path):
    with pytest.raises(NotImplementedError, match="glide"):
        strobe(Glide(), tmp_path / "strobe.png")


class FakeTerminal:
    def __init__(self, tty):
        self.tty, self.text = tty, ""

    def isatty(self):
        return self.tty

    def write(self, text):
        self.text += text

    def flush(self):
        pass


def test_progress_is_quiet_off_a_terminal_and_after_a_delay_on_one():
    off = FakeTerminal(False)
    bar = Progress("x", stream=off, delay=0.0)
    bar(5, 10)
    bar.done()
    assert off.text == ""
    slow = FakeTerminal(True)
    bar = Progress("x", stream=slow, delay=60.0)
    bar(5, 10)
    assert slow.text == ""  # a render shorter than the delay says nothing
    tty = FakeTerminal(True)
    bar = Progress("stroll", stream=tty, delay=0.0)
    bar(10, 10)
    bar.done()
    assert tty.text.startswith("\rstroll 10/10 frames 100%") and tty.text.endswith("\n")


def test_the_tradeoff_progress_line_counts_runs_and_says_how_long_it_all_takes(
    monkeypatch, tmp_path
):
    # The whole tradeoff demo took minutes and nothing said so before it started.
    import demos.tradeoff as tradeoff

    lines = []

    class Seen(Progress):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs, stream=FakeTerminal(True), delay=0.0)
            lines.append(self)

    monkeypatch.setattr(tradeoff, "Progress", Seen)
    monkeypatch.setattr(tradeoff.measure, "sweep", lambda *a, **k: [])
    monkeypatch.setattr(tradeoff.pendulum, "measure", lambda quick, progress: progress(1, 2) or [])

    class Stop(Exception):
        pass

    def stop(*args, **kwargs):
        raise Stop

    monkeypatch.setattr(tradeoff, "draw_work_precision", stop)
    args = argparse.Namespace(quick=False, out=tmp_path, size=None, overwrite=False)
    with pytest.raises(Stop):
        tradeoff.run(args)
    text = lines[1].stream.text
    assert text.startswith(f"\rtradeoff 2/4 ({tradeoff.TAKES[False]} in all): pendulum 1/2 runs")


def test_import_engine_does_not_import_pygame():
    code = "import sys, engine, engine.kinematics, engine.loop; print('pygame' in sys.modules)"
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "False"


def test_importing_the_renderer_starts_no_display():
    code = (
        "import pygame, engine.render; "
        "print(pygame.display.get_init(), pygame.font.get_init(), pygame.mixer.get_init())"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert result.stdout.split() == ["False", "False", "None"]
    assert "Hello from the pygame community" not in result.stdout


def test_play_runs_the_real_time_loop_until_the_window_closes(monkeypatch):
    # No display here: open the window on the dummy driver and close it with a timed QUIT.
    from engine.render import init_headless, recorder

    monkeypatch.setattr(recorder, "init_window", init_headless)
    scene = Glide()
    drawn = []
    original = Glide.draw

    def draw(self, surface, alpha):
        if not drawn:
            # Timed from the first frame, not from before the build (which, run alone, a cold
            # first import can make take longer than the 150 ms): about nine frames at 60 fps.
            pygame.time.set_timer(pygame.QUIT, 150, loops=1)
        drawn.append(self.time(alpha))
        original(self, surface, alpha)

    scene.draw = draw.__get__(scene)
    init_headless()
    recorder.play(scene, fps=60, size=(160, 20))
    assert len(drawn) >= 2
    assert drawn == sorted(drawn) and all(0.0 <= t <= scene.duration for t in drawn)
    assert not pygame.display.get_init()  # the window is closed again
