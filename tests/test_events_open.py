"""The soft step's events (engine.dynamics.events.ContactLedger.settle_open) are what the
ledger's general ``settle`` makes of the same reports: the same begins and ends in the same
order, the same open contacts, the same ends of things taken out, for any open contacts
before, any reports (begins and ends, in and out of order, of keys open or not; a begin of a
key touching at the end, as the soft step reports them) and any keys touching after; with ends
held and sensors' contacts among the open ones too (where ``settle_open`` hands the step to
``settle``). Both ways of finding the changes: in Python sets (a game's dozen keys) and by
binary searches (a pile's thousands). The began and ended lists are made when first read, the
same whenever that is, and not at all where nothing reads them before the next step."""

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
    # The soft step's reports: a contact begins where it touches at the step's end.
    raw = [r for r in raw if not r[2] or r[1] in touching]
    general = ledger(prev, exact_share, held, pending)
    soft = ledger(prev, exact_share, held, pending)
    sensing = np.array(touching, dtype=np.int64)
    general.settle(T0, T_END, list(raw), np.zeros(0, dtype=np.int64), sensing.copy(), gaps)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(events, "_FEW", few)
        soft.settle_open(T0, T_END, (lambda: list(raw)) if raw else None, sensing.copy(), gaps)
        made = state(soft)  # (read here: the lists are made when read, with ``_FEW`` patched)
    assert made == state(general)


def test_the_lists_are_made_when_read_and_not_where_nothing_reads_them() -> None:
    # Two steps of a pile's keys (binary searches): the reports are asked for once, when the
    # first step's lists are read, and the same lists come back whenever they are read; a
    # step whose lists nobody reads before the next never asks for its reports.
    asked: list[int] = []

    def raw(step: int, specs: list[Any]) -> Any:
        return lambda: asked.append(step) or list(specs)

    led = ContactLedger()
    led.keys = led.exact = np.arange(1, 301, dtype=np.int64)
    touching = np.arange(2, 302, dtype=np.int64)  # 1 parts, 301 begins
    led.settle_open(T0, T_END, raw(1, [(T0, 301, True, "b301")]), touching, gaps)
    assert asked == [] and led.keys.tolist() == touching.tolist()
    first = (list(led.began), list(led.ended))
    assert asked == [1]
    assert first == ([(T0, 301, True, "b301")], [(T_END, 1, False, None)])
    assert (led.began, led.ended) == first and asked == [1]
    led.settle_open(T_END, T_END + 0.1, raw(2, [(T_END, 302, True, "b302")]),
                    np.arange(3, 303, dtype=np.int64), gaps)  # fmt: skip
    led.settle_open(T_END + 0.1, T_END + 0.2, raw(3, []), np.arange(3, 303, dtype=np.int64), gaps)
    assert (led.began, led.ended) == ([], []) and asked == [1, 3]


def test_a_begin_of_a_key_not_touching_at_the_end_is_refused_when_read() -> None:
    # settle_open's caller's promise (the soft step keeps it): a contact that begins touches
    # at the step's end. A report that breaks it is a bug of the caller, said when read.
    led = ContactLedger()
    led.settle_open(T0, T_END, lambda: [(T0, 5, True, "b5")], np.array([4], np.int64), gaps)
    with pytest.raises(AssertionError, match="does not touch"):
        _ = led.began


def test_a_step_of_the_soft_ledger_opens_and_closes_by_key_after_the_reports() -> None:
    # Worked by hand: 1 and 2 open; the step reports 3 began and 1 ended; 2, 3 and 4 touch at
    # its end. 4 opens at the end, no report naming it; 1's end is the reported one; nothing
    # of 2.
    led = ContactLedger()
    led.keys = led.exact = np.array([1, 2], dtype=np.int64)
    raw = [(T_END, 3, True, "b3"), (T_END, 1, False, "e1")]
    led.settle_open(T0, T_END, lambda: raw, np.array([4, 3, 2, 3], dtype=np.int64), gaps)
    assert led.began == [(T_END, 3, True, "b3"), (T_END, 4, True, None)]
    assert led.ended == [(T_END, 1, False, "e1")]
    assert led.keys.tolist() == [2, 3, 4] and led.exact.tolist() == [2, 3, 4]
