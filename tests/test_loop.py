"""engine.loop: whole steps of dt per frame, alpha in [0, 1), the clamp, exact time."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine import Body, FixedStep, RealClock, VirtualClock, World

dts = st.sampled_from([1 / 60, 1 / 120, 0.01, 0.013, 1 / 7, 0.002, Fraction(1, 90)])
frames = st.lists(
    st.one_of(
        st.floats(0.0, 0.6, allow_nan=False),
        st.sampled_from([0.0, 1 / 60, 1 / 30, 0.25, 5.0]),
        st.fractions(0, 1, max_denominator=1000),
    ),
    min_size=1,
    max_size=60,
)


@settings(max_examples=150, deadline=None)
@given(dt=dts, frame_times=frames)
def test_alpha_is_always_in_0_1_and_no_time_is_lost(
    dt: float | Fraction, frame_times: list[float]
) -> None:
    loop = FixedStep(dt, max_frame=0.25)
    fed = Fraction(0)
    dropped = Fraction(0)
    for frame in frame_times:
        n = loop.advance(frame)
        assert n >= 0
        assert 0.0 <= loop.alpha < 1.0
        f = Fraction(frame)
        fed += min(f, Fraction(0.25))
        dropped += max(f - Fraction(0.25), Fraction(0))
    # Time is conserved: whole steps plus the leftover fraction are what was fed in
    # (after the clamp), to float precision of dt itself.
    taken = (loop.steps + loop.alpha) * float(dt)
    assert taken == pytest.approx(float(fed), rel=1e-9, abs=1e-12)
    # Whole steps: floor(fed / dt), where a ratio within 1e-9 of a whole number may go
    # either way (the loop reads 1/60 as the 1/60 meant, not the float's binary value).
    ratio = float(fed) / float(dt)
    assert loop.steps in {math.floor(ratio - 1e-9), math.floor(ratio + 1e-9)}
    assert loop.dropped == pytest.approx(float(dropped), abs=1e-12)
    assert loop.t == pytest.approx(loop.steps * float(dt), rel=1e-12)
    assert loop.frames == len(frame_times)


def test_step_count_is_exact_over_a_million_virtual_frames() -> None:
    # 10^6 frames of exactly 1/60 s with dt = 1/120 s: exactly two steps every frame.
    # A float accumulator drifts here (1/60 and 1/120 are not binary fractions).
    loop = FixedStep(dt=1 / 120)
    clock = VirtualClock(fps=60)
    counts = set()
    advance, tick = loop.advance, clock.tick
    for _ in range(1_000_000):
        counts.add(advance(tick()))
    assert counts == {2}
    assert loop.steps == 2_000_000
    assert loop.alpha == 0.0 and loop.accumulated == 0.0 and loop.dropped == 0.0
    assert clock.frames == 1_000_000 and clock.t == 1_000_000 / 60
    assert loop.t == float(Fraction(1_000_000, 60))


def test_float_frame_times_count_like_the_fractions_they_stand_for() -> None:
    # float(1/60) is a little less than 1/60: read naively, the first frame would make one
    # step of 1/120 s (with alpha rounding to 1.0) and a step would go missing at the end.
    loop = FixedStep(dt=1 / 120)
    counts = {loop.advance(1 / 60) for _ in range(10_000)}
    assert counts == {2} and loop.steps == 20_000 and loop.alpha == 0.0
    loop = FixedStep(dt=1 / 60)
    assert loop.advance(1 / 60) == 1 and loop.alpha == 0.0


def test_alpha_stays_below_one_when_the_leftover_is_a_hair_under_a_step() -> None:
    loop = FixedStep(dt=Fraction(1, 7))
    loop.advance(Fraction(1, 7) - Fraction(1, 10**18))
    assert loop.steps == 0 and 0.0 <= loop.alpha < 1.0


def test_a_long_frame_is_clamped_and_the_dropped_time_reported() -> None:
    loop = FixedStep(dt=1 / 120, max_frame=0.25)
    assert loop.advance(5.0) == 30  # 0.25 s / (1/120 s)
    assert loop.dropped == 4.75
    assert loop.alpha == 0.0
    assert loop.advance(1 / 60) == 2  # and then it carries on as normal
    assert loop.dropped == 4.75
    assert loop.t == pytest.approx(32 / 120, rel=1e-15)


def test_leftover_time_becomes_alpha() -> None:
    loop = FixedStep(dt=0.01)
    assert loop.advance(0.025) == 2
    assert loop.alpha == pytest.approx(0.5, rel=1e-12)
    assert loop.advance(0.005) == 1
    assert loop.alpha == pytest.approx(0.0, abs=1e-12)
    assert loop.advance(0.0) == 0


def test_a_tiny_dt_is_counted_as_itself() -> None:
    # A dt with no small fraction near it must not be rounded to one (2.5e-7 s to 0).
    for dt in (2.5e-7, 1.5e-6):
        loop = FixedStep(dt, max_frame=1.0)
        n = loop.advance(1e-3)
        assert abs(n - 1e-3 / dt) <= 1, dt
        assert 0.0 <= loop.alpha < 1.0
        assert loop.t == pytest.approx(n * dt, rel=1e-12)


def test_run_steps_the_world_and_keeps_its_clock_with_the_loop() -> None:
    world = World("exact")
    body = world.add(Body(0.0, 1.0, 0.0))
    loop = FixedStep(dt=1 / 120)
    clock = VirtualClock(fps=50)  # 2.4 steps a frame: alpha moves
    alphas = [loop.run(world, clock.tick()) for _ in range(50)]
    assert world.steps == loop.steps == 120
    assert world.t == pytest.approx(loop.t, rel=1e-14) and loop.t == pytest.approx(1.0)
    assert body.pos == pytest.approx(1.0, rel=1e-14)
    assert all(0.0 <= a < 1.0 for a in alphas) and len(set(alphas)) > 1


def test_virtual_clock_ticks_exact_frames() -> None:
    clock = VirtualClock(fps=30)
    assert clock.tick() == Fraction(1, 30)
    clock.tick()
    assert clock.frames == 2 and clock.t == pytest.approx(2 / 30)


def test_real_clock_returns_seconds_since_the_previous_tick() -> None:
    clock = RealClock()
    assert clock.tick() == 0.0
    elapsed = clock.tick()
    assert 0.0 <= elapsed < 1.0


# -- refusals ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("bad", "error", "message"),
    [
        (0, ValueError, "dt must be > 0"),
        (-1 / 60, ValueError, "dt must be > 0"),
        (math.nan, ValueError, "dt must be finite"),
        (math.inf, ValueError, "dt must be finite"),
        ("1/60", TypeError, "dt must be a number of seconds"),
        (True, TypeError, "dt must be a number of seconds"),
        (None, TypeError, "dt must be a number of seconds"),
    ],
)
def test_fixed_step_refuses_a_bad_dt(bad: object, error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        FixedStep(bad)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("bad", "error", "message"),
    [
        (0, ValueError, "max_frame must be > 0"),
        (-1, ValueError, "max_frame must be > 0"),
        (math.inf, ValueError, "max_frame must be finite"),
        ("0.25", TypeError, "max_frame must be a number of seconds"),
        (0.001, ValueError, r"max_frame \(0.001 s\) must be at least one step dt"),
    ],
)
def test_fixed_step_refuses_a_bad_max_frame(bad: object, error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        FixedStep(1 / 60, max_frame=bad)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("bad", "error", "message"),
    [
        (-0.01, ValueError, "frame_seconds must be >= 0"),
        (math.nan, ValueError, "frame_seconds must be finite"),
        (math.inf, ValueError, "frame_seconds must be finite"),
        ("0.016", TypeError, "frame_seconds must be a number of seconds"),
        (False, TypeError, "frame_seconds must be a number of seconds"),
    ],
)
def test_advance_refuses_a_bad_frame_time_and_changes_nothing(
    bad: object, error: type, message: str
) -> None:
    loop = FixedStep(1 / 60)
    loop.advance(0.02)
    before = (loop.steps, loop.alpha, loop.frames, loop.dropped)
    with pytest.raises(error, match=message):
        loop.advance(bad)  # type: ignore[arg-type]
    assert (loop.steps, loop.alpha, loop.frames, loop.dropped) == before


@pytest.mark.parametrize(
    ("bad", "error", "message"),
    [
        (0, ValueError, "fps must be > 0"),
        (-30, ValueError, "fps must be > 0"),
        (59.94, TypeError, "fps must be a whole number"),
        (True, TypeError, "fps must be a whole number"),
        ("60", TypeError, "fps must be a whole number"),
    ],
)
def test_virtual_clock_refuses_a_bad_fps(bad: object, error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        VirtualClock(bad)  # type: ignore[arg-type]
