"""What the demos load from disk is shipped in the wheel, so `pip install .` runs them too."""

from __future__ import annotations

import fnmatch
from pathlib import Path

import pytest

from demos import alfred, car

tomllib = pytest.importorskip("tomllib")  # in the standard library from Python 3.11

ROOT = Path(__file__).resolve().parent.parent
CONFIG = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]


def _shipped(path: Path) -> bool:
    # setuptools ships a package's files that match its package-data globs (relative to it).
    package = path.parent.relative_to(ROOT).as_posix().replace("/", ".")
    included = any(fnmatch.fnmatch(package, g) for g in CONFIG["packages"]["find"]["include"])
    globs = CONFIG["package-data"].get(package, [])
    has_init = (path.parent / "__init__.py").is_file()
    return included and has_init and any(fnmatch.fnmatch(path.name, g) for g in globs)


def test_every_sprite_the_demos_load_is_package_data() -> None:
    sprites = [
        alfred.ASSETS / "ant.png",
        alfred.ASSETS / "ant_small.png",
        alfred.ASSETS / "ant_top.png",
        car.ASSETS / "car.png",
    ]
    for sprite in sprites:
        assert sprite.is_file(), sprite
        assert _shipped(sprite), f"{sprite} would be missing from an installed wheel"


def test_the_readme_pictures_stay_out_of_the_wheel() -> None:
    pictures = sorted((ROOT / "assets" / "readme").glob("*.png"))
    assert pictures
    assert not any(_shipped(p) for p in pictures)
