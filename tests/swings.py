"""A swing's period, measured: the times a body's angular velocity crosses zero going down
(the end of each swing one way), taken between steps by straight lines."""

from __future__ import annotations

from engine import Body, World


def crossings(world: World, body: Body, dt: float, seconds: float) -> list[float]:
    """Step ``world`` by ``dt`` (s) for ``seconds``; the times (s) the ``body``'s angular
    velocity passed from > 0 to <= 0 (one a period)."""
    found: list[float] = []
    last = body.angular_velocity
    for _ in range(round(seconds / dt)):
        world.step(dt)
        now = body.angular_velocity
        if last > 0.0 >= now:
            found.append(world.t - dt * now / (now - last))
        last = now
    return found
