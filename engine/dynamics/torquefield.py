"""The torques of a World's generators, compiled once: what a step adds to the bodies' own.

A force generator may give a torque (engine.forces: ``Force.torque``, ``Torque``). Only the
bodies that turn are charged for it (a point, a kinematic body or one with ``fixed_rotation``
never is), and a World with no generator that gives one, or no body that turns, has no model
at all (``WorldState.torques``: None), so its steps do no more than before. The torques are
folded, once, into per-body arrays (by World row):

    tau = own torque + tau0 - c omega  (+ the generators that are neither, called each step)

* tau0 (N m) and c (N m s) from ``torque_affine()``: the step turns a free body by the exact
  closed form of a constant torque with angular drag (``engine.dynamics.rotation.Spin.free``);
* every other generator is called once a step, at its start, with the angle, angular velocity
  and moment of the bodies it acts on that turn (arrays of shape (k,)), and its torque is held
  over the step (first order in dt), checked: a number or k of them, finite;
* what the contacts, piles and joints read is the step's spin (``Spin``), so a generator's
  torque reaches a disc that rolls, a box in a pile or a wheel on a hinge the same way the
  body's own torque does.

The hold's limit: a held torque that slows a spin (``angular_damping`` c, N m s) takes
omega (1 - c dt / I) a step, which overshoots and grows past c dt / I = 2; the World warns
before the first such step (``StabilityWarning``), and a spin that turns non-finite (or
past ``SPIN_BOUND``) raises ``SimulationDiverged`` before it is kept. A folded drag has no limit.

>>> import numpy as np
>>> from engine.forces import AngularDrag, ConstantTorque
>>> model = TorqueModel.compile(
...     np.array([0.5, 0.0]), [(ConstantTorque(2.0), None), (AngularDrag(0.1), None)]
... )
>>> model.tau0.tolist(), model.c.tolist(), model.drives   # the second body does not turn
([2.0, 0.0], [0.1, 0.0], True)
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..forces import Force
from ..stability import SimulationDiverged, StabilityWarning
from ..vector import Vector
from .forcefield import Attachment

__all__ = ["TorqueModel", "HOLD_LIMIT", "SPIN_BOUND"]

#: The decay limit c dt / I of a torque held over a step from its start (explicit Euler's).
HOLD_LIMIT = 2.0
#: A spin (rad/s) or angle (rad) this large is a blow-up under way, refused before it is kept.
SPIN_BOUND = 1e150


@dataclass
class TorqueModel:
    """Generators' torques on a World's bodies that turn, by World row (N of them)."""

    tau0: np.ndarray | None  # (N,) folded constant torques (N m), None when none
    c: np.ndarray | None  # (N,) folded angular drag (N m s), None when none
    general: list[tuple[Force, np.ndarray]]  # called each step, with their rows that turn
    rate: np.ndarray  # (N,) held angular drag / I (1/s): the hold's stability limit
    #: How many times a general generator's torque has been called.
    evaluations: int = 0

    @classmethod
    def compile(cls, inv_moment: np.ndarray, attached: Sequence[Attachment]) -> TorqueModel | None:
        """Fold the generators of ``attached`` (force, rows or None for all) that give a torque,
        for bodies of inverse moments ``inv_moment`` (N,) (0: does not turn); None when none of
        them gives one to a body that turns."""
        n = len(inv_moment)
        turns = inv_moment > 0.0
        every = np.flatnonzero(turns)
        tau0, c, rate = np.zeros(n), np.zeros(n), np.zeros(n)
        general: list[tuple[Force, np.ndarray]] = []
        for force, rows in attached:
            if not force.gives_torque:
                continue
            sel = every if rows is None else rows[turns[rows]]
            if not len(sel):
                continue
            parts = force.torque_affine()
            if parts is None:
                general.append((force, sel))
                rate[sel] += force.angular_damping * inv_moment[sel]
                continue
            t0, k = _affine(force, parts)
            tau0[sel] += t0
            c[sel] += k
        if not general and not tau0.any() and not c.any():
            return None
        return cls(tau0 if tau0.any() else None, c if c.any() else None, general, rate)

    @property
    def drives(self) -> bool:
        """Whether a generator may turn a body at rest (a torque other than drag)."""
        return self.tau0 is not None or bool(self.general)

    def at(
        self, t: float, own: np.ndarray, angle: np.ndarray, omega: np.ndarray, moment: np.ndarray
    ) -> np.ndarray:
        """Every body's torque (N m) for the step from time ``t`` (s): its ``own`` plus tau0 plus
        the general generators' at (angle, omega), drag apart (``c``). A new array."""
        tau = own + self.tau0 if self.tau0 is not None else own.copy()
        for force, rows in self.general:
            self.evaluations += 1
            got = force.torque(t, angle[rows], omega[rows], moment[rows])
            tau[rows] += _checked(force, got, t, len(rows))
        return tau

    def unstable(self, dt: float) -> str | None:
        """Why the held torques blow up at ``dt`` (s), or None while c dt / I < 2 for all."""
        worst = float(self.rate.max()) if self.general else 0.0
        if worst * dt < HOLD_LIMIT:
            return None
        names = ", ".join(repr(f) for f, _ in self.general if f.angular_damping > 0.0)
        return (
            f"the torque of {names} is held over each step from its value at the step's "
            f"start (first order in dt): with its angular_damping the spin decays at "
            f"c / I = {worst:.4g} 1/s, and c dt / I = {worst * dt:.4g} at dt={dt:g} s is past "
            f"the hold's limit {HOLD_LIMIT:g}: each step overshoots and the spin grows; use "
            f"dt < {HOLD_LIMIT / worst:.4g} s, or give a drag tau0 - c omega as AngularDrag(c) "
            f"(or a torque_affine()), which is exact at any dt"
        )

    def capped(self, dt: float, inv_moment: np.ndarray) -> str | None:
        """Why a folded drag is held short for the bodies that touch something at ``dt`` (s):
        past c dt / I = 1 their step holds it at I / dt (engine.dynamics.rotation.Spin.free), or
        None."""
        if self.c is None:
            return None
        worst = float((self.c * inv_moment).max())
        if worst * dt <= 1.0:
            return None
        return (
            f"an angular drag is held over each step for the bodies it turns that touch "
            f"something (a collider, a pile, a joint): first order in dt, and with c / I = "
            f"{worst:.4g} 1/s, c dt / I = {worst * dt:.4g} at dt={dt:g} s is past 1, where it is "
            f"held at I / dt so as never to reverse a spin: such a body turns (a disc rolls) as "
            f"under a weaker drag; a body that touches nothing is exact. Use dt < "
            f"{1.0 / worst:.4g} s for it to hold in full"
        )

    def warn_if_unstable(
        self, dt: float, warned: set[Any], stacklevel: int, inv_moment: np.ndarray, touches: bool
    ) -> None:
        """Warn (StabilityWarning) once per (dt, rates) when the held torques blow up at dt, or
        (``touches``: the World has contacts or joints) a drag is held short."""
        for kind, message in (
            ("held torque", self.unstable(dt)),
            ("capped drag", self.capped(dt, inv_moment) if touches else None),
        ):
            if message is None:
                continue
            key = (kind, dt, message)
            if key not in warned:
                warned.add(key)
                warnings.warn(message, StabilityWarning, stacklevel=stacklevel + 1)

    def check_finite(
        self, angle: np.ndarray, omega: np.ndarray, name: str, dt: float, t: float
    ) -> None:
        """SimulationDiverged if a spin turned non-finite, or past ``SPIN_BOUND`` (a blow-up
        under way: the held torques are called on it next), in the step from ``t`` (s)."""
        with np.errstate(over="ignore", invalid="ignore"):
            total = float(np.add.reduce(np.abs(angle)) + np.add.reduce(np.abs(omega)))
        if total < SPIN_BOUND:
            return
        with np.errstate(invalid="ignore"):
            bad = np.flatnonzero(~((np.abs(angle) < SPIN_BOUND) & (np.abs(omega) < SPIN_BOUND)))
        bad = bad.tolist()
        limit = HOLD_LIMIT / float(self.rate.max()) if self.general and self.rate.any() else None
        hint = "" if limit is None else f"; the torques held are stable only for dt < {limit:.4g} s"
        raise SimulationDiverged(
            f"the spin diverged in the step from t={t:g} s with dt={dt:g} s: body "
            f"{', '.join(map(str, bad[:5]))}{' ...' if len(bad) > 5 else ''} would turn "
            f"non-finite (nan or inf) or past {SPIN_BOUND:g} rad or rad/s{hint}. The last "
            f"finite state is kept.",
            integrator=name,
            dt=dt,
            t=t,
            max_stable_dt=limit,
        )


def _affine(force: Force, parts: Any) -> tuple[float, float]:
    """(tau0 N m, c N m s) of ``force.torque_affine()``, checked: finite, c >= 0."""
    try:
        t0, k = (float(p) for p in parts)
    except (TypeError, ValueError):
        raise TypeError(
            f"{force!r}.torque_affine() must return (tau0, c): two numbers (N m, N m s) for a "
            f"torque tau0 - c omega, or None; got {parts!r}"
        ) from None
    if not (math.isfinite(t0) and math.isfinite(k) and k >= 0.0):
        raise ValueError(
            f"{force!r}.torque_affine() must return a finite tau0 (N m) and a finite c >= 0 "
            f"(N m s), got {parts!r}"
        )
    return t0, k


def _checked(force: Force, got: Any, t: float, k: int) -> Any:
    """A generator's torque as a float or a (k,) array, or TypeError / ValueError naming it."""
    valid = (
        f"a torque in N m: a number, or an array of shape ({k},), one per body it acts on that "
        f"turns"
    )
    if got is None or isinstance(got, (Vector, str, bytes)):
        raise TypeError(
            f"{force!r}.torque(t, angle, omega, moment) must return {valid}; got "
            f"{type(got).__name__} {got!r} at t={t:g} s"
        )
    try:
        arr = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(
            f"{force!r}.torque(t, angle, omega, moment) must return {valid}; got "
            f"{type(got).__name__} {got!r} at t={t:g} s"
        ) from None
    if arr.shape not in ((), (k,)):
        raise ValueError(
            f"{force!r}.torque(t, angle, omega, moment) must return {valid}; got shape "
            f"{arr.shape} ({got!r}) at t={t:g} s"
        )
    if not np.isfinite(arr).all():
        raise ValueError(
            f"{force!r}.torque(t, angle, omega, moment) returned a torque that is not finite "
            f"at t={t:g} s: {got!r}; it must be {valid}, each finite"
        )
    return arr
