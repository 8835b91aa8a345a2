"""Every demo can be paused, saved, resumed and rerun bit for bit.

A run is driven as the recorder drives it (one step ahead, then the fixed-step loop on a
virtual clock). At one frame the scene's snapshot is taken with the loop and clock (they are
the caller's, not the scene's). Then either the same scene runs on for a while and is
restored (a rerun), or a freshly built scene is restored (a resume). From there on, every
frame's pixels and every number of the scene's state must equal those of a run never
interrupted.
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Callable
from typing import Any

import numpy as np
import pygame
import pytest

from demos import (
    alfred,
    ballpit,
    bounce,
    car,
    cradle,
    crumb,
    fireworks,
    galton,
    hinges,
    stability,
    stack,
)
from engine import FixedStep, Vector, VirtualClock
from engine.render import Scene, init_headless

SIZE = (320, 180)  # the car needs 160x168 px at least
FPS = 15


def small_ballpit() -> Scene:
    """The ball pit with 150 balls: it lands, settles and sleeps within the 3 s recorded."""
    scene = ballpit.PitScene()
    scene.balls = 150
    return scene


SCENES: dict[str, Callable[[], Scene]] = {
    **{f"alfred/{name}": make for name, make in alfred.DEMO.scenes.items()},
    **{f"fireworks/{name}": make for name, make in fireworks.DEMO.scenes.items()},
    **{f"car/{name}": make for name, make in car.DEMO.scenes.items()},
    "crumb": crumb.CrumbScene,
    **{f"stability/{name}": make for name, make in stability.DEMO.scenes.items()},
    **{f"bounce/{name}": make for name, make in bounce.DEMO.scenes.items()},
    **{f"cradle/{name}": make for name, make in cradle.DEMO.scenes.items()},
    "ballpit": small_ballpit,
    **{f"galton/{name}": make for name, make in galton.DEMO.scenes.items()},
    **{f"hinges/{name}": make for name, make in hinges.DEMO.scenes.items()},
    "stack/dominoes": stack.DominoScene,  # (the other stacks' boxes cost more, alike)
}
#: Scenes that do not resume yet, and why.


def leaves(state: Any) -> list[Any]:
    """Every number and array in a snapshot, in order (dataclasses, tuples, dicts opened)."""
    if dataclasses.is_dataclass(state) and not isinstance(state, type):
        return [x for f in dataclasses.fields(state) for x in leaves(getattr(state, f.name))]
    if isinstance(state, (list, tuple)) and not isinstance(state, Vector):
        return [x for item in state for x in leaves(item)]
    if isinstance(state, dict):
        return [x for key in sorted(state) for x in [key, *leaves(state[key])]]
    return [state]


def same(a: list[Any], b: list[Any]) -> bool:
    """Equal bit for bit: arrays by dtype and value, everything else by type and ==."""
    if len(a) != len(b):
        return False
    for x, y in zip(a, b, strict=True):
        if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
            if not (
                isinstance(x, np.ndarray)
                and isinstance(y, np.ndarray)
                and x.dtype == y.dtype
                and np.array_equal(x, y)
            ):
                return False
        elif type(x) is not type(y) or x != y:
            return False
    return True


def run(
    make: Callable[[], Scene], frames: int, pause_at: int | None = None, how: str = "rerun"
) -> list[tuple[bytes, list[Any]]]:
    """Each frame's pixels and the scene's state; at ``pause_at``, save and rerun or resume."""
    init_headless()
    scene = make()
    size = (max(SIZE[0], scene.min_size[0]), max(SIZE[1], scene.min_size[1]))
    surface = pygame.Surface(size)
    scene.build(size)
    loop, clock = FixedStep(scene.dt, max_frame=1.0), VirtualClock(FPS)
    scene.step(scene.dt)
    out = []
    for index in range(frames):
        if index > 0:
            for _ in range(loop.advance(clock.tick())):
                scene.step(scene.dt)
        if index == pause_at:
            saved = scene.snapshot(), copy.deepcopy(loop), copy.deepcopy(clock)
            if how == "rerun":  # run on elsewhere, then come back
                for _ in range(12):
                    scene.draw(surface, loop.alpha)
                    for _ in range(loop.advance(clock.tick())):
                        scene.step(scene.dt)
            else:  # a new scene, built afresh, takes the saved state
                scene = make()
                scene.build(size)
            snapshot, loop, clock = saved
            scene.restore(snapshot)
        scene.draw(surface, loop.alpha)
        out.append((pygame.image.tobytes(surface, "RGB"), leaves(scene.snapshot())))
    return out


@pytest.fixture(scope="module")
def unbroken() -> dict[str, list[tuple[bytes, list[Any]]]]:
    return {}


FRAMES, PAUSE = 45, 20  # 3 s at 15 fps, paused at 1.33 s: rockets climbing, the car moving


@pytest.mark.parametrize("how", ["rerun", "resume"])
@pytest.mark.parametrize(
    "name",
    list(SCENES),
)
def test_a_scene_saved_mid_run_goes_on_as_if_never_interrupted(
    name: str, how: str, unbroken: dict[str, list[tuple[bytes, list[Any]]]]
) -> None:
    if name not in unbroken:
        unbroken[name] = run(SCENES[name], FRAMES)
    straight = unbroken[name]
    broken = run(SCENES[name], FRAMES, pause_at=PAUSE, how=how)
    assert len(broken) == FRAMES
    for index in range(PAUSE, FRAMES):
        (pixels, state), (want_pixels, want_state) = broken[index], straight[index]
        assert pixels == want_pixels, f"frame {index} differs"
        assert same(state, want_state), f"the state at frame {index} differs"
    # The test can tell: the scene's state moves on from frame to frame.
    assert not same(straight[PAUSE][1], straight[PAUSE + 12][1])


def test_the_comparison_sees_a_difference_in_any_leaf() -> None:
    a = leaves((np.zeros(3), {"k": 1}, [2.0, Vector(1, 2)]))
    b = leaves((np.zeros(3), {"k": 1}, [2.0, Vector(1, 2)]))
    assert same(a, b)
    assert not same(a, leaves((np.zeros(3, dtype=np.float32), {"k": 1}, [2.0, Vector(1, 2)])))
    assert not same(a, leaves((np.zeros(3), {"k": 1}, [2.0, Vector(1, 3)])))
    assert not same(a, leaves((np.zeros(3), {"k": 1.0}, [2.0, Vector(1, 2)])))
