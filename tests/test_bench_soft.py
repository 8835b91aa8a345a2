"""The soft step's bench (demos.bench.soft): the same scenes in the three engines, and what a
short run reports, never how fast."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from demos import stack
from demos.bench import soft
from tests.paths import FAST

pytest.importorskip("pymunk")


def scene(name: str) -> soft.Scene:
    return next(s for s in soft.SCENES if s.name == name)


@FAST
def test_the_soft_and_exact_pyramids_are_the_same_boxes_but_for_the_solver() -> None:
    made = [stack.pyramid(20, kernels="fast", solver=s) for s in ("soft", "exact")]
    (ws, bs), (we, be) = made
    assert (ws.solver, we.solver) == ("soft", "exact")
    assert np.array_equal(ws.positions(), we.positions())
    assert [b.mass for b in bs] == [b.mass for b in be]


@FAST
@pytest.mark.parametrize("name", ["pyramid 210", "segments 1,000"])
def test_a_short_run_reports_every_engine(name: str) -> None:
    got = soft.side_by_side(scene(name), steps=3)
    assert set(got) == {"soft", "exact", "pymunk"}
    for seconds, quality, warned in got.values():
        assert seconds > 0.0
        assert warned == 0  # no pile is past its iterations in 3 steps
        # 3 steps: the pyramid settles (the soft contacts give a centimetre or so under the
        # load above them, no box falls); no ball has left the box.
        assert 0.0 <= quality < (50.0 if name.startswith("pyramid") else 0.5)


@FAST
def test_the_quality_measure_sees_a_pyramid_knocked_over() -> None:
    # The pyramid's measure is the largest move of any box: a box flung 2 m reads 2,000 mm.
    step, moved = scene("pyramid 210").made("soft")
    assert moved() == 0.0
    world = step.__self__  # type: ignore[attr-defined]
    world.bodies[0].pos = world.bodies[0].pos + (2.0, 0.0)
    assert moved() == pytest.approx(2000.0, rel=1e-3)


def test_warnings_are_counted_by_engine_not_printed_among_the_lines() -> None:
    # A stand-in scene whose soft World warns in two of its steps and whose exact one in
    # none: the count is the soft engine's, and nothing reaches the warnings' printer.
    from engine.stability import StabilityWarning

    def made(engine: str) -> soft.Sim:
        count = [0]

        def step(dt: float) -> None:
            count[0] += 1
            if engine == "soft" and count[0] in (2, 3):
                warnings.warn("a pile past its iterations", StabilityWarning, stacklevel=2)

        return step, lambda: float(count[0])

    with warnings.catch_warnings(record=True) as outside:
        warnings.simplefilter("always")
        got = soft.side_by_side(soft.Scene("stand-in", made, 4, 0, "steps", True))
    assert {e: g[2] for e, g in got.items()} == {"soft": 2, "exact": 0, "pymunk": 0}
    assert {e: g[1] for e, g in got.items()} == {"soft": 4.0, "exact": 4.0, "pymunk": 4.0}
    assert not outside
