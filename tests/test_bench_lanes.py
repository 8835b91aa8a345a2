"""The model of the contacts' rows solved side by side (demos.bench.lanes): the colours are a
colouring, the two ways end with the same bits, and the rows keep their impulses' bounds.
Never how fast."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("numba")

from demos.bench import lanes  # noqa: E402  (needs numba)


@pytest.mark.parametrize("points", [1, 2])
def test_the_colours_share_no_moving_body_and_keep_every_row_once(points: int) -> None:
    s = lanes.scene(6, points)
    static = len(s["im"]) - 1
    order, starts, mids = lanes.colour_order(s["ca"], s["cb"], s["two"], static)
    assert sorted(order.tolist()) == list(range(len(s["ca"])))
    assert starts[0] == 0 and starts[-1] == len(order)
    for c in range(len(starts) - 1):
        rows = order[starts[c] : starts[c + 1]]
        bodies = np.concatenate([s["ca"][rows], s["cb"][rows]])
        moving = bodies[bodies != static]
        assert len(np.unique(moving)) == len(moving)  # no body twice in a colour
        # The two-point manifolds first, then the one-point ones from mids on.
        two = s["two"][rows]
        split = mids[c] - starts[c]
        assert (two[:split] == 1.0).all() and (two[split:] == 0.0).all()


@pytest.mark.parametrize("points", [1, 2])
def test_side_by_side_in_colour_order_gives_the_scalar_sweeps_bits(points: int) -> None:
    s = lanes.scene(7, points, seed=3)
    static = len(s["im"]) - 1
    order, starts, mids = lanes.colour_order(s["ca"], s["cb"], s["two"], static)
    ca, cb = s["ca"][order], s["cb"][order]
    ts, tl = lanes.table(s, order), lanes.table(s, order)
    vs, vl = s["v"].copy(), s["v"].copy()
    for _ in range(3):
        lanes.scalar(ca, cb, ts, vs, s["moves"], s["im"], s["ii"])
        lanes.lanes(ca, cb, starts, mids, tl, vl, s["moves"], s["im"], s["ii"])
    assert np.array_equal(vs, vl)
    assert np.array_equal(ts[14:], tl[14:])
    assert not np.array_equal(vs, s["v"])  # the rows pushed the bodies
    # The static body never moves; every normal impulse pushes, every friction impulse is
    # within mu times its point's normal impulse; a one-point manifold's second point none.
    assert (vs[:, static] == 0.0).all()
    for j in range(2):
        q = lanes.POINT + 9 * j
        normal, friction = ts[q + 7], ts[q + 8]
        assert (normal >= 0.0).all()
        assert (np.abs(friction) <= ts[17] * normal).all()
        if j == 1 and points == 1:
            assert (normal == 0.0).all() and (friction == 0.0).all()
    assert (ts[lanes.POINT + 7] > 0.0).any()
