"""Sleep: groups of bodies at rest on one another stop costing anything until something meets them.

A body is still while its speed stays below the still speed, |A| dt for the largest
acceleration A of the step (the speed the forces add in one step: Chipmunk's idle speed), or
``World.sleep_speed`` when set. Bodies resting on one another are joined into groups, the
connected pieces of the graph whose edges are the pile's pairs near enough to touch (the same
nearness ``wake_met`` wakes them by: a group falls asleep whole, or a body left awake beside
it would wake it again at once). A group sleeps (``sleep_still``) once every body in it

* has been still for ``sleep_time`` seconds (Chipmunk's and Box2D's half second by default),
* overlaps the others by at most ``SLEEP_OVERLAP`` of its radius (a pile still being pushed
  apart is not at rest),
* and is a member: a body in a resting pair, a pile's body resting on a wall, or one held
  exactly still on a collider by friction (a slow frictionless puck glides on). A body in
  flight never sleeps, however slow, nor does a kinematic body or a group it touches.

The groups are found by label propagation, with no Python loop over bodies: each body starts
with its own row as label, takes the smallest label of its neighbours, and then labels follow
labels (label = label[label]), which halves the distance to the root each time, until no
label changes. A sleeping body keeps its group's label.

Sleeping bodies stay exactly where they are, velocity 0, until an awake body meets one of
them (``wake_met``: moves near it faster than the still speed, or touches it at any speed;
its whole group wakes) or the World is changed by hand. Pairs of two sleepers are dropped
from the step.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..geometry.pair_math import isin_sorted, norm, sorted_unique
from .pile import components

if TYPE_CHECKING:
    from .contacts import Contacts

__all__ = ["SLEEP_OVERLAP", "sleep_still", "wake_met"]

#: A body sleeps only while it overlaps others by at most this fraction of its radius.
SLEEP_OVERLAP = 0.0075


def wake_met(
    a: np.ndarray,
    b: np.ndarray,
    x: np.ndarray,
    v: np.ndarray,
    radius: np.ndarray,
    asleep: np.ndarray,
    still: np.ndarray,
    group: np.ndarray,
    still_speed: float,
    shaped: np.ndarray | None = None,
    touching_keys: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Drop pairs (a, b) of two sleepers; wake the group of a sleeper an awake body meets
    (in place on ``asleep`` and ``still``, seconds each body has been still; ``group``: each
    sleeper's group label). ``shaped`` (N,) bool or None: the bodies with shapes other than
    discs, whose bounding circles say nothing of touching: a pair with one touches where
    its key a * N + b (a < b) is in ``touching_keys`` (the pairs the last step's rows found)."""
    sa, sb = asleep[a], asleep[b]
    mixed = np.flatnonzero(sa != sb)
    if len(mixed):
        awake = np.where(sa[mixed], b[mixed], a[mixed])
        sleeper = np.where(sa[mixed], a[mixed], b[mixed])
        # An awake body that moves near a sleeper, or touches it at any speed, wakes its
        # group (a sleeper pushed while asleep would be put back every step).
        ra, rs = radius[awake], radius[sleeper]
        touching = norm(x[awake] - x[sleeper]) <= ra + rs + 0.05 * np.minimum(ra, rs)
        if shaped is not None and touching_keys is not None:
            pair = shaped[awake] | shaped[sleeper]
            if pair.any():
                lo, hi = np.minimum(awake, sleeper), np.maximum(awake, sleeper)
                keys = lo.astype(np.int64) * len(x) + hi
                met = np.isin(keys, np.asarray(touching_keys, dtype=np.int64))
                touching = np.where(pair, met, touching)
        moving = (norm(v[awake]) > still_speed) | touching
        if moving.any():
            sleeper = sleeper[moving]
            groups = sorted_unique(group[sleeper])
            woken = asleep & isin_sorted(group, groups)
            asleep[woken] = False
            still[woken] = 0.0
    # The pairs of two sleepers left asleep are dropped (after the waking: a woken
    # group's own pairs are its contacts this step).
    keep = ~(asleep[a] & asleep[b])
    return a[keep], b[keep]


def sleep_still(
    v: np.ndarray,
    dt: float,
    live: np.ndarray,
    pa: np.ndarray,
    pb: np.ndarray,
    contacts: Contacts | None,
    still: np.ndarray,
    asleep: np.ndarray,
    group: np.ndarray,
    sleep_time: float,
    still_speed: float,
    kinematic: np.ndarray | None,
    overlap: np.ndarray,
    on_wall: np.ndarray,
    fast: bool = False,
    spin_speed: np.ndarray | None = None,
) -> np.ndarray:
    """Count how long each body has been still (in place on ``still``); put to sleep each
    group (bodies resting on one another, pairs pa, pb, or one resting on a collider) that
    has been still for ``sleep_time`` (in place on ``asleep`` and v). Returns each body's
    group label (``group`` with the new sleepers' labels).

    ``live``: the rows that collide; ``kinematic`` (N,) or None: bodies the game moves;
    ``overlap`` (N,): each body's deepest overlap over its radius (empty: not measured);
    ``on_wall``: the rows of a pile's bodies resting on a wall; ``fast``: label the groups
    by the loop kernel (engine.kernels); ``spin_speed`` (N,) or None: how fast each body's
    surface turns about its centre, |omega| r (length units/s): a disc spinning in place is
    not still."""
    if not math.isfinite(sleep_time):
        return group
    slow = norm(v[live]) <= still_speed
    if spin_speed is not None:
        slow &= spin_speed[live] <= still_speed
    still[live] = np.where(slow, still[live] + dt, 0.0)
    ready = (still >= sleep_time) & ~asleep
    if kinematic is not None:
        # A body the game moves never sleeps, nor does a group it touches.
        ready &= ~kinematic
    if len(overlap) == len(ready):
        # ... and overlapping by at most SLEEP_OVERLAP of its radius.
        ready &= overlap <= SLEEP_OVERLAP
    # Who may sleep: a body in a resting pair, or one resting on a collider; a body in
    # flight never does, however slow.
    member = np.zeros(len(v), dtype=bool)
    member[pa] = member[pb] = True
    member[on_wall] = True  # a pile's body resting on a wall alone
    if contacts is not None and len(contacts.rest) == len(v):
        # Held still on a collider by friction (exactly still: a slow frictionless puck
        # glides on).
        on = np.zeros(len(v), dtype=bool)
        on[live] = (contacts.rest[live] >= 0) & (v[live, 0] == 0.0) & (v[live, 1] == 0.0)
        member |= on
    member &= ~asleep
    if not (member & ready).any():
        return group
    # Groups: connected pieces of the graph of resting pairs among awake bodies, each
    # labelled by its least body (engine.exact.pile.components, the piles' labels).
    keep = ~asleep[pa] & ~asleep[pb]
    label = components(len(v), pa[keep], pb[keep], fast)
    # A group sleeps when every body in it is ready.
    not_ready = sorted_unique(label[member & ~ready])
    sleepers = member & ready & ~isin_sorted(label, not_ready)
    if sleepers.any():
        asleep[sleepers] = True
        group = np.where(sleepers, label, group)
        v[sleepers] = 0.0
    return group
