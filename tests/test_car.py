"""The car on Main Street: stops at the third light's line, never backwards, frames by pixels."""

from __future__ import annotations

import math

import numpy as np
import pygame
import pytest

from demos.car import LIGHTS, MPH, MainStreet, TooFast, plan_trip
from engine.render import iter_frames, record

LINE = LIGHTS[2]


def sample(scene: MainStreet, step: float = 0.002) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    trip = scene.trip
    ts = np.arange(0.0, trip.end.t0 + 2.0, step)
    return ts, np.array([trip.position(t) for t in ts]), np.array([trip.velocity(t) for t in ts])


@pytest.fixture
def main_street() -> MainStreet:
    scene = MainStreet()
    scene.build((320, 180))
    return scene


def test_ten_mph_is_4_4704_metres_per_second() -> None:
    assert 10 * MPH == pytest.approx(4.4704, abs=1e-12)


def test_car_stops_within_a_centimetre_of_the_third_stop_line(main_street: MainStreet) -> None:
    trip = main_street.trip
    assert abs(trip.end.s0 - LINE) < 0.01
    assert abs(trip.position(trip.end.t0 + 5.0) - LINE) < 0.01
    assert trip.velocity(trip.end.t0) == 0.0


def test_braking_starts_at_the_stopping_distance_before_the_line(main_street: MainStreet) -> None:
    braking = next(p for p in main_street.trip.phases if p.name == "braking")
    v, b = 10 * 0.44704, main_street.brake  # 10 mph in m/s, by hand
    assert braking.s0 == pytest.approx(LINE - v * v / (2 * b), abs=1e-9)
    assert braking.v0 == pytest.approx(v, abs=1e-12)


def test_car_never_goes_backwards_nor_past_ten_mph(main_street: MainStreet) -> None:
    _, x, v = sample(main_street)
    assert (np.diff(x) >= -1e-12).all()
    assert (v >= -1e-12).all()
    assert v.max() <= 10 * MPH * (1 + 1e-12)
    assert v.max() == pytest.approx(10 * MPH, rel=1e-12)  # and it does reach 10 mph


def test_position_is_continuous_across_phases(main_street: MainStreet) -> None:
    trip = main_street.trip
    for phase in trip.phases[1:]:
        before = trip.position(phase.t0 - 1e-9)
        assert trip.position(phase.t0) == pytest.approx(before, abs=1e-7)
        assert phase.s0 == pytest.approx(before, abs=1e-7)


def test_too_fast_runs_the_light_by_the_difference_of_stopping_distances() -> None:
    scene = TooFast()
    scene.build((320, 180))
    trip, b = scene.trip, scene.brake
    v, planned = 25 * MPH, 10 * MPH
    assert trip.end.s0 > LINE
    assert trip.end.s0 - LINE == pytest.approx((v * v - planned * planned) / (2 * b), abs=1e-9)
    # It crosses the line still moving: v^2 = v0^2 - 2 b d over the d = planned^2/(2b) it had.
    t_cross = next(t for t in np.arange(0, trip.end.t0, 0.001) if trip.position(t) >= LINE)
    assert trip.velocity(t_cross) == pytest.approx((v * v - planned**2) ** 0.5, rel=1e-3)
    # The exact crossing the screen reports: the same time, to the scan's 1 ms.
    assert trip.time_at(LINE) == pytest.approx(t_cross, abs=1e-3)
    assert trip.position(trip.time_at(LINE)) == pytest.approx(LINE, abs=1e-9)
    assert trip.velocity(trip.time_at(LINE)) == pytest.approx((v * v - planned**2) ** 0.5)
    assert trip.time_at(trip.end.s0 + 1.0) == math.inf  # it stops before that


def test_the_good_driver_reaches_the_line_only_as_it_stops(main_street: MainStreet) -> None:
    trip = main_street.trip
    assert trip.time_at(LINE) == pytest.approx(trip.end.t0, abs=1e-6)
    assert trip.velocity(trip.time_at(LINE)) == pytest.approx(0.0, abs=1e-6)


def test_plan_refuses_to_brake_before_cruise_speed() -> None:
    with pytest.raises(ValueError, match="brake_at"):
        plan_trip(10.0, 1.0, 2.0, brake_at=5.0)
    with pytest.raises(ValueError, match="cruise"):
        plan_trip(-1.0, 1.0, 2.0, brake_at=50.0)


def red_columns(surface: pygame.Surface) -> np.ndarray:
    """x of the pixels of the car's body colour (196, 42, 54), within a small distance."""
    rgb = pygame.surfarray.array3d(surface).astype(int)
    near = (np.abs(rgb - np.array([196, 42, 54])).sum(axis=2) < 40).nonzero()
    return near[0]


def test_car_moves_on_screen_as_the_closed_form_says() -> None:
    scene = MainStreet()
    fronts, times = [], []
    # fps >= 4: the recorder's loop clamps a frame to 0.25 s (see the report).
    for index, t, surface in iter_frames(scene, fps=5, seconds=7.0, size=(640, 360)):
        if index in (15, 35):  # t = 3 s and 7 s
            fronts.append(red_columns(surface).max())
            times.append(t)
    moved_px = fronts[1] - fronts[0]
    expected_px = scene.camera.length(scene.trip.position(times[1]) - scene.trip.position(times[0]))
    assert abs(moved_px - expected_px) <= 1.0


@pytest.mark.parametrize("scene_cls", [MainStreet, TooFast])
def test_car_frames_are_valid_not_flat_and_repeatable(scene_cls: type, tmp_path) -> None:
    a = record(scene_cls(), tmp_path / "a", fps=5, seconds=0.8, size=(320, 180), progress=False)
    b = record(scene_cls(), tmp_path / "b", fps=5, seconds=0.8, size=(320, 180), progress=False)
    assert a.count == 5
    for pa, pb in zip(a.paths(), b.paths(), strict=True):
        assert pa.read_bytes() == pb.read_bytes()
        image = pygame.image.load(str(pa))
        assert image.get_size() == (320, 180)
        colours = np.unique(pygame.surfarray.array3d(image).reshape(-1, 3), axis=0)
        assert len(colours) > 20


def test_the_trip_counts_its_time_in_whole_steps_and_saves_its_clock() -> None:
    trip = plan_trip(10 * MPH, 1.5, 2.0, brake_at=80.0)
    for _ in range(120):
        trip.step(1 / 120)
    assert trip.t == 1.0 and trip.steps == 120
    for _ in range(3):
        trip.step(0.5)  # a new dt: the second already counted is kept
    assert trip.t == 2.5 and trip.steps == 123
    saved = trip.snapshot()
    trip.step(0.5)
    trip.restore(saved)
    assert trip.t == 2.5 and trip.steps == 123
    for bad in (0.0, -1.0, math.inf, math.nan, True):
        with pytest.raises(ValueError, match="dt must be"):
            trip.step(bad)  # type: ignore[arg-type]
    assert trip.t == 2.5
    with pytest.raises(TypeError, match="Trip.snapshot"):
        trip.restore(2.5)  # type: ignore[arg-type]
