"""The impulse of an exact impact: two discs that meet, or a disc sent into a wall.

engine.exact.pair_impacts finds the moments; this module applies what happens at one. With the unit
normal n toward a (from b's centre to a's) and the closing speed u = -(v_a - v_b).n > 0, the
impulse along n is

    J = (1 + e) u / (w_a + w_b),        e = e_a e_b,  w = 1 / m (0: a wall),

the closed-form collision of two discs: momentum is kept exactly, and with e = 1 the energy.
Coulomb friction (mu = mu_a mu_b) acts along the tangent t = (-n_y, n_x), at most mu J.

**A moving wall** (a body of a pile met from outside it: engine.exact.pair_impacts) has
w = 0 in J, and takes -P in the pile's soft step. Given to a body lighter than the one that
struck it, that impulse carries more energy than the impact had: with the wall's own w_b, the
pair's kinetic energy changes by J (J (w_a + w_b) / 2 - u), which is > 0 once
J > 2 u / (w_a + w_b), as it is when (1 + e) w_b > (1 - e) w_a; the pile must then take it
away, and at masses 1e5 apart a few iterations do not (found exploring: a 1.3 g disc struck by
a 305 kg one left at 4e8 m/s). So a moving wall whose impulse would pass that bound (``own``:
the walls' own w) is struck as the free body it is, J = (1 + e) u / (w_a + w_b), and moves on
with its own w for the rest of the impacts' step (what struck it meets it again only if it
catches it up); the pile passes on what is left at its next contact. A wall heavier than
(1 + e) / (1 - e) times what strikes it is met as before.

**Bodies that do not turn** (``bounce`` without ``Turns``, or a pair neither of which turns,
or mu = 0): friction takes up to mu J of the tangential relative momentum of the centres,
never reversing it, as it always has.

**Discs that turn** (``Turns``; engine.dynamics.rotation). Friction acts at the point of contact,
c = x_a - r_a n = x_b + r_b n. In 2D omega x p = omega (i p), so a's point moves at
v_a + omega_a (i (-r_a n)) = v_a - omega_a r_a t and b's at v_b + omega_b r_b t: the slip of
a on b there is

    s = (v_a - v_b).t - omega_a r_a - omega_b r_b

(engine.exact.soft's vt = (v_B - v_A).t - omega_B l_B - omega_A l_A with A = b, B = a). An
impulse P = J n + Jt t on a, -P on b, turns a by (-r_a n) x P / I_a = -r_a Jt / I_a (n x t =
1) and b by (r_b n) x (-P) / I_b = -r_b Jt / I_b, and the normal part turns neither (its line
passes through both centres); so Jt changes the slip by

    ds = Jt K,        K = w_a + w_b + r_a^2 / I_a + r_b^2 / I_b

(a term 0 for a body that does not turn, a wall, a kinematic body, a sleeper), and Coulomb's
law is Jt = -s / K, the impulse that stops the slip, clamped to [-mu J, mu J]: it never
reverses the slip. Each body's angular momentum about c, I omega + m (x - c) x v, is kept (the
impulse passes through c), the pair's momentum and its angular momentum about any point too,
and no energy is gained: the normal and tangential parts are decoupled (n is perpendicular to
t, and the normal impulse has no lever), and Jt = -lam s / K with 0 <= lam <= 1 changes the
energy by -lam (1 - lam / 2) s^2 / K <= 0.

Within the step a body's spin is taken on the path that ends at its end state (omega1,
theta1), as the centre is (``state_at``): omega(t) = omega1 - alpha s, s = dt - t, with alpha
its angular acceleration over the step (``turns_of``). An impact at t changes omega1 by
d omega and theta1 by d omega (dt - t): the rest of the step is turned on the new spin, as it
is flown on the new velocity.

**A wall** met on a body's new path within the step (``wall_bounce``) bounces it as the static
contacts do (engine.exact.sweep ``bounce``): v_n becomes -e v_n and friction takes up to
mu (1 + e) |v_n|, at the point of contact for a disc that turns under friction, by the same
function (engine.dynamics.rotation ``grip``), so a disc sent into a wall by an impact turns as it
would off that wall alone.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..dynamics.rotation import grip
from ..geometry.pair_math import dot, norm, state_at, unit

if TYPE_CHECKING:
    from ..dynamics.rotation import Spin
    from .contacts import Contacts

__all__ = ["Turns", "bounce", "turns_of", "wall_bounce"]


class Turns(NamedTuple):
    """The spin of the exact impacts' bodies, by local place (engine.exact.pair_impacts ``exact``):
    the end of the step's angle and angular velocity (written by the impacts), the own
    angular acceleration, and what turns."""

    angle: np.ndarray  # (nU,) rad at the step's end
    omega: np.ndarray  # (nU,) rad/s at the step's end
    alpha: np.ndarray  # (nU,) rad/s^2, constant over the step
    #: (nU,) 1 / I (1 / (kg m^2)) of those an impulse turns: 0 for a body that does not turn,
    #: a wall (a pile's body, a sleeper), a kinematic body, or one without friction.
    inv_moment: np.ndarray
    #: (nU,) m r^2 / I (engine.dynamics.rotation's q) where ``rolls``, for the walls' rule.
    q: np.ndarray
    #: (nU,) bool: the body's surface may turn (it turns, or the game turns it): its pairs
    #: with friction take the rule of discs that turn.
    lever: np.ndarray
    #: (nU,) bool: turned by a wall's friction (``wall_bounce``): it turns, has a lever, friction
    #: and moves (engine.dynamics.rotation ``Spin.rolls``).
    rolls: np.ndarray


def turns_of(
    spin: Spin | None,
    store: Any,
    U: np.ndarray,
    w: np.ndarray,
    dt: float,
    resting: np.ndarray | None = None,
) -> Turns | None:
    """The ``Turns`` of the World rows U (inverse masses w, 0 for the walls), from the step's
    ``spin`` (engine.dynamics.rotation); None where no body of them turns with friction (then the
    impacts are those of bodies that do not turn, bit for bit). Without a ``spin`` (nothing
    spins this step: every omega and torque is 0), the store's bodies that turn start at rest.

    The angular acceleration over the step is the spin's own (the torque's), but for a disc
    ``resting`` on a face (by local place; None: none), which the static contacts turned all
    the step (rolling on a slope): the mean of what they did, (omega1 - omega0) / dt, as its
    centre's acceleration is (engine.pipeline.stepping)."""
    fr = store.friction[U]
    if spin is None:
        if not store.turns_any:
            return None
        inv_moment = store.inv_moment[U]
        lever = inv_moment > 0.0
        if not (lever & (fr > 0.0)).any():
            return None
        r = store.radius[U]
        # (Two arrays: the impacts write omega in place, and alpha must stay 0.)
        angle, omega, alpha = store.angle[U].copy(), np.zeros(len(U)), np.zeros(len(U))
        q = store.mass[U] * r * r * inv_moment
    else:
        lever = spin.turns[U]
        if not (lever & (fr > 0.0)).any():
            return None
        angle, omega = spin.angle[U].copy(), spin.omega[U].copy()
        alpha = spin.alpha[U]
        if resting is not None and resting.any():
            alpha = np.where(resting, (omega - spin.omega0[U]) * (1.0 / dt), alpha)
        inv_moment, q = store.inv_moment[U], spin.q[U]
    moves = lever & (fr > 0.0) & (w > 0.0)
    return Turns(angle, omega, alpha, np.where(moves, inv_moment, 0.0), q, lever, moves & (q > 0.0))


def bounce(
    pa: np.ndarray,
    pb: np.ndarray,
    t: np.ndarray,
    X: np.ndarray,
    V: np.ndarray,
    A: np.ndarray,
    w: np.ndarray,
    r: np.ndarray,
    e: np.ndarray,
    mu: np.ndarray,
    dt: float,
    turns: Turns | None = None,
    own: np.ndarray | None = None,
) -> tuple[np.ndarray, ...]:
    """Apply the impulses of impacts (pa, pb) (local places, no body twice) at times t (s, in
    the step), in place on the end state (X, V) and on ``turns``' spin; return them for the
    events: (pa, pb, point, normal toward a, impulse on a, t). ``own``: the inverse masses
    (1/kg) the bodies have of their own, where a pile's bodies are walls in ``w`` (None: none
    is), for the bound on a moving wall's impulse (the module's text)."""
    xa, va = state_at(pa, t, X, V, A, dt)
    xb, vb = state_at(pb, t, X, V, A, dt)
    d = xa - xb
    # hypot, not sqrt(d.d): centres 1e-200 apart would square to 0; coincident ones
    # part straight up (engine.geometry.pair_math.unit).
    nrm = unit(d, np.hypot(d[:, 0], d[:, 1]))
    vr = va - vb
    vn = dot(vr, nrm)  # < 0: closing
    # Two bodies that neither moves (a pile's, met as walls, or the game's) take no impulse.
    w2 = w[pa] + w[pb]
    wsum = np.where(w2 > 0.0, w2, math.inf)
    J = -(1.0 + e[pa] * e[pb]) * vn / wsum
    if own is not None:
        # A moving wall whose impulse would give the pair energy (past 2 |vn| / (w_a + w_b)
        # with its own w: the module's text) is struck as the free body it is, and moves on
        # from here with its own w, so that what struck it meets it again only if it catches
        # it up; its friction is then that of two free bodies too.
        w2o = own[pa] + own[pb]
        wo = np.where(w2o > 0.0, w2o, math.inf)
        past = J > -2.0 * vn / wo
        if past.any():
            J = np.where(past, -(1.0 + e[pa] * e[pb]) * vn / wo, J)
            w2, wsum = np.where(past, w2o, w2), np.where(past, wo, wsum)
            for side in (pa[past], pb[past]):
                w[side] = own[side]
    # Friction: up to mu J against the tangential relative velocity, never reversing it.
    mu2 = mu[pa] * mu[pb]
    tang = vr - nrm * vn[:, None]
    vt = norm(tang)
    Jt = np.minimum(mu2 * J, vt / wsum)
    tdir = tang / np.where(vt > 0.0, vt, 1.0)[:, None]
    P = nrm * J[:, None] - tdir * Jt[:, None]  # impulse on a; -P on b
    rem = (dt - t)[:, None]
    if turns is not None:
        k = np.flatnonzero((turns.lever[pa] | turns.lever[pb]) & (mu2 > 0.0))
        if len(k):
            P[k] = _at_the_point(pa[k], pb[k], t[k], nrm[k], vr[k], w2[k], J[k], mu2[k], r,
                                 dt, turns)  # fmt: skip
    dva, dvb = P * w[pa, None], -P * w[pb, None]
    V[pa] += dva
    V[pb] += dvb
    X[pa] += dva * rem
    X[pb] += dvb * rem
    return pa, pb, xb + nrm * r[pb, None], nrm, P, t


def _at_the_point(
    a: np.ndarray,
    b: np.ndarray,
    t: np.ndarray,
    n: np.ndarray,
    vr: np.ndarray,
    w2: np.ndarray,
    J: np.ndarray,
    mu2: np.ndarray,
    r: np.ndarray,
    dt: float,
    turns: Turns,
) -> np.ndarray:
    """The impulses on a (J n + Jt t) of impacts between discs some of which turn, with
    friction at the point of contact (the module's text); the spins are changed here."""
    rem = dt - t
    ra, rb = r[a], r[b]
    ia, ib = turns.inv_moment[a], turns.inv_moment[b]
    # Each spin at the moment of the impact, on its path to the step's end.
    oa = turns.omega[a] - turns.alpha[a] * rem
    ob = turns.omega[b] - turns.alpha[b] * rem
    tg = np.stack([-n[:, 1], n[:, 0]], axis=1)
    slip = dot(vr, tg) - oa * ra - ob * rb
    K = w2 + ra * ra * ia + rb * rb * ib
    K = np.where(K > 0.0, K, math.inf)
    cap = np.maximum(mu2 * J, 0.0)
    Jt = np.clip(-slip / K, -cap, cap)
    dwa, dwb = -ra * ia * Jt, -rb * ib * Jt
    turns.omega[a] += dwa
    turns.omega[b] += dwb
    turns.angle[a] += dwa * rem
    turns.angle[b] += dwb * rem
    return n * J[:, None] + tg * Jt[:, None]


def wall_bounce(
    contacts: Contacts,
    U: np.ndarray,
    t0: float,
    i: np.ndarray,
    t: np.ndarray,
    f: np.ndarray,
    nrm: np.ndarray,
    X: np.ndarray,
    V: np.ndarray,
    A: np.ndarray,
    w: np.ndarray,
    r: np.ndarray,
    e: np.ndarray,
    mu: np.ndarray,
    dt: float,
    turns: Turns | None = None,
) -> None:
    """Bounce local bodies i off faces f at times t, as the static contacts do: the normal
    speed v_n becomes -e v_n and friction takes up to mu (1 + e) |v_n| off the tangential
    speed, never reversing it (e, mu: the body's times the face's); for a disc that turns
    under friction (``turns.rolls``), off the slip at the point of contact (engine.dynamics.rotation
    ``grip``, as engine.exact.sweep's ``bounce``). The contacts record the bounce as an event of
    World row U[i] at time t0 + t."""
    faces = contacts.faces
    x, v = state_at(i, t, X, V, A, dt)
    vn = np.minimum(dot(v, nrm), 0.0)
    ee, mm = e[i] * faces.e[f], mu[i] * faces.mu[f]
    tang = v - nrm * dot(v, nrm)[:, None]
    speed_t = norm(tang)
    keep = np.maximum(speed_t + mm * (1.0 + ee) * vn, 0.0)
    scale = keep / np.where(speed_t > 0.0, speed_t, 1.0)
    v_new = tang * scale[:, None] - nrm * (ee * vn)[:, None]
    if turns is not None:
        k = np.flatnonzero(turns.rolls[i])
        if len(k):
            ik, nk, rem = i[k], nrm[k], dt - t[k]
            tg = np.stack([-nk[:, 1], nk[:, 0]], axis=1)
            u = dot(v[k], tg)
            om = turns.omega[ik] - turns.alpha[ik] * rem  # the spin at the bounce
            cap = mm[k] * (1.0 + ee[k]) * -vn[k]  # the most friction takes off u
            du, om_new = grip(u, om, turns.q[ik], r[ik], cap)
            v_new[k] = tg * (u + du)[:, None] - nk * (ee[k] * vn[k])[:, None]
            dw = om_new - om
            turns.omega[ik] += dw
            turns.angle[ik] += dw * rem
    dv = v_new - v
    V[i] += dv
    X[i] += dv * (dt - t)[:, None]
    # The event's impulse is the change of momentum, dv m = dv / w (none for a body no
    # impulse moves, w = 0: a pile's, met as a moving wall, whose path the soft step takes).
    wi = w[i]
    impulse = dv / np.where(wi > 0.0, wi, np.inf)[:, None]
    contacts.record(U[i], faces.owner[f], x - nrm * r[i, None], nrm, impulse, t0 + t)
