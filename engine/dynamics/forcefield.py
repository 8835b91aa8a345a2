"""The forces on many bodies, compiled once: what the World and Particles evaluate every step.

Constant forces and linear drag are folded, once, into two per-body arrays, so that the
acceleration of every body is

    a = a0 - c v  (+ the forces that are neither, evaluated each call)

with a0 = own acceleration + gravity + constant forces / m + k air / m and c = (sum of drag
coefficients k) / m. Adding two arrays of the same shape costs a fraction of broadcasting a
small vector over them every step (measured: a (2,) vector broadcast over (1000, 2) is ~5x the
cost of adding a (1000, 2) array), so the per-body arrays take the full shape of x.

The model also keeps, per body, what the stability limits need without calling any force:
omega = sqrt(sum of spring stiffness / m) (rad/s) and the velocity decay rate sum k / m (1/s).

>>> import numpy as np
>>> from engine.forces import Drag, Gravity
>>> model = ForceModel.compile(
...     np.array([2.0]), np.zeros((1, 2)), [(Gravity((0, -10)), None), (Drag(1.0), None)]
... )
>>> model.accel(0.0, np.zeros((1, 2)), np.array([[4.0, 0.0]])).tolist()   # g - (k/m) v
[[-2.0, -10.0]]
>>> model.rate.tolist(), model.all_constant
([0.5], False)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..forces import Force
from ..vector import Vector

__all__ = ["ForceModel", "Attachment"]

#: A force and the rows of the bodies it acts on (None: every body).
Attachment = tuple[Force, Any]


def _array(value: Any) -> Any:
    """A float stays a float; a Vector becomes a (2,) array."""
    return np.array(tuple(value), dtype=float) if isinstance(value, Vector) else float(value)


@dataclass
class ForceModel:
    """Forces folded into per-body arrays: a = a0 - c v + sum(general) / m."""

    a0: Any  # per-body constant acceleration, shaped like x
    c: Any  # per-body linear damping rate (1/s), shaped like v, or None when no drag
    general: list[Attachment]  # forces called every evaluation, with their rows or None
    mass: Any  # per-body mass, shaped like x
    all_constant: bool  # every force is constant: the closed form is exact
    omega: np.ndarray  # per-body sqrt(sum stiffness / m) (rad/s)
    rate: np.ndarray  # per-body sum damping / m (1/s), of every force, for the stability limits
    folded: Any  # the part of a0 the forces give (a0 minus the bodies' own accelerations)
    #: How many times ``accel`` has run: the supported way to count force evaluations.
    evaluations: int = 0
    #: Springs between bodies that the closed form holds too (engine.exact.spring_step), if any.
    springs: bool = False

    @classmethod
    def compile(
        cls, masses: np.ndarray, own_acc: np.ndarray, attached: Sequence[Attachment]
    ) -> ForceModel:
        """Fold ``attached`` forces for bodies of ``masses`` (N,) and own accelerations.

        ``own_acc`` has the shape of x: (N,) in 1D, (N, 2) in 2D. Each attachment's rows are an
        index array into the bodies, or None for all of them.
        """
        n = len(masses)
        shape = own_acc.shape
        # Per-body arrays take the full shape of x, (N, 2) in 2D, not (N, 1): numpy
        # multiplies two arrays of one shape several times faster than it broadcasts.
        mass = masses if len(shape) == 1 else np.repeat(masses[:, None], shape[1], axis=1)
        folded = np.zeros(shape)
        damping = np.zeros(n)
        stiffness = np.zeros(n)
        general: list[Attachment] = []
        all_constant = True
        drag = np.zeros(n)  # the folded drag coefficients (N s/m)
        for force, rows in attached:
            sel = slice(None) if rows is None else rows
            # Every force says its stiffness and damping for the stability limits, folded
            # or not (a gusty wind, a user's callable force that declares them).
            stiffness[sel] += force.stiffness
            damping[sel] += force.damping
            all_constant = all_constant and force.constant
            parts = force.affine()
            if parts is None:
                general.append((force, rows))
                continue
            accel, f0, k = parts
            # m a = m a0 + f0 - k v  =>  a = a0 + f0 / m - (k / m) v
            folded[sel] += _array(accel) + _array(f0) / mass[sel]
            drag[sel] += k
        rate = damping / masses if n else damping
        c = None
        if np.any(drag):
            c_rows = drag / masses
            c = c_rows if len(shape) == 1 else np.repeat(c_rows[:, None], shape[1], axis=1)
        omega = np.sqrt(stiffness / masses) if n else stiffness
        return cls(own_acc + folded, c, general, mass, all_constant, omega, rate, folded)

    @property
    def affine(self) -> bool:
        """True when every force is folded: a = a0 - c v, with no force to call."""
        return not self.general

    def accel(self, t: float, x: Any, v: Any) -> Any:
        """Acceleration of every body at time t (s) in state (x, v): a0 - c v + general / m."""
        self.evaluations += 1
        a = self.a0 if self.c is None else self.a0 - self.c * v
        if self.general:
            a = a.copy() if self.c is None else a
            for force, rows in self.general:
                if rows is None:
                    a += force(t, x, v, self.mass) / self.mass
                elif len(rows):
                    m = self.mass[rows]
                    a[rows] += force(t, x[rows], v[rows], m) / m
        return a

    def accel_of(self, row: int, t: float, x: Any, v: Any) -> Any:
        """Acceleration of the one body in ``row`` (shaped like a row of x), at time t (s)."""
        a = self.a0[row] if self.c is None else self.a0[row] - self.c[row] * v[row]
        for force, rows in self.general:
            if rows is None or row in rows:
                m = self.mass[row : row + 1]
                a = a + force(t, x[row : row + 1], v[row : row + 1], m)[0] / m[0]
        return a

    def set_own_acc(self, row: int, new: Any) -> None:
        """One body's own acceleration is now ``new``: update its a0 entry, nothing else."""
        self.a0[row] = new + self.folded[row]
