"""Fireworks: payload rules as data, seeded frames, bad input named."""

from __future__ import annotations

import io

import numpy as np
import pygame
import pytest

from demos.cli import main
from demos.fireworks import KINDS, ROCKETS, FireworksScene, kind_index
from engine.render import init_headless, iter_frames


def surfaces(seed: int, seconds: float = 2.4, **kw) -> list[bytes]:
    scene = FireworksScene(**kw)
    scene.seed = seed
    shots = iter_frames(scene, 5, seconds, size=(256, 144))
    return [pygame.image.tobytes(s, "RGB") for _, _, s in shots]


def test_same_seed_gives_byte_identical_frames_and_another_seed_does_not() -> None:
    a, b, c = surfaces(7), surfaces(7), surfaces(8)
    assert a == b
    assert a[-1] != c[-1]


def test_frames_are_not_one_flat_colour_and_show_sparks() -> None:
    last = np.frombuffer(surfaces(3)[-1], dtype=np.uint8).reshape(144, 256, 3)
    assert len(np.unique(last.reshape(-1, 3), axis=0)) > 50
    # Sparks are brighter than any sky pixel: the sky is dark blue (< 60 in every channel).
    sky = last[20:90]
    assert (sky.max(axis=2) > 150).sum() > 20


@pytest.mark.parametrize("parent", ["peony", "ring", "crossette"])
def test_a_burst_follows_its_payload_rule(parent: str) -> None:
    init_headless()
    scene = FireworksScene()
    scene.build((64, 36))
    scene.particles.clear()
    v_parent = np.array([3.0, -1.0])
    scene.burst(np.array([5.0, 20.0]), v_parent, kind_index(parent))
    p = scene.particles
    assert len(p) == sum(n for _, n in KINDS[kind_index(parent)].payload)
    for child, count in KINDS[kind_index(parent)].payload:
        rule = KINDS[kind_index(child)]
        mine = p.kinds == kind_index(child)
        assert mine.sum() == count
        spread = np.hypot(*(p.velocities[mine] - v_parent).T)  # speed added to the parent's
        low, high = rule.speed
        assert spread.max() <= high + 1e-9
        if rule.pattern == "ring":  # a flat ring: every spark at a speed in the range
            assert spread.min() >= low - 1e-9
        assert (p.lifetimes[mine] >= rule.fuse[0]).all()
        assert (p.lifetimes[mine] <= rule.fuse[1]).all()
        np.testing.assert_array_equal(p.positions[mine], np.tile([5.0, 20.0], (count, 1)))


def test_a_rocket_bursts_when_its_fuse_burns_out() -> None:
    init_headless()
    scene = FireworksScene(kinds=["peony"])
    scene.build((64, 36))
    scene.next_launch = 1e9  # only the two rockets fired at t = 0
    p = scene.particles
    rockets = p.kinds == kind_index("peony")
    assert rockets.sum() == 2  # the two at t = 0
    fuse = p.lifetimes[rockets].max()
    while p.t < fuse + 2 * p.dt:
        scene.step(p.dt)
    assert (p.kinds == kind_index("red star")).sum() == 2 * 260
    assert not (p.kinds == kind_index("peony")).any()


def test_every_payload_names_a_known_kind() -> None:
    for kind in KINDS:
        for child, count in kind.payload:
            assert KINDS[kind_index(child)].name == child and count > 0


def test_unknown_kind_is_refused_with_the_valid_names() -> None:
    with pytest.raises(ValueError, match=r"'sparkler'.*peony"):
        kind_index("sparkler")
    with pytest.raises(ValueError, match=r"'sparkler'.*valid"):
        FireworksScene(kinds=["sparkler"])
    with pytest.raises(ValueError, match=r"'gold star' is not a rocket.*peony"):
        FireworksScene(kinds=["gold star"])
    assert "peony" in ROCKETS


@pytest.mark.parametrize(
    ("wind", "error", "words"),
    [
        ((1.0, 2.0), TypeError, ["wind", "(1.0, 2.0)", "number"]),
        ("strong", TypeError, ["wind", "'strong'", "number"]),
        (-2.0, ValueError, ["wind", "-2.0", ">= 0"]),
        (float("inf"), ValueError, ["wind", "inf"]),
    ],
)
def test_bad_wind_is_refused_naming_it(wind: object, error: type, words: list[str]) -> None:
    with pytest.raises(error) as info:
        FireworksScene(wind=wind)  # type: ignore[arg-type]
    for word in words:
        assert word in str(info.value)


@pytest.mark.parametrize(
    "argv",
    [
        ["fireworks", "--kinds", "peony,sparkler"],
        ["fireworks", "--wind", "-3"],
        ["fireworks", "--wind", "east"],
    ],
)
def test_cli_usage_errors_exit_2_naming_the_option(argv: list[str], capsys) -> None:
    with pytest.raises(SystemExit) as info:
        main(argv, out=io.StringIO())
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert argv[1] in err and argv[2].split(",")[-1] in err
