"""The fast affine kernel: either Euler method on forces that are all folded (a = a0 - c v)
is a fixed affine map of the state, taken in four in-place array operations a step.

Semi-implicit Euler is v' = v + a dt, then x' = x + v' dt; explicit Euler moves x with the
old v first. With a = a0 - c v, v' = (1 - c dt) v + a0 dt = D v + B, with D and B computed
once per dt. (Without drag, D = 1 and v' = v + a0 dt bit for bit as the integrator functions
compute it.) No temporaries: the new positions go into the buffer of the old previous
positions.

No finiteness check is needed: the kernel gets a budget of steps proved not to overflow
(``safe_steps``), and is rebuilt, or the checked general step taken, when it is spent or
anything is written by hand. The World's state makes it and gives it its budget
(engine.pipeline.world_state, ``WorldState.prepare_affine``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .forcefield import ForceModel
from .store import BodyStore

__all__ = ["EULERS", "SAFE", "AffineKernel", "StepCount", "safe_steps"]

_mul, _add = np.multiply, np.add

#: The methods the World steps by its affine kernel when every force is folded.
EULERS = ("semi_implicit_euler", "explicit_euler")

#: Entries below this in size cannot overflow in one more step of the affine kernel.
SAFE = 1e300


def safe_steps(x_max: float, v_max: float, d: float, b: float, dt: float) -> int:
    """How many affine Euler steps surely keep every entry below 1e300 (0 to 2^20).

    From |x| <= X, |v| <= V and v' = D v + B, x' = x + v dt (v old or new), with d = max |D|
    and b = max |B|: after m steps |v| <= q (V + m b) with q = max(1, d)^m, and
    |x| <= X + m dt q (V + m b). The bound doubles m while it stays below 1e300 / 2 (the
    factor 2 is far above the round-off of 2^20 steps, ~1e-10 relative).
    """
    best = 0
    m = 1
    while m <= 2**20:
        q = max(1.0, d) ** m if d <= 1.0 or m * math.log(d) < 690.0 else math.inf
        v_m = q * (v_max + m * b)
        x_m = x_max + m * dt * v_m
        if not 2.0 * (x_m + v_m) < SAFE:
            break
        best = m
        m *= 2
    return best


class StepCount:
    """A World's count of steps since its time base (n in t = t_base + n dt), written by
    every step (the affine kernel adds to it without a call)."""

    __slots__ = ("n",)

    def __init__(self) -> None:
        self.n = 0


@dataclass(slots=True)
class AffineKernel:
    """An Euler step for affine forces at one dt (s), folded: v' = D v + B."""

    dt: float
    model: ForceModel
    store: BodyStore
    explicit: bool  # explicit Euler (x moves with the old v) rather than semi-implicit
    damp: Any  # D = 1 - c dt, shaped like v, or None without drag
    kick: Any  # B = a0 dt, shaped like v
    damp_max: float  # max |D| (1.0 without drag)
    kick_max: float  # max |B|
    count: StepCount  # the World's count of steps since its time base
    n_stop: int = 0  # the World's step count (of this dt) up to which no step can overflow
    n_from: int = 0  # the step count at which that proof was made
    taken: int = 0  # steps taken under earlier proofs (one force evaluation each)

    def take(self, dt: float) -> bool:
        """Take one step of ``dt`` (s) if it is this kernel's and within its budget."""
        count = self.count
        # type(dt) is float: True == 1.0 and 1 == 1.0, so without it step(True) after
        # step(1.0) would skip check_dt and run a step of "True" seconds.
        if not (count.n < self.n_stop and type(dt) is float and self.dt == dt):
            return False
        # The fixed cost per step is what small scenes pay, so this path makes no call it
        # can avoid. A kernel exists only while nothing has changed since it was made (the
        # World drops it), and its budget only while no state was written by hand.
        store = self.store
        v, x, x_new = store.v, store.x, store.prev_x
        if self.explicit:
            _mul(v, dt, x_new)
            _add(x, x_new, x_new)
        if self.damp is not None:
            _mul(v, self.damp, v)
        _add(v, self.kick, v)
        if not self.explicit:
            _mul(v, dt, x_new)
            _add(x, x_new, x_new)
        store.prev_x, store.x = x, x_new
        count.n += 1
        return True
