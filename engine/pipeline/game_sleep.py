"""Sleep in the soft step: islands that stay still stop costing anything until something comes.

The soft step (engine.pipeline.game_step) lets bodies sleep as Box2D v3 does (its
``sleepThreshold`` and ``B2_TIME_TO_SLEEP``, ``b2FinalizeBodiesTask`` in its ``solver.c``), on the
World's own sleep state (``World. sleeping``, ``World.is_sleeping``, ``Body.sleep``,
``Body.activate``, ``World.sleep_time``):

* A body is **still** while the fastest point of its shape moves slower than ``LINEAR`` (m/s;
  in a World of other length units, scaled by its ``length_units_per_meter``, as is ``RISE``):
  |v| + r |omega| < ``LINEAR``, r its bounding radius (Box2D v3's test, where v2.4 took the
  speed and the spin apart, 0.05 m/s and 2 degrees a second: a 6 m plank turning at 0.03
  rad/s, its ends at 9 cm/s, looked still, and a 5 cm disc spinning at 0.5 rad/s did not).
  Its still time counts up by dt each such step and back to 0 otherwise (and when the game
  writes its position or velocity). A body that one of pymunk's
  constraints holds (engine.dynamics.constraints) is still only while the step also moves it by less
  than ``LINEAR`` dt and turns it by less than ``ANGULAR`` dt (``drifting``): the joint's
  correction of its error moves it and leaves it no speed (engine.dynamics.solver's relax), so a
  body that a slow error_bias or a small max_bias still corrects would look still, and sleep with
  its error left; pymunk's body moves at the correction's speed, and its sleep sees it.
* A body that rests on a face of another is still only while its held loads have at most
  ``RISE`` (m) to lift it (engine.dynamics.solver's ``brise``): a pile's contacts take their
  loads slowly (engine.dynamics.solver's module doc, "A pile holds its load too"), and a
  pile lifts back from its sag at a few cm/s, under ``LINEAR``. Asleep at Box2D's test, the
  pyramid of 210 boxes slept while it rose, at 0.82 s, 26.9 mm from where it was put; now at
  4.3 s, 5.5 mm (0.3 mm: 3.55 s, 6.6 mm; 0.1 mm: 6.6 s, 4.2 mm). It costs a small pile
  awake time, not a look: a unit box on another sleeps at 1.5 s, not 0.52, 0.14 mm down,
  not 0.35; a column of five at 2.65 s, 0.57 mm down, not 3.5.
* **Islands**: the bodies joined by a touching contact between two of them, or by a hinge or a
  weld, one through another (a floor or a wall joins nothing). An island falls asleep whole once
  every body in it has been still for ``World.sleep_time`` seconds (0.5 s by default), and none
  of it may never sleep (a kinematic body, one a mouse joint drags).
* A sleeping body is static to the step: it does not move, nothing is solved for it, and two
  sleepers' pair is not even tested. Its contacts stay open (no end is reported while it sleeps;
  engine.pipeline.game_step keeps them).
* **Waking**: before the contacts are found, a sleeper whose bounding circle comes within reach
  of an awake body that moves (a dynamic body, or a kinematic one with a velocity) and that
  its filter lets it collide with (not a sensor) wakes with its whole island; the World wakes
  a body (and its island) whose state is written by hand.

``fall_asleep`` and ``woken`` are numpy on the bodies' and pairs' arrays: the same on both
paths, so the two paths stay the same bits.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exact.pile import components
from . import game_broadphase as broad

__all__ = ["ANGULAR", "LINEAR", "RISE", "drifting", "fall_asleep", "woken"]

#: Box2D's sleep threshold (m/s): a body whose shape's fastest point is slower is still.
LINEAR = 0.05
#: How fast a body a pymunk constraint holds may turn and still be still (rad/s; ``drifting``).
ANGULAR = 2.0 * np.pi / 180.0
#: A body whose held loads have yet to lift it by more than this (m) is not still.
RISE = 2e-4


def woken(
    asleep: np.ndarray,
    group: np.ndarray,
    active: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    store: Any,
    margin: np.ndarray,
    boxes: np.ndarray,
    meet: np.ndarray | None = None,
    unit: float = 1.0,
) -> np.ndarray:
    """The sleepers (bool (N,)) that wake before this step: the islands (``group``: each
    sleeper's island label) of those that an ``active`` body may come within the speculative
    distance of, among the broadphase's candidate pairs (rows ``a``, ``b``): by the bodies'
    circles and ``boxes``, grown by what each can move in the step (``margin``, m), as the
    step's pairs are found (engine.pipeline.game_broadphase's ``reaching``: a ball rolling past a
    sleeping crate's side, inside the crate's circle but 10 cm from its box, leaves it
    asleep), and where their filters let them collide (``filters_meet``: a feet sensor the
    game moves beside its sleeping player, or a body filtered apart from a sleeper, wakes
    nothing). ``store``: the bodies' positions, radii and filters (engine.dynamics.store);
    ``meet``: ``filters_meet`` of the candidates where the caller has kept it (None: asked
    here); ``unit``: the World's length units a metre (``reaching``'s)."""
    meets = (asleep[a] & active[b]) | (asleep[b] & active[a])
    if meet is None:
        meets[meets] = broad.filters_meet(store, a[meets], b[meets])
    else:
        meets &= meet
    # (np.count_nonzero for ndarray.any() here: a C call, where .any() goes through numpy's
    # Python wrapper at several times its cost on a game's few bodies.)
    if not np.count_nonzero(meets):
        return np.zeros(len(asleep), dtype=bool)
    a, b = a[meets], b[meets]
    near = broad.reaching(store, margin, boxes, a, b, unit)
    sleepers = np.concatenate([a[near], b[near]])
    sleepers = sleepers[asleep[sleepers]]
    # (The sleepers' labels sorted, duplicates and all: np.isin's answer, a few times faster.)
    return asleep & broad.in_sorted(group, np.sort(group[sleepers]))


def drifting(
    x0: np.ndarray,
    x1: np.ndarray,
    q0: np.ndarray,
    q1: np.ndarray,
    ja: np.ndarray,
    jb: np.ndarray,
    dt: float,
    unit: float = 1.0,
) -> np.ndarray:
    """The bodies (bool (N,)) that a pymunk constraint holds (its rows' ends ``ja``, ``jb``;
    row N, the static body, is none) and that the step moved faster than ``LINEAR`` or turned
    faster than ``ANGULAR``, from ``x0`` (N, 2) m and ``q0`` rad to ``x1`` and ``q1``: what
    the joint's correction moves them by, which their speed does not show (the module's
    text); ``unit``: the World's length units a metre, which ``LINEAR`` is scaled by.
    engine.pipeline.game_loop's ``step_loop`` makes the same products."""
    n = len(x0)
    held = np.zeros(n + 1, dtype=bool)
    held[ja] = True
    held[jb] = True
    if not np.count_nonzero(held[:n]):
        return held[:n]
    d = x1 - x0
    linear = LINEAR * unit
    near = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] < linear * linear * dt * dt
    level = np.abs(q1 - q0) < ANGULAR * dt
    return held[:n] & ~(near & level)


def fall_asleep(
    still: np.ndarray,
    asleep: np.ndarray,
    group: np.ndarray,
    awake: np.ndarray,
    never: np.ndarray,
    v: np.ndarray,
    omega: np.ndarray,
    radius: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
    dt: float,
    sleep_time: float,
    fast: bool,
    drift: np.ndarray | None = None,
    unit: float = 1.0,
) -> None:
    """After a step: each ``awake`` body's still time (s) counted on (``v`` (N, 2) m/s, ``omega``
    rad/s, ``radius`` (N,) its bounding radius m; not for a body ``drift`` marks,
    ``drifting``'s), and the islands of awake bodies
    joined by rows (``a``, ``b``: touching contacts and joints between two bodies) put to sleep
    (``asleep``, ``group`` their label) where every body has been still ``sleep_time`` s and
    none is ``never``; ``unit``: the World's length units a metre, which ``LINEAR`` is scaled
    by. In place."""
    n = len(still)
    linear = LINEAR * unit
    # The fastest point of its shape: |v| + r |omega| (the module's text).
    slow = np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1]) + radius * np.abs(omega) < linear
    if drift is not None:
        slow &= ~drift
    still[:] = np.where(awake & slow, still + dt, 0.0)
    if not np.isfinite(sleep_time) or not np.count_nonzero(still >= sleep_time):
        return
    inner = awake[a] & awake[b]
    label = components(n, a[inner].astype(np.int64), b[inner].astype(np.int64), fast)
    # An island sleeps when its stillest-but-one is still enough: its least still time does.
    least = np.full(n, np.inf)
    np.minimum.at(least, label, np.where(awake & ~never, still, -np.inf))
    ready = awake & (least[label] >= sleep_time)
    if np.count_nonzero(ready):
        asleep[ready] = True
        group[ready] = label[ready]
