"""The README's stills are what their demos draw now: each is made again as
``python assets/make_readme_images.py NAME`` makes it, and compared with the one in
``assets/readme/`` pixel for pixel (the demos draw the same frames run after run, on either
path). Four of them had gone stale unseen, a change of the physics or of a label later
(found 2026-12-04: the ball pit's still showed all 2,000 balls asleep at 5 s, where they
sleep from 5.33 s). A change that moves a still makes it again with that command."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pygame
import pytest

from assets.make_readme_images import HERE, STILLS, main_images
from tests.paths import drawn_on_numpy  # noqa: F401 (used by name below)

#: The drawing checks run on the numpy path alone (tests.paths.drawn_on_numpy).
pytestmark = pytest.mark.usefixtures("drawn_on_numpy")


def pixels(path: Path) -> np.ndarray:
    """An image's pixels (width, height, 3), as pygame reads them."""
    return pygame.surfarray.array3d(pygame.image.load(str(path)))


@pytest.mark.parametrize("name", [name for name, _, _ in STILLS])
def test_the_readme_still_is_what_its_demo_draws_now(name: str, tmp_path: Path) -> None:
    main_images(out=tmp_path, only=[name])
    made, kept = pixels(tmp_path / f"{name}.png"), pixels(HERE / "readme" / f"{name}.png")
    assert made.shape == kept.shape
    differ = int(np.any(made != kept, axis=2).sum())
    assert differ == 0, (
        f"{differ} pixels of {name}.png differ from what `python assets/make_readme_images.py "
        f"{name}` makes now: make it again, and look at it"
    )
