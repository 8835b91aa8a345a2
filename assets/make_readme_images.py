"""The README's stills, made by the project's own commands: ``python assets/make_readme_images.py``.

``python assets/make_readme_images.py ballpit cradle`` makes only the stills named.

Each still is one frame of a demo recorded by ``python -m demos ...`` at a small size (the
README shows them; they are kept small on purpose), copied to ``assets/readme/``. The chart
is ``python -m demos tradeoff --quick``'s work-precision chart, scaled down.
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

import pygame  # noqa: E402

from demos.cli import main  # noqa: E402

SIZE = "640x360"
FPS = 10
#: (image name, command-line arguments, which frame to keep)
STILLS = [
    ("alfred-sprint", ["alfred", "--scene", "sprint"], 44),
    ("alfred-paper", ["alfred", "--scene", "paper"], 20),
    ("car-main-street", ["car", "--scene", "main-street"], 120),
    ("fireworks", ["fireworks", "--scene", "show", "--seed", "7"], 45),
    ("stability-orbits", ["stability", "--scene", "orbits"], 60),
    ("crumb", ["crumb", "--seconds", "8"], 62),
    ("breakout", ["breakout", "--seconds", "16"], 150),
    ("bounce", ["bounce", "--scene", "drop"], 90),
    ("ballpit", ["ballpit"], 50),
    ("cradle", ["cradle", "--scene", "heavy"], 20),
    ("galton", ["galton", "--seconds", "300"], 3000),
    ("pendulum", ["pendulum", "--scene", "double", "--seconds", "17"], 170),
    ("crates", ["crates"], 4),
    ("incline", ["incline", "--scene", "race"], 24),
    ("stack", ["stack", "--scene", "dominoes"], 25),
    ("pinball", ["pinball", "--seconds", "5", "--size", "216x384"], 44),  # upright
    ("hinges", ["hinges", "--scene", "rod"], 45),
    ("platformer", ["platformer", "--seconds", "12"], 110),  # riding the platform
]


def main_images(out: Path = HERE / "readme", only: list[str] | None = None) -> None:
    """Record each still's demo to a temporary folder and keep its chosen frame (``only``:
    just the stills of those names, and no chart unless "work-precision" is among them)."""
    known = [name for name, _, _ in STILLS] + ["work-precision"]
    unknown = sorted(set(only or ()) - set(known))
    if unknown:
        raise SystemExit(f"no still named {', '.join(unknown)}; the stills: {', '.join(known)}")
    out.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for name, args, frame in STILLS:
            if only and name not in only:
                continue
            folder = Path(tmp) / name
            size = [] if "--size" in args else ["--size", SIZE]  # a still may give its own
            code = main([*args, *size, "--fps", str(FPS), "--out", str(folder)])
            if code != 0:
                raise SystemExit(f"{' '.join(args)} failed with exit code {code}")
            frames = sorted(folder.rglob("frame_*.png"))
            shutil.copyfile(frames[min(frame, len(frames) - 1)], out / f"{name}.png")
            print(f"wrote {out / name}.png")
        if only and "work-precision" not in only:
            return
        chart = Path(tmp) / "tradeoff"
        if main(["tradeoff", "--quick", "--out", str(chart)]) != 0:
            raise SystemExit("tradeoff --quick failed")
        image = pygame.image.load(str(chart / "work_precision.png"))
        small = pygame.transform.smoothscale(image, (800, 450))
        pygame.image.save(small, str(out / "work-precision.png"))
        print(f"wrote {out / 'work-precision.png'}")


if __name__ == "__main__":
    main_images(only=sys.argv[1:])
