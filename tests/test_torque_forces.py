"""Force generators that give a torque (issue "Bodies that turn": "A force generator may return
a torque"): ConstantTorque, AngularDrag, CallableTorque and a Force's own ``torque``.

Each number is checked against a closed form (free rotation, the exponential of a drag, a disc
rolling on a slope under a torque) or against the body's own torque, which must reach the
contacts the same way, bit for bit. No wall clock is read.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from engine import Body, Pin, Plane, Polygon, SimulationDiverged, StabilityWarning, Vector, World
from engine.forces import (
    AngularDrag,
    CallableTorque,
    ConstantTorque,
    Drag,
    Force,
    Gravity,
    Torque,
)

G = 9.81


def run(w: World, steps: int, dt: float) -> None:
    for _ in range(steps):
        w.step(dt)


class Counted:
    """A torque function that records how many bodies each call was given."""

    def __init__(self, value: float = 0.0) -> None:
        self.sizes: list[int] = []
        self.value = value

    def __call__(self, t: float, angle: np.ndarray, omega: np.ndarray, moment: np.ndarray):
        self.sizes.append(len(omega))
        return self.value + 0.0 * omega


# -- free rotation: the closed forms -------------------------------------------------------


@pytest.mark.parametrize("dt", [1 / 30, 1 / 60, 1 / 240])
def test_a_constant_torque_generator_is_the_closed_form_with_the_bodys_own(dt: float) -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), radius=0.3, mass=2.0, angle=0.4, angular_velocity=-1.5))
    b.torque = 0.2  # its own, kept: the generator's adds to it
    w.add_force(ConstantTorque(0.5))
    alpha = 0.7 / b.moment
    steps = round(10 / dt)
    run(w, steps, dt)
    t = steps * dt
    assert b.angle == pytest.approx(0.4 - 1.5 * t + 0.5 * alpha * t * t, rel=1e-12)
    assert b.angular_velocity == pytest.approx(-1.5 + alpha * t, rel=1e-12)
    assert b.torque == 0.2  # the generator's torque is not written into the body


@pytest.mark.parametrize("dt", [1 / 30, 1 / 60, 1 / 240, 0.5])
@pytest.mark.parametrize("tau0", [0.0, 0.3])
def test_angular_drag_on_a_free_spinning_box_is_the_exponential_closed_form(
    dt: float, tau0: float
) -> None:
    w = World()
    box = w.add(Body(Vector(1, 2), shape=Polygon.box(1.0, 0.5), mass=3.0, angle=0.2))
    box.angular_velocity, box.torque = 12.0, tau0
    c = 0.4
    w.add_force(AngularDrag(c))
    inertia = box.moment
    assert inertia == pytest.approx(3.0 * (1.0 + 0.25) / 12, rel=1e-15)
    k, w_inf = c / inertia, tau0 / c
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # exact: no limit, even at c dt / I = 0.5 s * 1.6 / s
        for n in range(1, round(20 / dt) + 1):
            w.step(dt)
            if n % 7 == 0 or n == round(20 / dt):
                t = n * dt
                omega = w_inf + (12.0 - w_inf) * math.exp(-k * t)
                angle = 0.2 + w_inf * t + (12.0 - w_inf) * (1 - math.exp(-k * t)) / k
                assert abs(box.angular_velocity - omega) <= 1e-12 * 12.0
                assert box.angle == pytest.approx(angle, rel=1e-12)
    assert box.pos == Vector(1, 2)  # a torque moves no body


def test_stiff_angular_drag_on_a_free_body_is_exact_past_the_explicit_limit() -> None:
    # c dt / I = 40: explicit Euler would multiply omega by -39 a step.
    w = World()
    b = w.add(Body(Vector(0, 0), radius=0.5, mass=2.0, angular_velocity=5.0))
    c = 40 * b.moment * 60
    w.add_force(AngularDrag(c))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        w.step(1 / 60)
    assert b.angular_velocity == pytest.approx(5.0 * math.exp(-40), rel=1e-12)
    assert b.angle == pytest.approx(5.0 * b.moment / c * (1 - math.exp(-40)), rel=1e-12)


def test_the_work_of_a_constant_torque_is_the_spins_energy() -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), radius=0.5, mass=1.0, angular_velocity=2.0))
    w.add_force(ConstantTorque(-0.3))
    e0, a0 = w.energy(), b.angle
    run(w, 600, 1 / 60)
    assert w.energy() - e0 == pytest.approx(-0.3 * (b.angle - a0), rel=1e-12)


# -- contacts: a generator's torque reaches them as the body's own does ---------------------


def slope(theta: float, mu: float, torque: float = 0.0) -> tuple[World, Body]:
    n = Vector(-math.sin(theta), math.cos(theta))  # downhill is -x
    w = World()
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), n, friction=1.0))
    b = w.add(Body(n * 0.5, radius=0.5, mass=2.0, friction=mu, restitution=0.0, torque=torque))
    return w, b


@pytest.mark.parametrize("share", [0.0, -0.5, -1.0, 0.25])
def test_a_torque_turns_a_disc_rolling_on_a_slope_as_the_closed_form(share: float) -> None:
    # Rolling (v = omega r downhill, omega > 0 counter-clockwise), friction f up the slope:
    #   m a = m g sin(theta) - f,  I alpha = f r + tau,  a = alpha r
    #   =>  a = (m g sin(theta) r^2 + tau r) / (I + m r^2).
    # share = -1 is the torque that holds the disc still (tau = -m g r sin(theta)); friction
    # f = m g sin(theta) - m a needs mu >= tan(30 degrees) there: mu = 1.
    theta, m, r = math.radians(30), 2.0, 0.5
    tau = share * m * G * r * math.sin(theta)
    w, b = slope(theta, mu=1.0)
    w.add_force(ConstantTorque(tau))
    a = (m * G * math.sin(theta) * r * r + tau * r) / (b.moment + m * r * r)
    start = b.pos
    run(w, 60, 1 / 60)
    downhill = Vector(-math.cos(theta), -math.sin(theta))
    assert (b.vel).dot(downhill) == pytest.approx(a * 1.0, abs=1e-9)
    assert (b.pos - start).dot(downhill) == pytest.approx(0.5 * a, abs=1e-9)
    assert b.angular_velocity * r == pytest.approx(a * 1.0, abs=1e-9)  # rolling
    assert b.angle * r == pytest.approx(0.5 * a, abs=1e-9)


def _scenes():
    def rolling(gen: bool) -> tuple[World, Body]:
        w, b = slope(math.radians(30), 0.5, 0.0 if gen else -1.5)
        if gen:
            w.add_force(ConstantTorque(-1.5))
        return w, b

    def box_in_a_pile(gen: bool) -> tuple[World, Body]:
        w = World()
        w.add_force(Gravity((0.0, -G)))
        w.add_collider(Plane((0.0, 0.0), Vector(0, 1)))
        w.add(Body(Vector(0, 0.5), shape=Polygon.box(1, 1), friction=0.6))
        top = w.add(Body(Vector(0.2, 1.5), shape=Polygon.box(1, 1), friction=0.6))
        top.torque = 0.0 if gen else 4.0
        if gen:
            w.add_force(ConstantTorque(4.0), bodies=[top])
        return w, top

    def pinned_wheel(gen: bool) -> tuple[World, Body]:
        w = World()
        wheel = w.add(Body(Vector(0, 0), radius=0.5, mass=1.0, torque=0.0 if gen else 0.7))
        w.add_link(Pin(wheel, Vector(0, 0)))
        if gen:
            w.add_force(ConstantTorque(0.7))
        return w, wheel

    return [rolling, box_in_a_pile, pinned_wheel]


@pytest.mark.parametrize("scene", _scenes(), ids=lambda f: f.__name__)
def test_a_generators_torque_reaches_the_contacts_as_the_bodys_own_does(scene) -> None:
    (w1, b1), (w2, b2) = scene(True), scene(False)
    for _ in range(90):
        w1.step(1 / 60)
        w2.step(1 / 60)
    assert b1.angle != 0.0
    assert (b1.pos, b1.vel, b1.angle, b1.angular_velocity) == (
        b2.pos,
        b2.vel,
        b2.angle,
        b2.angular_velocity,
    )


def test_angular_drag_on_a_rolling_disc_is_first_order_in_dt() -> None:
    # Rolling under tau = -c omega: a = (m g sin(theta) r^2 - c v) / (I + m r^2), so
    # v(t) = v_inf (1 - e^(-t / T)), v_inf = m g sin(theta) r^2 / c, T = (I + m r^2) / c.
    # A body that touches something holds its drag over the step: first order.
    theta, m, r, c = math.radians(30), 2.0, 0.5, 2.0
    errors = []
    for dt in (1 / 60, 1 / 120, 1 / 240):
        w, b = slope(theta, mu=1.0)
        w.add_force(AngularDrag(c))
        run(w, round(1 / dt), dt)
        big_t = (b.moment + m * r * r) / c
        v = m * G * math.sin(theta) * r * r / c * (1 - math.exp(-1 / big_t))
        errors.append(abs(abs(b.vel) - v) / v)
        assert b.angular_velocity * r == pytest.approx(abs(b.vel), rel=1e-12)  # rolling
    assert errors[0] < 0.005  # measured 0.44% at dt = 1/60
    assert errors[0] / errors[1] == pytest.approx(2.0, rel=0.02)
    assert errors[1] / errors[2] == pytest.approx(2.0, rel=0.02)


def test_stiff_angular_drag_in_contact_warns_and_settles() -> None:
    w = World()
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Plane((0.0, 0.0), Vector(0, 1)))
    b = w.add(Body(Vector(0, 0.5), radius=0.5, mass=2.0, friction=0.2, angular_velocity=50.0))
    w.add_force(AngularDrag(1e4))  # c dt / I = 667 at dt = 1/60
    with pytest.warns(StabilityWarning, match=r"c dt / I = 666.7 .* held at I / dt"):
        w.step(1 / 60)
    # The drag takes the spin to 0 in the step; friction, slowing it too, carries it past 0
    # by at most what it gives in a step: mu g q dt / r (q = m r^2 / I = 2).
    assert abs(b.angular_velocity) <= 0.2 * G * 2 / 60 / 0.5 * (1 + 1e-12)
    spins = []
    for _ in range(60):
        w.step(1 / 60)
        spins.append(abs(b.angular_velocity))
    assert all(later <= earlier for earlier, later in zip(spins, spins[1:], strict=False))
    assert spins[-1] < 1e-9 and abs(b.vel) < 1e-9


# -- who is charged for rotation -------------------------------------------------------------


def test_only_the_bodies_that_turn_are_given_to_a_torque_and_the_others_are_untouched() -> None:
    w = World()
    w.add_force(Gravity((0.0, -G)))
    point = w.add(Body(Vector(0, 0), Vector(1, 0)))
    block = w.add(Body(Vector(2, 0), radius=0.5, fixed_rotation=True))
    paddle = w.add(Body(Vector(4, 0), radius=0.5, kinematic=True))
    disc = w.add(Body(Vector(6, 0), radius=0.5))
    fn = Counted(1.0)
    w.add_force(CallableTorque(fn))
    run(w, 30, 1 / 60)
    assert fn.sizes == [1] * 30  # the disc alone, once a step
    assert disc.angular_velocity == pytest.approx(30 / 60 / disc.moment, rel=1e-12)
    for b in (point, block, paddle):
        assert b.angle == 0.0 and b.angular_velocity == 0.0
    assert point.vel == Vector(1, -G * 0.5)  # its motion is the forces' alone


def test_a_world_none_of_whose_bodies_turn_never_calls_a_torque() -> None:
    w = World()
    balls = w.add_all(Body(Vector(i, 0), Vector(1, 2)) for i in range(5))
    fn = Counted(1.0)
    w.add_force(CallableTorque(fn))
    w.add_force(AngularDrag(1.0))
    w.add_force(Drag(0.1))
    twin = World()
    others = twin.add_all(Body(Vector(i, 0), Vector(1, 2)) for i in range(5))
    twin.add_force(Drag(0.1))
    run(w, 100, 1 / 60)
    run(twin, 100, 1 / 60)
    assert fn.sizes == []
    assert [b.pos for b in balls] == [b.pos for b in others]


def test_a_body_that_stops_turning_is_no_longer_given_a_torque() -> None:
    w = World()
    b, other = w.add_all([Body(Vector(0, 0), radius=0.5), Body(Vector(2, 0), radius=0.5)])
    fn = Counted(1.0)
    w.add_force(CallableTorque(fn))
    run(w, 3, 1 / 60)
    spin = b.angular_velocity
    b.moment = math.inf  # it never turns from now on
    run(w, 3, 1 / 60)
    assert fn.sizes == [2, 2, 2, 1, 1, 1]
    assert b.angular_velocity == spin
    assert other.angular_velocity == pytest.approx(6 / 60 / other.moment, rel=1e-12)


def test_a_torque_on_some_bodies_only_turns_those() -> None:
    w = World()
    a, b = w.add_all([Body(Vector(0, 0), radius=0.5), Body(Vector(2, 0), radius=0.5)])
    w.add_force(ConstantTorque(1.0), bodies=[b])
    run(w, 60, 1 / 60)
    assert a.angular_velocity == 0.0
    assert b.angular_velocity == pytest.approx(1.0 / b.moment, rel=1e-12)


def test_a_force_may_give_a_torque_of_its_own() -> None:
    class Propeller(Force):
        """A push along +x and a twist, both constant."""

        constant = True

        def __call__(self, t, x, v, mass):
            return Vector(2.0, 0.0) if isinstance(x, Vector) else np.array([2.0, 0.0]) + 0 * x

        def torque(self, t, angle, omega, moment):
            return 0.5

    w = World()
    b = w.add(Body(Vector(0, 0), radius=0.5, mass=1.0))
    w.add_force(Propeller())
    run(w, 60, 1 / 60)
    assert b.vel.x == pytest.approx(2.0, rel=1e-12)
    assert b.angular_velocity == pytest.approx(0.5 / b.moment, rel=1e-12)


# -- a held torque and its limit ---------------------------------------------------------------


def test_a_held_torque_is_first_order_and_warns_before_it_blows_up() -> None:
    inertia = 0.125  # a disc of 1 kg, r = 0.5 m

    def make(c: float) -> tuple[World, Body]:
        w = World()
        b = w.add(Body(Vector(0, 0), radius=0.5, mass=1.0, angular_velocity=4.0))
        w.add_force(CallableTorque(lambda t, a, om, i: -c * om, angular_damping=c))
        return w, b

    # Below the limit: omega (1 - c dt / I)^n, first order against e^(-c t / I).
    errors = []
    for dt in (1 / 60, 1 / 120):
        w, b = make(0.5)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            run(w, round(1 / dt), dt)
        errors.append(abs(b.angular_velocity - 4.0 * math.exp(-0.5 / inertia)))
    assert errors[0] / errors[1] == pytest.approx(2.0, rel=0.1)
    # Past it: c dt / I = 2.4 > 2, said before the first step, then refused before inf lands.
    w, b = make(2.4 * inertia * 60)
    with pytest.warns(StabilityWarning, match=r"c dt / I = 2\.4 .* dt < 0\.01389 s"):
        w.step(1 / 60)
    with pytest.raises(SimulationDiverged, match="spin diverged"):
        run(w, 10_000, 1 / 60)
    assert math.isfinite(b.angular_velocity) and math.isfinite(b.angle)


# -- errors a person can act on ---------------------------------------------------------------


@pytest.mark.parametrize(
    ("returned", "error", "says"),
    [
        (np.ones(3), ValueError, r"shape \(1,\), one per body .* got shape \(3,\)"),
        (float("nan"), ValueError, "not finite"),
        (np.array([math.inf]), ValueError, "not finite"),
        (None, TypeError, "got NoneType None"),
        (Vector(1, 0), TypeError, "a number, or an array"),
        ("1", TypeError, "a number, or an array"),
    ],
)
def test_a_torque_of_the_wrong_kind_is_refused_naming_the_generator(returned, error, says) -> None:
    w = World()
    b = w.add(Body(Vector(0, 0), radius=0.5, angular_velocity=1.0))

    def bad(t, angle, omega, moment):
        return returned

    w.add_force(CallableTorque(bad))
    with pytest.raises(error, match=says) as caught:
        w.step(1 / 60)
    assert "CallableTorque(<function" in str(caught.value)
    assert b.angular_velocity == 1.0 and b.angle == 0.0  # nothing moved


def test_a_torque_generator_is_refused_by_a_1d_world_naming_it() -> None:
    w = World()
    w.add(Body(0.0, 1.0))
    with pytest.raises(
        TypeError, match=r"AngularDrag\(c=0\.5\) gives a torque, and this World is 1D"
    ):
        w.add_force(AngularDrag(0.5))
    empty = World()
    empty.add_force(ConstantTorque(1.0))  # an empty World takes 2D from it
    with pytest.raises(TypeError, match="1D but this World is 2D"):
        empty.add(Body(0.0, 1.0))


def test_torque_generators_check_what_they_are_given() -> None:
    with pytest.raises(ValueError, match="tau must be finite"):
        ConstantTorque(math.nan)
    with pytest.raises(ValueError, match="c must be >= 0"):
        AngularDrag(-1.0)
    with pytest.raises(TypeError, match=r"callable fn\(t, angle, omega, moment\)"):
        CallableTorque(3.0)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="angular_damping must be >= 0"):
        CallableTorque(lambda t, a, w, i: 0.0, angular_damping=-1.0)

    class Half(Torque):
        def torque_affine(self):
            return (1.0,)

    w = World()
    w.add(Body(Vector(0, 0), radius=0.5))
    w.add_force(Half())
    with pytest.raises(TypeError, match=r"torque_affine\(\) must return \(tau0, c\)"):
        w.step(1 / 60)


def test_a_torque_without_a_torque_says_what_to_define() -> None:
    w = World()
    w.add(Body(Vector(0, 0), radius=0.5))
    w.add_force(Torque())
    with pytest.raises(NotImplementedError, match=r"define torque\(t, angle, omega, moment\)"):
        w.step(1 / 60)


def test_forces_that_give_no_torque_say_so() -> None:
    assert not Gravity((0, -1)).gives_torque and not Drag(1.0).gives_torque
    assert ConstantTorque(1.0).gives_torque and AngularDrag(1.0).gives_torque
    assert Gravity((0, -1)).torque(0.0, 0.0, 0.0, 1.0) is None
    # Its force is none: folded, and constant (the closed form still moves the bodies).
    assert AngularDrag(1.0).affine() == (0.0, 0.0, 0.0) and AngularDrag(1.0).constant
