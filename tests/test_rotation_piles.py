"""Discs that turn in a pile: the soft step's friction rows have lever arms (engine.exact.soft,
Arms).

With the normal n from A to B and t = i n, the contact point sits at l_A n from A's centre and
at -l_B n from B's, and the slip there is vt = (v_B - v_A).t - omega_B l_B - omega_A l_A; a
tangential impulse lam_t t on B (-lam_t t on A) turns B by -l_B lam_t / I_B and A by
-l_A lam_t / I_A. Each test checks a physical outcome and can fail: the sign of a lever arm
wrong, or no lever arms at all (discs that slide as blocks), fails them.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from demos.bench import limits
from engine import Body, Box, Plane, Vector, World, kernels
from engine.exact.soft import Arms, Rows, SoftStep
from engine.forces import Gravity, Spring

G = 9.81
R = 0.5
PATHS = ["numpy", "fast"] if kernels.available() else ["numpy"]


def cross(p: complex, q: complex) -> float:
    """The 2D cross product p x q of two vectors given as complex numbers."""
    return p.real * q.imag - p.imag * q.real


# -- (1) angular momentum ----------------------------------------------------------------------


def test_the_soft_steps_impulses_give_the_spins_their_moment_to_rounding() -> None:
    """What should hold, exactly. A row's impulse P acts on B at x_B - l_B n and on A (as
    -P) at x_A + l_A n. Its moment about the origin, taken at the positions the rows were
    made at, (x_B - x_A) x P = |x_B - x_A| n x P, is what the spins take, -(l_A + l_B) n x P,
    with the opposite sign, when l_A + l_B = |x_B - x_A|: the lever arms of two overlapping
    discs (r + s / 2 each, s < 0 the gap: the contact point midway between the surfaces, as
    Box2D's). So L' = sum m x0 x v + I omega, at the rows' positions x0, is kept by a step of
    the soft step to rounding: here three discs, two of them spinning, the third thrown at
    them, with friction, and no force."""
    x0 = np.array([0.0 + 0.0j, 0.995 + 0.0j, 0.5 + 0.91j, 0.0])  # the static slot last
    r = np.array([0.5, 0.5, 0.55])
    m = np.array([1.0, 2.0, 1.5])
    inertia = 0.5 * m * r * r
    v0 = np.array([0.3 + 0.0j, -0.4 + 0.1j, 0.2 - 1.5j, 0.0])
    omega0 = np.array([12.0, -3.0, 0.0, 0.0])
    a, b = np.array([0, 0, 1]), np.array([1, 2, 2])
    d = x0[b] - x0[a]
    sep = np.abs(d) - r[a] - r[b]
    assert (sep < 0.0).all()  # overlapping: one contact point each

    def rows() -> Rows:
        z = np.zeros(3)
        return Rows(a, b, d / np.abs(d), sep, np.full(3, 0.4), z, z.copy(), z.copy(), z < 0)

    arms = Arms(r[a] + 0.5 * sep, r[b] + 0.5 * sep, np.append(1.0 / inertia, 0.0))
    w = np.append(1.0 / m, 0.0)
    moves = np.array([True, True, True, False])

    def moment(v: np.ndarray, omega: np.ndarray) -> float:
        return sum(m[k] * cross(x0[k], v[k]) + inertia[k] * omega[k] for k in range(3))

    L0 = moment(v0, omega0)
    for path in PATHS:
        step = SoftStep(rows(), w, moves, 1 / 60, fast=path == "fast", arms=arms)
        _, v = step.run(x0, v0, np.zeros(4, dtype=complex), omega0, np.zeros(4))
        assert abs(step.omega[0] - omega0[0]) > 1.0  # friction turned them ...
        assert moment(v, step.omega) == pytest.approx(L0, rel=1e-12, abs=1e-12)  # ... to rounding
        # Each body's momentum changes as much as the others' the other way.
        assert abs(sum(m[k] * (v[k] - v0[k]) for k in range(3))) < 1e-12


def pressed_pair(dt: float, path: str = "numpy", seconds: float = 2.0) -> dict[str, float]:
    """Two discs in free space pressed together by a spring toward the origin (a central
    force: no moment about it), one spinning at 10 rad/s, friction 0.5 each (0.25 the
    pair's): the largest change of L = sum m x x v + I omega about the origin over
    ``seconds``, L0, the spins and the slip at the contact at the end."""
    w = World(kernels=path)
    a = w.add(Body(Vector(-R, 0.0), radius=R, friction=0.5, restitution=0.0,
                   angular_velocity=10.0))  # fmt: skip
    b = w.add(Body(Vector(R, 0.0), radius=R, friction=0.5, restitution=0.0))
    w.add_force(Spring((0.0, 0.0), 20.0))

    def L() -> float:
        return sum(q.mass * q.pos.cross(q.vel) + q.moment * q.angular_velocity for q in (a, b))

    L0, drift = L(), 0.0
    for _ in range(round(seconds / dt)):
        w.step(dt)
        drift = max(drift, abs(L() - L0))
    d = b.pos - a.pos
    n = d / abs(d)
    t = Vector(-n.y, n.x)
    slip = (b.vel - a.vel).dot(t) - b.angular_velocity * R - a.angular_velocity * R
    return {"L0": L0, "drift": drift, "wa": a.angular_velocity, "wb": b.angular_velocity,
            "slip": slip}  # fmt: skip


@pytest.mark.parametrize("path", PATHS)
def test_two_pressed_discs_roll_on_each_other_and_keep_their_angular_momentum(path: str) -> None:
    """Friction makes the spinning disc turn the other (the other way, as gears do) until
    they roll on each other (no slip: omega_A - omega_B stays 10 rad/s, the spin shared
    as the moments of the pair allow) while the pair turns about the origin.

    What holds: the impulses keep L to rounding at the positions the step's rows were made
    at (the test above). Within a step the soft step moves the bodies (x += v h a part) but
    keeps each row's normal and lever arms, and the forces' pull, of the step's start: an
    impulse P given after the bodies moved by dx_A, dx_B changes L by (dx_B - dx_A) x P, a
    pull F after a move dx by dx x F. Those are the pile's own first-order errors (a pair
    orbiting without friction, nothing turning, drifts by 6% of its L here), so L is kept to
    first order in dt: the drift halves when dt does."""
    coarse, fine = pressed_pair(1 / 60, path), pressed_pair(1 / 120, path)
    for run in (coarse, fine):
        assert abs(run["slip"]) < 1e-3  # rolling on each other, from a slip of 10 * R
        assert run["wa"] - run["wb"] == pytest.approx(10.0, rel=1e-3)
        assert 5.0 < run["wa"] < 8.0 and -5.0 < run["wb"] < -2.0
    assert coarse["drift"] / coarse["L0"] < 0.03  # 2.6% at dt = 1/60 s
    assert coarse["drift"] / fine["drift"] == pytest.approx(2.0, rel=0.1)  # first order


@pytest.mark.parametrize("path", PATHS)
def test_a_pile_that_nothing_spins_turns_as_it_would_beside_a_far_collider(path: str) -> None:
    """Two discs pressed into each other (a pile), one sliding across the other, no force,
    nothing spinning: friction turns both alike (the way gears would not: the top one's
    underside is dragged back, the bottom one's top forward), as it does when a collider lies
    50 m off. Before, a World that had no collider and nothing spinning made no spin for
    the step, and its pile's friction acted on the centres and turned nothing."""
    got = []
    for far_wall in (False, True):
        w = World(kernels=path)
        if far_wall:
            w.add_collider(Plane((0.0, -50.0), (0.0, 1.0)))
        kw = dict(radius=0.1, mass=1.0, friction=0.8, restitution=0.5)
        top = w.add(Body(Vector(0.0, 0.0), Vector(1.0, -0.5), **kw))  # type: ignore[arg-type]
        low = w.add(Body(Vector(0.0, -0.199), Vector(0.0, 0.0), **kw))  # type: ignore[arg-type]
        for _ in range(3):
            w.step(1 / 60)
        got.append(np.array([*top.pos, *top.vel, top.angular_velocity,
                             *low.pos, *low.vel, low.angular_velocity]))  # fmt: skip
    assert got[1][4] < -1.0 and got[1][9] < -1.0  # both turned clockwise, by friction
    assert np.array_equal(got[0], got[1]), got


# -- (2) a disc rolls off another -------------------------------------------------------------


def column(turning: bool, path: str = "numpy") -> tuple[World, Body, Body]:
    """A disc resting on a disc on a floor, 0.1 m (a tenth of the diameter) off-centre toward
    +x, friction 0.5 each (0.25 between the discs)."""
    w = World(integrator="auto", kernels=path)
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
    kw = dict(radius=R, friction=0.5, restitution=0.0, fixed_rotation=not turning)
    bottom = w.add(Body(Vector(0.0, R), **kw))  # type: ignore[arg-type]
    top = w.add(Body(Vector(0.1, 3 * R), **kw))  # type: ignore[arg-type]
    return w, bottom, top


@pytest.mark.parametrize("path", PATHS)
def test_a_disc_on_a_disc_rolls_off_it(path: str) -> None:
    """Off-centre by 0.1 rad of its lean, the top disc stands on a disc that does not turn
    (static friction holds it while tan(lean) < mu = 0.25) but rolls off one that turns: it
    turns clockwise (omega < 0) going toward +x, the one below the other way, with no slip
    between them, and lands on the floor beside it."""
    w, bottom, top = column(turning=False, path=path)
    for _ in range(120):
        w.step(1 / 60)
    assert top.pos.y > 2.9 * R  # a block stands
    w, bottom, top = column(turning=True, path=path)
    slips = []
    for i in range(150):
        w.step(1 / 60)
        d = top.pos - bottom.pos
        if 3 <= i < 45 and abs(d) < 2 * R + 1e-3:  # once landed, while it leans on it
            n = d / abs(d)
            vt = (top.vel - bottom.vel).dot(Vector(-n.y, n.x))
            slips.append(vt - top.angular_velocity * R - bottom.angular_velocity * R)
            assert top.angular_velocity <= 0.0 <= bottom.angular_velocity
    assert len(slips) > 35 and max(abs(s) for s in slips) < 1e-3  # it rolled, not slid
    assert top.angular_velocity < -1.0 < 0.1 < bottom.angular_velocity
    assert top.pos.y == pytest.approx(R, abs=0.01) and top.pos.x > 2 * R  # on the floor


# -- (3) a spin is taken out by friction --------------------------------------------------------


@pytest.mark.parametrize("path", PATHS)
def test_a_disc_spinning_on_a_disc_slows_at_mu_n_r_over_i(path: str) -> None:
    """A disc set spinning on top of another slips on it: friction mu N (mu = 0.25, N = m g)
    at the lever arm r slows it at alpha = mu m g r / I = 2 mu g / r = 9.81 rad/s^2."""
    w, bottom, top = column(turning=True, path=path)
    top.pos = Vector(0.0, 3 * R)
    for _ in range(30):
        w.step(1 / 60)
    top.angular_velocity = 20.0
    w.step(1 / 60)
    alpha = (20.0 - top.angular_velocity) * 60.0
    assert alpha == pytest.approx(2 * 0.25 * G / R, rel=2e-3)
    assert bottom.angular_velocity < 0.0  # turned the other way by the same friction


def bin_of_seven(path: str) -> tuple[World, list[Body]]:
    """Four discs on the floor of a box 4 m wide (wall to wall) and three on them."""
    w = World(integrator="auto", kernels=path)
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Box((0.0, 0.0), (4.0, 100.0)))
    h = math.sqrt(3.0) * R
    spots = [(0.5 + k, R) for k in range(4)] + [(1.0 + k, R + h) for k in range(3)]
    bodies = [w.add(Body(Vector(*p), radius=R, friction=0.5, restitution=0.0)) for p in spots]
    return w, bodies


@pytest.mark.parametrize("path", PATHS)
def test_a_spinning_disc_in_a_pile_spins_down_and_the_pile_sleeps(path: str) -> None:
    """The middle disc of the upper row, set spinning at 20 rad/s, rubs on the two below it:
    their friction takes its spin out (at about mu N r / I, 2 s here), nothing else is set
    going, and the pile falls asleep, every spin 0."""
    w, bodies = bin_of_seven(path)
    for _ in range(60):
        w.step(1 / 60)
    spinner = bodies[5]
    spinner.angular_velocity = 20.0
    assert not w.is_sleeping(spinner)
    slowed_at = asleep_at = None
    for i in range(300):
        w.step(1 / 60)
        if slowed_at is None and abs(spinner.angular_velocity) < 0.1:
            slowed_at = (i + 1) / 60
        if all(w.is_sleeping(b) for b in bodies):
            asleep_at = (i + 1) / 60
            break
        assert spinner.angular_velocity > -0.1  # friction stops it, does not turn it back
    assert slowed_at is not None and 1.0 < slowed_at < 2.5
    assert asleep_at is not None and asleep_at < 3.0
    assert all(b.angular_velocity == 0.0 for b in bodies)
    assert (
        max(abs(b.pos.x - x) for b, x in zip(bodies, [0.5, 1.5, 2.5, 3.5, 1, 2, 3], strict=True))
        < 0.01
    )


# -- (4) the 200-ball pit of discs that turn ------------------------------------------------------


def test_the_200_ball_pit_of_turning_discs_comes_to_rest_and_sleeps() -> None:
    """The limits table's 200-ball pit (demos.bench.limits, QUICK[1]), its balls turning:
    they turn as they land and roll (nearly every ball leaves its angle), and the pit sleeps
    within the scene's 5 s (3.7 s here; 3.25 s for balls that do not turn), overlapping by
    under 1% of a radius at the end."""
    quick = limits.QUICK[1]
    world, width = limits.pit_of(200, 12.0, turning=True)(quick.iterations[0], 1)
    assert len(world.turning) == 200
    scene = limits.Scene(quick.label, lambda k, s: (world, width), quick.seconds, quick.iterations)
    result = limits.run(scene, quick.iterations[0], 1)
    assert result.asleep_at < quick.seconds
    assert result.final < 0.01
    assert np.mean([b.angle != 0.0 for b in world.bodies]) > 0.9
    assert all(b.angular_velocity == 0.0 for b in world.bodies)  # asleep: not turning


@pytest.mark.skipif(not kernels.available(), reason="numba is not installed: one path")
def test_a_pit_of_turning_discs_is_bit_identical_on_both_paths() -> None:
    """The turning 200-ball pit over 150 steps: the same positions, angles and spins on both
    paths, bit for bit."""
    from demos.bench.pit import make_world

    ends = []
    for path in ("numpy", "fast"):
        world = make_world(200, 4, width=12.0, kernels=path, fixed_rotation=False)
        for _ in range(150):
            world.step(1 / 60)
        spins = [(b.angle, b.angular_velocity) for b in world.bodies]
        ends.append(np.concatenate([world.positions(), np.array(spins)], axis=1))
    assert np.array_equal(ends[0], ends[1])
    assert np.abs(ends[0][:, 3]).max() > 0.1


def test_adding_a_body_leaves_a_moving_pile_of_discs_that_turn_as_it_was() -> None:
    """A pile still moving (a pyramid of discs that turn, rolling apart) goes on exactly as in
    a World without the ball added far away: its rows keep their impulses and their colours,
    so the Gauss-Seidel order is the same (it was coloured afresh, and the order matters
    while a pile moves: 1.8e-5 m apart after one step)."""

    def pyramid() -> tuple[World, list[Body]]:
        w = World(integrator="auto")
        w.add_force(Gravity((0.0, -9.81)))
        w.add_collider(Plane((0.0, 0.0), (0.0, 1.0)))
        r = 0.5
        balls = [
            w.add(Body(Vector((k + 0.5 * row) * 2 * r, r + row * r * math.sqrt(3)), radius=r))
            for row in range(5)
            for k in range(5 - row)
        ]
        return w, balls

    spawned, balls = pyramid()
    alone, twins = pyramid()
    for _ in range(20):
        spawned.step(1 / 60)
        alone.step(1 / 60)
    spawned.add(Body(Vector(40.0, 3.0), radius=0.5))
    for _ in range(60):
        spawned.step(1 / 60)
        alone.step(1 / 60)
        assert [(b.pos, b.angular_velocity) for b in balls] == [
            (b.pos, b.angular_velocity) for b in twins
        ]
    assert max(abs(b.angular_velocity) for b in balls) > 0.1  # it moves, and turns
