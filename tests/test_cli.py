"""The command line: listing, running headless, and usage errors that name the argument."""

import errno
import io
import os
import re
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


# -- one rule for every demo: an option it cannot honour is refused, exit 2, saying why -------


def _demos_and_refused() -> list[tuple[str, str]]:
    """(demo, option) for every shared option a demo with a run hook does not take."""
    values = {"--scene": "x", "--fps": "10", "--seconds": "1", "--size": "1280x720", "--seed": "1"}
    values |= {"--out": "out/x", "--video": "x.mp4", "--gif": "x.gif"}
    cases = []
    for name, demo in cli.discover().items():
        if isinstance(demo, cli.Demo) and demo.run is not None:
            for option in cli.SHARED:
                if option not in demo.takes:
                    cases.append(
                        (name, f"{option}={values[option]}" if option in values else option)
                    )
    return cases


@pytest.mark.parametrize(("name", "option"), _demos_and_refused())
def test_a_shared_option_a_demo_cannot_honour_is_refused_the_same_way(name, option, capsys):
    # --strobe was silently ignored by breakout, crumb and tradeoff (breakout wrote all its
    # frames); other demos said "skipped" or refused.
    code, out, err = run([name, option], capsys)
    flag = option.split("=")[0]
    assert code == 2, (name, option, out, err)
    assert f"argument {flag}: the demo '{name}' cannot honour it" in err
    assert err.startswith(f"usage: python -m demos {name}")
    assert out == ""


def test_every_game_and_chart_says_what_it_takes() -> None:
    taken = {n: d.takes for n, d in cli.discover().items() if isinstance(d, cli.Demo)}
    assert "--strobe" not in taken["breakout"] | taken["crumb"] | taken["tradeoff"]
    assert {"--out", "--overwrite"} <= taken["tradeoff"]
    assert "--window" in taken["breakout"] and "--window" in taken["crumb"]


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["car", "--strobe"], "argument --strobe: the demo 'car' has no motion diagram"),
        (
            ["bounce", "--scene", "drift", "--strobe"],
            "argument --strobe: the scene 'drift' has no motion diagram (scenes with one: "
            "drop, tunnel)",
        ),
        (["alfred", "--strobe", "--fps", "10"], "argument --fps: not allowed with argument"),
        (["alfred", "--strobe", "--seconds", "2"], "argument --seconds: not allowed with"),
        (["alfred", "--window", "--out", "x"], "argument --out: not allowed with argument"),
        (["alfred", "--window", "--overwrite"], "argument --overwrite: not allowed with"),
    ],
)
def test_a_scene_demo_refuses_what_its_scenes_cannot_honour(argv, says, capsys, tmp_path):
    code, out, err = run(argv, capsys)
    assert code == 2 and says in err, err
    assert err.startswith(f"usage: python -m demos {argv[0]}")


def test_a_strobe_of_every_scene_skips_those_without_one_and_says_so(capsys, tmp_path):
    code, out, _ = run(["bounce", "--strobe", "--size", "480x270", "--out", str(tmp_path)], capsys)
    assert code == 0
    assert "bounce/drift: no motion diagram for this scene, skipped" in out
    assert (tmp_path / "drop" / "strobe.png").is_file()


def test_an_error_in_a_shared_option_shows_the_demos_usage_not_the_top_levels(capsys):
    # An error in a shared flag printed the top-level usage, "python -m demos [-h] ...".
    for argv in (
        ["alfred", "--fps", "0"],
        ["tradeoff", "--size", "big"],
        ["galton", "--seed", "x"],
    ):
        code, _, err = run(argv, capsys)
        assert code == 2
        assert err.startswith(f"usage: python -m demos {argv[0]} "), err
        assert f"argument {argv[1]}:" in err


def test_one_frame_is_one_frame(capsys, tmp_path):
    argv = ["alfred", "--scene", "lazy", "--fps", "1", "--seconds", "0.5", "--out", str(tmp_path)]
    code, out, _ = run(argv, capsys)
    assert code == 0
    assert "alfred/lazy: wrote 1 frame (640x360, 1 fps, 0.5 s)" in out and "1 frames" not in out


def test_a_refusal_to_overwrite_names_the_option_not_the_python_argument(capsys, tmp_path):
    # The refusal said "pass overwrite=True (--overwrite)": a Python argument to a command line.
    frames = ["alfred", "--scene", "lazy", "--fps", "1", "--seconds", "1", "--out", str(tmp_path)]
    strobe = ["alfred", "--scene", "lazy", "--strobe", "--out", str(tmp_path)]
    for argv in (frames, strobe):
        assert run(argv, capsys)[0] == 0
        code, _, err = run(argv, capsys)
        assert code == 1
        assert "add --overwrite to replace" in err and "overwrite=True" not in err, err


# -- a demo's --help lists only what it takes, and every option it lists is taken -------------

#: A value for each option that takes one and has neither choices nor a default to try.
_VALUES = {"--fps": "10", "--seconds": "1", "--seed": "1", "--kinds": "peony"}


def _listed(name: str, capsys: pytest.CaptureFixture[str]) -> list[str]:
    """The options ``python -m demos NAME --help`` lists (argparse prints help to stdout)."""
    with pytest.raises(SystemExit) as exit_info:
        cli.main([name, "--help"], out=io.StringIO())
    assert exit_info.value.code == 0
    text = capsys.readouterr().out
    assert f"usage: python -m demos {name}" in text
    return [o for o in re.findall(r"^  (?:-h, )?(--[\w-]+)", text, re.M) if o != "--help"]


def _argv(name: str, demo: cli.Demo, option: str, tmp_path: Path) -> list[str]:
    """``name option [value]``: a valid value for each option, from its parser where it can."""
    action = cli._parser(cli.discover(), demo)._option_string_actions[option]
    if action.nargs == 0:  # a flag
        return [name, option]
    if option == "--size":
        value = "x".join(map(str, demo.size))
    elif option in ("--out", "--video", "--gif"):
        value = str(tmp_path / {"--out": "frames", "--video": "c.mp4", "--gif": "c.gif"}[option])
    elif action.choices:
        value = str(next(iter(action.choices)))
    elif option in _VALUES:
        value = _VALUES[option]
    else:
        assert action.default is not None, f"give {option} of {name} a value in _VALUES"
        value = str(action.default)
    return [name, option, value]


def _demo_names() -> list[str]:
    return sorted(n for n, d in cli.discover().items() if isinstance(d, cli.Demo))


@pytest.mark.parametrize("name", _demo_names())
def test_every_option_a_demos_help_lists_is_accepted(name, capsys, tmp_path, monkeypatch):
    # breakout, crumb, pinball and tradeoff listed --scene, --strobe, --window, --video, --gif,
    # --fps, --seconds and --seed, and then refused them. Each option listed is now parsed and
    # honoured (what would run is a stand-in: only the parsing and the refusals are real).
    import dataclasses

    import engine.render
    import engine.render.clips

    found = cli.discover()
    demo = found[name]
    assert isinstance(demo, cli.Demo)
    ran: list[str] = []
    if demo.run is not None:
        found = dict(found, **{name: dataclasses.replace(demo, run=lambda args: ran.append("run"))})
    monkeypatch.setattr(cli, "discover", lambda: found)
    monkeypatch.setattr(engine.render, "record", lambda *a, **k: ran.append("record") or _rec())
    monkeypatch.setattr(engine.render, "strobe", lambda *a, **k: ran.append("strobe") or Path())
    monkeypatch.setattr(engine.render, "play", lambda *a, **k: ran.append("play"))
    monkeypatch.setattr(engine.render.clips, "ffmpeg_exe", lambda: "ffmpeg")
    listed = _listed(name, capsys)
    assert "--size" in listed and "--out" in listed  # every demo takes these
    for option in listed:
        argv = _argv(name, demo, option, tmp_path)
        ran.clear()
        try:
            code = cli.main(argv, out=io.StringIO())
        except SystemExit as exc:  # a usage error
            code = exc.code
        err = capsys.readouterr().err
        assert code == 0 and ran, (argv, err)
        assert "cannot honour" not in err and "error" not in err, (argv, err)


def _rec() -> object:
    from engine.render import Recording

    return Recording(Path("out"), 1, 30, 1.0, (640, 360))


def test_the_games_and_the_charts_help_lists_only_what_they_take(capsys) -> None:
    assert _listed("tradeoff", capsys) == ["--size", "--out", "--overwrite", "--quick"]
    game = ["--fps", "--seconds", "--size", "--out", "--overwrite", "--window"]
    for name in ("breakout", "crumb", "pinball"):
        assert _listed(name, capsys) == [*game, "--seed"], name
    assert _listed("platformer", capsys) == game  # no dice: no --seed
    assert "--strobe" not in _listed("car", capsys)  # none of its scenes has a motion diagram
    assert "--strobe" in _listed("bounce", capsys)  # two of its three scenes have one


# -- --window where there is no display: the project's message alone -------------------------


@pytest.mark.parametrize("argv", [["alfred", "--scene", "lazy"], ["breakout"]])
def test_window_without_a_display_says_so_without_sdls_runtime_dir_line(argv):
    # With no display and no XDG_RUNTIME_DIR, SDL's Wayland driver printed "error:
    # XDG_RUNTIME_DIR is invalid or not set in the environment." before the project's message.
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in ("SDL_VIDEODRIVER", "DISPLAY", "WAYLAND_DISPLAY", "XDG_RUNTIME_DIR")
    }
    result = subprocess.run(
        [sys.executable, "-m", "demos", *argv, "--window"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 1, result.stderr
    assert "XDG_RUNTIME_DIR" not in result.stderr
    assert result.stderr.startswith("error: no window can open"), result.stderr
    assert "drop --window" in result.stderr


def test_sdl_gets_a_private_runtime_dir_only_where_there_is_none(monkeypatch):
    from engine.render import headless

    monkeypatch.delenv("XDG_RUNTIME_DIR", raising=False)
    with headless._runtime_dir():
        folder = Path(os.environ["XDG_RUNTIME_DIR"])
        assert folder.is_absolute() and folder.is_dir() and not list(folder.iterdir())
        assert folder.stat().st_mode & 0o077 == 0  # private: the user's alone
    assert "XDG_RUNTIME_DIR" not in os.environ and not folder.exists()
    monkeypatch.setenv("XDG_RUNTIME_DIR", "relative")  # invalid: not an absolute path
    with headless._runtime_dir():
        assert Path(os.environ["XDG_RUNTIME_DIR"]).is_absolute()
    assert os.environ["XDG_RUNTIME_DIR"] == "relative"
    monkeypatch.setenv("XDG_RUNTIME_DIR", "/run/user/1000")  # a session's own: left alone
    with headless._runtime_dir():
        assert os.environ["XDG_RUNTIME_DIR"] == "/run/user/1000"
