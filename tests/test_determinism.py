"""Determinism: the same command twice gives byte-identical frames.

The other demos have theirs beside their own tests (alfred, car, fireworks and crumb in
test_alfred.py, test_car.py, test_fireworks.py and test_crumb.py; tradeoff's CSV in
test_tradeoff.py); this file holds the ones that had none.
"""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from demos.cli import main


def _record(folder: Path, *args: str) -> list[bytes]:
    assert (
        main([*args, "--size", "320x200", "--fps", "5", "--out", str(folder)], io.StringIO()) == 0
    )
    return [p.read_bytes() for p in sorted(folder.glob("frame_*.png"))]


@pytest.mark.parametrize("scene", ["orbits", "limits"])
def test_the_stability_demo_twice_gives_identical_frames(tmp_path: Path, scene: str) -> None:
    args = ("stability", "--scene", scene, "--seconds", "6")
    first, second = _record(tmp_path / "a", *args), _record(tmp_path / "b", *args)
    assert len(first) == 31  # 6 s at 5 fps, both ends shown
    assert first == second
    assert len(set(first)) > 10  # the frames move: identical runs of a still would prove little
