"""Fuzzing the command line: generated argument lists to ``demos.cli.main``.

Each list is parsed for real; what would run (recording, strobe, window, a demo's own run
hook) is replaced by a stand-in that checks the options it was handed are in range, so a
thousand lists take seconds. Outcomes allowed: a run with valid options (exit 0), help
(exit 0), or a usage error, exit 2, whose message names the option.

Examples per test: generated argument lists 1000, odd --out paths run for real 100.
This file: 1,100.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import io
import math
import re
from pathlib import Path
from typing import Any

import pytest
from fuzzing import fuzz
from hypothesis import given
from hypothesis import strategies as st

import engine.render
from demos import cli
from engine.render import Recording

DEMOS = ["alfred", "car", "crumb", "fireworks", "stability", "tradeoff"]
OPTIONS = ["--scene", "--fps", "--seconds", "--size", "--out", "--seed", "--wind", "--kinds"]
FLAGS = ["--overwrite", "--window", "--strobe", "--quick", "-h"]
VALUES = st.one_of(
    st.sampled_from(
        [
            "0",
            "1",
            "-1",
            "30",
            "1001",
            "nan",
            "inf",
            "-inf",
            "1e308",
            "1e-320",
            "1e999",
            "0x10",
            "3.5",
            "",
            " ",
            "640x360",
            "64x64",
            "0x0",
            "99999x1",
            "640X360",
            "-640x360",
            "lazy",
            "stroll",
            "show",
            "peony,ring",
            "nope",
            "héllo",
            "🐜",
            "-",
            "--",
            "9" * 40,
            "-" + "9" * 40,
        ]
    ),
    st.text(max_size=6),
    st.floats().map(repr),
    st.integers(-(10**30), 10**30).map(str),
)
TOKENS = st.one_of(st.sampled_from(OPTIONS + FLAGS), VALUES)


@st.composite
def argument_lists(draw: st.DrawFn) -> list[str]:
    argv: list[str] = []
    if draw(st.integers(0, 9)):  # mostly a real demo first
        argv.append(draw(st.sampled_from(DEMOS)))
    for _ in range(draw(st.integers(0, 5))):
        if draw(st.booleans()):
            argv += [draw(st.sampled_from(OPTIONS)), draw(VALUES)]
        else:
            argv.append(draw(TOKENS))
    return argv


class Ran:
    """What the stand-ins were asked to do."""

    calls: list[tuple[str, dict[str, Any]]] = []


def _check_run_options(fps: Any, seconds: Any, size: Any) -> None:
    assert fps is None or (isinstance(fps, int) and 1 <= fps <= 1000), fps
    assert seconds is None or (math.isfinite(seconds) and 0 < seconds <= 3600), seconds
    width, height = size
    assert isinstance(width, int) and isinstance(height, int)
    assert 64 <= width <= 8192 and 64 <= height <= 8192, size


def _fake_record(scene: Any, folder: Any, fps: int, seconds: Any, size: Any, **kw: Any) -> Any:
    _check_run_options(fps, seconds, size)
    assert str(folder) not in ("", ".")
    Ran.calls.append(("record", {"fps": fps, "seconds": seconds, "size": size}))
    return Recording(Path(folder), 1, fps, seconds or 1.0, size)


def _fake_strobe(scene: Any, path: Any, size: Any, **kw: Any) -> Path:
    _check_run_options(None, None, size)
    Ran.calls.append(("strobe", {"size": size}))
    return Path(path)


def _fake_play(scene: Any, fps: int, size: Any, seconds: Any) -> None:
    _check_run_options(fps, seconds, size)
    Ran.calls.append(("play", {"size": size}))


def _fake_run(args: Any) -> int:
    _check_run_options(args.fps, args.seconds, args.size)
    assert args.seed is None or (isinstance(args.seed, int) and args.seed >= 0)
    Ran.calls.append(("run", {"size": args.size}))
    return 0


@functools.cache
def _demos_with_stand_in_hooks() -> dict[str, Any]:
    return {
        name: dataclasses.replace(demo, run=_fake_run)
        if isinstance(demo, cli.Demo) and demo.run is not None
        else demo
        for name, demo in cli.discover().items()
    }


@contextlib.contextmanager
def stand_ins() -> Any:
    fake = _demos_with_stand_in_hooks()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(cli, "discover", lambda: fake)
        mp.setattr(engine.render, "record", _fake_record)
        mp.setattr(engine.render, "strobe", _fake_strobe)
        mp.setattr(engine.render, "play", _fake_play)
        yield


# An argparse usage error names the option ("argument --fps: ..."), the demo name
# ("argument demo: invalid choice ..."), stray tokens ("unrecognized arguments: ...") or an
# abbreviation that fits several options ("ambiguous option: --s could match ...").
_NAMED = re.compile(
    r"error: (argument (--[a-z]+|demo)(/--[a-z]+)?:|unrecognized arguments: |ambiguous option: "
    r"|the demo '[a-z]+' needs)"
)


@fuzz(1000)
@given(argv=argument_lists())
def test_any_argument_list_runs_with_valid_options_or_is_a_usage_error_naming_the_option(
    argv: list[str],
) -> None:
    out, err = io.StringIO(), io.StringIO()
    Ran.calls = []
    with stand_ins(), contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        try:
            code = cli.main(argv, out=out)
        except SystemExit as exc:
            code = exc.code
    if code == 2:
        assert _NAMED.search(err.getvalue()), (argv, err.getvalue())
        assert not Ran.calls  # nothing ran
    else:
        assert code == 0, (argv, code, err.getvalue())
        assert "Traceback" not in err.getvalue()
        if "-h" not in argv and any(a in DEMOS for a in argv):
            assert Ran.calls or "skipped" in out.getvalue(), (argv, out.getvalue())


@fuzz(100)
@given(
    kind=st.sampled_from(["file", "under_file", "nested", "unicode", "long", "existing"]),
    name=st.text(
        alphabet=st.characters(blacklist_categories=("Cs",), blacklist_characters="/\x00"),
        min_size=1,
        max_size=8,
    ).filter(lambda s: s not in (".", "..") and not s.startswith("-")),
)
def test_odd_output_folders_record_or_fail_with_exit_1_and_the_folder_named(
    tmp_path_factory: pytest.TempPathFactory, kind: str, name: str
) -> None:
    base = tmp_path_factory.mktemp("cli")
    if kind in ("file", "under_file"):
        (base / "f").write_bytes(b"x")
    folder = {
        "file": base / "f",
        "under_file": base / "f" / name,
        "nested": base / "a" / name / "b",
        "unicode": base / f"{name}-🐜-é",
        "long": base / ("n" * 300),
        "existing": base / "done",
    }[kind]
    argv = ["alfred", "--scene", "lazy", "--fps", "1", "--seconds", "0.5", "--size", "128x72"]
    argv += ["--out", str(folder)]
    if kind == "existing":
        assert cli.main(argv, out=io.StringIO()) == 0
        before = {p.name: p.read_bytes() for p in folder.iterdir()}
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        code = cli.main(argv, out=io.StringIO())
    if kind in ("nested", "unicode"):
        assert code == 0
        assert sorted(p.name for p in folder.iterdir()) == ["frame_00000.png"]
    else:
        assert code == 1, (kind, err.getvalue())
        assert err.getvalue().startswith("error: ") and str(folder)[:60] in err.getvalue()
        assert "Traceback" not in err.getvalue()
    if kind == "existing":  # never overwritten without --overwrite
        assert "--overwrite" in err.getvalue()
        assert {p.name: p.read_bytes() for p in folder.iterdir()} == before
