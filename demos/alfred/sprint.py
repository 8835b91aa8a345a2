"""``sprint``: from rest at 1 in/s^2 (figure 6), as two ants on two tubes.

The lesson's "he reaches the end in 4 s" (0, 1, 3, 6, 10 in) is semi-implicit Euler with a 1 s
step; the exact answer, s = t^2 / 2 = 10 in, is t = sqrt(20) = 4.47 s. The shaded areas under
v(t) show why: Euler moves each whole second at the speed it has at the end of that second.
"""

from __future__ import annotations

from engine import World
from engine.render import EULER, EXACT

from .common import EULER_ANT_BODY, ant_sprite, sprite_zoom
from .tube import Ant, TubeScene, ant_1d


class Sprint(TubeScene):
    """From rest at 1 in/s^2: semi-implicit Euler at dt = 1 s against the exact closed form."""

    name = "sprint"
    summary = "from rest at 1 in/s\u00b2: Euler with dt = 1 s says 4 s, the exact answer is 4.47 s"
    title = "Alfred's sprint: a = 1 in/s\u00b2 from rest"
    formula = "Euler with 1 s steps says he reaches 10 in at 4 s; the exact answer is \u221a20 s"
    duration = 5.5
    arrow_seconds = 0.5
    #: The lesson's own time step: one second.
    dt = 1.0
    s_range = (0.0, 10.0)
    v_range = (0.0, 8.0)  # room above the curves for the area labels
    a_range = (0.0, 2.0)

    def make_ants(self) -> list[Ant]:
        """Semi-implicit Euler's Alfred (top) and the exact Alfred (bottom)."""
        euler = ant_1d(
            World(integrator="semi_implicit_euler"),
            0.0,
            0.0,
            1.0,
            row=0.0,
            color=EULER,
            sprite=ant_sprite(EULER_ANT_BODY, zoom=sprite_zoom(self.size)),
            label="semi-implicit\nEuler, dt = 1 s",
            short="Euler",
            stepped=True,
        )
        exact = ant_1d(
            World(integrator="exact"),
            0.0,
            0.0,
            1.0,
            row=-1.0,
            color=EXACT,
            sprite=ant_sprite(zoom=sprite_zoom(self.size)),
            label="exact\ns = t\u00b2/2",
            short="exact",
        )
        return [euler, exact]
