"""The numpy path's soft step takes a game's few contacts in plain Python (the contacts as the
solver's rows, their warm starts kept, the touching report, the faces that turn:
engine.pipeline.game_step, up to ``_FEW_FOUND`` manifolds) and many in numpy calls: both give
the same bits, checked by playing the platformer both ways."""

from __future__ import annotations

import numpy as np
import pytest

from demos import platformer_scene as ps
from engine.pipeline import game_step


def _played(steps: int) -> tuple[np.ndarray, list[int], list[str]]:
    """The platformer on the numpy path's soft step, its script played ``steps`` steps: every
    body's x, y, angle, velocity and angular velocity; the coins' order; the touching
    contacts' keys, points, normals and impulses at each step's end, as text."""
    game = ps.build("numpy", solver="soft")
    reports = []
    for _ in range(steps):
        game.step(ps.DT)
        report = game.world._s.game.report
        reports.append(report.keys.tobytes().hex() + report.packed.tobytes().hex())
    state = np.array(
        [(b.pos.x, b.pos.y, b.angle, b.vel.x, b.vel.y, b.angular_velocity)
         for b in game.world.bodies]
    )  # fmt: skip
    return state, list(game.collected), reports


@pytest.mark.parametrize("path", ["numpy"])
def test_a_few_contacts_in_plain_python_give_the_numpy_calls_bits(
    path: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    few = _played(200)
    monkeypatch.setattr(game_step, "_FEW_FOUND", -1)  # every step's contacts by numpy calls
    many = _played(200)
    assert np.array_equal(few[0], many[0])
    assert few[1] == many[1]
    assert few[2] == many[2]
    assert len(few[1]) >= 2  # the run took coins: the player met the level
