"""Dragging bodies with the mouse in a demo's window (engine.render.mouse_drag, wired into
engine.render.play): synthetic pygame events on the dummy video driver, a virtual clock."""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

import pygame
import pytest

from demos.crates import CratesScene
from engine import Body, Vector, World
from engine.loop import VirtualClock
from engine.render import Camera, init_headless, recorder
from engine.render.mouse_drag import MouseDrag


def test_the_window_loop_drags_a_body_to_the_pointer_and_lets_go(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A press on the crates demo's ball picks it, a move carries the target 1.5 m up, the ball
    comes to rest there (its point under the pointer by the soft step's mouse joint's sag
    under gravity, g / omega^2 = 9.9 mm at 5 Hz, Box2D's: the demo's World takes the soft step
    for its crates), and the release takes the joint out; a press on empty space picks
    nothing."""
    scene = CratesScene()
    seen: dict[str, Any] = {}
    polls = {"n": 0}

    def events() -> list[pygame.event.Event]:
        polls["n"] += 1
        n, cam = polls["n"], scene.camera
        ball = scene.bodies["ball"][0]
        if n == 3:
            return [pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=cam.to_px(-3.0, 5.5), button=1)]
        if n == 4:
            seen["empty"] = scene.world.mouse_joints
            return [pygame.event.Event(pygame.MOUSEBUTTONUP, pos=cam.to_px(-3.0, 5.5), button=1)]
        if n == 5:
            seen["target"] = ball.pos + Vector(0.0, 1.5)
            return [pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=cam.to_px(*ball.pos), button=1)]
        if n == 6:
            return [pygame.event.Event(pygame.MOUSEMOTION, pos=cam.to_px(*seen["target"]))]
        if n == 120:
            (joint,) = scene.world.mouse_joints
            seen["joint"], seen["miss"] = joint, (joint.world_anchor() - joint.target).length()
            seen["body"] = joint.body
            return [pygame.event.Event(pygame.MOUSEBUTTONUP, pos=(0, 0), button=1)]
        if n == 121:
            seen["after"] = scene.world.mouse_joints
            return [pygame.event.Event(pygame.QUIT)]
        return []

    monkeypatch.setattr(recorder, "init_window", init_headless)
    monkeypatch.setattr(recorder, "RealClock", lambda: VirtualClock(60))
    monkeypatch.setattr(pygame.event, "get", events)
    recorder.play(scene, fps=1000, size=(480, 270), seconds=5.0)
    assert seen["empty"] == ()
    assert seen["body"] is scene.bodies["ball"][0]
    assert (seen["joint"].target - seen["target"]).length() < 1e-12
    assert scene.world.solver == "soft"
    assert seen["miss"] == pytest.approx(9.81 / (2 * math.pi * 5.0) ** 2, rel=1e-3)
    assert seen["after"] == ()


def test_a_drag_ends_with_the_world_it_was_in_and_ignores_kinematic_bodies() -> None:
    init_headless()
    scene = CratesScene()
    scene.build((480, 270))
    drag = MouseDrag()
    lift = scene.bodies["lift"][0]
    edge = lift.pos + Vector(0.95, -0.05)  # (its rider crate sits over its middle)
    press = pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=scene.camera.to_px(*edge), button=1)
    assert not drag.handle(press, scene) and scene.world.mouse_joints == ()
    ball = scene.bodies["ball"][0]
    press = pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=scene.camera.to_px(*ball.pos), button=1)
    assert drag.handle(press, scene) and drag.joint is not None
    assert drag.joint.max_force == pytest.approx(1000.0 * ball.mass)
    old = scene.world
    scene.build((480, 270))  # restarted: the drag is gone with its World
    move = pygame.event.Event(pygame.MOUSEMOTION, pos=(10, 10))
    assert not drag.handle(move, scene) and drag.joint is None
    assert old.mouse_joints != () and scene.world.mouse_joints == ()


def test_a_press_in_a_world_on_the_closed_form_drags_nothing() -> None:
    """integrator="exact" takes no mouse joint: the press picks nothing, and nothing fails."""
    init_headless()
    world = World(integrator="exact")
    ball = world.add(Body(Vector(1.0, 1.0), radius=0.5))
    scene = SimpleNamespace(world=world, camera=Camera(50.0, (100.0, 200.0)))
    press = pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=scene.camera.to_px(*ball.pos), button=1)
    drag = MouseDrag()
    assert not drag.handle(press, scene) and drag.joint is None and world.mouse_joints == ()
