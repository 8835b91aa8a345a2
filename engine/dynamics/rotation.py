"""Rotation: the angle and angular velocity of bodies that turn, over one step.

A body that turns (``Body.turns``: a disc with a moment of inertia I, not ``fixed_rotation``,
not kinematic) has an angle theta (rad, counter-clockwise) and an angular velocity omega
(rad/s). Its own torque tau (N m, ``Body.torque``) is constant over a step, so the angular
acceleration alpha = tau / I is too, and the closed form is exact:

    theta(t) = theta0 + omega0 t + alpha t^2 / 2,      omega(t) = omega0 + alpha t.

That is what a step does to every body that turns and meets nothing (``Spin.free``). The
torques of the World's generators (engine.forces: ``ConstantTorque``, ``AngularDrag``, a
user's ``torque``) add to it (engine.dynamics.torquefield): an angular drag c (N m s) by its own
closed form, omega -> tau / c + (omega0 - tau / c) e^(-c t / I), exact too. A body
that touches a collider turns under its friction too (engine.exact.sweep, engine.exact.resting:
rolling, slipping, the spin a bounce gives), the discs of a pile under its rows' friction (the soft
step's lever arms: engine.exact.soft, ``Arms``; engine.exact.pile), and two discs that meet at an
exact impact, outside a pile, turn each other by the friction at their point of contact
(engine.exact.pair_bounce; tests/test_impact_spin.py); a sleeping body stops turning.

Model no more than a scene needs: a point, a body with corners (in this version), a kinematic
body or one with ``fixed_rotation=True`` has 1 / I = 0, and a World none of whose bodies turn
does none of this (``BodyStore.turns_any``).

For contacts, a body that turns is described by q = m r^2 / I (2 for a solid disc, 1 for a
hoop, 0 for what does not turn): the point of a disc of radius r that touches a surface of
unit normal n (toward the disc) is at -r n from its centre, and moves along the tangent
t = (-n_y, n_x) at the slip speed s = v.t - omega r. A tangential impulse J t there changes
v.t by J / m and omega by -J r / I, so s by J (1 + q) / m.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

__all__ = ["Spin", "Rolling", "grip", "rolling"]


@dataclass
class Spin:
    """The rotation of a World's bodies over one step, by World row: where it started
    (``angle0``, ``omega0``) and where it ends (``angle``, ``omega``, written by the contacts
    for the bodies they move), with each body's ``q`` = m r^2 / I (0: does not turn) and own
    angular acceleration ``alpha`` = tau / I (rad/s^2)."""

    angle0: np.ndarray  # (N,) rad
    omega0: np.ndarray  # (N,) rad/s
    angle: np.ndarray  # (N,) rad, after the step
    omega: np.ndarray  # (N,) rad/s, after the step
    q: np.ndarray  # (N,) m r^2 / I, no unit
    alpha: np.ndarray  # (N,) rad/s^2
    turns: np.ndarray  # (N,) bool: the rows that turn

    @classmethod
    def free(
        cls,
        angle0: np.ndarray,
        omega0: np.ndarray,
        inv_moment: np.ndarray,
        torque: np.ndarray,
        mass: np.ndarray,
        radius: np.ndarray,
        dt: float,
        drag: np.ndarray | None = None,
        kinematic: np.ndarray | None = None,
    ) -> Spin:
        """Every body turned freely for ``dt`` s by the closed form (exact for a constant
        torque, and with an angular ``drag`` c (N m s, by row; None: none) for the torque
        tau - c omega); the bodies that do not turn (1 / I = 0) keep their angle, but for the
        ``kinematic`` ones (N,) the game turns, at their own omega (they count as turning).

        Under drag, with k = c / I and omega_inf = tau / c, omega(t) = omega_inf +
        (omega0 - omega_inf) e^(-k t) and theta(t) = theta0 + omega_inf t + (omega0 -
        omega_inf) (1 - e^(-k t)) / k: exact at any dt. The contacts take the spin's
        ``alpha`` as constant over the step (first order in dt for a body they touch): under
        drag it is the torque at the step's start over I, (tau - c omega0) / I, with k held to
        at most 1 / dt, so that the drag never carries a spin past omega_inf within a step by
        itself (an explicit drag would, past k dt = 2; friction in the same step still may).
        The mean of the free step, (omega(dt) - omega0) / dt, is stable too, but 13 times
        further off for a rolling disc, whose spin decays at c / (I + m r^2), not c / I
        (measured at dt = 1/60)."""
        turns = inv_moment > 0.0
        if kinematic is not None:
            turns = turns | (kinematic & (omega0 != 0.0))
        alpha = torque * inv_moment
        angle = angle0 + omega0 * dt + alpha * (0.5 * dt * dt)
        omega = omega0 + alpha * dt
        if drag is not None:
            slowed = turns & (drag > 0.0)
            if slowed.any():
                c = drag[slowed]
                k = c * inv_moment[slowed]
                w_inf = torque[slowed] / c
                u = omega0[slowed] - w_inf
                e = np.expm1(-k * dt)  # e^(-k dt) - 1, exact for small k dt too
                omega[slowed] = omega0[slowed] + u * e
                angle[slowed] = angle0[slowed] + w_inf * dt - u * (e / k)
                alpha = alpha.copy()
                alpha[slowed] = -u * np.minimum(k, 1.0 / dt)
        q = mass * radius * radius * inv_moment
        return cls(angle0, omega0, angle, omega, q, alpha, turns)

    def rolls(self, friction: np.ndarray) -> np.ndarray:
        """Which bodies turn under friction (they turn, have a surface to roll on, r > 0, and
        friction), by World row. A point given a moment turns freely: it has no lever."""
        return self.turns & (self.q > 0.0) & (friction > 0.0)


class Rolling(NamedTuple):
    """The spin of the bodies a sweep takes that turn under friction (``rolling``), by place
    among its rows: angle (rad) and angular velocity (rad/s) at the step's start (the sweep
    writes ``omega`` as it goes), q = m r^2 / I, own angular acceleration (rad/s^2), and
    ``rolls``: which of the rows turn under friction (the others keep their free spin)."""

    angle: np.ndarray
    omega: np.ndarray
    q: np.ndarray
    alpha: np.ndarray
    rolls: np.ndarray

    def one(self, k: int) -> tuple[float, float, float, float] | None:
        """Place k's (angle, omega, q, alpha) as floats, or None if it does not roll."""
        if not self.rolls[k]:
            return None
        return (
            float(self.angle[k]),
            float(self.omega[k]),
            float(self.q[k]),
            float(self.alpha[k]),
        )


def rolling(spin: Spin | None, rows: np.ndarray, friction: np.ndarray) -> Rolling | None:
    """The ``Rolling`` of the World ``rows`` (``friction`` by World row), or None when none of
    them turns under friction (then the sweep is that of bodies that do not turn)."""
    if spin is None:
        return None
    rolls = spin.turns[rows] & (spin.q[rows] > 0.0) & (friction[rows] > 0.0)
    if not rolls.any():
        return None
    return Rolling(spin.angle0[rows], spin.omega0[rows], spin.q[rows], spin.alpha[rows], rolls)


def grip(
    u: np.ndarray, omega: np.ndarray, q: np.ndarray, r: np.ndarray, cap: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Friction at the point of contact of discs bounced off a surface (row by row): the
    change du of the tangential speed u = v.t and the angular velocity after it. The slip
    s = u - omega r is taken toward 0 by the tangential impulse per mass du, which changes it
    by du (1 + q) (the module's text), by at most ``cap`` (mu (1 + e) |v_n|: the friction
    impulse is at most mu times the normal one), never reversing it; omega becomes
    omega - du q / r. The angular momentum about the point of contact, I omega + m r u
    (n x t = 1, the centre at r n from the point), is kept: I (-du q / r) + m r du = 0."""
    slip = u - omega * r
    du = -np.copysign(np.minimum(np.abs(slip) / (1.0 + q), cap), slip)
    return du, omega - du * q / r
