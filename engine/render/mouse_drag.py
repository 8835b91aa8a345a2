"""Dragging a scene's bodies with the mouse in a window: a MouseJoint (engine.dynamics.mouse_joint)
per drag, as Box2D's samples and pymunk's examples do it.

A left button pressed on a body (a point query at the pointer, within ``PICK`` px) holds the
body's point under the pointer by a MouseJoint of ``hertz`` and ``damping_ratio`` whose force is
at most ``strength`` times the body's mass (N; Box2D's samples take 1000 m), its spin damped by
``angular_damping`` (1/s; 2: halved in 0.35 s, so a body held by a corner soon hangs still);
moving the mouse moves the joint's target; letting go takes the joint out. Kinematic bodies,
colliders, scenes whose ``world`` is not an engine World (or a wrapper with one as its
``world``) and Worlds that take no mouse joint (``integrator="exact"``) are left alone.
:func:`engine.render.play` hands every event to one of these.
"""

from __future__ import annotations

from typing import Any

import pygame

from engine.body import Body
from engine.dynamics.mouse_joint import MouseJoint
from engine.world import World

__all__ = ["MouseDrag", "PICK"]

#: How near the pointer (px) a body's surface must be to be picked.
PICK = 4.0


def scene_world(scene: Any) -> World | None:
    """The engine World a scene steps: its ``world``, or that one's own ``world``; or None."""
    world = getattr(scene, "world", None)
    if isinstance(world, World):
        return world
    inner = getattr(world, "world", None)
    return inner if isinstance(inner, World) else None


class MouseDrag:
    """One mouse's drag of a scene's bodies (the module's text)."""

    def __init__(
        self,
        hertz: float = 5.0,
        damping_ratio: float = 0.7,
        strength: float = 1000.0,
        angular_damping: float = 2.0,
    ) -> None:
        self.hertz, self.damping_ratio, self.strength = hertz, damping_ratio, strength
        self.angular_damping = angular_damping
        #: The joint of the drag under way and the World it is in, or None.
        self.joint: MouseJoint | None = None
        self._world: World | None = None

    def _where(self, scene: Any, pos: Any) -> tuple[float, float] | None:
        """The world point under the pixel ``pos``, or None without a camera that maps back."""
        to_world = getattr(getattr(scene, "camera", None), "to_world", None)
        if to_world is None:
            return None
        x, y = to_world(float(pos[0]), float(pos[1]))
        return float(x), float(y)

    def handle(self, event: pygame.event.Event, scene: Any) -> bool:
        """Take a mouse event for ``scene``: True when it started, moved or ended a drag."""
        world = scene_world(scene)
        if self.joint is not None and world is not self._world:
            self.joint = self._world = None  # the scene was built again: that drag is gone
        if world is None:
            return False
        if event.type == pygame.MOUSEBUTTONDOWN and event.button == 1:
            return self._pick(world, scene, event.pos)
        if self.joint is None:
            return False
        if event.type == pygame.MOUSEMOTION:
            point = self._where(scene, event.pos)
            if point is not None:
                self.joint.target = point
            return True
        if event.type == pygame.MOUSEBUTTONUP and event.button == 1:
            self.release()
            return True
        return False

    def _pick(self, world: World, scene: Any, pos: Any) -> bool:
        point = self._where(scene, pos)
        if point is None or world.dim != 2:
            return False
        self.release()
        reach = PICK / float(getattr(scene.camera, "scale", 1.0))
        for hit in world.point_query(point, reach):
            body = hit.shape
            if isinstance(body, Body) and not body.kinematic:
                joint = MouseJoint(
                    body,
                    point,
                    hertz=self.hertz,
                    damping_ratio=self.damping_ratio,
                    max_force=self.strength * body.mass,
                    angular_damping=self.angular_damping,
                )
                try:
                    self.joint = world.add_link(joint)
                except ValueError:
                    return False  # a World that takes none (integrator="exact"): no drag
                self._world = world
                return True
        return False

    def release(self) -> None:
        """End the drag under way (its joint taken out, if its body is still there)."""
        joint, world = self.joint, self._world
        self.joint = self._world = None
        if joint is not None and world is not None and joint in world.mouse_joints:
            world.remove_link(joint)

    def draw(self, surface: pygame.Surface, scene: Any) -> None:
        """A line from the dragged point to the pointer's target, over the frame."""
        camera = getattr(scene, "camera", None)
        if self.joint is None or camera is None or not hasattr(camera, "to_px"):
            return
        a = camera.to_px(*self.joint.world_anchor())
        b = camera.to_px(*self.joint.target)
        pygame.draw.line(surface, (255, 200, 0), a, b, 2)
        pygame.draw.circle(surface, (255, 200, 0), (round(b[0]), round(b[1])), 3)
