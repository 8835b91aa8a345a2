"""The soft step's events (engine.dynamics.events.ContactLedger.settle_open) are what the
ledger's general ``settle`` makes of the same reports: the same begins and ends in the same
order, the same open contacts, the same ends of things taken out, for any open contacts
before, any reports (begins and ends, in and out of order, of keys open or not, some of keys
not touching at the end) and any keys touching after; with ends held and sensors' contacts
among the open ones too (where ``settle_open`` hands the step to ``settle``). Both ways of
finding the changes: in Python sets (a game's dozen keys) and by binary searches (a pile's
thousands)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine.dynamics import events
from engine.dynamics.events import ContactEvent, ContactLedger

T0, T_END = 1.0, 1.0 + 1.0 / 60.0
KEYS = st.integers(0, 24).map(lambda k: (k % 5) << 32 | (k + 1))  # a few bodies, a few others


def gaps(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A gap for each key that depends on the key alone (some within the slack, some not)."""
    return (keys % 7 - 3) * 0.01, np.full(len(keys), 0.015)


def ledger(prev: list[int], exact_share: int, held: list[int], pending: int) -> ContactLedger:
    """A ledger with ``prev`` open (the first ``exact_share`` of them not sensors' where it is
    above 0, as the exact solvers leave it), ends held for ``held``, and ``pending`` ends of
    things taken out waiting, some of them later than the step's start."""
    out = ContactLedger()
    out.keys = np.array(sorted(set(prev)), dtype=np.int64)
    out.exact = out.keys[exact_share:].copy()
    out.held = {k: (T0 + 0.001, k, False, ("held", k)) for k in held if k in set(prev)}
    out.pending = [
        ContactEvent(None, None, (0.0, 0.0), (0.0, 1.0), (0.0, 0.0), T0 + 0.01 * (i - 1), True)
        for i in range(pending)
    ]
    return out


def state(led: ContactLedger) -> tuple[Any, ...]:
    return (
        led.keys.tolist(),
        led.exact.tolist(),
        list(led.began),
        list(led.ended),
        [tuple(e) for e in led.removed],
        list(led.pending),
        dict(led.held),
    )


report = st.tuples(
    st.one_of(st.floats(T0, T_END), st.sampled_from([T0 - 1e-15, T_END + 1e-15])),
    KEYS,
    st.booleans(),
).map(lambda r: (r[0], r[1], r[2], ("payload", r[1], r[2])))


@pytest.mark.parametrize("few", [events._FEW, 0], ids=["sets", "searches"])
@settings(max_examples=400)
@given(
    prev=st.lists(KEYS, max_size=12),
    raw=st.lists(report, max_size=8),
    touching=st.lists(KEYS, max_size=12),
    exact_share=st.sampled_from([0, 0, 0, 1]),
    held=st.lists(KEYS, max_size=2) | st.just([]),
    pending=st.integers(0, 2),
)
def test_settle_open_makes_what_settle_makes(
    few: int,
    prev: list[int],
    raw: list[Any],
    touching: list[int],
    exact_share: int,
    held: list[int],
    pending: int,
) -> None:
    general = ledger(prev, exact_share, held, pending)
    soft = ledger(prev, exact_share, held, pending)
    sensing = np.array(touching, dtype=np.int64)
    general.settle(T0, T_END, list(raw), np.zeros(0, dtype=np.int64), sensing.copy(), gaps)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(events, "_FEW", few)
        soft.settle_open(T0, T_END, list(raw), sensing.copy(), gaps)
    assert state(soft) == state(general)


def test_a_step_of_the_soft_ledger_opens_and_closes_by_key_after_the_reports() -> None:
    # Worked by hand: 1 and 2 open; the step reports 3 began and 1 ended; 2, 3 and 4 touch at
    # its end. 4 opens at the end, no report naming it; 1's end is the reported one; nothing
    # of 2.
    led = ContactLedger()
    led.keys = led.exact = np.array([1, 2], dtype=np.int64)
    raw = [(T_END, 3, True, "b3"), (T_END, 1, False, "e1")]
    led.settle_open(T0, T_END, raw, np.array([4, 3, 2, 3], dtype=np.int64), gaps)
    assert led.began == [(T_END, 3, True, "b3"), (T_END, 4, True, None)]
    assert led.ended == [(T_END, 1, False, "e1")]
    assert led.keys.tolist() == [2, 3, 4] and led.exact.tolist() == [2, 3, 4]
