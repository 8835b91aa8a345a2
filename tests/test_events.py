"""Contact events as a game needs them: one begin and one end for each contact, in time order,
no chatter at rest, ends for what is taken out, and the impulse of a contact that continues
(engine.dynamics.events)."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine import (
    Body,
    Box,
    Circle,
    ContactEvent,
    OverlapWarning,
    Plane,
    Polygon,
    Segment,
    StabilityWarning,
    Vector,
    World,
)
from engine import kernels as engine_kernels
from engine.dynamics.events import COLLIDER, ContactLedger
from engine.forces import Gravity
from engine.pipeline import body_sensors
from tests.paths import FAST, PATHS

G = 9.81


def ball(world: World, x: float, y: float, vx: float = 0.0, vy: float = 0.0, **kw) -> Body:
    kw.setdefault("radius", 0.5)
    return world.add(Body(Vector(x, y), Vector(vx, vy), Vector(0, 0), **kw))


def tally(world: World, target) -> tuple[list[ContactEvent], list[ContactEvent]]:
    began: list[ContactEvent] = []
    ended: list[ContactEvent] = []
    world.on_contact(target, begin=began.append, end=ended.append)
    return began, ended


def test_removing_the_last_body_after_a_bounce_then_stepping_reports_nothing() -> None:
    # pymunk's test suite found it: the empty World rebuilt the last step's raw events.
    w = World()
    wall = w.add_collider(Segment((2, -5), (2, 5)))
    b = ball(w, 0, 0, 10, 0, radius=1)
    seen: list[ContactEvent] = []
    w.on_contact(wall, begin=seen.append)
    w.step(0.1)
    assert len(seen) == 1 and seen[0].body is b
    w.remove(b)
    w.step(0.1)
    w.step(0.1)
    assert len(seen) == 1 and w.began == []


def test_events_of_a_step_come_in_time_order() -> None:
    # The later body in the list strikes first: its event comes first.
    w = World()
    wall = w.add_collider(Segment((1, -5), (1, 5)))
    slow = ball(w, 0.5, 0, 4.0, 0, radius=0.1, restitution=1.0)
    fast = ball(w, 0.0, 1, 10.0, 0, radius=0.1, restitution=1.0)
    times: list[float] = []
    w.on_contact(wall, begin=lambda e: times.append(e.time))
    w.step(0.1)
    assert [e.body for e in w.began] == [fast, slow]
    assert times == sorted(times) and abs(times[0] - 0.09) < 1e-12 and abs(times[1] - 0.1) < 1e-12


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "auto"])
def test_a_ball_placed_on_a_floor_begins_once_and_ends_once_when_thrown(integrator: str) -> None:
    w = World(integrator=integrator)
    w.add_force(Gravity((0, -G)))
    floor = w.add_collider(Plane((0, 0), (0, 1)))
    b = ball(w, 0, 0.5)
    began, ended = tally(w, b)
    for _ in range(10):
        w.step(1 / 60)
    assert [e.collider for e in began] == [floor] and ended == []
    b.vel = Vector(0, 5)
    for _ in range(10):
        w.step(1 / 60)
    assert len(began) == 1 and [e.collider for e in ended] == [floor]
    assert ended[0].time > began[0].time


@pytest.mark.parametrize("integrator", ["semi_implicit_euler", "auto"])
def test_a_resting_stack_does_not_chatter(integrator: str) -> None:
    # Two balls stacked on a floor: one begin for each of the two contacts, no end, while the
    # pile settles and sleeps (pymunk: 1 begin, 0 ends for each arbiter).
    w = World(integrator=integrator)
    w.add_force(Gravity((0, -G)))
    floor = w.add_collider(Plane((0, 0), (0, 1)))
    low = ball(w, 0, 0.5)
    high = ball(w, 0, 1.5)
    began, ended = [], []
    for _ in range(120):
        w.step(1 / 60)
        began += w.began
        ended += w.ended
    assert ended == []
    assert sorted((id(e.body), id(e.collider)) for e in began) == sorted(
        [(id(low), id(floor)), (id(low), id(high))]
    )
    assert w.sleeping == 2
    # The body added first is the event's body, for a contact between two bodies.
    assert [e.body for e in began if e.collider is high] == [low]


def test_an_inelastic_hit_while_gravity_pulls_the_ball_off_the_wall_balances() -> None:
    w = World()
    w.add_force(Gravity((0, -G)))
    wall = w.add_collider(Segment((1, -5), (1, 5)))
    b = ball(w, 0, 0, 3, 0, radius=0.2, restitution=0.0)
    began, ended = tally(w, b)
    for _ in range(120):
        w.step(1 / 60)
    assert [e.collider for e in began] == [wall] and [e.collider for e in ended] == [wall]


def test_removing_a_resting_body_ends_its_contacts_with_the_next_step() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0, -G)))
    floor = w.add_collider(Plane((0, 0), (0, 1)))
    b = ball(w, 0, 0.5)
    other = ball(w, 5, 0.5)
    began, ended = tally(w, floor)
    for _ in range(5):
        w.step(1 / 60)
    assert {e.body for e in began} == {b, other} and ended == []
    t_removed = w.t
    w.remove(b)
    w.step(1 / 60)
    assert [(e.body, e.removal) for e in ended] == [(b, True)]
    assert ended[0].time == t_removed
    assert [(e.body, e.removal) for e in w.ended] == [(b, True)]
    w.step(1 / 60)
    assert w.ended == [] and len(ended) == 1


def test_removing_a_collider_ends_the_contacts_on_it() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0, -G)))
    ledge = w.add_collider(Segment((-2, 0), (2, 0)))
    w.add_collider(Plane((0, -10), (0, 1)))
    b = ball(w, 0, 0.5, restitution=0.0)
    began, ended = tally(w, b)
    for _ in range(5):
        w.step(1 / 60)
    assert [e.collider for e in began] == [ledge]
    w.remove_collider(ledge)
    w.step(1 / 60)
    assert [(e.collider, e.removal) for e in ended] == [(ledge, True)]
    for _ in range(200):
        w.step(1 / 60)
    assert len(ended) == 1 and len(began) == 2  # then it lands on the floor below


def test_a_teleport_away_from_a_resting_place_ends_the_contact() -> None:
    w = World(integrator="auto")
    w.add_force(Gravity((0, -G)))
    floor = w.add_collider(Plane((0, 0), (0, 1)))
    b = ball(w, 0, 0.5)
    began, ended = tally(w, b)
    for _ in range(5):
        w.step(1 / 60)
    b.pos = Vector(0, 50)
    assert w.resting(b) is None  # the rest went with the teleport
    w.step(1 / 60)
    assert [e.collider for e in ended] == [floor]
    assert b.pos.y < 50 and b.vel.y < 0  # falling, not hovering


def test_a_sensor_reports_a_body_taken_out_while_inside() -> None:
    w = World()
    cup = w.add_collider(Circle((0, 0), 2.0, sensor=True))
    b = ball(w, 0, 0)
    began, ended = tally(w, cup)
    w.step(1 / 60)
    assert [e.body for e in began] == [b]
    w.remove(b)
    w.step(1 / 60)
    assert [(e.body, e.removal) for e in ended] == [(b, True)]


def test_post_solve_gives_a_resting_ball_its_weight_times_dt() -> None:
    # pymunk's post_solve: the impulse a continuing contact carried over the step.
    dt, m = 1 / 60, 2.0
    w = World(integrator="auto")
    w.add_force(Gravity((0, -G)))
    floor = w.add_collider(Plane((0, 0), (0, 1)))
    b = ball(w, 0, 0.5, mass=m)
    seen: list[ContactEvent] = []
    w.on_contact(b, post_solve=seen.append)
    for _ in range(5):
        w.step(dt)
    assert len(seen) >= 4
    last = seen[-1]
    assert last.collider is floor and last.body is b
    assert abs(last.impulse.y - m * G * dt) <= 1e-12 and abs(last.impulse.x) <= 1e-15
    assert [e.collider for e in w.touching] == [floor]


def test_post_solve_in_a_stack_carries_the_weight_above() -> None:
    dt = 1 / 60
    w = World(integrator="auto")
    w.add_force(Gravity((0, -G)))
    w.add_collider(Plane((0, 0), (0, 1)))
    low = ball(w, 0, 0.5, mass=1.0)
    high = ball(w, 0, 1.5, mass=3.0)
    w.sleep_time = math.inf
    for _ in range(120):
        w.step(dt)
    pair = [e for e in w.touching if e.collider is high]
    assert len(pair) == 1 and pair[0].body is low
    # The pair pushes low down by high's weight: the impulse on low is -3 g dt.
    assert abs(pair[0].impulse.y + 3.0 * G * dt) <= 1e-4 * 3.0 * G * dt


def test_each_contact_begins_before_it_ends_in_a_busy_room() -> None:
    # Forty balls in a room with a peg and a ledge, under gravity: per contact the events
    # alternate begin, end, begin ... and never two of one kind in a row.
    w = World()
    w.add_force(Gravity((0, -G)))
    w.add_collider(Box((-5, 0), (5, 10), restitution=0.5))
    w.add_collider(Circle((0, 3), 0.7))
    w.add_collider(Segment((-4, 5), (-1, 4)))
    for k in range(40):
        ball(w, -4 + (k % 8), 5.5 + 0.8 * (k // 8), (k % 3) - 1.0, 0.0, radius=0.3, restitution=0.6)
    state: dict[tuple[int, int], bool] = {}
    for _ in range(400):
        w.step(1 / 60)
        merged = [(e.time, 0, e) for e in w.began] + [(e.time, 1, e) for e in w.ended]
        assert [e.time for e in w.began] == sorted(e.time for e in w.began)
        assert [e.time for e in w.ended] == sorted(e.time for e in w.ended)
        for _, kind, e in sorted(merged, key=lambda m: (m[0], m[1])):
            key = (id(e.body), id(e.collider))
            if kind == 0:
                assert not state.get(key, False), f"begun twice: {e}"
                state[key] = True
            else:
                assert state.get(key, False), f"ended before it began: {e}"
                state[key] = False
    open_now = {k for k, v in state.items() if v}
    assert open_now == {(id(e.body), id(e.collider)) for e in w.touching}


def test_ends_of_things_taken_out_come_first_when_the_next_step_has_another_dt() -> None:
    # Found by the stateful fuzz: a room added over two balls pushes them into each other; a
    # handler takes one out as their contact begins, at t = 1/240. The next step, of 1/60,
    # starts there (its time summed another way): the removal's end comes first, at that
    # moment, and each list is in time order.
    w = World()
    w.add_force(Gravity((0, -G)))
    a = ball(w, 6.53, 2.066, -2.18, 2.56, radius=0.5)
    b = ball(w, 7.80, 2.456, 2.05, 1.02, radius=0.2)
    w.on_contact(b, begin=lambda e: w.remove(e.collider) if e.collider is a else None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", OverlapWarning)
        w.add_collider(Box((-7, -12), (7, 12)))
    w.step(1 / 240)
    assert a.world is None
    t_removed = w.t
    b.vel = Vector(1, 0)  # off the wall it rests against: that contact ends at once
    w.step(1 / 60)
    for events in (w.began, w.ended):
        assert [e.time for e in events] == sorted(e.time for e in events)
    assert w.ended[0].removal and w.ended[0].time == t_removed
    assert all(e.time >= t_removed for e in w.began)


def test_a_held_end_goes_with_its_collider_and_snapshots_still_work() -> None:
    # A ball leaving a peg slowly is within its contact's slack for a step or two, its end
    # held; taking the peg out then ends the contact by removal, and nothing of the held end
    # is left to name the peg (a snapshot named it: KeyError, found by the stateful fuzz).
    w = World(integrator="auto")
    w.add_force(Gravity((0, -G)))
    peg = w.add_collider(Circle((0, 0), 0.5))
    b = ball(w, 0, 0.6, 0.1, 0, radius=0.1, friction=0.0)
    while w.resting(b) is not None or w.t == 0.0:
        w.step(1 / 60)
    assert [e.collider for e in w.touching] == [peg]  # lifted off, but within the slack
    w.remove_collider(peg)
    saved = w.snapshot()
    w.step(1 / 60)
    assert [(e.collider, e.removal) for e in w.ended] == [(peg, True)]
    w.restore(saved)
    w.step(1 / 60)
    assert [(e.collider, e.removal) for e in w.ended] == [(peg, True)]


@pytest.mark.parametrize("kernels", ["numpy", pytest.param("fast", marks=FAST)])
def test_a_pile_asleep_keeps_its_contacts_open_with_no_events_until_woken(kernels: str) -> None:
    # 60 balls dropped in a pit with a sensor by the floor: once every body sleeps a step
    # moves nothing, so the contacts open as they fell asleep stay open, impulses and the
    # sensor's included, and none begins or ends (the step skips the ledger's measures then:
    # engine.pipeline.event_dispatch.quiet); a ball dropped on the pile wakes it and events come
    # again.
    w = World(integrator="auto", kernels=kernels)
    w.add_force(Gravity((0.0, -G)))
    w.add_collider(Box((0.0, 0.0), (12.0, 1000.0)))
    sensor = w.add_collider(Circle((1.0, 0.5), 0.2, sensor=True))
    for k in range(60):
        ball(w, 1.0 + (k % 10) + 0.5 * ((k // 10) % 2), 1.0 + 1.1 * (k // 10), restitution=0.5)

    def touching() -> list[tuple[int, int, float, float]]:
        rows = {id(b): i for i, b in enumerate(w.bodies)}
        return sorted(
            (rows[id(e.body)], rows.get(id(e.collider), -1 - id(e.collider) % 997),
             e.impulse.x, e.impulse.y)
            for e in w.touching
        )  # fmt: skip

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StabilityWarning)
        for _ in range(600):
            w.step(1 / 60)
            if w.sleeping == 60:
                break
        assert w.sleeping == 60
        asleep = touching()
        assert any(e.collider is sensor for e in w.touching)  # the sensor holds a ball
        for _ in range(200):
            w.step(1 / 60)
            assert not w.began and not w.ended
            assert touching() == asleep
        ball(w, 5.0, 20.0, vy=-5.0)
        woke = False
        for _ in range(120):
            w.step(1 / 60)
            woke = woke or bool(w.began)
    assert woke and w.sleeping < 60


# -- quiet steps: the ledger's and the soft settle's short cuts --------------------------------
# Most steps of a game touch what the step before touched: the soft settle searches no report
# when the keys are the same (engine.pipeline.event_dispatch), the ledger returns at once when
# nothing is reported or held at rest and what is inside sensors now is what is open, all sensors'
# (ContactLedger.settle), and the sensor bodies are found again only when a filter changes
# (engine.pipeline.body_sensors). The tests below take each kind of change in the step after quiet
# steps, and compare with the same steps through the whole settle (the short cuts off).

A, B, C, D = ((np.int64(s) << 32) | COLLIDER | 7 for s in (1, 2, 3, 4))
DT = 1 / 60


def full_settle(mp: pytest.MonkeyPatch) -> None:
    """Turn the short cuts off: no keys are ever the same, the sensor bodies found each step."""
    mp.setattr("engine.dynamics.events.same_keys", lambda a, b: False)
    mp.setattr("engine.pipeline.event_dispatch.same_keys", lambda a, b: False)
    rows = body_sensors._sensor_rows

    def afresh(state: Any) -> list[int]:
        state.sensor_rows = None
        return rows(state)

    mp.setattr(body_sensors, "_sensor_rows", afresh)


Gaps = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


def ledger_steps(fast: bool, steps: list[tuple[Any, ...]], gaps: Gaps) -> list[tuple[Any, ...]]:
    """Each step's (began keys, ended keys, open keys, sensors' keys, held keys) of a new
    ledger settling ``steps`` of (raw, resting, sensing), step k from k to k + 1 s."""
    ledger = ContactLedger()
    ledger.fast = fast
    out = []
    for t, (raw, resting, sensing) in enumerate(steps):
        ledger.settle(
            float(t),
            t + 1.0,
            list(raw),
            np.array(resting, dtype=np.int64),
            np.array(sensing, dtype=np.int64),
            gaps,
        )
        out.append(
            (
                [(s[0], s[1]) for s in ledger.began],
                [(s[0], s[1]) for s in ledger.ended],
                ledger.keys.tolist(),
                ledger.exact.tolist(),
                sorted(ledger.held),
            )
        )
    return out


def near(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every gap within its slack: a contact not a sensor's stays open unless reported."""
    return np.zeros(len(keys)), np.ones(len(keys))


@pytest.mark.parametrize("fast", [False, pytest.param(True, marks=FAST)])
def test_the_ledger_takes_each_change_in_the_step_after_a_quiet_one(fast: bool) -> None:
    a, b, c, d = (int(k) for k in (A, B, C, D))
    steps = [
        ((), (), [a, b]),  # 0: both begin
        ((), (), [a, b]),  # 1: quiet
        ((), (), [b, a, b]),  # 2: quiet, as it comes unsorted and with a repeat
        ((), (), [a]),  # 3: b ends
        ((), (), [a]),  # 4: quiet
        ((), (), [a, c]),  # 5: c begins while a stays
        ((), (), [a, c]),  # 6: quiet
        ((), [b], [a, c]),  # 7: b held at rest begins (not a sensor's)
        ((), (), [a, b, c]),  # 8: b inside now: nothing begins, b is a sensor's from now
        ((), (), [a, c]),  # 9: b ends as a sensor's does, within its slack though it is
        ((), (), [a, c]),  # 10: quiet
        (((11.3, d, True, None), (11.6, d, False, None)), (), [a, c]),  # 11: a bounce on d
        ((), (), [a, c]),  # 12: quiet
        ((), (), []),  # 13: both end
        ((), (), []),  # 14: nothing open, nothing inside
    ]
    got = ledger_steps(fast, steps, near)
    began = [[k for _, k in g[0]] for g in got]
    ended = [[k for _, k in g[1]] for g in got]
    assert began == [[a, b], [], [], [], [], [c], [], [b], [], [], [], [d], [], [], []]
    assert ended == [[], [], [], [b], [], [], [], [], [], [b], [], [d], [], [a, c], []]
    assert got[8][2] == got[8][3] == [a, b, c]
    assert got[11][0] == [(11.3, d)] and got[11][1] == [(11.6, d)]  # at its moments
    assert [g[2] for g in got] == [
        [a, b], [a, b], [a, b], [a], [a], [a, c], [a, c], [a, b, c], [a, b, c], [a, c],
        [a, c], [a, c], [a, c], [], [],
    ]  # fmt: skip
    with pytest.MonkeyPatch.context() as mp:
        full_settle(mp)
        assert ledger_steps(fast, steps, near) == got


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 2**32 - 1), st.booleans())
def test_the_ledgers_short_cut_changes_nothing_on_any_steps(seed: int, fast: bool) -> None:
    # Steps drawn from a few keys, most the step before's again (a quiet step, or the same
    # sensing unsorted, repeated), the others any change: whatever the ledger reports and
    # keeps is what the whole settle gives.
    fast = fast and engine_kernels.available()  # (the loop kernel only where numba is)
    rng = np.random.default_rng(seed)
    pool = [int(k) for k in (A, B, C, D)] + [(5 << 32) | 6, (6 << 32) | 9]

    def some(p: float) -> list[int]:
        return [k for k in pool if rng.random() < p]

    steps: list[tuple[Any, ...]] = []
    step: tuple[Any, ...] = ((), (), some(0.5))
    for t in range(40):
        r = rng.random()
        if r < 0.4 and t:
            raw, resting, sensing = step
            if rng.random() < 0.3 and sensing:  # the same keys, unsorted, one repeated
                sensing = [*rng.permutation(sensing).tolist(), sensing[0]]
            step = ((), resting if rng.random() < 0.5 else (), sensing)
        elif r < 0.7:
            step = ((), (), some(0.5))
        else:
            raw = tuple(
                (t + float(rng.random()), k, bool(rng.random() < 0.5), None) for k in some(0.2)
            )
            step = (raw, some(0.2) if rng.random() < 0.5 else (), some(0.4))
        steps.append(step)

    def gaps(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return (keys % 3).astype(float), np.ones(len(keys))  # within the slack, or past it

    got = ledger_steps(fast, steps, gaps)
    with pytest.MonkeyPatch.context() as mp:
        full_settle(mp)
        assert ledger_steps(fast, steps, gaps) == got


def soft_log(kernels: str) -> list[tuple[Any, ...]]:
    """Each step's began, ended and touching of a soft World: two boxes settle on a floor;
    a is lifted (its contact ends after quiet steps) and lands while b's stays; a kinematic
    sensor body (``feet``) is put on b, then b and the feet onto a sensor coin; a is made a
    sensor (it falls through the floor, overlapping it a while); the feet go; b leaves the
    coin for a ledge (its floor's contact ends as the ledge's begins). Events as (body,
    other, point, normal, impulse, time, removal)."""
    w = World(kernels=kernels, solver="soft")
    w.add_force(Gravity((0, -G)))
    floor = w.add_collider(Segment((-10, 0), (10, 0)))
    coin = w.add_collider(Circle((5, 0.5), 0.3, sensor=True))
    ledge = w.add_collider(Segment((6, 3), (9, 3)))
    a = w.add(Body(Vector(-2, 0.6), shape=Polygon.box(1, 1), mass=1.0, restitution=0.0))
    b = w.add(Body(Vector(2, 0.6), shape=Polygon.box(1, 1), mass=1.0, restitution=0.0))
    feet = w.add(Body(Vector(0, 5), shape=Polygon.box(0.6, 0.2), kinematic=True, sensor=True))
    names = {id(floor): "floor", id(coin): "coin", id(ledge): "ledge", id(a): "a", id(b): "b"}
    names[id(feet)] = "feet"

    def told(evs: list[ContactEvent]) -> list[tuple[Any, ...]]:
        return [(names[id(e.body)], names[id(e.collider)], *e[2:]) for e in evs]

    log = []
    for n in range(200):
        if n == 40:
            a.pos = Vector(-2, 1.5)
        if n == 100:
            feet.pos = Vector(2, 1.05)
        if n == 130:
            b.pos = Vector(5, b.pos.y)
            feet.pos = Vector(5, 1.05)
        if n == 150:
            a.sensor = True
        if n == 170:
            feet.pos = Vector(0, 5)
        if n == 185:
            b.pos = Vector(7, 3 + b.pos.y)  # onto the ledge: one contact for another
        w.step(DT)
        log.append((told(w.began), told(w.ended), sorted(told(w.touching))))
    return log


@pytest.mark.parametrize("kernels", PATHS)
def test_a_soft_world_reports_each_change_after_quiet_steps(kernels: str) -> None:
    log = soft_log(kernels)
    steps = {n: ([e[:2] for e in g], [e[:2] for e in x]) for n, (g, x, _) in enumerate(log)}
    busy = {n: v for n, v in steps.items() if v != ([], [])}
    assert list(busy)[0] < 30 and busy.pop(list(busy)[0]) == (
        [("a", "floor"), ("b", "floor")],
        [],
    )
    landed = [n for n in busy if busy[n] == ([("a", "floor")], [])]
    fell = [n for n in busy if n > 150 and busy[n] == ([], [("a", "floor")])]
    assert len(landed) == 1 and 40 < landed[0] < 100 and len(fell) == 1
    assert busy == {
        40: ([], [("a", "floor")]),  # lifted, after 30 quiet steps
        landed[0]: ([("a", "floor")], []),  # lands while b's contact stays
        100: ([("b", "feet")], []),  # a sensor body put on b
        130: ([("b", "coin")], []),  # b into the coin, the feet still on it
        150: ([("a", "floor")], [("a", "floor")]),  # a sensor now: its overlap, afresh
        170: ([], [("b", "feet")]),
        fell[0]: ([], [("a", "floor")]),  # a fell through
        185: ([("b", "ledge")], [("b", "floor"), ("b", "coin")]),
    }
    assert ("b", "floor") in [e[:2] for e in log[landed[0]][2]]
    # A contact the solver found begins with its impulse (engine.pipeline.event_dispatch._changes),
    # one it no longer finds ends where it last touched: the floor's under b, the ledge's.
    (ledge,) = log[185][0]
    assert ledge[4].y > 0.0 and ledge[3] == Vector(0.0, 1.0)
    assert 4.5 - 1e-9 <= log[185][1][0][2].x <= 5.5 + 1e-9  # under b by the coin, not now
    with pytest.MonkeyPatch.context() as mp:
        full_settle(mp)
        assert soft_log(kernels) == log
