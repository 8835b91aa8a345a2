"""A disc against a polygon in the joints' solve (engine.exact.joint_contacts,
engine.exact.joint_rows): its distance from the polygon wherever the polygon turns, from the side it
came in by.

Checked against geometry worked by hand (a box's faces and corners) and against the
derivative: each row's gradient is the finite difference of its value, for every kind of
contact row, and its value where the step began is the gap it was handed.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.exact.joint_contacts import polygon_distance
from engine.exact.joint_rows import CN, CT, Plan, evaluate
from engine.exact.pile import PUSHED_ON_ROWS, pushed_on
from engine.geometry.manifold_kinds import Capsules, Polygons

# A bat 8 long and 1 thick (its centre line on y = 0, from x = 0 to 8), as a polygon.
BAT = Polygons.of([[(0.0, -0.5), (8.0, -0.5), (8.0, 0.5), (0.0, 0.5)]])
ONE = np.zeros(1, dtype=np.intp)


def distance(p: tuple[float, float], p0: tuple[float, float]) -> tuple[float, ...]:
    dist, normal, corner, at = polygon_distance(BAT, ONE, np.array([p]), np.array([p0]))
    return float(dist[0]), float(normal[0, 0]), float(normal[0, 1]), bool(corner[0])


def test_outside_a_face_it_is_the_distance_from_the_face() -> None:
    assert distance((3.0, 2.5), (3.0, 4.0)) == pytest.approx((2.0, 0.0, 1.0, False), abs=1e-15)
    assert distance((3.0, -1.0), (3.0, -4.0)) == pytest.approx((0.5, 0.0, -1.0, False), abs=1e-15)


def test_past_a_face_s_end_it_is_the_distance_from_the_corner() -> None:
    d, nx, ny, corner = distance((11.0, 4.5), (12.0, 6.0))
    assert corner
    assert d == pytest.approx(5.0, abs=1e-15)  # from (8, 0.5): (3, 4)
    assert (nx, ny) == pytest.approx((0.6, 0.8), abs=1e-15)


def test_a_centre_that_went_through_is_measured_from_the_face_it_entered_by() -> None:
    # From above the bat to below it: nearest the bottom face (0.3 out), but it came in by the
    # top, so it is 1.3 in, along the top's normal.
    assert distance((4.0, -0.8), (4.0, 3.0)) == pytest.approx((-1.3, 0.0, 1.0, False), abs=1e-15)
    # Inside, nearer the bottom: measured from the top too.
    assert distance((4.0, -0.4), (4.0, 3.0)) == pytest.approx((-0.9, 0.0, 1.0, False), abs=1e-15)
    # In by the tip's end face, from the right.
    d, nx, ny, _ = distance((7.5, 0.0), (12.0, 0.0))
    assert (d, nx, ny) == pytest.approx((-0.5, 1.0, 0.0), abs=1e-15)


def test_a_path_round_the_tip_is_not_a_crossing() -> None:
    # From above right of the tip to below right of it: the path misses the bat.
    d, nx, ny, corner = distance((9.0, -2.0), (9.0, 2.0))
    assert corner
    assert d == pytest.approx(math.hypot(1.0, 1.5), abs=1e-15)
    assert ny < 0.0


def _plan(turn: int, rng: np.random.Generator) -> tuple[Plan, tuple[np.ndarray, ...]]:
    n0 = rng.normal(size=2)
    n0 /= np.linalg.norm(n0)
    fields = (
        n0, rng.normal(size=2), rng.normal(size=2), rng.normal(size=2) * 3.0,
        rng.normal(size=2) * 3.0, rng.normal(), rng.normal(), abs(rng.normal()),
    )  # fmt: skip
    touch = tuple(np.array([f, f]) for f in fields) + (
        np.array([turn, turn], dtype=np.int8),
        np.array([0 if turn else -1] * 2, dtype=np.intp),
        np.array([0.3, 0.3]),
    )
    plan = Plan(
        np.array([CN, CT]), np.zeros(2), np.array([0, 0]), np.array([1, 1]), np.zeros((2, 2)),
        np.zeros((2, 2)), touch, 6, BAT,
    )  # fmt: skip
    return plan, touch


@pytest.mark.parametrize("turn", [0, 1, -1])
def test_each_contact_row_s_gradient_is_the_derivative_of_its_value(turn: int) -> None:
    rng = np.random.default_rng(7 + turn)
    checked = 0
    for _ in range(20):
        plan, touch = _plan(turn, rng)
        q = rng.normal(size=6) * 3.0
        X, TH = q.reshape(2, 3)[:, :2], q.reshape(2, 3)[:, 2]
        c, J = evaluate(X, TH, plan)
        h = 1e-6
        for i in range(6):
            up, down = q.copy(), q.copy()
            up[i] += h
            down[i] -= h
            cu = evaluate(up.reshape(2, 3)[:, :2], up.reshape(2, 3)[:, 2], plan)[0][0]
            cd = evaluate(down.reshape(2, 3)[:, :2], down.reshape(2, 3)[:, 2], plan)[0][0]
            # (A random pose can sit on a feature's border, where the value has a kink.)
            if abs((cu - c[0]) - (c[0] - cd)) < 1e-9:
                assert (cu - cd) / (2 * h) == pytest.approx(J[0, i], abs=1e-7)
                checked += 1
        # Where the step left the two (began, for a disc and a polygon), it is the gap.
        X0 = np.array([touch[3][0], touch[4][0]])
        T0 = np.array([touch[5][0], touch[6][0]])
        assert evaluate(X0, T0, plan)[0][0] == pytest.approx(touch[7][0], abs=1e-12)
    assert checked >= 100  # of 120


# A capsule's core, from (0, 0) to (8, 0), as the two-vertex polygon the joints' solve takes.
CAPSULE = Polygons.from_capsules(Capsules(np.array([[0.0, 0.0]]), np.array([[8.0, 0.0]]), [0.5]))


def core(p: tuple[float, float], p0: tuple[float, float]) -> tuple[float, ...]:
    dist, normal, corner, _ = polygon_distance(CAPSULE, ONE, np.array([p]), np.array([p0]))
    return float(dist[0]), float(normal[0, 0]), float(normal[0, 1]), bool(corner[0])


def test_a_capsule_s_core_is_a_segment_with_round_ends() -> None:
    assert core((3.0, 2.0), (3.0, 4.0)) == pytest.approx((2.0, 0.0, 1.0, False), abs=1e-15)
    d, nx, ny, corner = core((11.0, 4.0), (11.0, 6.0))  # past its end: from the end
    assert corner and d == pytest.approx(5.0, abs=1e-15)
    assert (nx, ny) == pytest.approx((0.6, 0.8), abs=1e-15)


def test_a_path_through_a_capsule_s_core_is_measured_from_the_side_it_came_from() -> None:
    # Through the segment, from above: 0.3 below it, it is -0.3 from the top side.
    assert core((4.0, -0.3), (4.0, 3.0)) == pytest.approx((-0.3, 0.0, 1.0, False), abs=1e-15)
    # Across its line past the end (round the tip): not through it; 0.3 from the end.
    d, _, ny, corner = core((8.3, -1e-3), (8.3, 3.0))
    assert corner and ny < 0.0 and d == pytest.approx(math.hypot(0.3, 1e-3), abs=1e-15)


def chain(n: int, joined_first: bool = True) -> tuple[np.ndarray, ...]:
    """A pile of ``n`` bodies (World rows 10 ... 10 + n - 1) in a chain, each touching the
    next and the static world (slot n), the first held by a joint: (joined (N,), U, ra, rb)."""
    U = np.arange(10, 10 + n)
    joined = np.zeros(10 + n, dtype=bool)
    joined[10] = joined_first
    ra = np.concatenate([np.arange(n - 1), np.full(n, n)])
    rb = np.concatenate([np.arange(1, n), np.arange(n)])
    return joined, U, ra, rb


def handed(joined: np.ndarray, U: np.ndarray, ra: np.ndarray, rb: np.ndarray) -> int:
    """How many of the pile's rows touch a body of ``joined``."""
    nU = len(U)
    inner = ra < nU
    return int(np.count_nonzero(joined[U][rb] | (inner & joined[U][np.where(inner, ra, 0)])))


def test_a_small_pile_is_handed_to_the_joints_solve_whole() -> None:
    # A ball on a bat pushed into another (find 16): the joints' solve must move them all.
    joined, U, ra, rb = chain(5)
    grown = pushed_on(joined, U, ra, rb)
    assert grown[10:].all() and not grown[:10].any()
    assert handed(grown, U, ra, rb) == len(ra)  # 9 rows: 4 between the bodies, 5 on the floor


def test_a_long_pile_is_handed_a_ring_at_a_time_while_the_rows_stay_within_the_bound() -> None:
    joined, U, ra, rb = chain(60)
    grown = pushed_on(joined, U, ra, rb)
    k = int(np.count_nonzero(grown[10:]))
    assert grown[10 : 10 + k].all()  # the chain's first k, from the joint's body on
    assert handed(grown, U, ra, rb) <= PUSHED_ON_ROWS
    one_more = grown.copy()
    one_more[10 + k] = True
    assert handed(one_more, U, ra, rb) > PUSHED_ON_ROWS
    # Nothing joined, nothing handed.
    joined, U, ra, rb = chain(60, joined_first=False)
    assert not pushed_on(joined, U, ra, rb).any()


def test_a_joint_s_body_touching_many_hands_them_all_and_no_more() -> None:
    # A bat under 50 balls, each on the floor too: its own 50 rows go (as they always did),
    # the rings beyond them would pass the bound.
    n = 51
    U = np.arange(n)
    joined = np.zeros(n, dtype=bool)
    joined[0] = True
    ra = np.concatenate([np.zeros(n - 1, dtype=np.int64), np.full(n - 1, n)])
    rb = np.concatenate([np.arange(1, n), np.arange(1, n)])
    grown = pushed_on(joined, U, ra, rb)
    assert grown.tolist() == joined.tolist()
