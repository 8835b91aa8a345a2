"""The command line: ``python -m demos`` lists the demos, ``python -m demos NAME`` runs one.

Every module ``demos/<name>.py`` that defines a module-level ``DEMO = Demo(...)`` is found
automatically, so a new demo needs no change here::

    # demos/drop.py
    from demos.cli import Demo
    DEMO = Demo(name="drop", summary="A ball falls under gravity", scenes={"drop": DropScene})

A demo made of scenes gets the common options: it is recorded headless to numbered PNG frames
(``out/<demo>/<scene>/frame_00000.png`` ...) and/or to an MP4 or GIF clip (``--video``,
``--gif``; with them, frames are written too only if ``--out`` is given), shown in a window
(``--window``) or drawn as one still motion diagram per scene (``--strobe``). A demo that is
not made of scenes (a chart, a table) gives a ``run(args)`` hook instead, and can add its own
options with ``add_arguments(parser)``.

Every demo is given the same shared options (``SHARED``); one it cannot honour is refused,
the same way for every demo: a usage error naming the option and saying why (exit 2). A demo
with a ``run`` hook says which it honours (``Demo.takes``); a demo made of scenes honours them
all, except ``--strobe`` for a scene with no motion diagram, and the options that mean nothing
beside another (``--out`` in a window, ``--fps`` for a still). A demo's ``--help`` lists only
the shared options it honours (``offered``); the others are parsed still, to be refused.

Exit codes: 0 done, 1 the run failed (a frame or clip could not be written, the output folder
already holds frames or the clip's file exists, no display for ``--window``, the simulation
diverged), 2 a usage error (including ``--video`` or ``--gif`` without the ``video`` extra).
"""

from __future__ import annotations

import argparse
import importlib
import math
import pkgutil
import signal
import sys
import traceback
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

__all__ = ["SHARED", "Demo", "discover", "main", "number_option", "offered", "parse_size"]

#: Modules in the demos package that are not demos.
_NOT_DEMOS = frozenset({"cli", "games", "warned"})

#: The options every demo's command line has (its own come after them).
SHARED = (
    "--scene",
    "--fps",
    "--seconds",
    "--size",
    "--out",
    "--video",
    "--gif",
    "--overwrite",
    "--window",
    "--strobe",
    "--seed",
)


@dataclass(frozen=True)
class Demo:
    """A demo the command line can run.

    ``scenes`` maps a scene name to a factory: any callable with no arguments returning an
    :class:`engine.render.Scene` (usually the Scene subclass itself). ``add_arguments(parser)``
    adds the demo's own options; ``configure(scene, args)`` applies them to each scene before it
    is built. ``run(args)``, if given, replaces recording: it is called with the parsed options
    and returns an exit code (None means 0), for demos that make a chart rather than frames.
    ``takes``: the shared options (``SHARED``) a ``run`` hook honours; any other is refused
    before it runs (a demo of scenes honours them all). ``size``: the canvas (px) when
    ``--size`` is not given; ``min_size`` the smallest ``--size`` a run hook can draw on.
    """

    name: str
    summary: str
    scenes: Mapping[str, Callable[[], Any]] = field(default_factory=dict)
    add_arguments: Callable[[argparse.ArgumentParser], None] | None = None
    configure: Callable[[Any, argparse.Namespace], None] | None = None
    run: Callable[[argparse.Namespace], int | None] | None = None
    takes: frozenset[str] = frozenset(SHARED)
    size: tuple[int, int] = (640, 360)
    min_size: tuple[int, int] = (64, 64)

    def __post_init__(self) -> None:
        if not self.name or not self.name.replace("_", "").replace("-", "").isalnum():
            raise ValueError(f"Demo name must be a word such as 'alfred', got {self.name!r}")
        if not self.scenes and self.run is None:
            raise ValueError(f"Demo {self.name!r} needs scenes or a run hook")
        unknown = set(self.takes) - set(SHARED)
        if unknown:
            raise ValueError(
                f"Demo {self.name!r} takes must name shared options ({', '.join(SHARED)}), "
                f"got {sorted(unknown)}"
            )


@dataclass(frozen=True)
class _Broken:
    """A demo module that failed to import: listed with its error, raised again if run."""

    module: str
    error: str


def discover() -> dict[str, Demo | _Broken]:
    """Import every module of the demos package and collect their ``DEMO``s by name."""
    import demos

    found: dict[str, Demo | _Broken] = {}
    for info in sorted(pkgutil.iter_modules(demos.__path__), key=lambda m: m.name):
        if info.name.startswith("_") or info.name in _NOT_DEMOS:
            continue
        try:
            module = importlib.import_module(f"demos.{info.name}")
        except Exception:
            found[info.name] = _Broken(info.name, traceback.format_exc())
            continue
        demo = getattr(module, "DEMO", None)
        if isinstance(demo, Demo):
            found[demo.name] = demo
    return found


# --- argument types: each error names what is valid -------------------------------------------


def _fps(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if not 1 <= value <= 1000:
        raise argparse.ArgumentTypeError(
            f"must be a whole number of frames per second from 1 to 1000, got {text!r}"
        )
    return value


def number_option(
    low: float, high: float, meaning: str, *, low_open: bool = False
) -> Callable[[str], float]:
    """An argparse ``type``: a finite number from ``low`` to ``high``, else a usage error.

    ``meaning`` completes "must be ..." in the message, e.g. "a wind speed in m/s".
    ``low_open`` excludes ``low`` itself (for quantities that must be > 0).
    """
    bound = f"> {low:g} and at most {high:g}" if low_open else f"from {low:g} to {high:g}"

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        above = value > low if low_open else value >= low
        if not (math.isfinite(value) and above and value <= high):
            raise argparse.ArgumentTypeError(f"must be {meaning}, {bound}, got {text!r}")
        return value

    return parse


_seconds = number_option(0, 3600, "a number of simulated seconds", low_open=True)


def parse_size(text: str) -> tuple[int, int]:
    """'640x360' -> (640, 360); ArgumentTypeError unless both are whole pixels from 64 to 8192."""
    parts = text.lower().split("x")
    try:
        width, height = (int(p) for p in parts)
    except ValueError:
        width = height = 0
    if not (64 <= width <= 8192 and 64 <= height <= 8192):
        raise argparse.ArgumentTypeError(
            f"must be WIDTHxHEIGHT in whole pixels from 64 to 8192, such as 640x360, got {text!r}"
        )
    return width, height


def _seed(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:  # numpy's generators take seeds >= 0 only
        raise argparse.ArgumentTypeError(f"must be a whole number >= 0, got {text!r}")
    return value


def _out(text: str) -> Path:
    if not text or "\x00" in text:  # "" would be the current folder: a surprise for frames
        raise argparse.ArgumentTypeError(f"must be a folder path, got {text!r}")
    return Path(text)


def _clip(kind: str) -> Callable[[str], Path]:
    # An argparse type for --video / --gif: a file name with the clip's suffix. Its folder is
    # created if missing, as --out's is.
    suffix = f".{kind}"

    def parse(text: str) -> Path:
        path = Path(text) if text and "\x00" not in text else None
        if path is None or path.suffix.lower() != suffix or path.name.lower() == suffix:
            raise argparse.ArgumentTypeError(
                f"must be a file name ending in {suffix}, such as out/sprint{suffix}, got {text!r}"
            )
        if path.is_dir():
            raise argparse.ArgumentTypeError(
                f"must be a file name ending in {suffix}, got the folder {text!r}"
            )
        return path

    return parse


def offered(demo: Demo) -> frozenset[str]:
    """The shared options ``demo``'s ``--help`` lists: those it honours (``Demo.takes``),
    without ``--strobe`` for a demo of scenes none of which draws a motion diagram."""
    if demo.scenes and not any(_has_strobe(f) for f in demo.scenes.values()):
        return demo.takes - {"--strobe"}
    return demo.takes


def _about(demo: Demo | None) -> str:
    """The description at the top of the help: what a run makes, from what the demo takes."""
    if demo is None:
        return "Run a demo: headless to PNG frames (default), in a window, or as stills."
    if demo.scenes:
        modes = "in a window, or as stills" if "--strobe" in offered(demo) else "or in a window"
        return f"{demo.name}: {demo.summary}. Run headless to PNG frames (default), {modes}."
    if "--window" in demo.takes:
        return f"{demo.name}: {demo.summary}. Run headless to PNG frames (default), or in a window."
    return f"{demo.name}: {demo.summary}."


def _parser(
    demos: Mapping[str, Demo | _Broken], demo: Demo | None, typed: bool = True
) -> argparse.ArgumentParser:
    """The parser for ``demo`` (None: the top level). ``typed=False`` leaves every value a
    string: the first pass, which only finds the demo, then checks no value.

    Every shared option is parsed, but a demo's help shows only those it honours
    (:func:`offered`): one it does not is refused after parsing, saying why, as before."""

    def kind(convert: Callable[[str], Any]) -> Callable[[str], Any]:
        return convert if typed else str

    shown = frozenset(SHARED) if demo is None else offered(demo)

    def said(option: str, text: str) -> str:
        return text if option in shown else argparse.SUPPRESS

    scenes = demo is None or bool(demo.scenes)  # run hooks write what they write, not frames
    parser = argparse.ArgumentParser(
        prog="python -m demos" if demo is None else f"python -m demos {demo.name}",
        description=_about(demo),
        epilog="Run without a demo name to list the demos.",
    )
    parser.add_argument(
        "demo",
        nargs="?",
        choices=sorted(demos),
        # In a demo's own help the program line already names it.
        help="the demo to run" if demo is None else argparse.SUPPRESS,
    )
    # --scene is known in the first pass too, so its value is never taken for the demo's name.
    parser.add_argument(
        "--scene",
        choices=list(demo.scenes) if demo is not None and demo.scenes else None,
        help=said("--scene", "the scene to run (default: every scene in turn)"),
    )
    parser.add_argument(
        "--fps",
        type=kind(_fps),
        help=said("--fps", "frames per second (default 30; 60 in a window)"),
    )
    parser.add_argument(
        "--seconds",
        type=kind(_seconds),
        help=said("--seconds", "simulated seconds to show (default: the scene's own)"),
    )
    size = demo.size if demo is not None else (640, 360)
    parser.add_argument(
        "--size",
        type=kind(parse_size),
        help=said("--size", f"WIDTHxHEIGHT in pixels ({size[0]}x{size[1]})"),
    )
    parser.add_argument(
        "--out",
        type=kind(_out),
        help=said(
            "--out",
            "output folder for the PNG frames (default: out/<demo>/<scene>/; with --video or "
            "--gif, frames are written only if --out is given)"
            if scenes
            else f"output folder (default: out/{demo.name if demo else '<demo>'}/)",
        ),
    )
    parser.add_argument(
        "--video",
        type=kind(_clip("mp4")),
        metavar="PATH.mp4",
        help=said(
            "--video",
            "also write an H.264 MP4 clip, streamed as the frames are drawn (several scenes: "
            'PATH-<scene>.mp4); needs pip install -e ".[video]"',
        ),
    )
    parser.add_argument(
        "--gif",
        type=kind(_clip("gif")),
        metavar="PATH.gif",
        help=said(
            "--gif",
            "also write a looping GIF with its own palette (several scenes: PATH-<scene>.gif); "
            'needs pip install -e ".[video]"',
        ),
    )
    parser.add_argument(
        "--overwrite",
        action="store_true",
        help=said(
            "--overwrite",
            "replace frames already in the output folder and clips already at --video/--gif"
            if scenes
            else "replace what the output folder already holds",
        ),
    )
    # argparse cannot format the usage of a group with a hidden member (an AssertionError in
    # Python 3.11): the two are exclusive in the parser only where both are shown (where one is
    # hidden, giving it is refused anyway), and not in the first pass, so that the demo's own
    # parser is the one to say what is wrong.
    both = typed and {"--window", "--strobe"} <= shown
    mode = parser.add_mutually_exclusive_group() if both else parser
    mode.add_argument(
        "--window", action="store_true", help=said("--window", "play in a real-time window")
    )
    mode.add_argument(
        "--strobe",
        action="store_true",
        help=said("--strobe", "one still motion diagram per scene (strobe.png)"),
    )
    parser.add_argument(
        "--seed",
        type=kind(_seed),
        help=said("--seed", "random seed, for demos with randomness (default: the scene's)"),
    )
    if demo is not None and demo.add_arguments is not None:
        demo.add_arguments(parser)
    return parser


def _list(demos: Mapping[str, Demo | _Broken], out: TextIO) -> None:
    width = max((len(name) for name in demos), default=0)
    print("Demos (run one with: python -m demos NAME [--scene S] [--window] [--strobe]):", file=out)
    for name, demo in demos.items():
        if isinstance(demo, _Broken):
            last = demo.error.strip().splitlines()[-1]
            print(f"  {name:<{width}}  (broken: {last})", file=out)
            continue
        scenes = f"  [scenes: {', '.join(demo.scenes)}]" if demo.scenes else ""
        print(f"  {name:<{width}}  {demo.summary}{scenes}", file=out)


def _output_folder(args: argparse.Namespace, demo: Demo, scene_name: str, many: bool) -> Path:
    # --out names the folder for one scene; with several scenes each gets a subfolder of it.
    if args.out is None:
        return Path("out") / demo.name / scene_name
    return args.out / scene_name if many else args.out


def _clip_path(path: Path | None, scene_name: str, many: bool) -> Path | None:
    # --video / --gif name the clip of one scene; with several, each scene's name is added.
    if path is None or not many:
        return path
    return path.with_name(f"{path.stem}-{scene_name}{path.suffix}")


def _frames(count: int) -> str:
    """'1 frame', '2 frames'."""
    return f"{count} frame" if count == 1 else f"{count} frames"


def _run_scenes(demo: Demo, args: argparse.Namespace, out: TextIO) -> int:
    from engine.render import play, record, strobe
    from engine.render.clips import check_clip_path

    names = [args.scene] if args.scene else list(demo.scenes)
    many = len(names) > 1
    clips = args.video is not None or args.gif is not None
    if clips:
        # Every clip is checked before the first scene starts: no half-done batch.
        for scene_name in names:
            for kind, path in (("mp4", args.video), ("gif", args.gif)):
                if path is not None:
                    check_clip_path(_clip_path(path, scene_name, many), kind, args.overwrite)
    for scene_name in names:
        scene = demo.scenes[scene_name]()
        if args.seed is not None:
            scene.seed = args.seed
        if demo.configure is not None:
            demo.configure(scene, args)
        label = f"{demo.name}/{scene_name}"
        if args.window:
            play(scene, fps=args.fps or 60, size=args.size, seconds=args.seconds)
            continue
        folder = _output_folder(args, demo, scene_name, many)
        if args.strobe:
            if not scene.has_strobe:
                print(f"{label}: no motion diagram for this scene, skipped", file=out)
                continue
            path = strobe(scene, folder / "strobe.png", size=args.size, overwrite=args.overwrite)
            print(f"{label}: wrote the motion diagram {path}", file=out)
            continue
        rec = record(
            scene,
            folder if not clips or args.out is not None else None,
            fps=args.fps or 30,
            seconds=args.seconds,
            size=args.size,
            overwrite=args.overwrite,
            video=_clip_path(args.video, scene_name, many),
            gif=_clip_path(args.gif, scene_name, many),
        )
        width, height = rec.size
        timing = f"{rec.fps} fps, {rec.seconds:g} s"
        if rec.folder is not None:
            print(
                f"{label}: wrote {_frames(rec.count)} ({width}x{height}, {timing}) to {rec.folder}"
                f"{'/' if not str(rec.folder).endswith('/') else ''}frame_00000.png ...",
                file=out,
            )
        if rec.video is not None:
            video_w, video_h = rec.video_size
            cut = "" if rec.video_size == rec.size else f", cut from {width}x{height} to even sides"
            print(
                f"{label}: wrote the video {rec.video} (H.264 MP4, {video_w}x{video_h}{cut}, "
                f"{_frames(rec.count)}, {timing}, {rec.video.stat().st_size:,} bytes)",
                file=out,
            )
        if rec.gif is not None:
            print(
                f"{label}: wrote the GIF {rec.gif} ({width}x{height}, {_frames(rec.count)}, "
                f"{timing}, {rec.gif.stat().st_size:,} bytes)",
                file=out,
            )
    return 0


def _exists(exc: FileExistsError) -> str:
    """What is in the way, and the option that would replace it (not the Python argument)."""
    path = getattr(exc, "path", None)
    count = getattr(exc, "count", None)
    if path is None:
        return str(exc)
    if count is not None:
        return (
            f"{path} already holds {count} frame(s); add --overwrite to replace them, or "
            f"choose another folder with --out"
        )
    return f"{path} already exists; add --overwrite to replace it, or choose another name"


def _given(args: argparse.Namespace, option: str) -> bool:
    """Whether the shared ``option`` (such as "--fps") was given on the command line."""
    value = getattr(args, option[2:])
    return value is not None and value is not False


def _refuse_what_cannot_be_honoured(
    parser: argparse.ArgumentParser, demo: Demo, args: argparse.Namespace
) -> None:
    """A usage error (exit 2) for a shared option ``demo`` cannot honour, saying why."""
    given = [option for option in SHARED if _given(args, option)]
    for option in given:
        if option not in demo.takes:
            takes = ", ".join(o for o in SHARED if o in demo.takes) or "none of them"
            why = {
                "--scene": "it has no scenes to choose from",
                "--strobe": "it has no motion diagram",
                "--video": "it has no scenes to record",
                "--gif": "it has no scenes to record",
            }.get(option, "it does not use it")
            parser.error(
                f"argument {option}: the demo {demo.name!r} cannot honour it ({why}); of the "
                f"shared options it takes {takes}"
            )
    pairs = [
        ("--out", "--window", "a window writes nothing"),
        ("--overwrite", "--window", "a window writes nothing"),
        ("--video", "--window", "a clip is recorded headless"),
        ("--gif", "--window", "a clip is recorded headless"),
        ("--video", "--strobe", "a motion diagram is one still picture"),
        ("--gif", "--strobe", "a motion diagram is one still picture"),
        ("--fps", "--strobe", "a motion diagram is one still picture"),
        ("--seconds", "--strobe", "a motion diagram shows the scene's own times"),
    ]
    for option, mode, why in pairs:
        if option in given and mode in given:
            parser.error(f"argument {option}: not allowed with argument {mode} ({why})")
    if args.strobe and demo.scenes:
        # Among several scenes, those without one are skipped (and say so); none at all, or
        # the one scene asked for without one, is refused.
        names = [args.scene] if args.scene else list(demo.scenes)
        with_one = [n for n in demo.scenes if _has_strobe(demo.scenes[n])]
        if not any(n in with_one for n in names):
            which = f"the scene {args.scene!r}" if args.scene else f"the demo {demo.name!r}"
            others = f" (scenes with one: {', '.join(with_one)})" if with_one else ""
            parser.error(f"argument --strobe: {which} has no motion diagram{others}")


def _has_strobe(factory: Callable[[], Any]) -> bool:
    """Whether the scene a factory makes draws a motion diagram (without building it)."""
    from engine.render import Scene

    kind = factory if isinstance(factory, type) else type(factory())
    return issubclass(kind, Scene) and kind.draw_strobe is not Scene.draw_strobe


def main(argv: Sequence[str] | None = None, out: TextIO | None = None) -> int:
    """Run the command line with ``argv`` (default: sys.argv[1:]); return the exit code."""
    out = sys.stdout if out is None else out
    argv = list(sys.argv[1:] if argv is None else argv)
    demos = discover()
    # First pass: which demo? Its scenes and own options shape the full parser, so a help
    # request waits for the second pass: `python -m demos tradeoff --help` then lists the
    # tradeoff demo's own options too.
    helping = [arg for arg in argv if arg in ("-h", "--help")]
    first, _ = _parser(demos, None, typed=False).parse_known_args(
        [a for a in argv if a not in helping]
    )
    if first.demo is None:
        if helping:
            _parser(demos, None).print_help(out)
            print(file=out)
        elif argv:
            _parser(demos, None).parse_args(argv)  # report stray options as usage errors
        _list(demos, out)
        return 0
    demo = demos[first.demo]
    if isinstance(demo, _Broken):
        print(f"error: the demo {first.demo!r} failed to import:\n{demo.error}", file=sys.stderr)
        return 1
    parser = _parser(demos, demo)
    args = parser.parse_args(argv)
    _refuse_what_cannot_be_honoured(parser, demo, args)
    given_size = args.size is not None
    args.size = args.size or demo.size
    clip_option = "--video" if args.video is not None else "--gif" if args.gif is not None else None
    if clip_option is not None:
        from engine.render.clips import (
            GIF_MAX_FPS,
            ClipWriteError,
            EncoderUnavailableError,
            ffmpeg_exe,
        )

        if args.gif is not None and (args.fps or 30) > GIF_MAX_FPS:
            parser.error(
                f"argument --gif: a GIF plays at most {GIF_MAX_FPS} fps in browsers (its frame "
                f"times are whole hundredths of a second), got --fps {args.fps}; use --fps "
                f"{GIF_MAX_FPS} or less"
            )
        try:
            ffmpeg_exe()
        except EncoderUnavailableError as exc:
            parser.error(f"argument {clip_option}: {exc}")
        except ClipWriteError as exc:  # installed, but its binary is gone
            print(f"error: {exc}", file=sys.stderr)
            return 1
    for name in [args.scene] if args.scene else list(demo.scenes):
        need_w, need_h = getattr(demo.scenes[name], "min_size", (0, 0))
        if args.size[0] < need_w or args.size[1] < need_h:
            parser.error(
                f"argument --size: the scene {name!r} needs at least {need_w}x{need_h} px, "
                f"got {args.size[0]}x{args.size[1]}"
            )
    need_w, need_h = demo.min_size
    if given_size and (args.size[0] < need_w or args.size[1] < need_h):
        parser.error(
            f"argument --size: the demo {demo.name!r} needs at least {need_w}x{need_h} px, "
            f"got {args.size[0]}x{args.size[1]}"
        )

    from engine.render import (
        ClipExistsError,
        ClipWriteError,
        DisplayUnavailableError,
        EncoderUnavailableError,
        FramesExistError,
        FrameWriteError,
        RecordingInterrupted,
    )
    from engine.stability import SimulationDiverged

    # SIGTERM (a `kill`, a CI timeout) would end the process on the spot, mid-frame and
    # without a word; while a demo runs it stops it the way Ctrl-C does instead.
    signals: list[int] = []

    def stop(signum: int, _frame: object) -> None:
        signals.append(signum)
        raise KeyboardInterrupt

    try:
        previous = signal.signal(signal.SIGTERM, stop)
    except ValueError:  # not the main thread: leave signals alone
        previous = None
    # On the fast path, a kernel's first run compiles it (engine.kernels): say why we wait.
    from engine import kernels

    kernels.waiting = lambda message: print(f"{demo.name}: {message} ...", file=out, flush=True)
    try:
        if demo.run is not None:
            code = demo.run(args)
            return 0 if code is None else int(code)
        return _run_scenes(demo, args, out)
    except (FramesExistError, ClipExistsError) as exc:
        print(f"error: {_exists(exc)}", file=sys.stderr)
        return 1
    except (
        FrameWriteError,
        ClipWriteError,
        EncoderUnavailableError,
        DisplayUnavailableError,
        SimulationDiverged,
    ) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt as exc:
        how = "terminated (SIGTERM)" if signals else "interrupted"
        if isinstance(exc, RecordingInterrupted):
            print(f"{how}: {exc}", file=sys.stderr)
        else:
            print(f"{how}: the frames written so far are whole", file=sys.stderr)
        # The shell's convention: 128 + the signal's number.
        return 128 + (signals[0] if signals else signal.SIGINT)
    finally:
        kernels.waiting = None
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
