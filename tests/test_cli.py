"""The command line: listing, running headless, and usage errors that name the argument."""

import errno
import io
import os
import subprocess
import sys
from pathlib import Path

import pytest

from demos import cli
from engine.render import frames as frames_module

ROOT = Path(__file__).resolve().parent.parent


def run(argv, capsys):
    out = io.StringIO()
    try:
        code = cli.main(argv, out=out)
    except SystemExit as exc:  # argparse's usage errors
        code = exc.code
    return code, out.getvalue(), capsys.readouterr().err


def test_lists_the_demos_one_line_each(capsys):
    code, out, _ = run([], capsys)
    assert code == 0
    lines = [line for line in out.splitlines() if line.startswith("  ")]
    alfred = [line for line in lines if line.split()[0] == "alfred"]
    assert len(alfred) == 1 and "lazy, stroll, sprint, paper" in alfred[0]


def test_runs_as_a_module_and_lists_the_demos():
    result = subprocess.run(
        [sys.executable, "-m", "demos"], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert "alfred" in result.stdout
    assert "Hello from the pygame community" not in result.stdout


@pytest.mark.parametrize(
    ("argv", "named"),
    [
        (["nosuchdemo"], "argument demo: invalid choice: 'nosuchdemo'"),
        (["alfred", "--scene", "jog"], "argument --scene: invalid choice: 'jog'"),
        (["alfred", "--fps", "0"], "argument --fps: must be a whole number"),
        (["alfred", "--fps", "fast"], "argument --fps"),
        (["alfred", "--seconds", "-2"], "argument --seconds: must be a number"),
        (["alfred", "--seconds", "nan"], "argument --seconds"),
        (["alfred", "--size", "640by360"], "argument --size: must be WIDTHxHEIGHT"),
        (["alfred", "--size", "0x360"], "argument --size"),
        (
            ["alfred", "--window", "--strobe"],
            "argument --strobe: not allowed with argument --window",
        ),
    ],
)
def test_usage_errors_exit_2_naming_the_argument(argv, named, capsys, tmp_path):
    code, out, err = run([*argv, "--out", str(tmp_path / "x")], capsys)
    assert code == 2
    assert named in err
    assert not (tmp_path / "x").exists()


def test_headless_run_writes_frames_and_says_where(capsys, tmp_path):
    folder = tmp_path / "lesson" / "sprint"
    argv = ["alfred", "--scene", "sprint", "--fps", "2", "--seconds", "1", "--size", "320x180"]
    code, out, _ = run([*argv, "--out", str(folder)], capsys)
    assert code == 0
    assert sorted(p.name for p in folder.iterdir()) == [f"frame_{i:05d}.png" for i in range(3)]
    assert "alfred/sprint: wrote 3 frames (320x180, 2 fps, 1 s)" in out
    assert str(folder) in out


def test_every_scene_goes_in_its_own_folder(capsys, tmp_path):
    argv = ["alfred", "--fps", "1", "--seconds", "1", "--size", "160x90", "--out", str(tmp_path)]
    code, out, _ = run(argv, capsys)
    assert code == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["lazy", "paper", "sprint", "stroll"]
    assert len(out.strip().splitlines()) == 4


def test_strobe_writes_one_still_per_scene(capsys, tmp_path):
    argv = ["alfred", "--strobe", "--scene", "stroll", "--size", "320x180", "--out", str(tmp_path)]
    code, out, _ = run(argv, capsys)
    assert code == 0 and (tmp_path / "strobe.png").exists()
    assert "motion diagram" in out


def test_a_folder_with_frames_is_refused_with_a_message_and_exit_1(capsys, tmp_path):
    argv = ["alfred", "--scene", "lazy", "--fps", "1", "--seconds", "1", "--size", "160x90"]
    argv += ["--out", str(tmp_path)]
    assert run(argv, capsys)[0] == 0
    code, _, err = run(argv, capsys)
    assert code == 1
    assert "already holds 2 frame(s)" in err and "--overwrite" in err
    assert run([*argv, "--overwrite"], capsys)[0] == 0


def test_a_failing_write_is_a_message_and_exit_1(capsys, tmp_path, monkeypatch):
    def full_disk(*args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(frames_module, "open", full_disk, raising=False)
    argv = ["alfred", "--scene", "lazy", "--fps", "1", "--seconds", "1", "--size", "160x90"]
    code, _, err = run([*argv, "--out", str(tmp_path)], capsys)
    assert code == 1
    assert err.startswith("error: could not write frame") and "No space left on device" in err
    assert list(tmp_path.iterdir()) == []


def test_window_without_a_display_is_a_clear_error(capsys, monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    code, _, err = run(["alfred", "--scene", "lazy", "--window"], capsys)
    assert code == 1
    assert "no window can open" in err and "drop --window" in err


def test_discovers_a_new_demo_module_without_edits(tmp_path, monkeypatch, capsys):
    import demos

    extra = tmp_path / "demos_extra"
    extra.mkdir()
    (extra / "hello.py").write_text(
        "from demos.cli import Demo\n"
        "def run(args):\n"
        "    print('hello ran with', args.size)\n"
        "    return 3\n"
        "DEMO = Demo(name='hello', summary='says hello', run=run)\n"
    )
    (extra / "broken.py").write_text("raise RuntimeError('half-written demo')\n")
    monkeypatch.setattr(demos, "__path__", [*demos.__path__, str(extra)])
    code, out, _ = run([], capsys)
    assert "hello" in out and "says hello" in out
    assert "broken" in out and "half-written demo" in out
    code, _, _ = run(["hello", "--size", "100x100"], capsys)
    assert code == 3
    for name in ("demos.hello", "demos.broken"):
        sys.modules.pop(name, None)


def test_a_size_too_small_for_the_scene_is_a_usage_error_naming_the_minimum(capsys) -> None:
    from demos.stability import OrbitsScene

    need_w, need_h = OrbitsScene.min_size
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["stability", "--scene", "orbits", "--size", f"{need_w - 1}x{need_h}"])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert "--size" in err and f"{need_w}x{need_h}" in err


def test_the_recorder_refuses_a_canvas_below_the_scenes_minimum(tmp_path) -> None:
    from demos.car import MainStreet
    from engine.render import record

    need_w, need_h = MainStreet.min_size
    with pytest.raises(ValueError, match=f"at least {need_w}x{need_h} px"):
        record(MainStreet(), tmp_path / "car", size=(need_w, need_h - 1))
    assert not list(tmp_path.glob("car/frame_*.png"))
